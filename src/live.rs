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

use crate::engine::orientation::{OrientationSource, HOLD_S};
use crate::engine::pipeline::{Pipeline, PipelineConfig};
use crate::engine::replay::feed;
use crate::engine::types::Record;
use crate::engine::types::{ConfigError, GnssFix, ImuSample, InputError};
pub use crate::io::import::Platform;
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::VecDeque;

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

/// The `alpha` (degrees, W3C convention) of an iOS `deviceorientation` event from its
/// `webkitCompassHeading`. Safari's `alpha` is relative to an arbitrary start; the compass
/// heading is degrees clockwise from magnetic north of the top of the *interface*, so the
/// heading of the device's top adds the screen orientation angle (`screen.orientation.angle`,
/// 90 when the interface is turned a quarter counter-clockwise from portrait). The W3C `alpha`
/// grows counter-clockwise: α = 360° − heading. Not verified on a real iPhone here.
pub fn ios_compass_alpha(compass_heading_deg: f64, screen_angle_deg: f64) -> f64 {
    (360.0 - (compass_heading_deg + screen_angle_deg)).rem_euclid(360.0)
}

/// How long motion waits, from the first event, for an attitude before the session goes on
/// without one (and the engine on the gyroscope alone): Chromium and Safari start both
/// streams together, so a wait is short, and the first sample decides the orientation source.
pub const ATTITUDE_WAIT_S: f64 = 1.0;

/// The span of the scrolling vertical-acceleration view, s.
pub const SCOPE_S: f64 = 10.0;

/// One sample of the scrolling view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScopeSample {
    /// Time, s.
    pub t: f64,
    /// Vertical linear acceleration, m/s².
    pub up: f64,
    /// PLL output cos φ.
    pub pll: Option<f64>,
}

/// Where the input stopped and resumed.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GapMark {
    /// Last sample before the gap, s.
    pub t0: f64,
    /// First time after it, s.
    pub t1: f64,
    /// Position of the track during the gap (PDR frame), m.
    pub east_m: f64,
    /// See `east_m`.
    pub north_m: f64,
}

/// What the live view keeps of the samples as they pass: the scrolling signal and the gaps.
#[derive(Debug, Clone, Default)]
struct View {
    last_t: Option<f64>,
    gaps_seen: u64,
    gap_marks: Vec<GapMark>,
    scope: VecDeque<ScopeSample>,
}

impl View {
    /// Notes a record the pipeline accepted: a gap the engine counted (a `gap` record, or a
    /// pause it found in the samples themselves), and each sample's vertical acceleration and
    /// PLL output for the scrolling view.
    fn observe(&mut self, p: &Pipeline, r: &Record) {
        let t = match *r {
            Record::Imu(s) => s.t,
            Record::Gap(_, t1) => t1,
            Record::Gnss(_) => return,
        };
        let gaps = p.diagnostics().gaps;
        if gaps > self.gaps_seen {
            let t0 = match *r {
                Record::Gap(t0, _) => t0,
                _ => self.last_t.unwrap_or(t),
            };
            self.gaps_seen = gaps;
            let (east_m, north_m) = p
                .track()
                .last()
                .map_or((0.0, 0.0), |s| (s.east_m, s.north_m));
            self.gap_marks.push(GapMark {
                t0,
                t1: t,
                east_m,
                north_m,
            });
        }
        let Record::Imu(_) = r else { return };
        self.last_t = Some(t);
        if let Some(up) = p.vertical_accel() {
            self.scope.push_back(ScopeSample {
                t,
                up,
                pll: p.pll_output(),
            });
        }
        while self.scope.front().is_some_and(|x| x.t < t - SCOPE_S) {
            self.scope.pop_front();
        }
    }
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
    /// Fixes received.
    pub fixes: usize,
    /// Motion events received per second over the last two seconds.
    pub sample_rate_hz: f64,
    /// Motion samples used.
    pub samples: u64,
    /// Seconds since the first sample used.
    pub duration_s: f64,
    /// Gaps in the input (page hidden, sensor paused).
    pub gaps: u64,
    /// The orientation source the engine settled on (`os`, `madgwick`, …), once it has.
    pub orientation: Option<&'static str>,
    /// Whether headings are referenced to north (an absolute attitude has arrived).
    pub absolute_heading: bool,
    /// Motion events set aside while waiting for the first attitude.
    pub waited: u64,
    /// Events refused (with the reason of the last one).
    pub refused: u64,
    /// The last refusal.
    pub last_error: Option<String>,
    /// Whether the GNSS receiver should be on now (energy-saving mode).
    pub gnss_wanted: bool,
    /// How long the receiver has been wanted on since the first fix, and that span, s (the
    /// saving of energy-saving mode is the rest of the span).
    pub gnss_on_s: Option<(f64, f64)>,
    /// The fusion filter's step-length scale and its standard deviation, once fixes have come.
    pub fusion_scale: Option<(f64, f64)>,
}

