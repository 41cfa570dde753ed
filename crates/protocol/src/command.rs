//! Commands (host → controller): parsing and formatting. The grammar is in firmware/PROTOCOL.md.

pub use crate::grammar::{map_name, write_curve};
use crate::grammar::{number, Words};
use crate::mix::ChannelCommand;
use crate::number::{write_f32, write_f32_hex};
use crate::{ErrorCode, Fault, MAX_FACTORS};
use core::fmt::{self, Write};
use specpoly_core::light::channels::Goal;
use specpoly_core::{
    display::TABLE_MAX, DefaultSpectrum, GamutMap, Illuminant, Layout, Moments, Observer, Paper,
    PaperSpectrum, Spectrum, Transfer, Xyy, Xyz,
};

/// Which transfer curves a `trc` command sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channels {
    /// Red only (`r`).
    Red,
    /// Green only (`g`).
    Green,
    /// Blue only (`b`).
    Blue,
    /// All three (`rgb`).
    All,
}

impl Channels {
    /// The wire name.
    pub fn name(self) -> &'static str {
        match self {
            Channels::Red => "r",
            Channels::Green => "g",
            Channels::Blue => "b",
            Channels::All => "rgb",
        }
    }

    /// Whether channel `i` (0 = red) is included.
    pub fn includes(self, i: usize) -> bool {
        match self {
            Channels::Red => i == 0,
            Channels::Green => i == 1,
            Channels::Blue => i == 2,
            Channels::All => i < 3,
        }
    }
}

/// A reflectance in one of the two built-in representations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reflectance {
    /// The paper's 2 cubic spans split at 550 nm (`paper`, 8 coefficients).
    Paper(PaperSpectrum),
    /// The project default, 8 uniform cubic spans (`default`, 32 coefficients).
    Default(DefaultSpectrum),
}

impl Reflectance {
    /// The preset's wire name.
    pub fn preset(&self) -> &'static str {
        match self {
            Reflectance::Paper(_) => "paper",
            Reflectance::Default(_) => "default",
        }
    }

    /// XYZ as a reflectance under a light whose moments for both presets are given
    /// ([`Moments::xyz`]: three dot products), through `specpoly-kernels`, which the firmware
    /// builds for speed (`opt-level = 3`) while the rest is built for size (docs/performance.md).
    pub fn xyz(&self, paper: &Moments<2, 4, Paper>, default: &Moments<8, 4>) -> Xyz {
        match self {
            Reflectance::Paper(s) => specpoly_kernels::xyz_paper(paper, s),
            Reflectance::Default(s) => specpoly_kernels::xyz_default(default, s),
        }
    }

    /// The reduced product (the paper's eq. 6, [`Spectrum::mul`]); `None` for two presets.
    pub fn mul(&self, o: &Self) -> Option<Self> {
        match (self, o) {
            (Reflectance::Paper(a), Reflectance::Paper(b)) => {
                Some(Reflectance::Paper(specpoly_kernels::mul_paper(a, b)))
            }
            (Reflectance::Default(a), Reflectance::Default(b)) => {
                Some(Reflectance::Default(specpoly_kernels::mul_default(a, b)))
            }
            _ => None,
        }
    }

    /// Writes the coefficients on the wire order: span by span, each span's Chebyshev
    /// coefficients `c₀ … c₃` low to high, separated by spaces.
    pub fn write_coefficients<W: Write>(&self, w: &mut W) -> fmt::Result {
        self.write_coefficients_with(w, write_f32)
    }

    /// [`Self::write_coefficients`] with each number written by `num` (decimal or the compact
    /// hexadecimal form, [`crate::number`]).
    fn write_coefficients_with<W: Write>(&self, w: &mut W, num: NumberWriter<W>) -> fmt::Result {
        match self {
            Reflectance::Paper(s) => write_spectrum(w, s, num),
            Reflectance::Default(s) => write_spectrum(w, s, num),
        }
    }
}

/// How a number goes on the wire: [`write_f32`] or [`write_f32_hex`].
type NumberWriter<W> = fn(&mut W, f32) -> fmt::Result;

fn write_spectrum<W: Write, const S: usize, const C: usize, L: Layout<S>>(
    w: &mut W,
    s: &Spectrum<S, C, L>,
    num: NumberWriter<W>,
) -> fmt::Result {
    let c = s.coefficients();
    for span in 0..S {
        for k in 0..C {
            if span + k > 0 {
                w.write_char(' ')?;
            }
            num(w, c[k][span])?;
        }
    }
    Ok(())
}

