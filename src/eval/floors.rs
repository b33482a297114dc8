//! Floors and heights scored against the truth's landmarks, where the truth has them.
//! May import: `engine`, `io`.
//!
//! # Metrics
//! - **Floor**: at each landmark with a floor, the track's floor is the [`StepRecord::floor`] of
//!   the last step at or before the landmark's time (0 before the first step). Both floors are
//!   taken relative to the first landmark with a floor (the engine counts floors from where the
//!   walk started; the truth names the building's floors). A landmark is right when the two
//!   relative floors are equal. The first landmark is the reference and is not counted (it is
//!   right by construction): `landmarks` counts the ones after it.
//! - **Height**: only where the truth gives heights ([`Waypoint::height_m`]; no imported format
//!   carries one today: GetSensorData's `POSI` has a floor, not a height), the absolute
//!   difference between the track's [`StepRecord::up_m`] and the true height, both relative to
//!   the first such landmark, at every later one.

use super::percentile;
use crate::engine::pipeline::StepRecord;
use crate::io::import::Waypoint;
use serde::{Deserialize, Serialize};

/// One log's floor figures. Field names are stable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorResult {
    /// Landmarks with a floor after the first one (the reference).
    pub landmarks: u64,
    /// Of them, those where the track's relative floor is the truth's.
    pub right: u64,
    /// `right / landmarks` (0 when there is none).
    pub share: f64,
    /// Height error at the landmarks after the first that have a true height, m: mean, 75th
    /// percentile, largest. `None` (`null`) when the truth has no heights.
    #[serde(default)]
    pub height_error_m: Option<super::ErrorSummary>,
    /// Every height error, m (for pooling; not serialised).
    #[serde(skip)]
    pub height_errors_m: Vec<f64>,
}

/// The step at or before `t` (`None` before the first step). The track is in time order.
fn step_at(track: &[StepRecord], t: f64) -> Option<&StepRecord> {
    let i = track.partition_point(|s| s.t <= t);
    i.checked_sub(1).map(|k| &track[k])
}

/// The track's floor at `t`: the floor of the step at or before it, 0 before the first step.
pub fn floor_at(track: &[StepRecord], t: f64) -> i32 {
    step_at(track, t).map_or(0, |s| s.floor)
}

/// The track's height at `t`, m: the `up_m` of the step at or before it, 0 before the first.
pub fn up_at(track: &[StepRecord], t: f64) -> f64 {
    step_at(track, t).map_or(0.0, |s| s.up_m)
}

/// Scores the track's floors (and heights, where the truth has them) at the landmarks (see the
/// module documentation). `None` when fewer than two landmarks have a floor.
pub fn score_floors(track: &[StepRecord], wps: &[Waypoint]) -> Option<FloorResult> {
    let floors: Vec<(f64, i32)> = wps
        .iter()
        .filter_map(|w| w.floor.map(|f| (w.t, f)))
        .collect();
    let (&(t0, f0), rest) = floors.split_first()?;
    if rest.is_empty() {
        return None;
    }
    let e0 = floor_at(track, t0);
    let right = rest
        .iter()
        .filter(|&&(t, f)| {
            i64::from(floor_at(track, t)) - i64::from(e0) == i64::from(f) - i64::from(f0)
        })
        .count() as u64;
    let landmarks = rest.len() as u64;
    let heights: Vec<(f64, f64)> = wps
        .iter()
        .filter_map(|w| w.height_m.map(|h| (w.t, h)))
        .collect();
    let height_errors_m: Vec<f64> = match heights.split_first() {
        Some((&(ht0, h0), later)) => {
            let u0 = up_at(track, ht0);
            later
                .iter()
                .map(|&(t, h)| ((up_at(track, t) - u0) - (h - h0)).abs())
                .collect()
        }
        None => Vec::new(),
    };
    Some(FloorResult {
        landmarks,
        right,
        share: right as f64 / landmarks as f64,
        height_error_m: super::ErrorSummary::of(&height_errors_m),
        height_errors_m,
    })
}

