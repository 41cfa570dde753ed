//! `--instrument sim`: reads a simulated display (its truth plus its measurement noise).

use crate::error::InstrumentError;
use crate::instrument::Instrument;
use crate::sim::SimHandle;

/// Reads a simulated display.
pub struct SimInstrument {
    handle: SimHandle,
}

impl SimInstrument {
    /// Reads `handle`.
    pub fn new(handle: SimHandle) -> Self {
        Self { handle }
    }
}

impl Instrument for SimInstrument {
    fn describe(&self) -> String {
        format!(
            "simulated instrument reading the {}",
            self.handle.model().describe()
        )
    }

    fn measure(&mut self) -> Result<[f64; 3], InstrumentError> {
        Ok(self.handle.read())
    }
}
