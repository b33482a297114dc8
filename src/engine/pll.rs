//! Step detection by a phase-locked loop on vertical acceleration (Basso 2016 §II.C, Fig. 2;
//! Basso 2021 §2.2.2, Fig. 5).
//! May import: the rest of `engine`.
//!
//! The loop has the three blocks of Basso 2016 Fig. 2:
//! - **Phase detector**: a multiplier. With the normalised input x = A cos φᵢ and the oscillator
//!   phase φ, e = −x·sin φ = (A/2)·sin(φᵢ − φ) + (terms at 2f), so e ≈ K_d (φᵢ − φ) with
//!   K_d = A/2. The input is normalised by the σ_z of the motion detector, so A ≈ √2 and the loop
//!   gain does not depend on how hard the person walks.
//! - **Loop low-pass filter**: a first-order low-pass (cut-off [`PllConfig::loop_lpf_hz`]) that
//!   removes the 2f product term, followed by a proportional-integral stage. The PI stage makes the
//!   loop type 2: a frequency step is tracked with zero steady-state phase error, so the
//!   oscillator peaks stay on the vertical-acceleration peaks whatever the cadence.
//! - **Controlled oscillator**: φ advances by 2π f dt with the `dt` of each sample.
//!
//! A step is counted at each peak of the oscillator output cos φ (φ crossing a multiple of 2π),
//! at a time interpolated inside the sample interval, and f_k = 1/T_k (Basso 2016 §II.C).
//!
//! # Which peaks count (our additions)
//! A peak counts only if its cycle carries motion, judged over the cycle centred on it (φ from
//! −π to π, so the verdict comes half a period after the peak): its RMS must reach
//! [`PllConfig::cycle_rms_min`], and either [`PllConfig::cycle_rms_rel`]·σ_z or
//! [`PllConfig::same_leg_rel`] of the same leg's previous counted step (two cycles back), or
//! [`PllConfig::between_steps_rel`]·σ_z between two counted steps (given a cycle late); and the
//! input must rise to [`PllConfig::peak_share_min`] ([`PllConfig::thigh_peak_share_min`] on a
//! thigh or in a pocket) of that RMS within a quarter period of the oscillator's peak. Centring the cycle on
//! the peak means the half cycle of deceleration after the last step of a walk is not taken for
//! one more step.
//!
//! # Loop design
//! Linearised, the closed loop is s² + 2π K_d K_p s + 2π K_d K_i = 0, so with natural frequency
//! ω_n = 2π·[`PllConfig::natural_hz`] and damping ζ: K_p = 2ζω_n / (2π K_d), K_i = ω_n² / (2π K_d).
//! Defaults: f_n = 0.3 Hz, ζ = 0.707, so the noise bandwidth B_L = ω_n(ζ + 1/(4ζ))/2 ≈ 1.0 rad/s
//! (0.17 Hz) and the loop settles in about 4/(ζω_n) ≈ 3 s. The lock-in range (lock within one
//! beat cycle) is about ±2ζω_n/2π ≈ ±0.42 Hz around the free-running frequency; with the integrator
//! the pull-in range covers the whole band the frequency is clamped to.
//!
//! # Free-running frequencies and bands
//! Walking: 1.8 Hz (Basso 2016 and 2021), band 1.2–2.7 Hz. Running: 3.4 Hz, the middle of Basso
//! 2016's 2.7–4.2 Hz running band (geometric mean 3.37 Hz), band 2.3–4.6 Hz. The band follows the
//! motion state; clamping to it keeps the loop off the stride sub-harmonic (f/2, strong for a
//! phone on the thigh) and off the second harmonic.
//!
//! # Acquisition aid
//! Pull-in from far outside the lock-in range takes seconds with a loop this narrow (e.g. from
//! 1.8 Hz to 3.4 Hz when someone starts running). While the loop is unlocked, the frequency of
//! four regular upward zero crossings (three cycles) of the input re-seeds the integrator when it differs by
//! more than the lock-in range (a frequency-assisted PLL, Best 2007 ch. 2).
//!
//! # Loss of lock
//! A lock indicator, the low-passed in-phase product x·cos φ (≈ 0.7 when locked, ≈ 0 otherwise), is
//! reported for diagnostics. When the input stops being periodic the oscillator keeps running near
//! its last frequency; such cycles are not counted because each cycle must itself carry motion:
//! the RMS of the input over the cycle must reach [`PllConfig::cycle_rms_min`]. While the person is
//! still the loop idles in the walking band, and when there is nothing to follow its integrator
//! relaxes to the free-running frequency. When the motion detector confirms a gait, the pipeline
//! restarts the loop on the cadence found ([`Pll::restart`], [`Pll::start_on`]) and replays the last seconds
//! through it (the onset look-back, see [`crate::engine::pipeline`]).

