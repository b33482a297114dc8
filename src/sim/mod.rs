//! A gait simulator: phone-in-pocket IMU streams with known truth.
//! May import: `engine` and `io`.
//!
//! # Model
//! The walker follows a script of [`Segment`]s (still, handled, walking, running), each with a
//! cadence ramp and a total turn. The step phase φ advances by 2π f dt; a step ends at each
//! vertical-acceleration peak (φ ≡ 0 mod 2π). In the navigation frame (ENU) the phone's
//! acceleration is the sum of:
//! - the pelvis as an inverted pendulum: vertical a_up = A_v cos φ (+ a second harmonic),
//!   forward a_f = −A_f sin φ (forward speed peaks at double support, where a_up peaks);
//! - lateral sway at the stride frequency, A_l sin(φ/2), alternating left and right each step;
//! - waist rotation: the pelvis yaws ±W at the stride frequency, so each step's forward
//!   acceleration points slightly right or left of the path (Basso 2016 §III);
//! - the thigh swing: the pocket sits `lever_m` below the hip and the thigh pitches ±Θ at the
//!   stride frequency, adding its tangential and centripetal acceleration;
//! - the path itself: dv/dt along the path (cadence ramps) and v·dψ/dt across it (turns, with a
//!   raised-cosine yaw rate over the turning segment).
//!
//! The phone's attitude is path yaw ∘ waist yaw ∘ thigh pitch ∘ pocket mount, where the mount
//! holds the phone upright with its screen facing out of the thigh, rotated by an arbitrary
//! `pocket_yaw_deg` about the vertical. Gyroscope readings are the exact angular velocity of that
//! attitude plus bias and noise; accelerometer readings are the specific force R^T(a + g ẑ) plus
//! noise; the magnetometer sees a fixed field (20 µT north, 43 µT down).
//!
//! GNSS, on request ([`GnssSim`]): fixes of the true path at a fixed rate whose error is drawn
//! from the circular normal distribution their reported accuracy describes (a 68 % radius), a
//! share of outliers that their accuracy does not announce, and outages. With GNSS the phone's
//! attitude and magnetometer refer to magnetic north (declination from the World Magnetic
//! Model at the origin, for the date [`Scenario::clock_offset_s`] puts the walk on), and the OS
//! heading may carry a constant bias ([`Sensors::os_yaw_bias_deg`]).
//! On request the fixes carry a real phone's error shapes instead ([`GnssErrors`],
//! `gnss_errors`): a multipath bias correlated in time, urban canyons, an optimistic accuracy, a
//! stale first fix, wander while standing, latency and a hold at walk start.
//!
//! A foot-mounted IMU on the same walker, on request: [`foot`].
//!
//! Opt-in, for the pocket's own signal (Munoz Diaz 2015), none of which changes a scenario that
//! does not ask for it: a realistic thigh ([`ThighModel::Gait`], [`thigh`]: the paper's pitch
//! shape tied to the stride, stairs and sitting; its angle replaces the sinusoid in the attitude,
//! the rate and the lever arm), flights of stairs and sitting ([`Gait::StairsUp`],
//! [`Gait::StairsDown`], [`Gait::Sit`]; heights, tread-paced speed and hip drop in [`body`]),
//! eight pocket poses in either front pocket ([`PocketPose`]), a barometer ([`BaroSim`]), and a
//! truth with heights, floors, activities and the thigh's pitch ([`Truth`]).
//!
//! Opt-in, for the first and the last steps: real-shaped ends ([`ends`],
//! [`Scenario::real_ends`]): the standing sway, the first and the last steps at half strength,
//! the body settling, and the phone taken out of the pocket ([`Gait::TakeOut`]).
//!
//! Opt-in, for the heading across a change of carrying mode: the phone moved from one
//! mode to another while the walk goes on ([`Scenario::switches`], [`carry::Switch`]).
//!
//! Sampling is irregular on request: a nominal rate with uniform jitter, or a fixed interval,
//! with gaps removed. Noise comes from a seeded SplitMix64 generator with Box–Muller normals over
//! `libm`, so a scenario gives bit-identical samples natively and in WebAssembly.

mod baro;
pub mod body;
pub mod carry;
pub mod ends;
pub mod foot;
pub mod formats;
mod gnss;
mod gnss_errors;
mod kinematics;
pub mod pose;
mod rng;
pub mod scenarios;
mod script;
pub mod thigh;
mod truth;

