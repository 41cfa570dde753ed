//! `specpoly calibrate run`: measures a display ([`crate::calibrate::run`]) and prints what it
//! does as it goes.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//! ```
//! writes `CAL.ti3` (all readings, rewritten atomically after each patch so an interrupted run
//! keeps what it measured) and `CAL.toml` (the fit of the non-verification patches).

use crate::calibrate::file::{self, Calibration};
use crate::calibrate::fit::MatrixFit;
use crate::calibrate::run::{fit_and_save, measure_all, raw_primaries, save_ti3, split, ti3_path};
use crate::calibrate::{instrument, patch_display, patches};
use crate::error::{CliError, Result};
use crate::io::cgats::Ti3Info;
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
}

/// Prints one line on stdout.
fn line(s: &str) -> Result<()> {
    crate::io::stdout::print(&format!("{s}\n"))
}

/// The chromaticity ([`specpoly_core::chromaticity`]; a black reading shows the equal-energy
/// point) and luminance of an XYZ.
fn xyy(p: [f64; 3]) -> [f64; 3] {
    let [x, y] = specpoly_core::chromaticity(p, [1.0; 3]);
    [x, y, p[1]]
}

/// Runs `specpoly calibrate run`.
pub fn run(a: &RunArgs) -> Result<()> {
    let set = patches::standard(a.ramp_steps, a.verify)?;
    let ti3 = ti3_path(&a.output);
    if ti3 == a.output {
        return Err(CliError::usage(format!(
            "-o {}: name the calibration `.toml`; the readings go to `.ti3` beside it",
            a.output.display()
        )));
    }
    let display = patch_display::open(&a.display)?;
    line(&format!("display: {}", display.describe()))?;
    let (mut display, mut instrument) = instrument::open(&a.instrument, display)?;
    line(&format!("instrument: {}", instrument.describe()))?;
    let n_verify = set.iter().filter(|p| !p.kind.for_fit()).count();
    line(&format!(
        "{} patches ({} for the fit, {} to verify); readings → {}",
        set.len(),
        set.len() - n_verify,
        n_verify,
        ti3.display()
    ))?;
    let settle = a
        .settle
        .map(Duration::from_millis)
        .unwrap_or_else(|| display.default_settle());
    let info = Ti3Info {
        descriptor: "specpoly calibrate run".into(),
        instrument: Some(instrument.describe()),
        created: Some(file::now_utc()),
        absolute: true,
    };
    let taken = measure_all(display.as_mut(), instrument.as_mut(), &set, settle, |m| {
        save_ti3(&ti3, m, &info)
    })
    .map_err(|i| {
        let kept = if i.taken.is_empty() {
            "no readings taken".to_string()
        } else {
            format!("{} readings kept in {}", i.taken.len(), ti3.display())
        };
        match i.error {
            CliError::Usage(m) => CliError::usage(format!("{m}; {kept}")),
            e => CliError::data(format!("{e}; {kept}")),
        }
    })?;
    line(&format!(
        "measured {} patches → {}",
        taken.len(),
        ti3.display()
    ))?;
    if let Some(p) = raw_primaries(&set, &taken) {
        for (name, p) in ["red", "green", "blue"].iter().zip(p) {
            let c = xyy(p);
            line(&format!(
                "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (reading − black)",
                c[0], c[1], c[2]
            ))?;
        }
    }
    if let Some(sim) = display.simulation() {
        let m = sim.model();
        for (name, p) in ["red", "green", "blue"].iter().zip(m.primaries) {
            let c = xyy(p);
            line(&format!(
                "  {name:<5} x {:.4}  y {:.4}  Y {:.3} cd/m² (simulation's truth)",
                c[0], c[1], c[2]
            ))?;
        }
    }
    let (fit_set, verify_set) = split(&set, &taken);
    let cal = fit_and_save(&a.output, &ti3, &info, a.matrix, &fit_set, &verify_set)?;
    print_fit(&cal, &a.output)
}

/// Prints the fitted primaries and the fit's ΔE00.
fn print_fit(cal: &Calibration, out: &Path) -> Result<()> {
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
