//! The `specpoly` binary: parse, run, and turn any error into one line on stderr with exit code
//! 2 (usage) or 1 (data, I/O, device).

use clap::Parser;

fn main() {
    let cli = specpoly::cli::Cli::parse();
    if let Err(e) = specpoly::cli::run(cli) {
        eprintln!(
            "specpoly: error: {}",
            specpoly::io::escape::one_line(&e.to_string())
        );
        std::process::exit(e.exit_code());
    }
}
