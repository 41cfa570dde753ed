//! The LED's PWM channels: up to [`CHANNELS`] embedded-hal 1.0 [`SetDutyCycle`] channels
//! sharing one full-scale duty ([`Led`]), and the duties they are driven with ([`Duties`]).
//!
//! An LED's light output is proportional to its PWM duty (the drive current is constant while
//! on), so the duty *is* the linear drive of Cowan's model: the controller's transfer curve is
//! `linear` unless a measured curve says otherwise. Duties are `round(v · max)` for a device
//! value `v ∈ [0, 1]` ([`specpoly_core::quantize`]). The colour path drives the first three
//! channels (red, green, blue); the mixer drives as many as were uploaded (`channel`).

use embedded_hal::pwm::SetDutyCycle;

/// Most PWM channels a controller drives (the mixer's most channels).
pub const CHANNELS: usize = 6;

/// Why the LED could not be driven.
#[derive(Debug, PartialEq, Eq)]
pub enum LedError<E> {
    /// The channels have different full-scale duties (the first two that differ).
    UnequalMax(u16, u16),
    /// A channel has a full-scale duty of 0.
    ZeroMax,
    /// A channel refused a duty (its index).
    Channel(usize, E),
}

/// The duties of the first `n` channels; the others are off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Duties {
    duty: [u16; CHANNELS],
    n: u8,
}

impl Duties {
    /// The colour path's red, green and blue duties on the first three channels.
    pub fn colour(rgb: [u16; 3]) -> Self {
        Self::of(&rgb)
    }

    /// The duties in `d` on the first `d.len()` channels (at most [`CHANNELS`]).
    pub fn of(d: &[u16]) -> Self {
        let n = d.len().min(CHANNELS);
        let mut duty = [0; CHANNELS];
        duty[..n].copy_from_slice(&d[..n]);
        Self { duty, n: n as u8 }
    }

    /// The duties of the channels driven.
    pub fn lit(&self) -> &[u16] {
        &self.duty[..self.n as usize]
    }

    /// All [`CHANNELS`] duties, the channels not driven at 0.
    pub fn all(&self) -> [u16; CHANNELS] {
        self.duty
    }
}

/// `N` PWM channels of one full-scale duty.
pub struct Led<P, const N: usize> {
    channels: [P; N],
    max: u16,
    duty: [u16; N],
}

impl<P: SetDutyCycle, const N: usize> Led<P, N> {
    /// Takes the channels and switches the LED off.
    pub fn new(channels: [P; N]) -> Result<Self, LedError<P::Error>> {
        let maxes = channels.each_ref().map(P::max_duty_cycle);
        let max = maxes.first().copied().unwrap_or(0);
        if let Some(other) = maxes.iter().find(|m| **m != max) {
            return Err(LedError::UnequalMax(max, *other));
        }
        if max == 0 {
            return Err(LedError::ZeroMax);
        }
        let mut led = Self {
            channels,
            max,
            duty: [0; N],
        };
        led.set(&[0; N])?;
        Ok(led)
    }

    /// The full-scale duty.
    pub fn max(&self) -> u16 {
        self.max
    }

    /// The duties last set.
    pub fn duty(&self) -> [u16; N] {
        self.duty
    }

    /// Sets the first `duty.len()` channels (each clamped to the full scale) and switches the
    /// others off. On a channel's error the recorded duties stay as they were.
    pub fn set(&mut self, duty: &[u16]) -> Result<(), LedError<P::Error>> {
        let mut d = [0; N];
        for (to, from) in d.iter_mut().zip(duty) {
            *to = (*from).min(self.max);
        }
        for (i, (c, v)) in self.channels.iter_mut().zip(d).enumerate() {
            c.set_duty_cycle(v).map_err(|e| LedError::Channel(i, e))?;
        }
        self.duty = d;
        Ok(())
    }

