//! The track's heading change across each true turn, against the turn's angle.
//!
//! A true turn runs from `t_start` (the walker leaves the straight before it) to `t_end` (on
//! the straight after it). The track's heading before it is the circular mean of the headings
//! of the steps counted in the [`WINDOW_S`] before `t_start`; after it, of those counted from
//! [`SETTLE_S`] after `t_end` to [`WINDOW_S`] later. A step's heading covers the stride that
//! ends at its time, so waiting [`SETTLE_S`] (a stride) keeps the turn itself out of the "after"
//! steps. The change is counter-clockwise positive, as the truth gives the angle; the error is
//! the difference wrapped to ±180°. A turn without a step with a heading in either window is
//! not scored.

use crate::engine::math::wrap_pi;
use crate::engine::pipeline::StepRecord;
use crate::io::import::TrueTurn;
use serde::{Deserialize, Serialize};

/// Span of steps averaged on each side of a turn, s.
pub const WINDOW_S: f64 = 2.0;

/// Wait after a turn's end before the steps count as the straight after it, s.
pub const SETTLE_S: f64 = 1.0;

/// One log's turns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TurnResult {
    /// True turns in the log.
    pub turns: u64,
    /// Each scored turn: (true angle, the track's change, the error), degrees,
    /// counter-clockwise positive.
    pub scored: Vec<[f64; 3]>,
    /// Median absolute error over the scored turns, degrees.
    pub median_error_deg: Option<f64>,
}

/// Scores the track's heading change across each turn; `None` without turns.
pub fn score_turns(track: &[StepRecord], turns: &[TrueTurn]) -> Option<TurnResult> {
    if turns.is_empty() {
        return None;
    }
    let mean_heading = |t0: f64, t1: f64| {
        let (mut s, mut c, mut n) = (0.0, 0.0, 0);
        for h in track
            .iter()
            .filter(|st| st.t >= t0 && st.t <= t1)
            .filter_map(|st| st.heading_rad)
        {
            let (sh, ch) = libm::sincos(h);
            s += sh;
            c += ch;
            n += 1;
        }
        (n > 0 && s * s + c * c > 1e-18).then(|| libm::atan2(s, c))
    };
    let scored: Vec<[f64; 3]> = turns
        .iter()
        .filter_map(|turn| {
            let before = mean_heading(turn.t_start - WINDOW_S, turn.t_start)?;
            let after = mean_heading(turn.t_end + SETTLE_S, turn.t_end + SETTLE_S + WINDOW_S)?;
            // Headings are clockwise from north; the truth's angles counter-clockwise.
            let change = -wrap_pi(after - before).to_degrees();
            let error = wrap_pi((change - turn.angle_deg).to_radians()).to_degrees();
            Some([turn.angle_deg, change, error])
        })
        .collect();
    let abs: Vec<f64> = scored.iter().map(|s| s[2].abs()).collect();
    Some(TurnResult {
        turns: turns.len() as u64,
        median_error_deg: (!abs.is_empty()).then(|| super::percentile(&abs, 50.0)),
        scored,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::tests::step;

    /// Steps every 0.5 s heading north, then `turn_deg` counter-clockwise from t = 10 s.
    fn walk(turn_deg: f64, lag_s: f64) -> Vec<StepRecord> {
        (1..40)
            .map(|k| {
                let t = 0.5 * k as f64;
                let mut s = step(t, 0.0, 0.0);
                let h = if t > 10.0 + lag_s {
                    -turn_deg.to_radians()
                } else {
                    0.0
                };
                s.heading_rad = Some(h);
                s
            })
            .collect()
    }

    #[test]
    fn a_right_and_a_left_turn_score_their_own_errors() {
        let turns = [TrueTurn {
            t_start: 9.0,
            t_end: 11.0,
            angle_deg: 90.0,
        }];
        let r = score_turns(&walk(90.0, 0.0), &turns).unwrap();
        assert_eq!(r.turns, 1);
        assert!(r.median_error_deg.unwrap() < 1e-9, "{r:?}");
        // A right turn of 80° scored against a left one of 90°: 170° off.
        let r = score_turns(&walk(-80.0, 0.0), &turns).unwrap();
        assert!((r.scored[0][1] + 80.0).abs() < 1e-9, "{r:?}");
        assert!((r.median_error_deg.unwrap() - 170.0).abs() < 1e-9, "{r:?}");
        // A half turn measured as −175° is 5° off, not 355°.
        let half = [TrueTurn {
            t_start: 9.0,
            t_end: 11.0,
            angle_deg: 180.0,
        }];
        let r = score_turns(&walk(-175.0, 0.0), &half).unwrap();
        assert!((r.median_error_deg.unwrap() - 5.0).abs() < 1e-9, "{r:?}");
    }

    #[test]
    fn a_turn_without_steps_on_one_side_is_not_scored() {
        let turns = [TrueTurn {
            t_start: 30.0,
            t_end: 31.0,
            angle_deg: 90.0,
        }];
        let r = score_turns(&walk(90.0, 0.0), &turns).unwrap();
        assert_eq!((r.turns, r.scored.len()), (1, 0));
        assert_eq!(r.median_error_deg, None);
        assert!(score_turns(&walk(90.0, 0.0), &[]).is_none());
    }
}
