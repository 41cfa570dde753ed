//! Colorimetry: XYZ, xyY, CIELAB, CIEDE2000 and Bradford chromatic adaptation.
//!
//! Sources: CIE 015:2018 (xyY, CIELAB); Sharma, Wu & Dalal, "The CIEDE2000 colour-difference
//! formula: implementation notes, supplementary test data, and mathematical observations",
//! Color Res. Appl. 30 (2005) — the formula as written there, tested on its 34 pairs; Lam (1985)
//! for the Bradford matrix.
//!
//! `palette` implements Lab and CIEDE2000 too; we keep ~80 lines here so `specpoly-core` has no
//! dependency beyond `libm`/`heapless` on a microcontroller, and the host tests cross-check
//! against palette and Sharma's data.
//!
//! Component types follow the crate's policy (crate docs): [`Xyz`] is f32 in the kernels (the
//! default) or f64 at the host's edges, [`Xyy`] is f32, [`Lab`] and CIEDE2000 are f64;
//! [`bradford`] works at either type from the one [`BRADFORD`] table. Arithmetic where it
//! means something: tristimulus values add and scale (light adds, [`Xyz`]); CIELAB
//! coordinates subtract to a difference vector and average (`Add`, `Sub`, `Mul<f64>` on
//! [`Lab`]); chromaticities do neither (a mixture's chromaticity is not the sum of the
//! parts'), so [`Xyy`] has no arithmetic.
//! Conversions are named `from_xyz`/`to_xyz`.

use crate::matrix::Real;
use crate::Mat3;
use core::ops::{Add, Mul, Sub};

/// Chromaticity `x = X/(X+Y+Z)`, `y = Y/(X+Y+Z)` (the paper's eq. 8): the project's one
/// definition, in f64 (see [`Xyy::from_xyz`] for f32). Black (`X + Y + Z ≤ 0`) has no
/// chromaticity of its own and takes the `white`'s; a black white gives the equal-energy point
/// `(1/3, 1/3)`.
pub fn chromaticity(xyz: [f64; 3], white: [f64; 3]) -> [f64; 2] {
    chroma(xyz, white)
}

fn chroma<T: Real>(v: [T; 3], white: [T; 3]) -> [T; 2] {
    let own = |v: [T; 3]| {
        let s = v[0] + v[1] + v[2];
        (s > T::ZERO).then(|| [v[0] / s, v[1] / s])
    };
    own(v).or_else(|| own(white)).unwrap_or([T::THIRD; 2])
}

/// CIE XYZ tristimulus values (the project's convention: a perfect white has `Y = 100`), f32
/// in the kernels (the default) or f64 at the host's edges ([`Real`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Xyz<T = f32> {
    /// X
    pub x: T,
    /// Y (luminance)
    pub y: T,
    /// Z
    pub z: T,
}

impl<T> Xyz<T> {
    /// A new triple.
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
}

impl<T: Real> Xyz<T> {
    /// As an array `[X, Y, Z]`.
    pub fn to_array(self) -> [T; 3] {
        [self.x, self.y, self.z]
    }

