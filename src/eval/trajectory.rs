//! A track against a dense trajectory truth (motion capture): the heading of each step, the
//! distance walked and the position, each free of what the truth's frame cannot tell.
//!
//! The truth follows the device. In a trouser pocket it rides on the thigh, which swings
//! forward and back by tens of centimetres within each stride, so the truth is first smoothed
//! by a centred moving average over [`SMOOTH_S`] (a stride or two): what remains is the walker's
//! path. The truth's x and y are taken as a right-handed horizontal frame (x to the right of y,
//! as east is to north), whose direction is unknown: nothing is compared in absolute terms.
//!
//! - **Heading.** Each step that has a heading is compared with the direction the smoothed
//!   truth moved over a stride centred on the step's middle, halfway between its time and the
//!   step's before it: the step's heading is the direction that carries the track from the
//!   step before to this one. The stride is the span from the step two before to this step
//!   (when that is at most [`STRIDE_MAX_S`]; else [`STRIDE_MAX_S`]` / 2`), moved later by a
//!   quarter of its length, so that its middle, the step before's time, becomes the step's
//!   middle (steps of a stride take about as long). Unmoved, the stride's direction lags the
//!   step's by half a step: on a walk that turns, each step is charged half of the turn it
//!   makes, whatever its heading (`a_perfect_track_of_figure_eights_scores_nearly_zero`). A
//!   stride over which the truth moved less than [`MIN_MOVE_M`] has no
//!   direction and is left out. The differences are then freed of one constant, the offset
//!   between the truth's frame and north: the circular median of the differences, taken over
//!   those within 90° of their axial mean so that steps turned by half a turn (they happen)
//!   neither pull it nor escape being counted as 180° off (`robust_offset`). The walk's figure
//!   is the median absolute error that remains.
//! - **Distance ratio**: the track's length (the steps with a heading, which move the track)
//!   over the smoothed truth's path length over the same span, from the start of the first
//!   step (one step period before its time) to the last step.
//! - **Position**: the track pinned on the smoothed truth at the first step's time (the first
//!   that the truth covers) and turned
//!   by the one rotation (about that point) that best fits the truth at every step's time, in
//!   the least-squares sense (2-D Procrustes, no scale); the error at each step's time. The
//!   walk's figure is its 75th percentile.
//!
//! A hole in the truth (the cameras lost the device) longer than [`HOLE_S`] leaves its times
//! out; a shorter one is bridged linearly.

use crate::engine::math::wrap_pi;
use crate::engine::pipeline::{position_at, StepRecord};
use crate::io::import::TruePosition;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// Span of the centred moving average applied to the truth, s.
pub const SMOOTH_S: f64 = 1.0;

/// Longest hole in the truth bridged by a straight line, s.
pub const HOLE_S: f64 = 1.0;

/// Longest stride over which a step's heading is compared, s (a slow walk's stride is 1.4 s).
pub const STRIDE_MAX_S: f64 = 2.0;

/// The least the truth must move over a stride for its direction to count, m.
pub const MIN_MOVE_M: f64 = 0.2;

/// One walk's figures against its trajectory truth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryResult {
    /// Whether the walk has a track: a step with a heading that moved it.
    pub has_track: bool,
    /// Steps whose heading was compared.
    pub headings_scored: u64,
    /// Median absolute heading error after the walk's one offset, degrees.
    pub heading_error_deg: Option<f64>,
    /// Its 75th percentile, degrees.
    pub heading_error_p75_deg: Option<f64>,
    /// The offset removed (the truth frame's direction against the track's north), degrees.
    pub heading_offset_deg: Option<f64>,
    /// The track's length, m.
    pub track_distance_m: f64,
    /// The smoothed truth's path length over the same span, m.
    pub truth_distance_m: f64,
    /// Track length over truth length.
    pub distance_ratio: Option<f64>,
    /// 75th percentile of the position error after pinning the start and one rotation, m.
    pub position_p75_m: Option<f64>,
}