    /// Sets device values in `[0, 1]`, quantised with [`specpoly_core::quantize`]; returns the
    /// duties.
    pub fn set_device(&mut self, device: [f32; N]) -> Result<[u16; N], LedError<P::Error>> {
        let d = device.map(|v| specpoly_core::quantize(v, self.max));
        self.set(&d)?;
        Ok(d)
    }

    /// Gives the channels back.
    pub fn release(self) -> [P; N] {
        self.channels
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_hal_mock::eh1::pwm::{Mock, Transaction};
    use embedded_hal_mock::eh1::MockError;
    use std::io::ErrorKind;

    fn channel(max: u16, duties: &[u16]) -> Mock {
        let mut t = vec![Transaction::max_duty_cycle(max)];
        t.extend(duties.iter().map(|d| Transaction::set_duty_cycle(*d)));
        Mock::new(&t)
    }

    #[test]
    fn drives_the_channels() {
        let r = channel(1000, &[0, 1000, 500]);
        let g = channel(1000, &[0, 0, 250]);
        let b = channel(1000, &[0, 1000, 1000]);
        let mut led = Led::new([r, g, b]).unwrap();
        assert_eq!(led.max(), 1000);
        // out-of-range duties are clamped to the full scale
        led.set(&[1000, 0, 4000]).unwrap();
        assert_eq!(led.duty(), [1000, 0, 1000]);
        assert_eq!(led.set_device([0.5, 0.25, 1.5]).unwrap(), [500, 250, 1000]);
        for mut c in led.release() {
            c.done();
        }
    }

    #[test]
    fn channels_past_the_duties_given_are_switched_off() {
        let chans = [
            channel(100, &[0, 10, 30]),
            channel(100, &[0, 20, 0]),
            channel(100, &[0, 0, 0]),
            channel(100, &[0, 0, 0]),
        ];
        let mut led = Led::new(chans).unwrap();
        led.set(Duties::of(&[10, 20]).lit()).unwrap();
        assert_eq!(led.duty(), [10, 20, 0, 0]);
        led.set(&Duties::colour([30, 0, 0]).all()).unwrap();
        assert_eq!(led.duty(), [30, 0, 0, 0]);
        for mut c in led.release() {
            c.done();
        }
    }

    #[test]
    fn duties_keep_the_channels_given() {
        let d = Duties::of(&[1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(d.lit(), &[1, 2, 3, 4, 5, 6], "at most CHANNELS");
        assert_eq!(Duties::colour([7, 8, 9]).lit(), &[7, 8, 9]);
        assert_eq!(Duties::colour([7, 8, 9]).all(), [7, 8, 9, 0, 0, 0]);
    }

    #[test]
    fn rejects_unequal_channels() {
        let mut r = Mock::new(&[Transaction::max_duty_cycle(255)]);
        let mut g = Mock::new(&[Transaction::max_duty_cycle(1023)]);
        let mut b = Mock::new(&[Transaction::max_duty_cycle(255)]);
        assert!(matches!(
            Led::new([r.clone(), g.clone(), b.clone()]),
            Err(LedError::UnequalMax(255, 1023))
        ));
        r.done();
        g.done();
        b.done();
    }

    #[test]
    fn reports_a_failing_channel() {
        let r = channel(100, &[0, 50]);
        let mut g = Mock::new(&[
            Transaction::max_duty_cycle(100),
            Transaction::set_duty_cycle(0),
            Transaction::set_duty_cycle(50).with_error(MockError::Io(ErrorKind::Other)),
        ]);
        let b = channel(100, &[0]);
        let mut led = Led::new([r, g.clone(), b]).unwrap();
        assert_eq!(
            led.set(&[50, 50, 50]),
            Err(LedError::Channel(1, MockError::Io(ErrorKind::Other)))
        );
        // the failed set leaves the recorded duties unchanged
        assert_eq!(led.duty(), [0, 0, 0]);
        let [mut r, _, mut b] = led.release();
        r.done();
        g.done();
        b.done();
    }
}
