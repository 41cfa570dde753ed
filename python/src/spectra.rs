//! Reflectances → XYZ, xy, CIELAB (`specpoly xyz`) and polynomial fits (`specpoly fit`), batch
//! first. The same library calls as the CLI: each row becomes a named spectrum
//! ([`Named`]), multiplied by `scale` and refused unless it can be a reflectance
//! ([`specpoly_spectra::plausible`]), then [`colour::chains`] in the chosen representation
//! (the light tabulated, never fitted; CIELAB against the light's exact white, `Y = 100`).
//! Batches are split into chunks computed in parallel with the GIL released.

use crate::arrays::{self, out_1d, out_3d, out_rows, Rows};
use crate::{grid, lib_err};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};
use rayon::prelude::*;
use specpoly_core::{Observer, Tabulated};
use specpoly_spectra::colour::{self, Colour};
use specpoly_spectra::plausible::{self, Given};
use specpoly_spectra::repr::Repr;
use specpoly_spectra::spectrum_names::{self, Named};

/// Spectra per parallel chunk: the light's moments are computed once per chunk.
const CHUNK: usize = 512;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sd_to_xyz, m)?)?;
    m.add_function(wrap_pyfunction!(sd_to_xy, m)?)?;
    m.add_function(wrap_pyfunction!(sd_to_lab, m)?)?;
    m.add_function(wrap_pyfunction!(white_xyz, m)?)?;
    m.add_function(wrap_pyfunction!(sd_fit, m)?)?;
    m.add_function(wrap_pyfunction!(illuminants, m)?)?;
    Ok(())
}

/// The observer `s` as the CLI's `--observer` takes it
/// ([`specpoly_spectra::observer::parse`]): `1931` (`2`), `1964` (`10`), `2015-2`, `2015-10`,
/// `cie2006:age=A,field=F`, or a CSV file of three sensitivities; anything else is the
/// library's one-line error (a `ValueError`).
pub fn observer(s: &str) -> PyResult<Observer> {
    specpoly_spectra::observer::parse(s).map_err(lib_err)
}

/// The representation named `s` (as `--repr`).
fn repr(s: &str) -> PyResult<Repr> {
    s.parse::<Repr>().map_err(lib_err)
}

