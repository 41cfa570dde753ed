//! The ANSI/IES TM-30-20 report of one light (`specpoly light --tm30`, `--cvg`, `--report`):
//! Rf, Rg, CCT, Duv, the 16 hue bins (Rf,hj, Rcs,hj, Rhs,hj, the bins' mean a′, b′ and the
//! colour vector graphic's points), the 99 samples' fidelities Rf,CESi, the Annex E
//! design-intent levels, and what the report's plots draw: the light and its reference
//! normalised to equal luminous flux, and each sample's colour. Computed by
//! `specpoly_core::light::{tm30, design_intent}` on the standards' grid ([`Spd`]).

use crate::light::{extrapolated_from, standard_spd};
use crate::spectrum_names::Named;
use crate::{Error, Result};
use serde::Serialize;
use specpoly_core::colorimetry::bradford;
use specpoly_core::display::D65_XY;
use specpoly_core::light::design_intent::{design_intents, Intent};
use specpoly_core::light::reference::tm30_reference_spd;
use specpoly_core::light::samples::ces_table;
use specpoly_core::light::spd::START;
use specpoly_core::light::tm30::tm30_spd;
use specpoly_core::light::Spd;
use specpoly_core::{Display, GamutMap, Observer, Xyy, Xyz};

/// Rounds for printing (as `light` does).
fn r6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

/// One hue bin.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BinReport {
    /// Bin number, 1–16.
    pub bin: usize,
    /// The bin's hue range under the reference, degrees `[from, to)`.
    pub hue_deg: [f64; 2],
    /// How many of the 99 samples fall in it.
    pub samples: usize,
    /// Rf,hj.
    pub rf: f64,
    /// Rcs,hj in percent.
    pub rcs_percent: f64,
    /// Rhs,hj (radians).
    pub rhs: f64,
    /// Mean CAM02-UCS a′ of the bin's samples under the test light.
    pub test_a: f64,
    /// Mean b′ under the test light.
    pub test_b: f64,
    /// Mean a′ under the reference.
    pub reference_a: f64,
    /// Mean b′ under the reference.
    pub reference_b: f64,
    /// The colour vector graphic's arrow tail: the reference mean over its radius (on the unit
    /// circle).
    pub cvg_reference: [f64; 2],
    /// The arrow's tip: the test mean over the reference radius.
    pub cvg_test: [f64; 2],
}

/// One colour evaluation sample.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CesReport {
    /// CES number, 1–99.
    pub ces: usize,
    /// Its hue bin, 1–16.
    pub bin: usize,
    /// Rf,CESi.
    pub rf: f64,
}

/// Annex E priority levels: `P1`–`P3` or `P-`, `V1`–`V3` or `V-`, `F1`–`F3` or `F-`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct DesignIntents {
    /// Preference.
    pub preference: String,
    /// Vividness.
    pub vividness: String,
    /// Fidelity.
    pub fidelity: String,
}

/// The light and its reference on the light's grid, each normalised to equal luminous flux
/// (`Σ S ȳ`), both scaled so that the larger peak is 1 (what the report's spectrum plot
/// draws).
#[derive(Clone, Debug, PartialEq)]
pub struct SpdPair {
    /// Wavelengths, nm.
    pub nm: Vec<f64>,
    /// The test light.
    pub test: Vec<f64>,
    /// The reference illuminant (CIE 224:2017).
    pub reference: Vec<f64>,
}

/// The TM-30 report of a light (JSON keys as the field names).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Tm30Report {
    /// CCT, K.
    pub cct: f64,
    /// Duv.
    pub duv: f64,
    /// Rf.
    pub rf: f64,
    /// Rg.
    pub rg: f64,
    /// Annex E levels.
    pub design_intents: DesignIntents,
    /// The 16 hue bins.
    pub bins: Vec<BinReport>,
    /// The 99 samples.
    pub ces: Vec<CesReport>,
    /// The tabulated range when the end values were held to reach 380–780 nm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extrapolated_from_nm: Option<[f64; 2]>,
    /// The spectra the report plots (not in JSON).
    #[serde(skip)]
    pub spd: SpdPair,
    /// Each sample's colour under the reference, adapted to D65 (Bradford) and encoded as sRGB
    /// (out-of-gamut colours desaturated at equal luminance): the report's bar colours (not in
    /// JSON).
    #[serde(skip)]
    pub ces_srgb: Vec<[u8; 3]>,
}

