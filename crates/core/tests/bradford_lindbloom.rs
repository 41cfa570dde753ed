//! Bradford chromatic adaptation D65 → D50 against the matrix published by B. Lindbloom
//! (brucelindbloom.com, "Chromatic Adaptation", computed from the same whites).

use specpoly_core::{bradford, Xyz};

#[test]
fn d65_to_d50_matches_the_published_matrix() {
    let published = [
        [1.0478112, 0.0228866, -0.0501270],
        [0.0295424, 0.9904844, -0.0170491],
        [-0.0092345, 0.0150436, 0.7521316],
    ];
    let m = bradford(
        Xyz::new(0.95047, 1.0, 1.08883),
        Xyz::new(0.96422, 1.0, 0.82521),
    );
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (m.0[i][j] - published[i][j]).abs() < 2e-6,
                "[{i}][{j}] {}",
                m.0[i][j]
            );
        }
    }
    // the source white maps to the destination white
    let w = m.apply([0.95047, 1.0, 1.08883]);
    assert!((w[0] - 0.96422).abs() < 1e-5 && (w[2] - 0.82521).abs() < 1e-5);
}
