//! A WeAllWalk walk folder of a simulated walk (Core Motion's 41-column CSV, the heel strikes,
//! the path's straights and turns), as [`crate::io::import::weallwalk`] reads it.
//! May import: `engine` and `io`.

use super::{canonical, enu_to_core_motion, fixed, Walk};
use crate::engine::math::wrap_pi;
use crate::engine::orientation::G0;
use crate::sim::Simulation;
use nalgebra::Vector3;
use std::fmt::Write as _;

/// A step whose path heading differs from the previous step's by more than this, degrees, is
/// part of a turn.
pub const TURN_RATE_DEG_PER_STEP: f64 = 1.0;

/// A run of turning steps is written as a turn when it turns at least this much, degrees;
/// smaller ones (a bend of a long straight) stay in the straight.
pub const MIN_TURN_DEG: f64 = 10.0;

/// One row of `segments.csv`: a straight or a turn of the true path, on the simulation's clock.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSegment {
    /// Start, s (a straight: the end of the previous turn, or the start of the first step).
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// The turn, degrees counter-clockwise; `None` for a straight.
    pub turn_deg: Option<f64>,
    /// Compass heading of the path at the start, rad clockwise from north.
    pub heading_start_rad: f64,
    /// Compass heading of the path at the end, rad.
    pub heading_end_rad: f64,
    /// True steps ending in (start, end].
    pub steps: usize,
}

/// The straights and turns of a simulated walk, in time order, from its true steps' path
/// headings: a turn is a run of consecutive steps each turning more than
/// [`TURN_RATE_DEG_PER_STEP`], turning [`MIN_TURN_DEG`] or more in all, from the step before
/// the run to its last step; the straights fill the time between the start of the first step
/// (its end less one period) and the last step. Empty for a walk without steps. A turn that
/// starts and ends gently (a slow turn over many steps) loses its first and last few degrees to
/// the straights beside it: the demo walk's 60° turn while running is written as 55°.
pub fn path_segments(sim: &Simulation) -> Vec<PathSegment> {
    let steps: Vec<&crate::sim::TruthStep> = sim
        .truth
        .steps
        .iter()
        .filter(|s| s.t.is_finite() && s.heading_rad.is_finite())
        .collect();
    let (Some(first), Some(last)) = (steps.first(), steps.last()) else {
        return Vec::new();
    };
    let period = if first.freq_hz > 0.0 {
        1.0 / first.freq_hz
    } else {
        0.5
    };
    let rate = TURN_RATE_DEG_PER_STEP.to_radians();
    // Turns as (index of the step before, index of the last step, CCW angle in degrees).
    let mut turns: Vec<(usize, usize, f64)> = Vec::new();
    let mut k = 1;
    while k < steps.len() {
        let d = |i: usize| wrap_pi(steps[i].heading_rad - steps[i - 1].heading_rad);
        if d(k).abs() <= rate {
            k += 1;
            continue;
        }
        let a = k;
        let mut sum = 0.0;
        while k < steps.len() && d(k).abs() > rate {
            sum += d(k);
            k += 1;
        }
        let ccw = -sum.to_degrees();
        if ccw.abs() >= MIN_TURN_DEG {
            turns.push((a - 1, k - 1, ccw));
        }
    }
    let count = |start: f64, end: f64| steps.iter().filter(|s| s.t > start && s.t <= end).count();
    let heading_after = |t: f64| {
        steps
            .iter()
            .find(|s| s.t > t)
            .map_or(last.heading_rad, |s| s.heading_rad)
    };
    let mut out = Vec::new();
    let straight = |out: &mut Vec<PathSegment>, start: f64, end: f64| {
        if end > start {
            out.push(PathSegment {
                start,
                end,
                turn_deg: None,
                heading_start_rad: heading_after(start),
                heading_end_rad: heading_after(start),
                steps: count(start, end),
            });
        }
    };
    let mut cursor = first.t - period;
    for &(a, b, ccw) in &turns {
        straight(&mut out, cursor, steps[a].t);
        out.push(PathSegment {
            start: steps[a].t,
            end: steps[b].t,
            turn_deg: Some(ccw),
            heading_start_rad: steps[a].heading_rad,
            heading_end_rad: steps[b].heading_rad,
            steps: count(steps[a].t, steps[b].t),
        });
        cursor = steps[b].t;
    }
    straight(&mut out, cursor, last.t);
    out
}

/// The compass point of a heading (rad clockwise from north): `N`, `NE`, … `NW`.
fn compass(h: f64) -> &'static str {
    const POINTS: [&str; 8] = ["N", "NE", "E", "SE", "S", "SW", "W", "NW"];
    let k = libm::round(h.to_degrees() / 45.0).rem_euclid(8.0);
    POINTS.get(k as usize).copied().unwrap_or("N")
}

