//! `specpoly calibrate simulate | ccss | ccmx | match`: spectral measurements of a display,
//! ArgyllCMS colorimeter corrections made from them, and two displays' whites matched for an
//! observer. See docs/calibration.md, "Spectral displays and observers".
//!
//! Every output is checked whole before it is written (atomically): a bad input writes
//! nothing.

use crate::cli::args::observer;
use crate::error::{CliError, Result};
use specpoly_calibrate::corrections::{fit_ccmx, Colorimeter};
use specpoly_calibrate::matching::{self, Mismatch};
use specpoly_calibrate::patches;
use specpoly_calibrate::sim::{spectrum_xyz, SimModel};
use specpoly_calibrate::spectral_display::SpectralDisplay;
use specpoly_calibrate::Measurement;
use specpoly_core::Observer;
use specpoly_formats::cgats::{self, Ti3Info};
use specpoly_formats::spectral::{Bands, SpectralSet};
use specpoly_formats::{ccmx, ccss};
use std::path::{Path, PathBuf};

/// Which simulated instrument `simulate` reads with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SimInstrumentValue {
    /// A spectroradiometer: spectra 380–780 nm at 1 nm, and their CIE 1931 XYZ.
    Spectrometer,
    /// The simulated three-filter colorimeter (factory-calibrated on a broadband display).
    Colorimeter,
}

/// `calibrate simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// The simulated display: `sim:qdoled`, `sim:wled`, `sim:broadband`, `sim:crt` or
    /// `sim:FILE.csv`, with options (`sim:wled,white=120,black=0.2`).
    #[arg(long)]
    pub display: String,
    /// The instrument.
    #[arg(long, value_enum, default_value_t = SimInstrumentValue::Spectrometer)]
    pub instrument: SimInstrumentValue,
    /// Levels per channel ramp of the patch set (`calibrate patches`).
    #[arg(long, default_value_t = 5, value_name = "N")]
    pub ramp_steps: usize,
    /// Verification patches of the patch set.
    #[arg(long, default_value_t = 8, value_name = "N")]
    pub verify: usize,
    /// The observer the spectrometer's XYZ fields are computed under (1931, 1964, 2015-2,
    /// 2015-10, cie2006:age=A,field=F, or FILE.csv); the colorimeter reads through its own
    /// filters, so it takes 1931 only.
    #[arg(long, default_value = "1931", value_name = "NAME|FILE", value_parser = observer)]
    pub observer: Observer,
    /// The .ti3 to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// `calibrate ccss`.
