//! `specpoly calibrate run … --target T`: measure the display, calibrate it to the target with
//! video LUTs ([`specpoly_display::target`]), then measure it again through the LUT and fit
//! that (the profile then describes the display with the LUT loaded, as ArgyllCMS's
//! `dispcal` + `dispread -k` + `colprof` do).
//!
//! Files, for `-o CAL.toml`: `CAL.native.ti3` (the readings without a LUT), `CAL.cal` (the
//! LUT, ArgyllCMS's format), `CAL.ti3` (the readings through the LUT, with the LUT as its
//! `CAL` table, as `dispread -k` writes it) and `CAL.toml` (their fit, with the LUT in its
//! `[video_lut]`).

use crate::cli::calibrate::common::{cal_path, line, print_fit, RunArgs};
use crate::error::Result;
use specpoly_calibrate::fit::{self, FitOptions};
use specpoly_calibrate::patches::Patch;
use specpoly_calibrate::run::{fit_and_save, record_session, split, ti3_path, Devices, Rig};
use specpoly_calibrate::session::{Existing, Session};
use specpoly_display::target::{self, Score, Target};
use specpoly_formats::cgats::Ti3Info;

/// What `calibrate run` hands over.
pub struct Context<'a> {
    /// The arguments.
    pub args: &'a RunArgs,
    /// `--target`.
    pub target: &'a Target,
    /// The patch set.
    pub set: &'a [Patch],
    /// The line saying what will be measured.
    pub head: &'a str,
    /// The devices.
    pub devices: &'a Devices<'a>,
    /// What to do with existing readings files.
    pub existing: Existing,
    /// The readings files' keywords.
    pub info: Ti3Info,
}

fn score_line(s: &Score) -> String {
    format!(
        "  iteration {}: white x {:.4} y {:.4} (Δxy {:.4}, ΔE00 {:.2}), {:.2} cd/m²; tone error {:.2} %; greys ΔE00 mean {:.2}, max {:.2}",
        s.iteration,
        s.white_xy[0],
        s.white_xy[1],
        s.white_delta_xy,
        s.white_delta_e00,
        s.white_luminance,
        s.tone_error_percent,
        s.grey_delta_e00_mean,
        s.grey_delta_e00_max
    )
}

/// Runs the calibration; `native` is the open session of the native readings.
pub fn run(c: &Context<'_>, native: &mut Session) -> Result<()> {
    let a = c.args;
    let mut rig = Rig::open(c.devices, &mut |s| line(s))?;
    line(c.head)?;
    line(&format!("target: {}", c.target))?;
    record_session(&mut rig, c.set, native)?;
    let taken = native.measurements();
    line(&format!(
        "measured {} patches → {} (native, no LUT)",
        taken.len(),
        c.devices.ti3.display()
    ))?;
    crate::cli::wrote::wrote(c.devices.ti3, " (native readings)");
    let (fit_set, verify_set) = split(c.set, &taken);
    let opts = FitOptions {
        matrix: a.matrix.into(),
        ..FitOptions::default()
    };
    let model = fit::fit_and_verify(&fit_set, &verify_set, &opts)?;
    let w = model.predict([1.0; 3]);
    let s = w[0] + w[1] + w[2];
    line(&format!(
        "native white x {:.4} y {:.4}, {:.2} cd/m²; calibrating ({} grey levels per iteration)",
        w[0] / s,
        w[1] / s,
        w[1],
        target::Options::default().levels
    ))?;
    let outcome = target::calibrate(
        &model,
        c.target,
        &mut rig,
        &target::Options::default(),
        &mut |s| Ok(line(&score_line(s))?),
    )?;
    for n in &outcome.notes {
        eprintln!("note: {n}");
    }
    let best = outcome.score();
    line(&format!(
        "kept iteration {} of {}: {}",
        best.iteration,
        outcome.scores.len(),
        if best.met() {
            format!(
                "target met (every grey within ΔE00 {})",
                target::GREY_TOLERANCE
            )
        } else {
            "the closest the display reaches".to_string()
        }
    ))?;
    let cal_file = cal_path(&a.output);
    outcome.lut.save_cal(
        &cal_file,
        "specpoly calibrate run",
        &target::cal_keywords(c.target, &outcome),
    )?;
    crate::cli::wrote::wrote(&cal_file, "");

    // the display with the LUT loaded: measure again and fit that
    rig.set_lut(Some(outcome.lut.clone()));
    let ti3 = ti3_path(&a.output);
    let (mut session, note) = Session::open(&ti3, c.set, c.existing, c.info.clone())?;
    if let Some(n) = note {
        eprintln!("{}", specpoly_formats::escape::one_line(&n));
    }
    record_session(&mut rig, c.set, &mut session)?;
    // the LUT as the readings' CAL table (as `dispread -k` writes it)
    let text = specpoly_formats::read::text(&ti3)?;
    let with_cal = format!(
        "{text}\n{}",
        outcome.lut.to_cal(
            "specpoly calibrate run",
            &target::cal_keywords(c.target, &outcome)
        )
    );
    specpoly_formats::atomic::write(&ti3, with_cal.as_bytes())?;
    let taken = session.measurements();
    line(&format!(
        "measured {} patches through the LUT → {}",
        taken.len(),
        ti3.display()
    ))?;
    crate::cli::wrote::wrote(&ti3, " (readings through the LUT)");
    let (mut cal, _) = fit_and_save(
        &a.output,
        &ti3,
        session.info(),
        a.matrix.into(),
        c.set,
        &taken,
    )?;
    cal.set_video_lut(Some(outcome.lut.clone()))?;
    cal.report_mut().1.notes.push(format!(
        "calibrated to {} with a video LUT ({}): the model holds while it is loaded",
        c.target,
        cal_file.display()
    ));
    cal.save(&a.output)?;
    crate::cli::wrote::wrote(&a.output, "");
    print_fit(&cal, &a.output)
}
