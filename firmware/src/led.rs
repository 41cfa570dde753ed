//! An RGB LED on three PWM channels (embedded-hal 1.0 [`SetDutyCycle`]).
//!
//! An LED's light output is proportional to its PWM duty (the drive current is constant while
//! on), so the duty *is* the linear drive of Cowan's model: the controller's transfer curve is
//! `linear` unless a measured curve says otherwise. Duties are `round(v · max)` for a device
//! value `v ∈ [0, 1]` ([`specpoly_core::quantize`]).

use embedded_hal::pwm::SetDutyCycle;

/// Why the LED could not be driven.
#[derive(Debug, PartialEq, Eq)]
pub enum LedError<E> {
    /// The three channels have different full-scale duties (red, green, blue).
    UnequalMax([u16; 3]),
    /// A channel has a full-scale duty of 0.
    ZeroMax,
    /// A channel refused a duty (0 = red, 1 = green, 2 = blue).
    Channel(usize, E),
}

/// Three PWM channels, red, green and blue, sharing one full-scale duty.
pub struct RgbLed<R, G, B> {
    r: R,
    g: G,
    b: B,
    max: u16,
    duty: [u16; 3],
}

impl<R, G, B> RgbLed<R, G, B>
where
    R: SetDutyCycle,
    G: SetDutyCycle<Error = R::Error>,
    B: SetDutyCycle<Error = R::Error>,
{
    /// Takes the channels and switches the LED off.
    pub fn new(r: R, g: G, b: B) -> Result<Self, LedError<R::Error>> {
        let maxes = [r.max_duty_cycle(), g.max_duty_cycle(), b.max_duty_cycle()];
        if maxes[0] != maxes[1] || maxes[0] != maxes[2] {
            return Err(LedError::UnequalMax(maxes));
        }
        if maxes[0] == 0 {
            return Err(LedError::ZeroMax);
        }
        let mut led = Self {
            r,
            g,
            b,
            max: maxes[0],
            duty: [0; 3],
        };
        led.set(led.duty)?;
        Ok(led)
    }

    /// The full-scale duty.
    pub fn max(&self) -> u16 {
        self.max
    }

    /// The duties last set.
    pub fn duty(&self) -> [u16; 3] {
        self.duty
    }

    /// Sets the three duties (each clamped to the full scale).
    pub fn set(&mut self, duty: [u16; 3]) -> Result<(), LedError<R::Error>> {
        let d = duty.map(|v| v.min(self.max));
        self.r
            .set_duty_cycle(d[0])
            .map_err(|e| LedError::Channel(0, e))?;
        self.g
            .set_duty_cycle(d[1])
            .map_err(|e| LedError::Channel(1, e))?;
        self.b
            .set_duty_cycle(d[2])
            .map_err(|e| LedError::Channel(2, e))?;
        self.duty = d;
        Ok(())
    }

    /// Sets device values in `[0, 1]`, quantised with [`specpoly_core::quantize`]; returns the
    /// duties.
    pub fn set_device(&mut self, device: [f32; 3]) -> Result<[u16; 3], LedError<R::Error>> {
        let d = device.map(|v| specpoly_core::quantize(v, self.max));
        self.set(d)?;
        Ok(d)
    }

    /// Gives the channels back.
    pub fn release(self) -> (R, G, B) {
        (self.r, self.g, self.b)
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
    fn drives_the_three_channels() {
        let r = channel(1000, &[0, 1000, 500]);
        let g = channel(1000, &[0, 0, 250]);
        let b = channel(1000, &[0, 1000, 1000]);
        let mut led = RgbLed::new(r, g, b).unwrap();
        assert_eq!(led.max(), 1000);
        // out-of-range duties are clamped to the full scale
        led.set([1000, 0, 4000]).unwrap();
        assert_eq!(led.duty(), [1000, 0, 1000]);
        assert_eq!(led.set_device([0.5, 0.25, 1.5]).unwrap(), [500, 250, 1000]);
        let (mut r, mut g, mut b) = led.release();
        r.done();
        g.done();
        b.done();
    }

    #[test]
    fn rejects_unequal_channels() {
        let mut r = Mock::new(&[Transaction::max_duty_cycle(255)]);
        let mut g = Mock::new(&[Transaction::max_duty_cycle(1023)]);
        let mut b = Mock::new(&[Transaction::max_duty_cycle(255)]);
        assert!(matches!(
            RgbLed::new(r.clone(), g.clone(), b.clone()),
            Err(LedError::UnequalMax([255, 1023, 255]))
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
        let mut led = RgbLed::new(r, g.clone(), b).unwrap();
        assert_eq!(
            led.set([50, 50, 50]),
            Err(LedError::Channel(1, MockError::Io(ErrorKind::Other)))
        );
        // the failed set leaves the recorded duties unchanged
        assert_eq!(led.duty(), [0, 0, 0]);
        let (mut r, _, mut b) = led.release();
        r.done();
        g.done();
        b.done();
    }
}