/// The trajectory figures of a group of logs: medians over its walks that have a track.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrajectoryGroup {
    /// Logs with a trajectory truth.
    pub logs: u64,
    /// Of those, the walks without a track (no step with a heading).
    pub without_track: u64,
    /// Median of the walks' median heading errors, degrees.
    pub heading_error_deg: Option<f64>,
    /// Median of the walks' distance ratios.
    pub distance_ratio: Option<f64>,
    /// Median of the walks' position p75, m.
    pub position_p75_m: Option<f64>,
}

impl TrajectoryGroup {
    /// The figures of the trajectory results of a group of logs.
    pub fn of(results: &[&TrajectoryResult]) -> TrajectoryGroup {
        let with: Vec<&&TrajectoryResult> = results.iter().filter(|r| r.has_track).collect();
        let median = |get: fn(&TrajectoryResult) -> Option<f64>| {
            let v: Vec<f64> = with.iter().filter_map(|r| get(r)).collect();
            (!v.is_empty()).then(|| super::percentile(&v, 50.0))
        };
        TrajectoryGroup {
            logs: results.len() as u64,
            without_track: (results.len() - with.len()) as u64,
            heading_error_deg: median(|r| r.heading_error_deg),
            distance_ratio: median(|r| r.distance_ratio),
            position_p75_m: median(|r| r.position_p75_m),
        }
    }
}

/// The smoothed truth: (t, x, y) in time order.
struct Smoothed(Vec<(f64, f64, f64)>);

impl Smoothed {
    /// The centred moving average of `truth` over [`SMOOTH_S`] (the samples present within
    /// half of it on either side).
    fn of(truth: &[TruePosition]) -> Smoothed {
        let half = 0.5 * SMOOTH_S;
        let (mut lo, mut hi) = (0, 0);
        let (mut sx, mut sy) = (0.0, 0.0);
        let mut out = Vec::with_capacity(truth.len());
        for p in truth {
            while hi < truth.len() && truth[hi].t <= p.t + half {
                sx += truth[hi].x_m;
                sy += truth[hi].y_m;
                hi += 1;
            }
            while truth[lo].t < p.t - half {
                sx -= truth[lo].x_m;
                sy -= truth[lo].y_m;
                lo += 1;
            }
            let n = (hi - lo) as f64;
            out.push((p.t, sx / n, sy / n));
        }
        Smoothed(out)
    }

    /// The position at `t`: linear between the samples around it when they are at most
    /// [`HOLE_S`] apart; `None` outside the truth or in a longer hole.
    fn at(&self, t: f64) -> Option<(f64, f64)> {
        let s = &self.0;
        let i = s.partition_point(|p| p.0 <= t);
        let a = s.get(i.checked_sub(1)?)?;
        if a.0 == t {
            return Some((a.1, a.2));
        }
        let b = s.get(i)?;
        if b.0 - a.0 > HOLE_S {
            return None;
        }
        let w = (t - a.0) / (b.0 - a.0);
        Some((a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2)))
    }

    /// The path length between two times, m (holes bridged by straight lines).
    fn length(&self, t0: f64, t1: f64) -> f64 {
        let inside: Vec<(f64, f64)> = self
            .at(t0)
            .into_iter()
            .chain(
                self.0
                    .iter()
                    .filter(|p| p.0 > t0 && p.0 < t1)
                    .map(|p| (p.1, p.2)),
            )
            .chain(self.at(t1))
            .collect();
        inside
            .windows(2)
            .map(|w| libm::hypot(w[1].0 - w[0].0, w[1].1 - w[0].1))
            .sum()
    }
}