use super::detector::{Candidate, DetectorInput};
use super::math::OnePole;
use super::motion::Motion;
use super::types::{positive, ConfigError};
use std::f64::consts::{PI, TAU};

/// Settings of the PLL step detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PllConfig {
    /// Free-running frequency while walking or still, Hz (Basso: 1.8).
    pub free_running_walk_hz: f64,
    /// Free-running frequency while running, Hz.
    pub free_running_run_hz: f64,
    /// Frequency band while walking or still, Hz.
    pub walk_band_hz: (f64, f64),
    /// Frequency band while running, Hz.
    pub run_band_hz: (f64, f64),
    /// Loop natural frequency, Hz.
    pub natural_hz: f64,
    /// Loop damping ratio.
    pub damping: f64,
    /// Cut-off of the loop low-pass filter, Hz.
    pub loop_lpf_hz: f64,
    /// Minimum RMS of the vertical acceleration over one oscillator cycle for its peak to count
    /// as a step, m/s². Default: 0.35, about 2/3 of the motion detector's
    /// [`crate::engine::MotionConfig::periodic_sigma_min`], low enough for gentle hand-held
    /// walks (σ ≈ 1 m/s²).
    pub cycle_rms_min: f64,
    /// Minimum RMS of a cycle relative to the σ_z of the motion window. After a stop σ_z (2 s)
    /// stays high while the new cycles are quiet; this gate, not the absolute one, is what keeps
    /// steps from being counted while the window drains. 0.5: a steady gait gives ≈ 1.
    pub cycle_rms_rel: f64,
    /// With the phone on a thigh ([`DetectorInput::axis_tilt_sin`] given) or in a pocket
    /// ([`DetectorInput::pocket`]), a cycle that fails
    /// [`PllConfig::cycle_rms_rel`] and [`PllConfig::same_leg_rel`] but reaches this share of
    /// σ_z, right after a counted step, counts when the cycle after it counts too: a far leg's
    /// step between two of the near leg's. It is given a cycle late ([`Pll::take_late_step`]).
    /// Departure from the paper: in a trouser pocket σ_z is dominated by the near leg, and the
    /// far leg's cycles give 0.3–0.5 σ_z; the cycle after the last step of a walk is followed
    /// by no step, so the stop is still kept. Off a thigh both legs move the phone alike and
    /// the rule does nothing (applied to any phone it cost Oxford's counts 1.39 → 1.46 %). A back
    /// pocket rides on the buttock, which the leg pitch never takes for a thigh, so the carrying
    /// mode's pocket counts too: with it UbiComp's back pockets 3.96 → 2.70 %, Oxford 1.37 →
    /// 1.39 % (docs/methods/basso2016.md, "Every pocket, from its onset").
    ///
    /// Default 0.3. On WeAllWalk (pocket iPhones, heel strikes from shoe sensors) 90 of 7 035
    /// cycles within 0.3 s of a heel strike fall under 0.5 σ_z and 5 under 0.3 σ_z, against 53
    /// and 17 of the 165 cycles with no heel strike near them (docs/methods/basso2016.md, "The
    /// cycle gates in a pocket"). 0.5 or more turns the rule off.
    pub between_steps_rel: f64,
    /// A cycle that fails [`PllConfig::cycle_rms_rel`] still counts when its RMS reaches this
    /// share of the cycle two before it, if that one counted: the same leg's previous step.
    /// Departure from the paper: with the phone in a front pocket the near leg's steps are two
    /// to three times louder than the far leg's, so the σ-relative gate alone drops the far
    /// leg's. A stop still ends the count: the first quiet cycle is compared with a real step of
    /// the same leg and fails.
    pub same_leg_rel: f64,
    /// The input must rise to at least this share of the cycle's RMS within a quarter period
    /// of the oscillator's peak for the peak to count: a step has a peak where the oscillator
    /// puts it. The cycle after the last step of a walk (the body settling) carries some motion
    /// but no peak.
    pub peak_share_min: f64,
    /// [`PllConfig::peak_share_min`] with the phone on a thigh ([`DetectorInput::axis_tilt_sin`]
    /// given) or in a pocket ([`DetectorInput::pocket`]). There the loop holds the phase of the step frequency loosely (lock indicator
    /// 0.1–0.4 against ≈ 0.7 for a sinusoid: a thigh's vertical acceleration is far from one,
    /// with a strong stride harmonic and sharp heel strikes), so a real step's peak can fall at
    /// the edge of the quarter period. Departure from the paper, which has no such gate.
    ///
    /// Default 0.3. On WeAllWalk (pocket iPhones, heel strikes from shoe sensors), of the
    /// cycles with an RMS above [`PllConfig::cycle_rms_min`], 80 of 7 124 near a heel strike
    /// stay under 0.5 of their RMS and 43 under 0.3, against 42 and 29 of the 209 with none.
    /// For every phone, 0.3 cost the hand-held sets (IPIN 2023: one more log fused worse than
    /// its GNSS; Microsoft's waypoint p75 5.61 → 5.67 m).
    pub thigh_peak_share_min: f64,
    /// When the motion detector has a cadence estimate f_c (autocorrelation, see
    /// [`crate::engine::motion::Periodicity`]), the band is narrowed to [f_c/k, k·f_c] with this
    /// k. Departure from the paper, whose bands follow the σ_z state only: a band as wide as
    /// 1.2–2.7 Hz holds both the step frequency and its second harmonic for slow walks. k = 1.4,
    /// just under
    /// √2, the geometric midpoint between f and 2f (and f/2), so the loop can never hold either.
    pub cadence_band_ratio: f64,
    /// The first step of a walk, from standing, lifts the pelvis weakly: with the phone in a
    /// pocket its cycle's RMS is about half the σ_z of the walk and fails
    /// [`PllConfig::cycle_rms_rel`], while the thigh already swings much of a step.
    /// So with the leg pitch known ([`DetectorInput::pitch_deg`]) all through both cycles, a
    /// cycle that fails only the σ-relative gate just before the first step counted since a
    /// restart is counted too ([`Pll::take_late_step`]) when the limb swung over it by at least
    /// this share of that step's swing, itself at least [`FIRST_SWING_MIN_DEG`]. Departure from
    /// the paper; 0 turns it off.
    ///
    /// Default 0.4. The first step starts from standing, the thigh upright: the leading thigh
    /// flexes (to about 0.68 of a stride's Δθ, Munoz Diaz's θ_Hmax ≫ |θ_Hmin|), the trailing one
    /// only extends (to about 0.32 Δθ), against a walking cycle's swing of about 0.6 Δθ. So a
    /// trailing thigh's first cycle swings about half of the next at full strength, less for a
    /// short first step, and the share sits below that.
    pub first_swing_rel: f64,
    /// With the phone on a thigh, the first cycle over which the thigh's swing axis tilts
    /// further than this from the horizontal ([`DetectorInput::axis_tilt_sin`]) is no step: the
    /// phone is leaving the thigh. The cycles after it count as any phone's until one is level
    /// again, so a phone moved to the hand mid-walk loses one step, not the rest of the walk.
    /// Departure from the paper: taking the phone out of the pocket after a walk jerks it at a
    /// walking rhythm, which would count as a step; a walk's cycles tilt the axis by about the
    /// hip's ab- and adduction and the pelvis's roll, ±5° each on a real thigh. Default 15°,
    /// above that. A brisk real step can tilt it further for one cycle (UbiComp 2013's fast
    /// pace: 16–21°, the cycles before and after 3–9°), so the refused step counts, a cycle
    /// late, when the next cycle is level again (within [`LEVEL_TILT_DEG`]): a phone taken out
    /// stays tilted.
    pub axis_tilt_max_deg: f64,
    /// With the phone on a limb ([`DetectorInput::axis_tilt_sin`] given), a step after a
    /// standing cycle (one below [`PllConfig::cycle_rms_min`]) in a walk under way is held until
    /// the next cycle is judged, and is no step when that cycle moves without a step's peak
    /// (it fails [`PllConfig::peak_share_min`] or the tilt, not the RMS): a lone jolt between
    /// standing and handling. Departure from the paper: a phone taken out of the pocket just
    /// after the last step is jerked free at a walking rhythm over one cycle, which may tilt
    /// the thigh's axis by less than [`PllConfig::axis_tilt_max_deg`]. A step followed by a
    /// step, or by standing (a single step taken on the spot), counts, a cycle late. Off a limb
    /// the rule does nothing. `false`: as the paper.
    pub lone_step_confirm: bool,
}

