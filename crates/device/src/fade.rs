//! Fade pacing: the application loop asks [`Pacer::due`] with the board's millisecond count and, when
//! a step is due, takes one fade step ([`crate::Controller::fade_step`]: the next point solved
//! by the mixer and its duties shown). One step every [`STEP_MS`] ms, i.e.
//! [`STEPS_PER_SECOND`] solved steps per second; a solve takes ≈ 2.4 ms of a 25 MHz
//! Cortex-M4 at worst (six channels; docs/leds.md), so the pace is kept with room to spare.

pub use specpoly_core::light::channels::STEPS_PER_SECOND;

/// Milliseconds between fade steps.
pub const STEP_MS: u32 = 1000 / STEPS_PER_SECOND;

/// When the next fade step is due.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pacer {
    last: u32,
}

impl Pacer {
    /// A pacer whose first step is due [`STEP_MS`] after `now`.
    pub const fn new(now: u32) -> Self {
        Self { last: now }
    }

    /// Whether a step is due at `now` (milliseconds, wrapping); if so, the next one is due
    /// [`STEP_MS`] later.
    pub fn due(&mut self, now: u32) -> bool {
        if now.wrapping_sub(self.last) >= STEP_MS {
            self.last = now;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_due_every_step_ms_across_the_wrap() {
        let start = u32::MAX - 15;
        let mut p = Pacer::new(start);
        let due: Vec<u32> = (0..40u32)
            .map(|i| start.wrapping_add(i))
            .filter(|t| p.due(*t))
            .collect();
        assert_eq!(
            due,
            [
                start.wrapping_add(10),
                start.wrapping_add(20),
                start.wrapping_add(30)
            ]
        );
    }
}
