//! `specpoly mix`: PWM duties of 3–6 LED channels for a chromaticity or CCT target
//! (computations in [`specpoly_spectra::light`] and `specpoly_core::light::mix`).

use crate::cli::args::{observer, transfer, Curve};
use crate::cli::light::{chromaticity_cells, chromaticity_head, opt};
use crate::error::{CliError, Result};
use specpoly_core::light::{
    cct, ja8,
    mix_limits::{Limit, Metric},
    Target,
};
use specpoly_core::Observer;
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

/// One `--target`: a chromaticity, or the `ja8` specification.
#[derive(Clone, Debug, PartialEq)]
pub enum TargetArg {
    /// Where the mix is.
    Chromaticity(Target),
    /// California JA8's colour clauses: Ra >= 90 and R9 >= 50 on the mix, CCT <= 4000 K and
    /// |Duv| <= 0.0033 on the target.
    Ja8,
}

fn target_arg(s: &str) -> std::result::Result<TargetArg, String> {
    if s.trim().eq_ignore_ascii_case("ja8") {
        return Ok(TargetArg::Ja8);
    }
    parse_target(s).map(TargetArg::Chromaticity)
}

fn limit_arg(s: &str) -> std::result::Result<(String, f64), String> {
    let bad = || format!("`{s}`: a limit is NAME=VALUE, e.g. r9=50");
    let (k, v) = s.split_once('=').ok_or_else(bad)?;
    let v: f64 = v
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite())
        .ok_or_else(bad)?;
    Ok((k.trim().to_ascii_lowercase(), v))
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
    /// The target: xy:X,Y (under --observer), cct:K or cct:K,duv:D (Planckian locus, ANSI Duv
    /// offset), ansi:K (an ANSI C78.377-2017 nominal CCT's target, e.g. ansi:3000K); given
    /// twice, `ja8` adds California JA8's colour clauses (Ra >= 90, R9 >= 50 on the mix; CCT
    /// <= 4000 K, |Duv| <= 0.0033 on the target).
    #[arg(long, required = true, value_parser = target_arg, value_name = "xy:X,Y|cct:K[,duv:D]|ansi:K|ja8")]
    pub target: Vec<TargetArg>,
    /// A least value of the mix's ra, r9, rf or rg (repeatable): the mix meets it, or the
    /// closest the channels get is printed and the exit code is 1.
    #[arg(long = "min", value_parser = limit_arg, value_name = "ra|r9|rf|rg=VALUE")]
    pub min: Vec<(String, f64)>,
    /// A greatest value of the target's cct (K) or |duv| (repeatable; checked on the target).
    #[arg(long = "max", value_parser = limit_arg, value_name = "cct|duv=VALUE")]
    pub max: Vec<(String, f64)>,
    /// The observer the target chromaticity is met under: 1931 (2°), 1964 (10°), 2015-2,
    /// 2015-10, cie2006:age=A,field=F, or FILE.csv of three sensitivities. Under another than
    /// 1931 a cct:K target is the Planckian radiator's chromaticity under it (a Duv is defined
    /// on CIE 1931 only); CCT, Duv, Ra, Rf and efficacy stay on their standards' observers.
    #[arg(long, default_value = "1931", value_name = "NAME|FILE", value_parser = observer)]
    pub observer: Observer,
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
    /// Print JSON: {channels, duties, x, y, u_prime, v_prime, cct, duv, ra, rf, rg, efficacy,
    /// r9} and, with limits, limits: [{metric, min, value, met}].
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
    let (target, limits) = specification(a)?;
    let r = light::mix(
        &channels,
        target,
        a.observer,
        a.luminance,
        a.optimize.into(),
        &a.trc.into(),
        a.bits,
        &limits,
    )?;
    let missed: Vec<String> = r
        .limits
        .iter()
        .filter(|l| !l.met)
        .map(|l| {
            format!(
                "{} >= {} (best {})",
                l.metric,
                l.min,
                l.value.map_or("undefined".into(), |v| format!("{v:.2}"))
            )
        })
        .collect();
    let unmet = || {
        CliError::Data(format!(
            "no mix of these channels meets {}; the closest is printed",
            missed.join(", ")
        ))
    };
    if a.json {
        print_json(&r)?;
        return if missed.is_empty() {
            Ok(())
        } else {
            Err(unmet())
        };
    }
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# target {} at {} of the most the channels give there; optimize {}; {}",
        describe(&target),
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
    if let Some(c) = &r.observer {
        let _ = writeln!(
            o,
            "# under observer {}: x {:.6} y {:.6}, u' {:.6} v' {:.6}",
            specpoly_formats::escape::one_line(&c.name),
            c.x,
            c.y,
            c.u_prime,
            c.v_prime
        );
    }
    for l in &r.limits {
        let _ = writeln!(
            o,
            "# {} >= {}: {} {}",
            l.metric,
            l.min,
            opt(l.value, 2),
            if l.met { "met" } else { "MISSED" }
        );
    }
    specpoly_formats::stdout::print(&o)?;
    if missed.is_empty() {
        Ok(())
    } else {
        Err(unmet())
    }
}

