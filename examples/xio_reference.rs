//! The reference for foot mode: x-io's Gait-Tracking script
//! (`../shared/data/xio-foot/reference/gait_tracking.py`, MIT) re-implemented step by step, run
//! on both x-io walks beside foot mode (`placement=foot`), printing each one's loop closure.
//!
//! The script's steps: the Fusion AHRS (gain 0.5, no magnetometer, 10° acceleration rejection)
//! after Fusion's gyroscope offset correction; earth acceleration; "moving" when its norm
//! exceeds 3 m/s², widened by 100 ms margins on both sides; velocity integrated while moving,
//! with the linear drift of each moving period removed (zero at both ends); position integrated.
//! Fusion's AHRS here is its published algorithm (Madgwick's x-io Fusion library, `FusionAhrs.c`:
//! a complementary filter whose accelerometer feedback is the cross product of the measured and
//! the estimated gravity, with the gain ramped down from 10 over the first 3 s), without its
//! rejection-timeout recovery (never triggered on these walks: the rejection only ever lasts a
//! swing). The printed figures are x-io's: 0.082 m and 0.420 m (x-io's README: 82 mm and 421 mm).
//!
//! `cargo run --release --example xio_reference`

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use pdr::engine::foot::placement::Placement;
use pdr::engine::{replay, PipelineConfig, Record};
use std::path::Path;

/// The script's nominal sample rate (its margins and Fusion's time constants use it).
const SAMPLE_RATE: f64 = 400.0;

/// Fusion's gyroscope offset: when every axis stays under 3°/s for 1 s, the offset follows the
/// rate with a 0.02 Hz low-pass (`FusionOffset.c`).
struct Offset {
    timer: u32,
    offset: Vector3<f64>,
}

impl Offset {
    fn update(&mut self, g_deg: Vector3<f64>) -> Vector3<f64> {
        let out = g_deg - self.offset;
        if out.iter().any(|x| x.abs() > 3.0) {
            self.timer = 0;
            return out;
        }
        if f64::from(self.timer) < SAMPLE_RATE {
            self.timer += 1;
            return out;
        }
        let k = 2.0 * std::f64::consts::PI * 0.02 / SAMPLE_RATE;
        self.offset += (out) * k;
        out
    }
}

/// Fusion's AHRS without magnetometer (`FusionAhrsUpdate`), z up.
struct Ahrs {
    q: UnitQuaternion<f64>,
    gain: f64,
    ramped: f64,
    initialising: bool,
}

impl Ahrs {
    fn update(&mut self, g_deg: Vector3<f64>, a_g: Vector3<f64>, dt: f64) {
        if self.initialising {
            self.ramped -= (10.0 - self.gain) * dt / 3.0;
            if self.ramped < self.gain {
                self.ramped = self.gain;
                self.initialising = false;
            }
        }
        let q = self.q.quaternion();
        let (w, x, y, z) = (q.w, q.i, q.j, q.k);
        // Half the gravity direction in the sensor frame (third row of the rotation matrix).
        let half_gravity = Vector3::new(x * z - w * y, y * z + w * x, w * w - 0.5 + z * z);
        let mut feedback = Vector3::zeros();
        if a_g.norm() > 0.0 {
            let f = a_g.normalize().cross(&half_gravity);
            // Acceleration error: asin(2|f|); rejected above 10° once initialised.
            let err = libm::asin((2.0 * f.norm()).min(1.0)).to_degrees();
            if self.initialising || err <= 10.0 {
                feedback = f;
            }
        }
        let half_gyro = g_deg * (0.5 * std::f64::consts::PI / 180.0);
        let adj = half_gyro + feedback * self.ramped;
        let dq = q * Quaternion::new(0.0, adj.x, adj.y, adj.z) * dt;
        self.q = UnitQuaternion::from_quaternion(q + dq);
    }
}

