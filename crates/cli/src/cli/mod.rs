//! Command-line interface: one file per command (parse, call, print), dispatched here;
//! arguments several commands share are parsed once in [`args`].

use crate::error::Result;
use clap::{Parser, Subcommand};

pub mod accuracy;
pub mod args;
pub mod calibrate;
pub mod calibrate_lut3d;
pub mod calibrate_run;
pub mod calibrate_spectral;
pub mod calibrate_target;
pub mod calibrate_verify;
pub mod fit;
pub mod led;
pub mod light;
pub mod light_tm30;
pub mod mix;
pub mod plot;
pub mod render;
pub mod render_equal_time;
pub mod render_report;
pub mod table1;
pub mod wrote;
pub mod xyz;

/// Spectral shading with piecewise polynomials and calibrated colour output
/// (after Raso & Fournier 1991).
#[derive(Debug, Parser)]
#[command(name = "specpoly", version, about, long_about = None)]
pub struct Cli {
    /// The largest input file any command reads (default 64M): bytes or a number with K, M or
    /// G; it bounds memory on malformed input, raise it for large meshes.
    #[arg(long, global = true, value_parser = args::byte_size, value_name = "SIZE")]
    pub max_input_size: Option<u64>,
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// XYZ, xyY and Lab of reflectances under an illuminant, in any representation.
    Xyz(xyz::XyzArgs),
    /// Fit spectra: coefficients, per-span fit errors and the fit's ΔE00.
    Fit(fit::FitArgs),
    /// Plot data, fitted polynomials and span boundaries (the paper's Figures 4 and 5).
    Plot(plot::PlotArgs),
    /// The paper's Table 1 on our data, the paper's numbers beside ours.
    Table1(table1::Table1Args),
    /// ΔE00 of every representation against the 1 nm reference; writes docs/accuracy.md.
    Accuracy(accuracy::AccuracyArgs),
    /// Render a scene with the spectral ray tracer.
    Render(render::RenderArgs),
    /// Measure a display and write its calibration (and ICC profile).
    #[command(subcommand)]
    Calibrate(calibrate::CalibrateCommand),
    /// Drive the RGB-LED controller firmware over a serial port.
    Led(led::LedArgs),
    /// Colorimetry and colour rendering of a light: XYZ, xy, u′v′, CCT, Duv, Ra, R9, Rf, Rg;
    /// TM-30 in full (--tm30), its colour vector graphic (--cvg) and a report page (--report).
    Light(light::LightArgs),
    /// Duties of 3–6 LED channels for a chromaticity or CCT target.
    Mix(mix::MixArgs),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    if let Some(limit) = cli.max_input_size {
        specpoly_formats::read::set_max_input_bytes(limit);
    }
    match cli.command {
        Command::Xyz(a) => xyz::run(&a),
        Command::Fit(a) => fit::run(&a),
        Command::Plot(a) => plot::run(&a),
        Command::Table1(a) => table1::run(&a),
        Command::Accuracy(a) => accuracy::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Calibrate(c) => calibrate::run(c),
        Command::Led(a) => led::run(&a),
        Command::Light(a) => light::run(&a),
        Command::Mix(a) => mix::run(&a),
    }
}
