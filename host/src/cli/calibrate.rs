//! `specpoly calibrate` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// `specpoly calibrate` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum CalibrateCommand {
    /// Fit a calibration from ArgyllCMS .ti3 measurements.
    Fit {},
    /// Measure a display: show patches, read them, write CAL.ti3, fit and write CAL.toml.
    Run(crate::calibrate::run::RunArgs),
}

/// Runs `specpoly calibrate`.
pub fn run(c: CalibrateCommand) -> Result<()> {
    match c {
        CalibrateCommand::Run(a) => crate::calibrate::run::run_cli(&a),
        CalibrateCommand::Fit {} => Err(CliError::usage(
            "`calibrate fit` is not available in this build yet",
        )),
    }
}