/// Scores a track against a trajectory truth; `None` when the truth is empty or the track has
/// no step.
pub fn score_trajectory(track: &[StepRecord], truth: &[TruePosition]) -> Option<TrajectoryResult> {
    let (first, last) = (track.first()?, track.last()?);
    if truth.is_empty() {
        return None;
    }
    let truth = Smoothed::of(truth);
    let moved: Vec<&StepRecord> = track.iter().filter(|s| s.heading_rad.is_some()).collect();
    let track_distance_m: f64 = moved.iter().map(|s| s.length_m).sum();
    let start = first.t - 1.0 / first.freq_hz.max(0.1);
    let truth_distance_m = truth.length(start, last.t);
    let (errors, offset) = heading_errors(track, &truth);
    let mut result = TrajectoryResult {
        has_track: !moved.is_empty(),
        headings_scored: errors.len() as u64,
        heading_error_deg: None,
        heading_error_p75_deg: None,
        heading_offset_deg: offset.map(f64::to_degrees),
        track_distance_m,
        truth_distance_m,
        distance_ratio: (truth_distance_m > 0.0).then(|| track_distance_m / truth_distance_m),
        position_p75_m: position_p75(track, &truth),
    };
    if !errors.is_empty() {
        let deg: Vec<f64> = errors.iter().map(|e| e.to_degrees()).collect();
        result.heading_error_deg = Some(super::percentile(&deg, 50.0));
        result.heading_error_p75_deg = Some(super::percentile(&deg, 75.0));
    }
    Some(result)
}

/// Each scored step's absolute heading error after the walk's offset, rad, and the offset.
fn heading_errors(track: &[StepRecord], truth: &Smoothed) -> (Vec<f64>, Option<f64>) {
    let mut diffs = Vec::new();
    for (k, s) in track.iter().enumerate() {
        let Some(h) = s.heading_rad else { continue };
        let from = k
            .checked_sub(2)
            .map(|j| track[j].t)
            .filter(|&t0| s.t - t0 <= STRIDE_MAX_S)
            .unwrap_or(s.t - 0.5 * STRIDE_MAX_S);
        // A quarter of the stride later: its middle on the step's middle.
        let later = 0.25 * (s.t - from);
        let (Some(a), Some(b)) = (truth.at(from + later), truth.at(s.t + later)) else {
            continue;
        };
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        if libm::hypot(dx, dy) < MIN_MOVE_M {
            continue;
        }
        diffs.push(wrap_pi(h - libm::atan2(dx, dy)));
    }
    let Some(offset) = robust_offset(&diffs) else {
        return (Vec::new(), None);
    };
    let errors = diffs.iter().map(|d| wrap_pi(d - offset).abs()).collect();
    (errors, Some(offset))
}

/// The walk's offset: the circular median (the angle that minimises the sum of the absolute
/// wrapped differences, one of them) of the differences within 90° of their axial mean. The
/// axial mean (half the direction of Σ e^{2iθ}, on the side with more differences) ignores
/// steps turned by half a turn, which would otherwise pull a median either way: each of them
/// costs less the further the offset moves from the others. `None` for no difference.
fn robust_offset(d: &[f64]) -> Option<f64> {
    let (mut s, mut c) = (0.0, 0.0);
    for x in d {
        let (sx, cx) = libm::sincos(2.0 * x);
        s += sx;
        c += cx;
    }
    let axis = 0.5 * libm::atan2(s, c);
    let near = |a: f64| d.iter().filter(move |x| wrap_pi(*x - a).abs() < FRAC_PI_2);
    let side = if near(axis).count() >= near(axis + PI).count() {
        axis
    } else {
        axis + PI
    };
    let inliers: Vec<f64> = near(side).copied().collect();
    let cost = |c: f64| inliers.iter().map(|x| wrap_pi(x - c).abs()).sum::<f64>();
    inliers
        .iter()
        .map(|&c| (cost(c), c))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map(|(_, c)| c)
}

/// The track pinned on the truth: the first step the truth covers (its time, the track's
/// position and the truth's there), the (track, truth) displacements from there at each step's
/// time, and the least-squares rotation (sin, cos) of the track onto the truth.
struct Pinned {
    p0: (f64, f64),
    origin: (f64, f64),
    pairs: Vec<((f64, f64), (f64, f64))>,
    rotation: (f64, f64),
}

