//! `specpoly calibrate`: fit Cowan's model to measurements, show, predict, verify, export ICC,
//! and (`run`) measure a display. See docs/calibration.md.

use crate::error::{CliError, Result};
use specpoly_calibrate::fit::{self, FitOptions, InteractionChoice};
use specpoly_core::chromaticity;
use specpoly_display::calibration::{self, Calibration};
use specpoly_display::{export, icc};
use specpoly_formats::cgats;
use specpoly_formats::stdout::{print, print_json};
use std::path::PathBuf;

pub mod common;
pub mod values;

use common::fit_json;
use values::{
    BitsValue, FormatValue, IccVersionValue, MatrixFitArg, SourceValue, TransferValue, WhiteValue,
};

/// `specpoly calibrate` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum CalibrateCommand {
    /// Fit a calibration (Cowan's model) from a CGATS .ti3 (ArgyllCMS, DisplayCAL, `run`).
    Fit(FitArgs),
    /// Print a calibration's primaries, white, black and curves.
    Show(ShowArgs),
    /// Predict XYZ for device RGB triples (0–1) read from stdin, one per line, each answered
    /// as it arrives.
    Predict(crate::cli::calibrate_verify::PredictArgs),
    /// ΔE00 of a calibration's predictions against measured patches of a .ti3: DisplayCAL's and
    /// ISO 14861's criteria, pass/fail (exit 1 on a failure), optionally an HTML report.
    Verify(crate::cli::calibrate_verify::VerifyArgs),
    /// Export an ICC display profile (v2.4 or v4.4; matrix/TRC, `vcgt`, tables for models with
    /// channel interaction).
    Icc(IccArgs),
    /// Bake a framebuffer pixel transform (source RGB → panel codes) into C or Rust tables, or
    /// write the display model as a calibration blob for the C library (`--format c-blob`).
    Export(ExportArgs),
    /// Write a 3D LUT (.cube, .3dl, madVR .3dlut) from a source colour space (sRGB, Rec. 709,
    /// Display P3, Rec. 2020) to the display, inverted through its model.
    Lut3d(crate::cli::calibrate_lut3d::Lut3dArgs),
    /// Measure a display: show patches, read them, write CAL.ti3, fit and write CAL.toml.
    Run(common::RunArgs),
    /// Write the patch set `run` measures as an ArgyllCMS .ti1 (for dispread, or to edit and
    /// give back with `run --patches`).
    Patches(PatchesArgs),
    /// Measure a simulated display (QD-OLED, WLED, broadband, …) with a simulated
    /// spectrometer (a spectral .ti3, as dispread writes) or colorimeter.
    Simulate(crate::cli::calibrate_spectral::SimulateArgs),
    /// Write an ArgyllCMS .ccss (display spectral samples) from a spectral .ti3.
    Ccss(crate::cli::calibrate_spectral::CcssArgs),
    /// Write an ArgyllCMS .ccmx (colorimeter correction matrix) from a spectrometer's and a
    /// colorimeter's readings of the same patches.
    Ccmx(crate::cli::calibrate_spectral::CcmxArgs),
    /// Set display B's white (video LUT) to match display A's under an observer, and report the
    /// two whites' mismatch under the CIE 1931, 1964, 2015 and the viewer's observers.
    Match(crate::cli::calibrate_spectral::MatchArgs),
}

/// `calibrate patches`.
#[derive(Debug, clap::Args)]
pub struct PatchesArgs {
    /// The patch set to write (CGATS CTI1).
    #[arg(short, long, value_name = "SET.ti1")]
    pub output: PathBuf,
    /// Levels per channel ramp, 0 and 1 included (2–256).
    #[arg(long, default_value_t = 9, value_name = "N")]
    pub ramp_steps: usize,
    /// Verification patches (spread over the RGB cube).
    #[arg(long, default_value_t = 16, value_name = "N")]
    pub verify: usize,
}

