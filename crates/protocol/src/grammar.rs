//! The lexical layer shared by commands ([`crate::command`]), replies ([`crate::reply`]) and
//! the mixing and table commands ([`crate::mix`], [`crate::lut`]): a line's words with their
//! positions, a number word read into a [`Fault`] naming its position, and the wire names of
//! curves and gamut maps. Depends only on [`crate::number`] and [`crate::fault`].

use crate::fault::{ErrorCode, Fault};
#[cfg(feature = "fast-refl")]
use crate::number::word_f32;
use crate::number::{parse_f32, write_f32, write_int, NumberError};
use core::fmt::{self, Write};
use specpoly_core::{GamutMap, Transfer};

/// A number word at position `at`: a syntax error is `bad-number`, out of f32's range
/// `out-of-range`.
pub(crate) fn number(tok: &str, at: usize) -> Result<f32, Fault> {
    parse_f32(tok).map_err(|e| match e {
        NumberError::Syntax => Fault::at(ErrorCode::BadNumber, at),
        NumberError::Range => Fault::at(ErrorCode::OutOfRange, at),
    })
}

/// Words of a line with their positions: maximal runs of bytes other than ASCII whitespace
/// (as `str::split_ascii_whitespace` splits), found by one scan of the line's bytes.
#[derive(Clone, Copy)]
pub(crate) struct Words<'a> {
    line: &'a str,
    /// Byte offset of the first byte not yet read.
    at: usize,
    /// Position of the last word taken: the line's first word (the command) is 0.
    pub(crate) pos: usize,
}

impl<'a> Words<'a> {
    /// The line's first word (`None` for a blank line) and the words after it, numbered from 1.
    pub(crate) fn new(line: &'a str) -> (Option<&'a str>, Self) {
        let mut w = Words {
            line,
            at: 0,
            pos: 0,
        };
        let head = w.next().map(|(h, _)| h);
        w.pos = 0;
        (head, w)
    }

    /// The offset of the next word's first byte (the line's length when none is left).
    fn start(&self) -> usize {
        let b = self.line.as_bytes();
        let mut i = self.at;
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        i
    }

    pub(crate) fn next(&mut self) -> Option<(&'a str, usize)> {
        let b = self.line.as_bytes();
        let start = self.start();
        let mut i = start;
        while i < b.len() && !b[i].is_ascii_whitespace() {
            i += 1;
        }
        self.at = i;
        if i == start {
            return None;
        }
        self.pos += 1;
        // split at ASCII bytes, so always at character boundaries
        Some((self.line.get(start..i)?, self.pos))
    }
    pub(crate) fn need(&mut self) -> Result<(&'a str, usize), Fault> {
        self.next()
            .ok_or(Fault::at(ErrorCode::MissingArgument, self.pos + 1))
    }
    /// The next word, not taken.
    pub(crate) fn peek(&self) -> Option<&'a str> {
        let mut w = *self;
        w.next().map(|(w, _)| w)
    }
    pub(crate) fn number(&mut self) -> Result<f32, Fault> {
        let (w, at) = self.need()?;
        number(w, at)
    }
    /// The next `n` words as the coefficients of a `refl` factor, the `k`-th stored with
    /// `store(k, value)`: `err wrong-count` when the line ends or a word is `*` (a factor cut
    /// short), else each word as [`number`] reads it. With feature `fast-refl` the common words
    /// (a plain decimal or the hex form) are found and read in one pass over their bytes
    /// (`number::word_f32`, inlined here: the same value as [`parse_f32`], which reads the
    /// rest).
    #[cfg_attr(feature = "fast-refl", inline(always))]
    pub(crate) fn coefficients(
        &mut self,
        n: usize,
        mut store: impl FnMut(usize, f32),
    ) -> Result<(), Fault> {
        let b = self.line.as_bytes();
        for k in 0..n {
            let mut i = self.at;
            while i < b.len() && b[i].is_ascii_whitespace() {
                i += 1;
            }
            self.at = i;
            #[cfg(feature = "fast-refl")]
            if let Some((v, len)) = word_f32(&b[i..]) {
                self.at = i + len;
                self.pos += 1;
                store(k, v);
                continue;
            }
            match self.next() {
                Some(("*", at)) => return Err(Fault::at(ErrorCode::WrongCount, at)),
                Some((w, at)) => store(k, number(w, at)?),
                None => return Err(Fault::at(ErrorCode::WrongCount, self.pos + 1)),
            }
        }
        Ok(())
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
