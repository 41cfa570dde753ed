//! The drive-correction table's upload (`specpoly_core::drive_table`, firmware/PROTOCOL.md):
//!
//! - `lut begin N` — a new table of `N³` nodes (`N` = 2–17); the stored one is erased;
//! - `lut row R v…` — row `R` (`0 … N² − 1`, in order): the `N` nodes of red index `R / N`,
//!   green index `R mod N`, blue `0 … N − 1`, each three whole numbers `Δr Δg Δb` in Q15
//!   (−32768 … 32767);
//! - `lut end HHHHHHHH` — the FNV-1a checksum of the table in 8 hexadecimal digits; the table is
//!   applied (and kept across resets) only when it matches what was stored;
//! - `lut off` — no table.
//!
//! Every value is a whole number: no f32 on the way, so the table arrives bit for bit.

use crate::number::write_int;
use core::fmt::{self, Write};
use specpoly_core::drive_table::GRID_MAX;
#[cfg(feature = "lut")]
use {
    crate::fault::{ErrorCode, Fault},
    crate::grammar::Words,
    specpoly_core::drive_table::GRID_MIN,
};

/// Most values in one `lut row`: three per node of the largest grid's row.
pub const ROW_MAX: usize = 3 * GRID_MAX;

/// A `lut` command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LutCommand {
    /// `lut begin N`: a table of side `N` follows.
    Begin(u8),
    /// `lut row R v…`: row `R`'s nodes, three values each.
    Row {
        /// Row index, `red · N + green`.
        row: u16,
        /// `3 · N` values, Q15.
        values: heapless::Vec<i16, ROW_MAX>,
    },
    /// `lut end CHECK`: the table's checksum.
    End(u32),
    /// `lut off`: no table.
    Off,
}

/// A whole number in `lo ..= hi`: `bad-number` if not a whole number, `out-of-range` outside.
#[cfg(feature = "lut")]
fn whole(tok: &str, at: usize, lo: i32, hi: i32) -> Result<i32, Fault> {
    let digits = tok.strip_prefix('-').unwrap_or(tok);
    if digits.is_empty() || digits.len() > 9 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(Fault::at(ErrorCode::BadNumber, at));
    }
    let v: i32 = tok
        .parse()
        .map_err(|_| Fault::at(ErrorCode::BadNumber, at))?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(Fault::at(ErrorCode::OutOfRange, at))
    }
}

/// Parses the words after `lut`.
#[cfg(feature = "lut")]
pub(crate) fn parse(w: &mut Words<'_>) -> Result<LutCommand, Fault> {
    let (kind, at) = w.need()?;
    Ok(match kind {
        "begin" => {
            let (tok, at) = w.need()?;
            LutCommand::Begin(whole(tok, at, GRID_MIN as i32, GRID_MAX as i32)? as u8)
        }
        "row" => {
            let (tok, at) = w.need()?;
            let row = whole(tok, at, 0, (GRID_MAX * GRID_MAX - 1) as i32)? as u16;
            let mut values = heapless::Vec::new();
            while let Some((tok, at)) = w.next() {
                let v = whole(tok, at, i16::MIN as i32, i16::MAX as i32)? as i16;
                values
                    .push(v)
                    .map_err(|_| Fault::at(ErrorCode::WrongCount, at))?;
            }
            if values.len() < 3 * GRID_MIN || values.len() % 3 != 0 {
                return Err(Fault::at(ErrorCode::WrongCount, 3 + values.len()));
            }
            LutCommand::Row { row, values }
        }
        "end" => {
            let (tok, at) = w.need()?;
            let ok = tok.len() == 8 && tok.bytes().all(|b| b.is_ascii_hexdigit());
            let v = u32::from_str_radix(tok, 16).ok().filter(|_| ok);
            LutCommand::End(v.ok_or(Fault::at(ErrorCode::BadNumber, at))?)
        }
        "off" => LutCommand::Off,
        _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
    })
}

impl LutCommand {
    /// Writes the command line (no newline).
    pub fn write<W: Write>(&self, w: &mut W) -> fmt::Result {
        match self {
            LutCommand::Begin(n) => {
                w.write_str("lut begin ")?;
                write_int(w, *n as i64)
            }
            LutCommand::Row { row, values } => {
                w.write_str("lut row ")?;
                write_int(w, *row as i64)?;
                for v in values {
                    w.write_char(' ')?;
                    write_int(w, *v as i64)?;
                }
                Ok(())
            }
            LutCommand::End(check) => {
                w.write_str("lut end ")?;
                for i in (0..8).rev() {
                    let d = (check >> (4 * i) & 0xf) as u8;
                    w.write_char(char::from(if d < 10 { b'0' + d } else { b'a' + d - 10 }))?;
                }
                Ok(())
            }
            LutCommand::Off => w.write_str("lut off"),
        }
    }
}

#[cfg(all(test, feature = "lut"))]
mod tests {
    use crate::{Command, ErrorCode, Fault, LutCommand};

    fn parse(s: &str) -> Result<Command, Fault> {
        Command::parse(s)
    }

    #[test]
    fn lut_lines_parse_and_write_back() {
        for line in [
            "lut begin 9",
            "lut row 0 1 -2 3 32767 -32768 0",
            "lut end 0a1b2c3d",
            "lut off",
        ] {
            let c = parse(line).unwrap();
            let mut s = heapless::String::<128>::new();
            c.write(&mut s).unwrap();
            assert_eq!(s.as_str(), line);
        }
        assert_eq!(
            parse("lut end FFFFFFFF"),
            Ok(Command::Lut(LutCommand::End(u32::MAX)))
        );
    }

    #[test]
    fn bad_lut_lines_are_refused_at_the_word() {
        let at = |c, n| Err(Fault::at(c, n));
        assert_eq!(parse("lut begin 1"), at(ErrorCode::OutOfRange, 2));
        assert_eq!(parse("lut begin 18"), at(ErrorCode::OutOfRange, 2));
        assert_eq!(parse("lut begin 9.5"), at(ErrorCode::BadNumber, 2));
        assert_eq!(parse("lut begin"), at(ErrorCode::MissingArgument, 2));
        assert_eq!(parse("lut begin 9 9"), at(ErrorCode::ExtraArgument, 3));
        assert_eq!(parse("lut row 0 1 2 3 4 5"), at(ErrorCode::WrongCount, 8));
        assert_eq!(parse("lut row 0 1 2 3"), at(ErrorCode::WrongCount, 6));
        assert_eq!(
            parse("lut row 0 1 2 32768 4 5 6"),
            at(ErrorCode::OutOfRange, 5)
        );
        assert_eq!(
            parse("lut row 289 1 2 3 4 5 6"),
            at(ErrorCode::OutOfRange, 2)
        );
        assert_eq!(parse("lut row 0 1 2 x 4 5 6"), at(ErrorCode::BadNumber, 5));
        assert_eq!(parse("lut row 0 1 2 - 4 5 6"), at(ErrorCode::BadNumber, 5));
        let mut long = heapless::String::<256>::new();
        let _ = long.push_str("lut row 0");
        for _ in 0..54 {
            let _ = long.push_str(" 1");
        }
        assert_eq!(parse(&long), at(ErrorCode::WrongCount, 54));
        assert_eq!(parse("lut end 1234567"), at(ErrorCode::BadNumber, 2));
        assert_eq!(parse("lut end 1234567g"), at(ErrorCode::BadNumber, 2));
        assert_eq!(parse("lut end +1234567"), at(ErrorCode::BadNumber, 2));
        assert_eq!(parse("lut sideways"), at(ErrorCode::UnknownName, 1));
    }
}
