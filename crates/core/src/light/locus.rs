//! The Planckian locus as a small table, for a device: CCT (and Duv) → chromaticity without
//! Planck's law.
//!
//! [`super::cct`] computes the locus from its definition (Planck's law with
//! `c₂ = 1.4388·10⁻² m·K`, CIE 015:2018, summed at 1 nm against the CIE 1931 observer): 401
//! f64 `expm1` per point, too much for a microcontroller stepping a fade. Here the same exact
//! points are tabulated once, with their derivatives, at the nodes of a **mired grid**
//! (Robertson 1968 tabulates the locus on a mired grid, the scale on which it is smoothest):
//! CIE 1960 `(u, v)` and `d(u, v)/d(mired)` every 40 mired from 40 mired (25 000 K) to
//! 1000 mired (1000 K), 25 nodes (400 B of f32). Between nodes the locus is the **cubic Hermite**
//! interpolant of the values and derivatives (exact for cubics; error O(h⁴)).
//!
//! Error against the exact 1 nm Planck integration ([`super::cct::planck_uv`]), 9 601 points
//! over 1 000–25 000 K: at most **2.4·10⁻⁶ in u′v′** (near 10 000 K), 40× inside the 10⁻⁴
//! allowed; f32 evaluation adds a few 10⁻⁸ (unit tests below). The table's values are the
//! exact points rounded to f32; a unit test recomputes every node. Duv moves the point along
//! the locus normal (positive: above the locus, toward green; ANSI C78.377, Ohno 2013), the
//! normal taken from the interpolant's own tangent, whose direction is within 2.8·10⁻⁴ rad of
//! the exact one: at most 2.1·10⁻⁵ in u′v′ at |Duv| = 0.05, 4.2·10⁻⁷ per 0.001 of Duv (a
//! 20-mired grid would cut this to 2.6·10⁻⁶ for 384 B more flash).

/// Lowest CCT of the table, K (1000 mired).
pub const CCT_MIN: f32 = 1000.0;
/// Highest CCT of the table, K (40 mired).
pub const CCT_MAX: f32 = 25_000.0;
/// Largest |Duv| of a target (CIE 015:2018 §9.5: beyond it a CCT means nothing).
pub const DUV_MAX: f32 = 0.05;
/// Mired of the first node.
const MIRED_MIN: f32 = 40.0;
/// Mired between nodes.
const STEP: f32 = 40.0;

/// `[u, v, du/dmired, dv/dmired]` (CIE 1960) at `40 (i + 1)` mired.
const NODES: [[f32; 4]; 25] = [
    [0.18291527, 0.27413458, 9.018098e-05, 0.00029507413], // 40 mired, 25000 K
    [0.18738611, 0.28672144, 0.00013442687, 0.00032754274], // 80 mired, 12500 K
    [0.19369902, 0.29983342, 0.0001809267, 0.00032267542], // 120 mired, 8333 K
    [0.20179723, 0.3122053, 0.00022284177, 0.00029303643], // 160 mired, 6250 K
    [0.21142176, 0.32312983, 0.0002570092, 0.0002522307],  // 200 mired, 5000 K
    [0.22225027, 0.33235598, 0.00028313635, 0.00020919646], // 240 mired, 4167 K
    [0.23397775, 0.3398988, 0.00030215085, 0.00016857145], // 280 mired, 3571 K
    [0.24634345, 0.3459014, 0.00031524524, 0.00013237861], // 320 mired, 3125 K
    [0.25913334, 0.35055703, 0.00032353264, 0.0001012586], // 360 mired, 2778 K
    [0.27217475, 0.35406908, 0.0003279666, 7.515338e-05],  // 400 mired, 2500 K
    [0.28532994, 0.35663092, 0.00032934014, 5.3664622e-05], // 440 mired, 2273 K
    [0.29848987, 0.35841656, 0.0003283017, 3.6246973e-05], // 480 mired, 2083 K
    [0.31156892, 0.35957715, 0.00032537404, 2.2316008e-05], // 520 mired, 1923 K
    [0.32450017, 0.3602408, 0.000320973, 1.1308169e-05],   // 560 mired, 1786 K
    [0.33723152, 0.36051393, 0.00031542627, 2.7116944e-06], // 600 mired, 1667 K
    [0.34972247, 0.36048388, 0.00030899077, -3.920352e-06], // 640 mired, 1562 K
    [0.36194164, 0.3602214, 0.00030186778, -8.967795e-06], // 680 mired, 1471 K
    [0.37386486, 0.35978335, 0.00029421583, -1.2747102e-05], // 720 mired, 1389 K
    [0.38547355, 0.35921505, 0.00028616108, -1.55181e-05], // 760 mired, 1316 K
    [0.39675373, 0.35855252, 0.00027780526, -1.7491782e-05], // 800 mired, 1250 K
    [0.40769508, 0.35782406, 0.00026923185, -1.8838058e-05], // 840 mired, 1190 K
    [0.41829032, 0.357052, 0.00026051048, -1.9692914e-05], // 880 mired, 1136 K
    [0.42853472, 0.3562537, 0.00025170002, -2.0164673e-05], // 920 mired, 1087 K
    [0.4384258, 0.3554428, 0.00024285106, -2.0339328e-05], // 960 mired, 1042 K
    [0.44796288, 0.35462964, 0.00023400731, -2.0284984e-05], // 1000 mired, 1000 K
];

