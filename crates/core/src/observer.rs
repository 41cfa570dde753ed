//! Observers: three spectral sensitivities (colour-matching functions x̄, ȳ, z̄, or any other
//! three, such as a camera's or a colorimeter's filters) at 1 nm over 380–780 nm.
//!
//! An [`Observer`] is a small `Copy` value: either one of the compile-time CIE observers or a
//! borrowed [`CmfTable`] built at run time (from a CSV file, or the CIE 2006 physiological model
//! for an age and field size, on the host). Everything that takes an observer — moments, the 1 nm
//! reference, shading, light metrics — reads it through [`Observer::table`], so a runtime table
//! is used exactly like a built-in one.
//!
//! Built-in tables (compiled in as constants by `build.rs` from `data/cmf/`, f32, 4.8 kB each):
//!
//! - CIE 1931 2° and CIE 1964 10° standard observers: CIE 015:2018, as shipped by
//!   colour-science 0.4.7.
//! - CIE 2015 2° and 10° cone-fundamental-based XYZ observers: CIE 170-2:2015 (CVRL), as shipped
//!   by colour-science 0.4.7. These are defined from 390 nm; over 380–389 nm they are zero.
//!
//! The project's domain is 380–780 nm: every table ends there, and sums run over 1 nm steps of it.

#[allow(clippy::excessive_precision, clippy::approx_constant)] // tables copied digit for digit from the CIE data
mod tables {
    include!(concat!(env!("OUT_DIR"), "/tables.rs"));
}
use crate::Error;
use core::hash::{Hash, Hasher};
pub(crate) use tables::*;

/// Number of 1 nm samples over 380..=780 nm.
pub const CMF_LEN: usize = 401;

/// Capacity (bytes) of a runtime table's name; longer names are cut at a character boundary.
pub const NAME_CAP: usize = 64;

/// Three sensitivities at 1 nm over 380..=780 nm, made at run time: checked finite and
/// non-negative, with no channel zero everywhere. Channel 1 plays ȳ: it sets the white's `Y = 100`.
#[derive(Clone, Debug, PartialEq)]
pub struct CmfTable {
    name: heapless::String<NAME_CAP>,
    values: [[f32; 3]; CMF_LEN],
}

impl CmfTable {
    /// Checks and wraps `values[i]` = the three sensitivities at `380 + i` nm.
    ///
    /// Errors: [`Error::NonFinite`] or [`Error::Negative`] at the first bad sample (its index,
    /// 0 = 380 nm), [`Error::ZeroChannel`] if a channel is zero over the whole range.
    pub fn new(name: &str, values: [[f32; 3]; CMF_LEN]) -> Result<Self, Error> {
        let mut any = [false; 3];
        for (i, v) in values.iter().enumerate() {
            for (k, x) in v.iter().enumerate() {
                if !x.is_finite() {
                    return Err(Error::NonFinite(i));
                }
                if *x < 0.0 {
                    return Err(Error::Negative(i));
                }
                any[k] |= *x > 0.0;
            }
        }
        if let Some(k) = any.iter().position(|a| !a) {
            return Err(Error::ZeroChannel(k));
        }
        let mut n = heapless::String::new();
        for c in name.chars() {
            if n.push(c).is_err() {
                break;
            }
        }
        Ok(Self { name: n, values })
    }

    /// The name given at construction (cut to [`NAME_CAP`] bytes).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The table, `[x̄, ȳ, z̄]` at `380 + i` nm.
    pub fn values(&self) -> &[[f32; 3]; CMF_LEN] {
        &self.values
    }
}

/// An observer: a built-in CIE observer or a runtime table.
///
/// `Copy` and free of lifetimes so it can sit in settings and be passed by value; a runtime
/// table is borrowed for `'static` (the host keeps the few it makes for the life of the process:
/// `specpoly_spectra::observer::intern`).
#[derive(Clone, Copy, Debug)]
pub enum Observer {
    /// CIE 1931 2° standard observer.
    Cie1931,
    /// CIE 1964 10° standard observer (the one the paper used).
    Cie1964,
    /// CIE 2015 2° cone-fundamental-based observer (CIE 170-2:2015).
    Cie2015_2,
    /// CIE 2015 10° cone-fundamental-based observer (CIE 170-2:2015).
    Cie2015_10,
    /// A table made at run time (a sensitivity CSV, the CIE 2006 model for an age and field).
    Table(&'static CmfTable),
}

/// Built-in observers are equal by name; runtime tables are equal when they are the same table
/// (the host keeps each distinct table once, so equal contents are one table). Comparing
/// addresses, not 1 203 numbers, keeps the firmware's observer checks a few instructions.
impl PartialEq for Observer {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Observer::Table(a), Observer::Table(b)) => core::ptr::eq(*a, *b),
            (a, b) => core::mem::discriminant(a) == core::mem::discriminant(b),
        }
    }
}

