//! Where readings come from (`--instrument`): the [`Instrument`] trait and its
//! implementations.
//!
//! | spec | implementation |
//! |---|---|
//! | `serial:PORT[,baud=N][,timeout=SECS][,measure-timeout=SECS][,retries=N]` | [`serial::Pr6xx`]: a Photo Research PR-655/670 in remote mode |
//! | `sim` | [`sim::SimInstrument`] reading the `--display sim:…` display |
//! | `sim:SPD[,options]` | a simulated display that mirrors whatever `--display` shows (web, manual), read by [`sim::SimInstrument`] |
//! | `argyll[:options]` | [`argyll::Dispread`]: any instrument ArgyllCMS drives, measuring batches of patches with `dispread` (not an [`Instrument`]: `dispread` shows the patches itself) |

use crate::error::{Error, InstrumentError, Result};
use crate::patch_display::{Mirrored, PatchDisplay};
use crate::sim::{SimHandle, SimModel};
use specpoly_formats::device_spec::DeviceSpec;

pub mod argyll;
pub mod serial;
pub mod serial_failure;
pub mod sim;

/// A colorimeter or spectroradiometer.
pub trait Instrument {
    /// One line saying what and where.
    fn describe(&self) -> String;

    /// Measures the patch on screen: CIE 1931 XYZ in cd/m².
    fn measure(&mut self) -> Result<[f64; 3], InstrumentError>;
}

/// Opens the instrument named by `spec`; a `sim:SPD` instrument wraps `display` so the
/// simulation follows it. Returns the (possibly wrapped) display and the instrument.
pub fn open(
    spec: &str,
    display: Box<dyn PatchDisplay>,
) -> Result<(Box<dyn PatchDisplay>, Box<dyn Instrument>)> {
    let d = DeviceSpec::parse(spec);
    match (d.kind, d.arg) {
        ("sim", None) if d.options.is_empty() => {
            let h = display.simulation().ok_or(Error::SimNeedsSimDisplay)?;
            return Ok((display, Box::new(sim::SimInstrument::new(h))));
        }
        ("sim", Some(_)) => {
            if display.simulation().is_some() {
                return Err(Error::AlreadySimulated);
            }
            let h = SimHandle::new(SimModel::from_spec(&d)?);
            let m: Box<dyn PatchDisplay> = Box::new(Mirrored::new(display, h.clone()));
            return Ok((m, Box::new(sim::SimInstrument::new(h))));
        }
        ("serial", _) => return Ok((display, Box::new(serial::Pr6xx::from_spec(&d)?))),
        _ => {}
    }
    if argyll::is_argyll(spec) {
        return Err(Error::ArgyllNeedsArgyllDisplay);
    }
    Err(Error::UnknownInstrument {
        spec: spec.to_string(),
    })
}
