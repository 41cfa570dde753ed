//! The source colour spaces of a 3D LUT: primaries, white and EOTF (encoded value → relative
//! linear light), each from its standard.
//!
//! | name | primaries (x, y of R, G, B) | white | EOTF |
//! |---|---|---|---|
//! | `srgb` | ITU-R BT.709 | D65 | IEC 61966-2-1's piecewise curve |
//! | `rec709` | ITU-R BT.709 | D65 | ITU-R BT.1886 for the display's own white and black |
//! | `p3` | SMPTE EG 432-1 (Display P3) | D65 | IEC 61966-2-1's piecewise curve (Apple's Display P3) |
//! | `rec2020` | ITU-R BT.2020 | D65 | ITU-R BT.1886 for the display's own white and black |
//!
//! **BT.1886** (ITU-R BT.1886, Annex 1): `L = a · max(V + b, 0)^γ`, `γ = 2.4`,
//! `a = (L_W^(1/γ) − L_B^(1/γ))^γ`, `b = L_B^(1/γ) / (L_W^(1/γ) − L_B^(1/γ))`, with `L_W`, `L_B`
//! the display's white and black luminances, so `L(0) = L_B` and `L(1) = L_W`. The LUT uses
//! its relative form `g(V) = (L(V) − L_B) / (L_W − L_B)` in `[0, 1]` (see the module docs of
//! [`crate::lut3d`]: the colour is shown as `K + A·S·g(V)`, whose luminance is BT.1886's `L(V)`).

use crate::error::{Error, Result};
use specpoly_core::{Mat3, Transfer};

/// D65 as the standards write it (ITU-R BT.709, BT.2020, IEC 61966-2-1).
pub const D65_XY: [f64; 2] = [0.3127, 0.3290];

/// BT.1886's exponent.
pub const BT1886_GAMMA: f64 = 2.4;

/// A source colour space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SourceSpace {
    /// sRGB (IEC 61966-2-1).
    #[default]
    Srgb,
    /// Rec. 709 video shown with the BT.1886 EOTF.
    Rec709,
    /// Display P3.
    P3,
    /// Rec. 2020 video (SDR) shown with the BT.1886 EOTF.
    Rec2020,
}

impl SourceSpace {
    /// Every source space.
    pub const ALL: [SourceSpace; 4] = [Self::Srgb, Self::Rec709, Self::P3, Self::Rec2020];

    /// The name on the command line and in LUT headers.
    pub fn name(self) -> &'static str {
        match self {
            Self::Srgb => "srgb",
            Self::Rec709 => "rec709",
            Self::P3 => "p3",
            Self::Rec2020 => "rec2020",
        }
    }

    /// The space of a name ([`Self::name`], any case).
    pub fn from_name(s: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|v| v.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| {
                Error::invalid(
                    format!("source space `{s}`"),
                    "is not one of srgb, rec709, p3, rec2020",
                )
            })
    }

    /// What it is, with its standards (said in LUT headers).
    pub fn description(self) -> &'static str {
        match self {
            Self::Srgb => "sRGB (IEC 61966-2-1: BT.709 primaries, D65, the piecewise sRGB curve)",
            Self::Rec709 => "Rec. 709 (ITU-R BT.709 primaries, D65) with the ITU-R BT.1886 EOTF",
            Self::P3 => "Display P3 (SMPTE EG 432-1 primaries, D65, the sRGB curve)",
            Self::Rec2020 => "Rec. 2020 (ITU-R BT.2020 primaries, D65) with the ITU-R BT.1886 EOTF",
        }
    }

    /// The primaries' chromaticities `[x, y]`, red, green, blue.
    pub fn primaries(self) -> [[f64; 2]; 3] {
        match self {
            Self::Srgb | Self::Rec709 => [[0.640, 0.330], [0.300, 0.600], [0.150, 0.060]],
            Self::P3 => [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]],
            Self::Rec2020 => [[0.708, 0.292], [0.170, 0.797], [0.131, 0.046]],
        }
    }

    /// Linear RGB → XYZ with the white (D65) at `Y = 1`: the primaries' XYZ at `Y = 1` as
    /// columns, each scaled so that they sum to the white (SMPTE RP 177).
    pub fn rgb_to_xyz(self) -> Mat3<f64> {
        let xyz = |[x, y]: [f64; 2]| [x / y, 1.0, (1.0 - x - y) / y];
        let p = self.primaries().map(xyz);
        let cols = Mat3([0, 1, 2].map(|r| [p[0][r], p[1][r], p[2][r]]));
        // constant, non-singular primaries (unit-tested)
        let s = cols
            .inverse()
            .map(|inv| inv.apply(xyz(D65_XY)))
            .unwrap_or([1.0; 3]);
        Mat3([0, 1, 2].map(|r| [0, 1, 2].map(|c| cols.0[r][c] * s[c])))
    }

    /// The EOTF for a display whose black and white luminances are `black` and `white` (any
    /// one unit; only BT.1886 uses them).
    pub fn eotf(self, black: f64, white: f64) -> Eotf {
        match self {
            Self::Srgb | Self::P3 => Eotf::Srgb,
            Self::Rec709 | Self::Rec2020 => Eotf::bt1886(black, white),
        }
    }
}

