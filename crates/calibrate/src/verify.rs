//! Verification: how far a calibration's predictions are from measured patches, in CIEDE2000.
//!
//! Both the prediction and the measurement are converted to CIELAB relative to the
//! calibration's measured white (so the display white is `L* = 100, a* = b* = 0`, the usual
//! white-relative convention of display verification), and compared with ΔE00 (Sharma, Wu &
//! Dalal 2005). [`Verification`] holds every patch's result and the pass/fail outcome of
//! DisplayCAL's and ISO 14861's criteria ([`crate::criteria`]); `calibrate verify` prints it as
//! text or JSON and draws it as an HTML page ([`crate::report_html`]).
//!
//! A 3D LUT is verified the same way without measuring ([`Verification::lut3d`]): each source
//! patch goes through the LUT (tetrahedral interpolation) and the display's model, and what
//! the model predicts the display shows is compared with the colour the source asks for.

use crate::criteria::{self, Outcome, PatchResult};
use crate::error::{Error, Result};
use specpoly_core::delta_e2000_xyz;
use specpoly_core::display_model::FULL;
use specpoly_core::{DisplayModel, Xyz};
use specpoly_display::calibration::Calibration;
use specpoly_display::lut3d::{Lut3d, Target};
use specpoly_formats::measurement::Measurement;
use specpoly_formats::stats::Stats;

/// DisplayCAL's nominal tolerance: (mean, max).
pub const NOMINAL: (f64, f64) = (1.5, 4.0);
/// DisplayCAL's recommended tolerance: (mean, max).
pub const RECOMMENDED: (f64, f64) = (1.0, 3.0);

/// ΔE00 of the calibration's prediction against each measurement (same units as the
/// calibration).
pub fn delta_e(cal: &Calibration, meas: &[Measurement]) -> Vec<f64> {
    let white = cal.data().white;
    meas.iter()
        .map(|m| delta_e2000_xyz(cal.predict(m.device), m.xyz, white))
        .collect()
}

/// The .ti3's measurements in the calibration's units: absolute if both can be; otherwise
/// relative ones scaled by the calibration's white (see docs/calibration.md). Readings a fit
/// would refuse are refused here too ([`crate::readings::check_readings`]): a reading of 1e200
/// would make the mean ΔE00 NaN and hide the patch from the maximum.
pub fn measurements_for(
    cal: &Calibration,
    ti3: &specpoly_formats::cgats::Ti3,
) -> Result<Vec<Measurement>> {
    let (m, abs) = ti3.best_units();
    crate::readings::check_readings(&m)?;
    let k = match (cal.absolute(), abs) {
        (true, true) | (false, false) => 1.0,
        // relative (white Y = 100) → the calibration's cd/m²
        (true, false) => cal.data().white[1] / 100.0,
        // absolute → relative: the file's own white patch to Y = 100
        (false, true) => {
            let w = specpoly_formats::cgats::white_patch(&m).ok_or(Error::NoWhitePatch)?;
            100.0 / w[1]
        }
    };
    Ok(m.into_iter()
        .map(|p| Measurement {
            device: p.device,
            xyz: p.xyz.map(|v| v * k),
        })
        .collect())
}

/// Whether `readings` (a file's bytes) are the readings `cal` was fitted from: their SHA-256
/// is the one its `[provenance]` records (`readings_sha256`; absent in older files: false).
pub fn fitted_from(cal: &Calibration, readings: &[u8]) -> bool {
    let recorded = &cal.data().provenance.readings_sha256;
    !recorded.is_empty() && crate::session::sha256_hex(readings).eq_ignore_ascii_case(recorded)
}

/// The patches of `meas` (1-based positions) that the fit of `cal` dropped as bad readings
/// (its `[fit] outliers`, numbered by position in the file it was fitted from): those whose
/// position and device values match, when `meas` are that file's readings (`same_file`, see
/// [`fitted_from`]); none otherwise (another file's reading of the same colour is a new
/// reading).
pub fn fit_outliers(cal: &Calibration, meas: &[Measurement], same_file: bool) -> Vec<usize> {
    if !same_file {
        return Vec::new();
    }
    cal.data()
        .fit
        .outliers
        .iter()
        .filter(|o| {
            o.patch >= 1
                && meas
                    .get(o.patch - 1)
                    .is_some_and(|m| (0..3).all(|c| (m.device[c] - o.device[c]).abs() <= 1e-6))
        })
        .map(|o| o.patch)
        .collect()
}

