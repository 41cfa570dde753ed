//! Where patches are shown (`--display`): the [`PatchDisplay`] trait and its implementations.
//!
//! | spec | implementation |
//! |---|---|
//! | `web[:PORT][,wait=SECS][,timeout=SECS][,size=F][,background=L]` | [`web::WebDisplay`]: a page served on `127.0.0.1` (an ephemeral port unless given) |
//! | `led:PORT[,timeout=SECS]` | [`led_controller::LedControllerDisplay`]: the RGB-LED controller (`specpoly-firmware`) |
//! | `manual` | [`manual::ManualDisplay`]: prints the RGB to set and waits for Enter |
//! | `sim:SPD[,options]` | [`sim::SimDisplay`]: a simulated display (see [`crate::sim`]) |

use crate::error::{Error, PatchDisplayError, Result};
use crate::sim::{SimHandle, SimModel};
use specpoly_formats::device_spec::DeviceSpec;
use std::time::Duration;

pub mod led_controller;
pub mod manual;
pub mod sim;
pub mod web;

/// Something that shows colour patches.
pub trait PatchDisplay {
    /// One line saying what and where (printed at the start of a run; for `web` it holds the
    /// URL).
    fn describe(&self) -> String;

    /// Shows `rgb` (device values in `[0, 1]`, on the 8-bit grid) and returns once it is on
    /// screen.
    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError>;

    /// How long to wait after [`Self::show`] before measuring unless `--settle` says otherwise.
    fn default_settle(&self) -> Duration;

    /// The simulated display behind this one, if it is simulated (the `sim` instrument reads
    /// it).
    fn simulation(&self) -> Option<SimHandle> {
        None
    }
}

/// Opens the display named by `spec` (`KIND[:ARG][,KEY=VALUE...]`, see the table above).
pub fn open(spec: &str) -> Result<Box<dyn PatchDisplay>> {
    let d = DeviceSpec::parse(spec);
    match d.kind {
        "web" => Ok(Box::new(web::WebDisplay::from_spec(&d)?)),
        "led" => Ok(Box::new(led_controller::LedControllerDisplay::from_spec(
            &d,
        )?)),
        "manual" if spec == "manual" => Ok(Box::new(manual::ManualDisplay::stdin())),
        "sim" => Ok(Box::new(sim::SimDisplay::new(SimHandle::new(
            SimModel::from_spec(&d)?,
        )))),
        _ => Err(Error::UnknownDisplay {
            spec: spec.to_string(),
        }),
    }
}

/// A display whose patches a simulated display follows too: lets `--instrument sim:SPD`
/// measure what a real display (web page, manual) is showing.
pub struct Mirrored {
    inner: Box<dyn PatchDisplay>,
    sim: SimHandle,
}

impl Mirrored {
    /// `inner` mirrored onto `sim`.
    pub fn new(inner: Box<dyn PatchDisplay>, sim: SimHandle) -> Self {
        Self { inner, sim }
    }
}

impl PatchDisplay for Mirrored {
    fn describe(&self) -> String {
        self.inner.describe()
    }

    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError> {
        self.inner.show(rgb)?;
        self.sim.set(rgb);
        Ok(())
    }

    fn default_settle(&self) -> Duration {
        self.inner.default_settle()
    }

    fn simulation(&self) -> Option<SimHandle> {
        Some(self.sim.clone())
    }
}
