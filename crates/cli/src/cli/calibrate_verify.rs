//! `specpoly calibrate verify` and `calibrate predict`: a calibration against measurements, and
//! its predictions streamed line by line.
//!
//! ```text
//! specpoly calibrate verify --calibration CAL.toml --ti3 MEAS.ti3 [--require nominal|recommended]
//!                           [--report REPORT.html] [--tone-target gamma:2.2|srgb|linear] [--json]
//! specpoly calibrate predict --calibration CAL.toml [--json] < RGB lines
//! ```
//!
//! `verify` prints DisplayCAL's and ISO 14861's criteria side by side ([`specpoly_calibrate::criteria`])
//! and exits 1 when one fails at the required level. `predict` answers each input line as soon
//! as it is read (stdout is flushed per line, so a program can hold a conversation through a
//! pipe); a bad line stops it with an error naming the line, after the answers to the lines
//! before it. JSON keys: docs/calibration.md.

use crate::cli::args::{self, Curve};
use crate::cli::calibrate::values::{LutSourceValue, LutWhiteValue};
use crate::error::{CliError, Result};
use serde_json::json;
use specpoly_calibrate::criteria::{self, Level, Outcome};
use specpoly_calibrate::report_html::{self, ReportInfo};
use specpoly_calibrate::verify::{self, Verification};
use specpoly_display::calibration::{self, Calibration};
use specpoly_formats::cgats;
use specpoly_formats::stats::{percentile, Stats};
use specpoly_formats::stdout::{print, print_json};
use std::fmt::Write as _;
use std::io::{BufRead, Read};
use std::path::PathBuf;

/// `calibrate predict`.
#[derive(Debug, clap::Args)]
pub struct PredictArgs {
    /// The calibration file.
    #[arg(long)]
    pub calibration: PathBuf,
    /// One JSON object per input line (JSON Lines: `line`, `device`, `X`, `Y`, `Z`).
    #[arg(long)]
    pub json: bool,
}

/// `--require`: [`Level`] as the command line spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum LevelArg {
    /// DisplayCAL's nominal tolerances (and ISO 14861).
    #[default]
    Nominal,
    /// DisplayCAL's recommended tolerances (and ISO 14861).
    Recommended,
}

impl From<LevelArg> for Level {
    fn from(l: LevelArg) -> Level {
        match l {
            LevelArg::Nominal => Level::Nominal,
            LevelArg::Recommended => Level::Recommended,
        }
    }
}

/// `calibrate verify`.
#[derive(Debug, clap::Args)]
pub struct VerifyArgs {
    /// The calibration file.
    #[arg(long)]
    pub calibration: PathBuf,
    /// The measured patches.
    #[arg(long, required_unless_present = "lut3d", conflicts_with = "lut3d")]
    pub ti3: Option<PathBuf>,
    /// Instead of measurements: a 3D LUT (.cube or .3dl) for this display, verified through the
    /// display's model on source patches (grey and primary ramps, 128 spread colours).
    #[arg(long, value_name = "FILE.cube")]
    pub lut3d: Option<PathBuf>,
    /// With --lut3d: the LUT's source colour space.
    #[arg(long, value_enum, default_value_t = LutSourceValue::Srgb)]
    pub source: LutSourceValue,
    /// With --lut3d: how the LUT reproduces the source white.
    #[arg(long, value_enum, default_value_t = LutWhiteValue::Adapt)]
    pub white: LutWhiteValue,
    /// The level every criterion must meet for exit code 0: DisplayCAL's `nominal` or
    /// `recommended` tolerances (ISO 14861's one level counts at both).
    #[arg(long, value_enum, default_value_t = LevelArg::Nominal)]
    pub require: LevelArg,
    /// Also write the report as one self-contained HTML page (gamut, ΔE00 per patch, tone
    /// curves, the criteria).
    #[arg(long, value_name = "REPORT.html", conflicts_with = "lut3d")]
    pub report: Option<PathBuf>,
    /// The tone curve the report draws the measured ramps against: `gamma:G`, `srgb` or `linear`.
    #[arg(long, default_value = "gamma:2.2", value_parser = args::transfer, value_name = "CURVE")]
    pub tone_target: Curve,
    /// Count the patches the fit dropped as bad readings (its `[fit] outliers`) when verifying
    /// against the file it was fitted from; by default they are listed and left out.
    #[arg(long, conflicts_with = "lut3d")]
    pub include_outliers: bool,
    /// JSON instead of text (keys in docs/calibration.md).
    #[arg(long)]
    pub json: bool,
}

