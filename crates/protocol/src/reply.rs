//! Replies (controller → host): formatting and parsing. One line per command.
//!
//! Replies are `ok KIND key=value …` or `err CODE [at=N]`. Values with several components are
//! comma-separated. A reader ignores keys it does not know, so later protocol versions may add
//! keys without breaking older hosts.

use crate::grammar::{map_name, write_curve};
use crate::number::{
    parse_f32, parse_u16, write_f32_hex_list, write_f32_list, write_int, write_int_list,
};
use crate::{ErrorCode, Fault, PROTOCOL_VERSION};
use core::fmt::{self, Write};
use specpoly_core::{Drive, GamutMap, Observer, Transfer, Xyz};

/// How the last colour relates to the gamut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gamut {
    /// Inside: reproduced exactly, up to quantisation (`in`).
    In,
    /// Outside, mapped with this [`GamutMap`] (`out:clip`, `out:desaturate`).
    Out(GamutMap),
}

/// The result of a colour command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColourReport {
    /// The target XYZ (white `Y = 100`), as computed by the controller (`xyz=`).
    pub xyz: Xyz,
    /// The XYZ the LED emits at the quantised duties, same scale (`led=`).
    pub led: Xyz,
    /// Linear drive after gamut mapping, in `[0, 1]` (`linear=`).
    pub linear: [f32; 3],
    /// PWM duties in ticks (`duty=`), out of `max`.
    pub duty: [u16; 3],
    /// Full-scale duty (`max=`).
    pub max: u16,
    /// In or out of gamut (`gamut=`).
    pub gamut: Gamut,
    /// The numbers are written in the compact hexadecimal form (`0x` + the f32's bits): the
    /// reply to a `refl` line whose coefficients are ([`crate::Command::Reflect`]'s `hex`).
    /// Read back from the `xyz=` value's form.
    pub hex: bool,
}

impl ColourReport {
    /// The report of the core's drive step ([`specpoly_core::Display::drive`]) for `target`,
    /// on levels `0 ..= max`, with gamut map `map`.
    pub fn of(target: Xyz, drive: &Drive, map: GamutMap, max: u16) -> Self {
        Self {
            xyz: target,
            led: drive.emitted,
            linear: drive.linear,
            duty: drive.level,
            max,
            gamut: if drive.out_of_gamut {
                Gamut::Out(map)
            } else {
                Gamut::In
            },
            hex: false,
        }
    }

    /// Whether every number of the report is finite, i.e. the report can be written as a
    /// reply the host reads back ([`Reply::parse`] refuses `nan` and `inf`).
    pub fn is_finite(&self) -> bool {
        self.xyz
            .to_array()
            .into_iter()
            .chain(self.led.to_array())
            .chain(self.linear)
            .all(f32::is_finite)
    }
}

/// A transfer curve's summary in `state` replies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveSummary {
    /// `linear`
    Linear,
    /// `srgb`
    Srgb,
    /// `gamma:G`
    Gamma(f32),
    /// `table:N` (N points)
    Table(u16),
}

impl CurveSummary {
    /// The summary of a curve.
    pub fn of(t: &Transfer) -> Self {
        match t {
            Transfer::Linear => CurveSummary::Linear,
            Transfer::Srgb => CurveSummary::Srgb,
            Transfer::Gamma(g) => CurveSummary::Gamma(*g),
            Transfer::Table(t) => CurveSummary::Table(t.len() as u16),
        }
    }
}

/// The controller's state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateReport {
    /// Protocol version (`protocol=`).
    pub protocol: u16,
    /// `[x, y, Y]` per primary (`primaries=`, 9 numbers).
    pub primaries: [[f32; 3]; 3],
    /// Transfer curves (`trc=`).
    pub trc: [CurveSummary; 3],
    /// Gamut mapping (`map=`).
    pub map: GamutMap,
    /// Observer (`observer=`).
    pub observer: Observer,
    /// The grid side of the drive-correction table applied to colours (`lut=`; 0: none, or
    /// one stored for another calibration). A controller that predates tables omits the key:
    /// read as 0.
    pub lut: u8,
    /// Current duties (`duty=`) out of `max` (`max=`).
    pub duty: [u16; 3],
    /// Full-scale duty.
    pub max: u16,
}

/// A reply line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reply {
    /// `ok hello specpoly-led protocol=1 max_line=N max=M`
    Hello {
        /// Protocol version.
        protocol: u16,
        /// Longest accepted line in bytes.
        max_line: u16,
        /// Full-scale PWM duty.
        max: u16,
    },
    /// `ok cal|trc|map|observer`: a setting was accepted.
    Done(&'static str),
    /// `ok colour …`
    Colour(ColourReport),
    /// `ok state …`
    State(StateReport),
    /// `ok mix …` ([`crate::mix`])
    Mix(crate::mix::MixReport),
    /// `err CODE [at=N]`
    Error(Fault),
}

