//! The standards' test samples as fitted polynomial reflectances.
//!
//! CIE 13.3-1995's 14 test colour samples (TCS01–TCS14; Ra averages the first 8, R9 is the
//! saturated red) with the Japanese skin sample TCS15 of JIS Z 8726:1990 (R15; the CIE's 2024
//! data set of it), and CIE 224:2017's 99 colour evaluation samples (CES01–CES99), tabulated at
//! 5 nm over 380–780 nm (`data/reflectances/`, via colour-science 0.4.7), each fitted once with
//! the project default [`DefaultSpectrum`] (8 uniform cubic spans, [`crate::fit`]). A light is
//! never fitted: the samples' colours come from the light's moments.

use crate::illuminant::WAVELENGTHS_5NM;
use crate::observer::{CES99, TCS14, TCS15};
use crate::{DefaultSpectrum, Tabulated};

/// `N` fitted reflectance samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Samples<const N: usize> {
    /// The fitted reflectances, in the standard's order.
    pub spectra: [DefaultSpectrum; N],
}

fn fit_all<const N: usize>(table: &[[f32; 81]; N]) -> [DefaultSpectrum; N] {
    core::array::from_fn(|i| {
        Tabulated::new(&WAVELENGTHS_5NM, &table[i])
            .and_then(|t| DefaultSpectrum::fit(&t))
            // The built-in tables are finite, increasing and inside 380–780 nm (unit test below).
            .unwrap_or(DefaultSpectrum::ZERO)
    })
}

impl Samples<15> {
    /// The 14 test colour samples of CIE 13.3-1995 and JIS Z 8726's TCS15 (Japanese skin).
    pub fn cie13_3() -> Self {
        Self {
            spectra: fit_all(&tcs15_all()),
        }
    }
}

/// TCS01–TCS15 in one table.
fn tcs15_all() -> [[f32; 81]; 15] {
    core::array::from_fn(|i| if i < 14 { TCS14[i] } else { TCS15[0] })
}

impl Samples<99> {
    /// The 99 colour evaluation samples of CIE 224:2017 / ANSI-IES TM-30.
    pub fn cie224() -> Self {
        Self {
            spectra: fit_all(&CES99),
        }
    }
}

/// The tabulated 5 nm reflectance of TCS `i` (0-based, 0–14: TCS15 is index 14), for 1 nm
/// reference sums.
pub fn tcs_table(i: usize) -> Tabulated<'static> {
    table(if i < 14 { &TCS14[i] } else { &TCS15[0] })
}

/// The tabulated 5 nm reflectance of CES `i` (0-based), for 1 nm reference sums.
pub fn ces_table(i: usize) -> Tabulated<'static> {
    table(&CES99[i])
}

fn table(v: &'static [f32; 81]) -> Tabulated<'static> {
    match Tabulated::new(&WAVELENGTHS_5NM, v) {
        Ok(t) => t,
        // checked by the unit test below
        Err(_) => unreachable!("built-in sample tables are valid"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_valid_and_fit_closely() {
        let s = Samples::cie224();
        for i in 0..99 {
            let t = Tabulated::new(&WAVELENGTHS_5NM, &CES99[i]).unwrap();
            let e = s.spectra[i].fit_errors(&t);
            assert!(
                e.max.iter().all(|m| *m < 0.1),
                "CES{:02}: {:?}",
                i + 1,
                e.max
            );
        }
        let s = Samples::cie13_3();
        for i in 0..15 {
            let t = tcs_table(i);
            let e = s.spectra[i].fit_errors(&t);
            assert!(
                e.max.iter().all(|m| *m < 0.05),
                "TCS{:02}: {:?}",
                i + 1,
                e.max
            );
        }
    }
}
