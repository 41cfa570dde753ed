//! What `specpoly light` adds to a light's colorimetry: the spectrum's shape and hue (peak
//! wavelength, FWHM, dominant wavelength, excitation purity), CIE 13.3's R1–R14 and JIS Z 8726's
//! R15, CIE S 026's
//! α-opic quantities and the checks against ANSI C78.377-2017 and California's JA8. The
//! computations are `specpoly_core::light::{spectral, alpha_opic, ansi_c78377, ja8}`.

use serde::Serialize;
use specpoly_core::light::{
    alpha_opic::alpha_opic,
    ansi_c78377,
    cct::Cct,
    cri::Cri,
    ja8,
    spectral::{dominant, fwhm, peak, WHITE_E},
    Spd,
};

fn r6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

fn r3(v: f64) -> f64 {
    (v * 1e3).round() / 1e3
}

/// The added figures of one light (flattened into `light`'s JSON and CSV).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Checks {
    /// CIE 13.3 special indices R1–R14 (`None` without a CCT).
    pub ri: Option<[f64; 14]>,
    /// R15, the Japanese skin sample of JIS Z 8726:1990 (`None` without a CCT).
    pub r15: Option<f64>,
    /// Peak wavelength, nm: the largest value on the light's grid.
    pub peak_nm: f64,
    /// Full width at half maximum around the peak, nm (`None` for a broad-band light).
    pub fwhm_nm: Option<f64>,
    /// Dominant wavelength against the equal-energy stimulus E, nm; negative: complementary
    /// wavelength (a purple). `None` at E itself.
    pub dominant_nm: Option<f64>,
    /// Excitation purity against E.
    pub purity: Option<f64>,
    /// CIE S 026 α-opic equivalent daylight (D65) illuminance, lx, of s-cone, m-cone, l-cone,
    /// rhodopic, melanopic (the light as a spectral irradiance in W/m²/nm).
    pub edi_sc: f64,
    /// m-cone (chloropic) EDI, lx.
    pub edi_mc: f64,
    /// l-cone (erythropic) EDI, lx.
    pub edi_lc: f64,
    /// Rhodopic EDI, lx.
    pub edi_rh: f64,
    /// Melanopic EDI, lx.
    pub edi_mel: f64,
    /// α-opic daylight efficacy ratio, s-cone.
    pub der_sc: f64,
    /// DER, m-cone.
    pub der_mc: f64,
    /// DER, l-cone.
    pub der_lc: f64,
    /// DER, rhodopic.
    pub der_rh: f64,
    /// DER, melanopic.
    pub der_mel: f64,
    /// The ANSI C78.377-2017 nominal CCT whose quadrangle holds the light (`None`: none).
    pub ansi_c78377: Option<u32>,
    /// Whether the light meets JA8's colour clauses (`None` without a CCT).
    pub ja8: Option<bool>,
    /// The JA8 clauses it fails (`ra`, `r9`, `cct`, `duv`).
    pub ja8_fails: Vec<&'static str>,
}

/// The added figures of a light on the standards' grid, given its CIE 13.3 indices and CCT.
pub fn checks(s: &Spd, cri: Option<&Cri>, cct: Option<Cct>) -> Checks {
    let d = dominant(s.xy(), WHITE_E).ok();
    let a = alpha_opic(s);
    let clauses = match (cri, cct) {
        (Some(c), Some(t)) => ja8::ja8(c.ra, c.r[8], t.cct, t.duv).ok(),
        _ => None,
    };
    Checks {
        ri: cri.map(|c| c.r.map(r6)),
        r15: cri.map(|c| r6(c.r15)),
        peak_nm: peak(s).0,
        fwhm_nm: fwhm(s).map(r6),
        dominant_nm: d.map(|d| r3(d.wavelength)),
        purity: d.map(|d| r6(d.purity)),
        edi_sc: r6(a.edi[0]),
        edi_mc: r6(a.edi[1]),
        edi_lc: r6(a.edi[2]),
        edi_rh: r6(a.edi[3]),
        edi_mel: r6(a.edi[4]),
        der_sc: r6(a.der[0]),
        der_mc: r6(a.der[1]),
        der_lc: r6(a.der[2]),
        der_rh: r6(a.der[3]),
        der_mel: r6(a.der[4]),
        ansi_c78377: ansi_c78377::nominal_cct(s.xy()).map(|n| n.nominal),
        ja8: clauses.map(|c| c.iter().all(|c| c.pass)),
        ja8_fails: clauses
            .map(|c| c.iter().filter(|c| !c.pass).map(|c| c.key).collect())
            .unwrap_or_default(),
    }
}