/// `calibrate fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// The measurements (CGATS .ti3 with RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z).
    #[arg(long)]
    pub ti3: PathBuf,
    /// The calibration file to write (TOML).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The transfer curve the model uses (both are fitted and stored).
    #[arg(long, value_enum, default_value_t = TransferValue::Table)]
    pub transfer: TransferValue,
    /// How the matrix is found.
    #[arg(long, value_enum, default_value_t = MatrixFitArg::LeastSquares)]
    pub matrix: MatrixFitArg,
    /// Points of each transfer table (2–64).
    #[arg(long, default_value_t = 64)]
    pub table_points: usize,
    /// Hold out every 5th patch that is not black, white or a single-channel ramp step,
    /// and report ΔE00 on them (stored in the file's [fit.verification]).
    #[arg(long)]
    pub hold_out: bool,
    /// The channel-interaction lattice: auto (chosen by cross-validation), none, or its
    /// nodes per side (2–17).
    #[arg(long, default_value = "auto", value_name = "auto|none|N")]
    pub interaction: InteractionChoice,
    /// Keep every patch (no outlier test).
    #[arg(long)]
    pub keep_outliers: bool,
    /// Fit the model under this observer: every patch's XYZ recomputed from its spectrum in a
    /// spectral .ti3 (1931, 1964, 2015-2, 2015-10, cie2006:age=A,field=F, or FILE.csv of three
    /// sensitivities) [default: the file's XYZ, CIE 1931].
    #[arg(long, value_name = "NAME|FILE", value_parser = crate::cli::args::observer)]
    pub observer: Option<specpoly_core::Observer>,
    /// JSON instead of text (keys in docs/calibration.md).
    #[arg(long)]
    pub json: bool,
}

/// `calibrate show`.
#[derive(Debug, clap::Args)]
pub struct ShowArgs {
    /// The calibration file.
    pub calibration: PathBuf,
    /// JSON instead of text (keys in docs/calibration.md).
    #[arg(long)]
    pub json: bool,
}

/// `calibrate icc`.
#[derive(Debug, clap::Args)]
pub struct IccArgs {
    /// The calibration file.
    pub calibration: PathBuf,
    /// The profile to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The profile's description (`desc`); default: the display's name (the measurements' file
    /// name), else the calibration file's name.
    #[arg(long)]
    pub description: Option<String>,
    /// ICC version: 2 (v2.4, read by every consumer, ArgyllCMS 2.3 included) or 4 (v4.4).
    #[arg(long, value_enum, default_value = "2", value_name = "2|4")]
    pub version: IccVersionValue,
    /// Also write `A2B0`/`B2A0` tables sampled from the model [default: when the model has
    /// channel interaction].
    #[arg(long)]
    pub tables: bool,
}

/// `calibrate export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// The calibration file.
    #[arg(long)]
    pub calibration: PathBuf,
    /// The colour space the firmware's UI draws in.
    #[arg(long, value_enum, default_value_t = SourceValue::Srgb)]
    pub source: SourceValue,
    /// C header or Rust source, or the C library's calibration blob.
    #[arg(long, value_enum)]
    pub format: FormatValue,
    /// The panel's bits per channel.
    #[arg(long, value_enum, default_value_t = BitsValue::Rgb565)]
    pub bits: BitsValue,
    /// The source white: adapted to the panel's, or kept.
    #[arg(long, value_enum, default_value_t = WhiteValue::Adapt)]
    pub white: WhiteValue,
    /// The tables' name prefix (a C/Rust identifier).
    #[arg(long, default_value = "panel", value_parser = export::identifier)]
    pub name: String,
    /// The file to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Runs `specpoly calibrate`.