impl Pinned {
    fn of(track: &[StepRecord], truth: &Smoothed) -> Option<Pinned> {
        let (t0, origin) = track.iter().find_map(|s| Some((s.t, truth.at(s.t)?)))?;
        let p0 = position_at(track, t0);
        let pairs: Vec<((f64, f64), (f64, f64))> = track
            .iter()
            .filter_map(|s| {
                let r = truth.at(s.t)?;
                Some((
                    (s.east_m - p0.0, s.north_m - p0.1),
                    (r.0 - origin.0, r.1 - origin.1),
                ))
            })
            .collect();
        let (mut dot, mut cross) = (0.0, 0.0);
        for ((ex, ey), (rx, ry)) in &pairs {
            dot += ex * rx + ey * ry;
            cross += ex * ry - ey * rx;
        }
        Some(Pinned {
            p0,
            origin,
            pairs,
            rotation: libm::sincos(libm::atan2(cross, dot)),
        })
    }
}

/// The 75th percentile of the position error at the steps' times, the track pinned on the
/// truth at the first step and turned by the best rotation.
fn position_p75(track: &[StepRecord], truth: &Smoothed) -> Option<f64> {
    let pinned = Pinned::of(track, truth)?;
    let (s, c) = pinned.rotation;
    let errors: Vec<f64> = pinned
        .pairs
        .iter()
        .map(|((ex, ey), (rx, ry))| libm::hypot(c * ex - s * ey - rx, s * ex + c * ey - ry))
        .collect();
    (!errors.is_empty()).then(|| super::percentile(&errors, 75.0))
}

