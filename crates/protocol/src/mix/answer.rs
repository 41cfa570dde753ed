//! [`answer`]: a mixing command becomes a [`Mixer`](specpoly_core::light::channels::Mixer)
//! call and a reply. Above [`crate::command`] and [`crate::reply`] (it takes the one and
//! makes the other), which both sit above the mixing types of [`super`].

use super::{range, ChannelCommand, DeviceMixer, MixReport};
use crate::command::Command;
use crate::fault::{ErrorCode, Fault};
use crate::reply::Reply;
use specpoly_core::light::channels::{Channel, MixError};

/// Answers a mixing command with `mixer` on PWM channels of full scale `max`; `None` for any
/// other command. Errors: `channel` past the next free one → `out-of-range at=1`; a target
/// with fewer than three channels → `no-channels`; outside the channels' gamut →
/// `out-of-gamut`. On an error nothing changes.
pub fn answer(mixer: &mut DeviceMixer, cmd: &Command, max: u16) -> Option<Reply> {
    let r = match cmd {
        Command::Channel(ChannelCommand::Clear) => {
            mixer.channels.clear();
            Ok(Reply::Done("channel"))
        }
        Command::Channel(ChannelCommand::Set { index, xyz, cost }) => {
            let i = *index as usize;
            let curve = mixer.channels.list().get(i).map(Channel::curve);
            let c = Channel::new(*xyz, *cost, curve.unwrap_or_default());
            mixer.channels.set(i, c).map(|_| Reply::Done("channel"))
        }
        Command::Channel(ChannelCommand::Curve { index, curve }) => mixer
            .channels
            .set_curve(*index as usize, *curve)
            .map(|_| Reply::Done("channel")),
        Command::Fade(ms) => {
            mixer.fade_ms = *ms;
            Ok(Reply::Done("fade"))
        }
        Command::Mix(goal) => mixer.target(*goal, max).map(|s| {
            Reply::Mix(MixReport {
                xy: s.point.xy(),
                lum: s.point.lum,
                light: s.light,
                duty: s.duty,
                n: s.n as u8,
                max,
                steps: s.steps,
            })
        }),
        _ => return None,
    };
    Some(r.unwrap_or_else(|e| {
        Reply::Error(match e {
            MixError::Channels if matches!(cmd, Command::Channel(_)) => range(1),
            MixError::Channels => Fault::new(ErrorCode::NoChannels),
            MixError::OutOfGamut => Fault::new(ErrorCode::OutOfGamut),
            MixError::BadTarget => Fault::new(ErrorCode::OutOfRange),
        })
    }))
}
