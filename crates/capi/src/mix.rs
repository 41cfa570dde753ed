//! Mixing 3–[`SP_MAX_CHANNELS`] LED channels to an `xy` or CCT/Duv target, and the fade
//! stepper: [`specpoly_core::light::channels`] (the most light at the target chromaticity, the
//! freedom beyond three channels spent on the least weighted drive; fades linear in `u′v′` and
//! in `L^{1/3}`, one step per 10 ms).
//!
//! The whole state is the caller's [`SpMixer`]: the channels, the fade time and the fade under
//! way (its end points and step). Each call checks it and rebuilds the core's channel list from
//! it (six copies of 20 B); a target and each fade step are solved as the core's
//! [`specpoly_core::light::channels::Mixer`] solves them (the tests compare every value).

use crate::cct::SpXy;
use crate::status::{finite, of, Status};
use crate::{ptr, SpStatus};
use specpoly_core::light::channels::{Channel, Channels, Curve, Fade, Goal, MixError, Point};

/// The most channels a mix takes.
pub const SP_MAX_CHANNELS: usize = 6;

/// One LED channel.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpChannel {
    /// CIE 1931 X, Y, Z at full drive (any unit common to all channels).
    pub xyz: [f32; 3],
    /// The weight of its duty in the drive minimised with more than three channels (≥ 0; 1 for
    /// each gives the least total drive).
    pub cost: f32,
    /// Its transfer curve, duty → light: 1 linear (PWM), 0 the sRGB curve, else `l = v^gamma`
    /// (> 0).
    pub gamma: f32,
}

/// A mix target: CIE 1976 `u′v′` and relative luminance.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpPoint {
    /// u′.
    pub u: f32,
    /// v′.
    pub v: f32,
    /// Relative luminance in [0, 1] (a fraction of the most the channels give there).
    pub lum: f32,
}

/// The mixer's state, owned by the caller: zero it (or call `sp_mixer_init`), set `count`,
/// `channels` and `fade_ms`; the fade fields are written by `sp_mix_target_*` and
/// `sp_mix_step`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpMixer {
    /// Channels in use, 3 to `SP_MAX_CHANNELS`.
    pub count: u32,
    /// The channels; those past `count` are ignored.
    pub channels: [SpChannel; SP_MAX_CHANNELS],
    /// Fade time for new targets, ms (0: shown at once); one step per 10 ms.
    pub fade_ms: u32,
    /// The fade's start.
    pub from: SpPoint,
    /// The fade's end, the last target (u′ = v′ = 0: no target shown yet).
    pub to: SpPoint,
    /// Fade steps taken.
    pub step: u16,
    /// Fade steps in all (0: shown at once).
    pub steps: u16,
}

/// A solved target.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpMixResult {
    /// The target as CIE 1976 `u′v′` and relative luminance.
    pub point: SpPoint,
    /// The target's CIE 1931 chromaticity.
    pub xy: SpXy,
    /// Light fractions of the channels (before their curves); zeros past `count`.
    pub light: [f32; SP_MAX_CHANNELS],
    /// PWM duties out of `max`; zeros past `count`.
    pub duty: [u16; SP_MAX_CHANNELS],
    /// Fade steps that will take the light there (0: shown at once).
    pub steps: u32,
}

/// One fade step.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpMixStep {
    /// The step just taken, 1 to `steps`.
    pub step: u32,
    /// Steps in all.
    pub steps: u32,
    /// The point shown at this step.
    pub point: SpPoint,
    /// PWM duties out of `max`; zeros past the channel count.
    pub duty: [u16; SP_MAX_CHANNELS],
}

impl From<Point> for SpPoint {
    fn from(p: Point) -> Self {
        Self {
            u: p.uv[0],
            v: p.uv[1],
            lum: p.lum,
        }
    }
}

impl From<SpPoint> for Point {
    fn from(p: SpPoint) -> Self {
        Point {
            uv: [p.u, p.v],
            lum: p.lum,
        }
    }
}

