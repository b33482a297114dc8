//! The truth of a simulated walk: steps, path, height, floors, activities and the thigh's pitch.
//! May import: `engine` and `io`.

use super::{Gait, Scenario, Timeline};
use crate::engine::Activity;
use std::f64::consts::TAU;

/// One true step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TruthStep {
    /// End of the step, s.
    pub t: f64,
    /// Position after the step, m.
    pub east_m: f64,
    /// Position after the step, m.
    pub north_m: f64,
    /// Path heading at the step, rad from north.
    pub heading_rad: f64,
    /// Step length (horizontal), m.
    pub length_m: f64,
    /// Cadence, Hz.
    pub freq_hz: f64,
    /// Whether the step was observable (not inside a sampling gap).
    pub observed: bool,
    /// What the walker did during the step (the activity at its middle).
    pub activity: Activity,
    /// Height of the stair under the walker after the step, relative to the start, m: one riser
    /// per footfall on a flight.
    pub up_m: f64,
    /// Floor after the step, relative to the start (0 without a floor height).
    pub floor: i32,
}

/// The truth of a simulated walk.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Truth {
    /// Every step taken.
    pub steps: Vec<TruthStep>,
    /// Path length, m.
    pub distance_m: f64,
    /// Final position (east, north), m.
    pub end: (f64, f64),
    /// (start, end, gait) of each segment.
    pub segments: Vec<(f64, f64, Gait)>,
    /// The path every 0.1 s: (time, east, north), s and m.
    pub path: Vec<(f64, f64, f64)>,
    /// The geodetic frame of `path` and `steps` (origin at the start), when there is GNSS.
    pub frame: Option<crate::engine::geo::LocalFrame>,
    /// Height of the ground under the walker at the times of `path`: (time, up), s and m. (The
    /// phone drops below its standing height while seated; the barometer sees that, this does
    /// not.)
    pub up_path: Vec<(f64, f64)>,
    /// Height of one floor, m (0: the scenario has no floors).
    pub floor_height_m: f64,
    /// (start, end, activity) over the whole walk, s.
    pub activities: Vec<(f64, f64, Activity)>,
    /// The thigh's true pitch every 0.01 s: (time, θ), s and degrees, 0 standing, positive with
    /// the knee forward (hip flexion); see [`super::thigh`].
    pub thigh_pitch_deg: Vec<(f64, f64)>,
}

/// Linear interpolation in a time series of (t, value).
fn interpolate(series: &[(f64, f64)], t: f64) -> f64 {
    let i = series.partition_point(|p| p.0 <= t);
    match (i.checked_sub(1).map(|k| series[k]), series.get(i)) {
        (Some(a), Some(b)) if b.0 > a.0 => a.1 + (t - a.0) / (b.0 - a.0) * (b.1 - a.1),
        (Some(a), _) => a.1,
        (None, Some(b)) => b.1,
        (None, None) => 0.0,
    }
}

impl Truth {
    /// The true position at time `t` (east, north), interpolated along the path.
    pub fn position_at(&self, t: f64) -> (f64, f64) {
        let i = self.path.partition_point(|p| p.0 <= t);
        match (i.checked_sub(1).map(|k| self.path[k]), self.path.get(i)) {
            (Some(a), Some(b)) if b.0 > a.0 => {
                let w = (t - a.0) / (b.0 - a.0);
                (a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2))
            }
            (Some(a), _) => (a.1, a.2),
            (None, Some(b)) => (b.1, b.2),
            (None, None) => (0.0, 0.0),
        }
    }

    /// A found step's heading error against the direction of the true step it ends (the first
    /// true step at or after its time, else the last), rad in (−π, π]; `None` without a heading
    /// or a true step.
    pub fn heading_error(&self, step: &crate::engine::StepRecord) -> Option<f64> {
        let k = self.steps.partition_point(|x| x.t < step.t);
        let truth = self.steps.get(k).or(self.steps.last())?.heading_rad;
        step.heading_rad
            .map(|h| crate::engine::math::wrap_pi(h - truth))
    }

    /// Each true step's time and position after it, (t, east, north).
    pub fn step_points(&self) -> Vec<(f64, f64, f64)> {
        self.steps
            .iter()
            .map(|s| (s.t, s.east_m, s.north_m))
            .collect()
    }

    /// Steps that fall outside sampling gaps.
    pub fn observed_steps(&self) -> usize {
        self.steps.iter().filter(|s| s.observed).count()
    }

    /// The ground's height at `t` relative to the start, m.
    pub fn height_at(&self, t: f64) -> f64 {
        interpolate(&self.up_path, t)
    }

    /// The floor at `t` relative to the start (0 without a floor height).
    pub fn floor_at(&self, t: f64) -> i32 {
        floor_of(self.height_at(t), self.floor_height_m)
    }

    /// The true activity at `t`.
    pub fn activity_at(&self, t: f64) -> Activity {
        let i = self.activities.partition_point(|a| a.0 <= t);
        i.checked_sub(1)
            .map_or(Activity::Standing, |k| self.activities[k].2)
    }

    /// The thigh's true pitch at `t`, degrees (interpolated at 100 Hz).
    pub fn pitch_at(&self, t: f64) -> f64 {
        interpolate(&self.thigh_pitch_deg, t)
    }
}