/// The largest tilt of the thigh's swing axis over a cycle, degrees, for the cycle after one
/// refused for its tilt ([`PllConfig::axis_tilt_max_deg`]) to say the phone is still on the
/// thigh: a walk's cycles tilt the axis by about the hip's ab- and adduction and the pelvis's
/// roll, ±5° each.
pub const LEVEL_TILT_DEG: f64 = 10.0;

/// The leg pitch's range over a cycle that has had no sample yet.
const NO_PITCH_YET: (f64, f64) = (f64::INFINITY, f64::NEG_INFINITY);

/// The least swing of the limb over the first counted cycle, degrees, for the cycle before it
/// to be weighed by [`PllConfig::first_swing_rel`]: a thigh's or an arm's step swings it by
/// 20–40° over a cycle; a hand-held phone rocks about its dominant axis by a few degrees while
/// it is carried, but more while it is handled, when the other condition, a pitch known all
/// through both cycles, keeps its quiet cycle out.
pub const FIRST_SWING_MIN_DEG: f64 = 15.0;

impl Default for PllConfig {
    fn default() -> Self {
        PllConfig {
            free_running_walk_hz: 1.8,
            free_running_run_hz: 3.4,
            walk_band_hz: (1.2, 2.7),
            run_band_hz: (2.3, 4.6),
            natural_hz: 0.3,
            damping: 0.707,
            loop_lpf_hz: 1.5,
            cycle_rms_min: 0.35,
            cycle_rms_rel: 0.5,
            between_steps_rel: 0.3,
            same_leg_rel: 0.6,
            peak_share_min: 0.5,
            thigh_peak_share_min: 0.3,
            cadence_band_ratio: 1.4,
            first_swing_rel: 0.4,
            axis_tilt_max_deg: 15.0,
            lone_step_confirm: true,
        }
    }
}