/// A live session: the pipeline, the latest attitude, the recent signal for the scrolling view,
/// and the recording in pdr-log lines.
///
/// Times: the page passes `event.timeStamp` (ms since the page's time origin) and the session
/// adds the origin it was made with (`performance.timeOrigin`), so the recording is on Unix time.
/// A recording resumed after a reload therefore continues on the same clock, with the reload
/// as a gap, and the World Magnetic Model gets the date of the walk.
pub struct LiveSession {
    pipeline: Pipeline,
    platform: Platform,
    origin_ms: f64,
    attitude: Option<(f64, UnitQuaternion<f64>, bool)>,
    // The time of the sample that last carried the attitude; `None` while the newest has not
    // been carried yet.
    attitude_written_at: Option<f64>,
    // A Generic Sensor attitude holds until the next reading: the API reports changes only.
    attitude_sticky: bool,
    absolute: bool,
    first_event: Option<f64>,
    waited: u64,
    view: View,
    log: String,
    recent: VecDeque<f64>,
    refused: u64,
    last_error: Option<String>,
    // The smoothed track as of the filter's last correction: (corrections then, positions).
    smoothed: (u64, Vec<(f64, f64)>),
}

impl LiveSession {
    /// A session with the given configuration, for a platform's conventions, with event times
    /// counted from `origin_ms` (ms, Unix time; 0 keeps the page's clock).
    pub fn new(
        cfg: PipelineConfig,
        platform: Platform,
        origin_ms: f64,
    ) -> Result<Self, ConfigError> {
        Ok(LiveSession {
            pipeline: Pipeline::new(cfg)?,
            platform,
            origin_ms: if origin_ms.is_finite() {
                origin_ms
            } else {
                0.0
            },
            attitude: None,
            attitude_written_at: Some(f64::NEG_INFINITY),
            attitude_sticky: false,
            absolute: false,
            first_event: None,
            waited: 0,
            view: View::default(),
            smoothed: (0, Vec::new()),
            log: crate::io::pdrlog::preamble(),
            recent: VecDeque::new(),
            refused: 0,
            last_error: None,
        })
    }

    /// A session that continues a recording (pdr-log text, e.g. recovered after a reload): its
    /// records go through the engine again, and [`take_log`](Self::take_log) then returns only
    /// what comes after them.
    pub fn resume(
        cfg: PipelineConfig,
        platform: Platform,
        origin_ms: f64,
        recorded: &str,
    ) -> Result<Self, String> {
        let parsed = crate::io::pdrlog::read(recorded.as_bytes(), "the recovered recording")
            .map_err(|e| e.to_string())?;
        let mut s = Self::new(cfg, platform, origin_ms).map_err(|e| e.to_string())?;
        s.log.clear();
        s.absolute = parsed
            .records
            .iter()
            .any(|r| matches!(r, Record::Imu(i) if i.orientation.is_some()));
        let view = &mut s.view;
        feed(
            &mut s.pipeline,
            &parsed.records,
            &mut |p: &Pipeline, _, r: &Record, accepted| {
                if accepted {
                    view.observe(p, r);
                }
            },
        );
        Ok(s)
    }

    /// The pipeline (track, fixes, diagnostics).
    pub fn pipeline(&self) -> &Pipeline {
        &self.pipeline
    }

    /// The vertical acceleration and PLL output of the last [`SCOPE_S`] seconds.
    pub fn scope(&self) -> &VecDeque<ScopeSample> {
        &self.view.scope
    }

    /// Where the input stopped.
    pub fn gap_marks(&self) -> &[GapMark] {
        &self.view.gap_marks
    }

    fn refuse(&mut self, e: LiveError) -> LiveError {
        self.refused += 1;
        self.last_error = Some(e.to_string());
        e
    }

    fn seconds(&self, ms: f64) -> f64 {
        (self.origin_ms + ms) * 1e-3
    }

