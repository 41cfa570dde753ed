//! Display models (`specpoly calibrate`): fitted from a `.ti3`, or opened from a calibration
//! file, an ICC display profile, a display TOML or `sRGB` ([`DisplaySpec::open`]); batch
//! predict (device RGB → XYZ) and inverse (XYZ → device RGB) through the core's full model
//! (matrix, curves, interaction lattice), in parallel with the GIL released; calibration, ICC
//! and 3D LUT files written whole or not at all (`specpoly_formats::atomic`).

use crate::arrays::{self, out_1d, out_rows};
use crate::lib_err;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;
use specpoly_calibrate::fit::{self, FitOptions, InteractionChoice, MatrixFit};
use specpoly_core::display_model::FULL;
use specpoly_core::Xyz;
use specpoly_display::calibration::{Calibration, TransferKind};
use specpoly_display::icc::{self, IccOptions, IccVersion};
use specpoly_display::lut3d::source::SourceSpace;
use specpoly_display::lut3d::{self, file, GamutMode, Options, WhiteMode};
use specpoly_display::spec::DisplaySpec;
use specpoly_formats::cgats;
use std::path::{Path, PathBuf};

/// Triples per parallel chunk.
const CHUNK: usize = 4096;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<DisplayModel>()?;
    Ok(())
}

/// A display's model: device RGB (0–1) ↔ CIE XYZ (cd/m² for absolute measurements, else
/// relative to a white of `Y = 100`).
#[pyclass(module = "specpoly", frozen)]
pub struct DisplayModel {
    model: Box<specpoly_core::DisplayModel<FULL>>,
    calibration: Option<Calibration>,
    name: String,
}

fn path_string(p: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    p.extract::<PathBuf>()
        .map_err(|_| PyTypeError::new_err("path: give a str or os.PathLike"))
}

fn transfer(s: &str) -> PyResult<TransferKind> {
    match s {
        "table" => Ok(TransferKind::Table),
        "gamma" => Ok(TransferKind::Gamma),
        _ => Err(PyValueError::new_err(format!(
            "unknown transfer `{s}`: table or gamma"
        ))),
    }
}

fn matrix(s: &str) -> PyResult<MatrixFit> {
    match s {
        "least-squares" => Ok(MatrixFit::LeastSquares),
        "cowan" => Ok(MatrixFit::Cowan),
        _ => Err(PyValueError::new_err(format!(
            "unknown matrix fit `{s}`: least-squares or cowan"
        ))),
    }
}

impl DisplayModel {
    fn calibration(&self, what: &str) -> PyResult<&Calibration> {
        self.calibration.as_ref().ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what} needs a calibration (DisplayModel.fit_ti3 or a calibration file); `{}` is not one",
                self.name
            ))
        })
    }

    fn from_calibration(cal: Calibration, name: String) -> Self {
        DisplayModel {
            model: Box::new(cal.model().clone()),
            calibration: Some(cal),
            name,
        }
    }
}

/// Fits a calibration to a `.ti3` as `specpoly calibrate fit` does, with the same provenance
/// ([`fit::provenance::record`]).
fn fit_ti3(path: &Path, opts: FitOptions, hold_out: bool) -> Result<Calibration, String> {
    let shown = path.display().to_string();
    let bytes = specpoly_formats::read::bytes(path).map_err(|e| e.to_string())?;
    let sha = specpoly_calibrate::session::sha256_hex(&bytes);
    let ti3 = cgats::read_ti3(&specpoly_formats::read::decode(bytes), &shown)
        .map_err(|e| e.to_string())?;
    let (meas, absolute) = ti3.best_units();
    let (fit_set, verify_set) = if hold_out {
        fit::hold_out(meas)
    } else {
        (meas, Vec::new())
    };
    let opts = FitOptions { absolute, ..opts };
    let mut cal =
        fit::fit_and_verify(&fit_set, &verify_set, &opts).map_err(|e| format!("{shown}: {e}"))?;
    fit::provenance::record(&mut cal, &ti3, &shown, sha).map_err(|e| e.to_string())?;
    Ok(cal)
}

