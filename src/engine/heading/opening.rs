//! The side of a walk's first steps, held until something knows it (ours, none of the
//! papers starts a walk with the phone on a limb).
//! May import: the rest of `engine`.
//!
//! The acceleration heading gives a line; its 180° comes from the pelvis's vertical phase
//! ([`super::forward_sign`]) until a limb gives it ([`super::HeadingConfig::limb_sign`]), and a
//! limb needs strides to: the thigh's swing two strides that look like a thigh's, the swinging
//! arm the leg pitch's axis. Meanwhile the pelvis's rule is what a phone on a limb misreads (the
//! limb's own pendulum term, in antiphase with the pelvis's): on the simulator the first 2–6
//! steps of 19 of 20 short pocket walks and of 13 of 20 swinging ones walked backwards, or 90°
//! off where the A-HE average met a step of the other side.
//!
//! So a bout's steps whose side is only the pelvis's are **held**, not placed on the track:
//! - while held, each step's direction takes the side nearest the one before turned by the
//!   device's yaw since (the gyroscope's turn: a step's direction scatters by tens of degrees,
//!   a turn adds up to 90° a step, and the chain must not break there), and the pelvis's rule
//!   votes on that chain's side, one vote per step;
//! - the first step whose side something knows (a limb signed it, or it walks the device's
//!   yaw) settles the bout: the steps held are released, turned by 180° when the last of them
//!   points away from it;
//! - after [`super::HeadingConfig::opening_steps`] steps held, at a bout's end, after a gap, or
//!   when the input ends ([`crate::engine::Pipeline::finish`]), they are released as the
//!   pelvis's vote says;
//! - and so they are as soon as [`TRUNK_STEPS`] steps in a row after the bout's first tilt the
//!   phone by less than [`super::HeadingConfig::opening_limb_tilt_deg`]: the phone rides the
//!   trunk or the head (a bag, a jacket, the ear), where the pelvis's rule is the side, and no
//!   limb will sign it. Without this the ear's and a bag's walks waited for the cap at every
//!   bout's start, 11 steps. The bout's first step says nothing: from standing, a thigh swings
//!   by part of a stride (the simulator's real-shaped starts: 3.6–19° of tilt, against 13–25°
//!   for the next steps; the ear 0.2–1.0°, a bag 2.1–7.8°).
//!
//! A held step is late, not lost: live mode draws the walk's first steps a few seconds late,
//! as the onset look-back already does with the first second.

use super::NavSample;
use nalgebra::Vector3;
use std::collections::VecDeque;

/// The most steps [`super::HeadingConfig::opening_steps`] may hold: what a walk's opening holds
/// stays bounded (about half a minute of walking).
pub const MAX_STEPS: usize = 64;

/// Steps in a row, after a bout's first, that must tilt the phone by less than
/// [`super::HeadingConfig::opening_limb_tilt_deg`] to say that no limb carries it. Two: from
/// its second step on, a thigh tilts the phone by a good part of a stride.
pub const TRUNK_STEPS: usize = 2;

/// The phone's tilt over a step: the largest angle, degrees, between its up direction at the
/// samples of `buf` from `from` to `to` and their mean (a step swings a thigh from one end of its
/// stride to the other, so about half the stride's swing). `None` without an attitude.
pub fn step_tilt_deg(buf: &VecDeque<NavSample>, from: f64, to: f64) -> Option<f64> {
    let start = buf.partition_point(|x| x.t < from);
    let ups = || {
        buf.range(start..)
            .take_while(|x| x.t <= to)
            .map(|x| Vector3::from(x.device_up))
            .filter(|u| u.norm_squared() > 0.25)
    };
    let mean = ups()
        .fold(Vector3::zeros(), |a, u| a + u)
        .try_normalize(1e-9)?;
    let least = ups().map(|u| u.dot(&mean)).fold(1.0, f64::min);
    Some(libm::acos(least.clamp(-1.0, 1.0)).to_degrees())
}

/// The state of the bout's opening.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Opening {
    // Something knew the side of one of the bout's steps (or the bout's held steps were
    // released): the steps after walk as they come.
    settled: bool,
    // Steps held.
    held: usize,
    // The pelvis's rule: steps that agreed with the chain's side, less those that did not.
    vote: i32,
    // The device's yaw at the last step chained, compass radians, unwrapped.
    yaw: Option<f64>,
    // Steps in a row after the first held that tilted the phone as no limb does.
    trunk: usize,
}

impl Opening {
    /// Whether the bout's side is known.
    pub fn settled(&self) -> bool {
        self.settled
    }

    /// How many steps are held.
    pub fn held(&self) -> usize {
        self.held
    }

