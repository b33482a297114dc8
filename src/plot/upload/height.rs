//! Upload mode's height and floor against time (Munoz Diaz 2015 §6, with the barometer where
//! the log has one): the series the diagnostics plot draws and its axes.
//! May import: `analysis`, the decimation; never `web`, `live` or `eval`.

use super::decimate::{envelope, of};
use crate::analysis::Analysis;

/// Metres per floor on the floor axis: the floor axis is the height axis over this, so that
/// the floors' staircase lies along the height line (a display scale only: the floors are the
/// engine's).
pub const AXIS_M_PER_FLOOR: f64 = 3.0;

/// The height plot's series between `t0` and `t1` (time from `origin`, s): the height's runs
/// (m), and the floor as a staircase (one corner at each change).
pub struct HeightSeries {
    /// The height's runs, m ([`envelope`]).
    pub height: Vec<Vec<(f64, f64)>>,
    /// The floor: a staircase through the span.
    pub floor: Vec<(f64, f64)>,
    /// The height axis, m: what the span shows, at least 3 m, padded.
    pub metres: (f64, f64),
    /// The floor axis: the height axis over [`AXIS_M_PER_FLOOR`].
    pub floors: (f64, f64),
}

impl HeightSeries {
    /// The series of `a` between `t0` and `t1`, decimated to `cols` columns.
    pub fn new(a: &Analysis, t0: f64, t1: f64, cols: usize, origin: f64) -> Self {
        let tr = &a.trace;
        let height = envelope(&tr.t, of(&tr.height), t0, t1, cols, origin);
        let i0 = tr.t.partition_point(|&x| x < t0);
        let i1 = tr.t.partition_point(|&x| x <= t1);
        let mut floor = Vec::new();
        let mut last: Option<i16> = None;
        for i in i0..i1.min(tr.floor.len()) {
            let f = tr.floor[i];
            let x = tr.t[i] - origin;
            match last {
                None => floor.push((x, f64::from(f))),
                Some(l) if l != f => {
                    floor.push((x, f64::from(l)));
                    floor.push((x, f64::from(f)));
                }
                _ => {}
            }
            last = Some(f);
        }
        if let (Some(l), Some(&t)) = (last, tr.t.get(i1.saturating_sub(1))) {
            floor.push((t - origin, f64::from(l)));
        }
        let (lo, hi) = height
            .iter()
            .flatten()
            .map(|p| p.1)
            .chain(floor.iter().map(|p| p.1 * AXIS_M_PER_FLOOR))
            .fold((0.0_f64, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let pad = ((hi - lo).max(3.0) - (hi - lo)) / 2.0 + 0.08 * (hi - lo).max(3.0);
        let metres = (lo - pad, hi + pad);
        HeightSeries {
            height,
            floor,
            metres,
            floors: (metres.0 / AXIS_M_PER_FLOOR, metres.1 / AXIS_M_PER_FLOOR),
        }
    }
}

/// The floor axis's label: "+1", "0", "−2"; nothing between whole floors.
pub fn floor_tick(v: &f64) -> String {
    let r = v.round();
    if (v - r).abs() > 1e-6 {
        return String::new();
    }
    match r as i64 {
        0 => "0".to_string(),
        f if f > 0 => format!("+{f}"),
        f => format!("\u{2212}{}", f.unsigned_abs()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_ticks_are_whole_signed_floors() {
        assert_eq!(floor_tick(&0.0), "0");
        assert_eq!(floor_tick(&2.0), "+2");
        assert_eq!(floor_tick(&-1.0), "\u{2212}1");
        assert_eq!(floor_tick(&0.5), "");
    }
}
