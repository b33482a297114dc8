//! Where the IMU is worn, and recognising a foot-mounted log from its signal.
//! May import: the rest of `engine`.
//!
//! # Recognising a foot
//! A foot-mounted IMU shows what no phone in a pocket, a hand or a bag shows: every stride, a
//! stance in which the foot is still (|ω| and | |f| − g | under the stance detector's thresholds
//! for T_min) between swings in which the foot turns at several rad/s (6–11 rad/s on the x-io
//! walks), and the strapdown integration between two stances gives a plausible stride. The
//! [`Recogniser`] takes the strides of the foot stage, run alongside the body pipeline while the
//! placement is undecided, and says "foot" after [`FOOT_STRIDES`] plausible strides in a row:
//! a swing of 0.2–1.2 s turning at [`MIN_SWING_RATE`] or more, a horizontal length of
//! 0.3–2.5 m, a stance of at most 3 s before it (a stop between walks restarts the count). A
//! log undecided after [`DECIDE_WITHIN_S`] of samples is a body log for good (the foot stage is
//! dropped), and so is one in which the step detector counted [`BODY_STEPS_IN_SWING`] steps
//! within one of the foot stage's swings: a walking foot sets down every stride.
//!
//! Why the second rule: a phone swinging in the hand or riding in a bag shows no stance for as
//! long as the walk goes on, while the foot stage integrates its gyroscope's bias into its tilt
//! (0.1 rad in 20 s). Moved into a trouser pocket within the first 30 s, the thigh turns at up
//! to 4.1 rad/s at 1.8–2.0 Hz on the simulator and sits still enough at heel strike for a
//! stance, and the tilted filter turns gravity into strides of 0.7–1.6 m: plausible foot
//! strides, and the walk's steps were replaced by them (5 of 8 simulated walks from a bag and
//! from a swinging hand; from the hand or the ear: none).
//!
//! The real pocket and hand-held logs of `../shared/data` are never recognised as feet
//! (`tests/foot.rs`).
//!
//! No importer hint is needed or used: uploaded, replayed and live logs are recognised alike,
//! inside [`crate::engine::Pipeline::push`].

use super::Stride;

/// Where the IMU is worn.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// Recognised from the signal: foot mode once a foot's strides are seen within
    /// [`DECIDE_WITHIN_S`], body otherwise.
    #[default]
    Auto,
    /// A phone carried on the body (hand, pocket, bag): steps by the step detector.
    Body,
    /// A shoe-mounted IMU: strides by zero-velocity updates ([`super::Foot`]).
    Foot,
}

impl Placement {
    /// The settings value.
    pub fn as_str(self) -> &'static str {
        match self {
            Placement::Auto => "auto",
            Placement::Body => "body",
            Placement::Foot => "foot",
        }
    }
}

/// Plausible strides in a row that make a foot.
pub const FOOT_STRIDES: u32 = 4;
/// The least peak |ω| of a foot's swing, rad/s (x-io walks: 6–11 rad/s).
pub const MIN_SWING_RATE: f64 = 4.0;
/// How long, s of samples, the placement may stay undecided.
pub const DECIDE_WITHIN_S: f64 = 30.0;
/// The longest swing of a foot's stride, s.
pub const MAX_SWING_S: f64 = 1.2;
/// Steps of the step detector within one swing of the foot stage that make a body log: two
/// strides with no stance between them.
pub const BODY_STEPS_IN_SWING: usize = 4;

/// What the strides so far say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Not yet decided.
    Undecided,
    /// A foot.
    Foot,
    /// Not a foot: a phone on the body.
    Body,
}

/// Counts plausible foot strides in a row.
#[derive(Debug, Clone, Default)]
pub struct Recogniser {
    run: u32,
    last_end: Option<f64>,
}

