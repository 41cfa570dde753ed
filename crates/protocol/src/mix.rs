//! The multi-channel mixing commands (`channel`, `xy`, `cct`, `fade`) and their `ok mix` reply;
//! grammar in firmware/PROTOCOL.md. [`answer`] is the one place a command becomes a
//! [`Mixer`] call and a reply, shared by the firmware and the host's simulated controller so
//! the two cannot answer differently.

mod answer;

pub use answer::answer;

use crate::fault::{ErrorCode, Fault};
use crate::grammar::write_curve;
#[cfg(feature = "mix")]
use crate::grammar::{number, Words};
use crate::number::{parse_u16, write_f32, write_f32_list, write_int, write_int_list};
use core::fmt::{self, Write};
use specpoly_core::light::channels::{Curve, Goal, Mixer};
#[cfg(feature = "mix")]
use specpoly_core::light::locus;
use specpoly_core::Transfer;

/// Most channels a controller mixes.
pub const MIX_CHANNELS: usize = 6;

/// Longest fade, ms (10 minutes).
pub const FADE_MAX_MS: u32 = 600_000;

/// The controller's mixer.
pub type DeviceMixer = Mixer<MIX_CHANNELS>;

/// A `channel` command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ChannelCommand {
    /// `channel N X Y Z [COST]`: channel `N`'s tristimulus values at full drive and the weight
    /// of its duty (default 1); a new channel's curve is linear, an existing one keeps its curve.
    Set {
        /// 0-based channel.
        index: u8,
        /// `X, Y, Z`.
        xyz: [f32; 3],
        /// Weight in the minimised drive.
        cost: f32,
    },
    /// `channel N curve linear|srgb|gamma G`.
    Curve {
        /// 0-based channel.
        index: u8,
        /// The curve.
        curve: Curve,
    },
    /// `channel clear`: no channels.
    Clear,
}

/// What `ok mix` reports: the solved target and the duties that make it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MixReport {
    /// The target's CIE 1931 `(x, y)` as the controller computed it (for `cct`, from its locus
    /// table) (`xy=`).
    pub xy: [f32; 2],
    /// The relative luminance (`lum=`).
    pub lum: f32,
    /// Light fractions before the curves and quantisation (`light=`, `n` values).
    pub light: [f32; MIX_CHANNELS],
    /// PWM duties out of `max` (`duty=`, `n` values).
    pub duty: [u16; MIX_CHANNELS],
    /// Channel count.
    pub n: u8,
    /// Full-scale duty (`max=`).
    pub max: u16,
    /// Fade steps to get there, 10 ms each (`steps=`; 0: shown at once).
    pub steps: u16,
}

impl MixReport {
    /// The light fractions of the channels.
    pub fn light(&self) -> &[f32] {
        &self.light[..self.n as usize]
    }

    /// The duties of the channels.
    pub fn duty(&self) -> &[u16] {
        &self.duty[..self.n as usize]
    }
}

fn range(at: usize) -> Fault {
    Fault::at(ErrorCode::OutOfRange, at)
}

/// A number in `[lo, hi]` (both finite).
#[cfg(feature = "mix")]
fn within(w: &mut Words<'_>, lo: f32, hi: f32) -> Result<f32, Fault> {
    let (tok, at) = w.need()?;
    let v = number(tok, at)?;
    if !(lo..=hi).contains(&v) {
        return Err(range(at));
    }
    Ok(v)
}

