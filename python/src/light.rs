//! Light metrics of SPDs (`specpoly light`), batch first: colorimetry, CCT/Duv, CIE 13.3 Ra
//! and Ri, CIE 224:2017 Rf, TM-30 Rg, and TM-30 in full for one light. Each row goes through
//! the very functions the CLI's `light` command calls ([`specpoly_spectra::light::report`],
//! [`specpoly_spectra::light_tm30::tm30_report`]), so the numbers are the CLI's (rounded as it
//! prints them: 6 decimals, CCT to 0.01 K). A metric a light does not have (farther than
//! 0.05 Duv from the Planckian locus) is NaN.

use crate::arrays::{out_1d, out_rows};
use crate::lib_err;
use crate::spectra::{named, sampled};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use specpoly_core::light::cri::cri_spd;
use specpoly_core::light::tm30::tm30_spd;
use specpoly_spectra::light::{observer_colour, report, standard_spd, LightReport, ObserverColour};
use specpoly_spectra::light_tm30::tm30_report;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(light_metrics, m)?)?;
    m.add_function(wrap_pyfunction!(colour_rendering_index, m)?)?;
    m.add_function(wrap_pyfunction!(colour_fidelity_index, m)?)?;
    m.add_function(wrap_pyfunction!(tm30, m)?)?;
    Ok(())
}

/// One optional metric of a report.
type Metric = fn(&LightReport) -> Option<f64>;

fn nan(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// The metrics of SPDs, as `specpoly light --json` prints them: a dict of arrays, `XYZ` (n, 3)
/// (`Km·Σ S x̄ Δλ`, CIE 1931: lumens for Y when the SPD is in W/nm), `xy` and `uv_prime`
/// (n, 2), `CCT` (K), `Duv`, `Ra`, `R9`, `Rf`, `Rg` (n,); one light (k,) gives (3,), (2,) and
/// floats. Lights tabulated over less than 380–780 nm are refused unless `extrapolate` (the
/// end values held, CIE 015:2018). With `observer` (any of `sd_to_XYZ`'s: `2015-10`,
/// `cie2006:age=A,field=F`, a sensitivity CSV, …; `light --observer`), also the light's colour
/// under it: `observer_XYZ` (`Km·Σ S·[x̄, ȳ, z̄]·Δλ`), `observer_xy`, `observer_uv_prime`; CCT,
/// Duv, Ra and Rf stay on the observers their standards fix.
#[pyfunction]
#[pyo3(signature = (values, wavelengths, extrapolate=false, observer=None))]
fn light_metrics<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    extrapolate: bool,
    observer: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let (rows, wl) = sampled(values, wavelengths)?;
    let obs = observer.map(crate::spectra::observer).transpose()?;
    let reports: Vec<LightReport> = py
        .detach(|| {
            (0..rows.n)
                .into_par_iter()
                .map(|i| {
                    let n = named(&rows, &wl, i).map_err(|e| e.to_string())?;
                    let mut r = report(&n, extrapolate).map_err(|e| e.to_string())?;
                    if let Some(o) = obs {
                        let s = standard_spd(&n, extrapolate).map_err(|e| e.to_string())?;
                        r.observer = Some(observer_colour(&s, o));
                    }
                    Ok(r)
                })
                .collect::<Result<Vec<_>, String>>()
        })
        .map_err(lib_err)?;
    let n = reports.len();
    let col = |f: &dyn Fn(&LightReport) -> Vec<f64>, k: usize| {
        out_rows(py, reports.iter().flat_map(f).collect(), n, k, rows.one)
    };
    let d = PyDict::new(py);
    d.set_item("XYZ", col(&|r| vec![r.big_x, r.big_y, r.big_z], 3)?)?;
    d.set_item("xy", col(&|r| vec![r.x, r.y], 2)?)?;
    d.set_item("uv_prime", col(&|r| vec![r.u_prime, r.v_prime], 2)?)?;
    if obs.is_some() {
        // every report has the observer's colour when one was asked for
        let oc = |r: &LightReport, f: fn(&ObserverColour) -> Vec<f64>, k: usize| {
            r.observer.as_ref().map_or(vec![f64::NAN; k], f)
        };
        let xyz = col(&|r| oc(r, |o| vec![o.big_x, o.big_y, o.big_z], 3), 3)?;
        d.set_item("observer_XYZ", xyz)?;
        d.set_item("observer_xy", col(&|r| oc(r, |o| vec![o.x, o.y], 2), 2)?)?;
        let uv = col(&|r| oc(r, |o| vec![o.u_prime, o.v_prime], 2), 2)?;
        d.set_item("observer_uv_prime", uv)?;
    }
    let scalars: [(&str, Metric); 6] = [
        ("CCT", |r| r.cct),
        ("Duv", |r| r.duv),
        ("Ra", |r| r.ra),
        ("R9", |r| r.r9),
        ("Rf", |r| r.rf),
        ("Rg", |r| r.rg),
    ];
    for (key, f) in scalars {
        let v: Vec<f64> = reports.iter().map(|r| nan(f(r))).collect();
        if rows.one {
            d.set_item(key, v[0])?;
        } else {
            d.set_item(key, out_1d(py, v))?;
        }
    }
    Ok(d)
}