    /// Feeds a `devicemotion` event; returns how many steps it completed.
    pub fn push_motion(&mut self, ev: &MotionEvent) -> Result<usize, LiveError> {
        let m = normalise_motion(ev, self.platform).map_err(|e| self.refuse(e))?;
        self.push_normalised(Motion {
            t: m.t + self.origin_ms * 1e-3,
            ..m
        })
    }

    /// Feeds a Generic Sensor API reading: `Accelerometer` (m/s², gravity included, the
    /// specification's sign on every platform) with the latest `Gyroscope` reading (rad/s), at
    /// the sensor's `timestamp` (ms on the page's clock).
    pub fn push_sensor(
        &mut self,
        timestamp_ms: f64,
        accel: [f64; 3],
        gyro_rad_s: Option<[f64; 3]>,
    ) -> Result<usize, LiveError> {
        let all = [timestamp_ms, accel[0], accel[1], accel[2]];
        if !all.iter().all(|x| x.is_finite()) {
            return Err(self.refuse(LiveError::NonFinite("Accelerometer")));
        }
        if gyro_rad_s.is_some_and(|g| !g.iter().all(|x| x.is_finite())) {
            return Err(self.refuse(LiveError::NonFinite("Gyroscope")));
        }
        self.push_normalised(Motion {
            t: self.seconds(timestamp_ms),
            accel: Vector3::from(accel),
            gyro: gyro_rad_s.map(Vector3::from),
            interval_s: None,
        })
    }

    fn push_normalised(&mut self, m: Motion) -> Result<usize, LiveError> {
        // The first sample decides the engine's orientation source: wait a moment for an
        // attitude (these samples are not used, and not recorded, so that the recording
        // replays the same).
        if self.attitude.is_none() && self.pipeline.diagnostics().samples == 0 {
            let t0 = *self.first_event.get_or_insert(m.t);
            if m.t - t0 < ATTITUDE_WAIT_S {
                self.waited += 1;
                return Ok(0);
            }
        }
        // The attitude rides on the first sample after it arrives (the engine holds it for
        // the samples after that); an absolute attitude wins over a relative one.
        let stale = |at: f64| self.attitude_sticky && m.t - at >= 0.5 * HOLD_S;
        let orientation = match (self.attitude, self.attitude_written_at) {
            (Some((_, q, _)), None) => Some(q),
            (Some((_, q, _)), Some(at)) if stale(at) => Some(q),
            _ => None,
        };
        let s = ImuSample {
            t: m.t,
            accel: m.accel,
            gyro: m.gyro,
            mag: None,
            orientation,
        };
        let n = self
            .use_record(&Record::Imu(s))
            .map_err(|e| self.refuse(LiveError::Engine(e)))?;
        if orientation.is_some() {
            self.attitude_written_at = Some(m.t);
        }
        self.recent.push_back(m.t);
        while self.recent.front().is_some_and(|&t0| t0 < m.t - 2.0) {
            self.recent.pop_front();
        }
        Ok(n)
    }

    /// One record through the engine, the live view and the recording.
    fn use_record(&mut self, r: &Record) -> Result<usize, InputError> {
        let n = self.pipeline.push(r)?.len();
        self.log.push_str(&crate::io::pdrlog::line(r));
        self.view.observe(&self.pipeline, r);
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
        self.set_attitude(
            time_stamp_ms,
            orientation_quaternion(alpha, beta, gamma),
            absolute,
        );
    }

