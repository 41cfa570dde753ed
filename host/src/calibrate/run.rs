//! `specpoly calibrate run`: show patches, read them, save the readings as CGATS .ti3 after
//! every patch, fit Cowan's model and write the calibration.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//!                        [--patches SET.ti1] [--resume | --force]
//! ```
//! writes `CAL.ti3` (all readings, rewritten atomically after each patch — or each batch with
//! `--instrument argyll` — so an interrupted run keeps what it measured; see
//! [`crate::calibrate::session`]) and `CAL.toml` (the fit of the non-verification patches).
//! An existing `CAL.ti3` is never overwritten: `--resume` measures only the patches it lacks,
//! `--force` keeps it as `CAL.ti3.1` (`.2`, …) and starts over.

use crate::calibrate::display::{self, PatchDisplay};
use crate::calibrate::file;
use crate::calibrate::fit::{self, FitOptions, MatrixFit};
use crate::calibrate::instrument::{self, argyll, Instrument};
use crate::calibrate::interrupt;
use crate::calibrate::measurement::Measurement;
use crate::calibrate::patches::{self, Patch};
use crate::calibrate::session::{Existing, Session};
use crate::error::{CliError, Result};
use crate::io::cgats::Ti3Info;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Arguments of `specpoly calibrate run`.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Where patches are shown: `web[:PORT]` (a page on 127.0.0.1; open the printed URL),
    /// `led:PORT` (the RGB-LED controller), `manual` (prints the RGB, waits for Enter),
    /// `sim:SPD[,options]` (a simulated display, e.g. `sim:crt,noise=0.001`).
    #[arg(long, value_name = "DISPLAY")]
    pub display: String,
    /// Where readings come from: `serial:PORT[,options]` (a PR-655/670 in remote mode), `sim`
    /// (reads `--display sim:…`), `sim:SPD[,options]` (simulates what `--display` shows).
    #[arg(long, value_name = "INSTRUMENT")]
    pub instrument: String,
    /// The calibration to write (TOML); the readings go beside it with extension `.ti3`.
    #[arg(short, long, value_name = "CAL.toml")]
    pub output: PathBuf,
    /// Levels per channel ramp, 0 and 1 included (2–256).
    #[arg(long, default_value_t = 9, value_name = "N")]
    pub ramp_steps: usize,
    /// Verification patches (spread over the RGB cube; measured, not fitted).
    #[arg(long, default_value_t = 16, value_name = "N")]
    pub verify: usize,
    /// Wait after a patch is on screen before reading it, ms [default: 0 for sim and manual,
    /// 100 for led, 500 for web].
    #[arg(long, value_name = "MS")]
    pub settle: Option<u64>,
    /// How the fit finds the primaries' matrix: `cowan` (full-drive primaries minus black,
    /// Cowan 1983: what this patch set is made for) or `least-squares` (over every fit patch).
    #[arg(long, value_enum, default_value_t = MatrixFit::Cowan)]
    pub matrix: MatrixFit,
    /// Measure this patch set (an ArgyllCMS `.ti1`, e.g. from `targen -d3`, or from
    /// `calibrate patches`) instead of the ramps; every patch is fitted.
    #[arg(long, value_name = "SET.ti1")]
    pub patches: Option<PathBuf>,
    /// `CAL.ti3` exists: measure only the patches it lacks (same patch set only).
    #[arg(long, conflicts_with = "force")]
    pub resume: bool,
    /// `CAL.ti3` exists: keep it as `CAL.ti3.1` (`.2`, …) and start over.
    #[arg(long)]
    pub force: bool,
}

/// The patch set of a run: `--patches FILE.ti1`, or the standard ramps and verification
/// patches.
pub fn patch_set(a: &RunArgs) -> Result<Vec<Patch>> {
    match &a.patches {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| CliError::io(p, e))?;
            patches::from_devices(&crate::io::ti1::read_ti1(&text, &p.display().to_string())?)
        }
        None => patches::standard(a.ramp_steps, a.verify),
    }
}

/// Where the readings go: `CAL.toml` → `CAL.ti3`.
pub fn ti3_path(output: &Path) -> PathBuf {
    output.with_extension("ti3")
}

/// A failed run: the error and the readings taken before it.
#[derive(Debug)]
pub struct Interrupted {
    /// What went wrong, with the patch it happened at.
    pub error: CliError,
    /// Readings taken so far, in patch order.
    pub taken: Vec<Measurement>,
}

