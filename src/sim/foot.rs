//! A simulated foot IMU on the same walker as the pocket phone (for Strozzi 2017 §3.2 foot mode
//! and §4 hybrid heading).
//! May import: `engine` and `io`.
//!
//! # Model
//! The IMU is strapped on the instep of the **right** foot (the pocket leg). The walker, script,
//! path, cadence and step timing are the pocket phone's ([`super::Scenario`]): the steps end at
//! the vertical-acceleration peaks φ ≡ 0 (mod 2π), the right heel strikes at φ ≡ 0 (mod 4π)
//! (where the simulated waist yaw and thigh pitch peak), so each foot strides once per two steps.
//!
//! - **Rest** (stance, foot flat): zero velocity and rate, a share of the gait cycle
//!   ([`FootImu::rest_share_walk`], 0.6 walking; [`FootImu::rest_share_run`], 0.3 running).
//! - **Motion** (heel-off, swing, heel strike) fills the rest of the cycle, centred on φ ≡ 3π
//!   (mod 4π), halfway between the left and right heel strikes: there the simulated pelvis yaw
//!   crosses zero, the instant Strozzi §4.1 calls mid-swing, when the trunk heads along the
//!   walking direction. During it, with u ∈ [0, 1] its share of the motion:
//!   - horizontal: from one footprint to the next along the chord, by the minimum-jerk profile
//!     m(u) = 10u³ − 15u⁴ + 6u⁵ (zero velocity and acceleration at both ends);
//!   - height: H·64u³(1 − u)³, H = [`FootImu::clearance_m`] at mid-swing (zero height, vertical
//!     velocity and acceleration at both ends);
//!   - pitch: plantar flexion at heel-off and toe-off (toes down), dorsiflexion at heel strike
//!     (toes up): θ(u) = Θ·64u³(1 − u)³·cos(πu)/c, c its largest value, Θ =
//!     [`FootImu::pitch_deg`]; rate and angular acceleration are zero at both ends;
//!   - yaw: from the path heading at the last footprint to the path heading at the next, by
//!     m(u). So acceleration and rate are continuous everywhere.
//! - **Footprints.** The right foot rests on the path, [`FootImu::lateral_m`] to its right, at
//!   the path position of its mid-stance (φ ≡ π mod 4π): the footprint-to-footprint distance is
//!   the path walked over one stride, twice the step length at constant cadence. A motion that
//!   would not fit inside its walking bout is not made; the last motion of a bout lands at the
//!   walker's stopping point (the feet come together). Between bouts the foot stays where it is.
//!
//! Readings in the foot frame (x forward along the foot, y left, z up; flat at rest it reads
//! (0, 0, +g), Android sign as the rest of `sim`): gyroscope = the exact body rate
//! (−ψ̇_m sin θ, θ̇, ψ̇_m cos θ) with ψ_m = π/2 − ψ the mathematical yaw, + bias + noise;
//! accelerometer = R^T(p̈ + g ẑ) + bias + noise, with R = Rz(π/2 − ψ)·Ry(θ). Every derivative is
//! analytic. Samples are regular at [`FootImu::rate_hz`] (an x-io NGIMU records 400 Hz). The
//! noise comes from the same SplitMix64/Box–Muller generator as the phone's, seeded from the
//! scenario's seed on a stream of its own, so that adding a foot IMU leaves the phone's samples
//! bit-identical.