#[pymethods]
impl DisplayModel {
    /// Opens a display: a calibration file (TOML), an ICC display profile, a display TOML of
    /// primaries, or "sRGB".
    #[staticmethod]
    fn open(py: Python<'_>, spec: &Bound<'_, PyAny>) -> PyResult<Self> {
        let s = path_string(spec)?.display().to_string();
        let spec = py
            .detach(|| DisplaySpec::open(&s))
            .map_err(crate::lib_err)?;
        Ok(DisplayModel {
            model: spec.model(),
            name: spec.name(),
            calibration: spec.calibration().cloned(),
        })
    }

    /// Fits a display model to measurements in a CGATS `.ti3` (ArgyllCMS, DisplayCAL,
    /// `specpoly calibrate run`), as `specpoly calibrate fit` does.
    #[staticmethod]
    #[pyo3(signature = (path, transfer="table", matrix="least-squares", table_points=64, interaction="auto", hold_out=false, keep_outliers=false))]
    #[allow(clippy::too_many_arguments)]
    fn fit_ti3(
        py: Python<'_>,
        path: &Bound<'_, PyAny>,
        transfer: &str,
        matrix: &str,
        table_points: usize,
        interaction: &str,
        hold_out: bool,
        keep_outliers: bool,
    ) -> PyResult<Self> {
        let path = path_string(path)?;
        let opts = FitOptions {
            transfer: self::transfer(transfer)?,
            matrix: self::matrix(matrix)?,
            table_points,
            interaction: interaction
                .parse::<InteractionChoice>()
                .map_err(PyValueError::new_err)?,
            robust: !keep_outliers,
            ..Default::default()
        };
        let cal = py
            .detach(|| fit_ti3(&path, opts, hold_out))
            .map_err(lib_err)?;
        Ok(Self::from_calibration(cal, path.display().to_string()))
    }