pub fn run(c: CalibrateCommand) -> Result<()> {
    match c {
        CalibrateCommand::Fit(a) => fit_cmd(&a),
        CalibrateCommand::Show(a) => show(&a),
        CalibrateCommand::Predict(a) => crate::cli::calibrate_verify::predict(&a),
        CalibrateCommand::Verify(a) => crate::cli::calibrate_verify::verify(&a),
        CalibrateCommand::Icc(a) => icc_cmd(&a),
        CalibrateCommand::Export(a) => export_cmd(&a),
        CalibrateCommand::Lut3d(a) => crate::cli::calibrate_lut3d::run(&a),
        CalibrateCommand::Run(a) => crate::cli::calibrate_run::run(&a),
        CalibrateCommand::Patches(a) => patches_cmd(&a),
        CalibrateCommand::Simulate(a) => crate::cli::calibrate_spectral::simulate(&a),
        CalibrateCommand::Ccss(a) => crate::cli::calibrate_spectral::ccss_cmd(&a),
        CalibrateCommand::Ccmx(a) => crate::cli::calibrate_spectral::ccmx_cmd(&a),
        CalibrateCommand::Match(a) => crate::cli::calibrate_spectral::match_cmd(&a),
    }
}

fn patches_cmd(a: &PatchesArgs) -> Result<()> {
    let set = specpoly_calibrate::patches::standard(a.ramp_steps, a.verify)?;
    let devices: Vec<[f64; 3]> = set.iter().map(|p| p.device).collect();
    let text = specpoly_formats::ti1::write_ti1(&devices, "specpoly calibrate patches");
    specpoly_formats::atomic::write(&a.output, text.as_bytes())?;
    crate::cli::wrote::wrote(&a.output, &format!(" ({} patches)", set.len()));
    Ok(())
}

fn fit_cmd(a: &FitArgs) -> Result<()> {
    // the bytes read are the bytes hashed: the calibration names the readings it came from
    let bytes = specpoly_formats::read::bytes(&a.ti3)?;
    let readings_sha256 = specpoly_calibrate::session::sha256_hex(&bytes);
    let mut ti3 = cgats::read_ti3(
        &specpoly_formats::read::decode(bytes),
        &a.ti3.display().to_string(),
    )?;
    if let Some(o) = a.observer {
        let xyz =
            specpoly_calibrate::spectral_display::xyz_under(&ti3, o, &a.ti3.display().to_string())?;
        for (m, v) in ti3.measurements.iter_mut().zip(xyz) {
            m.xyz = v;
        }
    }
    let (meas, absolute) = ti3.best_units();
    // repeated white and black readings that disagree (patches numbered in the file)
    let drift = specpoly_calibrate::drift::check(&meas);
    // the fit numbers its outliers by position in what it is given: with --hold-out that is
    // the fit set, renumbered below as positions in the file (one numbering for fit and verify)
    let fit_positions = if a.hold_out {
        fit::hold_out_indices(&meas).0
    } else {
        (0..meas.len()).collect()
    };
    let (fit_set, verify_set) = if a.hold_out {
        fit::hold_out(meas)
    } else {
        (meas, Vec::new())
    };
    let opts = FitOptions {
        transfer: a.transfer.into(),
        matrix: a.matrix.into(),
        table_points: a.table_points,
        absolute,
        interaction: a.interaction,
        robust: !a.keep_outliers,
        observer: a.observer.unwrap_or(specpoly_core::Observer::Cie1931),
        ..Default::default()
    };
    let mut cal = fit::fit_and_verify(&fit_set, &verify_set, &opts)
        .map_err(|e| CliError::data(format!("{}: {e}", a.ti3.display())))?;
    let (report, prov) = cal.report_mut();
    for o in &mut report.outliers {
        if let Some(p) = o.patch.checked_sub(1).and_then(|i| fit_positions.get(i)) {
            o.patch = p + 1;
        }
    }
    prov.notes.extend(drift.iter().map(|d| d.note()));
    if let Some(o) = a.observer {
        prov.notes.push(format!(
            "XYZ computed from the readings' spectra under the {} observer (observer {})",
            o.label(),
            o.name()
        ));
    }
    fit::provenance::record(
        &mut cal,
        &ti3,
        &a.ti3.display().to_string(),
        readings_sha256,
    )?;
    cal.save(&a.output)?;
    crate::cli::wrote::wrote(&a.output, "");
    if a.json {
        return Ok(print_json(&fit_json(&cal, &a.output, fit_set.len()))?);
    }
    let d = cal.data();
    let mut s = format!(
        "fitted {} patches from {} → {}\n",
        fit_set.len(),
        a.ti3.display(),
        a.output.display()
    );
    s.push_str(&format!(
        "fit ΔE00: mean {:.3}, p95 {:.3}, max {:.3}\n",
        d.fit.residual.mean, d.fit.residual.p95, d.fit.residual.max
    ));
    if let Some(v) = d.fit.verification {
        s.push_str(&format!(
            "held-out ΔE00 ({} patches): mean {:.3}, p95 {:.3}, max {:.3}\n",
            v.n, v.mean, v.p95, v.max
        ));
    }
    if let (Some(de), Some(pc)) = (
        d.fit.additivity_delta_e00,
        d.fit.additivity_luminance_percent,
    ) {
        s.push_str(&format!(
            "additivity (R+G+B−2·black vs white): ΔE00 {de:.3}, luminance {pc:+.2} %\n"
        ));
    }
    s.push_str(&fit_facts(&d.fit));
    for n in &d.provenance.notes {
        s.push_str(&format!("note: {n}\n"));
    }
    Ok(print(&s)?)
}