#[derive(Debug, clap::Args)]
pub struct CcssArgs {
    /// Spectral measurements (a .ti3 with SPECTRAL_BANDS and SPEC_… fields).
    #[arg(long)]
    pub ti3: PathBuf,
    /// ArgyllCMS's display technology (`ccxxmake -??` lists them).
    #[arg(long, default_value = "LCD White LED")]
    pub technology: String,
    /// The display's make and model.
    #[arg(long)]
    pub display: Option<String>,
    /// The .ccss to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// `calibrate ccmx`.
#[derive(Debug, clap::Args)]
pub struct CcmxArgs {
    /// The reference instrument's readings (spectrometer) of the patches (.ti3).
    #[arg(long)]
    pub reference: PathBuf,
    /// The colorimeter's readings of the same patches, in the same order (.ti3).
    #[arg(long)]
    pub colorimeter: PathBuf,
    /// ArgyllCMS's display technology.
    #[arg(long, default_value = "LCD White LED")]
    pub technology: String,
    /// The display's make and model.
    #[arg(long)]
    pub display: Option<String>,
    /// The .ccmx to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// `calibrate match`.
#[derive(Debug, clap::Args)]
pub struct MatchArgs {
    /// Display A, the one to match: `sim:…` or a spectral .ti3.
    #[arg(long)]
    pub a: String,
    /// Display B, the one set to A's white: `sim:…` or a spectral .ti3.
    #[arg(long)]
    pub b: String,
    /// The observer the whites match under: 1931, 1964, 2015-2, 2015-10,
    /// cie2006:age=A,field=F (CIE 170-1, ages 20-80, fields 2-10°), or FILE.csv of three
    /// sensitivities.
    #[arg(long, default_value = "2015-10", value_name = "NAME|FILE", value_parser = observer)]
    pub observer: Observer,
    /// The viewer's observer (the same forms), reported besides the CIE ones.
    #[arg(long, value_name = "NAME|FILE", value_parser = observer)]
    pub viewer: Option<Observer>,
    /// B's video LUT to write (ArgyllCMS .cal, 256 entries, 16-bit values).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// The figure: both whites on the u′v′ diagram, per observer (.svg or .png).
    #[arg(long)]
    pub figure: Option<PathBuf>,
    /// JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The simulated model of `sim:…`.
fn sim(spec: &str) -> Result<SimModel> {
    let rest = spec.strip_prefix("sim:").ok_or_else(|| {
        CliError::usage(format!(
            "`{spec}`: a simulated display is `sim:qdoled`, `sim:wled`, `sim:broadband`, `sim:crt` or `sim:FILE.csv`"
        ))
    })?;
    Ok(SimModel::parse(rest)?)
}

/// A display for `match`: `sim:…` or a spectral `.ti3`.
fn display(spec: &str) -> Result<SpectralDisplay> {
    if spec.starts_with("sim:") {
        return Ok(SpectralDisplay::from_sim(&sim(spec)?));
    }
    let t = cgats::read_ti3_file(Path::new(spec))?;
    Ok(SpectralDisplay::from_ti3(&t, spec)?)
}

/// Runs `calibrate simulate`.
pub fn simulate(a: &SimulateArgs) -> Result<()> {
    let spectral = a.instrument == SimInstrumentValue::Spectrometer;
    if !spectral && a.observer != Observer::Cie1931 {
        return Err(CliError::usage(format!(
            "--observer {}: the colorimeter reads through its own filters (factory-calibrated to CIE 1931); simulate a spectrometer for another observer",
            a.observer.name()
        )));
    }
    let m = sim(&a.display)?;
    let set = patches::standard(a.ramp_steps, a.verify)?;
    let spectra: Vec<Vec<f64>> = set.iter().map(|p| m.spectrum(p.device)).collect();
    let colorimeter = Colorimeter::simulated();
    let meas: Vec<Measurement> = set
        .iter()
        .zip(&spectra)
        .map(|(p, s)| Measurement {
            device: p.device,
            xyz: if spectral {
                spectrum_xyz(a.observer, s)
            } else {
                colorimeter.read(s)
            },
        })
        .collect();
    let mut keywords = vec![
        (
            "INSTRUMENT_TYPE_SPECTRAL".to_string(),
            if spectral { "YES" } else { "NO" }.to_string(),
        ),
        ("DISPLAY_TYPE_REFRESH".to_string(), "NO".to_string()),
    ];
    if !spectral {
        keywords.push(("DISPLAY_TYPE_BASE_ID".to_string(), "1".to_string()));
    }
    let info = Ti3Info {
        instrument: Some(
            if spectral {
                "specpoly simulated spectrometer"
            } else {
                "specpoly simulated colorimeter"
            }
            .to_string(),
        ),
        created: Some(specpoly_display::calibration::now_utc()),
        absolute: true,
        keywords,
        ..Default::default()
    };
    let text = if spectral {
        // mW·sr⁻¹·m⁻²·nm⁻¹, as ArgyllCMS's instruments report
        let set = SpectralSet {
            bands: Bands::visible_1nm(),
            samples: spectra
                .iter()
                .map(|s| s.iter().map(|v| v * 1000.0).collect())
                .collect(),
        };
        cgats::write_spectral_ti3(&meas, &set, &info)?
    } else {
        cgats::write_ti3(&meas, &info)?
    };
    specpoly_formats::atomic::write(&a.output, text.as_bytes())?;
    crate::cli::wrote::wrote(
        &a.output,
        &format!(
            " ({} patches of the {}, {})",
            meas.len(),
            m.describe(),
            if spectral {
                format!(
                    "spectra 380–780 nm at 1 nm, XYZ under the {} observer",
                    a.observer.label()
                )
            } else {
                "simulated colorimeter".to_string()
            }
        ),
    );
    Ok(())
}

/// Runs `calibrate ccss`.
pub fn ccss_cmd(a: &CcssArgs) -> Result<()> {
    let name = a.ti3.display().to_string();
    let t = cgats::read_ti3_file(&a.ti3)?;
    let spectra = t.spectra.as_ref().ok_or_else(|| {
        CliError::Data(format!(
            "{name}: no spectra (SPECTRAL_BANDS and SPEC_… fields): measure with a spectrometer"
        ))
    })?;
    let c = ccss::Ccss {
        description: format!(
            "CCSS for {}",
            a.display.as_deref().unwrap_or(a.technology.as_str())
        ),
        display: a.display.clone(),
        technology: a.technology.clone(),
        refresh: t
            .keyword("DISPLAY_TYPE_REFRESH")
            .is_some_and(|v| v.eq_ignore_ascii_case("YES")),
        reference: t.keyword("TARGET_INSTRUMENT").map(str::to_string),
        created: Some(specpoly_display::calibration::now_utc()),
        samples: ccss::Ccss::normalise(spectra)?,
    };
    let text = ccss::write(&c)?;
    specpoly_formats::atomic::write(&a.output, text.as_bytes())?;
    crate::cli::wrote::wrote(
        &a.output,
        &format!(
            " ({} spectral samples, {}–{} nm, {} bands)",
            c.samples.samples.len(),
            c.samples.bands.start_nm,
            c.samples.bands.end_nm,
            c.samples.bands.count
        ),
    );
    Ok(())
}

/// Runs `calibrate ccmx`.
pub fn ccmx_cmd(a: &CcmxArgs) -> Result<()> {
    let r = cgats::read_ti3_file(&a.reference)?;
    let c = cgats::read_ti3_file(&a.colorimeter)?;
    let xyz =
        |t: &cgats::Ti3| -> Vec<[f64; 3]> { t.best_units().0.iter().map(|m| m.xyz).collect() };
    let (refs, cols) = (xyz(&r), xyz(&c));
    if let Some(i) = (0..refs.len().min(cols.len()))
        .find(|&i| r.measurements[i].device != c.measurements[i].device)
    {
        return Err(CliError::Data(format!(
            "patch {}: the reference measured device {:?}, the colorimeter {:?}: the same patches, in the same order",
            i + 1,
            r.measurements[i].device,
            c.measurements[i].device
        )));
    }
    let fit = fit_ccmx(&refs, &cols)?;
    let instrument = c
        .keyword("TARGET_INSTRUMENT")
        .unwrap_or("colorimeter")
        .to_string();
    let disp = a.display.as_deref().unwrap_or(a.technology.as_str());
    let m = ccmx::Ccmx {
        description: format!("{instrument} & {disp}"),
        instrument,
        display: a.display.clone(),
        technology: a.technology.clone(),
        base_id: c
            .keyword("DISPLAY_TYPE_BASE_ID")
            .and_then(|v| v.trim().parse().ok())
            .or(Some(1)),
        refresh: Some(
            c.keyword("DISPLAY_TYPE_REFRESH")
                .is_some_and(|v| v.eq_ignore_ascii_case("YES")),
        ),
        reference: r.keyword("TARGET_INSTRUMENT").map(str::to_string),
        created: Some(specpoly_display::calibration::now_utc()),
        matrix: fit.matrix,
    };
    let text = ccmx::write(&m)?;
    specpoly_formats::atomic::write(&a.output, text.as_bytes())?;
    crate::cli::wrote::wrote(
        &a.output,
        &format!(
            " ({} patches; CIE94 ΔE after correction: mean {:.3}, max {:.3})",
            refs.len(),
            fit.mean_de94,
            fit.max_de94
        ),
    );
    for row in &fit.matrix {
        println!("{:.6} {:.6} {:.6}", row[0], row[1], row[2]);
    }
    Ok(())
}

/// The figure of `match`: per observer, A's and B's whites on the u′v′ diagram, joined.
fn figure(rows: &[Mismatch], a: &str, b: &str, under: Observer) -> specpoly_plot::Figure {
    use specpoly_plot::{Figure, Series, Style};
    const COLOURS: [[u8; 3]; 6] = [
        [0, 90, 181],
        [220, 50, 32],
        [0, 150, 60],
        [150, 60, 180],
        [230, 140, 0],
        [90, 90, 90],
    ];
    let mut series = Vec::new();
    let (mut u0, mut u1, mut v0, mut v1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (k, r) in rows.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        for p in [r.a_uv, r.b_uv] {
            u0 = u0.min(p[0]);
            u1 = u1.max(p[0]);
            v0 = v0.min(p[1]);
            v1 = v1.max(p[1]);
        }
        series.push(Series {
            label: Some(format!(
                "{}: Δu′v′ {:.4}, ΔE00 {:.2}",
                r.observer.label(),
                r.delta_uv,
                r.delta_e00
            )),
            colour,
            style: Style::Line {
                width: 1.5,
                dash: None,
            },
            points: vec![(r.a_uv[0], r.a_uv[1]), (r.b_uv[0], r.b_uv[1])],
        });
        series.push(Series {
            label: None,
            colour,
            style: Style::Points(5.0),
            points: vec![(r.a_uv[0], r.a_uv[1])],
        });
        series.push(Series {
            label: None,
            colour,
            style: Style::Points(2.5),
            points: vec![(r.b_uv[0], r.b_uv[1])],
        });
    }
    let pad = ((u1 - u0).max(v1 - v0) * 0.15).max(0.0005);
    Figure {
        width: 900,
        height: 600,
        title: format!(
            "White of {b} matched to {a} under {} (large dot {a}, small {b})",
            under.label()
        ),
        x_label: "u′".into(),
        y_label: "v′".into(),
        x_range: (u0 - pad, u1 + pad),
        y_range: Some((v0 - pad, v1 + pad)),
        series,
        markers: Vec::new(),
    }
}

/// Runs `calibrate match`.
pub fn match_cmd(a: &MatchArgs) -> Result<()> {
    // every output checked before any is written
    let figure_format = match &a.figure {
        None => None,
        Some(p) => match p
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => Some(false),
            Some("png") => Some(true),
            _ => {
                return Err(CliError::usage(format!(
                    "{}: the figure must end in .svg or .png",
                    p.display()
                )))
            }
        },
    };
    let da = display(&a.a)?;
    let db = display(&a.b)?;
    let matched = matching::match_white(&da, &db, a.observer)?;
    let mut observers = Observer::ALL.to_vec();
    for v in [Some(a.observer), a.viewer].into_iter().flatten() {
        if !observers.contains(&v) {
            observers.push(v);
        }
    }
    let rows: Vec<Mismatch> = observers
        .iter()
        .map(|o| matching::mismatch(&da, &db, &matched, *o))
        .collect();
    let lut = specpoly_display::video_lut::VideoLut::new(
        matched.lut.iter().map(|e| e[0] as f64 / 65535.0).collect(),
        matched.lut.iter().map(|e| e[1] as f64 / 65535.0).collect(),
        matched.lut.iter().map(|e| e[2] as f64 / 65535.0).collect(),
    )?;
    let cal = lut.to_cal(
        "specpoly calibrate match",
        &[("TARGET_OBSERVER".to_string(), a.observer.name().to_string())],
    );
    let fig = match figure_format {
        None => None,
        Some(png) => {
            let f = figure(&rows, &a.a, &a.b, a.observer);
            Some(if png { f.png()? } else { f.svg()?.into_bytes() })
        }
    };
    if let Some(p) = &a.output {
        specpoly_formats::atomic::write(p, cal.as_bytes())?;
        crate::cli::wrote::wrote(
            p,
            &format!(
                " (B's video LUT: white at {:.5} {:.5} {:.5}, 16-bit)",
                matched.white_codes[0], matched.white_codes[1], matched.white_codes[2]
            ),
        );
    }
    if let (Some(p), Some(bytes)) = (&a.figure, fig) {
        specpoly_formats::atomic::write(p, &bytes)?;
        crate::cli::wrote::wrote(p, "");
    }
    if a.json {
        let j = serde_json::json!({
            "a": a.a,
            "b": a.b,
            "observer": a.observer.name(),
            "white_codes": matched.white_codes,
            "white_lut16": matched.white_lut16,
            "luminance_ratio": matched.luminance_ratio,
            "mismatch": rows.iter().map(|r| serde_json::json!({
                "observer": r.observer.name(),
                "a_uv": r.a_uv,
                "b_uv": r.b_uv,
                "delta_uv": r.delta_uv,
                "delta_e00": r.delta_e00,
            })).collect::<Vec<_>>(),
        });
        println!("{j:#}");
        return Ok(());
    }
    println!(
        "B ({}) matched to A ({}) under the {} observer: B's white at device {:.5} {:.5} {:.5} (16-bit {} {} {}), {:.1} % of A's luminance",
        a.b,
        a.a,
        a.observer.label(),
        matched.white_codes[0],
        matched.white_codes[1],
        matched.white_codes[2],
        matched.white_lut16[0],
        matched.white_lut16[1],
        matched.white_lut16[2],
        100.0 * matched.luminance_ratio
    );
    // a runtime observer's name (a CIE 2006 one, a file) may be longer than the CIE labels
    let w = rows
        .iter()
        .map(|r| r.observer.label().chars().count())
        .max()
        .unwrap_or(0)
        .max(16);
    println!(
        "{:<w$}  A u′      A v′      B u′      B v′      Δu′v′    ΔE00",
        "observer"
    );
    for r in &rows {
        println!(
            "{:<w$}  {:.5}   {:.5}   {:.5}   {:.5}   {:.5}  {:.2}{}",
            r.observer.label(),
            r.a_uv[0],
            r.a_uv[1],
            r.b_uv[0],
            r.b_uv[1],
            r.delta_uv,
            r.delta_e00,
            if r.observer == a.observer {
                "  (matched)"
            } else {
                ""
            }
        );
    }
    Ok(())
}