    /// From an array.
    pub fn from_array(a: [T; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// Scaled by `k` (the same as `self * k`).
    pub fn scale(self, k: T) -> Xyz<T> {
        Xyz::new(self.x * k, self.y * k, self.z * k)
    }
}

impl<T: Real> Add for Xyz<T> {
    type Output = Xyz<T>;
    /// Component-wise sum (lights add).
    fn add(self, o: Xyz<T>) -> Xyz<T> {
        Xyz::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> Sub for Xyz<T> {
    type Output = Xyz<T>;
    /// Component-wise difference (e.g. a reading minus the black level).
    fn sub(self, o: Xyz<T>) -> Xyz<T> {
        Xyz::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Mul<T> for Xyz<T> {
    type Output = Xyz<T>;
    /// Scaled by `k` ([`Xyz::scale`]).
    fn mul(self, k: T) -> Xyz<T> {
        self.scale(k)
    }
}

impl<T: Real> From<Xyz<T>> for [f64; 3] {
    /// As f64 (f32 widened; for CIELAB and reports).
    fn from(v: Xyz<T>) -> [f64; 3] {
        [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
    }
}

/// Chromaticity `x, y` (eq. 8 of the paper) and luminance `Y`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Xyy {
    /// x = X / (X+Y+Z)
    pub x: f32,
    /// y = Y / (X+Y+Z)
    pub y: f32,
    /// Y
    pub big_y: f32,
}

impl Xyy {
    /// Chromaticity and luminance of `xyz` ([`chromaticity`]'s definition, in f32): black
    /// takes the chromaticity of `white`.
    pub fn from_xyz(xyz: Xyz, white: Xyz) -> Xyy {
        let [x, y] = chroma(xyz.to_array(), white.to_array());
        Xyy { x, y, big_y: xyz.y }
    }

    /// Back to XYZ (`y = 0` gives black).
    pub fn to_xyz(self) -> Xyz {
        if self.y <= 0.0 {
            return Xyz::default();
        }
        let k = self.big_y / self.y;
        Xyz::new(self.x * k, self.big_y, (1.0 - self.x - self.y) * k)
    }
}

/// CIELAB (CIE 1976 L*a*b*), in f64.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lab {
    /// L*
    pub l: f64,
    /// a*
    pub a: f64,
    /// b*
    pub b: f64,
}

impl Lab {
    /// CIELAB of `xyz` relative to the reference `white` (same units), in f64: an f32 [`Xyz`]
    /// is widened, an `[f64; 3]` taken as is.
    pub fn from_xyz(xyz: impl Into<[f64; 3]>, white: impl Into<[f64; 3]>) -> Lab {
        let (xyz, white) = (xyz.into(), white.into());
        fn f(t: f64) -> f64 {
            const D: f64 = 6.0 / 29.0;
            if t > D * D * D {
                libm::cbrt(t)
            } else {
                t / (3.0 * D * D) + 4.0 / 29.0
            }
        }
        let fx = f(xyz[0] / white[0]);
        let fy = f(xyz[1] / white[1]);
        let fz = f(xyz[2] / white[2]);
        Lab {
            l: 116.0 * fy - 16.0,
            a: 500.0 * (fx - fy),
            b: 200.0 * (fy - fz),
        }
    }

    /// The XYZ of this CIELAB colour relative to `white` ([`Lab::from_xyz`]'s inverse, CIE
    /// 15:2004 §8.2.1: `f⁻¹(t) = t³` above `6/29`, else `3 (6/29)² (t − 4/29)`).
    pub fn to_xyz(self, white: impl Into<[f64; 3]>) -> [f64; 3] {
        let white = white.into();
        fn f_inv(t: f64) -> f64 {
            const D: f64 = 6.0 / 29.0;
            if t > D {
                t * t * t
            } else {
                3.0 * D * D * (t - 4.0 / 29.0)
            }
        }
        let fy = (self.l + 16.0) / 116.0;
        let f = [fy + self.a / 500.0, fy, fy - self.b / 200.0];
        [0, 1, 2].map(|i| white[i] * f_inv(f[i]))
    }
}

impl Add for Lab {
    type Output = Lab;
    /// Component-wise sum (with [`Mul`], means of colours).
    fn add(self, o: Lab) -> Lab {
        Lab {
            l: self.l + o.l,
            a: self.a + o.a,
            b: self.b + o.b,
        }
    }
}

impl Sub for Lab {
    type Output = Lab;
    /// The difference vector; its length is ΔE*ab (CIE 1976).
    fn sub(self, o: Lab) -> Lab {
        Lab {
            l: self.l - o.l,
            a: self.a - o.a,
            b: self.b - o.b,
        }
    }
}

impl Mul<f64> for Lab {
    type Output = Lab;
    /// Every coordinate times `k`.
    fn mul(self, k: f64) -> Lab {
        Lab {
            l: self.l * k,
            a: self.a * k,
            b: self.b * k,
        }
    }
}

/// The parts of a CIEDE2000 difference (kL = kC = kH = 1) between a reference `p` and a sample
/// `q`, following Sharma, Wu & Dalal (2005), eqs. 1–22: the modified chromas `C′ = √(a′² + b′²)`
/// with `a′ = (1 + G)·a*`, the differences `ΔL′ = L₂ − L₁`, `ΔC′ = C′₂ − C′₁`,
/// `ΔH′ = 2·√(C′₁C′₂)·sin(Δh′/2)`, the weights `S_L`, `S_C`, `S_H` and the rotation `R_T`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct De2000Terms {
    /// `C′₁`, `C′₂`: chroma after the `a*` rescaling by `1 + G`.
    pub c_prime: [f64; 2],
    /// `h′₁`, `h′₂` in degrees, 0–360 (0 for an achromatic colour).
    pub h_prime: [f64; 2],
    /// `ΔL′`.
    pub dl: f64,
    /// `ΔC′ = C′₂ − C′₁`.
    pub dc: f64,
    /// `ΔH′`.
    pub dh: f64,
    /// `S_L`.
    pub sl: f64,
    /// `S_C = 1 + 0.045·C̄′`.
    pub sc: f64,
    /// `S_H`.
    pub sh: f64,
    /// `R_T`.
    pub rt: f64,
}

impl De2000Terms {
    /// ΔE00 = √((ΔL′/S_L)² + (ΔC′/S_C)² + (ΔH′/S_H)² + R_T·(ΔC′/S_C)·(ΔH′/S_H)).
    pub fn delta_e(&self) -> f64 {
        let (x, y, z) = (self.dl / self.sl, self.dc / self.sc, self.dh / self.sh);
        libm::sqrt(x * x + y * y + z * z + self.rt * y * z)
    }

    /// The weighted chroma difference `ΔC′/(k_C·S_C)` (k_C = 1), signed: the chroma term of
    /// ΔE00, which DisplayCAL's grey-balance criterion averages as `|ΔC′00|`.
    pub fn weighted_dc(&self) -> f64 {
        self.dc / self.sc
    }
}

/// The terms of the CIEDE2000 difference from `p` to `q` ([`De2000Terms`]).
pub fn de2000_terms(p: Lab, q: Lab) -> De2000Terms {
    use core::f64::consts::PI;
    let deg = PI / 180.0;
    let c1 = libm::hypot(p.a, p.b);
    let c2 = libm::hypot(q.a, q.b);
    let cbar = 0.5 * (c1 + c2);
    let c7 = libm::pow(cbar, 7.0);
    let g = 0.5 * (1.0 - libm::sqrt(c7 / (c7 + libm::pow(25.0, 7.0))));
    let a1 = (1.0 + g) * p.a;
    let a2 = (1.0 + g) * q.a;
    let c1p = libm::hypot(a1, p.b);
    let c2p = libm::hypot(a2, q.b);
    let hue = |b: f64, a: f64| {
        if b == 0.0 && a == 0.0 {
            0.0
        } else {
            let h = libm::atan2(b, a);
            if h < 0.0 {
                h + 2.0 * PI
            } else {
                h
            }
        }
    };
    let h1 = hue(p.b, a1);
    let h2 = hue(q.b, a2);
    let dl = q.l - p.l;
    let dc = c2p - c1p;
    let dh = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2 - h1;
        if d > PI {
            d - 2.0 * PI
        } else if d < -PI {
            d + 2.0 * PI
        } else {
            d
        }
    };
    let dhh = 2.0 * libm::sqrt(c1p * c2p) * libm::sin(dh / 2.0);
    let lbar = 0.5 * (p.l + q.l);
    let cbarp = 0.5 * (c1p + c2p);
    let hbar = if c1p * c2p == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= PI {
        0.5 * (h1 + h2)
    } else if h1 + h2 < 2.0 * PI {
        0.5 * (h1 + h2 + 2.0 * PI)
    } else {
        0.5 * (h1 + h2 - 2.0 * PI)
    };
    let t = 1.0 - 0.17 * libm::cos(hbar - 30.0 * deg)
        + 0.24 * libm::cos(2.0 * hbar)
        + 0.32 * libm::cos(3.0 * hbar + 6.0 * deg)
        - 0.20 * libm::cos(4.0 * hbar - 63.0 * deg);
    let dtheta = 30.0 * deg * libm::exp(-libm::pow((hbar / deg - 275.0) / 25.0, 2.0));
    let cb7 = libm::pow(cbarp, 7.0);
    let rc = 2.0 * libm::sqrt(cb7 / (cb7 + libm::pow(25.0, 7.0)));
    let l50 = (lbar - 50.0) * (lbar - 50.0);
    De2000Terms {
        c_prime: [c1p, c2p],
        h_prime: [h1 / deg, h2 / deg],
        dl,
        dc,
        dh: dhh,
        sl: 1.0 + 0.015 * l50 / libm::sqrt(20.0 + l50),
        sc: 1.0 + 0.045 * cbarp,
        sh: 1.0 + 0.015 * cbarp * t,
        rt: -libm::sin(2.0 * dtheta) * rc,
    }
}

/// CIEDE2000 colour difference (kL = kC = kH = 1), following Sharma, Wu & Dalal (2005).
pub fn delta_e2000(p: Lab, q: Lab) -> f64 {
    de2000_terms(p, q).delta_e()
}

/// CIEDE2000 between two XYZ seen relative to `white` (all three in the same units): each to
/// CIELAB against `white`, then [`delta_e2000`].
pub fn delta_e2000_xyz(a: [f64; 3], b: [f64; 3], white: [f64; 3]) -> f64 {
    delta_e2000(Lab::from_xyz(a, white), Lab::from_xyz(b, white))
}

/// The Bradford cone-response matrix (Lam 1985), the one copy; [`bradford`] takes it at
/// either component type ([`Mat3::cast`]).
pub const BRADFORD: Mat3<f64> = Mat3([
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
]);

/// The ICC profile connection space's illuminant D50 as ICC.1 writes it (s15Fixed16-exact:
/// `X = 0.9642, Y = 1, Z = 0.8249`; CIE's D50 is 0.96422, 1, 0.82521).
pub const ICC_D50: Xyz<f64> = Xyz::new(0.9642, 1.0, 0.8249);

/// The matrix adapting XYZ seen under white `from` to the corresponding XYZ under white `to`
/// (Bradford: `M⁻¹ · diag(ρ_to / ρ_from) · M`), in f32 or f64.
pub fn bradford<T: Real>(from: Xyz<T>, to: Xyz<T>) -> Mat3<T> {
    let m: Mat3<T> = BRADFORD.cast();
    let s = m.apply(from.to_array());
    let d = m.apply(to.to_array());
    let diag = Mat3::diagonal([d[0] / s[0], d[1] / s[1], d[2] / s[2]]);
    // BRADFORD is invertible (det ≈ 1.9); this cannot fail.
    let inv = m.inverse().unwrap_or(Mat3::IDENTITY);
    inv.mul(&diag).mul(&m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_chromaticity_black_takes_the_whites() {
        let d65 = [95.047, 100.0, 108.883];
        let [x, y] = chromaticity(d65, [1.0; 3]);
        assert!((x - 0.31273).abs() < 1e-4 && (y - 0.32902).abs() < 1e-4);
        assert_eq!(chromaticity([0.0; 3], d65), chromaticity(d65, [1.0; 3]));
        assert_eq!(chromaticity([0.0; 3], [0.0; 3]), [1.0 / 3.0; 2]);
        let black = Xyy::from_xyz(Xyz::default(), Xyz::new(95.047, 100.0, 108.883));
        assert!((black.x - 0.31273).abs() < 1e-4 && black.big_y == 0.0);
        let red = Xyz::new(41.24, 21.26, 1.93);
        let back = Xyy::from_xyz(red, Xyz::default()).to_xyz();
        assert!((back - red).to_array().iter().all(|d| d.abs() < 1e-4));
    }

    #[test]
    fn lab_round_trips_through_xyz() {
        let w = [95.047, 100.0, 108.883];
        // above and below the cube root's linear foot (Y/Yn = 0.001 is below (6/29)³)
        for xyz in [
            [41.24, 21.26, 1.93],
            [0.05, 0.1, 0.2],
            [95.047, 100.0, 108.883],
        ] {
            let back = Lab::from_xyz(xyz, w).to_xyz(w);
            for i in 0..3 {
                assert!(
                    (back[i] - xyz[i]).abs() < 1e-9 * w[i],
                    "{xyz:?} -> {back:?}"
                );
            }
        }
        // CIE 15: L* = 50 is Y/Yn = ((50 + 16)/116)³ = 0.18419
        let grey = Lab {
            l: 50.0,
            a: 0.0,
            b: 0.0,
        }
        .to_xyz(w);
        assert!((grey[1] - 18.4187).abs() < 1e-3);
    }

    #[test]
    fn arithmetic() {
        let a = Xyz::new(1.0, 2.0, 3.0);
        assert_eq!(a + a - a, a);
        assert_eq!(a * 2.0, Xyz::new(2.0, 4.0, 6.0));
        let p = Lab {
            l: 50.0,
            a: 10.0,
            b: -10.0,
        };
        let q = Lab {
            l: 60.0,
            a: 0.0,
            b: 0.0,
        };
        assert_eq!(
            (p + q) * 0.5,
            Lab {
                l: 55.0,
                a: 5.0,
                b: -5.0
            }
        );
        assert_eq!(
            p - q,
            Lab {
                l: -10.0,
                a: 10.0,
                b: -10.0
            }
        );
        // from_xyz takes f32 and f64 alike
        assert_eq!(
            Lab::from_xyz(a, Xyz::new(2.0, 2.0, 2.0)),
            Lab::from_xyz([1.0, 2.0, 3.0], [2.0; 3])
        );
    }
}