fn mix_status(e: MixError) -> SpStatus {
    match e {
        MixError::Channels => SpStatus::Channels,
        MixError::OutOfGamut => SpStatus::OutOfGamut,
        MixError::BadTarget => SpStatus::Domain,
    }
}

/// The core's channel list from the caller's state, every field checked.
fn channels(m: &SpMixer) -> Status<Channels<SP_MAX_CHANNELS>> {
    let n = m.count as usize;
    if !(3..=SP_MAX_CHANNELS).contains(&n) {
        return Err(SpStatus::Channels);
    }
    let mut list = Channels::new();
    for (i, c) in m.channels[..n].iter().enumerate() {
        finite(&c.xyz)?;
        finite(&[c.cost, c.gamma])?;
        if !(c.cost >= 0.0 && c.gamma >= 0.0) {
            return Err(SpStatus::Domain);
        }
        let curve = match c.gamma {
            0.0 => Curve::Srgb,
            1.0 => Curve::Linear,
            g => Curve::Gamma(g),
        };
        list.set(i, Channel::new(c.xyz, c.cost, curve))
            .map_err(mix_status)?;
    }
    Ok(list)
}

/// The fade stored in the caller's state, checked: `(from, to, step, steps)`.
fn fade(m: &SpMixer) -> Status<(Point, Point, u16, u16)> {
    for p in [m.from, m.to] {
        finite(&[p.u, p.v, p.lum])?;
    }
    if m.step > m.steps {
        return Err(SpStatus::Domain);
    }
    Ok((m.from.into(), m.to.into(), m.step, m.steps))
}

/// The point of step `k` of the fade `from → to` in `steps` steps: the core's
/// [`Fade::at`] at `k / steps`, the target itself at the end ([`Fade::now`]).
fn fade_point(from: Point, to: Point, k: u16, steps: u16) -> Point {
    if k < steps {
        // Fade::new with 10 ms per step has exactly `steps` steps
        Fade::new(from, to, steps as u32 * 10).at(k as f32 / steps as f32)
    } else {
        to
    }
}

/// Zeroes a mixer: no channels, no fade time, nothing shown.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`m` NULL).
///
/// # Safety
/// `m` is NULL or points to a writable `SpMixer`.
#[no_mangle]
pub unsafe extern "C" fn sp_mixer_init(m: *mut SpMixer) -> SpStatus {
    // SAFETY: forwarded contract.
    of(unsafe { ptr::get_mut(m) }.map(|m| *m = SpMixer::default()))
}

fn target(m: &mut SpMixer, goal: Goal, max: u16) -> Status<SpMixResult> {
    let list = channels(m)?;
    let (from, to, step, steps) = fade(m)?;
    let point = goal.point().ok_or(SpStatus::Domain)?;
    let light = list.solve(point).map_err(mix_status)?;
    let duty = list.duties(&light, max);
    let shown = (to.uv != [0.0; 2]).then(|| fade_point(from, to, step, steps));
    let (start, steps) = if m.fade_ms > 0 {
        let start = shown.unwrap_or(Point { lum: 0.0, ..point });
        (start, Fade::new(start, point, m.fade_ms).progress().1)
    } else {
        (point, 0)
    };
    (m.from, m.to, m.step, m.steps) = (start.into(), point.into(), 0, steps);
    let [x, y] = point.xy();
    Ok(SpMixResult {
        point: point.into(),
        xy: SpXy { x, y },
        light,
        duty,
        steps: steps as u32,
    })
}

fn target_call(
    m: *mut SpMixer,
    goal: Goal,
    inputs: [f32; 3],
    max: u16,
    out: *mut SpMixResult,
) -> SpStatus {
    // SAFETY: the callers' contract: NULL or valid, unaliased pointers.
    let (m, out) = match unsafe { (ptr::get_mut(m), ptr::get_mut(out)) } {
        (Ok(m), Ok(out)) => (m, out),
        _ => return SpStatus::NullPointer,
    };
    of(finite(&inputs).and_then(|()| {
        *out = target(m, goal, max)?;
        Ok(())
    }))
}