use super::{ry, rz, Rng, Scenario, Simulation, Timeline, G};
use crate::engine::math::{heading_of, wrap_2pi, wrap_pi};
use crate::engine::types::ImuSample;
use crate::engine::Record;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The foot IMU and the foot's motion.
#[derive(Debug, Clone, PartialEq)]
pub struct FootImu {
    /// Sample rate, Hz.
    pub rate_hz: f64,
    /// Accelerometer white noise, m/s² (1σ).
    pub accel_noise: f64,
    /// Gyroscope white noise, rad/s (1σ).
    pub gyro_noise: f64,
    /// Gyroscope bias at the start, rad/s, sensor frame.
    pub gyro_bias: [f64; 3],
    /// Linear drift of the gyroscope bias, rad/s per second (a sensor warming up): what a
    /// bias estimated at the first stance does not remove, so foot mode's heading drifts.
    pub gyro_bias_drift: [f64; 3],
    /// Accelerometer bias, m/s², sensor frame.
    pub accel_bias: [f64; 3],
    /// Height of the instep at mid-swing, m.
    pub clearance_m: f64,
    /// Largest plantar flexion and dorsiflexion of the foot, degrees.
    pub pitch_deg: f64,
    /// Share of the gait cycle the foot rests flat on the ground, walking.
    pub rest_share_walk: f64,
    /// Share of the gait cycle the foot rests flat on the ground, running.
    pub rest_share_run: f64,
    /// Distance of the footprints to the right of the path, m.
    pub lateral_m: f64,
}

impl Default for FootImu {
    fn default() -> Self {
        FootImu {
            rate_hz: 400.0,
            accel_noise: 0.03,
            gyro_noise: 0.004,
            gyro_bias: [0.0005, -0.0004, 0.0003],
            gyro_bias_drift: [0.0; 3],
            accel_bias: [0.0, 0.0, 0.0],
            clearance_m: 0.12,
            pitch_deg: 30.0,
            rest_share_walk: 0.6,
            rest_share_run: 0.3,
            lateral_m: 0.09,
        }
    }
}

impl FootImu {
    /// The same IMU without noise nor bias.
    pub fn noiseless() -> Self {
        FootImu {
            accel_noise: 0.0,
            gyro_noise: 0.0,
            gyro_bias: [0.0; 3],
            gyro_bias_drift: [0.0; 3],
            ..FootImu::default()
        }
    }
}

/// One true stride of the foot.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FootStride {
    /// The foot leaves the ground (end of rest), s.
    pub t_start: f64,
    /// The foot is flat again (start of rest), s.
    pub t_end: f64,
    /// Middle of the motion, s.
    pub t_mid_swing: f64,
    /// Footprint before, east, north, m.
    pub from: (f64, f64),
    /// Footprint after, east, north, m.
    pub to: (f64, f64),
    /// Horizontal footprint-to-footprint distance, m.
    pub length_m: f64,
    /// Compass heading of the footprint-to-footprint chord, rad (its previous one when the
    /// stride has no length).
    pub heading_rad: f64,
    /// Path heading at the walker's position at mid-swing, rad: the direction of walking, what
    /// a trunk sensor sees there.
    pub path_heading_rad: f64,
}

/// The foot's pose and its derivatives at one instant (navigation frame ENU, z up from the
/// ground).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootPose {
    /// Position of the IMU, m.
    pub p: Vector3<f64>,
    /// Velocity, m/s.
    pub v: Vector3<f64>,
    /// Acceleration, m/s².
    pub a: Vector3<f64>,
    /// Attitude: sensor frame → ENU.
    pub r: Matrix3<f64>,
    /// Angular rate in the sensor frame, rad/s.
    pub w_body: Vector3<f64>,
}

/// One motion of the foot from footprint to footprint.
#[derive(Debug, Clone, Copy)]
struct Motion {
    t0: f64,
    dur: f64,
    from: Vector3<f64>,
    to: Vector3<f64>,
    yaw0: f64,
    yaw1: f64,
    path_heading: f64,
}

/// The foot's whole walk: its motions, and how it looks at any time.
#[derive(Debug, Clone)]
pub struct FootTrack {
    motions: Vec<Motion>,
    start: Vector3<f64>,
    start_yaw: f64,
    clearance: f64,
    pitch: f64,
    /// Added to every time written out, s.
    clock_offset_s: f64,
}

/// A simulated foot-mounted IMU walk.
pub struct FootSimulation {
    /// The foot IMU's samples, as `Record::Imu`, in time order, and the walker's truth: a
    /// foot-only log (writable as x-io CSV with [`crate::sim::formats::write`]).
    pub sim: Simulation,
    /// Every stride of the foot.
    pub strides: Vec<FootStride>,
    /// The foot's trajectory.
    pub track: FootTrack,
}