/// The light: `None` (D65), a name (a built-in illuminant, `FILE`, `FILE#COLUMN`) or a pair
/// `(wavelengths, values)`.
pub fn light(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Named> {
    let Some(obj) = obj else {
        return spectrum_names::light("D65").map_err(lib_err);
    };
    if let Ok(s) = obj.cast::<PyString>() {
        return spectrum_names::light(&s.to_cow()?).map_err(lib_err);
    }
    if let Ok(t) = obj.cast::<PyTuple>() {
        if t.len() == 2 {
            let wl = arrays::vector(&t.get_item(0)?, "illuminant wavelengths")?;
            let v = arrays::vector(&t.get_item(1)?, "illuminant values")?;
            if wl.len() != v.len() {
                return Err(PyValueError::new_err(format!(
                    "illuminant: {} wavelengths but {} values",
                    wl.len(),
                    v.len()
                )));
            }
            return Named::new("illuminant".into(), wl, v).map_err(lib_err);
        }
    }
    Err(PyTypeError::new_err(
        "illuminant: give a name (D65, A, FL11, FILE.csv#COLUMN) or a tuple (wavelengths, values)",
    ))
}

/// The rows of `values` on `wavelengths` (nm), checked: the same length, finite, increasing.
pub fn sampled(
    values: &Bound<'_, PyAny>,
    wavelengths: &Bound<'_, PyAny>,
) -> PyResult<(Rows, Vec<f32>)> {
    let wl = arrays::vector(wavelengths, "wavelengths")?;
    let rows = arrays::rows(values, "values", None)?;
    if rows.len != wl.len() {
        return Err(PyValueError::new_err(format!(
            "values: {} samples per spectrum but {} wavelengths (values must be (n, k) or (k,) with k = len(wavelengths))",
            rows.len,
            wl.len()
        )));
    }
    arrays::finite(&wl, "wavelengths", 0)?;
    arrays::finite(&rows.data, "values", if rows.one { 0 } else { rows.len })?;
    Ok((rows, wl))
}

/// Row `i` as a named spectrum (`values[i]`), checked by the core.
pub fn named(rows: &Rows, wl: &[f32], i: usize) -> Result<Named, specpoly_spectra::Error> {
    let name = if rows.one {
        "values".to_string()
    } else {
        format!("values[{i}]")
    };
    Named::new(name, wl.to_vec(), rows.row(i).to_vec())
}

/// Every row as a reflectance: scaled, then refused unless it can be one.
fn reflectances(rows: &Rows, wl: &[f32], scale: f64) -> Result<Vec<Named>, String> {
    (0..rows.n)
        .into_par_iter()
        .map(|i| {
            let n = plausible::scaled(named(rows, wl, i).map_err(|e| e.to_string())?, scale)
                .map_err(|e| e.to_string())?;
            plausible::reflectance_given(&n, Given::Python).map_err(|e| e.to_string())?;
            Ok(n)
        })
        .collect()
}

/// The colours of the rows (or of their product), as `specpoly xyz` computes them.
fn colours(
    rows: &Rows,
    wl: &[f32],
    light: &Named,
    observer: Observer,
    repr: Repr,
    scale: f64,
    product: bool,
) -> Result<Vec<Colour>, String> {
    let named = reflectances(rows, wl, scale)?;
    let tabs: Vec<Tabulated<'_>> = named.iter().map(Named::tabulated).collect();
    let lt = light.tabulated();
    let fail = |e: specpoly_core::Error| format!("{repr}: {e}");
    let out = if product {
        if tabs.is_empty() {
            return Err("product: no spectra to multiply".into());
        }
        colour::chains(repr, observer, &lt, &tabs, &[(0..tabs.len()).collect()]).map_err(fail)?
    } else {
        let parts = tabs
            .par_chunks(CHUNK)
            .map(|c| {
                let ch: Vec<Vec<usize>> = (0..c.len()).map(|i| vec![i]).collect();
                colour::chains(repr, observer, &lt, c, &ch).map_err(fail)
            })
            .collect::<Result<Vec<_>, String>>()?;
        parts.into_iter().flatten().collect()
    };
    for (n, c) in named.iter().zip(&out) {
        plausible::finite(&n.name, &c.xyz).map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// Parses the shared arguments, computes with the GIL released and maps each colour to `k`
/// numbers.
#[allow(clippy::too_many_arguments)]
fn batch<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer_name: &str,
    repr_name: &str,
    scale: f64,
    product: bool,
    k: usize,
    f: impl Fn(&Colour) -> [f64; 3] + Send + Sync,
) -> PyResult<Bound<'py, PyAny>> {
    // the arguments first (errors in the order of the per-spectrum path), then the grid's
    // batch path, which reads the values in place; the per-spectrum path when it declines
    let wl = arrays::vector(wavelengths, "wavelengths")?;
    arrays::finite(&wl, "wavelengths", 0)?;
    let light = light(illuminant)?;
    let obs = observer(observer_name)?;
    let repr = repr(repr_name)?;
    if !product {
        if let Some((data, n)) = grid::try_colours(py, values, &wl, &light, obs, repr, scale, k, &f)
        {
            return out_rows(py, data, n, k, false);
        }
    }
    let (rows, wl) = sampled(values, wavelengths)?;
    let (n, one) = if product {
        (1, true)
    } else {
        (rows.n, rows.one)
    };
    let data = py
        .detach(|| {
            colours(&rows, &wl, &light, obs, repr, scale, product).map(|cs| {
                cs.iter()
                    .flat_map(|c| f(c).into_iter().take(k))
                    .collect::<Vec<f64>>()
            })
        })
        .map_err(lib_err)?;
    out_rows(py, data, n, k, one)
}

/// CIE XYZ of reflectances under a light (the white has `Y = 100`).
///
/// values: (n, k) or (k,) reflectances (0–1) sampled at `wavelengths` (k,) nm, strictly
/// increasing, covering 380–780 nm or held at the ends. Returns (n, 3), or (3,) for one
/// spectrum or with `product=True` (the product of all rows: an inter-reflection chain).
/// observer: as the CLI's `--observer`: "1964" (default), "1931", "2015-2", "2015-10",
/// "cie2006:age=A,field=F", or a CSV file of three sensitivities. A 2-D float64/float32 batch
/// on one grid is one (3, k) matrix product (the grid's matrix built once and kept; equal to
/// the per-spectrum colours to f32 rounding).
#[pyfunction]
#[pyo3(name = "sd_to_XYZ", signature = (values, wavelengths, illuminant=None, observer="1964", repr="poly", scale=1.0, product=false))]
#[allow(clippy::too_many_arguments)]
fn sd_to_xyz<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer: &str,
    repr: &str,
    scale: f64,
    product: bool,
) -> PyResult<Bound<'py, PyAny>> {
    batch(
        py,
        values,
        wavelengths,
        illuminant,
        observer,
        repr,
        scale,
        product,
        3,
        |c| c.xyz,
    )
}