/// The smoothed truth drawn in the track's frame, placed as [`score_trajectory`] compares them
/// (the rotation undone about the track's position at the first step the truth covers), one
/// point every `every_s` seconds over the track's span; empty when they cannot be placed.
pub fn trajectory_in_track_frame(
    track: &[StepRecord],
    truth: &[TruePosition],
    every_s: f64,
) -> Vec<(f64, f64)> {
    let (Some(first), Some(last)) = (track.first(), track.last()) else {
        return Vec::new();
    };
    let smoothed = Smoothed::of(truth);
    let Some(pinned) = Pinned::of(track, &smoothed) else {
        return Vec::new();
    };
    let (s, c) = pinned.rotation;
    let mut out = Vec::new();
    let mut t = first.t - 1.0 / first.freq_hz.max(0.1);
    while t <= last.t && every_s > 0.0 {
        if let Some(r) = smoothed.at(t) {
            let (rx, ry) = (r.0 - pinned.origin.0, r.1 - pinned.origin.1);
            out.push((pinned.p0.0 + c * rx + s * ry, pinned.p0.1 - s * rx + c * ry));
        }
        t += every_s;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::tests::step;

    /// A walker standing 2 s, going three times round a 4 × 3 m rectangle at 1.2 m/s and
    /// standing 2 s, sampled at 60 Hz, with a thigh's forward-back swing of ±0.15 m at the
    /// stride frequency (0.9 Hz) along the walking direction; the frame turned by `yaw`
    /// (counter-clockwise) from the track's.
    fn rectangle(yaw: f64) -> (Vec<TruePosition>, Vec<(f64, f64, f64)>) {
        let mut corners = vec![(0.0, 0.0), (0.0, 0.0)];
        for _ in 0..3 {
            corners.extend([(4.0, 0.0), (4.0, 3.0), (0.0, 3.0), (0.0, 0.0)]);
        }
        corners.push((0.0, 0.0));
        let (sy, cy) = libm::sincos(yaw);
        let mut truth = Vec::new();
        let mut walk = Vec::new();
        let mut t = 0.0;
        for w in corners.windows(2) {
            let (dx, dy) = (w[1].0 - w[0].0, w[1].1 - w[0].1);
            let len = libm::hypot(dx, dy);
            let n = if len > 0.0 {
                (len / 1.2 * 60.0) as usize
            } else {
                120
            };
            for i in 0..n {
                let f = i as f64 / n as f64;
                let swing = if len > 0.0 {
                    0.15 * libm::sin(std::f64::consts::TAU * 0.9 * t) / len
                } else {
                    0.0
                };
                let x = w[0].0 + f * dx + swing * dx;
                let y = w[0].1 + f * dy + swing * dy;
                walk.push((t, w[0].0 + f * dx, w[0].1 + f * dy));
                truth.push(TruePosition {
                    t,
                    x_m: cy * x - sy * y,
                    y_m: sy * x + cy * y,
                    z_m: 0.9,
                });
                t += 1.0 / 60.0;
            }
        }
        (truth, walk)
    }

    /// Steps every 0.55 s along the true path, headings from its direction, `scale` × long.
    fn steps(walk: &[(f64, f64, f64)], scale: f64) -> Vec<StepRecord> {
        let at = |t: f64| {
            let i = walk.partition_point(|p| p.0 <= t).max(1) - 1;
            (walk[i].1, walk[i].2)
        };
        let mut out = Vec::new();
        let mut t = 2.55;
        let mut prev = at(2.0);
        let mut pos = (0.0, 0.0);
        while t < walk.last().unwrap().0 - 2.0 {
            let p = at(t);
            let (dx, dy) = (p.0 - prev.0, p.1 - prev.1);
            pos = (pos.0 + scale * dx, pos.1 + scale * dy);
            let mut s = step(t, pos.0, pos.1);
            s.heading_rad = Some(libm::atan2(dx, dy));
            s.length_m = scale * libm::hypot(dx, dy);
            s.freq_hz = 1.0 / 0.55;
            out.push(s);
            prev = p;
            t += 0.55;
        }
        out
    }

    #[test]
    fn a_true_track_in_a_turned_frame_scores_nearly_zero() {
        let (truth, walk) = rectangle(1.0);
        let track = steps(&walk, 1.0);
        let r = score_trajectory(&track, &truth).unwrap();
        assert!(r.has_track);
        assert!(r.headings_scored as usize > track.len() - 4);
        assert!(r.heading_error_deg.unwrap() < 2.0, "{r:?}");
        // Turning the frame counter-clockwise turns the truth's directions anticlockwise.
        assert!((r.heading_offset_deg.unwrap() - 57.3).abs() < 1.0, "{r:?}");
        // The smoothing cuts each corner by about 0.1 m: 12 corners of a 42 m walk.
        assert!((1.0..1.04).contains(&r.distance_ratio.unwrap()), "{r:?}");
        assert!(r.position_p75_m.unwrap() < 0.15, "{r:?}");
    }

    /// A walk of figure eights at 1 m/s, truth at 100 Hz: round a circle of 2 m radius to the
    /// left, then one to the right, and so on (0.5 rad/s either way). (truth, the path's
    /// samples).
    fn eights() -> (Vec<TruePosition>, Vec<(f64, f64, f64)>) {
        let (mut truth, mut walk) = (Vec::new(), Vec::new());
        let (mut x, mut y, mut heading) = (0.0, 0.0, 0.0);
        let lap = 2.0 * PI / 0.5;
        for i in 0..6000 {
            let t = i as f64 * 0.01;
            truth.push(TruePosition {
                t,
                x_m: x,
                y_m: y,
                z_m: 0.0,
            });
            walk.push((t, x, y));
            let left = (t / lap) as u64 % 2 == 0;
            heading += if left { -0.005 } else { 0.005 };
            let (s, c) = libm::sincos(heading);
            x += 0.01 * s;
            y += 0.01 * c;
        }
        (truth, walk)
    }

    #[test]
    fn a_perfect_track_of_figure_eights_scores_nearly_zero() {
        // Each step's heading is the direction from the step before's position to its own, as
        // dead reckoning uses it: 15.8° of turn per 0.55 s step, left and right in turn. Scored
        // over the stride before the step, each would be charged half of that, 7.9°, one way
        // on the left circles and the other on the right ones, which no offset removes: the
        // offset takes the left circles' (there are more), and the right circles' steps are
        // charged 15.8° (a p75 of 14.1°).
        let (truth, walk) = eights();
        let track = steps(&walk, 1.0);
        let r = score_trajectory(&track, &truth).unwrap();
        assert!(r.headings_scored as usize > track.len() - 4, "{r:?}");
        assert!(r.heading_error_deg.unwrap() < 1.0, "{r:?}");
        assert!(r.heading_error_p75_deg.unwrap() < 1.0, "{r:?}");
        assert!(r.position_p75_m.unwrap() < 0.1, "{r:?}");
    }

    #[test]
    fn a_long_track_and_flipped_steps_show_and_do_not_move_the_offset() {
        let (truth, walk) = rectangle(0.3);
        let clean = score_trajectory(&steps(&walk, 1.1), &truth).unwrap();
        let mut track = steps(&walk, 1.1);
        // Every fifth step turned by half a turn.
        for s in track.iter_mut().step_by(5) {
            s.heading_rad = s.heading_rad.map(|h| h + PI);
        }
        let r = score_trajectory(&track, &truth).unwrap();
        let (a, b) = (
            clean.heading_offset_deg.unwrap(),
            r.heading_offset_deg.unwrap(),
        );
        assert!((a - b).abs() < 1.0, "{a} {b}");
        let (diffs, offset) = heading_errors(&track, &Smoothed::of(&truth));
        let flipped = diffs.iter().filter(|e| **e > FRAC_PI_2).count();
        assert_eq!(offset.map(f64::to_degrees), Some(b));
        assert!(
            flipped.abs_diff(track.len() / 5) <= 1,
            "{flipped} of {}",
            track.len()
        );
        assert!((1.1..1.15).contains(&r.distance_ratio.unwrap()), "{r:?}");
        // 10 % long round a 4 × 3 m loop: up to 0.5 m off at the far corner.
        assert!((0.2..0.6).contains(&r.position_p75_m.unwrap()), "{r:?}");
    }

    #[test]
    fn the_truth_is_drawn_on_the_track_it_scores() {
        let (truth, walk) = rectangle(1.0);
        let track = steps(&walk, 1.0);
        let drawn = trajectory_in_track_frame(&track, &truth, 0.5);
        assert!(drawn.len() > 60, "{}", drawn.len());
        // Each drawn point lies on the (unrotated) track's rectangle: within the smoothing's
        // corner cut of its sides.
        let off = |&(x, y): &(f64, f64)| {
            let side = |a: f64, lo: f64, hi: f64| {
                if a < lo {
                    lo - a
                } else if a > hi {
                    a - hi
                } else {
                    0.0
                }
            };
            let outside = side(x, 0.0, 4.0).max(side(y, 0.0, 3.0));
            let inside = x
                .abs()
                .min((x - 4.0).abs())
                .min(y.abs())
                .min((y - 3.0).abs());
            outside.max(inside)
        };
        let worst = drawn.iter().map(off).fold(0.0, f64::max);
        assert!(worst < 0.3, "{worst}");
        assert!(trajectory_in_track_frame(&[], &truth, 0.5).is_empty());
    }

    #[test]
    fn a_walk_without_headings_has_no_track_and_holes_are_left_out() {
        let (mut truth, walk) = rectangle(0.0);
        let mut track = steps(&walk, 1.0);
        // A 2 s hole in the middle of the truth.
        truth.retain(|p| !(15.0..17.0).contains(&p.t));
        let with_hole = score_trajectory(&track, &truth).unwrap();
        assert!(with_hole.heading_error_deg.unwrap() < 2.0);
        for s in &mut track {
            s.heading_rad = None;
        }
        let r = score_trajectory(&track, &truth).unwrap();
        assert!(!r.has_track);
        assert_eq!(r.track_distance_m, 0.0);
        assert_eq!(r.distance_ratio, Some(0.0));
        assert_eq!(r.headings_scored, 0);
        assert!(score_trajectory(&[], &truth).is_none());
        assert!(score_trajectory(&track, &[]).is_none());
    }
}
