//! `specpoly led`: drive the RGB-LED controller firmware over a serial port.
//!
//! Settings given as options are sent first (`cal`, `trc`, `map`, `observer`), then the action;
//! the controller's reply line is printed. `--check` also computes the answer on the host in f64
//! ([`specpoly_led::check`]) and fails if the device disagrees.
//!
//! The LED's calibration comes from a calibration file written by `specpoly calibrate`
//! (`--calibration`: its primaries and transfer curves; the controller's model has no black
//! offset, an LED's black being zero) or from the command line (`--primaries`, `--trc`).

use crate::cli::args::{self, Curve, Gamut};
use crate::error::{CliError, Result};
use specpoly_core::light::channels::{Curve as ChannelCurve, Goal};
use specpoly_core::light::Source;
use specpoly_core::{Illuminant, Observer, Transfer};
use specpoly_display::spec::DisplaySpec;
use specpoly_formats::stdout::{print, print_json};
use specpoly_led::lines::{self, line, reply_line, Preset};
use specpoly_led::mix_check::{MixOracle, Weight};
use specpoly_led::table::{Correction, TABLE_DE};
use specpoly_led::{Link, Oracle};
use specpoly_protocol::number::write_f32;
use specpoly_protocol::{Channels, Command, MixReport, Reply, MIX_CHANNELS};
use specpoly_spectra::light::load_channel;
use std::time::Duration;

/// Arguments of `specpoly led`.
#[derive(Debug, clap::Args)]
pub struct LedArgs {
    /// Serial port of the controller (e.g. /dev/ttyUSB0, or the /dev/pts/N QEMU prints).
    #[arg(long)]
    pub port: String,
    /// How long to wait for each reply, in milliseconds (1 to 86 400 000, a day).
    #[arg(long, default_value_t = 3000, value_parser = clap::value_parser!(u64).range(1..=86_400_000))]
    pub timeout_ms: u64,
    /// A calibration file from `specpoly calibrate` (TOML): sends its primaries and its
    /// per-channel transfer curves.
    #[arg(long, conflicts_with_all = ["primaries", "trc"])]
    pub calibration: Option<std::path::PathBuf>,
    /// The LED's primaries: `xr,yr,Yr,xg,yg,Yg,xb,yb,Yb` (chromaticities and luminances at
    /// full drive, e.g. from a spectroradiometer).
    #[arg(long, allow_hyphen_values = true)]
    pub primaries: Option<String>,
    /// The channels' transfer curve: `linear` (PWM), `srgb` or `gamma:G`.
    #[arg(long, value_parser = args::transfer)]
    pub trc: Option<Curve>,
    /// Gamut mapping for colours the LED cannot show.
    #[arg(long, value_enum)]
    pub map: Option<Gamut>,
    /// Observer for reflectances: `1931` or `1964` (the latter needs a firmware built with
    /// feature `observer-1964`).
    #[arg(long, value_name = "1931|1964", value_parser = args::device_observer)]
    pub observer: Option<Observer>,
    /// A mixing channel: NAME=FILE.csv[#COLUMN], its SPD at full drive; 3 to 6 of them, in
    /// order. Uploaded as `channel` lines (its XYZ from the SPD at 1 nm) before the action.
    #[arg(long = "channel", value_name = "NAME=FILE.csv[#COLUMN]")]
    pub channels: Vec<String>,
    /// With more than three channels: what the device spends the freedom on (the weights
    /// uploaded with the channels): least total drive, or greatest luminous efficacy.
    #[arg(long, value_enum, default_value = "power")]
    pub optimize: WeightArg,
    /// Fade time for new `xy`/`cct` targets, ms (0 to 600000).
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u32).range(0..=600_000))]
    pub fade: Option<u32>,
    /// Recompute the answer on the host (an independent f64 computation) and fail unless the
    /// controller agrees within the tolerance table of `specpoly::led::check`. May stand before
    /// or after the action (`led --port P refl colorchecker#red --check`).
    #[arg(long, global = true)]
    pub check: bool,
    /// Print the reply (and the check) as JSON: `reply` (the kind: `colour`, `state`, `hello`,
    /// a setting, `err`), the reply's values under their protocol names, `line` (the reply as
    /// sent), and `check` (`agrees`, `detail`) with `--check`. May follow the action.
    #[arg(long, global = true)]
    pub json: bool,
    /// What to show or ask.
    #[command(subcommand)]
    pub action: LedAction,
}

/// `--optimize`: [`Weight`] as the command line spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum WeightArg {
    /// Least total drive `Σ dᵢ` (weights 1).
    Power,
    /// Greatest luminous efficacy of radiation (weights: each channel's radiant power).
    Efficacy,
}

