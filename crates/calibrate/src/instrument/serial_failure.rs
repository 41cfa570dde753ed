//! Why one exchange with a PR-655/670 failed: the serial driver's failures, with the
//! instrument's status codes explained.

use crate::interrupt;
use std::time::Duration;

/// Why one exchange with the instrument failed.
#[derive(Debug)]
pub enum Failure {
    /// No complete reply before the deadline.
    Timeout(&'static str, Duration),
    /// A reply that is not what the command returns.
    Garbled(&'static str, String),
    /// A non-zero status code.
    Status(&'static str, i64),
    /// The port failed: nothing more can be done.
    Gone(std::io::Error),
    /// Ctrl-C.
    Interrupted,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Timeout(c, d) => {
                write!(f, "no reply to `{c}` within {:.1} s", d.as_secs_f64())
            }
            Failure::Garbled(c, r) => write!(f, "garbled reply to `{c}`: `{r}`"),
            Failure::Status(c, s) => write!(
                f,
                "`{c}` failed with instrument error {s:04}{}",
                status_meaning(*s)
            ),
            Failure::Gone(e) => write!(
                f,
                "the serial port failed ({e}); was the instrument unplugged?"
            ),
            Failure::Interrupted => write!(f, "{}", interrupt::MESSAGE),
        }
    }
}

fn status_meaning(s: i64) -> &'static str {
    match s {
        10 | 18 => " (light too low)",
        _ => " (see the PR-655/670 manual's error codes)",
    }
}