    /// Feeds an `AbsoluteOrientationSensor` quaternion `[x, y, z, w]` (device → East-North-Up).
    pub fn push_quaternion(&mut self, timestamp_ms: f64, q: [f64; 4]) {
        let norm = libm::sqrt(q.iter().map(|v| v * v).sum());
        if !(timestamp_ms.is_finite() && norm.is_finite() && norm > 0.5) {
            let _ = self.refuse(LiveError::NonFinite("AbsoluteOrientationSensor.quaternion"));
            return;
        }
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[3], q[0], q[1], q[2]));
        self.set_attitude(timestamp_ms, q, true);
        self.attitude_sticky = true;
    }

    fn set_attitude(&mut self, time_stamp_ms: f64, q: UnitQuaternion<f64>, absolute: bool) {
        if !absolute && self.absolute {
            return;
        }
        self.absolute |= absolute;
        self.attitude = Some((self.seconds(time_stamp_ms), q, absolute));
        self.attitude_written_at = None;
        self.attitude_sticky = false;
    }

    /// Feeds a geolocation fix (`t` in ms on the page's clock).
    pub fn push_fix(&mut self, f: &GnssFix) -> Result<(), LiveError> {
        let f = GnssFix {
            t: self.seconds(f.t * 1e3),
            ..*f
        };
        self.use_record(&Record::Gnss(f))
            .map_err(|e| self.refuse(LiveError::Engine(e)))?;
        Ok(())
    }

    /// The page was hidden (or the sensors paused) between two times, ms on the page's clock.
    /// The gap starts no earlier than the last sample received.
    pub fn mark_gap(&mut self, t0_ms: f64, t1_ms: f64) {
        let t0 = self
            .seconds(t0_ms)
            .max(self.view.last_t.unwrap_or(f64::NEG_INFINITY));
        let t1 = self.seconds(t1_ms);
        if t1 > t0 && t0.is_finite() && t1.is_finite() {
            let _ = self.use_record(&Record::Gap(t0, t1));
        }
    }

    /// The frequencies of the steps counted so far, Hz (a calibration walk's f_k).
    pub fn step_freqs(&self) -> Vec<f64> {
        self.pipeline.track().iter().map(|s| s.freq_hz).collect()
    }

    /// The distance along the fixes no worse than `max_accuracy_m`, m: a fix is kept once it is
    /// at least 2·`max_accuracy_m` from the last kept one, so that the fixes' noise does not add
    /// up; the last fix closes the path. The calibration wizard's GNSS distance.
    pub fn fix_path_m(&self, max_accuracy_m: f64) -> f64 {
        // Between fixes by the haversine formula, as Basso 2021 §2.1 measures them.
        let pts: Vec<(f64, f64)> = self
            .pipeline
            .fixes()
            .iter()
            .filter(|f| f.h_accuracy_m <= max_accuracy_m)
            .map(|f| (f.lat_deg, f.lon_deg))
            .collect();
        let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
            return 0.0;
        };
        let d = |a: (f64, f64), b: (f64, f64)| crate::engine::geo::haversine_m(a.0, a.1, b.0, b.1);
        let mut kept = first;
        let mut total = 0.0;
        for &p in &pts {
            if d(kept, p) >= 2.0 * max_accuracy_m {
                total += d(kept, p);
                kept = p;
            }
        }
        total + d(kept, last)
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
            fixes: self.pipeline.fixes().len(),
            sample_rate_hz: if span > 0.0 {
                (self.recent.len() - 1) as f64 / span
            } else {
                0.0
            },
            samples: d.samples,
            duration_s: d.time_span.map_or(0.0, |(a, b)| b - a),
            gaps: d.gaps,
            orientation: d.orientation.map(|o| match o {
                OrientationSource::Os => "os",
                OrientationSource::Madgwick { .. } => "madgwick",
                OrientationSource::GravityLowPass { .. } => "gravity",
                OrientationSource::Auto => "auto",
            }),
            absolute_heading: self.absolute,
            waited: self.waited,
            refused: self.refused,
            last_error: self.last_error.clone(),
            gnss_wanted: self.pipeline.gnss_wanted(now),
            gnss_on_s: d.gnss_on_s,
            fusion_scale: self
                .pipeline
                .fused()
                .last()
                .map(|f| (f.scale, f.scale_bias_sd[0])),
        }
    }
}

/// What the live map shows, in one frame: the first fix's local tangent plane once there are
/// fixes (the PDR track then drawn from the fused estimate of its first step), else metres from
/// the start.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapData {
    /// The PDR track, from the start.
    pub pdr: Vec<(f64, f64)>,
    /// The fused track.
    pub fused: Vec<(f64, f64)>,
    /// The smoothed track: the walk so far with each fix's correction carried back over the
    /// steps before it (the past trajectory corrected, Basso 2021 §3.1.2; in energy-saving
    /// mode this takes out the jump at each window).
    pub smoothed: Vec<(f64, f64)>,
    /// Fixes: east, north, accuracy, m.
    pub fixes: Vec<(f64, f64, f64)>,
    /// Where the input stopped.
    pub gaps: Vec<(f64, f64)>,
    /// Heading of the last step, rad from north.
    pub heading_rad: Option<f64>,
}

