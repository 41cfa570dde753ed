//! The scene file's values resolved: a spectrum as written ([`SpectrumSpec`]: a number, a
//! name, a table, an sRGB colour) to tabulated data, and a point to a finite [`V3`]. File names
//! resolve against the scene file's folder ([`rebase`]). Every error names the value
//! (`scene.toml: materials.red.diffuse`).

use crate::error::{Error, Result};
use crate::geometry::V3;
use crate::sections::SpectrumSpec;
use crate::upsample;
use specpoly_spectra::spectrum_names::{self, Named};
use std::path::Path;

pub fn is_zero(s: &SpectrumSpec) -> bool {
    matches!(s, SpectrumSpec::Constant(v) if *v == 0.0)
}

pub fn flat(name: String, v: f32) -> Result<Named> {
    Ok(Named::new(name, vec![380.0, 780.0], vec![v, v])?)
}

/// Resolves one spectrum; `what` names it in errors (`scene.toml: materials.red.diffuse`).
/// File names are taken as given (relative to the current folder).
pub fn resolve_spectrum(spec: &SpectrumSpec, what: &str) -> Result<Named> {
    resolve_spectrum_in(spec, what, None)
}

/// `name` (`FILE`, `FILE#COLUMN`, or a built-in) with a relative `FILE` taken relative to
/// `base`, the scene file's folder. Built-in names (illuminants, tables) stay as they are.
pub fn rebase(name: &str, base: Option<&Path>) -> String {
    let Some(base) = base else {
        return name.to_string();
    };
    let (file, column) = match name.split_once('#') {
        Some((f, c)) => (f, Some(c)),
        None => (name, None),
    };
    let builtin = specpoly_core::Illuminant::from_name(file).is_some()
        || specpoly_spectra::data::TABLES
            .iter()
            .any(|t| t.name.eq_ignore_ascii_case(file));
    let path = Path::new(file);
    if builtin || path.is_absolute() {
        return name.to_string();
    }
    let joined = base.join(path).display().to_string();
    match column {
        Some(c) => format!("{joined}#{c}"),
        None => joined,
    }
}

/// [`resolve_spectrum`] with relative file names taken relative to `base`.
pub fn resolve_spectrum_in(spec: &SpectrumSpec, what: &str, base: Option<&Path>) -> Result<Named> {
    let data = |error| Error::Spectrum {
        what: what.to_string(),
        error: Box::new(error),
    };
    let finite = |v: f32, field: &str| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::invalid(what, format!("{field} must be finite")))
        }
    };
    match spec {
        SpectrumSpec::Constant(v) => flat(format!("{v}"), finite(*v, "the value")?),
        SpectrumSpec::Name(n) => {
            let mut v = spectrum_names::resolve(&rebase(n, base)).map_err(data)?;
            if v.len() != 1 {
                return Err(Error::invalid(
                    what,
                    format!("`{n}` names {} spectra; name one column", v.len()),
                ));
            }
            Ok(v.remove(0))
        }
        SpectrumSpec::Table(t) => {
            let mut named = match (&t.spectrum, t.rgb) {
                (Some(_), Some(_)) => {
                    return Err(Error::invalid(
                        what,
                        "give either `spectrum` or `rgb`, not both",
                    ))
                }
                (None, None) => {
                    return Err(Error::invalid(
                        what,
                        "a spectrum table needs `spectrum = NAME` or `rgb = [R, G, B]`",
                    ))
                }
                (Some(n), None) => resolve_spectrum_in(&SpectrumSpec::Name(n.clone()), what, base)?,
                (None, Some(rgb)) => {
                    for c in rgb {
                        finite(c, "rgb")?;
                    }
                    Named::new(
                        format!("rgb({}, {}, {})", rgb[0], rgb[1], rgb[2]),
                        upsample::wavelengths(),
                        upsample::rgb_to_reflectance(rgb),
                    )?
                }
            };
            let mut k = finite(t.scale.unwrap_or(1.0), "scale")?;
            if t.normalize {
                let t = named.tabulated();
                let max = (380..=780).map(|nm| t.at(nm as f64)).fold(0.0f64, f64::max);
                if max <= 0.0 {
                    return Err(Error::invalid(
                        what,
                        format!(
                            "cannot normalize `{}`: its maximum is not positive",
                            named.name
                        ),
                    ));
                }
                k /= max as f32;
            }
            if k != 1.0 {
                for v in named.values.iter_mut() {
                    *v *= k;
                }
                named.name = format!("{}×{k}", named.name);
            }
            Ok(named)
        }
    }
}

pub fn optional(spec: &SpectrumSpec, what: &str, base: Option<&Path>) -> Result<Option<Named>> {
    if is_zero(spec) {
        Ok(None)
    } else {
        resolve_spectrum_in(spec, what, base).map(Some)
    }
}

pub fn v3(a: [f32; 3], what: &str) -> Result<V3> {
    if a.iter().all(|v| v.is_finite()) {
        Ok(V3::from_array(a))
    } else {
        Err(Error::invalid(what, "coordinates must be finite"))
    }
}