impl Recogniser {
    /// Whether `s` is a foot's stride.
    pub fn plausible(s: &Stride, previous_end: Option<f64>) -> bool {
        let swing = s.t_end - s.t_start;
        let stance_ok = previous_end.map_or(true, |e| s.t_start - e <= 3.0);
        (0.2..=MAX_SWING_S).contains(&swing)
            && s.peak_rate_rad_s >= MIN_SWING_RATE
            && (0.3..=2.5).contains(&s.length_m)
            && stance_ok
    }

    /// Takes a stride and how many steps the step detector counted within its swing: a foot
    /// once [`FOOT_STRIDES`] plausible strides came in a row, the body once a swing held
    /// [`BODY_STEPS_IN_SWING`] steps.
    pub fn push(&mut self, s: &Stride, steps_in_swing: usize) -> Verdict {
        if s.t_end - s.t_start > MAX_SWING_S && steps_in_swing >= BODY_STEPS_IN_SWING {
            return Verdict::Body;
        }
        if Self::plausible(s, self.last_end) {
            self.run += 1;
        } else {
            self.run = 0;
        }
        self.last_end = Some(s.t_end);
        if self.run >= FOOT_STRIDES {
            Verdict::Foot
        } else {
            Verdict::Undecided
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stride(t: f64, len: f64, rate: f64) -> Stride {
        long_stride(t, 0.6, len, rate)
    }

    fn long_stride(t: f64, swing: f64, len: f64, rate: f64) -> Stride {
        Stride {
            t_start: t,
            t_end: t + swing,
            t_mid_swing: t + 0.3,
            length_m: len,
            heading_rad: 0.0,
            east_m: 0.0,
            north_m: 0.0,
            up_m: 0.0,
            peak_rate_rad_s: rate,
        }
    }

    #[test]
    fn four_plausible_strides_in_a_row_make_a_foot() {
        use Verdict::{Foot, Undecided};
        let mut r = Recogniser::default();
        assert_eq!(r.push(&stride(0.0, 1.4, 8.0), 0), Undecided);
        assert_eq!(r.push(&stride(1.0, 1.4, 8.0), 1), Undecided);
        assert_eq!(
            r.push(&stride(2.0, 0.1, 8.0), 0),
            Undecided,
            "too short: the count restarts"
        );
        assert_eq!(
            r.push(&stride(3.0, 1.4, 2.0), 0),
            Undecided,
            "turning too slowly"
        );
        for k in 0..3 {
            assert_eq!(r.push(&stride(4.0 + k as f64, 1.4, 8.0), 0), Undecided);
        }
        assert_eq!(
            r.push(&stride(20.0, 1.4, 8.0), 0),
            Undecided,
            "after a long stop"
        );
        for k in 0..3 {
            assert_eq!(r.push(&stride(21.0 + k as f64, 1.4, 8.0), 0), Undecided);
        }
        assert_eq!(r.push(&stride(24.0, 1.4, 8.0), 1), Foot);
    }

    #[test]
    fn a_swing_through_two_strides_of_steps_is_no_foot() {
        let mut r = Recogniser::default();
        // A stance that ends a long swing of steps (a phone swinging in the hand, then still
        // for a moment in a pocket): the body, whatever comes after.
        assert_eq!(
            r.push(&long_stride(3.0, 19.8, 15.9, 4.0), BODY_STEPS_IN_SWING),
            Verdict::Body
        );
        // A long swing without steps (a foot sensor's wearer shuffling while seated, a stance
        // the test missed) or with fewer than two strides' steps decides nothing.
        let mut r = Recogniser::default();
        assert_eq!(
            r.push(&long_stride(3.0, 19.8, 0.4, 4.0), 0),
            Verdict::Undecided
        );
        assert_eq!(
            r.push(&long_stride(23.0, 1.5, 0.4, 4.0), BODY_STEPS_IN_SWING - 1),
            Verdict::Undecided
        );
        for k in 0..3 {
            assert_eq!(
                r.push(&stride(25.0 + k as f64, 1.4, 8.0), 0),
                Verdict::Undecided
            );
        }
        assert_eq!(r.push(&stride(28.0, 1.4, 8.0), 2), Verdict::Foot);
    }
}
