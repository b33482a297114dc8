//! The one pipeline: IMU and GNSS records in time order in, step records out.
//! May import: the rest of `engine`.
//!
//! Live sensor events and uploaded logs go through the same [`Pipeline::push`]; replaying a log
//! ([`crate::engine::replay`](fn@crate::engine::replay)) is a loop over it.
//!
//! Per IMU sample: validate → orientation into ENU → motion detector (σ_z) → heading window →
//! step detector → for each step: period and frequency, heading, step length, dead reckoning
//! (Basso 2021 eq. 24 with x north and y east: north += SL cos θ, east += SL sin θ).
//!
//! # Decisions beyond the papers (measured in the tests; figures in docs/engine.md and docs/methods/)
//! - **Onset look-back.** The motion detector confirms a gait (σ_z and the periodicity of the
//!   vertical acceleration) one to three seconds after a person starts walking, so gating steps by
//!   the motion state alone misses the first steps of every walk. When it does, the step detector
//!   is started afresh on the cadence found and replays the last
//!   [`PipelineConfig::onset_lookback_s`] of samples; the steps it finds after the last cycle
//!   that is out of phase with the gait are emitted. Basso 2016 keeps "the restart instant" for
//!   the same reason: the first step period after a stop must not include the stop. Here the
//!   first step of a bout takes the detector's own period.
//! - **Cycle gate.** After a stop σ_z stays above the threshold for up to 2 s; a step additionally
//!   needs its own cycle to carry motion (see [`crate::engine::pll`]), so no phantom steps are
//!   counted while the window drains.
//! - **Gaps.** When two samples are more than [`PipelineConfig::gap_s`] apart (page hidden,
//!   logging paused), the gap is counted, the windows are cleared and the oscillator restarts: the
//!   gap is never bridged with phantom steps.
//! - **Bad input.** A record with a non-finite value, a time going backwards or a field the
//!   orientation source needs is refused with an [`InputError`], counted in [`Diagnostics`], and
//!   leaves the state untouched.

use super::activity::Activity;
use super::carry::{Carry, CarryMode};
use super::detector::DetectorInput;
use super::foot::placement::Placement;
use super::foot::FootDiagnostics;
use super::fusion::{DeclinationNote, FixCounts, FusedStep};
use super::handling::Handling;
use super::heading::{Heading, NavSample};
use super::hybrid::HybridDiagnostics;
use super::magnetic::Magnetic;
use super::motion::{Motion, MotionDetector};
use super::orientation::{Orientation, OrientationSource};
use super::step_length::StepLength;
use super::types::{time_in_range, ConfigError, ImuSample, InputError, Record};

mod bout;
mod clock;
mod config;
mod foot;
mod gnss;
mod pocket;
mod step_detector;
mod steps;
mod track;
mod two_sensor;
mod window;

pub use clock::{Now, Stage, StageClock};
pub use config::PipelineConfig;
use step_detector::Detector;
pub use step_detector::StepDetectorConfig;

/// One detected step and where it took the walker.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepRecord {
    /// Time of the step (end of the step), s.
    pub t: f64,
    /// Position after the step, east, m.
    pub east_m: f64,
    /// Position after the step, north, m.
    pub north_m: f64,
    /// Heading used for the step (two-step average when configured), rad from north.
    pub heading_rad: Option<f64>,
    /// Single-step direction θ_k before averaging, rad from north.
    pub step_heading_rad: Option<f64>,
    /// Step length, m.
    pub length_m: f64,
    /// Step frequency f_k = 1/T_k, Hz.
    pub freq_hz: f64,
    /// Motion state when the step was counted.
    pub motion: Motion,
    /// The activity of the step (Munoz Diaz 2015 §4.3; without a leg pitch, from `motion`).
    #[serde(default)]
    pub activity: Activity,
    /// Height after the step above the walk's start, m (Munoz Diaz 2015 §6, and the barometer
    /// where the log has one).
    #[serde(default)]
    pub up_m: f64,
    /// Floor after the step, relative to the walk's start (0), from the height's level changes.
    #[serde(default)]
    pub floor: i32,
    /// The leg pitch amplitude Δθ = θ_max − θ_min of the stride this step belongs to, degrees
    /// (Munoz Diaz 2015 eq. 4), when the leg pitch is known.
    #[serde(default)]
    pub pitch_amplitude_deg: Option<f64>,
    /// Where the phone was carried when the step was counted ([`crate::engine::carry`]), once
    /// the detector decided.
    #[serde(default)]
    pub carry: Option<CarryMode>,
    /// Whether the magnetometer was disturbed at the step, so that the heading followed the
    /// gyroscope ([`crate::engine::magnetic`]).
    #[serde(default)]
    pub gyro_heading: bool,
}

