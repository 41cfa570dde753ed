//! CIE standard illuminants, kept as tabulated data: a light is never fitted by a polynomial
//! (Raso & Fournier 1991, §7.1; a cubic fit of a fluorescent lamp is ≈ 9 ΔE00 off).
//!
//! Tables: CIE 015:2018 via colour-science 0.4.7 (`data/illuminants/`), 5 nm over 380–780 nm.

use crate::observer::{
    ILLUMINANT_A, ILLUMINANT_D50, ILLUMINANT_D65, ILLUMINANT_FL11, ILLUMINANT_FL2, ILLUMINANT_FL7,
};
use crate::Tabulated;

/// 380, 385, …, 780 nm: the wavelengths of every built-in illuminant table.
pub static WAVELENGTHS_5NM: [f32; 81] = {
    let mut w = [0.0f32; 81];
    let mut i = 0;
    while i < 81 {
        w[i] = 380.0 + 5.0 * i as f32;
        i += 1;
    }
    w
};

static EQUAL_ENERGY: [f32; 81] = [100.0; 81];

/// A built-in CIE illuminant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Illuminant {
    /// Incandescent (Planckian, 2856 K).
    A,
    /// Daylight, 5003 K.
    D50,
    /// Daylight, 6504 K.
    D65,
    /// Equal energy.
    E,
    /// Fluorescent, cool white (standard halophosphate).
    FL2,
    /// Fluorescent, broadband D65 simulator.
    FL7,
    /// Fluorescent, narrow tri-band (spiky).
    FL11,
}

impl Illuminant {
    /// Every built-in illuminant.
    pub const ALL: [Illuminant; 7] = [
        Illuminant::A,
        Illuminant::D50,
        Illuminant::D65,
        Illuminant::E,
        Illuminant::FL2,
        Illuminant::FL7,
        Illuminant::FL11,
    ];

    /// Its name as the CIE writes it.
    pub fn name(self) -> &'static str {
        match self {
            Illuminant::A => "A",
            Illuminant::D50 => "D50",
            Illuminant::D65 => "D65",
            Illuminant::E => "E",
            Illuminant::FL2 => "FL2",
            Illuminant::FL7 => "FL7",
            Illuminant::FL11 => "FL11",
        }
    }

    /// Looks a built-in up by name (case-insensitive).
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|i| i.name().eq_ignore_ascii_case(s))
    }

    /// Relative spectral power at 380, 385, …, 780 nm.
    pub fn values(self) -> &'static [f32; 81] {
        match self {
            Illuminant::A => &ILLUMINANT_A,
            Illuminant::D50 => &ILLUMINANT_D50,
            Illuminant::D65 => &ILLUMINANT_D65,
            Illuminant::E => &EQUAL_ENERGY,
            Illuminant::FL2 => &ILLUMINANT_FL2,
            Illuminant::FL7 => &ILLUMINANT_FL7,
            Illuminant::FL11 => &ILLUMINANT_FL11,
        }
    }

    /// The table as [`Tabulated`] data.
    pub fn tabulated(self) -> Tabulated<'static> {
        match Tabulated::new(&WAVELENGTHS_5NM, self.values()) {
            Ok(t) => t,
            // The built-in tables are checked by a unit test; this arm is unreachable.
            Err(_) => unreachable!("built-in illuminant tables are valid"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn built_in_tables_are_valid() {
        for i in Illuminant::ALL {
            assert!(Tabulated::new(&WAVELENGTHS_5NM, i.values()).is_ok());
            assert_eq!(
                Illuminant::from_name(&i.name().to_ascii_lowercase()),
                Some(i)
            );
        }
        // D65 is normalised to 100 at 560 nm
        assert!((Illuminant::D65.values()[36] - 100.0).abs() < 1e-3);
    }
}
