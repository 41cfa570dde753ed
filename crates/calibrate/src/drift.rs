//! Drift: a display (or an instrument) that changes while it is measured. Repeated readings
//! of one colour should agree within the instrument's repeatability; a white read at the start
//! and again at the end of a session that differ by more say that the display drifted (not
//! warmed up, a backlight or an ambient-light sensor that adjusts), and no model fits readings
//! that disagree with each other.
//!
//! The rule (`calibrate fit` reports it on the whole file, `calibrate run` on what it
//! measured): for the white `(1, 1, 1)` and the black `(0, 0, 0)`, each read at least twice,
//! the largest CIEDE2000 between two of its readings (CIELAB relative to the mean white) above
//! [`DRIFT_DE`], or for the white a luminance spread (largest − smallest over the mean) above
//! [`DRIFT_LUMINANCE`]. Both are well above what makers state for the short-term
//! repeatability of display colorimeters and spectroradiometers (a few tenths of a percent in
//! luminance, a few thousandths in x, y), so a reported drift is the display's.

use specpoly_core::delta_e2000_xyz;
use specpoly_formats::measurement::Measurement;

/// The largest CIEDE2000 between two readings of one colour taken as repeatability.
pub const DRIFT_DE: f64 = 0.5;
/// The largest luminance spread of the white's readings taken as repeatability (a fraction).
pub const DRIFT_LUMINANCE: f64 = 0.01;

/// One colour read several times whose readings disagree.
#[derive(Clone, Debug, PartialEq)]
pub struct Drift {
    /// `"white"` or `"black"`.
    pub what: &'static str,
    /// Its readings' positions in the measurements (1-based: the patch numbers).
    pub patches: Vec<usize>,
    /// The smallest and largest luminance read (the measurements' units).
    pub luminance: (f64, f64),
    /// `(largest − smallest) / mean` luminance.
    pub spread: f64,
    /// The largest CIEDE2000 between two readings (CIELAB relative to the mean white).
    pub delta_e00: f64,
}

impl Drift {
    /// One line for the fit's notes.
    pub fn note(&self) -> String {
        let list: Vec<String> = self.patches.iter().map(|p| p.to_string()).collect();
        format!(
            "the {} was read {} times (patches {}) and drifted: luminance {:.3}–{:.3} ({:.1} %), up to {:.2} ΔE00 apart, beyond an instrument's repeatability ({DRIFT_DE} ΔE00, {} %): the display changed while it was measured (let it warm up for 30 minutes; through --instrument argyll, drift=bw has dispread re-read white and black); no model fits readings that disagree",
            self.what,
            self.patches.len(),
            list.join(", "),
            self.luminance.0,
            self.luminance.1,
            100.0 * self.spread,
            self.delta_e00,
            100.0 * DRIFT_LUMINANCE
        )
    }
}

/// The white's and the black's repeated readings in `meas` that disagree (module docs).
pub fn check(meas: &[Measurement]) -> Vec<Drift> {
    let at = |v: f64| {
        meas.iter()
            .enumerate()
            .filter(|(_, m)| m.device.iter().all(|d| (d - v).abs() <= 1e-9))
            .map(|(i, m)| (i + 1, m.xyz))
            .collect::<Vec<_>>()
    };
    let whites = at(1.0);
    if whites.is_empty() {
        return Vec::new();
    }
    let n = whites.len() as f64;
    let white = [0, 1, 2].map(|c| whites.iter().map(|w| w.1[c]).sum::<f64>() / n);
    if !(white[1] > 0.0) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (what, reads) in [("white", whites), ("black", at(0.0))] {
        if reads.len() < 2 {
            continue;
        }
        let ys: Vec<f64> = reads.iter().map(|r| r.1[1]).collect();
        let lo = ys.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mean = ys.iter().sum::<f64>() / ys.len() as f64;
        let spread = if mean > 0.0 { (hi - lo) / mean } else { 0.0 };
        let mut de = 0.0f64;
        for (i, a) in reads.iter().enumerate() {
            for b in &reads[i + 1..] {
                de = de.max(delta_e2000_xyz(a.1, b.1, white));
            }
        }
        let luminance_drift = what == "white" && spread > DRIFT_LUMINANCE;
        if de > DRIFT_DE || luminance_drift {
            out.push(Drift {
                what,
                patches: reads.iter().map(|r| r.0).collect(),
                luminance: (lo, hi),
                spread,
                delta_e00: de,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(device: [f64; 3], xyz: [f64; 3]) -> Measurement {
        Measurement { device, xyz }
    }

    #[test]
    fn steady_readings_are_not_drift_and_a_dimming_white_is() {
        let steady = [
            m([1.0; 3], [95.0, 100.0, 108.0]),
            m([0.0; 3], [0.1, 0.1, 0.12]),
            m([0.5; 3], [20.0, 21.0, 23.0]),
            m([1.0; 3], [95.2, 100.2, 108.1]),
            m([0.0; 3], [0.1, 0.1, 0.12]),
        ];
        assert!(check(&steady).is_empty());
        // 12 % dimmer at the end: luminance spread 12/94 = 12.8 %
        let mut dim = steady.to_vec();
        dim.push(m([1.0; 3], [83.6, 88.0, 95.0]));
        let d = check(&dim);
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].what, "white");
        assert_eq!(d[0].patches, vec![1, 4, 6]);
        assert!(
            (d[0].spread - 12.2 / (288.2 / 3.0)).abs() < 1e-12,
            "{}",
            d[0].spread
        );
        assert!(d[0].note().contains("patches 1, 4, 6"));
    }
}