/// CIE 1960 `(u, v)` of the Planckian radiator at `cct` K and the locus tangent there
/// (`d(u, v)/d(mired)`); `None` outside [`CCT_MIN`]–[`CCT_MAX`] or not finite.
pub fn planck(cct: f32) -> Option<([f32; 2], [f32; 2])> {
    if !(CCT_MIN..=CCT_MAX).contains(&cct) {
        return None;
    }
    let x = (1e6 / cct - MIRED_MIN) / STEP;
    let i = (x as usize).min(NODES.len() - 2);
    let f = x - i as f32;
    let (a, b) = (NODES[i], NODES[i + 1]);
    // cubic Hermite basis on [0, 1] and its derivative (per unit of f)
    let (f2, f3) = (f * f, f * f * f);
    let h = [
        2.0 * f3 - 3.0 * f2 + 1.0,
        (f3 - 2.0 * f2 + f) * STEP,
        -2.0 * f3 + 3.0 * f2,
        (f3 - f2) * STEP,
    ];
    let d = [
        (6.0 * f2 - 6.0 * f) / STEP,
        3.0 * f2 - 4.0 * f + 1.0,
        (-6.0 * f2 + 6.0 * f) / STEP,
        3.0 * f2 - 2.0 * f,
    ];
    let at = |w: &[f32; 4], k: usize| w[0] * a[k] + w[1] * a[k + 2] + w[2] * b[k] + w[3] * b[k + 2];
    Some(([at(&h, 0), at(&h, 1)], [at(&d, 0), at(&d, 1)]))
}

/// CIE 1960 `(u, v)` of the point `duv` from the locus at `cct` K, along the normal with a
/// positive `v` component; `None` outside the table or beyond |Duv| [`DUV_MAX`].
pub fn uv(cct: f32, duv: f32) -> Option<[f32; 2]> {
    if !(duv.abs() <= DUV_MAX) {
        return None;
    }
    let (p, [du, dv]) = planck(cct)?;
    // √ by the powf the curves use: one routine less in a device's flash
    let h = crate::math::powf(du * du + dv * dv, 0.5);
    let (mut nu, mut nv) = (-dv / h, du / h);
    if nv < 0.0 {
        nu = -nu;
        nv = -nv;
    }
    Some([p[0] + duv * nu, p[1] + duv * nv])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::cct::{self, Cct};

    /// u′v′ distance of two CIE 1960 points.
    fn duv_prime(a: [f64; 2], b: [f64; 2]) -> f64 {
        libm::hypot(a[0] - b[0], 1.5 * (a[1] - b[1]))
    }

    #[test]
    fn every_node_is_the_exact_locus_rounded_to_f32() {
        for (i, n) in NODES.iter().enumerate() {
            let m = MIRED_MIN as f64 + STEP as f64 * i as f64;
            let p = cct::planck_uv(1e6 / m);
            let (a, b) = (
                cct::planck_uv(1e6 / (m + 1e-3)),
                cct::planck_uv(1e6 / (m - 1e-3)),
            );
            for k in 0..2 {
                assert!(
                    (n[k] as f64 - p[k]).abs() < 1e-7,
                    "node {i}: {n:?} vs {p:?}"
                );
                let d = (a[k] - b[k]) / 2e-3;
                assert!(
                    (n[k + 2] as f64 - d).abs() < 1e-7 + 1e-5 * d.abs(),
                    "node {i}"
                );
            }
        }
    }

    #[test]
    fn the_interpolant_is_within_3e_6_of_planck_from_1000_to_25000_k() {
        let mut worst = 0.0f64;
        for i in 0..=2000 {
            // even in mired, nodes included
            let m = 40.0 + 960.0 * i as f64 / 2000.0;
            let t = 1e6 / m;
            let (p, _) = planck(t as f32).unwrap();
            worst = worst.max(duv_prime(p.map(f64::from), cct::planck_uv(t)));
        }
        assert!(worst < 3e-6, "{worst}");
        assert!(planck(999.0).is_none() && planck(25_001.0).is_none());
        assert!(planck(f32::NAN).is_none());
    }

    #[test]
    fn duv_offsets_agree_with_the_exact_normal() {
        for t in [1000.0, 1500.0, 2700.0, 4000.0, 6500.0, 10_000.0, 25_000.0] {
            for d in [-0.05, -0.01, 0.0, 0.006, 0.05] {
                let exact = cct::cct_to_uv(Cct { cct: t, duv: d }).unwrap();
                let ours = uv(t as f32, d as f32).unwrap().map(f64::from);
                let e = duv_prime(ours, exact);
                // the point's error plus the tangent's direction error times |Duv|
                assert!(e < 3e-6 + 4.5e-4 * d.abs(), "{t} K duv {d}: {e}");
            }
        }
        assert!(uv(4000.0, 0.051).is_none() && uv(4000.0, f32::NAN).is_none());
    }
}
