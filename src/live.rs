//! Live input: browser sensor events into the engine's records. This is the one place where the
//! platforms' quirks are converted; everything after it is the same pipeline uploaded logs go
//! through. Pure Rust (the wasm glue in [`crate::web`] only passes numbers), so it is tested
//! natively and in the browser alike.
//!
//! # `devicemotion`, as browsers deliver it
//! - `accelerationIncludingGravity`, m/s², device frame (x right, y top, z out of the screen).
//!   Chromium follows the specification: a phone lying face up reads z = +9.81. Safari on iOS
//!   reports the opposite sign (z = −9.81 face up), so iOS values are negated
//!   ([`Platform::to_android`]).
//! - `rotationRate`, **degrees** per second: `alpha` about the device x axis, `beta` about y,
//!   `gamma` about z (w3c/deviceorientation #44). Checked in headless Chromium with its virtual
//!   gyroscope: a reading of (1, 0.5, 0.25) rad/s arrives as alpha 57.3, beta 28.6, gamma 14.3
//!   (`tests/e2e`). Converted to rad/s.
//! - `interval`: milliseconds in Chromium (a fixed 16 on desktop), **seconds** on iOS. It is
//!   only reported, never used for time: the time of a sample is `event.timeStamp` (ms on the
//!   page's clock), converted to seconds.
//!
//! # `deviceorientation(absolute)`
//! `alpha`, `beta`, `gamma` in degrees are the intrinsic Z-X'-Y'' angles of the W3C
//! specification: the device → earth rotation is R = Rz(α)·Rx(β)·Ry(γ), the earth frame being
//! East-North-Up when the event is absolute (alpha = 0 with the top of the device to the north;
//! alpha grows counter-clockwise, so the compass heading of the top is 360° − α).

use crate::engine::pipeline::{Pipeline, PipelineConfig, Record};
use crate::engine::types::{ConfigError, GnssFix, ImuSample, InputError};
pub use crate::io::import::Platform;
use nalgebra::{UnitQuaternion, Vector3};

/// One `devicemotion` event, fields as the browser gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionEvent {
    /// `event.timeStamp`, ms.
    pub time_stamp_ms: f64,
    /// `accelerationIncludingGravity` (x, y, z), m/s², platform sign.
    pub accel: Option<[f64; 3]>,
    /// `rotationRate` (alpha, beta, gamma), deg/s.
    pub rotation_rate_deg_s: Option<[f64; 3]>,
    /// `interval`: ms (Chromium) or s (iOS).
    pub interval: Option<f64>,
}

/// A motion event in the engine's units and conventions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Time, s.
    pub t: f64,
    /// Specific force including gravity, m/s², Android sign, device frame.
    pub accel: Vector3<f64>,
    /// Angular rate about x, y, z, rad/s.
    pub gyro: Option<Vector3<f64>>,
    /// The interval the browser reports, s.
    pub interval_s: Option<f64>,
}

/// Why a live event was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum LiveError {
    /// The event lacks acceleration (the device has no accelerometer, or the browser withholds
    /// it).
    NoAcceleration,
    /// A value is not a finite number.
    NonFinite(&'static str),
    /// The engine refused the sample.
    Engine(InputError),
}

impl std::fmt::Display for LiveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LiveError::NoAcceleration => write!(f, "the motion event carries no acceleration"),
            LiveError::NonFinite(field) => write!(f, "`{field}` is not a finite number"),
            LiveError::Engine(e) => write!(f, "{e}"),
        }
    }
}

/// Converts a `devicemotion` event (see the module documentation for every rule).
pub fn normalise_motion(ev: &MotionEvent, platform: Platform) -> Result<Motion, LiveError> {
    let finite = |v: &[f64], field| {
        if v.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(LiveError::NonFinite(field))
        }
    };
    finite(&[ev.time_stamp_ms], "timeStamp")?;
    let a = ev.accel.ok_or(LiveError::NoAcceleration)?;
    finite(&a, "accelerationIncludingGravity")?;
    let gyro = match ev.rotation_rate_deg_s {
        Some(r) => {
            finite(&r, "rotationRate")?;
            Some(Vector3::new(r[0], r[1], r[2]) * (std::f64::consts::PI / 180.0))
        }
        None => None,
    };
    let interval_s = ev
        .interval
        .filter(|i| i.is_finite() && *i > 0.0)
        .map(|i| match platform {
            Platform::Ios => i,
            Platform::Android => i * 1e-3,
        });
    Ok(Motion {
        t: ev.time_stamp_ms * 1e-3,
        accel: platform.to_android(Vector3::new(a[0], a[1], a[2])),
        gyro,
        interval_s,
    })
}