pub use baro::{standard_pressure_hpa, BaroSim};
pub use carry::Carry;
pub use foot::{FootImu, FootSimulation, FootStride};
pub use gnss::GnssSim;
pub use gnss_errors::{
    Canyon, GnssErrors, Multipath, StaleFix, CANYON_RAMP_S, HOLD_AFTER_STANDING_S,
};
pub use pose::PocketPose;
pub use script::{Gait, Segment, Stair};
pub use thigh::{GaitThigh, ThighModel};
pub use truth::{Truth, TruthStep};

use crate::engine::step_length::StepLengthProfile;
use crate::engine::types::ImuSample;
use crate::engine::Record;
use gnss::merge_in_time;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use rng::Rng;
use std::f64::consts::{PI, TAU};

/// Standard gravity used by the simulator, m/s².
const G: f64 = crate::engine::orientation::G0;

/// The walker's body.
#[derive(Debug, Clone, PartialEq)]
pub struct Walker {
    /// The true step-length law.
    pub step_length: StepLengthProfile,
    /// Waist yaw amplitude, degrees.
    pub waist_yaw_deg: f64,
    /// Thigh pitch amplitude, degrees.
    pub thigh_pitch_deg: f64,
    /// Distance from the hip joint to the pocket, m.
    pub lever_m: f64,
    /// Lateral sway amplitude, m/s².
    pub sway: f64,
    /// How the thigh pitches (the historic sinusoid by default).
    pub thigh: ThighModel,
}

impl Default for Walker {
    fn default() -> Self {
        Walker {
            step_length: StepLengthProfile::default(),
            waist_yaw_deg: 6.0,
            thigh_pitch_deg: 20.0,
            lever_m: 0.12,
            sway: 0.6,
            thigh: ThighModel::Sinusoid,
        }
    }
}

/// The phone's sensors and sampling.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensors {
    /// Nominal rate, Hz.
    pub rate_hz: f64,
    /// Uniform jitter of each interval, as a fraction of the nominal interval.
    pub jitter: f64,
    /// Intervals with no samples, (start, end) s.
    pub gaps: Vec<(f64, f64)>,
    /// Accelerometer white noise, m/s² (1σ).
    pub accel_noise: f64,
    /// Gyroscope white noise, rad/s (1σ).
    pub gyro_noise: f64,
    /// Gyroscope bias, rad/s, device frame.
    pub gyro_bias: [f64; 3],
    /// Magnetometer noise, µT (1σ).
    pub mag_noise: f64,
    /// Round acceleration to this step, m/s² (Chrome's virtual sensors: 0.1).
    pub accel_quantum: Option<f64>,
    /// Include the gyroscope.
    pub gyro: bool,
    /// Include the magnetometer.
    pub mag: bool,
    /// Include the OS orientation quaternion.
    pub os_orientation: bool,
    /// Yaw error of the OS orientation, degrees (1σ, slowly varying).
    pub os_yaw_error_deg: f64,
    /// Constant yaw error of the OS orientation, degrees: the OS heading reads this much
    /// clockwise (east) of the truth.
    pub os_yaw_bias_deg: f64,
    /// The barometer, if the phone has one on.
    pub barometer: Option<BaroSim>,
}

impl Default for Sensors {
    fn default() -> Self {
        Sensors {
            rate_hz: 100.0,
            jitter: 0.0,
            gaps: Vec::new(),
            accel_noise: 0.08,
            gyro_noise: 0.005,
            gyro_bias: [0.004, -0.003, 0.002],
            mag_noise: 0.5,
            accel_quantum: None,
            gyro: true,
            mag: true,
            os_orientation: true,
            os_yaw_error_deg: 0.0,
            os_yaw_bias_deg: 0.0,
            barometer: None,
        }
    }
}

/// A complete scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// The script.
    pub segments: Vec<Segment>,
    /// The body.
    pub walker: Walker,
    /// The sensors.
    pub sensors: Sensors,
    /// Phone yaw about the vertical inside the pocket, degrees.
    pub pocket_yaw_deg: f64,
    /// Initial compass heading of the path, degrees.
    pub start_heading_deg: f64,
    /// Noise seed.
    pub seed: u64,
    /// The GNSS receiver, if the phone has one on.
    pub gnss: Option<GnssSim>,
    /// Added to every time written out (samples, fixes, truth), s: a Unix time puts the walk on
    /// a date (for the magnetic declination).
    pub clock_offset_s: f64,
    /// How the phone sits in the pocket (before `pocket_yaw_deg`).
    pub pose: PocketPose,
    /// The phone is in the left front pocket (default the right one).
    pub left_pocket: bool,
    /// Height of one floor, m, for the truth's floor numbers (None: no floors).
    pub floor_height_m: Option<f64>,
    /// How the phone is carried ([`Carry::Pocket`]: `pose`, `left_pocket` and
    /// `pocket_yaw_deg` say how it sits there; the other modes ignore them).
    pub carry: Carry,
    /// Real-shaped starts and stops ([`ends`]): the standing sway, the first and the last steps
    /// at half strength, the body settling, the phone taken out ([`Gait::TakeOut`]).
    pub real_ends: bool,
    /// Changes of carrying mode mid-walk, in time order ([`carry::Switch`]; `carry` is the
    /// first mode).
    pub switches: Vec<carry::Switch>,
}

