//! Bradford chromatic adaptation D65 → D50 against the matrix published by B. Lindbloom
//! (brucelindbloom.com, "Chromatic Adaptation", computed from the same whites), at both
//! component types of the one `bradford`.

use specpoly_core::{bradford, Xyz};

/// Lindbloom's D65 → D50 Bradford matrix (7 decimals).
const PUBLISHED: [[f64; 3]; 3] = [
    [1.0478112, 0.0228866, -0.0501270],
    [0.0295424, 0.9904844, -0.0170491],
    [-0.0092345, 0.0150436, 0.7521316],
];
const D65: [f64; 3] = [0.95047, 1.0, 1.08883];
const D50: [f64; 3] = [0.96422, 1.0, 0.82521];

/// f32: a few ulps of the entries (≈ 1.2e-7 near 1) on top of the published rounding.
const TOL_F32: f64 = 2e-6;
/// f64: the published rounding, half a unit of the 7th decimal (the f64 arithmetic adds
/// ≈ 1e-16).
const TOL_F64: f64 = 5e-8;

#[test]
fn d65_to_d50_matches_the_published_matrix_in_f32() {
    let m = bradford(
        Xyz::<f32>::from_array(D65.map(|v| v as f32)),
        Xyz::<f32>::from_array(D50.map(|v| v as f32)),
    );
    for i in 0..3 {
        for j in 0..3 {
            let got = m.0[i][j] as f64;
            assert!((got - PUBLISHED[i][j]).abs() < TOL_F32, "[{i}][{j}] {got}");
        }
    }
    // the source white maps to the destination white
    let w = m.apply(D65.map(|v| v as f32));
    assert!((w[0] as f64 - D50[0]).abs() < 1e-5 && (w[2] as f64 - D50[2]).abs() < 1e-5);
}

#[test]
fn d65_to_d50_matches_the_published_matrix_in_f64() {
    let m = bradford(Xyz::<f64>::from_array(D65), Xyz::from_array(D50));
    for i in 0..3 {
        for j in 0..3 {
            let got = m.0[i][j];
            assert!((got - PUBLISHED[i][j]).abs() <= TOL_F64, "[{i}][{j}] {got}");
        }
    }
    let w = m.apply(D65);
    for c in 0..3 {
        assert!((w[c] - D50[c]).abs() < 1e-14, "{w:?}");
    }
}
