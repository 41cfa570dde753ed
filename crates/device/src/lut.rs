//! The drive-correction table (`specpoly_core::drive_table`; feature `lut`): the full display
//! model's inverse, tabulated by the host, uploaded with `lut begin|row|end` (firmware/
//! PROTOCOL.md) and kept in a flash region of its own, outside the settings store.
//!
//! Rows are programmed into flash as they arrive (nothing is buffered beyond the parsed line);
//! `lut end` reads the region back, checks the host's checksum over what flash holds, and only
//! then writes the header that makes the table valid, so an interrupted or damaged upload is
//! never applied. The colour path reads the eight corners of a cell from flash per colour
//! (48 bytes), never a RAM copy. The header carries the calibration key
//! ([`specpoly_core::drive_table::calibration_key`]) the table was made for: a table is applied
//! only while the controller's primaries and curves have that key (after `cal`/`trc` to other
//! values it rests, and applies again when they come back, e.g. by `load` or at start).
//!
//! Region layout (little-endian):
//!
//! | offset | bytes | field |
//! |---|---|---|
//! | 0 | 4 | magic `LUT1` (erased: no table) |
//! | 4 | 1 | grid side `N` (then 3 bytes 0) |
//! | 8 | 4 | calibration key |
//! | 12 | 4 | checksum |
//! | 16 + R·S | 6 N | row `R`: `N` nodes of 3 i16; `S = 6N` rounded up to 4 bytes |

use embedded_storage::nor_flash::{NorFlash, ReadNorFlash};
use specpoly_core::drive_table::{self, Nodes};
use specpoly_protocol::{ErrorCode, Fault, LutCommand, Reply};

/// Bytes before the first row.
pub const HEADER: usize = 16;

/// `LUT1`.
const MAGIC: [u8; 4] = *b"LUT1";

/// A row's bytes in flash: `6N` rounded up to whole 4-byte words (the QEMU flash's write unit).
pub const fn stride(grid: usize) -> usize {
    (6 * grid + 3) & !3
}

/// Bytes a table of side `grid` takes in its region.
pub const fn size(grid: usize) -> usize {
    HEADER + grid * grid * stride(grid)
}

/// The table's flash region, seen by the controller (one implementation for any NOR flash,
/// called through `dyn`: the colour path is compiled once).
pub trait Region {
    /// Reads `buf.len()` bytes at `offset`; `false` on a flash error.
    fn read(&mut self, offset: usize, buf: &mut [u8]) -> bool;
    /// Programs `bytes` (whole words) at `offset`; `false` on a flash error.
    fn write(&mut self, offset: usize, bytes: &[u8]) -> bool;
    /// Erases the whole region; `false` on a flash error.
    fn erase(&mut self) -> bool;
    /// Bytes in the region.
    fn capacity(&self) -> usize;
}

impl<F: NorFlash> Region for F {
    fn read(&mut self, offset: usize, buf: &mut [u8]) -> bool {
        ReadNorFlash::read(self, offset as u32, buf).is_ok()
    }
    fn write(&mut self, offset: usize, bytes: &[u8]) -> bool {
        NorFlash::write(self, offset as u32, bytes).is_ok()
    }
    fn erase(&mut self) -> bool {
        let end = ReadNorFlash::capacity(self) / F::ERASE_SIZE * F::ERASE_SIZE;
        NorFlash::erase(self, 0, end as u32).is_ok()
    }
    fn capacity(&self) -> usize {
        ReadNorFlash::capacity(self)
    }
}

/// The nodes of the stored table, read from flash one at a time.
pub struct FlashNodes<'a> {
    region: &'a mut dyn Region,
    grid: usize,
}

