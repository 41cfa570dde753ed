//! The CIE standard colorimetric observers (colour matching functions x̄, ȳ, z̄).
//!
//! Tables: CIE 015:2018, as shipped by colour-science 0.4.7 (`data/cmf/`), kept at 1 nm over
//! 380–780 nm and compiled in as constants by `build.rs`.

#[allow(clippy::excessive_precision, clippy::approx_constant)] // tables copied digit for digit from the CIE data
mod tables {
    include!(concat!(env!("OUT_DIR"), "/tables.rs"));
}
pub(crate) use tables::*;

/// A CIE standard observer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Observer {
    /// CIE 1931 2° standard observer.
    Cie1931,
    /// CIE 1964 10° standard observer (the one the paper used).
    Cie1964,
}

impl Observer {
    /// Both observers.
    pub const ALL: [Observer; 2] = [Observer::Cie1931, Observer::Cie1964];

    /// `[x̄, ȳ, z̄]` at integer wavelength `nm` (clamped to 380–780 nm; the table is zero-free
    /// there and the project's domain ends at those limits).
    pub fn cmf(self, nm: u32) -> [f32; 3] {
        let i = nm.clamp(380, 780) as usize - 380;
        self.table()[i]
    }

    /// `[x̄, ȳ, z̄]` at any wavelength, linearly interpolated between the 1 nm entries.
    pub fn cmf_at(self, nm: f64) -> [f64; 3] {
        let x = nm.clamp(380.0, 780.0) - 380.0;
        let i = (x as usize).min(399);
        let f = x - i as f64;
        let t = self.table();
        let mut out = [0.0; 3];
        for (k, o) in out.iter_mut().enumerate() {
            *o = t[i][k] as f64 * (1.0 - f) + t[i + 1][k] as f64 * f;
        }
        out
    }

    /// The 1 nm table over 380..=780 nm.
    pub fn table(self) -> &'static [[f32; 3]; 401] {
        match self {
            Observer::Cie1931 => &CIE1931,
            Observer::Cie1964 => &CIE1964,
        }
    }

    /// Parses `1931`/`2` or `1964`/`10`.
    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "1931" | "2" | "CIE1931" | "cie1931" => Some(Observer::Cie1931),
            "1964" | "10" | "CIE1964" | "cie1964" => Some(Observer::Cie1964),
            _ => None,
        }
    }

    /// `"1931"` or `"1964"`.
    pub fn name(self) -> &'static str {
        match self {
            Observer::Cie1931 => "1931",
            Observer::Cie1964 => "1964",
        }
    }
}
