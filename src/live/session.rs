//! The live session: samples in (through [`super::events`]), the one pipeline, the readouts,
//! the map's and the scope's data, and the recording as pdr-log lines.
//! May import: `engine`, `io` (the pdr-log), and [`super::events`].

use super::events::{
    normalise_motion, sensor_sample, EventError, MotionEvent, OrientationEvent, Platform,
    SensorReading,
};
use crate::engine::fusion::GnssVerdict;
use crate::engine::orientation::{OrientationSource, HOLD_S};
use crate::engine::recorded_walk::FuzzyLengths;
use crate::engine::replay::feed;
use crate::engine::types::{time_in_range, ConfigError, GnssFix, ImuSample, InputError, Record};
use crate::engine::{Pipeline, PipelineConfig};
use crate::io::fusion_words;
use nalgebra::UnitQuaternion;
use std::collections::VecDeque;
use std::fmt;

/// Why a live event or session was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum LiveError {
    /// The event carries no usable sample.
    Event(EventError),
    /// The engine refused the sample.
    Engine(InputError),
    /// The configuration is invalid.
    Config(ConfigError),
}

impl fmt::Display for LiveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LiveError::Event(e) => write!(f, "{e}"),
            LiveError::Engine(e) => write!(f, "{e}"),
            LiveError::Config(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for LiveError {}

impl From<EventError> for LiveError {
    fn from(e: EventError) -> Self {
        LiveError::Event(e)
    }
}

/// How long after the start the page says that no motion data has come, ms.
pub const NO_MOTION_MS: f64 = 3000.0;

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

/// What the scrolling view draws.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ScopeData {
    /// (t, vertical acceleration, PLL output) of each sample, s, m/s².
    pub samples: Vec<(f64, f64, Option<f64>)>,
    /// The times of the steps among them, s.
    pub steps: Vec<f64>,
    /// The newest time, s.
    pub now: f64,
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
            Record::Gnss(_) | Record::Foot(_) | Record::Pressure(_) => return,
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
    /// Where the last step on the track ended, [east, north] of the start in m: the PDR
    /// track's current position (`pdr run --track`'s last row).
    pub end_m: Option<[f64; 2]>,
    /// Steps counted but not yet on the track: a walk's first steps wait until something
    /// knows which way is forward ([`crate::engine::heading::opening`]).
    pub held_steps: usize,
    /// `still`, `walking` or `running`.
    pub motion: Option<&'static str>,
    /// The activity in words ("Walking upstairs", "Sitting", …; Munoz Diaz 2015 §4.3): the
    /// engine's, else the motion state's ("Still", "Walking", "Running"), once a sample came.
    pub activity: Option<&'static str>,
    /// The activity's name as the files write it (`upstairs`, …).
    pub activity_key: Option<&'static str>,
    /// Where the phone is carried, in words ("In a pocket", "At the ear", …), once the
    /// detector decided ([`crate::engine::carry`]).
    pub carry: Option<&'static str>,
    /// Its name as the CSV's `carry` column writes it.
    pub carry_key: Option<&'static str>,
    /// Floor now relative to the start.
    pub floor: i32,
    /// The floor change for people: "+1 floor", "−2 floors"; none at the start's floor.
    pub floor_change: Option<String>,
    /// Height above the start, m, once the engine has one (`Diagnostics::vertical`).
    pub up_m: Option<f64>,
    /// What the height comes from ("leg pitch"; browsers have no barometer).
    pub height_source: Option<&'static str>,
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
    /// Events refused (with the reason of the last one).
    pub refused: u64,
    /// Lines of a resumed recording that could not be read.
    pub skipped_lines: u64,
    /// The last refusal.
    pub last_error: Option<String>,
    /// Whether the GNSS receiver should be on now (energy-saving mode).
    pub gnss_wanted: bool,
    /// How long the receiver has been wanted on since the first fix, and that span, s (the
    /// saving of energy-saving mode is the rest of the span).
    pub gnss_on_s: Option<(f64, f64)>,
    /// The fusion filter's step-length scale and its standard deviation, once fixes have come.
    pub fusion_scale: Option<(f64, f64)>,
    /// The filter's heading correction and its standard deviation, degrees, once fixes have
    /// come.
    pub fusion_correction_deg: Option<(f64, f64)>,
    /// The scale for people: "0.93 ± 0.02" (`io::fusion_words`).
    pub scale_text: Option<String>,
    /// The heading correction for people: "−4.1° ± 1.2°".
    pub correction_text: Option<String>,
    /// The filter's verdict on the GNSS (`waiting`, `learning`, `calibrated`, `distrusted`),
    /// once fixes have come with the fusion on (`waiting` while none was good enough to start
    /// it).
    pub gnss_verdict: Option<crate::engine::fusion::GnssVerdict>,
    /// The notice the page shows when the verdict is `waiting` or `distrusted` ("GNSS disagrees
    /// with your steps: using steps"); none otherwise.
    pub gnss_notice: Option<&'static str>,
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
    view: View,
    log: String,
    recent: VecDeque<f64>,
    refused: u64,
    skipped_lines: u64,
    last_error: Option<String>,
    // The smoothed track as of the filter's last correction: (corrections then, positions).
    smoothed: (u64, Vec<(f64, f64)>),
    // The calibration wizard's fuzzy lengths: the fuzzy model (scale 1) asked about each step
    // the pipeline emits, one per step of the track.
    fuzzy: FuzzyLengths,
}

