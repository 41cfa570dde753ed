//! `--display led:PORT[,timeout=SECS]`: the RGB-LED controller (`specpoly-firmware`, host side
//! in [`specpoly_led`]) as the display to measure.
//!
//! The controller only takes colours (`xyz`, `xyy`, `refl`), which it turns into PWM duties
//! through its own calibration. To drive raw device values, the display first loads a neutral
//! calibration — Rec. 709 primaries with the luminances of Rec. 709's white (`cal 0.64 0.33
//! 0.2126 0.3 0.6 0.7152 0.15 0.06 0.0722`), linear curves (`trc rgb linear`), clipping
//! (`map clip`) — under which device value = linear drive = `M⁻¹ · XYZ`. Each patch `rgb` is then
//! sent as `xyz` of `100 · M · rgb` (white `Y = 100`), and the reply's duties are checked to be
//! `round(rgb · max)` within one tick. The controller keeps the neutral calibration afterwards:
//! load the fitted one with `specpoly led` when done.

use crate::error::{PatchDisplayError, Result};
use crate::patch_display::PatchDisplay;
use specpoly_core::{Display, GamutMap, Transfer, Xyz};
use specpoly_formats::device_spec::DeviceSpec;
use specpoly_led::lines::line;
use specpoly_led::Link;
use specpoly_protocol::{Channels, Command, Reply};
use std::time::Duration;

/// Rec. 709 primaries and their luminances in Rec. 709's white (sum 1).
const XY: [[f32; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
const LUM: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// The LED controller showing patches.
pub struct LedControllerDisplay {
    link: Link<Box<dyn serialport::SerialPort>>,
    name: String,
    max: u16,
    neutral: Display,
}

impl LedControllerDisplay {
    /// Opens the controller of `led:PORT[,timeout=SECS]`.
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let path = spec.required_arg("the controller's port", "led:/dev/ttyACM0")?;
        let mut timeout = Duration::from_secs(2);
        for &(k, v) in &spec.options {
            match k {
                "timeout" => timeout = spec.seconds(k, v)?,
                _ => return Err(spec.unknown(k, "timeout").into()),
            }
        }
        Ok(Self::open(path, timeout)?)
    }

    /// Opens the controller on `path`, checks the protocol and loads the neutral calibration.
    pub fn open(path: &str, timeout: Duration) -> Result<Self, PatchDisplayError> {
        let mut link = Link::open(path, timeout)?;
        let max = link.hello()?;
        let linear = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        let neutral = Display::from_primaries(XY, LUM, Xyz::default(), linear)
            .map_err(PatchDisplayError::LedModel)?;
        for c in [
            Command::Calibrate {
                xy: XY,
                luminance: LUM,
            },
            Command::Transfer {
                channels: Channels::All,
                curve: Transfer::Linear,
            },
            Command::Map(GamutMap::Clip),
        ] {
            link.send(&line(&c))?;
        }
        Ok(Self {
            link,
            name: path.to_string(),
            max,
            neutral,
        })
    }
}

impl PatchDisplay for LedControllerDisplay {
    fn describe(&self) -> String {
        format!(
            "LED controller on {} ({} duty steps per channel)",
            self.name, self.max
        )
    }

    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError> {
        let xyz = self
            .neutral
            .device_to_xyz(rgb.map(|v| v as f32))
            .scale(100.0);
        let reply = self.link.send(&line(&Command::Xyz(xyz)))?;
        let Reply::Colour(c) = reply else {
            return Err(PatchDisplayError::LedReply {
                port: self.name.clone(),
                reply: specpoly_led::lines::reply_line(&reply),
            });
        };
        let want = rgb.map(|v| (v * self.max as f64).round() as i64);
        if (0..3).any(|k| (c.duty[k] as i64 - want[k]).abs() > 1) {
            return Err(PatchDisplayError::LedDuty {
                port: self.name.clone(),
                duty: specpoly_formats::stdout::values(&c.duty),
                device: specpoly_formats::stdout::values(&rgb),
                expected: specpoly_formats::stdout::values(&want),
                max: self.max,
            });
        }
        Ok(())
    }

    fn default_settle(&self) -> Duration {
        Duration::from_millis(100)
    }
}
