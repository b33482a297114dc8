//! How far each turn of a walk shifts the track sideways (the heading in a turn): a
//! heading that lags or leads the path in a turn cuts or overshoots the corner, and the track
//! keeps the shift after the turn.
//!
//! Each found step is matched to the true step it ends (the first true step at or after its
//! time less `match_s`); its error is its heading against that true step's direction. A turn is
//! a run of found steps whose true step or the next one changes direction by more than
//! [`TURN_RAD`]; its shift is Σ length·sin(error − the walk's own error), from the turn's first
//! step to [`AFTER`] steps after its last, the walk's own error the median over the 9 steps
//! before the turn (so a walk's constant bias does not count).

/// The least change of the true direction from step to step that is a turn, rad.
pub const TURN_RAD: f64 = 0.01;

/// Steps after a turn over which its shift is summed: a heading averaged over strides settles.
pub const AFTER: usize = 6;

/// A found step: time, s; heading, rad from north; length, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    /// Time, s.
    pub t: f64,
    /// Heading, rad clockwise from north.
    pub heading_rad: f64,
    /// Length, m.
    pub length_m: f64,
}

impl Found {
    /// The steps of a track that have a heading.
    pub fn from_track(track: &[crate::engine::StepRecord]) -> Vec<Found> {
        track
            .iter()
            .filter_map(|s| {
                s.heading_rad.map(|h| Found {
                    t: s.t,
                    heading_rad: h,
                    length_m: s.length_m,
                })
            })
            .collect()
    }
}

/// The shift of each turn, m (signed: positive to the right of the path), and each found
/// step's heading error against the true step's direction, rad. `truth` holds the true
/// footfalls' times, s, and positions (east, north), m, in order. Turns within the walk's first
/// 12 found steps are left out (no 9 steps before them).
pub fn turn_shifts(
    found: &[Found],
    truth: &[(f64, f64, f64)],
    match_s: f64,
) -> (Vec<f64>, Vec<f64>) {
    let dir = |k: usize| libm::atan2(truth[k].1 - truth[k - 1].1, truth[k].2 - truth[k - 1].2);
    let wrap = |a: f64| libm::remainder(a, std::f64::consts::TAU);
    let turns_at =
        |k: usize| k >= 2 && k < truth.len() && wrap(dir(k) - dir(k - 1)).abs() > TURN_RAD;
    let steps: Vec<(f64, f64, bool)> = found
        .iter()
        .filter_map(|s| {
            let k = truth.partition_point(|x| x.0 < s.t - match_s);
            (k >= 1 && k < truth.len()).then(|| {
                (
                    wrap(s.heading_rad - dir(k)),
                    s.length_m,
                    turns_at(k) || turns_at(k + 1),
                )
            })
        })
        .collect();
    let mut shifts = Vec::new();
    let mut i = 0;
    while i < steps.len() {
        if !steps[i].2 {
            i += 1;
            continue;
        }
        let start = i;
        while i < steps.len() && steps[i].2 {
            i += 1;
        }
        if start < 12 {
            continue;
        }
        let mut before: Vec<f64> = steps[start - 10..start - 1].iter().map(|s| s.0).collect();
        crate::engine::sort::sort_by(&mut before, f64::total_cmp);
        let base = before[before.len() / 2];
        shifts.push(
            steps[start..(i + AFTER).min(steps.len())]
                .iter()
                .map(|s| libm::sin(s.0 - base) * s.1)
                .sum(),
        );
    }
    (shifts, steps.iter().map(|s| s.0).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 40 steps north, a right angle over 8 steps, 30 steps east; 0.7 m a step, 0.5 s apart.
    fn walk() -> Vec<(f64, f64, f64)> {
        let (mut e, mut n, mut h) = (0.0, 0.0, 0.0f64);
        let mut out = vec![(0.0, 0.0, 0.0)];
        for k in 1..=78 {
            if (41..=48).contains(&k) {
                h += std::f64::consts::FRAC_PI_2 / 8.0;
            }
            e += 0.7 * libm::sin(h);
            n += 0.7 * libm::cos(h);
            out.push((0.5 * k as f64, e, n));
        }
        out
    }

    #[test]
    fn a_heading_a_step_late_cuts_the_corner_by_a_step_times_the_angle() {
        let truth = walk();
        let heading = |k: usize| {
            let (a, b) = (truth[k - 1], truth[k]);
            libm::atan2(b.1 - a.1, b.2 - a.2)
        };
        let found = |late: usize| -> Vec<Found> {
            (2..truth.len())
                .map(|k| Found {
                    t: truth[k].0,
                    heading_rad: heading(k - late) + 0.1,
                    length_m: 0.7,
                })
                .collect()
        };
        let (on_time, errors) = turn_shifts(&found(0), &truth, 0.1);
        assert_eq!(on_time.len(), 1);
        assert!(on_time[0].abs() < 1e-9, "{on_time:?}");
        assert!(errors.iter().all(|e| (e - 0.1).abs() < 1e-9));
        let (late, _) = turn_shifts(&found(1), &truth, 0.1);
        // Cut to the left (negative) by about 0.7 m × π/2.
        assert!(
            (late[0] + 0.7 * std::f64::consts::FRAC_PI_2).abs() < 0.1,
            "{late:?}"
        );
    }
}
