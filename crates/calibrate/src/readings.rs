//! The rule for measured readings, one for every command that takes them: `calibrate fit` and
//! `run` fit them ([`crate::fit`]), `calibrate verify` compares them ([`crate::verify`]).

use crate::error::{Error, Result};
use specpoly_formats::measurement::Measurement;

/// The largest |X|, |Y| or |Z| accepted from an instrument (cd/m²): a hundred times the
/// brightest HDR display; beyond it the fit's squares would overflow and no display shows it.
pub const MAX_READING: f64 = 1e6;

/// The rule for readings, one for every command that takes them (`calibrate fit` and `run`
/// fit them, `calibrate verify` compares them): every device value and XYZ finite, and
/// |X|, |Y|, |Z| at most [`MAX_READING`]. The first measurement (1-based) that breaks it is
/// the error ([`Error::NotFinite`], [`Error::BeyondRange`]).
pub fn check_readings(meas: &[Measurement]) -> Result<()> {
    if let Some(i) = meas
        .iter()
        .position(|m| m.device.iter().chain(&m.xyz).any(|v| !v.is_finite()))
    {
        return Err(Error::NotFinite { index: i + 1 });
    }
    if let Some(i) = meas
        .iter()
        .position(|m| m.xyz.iter().any(|v| v.abs() > MAX_READING))
    {
        return Err(Error::BeyondRange {
            index: i + 1,
            xyz: meas[i].xyz,
            max: MAX_READING,
        });
    }
    Ok(())
}
