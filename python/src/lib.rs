//! # specpoly for Python
//!
//! The `specpoly._specpoly` extension module: the library crates' functions over NumPy arrays,
//! batch first. Every function checks its arrays (shape, dtype, finiteness) before any work,
//! converts them once to the library's types, releases the GIL for the batch and returns new
//! arrays. Nothing here computes colour: the maths is the library's, called exactly as the CLI
//! calls it (`specpoly xyz`, `light`, `calibrate fit|predict|icc|lut3d`), so the package and the
//! CLI print the same numbers.
//!
//! - [`arrays`]: NumPy in and out (shapes, dtypes, the one-line errors for bad input);
//! - [`spectra`]: reflectances → XYZ, xy, CIELAB and polynomial fits (`specpoly xyz`, `fit`);
//! - [`grid`]: the batch path for reflectances on one shared wavelength grid (one matrix);
//! - [`light`]: CCT/Duv, CIE 13.3 Ra/Ri, CIE 224 Rf, TM-30 Rg and hue bins (`specpoly light`);
//! - [`display`]: display models (`.ti3` fits, calibrations, ICC profiles), predict, inverse,
//!   ICC and 3D LUT files (`specpoly calibrate`).
//!
//! Errors: the library's errors are raised as `specpoly.SpecpolyError` (a `ValueError`) with the
//! library's one-line message; bad arrays as `ValueError` (shape, values) or `TypeError` (dtype).
//!
//! `unsafe_code` is denied rather than forbidden: PyO3's macros expand to `unsafe` blocks they
//! allow locally, which `forbid` would refuse; this crate writes none.
#![deny(unsafe_code)]

use pyo3::prelude::*;

pub mod arrays;
pub mod display;
pub mod grid;
pub mod light;
pub mod spectra;

pyo3::create_exception!(
    specpoly,
    SpecpolyError,
    pyo3::exceptions::PyValueError,
    "An error of the specpoly library, with its one-line message (a ValueError)."
);

/// The library's error `e` as a Python exception (its one-line message).
pub fn lib_err(e: impl std::fmt::Display) -> PyErr {
    SpecpolyError::new_err(e.to_string())
}

#[pymodule]
fn _specpoly(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SpecpolyError", m.py().get_type::<SpecpolyError>())?;
    spectra::register(m)?;
    light::register(m)?;
    display::register(m)?;
    Ok(())
}