/// A command to the controller.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// `hello`: protocol version and limits.
    Hello,
    /// `cal xr yr Yr xg yg Yg xb yb Yb`: the primaries' chromaticities and luminances at full
    /// drive (Cowan's model, paper §7.3).
    Calibrate {
        /// `[x, y]` of red, green, blue.
        xy: [[f32; 2]; 3],
        /// Luminance `Y` of each primary at full drive (any unit; only ratios matter).
        luminance: [f32; 3],
    },
    /// `trc CHANNELS CURVE`: a transfer curve.
    Transfer {
        /// Which channels.
        channels: Channels,
        /// The curve.
        curve: Transfer,
    },
    /// `map clip|desaturate`: the gamut mapping.
    Map(GamutMap),
    /// `observer 1931|1964`: the observer used for reflectances.
    Observer(Observer),
    /// `xyz X Y Z`: a colour, relative to the LED's white at `Y = 100`.
    Xyz(Xyz),
    /// `xyy x y Y`: a colour by chromaticity and relative luminance (white `Y = 100`).
    Xyy(Xyy),
    /// `refl PRESET ILLUMINANT c… [* c…]…`: a reflectance, or the product of up to
    /// [`MAX_FACTORS`] reflectances, under a built-in illuminant. The parser folds the factors
    /// with the reduced product as it reads them.
    Reflect {
        /// The light.
        illuminant: Illuminant,
        /// The product of the factors.
        product: Reflectance,
        /// How many factors were multiplied.
        factors: u8,
        /// The first coefficient was in the compact hexadecimal form (`0x` + the f32's bits):
        /// the colour reply's numbers are then written in that form too (PROTOCOL.md,
        /// "Numbers"), ≈ 1 000 instructions fewer per number on the controller.
        hex: bool,
    },
    /// `state`: the calibration and the last colour.
    State,
    /// `save`: keep the settings (calibration, curves, map, observer) in the controller's flash;
    /// they are loaded again at every start.
    Save,
    /// `load`: the settings last saved, now.
    Load,
    /// `channel …`: a mixing channel ([`crate::mix`]).
    Channel(ChannelCommand),
    /// `xy x y [lum L]` or `cct K [duv D] [lum L]`: a mix of the channels.
    Mix(Goal),
    /// `fade MS`: the fade time for new mix targets.
    Fade(u32),
    /// `lut …`: the drive-correction table's upload ([`crate::lut`]).
    Lut(crate::lut::LutCommand),
}