/// Parses one line of `predict` input: three numbers in `[0, 1]`.
pub fn parse_rgb(line: &str, n: usize) -> Result<[f64; 3]> {
    let parts: Vec<&str> = line
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|s| !s.is_empty())
        .collect();
    if parts.len() != 3 {
        return Err(CliError::data(format!(
            "stdin:{n}: expected three device values R G B in 0–1, found {} values",
            parts.len()
        )));
    }
    let mut v = [0.0; 3];
    for (k, p) in parts.iter().enumerate() {
        v[k] = match p.parse::<f64>() {
            Ok(x) if (0.0..=1.0).contains(&x) => x,
            Ok(_) => return Err(CliError::data(format!("stdin:{n}: `{p}` is outside 0–1"))),
            Err(_) => return Err(CliError::data(format!("stdin:{n}: `{p}` is not a number"))),
        };
    }
    Ok(v)
}

/// Runs `calibrate predict`: one answer per line, written and flushed as each line arrives.
pub fn predict(a: &PredictArgs) -> Result<()> {
    let cal = calibration::load(&a.calibration)?;
    let stdin = std::io::stdin();
    let mut input = stdin.lock();
    let mut buf = String::new();
    let mut n = 0;
    // a line longer than this is not three numbers: refuse it instead of growing the buffer
    const MAX_LINE: u64 = 4096;
    loop {
        buf.clear();
        let read = input
            .by_ref()
            .take(MAX_LINE)
            .read_line(&mut buf)
            .map_err(|e| CliError::io("stdin", e))?;
        if read == 0 {
            return Ok(());
        }
        n += 1;
        if read as u64 == MAX_LINE && !buf.ends_with('\n') {
            return Err(CliError::data(format!(
                "stdin:{n}: line longer than {MAX_LINE} bytes"
            )));
        }
        let t = buf.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let rgb = parse_rgb(t, n)?;
        let x = cal.predict(rgb);
        if a.json {
            let v = json!({"line": n, "device": rgb, "X": x[0], "Y": x[1], "Z": x[2]});
            print(&format!("{v}\n"))?;
        } else {
            print(&format!("{:.6} {:.6} {:.6}\n", x[0], x[1], x[2]))?;
        }
    }
}

/// The source patches `verify --lut3d` checks: black, white, red, green, blue and grey ramps
/// of 17 levels and 128 colours spread over the cube (the patch set of `calibrate run
/// --ramp-steps 17 --verify 128`).
pub const LUT3D_RAMP_STEPS: usize = 17;
/// … and its spread colours.
pub const LUT3D_SPREAD: usize = 128;

/// `calibrate verify --lut3d`: the LUT through the calibration's model.
fn verify_lut3d(a: &VerifyArgs, cal: &Calibration, path: &std::path::Path) -> Result<()> {
    use specpoly_display::lut3d::{file, Target};
    let format = file::Format::from_path(path)
        .filter(|f| *f != file::Format::MadVr)
        .ok_or_else(|| {
            CliError::Usage(format!(
                "--lut3d `{}`: give a .cube or .3dl file",
                path.display()
            ))
        })?;
    let text = specpoly_formats::read::text(path)?;
    let lut = file::read(&text, format, &path.display().to_string())?;
    let target = Target::new(cal.model(), a.source.into(), a.white.into())?;
    let sources: Vec<[f64; 3]> =
        specpoly_calibrate::patches::standard(LUT3D_RAMP_STEPS, LUT3D_SPREAD)?
            .iter()
            .map(|p| p.device)
            .collect();
    let (v, outside) = Verification::lut3d(cal.model(), &lut, &target, &sources);
    let label = format!(
        "{} ({} source patches, {outside} outside the display's gamut not counted)",
        path.display(),
        args::name(&a.source)
    );
    if a.json {
        let mut j = verification_json(&v, a, &path.display().to_string());
        j["lut3d"] = json!({
            "file": path.display().to_string(),
            "source": args::name(&a.source),
            "white": args::name(&a.white),
            "patches": sources.len(),
            "outside_gamut": outside,
        });
        print_json(&j)?;
    } else {
        print(&verification_text(&v, cal, a, &label))?;
    }
    match criteria::failures(&v.outcomes, a.require.into()) {
        None => Ok(()),
        Some(f) => Err(CliError::data(format!(
            "{}: verification failed: {f}",
            path.display()
        ))),
    }
}