/// An EOTF in relative form: encoded `V ∈ [0, 1]` → linear light in `[0, 1]`, `0 → 0`, `1 → 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Eotf {
    /// IEC 61966-2-1 (the core's [`Transfer::Srgb`]).
    Srgb,
    /// ITU-R BT.1886 for a black-to-white ratio, in relative form (module docs): `a`, `b` of
    /// the standard for `L_W = 1`, and `L_B`.
    Bt1886 {
        /// The gain `a`.
        a: f64,
        /// The lift `b`.
        b: f64,
        /// `L_B / L_W`.
        black: f64,
    },
}

impl Eotf {
    /// BT.1886 for a display of black `black` and white `white` (same unit; a black below 0
    /// or a white below the black is taken as a black of 0).
    pub fn bt1886(black: f64, white: f64) -> Eotf {
        let lb = if white > 0.0 && black > 0.0 && black < white {
            black / white
        } else {
            0.0
        };
        let g = BT1886_GAMMA;
        let (w, k) = (1.0f64, lb.powf(1.0 / g));
        let span = w - k;
        Eotf::Bt1886 {
            a: span.powf(g),
            b: k / span,
            black: lb,
        }
    }

    /// Relative linear light of the encoded value `v` (clamped to `[0, 1]`).
    pub fn decode(&self, v: f64) -> f64 {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        match *self {
            Eotf::Srgb => f64::from(Transfer::Srgb.decode(v as f32)),
            Eotf::Bt1886 { a, b, black } => {
                let l = a * (v + b).max(0.0).powf(BT1886_GAMMA);
                ((l - black) / (1.0 - black)).clamp(0.0, 1.0)
            }
        }
    }

    /// The description said in LUT headers.
    pub fn describe(&self) -> String {
        match *self {
            Eotf::Srgb => "the IEC 61966-2-1 curve".into(),
            Eotf::Bt1886 { a, b, black } => format!(
                "ITU-R BT.1886 for the display's black/white {black:.6} (a = {a:.6}, b = {b:.6}, gamma 2.4)"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrices_match_the_standards() {
        // IEC 61966-2-1's matrix (four decimals)
        let m = SourceSpace::Srgb.rgb_to_xyz().0;
        let srgb = [
            [0.4124, 0.3576, 0.1805],
            [0.2126, 0.7152, 0.0722],
            [0.0193, 0.1192, 0.9505],
        ];
        for r in 0..3 {
            for c in 0..3 {
                assert!((m[r][c] - srgb[r][c]).abs() < 1e-4, "{m:?}");
            }
        }
        // ITU-R BT.2020's luminance coefficients (Y row): 0.2627, 0.6780, 0.0593
        let y = SourceSpace::Rec2020.rgb_to_xyz().0[1];
        for (a, b) in y.iter().zip([0.2627, 0.6780, 0.0593]) {
            assert!((a - b).abs() < 1e-4, "{y:?}");
        }
    }

    #[test]
    fn bt1886_reaches_the_displays_black_and_white() {
        // L_W = 100, L_B = 0.1: L(V) for V = 0.5 by the standard's formula
        let e = Eotf::bt1886(0.1, 100.0);
        let (w, k) = (100f64.powf(1.0 / 2.4), 0.1f64.powf(1.0 / 2.4));
        let l = (w - k).powf(2.4) * (0.5 + k / (w - k)).powf(2.4);
        assert!((e.decode(0.5) - (l - 0.1) / 99.9).abs() < 1e-12);
        assert_eq!(e.decode(0.0), 0.0);
        assert!((e.decode(1.0) - 1.0).abs() < 1e-12);
        // no black: a pure 2.4 power law
        assert!((Eotf::bt1886(0.0, 100.0).decode(0.5) - 0.5f64.powf(2.4)).abs() < 1e-12);
        assert!(SourceSpace::from_name("xyz").is_err());
        assert_eq!(
            SourceSpace::from_name("Rec2020").unwrap(),
            SourceSpace::Rec2020
        );
    }
}
