//! Absolute errors against geodetic truth: GNSS alone, the fused and the smoothed track at the
//! times of the landmarks, in the pipeline's local frame (nothing aligned), and the fusion
//! yardsticks beside them.

use super::{yardstick, ErrorSummary, LogResult};
use crate::engine::fusion::FusedStep;
use crate::engine::pipeline::Pipeline;
use crate::io::import::Waypoint;

/// Errors of GNSS alone, the fused and the smoothed track at the times of geodetic truth
/// waypoints, in the pipeline's local frame (absolute: nothing is aligned).
pub fn absolute_errors(p: &Pipeline, wps: &[Waypoint], res: &mut LogResult) {
    let Some(frame) = p.frame() else {
        return;
    };
    let fixes: Vec<(f64, f64, f64)> = p
        .fixes()
        .iter()
        .map(|f| {
            let (e, n) = frame.en_of_fix(f);
            (f.t, e, n)
        })
        .collect();
    let as_points = |s: &[FusedStep]| -> Vec<(f64, f64, f64)> {
        s.iter().map(|x| (x.t, x.east_m, x.north_m)).collect()
    };
    let tracks = [fixes, as_points(p.fused()), as_points(&p.smoothed())];
    // A fix is only good for the truth within a few seconds of it; a step track holds between
    // steps and until the next one.
    let reach = [2.0, f64::INFINITY, f64::INFINITY];
    for w in wps {
        let Some((lat, lon)) = w.geo else {
            continue;
        };
        let [te, tn, _] = frame.to_enu(lat, lon, frame.h0_m);
        for (k, track) in tracks.iter().enumerate() {
            if let Some((e, n)) = interpolate(track, w.t, reach[k]) {
                res.absolute_errors_m[k].push(libm::hypot(e - te, n - tn));
            }
        }
    }
    let [g, f, sm] = &res.absolute_errors_m;
    res.gnss_error_m = ErrorSummary::of(g);
    res.fused_error_m = ErrorSummary::of(f);
    res.smoothed_error_m = ErrorSummary::of(sm);
    if let Some((offline, causal)) = yardstick::yardsticks(frame, p.fixes(), wps) {
        res.yardstick_p75_m = Some(offline);
        res.causal_yardstick_p75_m = Some(causal);
    }
}

/// Position at `t` on a time-ordered list of (t, east, north): linear between the points around
/// it, or the nearest point when it lies within `reach` s of `t` (before the first point: none).
fn interpolate(points: &[(f64, f64, f64)], t: f64, reach: f64) -> Option<(f64, f64)> {
    let i = points.partition_point(|p| p.0 <= t);
    let prev = i.checked_sub(1).map(|k| points[k]);
    let next = points.get(i).copied();
    match (prev, next) {
        (Some(a), Some(b)) if b.0 - a.0 <= 2.0 * reach.min(5.0) || reach.is_infinite() => {
            let w = if b.0 > a.0 {
                (t - a.0) / (b.0 - a.0)
            } else {
                0.0
            };
            Some((a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2)))
        }
        (Some(a), _) if t - a.0 <= reach => Some((a.1, a.2)),
        (_, Some(b)) if b.0 - t <= reach && prev.is_some() => Some((b.1, b.2)),
        _ => None,
    }
}
