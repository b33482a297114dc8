//! Headings drawn without a line across the plot at the 0°/360° wrap: unwrapped (each value on
//! the whole turn nearest the one before it), with the line broken across gaps.
//! May import: nothing beyond `std`; never `web`, `live` or `eval`.

/// Steps further apart than this (s) end a bout: the heading line breaks there.
pub const BOUT_GAP_S: f64 = 3.0;

/// `deg` moved by whole turns to lie within 180° of `near`.
pub fn nearest_turn(deg: f64, near: f64) -> f64 {
    deg - 360.0 * ((deg - near) / 360.0).round()
}

/// Headings (t in s, degrees on any turn; NaN for none) in time order, unwrapped into the runs
/// of a line: within a run each heading lies on the turn nearest the one before it, so no
/// segment is longer than 180° and a turn through north is a turn, not a jump. A run ends at a
/// missing heading or where the next is more than `gap_s` later; the next run starts on the
/// turn nearest where the last one ended (the first in 0…360°), so that bouts of walking in one
/// direction lie at one height, not a whole turn apart, unless that start leaves −180…540°:
/// then it starts in 0…360° again, so that a long walk of many loops with stops between them
/// keeps an axis a few turns high, not tens.
pub fn unwrap_runs(
    points: impl IntoIterator<Item = (f64, f64)>,
    gap_s: f64,
) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    let mut end: Option<(f64, f64)> = None;
    for (t, h) in points {
        if !h.is_finite() || !t.is_finite() {
            if !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
            continue;
        }
        let v = match end {
            Some((last_t, last)) => {
                if t - last_t > gap_s && !run.is_empty() {
                    runs.push(std::mem::take(&mut run));
                }
                let v = nearest_turn(h, last);
                if run.is_empty() && !(-180.0..540.0).contains(&v) {
                    nearest_turn(h, 180.0)
                } else {
                    v
                }
            }
            None => h.rem_euclid(360.0),
        };
        run.push((t, v));
        end = Some((t, v));
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// The unwrapped heading line's value nearest time `t` (the runs of [`unwrap_runs`]).
pub fn line_at(runs: &[Vec<(f64, f64)>], t: f64) -> Option<f64> {
    let k = runs.partition_point(|r| r.last().is_some_and(|p| p.0 < t));
    let near = |r: &Vec<(f64, f64)>| {
        let i = r.partition_point(|p| p.0 < t);
        [i.checked_sub(1), (i < r.len()).then_some(i)]
            .into_iter()
            .flatten()
            .map(|i| r[i])
            .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
    };
    [k.checked_sub(1), (k < runs.len()).then_some(k)]
        .into_iter()
        .flatten()
        .filter_map(|k| near(&runs[k]))
        .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
        .map(|p| p.1)
}

/// [`line_at`] for times asked in increasing order, in constant time per call (amortised): the
/// device's heading asks it for every sample drawn.
pub struct LineCursor<'a> {
    points: Vec<&'a (f64, f64)>,
    k: usize,
}

impl<'a> LineCursor<'a> {
    /// A cursor over the runs of [`unwrap_runs`].
    pub fn new(runs: &'a [Vec<(f64, f64)>]) -> Self {
        LineCursor {
            points: runs.iter().flatten().collect(),
            k: 0,
        }
    }

    /// The line's value nearest time `t`, as [`line_at`]; `t` must not decrease between calls.
    pub fn at(&mut self, t: f64) -> Option<f64> {
        while self.k + 1 < self.points.len() && self.points[self.k + 1].0 <= t {
            self.k += 1;
        }
        let here = self.points.get(self.k)?;
        Some(match self.points.get(self.k + 1) {
            Some(next) if (next.0 - t).abs() < (here.0 - t).abs() => next.1,
            _ => here.1,
        })
    }
}

