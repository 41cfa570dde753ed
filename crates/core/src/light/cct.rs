//! CIE 1960 UCS, correlated colour temperature (CCT) and Duv.
//!
//! The CCT of a light is the temperature of the Planckian radiator whose chromaticity is
//! nearest in the CIE 1960 (u, v) diagram; Duv is that distance, positive above the locus
//! (CIE 015:2018 §9.5; ANSI C78.377). Robertson (1968) and Ohno (2013) approximate this minimum
//! from tables; here it is found directly: the Planckian chromaticity is computed from Planck's
//! law with `c₂ = 1.4388·10⁻² m·K` (CIE 015:2018) against the CIE 1931 observer at 1 nm over
//! 380–780 nm (the same sums as every light's), the distance is scanned on a ≈ 20 mired grid
//! over 10–1000 mired (100 000 K to 1000 K) and refined by successive parabolic interpolation
//! to 10⁻⁵ mired (the last steps with the full 1 nm sums). The result equals the definition to better than 0.01 K at 10 000 K (10⁻⁵ mired
//! is 0.001 K there; the unit tests round-trip locus points to 2·10⁻⁵ relative); Ohno (2013)
//! states ±1 K for its cascade.
//!
//! CCT is undefined farther than |Duv| = 0.05 from the locus ([`LightError::NoCct`]).

use super::{reference::planck, LightError};
use crate::Observer;

/// Largest |Duv| for which a CCT is reported (CIE 015:2018 §9.5).
pub const DUV_MAX: f64 = 0.05;
/// Lowest CCT searched, K.
pub const CCT_MIN: f64 = 1000.0;
/// Highest CCT searched, K.
pub const CCT_MAX: f64 = 100_000.0;

/// A correlated colour temperature and the signed distance from the Planckian locus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cct {
    /// Correlated colour temperature, K.
    pub cct: f64,
    /// Signed distance in CIE 1960 (u, v), positive above (greener than) the locus.
    pub duv: f64,
}

/// CIE 1960 `(u, v)` of tristimulus values: `u = 4X / (X + 15Y + 3Z)`, `v = 6Y / (X + 15Y + 3Z)`.
pub fn uv_1960(xyz: [f64; 3]) -> [f64; 2] {
    let d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
    [4.0 * xyz[0] / d, 6.0 * xyz[1] / d]
}

/// CIE 1931 `(x, y)` from CIE 1960 `(u, v)`.
pub fn uv_to_xy(uv: [f64; 2]) -> [f64; 2] {
    let [u, v] = uv;
    let d = 2.0 * u - 8.0 * v + 4.0;
    [3.0 * u / d, 2.0 * v / d]
}

/// CIE 1960 `(u, v)` from CIE 1931 `(x, y)`.
pub fn xy_to_uv(xy: [f64; 2]) -> [f64; 2] {
    let [x, y] = xy;
    let d = -2.0 * x + 12.0 * y + 3.0;
    [4.0 * x / d, 6.0 * y / d]
}

/// CIE 1960 `(u, v)` of a Planckian radiator at `t` kelvin (CIE 1931 observer, 1 nm sums).
pub fn planck_uv(t: f64) -> [f64; 2] {
    planck_uv_step(t, 1)
}

/// The same sums at every `step` nm (a cheaper estimate for the coarse scan).
fn planck_uv_step(t: f64, step: usize) -> [f64; 2] {
    let mut xyz = [0.0f64; 3];
    for (i, cmf) in Observer::Cie1931.table().iter().enumerate().step_by(step) {
        let p = planck(380.0 + i as f64, t);
        for k in 0..3 {
            xyz[k] += p * cmf[k] as f64;
        }
    }
    uv_1960(xyz)
}

fn dist2(uv: [f64; 2], p: [f64; 2]) -> f64 {
    (uv[0] - p[0]) * (uv[0] - p[0]) + (uv[1] - p[1]) * (uv[1] - p[1])
}

