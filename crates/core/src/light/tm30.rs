//! CIE 224:2017 colour fidelity index Rf and ANSI/IES TM-30-18 gamut index Rg.
//!
//! The 99 colour evaluation samples are taken to XYZ under the test light and under the
//! reference at the same CCT ([`super::reference::tm30_reference`]) with the CIE 1964 10°
//! observer, each light's white at `Y = 100`; then to CAM02-UCS with `L_A = 100 cd/m²`,
//! `Y_b = 20`, average surround and complete adaptation ([`super::cam02`]).
//! `ΔE′ᵢ` is the J′a′b′ distance, `Rf = 10·ln(exp((100 − 6.73·mean ΔE′)/10) + 1)` (and `Rf,i` per
//! sample). For Rg the samples are put in 16 hue bins of 22.5° by their hue under the reference;
//! the mean a′, b′ of each bin under the test and the reference light are the vertices of two
//! polygons, and `Rg = 100·A_test / A_ref` (shoelace areas).

use super::{
    cam02::{Cam02, Ucs, AVERAGE},
    cct::Cct,
    cri::to64,
    reference::tm30_reference,
    samples::Samples,
    source::Source,
    LightError,
};

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
    /// CCT and Duv of the light (CIE 1931 observer).
    pub cct: Cct,
}

/// `Rf` from a colour difference: `10·ln(exp((100 − c_f·ΔE)/10) + 1)`.
pub fn rf_of(delta_e: f64) -> f64 {
    10.0 * libm::log1p(libm::exp((100.0 - C_F * delta_e) / 10.0))
}

fn ucs_all(light: &Source, ces: &Samples<99>) -> [Ucs; 99] {
    let cam = Cam02::new(to64(light.m10.white().to_array()), L_A, Y_B, AVERAGE);
    core::array::from_fn(|i| cam.ucs(to64(light.m10.xyz(&ces.spectra[i]).to_array())))
}

/// Rf and Rg of `light` with the colour evaluation samples `ces`.
pub fn tm30(light: &Source, ces: &Samples<99>) -> Result<Tm30, LightError> {
    let c = light.cct()?;
    let reference = tm30_reference(c.cct)?;
    let test = ucs_all(light, ces);
    let refs = ucs_all(&reference, ces);
    let mut rf_i = [0.0; 99];
    let mut sum = 0.0;
    // bins: Σa′, Σb′ (test), Σa′, Σb′ (reference), count
    let mut bins = [[0.0f64; 5]; 16];
    for i in 0..99 {
        let de = test[i].delta_e(&refs[i]);
        rf_i[i] = rf_of(de);
        sum += de;
        let b = ((refs[i].h / 22.5) as usize).min(15);
        bins[b][0] += test[i].a;
        bins[b][1] += test[i].b;
        bins[b][2] += refs[i].a;
        bins[b][3] += refs[i].b;
        bins[b][4] += 1.0;
    }
    let area = |o: usize| {
        let mut a = 0.0;
        let mut pts = bins
            .iter()
            .filter(|b| b[4] > 0.0)
            .map(|b| (b[o] / b[4], b[o + 1] / b[4]));
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
    Ok(Tm30 {
        rf: rf_of(sum / 99.0),
        rg: 100.0 * area(0) / area(2),
        rf_i,
        cct: c,
    })
}