/// The estimated position (east, north) at time `t`, interpolated between steps.
pub fn position_at(track: &[StepRecord], t: f64) -> (f64, f64) {
    let i = track.partition_point(|s| s.t <= t);
    let (prev_t, prev) = match i.checked_sub(1) {
        Some(k) => (track[k].t, (track[k].east_m, track[k].north_m)),
        None => return (0.0, 0.0),
    };
    match track.get(i) {
        Some(next) if next.t > prev_t => {
            let w = (t - prev_t) / (next.t - prev_t);
            (
                prev.0 + w * (next.east_m - prev.0),
                prev.1 + w * (next.north_m - prev.1),
            )
        }
        _ => prev,
    }
}

/// The shift that draws a PDR track in the frame of the fixes: the position of a fused (or
/// smoothed) step minus the track's position at its time; zero without one.
pub fn offset_onto(track: &[StepRecord], anchor: Option<&FusedStep>) -> (f64, f64) {
    anchor.map_or((0.0, 0.0), |f| {
        let at = position_at(track, f.t);
        (f.east_m - at.0, f.north_m - at.1)
    })
}

/// Counters and current values; read-only.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Diagnostics {
    /// IMU samples accepted.
    pub samples: u64,
    /// Records refused for a non-finite value.
    pub rejected_non_finite: u64,
    /// Records refused because time went backwards.
    pub rejected_backwards: u64,
    /// Samples refused for lacking a field the orientation source needs.
    pub rejected_missing_field: u64,
    /// GNSS fixes accepted.
    pub gnss_fixes: u64,
    /// Gaps in the IMU stream.
    pub gaps: u64,
    /// Time spent in gaps, s.
    pub gap_time_s: f64,
    /// Time the phone was being handled, not walked with ([`crate::engine::handling`]), s.
    pub handling_s: f64,
    /// Where the phone is carried, once decided ([`crate::engine::carry`]).
    pub carry: Option<CarryMode>,
    /// Steps counted, with those a bout's opening still holds off the track
    /// ([`heading::opening`](crate::engine::heading::opening)).
    pub steps: u64,
    /// Steps recovered by the onset look-back.
    pub onset_steps: u64,
    /// Steps for which no heading could be estimated (no displacement applied).
    pub steps_without_heading: u64,
    /// Distance walked, m.
    pub distance_m: f64,
    /// The orientation source in use.
    pub orientation: Option<OrientationSource>,
    /// Current motion state.
    pub motion: Option<Motion>,
    /// Current σ_z, m/s².
    pub sigma_z: f64,
    /// Current detector frequency, Hz (PLL only).
    pub pll_freq_hz: Option<f64>,
    /// Whether the PLL is locked.
    pub pll_locked: Option<bool>,
    /// Step frequency of the periodic gait the motion detector sees, Hz (autocorrelation).
    pub cadence_hz: Option<f64>,
    /// First and last accepted IMU times, s.
    pub time_span: Option<(f64, f64)>,
    /// Magnetic declination applied by the fusion, degrees.
    pub declination_deg: Option<f64>,
    /// Why the declination may be off (no date, no model).
    pub declination_note: Option<DeclinationNote>,
    /// What happened to the fixes in the fusion.
    pub fix_counts: Option<FixCounts>,
    /// Time the GNSS receiver was (or would have been) on, from the first fix to the last
    /// sample, s; and that whole span, s. Energy saving leaves it on for its windows only.
    pub gnss_on_s: Option<(f64, f64)>,
    /// The hybrid heading, with a foot-mounted IMU.
    pub hybrid: Option<HybridDiagnostics>,
    /// The mode that ran: `body` (steps) or `foot` (strides); `auto` while undecided (steps as
    /// `body`).
    pub placement: Placement,
    /// Strides counted in foot mode (each also counts as two steps in `steps`).
    pub strides: u64,
    /// The foot stage, while it runs.
    pub foot: Option<FootDiagnostics>,
    /// The pitch detector was chosen, but the log has no gyroscope: the PLL counted its steps.
    pub detector_fallback: bool,
    /// Barometer readings accepted.
    pub pressure_samples: u64,
    /// The activity now (Munoz Diaz 2015 §4.3), once a sample arrived.
    pub activity: Option<Activity>,
    /// Leg pitch now, degrees (thigh forward positive), when the phone is in a pocket and the
    /// log has a gyroscope.
    pub pitch_deg: Option<f64>,
    /// The leg pitch stage: the swing axis's share and the sign's vote.
    pub leg_pitch: Option<super::leg_pitch::LegPitchDiagnostics>,
    /// Which pocket: the mean swing-axis share, and whether the last step rode behind the hip.
    pub back_pocket: super::back_pocket::BackPocketDiagnostics,
    /// Height now above the walk's start, m.
    pub up_m: f64,
    /// Floor now, relative to the walk's start.
    pub floor: i32,
    /// What the height comes from, once a step changed it or a barometer reading arrived.
    pub vertical: Option<super::vertical::VerticalSource>,
}

