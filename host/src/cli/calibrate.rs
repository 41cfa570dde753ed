//! `specpoly calibrate` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// `specpoly calibrate` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum CalibrateCommand {
    /// Fit a calibration from ArgyllCMS .ti3 measurements.
    Fit {},
}

/// Runs `specpoly calibrate`.
pub fn run(_: CalibrateCommand) -> Result<()> {
    Err(CliError::usage(
        "`calibrate` is not available in this build yet",
    ))
}