impl Nodes for FlashNodes<'_> {
    fn grid(&self) -> usize {
        self.grid
    }
    fn node(&mut self, index: usize) -> [i16; 3] {
        let g = self.grid;
        let at = HEADER + index / g * stride(g) + index % g * 6;
        let mut b = [0u8; 6];
        if !self.region.read(at, &mut b) {
            return [0; 3];
        }
        [0, 1, 2].map(|i| i16::from_le_bytes([b[2 * i], b[2 * i + 1]]))
    }
}

/// The controller's table: its region, the side of the table applied, and an upload under
/// way. 12 bytes of RAM.
pub struct Lut {
    region: Option<&'static mut dyn Region>,
    /// Side of the table applied to colours (0: none).
    applied: u8,
    /// Side of the table being uploaded (0: none) and its next row.
    upload: u8,
    next: u16,
}

impl Lut {
    /// No region: `lut` commands are answered `err storage`.
    pub const fn new() -> Self {
        Self {
            region: None,
            applied: 0,
            upload: 0,
            next: 0,
        }
    }

    /// The region the table lives in (the board's).
    pub fn attach(&mut self, region: &'static mut dyn Region) {
        self.region = Some(region);
    }

    /// Side of the table applied (0: none).
    pub fn applied(&self) -> u8 {
        self.applied
    }

    /// Reads the header: the stored table applies when it is intact and was made for the
    /// calibration of key `key`.
    pub fn refresh(&mut self, key: u32) {
        self.applied = 0;
        let Some(r) = self.region.as_deref_mut() else {
            return;
        };
        let mut h = [0u8; HEADER];
        if !r.read(0, &mut h) || h[..4] != MAGIC {
            return;
        }
        let g = h[4] as usize;
        let stored_key = u32::from_le_bytes([h[8], h[9], h[10], h[11]]);
        let fits =
            (drive_table::GRID_MIN..=drive_table::GRID_MAX).contains(&g) && size(g) <= r.capacity();
        if fits && stored_key == key {
            self.applied = g as u8;
        }
    }

    /// The applied table's nodes, if one is applied.
    pub fn nodes(&mut self) -> Option<FlashNodes<'_>> {
        let grid = self.applied as usize;
        match self.region.as_deref_mut() {
            Some(region) if grid > 0 => Some(FlashNodes { region, grid }),
            _ => None,
        }
    }

    /// Answers a `lut` command; `key` is the calibration's (module docs). Any refusal
    /// abandons an upload under way.
    pub fn command(&mut self, c: &LutCommand, key: u32) -> Reply {
        match self.step(c, key) {
            Ok(()) => Reply::Done("lut"),
            Err(f) => {
                self.upload = 0;
                Reply::Error(f)
            }
        }
    }

    fn step(&mut self, c: &LutCommand, key: u32) -> Result<(), Fault> {
        let storage = Fault::new(ErrorCode::Storage);
        let r = self.region.as_deref_mut().ok_or(storage)?;
        match c {
            LutCommand::Begin(g) => {
                if size(*g as usize) > r.capacity() {
                    return Err(Fault::at(ErrorCode::OutOfRange, 2));
                }
                self.applied = 0;
                self.upload = 0;
                if !r.erase() {
                    return Err(storage);
                }
                (self.upload, self.next) = (*g, 0);
            }
            LutCommand::Row { row, values } => {
                let g = self.upload as usize;
                if g == 0 || *row != self.next {
                    return Err(Fault::at(ErrorCode::LutOrder, 2));
                }
                if values.len() != 3 * g {
                    return Err(Fault::at(
                        ErrorCode::WrongCount,
                        3 + values.len().min(3 * g),
                    ));
                }
                let at = HEADER + *row as usize * stride(g);
                // word by word: no row buffer on the stack
                for w in 0..stride(g) / 4 {
                    let word: [u8; 4] = core::array::from_fn(|b| {
                        let byte = 4 * w + b;
                        values
                            .get(byte / 2)
                            .map_or(0xFF, |v| v.to_le_bytes()[byte % 2])
                    });
                    if !r.write(at + 4 * w, &word) {
                        return Err(storage);
                    }
                }
                self.next += 1;
            }
            LutCommand::End(check) => {
                let g = self.upload as usize;
                if g == 0 || self.next as usize != g * g {
                    return Err(Fault::new(ErrorCode::LutOrder));
                }
                let mut nodes = FlashNodes { region: r, grid: g };
                let n = g * g * g;
                let sum = drive_table::checksum(g, (0..n).map(|i| nodes.node(i)));
                if sum != *check {
                    return Err(Fault::at(ErrorCode::LutCheck, 2));
                }
                let mut h = [0u8; HEADER];
                h[..4].copy_from_slice(&MAGIC);
                h[4] = g as u8;
                h[8..12].copy_from_slice(&key.to_le_bytes());
                h[12..].copy_from_slice(&check.to_le_bytes());
                if !nodes.region.write(0, &h) {
                    return Err(storage);
                }
                self.upload = 0;
                self.refresh(key);
            }
            LutCommand::Off => {
                (self.applied, self.upload) = (0, 0);
                if !r.erase() {
                    return Err(storage);
                }
            }
        }
        Ok(())
    }
}

