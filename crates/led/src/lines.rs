//! The protocol lines the host sends to the controller, built and checked by the controller's
//! own parser before anything is sent: settings (`cal`, `trc`) from the command line or a
//! calibration file, and `refl` lines for named reflectances fitted on the host.

use crate::error::{Error, Result};
use crate::table::{Correction, DEFAULT_GRID};
use specpoly_core::{DefaultSpectrum, Illuminant, PaperSpectrum};
use specpoly_display::spec::DisplaySpec;
use specpoly_protocol::number::parse_f32;
use specpoly_protocol::{
    write_reflect, write_reflect_hex, Channels, Command, Reflectance, Reply, MAX_FACTORS,
};
use specpoly_spectra::spectrum_names;

/// The spectrum presets the controller takes in a `refl` line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// 8 uniform cubic spans (32 coefficients), the project default.
    Poly,
    /// The paper's 2 cubic spans split at 550 nm.
    Paper,
}

/// A command as the line sent for it.
pub fn line(c: &Command) -> String {
    let mut s = String::new();
    // writing to a String cannot fail
    let _ = c.write(&mut s);
    s
}

/// A reply as the line the controller sends.
pub fn reply_line(r: &Reply) -> String {
    let mut s = String::new();
    let _ = r.write(&mut s);
    s
}

/// The `cal` command from `xr,yr,Yr,xg,yg,Yg,xb,yb,Yb`.
pub fn primaries(s: &str) -> Result<Command> {
    let v: Vec<f32> = s
        .split(',')
        .map(|t| {
            parse_f32(t.trim()).map_err(|_| Error::PrimariesNotANumber {
                token: t.to_string(),
            })
        })
        .collect::<Result<_>>()?;
    if v.len() != 9 {
        return Err(Error::PrimariesCount { got: v.len() });
    }
    let c = Command::Calibrate {
        xy: [[v[0], v[1]], [v[3], v[4]], [v[6], v[7]]],
        luminance: [v[2], v[5], v[8]],
    };
    // the controller's own checks, before anything is sent
    Command::parse(&line(&c)).map_err(|fault| Error::PrimariesRejected { fault })
}

/// The `cal` and three `trc` lines of a calibration file.
pub fn calibration(spec: &DisplaySpec) -> Result<Vec<String>> {
    let display = spec.display();
    let (xy, luminance) = display.primaries();
    let mut lines = vec![line(&Command::Calibrate { xy, luminance })];
    for (channels, curve) in [Channels::Red, Channels::Green, Channels::Blue]
        .into_iter()
        .zip(display.transfer().iter())
    {
        lines.push(line(&Command::Transfer {
            channels,
            curve: curve.clone(),
        }));
    }
    for l in &lines {
        // the controller's own checks (ranges, line length), before anything is sent
        if l.len() > specpoly_protocol::MAX_LINE {
            return Err(Error::CurveTooLong { name: spec.name() });
        }
        Command::parse(l).map_err(|fault| Error::NotLedCalibration {
            name: spec.name(),
            fault,
        })?;
    }
    Ok(lines)
}

/// The drive-correction table for `led --calibration FILE` when the file's model has channel
/// interaction (a calibration's lattice, or a LUT ICC profile's): built with the full model's
/// exact inverse against the matrix model the `cal` and `trc` lines give the controller
/// ([`crate::table`]); `None` for a matrix model.
pub fn calibration_table(spec: &DisplaySpec) -> Result<Option<Correction>> {
    let Some(model) = spec.interaction_model() else {
        return Ok(None);
    };
    Correction::new(model, DEFAULT_GRID)
        .map(Some)
        .ok_or_else(|| Error::NoColourSpace { name: spec.name() })
}

/// The `refl` line for named reflectances (names as in `specpoly xyz`; several are multiplied),
/// each fitted in `preset`, under `illuminant`.
pub fn refl(preset: Preset, illuminant: Illuminant, names: &[String]) -> Result<String> {
    refl_form(preset, illuminant, names, false)
}

/// [`refl`] with the coefficients in the protocol's compact form, `0x` and the f32's bit
/// pattern in 8 hexadecimal digits (`firmware/PROTOCOL.md`): exact, and fewer instructions
/// for the controller to read.
pub fn refl_hex(preset: Preset, illuminant: Illuminant, names: &[String]) -> Result<String> {
    refl_form(preset, illuminant, names, true)
}

fn refl_form(
    preset: Preset,
    illuminant: Illuminant,
    names: &[String],
    hex: bool,
) -> Result<String> {
    let named = spectrum_names::resolve_all(names)?;
    if named.is_empty() || named.len() > MAX_FACTORS {
        return Err(Error::ReflectanceCount {
            got: named.len(),
            max: MAX_FACTORS,
        });
    }
    let mut factors = Vec::new();
    for n in &named {
        let t = n.tabulated();
        let fit_err = |source| Error::CannotFit {
            name: n.short().to_string(),
            source,
        };
        factors.push(match preset {
            Preset::Paper => Reflectance::Paper(PaperSpectrum::fit(&t).map_err(fit_err)?),
            Preset::Poly => Reflectance::Default(DefaultSpectrum::fit(&t).map_err(fit_err)?),
        });
    }
    let mut line = String::new();
    if hex {
        write_reflect_hex(&mut line, illuminant, &factors)
    } else {
        write_reflect(&mut line, illuminant, &factors)
    }
    .map_err(|_| Error::ReflLine)?;
    Ok(line)
}