/// The chromaticity target and the mix's lower limits from `--target`, `--min` and `--max`;
/// the target-level limits (JA8's CCT and Duv, `--max`) are checked here.
fn specification(a: &MixArgs) -> Result<(Target, Vec<Limit>)> {
    let mut chroma = a.target.iter().filter_map(|t| match t {
        TargetArg::Chromaticity(c) => Some(*c),
        TargetArg::Ja8 => None,
    });
    let target = chroma.next().ok_or_else(|| {
        CliError::usage("--target ja8 needs a chromaticity --target too (e.g. cct:3000)")
    })?;
    if chroma.next().is_some() {
        return Err(CliError::usage(
            "one chromaticity --target (plus ja8 if wanted)",
        ));
    }
    let ja8 = a.target.contains(&TargetArg::Ja8);
    let mut limits = vec![];
    let mut min = |m: Metric, v: f64| limits.push(Limit { metric: m, min: v });
    if ja8 {
        min(Metric::Ra, ja8::RA_MIN);
        min(Metric::R9, ja8::R9_MIN);
    }
    for (k, v) in &a.min {
        let m = match k.as_str() {
            "ra" => Metric::Ra,
            "r9" => Metric::R9,
            "rf" => Metric::Rf,
            "rg" => Metric::Rg,
            _ => {
                return Err(CliError::usage(format!(
                    "--min {k}: a least value is of ra, r9, rf or rg"
                )))
            }
        };
        min(m, *v);
    }
    let mut most: Vec<(&str, f64)> = a.max.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    if ja8 {
        most.push(("cct", ja8::CCT_MAX));
        most.push(("duv", ja8::DUV_MAX));
    }
    for (k, v) in most {
        let (cct, duv) = match target {
            Target::Cct(c) => (c.cct, c.duv),
            Target::Xy(_) if a.observer != Observer::Cie1931 => {
                return Err(CliError::usage(format!(
                    "--target {}: a CCT and Duv limit is checked on the CIE 1931 diagram; under the {} observer give the target as cct:K",
                    describe(&target),
                    a.observer.name()
                )))
            }
            Target::Xy(xy) => {
                let c = cct::cct_duv(cct::xy_to_uv(xy))
                    .map_err(|e| CliError::usage(format!("--target {}: {e}", describe(&target))))?;
                (c.cct, c.duv)
            }
        };
        let (have, ok) = match k {
            "cct" => (cct, cct <= v),
            "duv" => (duv, duv.abs() <= v),
            _ => {
                return Err(CliError::usage(format!(
                    "--max {k}: a greatest value is of cct or duv"
                )))
            }
        };
        if !ok {
            return Err(CliError::usage(format!(
                "--target {} has {k} {have:.5}, beyond the limit {v}",
                describe(&target)
            )));
        }
    }
    Ok((target, limits))
}
