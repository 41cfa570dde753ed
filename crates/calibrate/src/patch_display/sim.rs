//! `--display sim:SPD[,options]`: patches go to a simulated display (no screen, no waiting).

use crate::error::PatchDisplayError;
use crate::patch_display::PatchDisplay;
use crate::sim::SimHandle;
use std::time::Duration;

/// A simulated display.
pub struct SimDisplay {
    handle: SimHandle,
}

impl SimDisplay {
    /// Shows patches on `handle`.
    pub fn new(handle: SimHandle) -> Self {
        Self { handle }
    }
}

impl PatchDisplay for SimDisplay {
    fn describe(&self) -> String {
        self.handle.model().describe()
    }

    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError> {
        self.handle.set(rgb);
        Ok(())
    }

    fn default_settle(&self) -> Duration {
        Duration::ZERO
    }

    fn simulation(&self) -> Option<SimHandle> {
        Some(self.handle.clone())
    }
}
