//! The lexical layer shared by commands ([`crate::command`]), replies ([`crate::reply`]) and
//! the mixing and table commands ([`crate::mix`], [`crate::lut`]): a line's words with their
//! positions, a number word read into a [`Fault`] naming its position, and the wire names of
//! curves and gamut maps. Depends only on [`crate::number`] and [`crate::fault`].

use crate::fault::{ErrorCode, Fault};
use crate::number::{parse_f32, write_f32, write_int, NumberError};
use core::fmt::{self, Write};
use core::str::SplitAsciiWhitespace;
use specpoly_core::{GamutMap, Transfer};

/// A number word at position `at`: a syntax error is `bad-number`, out of f32's range
/// `out-of-range`.
pub(crate) fn number(tok: &str, at: usize) -> Result<f32, Fault> {
    parse_f32(tok).map_err(|e| match e {
        NumberError::Syntax => Fault::at(ErrorCode::BadNumber, at),
        NumberError::Range => Fault::at(ErrorCode::OutOfRange, at),
    })
}

/// Words of a line with their positions.
pub(crate) struct Words<'a> {
    it: SplitAsciiWhitespace<'a>,
    pub(crate) pos: usize,
}

impl<'a> Words<'a> {
    /// The words after a line's first.
    pub(crate) fn new(it: SplitAsciiWhitespace<'a>) -> Self {
        Words { it, pos: 0 }
    }

    pub(crate) fn next(&mut self) -> Option<(&'a str, usize)> {
        let w = self.it.next()?;
        self.pos += 1;
        Some((w, self.pos))
    }
    pub(crate) fn need(&mut self) -> Result<(&'a str, usize), Fault> {
        self.next()
            .ok_or(Fault::at(ErrorCode::MissingArgument, self.pos + 1))
    }
    /// The next word, not taken.
    pub(crate) fn peek(&self) -> Option<&'a str> {
        self.it.clone().next()
    }
    pub(crate) fn number(&mut self) -> Result<f32, Fault> {
        let (w, at) = self.need()?;
        number(w, at)
    }
    pub(crate) fn end(&mut self) -> Result<(), Fault> {
        match self.next() {
            None => Ok(()),
            Some((_, at)) => Err(Fault::at(ErrorCode::ExtraArgument, at)),
        }
    }
}

/// The wire name of a gamut map.
pub fn map_name(m: GamutMap) -> &'static str {
    match m {
        GamutMap::Clip => "clip",
        GamutMap::Desaturate => "desaturate",
    }
}

/// Writes a curve as `linear`, `srgb`, `gamma G` or `table v0 v1 …`, with `sep` between the
/// kind and its numbers (`' '` in commands, `':'` in `state` replies, where a table is written
/// as its point count only).
pub fn write_curve<W: Write>(w: &mut W, c: &Transfer, sep: char) -> fmt::Result {
    match c {
        Transfer::Linear => w.write_str("linear"),
        Transfer::Srgb => w.write_str("srgb"),
        Transfer::Gamma(g) => {
            w.write_str("gamma")?;
            w.write_char(sep)?;
            write_f32(w, *g)
        }
        Transfer::Table(t) => {
            w.write_str("table")?;
            if sep == ' ' {
                for v in t {
                    w.write_char(' ')?;
                    write_f32(w, *v)?;
                }
                Ok(())
            } else {
                w.write_char(sep)?;
                write_int(w, t.len() as i64)
            }
        }
    }
}
