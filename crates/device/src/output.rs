//! Which path the LED channels show: the colour path (`xyz`, `xyy`, `refl`, and every other
//! command, e.g. `cal`, `trc`, `map`, `load`, `lut`, which re-drive the last colour) on the
//! first three channels, or the mixer (`xy`, `cct` and their fade steps) on the channels
//! uploaded. A colour reply hands the channels to the colour path, a mix reply or a fade step to
//! the mixer; while the mixer shows, other commands leave the channels as they are.

use crate::led::Duties;
use crate::Controller;
use specpoly_protocol::Reply;

/// The path shown, updated from every reply.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Output {
    mixing: bool,
}

impl Output {
    /// The duties to drive after `reply` (the controller's answer to a line), or `None` when
    /// the channels stay as they are: while the mixer shows, any reply but a colour or a mix
    /// one; a mix target that starts a fade (its steps drive the channels: [`Output::step`]).
    pub fn after(&mut self, reply: &Reply, controller: &Controller) -> Option<Duties> {
        match reply {
            #[cfg(feature = "mixing")]
            Reply::Mix(r) => {
                self.mixing = true;
                (!controller.mixer.fading()).then(|| Duties::of(r.duty()))
            }
            Reply::Colour(_) => {
                self.mixing = false;
                Some(Duties::colour(controller.duty()))
            }
            _ if !self.mixing => Some(Duties::colour(controller.duty())),
            _ => None,
        }
    }

    /// One fade step's duties (`duty`: those of the channels uploaded): the mixer shows.
    pub fn step(&mut self, duty: &[u16]) -> Duties {
        self.mixing = true;
        Duties::of(duty)
    }

    /// Whether the mixer is shown.
    pub fn mixing(&self) -> bool {
        self.mixing
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_protocol::Command;

    fn answer(c: &mut Controller, o: &mut Output, line: &str) -> (Reply, Option<Duties>) {
        let reply = c.handle(Command::parse(line));
        let d = o.after(&reply, c);
        (reply, d)
    }

    #[test]
    fn colours_drive_the_first_three_channels() {
        let (mut c, mut o) = (Controller::new(1000), Output::default());
        let (reply, d) = answer(&mut c, &mut o, "xyz 20 20 20");
        let Reply::Colour(r) = reply else {
            panic!("{reply:?}")
        };
        assert_eq!(d, Some(Duties::colour(r.duty)));
        // a new calibration re-drives the colour: the channels follow
        let (_, d) = answer(&mut c, &mut o, "trc rgb gamma 2.2");
        assert_eq!(d.map(|d| d.all()[..3] == c.duty()), Some(true));
        assert_ne!(d.unwrap().lit(), r.duty, "gamma moved the duties");
        // other replies leave the duties as they are
        for l in ["state", "bogus", "observer 1931", "xyy 0.5 1e-45 3.4e38"] {
            assert_eq!(answer(&mut c, &mut o, l).1, d, "{l}");
        }
    }

    #[cfg(feature = "mixing")]
    #[test]
    fn a_mix_drives_its_channels_and_a_fade_waits_for_its_steps() {
        let (mut c, mut o) = (Controller::new(1000), Output::default());
        for l in [
            "channel 0 0.65 0.3 0",
            "channel 1 0.25 0.7 0.1",
            "channel 2 0.18 0.08 0.95",
            "channel 3 0.95 1 0.85",
        ] {
            let (_, d) = answer(&mut c, &mut o, l);
            assert_eq!(
                d,
                Some(Duties::colour([0; 3])),
                "{l}: the colour path shows, off"
            );
        }
        let (reply, d) = answer(&mut c, &mut o, "cct 4000 lum 0.5");
        let Reply::Mix(r) = reply else {
            panic!("{reply:?}")
        };
        assert_eq!(d.map(|d| d.lit().to_vec()), Some(r.duty().to_vec()));
        assert_eq!(d.unwrap().lit().len(), 4);
        assert!(o.mixing());
        // a calibration, an error do not touch the mixed channels
        for l in ["trc rgb gamma 2.2", "cct 4000 lum 7", "state"] {
            assert_eq!(answer(&mut c, &mut o, l).1, None, "{l}");
        }
        answer(&mut c, &mut o, "fade 30");
        let (_, d) = answer(&mut c, &mut o, "cct 6500 lum 0.9");
        assert_eq!(d, None, "the fade's steps drive the channels");
        let mut last = None;
        while let Some((_, _, duty)) = c.fade_step() {
            last = Some(o.step(&duty[..4]));
        }
        let end = c.mix_duty();
        assert_eq!(last.map(|d| d.lit().to_vec()), Some(end[..4].to_vec()));
        // a colour takes the channels back
        let (_, d) = answer(&mut c, &mut o, "xyz 20 20 20");
        assert_eq!(d.map(|d| d.lit().len()), Some(3));
        assert!(!o.mixing());
    }
}