impl Walk<'_> {
    /// The folder `T1_ID0_1L/` (path, subject, phone in the left pocket):
    ///
    /// `sensors.csv`, the 41 columns of the recording app, 6 decimals, no header, one row per IMU
    /// sample that has a gyroscope value and an orientation (Core Motion gives them together):
    /// time since the start (s); roll, pitch, yaw (rad: R = Rz(yaw)·Rx(pitch)·Ry(roll)); the
    /// rotation matrix reference → device, by rows (both as the data set's rows have them: its
    /// angles and matrix follow from its quaternion so, to its 6 decimals); the quaternion x, y, z, w (device →
    /// Core Motion's x-north, z-up reference); rotation rate (rad/s); user acceleration and
    /// gravity (g, Core Motion's sign: gravity is the down direction in device axes, the user
    /// acceleration the rest of −acceleration / g); the calibrated field `0,0,0,-1` (as the
    /// data set has it: unusable); the raw accelerometer (g, Core Motion's sign) of the next row,
    /// as the app's runs one row ahead; the raw gyroscope (rad/s); the magnetometer (µT, 0
    /// without one); and the app's two flags, 0.
    ///
    /// `steps.csv`: `t_s,foot`, one row per true step (4 decimals), the feet alternating from
    /// `L`. `segments.csv`: the straights and turns of [`path_segments`], with the compass point
    /// of each straight, `Turn<from>to<to>`, the middle of each turn, its angle (whole degrees,
    /// counter-clockwise positive) and the steps in each.
    pub(super) fn weallwalk(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let dir = "T1_ID0_1L";
        let imu: Vec<_> = self
            .imu()
            .into_iter()
            .filter(|s| s.gyro.is_some() && s.orientation.is_some())
            .collect();
        let to_reference = enu_to_core_motion();
        let mut out = String::new();
        let f6 = |v: f64| fixed(v, 6);
        for (i, s) in imu.iter().enumerate() {
            let (Some(w), Some(q)) = (s.gyro, s.orientation) else {
                continue;
            };
            let q_ref = to_reference * q;
            // Core Motion's gravity: the down direction in device axes, g.
            let gravity = q_ref.inverse() * Vector3::new(0.0, 0.0, -1.0);
            let total = -s.accel / G0;
            let user = total - gravity;
            let raw = imu.get(i + 1).map_or(total, |n| -n.accel / G0);
            let r = q_ref.to_rotation_matrix();
            let m = r.matrix();
            let pitch = libm::asin(m[(2, 1)].clamp(-1.0, 1.0));
            let roll = libm::atan2(-m[(2, 0)], m[(2, 2)]);
            let yaw = libm::atan2(-m[(0, 1)], m[(1, 1)]);
            let c = canonical(&q_ref);
            let mag = s.mag.unwrap_or_else(Vector3::zeros);
            let mut row: Vec<String> = vec![f6(self.rel(s.t)), f6(roll), f6(pitch), f6(yaw)];
            // Reference → device: the transpose of device → reference, by rows.
            for a in 0..3 {
                for b in 0..3 {
                    row.push(f6(m[(b, a)]));
                }
            }
            row.extend([c.i, c.j, c.k, c.w].map(f6));
            row.extend([w.x, w.y, w.z].map(f6));
            row.extend([user.x, user.y, user.z].map(f6));
            row.extend([gravity.x, gravity.y, gravity.z].map(f6));
            row.extend(["0.000000", "0.000000", "0.000000", "-1"].map(String::from));
            row.extend([raw.x, raw.y, raw.z].map(f6));
            row.extend([w.x, w.y, w.z].map(f6));
            row.extend([mag.x, mag.y, mag.z].map(f6));
            row.extend(["0", "0"].map(String::from));
            out.push_str(&row.join(","));
            out.push('\n');
        }
        let mut steps = String::from("t_s,foot\n");
        for (k, st) in sim.truth.steps.iter().enumerate() {
            if st.t.is_finite() {
                let foot = if k % 2 == 0 { "L" } else { "R" };
                let _ = writeln!(steps, "{},{foot}", fixed(self.rel(st.t), 4));
            }
        }
        let mut segments = String::from(
            "segment,spatial_segment,start_s,end_s,direction,turn_time_s,turn_deg,steps\n",
        );
        let mut straight_no = 0u32;
        for (k, seg) in path_segments(sim).iter().enumerate() {
            let (spatial, direction, turn_time, turn) = match seg.turn_deg {
                None => {
                    straight_no += 1;
                    (
                        straight_no.to_string(),
                        compass(seg.heading_start_rad).to_string(),
                        String::new(),
                        String::new(),
                    )
                }
                Some(deg) => (
                    format!("{straight_no}-{}", straight_no + 1),
                    format!(
                        "Turn{}to{}",
                        compass(seg.heading_start_rad),
                        compass(seg.heading_end_rad)
                    ),
                    fixed(self.rel(0.5 * (seg.start + seg.end)), 4),
                    fixed(deg, 0),
                ),
            };
            let _ = writeln!(
                segments,
                "{},{spatial},{},{},{direction},{turn_time},{turn},{}",
                k + 1,
                fixed(self.rel(seg.start), 4),
                fixed(self.rel(seg.end), 4),
                seg.steps
            );
        }
        vec![
            (format!("{dir}/segments.csv"), segments.into_bytes()),
            (format!("{dir}/sensors.csv"), out.into_bytes()),
            (format!("{dir}/steps.csv"), steps.into_bytes()),
        ]
    }
}
