//! Ctrl-C (SIGINT, and SIGTERM) during a measurement: the handler only raises a flag; the
//! measuring loop, the serial driver's reads and the ArgyllCMS child's watchdog poll it, stop
//! at the next check (at most ~100 ms later), keep every reading taken, return the instrument
//! to local mode and end with one error line. The `ctrlc` crate installs the handler (the
//! project forbids the `unsafe` a hand-written `sigaction` needs).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

static REQUESTED: AtomicBool = AtomicBool::new(false);
static INSTALL: Once = Once::new();

/// Installs the handler (once per process; later calls do nothing). A failure to install
/// is ignored: Ctrl-C then ends the process the default way, and the readings written so far
/// stay valid (every `.ti3` update is an atomic rename).
pub fn install() {
    INSTALL.call_once(|| {
        let _ = ctrlc::set_handler(|| REQUESTED.store(true, Ordering::SeqCst));
    });
}

/// Whether Ctrl-C was pressed since the start.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// The message of a run stopped by Ctrl-C.
pub const MESSAGE: &str = "interrupted (Ctrl-C)";
