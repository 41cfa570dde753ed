//! Light metrics of SPDs (`specpoly light`), batch first: colorimetry, CCT/Duv, CIE 13.3 Ra
//! and Ri, CIE 224:2017 Rf, TM-30 Rg, CIE S 026 α-opic quantities, the ANSI C78.377 and JA8
//! checks, TM-30 in full for one light, and the PWM duties of LED channels for a target. Each
//! row goes through the very functions the CLI's `light` and `mix` commands call
//! ([`specpoly_spectra::light::report`], [`specpoly_spectra::light_tm30::tm30_report`],
//! [`specpoly_spectra::light::mix`]), so the numbers are the CLI's (rounded as it
//! prints them: 6 decimals, CCT to 0.01 K). A metric a light does not have (farther than
//! 0.05 Duv from the Planckian locus) is NaN.

use crate::arrays::{out_1d, out_rows, Rows};
use crate::lib_err;
use crate::spectra::{named, sampled};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use specpoly_core::light::cct::Cct;
use specpoly_core::light::cri::cri_spd;
use specpoly_core::light::mix_limits::{Limit, Metric as LimitMetric};
use specpoly_core::light::tm30::tm30_spd;
use specpoly_core::light::Spd;
use specpoly_core::light::Target;
use specpoly_core::Transfer;
use specpoly_spectra::light::{
    self, metric_key, observer_colour, parse_target, report, standard_spd, Channel, LightReport,
    ObserverColour, Optimize,
};
use specpoly_spectra::light_tm30::tm30_report;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(light_metrics, m)?)?;
    m.add_function(wrap_pyfunction!(colour_rendering_index, m)?)?;
    m.add_function(wrap_pyfunction!(colour_fidelity_index, m)?)?;
    m.add_function(wrap_pyfunction!(tm30, m)?)?;
    m.add_function(wrap_pyfunction!(mix, m)?)?;
    Ok(())
}

/// One optional metric of a report.
type Metric = fn(&LightReport) -> Option<f64>;