/// A calibration checked against measured patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Verification {
    /// Every patch, in file order.
    pub patches: Vec<PatchResult>,
    /// ΔE00 count, mean, 95th percentile and maximum.
    pub stats: Stats,
    /// Each criterion of [`criteria::CRITERIA`], judged.
    pub outcomes: Vec<Outcome>,
    /// The white the CIELAB values are relative to (the calibration's).
    pub white: [f64; 3],
}

impl Verification {
    /// Compares the calibration's prediction of each measurement's device values with the
    /// measurement; `lines` are the measurements' lines in their file (1-based, same order).
    pub fn new(cal: &Calibration, meas: &[Measurement], lines: &[usize]) -> Verification {
        Self::excluding(cal, meas, lines, &[]).0
    }

    /// [`Self::new`] without the patches numbered in `exclude` (1-based positions in `meas`,
    /// the numbering of the fit's outliers: [`fit_outliers`]): the verification and the
    /// patches left out, each with its ΔE00.
    pub fn excluding(
        cal: &Calibration,
        meas: &[Measurement],
        lines: &[usize],
        exclude: &[usize],
    ) -> (Verification, Vec<PatchResult>) {
        let white = cal.data().white;
        let (mut patches, mut left_out) = (Vec::new(), Vec::new());
        for (i, m) in meas.iter().enumerate() {
            let line = lines.get(i).copied().unwrap_or(i + 1);
            let mut r = PatchResult::new(line, m.device, cal.predict(m.device), m.xyz, white);
            r.patch = i + 1;
            if exclude.contains(&(i + 1)) {
                left_out.push(r);
            } else {
                patches.push(r);
            }
        }
        let de: Vec<f64> = patches.iter().map(|p| p.delta_e00).collect();
        let v = Verification {
            stats: Stats::of(&de),
            outcomes: criteria::evaluate(&patches, white),
            patches,
            white,
        };
        (v, left_out)
    }

    /// A 3D LUT on a display, predicted through its model: for each source patch `c` (encoded
    /// source RGB) whose colour `target.xyz(c)` the display shows (inside the gamut: the
    /// matrix test of [`Target::in_gamut`] and the model's inverse reaching it), the reference
    /// is that colour and the "measurement" the model's prediction at the LUT's device values
    /// `lut.apply(c)`; CIELAB relative to the display's white. Patch numbers are 1-based
    /// positions in `sources`. Returns the verification and the number of patches outside the
    /// gamut, not counted.
    pub fn lut3d(
        model: &DisplayModel<FULL>,
        lut: &Lut3d,
        target: &Target,
        sources: &[[f64; 3]],
    ) -> (Verification, usize) {
        let white = target.white();
        let mut outside = 0;
        let mut patches = Vec::with_capacity(sources.len());
        for (i, c) in sources.iter().enumerate() {
            let want = target.xyz(*c);
            let shown = target.in_gamut(want)
                && model.inverse(Xyz::from_array(want.map(|v| v as f32))).exact;
            if !shown {
                outside += 1;
                continue;
            }
            let device = lut.apply(*c).map(|v| v as f32);
            let got: [f64; 3] = model.device_to_xyz(device).into();
            patches.push(PatchResult::new(i + 1, *c, want, got, white));
        }
        let de: Vec<f64> = patches.iter().map(|p| p.delta_e00).collect();
        let v = Verification {
            stats: Stats::of(&de),
            outcomes: criteria::evaluate(&patches, white),
            patches,
            white,
        };
        (v, outside)
    }

    /// The patch with the largest ΔE00 (a NaN counts as largest).
    pub fn worst(&self) -> Option<&PatchResult> {
        self.patches
            .iter()
            .max_by(|a, b| a.delta_e00.total_cmp(&b.delta_e00))
    }
}
