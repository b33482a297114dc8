//! The fusion yardstick: how close to the landmarks a perfect walk shape gets when only the
//! fixes place it.
//!
//! The true walk shape is the surveyed landmarks, linear in time between them. It is placed by
//! one translation, the Huber-weighted mean of (fix − truth at the fix's time) over the fixes
//! that report an accuracy of at most [`MAX_ACCURACY_M`] and fall inside the landmarks' time
//! span (outside it the truth is unknown). At a landmark the placed shape is then off by that
//! translation, so:
//! - the **offline** yardstick, every fix in view, is the translation's length at every landmark
//!   (its p75 is that length);
//! - the **causal** yardstick places the shape at each landmark with the fixes up to that
//!   landmark's time, and is the p75 of those lengths over the landmarks that have a fix
//!   before them.
//!
//! They tell what the fixes allow: a fusion with a faultless PDR shape and nothing but the
//! fixes to place it would score about these. They are not bounds: a smoother may bend a shape
//! towards the fixes and beat them. They use the truth, so they are evaluation figures only.

use crate::engine::geo::LocalFrame;
use crate::engine::types::GnssFix;
use crate::io::import::Waypoint;

/// Fixes reporting a horizontal accuracy above this are left out, m.
pub const MAX_ACCURACY_M: f64 = 50.0;

/// Huber's threshold on a fix's residual from the mean, m: residuals up to it weigh fully, a
/// larger one weighs `HUBER_K_M / residual` (a good phone fix's error is a few metres; fixes
/// off by tens of metres still pull, but only as far as this).
pub const HUBER_K_M: f64 = 5.0;

/// Both yardsticks of one log: (offline p75, causal p75), m. `None` without two geodetic
/// landmarks or without a usable fix inside their span.
pub fn yardsticks(
    frame: &LocalFrame,
    fixes: &[GnssFix],
    landmarks: &[Waypoint],
) -> Option<(f64, f64)> {
    let truth: Vec<(f64, f64, f64)> = landmarks
        .iter()
        .filter_map(|w| {
            let (lat, lon) = w.geo?;
            let [e, n, _] = frame.to_enu(lat, lon, frame.h0_m);
            Some((w.t, e, n))
        })
        .collect();
    let offsets = fix_offsets(frame, fixes, &truth)?;
    let all: Vec<(f64, f64)> = offsets.iter().map(|o| (o.1, o.2)).collect();
    let offline = length(huber_mean(&all)?);
    let causal: Vec<f64> = truth
        .iter()
        .filter_map(|&(t, _, _)| {
            let upto = offsets.partition_point(|o| o.0 <= t);
            let seen: Vec<(f64, f64)> = offsets[..upto].iter().map(|o| (o.1, o.2)).collect();
            huber_mean(&seen).map(length)
        })
        .collect();
    Some((offline, super::percentile(&causal, 75.0)))
}

/// (t, fix − truth east, north) of every usable fix inside the truth's span, in time order.
fn fix_offsets(
    frame: &LocalFrame,
    fixes: &[GnssFix],
    truth: &[(f64, f64, f64)],
) -> Option<Vec<(f64, f64, f64)>> {
    let (first, last) = (truth.first()?.0, truth.last()?.0);
    if truth.len() < 2 {
        return None;
    }
    let mut out: Vec<(f64, f64, f64)> = fixes
        .iter()
        .filter(|f| f.h_accuracy_m <= MAX_ACCURACY_M && f.t >= first && f.t <= last)
        .filter_map(|f| {
            let (te, tn) = truth_at(truth, f.t)?;
            let (e, n) = frame.en_of_fix(f);
            Some((f.t, e - te, n - tn))
        })
        .collect();
    crate::engine::sort::sort_by(&mut out, |a, b| a.0.total_cmp(&b.0));
    (!out.is_empty()).then_some(out)
}

/// The truth at `t`, linear between the landmarks around it (`t` inside their span).
fn truth_at(truth: &[(f64, f64, f64)], t: f64) -> Option<(f64, f64)> {
    let i = truth.partition_point(|p| p.0 <= t);
    let a = truth.get(i.checked_sub(1)?)?;
    let Some(b) = truth.get(i) else {
        return Some((a.1, a.2));
    };
    let w = if b.0 > a.0 {
        (t - a.0) / (b.0 - a.0)
    } else {
        0.0
    };
    Some((a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2)))
}

