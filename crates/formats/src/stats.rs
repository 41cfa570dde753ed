//! Summary statistics of colour differences (ΔE00): count, mean, nearest-rank 95th percentile
//! and maximum. One definition for the accuracy report, the renderer's comparisons and the
//! calibration fit and verification.
//!
//! The percentile is the nearest rank (Hyndman & Fan 1996, definition 1): the `⌈p·n⌉`-th
//! smallest value, so it is always one of the values.

use serde::{Deserialize, Serialize};

/// Count, mean, 95th percentile and maximum of a set of values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Number of values (patches, colours or pixels). Calibration files call it `patches`.
    #[serde(rename = "patches")]
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// 95th percentile (nearest rank).
    pub p95: f64,
    /// Maximum.
    pub max: f64,
}

/// The nearest-rank `p`-quantile (`0 < p ≤ 1`) of values sorted in increasing order: the
/// `⌈p·n⌉`-th smallest; 0 when empty.
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let n = sorted.len();
    let rank = ((p * n as f64).ceil() as usize).clamp(1, n);
    sorted[rank - 1]
}

impl Stats {
    /// Statistics of `v` (all zero when empty).
    pub fn of(v: &[f64]) -> Stats {
        if v.is_empty() {
            return Stats::default();
        }
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        let n = s.len();
        Stats {
            n,
            mean: s.iter().sum::<f64>() / n as f64,
            p95: percentile(&s, 0.95),
            max: s[n - 1],
        }
    }

    /// Whether the statistics meet a `(mean, max)` tolerance.
    pub fn within(&self, tolerance: (f64, f64)) -> bool {
        self.mean <= tolerance.0 && self.max <= tolerance.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_rank() {
        let v: Vec<f64> = (1..=20).map(f64::from).collect();
        let s = Stats::of(&v);
        assert_eq!((s.n, s.mean, s.p95, s.max), (20, 10.5, 19.0, 20.0));
        assert_eq!(Stats::of(&[]), Stats::default());
        assert_eq!(percentile(&[3.0], 0.95), 3.0);
    }
}