/// CIE 13.3 colour rendering: `(Ra, Ri)` with Ra (n,) and the special indices R1–R14 (n, 14)
/// (or a float and (14,) for one light), unrounded; NaN where the light has no CCT.
#[pyfunction]
#[pyo3(signature = (values, wavelengths, extrapolate=false))]
fn colour_rendering_index<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    extrapolate: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (rows, wl) = sampled(values, wavelengths)?;
    let cri: Vec<Option<_>> = py
        .detach(|| {
            (0..rows.n)
                .into_par_iter()
                .map(|i| {
                    let n = named(&rows, &wl, i).map_err(|e| e.to_string())?;
                    let s = standard_spd(&n, extrapolate).map_err(|e| e.to_string())?;
                    Ok(cri_spd(&s).ok())
                })
                .collect::<Result<Vec<_>, String>>()
        })
        .map_err(lib_err)?;
    let ra: Vec<f64> = cri.iter().map(|c| nan(c.map(|c| c.ra))).collect();
    let ri: Vec<f64> = cri
        .iter()
        .flat_map(|c| c.map_or([f64::NAN; 14], |c| c.r))
        .collect();
    let ra = if rows.one {
        ra[0].into_pyobject(py)?.into_any()
    } else {
        out_1d(py, ra)
    };
    Ok((ra, out_rows(py, ri, cri.len(), 14, rows.one)?))
}

/// CIE 224:2017 Rf and ANSI/IES TM-30-20 Rg: `(Rf, Rg)`, each (n,) (or floats for one light),
/// unrounded (`light_metrics` rounds them as the CLI prints them, to 6 decimals); NaN where the
/// light has no CCT. Only TM-30 is computed (`light_metrics` also computes CIE 13.3 and the
/// standards' checks).
#[pyfunction]
#[pyo3(signature = (values, wavelengths, extrapolate=false))]
fn colour_fidelity_index<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    extrapolate: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (rows, wl) = sampled(values, wavelengths)?;
    let rfg: Vec<[f64; 2]> = py
        .detach(|| {
            (0..rows.n)
                .into_par_iter()
                .map(|i| {
                    let n = named(&rows, &wl, i).map_err(|e| e.to_string())?;
                    let s = standard_spd(&n, extrapolate).map_err(|e| e.to_string())?;
                    Ok(tm30_spd(&s).map_or([f64::NAN; 2], |t| [t.rf, t.rg]))
                })
                .collect::<Result<Vec<_>, String>>()
        })
        .map_err(lib_err)?;
    let out = |k: usize| -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = rfg.iter().map(|r| r[k]).collect();
        if rows.one {
            Ok(v[0].into_pyobject(py)?.into_any())
        } else {
            Ok(out_1d(py, v))
        }
    };
    Ok((out(0)?, out(1)?))
}

/// ANSI/IES TM-30-20 in full for one light (k,) (`specpoly light --tm30 --json`): a dict with
/// `Rf`, `Rg`, `CCT`, `Duv` (floats), the 16 hue bins' `Rf_hj`, `Rcs_hj` (percent), `Rhs_hj`
/// (16,), the bins' mean CAM02-UCS `test_ab` and `reference_ab` (16, 2), `Rf_ces` (99,) and
/// `bin_of_ces` (99,) (1–16), and `design_intents` (P, V, F levels).
#[pyfunction]
#[pyo3(signature = (values, wavelengths, extrapolate=false))]
fn tm30<'py>(
    py: Python<'py>,
    values: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    extrapolate: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let (rows, wl) = sampled(values, wavelengths)?;
    if !rows.one {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "tm30: give one light, shape (k,)",
        ));
    }
    let r = py
        .detach(|| {
            let n = named(&rows, &wl, 0).map_err(|e| e.to_string())?;
            tm30_report(&n, extrapolate).map_err(|e| e.to_string())
        })
        .map_err(lib_err)?;
    let d = PyDict::new(py);
    d.set_item("Rf", r.rf)?;
    d.set_item("Rg", r.rg)?;
    d.set_item("CCT", r.cct)?;
    d.set_item("Duv", r.duv)?;
    let bins = |f: &dyn Fn(&specpoly_spectra::light_tm30::BinReport) -> f64| {
        out_1d(py, r.bins.iter().map(f).collect())
    };
    d.set_item("Rf_hj", bins(&|b| b.rf))?;
    d.set_item("Rcs_hj", bins(&|b| b.rcs_percent))?;
    d.set_item("Rhs_hj", bins(&|b| b.rhs))?;
    let ab = |f: &dyn Fn(&specpoly_spectra::light_tm30::BinReport) -> [f64; 2]| {
        out_rows(py, r.bins.iter().flat_map(f).collect(), 16, 2, false)
    };
    d.set_item("test_ab", ab(&|b| [b.test_a, b.test_b])?)?;
    d.set_item("reference_ab", ab(&|b| [b.reference_a, b.reference_b])?)?;
    d.set_item("Rf_ces", out_1d(py, r.ces.iter().map(|c| c.rf).collect()))?;
    d.set_item(
        "bin_of_ces",
        r.ces.iter().map(|c| c.bin).collect::<Vec<usize>>(),
    )?;
    let di = PyDict::new(py);
    di.set_item("preference", &r.design_intents.preference)?;
    di.set_item("vividness", &r.design_intents.vividness)?;
    di.set_item("fidelity", &r.design_intents.fidelity)?;
    d.set_item("design_intents", di)?;
    Ok(d)
}