/// The device → earth attitude of a `deviceorientation` event (degrees), R = Rz(α)·Rx(β)·Ry(γ).
pub fn orientation_quaternion(alpha: f64, beta: f64, gamma: f64) -> UnitQuaternion<f64> {
    let d = std::f64::consts::PI / 180.0;
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), alpha * d)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), beta * d)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), gamma * d)
}

/// The W3C angles (degrees) of a device → earth attitude: the inverse of
/// [`orientation_quaternion`], with β in [−90°, 90°] (an equivalent decomposition to the
/// specification's β in [−180°, 180°), γ in [−90°, 90°)).
pub fn orientation_angles(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let r = q.to_rotation_matrix();
    let m = r.matrix();
    let beta = libm::asin(m[(2, 1)].clamp(-1.0, 1.0));
    let alpha = libm::atan2(-m[(0, 1)], m[(1, 1)]);
    let gamma = libm::atan2(-m[(2, 0)], m[(2, 2)]);
    let d = 180.0 / std::f64::consts::PI;
    (alpha * d, beta * d, gamma * d)
}

/// What the live page shows.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Readouts {
    /// Steps counted.
    pub steps: usize,
    /// Distance walked, m.
    pub distance_m: f64,
    /// Cadence of the last step, Hz.
    pub cadence_hz: Option<f64>,
    /// Heading of the last step, degrees from north.
    pub heading_deg: Option<f64>,
    /// `still`, `walking` or `running`.
    pub motion: Option<&'static str>,
    /// Accuracy of the latest fix, m.
    pub gnss_accuracy_m: Option<f64>,
    /// Motion events received per second over the last two seconds.
    pub sample_rate_hz: f64,
    /// Gaps in the input (page hidden, sensor paused).
    pub gaps: u64,
    /// Events refused (with the reason of the last one).
    pub refused: u64,
    /// The last refusal.
    pub last_error: Option<String>,
    /// Whether the GNSS receiver should be on now (energy-saving mode).
    pub gnss_wanted: bool,
}

/// A live session: the pipeline, the latest attitude, and the recording in pdr-log lines.
pub struct LiveSession {
    pipeline: Pipeline,
    platform: Platform,
    attitude: Option<(f64, UnitQuaternion<f64>, bool)>,
    attitude_written: bool,
    log: String,
    recent: std::collections::VecDeque<f64>,
    refused: u64,
    last_error: Option<String>,
}

impl LiveSession {
    /// A session with the given configuration, for a platform's conventions.
    pub fn new(cfg: PipelineConfig, platform: Platform) -> Result<Self, ConfigError> {
        Ok(LiveSession {
            pipeline: Pipeline::new(cfg)?,
            platform,
            attitude: None,
            attitude_written: true,
            log: crate::io::pdrlog::preamble(),
            recent: std::collections::VecDeque::new(),
            refused: 0,
            last_error: None,
        })
    }

    /// The pipeline (track, fixes, diagnostics).
    pub fn pipeline(&self) -> &Pipeline {
        &self.pipeline
    }

    fn refuse(&mut self, e: LiveError) -> LiveError {
        self.refused += 1;
        self.last_error = Some(e.to_string());
        e
    }

    /// Feeds a `devicemotion` event; returns how many steps it completed.
    pub fn push_motion(&mut self, ev: &MotionEvent) -> Result<usize, LiveError> {
        let m = normalise_motion(ev, self.platform).map_err(|e| self.refuse(e))?;
        // The attitude rides on the first sample after it arrives (the engine holds it for
        // the samples after that); an absolute attitude wins over a relative one.
        let orientation = match self.attitude {
            Some((_, q, _)) if !self.attitude_written => Some(q),
            _ => None,
        };
        let s = ImuSample {
            t: m.t,
            accel: m.accel,
            gyro: m.gyro,
            mag: None,
            orientation,
        };
        let n = match self.pipeline.push_imu(&s) {
            Ok(steps) => steps.len(),
            Err(e) => return Err(self.refuse(LiveError::Engine(e))),
        };
        self.attitude_written = true;
        self.log.push_str(&crate::io::pdrlog::line(&Record::Imu(s)));
        self.recent.push_back(m.t);
        while self.recent.front().is_some_and(|&t0| t0 < m.t - 2.0) {
            self.recent.pop_front();
        }
        Ok(n)
    }

    /// Feeds a `deviceorientation` or `deviceorientationabsolute` event (degrees). Relative
    /// events are ignored once absolute ones have come.
    pub fn push_orientation(
        &mut self,
        time_stamp_ms: f64,
        alpha: f64,
        beta: f64,
        gamma: f64,
        absolute: bool,
    ) {
        if ![time_stamp_ms, alpha, beta, gamma]
            .iter()
            .all(|x| x.is_finite())
        {
            let _ = self.refuse(LiveError::NonFinite("deviceorientation"));
            return;
        }
        if !absolute && self.attitude.is_some_and(|a| a.2) {
            return;
        }
        self.attitude = Some((
            time_stamp_ms * 1e-3,
            orientation_quaternion(alpha, beta, gamma),
            absolute,
        ));
        self.attitude_written = false;
    }