impl Command {
    /// Parses one line (without its newline). Never panics; any input gives a command or a
    /// [`Fault`].
    pub fn parse(line: &str) -> Result<Command, Fault> {
        let (head, mut w) = Words::new(line);
        let head = head.ok_or(Fault::at(ErrorCode::UnknownCommand, 0))?;
        let cmd = match head {
            "hello" => Command::Hello,
            "state" => Command::State,
            "save" => Command::Save,
            "load" => Command::Load,
            "cal" => {
                let mut xy = [[0.0; 2]; 3];
                let mut luminance = [0.0; 3];
                for i in 0..3 {
                    for c in 0..3 {
                        let (tok, at) = w.need()?;
                        let v = number(tok, at)?;
                        let ok = if c < 2 {
                            (0.0..=1.0).contains(&v) && !(c == 1 && v == 0.0)
                        } else {
                            v > 0.0
                        };
                        if !ok {
                            return Err(Fault::at(ErrorCode::OutOfRange, at));
                        }
                        if c < 2 {
                            xy[i][c] = v;
                        } else {
                            luminance[i] = v;
                        }
                    }
                }
                Command::Calibrate { xy, luminance }
            }
            "trc" => {
                let (ch, at) = w.need()?;
                let channels = match ch {
                    "r" => Channels::Red,
                    "g" => Channels::Green,
                    "b" => Channels::Blue,
                    "rgb" => Channels::All,
                    _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
                };
                let (kind, at) = w.need()?;
                let curve = match kind {
                    "linear" => Transfer::Linear,
                    "srgb" => Transfer::Srgb,
                    "gamma" => {
                        let (tok, at) = w.need()?;
                        let g = number(tok, at)?;
                        if !(0.1..=10.0).contains(&g) {
                            return Err(Fault::at(ErrorCode::OutOfRange, at));
                        }
                        Transfer::Gamma(g)
                    }
                    "table" => {
                        let mut v = [0.0f32; TABLE_MAX];
                        let mut n = 0;
                        while let Some((tok, at)) = w.next() {
                            if n == TABLE_MAX {
                                return Err(Fault::at(ErrorCode::BadCurve, at));
                            }
                            v[n] = number(tok, at)?;
                            n += 1;
                        }
                        let t = Transfer::table(&v[..n])
                            .map_err(|_| Fault::at(ErrorCode::BadCurve, 2))?;
                        // linear light from 0 (off) to 1 (full drive): the word at fault
                        // is the first value (word 3) or the last (word 2 + n)
                        if v[0] != 0.0 {
                            return Err(Fault::at(ErrorCode::BadCurve, 3));
                        }
                        if v[n - 1] != 1.0 {
                            return Err(Fault::at(ErrorCode::BadCurve, 2 + n));
                        }
                        t
                    }
                    _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
                };
                Command::Transfer { channels, curve }
            }
            "map" => {
                let (m, at) = w.need()?;
                Command::Map(match m {
                    "clip" => GamutMap::Clip,
                    "desaturate" => GamutMap::Desaturate,
                    _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
                })
            }
            "observer" => {
                let (o, at) = w.need()?;
                Command::Observer(match o {
                    "1931" => Observer::Cie1931,
                    "1964" => Observer::Cie1964,
                    _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
                })
            }
            "xyz" => {
                let x = w.number()?;
                let y = w.number()?;
                let z = w.number()?;
                Command::Xyz(Xyz::new(x, y, z))
            }
            "xyy" => {
                let mut v = [0.0; 3];
                for (i, o) in v.iter_mut().enumerate() {
                    let (tok, at) = w.need()?;
                    *o = number(tok, at)?;
                    let ok = match i {
                        0 => (0.0..=1.0).contains(o),
                        1 => *o > 0.0 && *o <= 1.0,
                        _ => true,
                    };
                    if !ok {
                        return Err(Fault::at(ErrorCode::OutOfRange, at));
                    }
                }
                Command::Xyy(Xyy {
                    x: v[0],
                    y: v[1],
                    big_y: v[2],
                })
            }
            "refl" => {
                let (preset, at) = w.need()?;
                let paper = match preset {
                    "paper" => true,
                    "default" => false,
                    _ => return Err(Fault::at(ErrorCode::UnknownName, at)),
                };
                let (ill, at) = w.need()?;
                let illuminant =
                    Illuminant::from_name(ill).ok_or(Fault::at(ErrorCode::UnknownName, at))?;
                // the reply's number form follows the first coefficient's
                let hex = w.peek().is_some_and(|t| t.starts_with("0x"));
                let (product, factors) = if paper {
                    let (p, n) = read_product(&mut w, specpoly_kernels::mul_paper)?;
                    (Reflectance::Paper(p), n)
                } else {
                    let (p, n) = read_product(&mut w, specpoly_kernels::mul_default)?;
                    (Reflectance::Default(p), n)
                };
                Command::Reflect {
                    illuminant,
                    product,
                    factors,
                    hex,
                }
            }
            // without feature `mix` (a firmware without mixing) these are unknown commands
            #[cfg(feature = "mix")]
            "channel" => Command::Channel(crate::mix::parse_channel(&mut w)?),
            #[cfg(feature = "mix")]
            "xy" => Command::Mix(crate::mix::parse_goal(&mut w, false)?),
            #[cfg(feature = "mix")]
            "cct" => Command::Mix(crate::mix::parse_goal(&mut w, true)?),
            #[cfg(feature = "mix")]
            "fade" => Command::Fade(crate::mix::parse_fade(&mut w)?),
            #[cfg(feature = "lut")]
            "lut" => Command::Lut(crate::lut::parse(&mut w)?),
            _ => return Err(Fault::at(ErrorCode::UnknownCommand, 0)),
        };
        w.end()?;
        Ok(cmd)
    }