/// A progress bar with the patch count and the time left, drawn on stderr only when it is a
/// terminal.
fn progress_bar(n: usize) -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(n as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "measuring [{bar:30}] {pos}/{len} patches, {eta} left",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Shows each patch, waits `settle`, reads it, and calls `save` with all readings so far after
/// every patch. Stops at the first failure (of the display, the instrument or `save`).
pub fn measure_all(
    display: &mut dyn PatchDisplay,
    instrument: &mut dyn Instrument,
    patches: &[Patch],
    settle: Duration,
    mut save: impl FnMut(&[Measurement]) -> Result<()>,
) -> std::result::Result<Vec<Measurement>, Interrupted> {
    let bar = progress_bar(patches.len());
    let mut taken: Vec<Measurement> = Vec::with_capacity(patches.len());
    for (i, p) in patches.iter().enumerate() {
        let at = |e: CliError| {
            let msg = format!(
                "patch {} of {} ({} {:.3} {:.3} {:.3}): {e}",
                i + 1,
                patches.len(),
                p.kind.name(),
                p.device[0],
                p.device[1],
                p.device[2]
            );
            match e {
                CliError::Usage(_) => CliError::usage(msg),
                _ => CliError::data(msg),
            }
        };
        if interrupt::requested() {
            bar.abandon();
            return Err(Interrupted {
                error: at(CliError::data(interrupt::MESSAGE)),
                taken,
            });
        }
        let reading = display
            .show(p.device)
            .and_then(|()| {
                if !settle.is_zero() {
                    std::thread::sleep(settle);
                }
                instrument.measure()
            })
            .map_err(at);
        let xyz = match reading {
            Ok(x) => x,
            Err(error) => {
                bar.abandon();
                return Err(Interrupted { error, taken });
            }
        };
        taken.push(Measurement {
            device: p.device,
            xyz,
        });
        if let Err(e) = save(&taken) {
            bar.abandon();
            return Err(Interrupted { error: e, taken });
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(taken)
}

/// Opens the display and the instrument named on the command line.
pub fn open(
    display_spec: &str,
    instrument_spec: &str,
) -> Result<(Box<dyn PatchDisplay>, Box<dyn Instrument>)> {
    let d = display::open(display_spec)?;
    instrument::open(instrument_spec, d)
}

/// The chromaticity and luminance of an XYZ.
fn xyy(p: [f64; 3]) -> [f64; 3] {
    let s = p[0] + p[1] + p[2];
    if s > 0.0 {
        [p[0] / s, p[1] / s, p[1]]
    } else {
        [0.0, 0.0, p[1]]
    }
}

/// The primaries as the raw readings give them: full channel minus black (what a fit must
/// come close to), `None` if a patch is missing.
pub fn raw_primaries(patches: &[Patch], m: &[Measurement]) -> Option<[[f64; 3]; 3]> {
    let find = |d: [f64; 3]| {
        patches
            .iter()
            .zip(m)
            .find(|(p, _)| p.device == d)
            .map(|(_, m)| m.xyz)
    };
    let black = find([0.0; 3])?;
    let mut out = [[0.0; 3]; 3];
    for (ch, o) in out.iter_mut().enumerate() {
        let mut d = [0.0; 3];
        d[ch] = 1.0;
        let f = find(d)?;
        *o = [0, 1, 2].map(|k| f[k] - black[k]);
    }
    Some(out)
}

/// Runs `specpoly calibrate run`.
pub fn run_cli(a: &RunArgs) -> Result<()> {
    let set = patch_set(a)?;
    let ti3 = ti3_path(&a.output);
    if ti3 == a.output {
        return Err(CliError::usage(format!(
            "-o {}: name the calibration `.toml`; the readings go to `.ti3` beside it",
            a.output.display()
        )));
    }
    let existing = if a.resume {
        Existing::Resume
    } else if a.force {
        Existing::Force
    } else {
        Existing::Refuse
    };
    let info = Ti3Info {
        descriptor: "specpoly calibrate run".into(),
        instrument: None,
        created: Some(file::now_utc()),
        absolute: true,
        keywords: Vec::new(),
    };
    let (mut session, note) = Session::open(&ti3, &set, existing, info)?;
    if let Some(n) = note {
        eprintln!("{n}");
    }
    interrupt::install();
    let n_verify = set.iter().filter(|p| !p.kind.for_fit()).count();
    let head = format!(
        "{} patches ({} for the fit, {} to verify); readings → {}",
        set.len(),
        set.len() - n_verify,
        n_verify,
        ti3.display()
    );
    let measured = if argyll::is_argyll(&a.instrument) {
        measure_with_argyll(a, &set, &mut session, &head).map(|()| None)
    } else {
        measure_direct(a, &set, &mut session, &head)
    };
    let truth = measured.map_err(|e| {
        let n = session.taken();
        let kept = if n == 0 {
            "no readings taken".to_string()
        } else {
            format!(
                "{n} readings kept in {} (run again with --resume to measure the other {})",
                ti3.display(),
                set.len() - n
            )
        };
        match e {
            CliError::Usage(m) => CliError::usage(format!("{m}; {kept}")),
            e => CliError::data(format!("{e}; {kept}")),
        }
    })?;
    let taken = session.measurements();
    println!("measured {} patches → {}", taken.len(), ti3.display());
    if let Some(p) = raw_primaries(&set, &taken) {
        for (name, p) in ["red", "green", "blue"].iter().zip(p) {
            let c = xyy(p);
            println!(
                "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (reading − black)",
                c[0], c[1], c[2]
            );
        }
    }
    if let Some(m) = truth {
        for (name, p) in ["red", "green", "blue"].iter().zip(m) {
            let c = xyy(p);
            println!(
                "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (simulation's truth)",
                c[0], c[1], c[2]
            );
        }
    }
    let fit_set: Vec<Measurement> = set
        .iter()
        .zip(&taken)
        .filter(|(p, _)| p.kind.for_fit())
        .map(|(_, m)| *m)
        .collect();
    let verify_set: Vec<Measurement> = set
        .iter()
        .zip(&taken)
        .filter(|(p, _)| !p.kind.for_fit())
        .map(|(_, m)| *m)
        .collect();
    fit_and_write(
        &a.output,
        &ti3,
        session.info(),
        a.matrix,
        &fit_set,
        &verify_set,
    )
}

/// Measures the patches `session` lacks with `--display` and `--instrument` (one patch at a
/// time, each saved at once). Returns the simulated display's true primaries, if simulated.
fn measure_direct(
    a: &RunArgs,
    set: &[Patch],
    session: &mut Session,
    head: &str,
) -> Result<Option<[[f64; 3]; 3]>> {
    if a.display.starts_with("argyll") {
        return Err(CliError::usage(
            "--display argyll is ArgyllCMS's own patch window: use it with --instrument argyll[:options]",
        ));
    }
    let display = display::open(&a.display)?;
    println!("display: {}", display.describe());
    let (mut display, mut instrument) = instrument::open(&a.instrument, display)?;
    println!("instrument: {}", instrument.describe());
    println!("{head}");
    session.set_instrument(instrument.describe());
    let settle = a
        .settle
        .map(Duration::from_millis)
        .unwrap_or_else(|| display.default_settle());
    let missing = session.missing();
    let todo: Vec<Patch> = missing.iter().map(|&i| set[i]).collect();
    measure_all(display.as_mut(), instrument.as_mut(), &todo, settle, |m| {
        let k = m.len() - 1;
        session.record(missing[k], m[k].xyz)
    })
    .map_err(|i| i.error)?;
    Ok(display.simulation().map(|s| s.model().primaries))
}

/// Measures the patches `session` lacks with ArgyllCMS's `dispread`, a batch at a time, each
/// batch saved before the next starts.
fn measure_with_argyll(
    a: &RunArgs,
    set: &[Patch],
    session: &mut Session,
    head: &str,
) -> Result<()> {
    let ti3 = ti3_path(&a.output);
    let mut reader = argyll::Dispread::open(
        &a.instrument,
        &a.display,
        &ti3,
        a.settle.map(Duration::from_millis),
    )?;
    println!("display: {}", reader.describe_display());
    println!("instrument: {}", reader.describe());
    println!("{head}");
    session.set_instrument(reader.describe());
    if !reader.is_fake() && std::io::stdin().is_terminal() {
        eprintln!(
            "put the instrument on the middle of the screen (where ArgyllCMS's patch window opens) and press Enter"
        );
        let mut line = String::new();
        std::io::stdin()
            .read_line(&mut line)
            .map_err(|e| CliError::io("stdin", e))?;
    }
    let missing = session.missing();
    let bar = progress_bar(missing.len());
    let total = set.len();
    for chunk in missing.chunks(reader.batch()) {
        let devices: Vec<[f64; 3]> = chunk.iter().map(|&i| set[i].device).collect();
        let first = chunk[0] + 1;
        let last = chunk[chunk.len() - 1] + 1;
        let xyz = reader.measure(&devices).map_err(|e| {
            bar.abandon();
            CliError::data(format!("patches {first}–{last} of {total}: {e}"))
        })?;
        let rows: Vec<(usize, [f64; 3])> = chunk.iter().copied().zip(xyz).collect();
        session.set_instrument(reader.describe());
        session.record_all(&rows)?;
        bar.inc(chunk.len() as u64);
    }
    bar.finish_and_clear();
    Ok(())
}

/// Fits Cowan's model to `fit_set`, verifies it on `verify_set`, writes `out` and prints the
/// result.
fn fit_and_write(
    out: &Path,
    ti3: &Path,
    info: &Ti3Info,
    matrix: MatrixFit,
    fit_set: &[Measurement],
    verify_set: &[Measurement],
) -> Result<()> {
    let opts = FitOptions {
        matrix,
        ..FitOptions::default()
    };
    let mut cal = fit::fit_and_verify(fit_set, verify_set, &opts)?;
    {
        let (_, prov) = cal.report_mut();
        prov.source = ti3.display().to_string();
        prov.instrument = info.instrument.clone().unwrap_or_default();
        prov.measured = info.created.clone().unwrap_or_default();
    }
    cal.save(out)?;
    let d = cal.data();
    println!("fit ({} matrix) → {}", d.fit.matrix, out.display());
    for (name, p) in ["red", "green", "blue"].iter().zip(d.primaries.array()) {
        println!(
            "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (fit)",
            p.x, p.y, p.luminance
        );
    }
    let r = &d.fit.residual;
    println!(
        "  ΔE00 on the {} fit patches: mean {:.2}, max {:.2}",
        r.patches, r.mean, r.max
    );
    if let Some(v) = &d.fit.verification {
        println!(
            "  ΔE00 on the {} verification patches: mean {:.2}, 95th percentile {:.2}, max {:.2}",
            v.patches, v.mean, v.p95, v.max
        );
    }
    Ok(())
}