impl PllConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("pll.natural_hz", self.natural_hz)?;
        positive("pll.damping", self.damping)?;
        positive("pll.loop_lpf_hz", self.loop_lpf_hz)?;
        positive("pll.cycle_rms_min", self.cycle_rms_min)?;
        positive("pll.cycle_rms_rel", self.cycle_rms_rel)?;
        positive("pll.between_steps_rel", self.between_steps_rel)?;
        positive("pll.same_leg_rel", self.same_leg_rel)?;
        positive("pll.peak_share_min", self.peak_share_min)?;
        positive("pll.thigh_peak_share_min", self.thigh_peak_share_min)?;
        positive("pll.axis_tilt_max_deg", self.axis_tilt_max_deg)?;
        if !(0.0..=1.0).contains(&self.first_swing_rel) {
            return Err(ConfigError::new("pll.first_swing_rel", "must be in [0, 1]"));
        }
        if !(self.cadence_band_ratio > 1.0) {
            return Err(ConfigError::new("pll.cadence_band_ratio", "must exceed 1"));
        }
        for (band, free, name) in [
            (
                self.walk_band_hz,
                self.free_running_walk_hz,
                "pll.walk_band_hz",
            ),
            (
                self.run_band_hz,
                self.free_running_run_hz,
                "pll.run_band_hz",
            ),
        ] {
            positive(name, band.0)?;
            if !(band.1 > band.0 && free >= band.0 && free <= band.1) {
                return Err(ConfigError::new(name, format!("band {band:?} must be increasing and contain the free-running frequency {free}")));
            }
        }
        Ok(())
    }
}

/// The loop's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PllDiagnostics {
    /// Tracked step frequency, Hz ([`Pll::frequency`]).
    pub freq_hz: f64,
    /// Oscillator output cos φ.
    pub output: f64,
    /// Lock indicator ([`Pll::lock_indicator`]).
    pub lock_indicator: f64,
    /// Whether the loop is considered locked.
    pub locked: bool,
    /// Oscillator phase in [0, 2π).
    pub phase: f64,
}

/// The PLL: its settings, the loop gains derived from them once, and its running state.
#[derive(Debug, Clone)]
pub struct Pll {
    cfg: PllConfig,
    kp: f64,
    ki: f64,
    s: PllState,
    // Whether the last cycle tilted the thigh's swing axis beyond [`PllConfig::axis_tilt_max_deg`]:
    // the phone left the thigh in the first such cycle, which was refused, and until a cycle
    // is level again (the axis learnt afresh, or the phone back) the tilt refuses no other.
    // Kept across a restart: it says where the phone is, not what the loop does.
    tilted: bool,
}