fn min_jerk(u: f64) -> (f64, f64, f64) {
    let u2 = u * u;
    (
        u2 * u * (10.0 - 15.0 * u + 6.0 * u2),
        30.0 * u2 * (1.0 - u) * (1.0 - u),
        60.0 * u * (1.0 - u) * (1.0 - 2.0 * u),
    )
}

/// 64u³(1 − u)³ and its first two derivatives.
fn bump(u: f64) -> (f64, f64, f64) {
    let w = 1.0 - u;
    let s = 1.0 - 2.0 * u;
    (
        64.0 * u * u * u * w * w * w,
        192.0 * u * u * w * w * s,
        384.0 * u * w * (s * s - u * w),
    )
}

/// The largest value of 64u³(1 − u)³·cos(πu) on [0, 1] (about 0.353, near u = 0.32).
fn pitch_norm() -> f64 {
    (0..=1000)
        .map(|i| {
            let u = f64::from(i) / 1000.0;
            bump(u).0 * libm::cos(PI * u)
        })
        .fold(0.0, f64::max)
}

impl FootTrack {
    /// The pose at simulation time `t` (without the clock offset).
    pub fn pose(&self, t: f64) -> FootPose {
        let i = self.motions.partition_point(|m| m.t0 <= t);
        let rest = |p: Vector3<f64>, yaw: f64| FootPose {
            p,
            v: Vector3::zeros(),
            a: Vector3::zeros(),
            r: rz(FRAC_PI_2 - yaw),
            w_body: Vector3::zeros(),
        };
        let Some(m) = i.checked_sub(1).map(|k| self.motions[k]) else {
            return rest(self.start, self.start_yaw);
        };
        let u = (t - m.t0) / m.dur;
        if u >= 1.0 {
            return rest(m.to, m.yaw1);
        }
        let d = m.dur;
        let (mj, mj1, mj2) = min_jerk(u);
        let (b, b1, b2) = bump(u);
        let dp = m.to - m.from;
        let up = Vector3::z() * self.clearance;
        let p = m.from + dp * mj + up * b;
        let v = (dp * mj1 + up * b1) / d;
        let a = (dp * mj2 + up * b2) / (d * d);
        let dyaw = wrap_pi(m.yaw1 - m.yaw0);
        let yaw = m.yaw0 + dyaw * mj;
        let yaw_rate = dyaw * mj1 / d;
        let (sp, cp) = libm::sincos(PI * u);
        let theta = self.pitch * b * cp;
        let theta_rate = self.pitch * (b1 * cp - PI * b * sp) / d;
        // R = Rz(α)·Ry(θ), α = π/2 − ψ: ω_body = α̇·Ry(θ)ᵀẑ + θ̇·ŷ.
        let alpha_rate = -yaw_rate;
        let (st, ct) = libm::sincos(theta);
        FootPose {
            p,
            v,
            a,
            r: rz(FRAC_PI_2 - yaw) * ry(theta),
            w_body: Vector3::new(-alpha_rate * st, theta_rate, alpha_rate * ct),
        }
    }

    /// Number of motions (strides).
    pub fn len(&self) -> usize {
        self.motions.len()
    }

    /// Whether the foot never moves.
    pub fn is_empty(&self) -> bool {
        self.motions.is_empty()
    }

    /// The clock offset of the scenario, s.
    pub fn clock_offset_s(&self) -> f64 {
        self.clock_offset_s
    }
}

/// A point on the walker's path: time, position, heading.
#[derive(Clone, Copy)]
struct PathPoint {
    t: f64,
    e: f64,
    n: f64,
    psi: f64,
    f: f64,
    run: bool,
}

impl Scenario {
    /// The foot's trajectory for this scenario's walker.
    pub fn foot_track(&self, foot: &FootImu) -> FootTrack {
        let marks = self.path_marks();
        let start_yaw = self.start_heading_deg.to_radians();
        let start = {
            let (s, c) = libm::sincos(start_yaw);
            Vector3::new(foot.lateral_m * c, -foot.lateral_m * s, 0.0)
        };
        FootTrack {
            motions: foot_motions(foot, &marks, start, start_yaw),
            start,
            start_yaw,
            clearance: foot.clearance_m,
            pitch: foot.pitch_deg.to_radians() / pitch_norm(),
            clock_offset_s: self.clock_offset_s,
        }
    }