impl From<WeightArg> for Weight {
    fn from(w: WeightArg) -> Weight {
        match w {
            WeightArg::Power => Weight::Power,
            WeightArg::Efficacy => Weight::Efficacy,
        }
    }
}

/// `refl --repr`: [`Preset`] as the command line spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PresetArg {
    /// 8 uniform cubic spans (32 coefficients), the project default.
    #[value(alias = "default")]
    Poly,
    /// The paper's 2 cubic spans split at 550 nm.
    Paper,
}

impl From<PresetArg> for Preset {
    fn from(p: PresetArg) -> Preset {
        match p {
            PresetArg::Poly => Preset::Poly,
            PresetArg::Paper => Preset::Paper,
        }
    }
}

/// What `specpoly led` does after the settings.
#[derive(Debug, clap::Subcommand)]
pub enum LedAction {
    /// Show a colour given as XYZ, relative to the LED's white at Y = 100.
    #[command(allow_negative_numbers = true)]
    Xyz {
        /// X
        x: f32,
        /// Y
        y: f32,
        /// Z
        z: f32,
    },
    /// Show a colour given as chromaticity x, y and relative luminance Y (white = 100).
    Xyy {
        /// x
        x: f32,
        /// y
        y: f32,
        /// Y
        big_y: f32,
    },
    /// Show the colour of a reflectance (or the product of up to 4) under a built-in light.
    Refl {
        /// Representation sent: `poly` (8 cubic spans, 32 coefficients) or `paper` (2 spans).
        #[arg(long, value_enum, default_value_t = PresetArg::Poly)]
        repr: PresetArg,
        /// Built-in illuminant: A D50 D65 E FL2 FL7 FL11.
        #[arg(long, default_value = "D65", value_parser = args::builtin_illuminant)]
        illuminant: Illuminant,
        /// Reflectances (names as in `specpoly xyz`, e.g. colorchecker#red); several are
        /// multiplied.
        #[arg(required = true)]
        spectra: Vec<String>,
        /// Send the coefficients in the compact form (`0x` + the f32's 8 hex digits): exact,
        /// and fewer instructions for the controller to read.
        #[arg(long)]
        hex: bool,
    },
    /// Mix the channels (--channel) to a chromaticity x, y on the device.
    Xy {
        /// x (CIE 1931)
        x: f32,
        /// y
        y: f32,
        /// Relative luminance: the fraction of the most the channels give there (0 to 1).
        #[arg(long, default_value_t = 1.0)]
        lum: f32,
    },
    /// Mix the channels (--channel) to a correlated colour temperature on the device.
    Cct {
        /// CCT, K (1000 to 25000)
        k: f32,
        /// Distance from the Planckian locus (|duv| ≤ 0.05, positive above)
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        duv: f32,
        /// Relative luminance (0 to 1).
        #[arg(long, default_value_t = 1.0)]
        lum: f32,
    },
    /// Print the controller's calibration and duties.
    State,
    /// Print the controller's protocol version and limits.
    Hello,
    /// Send one raw protocol line and print the reply.
    Raw {
        /// The line, e.g. "xyz 20 20 20".
        line: String,
    },
}

/// Checks a colour reply against the host's computation from the controller's `state`, with
/// the transfer curves of `curves` (a calibration file just sent) when `state` only names
/// their size (tables). `Some(detail)` when the host agrees, `None` when there is nothing to
/// check.
fn check(
    link: &mut Link<Box<dyn serialport::SerialPort>>,
    sent: &str,
    got: &Reply,
    curves: Option<[Transfer; 3]>,
    mix: Option<&MixOracle>,
    table: Option<&Correction>,
) -> Result<Option<String>> {
    let dev = match got {
        Reply::Colour(dev) => dev,
        Reply::Mix(r) => return check_mix(sent, r, mix).map(Some),
        _ => return Ok(None),
    };
    let state = match link.send("state")? {
        Reply::State(s) => s,
        other => {
            return Err(CliError::data(format!(
                "unexpected reply to state: `{}`",
                reply_line(&other)
            )))
        }
    };
    let oracle = Oracle::from_state(&state, curves.as_ref()).ok_or_else(|| {
        CliError::data("--check needs the tabulated curves: give them with --calibration")
    })?;
    let Ok(cmd) = Command::parse(sent) else {
        return Ok(None);
    };
    if oracle.target(&cmd).is_none() {
        return Ok(None);
    }
    if let Some(t) = table {
        return check_table(&oracle, &cmd, dev, t).map(Some);
    }
    match oracle.verify(&cmd, dev) {
        Ok(a) => {
            let mut s = String::new();
            let _ = write_f32(&mut s, a.xyz() as f32);
            Ok(Some(format!(
                "the host agrees (|ΔXYZ| ≤ {s}, |Δduty| ≤ {})",
                a.duty
            )))
        }
        Err(d) => Err(CliError::data(format!(
            "the controller disagrees with the host: {d}"
        ))),
    }
}