/// Parses the words after `channel`.
#[cfg(feature = "mix")]
pub(crate) fn parse_channel(w: &mut Words<'_>) -> Result<ChannelCommand, Fault> {
    let (first, at) = w.need()?;
    if first == "clear" {
        return Ok(ChannelCommand::Clear);
    }
    let index = match parse_u16(first) {
        Some(i) if (i as usize) < MIX_CHANNELS => i as u8,
        Some(_) => return Err(range(at)),
        None => return Err(Fault::at(ErrorCode::BadNumber, at)),
    };
    let (tok, at) = w.need()?;
    if tok == "curve" {
        let (kind, at) = w.need()?;
        let curve = match kind {
            "linear" => Curve::Linear,
            "srgb" => Curve::Srgb,
            "gamma" => Curve::Gamma(within(w, 0.1, 10.0)?),
            _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
        };
        return Ok(ChannelCommand::Curve { index, curve });
    }
    let mut xyz = [number(tok, at)?, 0.0, 0.0];
    if !(0.0..=f32::MAX).contains(&xyz[0]) {
        return Err(range(at));
    }
    xyz[1] = within(w, f32::MIN_POSITIVE, f32::MAX)?;
    xyz[2] = within(w, 0.0, f32::MAX)?;
    let cost = match w.next() {
        None => 1.0,
        Some((tok, at)) => {
            let c = number(tok, at)?;
            if !(0.0..=f32::MAX).contains(&c) {
                return Err(range(at));
            }
            c
        }
    };
    Ok(ChannelCommand::Set { index, xyz, cost })
}

/// Parses the words after `xy` (`cct == false`) or `cct`.
#[cfg(feature = "mix")]
pub(crate) fn parse_goal(w: &mut Words<'_>, cct: bool) -> Result<Goal, Fault> {
    let (a, b) = if cct {
        (within(w, locus::CCT_MIN, locus::CCT_MAX)?, 0.0)
    } else {
        let x = within(w, 0.0, 1.0)?;
        let (tok, at) = w.need()?;
        let y = number(tok, at)?;
        if !(x > 0.0 && y > 0.0 && x + y < 1.0) {
            return Err(range(at));
        }
        (x, y)
    };
    let (mut duv, mut lum) = (None, None);
    while let Some((key, at)) = w.next() {
        match key {
            "duv" if cct && duv.is_none() => {
                duv = Some(within(w, -locus::DUV_MAX, locus::DUV_MAX)?)
            }
            "lum" if lum.is_none() => lum = Some(within(w, 0.0, 1.0)?),
            _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
        }
    }
    let lum = lum.unwrap_or(1.0);
    Ok(if cct {
        Goal::Cct {
            cct: a,
            duv: duv.unwrap_or(0.0),
            lum,
        }
    } else {
        Goal::Xy { xy: [a, b], lum }
    })
}

/// Parses the words after `fade`: whole milliseconds, 0 to [`FADE_MAX_MS`].
#[cfg(feature = "mix")]
pub(crate) fn parse_fade(w: &mut Words<'_>) -> Result<u32, Fault> {
    let (tok, at) = w.need()?;
    let v = number(tok, at)?;
    if !(0.0..=FADE_MAX_MS as f32).contains(&v) || v != (v as u32) as f32 {
        return Err(range(at));
    }
    Ok(v as u32)
}

fn curve_transfer(c: Curve) -> Transfer {
    c.transfer()
}

/// Writes a `channel …` command.
pub(crate) fn write_channel<W: Write>(w: &mut W, c: &ChannelCommand) -> fmt::Result {
    match c {
        ChannelCommand::Clear => w.write_str("channel clear"),
        ChannelCommand::Set { index, xyz, cost } => {
            w.write_str("channel ")?;
            write_int(w, *index as i64)?;
            for v in [xyz[0], xyz[1], xyz[2], *cost] {
                w.write_char(' ')?;
                write_f32(w, v)?;
            }
            Ok(())
        }
        ChannelCommand::Curve { index, curve } => {
            w.write_str("channel ")?;
            write_int(w, *index as i64)?;
            w.write_str(" curve ")?;
            write_curve(w, &curve_transfer(*curve), ' ')
        }
    }
}

/// Writes an `xy …` or `cct …` command.
pub(crate) fn write_goal<W: Write>(w: &mut W, g: &Goal) -> fmt::Result {
    match g {
        Goal::Xy { xy, lum } => {
            w.write_str("xy ")?;
            write_f32(w, xy[0])?;
            w.write_char(' ')?;
            write_f32(w, xy[1])?;
            w.write_str(" lum ")?;
            write_f32(w, *lum)
        }
        Goal::Cct { cct, duv, lum } => {
            w.write_str("cct ")?;
            write_f32(w, *cct)?;
            w.write_str(" duv ")?;
            write_f32(w, *duv)?;
            w.write_str(" lum ")?;
            write_f32(w, *lum)
        }
    }
}

