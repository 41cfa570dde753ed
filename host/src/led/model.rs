//! The host's own computation of a controller's answer, with `specpoly-core` directly:
//!
//! `XYZ (white Y = 100) ─Display::encode_relative─▶ device ─round(v·max)─▶ duties`, and the
//! emitted XYZ `= device_to_xyz(duty / max) · 100 / Y_white`; a reflectance's XYZ is
//! `Moments::new(observer, light, breaks).xyz(r)`. This is the specification the firmware is
//! tested against (`tests/tests/firmware_qemu.rs`, `specpoly led --check`).

use specpoly_core::{
    quantize16, Breaks, Display, Error, GamutMap, Illuminant, Moments, Observer, Transfer, Xyz,
    PAPER_BREAKS,
};
use specpoly_protocol::{ColourReport, CurveSummary, Gamut, Reflectance, StateReport};

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

/// `round(v · max)`, v clamped to `[0, 1]`.
fn duty_of(v: f32, max: u16) -> u16 {
    if max == u16::MAX {
        return quantize16(v);
    }
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    (v * max as f32 + 0.5) as u16
}

impl Model {
    /// From a `state` reply. A tabulated transfer curve is not in the reply (only its size):
    /// `None` then.
    pub fn from_state(s: &StateReport) -> Result<Option<Self>, Error> {
        let mut t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        for (o, c) in t.iter_mut().zip(s.trc) {
            *o = match c {
                CurveSummary::Linear => Transfer::Linear,
                CurveSummary::Srgb => Transfer::Srgb,
                CurveSummary::Gamma(g) => Transfer::Gamma(g),
                CurveSummary::Table(_) => return Ok(None),
            };
        }
        let xy = s.primaries.map(|p| [p[0], p[1]]);
        let lum = s.primaries.map(|p| p[2]);
        let display = Display::from_primaries(xy, lum, Xyz::default(), t)?;
        Ok(Some(Self {
            display,
            map: s.map,
            observer: s.observer,
            max: s.max,
        }))
    }

    /// XYZ (perfect white `Y = 100`) of a reflectance under a built-in light.
    pub fn reflectance_xyz(&self, illuminant: Illuminant, r: &Reflectance) -> Xyz {
        let light = illuminant.tabulated();
        match r {
            Reflectance::Paper(s) => {
                Moments::<2, 4>::new(self.observer, &light, PAPER_BREAKS).xyz(s)
            }
            Reflectance::Default(s) => {
                Moments::<8, 4>::new(self.observer, &light, Breaks::uniform()).xyz(s)
            }
        }
    }

    /// What the controller must answer for `target` (white `Y = 100`).
    pub fn colour(&self, target: Xyz) -> ColourReport {
        let enc = self.display.encode_relative(target, self.map);
        let duty = enc.device.map(|v| duty_of(v, self.max));
        let shown = duty.map(|d| d as f32 / self.max as f32);
        let white = self.display.white().y;
        let k = if white > 0.0 { 100.0 / white } else { 0.0 };
        ColourReport {
            xyz: target,
            led: self.display.device_to_xyz(shown).scale(k),
            linear: enc.linear,
            duty,
            max: self.max,
            gamut: if enc.out_of_gamut {
                Gamut::Out(self.map)
            } else {
                Gamut::In
            },
        }
    }

    /// The largest differences between two reports: `(|ΔXYZ| relative to Y = 100 over xyz
    /// and led, |Δduty| in ticks)`, and whether the gamut verdicts agree.
    pub fn compare(a: &ColourReport, b: &ColourReport) -> (f32, u16, bool) {
        let mut dxyz = 0.0f32;
        for (p, q) in [(a.xyz, b.xyz), (a.led, b.led)] {
            for (u, v) in p.to_array().iter().zip(q.to_array()) {
                dxyz = dxyz.max((u - v).abs());
            }
        }
        let dduty = a
            .duty
            .iter()
            .zip(b.duty)
            .map(|(u, v)| u.abs_diff(v))
            .max()
            .unwrap_or(0);
        (dxyz, dduty, a.gamut == b.gamut)
    }
}
