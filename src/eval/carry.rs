//! The carrying mode against the truth's: for a recording whose data set says how the phone
//! was carried throughout (TyrEx's folder names, the pocket sets), the share of the steps the
//! engine gave that mode. Steps outside the truth's step window (the phone handled before and
//! after the walk) are not scored.

use super::LogResult;
use crate::engine::pipeline::StepRecord;
use crate::io::import::Truth;
use std::collections::BTreeMap;

/// [steps whose carrying mode is the truth's, steps scored]; `None` when the truth does not
/// say how the phone was carried.
pub fn score_carry(track: &[StepRecord], truth: &Truth) -> Option<[u64; 2]> {
    let mode = truth.carry?;
    let inside = |t: f64| truth.step_window.map_or(true, |(a, b)| t >= a && t <= b);
    let scored: Vec<&StepRecord> = track.iter().filter(|s| inside(s.t)).collect();
    let right = scored.iter().filter(|s| s.carry == Some(mode)).count();
    Some([right as u64, scored.len() as u64])
}

/// The share of the scored steps with the right mode per group (`other` without one) and over
/// `all` the logs, pooled over their steps; groups without a scored step are left out.
pub fn pool(logs: &[LogResult]) -> BTreeMap<String, f64> {
    let mut counts = BTreeMap::<String, [u64; 2]>::new();
    for l in logs {
        let Some([right, scored]) = l.carry_steps else {
            continue;
        };
        let group = l.group.clone().unwrap_or_else(|| "other".into());
        for g in [group, "all".into()] {
            let e = counts.entry(g).or_default();
            e[0] += right;
            e[1] += scored;
        }
    }
    counts
        .into_iter()
        .filter(|(_, [_, n])| *n > 0)
        .map(|(g, [r, n])| (g, r as f64 / n as f64))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::carry::CarryMode;
    use crate::eval::tests::step;

    fn carried(t: f64, mode: Option<CarryMode>) -> StepRecord {
        StepRecord {
            carry: mode,
            ..step(t, 0.0, 0.0)
        }
    }

    #[test]
    fn steps_are_scored_inside_the_window_against_the_mode() {
        let track = [
            carried(1.0, Some(CarryMode::Hand)),
            carried(2.0, Some(CarryMode::Pocket)),
            carried(3.0, None),
            carried(4.0, Some(CarryMode::Pocket)),
            carried(9.0, Some(CarryMode::Hand)),
        ];
        let mut truth = Truth::default();
        assert_eq!(score_carry(&track, &truth), None);
        truth.carry = Some(CarryMode::Pocket);
        assert_eq!(score_carry(&track, &truth), Some([2, 5]));
        truth.step_window = Some((1.5, 5.0));
        assert_eq!(score_carry(&track, &truth), Some([2, 3]));
    }

    #[test]
    fn groups_pool_their_steps_and_all_pools_every_log() {
        let log = |group: &str, steps: Option<[u64; 2]>| {
            let mut l = LogResult::failed("x", "tyrex", String::new());
            l.group = Some(group.into());
            l.carry_steps = steps;
            l
        };
        let logs = [
            log("Swinging", Some([9, 10])),
            log("Swinging", Some([1, 30])),
            log("Texting", Some([0, 0])),
            log("Phoning", None),
        ];
        let p = pool(&logs);
        assert_eq!(p.len(), 2, "{p:?}");
        assert_eq!(p["Swinging"], 0.25);
        assert_eq!(p["all"], 0.25);
    }
}