/// CCT and Duv of a chromaticity given in CIE 1960 `(u, v)` (see the module docs): a scan at
/// ≈ 20 mired steps with 10 nm sums, then successive parabolic interpolation of the squared
/// distance, the bracket shrinking tenfold per step down to 10⁻⁵ mired (5 nm sums while it is
/// wider than 0.1 mired, 1 nm sums after).
pub fn cct_duv(uv: [f64; 2]) -> Result<Cct, LightError> {
    let no = LightError::NoCct { u: uv[0], v: uv[1] };
    if !uv[0].is_finite() || !uv[1].is_finite() {
        return Err(no);
    }
    let (lo_m, hi_m) = (1e6 / CCT_MAX, 1e6 / CCT_MIN);
    let steps = 50;
    let h0 = (hi_m - lo_m) / steps as f64;
    let mut best = (f64::INFINITY, lo_m);
    for i in 0..=steps {
        let m = lo_m + h0 * i as f64;
        let d = dist2(uv, planck_uv_step(1e6 / m, 10));
        if d < best.0 {
            best = (d, m);
        }
    }
    // `max(lo).min(hi)`, not `clamp`: the same for every non-NaN value, and without `clamp`'s
    // formatted assertion, whose f64 formatting is 20 KiB of a device's flash (docs/c.md)
    let within = |v: f64, lo: f64, hi: f64| v.max(lo).min(hi);
    // 5 nm sums while the bracket is wider than 0.1 mired, 1 nm sums after
    let f = |m: f64, step: usize| dist2(uv, planck_uv_step(1e6 / within(m, lo_m, hi_m), step));
    let mut m = best.1;
    let mut h = h0;
    let mut moves = 0;
    while h > 1e-5 {
        let st = if h > 0.1 { 5 } else { 1 };
        let (fa, fm, fb) = (f(m - h, st), f(m, st), f(m + h, st));
        let curv = fa - 2.0 * fm + fb;
        let step = if curv > 0.0 {
            within(0.5 * h * (fa - fb) / curv, -h, h)
        } else if fa < fb {
            -h
        } else {
            h
        };
        m = within(m + step, lo_m, hi_m);
        // a step that reached the bracket's edge may not have reached the minimum: step again
        // at this scale (bounded) before shrinking
        if step.abs() < h || moves >= 20 {
            h *= 0.1;
            moves = 0;
        } else {
            moves += 1;
        }
    }
    if m <= lo_m + 1e-3 || m >= hi_m - 1e-3 {
        return Err(no);
    }
    let t = 1e6 / m;
    let p = planck_uv(t);
    let dist = libm::sqrt(dist2(uv, p));
    let duv = if uv[1] >= p[1] { dist } else { -dist };
    if duv.abs() > DUV_MAX {
        return Err(no);
    }
    Ok(Cct { cct: t, duv })
}

/// CIE 1960 `(u, v)` of the point at `cct` K on the Planckian locus moved `duv` along the
/// locus normal (positive: above). The normal is from the locus tangent at `cct` by central
/// differences of ±0.01 K (as Ohno 2013).
pub fn cct_to_uv(c: Cct) -> Result<[f64; 2], LightError> {
    if !(CCT_MIN..=CCT_MAX).contains(&c.cct) || !c.duv.is_finite() || c.duv.abs() > DUV_MAX {
        return Err(LightError::BadTarget);
    }
    let p = planck_uv(c.cct);
    let p0 = planck_uv(c.cct - 0.01);
    let p1 = planck_uv(c.cct + 0.01);
    let (du, dv) = (p1[0] - p0[0], p1[1] - p0[1]);
    let h = libm::sqrt(du * du + dv * dv);
    // the unit normal with positive v component
    let (mut nu, mut nv) = (-dv / h, du / h);
    if nv < 0.0 {
        nu = -nu;
        nv = -nv;
    }
    Ok([p[0] + c.duv * nu, p[1] + c.duv * nv])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planckian_points_round_trip() {
        for t in [1500.0, 2700.0, 4000.0, 6500.0, 10000.0, 20000.0] {
            for duv in [-0.045, -0.02, 0.0, 0.01, 0.045] {
                let uv = cct_to_uv(Cct { cct: t, duv }).unwrap();
                let c = cct_duv(uv).unwrap();
                assert!((c.cct - t).abs() < 0.02 * t / 1000.0, "{t} {duv} {c:?}");
                assert!((c.duv - duv).abs() < 1e-6, "{t} {duv} {c:?}");
            }
        }
    }

    #[test]
    fn far_from_locus_has_no_cct() {
        assert!(cct_duv(xy_to_uv([0.7, 0.29])).is_err());
        assert!(cct_duv(xy_to_uv([0.17, 0.7])).is_err());
        assert!(cct_duv([f64::NAN, 0.3]).is_err());
    }
}