/// The streaming engine: it routes each record through its stages.
pub struct Pipeline {
    cfg: PipelineConfig,
    orientation: Orientation,
    motion: MotionDetector,
    handling: Handling,
    carry: Carry,
    magnetic: Magnetic,
    detector: Detector,
    window: window::Window,
    heading: Heading,
    step_length: StepLength,
    bout: bout::Bout,
    track: track::Track,
    gnss: gnss::Gnss,
    foot: foot::FootMode,
    pocket: pocket::Pocket,
    last_t: Option<f64>,
    // The motion state of the latest sample, still while the phone is being handled.
    prev_state: Motion,
    // The last gait the motion detector saw (walking or running).
    last_gait: Motion,
    attitude: Option<nalgebra::UnitQuaternion<f64>>,
    // Whether a sample with a gyroscope has come.
    gyro_seen: bool,
    diag: Diagnostics,
    // The stage clock, when someone times the stages (`pdr bench`).
    clock: Option<Box<StageClock>>,
}

impl Pipeline {
    /// A pipeline with a validated configuration.
    pub fn new(cfg: PipelineConfig) -> Result<Self, ConfigError> {
        cfg.validate()?;
        Ok(Pipeline {
            motion: MotionDetector::new(cfg.motion),
            handling: Handling::new(cfg.handling),
            carry: Carry::new(cfg.carry),
            magnetic: Magnetic::new(cfg.magnetic),
            window: window::Window::new(
                cfg.heading
                    .history_s()
                    .max(cfg.motion.window_s + 2.0)
                    .max(cfg.onset_lookback_s.max(cfg.onset_pocket_lookback_s) + 0.5),
            ),
            detector: Detector::new(cfg.detector),
            heading: Heading::new(cfg.heading),
            step_length: StepLength::new(cfg.step_length.clone(), cfg.thigh_step_length),
            orientation: Orientation::new(cfg.orientation),
            bout: bout::Bout::default(),
            track: track::Track::default(),
            gnss: gnss::Gnss::new(cfg.fusion),
            foot: foot::FootMode::new(&cfg)?,
            pocket: pocket::Pocket::new(&cfg),
            cfg,
            last_t: None,
            prev_state: Motion::Still,
            last_gait: Motion::Walking,
            attitude: None,
            gyro_seen: false,
            diag: Diagnostics::default(),
            clock: None,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &PipelineConfig {
        &self.cfg
    }

    /// Feeds one record of a log: the one entry every caller uses, live or replayed. Returns the
    /// steps it placed on the track (usually none, sometimes several: the onset look-back's, or
    /// those a bout's opening held, [`heading::opening`](crate::engine::heading::opening)). A refused record leaves the state
    /// untouched.
    pub fn push(&mut self, r: &Record) -> Result<&[StepRecord], InputError> {
        match r {
            Record::Imu(s) => self.push_imu(s),
            Record::Gnss(f) => match self.push_gnss(f) {
                Ok(()) => Ok(&[][..]),
                Err(e) => Err(self.refused(e)),
            },
            Record::Gap(t0, t1) => {
                // A gap ends the bout: the steps its opening held are placed.
                let first = self.track.len();
                self.mark_gap(*t0, *t1);
                Ok(&self.track.steps()[first..])
            }
            Record::Foot(s) => self.push_foot_imu(s),
            Record::Pressure(p) => match self.pocket.push_pressure(p) {
                Ok(()) => Ok(&[][..]),
                Err(e) => Err(self.refused(e)),
            },
        }
    }

    /// Counts a refused record by its reason, and returns the reason.
    pub(super) fn refused(&mut self, e: InputError) -> InputError {
        match e {
            InputError::NonFinite { .. } => self.diag.rejected_non_finite += 1,
            InputError::TimeWentBackwards { .. } => self.diag.rejected_backwards += 1,
            InputError::MissingField { .. } => self.diag.rejected_missing_field += 1,
        }
        e
    }

    /// Feeds one IMU sample. Returns the steps it placed on the track (see [`Self::push`]).
    fn push_imu(&mut self, s: &ImuSample) -> Result<&[StepRecord], InputError> {
        if let Err(e) = self.timed(Stage::Check, |p| p.check(s)) {
            return Err(self.refused(e));
        }
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(c) = self.clock.as_mut() {
            c.own_lap();
        }
        let first = self.track.len();
        if self.bout.stalled(s.t) {
            // A bout whose opening is held and has had no step for two strides has ended.
            self.release_opening();
        }
        let dt = self.advance(s.t);
        let nav = self.timed(Stage::Orientation, |p| p.orientation.push(s, dt))?;
        self.diag.orientation = Some(self.orientation.source_now());
        if self.orientation.switched() {
            // The yaw of the new source is not the old one's: the guard's reference restarts.
            self.magnetic.reset();
        }
        let nav = self.timed(Stage::Magnetic, |p| p.magnetic.push(s, dt, nav));
        self.pitch_detector_fallback(s);
        self.timed(Stage::Attitude, |p| {
            p.heading.push_attitude(nav.attitude);
            p.push_trunk_attitude(s.t, nav.attitude);
        });
        self.attitude = nav.attitude;
        let state = self.timed(Stage::Motion, |p| p.motion.push(s.t, nav.up));
        // The phone turned over in the hand walks nowhere.
        let handled = self.timed(Stage::Handling, |p| {
            p.handling.push(s.t, s.gyro.as_ref(), state)
        });
        let state = if handled { Motion::Still } else { state };
        let m = self.motion.diagnostics();
        self.timed(Stage::Carry, |p| {
            p.carry
                .push(s.t, &s.accel, nav.up, s.gyro.as_ref(), handled)
        });
        let mut x = DetectorInput {
            t: s.t,
            dt,
            up: nav.up,
            mean: m.mean_z,
            sigma: m.sigma_z,
            motion: state,
            cadence_hz: m.cadence_hz,
            pitch_deg: None,
            axis_tilt_sin: None,
            pocket: self.carry.mode() == Some(CarryMode::Pocket),
        };
        self.timed(Stage::LegPitch, |p| {
            p.pocket_sample(s, dt, state, &x);
            x.pitch_deg = p.pocket.pitch;
            x.axis_tilt_sin = p.pocket.leg.axis_tilt_sin();
        });
        let (e, n) = nav.horizontal.unwrap_or((0.0, 0.0));
        self.timed(Stage::Window, |p| {
            p.window.push(NavSample {
                t: s.t,
                e,
                n,
                up: nav.up,
                pitch: x.pitch_deg,
                axis_tilt_sin: x.axis_tilt_sin,
                yaw: p.heading.pose().yaw,
                // q⁻¹·ẑ of this sample's attitude: the leg pitch has just taken it.
                device_up: p.pocket.leg.device_up().map_or([0.0; 3], Into::into),
                screen: nav.attitude.map_or([0.0; 2], |q| {
                    let z = q * nalgebra::Vector3::z();
                    [z.x, z.y]
                }),
                guard: p.magnetic.correction(),
                sigma_z: m.sigma_z,
            })
        });
        self.detect_steps(&x);
        // Recognising a foot replaces the steps so far by the strides: all are new then.
        let on_foot = self.timed(Stage::Foot, |p| p.push_foot(s, dt));
        let first = if on_foot { 0 } else { first };
        Ok(&self.track.steps()[first..])
    }

    /// Runs `f` on the pipeline, adding its time to `stage` when a stage clock is on (natively:
    /// a WebAssembly build, the phone's, times nothing and pays nothing for it).
    #[inline(always)]
    fn timed<R>(&mut self, stage: Stage, f: impl FnOnce(&mut Self) -> R) -> R {
        #[cfg(target_arch = "wasm32")]
        {
            let _ = stage;
            f(self)
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            // One call of `f`, so that it is inlined as the stage was before the clock came.
            let start = self.clock.as_ref().map(|c| c.read());
            let r = f(self);
            if let (Some(start), Some(c)) = (start, self.clock.as_mut()) {
                c.lap(stage, start);
            }
            r
        }
    }

    /// Times each stage from now on with `clock` (`None`: no timing, the default). Native
    /// builds only: a WebAssembly build keeps the clock but times nothing.
    pub fn set_stage_clock(&mut self, clock: Option<StageClock>) {
        self.clock = clock.map(Box::new);
    }

    /// The stage clock, when one is on.
    pub fn stage_clock(&self) -> Option<&StageClock> {
        self.clock.as_deref()
    }

    /// The time of the next accepted sample, `t`, s: a gap before it is counted and ends the
    /// bout. Returns the interval since the previous sample, s (0 after a gap).
    fn advance(&mut self, t: f64) -> f64 {
        let mut dt = self.last_t.map_or(0.0, |l| t - l);
        if dt > self.cfg.gap_s {
            self.gap(dt);
            dt = 0.0;
        }
        self.last_t = Some(t);
        self.diag.samples += 1;
        self.diag.time_span = Some((self.diag.time_span.map_or(t, |p| p.0), t));
        dt
    }

    /// Runs the step detector on sample `x` and emits its steps: at the onset of a gait the
    /// look-back's, else the step decided now and the one it held a cycle, if any. Foot mode
    /// emits strides instead.
    fn detect_steps(&mut self, x: &DetectorInput) {
        let state = x.motion;
        let cand = self.timed(Stage::StepDetector, |p| p.detector.push(x));
        // A step the PLL decided only now, earlier than `cand`, with the pose at which it was
        // held for the next cycle, if it was.
        let late = self.detector.take_late_step();
        let heading = &self.heading;
        let late_pose = self
            .bout
            .follow_detector(late.is_some(), self.detector.holding(), || heading.pose());
        if state.is_moving() && !self.prev_state.is_moving() {
            // Onset: σ_z and the periodicity confirm a gait only a second or two after it
            // starts. The detector looks back over the samples of that delay, started afresh
            // on the cadence now found, and its steps are emitted.
            for c in self.look_back(x.t, state) {
                if self.foot.on_foot() {
                    continue;
                }
                if self.bout.is_new(&c) {
                    self.track.count_onset();
                    self.timed(Stage::Emission, |p| p.emit(c, state, None));
                }
            }
        } else if !self.foot.on_foot() {
            // A step held while a gait was seen counts even when the motion detector has
            // stopped seeing it since.
            if let Some(c) = late {
                let gait = self.last_gait;
                self.timed(Stage::Emission, |p| p.emit(c, gait, late_pose));
            }
            if let Some(c) = cand.filter(|_| state.is_moving()) {
                self.timed(Stage::Emission, |p| p.emit(c, state, None));
            }
        }
        if state.is_moving() {
            self.last_gait = state;
        }
        self.prev_state = state;
    }

    /// The leg pitch needs a gyroscope: without one the PLL counts the steps. A gyroscope that
    /// begins after the first samples (as phones' do) gets the pitch detector back when it
    /// does; one that stops after it began leaves the PLL to count.
    fn pitch_detector_fallback(&mut self, s: &ImuSample) {
        match (s.gyro, &self.cfg.detector, &self.detector) {
            (None, _, Detector::Pitch(_)) => {
                self.detector = Detector::new(StepDetectorConfig::default());
                self.diag.detector_fallback = true;
            }
            (Some(_), StepDetectorConfig::Pitch(c), _)
                if self.diag.detector_fallback && !self.gyro_seen =>
            {
                self.detector = Detector::new(StepDetectorConfig::Pitch(*c));
                self.diag.detector_fallback = false;
            }
            _ => {}
        }
        self.gyro_seen |= s.gyro.is_some();
    }

    fn check(&self, s: &ImuSample) -> Result<(), InputError> {
        s.check()?;
        if let Some(last) = self.last_t {
            if s.t < last {
                return Err(InputError::TimeWentBackwards { t: s.t, last });
            }
        }
        self.orientation.check(s)
    }

    fn gap(&mut self, dt: f64) {
        self.diag.gaps += 1;
        self.diag.gap_time_s += dt;
        self.motion.clear_window();
        self.handling.clear();
        self.carry.clear();
        self.magnetic.reset();
        self.window.clear();
        self.detector.gap();
        self.foot.gap();
        self.end_bout();
    }

    fn end_bout(&mut self) {
        self.release_opening();
        self.gnss.end_bout();
        self.bout.end();
        self.heading.end_bout();
    }

    /// Tells the engine that the input stopped between `t0` and `t1` (page hidden, sensor
    /// paused). The next sample after `t1` starts a new bout; nothing bridges the gap. A gap
    /// whose times are out of range ([`super::types::MAX_TIME_S`]) is ignored.
    pub fn mark_gap(&mut self, t0: f64, t1: f64) {
        if t1 > t0 && time_in_range(t0) && time_in_range(t1) {
            self.gap(t1 - t0);
            // The interval is now accounted for; the next sample must not count it again.
            self.last_t = Some(self.last_t.map_or(t1, |l| l.max(t1)));
        }
    }

    /// The input has ended: places the steps still held at a bout's opening
    /// ([`heading::opening`](crate::engine::heading::opening)) and returns them.
    pub fn finish(&mut self) -> &[StepRecord] {
        let first = self.track.len();
        self.release_opening();
        &self.track.steps()[first..]
    }

    /// Every step so far (without the few a bout's opening may still hold, [`Self::finish`]).
    pub fn track(&self) -> &[StepRecord] {
        self.track.steps()
    }

    /// The steps a bout's opening holds off the track, in order: they follow [`Self::track`]
    /// when released ([`heading::opening`](crate::engine::heading::opening)); their positions are not yet known (0).
    pub fn held_steps(&self) -> impl Iterator<Item = &StepRecord> {
        self.bout.held_steps()
    }

    /// The carrying-mode detector's features and votes.
    pub fn carry_diagnostics(&self) -> crate::engine::carry::CarryDiagnostics {
        self.carry.diagnostics()
    }

    /// The magnetic guard's reference, share disturbed and yaw correction.
    pub fn magnetic_diagnostics(&self) -> crate::engine::magnetic::MagneticDiagnostics {
        self.magnetic.diagnostics()
    }

    /// Counters and current values.
    pub fn diagnostics(&self) -> Diagnostics {
        let mut d = self.diag;
        let t = self.track.counts();
        d.steps = t.steps;
        d.onset_steps = t.onset_steps;
        d.steps_without_heading = t.steps_without_heading;
        d.distance_m = t.distance_m;
        d.strides = t.strides;
        let g = self.gnss.diagnostics();
        d.gnss_fixes = g.fixes;
        d.declination_deg = g.declination_deg;
        d.declination_note = g.declination_note;
        d.fix_counts = g.fix_counts;
        d.gnss_on_s = g.gnss_on_s;
        d.hybrid = self.foot.hybrid_diagnostics();
        let m = self.motion.diagnostics();
        let started = self.diag.samples > 0;
        d.motion = started.then_some(self.prev_state);
        d.sigma_z = m.sigma_z;
        d.cadence_hz = m.cadence_hz;
        d.handling_s = self.handling.total_s();
        d.carry = self.carry.mode();
        d.placement = self.foot.placement();
        d.foot = self.foot.diagnostics();
        if let Detector::Pll(p) = &self.detector {
            let p = p.diagnostics();
            d.pll_freq_hz = Some(p.freq_hz);
            d.pll_locked = Some(p.locked);
        }
        self.pocket_diagnostics(&mut d);
        d
    }

    /// The activity, the leg pitch and the height in `d`.
    fn pocket_diagnostics(&self, d: &mut Diagnostics) {
        let started = self.diag.samples > 0;
        d.activity = started.then(|| {
            if self.handling.active() {
                Activity::Handling
            } else if self.prev_state.is_moving() {
                self.track
                    .steps()
                    .last()
                    .map_or(Activity::Walking, |s| s.activity)
            } else {
                self.pocket.activity.diagnostics().activity
            }
        });
        d.pitch_deg = self.pocket.pitch.map(|r| self.pocket.leg.signed(r));
        d.leg_pitch = Some(self.pocket.leg.diagnostics());
        d.back_pocket = self.pocket.side.diagnostics();
        d.pressure_samples = self.pocket.pressure_samples;
        let v = self.pocket.vertical.diagnostics();
        d.up_m = v.up_m;
        d.floor = v.floor;
        d.vertical = v.source;
    }

    /// Vertical linear acceleration of the latest sample, m/s², up positive.
    pub fn vertical_accel(&self) -> Option<f64> {
        self.window.last().map(|x| x.up)
    }

    /// The latest sample in the navigation frame: vertical, east and north acceleration, m/s².
    pub fn last_nav(&self) -> Option<(f64, f64, f64)> {
        self.window.last().map(|x| (x.up, x.e, x.n))
    }

    /// The motion state now: the motion detector's, still while the phone is being handled.
    pub fn motion_state(&self) -> Motion {
        self.prev_state
    }

    /// The device → ENU attitude of the latest sample, when the orientation source has one.
    pub fn attitude(&self) -> Option<nalgebra::UnitQuaternion<f64>> {
        self.attitude
    }

    /// The orientation stage's diagnostics (the KF-NFA's R scale and mismatch), once started.
    pub fn orientation_diagnostics(&self) -> Option<super::orientation::OrientationDiagnostics> {
        (self.diag.samples > 0).then(|| self.orientation.diagnostics())
    }

    /// Mean and σ of the vertical acceleration over the motion detector's window, m/s².
    pub fn vertical_stats(&self) -> (f64, f64) {
        (self.motion.mean(), self.motion.sigma())
    }

    /// PLL oscillator output cos φ, if the detector is a PLL.
    pub fn pll_output(&self) -> Option<f64> {
        match &self.detector {
            Detector::Pll(p) => Some(p.output()),
            Detector::Peak(_) | Detector::ZeroCrossing(_) | Detector::Pitch(_) => None,
        }
    }
}
