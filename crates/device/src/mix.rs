//! The multi-channel mixer's settings in flash: channels, their curves and the fade time, as a
//! second record (map key [`KEY`]) beside the calibration record ([`crate::settings`]).
//!
//! The commands themselves (`channel`, `xy`, `cct`, `fade`) are answered by the protocol's
//! shared [`specpoly_protocol::mix::answer`] on the controller's
//! [`specpoly_core::light::channels::Mixer`]; fades are stepped by the application loop
//! ([`crate::fade`]).
//!
//! Why a record of its own rather than a new version of the calibration record: the store's
//! work buffer is sized by the largest record (three 64-point curves, 816 B of RAM), and
//! the mixer's 132 B would grow it; a second, smaller item reuses the same buffer, and the RAM
//! budget (6 KiB) has no 128 B to spare. A calibration record of format 1 stays valid.
//!
//! Record format [`FORMAT`] = 1, little-endian, at most [`RECORD_MAX`] bytes:
//!
//! | bytes | field |
//! |---|---|
//! | 1 | format version (`1`) |
//! | 4 | fade time, ms (u32, ≤ 600 000) |
//! | 1 | channel count `n` (0–6) |
//! | n × (16 + 1 …) | per channel `X Y Z cost` (f32), a curve tag: `0` linear, `1` sRGB, `2` gamma + f32 γ |
//!
//! [`read`] checks every field with the protocol's ranges; a record of another format or out
//! of range is refused whole ([`RecordError`]) and nothing changes.

use crate::settings::RecordError;
use specpoly_core::light::channels::{Channel, Curve};
use specpoly_protocol::{mix::FADE_MAX_MS, DeviceMixer, MIX_CHANNELS};

/// The map key of the mixer's record.
pub const KEY: u8 = 2;

/// The record format written by this firmware.
pub const FORMAT: u8 = 1;

/// Largest record: six channels with gamma curves.
pub const RECORD_MAX: usize = 1 + 4 + 1 + MIX_CHANNELS * (16 + 1 + 4);

/// The mixer's settings, borrowed to be written.
#[derive(Clone, Copy, Debug)]
pub struct Record<'a>(pub &'a DeviceMixer);

impl Record<'_> {
    /// Writes the record into `out`; its length, or `None` when `out` is too short.
    pub fn encode(&self, out: &mut [u8]) -> Option<usize> {
        let mut at = 0;
        let mut put = |b: &[u8]| {
            let end = at + b.len();
            if let Some(o) = out.get_mut(at..end) {
                o.copy_from_slice(b);
            }
            at = end;
        };
        let list = self.0.channels.list();
        put(&[FORMAT]);
        put(&self.0.fade_ms.to_le_bytes());
        put(&[list.len() as u8]);
        for c in list {
            for v in [c.xyz[0], c.xyz[1], c.xyz[2], c.cost] {
                put(&v.to_le_bytes());
            }
            match c.curve() {
                Curve::Linear => put(&[0]),
                Curve::Srgb => put(&[1]),
                Curve::Gamma(g) => {
                    put(&[2]);
                    put(&g.to_le_bytes());
                }
            }
        }
        (at <= out.len()).then_some(at)
    }
}

/// Reads a record written by [`Record::encode`] into `mixer` (its channels and fade time), all
/// fields checked first: on an error `mixer` is unchanged.
pub fn read(bytes: &[u8], mixer: &mut DeviceMixer) -> Result<(), RecordError> {
    let mut at = 0;
    let mut take = |n: usize| -> Result<&[u8], RecordError> {
        let b = bytes.get(at..at + n).ok_or(RecordError::Invalid)?;
        at += n;
        Ok(b)
    };
    let f32_of = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    let format = take(1)?[0];
    if format != FORMAT {
        return Err(RecordError::Format(format));
    }
    let t = take(4)?;
    let fade_ms = u32::from_le_bytes([t[0], t[1], t[2], t[3]]);
    let n = take(1)?[0] as usize;
    if fade_ms > FADE_MAX_MS || n > MIX_CHANNELS {
        return Err(RecordError::Invalid);
    }
    let mut channels = [Channel::new([0.0; 3], 0.0, Curve::Linear); MIX_CHANNELS];
    for c in channels.iter_mut().take(n) {
        let v = take(16)?;
        let [x, y, z, cost] = [0, 4, 8, 12].map(|i| f32_of(&v[i..]));
        // the `channel` command's ranges
        let ok = |v: f32| (0.0..=f32::MAX).contains(&v);
        if !(ok(x) && ok(z) && ok(cost) && y > 0.0 && ok(y)) {
            return Err(RecordError::Invalid);
        }
        c.xyz = [x, y, z];
        c.cost = cost;
        let curve = match take(1)?[0] {
            0 => Curve::Linear,
            1 => Curve::Srgb,
            2 => {
                let g = f32_of(take(4)?);
                if !(0.1..=10.0).contains(&g) {
                    return Err(RecordError::Invalid);
                }
                Curve::Gamma(g)
            }
            _ => return Err(RecordError::Invalid),
        };
        c.set_curve(curve);
    }
    if at != bytes.len() {
        return Err(RecordError::Invalid);
    }
    mixer.channels.clear();
    for (i, c) in channels.iter().take(n).enumerate() {
        // fewer than the capacity, in order: cannot fail
        let _ = mixer.channels.set(i, *c);
    }
    mixer.fade_ms = fade_ms;
    Ok(())
}

#[cfg(all(test, feature = "mixing"))]
mod tests {
    use super::*;
    use specpoly_protocol::{mix::answer, Command};

    fn mixer() -> DeviceMixer {
        let mut m = DeviceMixer::new();
        for l in [
            "channel 0 0.65 0.3 0 2",
            "channel 1 0.25 0.7 0.1",
            "channel 2 0.18 0.08 0.95 0.5",
            "channel 3 0.95 1 0.85",
            "channel 4 0.6 0.5 0.02",
            "channel 5 0.9 0.85 0.4",
            "channel 1 curve gamma 2.2",
            "channel 2 curve srgb",
            "fade 250",
        ] {
            answer(&mut m, &Command::parse(l).unwrap(), 65535);
        }
        m
    }

    #[test]
    fn the_mixers_record_reads_back_and_damage_is_refused() {
        let m = mixer();
        let mut buf = [0u8; RECORD_MAX];
        let n = Record(&m).encode(&mut buf).unwrap();
        assert_eq!(n, 1 + 4 + 1 + 6 * 17 + 4, "one gamma curve");
        let mut back = DeviceMixer::new();
        read(&buf[..n], &mut back).unwrap();
        assert_eq!(back.channels, m.channels);
        assert_eq!(back.fade_ms, 250);
        assert_eq!(Record(&m).encode(&mut buf[..n - 1]), None);
        let before = back.clone();
        let mut old = buf;
        old[0] = 0;
        assert_eq!(read(&old[..n], &mut back), Err(RecordError::Format(0)));
        assert_eq!(read(&buf[..n - 1], &mut back), Err(RecordError::Invalid));
        // channel 0's Y (bytes 10..14) zero, an unknown curve tag
        let mut dark = buf;
        dark[10..14].copy_from_slice(&0f32.to_le_bytes());
        assert_eq!(read(&dark[..n], &mut back), Err(RecordError::Invalid));
        let mut tag = buf;
        tag[22] = 7;
        assert_eq!(read(&tag[..n], &mut back), Err(RecordError::Invalid));
        assert_eq!(back, before, "unchanged by refused records");
    }
}