    /// Feeds a geolocation fix (time in ms on the page's clock).
    pub fn push_fix(&mut self, f: &GnssFix) -> Result<(), LiveError> {
        self.pipeline
            .push_gnss(f)
            .map_err(|e| self.refuse(LiveError::Engine(e)))?;
        self.log
            .push_str(&crate::io::pdrlog::line(&Record::Gnss(*f)));
        Ok(())
    }

    /// The page was hidden (or the sensors paused) between two times, ms.
    pub fn mark_gap(&mut self, t0_ms: f64, t1_ms: f64) {
        let (t0, t1) = (t0_ms * 1e-3, t1_ms * 1e-3);
        self.pipeline.mark_gap(t0, t1);
        if t1 > t0 {
            self.log
                .push_str(&crate::io::pdrlog::line(&Record::Gap(t0, t1)));
        }
    }

    /// The recording since the last call, pdr-log lines (the first call starts with the
    /// version tag): the page appends it to storage in small batches.
    pub fn take_log(&mut self) -> String {
        std::mem::take(&mut self.log)
    }

    /// What the page shows now.
    pub fn readouts(&self) -> Readouts {
        let d = self.pipeline.diagnostics();
        let last = self.pipeline.track().last();
        let span = match (self.recent.front(), self.recent.back()) {
            (Some(a), Some(b)) if b > a => b - a,
            _ => 0.0,
        };
        let now = d.time_span.map_or(0.0, |s| s.1);
        Readouts {
            steps: self.pipeline.track().len(),
            distance_m: d.distance_m,
            cadence_hz: last.map(|s| s.freq_hz),
            heading_deg: last.and_then(|s| s.heading_rad).map(f64::to_degrees),
            motion: d.motion.map(|m| m.as_str()),
            gnss_accuracy_m: self.pipeline.fixes().last().map(|f| f.h_accuracy_m),
            sample_rate_hz: if span > 0.0 {
                (self.recent.len() - 1) as f64 / span
            } else {
                0.0
            },
            gaps: d.gaps,
            refused: self.refused,
            last_error: self.last_error.clone(),
            gnss_wanted: self.pipeline.gnss_wanted(now),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ios_and_android_events_give_the_same_sample() {
        let android = MotionEvent {
            time_stamp_ms: 1500.0,
            accel: Some([0.3, -0.2, 9.81]),
            rotation_rate_deg_s: Some([57.2958, 0.0, -28.6479]),
            interval: Some(16.0),
        };
        let ios = MotionEvent {
            accel: Some([-0.3, 0.2, -9.81]),
            interval: Some(0.016),
            ..android
        };
        let a = normalise_motion(&android, Platform::Android).unwrap();
        let i = normalise_motion(&ios, Platform::Ios).unwrap();
        assert_eq!(a, i);
        assert_eq!(a.t, 1.5);
        assert_eq!(a.interval_s, Some(0.016));
        // alpha is about x, gamma about z, in deg/s.
        let g = a.gyro.unwrap();
        assert!((g.x - 1.0).abs() < 1e-5 && g.y == 0.0 && (g.z + 0.5).abs() < 1e-5);
        assert_eq!(
            normalise_motion(
                &MotionEvent {
                    accel: None,
                    ..android
                },
                Platform::Android
            ),
            Err(LiveError::NoAcceleration)
        );
        assert!(normalise_motion(
            &MotionEvent {
                accel: Some([f64::NAN, 0.0, 9.8]),
                ..android
            },
            Platform::Android
        )
        .is_err());
    }

    #[test]
    fn angles_round_trip() {
        for (a, b, g) in [(10.0, 20.0, 30.0), (250.0, -60.0, 80.0), (0.0, 89.0, -45.0)] {
            let q = orientation_quaternion(a, b, g);
            let (a2, b2, g2) = orientation_angles(&q);
            assert!(q.angle_to(&orientation_quaternion(a2, b2, g2)) < 1e-9);
        }
    }

    #[test]
    fn orientation_angles_follow_the_specification() {
        // Flat, face up, alpha 90°: the top of the device points west.
        let q = orientation_quaternion(90.0, 0.0, 0.0);
        let top = q * Vector3::y();
        assert!((top - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12);
        // Upright (beta 90°): the screen faces south, the top points up.
        let q = orientation_quaternion(0.0, 90.0, 0.0);
        assert!((q * Vector3::y() - Vector3::z()).norm() < 1e-12);
        assert!((q * Vector3::z() - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12);
        // Rolled right (gamma 90°): the screen faces east, the device's x axis points down.
        let q = orientation_quaternion(0.0, 0.0, 90.0);
        assert!((q * Vector3::x() - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12);
    }
}
