//! NumPy arrays in and out. Inputs are any array-like of real numbers (float64, float32 or
//! integers; anything else is a `TypeError`), converted once to the library's f32 (the kernels'
//! type: measured spectra carry 3–4 digits) in row-major order whatever the strides; outputs are
//! new float64 arrays.

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{
    IntoPyArray, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// Values of an array in row-major order and its shape.
pub struct Floats {
    /// The values.
    pub data: Vec<f32>,
    /// The shape.
    pub shape: Vec<usize>,
}

/// `obj` as an array of real numbers (`what` names it in errors).
pub fn floats(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Floats> {
    let py = obj.py();
    let arr = if obj.is_instance_of::<PyUntypedArray>() {
        obj.clone()
    } else {
        py.import("numpy")?
            .getattr("asarray")?
            .call1((obj,))
            .map_err(|e| PyTypeError::new_err(format!("{what}: not an array of numbers ({e})")))?
    };
    if let Ok(a) = arr.cast::<PyArrayDyn<f64>>() {
        let r = a.readonly();
        let v = r.as_array();
        return Ok(Floats {
            data: v.iter().map(|x| *x as f32).collect(),
            shape: v.shape().to_vec(),
        });
    }
    if let Ok(a) = arr.cast::<PyArrayDyn<f32>>() {
        let r = a.readonly();
        let v = r.as_array();
        return Ok(Floats {
            data: v.iter().copied().collect(),
            shape: v.shape().to_vec(),
        });
    }
    let u = arr.cast::<PyUntypedArray>()?;
    let dtype = u.dtype();
    let kind = dtype.kind();
    if kind == b'i' || kind == b'u' || (kind == b'f' && dtype.itemsize() != 16) {
        // integers and float16: exactly representable as float64
        let f = arr.call_method1("astype", ("float64",))?;
        return floats(&f, what);
    }
    Err(PyTypeError::new_err(format!(
        "{what}: expected an array of real numbers (float64, float32 or integers), got dtype {}",
        dtype.str()?
    )))
}

/// A batch of rows of `len` values: `(n, len)`, or `(len,)` for one row (`one`).
pub struct Rows {
    /// Row-major values.
    pub data: Vec<f32>,
    /// Number of rows.
    pub n: usize,
    /// Values per row.
    pub len: usize,
    /// Given as one row (1-D): the result drops its batch axis.
    pub one: bool,
}

impl Rows {
    /// Row `i`.
    pub fn row(&self, i: usize) -> &[f32] {
        &self.data[i * self.len..(i + 1) * self.len]
    }
}

/// `obj` as rows: shape `(n, len)` or `(len,)`, with `len` fixed when `len` is given; `what`
/// names it and `axis` names its last axis in errors.
pub fn rows(obj: &Bound<'_, PyAny>, what: &str, len: Option<usize>) -> PyResult<Rows> {
    let f = floats(obj, what)?;
    let (n, k, one) = match f.shape[..] {
        [k] => (1, k, true),
        [n, k] => (n, k, false),
        _ => {
            return Err(PyValueError::new_err(format!(
                "{what}: expected a 1-D or 2-D array, got shape {:?}",
                f.shape
            )))
        }
    };
    if let Some(want) = len {
        if k != want {
            return Err(PyValueError::new_err(format!(
                "{what}: expected shape (n, {want}) or ({want},), got {:?}",
                f.shape
            )));
        }
    }
    Ok(Rows {
        data: f.data,
        n,
        len: k,
        one,
    })
}

/// `obj` as one 1-D array.
pub fn vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f32>> {
    let f = floats(obj, what)?;
    if f.shape.len() != 1 {
        return Err(PyValueError::new_err(format!(
            "{what}: expected a 1-D array, got shape {:?}",
            f.shape
        )));
    }
    Ok(f.data)
}

/// Refuses non-finite values (`what` names the array).
pub fn finite(data: &[f32], what: &str, row_len: usize) -> PyResult<()> {
    match data.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) if row_len > 0 => Err(PyValueError::new_err(format!(
            "{what}[{}, {}] is not finite",
            i / row_len,
            i % row_len
        ))),
        Some(i) => Err(PyValueError::new_err(format!("{what}[{i}] is not finite"))),
    }
}

/// `n` rows of `k` values as a float64 array: `(n, k)`, or `(k,)` when `one`.
pub fn out_rows<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    n: usize,
    k: usize,
    one: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if one {
        return Ok(Array1::from_vec(data).into_pyarray(py).into_any());
    }
    let a = Array2::from_shape_vec((n, k), data)
        .map_err(|e| PyValueError::new_err(format!("result shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any())
}

/// A float64 array of shape `(a, b, c)`.
pub fn out_3d<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    shape: (usize, usize, usize),
) -> PyResult<Bound<'py, PyAny>> {
    let a = Array3::from_shape_vec(shape, data)
        .map_err(|e| PyValueError::new_err(format!("result shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any())
}

/// A 1-D float64 array.
pub fn out_1d(py: Python<'_>, data: Vec<f64>) -> Bound<'_, PyAny> {
    Array1::from_vec(data).into_pyarray(py).into_any()
}
