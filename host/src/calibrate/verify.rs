//! Verification: how far a calibration's predictions are from measured patches, in CIEDE2000.
//!
//! Both the prediction and the measurement are converted to CIELAB relative to the
//! calibration's measured white (so the display white is `L* = 100, a* = b* = 0`, the usual
//! white-relative convention of display verification), and compared with ΔE00 (Sharma, Wu &
//! Dalal 2005). Tolerances are DisplayCAL's for a measurement report: nominal mean ≤ 1.5,
//! max ≤ 4; recommended mean ≤ 1, max ≤ 3.

use super::file::{Calibration, Stats};
use super::measurement::Measurement;
use specpoly_core::{delta_e2000, Lab};

/// DisplayCAL's nominal tolerance: (mean, max).
pub const NOMINAL: (f64, f64) = (1.5, 4.0);
/// DisplayCAL's recommended tolerance: (mean, max).
pub const RECOMMENDED: (f64, f64) = (1.0, 3.0);

/// ΔE00 between two XYZ relative to `white` (all in the same units).
pub fn delta_e00(a: [f64; 3], b: [f64; 3], white: [f64; 3]) -> f64 {
    delta_e2000(Lab::from_xyz(a, white), Lab::from_xyz(b, white))
}

/// ΔE00 of the calibration's prediction against each measurement (same units as the
/// calibration).
pub fn delta_e(cal: &Calibration, meas: &[Measurement]) -> Vec<f64> {
    let white = cal.data().white;
    meas.iter()
        .map(|m| delta_e00(cal.predict(m.device), m.xyz, white))
        .collect()
}

/// Mean, 95th percentile (nearest rank) and maximum.
pub fn stats(de: &[f64]) -> Stats {
    if de.is_empty() {
        return Stats::default();
    }
    let mut s = de.to_vec();
    s.sort_by(f64::total_cmp);
    let rank = ((0.95 * s.len() as f64).ceil() as usize).clamp(1, s.len());
    Stats {
        patches: s.len(),
        mean: s.iter().sum::<f64>() / s.len() as f64,
        p95: s[rank - 1],
        max: s[s.len() - 1],
    }
}

/// Whether statistics meet a (mean, max) tolerance.
pub fn passes(s: &Stats, tol: (f64, f64)) -> bool {
    s.mean <= tol.0 && s.max <= tol.1
}