/// x-io's Gait-Tracking on one file: its final displacement, m, and the distance, m.
fn gait_tracking(t: &[f64], gyro_deg: &[Vector3<f64>], acc_g: &[Vector3<f64>]) -> (f64, f64) {
    let n = t.len();
    let mut offset = Offset {
        timer: 0,
        offset: Vector3::zeros(),
    };
    let mut ahrs = Ahrs {
        q: UnitQuaternion::identity(),
        gain: 0.5,
        ramped: 10.0,
        initialising: true,
    };
    let dt: Vec<f64> = (0..n)
        .map(|i| if i == 0 { 0.0 } else { t[i] - t[i - 1] })
        .collect();
    let mut acc = vec![Vector3::zeros(); n];
    for i in 0..n {
        let g = offset.update(gyro_deg[i]);
        ahrs.update(g, acc_g[i], dt[i]);
        // Earth acceleration: the reading rotated to the earth frame, gravity removed.
        let e = ahrs.q * acc_g[i] - Vector3::z();
        acc[i] = e * 9.81;
    }
    let raw: Vec<bool> = acc.iter().map(|a| a.norm() > 3.0).collect();
    let margin = (0.1 * SAMPLE_RATE) as usize;
    let mut moving = raw.clone();
    for i in 0..n.saturating_sub(margin) {
        moving[i] = moving[i..i + margin].iter().any(|&x| x);
    }
    for i in (margin + 1..n).rev() {
        moving[i] = moving[i - margin..i].iter().any(|&x| x);
    }
    let mut vel = vec![Vector3::zeros(); n];
    for i in 0..n {
        if moving[i] {
            // numpy's velocity[index - 1] at index 0 is the last row (still zero then).
            let prev = if i == 0 { vel[n - 1] } else { vel[i - 1] };
            vel[i] = prev + acc[i] * dt[i];
        }
    }
    // Moving periods from the diff of is_moving (append the last value).
    let diff: Vec<i32> = (0..n)
        .map(|i| {
            let next = if i + 1 < n {
                moving[i + 1]
            } else {
                moving[n - 1]
            };
            i32::from(next) - i32::from(moving[i])
        })
        .collect();
    let mut start = None;
    let mut periods = Vec::new();
    for (i, &d) in diff.iter().enumerate() {
        match start {
            None if d == 1 => start = Some(i),
            Some(s) if d == -1 => {
                periods.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    let mut drift = vec![Vector3::zeros(); n];
    for (s, e) in periods {
        let span = t[e] - t[s];
        for (i, d) in drift.iter_mut().enumerate().take(e + 1).skip(s) {
            let w = if span > 0.0 {
                (t[i] - t[s]) / span
            } else {
                0.0
            };
            *d = vel[s] + (vel[e] - vel[s]) * w;
        }
    }
    let mut pos = Vector3::zeros();
    let mut dist = 0.0;
    for i in 0..n {
        let v = vel[i] - drift[i];
        let step = v * dt[i];
        pos += step;
        dist += (step.x * step.x + step.y * step.y).sqrt();
    }
    (pos.norm(), dist)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/xio-foot");
    for name in ["short_walk.csv", "long_walk.csv"] {
        let Ok(text) = std::fs::read_to_string(dir.join(name)) else {
            println!(
                "skipped: {} not found (the shared data set is not beside this checkout)",
                dir.display()
            );
            return;
        };
        let (mut t, mut g, mut a) = (Vec::new(), Vec::new(), Vec::new());
        for line in text.lines().skip(1) {
            let v: Vec<f64> = line
                .split(',')
                .filter_map(|x| x.trim().parse().ok())
                .collect();
            if v.len() == 7 {
                t.push(v[0]);
                g.push(Vector3::new(v[1], v[2], v[3]));
                a.push(Vector3::new(v[4], v[5], v[6]));
            }
        }
        let (reference, ref_dist) = gait_tracking(&t, &g, &a);
        let log = pdr::io::import::xio::read_xio(text.as_bytes(), name).expect("x-io CSV");
        let records: &[Record] = &log.records;
        let cfg = PipelineConfig {
            placement: Placement::Foot,
            ..PipelineConfig::default()
        };
        let r = replay(cfg, records).expect("config");
        let d = r.pipeline.diagnostics();
        let last = r
            .pipeline
            .track()
            .last()
            .map_or((0.0, 0.0), |s| (s.east_m, s.north_m));
        let ours = libm::hypot(last.0, last.1);
        println!(
            "{name}: x-io Gait-Tracking (re-implemented) {reference:.3} m over {ref_dist:.2} m ({:.2} %); \
             foot mode {ours:.3} m over {:.2} m ({:.2} %), {} strides",
            100.0 * reference / ref_dist,
            d.distance_m,
            100.0 * ours / d.distance_m,
            d.strides
        );
    }
}