impl LiveSession {
    /// A session with the given configuration, for a platform's conventions, with event times
    /// counted from `origin_ms` (ms, Unix time; 0 keeps the page's clock).
    /// The time origin also dates the walk for the declination (`fusion.date_unix_s`, unless
    /// `cfg` sets it), so the World Magnetic Model has the date before the first fix.
    pub fn new(
        mut cfg: PipelineConfig,
        platform: Platform,
        origin_ms: f64,
    ) -> Result<Self, ConfigError> {
        if cfg.fusion.date_unix_s.is_none() {
            cfg.fusion.date_unix_s = crate::io::import::date::from_clock(Some(origin_ms * 1e-3));
        }
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
            view: View::default(),
            smoothed: (0, Vec::new()),
            fuzzy: FuzzyLengths::new(),
            log: crate::io::pdrlog::preamble(),
            recent: VecDeque::new(),
            refused: 0,
            skipped_lines: 0,
            last_error: None,
        })
    }

    /// A session that continues a recording (pdr-log text, e.g. recovered after a reload): its
    /// records go through the engine again, and [`take_log`](Self::take_log) then returns only
    /// what comes after them. The recording is read as [`crate::io::pdrlog::recover`] reads
    /// one piece: a bad line, a last line cut short or a missing version tag is skipped and
    /// counted (`skipped_lines`, the first reason in `last_error`), never fatal; records the
    /// engine refuses are counted in `refused`.
    pub fn resume(
        cfg: PipelineConfig,
        platform: Platform,
        origin_ms: f64,
        recorded: &str,
    ) -> Result<Self, LiveError> {
        let parsed = crate::io::pdrlog::recover(&[(0, Some(recorded))]);
        let mut s = Self::new(cfg, platform, origin_ms).map_err(LiveError::Config)?;
        s.log.clear();
        s.skipped_lines = parsed.skipped_lines;
        s.last_error = parsed
            .notes
            .first()
            .map(|n| format!("the recovered recording: {n}"));
        s.absolute = parsed
            .records
            .iter()
            .any(|r| matches!(r, Record::Imu(i) if i.orientation.is_some()));
        let view = &mut s.view;
        let fuzzy = &mut s.fuzzy;
        let refusals = feed(
            &mut s.pipeline,
            &parsed.records,
            &mut |p: &Pipeline, _, r: &Record, accepted| {
                if accepted {
                    view.observe(p, r);
                    fuzzy.observe(p);
                }
            },
        );
        s.refused += refusals.count;
        if let Some((i, e)) = refusals.errors.first() {
            s.last_error = Some(format!("the recovered recording, record {}: {e}", i + 1));
        }
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
        let m = normalise_motion(ev, self.platform).map_err(|e| self.refuse(e.into()))?;
        self.push_sample(ImuSample {
            t: m.t + self.origin_ms * 1e-3,
            ..m
        })
    }

    /// Feeds a Generic Sensor API reading; returns how many steps it completed.
    pub fn push_sensor(&mut self, r: &SensorReading) -> Result<usize, LiveError> {
        let (accel, gyro) = sensor_sample(r).map_err(|e| self.refuse(e.into()))?;
        self.push_sample(ImuSample {
            t: self.seconds(r.timestamp_ms),
            accel,
            gyro,
            mag: None,
            orientation: None,
        })
    }

    /// A motion sample on the session's clock, before its attitude is attached.
    fn push_sample(&mut self, m: ImuSample) -> Result<usize, LiveError> {
        // No wait for the attitude: the engine's `auto` orientation starts on what the first
        // samples hold and moves up when the attitude (or a rotation rate) first comes.
        // The attitude rides on the first sample after it arrives (the engine holds it for
        // the samples after that); an absolute attitude wins over a relative one.
        let stale = |at: f64| self.attitude_sticky && m.t - at >= 0.5 * HOLD_S;
        let orientation = match (self.attitude, self.attitude_written_at) {
            (Some((_, q, _)), None) => Some(q),
            (Some((_, q, _)), Some(at)) if stale(at) => Some(q),
            _ => None,
        };
        let s = ImuSample { orientation, ..m };
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
        self.fuzzy.observe(&self.pipeline);
        Ok(n)
    }

    /// Feeds a `deviceorientation` or `deviceorientationabsolute` event. Relative events are
    /// ignored once absolute ones have come.
    pub fn push_orientation(&mut self, ev: &OrientationEvent) {
        match ev.attitude() {
            Ok(Some((q, absolute))) => self.set_attitude(ev.time_stamp_ms, q, absolute),
            Ok(None) => {}
            Err(e) => {
                let _ = self.refuse(e.into());
            }
        }
    }

    /// Feeds an `AbsoluteOrientationSensor` quaternion `[x, y, z, w]` (device → East-North-Up).
    pub fn push_quaternion(&mut self, timestamp_ms: f64, q: [f64; 4]) {
        let norm = libm::sqrt(q.iter().map(|v| v * v).sum());
        if !(timestamp_ms.is_finite() && norm.is_finite() && norm > 0.5) {
            let _ =
                self.refuse(EventError::NonFinite("AbsoluteOrientationSensor.quaternion").into());
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

    /// Feeds a geolocation fix (`t` in seconds on the page's clock).
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
    /// The gap starts no earlier than the last sample received. A gap with a time out of the
    /// engine's range ([`crate::engine::types::MAX_TIME_S`]) is ignored, and not recorded.
    pub fn mark_gap(&mut self, t0_ms: f64, t1_ms: f64) {
        let t0 = self
            .seconds(t0_ms)
            .max(self.view.last_t.unwrap_or(f64::NEG_INFINITY));
        let t1 = self.seconds(t1_ms);
        if t1 > t0 && time_in_range(t0) && time_in_range(t1) {
            let _ = self.use_record(&Record::Gap(t0, t1));
        }
    }

    /// The frequencies of the steps counted so far, Hz (a calibration walk's f_k).
    pub fn step_freqs(&self) -> Vec<f64> {
        self.pipeline.track().iter().map(|s| s.freq_hz).collect()
    }

    /// The leg pitch amplitude Δθ of each step counted so far, degrees, NaN for a step without
    /// one (a calibration walk's Δθ_k for the pitch step length's offset,
    /// [`crate::engine::calibration::pitch_offset`]).
    pub fn pitch_amplitudes(&self) -> Vec<f64> {
        self.pipeline
            .track()
            .iter()
            .map(|s| s.pitch_amplitude_deg.unwrap_or(f64::NAN))
            .collect()
    }

    /// The unscaled fuzzy step length (Ibarra 2015, scale 1) of each step counted so far, m, in
    /// the order of the track, whatever step-length model the session runs: a calibration
    /// walk's L_k for the fuzzy scale ([`crate::engine::calibration::fit_fuzzy_scale`]).
    pub fn fuzzy_lengths(&self) -> &[f64] {
        &self.fuzzy.lengths
    }

    /// What the walk says about the user's step length: the fusion filter's scale and its
    /// standard deviation, its verdict and the fixes it used, the fixes received and the steps'
    /// frequencies.
    pub fn walk_evidence(&self) -> crate::engine::refinement::WalkEvidence {
        let fusion = self.pipeline.fusion().map(|f| f.diagnostics());
        crate::engine::refinement::WalkEvidence {
            fixes: self.pipeline.fixes().len(),
            fixes_used: fusion.as_ref().map_or(0, |d| d.counts.used),
            verdict: fusion.map(|d| d.verdict),
            scale: self
                .pipeline
                .fused()
                .last()
                .map(|f| (f.scale, f.scale_bias_sd[0])),
            step_freqs_hz: self.step_freqs(),
        }
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

    /// The recording has stopped: places the steps a bout's opening still holds
    /// ([`Pipeline::finish`]), as a replay of the recording does; returns how many.
    pub fn finish(&mut self) -> usize {
        self.pipeline.finish().len()
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
        let fused = self.pipeline.fused().last();
        // Fixes that came but none good enough to start the filter: waiting for a usable one.
        let fusion_on = self.pipeline.config().fusion.mode != crate::engine::fusion::GnssMode::Off;
        let verdict = match self.pipeline.fusion() {
            Some(f) => Some(f.verdict()),
            None if fusion_on && !self.pipeline.fixes().is_empty() => Some(GnssVerdict::Waiting),
            None => None,
        };
        Readouts {
            // A stride (foot mode) counts as two steps.
            steps: d.steps as usize,
            distance_m: d.distance_m,
            cadence_hz: last.map(|s| s.freq_hz),
            heading_deg: last.and_then(|s| s.heading_rad).map(f64::to_degrees),
            end_m: last.map(|s| [s.east_m, s.north_m]),
            held_steps: self.pipeline.held_steps().count(),
            motion: d.motion.map(|m| m.as_str()),
            activity: activity_now(&d).map(crate::io::export::activity_words),
            activity_key: activity_now(&d).map(|a| a.as_str()),
            carry: d.carry.map(|c| c.words()),
            carry_key: d.carry.map(|c| c.as_str()),
            floor: d.floor,
            floor_change: crate::io::export::floor_change(d.floor),
            up_m: (d.vertical.is_some() || d.floor != 0 || d.up_m != 0.0).then_some(d.up_m),
            height_source: d.vertical.map(|v| v.as_str()),
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
                OrientationSource::KfNfa(_) => "kf_nfa",
                OrientationSource::GravityLowPass { .. } => "gravity",
                OrientationSource::Auto => "auto",
            }),
            absolute_heading: self.absolute,
            refused: self.refused,
            skipped_lines: self.skipped_lines,
            last_error: self.last_error.clone(),
            gnss_wanted: self.pipeline.gnss_wanted(now),
            gnss_on_s: d.gnss_on_s,
            fusion_scale: fused.map(|f| (f.scale, f.scale_bias_sd[0])),
            fusion_correction_deg: fused
                .map(|f| (f.bias_rad.to_degrees(), f.scale_bias_sd[1].to_degrees())),
            scale_text: fused.map(|f| fusion_words::scale_text(f.scale, f.scale_bias_sd[0])),
            correction_text: fused
                .map(|f| fusion_words::correction_text(f.bias_rad, f.scale_bias_sd[1])),
            gnss_verdict: verdict,
            gnss_notice: verdict
                .filter(|v| matches!(v, GnssVerdict::Waiting | GnssVerdict::Distrusted))
                .map(GnssVerdict::text),
        }
    }
}

/// The activity now: the engine's, else the motion state's.
fn activity_now(d: &crate::engine::Diagnostics) -> Option<crate::engine::Activity> {
    use crate::engine::{Activity, Motion};
    d.activity.or(d.motion.map(|m| match m {
        Motion::Still => Activity::Still,
        Motion::Walking => Activity::Walking,
        Motion::Running => Activity::Running,
    }))
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
    /// The geodetic origin of the positions' frame (the first fix), once there is one: where
    /// the base map is placed.
    pub origin: Option<crate::engine::geo::LocalFrame>,
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
            origin: p.frame().copied(),
        }
    }

    /// The scrolling view's data: the last [`SCOPE_S`] of samples, the step times among them,
    /// and the newest time.
    pub fn scope_data(&self) -> ScopeData {
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
        ScopeData {
            samples,
            steps,
            now,
        }
    }
}
