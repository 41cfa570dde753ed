//! `specpoly calibrate run`: show patches, read them, save the readings as CGATS .ti3 after
//! every patch, fit Cowan's model and write the calibration.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//! ```
//! writes `CAL.ti3` (all readings, rewritten atomically after each patch so an interrupted run
//! keeps what it measured) and `CAL.toml` (the fit of the non-verification patches).

use crate::calibrate::display::{self, PatchDisplay};
use crate::calibrate::instrument::{self, Instrument};
use crate::calibrate::measurement::Measurement;
use crate::calibrate::patches::Patch;
use crate::error::{CliError, Result};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Arguments of `specpoly calibrate run`.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Where patches are shown: `web[:PORT]` (a page on 127.0.0.1; open the printed URL),
    /// `manual` (prints the RGB, waits for Enter), `sim:SPD[,options]` (a simulated display,
    /// e.g. `sim:crt,noise=0.001`).
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
    /// 500 for web].
    #[arg(long, value_name = "MS")]
    pub settle: Option<u64>,
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
