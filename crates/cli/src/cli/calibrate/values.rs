//! The `calibrate` command line's value enums (clap's `ValueEnum`, with the spellings and
//! `--help` texts of the options), each converted to the display crate's type with `From`
//! (`specpoly-display` has no clap).

use specpoly_calibrate::fit::MatrixFit;
use specpoly_display::calibration::TransferKind;
use specpoly_display::export::{Bits, Format, SourceArg, WhiteArg};
use specpoly_display::icc::IccVersion;
use specpoly_display::lut3d::file::Format as LutFormat;
use specpoly_display::lut3d::source::SourceSpace;
use specpoly_display::lut3d::{GamutMode, WhiteMode};

/// Which transfer curve the model uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum TransferValue {
    /// The measured ramp, resampled to at most 64 evenly spaced points.
    #[default]
    Table,
    /// A pure power law `l = v^γ` per channel.
    Gamma,
}

/// The profile version written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum IccVersionValue {
    /// ICC v2.4 (the default: every consumer reads it).
    #[default]
    #[value(name = "2")]
    V2,
    /// ICC v4.4.
    #[value(name = "4")]
    V4,
}

/// The source colour space of the firmware's UI.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum SourceValue {
    /// sRGB (IEC 61966-2-1).
    #[default]
    Srgb,
    /// Display P3.
    P3,
    /// Linear-light sRGB.
    Linear,
}

/// What to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatValue {
    /// A C99 header: tables and `NAME_levels`, `NAME_codes`, `NAME_rgb565`.
    CTable,
    /// Rust: `pub static NAME: specpoly_core::pixel::PixelTransform`.
    Rust,
    /// The display model as a calibration blob for the C library (`sp_calibration_load`;
    /// binary, versioned, CRC-32; `--source`, `--bits`, `--white`, `--name` do not apply).
    CBlob,
}

/// The panel's bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum BitsValue {
    /// 5-6-5.
    #[default]
    Rgb565,
    /// 6-6-6.
    Rgb666,
    /// 8-8-8.
    Rgb888,
}

/// How the source white is reproduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum WhiteValue {
    /// Adapted (Bradford) to the panel's white: source white → full drive.
    #[default]
    Adapt,
    /// D65 kept (clips at the source white on a panel whose white is not D65).
    Absolute,
}

/// The source colour space of a 3D LUT.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum LutSourceValue {
    /// sRGB (IEC 61966-2-1: BT.709 primaries, D65, the piecewise sRGB curve).
    #[default]
    Srgb,
    /// Rec. 709 video shown with the BT.1886 EOTF for the display's own black and white.
    Rec709,
    /// Display P3 (P3 primaries, D65, the sRGB curve).
    P3,
    /// Rec. 2020 (SDR) shown with the BT.1886 EOTF for the display's own black and white.
    Rec2020,
}

/// How a 3D LUT reproduces the source white.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum LutWhiteValue {
    /// Bradford-adapted to the display's white (source white = the display's white).
    #[default]
    Adapt,
    /// Kept (absolute colorimetric), at the most luminance the display reaches at it.
    Keep,
}

/// How a 3D LUT brings colours outside the display's gamut in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum LutGamutValue {
    /// Clip each channel of the display's linear drive (device RGB).
    #[default]
    Clip,
    /// Keep CIELAB lightness and hue, reduce chroma to the gamut boundary.
    Desaturate,
}

/// A 3D LUT file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LutFormatValue {
    /// Adobe/Resolve .cube (Cube LUT Specification 1.0).
    Cube,
    /// Autodesk Lustre .3dl (10-bit mesh, 12-bit outputs).
    #[value(name = "3dl")]
    ThreeDl,
    /// madVR .3dlut (binary, 256³ × 16 bits).
    Madvr,
}

/// Both ways between a value enum and the display crate's enum, variant for variant.
macro_rules! both_ways {
    ($cli:ident, $lib:ty, $($v:ident => $w:ident),+) => {
        impl From<$cli> for $lib {
            fn from(v: $cli) -> $lib {
                match v {
                    $($cli::$v => <$lib>::$w,)+
                }
            }
        }
        impl From<$lib> for $cli {
            fn from(v: $lib) -> $cli {
                match v {
                    $(<$lib>::$w => $cli::$v,)+
                }
            }
        }
    };
}

both_ways!(TransferValue, TransferKind, Table => Table, Gamma => Gamma);
both_ways!(IccVersionValue, IccVersion, V2 => V2, V4 => V4);
both_ways!(SourceValue, SourceArg, Srgb => Srgb, P3 => P3, Linear => Linear);
both_ways!(FormatValue, Format, CTable => CTable, Rust => Rust, CBlob => CBlob);
both_ways!(BitsValue, Bits, Rgb565 => Rgb565, Rgb666 => Rgb666, Rgb888 => Rgb888);
both_ways!(WhiteValue, WhiteArg, Adapt => Adapt, Absolute => Absolute);
both_ways!(LutSourceValue, SourceSpace, Srgb => Srgb, Rec709 => Rec709, P3 => P3, Rec2020 => Rec2020);
both_ways!(LutWhiteValue, WhiteMode, Adapt => Adapt, Keep => Keep);
both_ways!(LutGamutValue, GamutMode, Clip => Clip, Desaturate => Desaturate);
both_ways!(LutFormatValue, LutFormat, Cube => Cube, ThreeDl => ThreeDl, Madvr => MadVr);

/// `--matrix`: [`MatrixFit`] as the command line spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum MatrixFitArg {
    /// Cowan: the full-drive primaries minus black.
    Cowan,
    /// Weighted linear least squares over every fit patch (needs mixtures among them).
    #[default]
    #[value(name = "least-squares")]
    LeastSquares,
}

impl From<MatrixFitArg> for MatrixFit {
    fn from(m: MatrixFitArg) -> MatrixFit {
        match m {
            MatrixFitArg::Cowan => MatrixFit::Cowan,
            MatrixFitArg::LeastSquares => MatrixFit::LeastSquares,
        }
    }
}