/// Runs `calibrate verify`.
pub fn verify(a: &VerifyArgs) -> Result<()> {
    let cal = calibration::load(&a.calibration)?;
    if let Some(lut) = &a.lut3d {
        return verify_lut3d(a, &cal, lut);
    }
    let Some(ti3_path) = &a.ti3 else {
        return Err(CliError::Usage("give --ti3 FILE or --lut3d FILE".into()));
    };
    let bytes = specpoly_formats::read::bytes(ti3_path)?;
    let self_fit = verify::fitted_from(&cal, &bytes);
    let ti3 = cgats::read_ti3(
        &specpoly_formats::read::decode(bytes),
        &ti3_path.display().to_string(),
    )?;
    let m = verify::measurements_for(&cal, &ti3)
        .map_err(|e| CliError::data(format!("{}: {e}", ti3_path.display())))?;
    let outliers = verify::fit_outliers(&cal, &m, self_fit);
    let exclude = if a.include_outliers {
        &[][..]
    } else {
        &outliers
    };
    let (v, left_out) = Verification::excluding(&cal, &m, &ti3.lines, exclude);
    if self_fit {
        let w = format!(
            "warning: {} is the file {} was fitted from (the same SHA-256): these are the fit's own residuals, not a verification; verify against other readings (calibrate run --verify N measures some) or fit with --hold-out",
            ti3_path.display(),
            a.calibration.display()
        );
        eprintln!("{}", specpoly_formats::escape::one_line(&w));
    }
    if let Some(path) = &a.report {
        let curve = a.tone_target;
        let name = match curve {
            Curve::Linear => "linear".to_string(),
            Curve::Srgb => "the sRGB curve".to_string(),
            Curve::Gamma(g) => format!("gamma {g}"),
        };
        let info = ReportInfo {
            calibration: &a.calibration.display().to_string(),
            measurements: &ti3_path.display().to_string(),
            tone_target: (curve.into(), name),
            level: a.require.into(),
        };
        let html = report_html::page(&v, &cal, &info);
        specpoly_formats::atomic::write(path, html.as_bytes())?;
        crate::cli::wrote::wrote(path, "");
    }
    let measurements = ti3_path.display().to_string();
    let counted: Vec<usize> = if a.include_outliers {
        outliers.clone()
    } else {
        Vec::new()
    };
    if a.json {
        let mut j = verification_json(&v, a, &measurements);
        j["self_fit"] = json!(self_fit);
        j["excluded_outliers"] = left_out.iter().map(patch_ref_json).collect();
        j["counted_outliers"] = json!(counted);
        print_json(&j)?;
    } else {
        let mut t = verification_text(&v, &cal, a, &measurements);
        for p in &left_out {
            let _ = writeln!(
                t,
                "left out: patch {} (line {}: RGB {:.4} {:.4} {:.4}), ΔE00 {:.3}: the fit dropped it as a bad reading (--include-outliers counts it)",
                p.patch, p.line, p.device[0], p.device[1], p.device[2], p.delta_e00
            );
        }
        for n in &counted {
            let _ = writeln!(
                t,
                "counted: patch {n}, which the fit dropped as a bad reading (--include-outliers)"
            );
        }
        print(&t)?;
    }
    match criteria::failures(&v.outcomes, a.require.into()) {
        None => Ok(()),
        Some(f) => Err(CliError::data(format!(
            "{}: verification failed: {f}",
            a.calibration.display()
        ))),
    }
}

/// The 99th percentile ΔE00 (nearest rank).
fn p99(v: &Verification) -> f64 {
    let mut d: Vec<f64> = v.patches.iter().map(|p| p.delta_e00).collect();
    d.sort_by(f64::total_cmp);
    percentile(&d, 0.99)
}

/// Finite numbers as JSON numbers, anything else as `null` (JSON has no NaN).
fn number(x: f64) -> serde_json::Value {
    if x.is_finite() {
        json!(x)
    } else {
        serde_json::Value::Null
    }
}