/// What the fit decided, one line each: the model and how it was chosen, the patches dropped
/// as bad readings, the primaries constrained.
pub fn fit_facts(f: &calibration::FitReport) -> String {
    let mut s = String::new();
    if !f.model.is_empty() {
        let cv: Vec<String> = f
            .candidates
            .iter()
            .map(|c| format!("{} {:.3}", c.model, c.cv_mean))
            .collect();
        s.push_str(&format!("model: {}", f.model));
        if !cv.is_empty() {
            s.push_str(&format!(" (cross-validated ΔE00 mean: {})", cv.join(", ")));
        }
        s.push('\n');
    }
    for o in &f.outliers {
        s.push_str(&format!(
            "outlier dropped: patch {} (RGB {:.4} {:.4} {:.4}): {}\n",
            o.patch, o.device[0], o.device[1], o.device[2], o.reason
        ));
    }
    for c in &f.constrained {
        s.push_str(&format!("constrained: {c}\n"));
    }
    s
}

/// The JSON `calibrate show --json` prints (keys documented in docs/calibration.md).
pub fn show_json(cal: &Calibration) -> serde_json::Value {
    let d = cal.data();
    let prim = |p: &calibration::Primary| serde_json::json!({"x": p.x, "y": p.y, "Y": p.luminance});
    let xyy = |v: [f64; 3]| {
        let [x, y] = chromaticity(v, d.white);
        serde_json::json!({"X": v[0], "Y": v[1], "Z": v[2], "x": x, "y": y})
    };
    serde_json::json!({
        "format": d.format,
        "version": d.version,
        "units": d.units,
        "primaries": {
            "red": prim(&d.primaries.red),
            "green": prim(&d.primaries.green),
            "blue": prim(&d.primaries.blue),
        },
        "white": xyy(d.white),
        "black": xyy(d.black),
        "contrast": d.white[1] / d.black[1].max(f64::MIN_POSITIVE),
        "transfer": d.transfer.kind,
        "gamma": d.transfer.gamma,
        "matrix": d.fit.matrix,
        "fit": d.fit,
        "provenance": d.provenance,
    })
}

