//! The one progress bar: drawn on stderr when it is a terminal, hidden otherwise (so piped
//! and tested runs print nothing extra).

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A bar of `len` steps counting `unit` (e.g. `rows`, `patches`), labelled `label`.
pub fn bar(len: u64, label: &str, unit: &str) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(len);
    let template =
        format!("{{prefix:>10}} [{{bar:40}}] {{pos}}/{{len}} {unit}, {{elapsed}}, {{eta}} left");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_prefix(label.to_string());
    pb
}
