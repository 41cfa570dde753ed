//! `specpoly mix`: PWM duties of 3–6 LED channels for a chromaticity or CCT target
//! (computations in [`specpoly_spectra::light`] and `specpoly_core::light::mix`).

use crate::cli::args::{transfer, Curve};
use crate::cli::light::{chromaticity_cells, chromaticity_head, opt};
use crate::error::{CliError, Result};
use specpoly_core::light::Target;
use specpoly_formats::stdout::print_json;
use specpoly_spectra::light::{self, describe, load_channel, parse_target};
use std::fmt::Write as _;

fn luminance(s: &str) -> std::result::Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 1.0 => Ok(v),
        _ => Err(format!(
            "`{s}`: the relative luminance is a number in (0, 1]"
        )),
    }
}

/// What the freedom of more than three channels is spent on (`--optimize`; the command line's
/// spelling of [`light::Optimize`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Optimize {
    /// Greatest CIE 224:2017 fidelity Rf.
    Rf,
    /// Greatest CIE 13.3 Ra.
    Ra,
    /// Greatest luminous efficacy of radiation.
    Efficacy,
    /// Least total drive.
    Power,
}

impl From<Optimize> for light::Optimize {
    fn from(o: Optimize) -> Self {
        match o {
            Optimize::Rf => light::Optimize::Rf,
            Optimize::Ra => light::Optimize::Ra,
            Optimize::Efficacy => light::Optimize::Efficacy,
            Optimize::Power => light::Optimize::Power,
        }
    }
}

/// Arguments of `specpoly mix`.
#[derive(Debug, clap::Args)]
pub struct MixArgs {
    /// A channel: NAME=FILE.csv[#COLUMN], its SPD at full drive; 3 to 6 of them, in order.
    #[arg(
        long = "channel",
        required = true,
        value_name = "NAME=FILE.csv[#COLUMN]"
    )]
    pub channels: Vec<String>,
    /// The target: xy:X,Y (CIE 1931), cct:K or cct:K,duv:D (Planckian locus, ANSI Duv offset).
    #[arg(long, value_parser = parse_target, value_name = "xy:X,Y|cct:K[,duv:D]")]
    pub target: Target,
    /// Relative luminance: the fraction of the most the channels give at that chromaticity.
    #[arg(long, default_value = "1", value_parser = luminance, value_name = "0..1")]
    pub luminance: f64,
    /// With more than three channels: what the free duties maximise (rf, ra, efficacy) or
    /// minimise (power: the sum of duties).
    #[arg(long, value_enum, default_value = "rf")]
    pub optimize: Optimize,
    /// The channels' response, device value → light: linear (PWM), srgb or gamma:G.
    #[arg(long, default_value = "linear", value_parser = transfer, value_name = "linear|srgb|gamma:G")]
    pub trc: Curve,
    /// Quantise the duties to this many PWM bits (and report what the quantised mix makes).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub bits: Option<u32>,
    /// Print JSON: {channels, duties, x, y, u_prime, v_prime, cct, duv, ra, rf, rg, efficacy}.
    #[arg(long)]
    pub json: bool,
}

/// Runs `specpoly mix`.
pub fn run(a: &MixArgs) -> Result<()> {
    if !(3..=6).contains(&a.channels.len()) {
        return Err(CliError::usage(format!(
            "{} channels: a mix takes 3 to 6 --channel NAME=FILE.csv[#COLUMN]",
            a.channels.len()
        )));
    }
    let channels = a
        .channels
        .iter()
        .map(|c| load_channel(c))
        .collect::<Result<Vec<_>, _>>()?;
    let r = light::mix(
        &channels,
        a.target,
        a.luminance,
        a.optimize.into(),
        &a.trc.into(),
        a.bits,
    )?;
    if a.json {
        return Ok(print_json(&r)?);
    }
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# target {} at {} of the most the channels give there; optimize {}; {}",
        describe(&a.target),
        a.luminance,
        crate::cli::args::name(&a.optimize),
        a.bits.map_or("unquantised duties".to_string(), |b| format!(
            "{b}-bit duties"
        ))
    );
    let w = r.channels.iter().map(|c| c.len()).max().unwrap_or(7).max(7);
    let _ = writeln!(o, "{:<w$} {:>9}", "channel", "duty");
    for (c, d) in r.channels.iter().zip(&r.duties) {
        let _ = writeln!(o, "{c:<w$} {d:>9.6}");
    }
    let _ = writeln!(
        o,
        "{} {:>6} {:>6} {:>6} {:>9}",
        chromaticity_head(),
        "ra",
        "rf",
        "rg",
        "lm/W"
    );
    let _ = writeln!(
        o,
        "{} {:>6} {:>6} {:>6} {:>9.1}",
        chromaticity_cells([r.x, r.y, r.u_prime, r.v_prime], r.cct, r.duv),
        opt(r.ra, 1),
        opt(r.rf, 1),
        opt(r.rg, 1),
        r.efficacy
    );
    Ok(specpoly_formats::stdout::print(&o)?)
}