/// Solves the chromaticity `(x, y)` at relative luminance `lum` on duties `0..=max`; with a fade
/// time, starts a fade from the point shown now (from black at the target's chromaticity when
/// nothing was shown), else shows it at once. On an error the mixer is unchanged.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`m` or `out` NULL); `SP_STATUS_NOT_FINITE`
/// (an input, a channel's field or the fade's points NaN or infinite); `SP_STATUS_DOMAIN` (not
/// `x, y > 0`, `x + y < 1`; `lum` outside [0, 1]; a negative cost or gamma; `step > steps`);
/// `SP_STATUS_CHANNELS` (`count` outside 3 to `SP_MAX_CHANNELS`); `SP_STATUS_OUT_OF_GAMUT`.
///
/// # Safety
/// `m` and `out` are NULL or point to a valid `SpMixer` and a writable `SpMixResult`.
#[no_mangle]
pub unsafe extern "C" fn sp_mix_target_xy(
    m: *mut SpMixer,
    x: f32,
    y: f32,
    lum: f32,
    max: u16,
    out: *mut SpMixResult,
) -> SpStatus {
    let goal = Goal::Xy { xy: [x, y], lum };
    target_call(m, goal, [x, y, lum], max, out)
}

/// As `sp_mix_target_xy` for a CCT (1000–25 000 K) and Duv (|Duv| ≤ 0.05, positive above the
/// locus): the chromaticity of `sp_cct_to_xy`. The same statuses (`SP_STATUS_DOMAIN` for a CCT
/// or Duv outside those ranges).
///
/// # Safety
/// `m` and `out` are NULL or point to a valid `SpMixer` and a writable `SpMixResult`.
#[no_mangle]
pub unsafe extern "C" fn sp_mix_target_cct(
    m: *mut SpMixer,
    cct: f32,
    duv: f32,
    lum: f32,
    max: u16,
    out: *mut SpMixResult,
) -> SpStatus {
    let goal = Goal::Cct { cct, duv, lum };
    target_call(m, goal, [cct, duv, lum], max, out)
}

fn step(m: &mut SpMixer, max: u16) -> Status<Option<SpMixStep>> {
    let list = channels(m)?;
    let (from, to, step, steps) = fade(m)?;
    if step >= steps {
        return Ok(None);
    }
    let k = step + 1;
    let p = fade_point(from, to, k, steps);
    match list.solve(p) {
        Ok(light) => {
            m.step = k;
            Ok(Some(SpMixStep {
                step: k as u32,
                steps: steps as u32,
                point: p.into(),
                duty: list.duties(&light, max),
            }))
        }
        Err(e) => {
            // the channels changed meanwhile: the fade ends where it is
            (m.from, m.to, m.step, m.steps) = (p.into(), p.into(), 0, 0);
            Err(mix_status(e))
        }
    }
}

/// One fade step (call it every 10 ms while it returns `SP_STATUS_OK`): the next point, solved
/// on duties `0..=max`; the last step is the target exactly.
///
/// Returns `SP_STATUS_OK` (`out` written); `SP_STATUS_FADE_DONE` (no step pending; `out`
/// untouched); `SP_STATUS_NULL_POINTER`; `SP_STATUS_NOT_FINITE`, `SP_STATUS_DOMAIN`,
/// `SP_STATUS_CHANNELS` (a mixer state `sp_mix_target_xy` would refuse); `SP_STATUS_OUT_OF_GAMUT`
/// (the channels changed since the target and cannot make this step: the fade ends there).
///
/// # Safety
/// `m` and `out` are NULL or point to a valid `SpMixer` and a writable `SpMixStep`.
#[no_mangle]
pub unsafe extern "C" fn sp_mix_step(m: *mut SpMixer, max: u16, out: *mut SpMixStep) -> SpStatus {
    // SAFETY: forwarded contract.
    let (m, out) = match unsafe { (ptr::get_mut(m), ptr::get_mut(out)) } {
        (Ok(m), Ok(out)) => (m, out),
        _ => return SpStatus::NullPointer,
    };
    match step(m, max) {
        Ok(Some(s)) => {
            *out = s;
            SpStatus::Ok
        }
        Ok(None) => SpStatus::FadeDone,
        Err(e) => e,
    }
}