impl Default for Lut {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Controller;
    use specpoly_core::drive_table::{checksum, corrected, Table};
    use specpoly_core::Xyz;
    use specpoly_protocol::{Command, ErrorCode, Fault, Reply};

    /// A NOR flash in RAM: erase sets `0xFF`, a write clears bits; `fail` makes writes fail.
    struct Ram {
        bytes: Vec<u8>,
        fail: bool,
    }

    impl Region for Ram {
        fn read(&mut self, offset: usize, buf: &mut [u8]) -> bool {
            match self.bytes.get(offset..offset + buf.len()) {
                Some(b) => {
                    buf.copy_from_slice(b);
                    true
                }
                None => false,
            }
        }
        fn write(&mut self, offset: usize, bytes: &[u8]) -> bool {
            if self.fail || offset % 4 != 0 || bytes.len() % 4 != 0 {
                return false;
            }
            match self.bytes.get_mut(offset..offset + bytes.len()) {
                Some(b) => {
                    b.iter_mut().zip(bytes).for_each(|(o, n)| *o &= n);
                    true
                }
                None => false,
            }
        }
        fn erase(&mut self) -> bool {
            self.bytes.fill(0xFF);
            true
        }
        fn capacity(&self) -> usize {
            self.bytes.len()
        }
    }

    fn controller(capacity: usize) -> Controller {
        let mut c = Controller::new(65535);
        let ram = Box::leak(Box::new(Ram {
            bytes: vec![0xFF; capacity],
            fail: false,
        }));
        c.attach_lut(ram);
        c
    }

    /// A table of side `g` with distinct, sizeable corrections.
    fn nodes(g: usize) -> Vec<[i16; 3]> {
        (0..g * g * g)
            .map(|i| {
                let v = (i as i32 * 37 % 2001 - 1000) as i16;
                [v, -v / 2, v / 3]
            })
            .collect()
    }

    fn upload(c: &mut Controller, g: usize, n: &[[i16; 3]], check: u32) -> Vec<Reply> {
        let mut lines = vec![format!("lut begin {g}")];
        for (r, row) in n.chunks(g).enumerate() {
            let mut l = format!("lut row {r}");
            for v in row.iter().flatten() {
                l.push_str(&format!(" {v}"));
            }
            lines.push(l);
        }
        lines.push(format!("lut end {check:08x}"));
        lines.iter().map(|l| c.handle(Command::parse(l))).collect()
    }

    fn state_lut(c: &mut Controller) -> u8 {
        match c.handle(Command::parse("state")) {
            Reply::State(s) => s.lut,
            other => panic!("{other:?}"),
        }
    }