/// The Huber-weighted mean of 2-D points, by iteratively reweighted means from the
/// coordinate-wise median, with threshold [`HUBER_K_M`]. `None` for no points.
pub fn huber_mean(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    if points.is_empty() {
        return None;
    }
    let median = |f: fn(&(f64, f64)) -> f64| {
        let v: Vec<f64> = points.iter().map(f).collect();
        super::percentile(&v, 50.0)
    };
    let mut m = (median(|p| p.0), median(|p| p.1));
    for _ in 0..100 {
        let (mut sw, mut se, mut sn) = (0.0, 0.0, 0.0);
        for &(e, n) in points {
            let r = libm::hypot(e - m.0, n - m.1);
            let w = if r <= HUBER_K_M { 1.0 } else { HUBER_K_M / r };
            sw += w;
            se += w * e;
            sn += w * n;
        }
        let next = (se / sw, sn / sw);
        let moved = libm::hypot(next.0 - m.0, next.1 - m.1);
        m = next;
        if moved < 1e-6 {
            break;
        }
    }
    Some(m)
}

fn length(v: (f64, f64)) -> f64 {
    libm::hypot(v.0, v.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> LocalFrame {
        LocalFrame::new(49.46, 11.11, 300.0)
    }

    fn landmark(frame: &LocalFrame, t: f64, e: f64, n: f64) -> Waypoint {
        let (lat, lon, _) = frame.to_geodetic([e, n, 0.0]);
        Waypoint {
            t,
            x_m: e,
            y_m: n,
            geo: Some((lat, lon)),
            floor: None,
            height_m: None,
        }
    }

    fn fix(frame: &LocalFrame, t: f64, e: f64, n: f64, acc: f64) -> GnssFix {
        let (lat, lon, _) = frame.to_geodetic([e, n, 0.0]);
        GnssFix {
            t,
            lat_deg: lat,
            lon_deg: lon,
            h_accuracy_m: acc,
            altitude_m: None,
            speed_mps: None,
            bearing_deg: None,
        }
    }

    /// A walk east at 1 m/s from t = 10 s to 110 s, landmarks every 10 s.
    fn walk(f: &LocalFrame) -> Vec<Waypoint> {
        (0..=10)
            .map(|k| landmark(f, 10.0 + 10.0 * k as f64, 10.0 * k as f64, 0.0))
            .collect()
    }

    #[test]
    fn fixes_off_by_a_constant_give_that_constant_and_outliers_barely_move_it() {
        let f = frame();
        let mut fixes: Vec<GnssFix> = (10..=110)
            .map(|t| fix(&f, t as f64, (t - 10) as f64 + 3.0, 4.0, 5.0))
            .collect();
        let (y, c) = yardsticks(&f, &fixes, &walk(&f)).unwrap();
        assert!((y - 5.0).abs() < 1e-6 && (c - 5.0).abs() < 1e-6, "{y} {c}");
        // Five fixes 200 m off: a plain mean would move by 10 m; Huber's by well under 1 m.
        for k in 0..5 {
            fixes.push(fix(&f, 50.5 + k as f64, 40.0, 200.0, 10.0));
        }
        let (y, _) = yardsticks(&f, &fixes, &walk(&f)).unwrap();
        assert!((y - 5.0).abs() < 0.5, "{y}");
    }

    #[test]
    fn causal_places_each_landmark_with_the_fixes_before_it() {
        let f = frame();
        // Off by 10 m north in the first half, exact in the second: offline sits between, the
        // causal one is 10 m at every landmark up to the middle.
        let fixes: Vec<GnssFix> = (10..=110)
            .map(|t| {
                let n = if t < 60 { 10.0 } else { 0.0 };
                fix(&f, t as f64, (t - 10) as f64, n, 5.0)
            })
            .collect();
        let (y, c) = yardsticks(&f, &fixes, &walk(&f)).unwrap();
        assert!(y > 2.0 && y < 8.0, "{y}");
        assert!(c > y, "{c} {y}");
    }

    #[test]
    fn poor_fixes_and_fixes_outside_the_landmarks_are_left_out() {
        let f = frame();
        let mut fixes = vec![
            fix(&f, 5.0, 500.0, 0.0, 3.0),
            fix(&f, 120.0, 0.0, 500.0, 3.0),
        ];
        assert_eq!(yardsticks(&f, &fixes, &walk(&f)), None);
        fixes.push(fix(&f, 30.0, 20.0, 300.0, 80.0));
        assert_eq!(yardsticks(&f, &fixes, &walk(&f)), None);
        fixes.push(fix(&f, 30.0, 20.0, 2.0, 8.0));
        let (y, c) = yardsticks(&f, &fixes, &walk(&f)).unwrap();
        assert!((y - 2.0).abs() < 1e-6 && (c - 2.0).abs() < 1e-6, "{y} {c}");
        assert_eq!(yardsticks(&f, &fixes, &walk(&f)[..1]), None);
    }
}
