//! CIE 13.3-1995 colour rendering index: the general index Ra (mean of R1–R8) and the special
//! indices R1–R14 (R9: saturated red), with R15 (JIS Z 8726:1990's Japanese skin sample, TCS15,
//! computed by the same rule; colour-science's "CIE 2024" method and luxpy's `ciera-15`).
//!
//! For the test light `k` and the reference `r` at the same CCT ([`super::reference`]), each test
//! colour sample `i` is taken to CIE 1960 (u, v) with `Y` relative to the light's white (100)
//! under the CIE 1931 observer; the test colours get the von Kries transform of CIE 13.3 eq. (9)
//! with `c = (4 − u − 10v)/v`, `d = (1.708v + 0.404 − 1.481u)/v`:
//! `u′ = (10.872 + 0.404·c_r/c_k·c_ki − 4·d_r/d_k·d_ki) / (16.518 + 1.481·c_r/c_k·c_ki − d_r/d_k·d_ki)`,
//! `v′ = 5.520 / (same denominator)`; both go to CIE 1964 `W* = 25Y^⅓ − 17`,
//! `U* = 13W*(u − u_r)`, `V* = 13W*(v − v_r)`, and `Rᵢ = 100 − 4.6·ΔEᵢ` (the Euclidean U*V*W*
//! difference).

use super::samples::tcs_table;
use super::{
    cct,
    cct::Cct,
    reference::{cri_reference, cri_reference_spd},
    samples::Samples,
    source::Source,
    spd::Spd,
    sprague, LightError,
};
use crate::Observer;

/// The CIE 13.3 indices of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cri {
    /// General colour rendering index (mean of R1–R8).
    pub ra: f64,
    /// Special indices R1–R14 (`r[8]` is R9).
    pub r: [f64; 14],
    /// R15, the Japanese skin sample of JIS Z 8726:1990 (not part of CIE 13.3).
    pub r15: f64,
    /// CCT and Duv of the light (the reference's temperature).
    pub cct: Cct,
}

fn cd(uv: [f64; 2]) -> (f64, f64) {
    let [u, v] = uv;
    (
        (4.0 - u - 10.0 * v) / v,
        (1.708 * v + 0.404 - 1.481 * u) / v,
    )
}

fn uvw(y: f64, uv: [f64; 2], white: [f64; 2]) -> [f64; 3] {
    let w = 25.0 * libm::cbrt(y) - 17.0;
    [
        13.0 * w * (uv[0] - white[0]),
        13.0 * w * (uv[1] - white[1]),
        w,
    ]
}

/// The CIE 13.3 indices of `light` with the test colour samples `tcs` (the light's moments
/// and the fitted samples: the fast form, for the mixing optimiser).
pub fn cri(light: &Source, tcs: &Samples<15>) -> Result<Cri, LightError> {
    let uv_k = light.uv();
    let c = cct::cct_duv(uv_k)?;
    let reference = cri_reference(c.cct)?;
    let r = indices(
        uv_k,
        reference.uv(),
        |i| to64(light.m2.xyz(&tcs.spectra[i]).to_array()),
        |i| to64(reference.m2.xyz(&tcs.spectra[i]).to_array()),
    );
    Ok(Cri::from_indices(r, c))
}

/// The CIE 13.3 indices of `light` by 1 nm sums with the tabulated test colour samples: a
/// 5 nm light and the 5 nm samples are first taken to 1 nm by [`sprague`] interpolation
/// (CIE 167:2005; colour-science does the same; summing the 5 nm data directly differs by up to
/// 0.14 in Rᵢ on line spectra such as mercury and low-pressure sodium lamps). The standard's
/// computation, for reports; the CCT that chooses the reference is the 1 nm light's.
pub fn cri_spd(light: &Spd) -> Result<Cri, LightError> {
    let fine;
    let light = if light.step() == 5 {
        let v: [f64; 81] = core::array::from_fn(|k| light.values()[k]);
        let v1 = sprague::to_1nm(&v);
        fine = Spd::from_fn(1, |nm| v1[(nm - 380.0) as usize])?;
        &fine
    } else {
        light
    };
    let uv_k = light.uv();
    let c = cct::cct_duv(uv_k)?;
    let reference = cri_reference_spd(c.cct, 1)?;
    let tcs: [[f64; 401]; 15] = core::array::from_fn(|i| {
        let t = tcs_table(i);
        sprague::to_1nm(&core::array::from_fn(|k| t.values()[k] as f64))
    });
    let xyz = |s: &Spd, i: usize| {
        let y = s.sums(Observer::Cie1931)[1];
        s.sums_with(Observer::Cie1931, |k| tcs[i][k])
            .map(|v| 100.0 * v / y)
    };
    let r = indices(
        uv_k,
        reference.uv(),
        |i| xyz(light, i),
        |i| xyz(&reference, i),
    );
    Ok(Cri::from_indices(r, c))
}

impl Cri {
    /// Ra and the named indices from R1–R15.
    fn from_indices(r: [f64; 15], cct: Cct) -> Self {
        Self {
            ra: r[..8].iter().sum::<f64>() / 8.0,
            r: core::array::from_fn(|i| r[i]),
            r15: r[14],
            cct,
        }
    }
}

/// `Rᵢ` of the 15 samples from the test light's and the reference's chromaticities and the
/// samples' XYZ under each (white `Y = 100`).
fn indices(
    uv_k: [f64; 2],
    uv_r: [f64; 2],
    xyz_k: impl Fn(usize) -> [f64; 3],
    xyz_r: impl Fn(usize) -> [f64; 3],
) -> [f64; 15] {
    let (ck, dk) = cd(uv_k);
    let (cr, dr) = cd(uv_r);
    core::array::from_fn(|i| {
        let (xyz_r, xyz_k) = (xyz_r(i), xyz_k(i));
        let ref_uvw = uvw(xyz_r[1], cct::uv_1960(xyz_r), uv_r);
        let (cki, dki) = cd(cct::uv_1960(xyz_k));
        let (cc, dd) = (cr / ck * cki, dr / dk * dki);
        let den = 16.518 + 1.481 * cc - dd;
        let adapted = [(10.872 + 0.404 * cc - 4.0 * dd) / den, 5.520 / den];
        let test_uvw = uvw(xyz_k[1], adapted, uv_r);
        let de = libm::sqrt(
            (0..3)
                .map(|k| (test_uvw[k] - ref_uvw[k]) * (test_uvw[k] - ref_uvw[k]))
                .sum::<f64>(),
        );
        100.0 - 4.6 * de
    })
}

pub(crate) fn to64(v: [f32; 3]) -> [f64; 3] {
    v.map(|c| c as f64)
}