fn show(a: &ShowArgs) -> Result<()> {
    let cal = calibration::load(&a.calibration)?;
    if a.json {
        return Ok(print_json(&show_json(&cal))?);
    }
    let d = cal.data();
    let u = if cal.absolute() { "cd/m²" } else { "relative" };
    let mut s = format!("{}  (units: {u})\n", a.calibration.display());
    s.push_str("          x        y        Y\n");
    for (n, p) in ["red", "green", "blue"].iter().zip(d.primaries.array()) {
        s.push_str(&format!(
            "{n:<6} {:8.4} {:8.4} {:10.4}\n",
            p.x, p.y, p.luminance
        ));
    }
    for (n, v) in [("white", d.white), ("black", d.black)] {
        let [x, y] = chromaticity(v, d.white);
        s.push_str(&format!("{n:<6} {x:8.4} {y:8.4} {:10.4}\n", v[1]));
    }
    s.push_str(&format!(
        "gamma  R {:.3}  G {:.3}  B {:.3}  (model uses the {} curve)\n",
        d.transfer.gamma[0],
        d.transfer.gamma[1],
        d.transfer.gamma[2],
        crate::cli::args::name(&TransferValue::from(d.transfer.kind))
    ));
    s.push_str(&format!(
        "matrix {}; fit ΔE00 mean {:.3}, max {:.3} over {} patches\n",
        d.fit.matrix, d.fit.residual.mean, d.fit.residual.max, d.fit.residual.n
    ));
    if let Some(v) = d.fit.verification {
        s.push_str(&format!(
            "held-out ΔE00 mean {:.3}, p95 {:.3}, max {:.3} over {} patches\n",
            v.mean, v.p95, v.max, v.n
        ));
    }
    s.push_str(&fit_facts(&d.fit));
    s.push_str(&format!(
        "source {} (fitted {})\n",
        d.provenance.source, d.provenance.created
    ));
    Ok(print(&s)?)
}

fn icc_cmd(a: &IccArgs) -> Result<()> {
    let cal = calibration::load(&a.calibration)?;
    let desc = a
        .description
        .clone()
        .unwrap_or_else(|| icc::description(&cal, &a.calibration));
    let auto = icc::IccOptions::for_calibration(&cal);
    let opts = icc::IccOptions {
        version: a.version.into(),
        tables: a.tables || auto.tables,
    };
    let bytes = icc::build(&cal, &desc, &opts)?;
    specpoly_formats::atomic::write(&a.output, &bytes)?;
    let version = match a.version {
        IccVersionValue::V2 => "v2.4",
        IccVersionValue::V4 => "v4.4",
    };
    let mut what = format!("ICC {version} matrix/TRC display profile");
    if opts.tables {
        what.push_str(", A2B0/B2A0 tables");
    }
    if let Some(l) = cal.video_lut() {
        what.push_str(&format!(", vcgt of {} entries", l.len()));
    }
    crate::cli::wrote::wrote(&a.output, &format!(" ({} bytes, {what})", bytes.len()));
    Ok(())
}

fn export_cmd(a: &ExportArgs) -> Result<()> {
    let cal = calibration::load(&a.calibration)?;
    if a.format == FormatValue::CBlob {
        let bytes = export::blob(&cal)?;
        specpoly_formats::atomic::write(&a.output, &bytes)?;
        crate::cli::wrote::wrote(
            &a.output,
            &format!(
                " ({} bytes: calibration blob version {}, for sp_calibration_load)",
                bytes.len(),
                specpoly_core::blob::VERSION
            ),
        );
        return Ok(());
    }
    let p = export::transform(&cal, a.source.into(), a.white.into(), a.bits.into())?;
    let origin = format!(
        "calibration {}, source {}, white {}, {}",
        a.calibration.display(),
        crate::cli::args::name(&a.source),
        crate::cli::args::name(&a.white),
        crate::cli::args::name(&a.bits)
    );
    let text = export::source_text(&p, a.format.into(), &a.name, &origin)?;
    specpoly_formats::atomic::write(&a.output, text.as_bytes())?;
    crate::cli::wrote::wrote(
        &a.output,
        &format!(
            " ({} bytes of tables)",
            specpoly_core::pixel::PanelTransform::TABLE_BYTES
        ),
    );
    Ok(())
}
