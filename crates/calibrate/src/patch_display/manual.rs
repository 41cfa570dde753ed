//! `--display manual`: prints the RGB to set (8-bit and percent) and waits for Enter, for
//! displays the program cannot drive (a projector menu, another computer). Typing `q` stops.

use crate::error::PatchDisplayError;
use crate::patch_display::PatchDisplay;
use specpoly_core::quantize8;
use std::io::{BufRead, Write};
use std::time::Duration;

/// Asks a person to show each patch.
pub struct ManualDisplay<R: BufRead, W: Write> {
    input: R,
    prompt: W,
    count: usize,
}

impl ManualDisplay<std::io::StdinLock<'static>, std::io::Stderr> {
    /// Reads Enter from stdin, prompts on stderr.
    pub fn stdin() -> Self {
        Self::new(std::io::stdin().lock(), std::io::stderr())
    }
}

impl<R: BufRead, W: Write> ManualDisplay<R, W> {
    /// Reads confirmations from `input`, writes prompts to `prompt`.
    pub fn new(input: R, prompt: W) -> Self {
        Self {
            input,
            prompt,
            count: 0,
        }
    }
}

/// The prompt for a patch.
pub fn prompt_text(n: usize, rgb: [f64; 3]) -> String {
    let b = rgb.map(|v| quantize8(v as f32));
    format!(
        "patch {n}: set RGB {} {} {} (= {:.1} % {:.1} % {:.1} %), then press Enter (q to stop)",
        b[0],
        b[1],
        b[2],
        rgb[0] * 100.0,
        rgb[1] * 100.0,
        rgb[2] * 100.0
    )
}

impl<R: BufRead, W: Write> PatchDisplay for ManualDisplay<R, W> {
    fn describe(&self) -> String {
        "manual display: set each patch by hand and press Enter".to_string()
    }

    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError> {
        self.count += 1;
        let _ = writeln!(self.prompt, "{}", prompt_text(self.count, rgb));
        let _ = self.prompt.flush();
        let mut line = String::new();
        let n = self
            .input
            .read_line(&mut line)
            .map_err(PatchDisplayError::Stdin)?;
        if n == 0 {
            return Err(PatchDisplayError::StdinClosed);
        }
        if line.trim().eq_ignore_ascii_case("q") {
            return Err(PatchDisplayError::StoppedByUser);
        }
        Ok(())
    }

    fn default_settle(&self) -> Duration {
        Duration::ZERO
    }
}