impl Scenario {
    /// A scenario with default body and sensors.
    pub fn new(segments: Vec<Segment>) -> Self {
        Scenario {
            segments,
            walker: Walker::default(),
            sensors: Sensors::default(),
            pocket_yaw_deg: 30.0,
            start_heading_deg: 0.0,
            seed: 1,
            gnss: None,
            clock_offset_s: 0.0,
            pose: PocketPose::UprightOut,
            left_pocket: false,
            floor_height_m: None,
            carry: Carry::Pocket,
            real_ends: false,
            switches: Vec::new(),
        }
    }

    /// The same scenario with the realistic thigh ([`ThighModel::Gait`], default parameters).
    pub fn with_gait_thigh(mut self) -> Self {
        self.walker.thigh = ThighModel::Gait(GaitThigh::default());
        self
    }

    /// Total duration, s.
    pub fn duration_s(&self) -> f64 {
        self.timed_segments().iter().map(|s| s.duration_s).sum()
    }

    /// The segments as walked: the last moving segment of each bout (before a stop, or at the
    /// end) lasts so that the bout holds a whole number of steps. A bout starts half a cycle
    /// before its first step ends and so ends half a cycle after its last one: the walker comes
    /// to rest after a completed step, not part-way into the next.
    pub fn timed_segments(&self) -> Vec<Segment> {
        let mut out = self.segments.clone();
        let mut cycles = 0.0;
        for i in 0..out.len() {
            let s = out[i];
            if !s.gait.moving() {
                cycles = 0.0;
                continue;
            }
            let f = 0.5 * (s.cadence_hz.0 + s.cadence_hz.1);
            let ends_bout = out.get(i + 1).map_or(true, |n| !n.gait.moving());
            if ends_bout && f > 0.0 {
                let whole = (cycles + s.duration_s * f)
                    .round()
                    .max(cycles.floor() + 1.0);
                out[i].duration_s = (whole - cycles) / f;
            }
            cycles += out[i].duration_s * f;
        }
        out
    }
}

/// A generated walk.
pub struct Simulation {
    /// The samples, in time order.
    pub records: Vec<Record>,
    /// What really happened.
    pub truth: Truth,
}

/// Kinematic state at one instant.
struct State {
    gait: Gait,
    /// Step phase, rad (peaks of a_up at multiples of 2π).
    phi: f64,
    /// Cadence, Hz.
    f: f64,
    /// Cadence rate, Hz/s.
    fdot: f64,
    /// Path heading (compass), rad, its rate and its acceleration.
    psi: f64,
    psi_dot: f64,
    psi_ddot: f64,
    /// Time into a still/handled segment, s.
    tau: f64,
}

/// Segment timeline with phase continuity.
struct Timeline {
    segs: Vec<(f64, Segment, f64, f64)>, // (t_start, seg, phi_start, psi_start)
}

impl Timeline {
    fn new(sc: &Scenario) -> Self {
        let mut t = 0.0;
        let mut phi = PI;
        let mut psi = sc.start_heading_deg.to_radians();
        let mut segs = Vec::new();
        let mut prev_moving = false;
        for s in &sc.timed_segments() {
            if s.gait.moving() && !prev_moving {
                // Start each bout half a cycle before a step ends.
                phi = PI + TAU * (phi / TAU).floor();
            }
            segs.push((t, *s, phi, psi));
            if s.gait.moving() {
                phi += TAU * s.duration_s * 0.5 * (s.cadence_hz.0 + s.cadence_hz.1);
            }
            psi += s.turn_deg.to_radians();
            t += s.duration_s;
            prev_moving = s.gait.moving();
        }
        Timeline { segs }
    }

    /// The state at `t`, found by bisection (for evaluations on either side of `t`).
    fn state_at(&self, t: f64) -> State {
        let mut i = self.segs.partition_point(|s| s.0 <= t).saturating_sub(1);
        self.state(t, &mut i)
    }