impl Eq for Observer {}

impl Hash for Observer {
    fn hash<H: Hasher>(&self, state: &mut H) {
        core::mem::discriminant(self).hash(state);
        if let Observer::Table(t) = self {
            core::ptr::hash(*t, state);
        }
    }
}

impl Observer {
    /// The built-in observers.
    pub const ALL: [Observer; 4] = [
        Observer::Cie1931,
        Observer::Cie1964,
        Observer::Cie2015_2,
        Observer::Cie2015_10,
    ];

    /// The two classic standard observers the paper and the firmware use (1931 and 1964).
    pub const CLASSIC: [Observer; 2] = [Observer::Cie1931, Observer::Cie1964];

    /// `[x̄, ȳ, z̄]` at integer wavelength `nm` (clamped to 380–780 nm).
    pub fn cmf(self, nm: u32) -> [f32; 3] {
        let i = nm.clamp(380, 780) as usize - 380;
        self.table()[i]
    }

    /// `[x̄, ȳ, z̄]` at any wavelength, linearly interpolated between the 1 nm entries.
    pub fn cmf_at(self, nm: f64) -> [f64; 3] {
        let x = nm.clamp(380.0, 780.0) - 380.0;
        let i = (x as usize).min(CMF_LEN - 2);
        let f = x - i as f64;
        let t = self.table();
        let mut out = [0.0; 3];
        for (k, o) in out.iter_mut().enumerate() {
            *o = t[i][k] as f64 * (1.0 - f) + t[i + 1][k] as f64 * f;
        }
        out
    }

    /// The 1 nm table over 380..=780 nm.
    pub fn table(self) -> &'static [[f32; 3]; CMF_LEN] {
        match self {
            Observer::Cie1931 => &CIE1931,
            Observer::Cie1964 => &CIE1964,
            Observer::Cie2015_2 => &CIE2015_2,
            Observer::Cie2015_10 => &CIE2015_10,
            Observer::Table(t) => &t.values,
        }
    }

    /// Parses a built-in observer's name: `1931` (also `2`, `CIE1931`), `1964` (also `10`,
    /// `CIE1964`), `2015-2` (also `CIE2015-2`) or `2015-10` (also `CIE2015-10`), any case.
    pub fn from_name(s: &str) -> Option<Self> {
        let s = s.trim();
        let s = match (s.get(..3), s.get(3..)) {
            (Some(p), Some(rest)) if p.eq_ignore_ascii_case("cie") => rest,
            _ => s,
        };
        match s {
            "1931" | "2" => Some(Observer::Cie1931),
            "1964" | "10" => Some(Observer::Cie1964),
            "2015-2" | "2015_2" => Some(Observer::Cie2015_2),
            "2015-10" | "2015_10" => Some(Observer::Cie2015_10),
            _ => None,
        }
    }

    /// `"1931"`, `"1964"`, `"2015-2"`, `"2015-10"` (the names [`Self::from_name`] reads), or a
    /// runtime table's own name.
    pub fn name(self) -> &'static str {
        match self {
            Observer::Cie1931 => "1931",
            Observer::Cie1964 => "1964",
            Observer::Cie2015_2 => "2015-2",
            Observer::Cie2015_10 => "2015-10",
            Observer::Table(t) => t.name(),
        }
    }

    /// A short description for reports: "CIE 1931", "CIE 1964", "CIE 2015 2°", "CIE 2015 10°", or
    /// the runtime table's name.
    pub fn label(self) -> &'static str {
        match self {
            Observer::Cie1931 => "CIE 1931",
            Observer::Cie1964 => "CIE 1964",
            Observer::Cie2015_2 => "CIE 2015 2°",
            Observer::Cie2015_10 => "CIE 2015 10°",
            Observer::Table(t) => t.name(),
        }
    }

    /// Whether this is a compile-time observer (not a runtime table).
    pub fn is_builtin(self) -> bool {
        !matches!(self, Observer::Table(_))
    }
}
