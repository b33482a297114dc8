//! Where the IMU is worn, and recognising a foot-mounted log from its signal.
//! May import: the rest of `engine`.
//!
//! # Recognising a foot
//! A foot-mounted IMU shows what no phone in a pocket, a hand or a bag shows: every stride, a
//! stance in which the foot is still (|ω| under 1 rad/s and |f| within 1.5 m/s² of g for
//! T_min) between swings in which the foot turns at several rad/s (6–11 rad/s on the x-io
//! walks), and the strapdown integration between two stances gives a plausible stride. The
//! [`Recogniser`] takes the strides of the foot stage, run alongside the body pipeline while the
//! placement is undecided, and says "foot" after [`FOOT_STRIDES`] plausible strides in a row:
//! a swing of 0.2–1.2 s turning at [`MIN_SWING_RATE`] or more, a horizontal length of
//! 0.3–2.5 m, a stance of at most 3 s before it (a stop between walks restarts the count). A
//! log undecided after [`DECIDE_WITHIN_S`] of samples is a body log for good (the foot stage is
//! dropped). The real pocket and hand-held logs of `../shared/data` are never recognised as
//! feet (`tests/foot.rs`).
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
        (0.2..=1.2).contains(&swing)
            && s.peak_rate_rad_s >= MIN_SWING_RATE
            && (0.3..=2.5).contains(&s.length_m)
            && stance_ok
    }

    /// Takes a stride; true once [`FOOT_STRIDES`] plausible strides came in a row.
    pub fn push(&mut self, s: &Stride) -> bool {
        if Self::plausible(s, self.last_end) {
            self.run += 1;
        } else {
            self.run = 0;
        }
        self.last_end = Some(s.t_end);
        self.run >= FOOT_STRIDES
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stride(t: f64, len: f64, rate: f64) -> Stride {
        Stride {
            t_start: t,
            t_end: t + 0.6,
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
        let mut r = Recogniser::default();
        assert!(!r.push(&stride(0.0, 1.4, 8.0)));
        assert!(!r.push(&stride(1.0, 1.4, 8.0)));
        assert!(
            !r.push(&stride(2.0, 0.1, 8.0)),
            "too short: the count restarts"
        );
        assert!(!r.push(&stride(3.0, 1.4, 2.0)), "turning too slowly");
        for k in 0..3 {
            assert!(!r.push(&stride(4.0 + k as f64, 1.4, 8.0)));
        }
        assert!(!r.push(&stride(20.0, 1.4, 8.0)), "after a long stop");
        for k in 0..3 {
            assert!(!r.push(&stride(21.0 + k as f64, 1.4, 8.0)));
        }
        assert!(r.push(&stride(24.0, 1.4, 8.0)));
    }
}