    fn state(&self, t: f64, hint: &mut usize) -> State {
        while *hint + 1 < self.segs.len() && t >= self.segs[*hint + 1].0 {
            *hint += 1;
        }
        let (t0, s, phi0, psi0) = self.segs[*hint];
        let tau = (t - t0).clamp(0.0, s.duration_s);
        let fdot = (s.cadence_hz.1 - s.cadence_hz.0) / s.duration_s;
        // Turns follow a raised-cosine yaw rate, zero at both ends of the segment: a walker's
        // yaw rate rises and falls smoothly over a turn, and so does the centripetal
        // acceleration v·ψ̇. (A constant rate switched on and off made it jump by ≈ 1.3 m/s²
        // at a 90° corner over three steps, which leaks into the first harmonic of the step.)
        let turn = s.turn_deg.to_radians();
        let x = tau / s.duration_s;
        let (sx, cx) = libm::sincos(TAU * x);
        let psi = psi0 + turn * (x - sx / TAU);
        let psi_dot = turn / s.duration_s * (1.0 - cx);
        let psi_ddot = turn / (s.duration_s * s.duration_s) * TAU * sx;
        let (f, phi) = if s.gait.moving() {
            (
                s.cadence_hz.0 + fdot * tau,
                phi0 + TAU * (s.cadence_hz.0 * tau + 0.5 * fdot * tau * tau),
            )
        } else {
            (0.0, phi0)
        };
        State {
            gait: s.gait,
            phi,
            f,
            fdot: if s.gait.moving() { fdot } else { 0.0 },
            psi,
            psi_dot,
            psi_ddot,
            tau,
        }
    }
}

/// Gait accelerations amplitudes (vertical, forward, lateral) for a gait and cadence.
fn amplitudes(gait: Gait, f: f64, sway: f64) -> (f64, f64, f64) {
    match gait {
        Gait::Walk => {
            let av = 3.2 + 2.0 * (f - 1.8);
            (av, 0.5 * av, sway)
        }
        Gait::Run => {
            let av = 11.5 + 2.0 * (f - 3.0);
            (av, 0.4 * av, 1.6 * sway)
        }
        _ => (0.0, 0.0, 0.0),
    }
}

