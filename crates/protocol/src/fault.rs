//! What an `err` reply says: a code and, for argument errors, the argument's position.

use core::fmt::{self, Write};

/// The code of an `err` reply (its wire name in brackets).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorCode {
    /// The line exceeded [`crate::MAX_LINE`] bytes (`too-long`); it was discarded whole.
    TooLong,
    /// A byte outside printable ASCII, tab and CR (`bad-byte`).
    BadByte,
    /// The first word is no command (`unknown-command`).
    UnknownCommand,
    /// Fewer arguments than the command takes (`missing-argument`).
    MissingArgument,
    /// More arguments than the command takes (`extra-argument`).
    ExtraArgument,
    /// An argument is not a decimal number (`bad-number`).
    BadNumber,
    /// A number outside its allowed range, or beyond f32 (`out-of-range`).
    OutOfRange,
    /// An unknown name: illuminant, preset, observer, channel, curve or gamut map
    /// (`unknown-name`).
    UnknownName,
    /// A reflectance factor with the wrong number of coefficients, or too many factors
    /// (`wrong-count`).
    WrongCount,
    /// A transfer table that is not non-decreasing or has too few or too many points
    /// (`bad-curve`).
    BadCurve,
    /// Primaries that do not span a colour space (`singular`).
    Singular,
    /// A reply the host could not read (host side only; `bad-reply`).
    BadReply,
    /// The settings could not be written to or read from flash (`storage`).
    Storage,
    /// `load` found no saved settings of this firmware's format (`not-saved`).
    NotSaved,
    /// A colour command whose result is not a finite f32 (an overflow inside the colour
    /// conversion); nothing changes (`not-finite`).
    NotFinite,
    /// A mix target with fewer than three channels set (`no-channels`).
    NoChannels,
    /// A mix target the channels cannot make (`out-of-gamut`); nothing changes.
    OutOfGamut,
    /// A `lut row` or `lut end` out of order: no upload begun, a row other than the next, or
    /// an end before the last row (`lut-order`); the upload is abandoned.
    LutOrder,
    /// A `lut end` whose checksum is not that of the rows stored (`lut-check`); the table is
    /// discarded.
    LutCheck,
}

impl ErrorCode {
    /// Every code.
    pub const ALL: [ErrorCode; 19] = [
        ErrorCode::TooLong,
        ErrorCode::BadByte,
        ErrorCode::UnknownCommand,
        ErrorCode::MissingArgument,
        ErrorCode::ExtraArgument,
        ErrorCode::BadNumber,
        ErrorCode::OutOfRange,
        ErrorCode::UnknownName,
        ErrorCode::WrongCount,
        ErrorCode::BadCurve,
        ErrorCode::Singular,
        ErrorCode::BadReply,
        ErrorCode::Storage,
        ErrorCode::NotSaved,
        ErrorCode::NotFinite,
        ErrorCode::NoChannels,
        ErrorCode::OutOfGamut,
        ErrorCode::LutOrder,
        ErrorCode::LutCheck,
    ];

    /// The wire name.
    pub fn name(self) -> &'static str {
        match self {
            ErrorCode::TooLong => "too-long",
            ErrorCode::BadByte => "bad-byte",
            ErrorCode::UnknownCommand => "unknown-command",
            ErrorCode::MissingArgument => "missing-argument",
            ErrorCode::ExtraArgument => "extra-argument",
            ErrorCode::BadNumber => "bad-number",
            ErrorCode::OutOfRange => "out-of-range",
            ErrorCode::UnknownName => "unknown-name",
            ErrorCode::WrongCount => "wrong-count",
            ErrorCode::BadCurve => "bad-curve",
            ErrorCode::Singular => "singular",
            ErrorCode::BadReply => "bad-reply",
            ErrorCode::Storage => "storage",
            ErrorCode::NotSaved => "not-saved",
            ErrorCode::NotFinite => "not-finite",
            ErrorCode::NoChannels => "no-channels",
            ErrorCode::OutOfGamut => "out-of-gamut",
            ErrorCode::LutOrder => "lut-order",
            ErrorCode::LutCheck => "lut-check",
        }
    }

    /// From the wire name.
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == s)
    }
}

/// An error: its code and the 0-based position of the offending word (the command is word 0),
/// when one word is to blame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fault {
    /// What went wrong.
    pub code: ErrorCode,
    /// Which word.
    pub at: Option<u16>,
}

impl Fault {
    /// A fault with no position.
    pub const fn new(code: ErrorCode) -> Self {
        Self { code, at: None }
    }

    /// A fault at word `at`.
    pub fn at(code: ErrorCode, at: usize) -> Self {
        Self {
            code,
            at: Some(at.min(u16::MAX as usize) as u16),
        }
    }
}

impl fmt::Display for Fault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.code.name())?;
        if let Some(at) = self.at {
            f.write_str(" at word ")?;
            crate::number::write_int(f, at as i64)?;
        }
        Ok(())
    }
}

impl Fault {
    /// Writes the wire form `err CODE [at=N]` (no newline).
    pub fn write<W: Write>(&self, w: &mut W) -> fmt::Result {
        w.write_str("err ")?;
        w.write_str(self.code.name())?;
        if let Some(at) = self.at {
            w.write_str(" at=")?;
            crate::number::write_int(w, at as i64)?;
        }
        Ok(())
    }
}
