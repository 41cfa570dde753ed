//! `specpoly calibrate run`: measures a display ([`specpoly_calibrate::run`]) and prints what it
//! does as it goes.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//!                        [--patches SET.ti1] [--resume | --force]
//! ```
//! writes `CAL.ti3` (every reading, committed atomically as it is taken; never overwritten:
//! see [`specpoly_calibrate::session`]) and `CAL.toml` (the fit of the non-verification
//! patches).

use crate::cli::calibrate::MatrixFitArg;
use crate::error::from_calibrate;
use specpoly_calibrate::interrupt;
use specpoly_calibrate::run::{
    fit_and_save, measure_session, patch_set, raw_primaries, ti3_path, Devices,
};
use specpoly_calibrate::session::{Existing, Session};
use specpoly_display::calibration::{self, Calibration};
use specpoly_formats::cgats::Ti3Info;
use specpoly_formats::error::{CliError, Result};
use std::path::{Path, PathBuf};

/// Arguments of `specpoly calibrate run`.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Where patches are shown: `web[:PORT]` (a page on 127.0.0.1; open the printed URL),
    /// `led:PORT` (the RGB-LED controller), `manual` (prints the RGB, waits for Enter),
    /// `sim:SPD[,options]` (a simulated display, e.g. `sim:crt,noise=0.001`), `argyll[:N]`
    /// (ArgyllCMS's patch window, with `--instrument argyll`).
    #[arg(long, value_name = "DISPLAY")]
    pub display: String,
    /// Where readings come from: `serial:PORT[,options]` (a PR-655/670 in remote mode),
    /// `argyll[:options]` (any ArgyllCMS instrument, through `dispread`; with `--display
    /// argyll[:N]`), `sim` (reads `--display sim:…`), `sim:SPD[,options]` (simulates what
    /// `--display` shows).
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
    #[arg(long, value_enum, default_value_t = MatrixFitArg::Cowan)]
    pub matrix: MatrixFitArg,
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
    /// Progress on stderr, and the result as JSON on stdout (keys in docs/calibration.md).
    #[arg(long)]
    pub json: bool,
    /// Calibrate to a target first (video LUTs, as ArgyllCMS's dispcal):
    /// `white=D65|native|X,Y,gamma=G|srgb|bt1886|lstar,luminance=N|native`. The native
    /// readings go to `CAL.native.ti3`, the LUT to `CAL.cal`, the readings through it to
    /// `CAL.ti3` and their fit (with the LUT) to `CAL.toml`. See docs/calibration.md.
    #[arg(long, value_name = "TARGET", value_parser = specpoly_display::target::parse)]
    pub target: Option<specpoly_display::target::Target>,
}

/// Prints one line of progress: on stdout, or on stderr when stdout carries `--json`.
pub(crate) fn line(s: &str) -> Result<()> {
    if JSON.load(std::sync::atomic::Ordering::Relaxed) {
        eprintln!("{}", specpoly_formats::escape::one_line(s));
        return Ok(());
    }
    specpoly_formats::stdout::print(&format!("{s}\n"))
}

/// Whether this run prints JSON (set once at the start of [`run`]).
static JSON: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// The chromaticity ([`specpoly_core::chromaticity`]; a black reading shows the equal-energy
/// point) and luminance of an XYZ.
fn xyy(p: [f64; 3]) -> [f64; 3] {
    let [x, y] = specpoly_core::chromaticity(p, [1.0; 3]);
    [x, y, p[1]]
}

/// Runs `specpoly calibrate run`.
pub fn run(a: &RunArgs) -> Result<()> {
    JSON.store(a.json, std::sync::atomic::Ordering::Relaxed);
    let set = patch_set(a.patches.as_deref(), a.ramp_steps, a.verify).map_err(from_calibrate)?;
    let ti3 = match a.target {
        Some(_) => crate::cli::calibrate_target::native_ti3_path(&a.output),
        None => ti3_path(&a.output),
    };
    if ti3_path(&a.output) == a.output {
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
        created: Some(calibration::now_utc()),
        absolute: true,
        keywords: Vec::new(),
    };
    let (mut session, note) =
        Session::open(&ti3, &set, existing, info.clone()).map_err(from_calibrate)?;
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
    let devices = Devices {
        display: &a.display,
        instrument: &a.instrument,
        settle: a.settle,
        ti3: &ti3,
    };
    if let Some(target) = &a.target {
        let ctx = crate::cli::calibrate_target::Context {
            args: a,
            target,
            set: &set,
            head: &head,
            devices: &devices,
            existing,
            info,
        };
        return crate::cli::calibrate_target::run(&ctx, &mut session);
    }
    let truth = measure_session(&devices, &set, &mut session, &head, &mut |s| line(s))
        .map_err(from_calibrate)?;
    let taken = session.measurements();
    line(&format!(
        "measured {} patches → {}",
        taken.len(),
        ti3.display()
    ))?;
    let primaries = raw_primaries(&set, &taken).map(|p| (p, "reading − black"));
    for (p, what) in primaries
        .into_iter()
        .chain(truth.map(|m| (m, "simulation's truth")))
    {
        for (name, p) in ["red", "green", "blue"].iter().zip(p) {
            let c = xyy(p);
            line(&format!(
                "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² ({what})",
                c[0], c[1], c[2]
            ))?;
        }
    }
    let (cal, [n_fit, n_verify]) = fit_and_save(
        &a.output,
        &ti3,
        session.info(),
        a.matrix.into(),
        &set,
        &taken,
    )
    .map_err(from_calibrate)?;
    eprintln!(
        "wrote {}",
        specpoly_formats::escape::one_line(&a.output.display().to_string())
    );
    if a.json {
        let mut v = crate::cli::calibrate::fit_json(&cal, &a.output, n_fit);
        v["readings"] = serde_json::json!(ti3.display().to_string());
        v["patches_measured"] = serde_json::json!(taken.len());
        v["patches_verify"] = serde_json::json!(n_verify);
        return specpoly_formats::stdout::print_json(&v);
    }
    print_fit(&cal, &a.output)
}

/// Prints the fitted primaries and the fit's ΔE00.
pub(crate) fn print_fit(cal: &Calibration, out: &Path) -> Result<()> {
    let d = cal.data();
    line(&format!(
        "fit ({} matrix) → {}",
        d.fit.matrix,
        out.display()
    ))?;
    for (name, p) in ["red", "green", "blue"].iter().zip(d.primaries.array()) {
        line(&format!(
            "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (fit)",
            p.x, p.y, p.luminance
        ))?;
    }
    let r = &d.fit.residual;
    line(&format!(
        "  ΔE00 on the {} fit patches: mean {:.2}, max {:.2}",
        r.n, r.mean, r.max
    ))?;
    if let Some(v) = &d.fit.verification {
        line(&format!(
            "  ΔE00 on the {} verification patches: mean {:.2}, 95th percentile {:.2}, max {:.2}",
            v.n, v.mean, v.p95, v.max
        ))?;
    }
    Ok(())
}