/// CIE xy chromaticity of reflectances under a light: (n, 2) or (2,).
#[pyfunction]
#[pyo3(signature = (values, wavelengths, illuminant=None, observer="1964", repr="poly", scale=1.0, product=false))]
#[allow(clippy::too_many_arguments)]
fn sd_to_xy<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer: &str,
    repr: &str,
    scale: f64,
    product: bool,
) -> PyResult<Bound<'py, PyAny>> {
    batch(
        py,
        values,
        wavelengths,
        illuminant,
        observer,
        repr,
        scale,
        product,
        2,
        |c| {
            let [x, y] = c.xy();
            [x, y, 0.0]
        },
    )
}

/// CIELAB of reflectances against the light's exact white: (n, 3) or (3,).
#[pyfunction]
#[pyo3(name = "sd_to_Lab", signature = (values, wavelengths, illuminant=None, observer="1964", repr="poly", scale=1.0, product=false))]
#[allow(clippy::too_many_arguments)]
fn sd_to_lab<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer: &str,
    repr: &str,
    scale: f64,
    product: bool,
) -> PyResult<Bound<'py, PyAny>> {
    batch(
        py,
        values,
        wavelengths,
        illuminant,
        observer,
        repr,
        scale,
        product,
        3,
        |c| {
            let l = c.lab();
            [l.l, l.a, l.b]
        },
    )
}

/// XYZ of the light's white (the perfect reflector, `Y = 100`, 1 nm sum): (3,).
#[pyfunction]
#[pyo3(name = "white_XYZ", signature = (illuminant=None, observer="1964"))]
fn white_xyz<'py>(
    py: Python<'py>,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let light = light(illuminant)?;
    let w = colour::white(self::observer(observer)?, &light.tabulated());
    Ok(out_1d(py, w.to_vec()))
}

/// The built-in illuminants' names.
#[pyfunction]
fn illuminants() -> Vec<&'static str> {
    specpoly_core::Illuminant::ALL
        .iter()
        .map(|i| i.name())
        .collect()
}

/// Fits reflectances by a piecewise polynomial (`specpoly fit`): a dict with
/// `coefficients` (n, spans, coeffs) Chebyshev coefficients per span (t in [-1, 1] over the
/// span), `breaks` (spans + 1,) nm, `rms` and `max` (n, spans) fit errors, `delta_E00` (n,) the
/// fit's colour error under the light.
#[pyfunction]
#[pyo3(signature = (values, wavelengths, repr="poly", illuminant=None, observer="1964", scale=1.0))]
fn sd_fit<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    repr: &str,
    illuminant: Option<&Bound<'py, PyAny>>,
    observer: &str,
    scale: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (rows, wl) = sampled(values, wavelengths)?;
    let light = light(illuminant)?;
    let obs = self::observer(observer)?;
    let repr = self::repr(repr)?
        .polynomial_for("sd_fit")
        .map_err(lib_err)?;
    let reports = py
        .detach(|| {
            let named = reflectances(&rows, &wl, scale)?;
            let lt = light.tabulated();
            named
                .par_iter()
                .map(|n| {
                    specpoly_paper::fit_report::fit_one(n, repr, obs, &lt)
                        .map_err(|e| e.to_string())
                })
                .collect::<Result<Vec<_>, String>>()
        })
        .map_err(lib_err)?;
    let spans = reports.first().map_or(0, |r| r.spans.len());
    let coeffs = reports
        .first()
        .and_then(|r| r.spans.first())
        .map_or(0, |s| s.coefficients.len());
    let n = reports.len();
    let mut c = Vec::with_capacity(n * spans * coeffs);
    let (mut rms, mut max, mut de) = (Vec::new(), Vec::new(), Vec::new());
    for r in &reports {
        for s in &r.spans {
            c.extend(s.coefficients.iter().map(|v| *v as f64));
            rms.push(s.rms as f64);
            max.push(s.max as f64);
        }
        de.push(r.delta_e00);
    }
    let breaks: Vec<f64> = reports.first().map_or(Vec::new(), |r| {
        let mut b: Vec<f64> = r.spans.iter().map(|s| s.from_nm as f64).collect();
        b.extend(r.spans.last().map(|s| s.to_nm as f64));
        b
    });
    let d = PyDict::new(py);
    if rows.one {
        d.set_item("coefficients", out_rows(py, c, spans, coeffs, false)?)?;
        d.set_item("rms", out_1d(py, rms))?;
        d.set_item("max", out_1d(py, max))?;
        d.set_item("delta_E00", de.first().copied().unwrap_or(f64::NAN))?;
    } else {
        d.set_item("coefficients", out_3d(py, c, (n, spans, coeffs))?)?;
        d.set_item("rms", out_rows(py, rms, n, spans, false)?)?;
        d.set_item("max", out_rows(py, max, n, spans, false)?)?;
        d.set_item("delta_E00", out_1d(py, de))?;
    }
    d.set_item("breaks", out_1d(py, breaks))?;
    Ok(d)
}
