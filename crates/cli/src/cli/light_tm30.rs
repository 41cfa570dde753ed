//! `specpoly light SPD --tm30 | --cvg FILE | --report FILE`: ANSI/IES TM-30-20 in full for one
//! light (computations in [`specpoly_spectra::light_tm30`], drawing in
//! [`specpoly_plot::vector_graphic`] and [`specpoly_plot::tm30_page`]).
//!
//! Options of `light` rather than a `tm30` command: TM-30 describes the same light `light`
//! reports, named and refused (short range, `--extrapolate`) the same way, so its detail is more
//! output of that command, as `--json` is; a second command would repeat the argument and the
//! checks. Every file is computed whole before any is written, and written atomically: a light
//! without a CCT or an unwritable path leaves no file.

use crate::error::{CliError, Result};
use specpoly_formats::atomic;
use specpoly_formats::escape::one_line;
use specpoly_plot::tm30_page::{Tm30Page, HEIGHT, WIDTH};
use specpoly_plot::vector_graphic::VectorGraphic;
use specpoly_spectra::light::LightReport;
use specpoly_spectra::light_tm30::{tm30_report, Tm30Report};
use specpoly_spectra::spectrum_names::Named;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Side of the colour vector graphic `--cvg` writes, px.
pub const CVG_SIZE: u32 = 600;

/// How long Chromium may take to render the report.
const CHROMIUM_TIMEOUT: Duration = Duration::from_secs(60);

/// What the TM-30 options asked for.
pub struct Tm30Args<'a> {
    /// Print the hue bins and samples.
    pub print: bool,
    /// As JSON.
    pub json: bool,
    /// Write the colour vector graphic here (.svg or .png).
    pub cvg: Option<&'a Path>,
    /// Write the report here (.html or .png).
    pub report: Option<&'a Path>,
    /// Hold the end values of a short light.
    pub extrapolate: bool,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Svg,
    Png,
    Html,
}

fn kind(path: &Path, allowed: &[(&str, Kind)], what: &str) -> Result<Kind> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    allowed
        .iter()
        .find(|(e, _)| Some(*e) == ext.as_deref())
        .map(|(_, k)| *k)
        .ok_or_else(|| {
            let names: Vec<String> = allowed.iter().map(|(e, _)| format!(".{e}")).collect();
            CliError::usage(format!(
                "{}: {what} must end in {}",
                one_line(&path.display().to_string()),
                names.join(" or ")
            ))
        })
}

/// The colour vector graphic of a report.
pub fn graphic(t: &Tm30Report, size: u32) -> VectorGraphic {
    VectorGraphic {
        size,
        reference: std::array::from_fn(|j| t.bins[j].cvg_reference),
        test: std::array::from_fn(|j| t.bins[j].cvg_test),
        top_left: vec![format!("Rf {:.0}", t.rf), format!("Rg {:.0}", t.rg)],
        top_right: vec![format!("CCT {:.0} K", t.cct), format!("Duv {:.4}", t.duv)],
    }
}

fn intents(t: &Tm30Report) -> String {
    let d = &t.design_intents;
    format!("{} {} {}", d.preference, d.vividness, d.fidelity)
}