/// Settings acknowledged by [`Reply::Done`].
pub const SETTINGS: [&str; 9] = [
    "cal", "trc", "map", "observer", "save", "load", "channel", "fade", "lut",
];

fn write_duty<W: Write>(w: &mut W, duty: [u16; 3], max: u16) -> fmt::Result {
    write_int_list(w, "duty", &duty)?;
    w.write_str(" max=")?;
    write_int(w, max as i64)
}

fn gamut_name(g: Gamut) -> &'static str {
    match g {
        Gamut::In => "in",
        Gamut::Out(GamutMap::Clip) => "out:clip",
        Gamut::Out(GamutMap::Desaturate) => "out:desaturate",
    }
}

impl Reply {
    /// Writes the reply line (no newline).
    pub fn write<W: Write>(&self, w: &mut W) -> fmt::Result {
        match self {
            Reply::Hello {
                protocol,
                max_line,
                max,
            } => {
                w.write_str("ok hello specpoly-led protocol=")?;
                write_int(w, *protocol as i64)?;
                w.write_str(" max_line=")?;
                write_int(w, *max_line as i64)?;
                w.write_str(" max=")?;
                write_int(w, *max as i64)
            }
            Reply::Done(what) => {
                w.write_str("ok ")?;
                w.write_str(what)
            }
            Reply::Colour(c) => {
                w.write_str("ok colour")?;
                let list = if c.hex {
                    write_f32_hex_list
                } else {
                    write_f32_list
                };
                list(w, "xyz", &c.xyz.to_array())?;
                list(w, "led", &c.led.to_array())?;
                list(w, "linear", &c.linear)?;
                write_duty(w, c.duty, c.max)?;
                w.write_str(" gamut=")?;
                w.write_str(gamut_name(c.gamut))
            }
            Reply::State(s) => {
                w.write_str("ok state protocol=")?;
                write_int(w, s.protocol as i64)?;
                let mut p = [0.0f32; 9];
                for i in 0..9 {
                    p[i] = s.primaries[i / 3][i % 3];
                }
                write_f32_list(w, "primaries", &p)?;
                w.write_str(" trc=")?;
                for (i, c) in s.trc.iter().enumerate() {
                    if i > 0 {
                        w.write_char(',')?;
                    }
                    match c {
                        CurveSummary::Linear => write_curve(w, &Transfer::Linear, ':')?,
                        CurveSummary::Srgb => write_curve(w, &Transfer::Srgb, ':')?,
                        CurveSummary::Gamma(g) => write_curve(w, &Transfer::Gamma(*g), ':')?,
                        CurveSummary::Table(n) => {
                            w.write_str("table:")?;
                            write_int(w, *n as i64)?;
                        }
                    }
                }
                w.write_str(" map=")?;
                w.write_str(map_name(s.map))?;
                w.write_str(" observer=")?;
                w.write_str(s.observer.name())?;
                w.write_str(" lut=")?;
                write_int(w, s.lut as i64)?;
                write_duty(w, s.duty, s.max)
            }
            Reply::Mix(r) => crate::mix::write_report(w, r),
            Reply::Error(f) => f.write(w),
        }
    }

