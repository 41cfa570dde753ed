//! `specpoly led`: drive the RGB-LED controller firmware over a serial port.
//!
//! Settings given as options are sent first (`cal`, `trc`, `map`, `observer`), then the action;
//! the controller's reply line is printed. `--check` also computes the answer on the host in f64
//! ([`crate::led::check`]) and fails if the device disagrees.
//!
//! The LED's calibration comes from a calibration file written by `specpoly calibrate`
//! (`--calibration`: its primaries and transfer curves; the controller's model has no black
//! offset, an LED's black being zero) or from the command line (`--primaries`, `--trc`).

use crate::error::{CliError, Result};
use crate::led::{Link, Oracle};
use crate::spectra;
use specpoly_core::{DefaultSpectrum, Illuminant, PaperSpectrum, Transfer};
use specpoly_protocol::number::{parse_f32, write_f32};
use specpoly_protocol::{write_reflect, Channels, Command, Reflectance, Reply, MAX_FACTORS};
use std::time::Duration;

/// Arguments of `specpoly led`.
#[derive(Debug, clap::Args)]
pub struct LedArgs {
    /// Serial port of the controller (e.g. /dev/ttyUSB0, or the /dev/pts/N QEMU prints).
    #[arg(long)]
    pub port: String,
    /// How long to wait for each reply, in milliseconds.
    #[arg(long, default_value_t = 3000)]
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
    #[arg(long)]
    pub trc: Option<String>,
    /// Gamut mapping for colours the LED cannot show: `clip` or `desaturate`.
    #[arg(long)]
    pub map: Option<String>,
    /// Observer for reflectances: `1931` or `1964` (the latter needs a firmware built with
    /// feature `observer-1964`).
    #[arg(long)]
    pub observer: Option<String>,
    /// Recompute the answer on the host (an independent f64 computation) and fail unless the
    /// controller agrees within the tolerance table of `specpoly::led::check`.
    #[arg(long)]
    pub check: bool,
    /// What to show or ask.
    #[command(subcommand)]
    pub action: LedAction,
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
        #[arg(long, default_value = "poly")]
        repr: String,
        /// Built-in illuminant: A D50 D65 E FL2 FL7 FL11.
        #[arg(long, default_value = "D65")]
        illuminant: String,
        /// Reflectances (names as in `specpoly xyz`, e.g. colorchecker#red); several are
        /// multiplied.
        #[arg(required = true)]
        spectra: Vec<String>,
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

fn line_of(c: &Command) -> String {
    let mut s = String::new();
    // writing to a String cannot fail
    let _ = c.write(&mut s);
    s
}

fn reply_line(r: &Reply) -> String {
    let mut s = String::new();
    let _ = r.write(&mut s);
    s
}

/// The `cal` command from `--primaries`.
pub fn primaries_command(s: &str) -> Result<Command> {
    let v: Vec<f32> = s
        .split(',')
        .map(|t| {
            parse_f32(t.trim())
                .map_err(|_| CliError::usage(format!("--primaries: `{t}` is not a number")))
        })
        .collect::<Result<_>>()?;
    if v.len() != 9 {
        return Err(CliError::usage(format!(
            "--primaries takes 9 numbers (xr,yr,Yr,xg,yg,Yg,xb,yb,Yb), got {}",
            v.len()
        )));
    }
    let c = Command::Calibrate {
        xy: [[v[0], v[1]], [v[3], v[4]], [v[6], v[7]]],
        luminance: [v[2], v[5], v[8]],
    };
    // the controller's own checks, before anything is sent
    Command::parse(&line_of(&c))
        .map_err(|f| CliError::usage(format!("--primaries: {f} (number {:?})", f.at)))
}

/// The `cal` and three `trc` lines of a calibration file.
pub fn calibration_lines(path: &std::path::Path) -> Result<Vec<String>> {
    let display = crate::calibrate::file::load_display(path)?;
    let (xy, luminance) = display.primaries();
    let mut lines = vec![line_of(&Command::Calibrate { xy, luminance })];
    for (channels, curve) in [Channels::Red, Channels::Green, Channels::Blue]
        .into_iter()
        .zip(display.transfer().iter())
    {
        lines.push(line_of(&Command::Transfer {
            channels,
            curve: curve.clone(),
        }));
    }
    for l in &lines {
        // the controller's own checks (ranges, line length), before anything is sent
        if l.len() > specpoly_protocol::MAX_LINE {
            return Err(CliError::data(format!(
                "{}: a curve does not fit one protocol line",
                path.display()
            )));
        }
        Command::parse(l).map_err(|f| {
            CliError::data(format!(
                "{}: not a usable LED calibration: {f}",
                path.display()
            ))
        })?;
    }
    Ok(lines)
}

/// The `trc rgb …` command from `--trc`.
pub fn trc_command(s: &str) -> Result<Command> {
    let curve = match s.split_once(':') {
        None if s == "linear" => Transfer::Linear,
        None if s == "srgb" => Transfer::Srgb,
        Some(("gamma", g)) => match parse_f32(g) {
            Ok(g) if (0.1..=10.0).contains(&g) => Transfer::Gamma(g),
            _ => return Err(CliError::usage(format!("--trc: bad gamma `{g}`"))),
        },
        _ => {
            return Err(CliError::usage(format!(
                "--trc: `{s}` is not linear, srgb or gamma:G"
            )))
        }
    };
    Ok(Command::Transfer {
        channels: Channels::All,
        curve,
    })
}

/// The `refl` line for named reflectances, fitted in the chosen representation.
pub fn refl_line(repr: &str, illuminant: &str, names: &[String]) -> Result<String> {
    let ill = Illuminant::from_name(illuminant).ok_or_else(|| {
        CliError::usage(format!(
            "unknown illuminant `{illuminant}` (built in: A D50 D65 E FL2 FL7 FL11)"
        ))
    })?;
    let named = spectra::resolve_all(names)?;
    if named.is_empty() || named.len() > MAX_FACTORS {
        return Err(CliError::usage(format!(
            "refl takes 1 to {MAX_FACTORS} reflectances, got {}",
            named.len()
        )));
    }
    let mut factors = Vec::new();
    for n in &named {
        let t = n.tabulated();
        let fit_err = |e| CliError::data(format!("{}: cannot fit: {e}", n.short()));
        factors.push(match repr {
            "paper" => Reflectance::Paper(PaperSpectrum::fit(&t).map_err(fit_err)?),
            "poly" | "default" => Reflectance::Default(DefaultSpectrum::fit(&t).map_err(fit_err)?),
            other => {
                return Err(CliError::usage(format!(
                    "--repr: `{other}` is not poly or paper (the controller's presets)"
                )))
            }
        });
    }
    let mut line = String::new();
    write_reflect(&mut line, ill, &factors)
        .map_err(|_| CliError::usage("cannot write the refl command"))?;
    Ok(line)
}

/// Checks a colour reply against the host's computation from the controller's `state`, with
/// the transfer curves of `curves` (a calibration file just sent) when `state` only names
/// their size (tables).
fn check(
    link: &mut Link<Box<dyn serialport::SerialPort>>,
    sent: &str,
    got: &Reply,
    curves: Option<[Transfer; 3]>,
) -> Result<()> {
    let Reply::Colour(dev) = got else {
        return Ok(());
    };
    let dev_err = |e: crate::led::LedError| CliError::data(e.to_string());
    let state = match link.send("state").map_err(dev_err)? {
        Reply::State(s) => s,
        other => {
            return Err(CliError::data(format!(
                "unexpected reply to state: {other:?}"
            )))
        }
    };
    let oracle = Oracle::from_state(&state, curves.as_ref()).ok_or_else(|| {
        CliError::data("--check needs the tabulated curves: give them with --calibration")
    })?;
    let Ok(cmd) = Command::parse(sent) else {
        return Ok(());
    };
    if oracle.target(&cmd).is_none() {
        return Ok(());
    }
    match oracle.verify(&cmd, dev) {
        Ok(a) => {
            let mut s = String::new();
            let _ = write_f32(&mut s, a.xyz() as f32);
            println!(
                "check: the host agrees (|ΔXYZ| ≤ {s}, |Δduty| ≤ {})",
                a.duty
            );
            Ok(())
        }
        Err(d) => Err(CliError::data(format!(
            "the controller disagrees with the host: {d}"
        ))),
    }
}

/// Runs `specpoly led`.
pub fn run(args: &LedArgs) -> Result<()> {
    // build every line first: usage errors before touching the device
    let mut settings = Vec::new();
    if let Some(path) = &args.calibration {
        settings.extend(calibration_lines(path)?);
    }
    if let Some(p) = &args.primaries {
        settings.push(line_of(&primaries_command(p)?));
    }
    if let Some(t) = &args.trc {
        settings.push(line_of(&trc_command(t)?));
    }
    if let Some(m) = &args.map {
        if m != "clip" && m != "desaturate" {
            return Err(CliError::usage(format!(
                "--map: `{m}` is not clip or desaturate"
            )));
        }
        settings.push(format!("map {m}"));
    }
    if let Some(o) = &args.observer {
        if o != "1931" && o != "1964" {
            return Err(CliError::usage(format!(
                "--observer: `{o}` is not 1931 or 1964"
            )));
        }
        settings.push(format!("observer {o}"));
    }
    let action = match &args.action {
        LedAction::Xyz { x, y, z } => line_of(&Command::Xyz(specpoly_core::Xyz::new(*x, *y, *z))),
        LedAction::Xyy { x, y, big_y } => {
            let l = line_of(&Command::Xyy(specpoly_core::Xyy {
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
        } => refl_line(repr, illuminant, spectra)?,
        LedAction::State => "state".to_owned(),
        LedAction::Hello => "hello".to_owned(),
        LedAction::Raw { line } => line.clone(),
    };

    let dev_err = |e: crate::led::LedError| CliError::data(e.to_string());
    let mut link =
        Link::open(&args.port, Duration::from_millis(args.timeout_ms)).map_err(dev_err)?;
    link.hello().map_err(dev_err)?;
    for s in &settings {
        link.send(s).map_err(dev_err)?;
    }
    let reply = link.send(&action).map_err(dev_err)?;
    println!("{}", reply_line(&reply));
    if args.check {
        let curves = match &args.calibration {
            Some(path) => Some(
                crate::calibrate::file::load_display(path)?
                    .transfer()
                    .clone(),
            ),
            None => None,
        };
        check(&mut link, &action, &reply, curves)?;
    }
    Ok(())
}
