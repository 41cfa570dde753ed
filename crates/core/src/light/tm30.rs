//! CIE 224:2017 colour fidelity index Rf and ANSI/IES TM-30-18 gamut index Rg.
//!
//! The 99 colour evaluation samples are taken to XYZ under the test light and under the
//! reference at the same CCT ([`super::reference::tm30_reference`]) with the CIE 1964 10°
//! observer, each light's white at `Y = 100`; then to CAM02-UCS with `L_A = 100 cd/m²`,
//! `Y_b = 20`, average surround and complete adaptation ([`super::cam02`]).
//! `ΔE′ᵢ` is the J′a′b′ distance, `Rf = 10·ln(exp((100 − 6.73·mean ΔE′)/10) + 1)` (and `Rf,i` per
//! sample). For Rg the samples are put in 16 hue bins of 22.5° by their hue under the reference;
//! the mean a′, b′ of each bin under the test and the reference light are the vertices of two
//! polygons, and `Rg = 100·A_test / A_ref` (shoelace areas). Per bin `j` (centre
//! `θⱼ = 22.5°·j + 11.25°`, mean shift `Δa′, Δb′`, reference mean radius `r`): `Rf,hj` from the
//! bin's mean ΔE′, chroma shift `Rcs,hj = (Δa′ cos θⱼ + Δb′ sin θⱼ)/r`, hue shift
//! `Rhs,hj = (−Δa′ sin θⱼ + Δb′ cos θⱼ)/r` (ANSI/IES TM-30-18 §4.3).
//!
//! The **colour vector graphic** (ANSI/IES TM-30-20) is drawn from the same bin means, each
//! bin scaled by its reference radius `r = |(ā′_r, b̄′_r)|`: the reference point
//! `(ā′_r, b̄′_r)/r` lies on the unit circle, the test point is `(ā′_t, b̄′_t)/r`, and the arrow of
//! bin `j` runs from the first to the second ([`Tm30::vector_graphic`]; luxpy's
//! `_get_hue_bin_data` normalises the same way). colour-science 0.4.7 instead starts each arrow
//! on the unit circle at the mean hue angle of the bin's samples and adds the same offset
//! `(ā′_t − ā′_r, b̄′_t − b̄′_r)/r`; the two starts differ by the angle between the mean of the
//! hues and the hue of the mean (measured in `docs/leds.md`).
//!
//! Two forms: [`tm30`] from a [`Source`]'s moments and the fitted samples (fast, linear in a
//! mix: the optimiser's), and [`tm30_spd`] from an [`Spd`] on its own 1 nm or 5 nm grid with
//! the tabulated samples, the standard's computation (reports, `specpoly light`).

use super::{
    cam02::{Cam02, Ucs, AVERAGE},
    cct::Cct,
    cri::to64,
    reference::{tm30_reference, tm30_reference_spd},
    samples::Samples,
    source::Source,
    spd::Spd,
    LightError,
};
use crate::observer::{CES99, CES99_1NM};
use crate::Observer;

/// Adapting luminance, cd/m² (CIE 224:2017).
pub const L_A: f64 = 100.0;
/// Background luminance factor (CIE 224:2017).
pub const Y_B: f64 = 20.0;
/// Scale factor of the fidelity index (CIE 224:2017).
pub const C_F: f64 = 6.73;

/// CIE 224:2017 / TM-30 results for a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tm30 {
    /// Fidelity index Rf.
    pub rf: f64,
    /// Gamut index Rg.
    pub rg: f64,
    /// Per-sample fidelity Rf,i (CES01–CES99).
    pub rf_i: [f64; 99],
    /// Hue-bin fidelity Rf,hj (bins 1–16).
    pub rf_h: [f64; 16],
    /// Hue-bin chroma shift Rcs,hj, a fraction (TM-30 prints it ×100 as %).
    pub rcs_h: [f64; 16],
    /// Hue-bin hue shift Rhs,hj.
    pub rhs_h: [f64; 16],
    /// The hue bin (0–15) of each sample, by its hue under the reference.
    pub bin_of: [u8; 99],
    /// Number of samples in each hue bin.
    pub bin_count: [u8; 16],
    /// Mean CAM02-UCS `(a′, b′)` of each hue bin's samples under the test light (NaN for an
    /// empty bin).
    pub test_ab: [[f64; 2]; 16],
    /// Mean CAM02-UCS `(a′, b′)` of each hue bin's samples under the reference (NaN for an
    /// empty bin).
    pub reference_ab: [[f64; 2]; 16],
    /// CCT and Duv of the light (CIE 1931 observer).
    pub cct: Cct,
}

/// The colour vector graphic's points, each hue bin scaled by its reference radius (see the
/// module docs): arrows from `reference[j]` (on the unit circle) to `test[j]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VectorGraphic {
    /// `(ā′_r, b̄′_r)/r` per bin.
    pub reference: [[f64; 2]; 16],
    /// `(ā′_t, b̄′_t)/r` per bin.
    pub test: [[f64; 2]; 16],
}

impl Tm30 {
    /// The colour vector graphic's points (NaN for an empty bin).
    pub fn vector_graphic(&self) -> VectorGraphic {
        let mut reference = [[f64::NAN; 2]; 16];
        let mut test = [[f64::NAN; 2]; 16];
        for j in 0..16 {
            let [ar, br] = self.reference_ab[j];
            let r = libm::hypot(ar, br);
            if r > 0.0 {
                reference[j] = [ar / r, br / r];
                test[j] = [self.test_ab[j][0] / r, self.test_ab[j][1] / r];
            }
        }
        VectorGraphic { reference, test }
    }
}