/// Writes a `fade …` command.
pub(crate) fn write_fade<W: Write>(w: &mut W, ms: u32) -> fmt::Result {
    w.write_str("fade ")?;
    write_int(w, ms as i64)
}

/// Writes `ok mix xy=x,y lum=L light=… duty=… max=M steps=K`.
pub(crate) fn write_report<W: Write>(w: &mut W, r: &MixReport) -> fmt::Result {
    w.write_str("ok mix")?;
    write_f32_list(w, "xy", &r.xy)?;
    write_f32_list(w, "lum", &[r.lum])?;
    write_f32_list(w, "light", r.light())?;
    write_int_list(w, "duty", r.duty())?;
    w.write_str(" max=")?;
    write_int(w, r.max as i64)?;
    w.write_str(" steps=")?;
    write_int(w, r.steps as i64)
}

/// Reads the `key=value` words of an `ok mix` reply (after `ok mix`).
pub(crate) fn parse_report<'a>(words: impl Iterator<Item = &'a str>) -> Result<MixReport, Fault> {
    let bad = Fault::new(ErrorCode::BadReply);
    let f32_of = |s: &str| crate::number::parse_f32(s).map_err(|_| bad);
    let mut r = MixReport {
        xy: [0.0; 2],
        lum: 0.0,
        light: [0.0; MIX_CHANNELS],
        duty: [0; MIX_CHANNELS],
        n: 0,
        max: 0,
        steps: 0,
    };
    let mut seen = [false; 6];
    let mut light_n = None;
    for tok in words {
        let (k, v) = tok.split_once('=').ok_or(bad)?;
        let slot = match k {
            "xy" => {
                let (x, y) = v.split_once(',').ok_or(bad)?;
                r.xy = [f32_of(x)?, f32_of(y)?];
                0
            }
            "lum" => {
                r.lum = f32_of(v)?;
                1
            }
            "light" => {
                let mut n = 0;
                for p in v.split(',') {
                    *r.light.get_mut(n).ok_or(bad)? = f32_of(p)?;
                    n += 1;
                }
                light_n = Some(n);
                2
            }
            "duty" => {
                let mut n = 0;
                for p in v.split(',') {
                    *r.duty.get_mut(n).ok_or(bad)? = parse_u16(p).ok_or(bad)?;
                    n += 1;
                }
                r.n = n as u8;
                3
            }
            "max" => {
                r.max = parse_u16(v).ok_or(bad)?;
                4
            }
            "steps" => {
                r.steps = parse_u16(v).ok_or(bad)?;
                5
            }
            // readers ignore keys they do not know
            _ => continue,
        };
        seen[slot] = true;
    }
    if !seen.iter().all(|s| *s) || light_n != Some(r.n as usize) || r.n < 3 {
        return Err(bad);
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::{Command, Reply};
    use std::string::String;

    fn parse(l: &str) -> Result<Command, Fault> {
        Command::parse(l)
    }

    fn round_trip(l: &str) {
        let c = parse(l).unwrap_or_else(|f| panic!("{l}: {f}"));
        let mut s = String::new();
        c.write(&mut s).unwrap();
        assert_eq!(parse(&s), Ok(c), "{l} → {s}");
    }

    #[test]
    fn commands_parse_and_write_back() {
        for l in [
            "channel 0 0.65 0.3 0.01",
            "channel 5 0.95 1 0.85 0.0031",
            "channel 2 curve gamma 2.2",
            "channel 1 curve srgb",
            "channel clear",
            "xy 0.3127 0.329",
            "xy 0.4 0.4 lum 0.25",
            "cct 2700",
            "cct 4000 duv -0.006 lum 0.8",
            "cct 6500 lum 0 duv 0.05",
            "fade 250",
            "fade 0",
        ] {
            round_trip(l);
        }
        assert_eq!(
            parse("cct 4000 duv 0.01"),
            Ok(Command::Mix(Goal::Cct {
                cct: 4000.0,
                duv: 0.01,
                lum: 1.0
            }))
        );
    }

    #[test]
    fn bad_mixing_commands_name_the_word_at_fault() {
        let at = |code, n| Err(Fault::at(code, n));
        assert_eq!(parse("channel 6 1 1 1"), at(ErrorCode::OutOfRange, 1));
        assert_eq!(parse("channel x 1 1 1"), at(ErrorCode::BadNumber, 1));
        assert_eq!(parse("channel 0 1 0 1"), at(ErrorCode::OutOfRange, 3));
        assert_eq!(parse("channel 0 -1 1 1"), at(ErrorCode::OutOfRange, 2));
        assert_eq!(parse("channel 0 1 1 1 -2"), at(ErrorCode::OutOfRange, 5));
        assert_eq!(parse("channel 0 1 1"), at(ErrorCode::MissingArgument, 4));
        assert_eq!(
            parse("channel 0 curve table"),
            at(ErrorCode::UnknownName, 3)
        );
        assert_eq!(parse("xy 0.7 0.4"), at(ErrorCode::OutOfRange, 2));
        assert_eq!(parse("xy 0.3 0.3 lum 1.5"), at(ErrorCode::OutOfRange, 4));
        assert_eq!(parse("xy 0.3 0.3 duv 0"), at(ErrorCode::UnknownName, 3));
        assert_eq!(parse("cct 999"), at(ErrorCode::OutOfRange, 1));
        assert_eq!(parse("cct 25001"), at(ErrorCode::OutOfRange, 1));
        assert_eq!(parse("cct 3000 duv 0.06"), at(ErrorCode::OutOfRange, 3));
        assert_eq!(parse("cct 3000 lum 1 lum 1"), at(ErrorCode::UnknownName, 4));
        assert_eq!(parse("fade 1.5"), at(ErrorCode::OutOfRange, 1));
        assert_eq!(parse("fade 600001"), at(ErrorCode::OutOfRange, 1));
        assert_eq!(parse("fade 10 20"), at(ErrorCode::ExtraArgument, 2));
    }

    #[test]
    fn the_mixer_answers_and_its_reply_reads_back() {
        let mut m = DeviceMixer::new();
        let mut run = |l: &str| answer(&mut m, &parse(l).unwrap(), 65535).unwrap();
        assert_eq!(
            run("xy 0.3 0.3"),
            Reply::Error(Fault::new(ErrorCode::NoChannels))
        );
        assert_eq!(
            run("channel 1 1 1 1"),
            Reply::Error(Fault::at(ErrorCode::OutOfRange, 1))
        );
        for l in [
            "channel 0 0.65 0.3 0",
            "channel 1 0.25 0.7 0.1",
            "channel 2 0.18 0.08 0.95",
            "channel 3 0.95 1 0.85",
            "channel 3 curve gamma 2.2",
        ] {
            assert_eq!(run(l), Reply::Done("channel"), "{l}");
        }
        let r = run("cct 4000 lum 0.5");
        let Reply::Mix(report) = r else {
            panic!("{r:?}")
        };
        assert_eq!((report.n, report.steps), (4, 0));
        let mut s = String::new();
        r.write(&mut s).unwrap();
        assert!(s.starts_with("ok mix xy="), "{s}");
        assert_eq!(Reply::parse(&s), Ok(r), "{s}");
        assert_eq!(
            run("xy 0.08 0.85"),
            Reply::Error(Fault::new(ErrorCode::OutOfGamut))
        );
        assert_eq!(run("fade 100"), Reply::Done("fade"));
        assert!(matches!(run("xy 0.3 0.3"), Reply::Mix(r) if r.steps == 10));
        assert_eq!(answer(&mut m, &Command::Hello, 1), None);
    }
}
