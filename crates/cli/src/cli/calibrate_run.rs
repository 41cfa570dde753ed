//! `specpoly calibrate run`: measures a display ([`specpoly_calibrate::run`]) and prints what it
//! does as it goes.
//!
//! ```text
//! specpoly calibrate run --display D --instrument I -o CAL.toml [--ramp-steps N] [--verify N]
//!                        [--patches SET.ti1] [--resume | --force]
//! ```
//! writes `CAL.ti3` (every reading, committed atomically as it is taken; never overwritten:
//! see [`specpoly_calibrate::session`]) and `CAL.toml` (the fit of the non-verification
//! patches, with the readings file's SHA-256). One run per output: a second run on the same
//! `-o` stops at once ([`specpoly_calibrate::lock`]).

use crate::cli::calibrate::common::{
    fit_json, line, native_ti3_path, print_fit, set_json, RunArgs,
};
use crate::error::{CliError, Result};
use specpoly_calibrate::interrupt;
use specpoly_calibrate::lock::RunLock;
use specpoly_calibrate::run::{
    fit_and_save, measure_session, patch_set, raw_primaries, ti3_path, Devices,
};
use specpoly_calibrate::session::{Existing, Session};
use specpoly_display::calibration;
use specpoly_formats::cgats::Ti3Info;

/// The chromaticity ([`specpoly_core::chromaticity`]; a black reading shows the equal-energy
/// point) and luminance of an XYZ.
fn xyy(p: [f64; 3]) -> [f64; 3] {
    let [x, y] = specpoly_core::chromaticity(p, [1.0; 3]);
    [x, y, p[1]]
}

/// Runs `specpoly calibrate run`.
pub fn run(a: &RunArgs) -> Result<()> {
    set_json(a.json);
    let set = patch_set(a.patches.as_deref(), a.ramp_steps, a.verify)?;
    let ti3 = match a.target {
        Some(_) => native_ti3_path(&a.output),
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
    // one run per output, from before the readings are touched until the calibration is
    // written (released when `_lock` is dropped, or by the OS however the process ends)
    let (_lock, note) = RunLock::acquire(&a.output, &calibration::now_utc())?;
    if let Some(n) = note {
        eprintln!("{}", specpoly_formats::escape::one_line(&n));
    }
    let (mut session, note) = Session::open(&ti3, &set, existing, info.clone())?;
    if let Some(n) = note {
        eprintln!("{}", specpoly_formats::escape::one_line(&n));
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
    let truth = measure_session(&devices, &set, &mut session, &head, &mut |s| line(s))?;
    let taken = session.measurements();
    line(&format!(
        "measured {} patches → {}",
        taken.len(),
        ti3.display()
    ))?;
    crate::cli::wrote::wrote(&ti3, "");
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
    )?;
    crate::cli::wrote::wrote(&a.output, "");
    if a.json {
        let mut v = fit_json(&cal, &a.output, n_fit);
        v["readings"] = serde_json::json!(ti3.display().to_string());
        v["patches_measured"] = serde_json::json!(taken.len());
        v["patches_verify"] = serde_json::json!(n_verify);
        return Ok(specpoly_formats::stdout::print_json(&v)?);
    }
    print_fit(&cal, &a.output)
}