fn level(intent: Intent, l: Option<u8>) -> String {
    match l {
        Some(k) => format!("{}{k}", intent.letter()),
        None => format!("{}-", intent.letter()),
    }
}

/// The TM-30 report of `light` (refused like `light` when short of 380–780 nm unless
/// `extrapolate`; an error when it has no CCT, i.e. farther than 0.05 Duv from the Planckian
/// locus).
pub fn tm30_report(light: &Named, extrapolate: bool) -> Result<Tm30Report> {
    let s = standard_spd(light, extrapolate)?;
    let err = |source| Error::Light {
        name: light.name.clone(),
        source,
    };
    let t = tm30_spd(&s).map_err(err)?;
    let reference = tm30_reference_spd(t.cct.cct, s.step()).map_err(err)?;
    let g = t.vector_graphic();
    let bins = (0..16)
        .map(|j| BinReport {
            bin: j + 1,
            hue_deg: [22.5 * j as f64, 22.5 * (j + 1) as f64],
            samples: t.bin_count[j] as usize,
            rf: r6(t.rf_h[j]),
            rcs_percent: r6(100.0 * t.rcs_h[j]),
            rhs: r6(t.rhs_h[j]),
            test_a: r6(t.test_ab[j][0]),
            test_b: r6(t.test_ab[j][1]),
            reference_a: r6(t.reference_ab[j][0]),
            reference_b: r6(t.reference_ab[j][1]),
            cvg_reference: g.reference[j].map(r6),
            cvg_test: g.test[j].map(r6),
        })
        .collect();
    let ces = (0..99)
        .map(|i| CesReport {
            ces: i + 1,
            bin: t.bin_of[i] as usize + 1,
            rf: r6(t.rf_i[i]),
        })
        .collect();
    let [p, v, f] = design_intents(&t);
    Ok(Tm30Report {
        cct: (t.cct.cct * 100.0).round() / 100.0,
        duv: r6(t.cct.duv),
        rf: r6(t.rf),
        rg: r6(t.rg),
        design_intents: DesignIntents {
            preference: level(Intent::Preference, p),
            vividness: level(Intent::Vividness, v),
            fidelity: level(Intent::Fidelity, f),
        },
        bins,
        ces,
        extrapolated_from_nm: extrapolated_from(light, &s),
        spd: spd_pair(&s, &reference),
        ces_srgb: ces_colours(&reference),
    })
}

fn spd_pair(test: &Spd, reference: &Spd) -> SpdPair {
    let unit = |s: &Spd| {
        let y = s.sums(Observer::Cie1931)[1];
        s.values().iter().map(|v| v / y).collect::<Vec<f64>>()
    };
    let (mut t, mut r) = (unit(test), unit(reference));
    let peak = t.iter().chain(&r).fold(0.0f64, |m, v| m.max(*v));
    if peak > 0.0 {
        t.iter_mut().chain(r.iter_mut()).for_each(|v| *v /= peak);
    }
    let nm = (0..t.len())
        .map(|i| START + (i * test.step()) as f64)
        .collect();
    SpdPair {
        nm,
        test: t,
        reference: r,
    }
}

fn ces_colours(reference: &Spd) -> Vec<[u8; 3]> {
    let white = reference.sums(Observer::Cie1931);
    let k = 1.0 / white[1];
    let d65 = Xyy {
        x: D65_XY[0],
        y: D65_XY[1],
        big_y: 1.0,
    }
    .to_xyz();
    let from = Xyz::new(white[0] * k, 1.0, white[2] * k);
    let to = Xyz::new(d65.x as f64, d65.y as f64, d65.z as f64);
    let adapt = bradford(from, to);
    let srgb = Display::srgb();
    (0..99)
        .map(|i| {
            let t = ces_table(i);
            let step = reference.step() as f64;
            let xyz = reference
                .sums_with(Observer::Cie1931, |j| t.at(START + j as f64 * step))
                .map(|v| v * k);
            let [x, y, z] = adapt.apply(xyz);
            let e = srgb.encode(Xyz::new(x as f32, y as f32, z as f32), GamutMap::Desaturate);
            e.device.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect()
}
