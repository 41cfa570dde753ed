//! Arguments several commands share, each parsed once by a typed clap value parser (so
//! `xyz --observer 10` and `led --observer 10` are judged by the same function), and the
//! flattened groups commands take them in.
//!
//! | option | type | parser |
//! |---|---|---|
//! | `--illuminant`, `--observer` (`xyz`, `fit`) | [`Colorimetry`] | [`observer`] |
//! | `--observer` (`led`) | [`Observer`] | [`device_observer`] |
//! | `--illuminant` (`led refl`) | [`Illuminant`] | [`builtin_illuminant`] |
//! | `--repr`, `--mode` | [`specpoly_spectra::repr::Repr`] | its `FromStr` (the list of representations) |
//! | `--gamut` (`render`), `--map` (`led`) | [`Gamut`] | clap `ValueEnum` |
//! | `--size` | [`specpoly_plot::size::Size`] | its `FromStr` |
//! | `--trc` (`led`) | [`Curve`] | [`transfer`] |

use crate::error::{CliError, Result};
use specpoly_core::{GamutMap, Illuminant, Observer, Transfer};
use specpoly_protocol::number::parse_f32;

/// The light and the observer a colour is computed for.
#[derive(Clone, Debug, clap::Args)]
pub struct Colorimetry {
    /// The light: A, D50, D65, E, FL2, FL7, FL11, or FILE / FILE#COLUMN.
    #[arg(long, short = 'i', default_value = "D65", value_name = "NAME|FILE")]
    pub illuminant: String,
    /// Observer: 1931 (2°), 1964 (10°), 2015-2, 2015-10 (CIE 170-2), cie2006:age=A,field=F
    /// (CIE 170-1, ages 20-80, fields 2-10°), or FILE.csv of three sensitivities.
    #[arg(long, default_value = "1964", value_name = "NAME|FILE", value_parser = observer)]
    pub observer: Observer,
}

/// Parses an observer: a built-in name (`1931`/`2`, `1964`/`10`, `2015-2`, `2015-10`),
/// `cie2006:age=A,field=F`, or a CSV file of three sensitivities
/// ([`specpoly_spectra::observer::parse`]; clap reports a refusal as a usage error, exit 2).
pub fn observer(s: &str) -> Result<Observer> {
    Ok(specpoly_spectra::observer::parse(s)?)
}

/// Parses one of the observers the controller carries (`1931`, `1964`): the firmware holds
/// precomputed moments for those only.
pub fn device_observer(s: &str) -> Result<Observer> {
    match Observer::from_name(s) {
        Some(o) if Observer::CLASSIC.contains(&o) => Ok(o),
        _ => Err(CliError::usage(format!(
            "unknown observer `{s}` (the controller carries 1931 (2°) and 1964 (10°))"
        ))),
    }
}

/// Parses a built-in illuminant's name (any case).
pub fn builtin_illuminant(s: &str) -> Result<Illuminant> {
    Illuminant::from_name(s).ok_or_else(|| {
        CliError::usage(format!(
            "unknown illuminant `{s}` (built in: A D50 D65 E FL2 FL7 FL11)"
        ))
    })
}

/// A transfer curve named on the command line (a table comes from a file instead).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Curve {
    /// `linear`.
    Linear,
    /// `srgb`.
    Srgb,
    /// `gamma:G`.
    Gamma(f32),
}

impl From<Curve> for Transfer {
    fn from(c: Curve) -> Transfer {
        match c {
            Curve::Linear => Transfer::Linear,
            Curve::Srgb => Transfer::Srgb,
            Curve::Gamma(g) => Transfer::Gamma(g),
        }
    }
}

/// Parses a transfer curve: `linear`, `srgb` or `gamma:G` (`0.1 ≤ G ≤ 10`).
pub fn transfer(s: &str) -> Result<Curve> {
    match s.split_once(':') {
        None if s == "linear" => Ok(Curve::Linear),
        None if s == "srgb" => Ok(Curve::Srgb),
        Some(("gamma", g)) => match parse_f32(g) {
            Ok(g) if (0.1..=10.0).contains(&g) => Ok(Curve::Gamma(g)),
            _ => Err(CliError::usage(format!("bad gamma `{g}` (0.1 to 10)"))),
        },
        _ => Err(CliError::usage(format!(
            "`{s}` is not linear, srgb or gamma:G"
        ))),
    }
}

/// The command-line name of a `ValueEnum` value (`rgb565`, `least-squares`): what messages and
/// written files show instead of its Rust `Debug` form.
pub fn name<T: clap::ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// Gamut mapping for colours a display cannot show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Gamut {
    /// Clip each channel (as the paper, §7.3).
    Clip,
    /// Mix with the grey of equal luminance (keeps the dominant wavelength).
    Desaturate,
}

impl From<Gamut> for GamutMap {
    fn from(g: Gamut) -> GamutMap {
        match g {
            Gamut::Clip => GamutMap::Clip,
            Gamut::Desaturate => GamutMap::Desaturate,
        }
    }
}

/// `--max-input-size`: bytes, or a number with `K`, `M`, `G` (binary: KiB, MiB, GiB), at
/// least 1 byte and at most 1 TiB.
pub fn byte_size(s: &str) -> std::result::Result<u64, String> {
    let t = s.trim();
    let (num, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => (&t[..i], t[i..].trim_end_matches(['i', 'B', 'b'])),
        None => (t, ""),
    };
    let shift = match unit.to_ascii_uppercase().as_str() {
        "" => 0,
        "K" => 10,
        "M" => 20,
        "G" => 30,
        _ => return Err(format!("`{s}`: a size is bytes or a number with K, M or G")),
    };
    let n: u64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{s}`: a size is bytes or a number with K, M or G"))?;
    match n.checked_mul(1 << shift) {
        Some(b) if (1..=1 << 40).contains(&b) => Ok(b),
        _ => Err(format!("`{s}`: between 1 byte and 1 TiB")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn observers_and_curves() {
        assert_eq!(observer("10").unwrap(), Observer::Cie1964);
        assert!(observer("1976").is_err());
        assert!(transfer("gamma:2.2").is_ok());
        assert!(transfer("cubic").is_err());
    }
}
