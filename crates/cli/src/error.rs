//! The CLI's errors: the library crates' errors mapped to [`CliError`] (exit codes and
//! messages, one submodule per crate), and clap's folded to one line ([`clap_error_line`]);
//! `main` prints one line and exits with the error's code.

pub use specpoly_formats::error::{CliError, Result};

// The library crates' errors mapped to the CLI's: one file per crate. The mapping is a function
// (`.map_err(from_X)?`), not `impl From`, while `CliError` is defined in `specpoly-formats`: the
// orphan rule forbids implementing a foreign trait (`From`) between two foreign types here.
mod calibrate;
mod led;

pub use calibrate::from_calibrate;
pub use led::from_led;

/// A clap error as one line (`unexpected argument '--x' found (tip: …); usage: specpoly …`), or
/// `None` for `--help` and `--version`, which clap prints itself.
pub fn clap_error_line(e: &clap::Error) -> Option<String> {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        return None;
    }
    let text = e.render().to_string();
    let usage = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(str::trim);
    if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        return Some(format!(
            "a command is missing; usage: {}; `--help` lists the commands",
            usage.unwrap_or("specpoly <COMMAND>")
        ));
    }
    let mut main: Option<&str> = None;
    let mut extra = Vec::new();
    let mut tips = Vec::new();
    for l in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(m) = l.strip_prefix("error: ") {
            if main.is_none() {
                main = Some(m.trim_end_matches(':'));
                continue;
            }
        }
        let boilerplate = l.starts_with("Usage: ") || l.starts_with("For more information");
        if let Some(t) = l.strip_prefix("tip: ") {
            tips.push(t);
        } else if !boilerplate && main.is_some() {
            extra.push(l);
        }
    }
    let mut s = main.unwrap_or("bad command line").to_string();
    if !extra.is_empty() {
        s.push_str(": ");
        s.push_str(&extra.join(", "));
    }
    if !tips.is_empty() {
        s.push_str(&format!(" (tip: {})", tips.join("; ")));
    }
    if let Some(u) = usage {
        s.push_str(&format!("; usage: {u}"));
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn line(args: &[&str]) -> Option<String> {
        let e = crate::cli::Cli::try_parse_from(args).expect_err("an error");
        clap_error_line(&e)
    }

    #[test]
    fn clap_errors_fold_to_one_line() {
        let l = line(&["specpoly", "xyz", "colorchecker#red", "--bogus"]).unwrap();
        assert!(
            l.contains("--bogus") && l.contains("usage: specpoly xyz"),
            "{l}"
        );
        assert!(!l.contains('\n'), "{l}");
        let l = line(&["specpoly", "plot", "colorchecker#red"]).unwrap();
        assert!(l.contains("--output"), "{l}");
        let l = line(&["specpoly", "calibrate"]).unwrap();
        assert!(l.contains("usage: specpoly calibrate"), "{l}");
        assert_eq!(line(&["specpoly", "--help"]), None);
        assert_eq!(line(&["specpoly", "--version"]), None);
    }
}