    /// Walks the path as `truth` does (1 ms midpoint steps), noting the crossings of φ = π
    /// (mod 2π) and the ends of the walking bouts.
    fn path_marks(&self) -> PathMarks {
        let tl = Timeline::new(self);
        let dur = self.duration_s();
        let mut centres = Vec::new(); // φ ≡ 3π (mod 4π): motion centres
        let mut rests = Vec::new(); // φ ≡ π (mod 4π): footprints
        let mut bouts: Vec<(f64, f64, PathPoint)> = Vec::new(); // (start, end, end point)
        let dt = 1e-3;
        let mut hint = 0;
        let (mut e, mut n) = (0.0, 0.0);
        let mut prev = tl.state(0.0, &mut hint);
        let mut bout_start = prev.gait.moving().then_some(0.0);
        let mut t = 0.0;
        let point = |t: f64, e: f64, n: f64, st: &super::State| PathPoint {
            t,
            e,
            n,
            psi: st.psi,
            f: st.f,
            run: st.gait == super::Gait::Run,
        };
        while t < dur {
            let t1 = (t + dt).min(dur);
            let st = tl.state(t1, &mut hint);
            let (e0, n0) = (e, n);
            if st.gait.moving() {
                let mid = tl.state(0.5 * (t + t1), &mut hint.clone());
                let v = self.walker.step_length.length(mid.f) * mid.f;
                let ds = v * (t1 - t);
                e += ds * libm::sin(mid.psi);
                n += ds * libm::cos(mid.psi);
                let shifted = |phi: f64| (phi - PI) / TAU;
                if prev.gait.moving() && shifted(st.phi).floor() > shifted(prev.phi).floor() {
                    let k = shifted(st.phi).floor();
                    let frac = (k * TAU + PI - prev.phi) / (st.phi - prev.phi);
                    let tc = t + frac * (t1 - t);
                    let p = point(tc, e0 + frac * (e - e0), n0 + frac * (n - n0), &st);
                    if (k as i64).rem_euclid(2) == 1 {
                        centres.push(p);
                    } else {
                        rests.push(p);
                    }
                }
                if bout_start.is_none() {
                    bout_start = Some(t);
                }
            } else if let Some(b) = bout_start.take() {
                bouts.push((b, t, point(t, e, n, &prev)));
            }
            prev = st;
            t = t1;
        }
        if let Some(b) = bout_start {
            bouts.push((b, dur, point(dur, e, n, &prev)));
        }
        PathMarks {
            centres,
            rests,
            bouts,
        }
    }

    /// The foot IMU's samples (times with the clock offset), its strides and trajectory, and the
    /// walker's truth: a foot-only walk.
    pub fn generate_foot(&self, foot: &FootImu) -> FootSimulation {
        let track = self.foot_track(foot);
        let mut rng = Rng(self.seed ^ 0xF007_1A1B_5EED_F00D);
        let dur = self.duration_s();
        let gyro_bias = Vector3::from(foot.gyro_bias);
        let gyro_drift = Vector3::from(foot.gyro_bias_drift);
        let accel_bias = Vector3::from(foot.accel_bias);
        let rate = if foot.rate_hz.is_finite() && foot.rate_hz > 0.0 {
            foot.rate_hz
        } else {
            400.0
        };
        let count = (dur * rate).floor() as u64 + 1;
        let mut records = Vec::with_capacity(count as usize);
        for i in 0..count {
            let t = i as f64 / rate;
            let pose = track.pose(t);
            let rt = pose.r.transpose();
            let accel = rt * (pose.a + Vector3::z() * G) + accel_bias + rng.vec3(foot.accel_noise);
            let gyro = pose.w_body + gyro_bias + gyro_drift * t + rng.vec3(foot.gyro_noise);
            records.push(Record::Imu(ImuSample {
                t: t + self.clock_offset_s,
                accel,
                gyro: Some(gyro),
                mag: None,
                orientation: None,
            }));
        }
        let off = self.clock_offset_s;
        let mut strides = Vec::with_capacity(track.motions.len());
        let mut last_heading = wrap_2pi(track.start_yaw);
        for m in &track.motions {
            let (de, dn) = (m.to.x - m.from.x, m.to.y - m.from.y);
            let length_m = libm::hypot(de, dn);
            if length_m > 1e-9 {
                last_heading = heading_of(de, dn);
            }
            strides.push(FootStride {
                t_start: m.t0 + off,
                t_end: m.t0 + m.dur + off,
                t_mid_swing: m.t0 + 0.5 * m.dur + off,
                from: (m.from.x, m.from.y),
                to: (m.to.x, m.to.y),
                length_m,
                heading_rad: last_heading,
                path_heading_rad: wrap_2pi(m.path_heading),
            });
        }
        let truth = self.truth(&Timeline::new(self));
        FootSimulation {
            sim: Simulation { records, truth },
            strides,
            track,
        }
    }
}