    /// Parses a reply line. Never panics; unreadable lines give [`ErrorCode::BadReply`].
    pub fn parse(line: &str) -> Result<Reply, Fault> {
        let bad = Fault::new(ErrorCode::BadReply);
        let mut it = line.split_ascii_whitespace();
        match it.next() {
            Some("ok") => {}
            Some("err") => {
                let code = it.next().and_then(ErrorCode::from_name).ok_or(bad)?;
                let at = match it.next() {
                    None => None,
                    Some(t) => Some(t.strip_prefix("at=").and_then(parse_u16).ok_or(bad)?),
                };
                return Ok(Reply::Error(Fault { code, at }));
            }
            _ => return Err(bad),
        }
        let kind = it.next().ok_or(bad)?;
        if let Some(s) = SETTINGS.iter().find(|s| **s == kind) {
            return Ok(Reply::Done(s));
        }
        if kind == "mix" {
            return crate::mix::parse_report(it).map(Reply::Mix);
        }
        let mut keys = Keys::default();
        if kind == "hello" && it.next() != Some("specpoly-led") {
            return Err(bad);
        }
        for tok in it {
            let (k, v) = tok.split_once('=').ok_or(bad)?;
            keys.set(k, v);
        }
        match kind {
            "hello" => Ok(Reply::Hello {
                protocol: keys.int(keys.protocol)?,
                max_line: keys.int(keys.max_line)?,
                max: keys.int(keys.max)?,
            }),
            "colour" => {
                let mut linear = [0.0; 3];
                floats(keys.linear.ok_or(bad)?, &mut linear)?;
                let gamut = match keys.gamut.ok_or(bad)? {
                    "in" => Gamut::In,
                    "out:clip" => Gamut::Out(GamutMap::Clip),
                    "out:desaturate" => Gamut::Out(GamutMap::Desaturate),
                    _ => return Err(bad),
                };
                Ok(Reply::Colour(ColourReport {
                    xyz: keys.xyz(keys.xyz)?,
                    led: keys.xyz(keys.led)?,
                    linear,
                    duty: keys.duty()?,
                    max: keys.int(keys.max)?,
                    gamut,
                    hex: keys.xyz.is_some_and(|v| v.starts_with("0x")),
                }))
            }
            "state" => {
                let mut p = [0.0; 9];
                floats(keys.primaries.ok_or(bad)?, &mut p)?;
                let mut primaries = [[0.0; 3]; 3];
                for i in 0..9 {
                    primaries[i / 3][i % 3] = p[i];
                }
                let mut trc = [CurveSummary::Linear; 3];
                let mut parts = keys.trc.ok_or(bad)?.split(',');
                for t in trc.iter_mut() {
                    let part = parts.next().ok_or(bad)?;
                    *t = match part.split_once(':') {
                        None if part == "linear" => CurveSummary::Linear,
                        None if part == "srgb" => CurveSummary::Srgb,
                        Some(("gamma", g)) => CurveSummary::Gamma(parse_f32(g).map_err(|_| bad)?),
                        Some(("table", n)) => CurveSummary::Table(parse_u16(n).ok_or(bad)?),
                        _ => return Err(bad),
                    };
                }
                if parts.next().is_some() {
                    return Err(bad);
                }
                let map = match keys.map.ok_or(bad)? {
                    "clip" => GamutMap::Clip,
                    "desaturate" => GamutMap::Desaturate,
                    _ => return Err(bad),
                };
                let observer = keys.observer.and_then(Observer::from_name).ok_or(bad)?;
                Ok(Reply::State(StateReport {
                    protocol: keys.int(keys.protocol)?,
                    primaries,
                    trc,
                    map,
                    observer,
                    lut: match keys.lut {
                        None => 0,
                        Some(v) => parse_u16(v).and_then(|n| u8::try_from(n).ok()).ok_or(bad)?,
                    },
                    duty: keys.duty()?,
                    max: keys.int(keys.max)?,
                }))
            }
            _ => Err(bad),
        }
    }

    /// The hello reply of this protocol version.
    pub fn hello(max: u16) -> Reply {
        Reply::Hello {
            protocol: PROTOCOL_VERSION,
            max_line: crate::MAX_LINE as u16,
            max,
        }
    }
}

/// Comma-separated floats, exactly `out.len()` of them.
fn floats(s: &str, out: &mut [f32]) -> Result<(), Fault> {
    let bad = Fault::new(ErrorCode::BadReply);
    let mut parts = s.split(',');
    for o in out.iter_mut() {
        *o = parts.next().and_then(|p| parse_f32(p).ok()).ok_or(bad)?;
    }
    if parts.next().is_some() {
        return Err(bad);
    }
    Ok(())
}

/// The keys a reply may carry (unknown keys are ignored).
#[derive(Default)]
struct Keys<'a> {
    protocol: Option<&'a str>,
    max_line: Option<&'a str>,
    max: Option<&'a str>,
    xyz: Option<&'a str>,
    led: Option<&'a str>,
    linear: Option<&'a str>,
    duty: Option<&'a str>,
    gamut: Option<&'a str>,
    primaries: Option<&'a str>,
    trc: Option<&'a str>,
    map: Option<&'a str>,
    observer: Option<&'a str>,
    lut: Option<&'a str>,
}

impl<'a> Keys<'a> {
    fn set(&mut self, k: &str, v: &'a str) {
        let slot = match k {
            "protocol" => &mut self.protocol,
            "max_line" => &mut self.max_line,
            "max" => &mut self.max,
            "xyz" => &mut self.xyz,
            "led" => &mut self.led,
            "linear" => &mut self.linear,
            "duty" => &mut self.duty,
            "gamut" => &mut self.gamut,
            "primaries" => &mut self.primaries,
            "trc" => &mut self.trc,
            "map" => &mut self.map,
            "observer" => &mut self.observer,
            "lut" => &mut self.lut,
            _ => return,
        };
        *slot = Some(v);
    }
    fn int(&self, v: Option<&str>) -> Result<u16, Fault> {
        v.and_then(parse_u16).ok_or(Fault::new(ErrorCode::BadReply))
    }
    fn xyz(&self, v: Option<&str>) -> Result<Xyz, Fault> {
        let mut a = [0.0; 3];
        floats(v.ok_or(Fault::new(ErrorCode::BadReply))?, &mut a)?;
        Ok(Xyz::from_array(a))
    }
    fn duty(&self) -> Result<[u16; 3], Fault> {
        let bad = Fault::new(ErrorCode::BadReply);
        let mut d = [0u16; 3];
        let mut parts = self.duty.ok_or(bad)?.split(',');
        for o in d.iter_mut() {
            *o = parts.next().and_then(parse_u16).ok_or(bad)?;
        }
        if parts.next().is_some() {
            return Err(bad);
        }
        Ok(d)
    }
}