fn rz(a: f64) -> Matrix3<f64> {
    let (s, c) = libm::sincos(a);
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

fn ry(a: f64) -> Matrix3<f64> {
    let (s, c) = libm::sincos(a);
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

fn rx(a: f64) -> Matrix3<f64> {
    let (s, c) = libm::sincos(a);
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

impl Scenario {
    /// The phone-in-body mount: upright (device y up), screen facing out of the right thigh,
    /// then yawed by `pocket_yaw_deg` about the vertical. Body frame: x forward, y left, z up.
    /// Other poses and the left pocket: [`PocketPose`].
    pub fn mount(&self) -> Matrix3<f64> {
        self.carry.mount().unwrap_or_else(|| self.pocket_mount())
    }

    /// The pocket's mount, whatever `carry` says.
    fn pocket_mount(&self) -> Matrix3<f64> {
        let base = self.pose.mount(self.left_pocket);
        rz(self.pocket_yaw_deg.to_radians()) * base
    }

    /// The slow motions of the script (bouts, flights, sitting, activities).
    pub(super) fn body(&self) -> body::Body {
        let (tr, drop) = match &self.walker.thigh {
            ThighModel::Gait(g) => (g.transition_s, g.sit_drop_m),
            ThighModel::Sinusoid => (GaitThigh::default().transition_s, 0.0),
        };
        body::Body::new(&self.timed_segments(), tr, drop)
    }

    /// The thigh's true pitch at `t` (simulation time), degrees, positive with the knee forward.
    fn thigh_deg(&self, tl: &Timeline, body: &body::Body, t: f64) -> f64 {
        let st = tl.state_at(t);
        let g = match &self.walker.thigh {
            ThighModel::Sinusoid => {
                if !st.gait.moving() {
                    return 0.0;
                }
                let k = if st.gait == Gait::Run { 1.4 } else { 1.0 };
                return -k * self.walker.thigh_pitch_deg * libm::cos(0.5 * st.phi);
            }
            ThighModel::Gait(g) => g,
        };
        let mut theta = 0.0;
        let e = body.walk_envelope(t);
        if e > 0.0 && st.f > 0.0 {
            // Stride phase: 0 at the pocket leg's heel strike (φ ≡ 0 mod 4π on the right).
            let mut s = st.phi / (2.0 * TAU) + if self.left_pocket { 0.5 } else { 0.0 };
            s -= libm::floor(s);
            let mut dh = g.level_amplitude_deg(2.0 * self.walker.step_length.length(st.f));
            if st.gait == Gait::Run {
                dh = dh.min(g.run_max_deg);
            }
            let (mut level, mut stairs) = (1.0, 0.0);
            for (w, fl) in body.flights_at(t) {
                let shape = if fl.up {
                    thigh::Shape::Up
                } else {
                    thigh::Shape::Down
                };
                level -= w;
                stairs += w * g.pitch_deg(shape, s, dh, fl.riser_m);
            }
            theta = e * (level * g.pitch_deg(thigh::Shape::Level, s, dh, 0.0) + stairs);
        }
        theta + body.sit(t).0 * g.sit_deg_at(t)
    }

    /// Generates the samples and the truth.
    pub fn generate(&self) -> Simulation {
        let tl = Timeline::new(self);
        let body = self.body();
        let extended = self.real_ends
            || !self.switches.is_empty()
            || matches!(self.walker.thigh, ThighModel::Gait(_))
            || !body.flights.is_empty()
            || !body.sits.is_empty();
        let mut rng = Rng(self.seed ^ 0x5EED_0F0D);
        let mount = self.mount();
        let dur = self.duration_s();
        let in_gap = |t: f64| self.sensors.gaps.iter().any(|&(a, b)| t > a && t < b);
        // Magnetic north lies `declination` east of true north; the OS attitude and the
        // magnetometer refer to it, and the OS heading carries its constant bias.
        let declination = self
            .gnss
            .as_ref()
            .filter(|g| g.magnetic_north)
            .and_then(|g| {
                let date = (self.clock_offset_s > 1.5e9).then_some(self.clock_offset_s);
                crate::engine::fusion::wmm_declination_deg(g.origin.0, g.origin.1, g.origin.2, date)
            })
            .map_or(0.0, |d| d.0.to_radians());
        let north_turn = declination - self.sensors.os_yaw_bias_deg.to_radians();
        let (sd, cd) = libm::sincos(declination);
        let mag_world = Vector3::new(20.0 * sd, 20.0 * cd, -43.0);
        let bias = Vector3::from(self.sensors.gyro_bias);
        let nominal = 1.0 / self.sensors.rate_hz;
        let mut records = Vec::with_capacity((dur * self.sensors.rate_hz) as usize + 1);
        let mut hint = 0;
        let mut t = 0.0;
        let mut yaw_err = 0.0;
        while t <= dur {
            if !in_gap(t) {
                let st = tl.state(t, &mut hint);
                let ext = extended.then_some((&tl, &body, t));
                let (r, w_world, a) = self.kinematics(&st, &mount, ext);
                let rt = r.transpose();
                let mut accel =
                    rt * (a + Vector3::new(0.0, 0.0, G)) + rng.vec3(self.sensors.accel_noise);
                if let Some(q) = self.sensors.accel_quantum {
                    accel = accel.map(|v| (v / q).round() * q);
                }
                let gyro = self
                    .sensors
                    .gyro
                    .then(|| rt * w_world + bias + rng.vec3(self.sensors.gyro_noise));
                let mag = self
                    .sensors
                    .mag
                    .then(|| rt * mag_world + rng.vec3(self.sensors.mag_noise));
                yaw_err = 0.999 * yaw_err
                    + 0.045 * self.sensors.os_yaw_error_deg.to_radians() * rng.normal();
                let orientation = self.sensors.os_orientation.then(|| {
                    let rot = Rotation3::from_matrix_unchecked(rz(yaw_err + north_turn) * r);
                    UnitQuaternion::from_rotation_matrix(&rot)
                });
                records.push(Record::Imu(ImuSample {
                    t: t + self.clock_offset_s,
                    accel,
                    gyro,
                    mag,
                    orientation,
                }));
            }
            let j = if self.sensors.jitter > 0.0 {
                self.sensors.jitter * (2.0 * rng.uniform() - 1.0)
            } else {
                0.0
            };
            t += nominal * (1.0 + j);
        }
        let mut truth = self.truth(&tl);
        if let Some(g) = &self.gnss {
            let fixes = self.fixes(g, &truth);
            records = merge_in_time(records, fixes);
            truth.frame = Some(crate::engine::geo::LocalFrame::new(
                g.origin.0, g.origin.1, g.origin.2,
            ));
        }
        if let Some(b) = &self.sensors.barometer {
            let p = b.samples(
                self.seed,
                dur,
                self.clock_offset_s,
                &self.sensors.gaps,
                |t| body.phone_height(t),
            );
            records = merge_in_time(records, p);
        }
        Simulation { records, truth }
    }
}