/// The marks on the walker's path from which the foot's motions are built.
struct PathMarks {
    /// φ ≡ 3π (mod 4π): the centres of the right foot's motions.
    centres: Vec<PathPoint>,
    /// φ ≡ π (mod 4π): the right foot's footprints.
    rests: Vec<PathPoint>,
    /// The walking bouts: (start, end, the path's point at the end).
    bouts: Vec<(f64, f64, PathPoint)>,
}

/// The right foot's motions, one per stride centred on each motion centre that a bout holds
/// whole, from the footprint before to the next one (or the bout's end), the foot `lateral_m`
/// to the right of the path; it starts at `start` with yaw `start_yaw`.
fn foot_motions(
    foot: &FootImu,
    marks: &PathMarks,
    start: Vector3<f64>,
    start_yaw: f64,
) -> Vec<Motion> {
    let PathMarks {
        centres,
        rests,
        bouts,
    } = marks;
    let right = |p: &PathPoint| {
        let (s, c) = libm::sincos(p.psi);
        Vector3::new(p.e + foot.lateral_m * c, p.n - foot.lateral_m * s, 0.0)
    };
    let mut motions: Vec<Motion> = Vec::new();
    let (mut at, mut yaw) = (start, start_yaw);
    for c in centres {
        let Some(&(b0, b1, end)) = bouts.iter().find(|b| c.t >= b.0 && c.t <= b.1) else {
            continue;
        };
        let share = if c.run {
            foot.rest_share_run
        } else {
            foot.rest_share_walk
        };
        let d = (1.0 - share) * 2.0 / c.f.max(1e-6);
        let (t0, t1) = (c.t - 0.5 * d, c.t + 0.5 * d);
        if t0 < b0 || t1 > b1 || motions.last().is_some_and(|m| m.t0 + m.dur > t0) {
            continue;
        }
        let target = rests
            .iter()
            .find(|r| r.t > c.t && r.t <= b1)
            .copied()
            .unwrap_or(end);
        let to = right(&target);
        motions.push(Motion {
            t0,
            dur: d,
            from: at,
            to,
            yaw0: yaw,
            yaw1: target.psi,
            path_heading: c.psi,
        });
        at = to;
        yaw = target.psi;
    }
    motions
}

impl Scenario {
    /// A two-sensor walk (Strozzi 2017 §4): the pocket phone's records ([`Scenario::generate`])
    /// with the foot IMU's samples merged in time as `Record::Foot`, the walker's truth, and the
    /// foot's strides and trajectory.
    pub fn generate_two_sensor(&self, foot: &FootImu) -> (Simulation, FootSimulation) {
        let mut phone = self.generate();
        let fs = self.generate_foot(foot);
        let feet: Vec<Record> = fs
            .sim
            .records
            .iter()
            .filter_map(|r| match r {
                Record::Imu(s) => Some(Record::Foot(*s)),
                _ => None,
            })
            .collect();
        phone.records = super::gnss::merge_in_time(std::mem::take(&mut phone.records), feet);
        (phone, fs)
    }
}
