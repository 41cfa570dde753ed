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

use crate::Mat3;

/// CIE XYZ tristimulus values (the project's convention: a perfect white has `Y = 100`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Xyz {
    /// X
    pub x: f32,
    /// Y (luminance)
    pub y: f32,
    /// Z
    pub z: f32,
}

impl Xyz {
    /// A new triple.
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }

    /// As an array `[X, Y, Z]`.
    pub fn to_array(self) -> [f32; 3] {
        [self.x, self.y, self.z]
    }

    /// From an array.
    pub fn from_array(a: [f32; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// Scaled by `k`.
    pub fn scale(self, k: f32) -> Xyz {
        Xyz::new(self.x * k, self.y * k, self.z * k)
    }

    /// Chromaticity and luminance. A black (X+Y+Z = 0) gets the chromaticity of D65.
    pub fn to_xyy(self) -> Xyy {
        let s = self.x + self.y + self.z;
        if s <= 0.0 {
            return Xyy {
                x: 0.3127,
                y: 0.3290,
                big_y: self.y,
            };
        }
        Xyy {
            x: self.x / s,
            y: self.y / s,
            big_y: self.y,
        }
    }
}

impl core::ops::Add for Xyz {
    type Output = Xyz;
    /// Component-wise sum.
    fn add(self, o: Xyz) -> Xyz {
        Xyz::new(self.x + o.x, self.y + o.y, self.z + o.z)
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
    /// CIELAB of `xyz` relative to the reference `white` (same units).
    pub fn from_xyz(xyz: [f64; 3], white: [f64; 3]) -> Lab {
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

    /// CIELAB of an f32 [`Xyz`] against an f32 white.
    pub fn from(xyz: Xyz, white: Xyz) -> Lab {
        let c = |v: Xyz| [v.x as f64, v.y as f64, v.z as f64];
        Lab::from_xyz(c(xyz), c(white))
    }
}

/// CIEDE2000 colour difference (kL = kC = kH = 1), following Sharma, Wu & Dalal (2005).
pub fn delta_e2000(p: Lab, q: Lab) -> f64 {
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
    let sl = 1.0 + 0.015 * l50 / libm::sqrt(20.0 + l50);
    let sc = 1.0 + 0.045 * cbarp;
    let sh = 1.0 + 0.015 * cbarp * t;
    let rt = -libm::sin(2.0 * dtheta) * rc;
    let (x, y, z) = (dl / sl, dc / sc, dhh / sh);
    libm::sqrt(x * x + y * y + z * z + rt * y * z)
}

/// The Bradford cone-response matrix (Lam 1985).
pub const BRADFORD: Mat3 = Mat3([
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
]);

/// The matrix adapting XYZ seen under white `from` to the corresponding XYZ under white `to`
/// (Bradford: `M⁻¹ · diag(ρ_to / ρ_from) · M`).
pub fn bradford(from: Xyz, to: Xyz) -> Mat3 {
    let m = BRADFORD;
    let s = m.apply(from.to_array());
    let d = m.apply(to.to_array());
    let diag = Mat3([
        [d[0] / s[0], 0.0, 0.0],
        [0.0, d[1] / s[1], 0.0],
        [0.0, 0.0, d[2] / s[2]],
    ]);
    // BRADFORD is invertible (det ≈ 1.9); this cannot fail.
    let inv = m.inverse().unwrap_or(Mat3::IDENTITY);
    inv.mul(&diag).mul(&m)
}
