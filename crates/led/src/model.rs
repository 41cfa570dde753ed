//! The controller as the host models it: its settings and the **same core calls** the firmware
//! makes — the drive step [`specpoly_core::Display::drive`] for a colour (corrected by
//! [`specpoly_core::drive_table::corrected`] when the controller holds a table) and
//! [`specpoly_core::Moments::xyz`] for a reflectance. The host's tests use it to play a
//! faithful controller; whether a real controller is right is decided by the independent f64
//! reference in [`crate::check`], not by this.

use crate::table::DriveTable;
use specpoly_core::{drive_table, Display, GamutMap, Illuminant, Moments, Observer, Xyz};
use specpoly_protocol::{ColourReport, Command, DeviceMixer, ErrorCode, Fault, Reflectance, Reply};

/// A controller's calibration and settings, as the host knows them.
#[derive(Clone, Debug)]
pub struct Model {
    /// The LED as a display (Cowan's model).
    pub display: Display,
    /// Gamut mapping.
    pub map: GamutMap,
    /// Observer for reflectances.
    pub observer: Observer,
    /// Full-scale duty.
    pub max: u16,
}

impl Model {
    /// XYZ (perfect white `Y = 100`) of a reflectance under a built-in light.
    pub fn reflectance_xyz(&self, illuminant: Illuminant, r: &Reflectance) -> Xyz {
        let light = illuminant.tabulated();
        match r {
            Reflectance::Paper(s) => Moments::new(self.observer, &light).xyz(s),
            Reflectance::Default(s) => Moments::new(self.observer, &light).xyz(s),
        }
    }

    /// What the controller answers for `target` (white `Y = 100`): the core's drive step.
    pub fn colour(&self, target: Xyz) -> ColourReport {
        self.colour_with(target, None)
    }

    /// [`Model::colour`] on a controller holding the drive-correction table `table`
    /// (`lut`, applied as the firmware applies it: [`drive_table::corrected`]).
    pub fn colour_with(&self, target: Xyz, table: Option<&DriveTable>) -> ColourReport {
        let mut drive = self.display.drive(target, self.map, self.max);
        if let Some(mut t) = table.and_then(DriveTable::table) {
            drive = drive_table::corrected(&mut t, drive, self.max);
        }
        ColourReport::of(target, &drive, self.map, self.max)
    }

    /// The controller's reply to a colour command (`xyz`, `xyy`, `refl`) whose target is
    /// `target`: the colour report, or `err not-finite` when a number of the report would not
    /// be a finite f32 — what the firmware's `Controller` answers (firmware/PROTOCOL.md,
    /// `not-finite`), so a fake controller built on this model refuses the same inputs.
    pub fn answer(&self, target: Xyz) -> Reply {
        self.answer_in(target, false)
    }

    /// [`Model::answer`] with the numbers in the compact hexadecimal form when `hex` (the
    /// reply to a `refl` line written in that form, as the firmware answers it).
    pub fn answer_in(&self, target: Xyz, hex: bool) -> Reply {
        if let Err(code) = specpoly_protocol::target::check_target(target) {
            return Reply::Error(Fault::new(code));
        }
        Self::finite(ColourReport {
            hex,
            ..self.colour(target)
        })
    }

    /// [`Model::answer`] with the drive-correction table `table` applied.
    pub fn answer_with(&self, target: Xyz, table: Option<&DriveTable>) -> Reply {
        if let Err(code) = specpoly_protocol::target::check_target(target) {
            return Reply::Error(Fault::new(code));
        }
        Self::finite(self.colour_with(target, table))
    }

    /// `report` as the reply, or `err not-finite` when one of its numbers is not finite.
    fn finite(report: ColourReport) -> Reply {
        if report.is_finite() {
            Reply::Colour(report)
        } else {
            Reply::Error(Fault::new(ErrorCode::NotFinite))
        }
    }

    /// The reply to a colour command (`xyz`, `xyy`, `refl`); `None` for other commands.
    pub fn reply(&self, cmd: &Command) -> Option<Reply> {
        match cmd {
            Command::Xyz(v) => Some(self.answer(*v)),
            Command::Xyy(v) => Some(self.answer(v.to_xyz())),
            Command::Reflect {
                illuminant,
                product,
                hex,
                ..
            } => Some(self.answer_in(self.reflectance_xyz(*illuminant, product), *hex)),
            _ => None,
        }
    }
}

/// The controller's multi-channel mixer as the host models it: the protocol's shared answer
/// ([`specpoly_protocol::mix::answer`]) on the core's mixer, the very calls the firmware makes.
/// `tests/tests/firmware_qemu.rs` checks that the firmware's replies equal these.
#[derive(Clone, Debug, PartialEq)]
pub struct MixModel {
    /// Channels, fade time and the point shown.
    pub mixer: DeviceMixer,
    /// Full-scale duty.
    pub max: u16,
}

impl MixModel {
    /// No channels, PWM full scale `max`.
    pub fn new(max: u16) -> Self {
        Self {
            mixer: DeviceMixer::new(),
            max,
        }
    }

    /// The reply to a mixing command (`channel`, `xy`, `cct`, `fade`); `None` for others.
    pub fn answer(&mut self, cmd: &Command) -> Option<Reply> {
        specpoly_protocol::mix::answer(&mut self.mixer, cmd, self.max)
    }
}