/// The floor figures pooled over logs: (logs with floors, landmarks, right, share over all
/// landmarks, 75th percentile of all height errors).
pub fn pool(results: &[&FloorResult]) -> (u64, u64, u64, Option<f64>, Option<f64>) {
    let landmarks: u64 = results.iter().map(|r| r.landmarks).sum();
    let right: u64 = results.iter().map(|r| r.right).sum();
    let heights: Vec<f64> = results
        .iter()
        .flat_map(|r| r.height_errors_m.iter().copied())
        .collect();
    (
        results.len() as u64,
        landmarks,
        right,
        (landmarks > 0).then(|| right as f64 / landmarks as f64),
        (!heights.is_empty()).then(|| percentile(&heights, 75.0)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(t: f64, floor: i32, up_m: f64) -> StepRecord {
        StepRecord {
            floor,
            up_m,
            ..super::super::tests::step(t, 0.0, 0.0)
        }
    }

    fn landmark(t: f64, floor: Option<i32>, height_m: Option<f64>) -> Waypoint {
        Waypoint {
            t,
            x_m: 0.0,
            y_m: 0.0,
            geo: None,
            floor,
            height_m,
        }
    }

    #[test]
    fn relative_floors_right_wrong_and_before_the_first_step() {
        // The track: steps from t = 10 s; down one floor at 20 s, down another at 30 s, back up
        // one at 40 s.
        let track: Vec<StepRecord> = (10..=50)
            .map(|t| {
                let f = match t {
                    ..=19 => 0,
                    20..=29 => -1,
                    30..=39 => -2,
                    _ => -1,
                };
                step(t as f64, f, 3.0 * f as f64)
            })
            .collect();
        assert_eq!(floor_at(&track, 5.0), 0, "before the first step");
        assert_eq!(floor_at(&track, 20.0), -1, "at a step");
        assert_eq!(floor_at(&track, 29.9), -1, "between steps");
        // The truth counts floors from 2 (the building's), the walk starts before the first
        // step (floor 0 there).
        let wps = [
            landmark(5.0, Some(2), None),  // reference
            landmark(15.0, Some(2), None), // right: 0 = 0
            landmark(25.0, Some(1), None), // right: −1 = −1
            landmark(35.0, Some(1), None), // wrong: track −2, truth −1
            landmark(38.0, None, None),    // no floor: not scored
            landmark(45.0, Some(1), None), // right
            landmark(60.0, Some(3), None), // wrong: track −1 (last step), truth +1
        ];
        let r = score_floors(&track, &wps).unwrap();
        assert_eq!((r.landmarks, r.right), (5, 3));
        assert!((r.share - 0.6).abs() < 1e-12);
        assert_eq!(r.height_error_m, None, "no true heights");
        // Everything off by one floor from the second landmark: all wrong.
        let shifted: Vec<Waypoint> = wps
            .iter()
            .enumerate()
            .map(|(i, w)| landmark(w.t, w.floor.map(|f| f + i32::from(i > 0)), None))
            .collect();
        let r = score_floors(&track, &shifted).unwrap();
        assert_eq!((r.landmarks, r.right), (5, 0));
    }

    #[test]
    fn heights_scored_only_where_the_truth_has_them() {
        let track: Vec<StepRecord> = (0..=20)
            .map(|t| step(t as f64, 0, 0.1 * t as f64))
            .collect();
        let wps = [
            landmark(0.0, Some(0), Some(300.0)),
            landmark(10.0, Some(0), Some(301.5)), // track +1.0: error 0.5
            landmark(20.0, Some(0), None),
        ];
        let r = score_floors(&track, &wps).unwrap();
        let h = r.height_error_m.unwrap();
        assert!(
            (h.max - 0.5).abs() < 1e-9 && (h.mean - 0.5).abs() < 1e-9,
            "{h:?}"
        );
        let (logs, landmarks, right, share, p75) = pool(&[&r, &r]);
        assert_eq!((logs, landmarks, right), (2, 4, 4));
        assert_eq!(share, Some(1.0));
        assert!((p75.unwrap() - 0.5).abs() < 1e-9);
    }

    #[test]
    fn no_floors_no_score() {
        let track = vec![step(1.0, 0, 0.0)];
        let without = [landmark(0.0, None, None), landmark(5.0, None, None)];
        assert_eq!(score_floors(&track, &without), None);
        let one = [landmark(0.0, Some(0), None), landmark(5.0, None, None)];
        assert_eq!(score_floors(&track, &one), None);
        assert_eq!(pool(&[]), (0, 0, 0, None, None));
    }
}