/// Checks a mix reply against the host's f64 computation from the channels' spectra.
/// `--check` of a controller holding the drive-correction table: the target, linear drive and
/// gamut verdict against the f64 reference (the table leaves them the matrix model's), and the
/// full model's emission at the duties against the target within the table's bound
/// ([`TABLE_DE`]).
fn check_table(
    oracle: &Oracle,
    cmd: &Command,
    dev: &specpoly_protocol::ColourReport,
    t: &Correction,
) -> Result<String> {
    oracle
        .verify_matrix_part(cmd, dev)
        .map_err(|d| CliError::data(format!("the controller disagrees with the host: {d}")))?;
    match t.miss(dev.xyz, dev.duty, dev.max) {
        Some(de) if de <= TABLE_DE => Ok(format!(
            "the host agrees (full model at the duties: ΔE00 {de:.3} ≤ {TABLE_DE})"
        )),
        Some(de) => Err(CliError::data(format!(
            "the controller disagrees with the host: the full model at duty {:?} is ΔE00 {de:.3} from the target (bound {TABLE_DE})",
            dev.duty
        ))),
        None => Ok(
            "the host agrees on the target; the colour is outside the full model's gamut (duties not checked)"
                .to_owned(),
        ),
    }
}

fn check_mix(sent: &str, r: &MixReport, oracle: Option<&MixOracle>) -> Result<String> {
    let oracle =
        oracle.ok_or_else(|| CliError::usage("--check of a mix needs its --channel spectra"))?;
    let Ok(Command::Mix(goal)) = Command::parse(sent) else {
        return Err(CliError::usage(format!("`{sent}` is not a mix target")));
    };
    match oracle.verify(&goal, r) {
        Ok(a) => Ok(format!(
            "the host agrees (Δu′v′ {:.1e} before, {:.1e} after quantisation)",
            a.chromaticity, a.quantised
        )),
        Err(d) => Err(CliError::data(format!(
            "the controller disagrees with the host: {d}"
        ))),
    }
}

/// The mixing channels of `--channel`, with the weights of `--optimize`.
fn mix_oracle(channels: &[String], weight: Weight) -> Result<MixOracle> {
    if !(3..=MIX_CHANNELS).contains(&channels.len()) {
        return Err(CliError::usage(format!(
            "{} channels: the controller mixes 3 to {MIX_CHANNELS} --channel NAME=FILE.csv[#COLUMN]",
            channels.len()
        )));
    }
    let mut sources = Vec::new();
    for c in channels {
        let ch = load_channel(c)?;
        sources.push(
            Source::new(&ch.spd.tabulated())
                .map_err(|e| CliError::data(format!("{}: {e}", ch.name)))?,
        );
    }
    let curves = vec![ChannelCurve::Linear; sources.len()];
    Ok(MixOracle::new(sources, curves, weight))
}

/// Runs `specpoly led`.
pub fn run(args: &LedArgs) -> Result<()> {
    // build every line first: usage errors before touching the device
    let mut settings = Vec::new();
    let mut table = None;
    let calibration = args
        .calibration
        .as_deref()
        .map(DisplaySpec::open_measured)
        .transpose()?;
    if let Some(spec) = &calibration {
        settings.extend(lines::calibration(spec)?);
        // the interaction lattice as a drive-correction table, after `cal` and `trc`: the
        // controller binds it to the calibration it then holds
        table = lines::calibration_table(spec)?;
        if let Some(t) = &table {
            settings.extend(t.table.commands().iter().map(line));
        }
    }
    if let Some(p) = &args.primaries {
        settings.push(line(&lines::primaries(p)?));
    }
    if let Some(curve) = args.trc {
        settings.push(line(&Command::Transfer {
            channels: Channels::All,
            curve: curve.into(),
        }));
    }
    if let Some(m) = args.map {
        settings.push(line(&Command::Map(m.into())));
    }
    if let Some(o) = args.observer {
        settings.push(line(&Command::Observer(o)));
    }
    let mix = if args.channels.is_empty() {
        None
    } else {
        let oracle = mix_oracle(&args.channels, args.optimize.into())?;
        settings.extend(oracle.commands().iter().map(line));
        Some(oracle)
    };
    if let Some(ms) = args.fade {
        settings.push(line(&Command::Fade(ms)));
    }
    let action = match &args.action {
        LedAction::Xyz { x, y, z } => line(&Command::Xyz(specpoly_core::Xyz::new(*x, *y, *z))),
        LedAction::Xyy { x, y, big_y } => {
            let l = line(&Command::Xyy(specpoly_core::Xyy {
                x: *x,
                y: *y,
                big_y: *big_y,
            }));
            Command::parse(&l).map_err(|f| CliError::usage(format!("xyy: {f}")))?;
            l
        }
        LedAction::Refl {
            repr,
            illuminant,
            spectra,
            hex: false,
        } => lines::refl((*repr).into(), *illuminant, spectra)?,
        LedAction::Refl {
            repr,
            illuminant,
            spectra,
            hex: true,
        } => lines::refl_hex((*repr).into(), *illuminant, spectra)?,
        LedAction::Xy { x, y, lum } => goal(Goal::Xy {
            xy: [*x, *y],
            lum: *lum,
        })?,
        LedAction::Cct { k, duv, lum } => goal(Goal::Cct {
            cct: *k,
            duv: *duv,
            lum: *lum,
        })?,
        LedAction::State => "state".to_owned(),
        LedAction::Hello => "hello".to_owned(),
        LedAction::Raw { line } => line.clone(),
    };

    let mut link = Link::open(&args.port, Duration::from_millis(args.timeout_ms))?;
    link.hello()?;
    for s in &settings {
        link.send(s)?;
    }
    let reply = link.send(&action)?;
    if !args.json {
        print(&format!("{}\n", reply_line(&reply)))?;
    }
    let mut agreed = None;
    if args.check {
        let curves = calibration
            .as_ref()
            .map(|spec| spec.display().transfer().clone());
        agreed = check(
            &mut link,
            &action,
            &reply,
            curves,
            mix.as_ref(),
            table.as_ref(),
        )?;
    }
    if args.json {
        let mut v = reply_json(&reply);
        if args.check {
            v["check"] = serde_json::json!({"agrees": true, "detail": agreed});
        }
        return Ok(print_json(&v)?);
    }
    if let Some(d) = agreed {
        print(&format!("check: {d}\n"))?;
    }
    Ok(())
}