impl LiveSession {
    /// The map's data. The smoother's backward pass runs again only when a fix has corrected
    /// the filter since the last call: after the last correction the smoothed steps are the
    /// filtered ones.
    pub fn map_data(&mut self) -> MapData {
        let corrections = self
            .pipeline
            .diagnostics()
            .fix_counts
            .map_or(0, |c| c.used + c.resets);
        if corrections != self.smoothed.0 {
            let s = self.pipeline.smoothed();
            self.smoothed = (
                corrections,
                s.iter().map(|f| (f.east_m, f.north_m)).collect(),
            );
        }
        let p = &self.pipeline;
        let mut smoothed = self.smoothed.1.clone();
        smoothed.extend(
            p.fused()
                .iter()
                .skip(smoothed.len())
                .map(|f| (f.east_m, f.north_m)),
        );
        let track = p.track();
        let fused: Vec<(f64, f64)> = p.fused().iter().map(|f| (f.east_m, f.north_m)).collect();
        let offset = p.pdr_offset();
        let shift = |e: f64, n: f64| (e + offset.0, n + offset.1);
        MapData {
            pdr: std::iter::once((0.0, 0.0))
                .chain(track.iter().map(|s| (s.east_m, s.north_m)))
                .map(|(e, n)| shift(e, n))
                .collect(),
            fused,
            smoothed,
            fixes: p.frame().map_or_else(Vec::new, |frame| {
                p.fixes()
                    .iter()
                    .map(|f| {
                        let (e, n) = frame.en_of_fix(f);
                        (e, n, f.h_accuracy_m)
                    })
                    .collect()
            }),
            gaps: self
                .view
                .gap_marks
                .iter()
                .map(|g| shift(g.east_m, g.north_m))
                .collect(),
            heading_rad: track.last().and_then(|s| s.heading_rad),
        }
    }

    /// The scrolling view's data: (t, vertical acceleration, PLL output) of the last
    /// [`SCOPE_S`], the step times among them, and the newest time.
    #[allow(clippy::type_complexity)]
    pub fn scope_data(&self) -> (Vec<(f64, f64, Option<f64>)>, Vec<f64>, f64) {
        let samples: Vec<_> = self.view.scope.iter().map(|s| (s.t, s.up, s.pll)).collect();
        let now = samples.last().map_or(0.0, |s| s.0);
        let steps = self
            .pipeline
            .track()
            .iter()
            .rev()
            .map(|s| s.t)
            .take_while(|&t| t >= now - SCOPE_S)
            .collect();
        (samples, steps, now)
    }
}

/// One browser event of a simulated walk, as the page receives it (see [`browser_events`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum BrowserEvent {
    /// A `devicemotion` event.
    Motion {
        /// `timeStamp`, ms.
        t: f64,
        /// `accelerationIncludingGravity`, the platform's sign.
        x: f64,
        /// See `x`.
        y: f64,
        /// See `x`.
        z: f64,
        /// `rotationRate`, deg/s.
        alpha: Option<f64>,
        /// See `alpha`.
        beta: Option<f64>,
        /// See `alpha`.
        gamma: Option<f64>,
        /// `interval` in the platform's unit.
        interval: f64,
    },
    /// A `deviceorientationabsolute` event (absolute `deviceorientation` on iOS).
    Orientation {
        /// `timeStamp`, ms.
        t: f64,
        /// Degrees.
        alpha: f64,
        /// Degrees.
        beta: f64,
        /// Degrees.
        gamma: f64,
    },
}

/// The samples of a log (a simulated walk) as the browser events a phone of `platform` would
/// fire: the inverse of [`normalise_motion`] and [`orientation_quaternion`]. The end-to-end
/// tests dispatch these on the live page.
pub fn browser_events(records: &[Record], platform: Platform) -> Vec<BrowserEvent> {
    let deg = 180.0 / std::f64::consts::PI;
    let mut out = Vec::new();
    let mut last = None;
    for r in records {
        let Record::Imu(s) = r else { continue };
        let t = s.t * 1e3;
        if let Some(q) = s.orientation {
            let (alpha, beta, gamma) = orientation_angles(&q);
            out.push(BrowserEvent::Orientation {
                t,
                alpha: alpha.rem_euclid(360.0),
                beta,
                gamma,
            });
        }
        let a = platform.to_android(s.accel);
        let interval_ms = last.map_or(10.0, |l| t - l);
        last = Some(t);
        out.push(BrowserEvent::Motion {
            t,
            x: a.x,
            y: a.y,
            z: a.z,
            alpha: s.gyro.map(|g| g.x * deg),
            beta: s.gyro.map(|g| g.y * deg),
            gamma: s.gyro.map(|g| g.z * deg),
            interval: match platform {
                Platform::Ios => interval_ms * 1e-3,
                Platform::Android => interval_ms,
            },
        });
    }
    out
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
