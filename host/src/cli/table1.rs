//! `specpoly table1` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly table1`.
#[derive(Debug, clap::Args)]
pub struct Table1Args {}

/// Runs `specpoly table1`.
pub fn run(_: &Table1Args) -> Result<()> {
    Err(CliError::usage(
        "`table1` is not available in this build yet",
    ))
}