fn floor_of(up_m: f64, floor_height_m: f64) -> i32 {
    if floor_height_m > 0.0 {
        (up_m / floor_height_m).round() as i32
    } else {
        0
    }
}

impl Scenario {
    /// The truth along the timeline.
    pub(super) fn truth(&self, tl: &Timeline) -> Truth {
        let body = self.body();
        let stairs = !body.flights.is_empty();
        let fh = self.floor_height_m.unwrap_or(0.0);
        let mut tr = Truth::default();
        let dt = 1e-3;
        let dur = self.duration_s();
        let mut hint = 0;
        let (mut e, mut n, mut dist) = (0.0, 0.0, 0.0);
        let mut last_step_dist = 0.0;
        let mut prev = tl.state(0.0, &mut hint);
        let mut t = 0.0;
        let mut ticks = 0u64;
        tr.path.push((0.0, 0.0, 0.0));
        tr.up_path.push((0.0, 0.0));
        while t < dur {
            let t1 = (t + dt).min(dur);
            ticks += 1;
            let st = tl.state(t1, &mut hint);
            if st.gait.moving() {
                let mid = tl.state(0.5 * (t + t1), &mut hint.clone());
                let mut v = self.walker.step_length.length(mid.f) * mid.f;
                if stairs {
                    v = body.speed(0.5 * (t + t1), v, 0.0).0;
                }
                if self.real_ends {
                    // Getting under way and braking ([`super::ends`]).
                    v *= body.walk_envelope(0.5 * (t + t1));
                }
                let ds = v * (t1 - t);
                e += ds * libm::sin(mid.psi);
                n += ds * libm::cos(mid.psi);
                dist += ds;
                if prev.gait.moving() && (st.phi / TAU).floor() > (prev.phi / TAU).floor() {
                    // Interpolate the crossing of the multiple of 2π.
                    let k = (st.phi / TAU).floor() * TAU;
                    let frac = (k - prev.phi) / (st.phi - prev.phi);
                    let tc = t + frac * (t1 - t);
                    let observed = !self.sensors.gaps.iter().any(|&(a, b)| tc > a && tc < b);
                    let up_m = body.stair_height(tc);
                    tr.steps.push(TruthStep {
                        t: tc,
                        east_m: e,
                        north_m: n,
                        heading_rad: crate::engine::math::wrap_2pi(st.psi),
                        length_m: dist - last_step_dist,
                        freq_hz: st.f,
                        observed,
                        activity: body.activity_at(tc - 0.5 / st.f.max(0.5)),
                        up_m,
                        floor: floor_of(up_m, fh),
                    });
                    last_step_dist = dist;
                }
            }
            prev = st;
            t = t1;
            if ticks % 100 == 0 || t >= dur {
                tr.path.push((t, e, n));
                tr.up_path.push((t, body.height(t)));
            }
        }
        let off = self.clock_offset_s;
        for s in &mut tr.steps {
            s.t += off;
        }
        for p in &mut tr.path {
            p.0 += off;
        }
        for p in &mut tr.up_path {
            p.0 += off;
        }
        tr.distance_m = dist;
        tr.end = (e, n);
        let mut t0 = self.clock_offset_s;
        for s in &self.timed_segments() {
            tr.segments.push((t0, t0 + s.duration_s, s.gait));
            t0 += s.duration_s;
        }
        tr.floor_height_m = fh;
        tr.activities = body
            .activities
            .iter()
            .map(|&(a, b, act)| (a + off, b + off, act))
            .collect();
        let n100 = (dur * 100.0).floor() as usize;
        tr.thigh_pitch_deg = (0..=n100)
            .map(|k| {
                let t = k as f64 / 100.0;
                (t + off, self.thigh_deg(tl, &body, t))
            })
            .collect();
        tr
    }
}