/// The report page of a light.
pub fn page(name: &str, t: &Tm30Report) -> Tm30Page {
    let b1 = &t.bins[0];
    let summary = vec![
        ("CCT".to_string(), format!("{:.0} K", t.cct)),
        ("Duv".to_string(), format!("{:.4}", t.duv)),
        ("Fidelity index Rf".to_string(), format!("{:.0}", t.rf)),
        ("Gamut index Rg".to_string(), format!("{:.0}", t.rg)),
        ("Rf,h1 (red)".to_string(), format!("{:.0}", b1.rf)),
        (
            "Rcs,h1 (red)".to_string(),
            format!("{:.0} %", b1.rcs_percent),
        ),
        (
            "Design intents (Annex E): preference, vividness, fidelity".to_string(),
            intents(t),
        ),
    ];
    let mut notes = vec![
        "Rf, Rf,hj and Rf,CESi: CIE 224:2017 / ANSI/IES TM-30-20 (CAM02-UCS, 99 samples, the \
         reference at the light's CCT: Planckian below 4000 K, CIE daylight above 5000 K, \
         blended between). Rg, Rcs,hj, Rhs,hj: TM-30's 16 hue bins of 22.5° by the samples' \
         hue under the reference. The graphic shows each bin's mean a′, b′ under the test \
         light over the bin's reference radius (reference: the black circle); the spectra are \
         normalised to equal luminous flux."
            .to_string(),
        "Design intents: TM-30-20 Annex E priority levels (1 highest; - below 3), a level \
         meeting its own and every lower level's criteria, figures rounded to 0.01, from the \
         Annex E table as luxpy 1.12.5 publishes it (docs/leds.md). Computed by specpoly."
            .to_string(),
    ];
    if let Some([lo, hi]) = t.extrapolated_from_nm {
        notes.push(format!(
            "The light is tabulated over {lo}-{hi} nm; its end values were held to reach \
             380-780 nm (CIE 015:2018)."
        ));
    }
    Tm30Page {
        name: name.to_string(),
        summary,
        nm: t.spd.nm.clone(),
        test: t.spd.test.clone(),
        reference: t.spd.reference.clone(),
        graphic: graphic(t, specpoly_plot::tm30_page::CVG_BOX.2),
        rf_h: std::array::from_fn(|j| t.bins[j].rf),
        rcs_h_percent: std::array::from_fn(|j| t.bins[j].rcs_percent),
        rhs_h: std::array::from_fn(|j| t.bins[j].rhs),
        rf_ces: t.ces.iter().map(|c| c.rf).collect(),
        ces_colours: t.ces_srgb.clone(),
        notes,
    }
}

/// The text of `--tm30`.
pub fn text(name: &str, t: &Tm30Report) -> String {
    let name = one_line(name);
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# {name}: ANSI/IES TM-30-20 (CIE 224:2017 Rf); design intents (Annex E): {}",
        intents(t)
    );
    let _ = writeln!(o, "{:>8} {:>9} {:>6} {:>6}", "cct", "duv", "rf", "rg");
    let _ = writeln!(
        o,
        "{:>8.1} {:>9.5} {:>6.1} {:>6.1}",
        t.cct, t.duv, t.rf, t.rg
    );
    let _ = writeln!(
        o,
        "# hue bins (by the samples' hue under the reference): Rf,hj; Rcs,hj (%); Rhs,hj; mean \
         a', b' under the test light and the reference; the colour vector graphic's test point \
         (a', b' over the reference radius)"
    );
    let _ = writeln!(
        o,
        "{:>3} {:>11} {:>3} {:>6} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>7} {:>7}",
        "bin",
        "hue",
        "n",
        "rf",
        "rcs%",
        "rhs",
        "test_a",
        "test_b",
        "ref_a",
        "ref_b",
        "cvg_a",
        "cvg_b"
    );
    for b in &t.bins {
        let _ = writeln!(
            o,
            "{:>3} {:>11} {:>3} {:>6.1} {:>7.1} {:>7.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>7.4} {:>7.4}",
            b.bin,
            format!("{:.1}-{:.1}", b.hue_deg[0], b.hue_deg[1]),
            b.samples,
            b.rf,
            b.rcs_percent,
            b.rhs,
            b.test_a,
            b.test_b,
            b.reference_a,
            b.reference_b,
            b.cvg_test[0],
            b.cvg_test[1]
        );
    }
    let _ = writeln!(o, "# colour evaluation samples: Rf,CESi and hue bin");
    let _ = writeln!(o, "{:>3} {:>3} {:>6}", "ces", "bin", "rf");
    for c in &t.ces {
        let _ = writeln!(o, "{:>3} {:>3} {:>6.1}", c.ces, c.bin, c.rf);
    }
    o
}

/// `light --tm30 --json`: the light's keys and `tm30`.
#[derive(serde::Serialize)]
struct Json<'a> {
    #[serde(flatten)]
    light: &'a LightReport,
    tm30: &'a Tm30Report,
}

/// Chromium's executable: `$CHROMIUM`, else `chromium` or `chromium-browser` on the PATH.
fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|d| [d.join("chromium"), d.join("chromium-browser")])
        .find(|p| p.is_file())
}

/// A fresh private folder under the system's temporary folder (removed when dropped).
struct TempDir(PathBuf);

