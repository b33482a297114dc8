//! The first and the last steps of a walk: a count split into the walk's start, its
//! middle and its end, against true steps one by one (the Oxford contacts, the simulator's
//! footfalls), so that a step lost at the start and a phantom at the end do not cancel.
//!
//! The engine's step times lag the truth's (it releases a step at the acceleration's peak, a
//! contact sensor at the heel): the lag is the median distance from a counted step to the
//! nearest true one in the middle of the walk, and counted times are moved back by it before
//! they are split. The start is everything up to `window_s` after the first true step, the end
//! everything from `window_s` before the last one; each boundary lies halfway between two true
//! steps, as far from both as it can be.

/// A count split at both ends of a walk.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EndErrors {
    /// Steps counted minus true steps at the start.
    pub start: i64,
    /// At the end.
    pub end: i64,
    /// In between.
    pub middle: i64,
    /// The counted steps' lag behind the true ones, s.
    pub lag_s: f64,
}

/// Splits the count of `found` (step times, s, in order) against `truth` (true step times, s,
/// in order) into the first and the last `window_s` of the walk and its middle (empty when the
/// walk is shorter than both windows). `None` when there are fewer than two true steps.
pub fn end_errors(found: &[f64], truth: &[f64], window_s: f64) -> Option<EndErrors> {
    let (&t0, &t1) = (truth.first()?, truth.last()?);
    if truth.len() < 2 {
        return None;
    }
    let mut lags: Vec<f64> = found
        .iter()
        .filter(|&&t| t > t0 + window_s && t < t1 - window_s)
        .map(|&t| {
            let i = truth.partition_point(|&x| x <= t);
            let before = i.checked_sub(1).map_or(f64::INFINITY, |k| t - truth[k]);
            let after = truth.get(i).map_or(f64::INFINITY, |&x| t - x);
            if before.abs() < after.abs() {
                before
            } else {
                after
            }
        })
        .collect();
    crate::engine::sort::sort_by(&mut lags, f64::total_cmp);
    let lag_s = lags.get(lags.len() / 2).copied().unwrap_or(0.0);
    let below = |v: &[f64], shift: f64, b: f64| v.iter().filter(|&&t| t - shift < b).count() as i64;
    // Halfway between the true steps on either side of `t`.
    let between = |t: f64| {
        let i = truth.partition_point(|&x| x < t).clamp(1, truth.len() - 1);
        0.5 * (truth[i - 1] + truth[i])
    };
    // A walk shorter than both windows has no middle.
    let a = between(t0 + window_s);
    let b = between(t1 - window_s).max(a);
    let start = below(found, lag_s, a) - below(truth, 0.0, a);
    let end =
        (found.len() as i64 - below(found, lag_s, b)) - (truth.len() as i64 - below(truth, 0.0, b));
    let total = found.len() as i64 - truth.len() as i64;
    Some(EndErrors {
        start,
        end,
        middle: total - start - end,
        lag_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lost_first_step_and_a_phantom_last_one_do_not_cancel() {
        let truth: Vec<f64> = (0..40).map(|k| 0.5 * k as f64).collect();
        // Counted 0.1 s late, without the first step, with one more after the last.
        let found: Vec<f64> = (1..41).map(|k| 0.5 * k as f64 + 0.1).collect();
        let e = end_errors(&found, &truth, 4.0).unwrap();
        assert_eq!((e.start, e.end, e.middle), (-1, 1, 0));
        assert!((e.lag_s - 0.1).abs() < 1e-9);
        let e = end_errors(&truth, &truth, 4.0).unwrap();
        assert_eq!((e.start, e.end, e.middle), (0, 0, 0));
        assert_eq!(end_errors(&truth, &[1.0], 4.0), None);
    }
}
