//! `specpoly xyz`: XYZ, xyY and CIELAB of reflectances (or of their product, an
//! inter-reflection chain) under an illuminant, in any representation.
//!
//! Every representation runs the same generic code ([`specpoly_spectra::colour::Chains`] through
//! [`specpoly_spectra::repr::dispatch`]); CIELAB is against the light's exact white (`Y = 100`).

use crate::cli::args::Colorimetry;
use crate::error::{CliError, Result};
use specpoly_core::Tabulated;
use specpoly_formats::stdout::print_json;
use specpoly_spectra::colour::{self, Colour};
use specpoly_spectra::repr::Repr;
use specpoly_spectra::spectrum_names::{self, Named};
use std::fmt::Write as _;

/// Arguments of `specpoly xyz`.
#[derive(Debug, clap::Args)]
pub struct XyzArgs {
    /// Reflectances: FILE, FILE#COLUMN, FILE#* or a built-in such as colorchecker#red.
    #[arg(required = true, value_name = "SPECTRUM")]
    pub spectra: Vec<String>,
    /// The light and the observer.
    #[command(flatten)]
    pub colorimetry: Colorimetry,
    /// Representation: poly, paper, poly:SxD, sampled:N, rgb, exact.
    #[arg(long, default_value = "poly", value_name = "REPR")]
    pub repr: Repr,
    /// Multiply the spectra (an inter-reflection chain) and print one result.
    #[arg(long)]
    pub product: bool,
    /// Print JSON: a list of {name, X, Y, Z, x, y, L, a, b}.
    #[arg(long)]
    pub json: bool,
    /// Multiply every reflectance by FACTOR first (0.01 for data in percent).
    #[arg(long, default_value_t = 1.0, value_name = "FACTOR")]
    pub scale: f64,
    /// Also print the device RGB (0–1, clipped to the gamut) on this display: `sRGB`, a
    /// display TOML, a calibration file (through its full model, interaction lattice
    /// included) or an ICC display profile (XYZ relative to the display's white, Y = 100).
    #[arg(long, value_name = "sRGB|FILE")]
    pub display: Option<String>,
}

/// One printed result.
#[derive(Clone, Debug, serde::Serialize)]
pub struct XyzRow {
    /// The spectrum's (or chain's) name.
    pub name: String,
    #[serde(rename = "X")]
    x_: f64,
    #[serde(rename = "Y")]
    y_: f64,
    #[serde(rename = "Z")]
    z_: f64,
    x: f64,
    y: f64,
    #[serde(rename = "L")]
    l: f64,
    a: f64,
    b: f64,
    /// Device RGB on `--display`, if given.
    #[serde(skip_serializing_if = "Option::is_none")]
    rgb: Option<[f64; 3]>,
}

impl XyzRow {
    fn new(name: String, c: &Colour) -> Self {
        let [x, y] = c.xy();
        let lab = c.lab();
        // Six decimals: far below any visible difference, without f32 noise in the output.
        let r = |v: f64| (v * 1e6).round() / 1e6;
        XyzRow {
            name,
            x_: r(c.xyz[0]),
            y_: r(c.xyz[1]),
            z_: r(c.xyz[2]),
            x: r(x),
            y: r(y),
            l: r(lab.l),
            a: r(lab.a),
            b: r(lab.b),
            rgb: None,
        }
    }
}

/// Computes the rows `xyz` prints.
pub fn compute(a: &XyzArgs) -> Result<Vec<XyzRow>> {
    let Colorimetry {
        illuminant,
        observer,
    } = &a.colorimetry;
    let light = spectrum_names::light(illuminant)?;
    let named: Vec<Named> = specpoly_spectra::plausible::reflectances(&a.spectra, a.scale, true)?;
    let tabs: Vec<Tabulated<'_>> = named.iter().map(Named::tabulated).collect();
    let (chains, names): (Vec<Vec<usize>>, Vec<String>) = if a.product {
        let name = named
            .iter()
            .map(|n| n.name.as_str())
            .collect::<Vec<_>>()
            .join(" * ");
        (vec![(0..named.len()).collect()], vec![name])
    } else {
        (
            (0..named.len()).map(|i| vec![i]).collect(),
            named.iter().map(|n| n.name.clone()).collect(),
        )
    };
    let colours = colour::chains(a.repr, *observer, &light.tabulated(), &tabs, &chains)
        .map_err(|e| CliError::data(format!("{}: {e}", a.repr)))?;
    for (n, c) in names.iter().zip(&colours) {
        specpoly_spectra::plausible::finite(n, &c.xyz)?;
    }
    let display = a
        .display
        .as_deref()
        .map(specpoly_display::spec::DisplaySpec::open)
        .transpose()?
        .map(|spec| spec.model());
    Ok(names
        .into_iter()
        .zip(&colours)
        .map(|(n, c)| {
            let mut row = XyzRow::new(n, c);
            if let Some(d) = &display {
                let xyz =
                    specpoly_core::Xyz::new(c.xyz[0] as f32, c.xyz[1] as f32, c.xyz[2] as f32);
                let e = d.encode_relative(xyz, specpoly_core::GamutMap::Clip);
                row.rgb = Some(e.device.map(|v| (v as f64 * 1e6).round() / 1e6));
            }
            row
        })
        .collect())
}

/// The widest name column printed (characters).
const NAME_COLUMN: usize = 48;

/// Runs `specpoly xyz`.
pub fn run(a: &XyzArgs) -> Result<()> {
    let rows = compute(a)?;
    if a.json {
        return Ok(print_json(&rows)?);
    }
    let mut o = String::new();
    // names longer than NAME_COLUMN overflow their column rather than widen every row
    let w = rows
        .iter()
        .map(|r| r.name.chars().count())
        .max()
        .unwrap_or(4)
        .clamp(4, NAME_COLUMN);
    let _ = writeln!(
        o,
        "# illuminant {}, {} observer, repr {}; Lab against the illuminant's white (Y = 100)",
        a.colorimetry.illuminant,
        a.colorimetry.observer.label(),
        a.repr
    );
    let _ = write!(
        o,
        "{:<w$} {:>9} {:>9} {:>9} {:>7} {:>7} {:>8} {:>8} {:>8}",
        "name", "X", "Y", "Z", "x", "y", "L*", "a*", "b*"
    );
    o.push_str(if a.display.is_some() {
        "        R        G        B\n"
    } else {
        "\n"
    });
    for r in &rows {
        let _ = write!(
            o,
            "{:<w$} {:>9.4} {:>9.4} {:>9.4} {:>7.4} {:>7.4} {:>8.3} {:>8.3} {:>8.3}",
            r.name, r.x_, r.y_, r.z_, r.x, r.y, r.l, r.a, r.b
        );
        match r.rgb {
            Some([red, green, blue]) => {
                let _ = writeln!(o, " {red:>8.5} {green:>8.5} {blue:>8.5}");
            }
            None => o.push('\n'),
        }
    }
    Ok(specpoly_formats::stdout::print(&o)?)
}