    /// An uploaded table is applied to colours as the core's `corrected` applies it to the
    /// matrix model's drive (the host model's call), and reported by `state`.
    #[test]
    fn an_uploaded_table_corrects_colours_as_the_core_does() {
        let mut c = controller(8192);
        c.handle(Command::parse("trc rgb gamma 2.2"));
        let g = 7;
        let n = nodes(g);
        let replies = upload(&mut c, g, &n, checksum(g, n.iter().copied()));
        assert!(
            replies.iter().all(|r| *r == Reply::Done("lut")),
            "{replies:?}"
        );
        assert_eq!(state_lut(&mut c), 7);
        let target = Xyz::new(30.0, 25.0, 20.0);
        let plain = c.display().drive(target, c.record().map, 65535);
        let mut t = Table::new(g, &n).unwrap();
        let want = corrected(&mut t, plain, 65535);
        assert_ne!(want.level, plain.level);
        match c.handle(Command::parse("xyz 30 25 20")) {
            Reply::Colour(r) => assert_eq!(r.duty, want.level),
            other => panic!("{other:?}"),
        }
        // another calibration: the table rests; the same one again: it applies again
        c.handle(Command::parse("trc rgb srgb"));
        assert_eq!(state_lut(&mut c), 0);
        c.handle(Command::parse("trc rgb gamma 2.2"));
        assert_eq!(state_lut(&mut c), 7);
        assert_eq!(c.handle(Command::parse("lut off")), Reply::Done("lut"));
        assert_eq!(state_lut(&mut c), 0);
    }

    #[test]
    fn bad_uploads_are_refused_and_never_applied() {
        let mut c = controller(8192);
        let g = 5;
        let n = nodes(g);
        let good = checksum(g, n.iter().copied());
        let err = |code, at: Option<usize>| {
            Reply::Error(match at {
                Some(a) => Fault::at(code, a),
                None => Fault::new(code),
            })
        };
        // a wrong checksum
        let r = upload(&mut c, g, &n, good ^ 1);
        assert_eq!(*r.last().unwrap(), err(ErrorCode::LutCheck, Some(2)));
        assert_eq!(state_lut(&mut c), 0);
        // rows without a begin, out of order, of the wrong length; an early end
        assert_eq!(
            c.handle(Command::parse("lut row 0 1 2 3 4 5 6")),
            err(ErrorCode::LutOrder, Some(2))
        );
        c.handle(Command::parse("lut begin 5"));
        assert_eq!(
            c.handle(Command::parse("lut row 1 1 2 3 4 5 6")),
            err(ErrorCode::LutOrder, Some(2))
        );
        c.handle(Command::parse("lut begin 5"));
        assert_eq!(
            c.handle(Command::parse("lut row 0 1 2 3 4 5 6")),
            err(ErrorCode::WrongCount, Some(9))
        );
        c.handle(Command::parse("lut begin 5"));
        assert_eq!(
            c.handle(Command::parse("lut end 00000000")),
            err(ErrorCode::LutOrder, None)
        );
        // a table larger than the region
        assert_eq!(
            c.handle(Command::parse("lut begin 17")),
            err(ErrorCode::OutOfRange, Some(2))
        );
        assert_eq!(state_lut(&mut c), 0);
        // then a good one is taken
        let r = upload(&mut c, g, &n, good);
        assert_eq!(*r.last().unwrap(), Reply::Done("lut"));
        assert_eq!(state_lut(&mut c), 5);
        // a new begin drops the stored table at once
        c.handle(Command::parse("lut begin 5"));
        assert_eq!(state_lut(&mut c), 0);
        // a controller without a region refuses
        let mut bare = Controller::new(255);
        assert_eq!(
            bare.handle(Command::parse("lut begin 5")),
            err(ErrorCode::Storage, None)
        );
    }

    #[test]
    fn rows_take_whole_words() {
        assert_eq!(stride(9), 56);
        assert_eq!(stride(10), 60);
        assert_eq!(size(13), 13_536);
        assert!(size(14) > 16_384);
    }
}