/// The loop's running state, apart from its settings: a restart is a fresh state.
#[derive(Debug, Clone)]
struct PllState {
    phase: f64,
    freq: f64,
    integ: f64,
    loop_lpf: OnePole,
    lock: OnePole,
    cycle_sq: f64,
    cycle_dt: f64,
    // Σ d·cos φ·dt and Σ cos² φ·dt over the cycle.
    cycle_xc: f64,
    cycle_cc: f64,
    // Largest input within a quarter period of the oscillator's peak.
    peak_max: f64,
    // The last oscillator peak (time, period) whose cycle is not judged yet.
    pending: Option<(f64, f64)>,
    // RMS of the last two cycles, newest first, and whether they counted.
    prev_cycles: [(f64, bool); 2],
    // The leg pitch's least and largest raw angle over the cycle, degrees ([`NO_PITCH_YET`]
    // before its first sample); `None` once a sample of the cycle had none.
    cycle_pitch: Option<(f64, f64)>,
    // The sine of the largest tilt of the thigh's swing axis over the cycle (0 without one):
    // the largest sine, whose arcsine is the largest tilt.
    cycle_tilt_sin: f64,
    // Whether a cycle counted since the restart.
    counted: bool,
    // The last cycle, when it failed only the σ-relative gate before any counted: its step
    // and the limb's swing over it.
    quiet: Option<(Candidate, f64)>,
    // A step counted only with the next cycle's judgement ([`Pll::take_late_step`]): the
    // quiet one before the first counted, or the held one below once the next cycle stepped
    // or stood.
    late: Option<Candidate>,
    // A step after a standing cycle, held until the next cycle is judged
    // ([`PllConfig::lone_step_confirm`]).
    held: Option<Candidate>,
    // A quiet cycle right after a counted step, which counts if the next cycle does
    // ([`PllConfig::between_steps_rel`]).
    between: Option<Candidate>,
    // A step refused only for its cycle's tilt, which counts if the next cycle is level again
    // ([`PllConfig::axis_tilt_max_deg`]).
    tilt_held: Option<Candidate>,
    output: f64,
    phasor: (f64, f64),
    // Acquisition aid: times of upward zero crossings (with hysteresis) of the input.
    armed: bool,
    crossings: [f64; 4],
    n_cross: usize,
    // The band of the last (motion, cadence), which change a few times a second at most.
    band_key: Option<(Motion, Option<f64>)>,
    band_val: (f64, f64, f64),
}

impl PllState {
    /// At the walking free-running frequency, phase 0.
    fn new(cfg: &PllConfig) -> Self {
        PllState {
            phase: 0.0,
            freq: cfg.free_running_walk_hz,
            integ: cfg.free_running_walk_hz,
            loop_lpf: OnePole::with_cutoff_hz(cfg.loop_lpf_hz),
            lock: OnePole::new(1.0),
            cycle_sq: 0.0,
            cycle_dt: 0.0,
            cycle_xc: 0.0,
            cycle_cc: 0.0,
            peak_max: f64::NEG_INFINITY,
            prev_cycles: [(0.0, false); 2],
            cycle_pitch: Some(NO_PITCH_YET),
            cycle_tilt_sin: 0.0,
            counted: false,
            quiet: None,
            late: None,
            held: None,
            between: None,
            tilt_held: None,
            pending: None,
            output: 1.0,
            phasor: (0.0, 1.0),
            armed: false,
            crossings: [0.0; 4],
            n_cross: 0,
            band_key: None,
            band_val: (0.0, 0.0, 0.0),
        }
    }
}

impl Pll {
    /// A loop at the walking free-running frequency.
    pub fn new(cfg: PllConfig) -> Self {
        // K_d ≈ A/2 with the normalised amplitude A = √2.
        let kd = std::f64::consts::FRAC_1_SQRT_2;
        let wn = TAU * cfg.natural_hz;
        let kp = 2.0 * cfg.damping * wn / (TAU * kd);
        let ki = wn * wn / (TAU * kd);
        Pll {
            s: PllState::new(&cfg),
            cfg,
            kp,
            ki,
            tilted: false,
        }
    }

