//! `specpoly calibrate lut3d DISPLAY -o FILE`: a 3D LUT from a source colour space to a measured
//! display (`specpoly_display::lut3d`), written whole or not at all. See docs/calibration.md,
//! "3D LUTs".

use crate::cli::calibrate::values::{LutFormatValue, LutGamutValue, LutSourceValue, LutWhiteValue};
use crate::error::{CliError, Result};
use specpoly_display::lut3d::{self, file, Options};
use specpoly_display::spec::DisplaySpec;
use specpoly_formats::escape::one_line;
use std::path::PathBuf;

/// `calibrate lut3d`.
#[derive(Debug, clap::Args)]
pub struct Lut3dArgs {
    /// The display: a calibration file, an ICC display profile or a display TOML (or sRGB).
    pub display: String,
    /// The LUT file to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The colour space of the LUT's input.
    #[arg(long, value_enum, default_value_t = LutSourceValue::Srgb)]
    pub source: LutSourceValue,
    /// Nodes per side (2–65; 17, 33 and 65 are the usual).
    #[arg(long, default_value_t = 33, value_parser = size)]
    pub size: usize,
    /// The file format [default: from the output's extension: .cube, .3dl, .3dlut].
    #[arg(long, value_enum)]
    pub format: Option<LutFormatValue>,
    /// The source white: adapted to the display's white, or kept (absolute).
    #[arg(long, value_enum, default_value_t = LutWhiteValue::Adapt)]
    pub white: LutWhiteValue,
    /// Colours outside the display's gamut: clipped per channel, or desaturated (lightness and
    /// hue kept).
    #[arg(long, value_enum, default_value_t = LutGamutValue::Clip)]
    pub gamut: LutGamutValue,
    /// Each node the exact inverse of its own colour (default: nodes fitted to the colours
    /// between them, where the interpolation would miss; docs/calibration.md).
    #[arg(long)]
    pub exact_nodes: bool,
}

/// `--size`: a whole number in the LUT's range (the library's check, as a usage error).
fn size(s: &str) -> std::result::Result<usize, String> {
    let n: usize = s
        .parse()
        .map_err(|_| format!("`{s}` is not a whole number of nodes"))?;
    lut3d::check_size(n).map_err(|e| e.to_string())?;
    Ok(n)
}

/// Runs `calibrate lut3d`.
pub fn run(a: &Lut3dArgs) -> Result<()> {
    let format = match a.format {
        Some(f) => file::Format::from(f),
        None => file::Format::from_path(&a.output).ok_or_else(|| {
            CliError::Usage(format!(
                "cannot tell the LUT format from `{}`: name it .cube, .3dl or .3dlut, or give --format cube|3dl|madvr",
                a.output.display()
            ))
        })?,
    };
    let spec = DisplaySpec::open(&a.display)?;
    let model = spec.model();
    let opts = Options {
        source: a.source.into(),
        size: a.size,
        white: a.white.into(),
        gamut: a.gamut.into(),
        refine: !a.exact_nodes,
    };
    let started = std::time::Instant::now();
    let lut = lut3d::build(&model, &spec.name(), &opts)?;
    let built = started.elapsed().as_secs_f64();
    let bytes = file::write(&lut, format, opts.source);
    specpoly_formats::atomic::write(&a.output, &bytes)?;
    let st = lut.stats();
    eprintln!(
        "wrote {} ({}, {n}^3 = {} nodes from {} to the display, white {}, gamut {}; {} nodes outside its gamut; built in {built:.1} s)",
        one_line(&a.output.display().to_string()),
        format.name(),
        st.nodes,
        opts.source.name(),
        opts.white.name(),
        opts.gamut.name(),
        st.out_of_gamut,
        n = a.size,
    );
    if format == file::Format::MadVr {
        eprintln!("note: madVR's table is 256^3: the {n}^3 LUT interpolated (tetrahedral) at every 8-bit code", n = a.size);
    }
    if spec.calibration().is_some_and(|c| c.video_lut().is_some()) {
        eprintln!(
            "note: the display was measured through a video LUT (the calibration's [video_lut]): load it (e.g. its ICC profile's vcgt) while the 3D LUT is in use"
        );
    }
    Ok(())
}