    /// The pelvis's direction `theta` (rad from north) of a step that may be held, on the side
    /// of `previous`, the last held step's direction (none for the first), turned by the
    /// device's `yaw` since (compass radians, unwrapped); the pelvis votes.
    pub fn chain(&mut self, theta: f64, previous: Option<f64>, yaw: f64) -> f64 {
        let turned = self.yaw.replace(yaw).map_or(0.0, |y| yaw - y);
        match previous {
            Some(p) if self.held > 0 && libm::cos(theta - p - turned) < 0.0 => {
                self.vote -= 1;
                super::wrap_2pi(theta + std::f64::consts::PI)
            }
            _ => {
                self.vote += 1;
                theta
            }
        }
    }

    /// The tilt of a step that may be held ([`step_tilt_deg`]), before it is chained: with
    /// others before it, a tilt under `limit_deg` counts towards [`Self::no_limb`], and any
    /// other (or none known) starts the count again.
    pub fn tilt(&mut self, tilt_deg: Option<f64>, limit_deg: f64) {
        if self.held == 0 {
            return;
        }
        self.trunk = match tilt_deg {
            Some(t) if t < limit_deg => self.trunk + 1,
            _ => 0,
        };
    }

    /// Whether [`TRUNK_STEPS`] steps in a row tilted the phone as no limb does.
    pub fn no_limb(&self) -> bool {
        self.trunk >= TRUNK_STEPS
    }

    /// One more step held.
    pub fn hold(&mut self) {
        self.held = self.held.saturating_add(1);
    }

    /// The held steps are released, settling the bout; returns whether the pelvis's vote turns
    /// them by 180°.
    pub fn release_by_vote(&mut self) -> bool {
        let turn = self.vote < 0;
        self.settle();
        turn
    }

    /// The bout's side is known: nothing more is held.
    pub fn settle(&mut self) {
        *self = Opening {
            settled: true,
            ..Opening::default()
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chain_keeps_one_side_and_the_pelvis_votes_on_it() {
        let mut o = Opening::default();
        let first = o.chain(0.1, None, 0.0);
        o.hold();
        // The pelvis turned the next step over: the chain keeps the side, the vote goes down.
        let second = o.chain(0.2 + std::f64::consts::PI, Some(first), 0.0);
        o.hold();
        assert!((second - 0.2).abs() < 1e-12, "{second}");
        // A turn of 100° in a step, which the yaw saw, does not break the chain.
        let turn = 100f64.to_radians();
        let third = o.chain(0.2 + turn + std::f64::consts::PI, Some(second), turn);
        o.hold();
        assert!((third - 0.2 - turn).abs() < 1e-12, "{third}");
        assert_eq!(o.held(), 3);
        // Two against one: the held steps turn.
        assert!(o.release_by_vote());
        assert!(o.settled() && o.held() == 0);
    }

    /// Samples 0.01 s apart over 1 s whose up direction in the device leans by `lean(t)`
    /// degrees about the device's x axis.
    fn leaning(lean: impl Fn(f64) -> f64) -> VecDeque<NavSample> {
        (0..=100)
            .map(|i| {
                let t = i as f64 * 0.01;
                let a = lean(t).to_radians();
                NavSample {
                    device_up: [0.0, libm::sin(a), libm::cos(a)],
                    ..NavSample::empty(t)
                }
            })
            .collect()
    }

    #[test]
    fn a_steps_tilt_is_its_up_directions_largest_angle_from_their_mean() {
        // A step swings from one end to the other: ±20° about the mean.
        let buf = leaning(|t| 20.0 * libm::cos(std::f64::consts::PI * t));
        let tilt = step_tilt_deg(&buf, 0.0, 1.0).unwrap();
        assert!((tilt - 20.0).abs() < 0.5, "{tilt}");
        // Only the samples of the window count; none without an attitude.
        assert!(step_tilt_deg(&buf, 0.5, 0.5).unwrap() < 1e-6);
        let mut none = leaning(|_| 0.0);
        none.iter_mut().for_each(|x| x.device_up = [0.0; 3]);
        assert_eq!(step_tilt_deg(&none, 0.0, 1.0), None);
    }

    #[test]
    fn two_steps_after_the_first_that_tilt_as_no_limb_does_say_so() {
        let mut o = Opening::default();
        let step = |o: &mut Opening, tilt: Option<f64>| {
            o.tilt(tilt, 12.5);
            o.chain(0.0, Some(0.0), 0.0);
            o.hold();
        };
        // The first step says nothing, however little it tilts.
        step(&mut o, Some(1.0));
        step(&mut o, Some(5.0));
        assert!(!o.no_limb());
        // A limb's tilt, or none known, starts the count again.
        step(&mut o, Some(20.0));
        step(&mut o, Some(5.0));
        step(&mut o, None);
        step(&mut o, Some(5.0));
        assert!(!o.no_limb());
        step(&mut o, Some(12.0));
        assert!(o.no_limb());
    }
}
