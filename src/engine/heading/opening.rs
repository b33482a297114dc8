//! The side of a walk's first steps, held until something knows it (issue 20; ours, none of the
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
//!   pelvis's vote says.
//!
//! A held step is late, not lost: live mode draws the walk's first steps a few seconds late,
//! as the onset look-back already does with the first second.

/// The most steps [`super::HeadingConfig::opening_steps`] may hold: what a walk's opening holds
/// stays bounded (about half a minute of walking).
pub const MAX_STEPS: usize = 64;

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
}