/// `f` of each light (a row of `rows`) on the standard 380–780 nm grid, in parallel with the
/// GIL released; a bad row gives the library's one-line error.
fn per_light<T: Send>(
    py: Python<'_>,
    rows: &Rows,
    wl: &[f32],
    extrapolate: bool,
    f: impl Fn(&Spd) -> T + Sync,
) -> PyResult<Vec<T>> {
    py.detach(|| {
        (0..rows.n)
            .into_par_iter()
            .map(|i| {
                let n = named(rows, wl, i).map_err(|e| e.to_string())?;
                let s = standard_spd(&n, extrapolate).map_err(|e| e.to_string())?;
                Ok(f(&s))
            })
            .collect::<Result<Vec<_>, String>>()
    })
    .map_err(lib_err)
}

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
/// Duv, Ra and Rf stay on the observers their standards fix. Also the spectrum's shape and
/// the standards' checks, as `light --json` prints them: CIE S 026 `alpha_opic_EDI` (lx) and
/// `alpha_opic_DER` (n, 5) (s-cone, m-cone, l-cone, rhodopic, melanopic; the SPD as W/m²/nm),
/// `R15`, `peak_nm`, `fwhm_nm`, `dominant_nm` (negative: complementary), `purity` (n,),
/// `ANSI_C78377` (the nominal CCT whose quadrangle holds the light, NaN: none) (n,), `JA8` (a
/// list of `True`/`False`/`None` without a CCT) and `JA8_fails` (a list of the failed clauses
/// per light: `ra`, `r9`, `cct`, `duv`).
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
    let edi = |r: &LightReport| {
        let c = &r.checks;
        vec![c.edi_sc, c.edi_mc, c.edi_lc, c.edi_rh, c.edi_mel]
    };
    d.set_item("alpha_opic_EDI", col(&edi, 5)?)?;
    let der = |r: &LightReport| {
        let c = &r.checks;
        vec![c.der_sc, c.der_mc, c.der_lc, c.der_rh, c.der_mel]
    };
    d.set_item("alpha_opic_DER", col(&der, 5)?)?;
    let scalars: [(&str, Metric); 12] = [
        ("CCT", |r| r.cct),
        ("Duv", |r| r.duv),
        ("Ra", |r| r.ra),
        ("R9", |r| r.r9),
        ("R15", |r| r.checks.r15),
        ("Rf", |r| r.rf),
        ("Rg", |r| r.rg),
        ("peak_nm", |r| Some(r.checks.peak_nm)),
        ("fwhm_nm", |r| r.checks.fwhm_nm),
        ("dominant_nm", |r| r.checks.dominant_nm),
        ("purity", |r| r.checks.purity),
        ("ANSI_C78377", |r| r.checks.ansi_c78377.map(f64::from)),
    ];
    for (key, f) in scalars {
        let v: Vec<f64> = reports.iter().map(|r| nan(f(r))).collect();
        if rows.one {
            d.set_item(key, v[0])?;
        } else {
            d.set_item(key, out_1d(py, v))?;
        }
    }
    let ja8: Vec<Option<bool>> = reports.iter().map(|r| r.checks.ja8).collect();
    let fails: Vec<Vec<&str>> = reports.iter().map(|r| r.checks.ja8_fails.clone()).collect();
    if rows.one {
        d.set_item("JA8", ja8[0])?;
        d.set_item("JA8_fails", &fails[0])?;
    } else {
        d.set_item("JA8", ja8)?;
        d.set_item("JA8_fails", fails)?;
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
    let cri = per_light(py, &rows, &wl, extrapolate, |s| cri_spd(s).ok())?;
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
    let rfg = per_light(py, &rows, &wl, extrapolate, |s| {
        tm30_spd(s).map_or([f64::NAN; 2], |t| [t.rf, t.rg])
    })?;
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

/// The mix's target: a string as `specpoly mix --target` takes it (`xy:X,Y`, `cct:K[,duv:D]`,
/// `ansi:K`), a number (a CCT in K, `duv` from the Planckian locus) or a pair `(x, y)`.
fn mix_target(obj: &Bound<'_, PyAny>, duv: f64) -> PyResult<Target> {
    let bad = |e: String| pyo3::exceptions::PyValueError::new_err(format!("target: {e}"));
    let t = if let Ok(s) = obj.cast::<pyo3::types::PyString>() {
        parse_target(&s.to_cow()?).map_err(bad)?
    } else if let Ok(k) = obj.extract::<f64>() {
        Target::Cct(Cct { cct: k, duv })
    } else if let Ok((x, y)) = obj.extract::<(f64, f64)>() {
        Target::Xy([x, y])
    } else {
        return Err(bad(
            "give a string (xy:X,Y, cct:K[,duv:D], ansi:K), a CCT in K or a pair (x, y)".into(),
        ));
    };
    t.xy().map_err(|e| bad(e.to_string()))?;
    Ok(t)
}

fn mix_optimize(s: &str) -> PyResult<Optimize> {
    match s.to_ascii_lowercase().as_str() {
        "rf" => Ok(Optimize::Rf),
        "ra" => Ok(Optimize::Ra),
        "efficacy" => Ok(Optimize::Efficacy),
        "power" => Ok(Optimize::Power),
        _ => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "optimize: `{s}` is not rf, ra, efficacy or power"
        ))),
    }
}

fn mix_limit(k: &str, min: f64) -> PyResult<Limit> {
    let metric = match k.to_ascii_lowercase().as_str() {
        "ra" => LimitMetric::Ra,
        "r9" => LimitMetric::R9,
        "rf" => LimitMetric::Rf,
        "rg" => LimitMetric::Rg,
        _ => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "minimum: `{k}` is not ra, r9, rf or rg"
            )))
        }
    };
    if !min.is_finite() {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "minimum: {k} = {min} is not a finite number"
        )));
    }
    Ok(Limit { metric, min })
}

