//! ANSI C78.377-2017 (chromaticity of solid-state lighting products): the ten nominal CCTs
//! and their quadrangles.
//!
//! Each nominal CCT has a target (CCT, Duv) and a quadrangle in the CIE 1931 (x, y) diagram
//! whose corners lie on the isotemperature lines at the target CCT ± its tolerance, 0.006 in
//! Duv above and below the target Duv line (the standard's "7-step" tolerance: the quadrangles
//! are sized like 7-step MacAdam ellipses). A light *meets* a nominal CCT when its (x, y) lies in
//! that quadrangle (edges included).
//!
//! **The corners.** 2700–6500 K: the corner coordinates of the 2015 edition's Table 1, which
//! the 2017 edition keeps, as public code reproduces them (four decimals; the standard itself
//! was not available here). They agree with the targets of [`NOMINAL`] (the standard's Table 1
//! as quoted by its users): the centres to 1.4·10⁻⁴ in x, y, and the corners' Duv are the
//! target line `57700/T² − 44.6/T + 0.0085` (the 2015 edition's Duv of a flexible CCT) ± 0.006
//! at the boundary CCTs, to 2.6·10⁻⁴ (tested). 2200 K and 2500 K (added in 2015): corners
//! computed here by the rule the 2700 K corners follow to 4·10⁻⁵ (target Duv 0 ± 0.006 at the
//! target CCT ± tolerance), rounded to four decimals, sharing 2700 K's corners where the
//! quadrangles meet.

/// A nominal CCT of ANSI C78.377-2017.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nominal {
    /// Nominal CCT, K.
    pub nominal: u32,
    /// Target CCT, K.
    pub cct: f64,
    /// CCT tolerance, ± K.
    pub cct_tolerance: f64,
    /// Target Duv.
    pub duv: f64,
    /// The quadrangle's corners (x, y), in order around it from the upper warm corner.
    pub corners: [[f64; 2]; 4],
    /// The centre (x, y) the standard tabulates.
    pub centre: [f64; 2],
}

/// Duv tolerance of every nominal CCT (± 0.006).
pub const DUV_TOLERANCE: f64 = 0.006;

/// The ten nominal CCTs, warmest first.
#[allow(clippy::approx_constant)] // tabulated coordinates (0.4342), not log10(e)
pub const NOMINAL: [Nominal; 10] = [
    Nominal {
        nominal: 2200,
        cct: 2238.0,
        cct_tolerance: 102.0,
        duv: 0.0,
        corners: [
            [0.5259, 0.4342],
            [0.4993, 0.3967],
            [0.4799, 0.3967],
            [0.5045, 0.4344],
        ],
        centre: [0.5018, 0.4153],
    },
    Nominal {
        nominal: 2500,
        cct: 2470.0,
        cct_tolerance: 109.0,
        duv: 0.0,
        corners: [
            [0.5023, 0.4343],
            [0.4780, 0.3966],
            [0.4593, 0.3944],
            [0.4813, 0.4319],
        ],
        centre: [0.4797, 0.4140],
    },
    Nominal {
        nominal: 2700,
        cct: 2725.0,
        cct_tolerance: 145.0,
        duv: 0.0,
        corners: [
            [0.4813, 0.4319],
            [0.4593, 0.3944],
            [0.4373, 0.3893],
            [0.4562, 0.4260],
        ],
        centre: [0.4578, 0.4101],
    },
    Nominal {
        nominal: 3000,
        cct: 3045.0,
        cct_tolerance: 175.0,
        duv: 0.0001,
        corners: [
            [0.4562, 0.4260],
            [0.4373, 0.3893],
            [0.4150, 0.3821],
            [0.4303, 0.4173],
        ],
        centre: [0.4339, 0.4033],
    },
    Nominal {
        nominal: 3500,
        cct: 3465.0,
        cct_tolerance: 245.0,
        duv: 0.0005,
        corners: [
            [0.4303, 0.4173],
            [0.4150, 0.3821],
            [0.3895, 0.3709],
            [0.4003, 0.4035],
        ],
        centre: [0.4078, 0.3930],
    },
    Nominal {
        nominal: 4000,
        cct: 3985.0,
        cct_tolerance: 275.0,
        duv: 0.0010,
        corners: [
            [0.4003, 0.4035],
            [0.3895, 0.3709],
            [0.3671, 0.3583],
            [0.3737, 0.3880],
        ],
        centre: [0.3818, 0.3797],
    },
    Nominal {
        nominal: 4500,
        cct: 4503.0,
        cct_tolerance: 243.0,
        duv: 0.0015,
        corners: [
            [0.3737, 0.3882],
            [0.3672, 0.3585],
            [0.3514, 0.3482],
            [0.3550, 0.3754],
        ],
        centre: [0.3613, 0.3670],
    },
    Nominal {
        nominal: 5000,
        cct: 5029.0,
        cct_tolerance: 283.0,
        duv: 0.0020,
        corners: [
            [0.3550, 0.3753],
            [0.3515, 0.3481],
            [0.3366, 0.3373],
            [0.3375, 0.3619],
        ],
        centre: [0.3446, 0.3551],
    },
    Nominal {
        nominal: 5700,
        cct: 5667.0,
        cct_tolerance: 355.0,
        duv: 0.0025,
        corners: [
            [0.3375, 0.3619],
            [0.3366, 0.3374],
            [0.3221, 0.3256],
            [0.3205, 0.3476],
        ],
        centre: [0.3287, 0.3425],
    },
    Nominal {
        nominal: 6500,
        cct: 6532.0,
        cct_tolerance: 510.0,
        duv: 0.0031,
        corners: [
            [0.3205, 0.3477],
            [0.3221, 0.3255],
            [0.3067, 0.3119],
            [0.3026, 0.3311],
        ],
        centre: [0.3123, 0.3283],
    },
];

/// Whether `xy` lies in the convex quadrangle `q` (edges included).
pub fn inside(q: &[[f64; 2]; 4], xy: [f64; 2]) -> bool {
    let mut sign = 0.0f64;
    for i in 0..4 {
        let (a, b) = (q[i], q[(i + 1) % 4]);
        let c = (b[0] - a[0]) * (xy[1] - a[1]) - (b[1] - a[1]) * (xy[0] - a[0]);
        if c != 0.0 {
            if sign != 0.0 && c.signum() != sign {
                return false;
            }
            sign = c.signum();
        }
    }
    true
}

/// The nominal CCT whose quadrangle holds `xy`, if any.
pub fn nominal_cct(xy: [f64; 2]) -> Option<&'static Nominal> {
    NOMINAL.iter().find(|n| inside(&n.corners, xy))
}

/// The nominal CCT named `k` kelvin (2200, 2500, …, 6500).
pub fn by_name(k: u32) -> Option<&'static Nominal> {
    NOMINAL.iter().find(|n| n.nominal == k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_are_inside_their_own_quadrangle_only() {
        for n in &NOMINAL {
            assert_eq!(nominal_cct(n.centre).map(|m| m.nominal), Some(n.nominal));
        }
        // far from white: none
        assert_eq!(nominal_cct([0.6, 0.3]), None);
    }

    #[test]
    fn corners_are_inclusive() {
        for n in &NOMINAL {
            for c in n.corners {
                assert!(inside(&n.corners, c));
            }
        }
    }
}