    fn band(&self, m: Motion, cadence: Option<f64>) -> (f64, f64, f64) {
        let (w, r) = (self.cfg.walk_band_hz, self.cfg.run_band_hz);
        let (lo, hi, free) = match m {
            Motion::Running => (r.0, r.1, self.cfg.free_running_run_hz),
            Motion::Walking => (w.0, w.1, self.cfg.free_running_walk_hz),
            // While still the loop idles in the walking band; a start is looked back on with
            // the cadence found (see the pipeline's onset look-back).
            Motion::Still => (w.0, w.1, self.cfg.free_running_walk_hz),
        };
        match cadence {
            Some(fc) => {
                let k = self.cfg.cadence_band_ratio;
                let (l, h) = (lo.max(fc / k), hi.min(fc * k));
                if l < h {
                    (l, h, free.clamp(l, h))
                } else {
                    (lo, hi, free)
                }
            }
            None => (lo, hi, free),
        }
    }

    /// Starts the loop on a gait already under way: frequency `freq_hz` (the motion detector's
    /// cadence estimate), phase fitted to `samples` (time s, vertical acceleration m/s², with
    /// window mean `mu`) that are about to be fed to [`Pll::push`], so that the oscillator peaks
    /// fall on the acceleration peaks from the first cycle. The phase is that of the Fourier
    /// coefficient at `freq_hz` of the samples from `fit_from` s on (trapezoidal sums; computed
    /// once per start): the samples before it are fed to the loop but not fitted.
    pub fn start_on(&mut self, freq_hz: f64, samples: &[(f64, f64)], mu: f64, fit_from: f64) {
        let Some(&(t0, _)) = samples.first() else {
            return;
        };
        let w = TAU * freq_hz;
        let (mut c, mut s) = (0.0, 0.0);
        for p in samples.windows(2).filter(|p| p[0].0 >= fit_from) {
            let ((ta, a), (tb, b)) = (p[0], p[1]);
            let (sa, ca) = libm::sincos(w * (ta - t0));
            let (sb, cb) = libm::sincos(w * (tb - t0));
            let h = 0.5 * (tb - ta);
            c += h * ((a - mu) * ca + (b - mu) * cb);
            s += h * ((a - mu) * sa + (b - mu) * sb);
        }
        // Input ≈ A cos(w(t − t0) − ψ) with ψ = atan2(s, c); the oscillator is cos φ.
        let phase = crate::engine::math::wrap_2pi(-libm::atan2(s, c));
        self.reset_phase();
        self.s.phase = phase;
        self.s.phasor = libm::sincos(phase);
        self.s.integ = freq_hz;
        self.s.freq = freq_hz;
    }

    /// Restarts the oscillator at a peak at time of the next sample (after a gap).
    pub fn reset_phase(&mut self) {
        self.s.phase = 0.0;
        self.s.phasor = (0.0, 1.0);
        self.s.cycle_sq = 0.0;
        self.s.cycle_dt = 0.0;
        self.s.cycle_xc = 0.0;
        self.s.cycle_cc = 0.0;
        self.s.peak_max = f64::NEG_INFINITY;
        self.s.prev_cycles = [(0.0, false); 2];
        self.s.cycle_pitch = Some(NO_PITCH_YET);
        self.s.cycle_tilt_sin = 0.0;
        self.s.pending = None;
        // A step held for the next cycle is undecided: counted, as without the rule.
        self.s.late = self.s.late.or(self.s.held.take());
        // A quiet cycle waiting for the next one is undecided: not counted, as without the rule;
        // so is a tilted one.
        self.s.between = None;
        self.s.tilt_held = None;
        self.s.loop_lpf.reset();
        self.s.n_cross = 0;
    }

    /// Frequency from the last upward zero crossings of the input, when they are regular.
    fn crossing_frequency(&mut self, t: f64, x: f64) -> Option<f64> {
        if x < -0.3 {
            self.s.armed = true;
        } else if x > 0.3 && self.s.armed {
            self.s.armed = false;
            self.s.crossings.rotate_left(1);
            self.s.crossings[3] = t;
            self.s.n_cross = (self.s.n_cross + 1).min(4);
            if self.s.n_cross == 4 {
                let c = &self.s.crossings;
                let span = c[3] - c[0];
                let regular = (1..4).all(|i| ((c[i] - c[i - 1]) * 3.0 / span - 1.0).abs() < 0.2);
                if regular && span > 0.0 {
                    return Some(3.0 / span);
                }
            }
        }
        None
    }