/// The criteria as JSON objects.
pub fn outcomes_json(outcomes: &[Outcome], level: Level) -> serde_json::Value {
    outcomes
        .iter()
        .map(|o| {
            json!({
                "id": o.criterion.id,
                "standard": o.criterion.standard,
                "description": o.criterion.description,
                "nominal": o.criterion.nominal,
                "recommended": o.criterion.recommended,
                "value": o.value.map(number),
                "patches": o.patches,
                "nominal_pass": o.nominal_pass,
                "recommended_pass": o.recommended_pass,
                "pass": o.value.map(|_| !o.fails(level)),
            })
        })
        .collect()
}

/// A patch named in JSON: `patch`, `line`, `device`, `delta_e00`.
fn patch_ref_json(p: &criteria::PatchResult) -> serde_json::Value {
    json!({"patch": p.patch, "line": p.line, "device": p.device, "delta_e00": number(p.delta_e00)})
}

/// The JSON `calibrate verify --json` prints; `measurements` names what was verified.
pub fn verification_json(
    v: &Verification,
    a: &VerifyArgs,
    measurements: &str,
) -> serde_json::Value {
    let s: &Stats = &v.stats;
    let worst = v.worst().map(patch_ref_json);
    let patches: Vec<serde_json::Value> = v
        .patches
        .iter()
        .map(|p| {
            let lab = |l: &specpoly_core::Lab| [l.l, l.a, l.b].map(number);
            json!({
                "patch": p.patch,
                "line": p.line,
                "device": p.device,
                "reference_xyz": p.reference.map(number),
                "measured_xyz": p.measured.map(number),
                "reference_lab": lab(&p.reference_lab),
                "measured_lab": lab(&p.measured_lab),
                "delta_e00": number(p.delta_e00),
                "delta_c00": number(p.delta_c00),
            })
        })
        .collect();
    json!({
        "calibration": a.calibration.display().to_string(),
        "measurements": measurements,
        "white": v.white,
        "delta_e00": {
            "patches": s.n,
            "mean": number(s.mean),
            "p95": number(s.p95),
            "p99": number(p99(v)),
            "max": number(s.max),
        },
        "worst": worst,
        "level": Level::from(a.require),
        "pass": criteria::failures(&v.outcomes, a.require.into()).is_none(),
        "criteria": outcomes_json(&v.outcomes, a.require.into()),
        "report": a.report.as_ref().map(|p| p.display().to_string()),
        "patch_results": patches,
    })
}

fn verification_text(v: &Verification, cal: &Calibration, a: &VerifyArgs, what: &str) -> String {
    let s = &v.stats;
    let mut t = format!(
        "{} patches of {} against {} ({})\n",
        s.n,
        what,
        a.calibration.display(),
        if cal.absolute() {
            "cd/m²"
        } else {
            "relative units"
        }
    );
    let _ = write!(
        t,
        "ΔE00 mean {:.3}  p95 {:.3}  p99 {:.3}  max {:.3}",
        s.mean,
        s.p95,
        p99(v),
        s.max
    );
    if let Some(w) = v.worst() {
        let _ = write!(
            t,
            " (patch {}, line {}: RGB {:.4} {:.4} {:.4})",
            w.patch, w.line, w.device[0], w.device[1], w.device[2]
        );
    }
    t.push('\n');
    let _ = writeln!(
        t,
        "{:<11} {:<46} {:>8} {:>8} {:>11} {:>7}  result",
        "standard", "criterion", "value", "nominal", "recommended", "patches"
    );
    for o in &v.outcomes {
        let c = &o.criterion;
        let result = match (o.value, o.fails(a.require.into())) {
            (None, _) => "n/a (no such patch)".to_string(),
            (Some(_), true) => "FAIL".to_string(),
            (Some(_), false) if c.recommended.is_none() => "pass".into(),
            (Some(_), false) if o.recommended_pass == Some(true) => "pass (recommended)".into(),
            (Some(_), false) => "pass (nominal)".into(),
        };
        let _ = writeln!(
            t,
            "{:<11} {:<46} {:>8} {:>8} {:>11} {:>7}  {result}",
            c.standard,
            c.description,
            o.value.map_or("n/a".into(), |x| format!("{x:.3}")),
            format!("≤ {}", c.nominal),
            c.recommended.map_or(String::new(), |r| format!("≤ {r}")),
            o.patches
        );
    }
    t
}