/// PWM duties of 3–6 LED channels for a chromaticity target (`specpoly mix --json`): the
/// channels' SPDs at full drive `channels` (m, k) on `wavelengths` (k,), the target (see
/// [`mix_target`]) met under `observer`, at `luminance` (0, 1] of the most the channels give
/// there; with more than three channels the free duties maximise `optimize` (`rf`, `ra`,
/// `efficacy`) or minimise the total drive (`power`); `minimum` is a dict of least values of
/// the mix's `ra`, `r9`, `rf`, `rg`; `bits` quantises the duties. Returns a dict: `duties`
/// (m,) (linear drive: the mix is `duties @ channels`), the mix's `x`, `y`, `u_prime`,
/// `v_prime`, `CCT`, `Duv`, `Ra`, `R9`, `Rf`, `Rg` (NaN where undefined), `efficacy` (lm/W),
/// `limits` (a list of dicts `metric`, `min`, `value`, `met`; a limit no mix meets is reported
/// as missed with the closest mix, not raised), and `observer_xy` under another observer than
/// CIE 1931.
#[pyfunction]
#[pyo3(signature = (channels, wavelengths, target, duv=0.0, luminance=1.0, optimize="rf", observer="1931", minimum=None, bits=None, names=None))]
#[allow(clippy::too_many_arguments)]
fn mix<'py>(
    py: Python<'py>,
    channels: &Bound<'py, PyAny>,
    wavelengths: &Bound<'py, PyAny>,
    target: &Bound<'py, PyAny>,
    duv: f64,
    luminance: f64,
    optimize: &str,
    observer: &str,
    minimum: Option<std::collections::HashMap<String, f64>>,
    bits: Option<u32>,
    names: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (rows, wl) = sampled(channels, wavelengths)?;
    let value_err = pyo3::exceptions::PyValueError::new_err;
    if rows.one || !(3..=6).contains(&rows.n) {
        return Err(value_err(format!(
            "channels: a mix takes 3 to 6 channels, shape (m, k) with m in 3..=6 (got {})",
            if rows.one { 1 } else { rows.n }
        )));
    }
    if !(luminance > 0.0 && luminance <= 1.0) {
        return Err(value_err(format!(
            "luminance: {luminance}: the relative luminance is a number in (0, 1]"
        )));
    }
    if let Some(b) = bits {
        if !(1..=16).contains(&b) {
            return Err(value_err(format!("bits: {b} is not in 1..=16")));
        }
    }
    let names = match names {
        Some(n) if n.len() != rows.n => {
            return Err(value_err(format!(
                "names: {} names for {} channels",
                n.len(),
                rows.n
            )))
        }
        Some(n) => n,
        None => (0..rows.n).map(|i| format!("channel{i}")).collect(),
    };
    let target = mix_target(target, duv)?;
    let optimize = mix_optimize(optimize)?;
    let obs = crate::spectra::observer(observer)?;
    let mut limits = minimum
        .unwrap_or_default()
        .into_iter()
        .map(|(k, v)| mix_limit(&k, v))
        .collect::<PyResult<Vec<_>>>()?;
    limits.sort_by_key(|l| metric_key(l.metric));
    let chans = (0..rows.n)
        .map(|i| {
            Ok(Channel {
                name: names[i].clone(),
                spd: named(&rows, &wl, i).map_err(lib_err)?,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let r = py
        .detach(|| {
            light::mix(
                &chans,
                target,
                obs,
                luminance,
                optimize,
                &Transfer::Linear,
                bits,
                &limits,
            )
        })
        .map_err(lib_err)?;
    let d = PyDict::new(py);
    d.set_item("channels", &r.channels)?;
    d.set_item("duties", out_1d(py, r.duties.clone()))?;
    d.set_item("x", r.x)?;
    d.set_item("y", r.y)?;
    d.set_item("u_prime", r.u_prime)?;
    d.set_item("v_prime", r.v_prime)?;
    d.set_item("CCT", nan(r.cct))?;
    d.set_item("Duv", nan(r.duv))?;
    d.set_item("Ra", nan(r.ra))?;
    d.set_item("R9", nan(r.r9))?;
    d.set_item("Rf", nan(r.rf))?;
    d.set_item("Rg", nan(r.rg))?;
    d.set_item("efficacy", r.efficacy)?;
    let l = pyo3::types::PyList::empty(py);
    for x in &r.limits {
        let e = PyDict::new(py);
        e.set_item("metric", x.metric)?;
        e.set_item("min", x.min)?;
        e.set_item("value", nan(x.value))?;
        e.set_item("met", x.met)?;
        l.append(e)?;
    }
    d.set_item("limits", l)?;
    if let Some(o) = &r.observer {
        d.set_item("observer_xy", (o.x, o.y))?;
    }
    Ok(d)
}
