//! Pass/fail criteria of a display verification: DisplayCAL's measurement-report tolerances and
//! ISO 14861:2015's colour-accuracy criteria, side by side.
//!
//! Every statistic compares each measured patch with its reference (the calibration's
//! prediction) in CIELAB relative to the display white, with CIEDE2000 (Sharma, Wu & Dalal 2005,
//! [`specpoly_core::de2000_terms`]):
//!
//! | id | statistic | DisplayCAL nominal / recommended | ISO 14861 |
//! |---|---|---|---|
//! | `mean_delta_e00` | mean ΔE00 over all patches | ≤ 1.5 / ≤ 1.0 | |
//! | `max_delta_e00` | maximum ΔE00 | ≤ 4 / ≤ 3 | |
//! | `white_delta_e00` | ΔE00 of the white patch (device 1, 1, 1; several are averaged in XYZ first) | ≤ 2 / ≤ 1 | |
//! | `grey_balance_delta_c00` | mean `\|ΔC′00\|` over the grey patches (R = G = B, measured Y ≥ 1 % of white) | ≤ 1.0 / ≤ 0.5 | |
//! | `iso14861_mean_delta_e00` | mean ΔE00 | | ≤ 2.5 |
//! | `iso14861_p99_delta_e00` | 99th percentile ΔE00 (nearest rank, [`specpoly_formats::stats::percentile`]) | | ≤ 4.5 |
//!
//! `ΔC′00` is CIEDE2000's weighted chroma term `ΔC′/(k_C·S_C)` with `k_C = 1`: `ΔC′ = C′₂ − C′₁`
//! is the difference of the chromas after `a*` is scaled by `1 + G`, and
//! `S_C = 1 + 0.045·(C′₁ + C′₂)/2` (Sharma et al. 2005, eqs. 2–4, 7, 15, 18); this is DisplayCAL's
//! "average absolute weighted ΔC′00" of its grey-balance rule. Tested against the C′ and S_C
//! columns of Sharma's Table 1 (`data/ciede2000/sharma2005_table1.csv`).
//!
//! A criterion whose patches are missing (no white or no grey patch measured) is reported as not
//! applicable and does not fail. `calibrate verify` fails (exit 1) when a criterion exceeds the
//! level it is asked to meet (`--require nominal`, the default, or `recommended`); ISO 14861 has
//! one level and counts at both. Sources: DisplayCAL 3's report criteria (`report.js`,
//! `CRITERIA_RULES_DEFAULT`/`_VERIFY`, `ISO_14861_COLOR_ACCURACY`); ISO 14861:2015 §5 as DisplayCAL
//! implements it.

use serde::Serialize;
use specpoly_core::{de2000_terms, Lab};
use specpoly_formats::stats::percentile;

/// One verified patch: its reference and measurement in CIELAB (relative to the display white)
/// and their difference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatchResult {
    /// The patch's number: its position among the file's measurements (1-based), as the fit
    /// numbers its outliers (`fit` and `verify` say "patch N"); for a 3D LUT, the source patch's.
    pub patch: usize,
    /// The patch's line in the measurement file (1-based).
    pub line: usize,
    /// Device RGB, 0–1.
    pub device: [f64; 3],
    /// The reference (prediction) XYZ.
    pub reference: [f64; 3],
    /// The measured XYZ.
    pub measured: [f64; 3],
    /// The reference's CIELAB.
    #[serde(serialize_with = "lab")]
    pub reference_lab: Lab,
    /// The measurement's CIELAB.
    #[serde(serialize_with = "lab")]
    pub measured_lab: Lab,
    /// CIEDE2000 from reference to measurement.
    pub delta_e00: f64,
    /// `ΔC′00` (signed; the criterion averages its absolute value).
    pub delta_c00: f64,
}

fn lab<S: serde::Serializer>(l: &Lab, s: S) -> Result<S::Ok, S::Error> {
    [l.l, l.a, l.b].serialize(s)
}

impl PatchResult {
    /// Compares `measured` with `reference` (XYZ) relative to `white`; the patch at `line`,
    /// numbered `line` too until its owner sets [`Self::patch`].
    pub fn new(
        line: usize,
        device: [f64; 3],
        reference: [f64; 3],
        measured: [f64; 3],
        white: [f64; 3],
    ) -> PatchResult {
        let reference_lab = Lab::from_xyz(reference, white);
        let measured_lab = Lab::from_xyz(measured, white);
        let t = de2000_terms(reference_lab, measured_lab);
        PatchResult {
            patch: line,
            line,
            device,
            reference,
            measured,
            reference_lab,
            measured_lab,
            delta_e00: t.delta_e(),
            delta_c00: t.weighted_dc(),
        }
    }

    /// Device white (1, 1, 1).
    pub fn is_white(&self) -> bool {
        self.device.iter().all(|&v| v >= 1.0 - 1e-9)
    }

    /// A grey: R = G = B, not black.
    pub fn is_grey(&self) -> bool {
        let [r, g, b] = self.device;
        (r - g).abs() < 1e-6 && (g - b).abs() < 1e-6 && r > 1e-9
    }
}

