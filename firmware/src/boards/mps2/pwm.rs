//! A PWM channel stand-in: QEMU's mps2-an386 has no PWM, so a channel only keeps its duty,
//! which the firmware reports over the UART (in replies) and semihosting.

use embedded_hal::pwm::{ErrorType, SetDutyCycle};

/// A 16-bit PWM channel that records its duty.
#[derive(Debug, Default)]
pub struct ReportedPwm {
    duty: u16,
}

impl ReportedPwm {
    /// Full-scale duty.
    pub const MAX: u16 = u16::MAX;

    /// The duty last set.
    pub fn duty(&self) -> u16 {
        self.duty
    }
}

impl ErrorType for ReportedPwm {
    type Error = core::convert::Infallible;
}

impl SetDutyCycle for ReportedPwm {
    fn max_duty_cycle(&self) -> u16 {
        Self::MAX
    }

    fn set_duty_cycle(&mut self, duty: u16) -> Result<(), Self::Error> {
        self.duty = duty;
        Ok(())
    }
}