    /// Feeds one vertical-acceleration sample with the motion detector's view of it.
    pub fn push(&mut self, x: &DetectorInput) -> Option<Candidate> {
        let (lo, hi) = self.follow_band(x);
        // Controlled oscillator.
        let prev = self.s.phase;
        self.s.phase += TAU * self.s.freq * x.dt;
        let d = x.up - x.mean;
        // A peak of the oscillator (φ crossing 2π) is a step candidate at the time interpolated
        // inside the sample interval.
        let wrapped = self.s.phase >= TAU;
        if wrapped {
            let frac = if self.s.phase > prev {
                (TAU - prev) / (self.s.phase - prev)
            } else {
                1.0
            };
            self.s.pending = Some((x.t - x.dt + frac * x.dt, 1.0 / self.s.integ));
            self.s.phase -= TAU * (self.s.phase / TAU).floor();
        }
        // The step's cycle runs from the trough before its peak to the trough after it (φ from
        // −π to π), so it is judged half a period after the peak, when φ crosses π.
        let from = if wrapped { prev - TAU } else { prev };
        let out = if from < PI && self.s.phase >= PI {
            self.end_cycle(x, d, from)
        } else {
            self.s.cycle_tilt_sin = self.s.cycle_tilt_sin.max(x.axis_tilt_sin.unwrap_or(0.0));
            self.s.cycle_sq += d * d * x.dt;
            self.s.cycle_dt += x.dt;
            self.s.cycle_pitch = self
                .s
                .cycle_pitch
                .zip(x.pitch_deg)
                .map(|((lo, hi), p)| (lo.min(p), hi.max(p)));
            None
        };
        self.track(x, d, prev, wrapped, (lo, hi));
        out
    }

    /// The frequency band of the motion state and cadence of `x`, low and high, Hz, with the
    /// integrator clamped into it and, with nothing to follow, relaxed towards the free-running
    /// frequency.
    fn follow_band(&mut self, x: &DetectorInput) -> (f64, f64) {
        if self.s.band_key != Some((x.motion, x.cadence_hz)) {
            self.s.band_key = Some((x.motion, x.cadence_hz));
            self.s.band_val = self.band(x.motion, x.cadence_hz);
        }
        let (lo, hi, free) = self.s.band_val;
        // A change of band (walking ↔ running) clamps the estimate into the new band, so the
        // loop keeps its lock across the transition.
        self.s.integ = self.s.integ.clamp(lo, hi);
        if x.motion == Motion::Still && x.sigma < 0.5 * self.cfg.cycle_rms_min {
            // Nothing to follow: relax towards the free-running frequency (time constant 2 s).
            self.s.integ += x.dt / (2.0 + x.dt) * (free - self.s.integ);
        }
        (lo, hi)
    }

    /// The cycle ends at this sample (φ crossed π after `from`): the step of its peak is judged
    /// ([`Self::judge`]) and the next cycle starts with the rest of the sample. `d` is the
    /// sample's deviation from the mean, m/s².
    fn end_cycle(&mut self, x: &DetectorInput, d: f64, from: f64) -> Option<Candidate> {
        let (dt, tilt_sin) = (x.dt, x.axis_tilt_sin.unwrap_or(0.0));
        let frac = (PI - from) / (self.s.phase - from);
        let sq = self.s.cycle_sq + d * d * dt * frac;
        let rms = libm::sqrt(sq / (self.s.cycle_dt + dt * frac).max(1e-9));
        let tilt_deg = libm::asin(self.s.cycle_tilt_sin.max(tilt_sin)).to_degrees();
        let tilted = tilt_deg > self.cfg.axis_tilt_max_deg;
        let left_thigh = tilted && !self.tilted;
        self.tilted = tilted;
        let out = self.judge(x, sq, rms, left_thigh, tilt_deg <= LEVEL_TILT_DEG);
        self.s.cycle_xc = 0.0;
        self.s.cycle_cc = 0.0;
        self.s.peak_max = f64::NEG_INFINITY;
        self.s.cycle_sq = d * d * dt * (1.0 - frac);
        self.s.cycle_dt = dt * (1.0 - frac);
        self.s.cycle_pitch = x.pitch_deg.map(|p| (p, p));
        self.s.cycle_tilt_sin = tilt_sin;
        out
    }