    /// Writes the command line (no newline). [`Command::Reflect`] is written as its product,
    /// one factor; use [`write_reflect`] to send the factors themselves.
    pub fn write<W: Write>(&self, w: &mut W) -> fmt::Result {
        match self {
            Command::Hello => w.write_str("hello"),
            Command::State => w.write_str("state"),
            Command::Save => w.write_str("save"),
            Command::Load => w.write_str("load"),
            Command::Calibrate { xy, luminance } => {
                w.write_str("cal")?;
                for i in 0..3 {
                    for v in [xy[i][0], xy[i][1], luminance[i]] {
                        w.write_char(' ')?;
                        write_f32(w, v)?;
                    }
                }
                Ok(())
            }
            Command::Transfer { channels, curve } => {
                w.write_str("trc ")?;
                w.write_str(channels.name())?;
                w.write_char(' ')?;
                write_curve(w, curve, ' ')
            }
            Command::Map(m) => {
                w.write_str("map ")?;
                w.write_str(map_name(*m))
            }
            Command::Observer(o) => {
                w.write_str("observer ")?;
                w.write_str(o.name())
            }
            Command::Xyz(v) => {
                w.write_str("xyz")?;
                for c in v.to_array() {
                    w.write_char(' ')?;
                    write_f32(w, c)?;
                }
                Ok(())
            }
            Command::Xyy(v) => {
                w.write_str("xyy")?;
                for c in [v.x, v.y, v.big_y] {
                    w.write_char(' ')?;
                    write_f32(w, c)?;
                }
                Ok(())
            }
            Command::Reflect {
                illuminant,
                product,
                hex: false,
                ..
            } => write_reflect(w, *illuminant, core::slice::from_ref(product)),
            Command::Reflect {
                illuminant,
                product,
                hex: true,
                ..
            } => write_reflect_hex(w, *illuminant, core::slice::from_ref(product)),
            Command::Channel(c) => crate::mix::write_channel(w, c),
            Command::Mix(g) => crate::mix::write_goal(w, g),
            Command::Fade(ms) => crate::mix::write_fade(w, *ms),
            Command::Lut(c) => c.write(w),
        }
    }
}

/// Reads `S·C` coefficients per factor, factors separated by `*`, folding them with the
/// reduced product `mul` (the preset's [`Spectrum::mul`] from `specpoly-kernels`). Coefficients
/// are span by span, each span's `c₀ … c_{C−1}`.
fn read_product<const S: usize, const C: usize, L: Layout<S>>(
    w: &mut Words<'_>,
    mul: fn(&Spectrum<S, C, L>, &Spectrum<S, C, L>) -> Spectrum<S, C, L>,
) -> Result<(Spectrum<S, C, L>, u8), Fault> {
    let mut product = Spectrum::<S, C, L>::ZERO;
    let mut f = Spectrum::<S, C, L>::ZERO;
    let mut factors = 0u8;
    loop {
        // one call site: the reader is inlined once per preset; the first factor is read into
        // the product itself
        let into = if factors == 0 { &mut product } else { &mut f };
        w.coefficients(S * C, |i, v| into.coefficients_mut()[i % C][i / C] = v)?;
        if factors > 0 {
            product = mul(&product, &f);
        }
        factors += 1;
        match w.next() {
            None => break,
            Some(("*", at)) => {
                if factors as usize >= MAX_FACTORS {
                    return Err(Fault::at(ErrorCode::WrongCount, at));
                }
            }
            Some((_, at)) => return Err(Fault::at(ErrorCode::WrongCount, at)),
        }
    }
    // A product that overflows f32 (finite factors near `f32::MAX`) is refused here, as the
    // colour it would give is: it could not be written back as numbers.
    if !product
        .coefficients()
        .iter()
        .flatten()
        .all(|c| c.is_finite())
    {
        return Err(Fault::new(ErrorCode::NotFinite));
    }
    Ok((product, factors))
}

/// Writes `refl PRESET ILLUMINANT c… * c… …` for the product of `factors` (at least one, all
/// of one preset, at most [`MAX_FACTORS`]).
pub fn write_reflect<W: Write>(
    w: &mut W,
    illuminant: Illuminant,
    factors: &[Reflectance],
) -> fmt::Result {
    write_reflect_with(w, illuminant, factors, write_f32)
}

/// [`write_reflect`] with the coefficients in the compact form `0x` + 8 hexadecimal digits
/// (each f32's bit pattern, `firmware/PROTOCOL.md`): exact, and cheaper for the controller to
/// read than shortest decimals (the word handling around each number stays the same).
pub fn write_reflect_hex<W: Write>(
    w: &mut W,
    illuminant: Illuminant,
    factors: &[Reflectance],
) -> fmt::Result {
    write_reflect_with(w, illuminant, factors, write_f32_hex)
}

fn write_reflect_with<W: Write>(
    w: &mut W,
    illuminant: Illuminant,
    factors: &[Reflectance],
    num: NumberWriter<W>,
) -> fmt::Result {
    let first = factors.first().ok_or(fmt::Error)?;
    if factors.len() > MAX_FACTORS || factors.iter().any(|f| f.preset() != first.preset()) {
        return Err(fmt::Error);
    }
    w.write_str("refl ")?;
    w.write_str(first.preset())?;
    w.write_char(' ')?;
    w.write_str(illuminant.name())?;
    for (i, f) in factors.iter().enumerate() {
        w.write_str(if i == 0 { " " } else { " * " })?;
        f.write_coefficients_with(w, num)?;
    }
    Ok(())
}