impl TempDir {
    fn new() -> Result<Self> {
        let base = std::env::temp_dir();
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.subsec_nanos())
            .unwrap_or(0);
        for k in 0..100u32 {
            let p = base.join(format!("specpoly-tm30-{}-{nanos}-{k}", std::process::id()));
            match std::fs::create_dir(&p) {
                Ok(()) => return Ok(TempDir(p)),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(CliError::io(&p, e)),
            }
        }
        Err(CliError::data("no temporary folder could be created"))
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The page as a PNG screenshot by headless Chromium, [`WIDTH`] × [`HEIGHT`] px.
fn screenshot(html: &str) -> Result<Vec<u8>> {
    let browser = chromium().ok_or_else(|| {
        CliError::data(
            "a PNG report is a screenshot by headless Chromium, which was not found (install \
             chromium or set $CHROMIUM), or write the report as .html",
        )
    })?;
    let dir = TempDir::new()?;
    let page = dir.0.join("report.html");
    let shot = dir.0.join("report.png");
    std::fs::write(&page, html).map_err(|e| CliError::io(&page, e))?;
    let mut child = Command::new(&browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--no-first-run",
            "--disable-sync",
            "--force-color-profile=srgb",
            "--hide-scrollbars",
        ])
        .arg(format!(
            "--user-data-dir={}",
            dir.0.join("profile").display()
        ))
        .arg(format!("--window-size={WIDTH},{HEIGHT}"))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", page.display()))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| CliError::io(&browser, e))?;
    let deadline = Instant::now() + CHROMIUM_TIMEOUT;
    let status = loop {
        match child.try_wait().map_err(|e| CliError::io(&browser, e))? {
            Some(s) => break s,
            None if Instant::now() > deadline => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(CliError::data(format!(
                    "Chromium did not render the report within {} s",
                    CHROMIUM_TIMEOUT.as_secs()
                )));
            }
            None => std::thread::sleep(Duration::from_millis(20)),
        }
    };
    let bytes = std::fs::read(&shot).unwrap_or_default();
    // a PNG's signature, then IHDR with the width and height asked for
    let ok = bytes.len() > 24
        && bytes[..8] == [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A]
        && bytes[16..20] == WIDTH.to_be_bytes()
        && bytes[20..24] == HEIGHT.to_be_bytes();
    if !status.success() || !ok {
        return Err(CliError::data(format!(
            "Chromium ({}) did not write a {WIDTH}x{HEIGHT} screenshot of the report ({status})",
            browser.display()
        )));
    }
    Ok(bytes)
}

/// Runs the TM-30 options for one light; `light` is its report (for `--json`).
pub fn run(named: &Named, light: &LightReport, a: &Tm30Args) -> Result<()> {
    let cvg_kind = a
        .cvg
        .map(|p| kind(p, &[("svg", Kind::Svg), ("png", Kind::Png)], "--cvg"))
        .transpose()?;
    let report_kind = a
        .report
        .map(|p| kind(p, &[("html", Kind::Html), ("png", Kind::Png)], "--report"))
        .transpose()?;
    if let (Some(c), Some(r)) = (a.cvg, a.report) {
        if c == r {
            return Err(CliError::usage(format!(
                "{}: --cvg and --report name the same file",
                one_line(&c.display().to_string())
            )));
        }
    }
    let t = tm30_report(named, a.extrapolate)?;
    // every file whole in memory before any is written
    let mut files: Vec<(&Path, Vec<u8>)> = vec![];
    if let (Some(p), Some(k)) = (a.cvg, cvg_kind) {
        let g = graphic(&t, CVG_SIZE);
        let bytes = if k == Kind::Png {
            g.png()?
        } else {
            g.svg()?.into_bytes()
        };
        files.push((p, bytes));
    }
    if let (Some(p), Some(k)) = (a.report, report_kind) {
        let html = page(&named.name, &t).html()?;
        let bytes = if k == Kind::Png {
            screenshot(&html)?
        } else {
            html.into_bytes()
        };
        files.push((p, bytes));
    }
    for (p, bytes) in &files {
        atomic::write(p, bytes)?;
        super::wrote::wrote(p, "");
    }
    if !a.print {
        return Ok(());
    }
    if a.json {
        return Ok(specpoly_formats::stdout::print_json(&Json {
            light,
            tm30: &t,
        })?);
    }
    Ok(specpoly_formats::stdout::print(&text(&named.name, &t))?)
}