    /// The file it came from, or "sRGB".
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The model's white (device RGB 1, 1, 1) XYZ: (3,).
    #[getter]
    fn white<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let w = self.model.white();
        out_1d(py, vec![w.x as f64, w.y as f64, w.z as f64])
    }

    /// Whether the model has a channel-interaction lattice.
    #[getter]
    fn has_interaction(&self) -> bool {
        self.model.interaction().is_some()
    }

    /// The fit's ΔE00 over its patches `(mean, p95, max)` (calibrations only).
    #[getter]
    fn fit_delta_e00(&self) -> PyResult<(f64, f64, f64)> {
        let r = &self.calibration("fit_delta_e00")?.data().fit.residual;
        Ok((r.mean, r.p95, r.max))
    }

    /// XYZ of device RGB (0–1): rgb (n, 3) or (3,) → (n, 3) or (3,).
    fn predict<'py>(
        &self,
        py: Python<'py>,
        rgb: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let rows = arrays::rows(rgb, "rgb", Some(3))?;
        arrays::finite(&rows.data, "rgb", if rows.one { 0 } else { 3 })?;
        let out: Vec<f64> = py.detach(|| {
            rows.data
                .par_chunks(3 * CHUNK)
                .flat_map_iter(|c| {
                    c.chunks_exact(3).flat_map(|t| {
                        let x = self.model.device_to_xyz([t[0], t[1], t[2]]);
                        [x.x as f64, x.y as f64, x.z as f64]
                    })
                })
                .collect()
        });
        out_rows(py, out, rows.n, 3, rows.one)
    }

    /// Device RGB (0–1) whose prediction is XYZ: xyz (n, 3) or (3,) → (n, 3) or (3,); exact
    /// (ΔE00 ≤ 0.005) inside the gamut, outside it the nearest prediction within the cube.
    fn inverse<'py>(
        &self,
        py: Python<'py>,
        xyz: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let rows = arrays::rows(xyz, "xyz", Some(3))?;
        arrays::finite(&rows.data, "xyz", if rows.one { 0 } else { 3 })?;
        let out: Vec<f64> = py.detach(|| {
            rows.data
                .par_chunks(3 * CHUNK)
                .flat_map_iter(|c| {
                    c.chunks_exact(3).flat_map(|t| {
                        let s = self.model.inverse(Xyz::new(t[0], t[1], t[2]));
                        s.device.map(f64::from)
                    })
                })
                .collect()
        });
        out_rows(py, out, rows.n, 3, rows.one)
    }

    /// Writes the calibration file (TOML), whole or not at all.
    fn save(&self, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = path_string(path)?;
        self.calibration("save")?.save(&path).map_err(lib_err)
    }

    /// Writes an ICC display profile (`specpoly calibrate icc`): version 2 (v2.4) or 4 (v4.4);
    /// `tables` adds A2B0/B2A0 (default: when the model has channel interaction).
    #[pyo3(signature = (path, version=2, tables=None, description=None))]
    fn write_icc(
        &self,
        path: &Bound<'_, PyAny>,
        version: u8,
        tables: Option<bool>,
        description: Option<String>,
    ) -> PyResult<()> {
        let path = path_string(path)?;
        let cal = self.calibration("write_icc")?;
        let version = match version {
            2 => IccVersion::V2,
            4 => IccVersion::V4,
            v => {
                return Err(PyValueError::new_err(format!(
                    "ICC version {v}: give 2 or 4"
                )))
            }
        };
        let auto = IccOptions::for_calibration(cal);
        let opts = IccOptions {
            version,
            tables: tables.unwrap_or(auto.tables),
        };
        let desc = description.unwrap_or_else(|| icc::description(cal, Path::new(&self.name)));
        let bytes = icc::build(cal, &desc, &opts).map_err(lib_err)?;
        specpoly_formats::atomic::write(&path, &bytes).map_err(lib_err)
    }

    /// Writes a 3D LUT from a source colour space to the display (`specpoly calibrate
    /// lut3d`): .cube, .3dl or .3dlut by the file's extension; source srgb, rec709,
    /// display-p3 or rec2020; white adapt or keep; gamut clip or desaturate.
    #[pyo3(signature = (path, source="srgb", size=33, white="adapt", gamut="clip", exact_nodes=false))]
    #[allow(clippy::too_many_arguments)]
    fn write_lut3d(
        &self,
        py: Python<'_>,
        path: &Bound<'_, PyAny>,
        source: &str,
        size: usize,
        white: &str,
        gamut: &str,
        exact_nodes: bool,
    ) -> PyResult<()> {
        let path = path_string(path)?;
        let format = file::Format::from_path(&path).ok_or_else(|| {
            PyValueError::new_err(format!(
                "cannot tell the LUT format from `{}`: name it .cube, .3dl or .3dlut",
                path.display()
            ))
        })?;
        let source = SourceSpace::from_name(source).map_err(lib_err)?;
        let white = match white {
            "adapt" => WhiteMode::Adapt,
            "keep" => WhiteMode::Keep,
            w => {
                return Err(PyValueError::new_err(format!(
                    "unknown white `{w}`: adapt or keep"
                )))
            }
        };
        let gamut = match gamut {
            "clip" => GamutMode::Clip,
            "desaturate" => GamutMode::Desaturate,
            g => {
                return Err(PyValueError::new_err(format!(
                    "unknown gamut `{g}`: clip or desaturate"
                )))
            }
        };
        lut3d::check_size(size).map_err(lib_err)?;
        let opts = Options {
            source,
            size,
            white,
            gamut,
            refine: !exact_nodes,
        };
        py.detach(|| {
            let lut = lut3d::build(&self.model, &self.name, &opts).map_err(|e| e.to_string())?;
            let bytes = file::write(&lut, format, opts.source);
            specpoly_formats::atomic::write(&path, &bytes).map_err(|e| e.to_string())
        })
        .map_err(lib_err)
    }

    fn __repr__(&self) -> String {
        format!("DisplayModel({:?})", self.name)
    }
}