/// Which statistic a criterion bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// Mean ΔE00 over all patches.
    MeanDeltaE00,
    /// Maximum ΔE00.
    MaxDeltaE00,
    /// ΔE00 of the white patch.
    WhiteDeltaE00,
    /// Mean `|ΔC′00|` over grey patches at ≥ 1 % of white luminance.
    GreyMeanAbsDeltaC00,
    /// 99th percentile ΔE00 (nearest rank).
    P99DeltaE00,
}

/// A tolerance on one statistic.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Criterion {
    /// Stable key (JSON, HTML).
    pub id: &'static str,
    /// Whose tolerance: `DisplayCAL` or `ISO 14861`.
    pub standard: &'static str,
    /// What it bounds, in words.
    pub description: &'static str,
    /// The statistic.
    pub statistic: Statistic,
    /// The nominal tolerance (upper bound).
    pub nominal: f64,
    /// The recommended tolerance, where the standard has a second level.
    pub recommended: Option<f64>,
}

/// Grey patches below this fraction of white luminance are left out of the grey balance (as
/// DisplayCAL's `>= 1% luminance`).
pub const GREY_MIN_LUMINANCE: f64 = 0.01;

/// The criteria, DisplayCAL's then ISO 14861's.
pub const CRITERIA: [Criterion; 6] = [
    Criterion {
        id: "mean_delta_e00",
        standard: "DisplayCAL",
        description: "mean ΔE00",
        statistic: Statistic::MeanDeltaE00,
        nominal: 1.5,
        recommended: Some(1.0),
    },
    Criterion {
        id: "max_delta_e00",
        standard: "DisplayCAL",
        description: "maximum ΔE00",
        statistic: Statistic::MaxDeltaE00,
        nominal: 4.0,
        recommended: Some(3.0),
    },
    Criterion {
        id: "white_delta_e00",
        standard: "DisplayCAL",
        description: "white ΔE00",
        statistic: Statistic::WhiteDeltaE00,
        nominal: 2.0,
        recommended: Some(1.0),
    },
    Criterion {
        id: "grey_balance_delta_c00",
        standard: "DisplayCAL",
        description: "grey balance: mean |ΔC′00| (Y ≥ 1 % of white)",
        statistic: Statistic::GreyMeanAbsDeltaC00,
        nominal: 1.0,
        recommended: Some(0.5),
    },
    Criterion {
        id: "iso14861_mean_delta_e00",
        standard: "ISO 14861",
        description: "mean ΔE00",
        statistic: Statistic::MeanDeltaE00,
        nominal: 2.5,
        recommended: None,
    },
    Criterion {
        id: "iso14861_p99_delta_e00",
        standard: "ISO 14861",
        description: "99th percentile ΔE00",
        statistic: Statistic::P99DeltaE00,
        nominal: 4.5,
        recommended: None,
    },
];

/// The level `calibrate verify` requires.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// DisplayCAL's nominal tolerances (and ISO 14861).
    #[default]
    Nominal,
    /// DisplayCAL's recommended tolerances (and ISO 14861).
    Recommended,
}

/// A criterion judged on a set of patches.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// The criterion.
    #[serde(flatten)]
    pub criterion: Criterion,
    /// The statistic's value; `None` when no patch it needs was measured.
    pub value: Option<f64>,
    /// Patches the statistic is over.
    pub patches: usize,
    /// Within the nominal tolerance (`None`: not applicable).
    pub nominal_pass: Option<bool>,
    /// Within the recommended tolerance (`None`: not applicable or no such level).
    pub recommended_pass: Option<bool>,
}

impl Outcome {
    /// Whether this outcome fails `level` (a criterion without a recommended level is judged by
    /// its one tolerance).
    pub fn fails(&self, level: Level) -> bool {
        let at = match (level, self.recommended_pass) {
            (Level::Recommended, Some(p)) => Some(p),
            _ => self.nominal_pass,
        };
        at == Some(false)
    }

    /// The tolerance `level` judges by.
    pub fn tolerance(&self, level: Level) -> f64 {
        match level {
            Level::Recommended => self.criterion.recommended.unwrap_or(self.criterion.nominal),
            Level::Nominal => self.criterion.nominal,
        }
    }
}

/// The mean of `v`; `None` when empty.
fn mean(v: impl Iterator<Item = f64>) -> Option<(f64, usize)> {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n > 0 {
        Some((s / n as f64, n))
    } else {
        None
    }
}