/// `Rf` from a colour difference: `10·ln(exp((100 − c_f·ΔE)/10) + 1)`.
pub fn rf_of(delta_e: f64) -> f64 {
    10.0 * libm::log1p(libm::exp((100.0 - C_F * delta_e) / 10.0))
}

fn ucs_all(white: [f64; 3], xyz: impl Fn(usize) -> [f64; 3]) -> [Ucs; 99] {
    let cam = Cam02::new(white, L_A, Y_B, AVERAGE);
    core::array::from_fn(|i| cam.ucs(xyz(i)))
}

fn ucs_moments(light: &Source, ces: &Samples<99>) -> [Ucs; 99] {
    ucs_all(to64(light.m10.white().to_array()), |i| {
        to64(light.m10.xyz(&ces.spectra[i]).to_array())
    })
}

/// Rf and Rg of `light` with the colour evaluation samples `ces` (the light's moments and the
/// fitted samples: the fast form, for the mixing optimiser).
pub fn tm30(light: &Source, ces: &Samples<99>) -> Result<Tm30, LightError> {
    let c = light.cct()?;
    let reference = tm30_reference(c.cct)?;
    Ok(indices(
        &ucs_moments(light, ces),
        &ucs_moments(&reference, ces),
        c,
    ))
}

/// Rf, Rg and the hue bins of `light` by sums on its own grid with the tabulated colour
/// evaluation samples at the same interval (CIE 224:2017's 1 nm or 5 nm tables): the
/// standard's computation, for reports.
pub fn tm30_spd(light: &Spd) -> Result<Tm30, LightError> {
    let c = light.cct()?;
    let reference = tm30_reference_spd(c.cct, light.step())?;
    let step = light.step();
    let ces = |i: usize, k: usize| -> f64 {
        if step == 5 {
            CES99[i][k] as f64
        } else {
            CES99_1NM[i][k] as f64
        }
    };
    let ucs = |s: &Spd| {
        let w = s.sums(Observer::Cie1964);
        let k = 100.0 / w[1];
        ucs_all(w.map(|v| v * k), |i| {
            s.sums_with(Observer::Cie1964, |j| ces(i, j)).map(|v| v * k)
        })
    };
    Ok(indices(&ucs(light), &ucs(&reference), c))
}

/// The indices from the samples' CAM02-UCS coordinates under the test light and the reference.
fn indices(test: &[Ucs; 99], refs: &[Ucs; 99], cct: Cct) -> Tm30 {
    let mut rf_i = [0.0; 99];
    let mut bin_of = [0u8; 99];
    let mut sum = 0.0;
    // bins: Σa′, Σb′ (test), Σa′, Σb′ (reference), ΣΔE′, count
    let mut bins = [[0.0f64; 6]; 16];
    for i in 0..99 {
        let de = test[i].delta_e(&refs[i]);
        rf_i[i] = rf_of(de);
        sum += de;
        let b = ((refs[i].h / 22.5) as usize).min(15);
        bin_of[i] = b as u8;
        bins[b][0] += test[i].a;
        bins[b][1] += test[i].b;
        bins[b][2] += refs[i].a;
        bins[b][3] += refs[i].b;
        bins[b][4] += de;
        bins[b][5] += 1.0;
    }
    let area = |o: usize| {
        let mut a = 0.0;
        let mut pts = bins
            .iter()
            .filter(|b| b[5] > 0.0)
            .map(|b| (b[o] / b[5], b[o + 1] / b[5]));
        if let Some(first) = pts.next() {
            let mut prev = first;
            for p in pts {
                a += prev.0 * p.1 - prev.1 * p.0;
                prev = p;
            }
            a += prev.0 * first.1 - prev.1 * first.0;
        }
        0.5 * a
    };
    let (mut rf_h, mut rcs_h, mut rhs_h) = ([f64::NAN; 16], [f64::NAN; 16], [f64::NAN; 16]);
    let mut bin_count = [0u8; 16];
    let (mut test_ab, mut reference_ab) = ([[f64::NAN; 2]; 16], [[f64::NAN; 2]; 16]);
    for (j, b) in bins.iter().enumerate() {
        if b[5] == 0.0 {
            continue;
        }
        let n = b[5];
        bin_count[j] = n as u8;
        test_ab[j] = [b[0] / n, b[1] / n];
        reference_ab[j] = [b[2] / n, b[3] / n];
        let (da, db) = ((b[0] - b[2]) / n, (b[1] - b[3]) / n);
        let norm = libm::hypot(b[2] / n, b[3] / n);
        let theta = (22.5 * j as f64 + 11.25).to_radians();
        let (s, co) = (libm::sin(theta), libm::cos(theta));
        rf_h[j] = rf_of(b[4] / n);
        rcs_h[j] = (da * co + db * s) / norm;
        rhs_h[j] = (-da * s + db * co) / norm;
    }
    Tm30 {
        rf: rf_of(sum / 99.0),
        rg: 100.0 * area(0) / area(2),
        rf_i,
        rf_h,
        rcs_h,
        rhs_h,
        bin_of,
        bin_count,
        test_ab,
        reference_ab,
        cct,
    }
}
