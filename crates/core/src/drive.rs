//! One drive step of a display: the colour a device is asked for, the integer levels it is
//! driven at, and the colour it then emits. The RGB-LED firmware answers every colour command
//! with it, and the host's model of the controller (`specpoly::led::Model`) calls the same
//! function, so there is one implementation of the step; both are checked against an
//! independent f64 computation (`specpoly::led::check`).
//!
//! `target XYZ (white Y = 100) ─scale to the display's white─▶ M⁻¹ ─gamut map─▶ linear drive
//! ─transfer curve⁻¹─▶ device value v ─round(v · max)─▶ level ─transfer curve, M─▶ emitted XYZ`
//!
//! (Cowan 1983, the paper's §7.3; quantisation as in [`crate::quantize`].)
//!
//! The step and the functions it calls are `#[inline]` so that they are compiled where they are
//! instantiated: the firmware runs it through `specpoly-kernels`, built for speed.

use crate::{quantize, Display, Encoded, GamutMap, Xyz};

/// What a display shows for a target colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drive {
    /// Linear drive after gamut mapping, in `[0, 1]`.
    pub linear: [f32; 3],
    /// Integer drive levels (PWM duties, DAC codes), `round(v · max)` of the device values.
    pub level: [u16; 3],
    /// The XYZ the display emits at those levels, relative to its white at `Y = 100`.
    pub emitted: Xyz,
    /// Whether the target was outside the gamut (and was mapped).
    pub out_of_gamut: bool,
}

impl Display {
    /// The drive step for `target` (relative to a white of `Y = 100`) on levels `0 ..= max`.
    #[inline]
    pub fn drive(&self, target: Xyz, map: GamutMap, max: u16) -> Drive {
        step(
            self.encode_relative(target, map),
            max,
            self.white().y,
            |shown| self.device_to_xyz(shown),
        )
    }
}

/// The step after encoding (shared by [`Display::drive`] and the full model's
/// [`crate::DisplayModel::drive`]): quantise `enc`'s device values to `0 ..= max`, and the
/// XYZ `emit` predicts at those levels, relative to a white of luminance `white_y` at 100.
pub(crate) fn step(enc: Encoded, max: u16, white_y: f32, emit: impl Fn([f32; 3]) -> Xyz) -> Drive {
    let level = enc.device.map(|v| quantize(v, max));
    let full = max.max(1) as f32;
    let shown = level.map(|d| d as f32 / full);
    let k = if white_y > 0.0 { 100.0 / white_y } else { 0.0 };
    Drive {
        linear: enc.linear,
        level,
        emitted: emit(shown).scale(k),
        out_of_gamut: enc.out_of_gamut,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Transfer, Xyy};

    #[test]
    fn full_scale_shows_the_white() {
        let d = Display::srgb();
        let w = d.white().scale(100.0 / d.white().y);
        let r = d.drive(w, GamutMap::Clip, 1000);
        assert_eq!(r.level, [1000; 3]);
        assert!(!r.out_of_gamut);
        assert!((r.emitted.y - 100.0).abs() < 1e-3, "{r:?}");
    }

    #[test]
    fn black_and_a_degenerate_scale_stay_dark() {
        let lin = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        let (xy, lum) = Display::srgb().primaries();
        let d = Display::from_primaries(xy, lum, Xyz::default(), lin).unwrap();
        let t = Xyy {
            x: 0.3,
            y: 0.3,
            big_y: 20.0,
        }
        .to_xyz();
        assert_eq!(d.drive(Xyz::default(), GamutMap::Clip, 255).level, [0; 3]);
        let z = d.drive(t, GamutMap::Clip, 0);
        assert_eq!(z.level, [0; 3]);
        assert_eq!(z.emitted, Xyz::default());
    }
}