/// The value of `statistic` over `patches` and how many patches it covers; `white` is the
/// display white the CIELAB values are relative to.
pub fn statistic(
    statistic: Statistic,
    patches: &[PatchResult],
    white: [f64; 3],
) -> (Option<f64>, usize) {
    let de = || patches.iter().map(|p| p.delta_e00);
    match statistic {
        Statistic::MeanDeltaE00 => mean(de()).map_or((None, 0), |(m, n)| (Some(m), n)),
        Statistic::MaxDeltaE00 => {
            let n = patches.len();
            let max = de().fold(None, |m: Option<f64>, x| {
                Some(match m {
                    // a NaN anywhere makes the maximum NaN, which fails every tolerance
                    Some(m) if m.is_nan() || x.is_nan() => f64::NAN,
                    Some(m) => m.max(x),
                    None => x,
                })
            });
            (max, n)
        }
        Statistic::P99DeltaE00 => {
            let mut v: Vec<f64> = de().collect();
            if v.is_empty() {
                return (None, 0);
            }
            v.sort_by(f64::total_cmp);
            (Some(percentile(&v, 0.99)), v.len())
        }
        Statistic::WhiteDeltaE00 => {
            let w: Vec<&PatchResult> = patches.iter().filter(|p| p.is_white()).collect();
            if w.is_empty() {
                return (None, 0);
            }
            let avg = |f: fn(&PatchResult) -> [f64; 3]| {
                let mut s = [0.0; 3];
                for p in &w {
                    for (k, v) in f(p).into_iter().enumerate() {
                        s[k] += v / w.len() as f64;
                    }
                }
                s
            };
            let r = PatchResult::new(
                w[0].line,
                [1.0; 3],
                avg(|p| p.reference),
                avg(|p| p.measured),
                white,
            );
            (Some(r.delta_e00), w.len())
        }
        Statistic::GreyMeanAbsDeltaC00 => mean(
            patches
                .iter()
                .filter(|p| p.is_grey() && p.measured[1] >= GREY_MIN_LUMINANCE * white[1])
                .map(|p| p.delta_c00.abs()),
        )
        .map_or((None, 0), |(m, n)| (Some(m), n)),
    }
}

/// Judges every criterion of [`CRITERIA`] on `patches`.
pub fn evaluate(patches: &[PatchResult], white: [f64; 3]) -> Vec<Outcome> {
    CRITERIA
        .iter()
        .map(|c| {
            let (value, n) = statistic(c.statistic, patches, white);
            // `!(v > t)` would pass a NaN; `v <= t` fails it
            let within = |t: f64| value.map(|v| v <= t);
            Outcome {
                criterion: *c,
                value,
                patches: n,
                nominal_pass: within(c.nominal),
                recommended_pass: c.recommended.and_then(within),
            }
        })
        .collect()
}

/// The outcomes that fail `level`, as one line (`mean ΔE00 2.10 > 1.5 (DisplayCAL nominal); …`),
/// or `None` when all pass.
pub fn failures(outcomes: &[Outcome], level: Level) -> Option<String> {
    let f: Vec<String> = outcomes
        .iter()
        .filter(|o| o.fails(level))
        .map(|o| {
            let name = match (o.criterion.standard, o.criterion.recommended) {
                (s, None) => s.to_string(),
                (s, Some(_)) => format!(
                    "{s} {}",
                    match level {
                        Level::Nominal => "nominal",
                        Level::Recommended => "recommended",
                    }
                ),
            };
            format!(
                "{} {:.2} > {} ({name})",
                o.criterion.description,
                o.value.unwrap_or(f64::NAN),
                o.tolerance(level)
            )
        })
        .collect();
    (!f.is_empty()).then(|| f.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn patch(device: [f64; 3], measured: [f64; 3]) -> PatchResult {
        let white = [95.047, 100.0, 108.883];
        let reference = if device == [1.0; 3] {
            white
        } else {
            device.map(|v| v * 50.0)
        };
        PatchResult::new(1, device, reference, measured, white)
    }

    #[test]
    fn exact_patches_pass_everything() {
        let white = [95.047, 100.0, 108.883];
        let p = vec![
            PatchResult::new(1, [1.0; 3], white, white, white),
            PatchResult::new(
                2,
                [0.5; 3],
                white.map(|v| v * 0.2),
                white.map(|v| v * 0.2),
                white,
            ),
        ];
        let o = evaluate(&p, white);
        assert_eq!(o.len(), CRITERIA.len());
        for o in &o {
            assert_eq!(o.value, Some(0.0), "{}", o.criterion.id);
            assert_eq!(o.nominal_pass, Some(true));
        }
        assert_eq!(failures(&o, Level::Recommended), None);
    }

    #[test]
    fn missing_greys_are_not_applicable_and_nan_fails() {
        let white = [95.047, 100.0, 108.883];
        let p = vec![patch([1.0, 0.0, 0.0], [f64::NAN, 1.0, 1.0])];
        let o = evaluate(&p, white);
        let by = |id: &str| o.iter().find(|o| o.criterion.id == id).unwrap();
        assert_eq!(by("grey_balance_delta_c00").nominal_pass, None);
        assert_eq!(by("white_delta_e00").value, None);
        assert_eq!(by("max_delta_e00").nominal_pass, Some(false));
        assert_eq!(by("mean_delta_e00").nominal_pass, Some(false));
        assert!(failures(&o, Level::Nominal)
            .unwrap()
            .contains("maximum ΔE00"));
    }
}