/// The line of a mix target, checked by the controller's own parser before anything is sent.
fn goal(g: Goal) -> Result<String> {
    let l = line(&Command::Mix(g));
    Command::parse(&l).map_err(|f| CliError::usage(format!("{l}: {f}")))?;
    Ok(l)
}

/// A reply as JSON: `reply` (its kind), `line` (the reply as sent) and its values under the
/// protocol's key names (firmware/PROTOCOL.md), numbers as numbers.
pub fn reply_json(r: &Reply) -> serde_json::Value {
    use serde_json::json;
    let line = reply_line(r);
    let mut v = match r {
        Reply::Hello {
            protocol,
            max_line,
            max,
        } => json!({"reply": "hello", "protocol": protocol, "max_line": max_line, "max": max}),
        Reply::Done(what) => json!({"reply": what}),
        Reply::Colour(c) => json!({
            "reply": "colour",
            "xyz": c.xyz.to_array(),
            "led": c.led.to_array(),
            "linear": c.linear,
            "duty": c.duty,
            "max": c.max,
            "gamut": match c.gamut {
                specpoly_protocol::Gamut::In => "in".to_string(),
                specpoly_protocol::Gamut::Out(m) =>
                    format!("out:{}", specpoly_protocol::command::map_name(m)),
            },
        }),
        Reply::State(s) => {
            // the state line's own words for the curves, map and observer
            let word = |key: &str| {
                line.split_whitespace()
                    .find_map(|t| t.strip_prefix(key))
                    .unwrap_or_default()
                    .to_string()
            };
            json!({
                "reply": "state",
                "protocol": s.protocol,
                "primaries": s.primaries,
                "trc": word("trc=").split(',').collect::<Vec<_>>(),
                "map": word("map="),
                "observer": word("observer="),
                "duty": s.duty,
                "max": s.max,
            })
        }
        Reply::Mix(m) => json!({
            "reply": "mix",
            "xy": m.xy,
            "lum": m.lum,
            "light": m.light(),
            "duty": m.duty(),
            "max": m.max,
            "steps": m.steps,
        }),
        Reply::Error(f) => json!({"reply": "err", "code": f.code.name(), "at": f.at}),
    };
    v["line"] = json!(line);
    v
}

#[cfg(test)]
mod tests {
    use crate::cli::{Cli, Command};
    use clap::Parser;

    /// Whether `specpoly led --port /dev/null WORDS…` asks for `--check`.
    fn checks(words: &str) -> bool {
        let args = ["specpoly", "led", "--port", "/dev/null"]
            .into_iter()
            .chain(words.split_whitespace());
        match Cli::try_parse_from(args).expect("parses").command {
            Command::Led(led) => led.check,
            other => panic!("not led: {other:?}"),
        }
    }

    /// The README's form: `--check` after the action's own arguments.
    #[test]
    fn check_may_follow_the_action() {
        assert!(checks("refl colorchecker#red --illuminant FL11 --check"));
        assert!(checks("--check refl colorchecker#red"));
        assert!(!checks("refl colorchecker#red"));
    }
}
