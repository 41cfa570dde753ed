//! `specpoly led` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly led`.
#[derive(Debug, clap::Args)]
pub struct LedArgs {}

/// Runs `specpoly led`.
pub fn run(_: &LedArgs) -> Result<()> {
    Err(CliError::usage("`led` is not available in this build yet"))
}