/// Grid lines of a heading axis from `y0` to `y1` (unwrapped degrees): every 45°, 90° or 180°,
/// whichever gives two to eight lines (whole turns beyond that: see [`grid_label`]).
pub fn grid(y0: f64, y1: f64) -> Vec<f64> {
    let step = [45.0, 90.0, 180.0, 360.0]
        .into_iter()
        .find(|s| (y1 - y0) / s <= 8.0)
        .unwrap_or(720.0);
    let first = (y0 / step).ceil() as i64;
    let last = (y1 / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// The label of grid line `g` of a heading axis from `y0` to `y1`: [`label`] while the lines
/// are less than a turn apart; on an axis of many turns (a walk up a staircase turns 180° at
/// every landing), where every line would read "0° N", the turns from north ("+3 turns").
pub fn grid_label(g: f64, y0: f64, y1: f64) -> String {
    let spaced = grid(y0, y1);
    if spaced.len() >= 2 && spaced[1] - spaced[0] >= 360.0 {
        let turns = (g / 360.0).round() as i64;
        match turns {
            0 => "0° N".to_string(),
            1 | -1 => format!("{turns:+} turn"),
            _ => format!("{turns:+} turns"),
        }
    } else {
        label(g)
    }
}

/// The label of an unwrapped heading: the heading itself in 0…360°, with its compass point on
/// a cardinal one (`450°` is `90° E`, `-45°` is `315°`: short enough for a phone's axis).
pub fn label(deg: f64) -> String {
    // `+ 0.0` turns the -0 of a negative whole turn into 0.
    let h = deg.round().rem_euclid(360.0) + 0.0;
    match ["N", "E", "S", "W"].get((h / 90.0) as usize) {
        Some(point) if h % 90.0 == 0.0 => format!("{h:.0}° {point}"),
        _ => format!("{h:.0}°"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heading_wiggling_about_north_is_one_line_without_jumps() {
        // Walking north for 5 minutes at two steps a second, wiggling ±8° about north: the
        // wrapped headings cross 0°/360° hundreds of times.
        let pts: Vec<(f64, f64)> = (0..600)
            .map(|i| {
                let t = i as f64 * 0.5;
                (t, (8.0 * libm::sin(t * 1.7)).rem_euclid(360.0))
            })
            .collect();
        let crossings = pts
            .windows(2)
            .filter(|w| (w[0].1 - w[1].1).abs() > 180.0)
            .count();
        assert!(crossings > 100, "{crossings}");
        let runs = unwrap_runs(pts.iter().copied(), BOUT_GAP_S);
        assert_eq!(runs.len(), 1);
        let longest = runs[0]
            .windows(2)
            .map(|w| (w[1].1 - w[0].1).abs())
            .fold(0.0, f64::max);
        assert!(longest < 20.0, "{longest}");
        // Every point is the heading it was, on some turn.
        for (p, q) in pts.iter().zip(&runs[0]) {
            assert!(((p.1 - q.1).rem_euclid(360.0) + 1e-9) % 360.0 < 1e-6);
        }
    }

    #[test]
    fn loops_unwrap_and_gaps_and_missing_headings_break_the_line() {
        // Three loops turning right (a whole turn each), a 10 s stop, then more of the turn,
        // a missing heading.
        let mut pts: Vec<(f64, f64)> = (0..300)
            .map(|i| (i as f64 * 0.5, (i as f64 * 3.6).rem_euclid(360.0)))
            .collect();
        pts.extend((0..20).map(|i| (160.0 + i as f64 * 0.5, (10.0 * i as f64).rem_euclid(360.0))));
        pts.insert(310, (154.0, f64::NAN));
        let runs = unwrap_runs(pts, BOUT_GAP_S);
        assert_eq!(
            runs.len(),
            3,
            "{:?}",
            runs.iter().map(Vec::len).collect::<Vec<_>>()
        );
        // The loops climb: three whole turns in the first run.
        let first = &runs[0];
        assert!((first.last().unwrap().1 - first[0].1 - 299.0 * 3.6).abs() < 1e-6);
        // No segment of any run is longer than the largest true change between two points.
        for r in &runs {
            for w in r.windows(2) {
                assert!((w[1].1 - w[0].1).abs() <= 10.0 + 1e-9, "{w:?}");
            }
        }
        // Three turns up, the line starts again within 0…360° after the stop; after the missing
        // heading, on the turn nearest where it broke off.
        assert!((0.0..=360.0).contains(&runs[1][0].1), "{:?}", runs[1][0]);
        assert!((runs[2][0].1 - runs[1].last().unwrap().1).abs() <= 180.0);
        // A short stop in the middle of a walk north: the line goes on at the same height.
        let runs = unwrap_runs([(0.0, 350.0), (1.0, 355.0), (9.0, 5.0)], BOUT_GAP_S);
        assert_eq!(
            runs,
            vec![vec![(0.0, 350.0), (1.0, 355.0)], vec![(9.0, 365.0)]]
        );
    }

    #[test]
    fn the_line_value_nearest_a_time_the_grid_and_labels() {
        let runs = unwrap_runs([(0.0, 350.0), (1.0, 10.0), (10.0, 20.0)], BOUT_GAP_S);
        assert_eq!(
            runs,
            vec![vec![(0.0, 350.0), (1.0, 370.0)], vec![(10.0, 380.0)]]
        );
        assert_eq!(line_at(&runs, -5.0), Some(350.0));
        assert_eq!(line_at(&runs, 0.8), Some(370.0));
        assert_eq!(line_at(&runs, 6.0), Some(380.0));
        assert_eq!(line_at(&runs, 99.0), Some(380.0));
        assert_eq!(line_at(&[], 1.0), None);
        let mut cursor = LineCursor::new(&runs);
        for t in [-5.0, 0.0, 0.4, 0.8, 1.0, 6.0, 9.0, 99.0] {
            assert_eq!(cursor.at(t), line_at(&runs, t), "{t}");
        }
        assert_eq!(LineCursor::new(&[]).at(1.0), None);
        assert_eq!(nearest_turn(5.0, 350.0), 365.0);
        assert_eq!(nearest_turn(355.0, 0.0), -5.0);
        assert_eq!(grid(-30.0, 400.0), vec![0.0, 90.0, 180.0, 270.0, 360.0]);
        assert_eq!(grid(10.0, 100.0), vec![45.0, 90.0]);
        assert_eq!(label(450.0), "90° E");
        assert_eq!(label(-45.0), "315°");
        assert_eq!(label(-360.0), "0° N");
        assert_eq!(label(719.7), "0° N");
        // An axis of many turns labels the turns, not eight "0° N".
        let lines = grid(-100.0, 3000.0);
        let labels: Vec<String> = lines
            .iter()
            .map(|&g| grid_label(g, -100.0, 3000.0))
            .collect();
        assert_eq!(labels[..3], ["0° N", "+2 turns", "+4 turns"]);
        assert_eq!(grid_label(360.0, 0.0, 2000.0), "+1 turn");
        assert_eq!(grid_label(90.0, 0.0, 400.0), "90° E");
        assert_eq!(label(-540.0), "180° S");
    }
}
