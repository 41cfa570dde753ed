//! `specpoly xyz` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly xyz`.
#[derive(Debug, clap::Args)]
pub struct XyzArgs {}

/// Runs `specpoly xyz`.
pub fn run(_: &XyzArgs) -> Result<()> {
    Err(CliError::usage("`xyz` is not available in this build yet"))
}