    /// The loop's update at every sample: the phase detector on the normalised input, the
    /// acquisition aid, the oscillator's phasor, the lock indicator and the PI stage, whose
    /// frequency stays in the band `(lo, hi)`, Hz. `prev` is the phase before this sample's
    /// advance, `wrapped` whether it crossed 2π.
    fn track(&mut self, x: &DetectorInput, d: f64, prev: f64, wrapped: bool, band: (f64, f64)) {
        let (lo, hi) = band;
        let dt = x.dt;
        // Phase detector on the normalised input. The floor keeps noise small while still.
        let xn = (d / x.sigma.max(0.5 * self.cfg.cycle_rms_min)).clamp(-3.0, 3.0);
        // Acquisition aid: a type-2 loop this narrow pulls in slowly from far away (seconds for
        // walking → running from a standstill). When the loop is not locked and three regular
        // input cycles disagree with it by more than its lock-in range, re-seed the integrator.
        if let Some(fz) = self.crossing_frequency(x.t, xn) {
            let lock_in = 2.0 * self.cfg.damping * self.cfg.natural_hz;
            if !self.locked() && (fz - self.s.integ).abs() > lock_in && fz >= lo && fz <= hi {
                self.s.integ = fz;
            }
        }
        // Oscillator phasor: rotated by the phase increment; re-anchored at every wrap.
        if wrapped {
            self.s.phasor = libm::sincos(self.s.phase);
        } else {
            let (ds, dc) = crate::engine::math::sincos_increment(self.s.phase - prev);
            let (s0, c0) = self.s.phasor;
            self.s.phasor = (s0 * dc + c0 * ds, c0 * dc - s0 * ds);
        }
        let (s, c) = self.s.phasor;
        self.s.output = c;
        self.s.cycle_xc += d * c * dt;
        self.s.cycle_cc += c * c * dt;
        if c > 0.0 {
            // Within a quarter period of the oscillator's peak.
            self.s.peak_max = self.s.peak_max.max(d);
        }
        let e = self.s.loop_lpf.update(-xn * s, dt);
        self.s.lock.update(xn * c, dt);
        self.s.integ = (self.s.integ + self.ki * e * dt).clamp(lo, hi);
        self.s.freq = (self.s.integ + self.kp * e).clamp(lo, hi);
    }

    /// A step decided only with a later cycle, earlier than any step [`Pll::push`] gives with
    /// it; taken once, right after that push. Either the step before the first one counted
    /// since the restart, when its cycle failed only the σ-relative gate but the limb swung
    /// over it ([`PllConfig::first_swing_rel`]), a step after a standing cycle, once the
    /// next cycle stepped or stood ([`PllConfig::lone_step_confirm`]), a quiet cycle
    /// between two counted steps ([`PllConfig::between_steps_rel`]), or a step refused for its
    /// cycle's tilt alone, once the next cycle was level ([`PllConfig::axis_tilt_max_deg`]).
    pub fn take_late_step(&mut self) -> Option<Candidate> {
        self.s.late.take()
    }

    /// Whether a step is held for the next cycle's judgement ([`PllConfig::lone_step_confirm`]).
    pub fn holding(&self) -> bool {
        self.s.held.is_some()
    }

    /// The step held for the next cycle's judgement ([`PllConfig::lone_step_confirm`]), given
    /// up undecided: counted, as without the rule. The onset look-back ends with it, so that
    /// its step is weighed with the others found there.
    pub fn release_held(&mut self) -> Option<Candidate> {
        self.s.held.take()
    }

    /// The settings.
    pub fn config(&self) -> &PllConfig {
        &self.cfg
    }

    /// Starts afresh: the running state of a new loop, the settings kept.
    pub fn restart(&mut self) {
        self.s = PllState::new(&self.cfg);
    }

    /// The loop's current values.
    pub fn diagnostics(&self) -> PllDiagnostics {
        PllDiagnostics {
            freq_hz: self.frequency(),
            output: self.output(),
            lock_indicator: self.lock_indicator(),
            locked: self.locked(),
            phase: self.phase(),
        }
    }

    /// Tracked step frequency, Hz: the integrator of the loop filter, which is the oscillator
    /// frequency without the proportional term's ripple.
    pub fn frequency(&self) -> f64 {
        self.s.integ
    }

    /// Oscillator output cos φ.
    pub fn output(&self) -> f64 {
        self.s.output
    }

    /// Lock indicator: low-passed in-phase product (≈0.7 locked, ≈0 unlocked).
    pub fn lock_indicator(&self) -> f64 {
        self.s.lock.value().unwrap_or(0.0)
    }

    /// Whether the loop is considered locked (indicator above 0.35).
    pub fn locked(&self) -> bool {
        self.lock_indicator() > 0.35
    }

    /// Oscillator phase in [0, 2π), 0 at the output peak.
    pub fn phase(&self) -> f64 {
        self.s.phase
    }
}

mod judge;
#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests;
