//! `specpoly render` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {}

/// Runs `specpoly render`.
pub fn run(_: &RenderArgs) -> Result<()> {
    Err(CliError::usage(
        "`render` is not available in this build yet",
    ))
}
