//! The colour spaces a UI is designed in, and how the source white meets the panel's.

use crate::display::{Display, Transfer, D65_XY, SRGB_PRIMARIES};
use crate::{bradford, Error, Mat3, Xyz};

/// Display P3 primaries (SMPTE EG 432-1 with a D65 white; Apple's Display P3).
pub const P3_PRIMARIES: [[f32; 2]; 3] = [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]];

/// A source colour space of 8-bit pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Source {
    /// sRGB (IEC 61966-2-1): Rec. 709 primaries, D65, the sRGB curve.
    #[default]
    Srgb,
    /// Display P3: P3 primaries, D65, the sRGB curve.
    DisplayP3,
    /// Linear-light sRGB: Rec. 709 primaries, D65, no curve.
    LinearSrgb,
}

impl Source {
    /// Every source.
    pub const ALL: [Source; 3] = [Source::Srgb, Source::DisplayP3, Source::LinearSrgb];

    /// The source as a display of white luminance 1 (its primaries, white and curve).
    pub fn display(self) -> Display {
        let (xy, t) = match self {
            Source::Srgb => (SRGB_PRIMARIES, Transfer::Srgb),
            Source::DisplayP3 => (P3_PRIMARIES, Transfer::Srgb),
            Source::LinearSrgb => (SRGB_PRIMARIES, Transfer::Linear),
        };
        match Display::from_primaries_white(xy, D65_XY, 1.0, [t.clone(), t.clone(), t]) {
            Ok(d) => d,
            // constant, non-singular primaries (unit-tested)
            Err(_) => unreachable!("source primaries are valid"),
        }
    }

    /// The source's curve: code value in `[0, 1]` → linear light.
    pub fn decode(self, v: f32) -> f32 {
        match self {
            Source::LinearSrgb => Transfer::Linear.decode(v),
            _ => Transfer::Srgb.decode(v),
        }
    }

    /// The name used on the command line: `srgb`, `p3`, `linear`.
    pub fn name(self) -> &'static str {
        match self {
            Source::Srgb => "srgb",
            Source::DisplayP3 => "p3",
            Source::LinearSrgb => "linear",
        }
    }
}

/// How the source's white is reproduced on the panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum White {
    /// Adapted (Bradford) to the panel's own white: source white → full drive. What the eye,
    /// adapted to the panel, expects (ICC relative colorimetric).
    #[default]
    Adapt,
    /// The source white's chromaticity (D65) kept, its luminance the panel white's: a panel
    /// whose white is not D65 then clips at the source white.
    Absolute,
}

/// The panel's linear drive per unit of source linear RGB: `T = M⁻¹ · A · S`, with `A` the
/// Bradford adaptation from the source white to the panel white `M · 1` ([`White::Adapt`]) or the
/// luminance ratio alone ([`White::Absolute`]). The panel's black is added back by the panel
/// (`XYZ = K + M · l`), so source black maps to panel black.
pub fn linear_matrix(panel: &Display, source: Source, white: White) -> Result<Mat3, Error> {
    let s = source.display();
    let src_white = Xyz::from_array(s.rgb_to_xyz().apply([1.0; 3]));
    let panel_white = Xyz::from_array(panel.rgb_to_xyz().apply([1.0; 3]));
    if !(panel_white.y > 0.0) || !(src_white.y > 0.0) {
        return Err(Error::Singular);
    }
    let a = match white {
        White::Adapt => bradford(src_white, panel_white),
        White::Absolute => {
            let k = panel_white.y / src_white.y;
            Mat3([[k, 0.0, 0.0], [0.0, k, 0.0], [0.0, 0.0, k]])
        }
    };
    let t = panel.xyz_to_rgb().mul(&a.mul(s.rgb_to_xyz()));
    if t.0.iter().flatten().all(|v| v.is_finite()) {
        Ok(t)
    } else {
        Err(Error::Singular)
    }
}
