//! The `specpoly` binary: parse, run, and turn any error into one line on stderr with exit code
//! 2 (usage) or 1 (data, I/O, device). clap's own errors are folded to one line too
//! ([`specpoly::error::clap_error_line`]); `--help` and `--version` print as usual.

use clap::Parser;

fn main() {
    let cli = match specpoly::cli::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => match specpoly::error::clap_error_line(&e) {
            None => e.exit(),
            Some(line) => {
                eprintln!(
                    "specpoly: error: {}",
                    specpoly_formats::escape::one_line(&line)
                );
                std::process::exit(2);
            }
        },
    };
    if let Err(e) = specpoly::cli::run(cli) {
        eprintln!(
            "specpoly: error: {}",
            specpoly_formats::escape::one_line(&e.to_string())
        );
        std::process::exit(e.exit_code());
    }
}
