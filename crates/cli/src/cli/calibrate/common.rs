//! What the `calibrate` command files share, below all of them: `run`'s arguments (also
//! handed to `run --target`), the progress printer, the fit's printout and JSON, and the
//! files beside a calibration. The command files (`calibrate.rs`, `calibrate_run.rs`,
//! `calibrate_target.rs`, `calibrate_verify.rs`) depend on this module and downward only.

use super::values::MatrixFitArg;
use crate::error::Result;
use specpoly_display::calibration::Calibration;
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
pub(crate) fn line(s: &str) -> specpoly_formats::Result<()> {
    if JSON.load(std::sync::atomic::Ordering::Relaxed) {
        eprintln!("{}", specpoly_formats::escape::one_line(s));
        return Ok(());
    }
    specpoly_formats::stdout::print(&format!("{s}\n"))
}

/// Whether this run prints JSON (set once at the start of `calibrate run`, [`set_json`]).
static JSON: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether [`line`] prints on stderr (`json`: stdout carries the run's JSON) or on stdout.
pub fn set_json(json: bool) {
    JSON.store(json, std::sync::atomic::Ordering::Relaxed);
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

/// The JSON `calibrate fit --json` (and `run --json`) prints about a fitted calibration
/// written to `output` from `fitted` patches (keys documented in docs/calibration.md).
pub fn fit_json(cal: &Calibration, output: &std::path::Path, fitted: usize) -> serde_json::Value {
    let d = cal.data();
    serde_json::json!({
        "output": output.display().to_string(),
        "source": d.provenance.source,
        "units": d.units,
        "matrix": d.fit.matrix,
        "patches_fit": fitted,
        "fit_delta_e00": d.fit.residual,
        "held_out_delta_e00": d.fit.verification,
        "additivity": match (d.fit.additivity_delta_e00, d.fit.additivity_luminance_percent) {
            (Some(de), Some(pc)) => serde_json::json!({"delta_e00": de, "luminance_percent": pc}),
            _ => serde_json::Value::Null,
        },
        "notes": d.provenance.notes,
        "model": d.fit.model,
        "model_candidates": d.fit.candidates,
        "outliers": d.fit.outliers,
        "constrained": d.fit.constrained,
    })
}

/// Where the native readings go: `CAL.toml` → `CAL.native.ti3`.
pub fn native_ti3_path(output: &Path) -> PathBuf {
    output.with_extension("native.ti3")
}

/// Where the LUT goes: `CAL.toml` → `CAL.cal`.
pub fn cal_path(output: &Path) -> PathBuf {
    output.with_extension("cal")
}
