//! Zero-crossing + area step detector (Ibarra 2015 thesis, §1.4.1.1 and §4.4.1, eqs. 4.2, 4.3,
//! 4.8, 4.9), in the same stage shape as the PLL and the peak counter.
//! May import: the rest of `engine`.
//!
//! What the thesis prints, and what we do with it:
//! 1. **Normalised signal** (eqs. 4.1–4.3): the norm of the acceleration minus its mean over a
//!    sliding window of N = 100 samples (2 s at 50 Hz). We take the vertical linear
//!    acceleration instead of the norm (the engine has it for every orientation source, and a
//!    phone in the hand or a pocket is not the waist-mounted IMU of the thesis, whose norm is
//!    dominated by the vertical), minus the motion detector's mean over its 2 s window
//!    ([`DetectorInput::mean`]): eq. 4.3 with eq. 4.2's 2 s.
//! 2. **Smoothing** (eq. 4.8): Â_k = α·A_k + (1 − α)·Â_{k−1}, α = 0.3 at 50 Hz, initial
//!    condition the first value. Our samples come at 15–400 Hz with jitter, so the per-sample
//!    weight is the one with the same time constant: α(dt) = 1 − (1 − α)^(dt / 0.02 s)
//!    (τ = 56 ms, a 2.8 Hz cut-off; identical to eq. 4.8 at 50 Hz).
//! 3. **Zero crossings**: positive-going and negative-going crossings of Â; the maximum peak
//!    between a positive-going crossing and the next negative-going one is the candidate step
//!    (Fig. 4.6), at the time of that maximum.
//! 4. **Area** (eq. 4.9): S = Σ f(x_i*)(x_i − x_{i−1}) over the samples of that range R_ng (a
//!    Riemann sum of Â with each sample's own dt, not the thesis's fixed 0.02 s).
//! 5. **Validation**: "the algorithm compares the value of S against a sliding window average
//!    (S_mean) … If the ratio is greater than some value previously specified the event is
//!    considered a valid step". The thesis prints neither the window nor the ratio. Ours:
//!    S_mean is the mean area of every positive lobe (valid or not) that ended within the last
//!    [`ZeroCrossingConfig::window_s`], this one included, and the ratio is
//!    [`ZeroCrossingConfig::ratio_min`]; both chosen on the simulator and the whole Oxford set
//!    (see the fields).
//! 6. **Minimum step period** (§1.4.1.1: "taking the minimum step period into account"), value
//!    not printed: [`ZeroCrossingConfig::min_interval_s`], as the peak counter's.
//!
//! Added by us, because the engine runs on any stream: an absolute floor on the area
//! ([`ZeroCrossingConfig::area_min`]), so that a ratio of small noise lobes is not a step when
//! the pipeline's motion gate lets it through, and a cap on the lobes remembered
//! ([`MAX_LOBES`]), so that memory stays bounded whatever the sampling rate.

use super::detector::{Candidate, DetectorInput};
use super::types::{positive, ConfigError};
use std::collections::VecDeque;

/// The most lobe areas kept for S_mean (a noisy 400 Hz stream can cross zero every few
/// samples; the window is bounded in time and in count).
pub const MAX_LOBES: usize = 256;

/// The sampling interval eq. 4.8's α refers to, s (50 Hz, Ibarra 2015 §4.2).
const THESIS_DT_S: f64 = 0.02;

/// Settings of the zero-crossing detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ZeroCrossingConfig {
    /// α of eq. 4.8 at 50 Hz (thesis: 0.3); rescaled to each sample's dt.
    pub alpha: f64,
    /// S_mean's sliding window, s (not printed in the thesis). 1.5 s, chosen with
    /// [`ZeroCrossingConfig::ratio_min`] on the whole Oxford set by the mean absolute count
    /// error, each placement left out in turn; 1–2 s are reasonable. The grid and its figures are
    /// in `docs/methods/ibarra2015.md`.
    pub window_s: f64,
    /// The smallest S / S_mean of a valid step (not printed in the thesis). 0.4, chosen with the
    /// window: lower ratios count the second bump of a front-pocket step, higher ones drop the
    /// weak steps of a swinging arm.
    pub ratio_min: f64,
    /// Minimum time between steps, s (0.2 s admits 4.6 Hz running; the peak counter's value).
    pub min_interval_s: f64,
    /// Smallest area of a step's lobe, m/s (ours): a half-sine lobe of a 0.5 m/s² RMS cycle at
    /// 2 Hz has an area of √2·0.5/(π·2) ≈ 0.11 m/s; a quarter of that.
    pub area_min: f64,
}

impl Default for ZeroCrossingConfig {
    fn default() -> Self {
        ZeroCrossingConfig {
            alpha: 0.3,
            window_s: 1.5,
            ratio_min: 0.4,
            min_interval_s: 0.2,
            area_min: 0.03,
        }
    }
}

impl ZeroCrossingConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            return Err(ConfigError::new(
                "detector.alpha",
                "must lie strictly between 0 and 1",
            ));
        }
        positive("detector.window_s", self.window_s)?;
        positive("detector.ratio_min", self.ratio_min)?;
        positive("detector.min_interval_s", self.min_interval_s)?;
        if !(self.area_min >= 0.0 && self.area_min.is_finite()) {
            return Err(ConfigError::new(
                "detector.area_min",
                "must be a finite number, 0 or more",
            ));
        }
        Ok(())
    }
}

/// The zero-crossing detector: its settings and its running state.
#[derive(Debug, Clone)]
pub struct ZeroCrossing {
    cfg: ZeroCrossingConfig,
    /// ln(1 − α) / 0.02 s: the per-second decay of eq. 4.8.
    decay: f64,
    s: ZcState,
    lobes: u64,
    rejected: u64,
}

/// The lobe being integrated: from a positive-going crossing to the next negative-going one.
#[derive(Debug, Clone, Copy)]
struct Lobe {
    area: f64,
    peak_t: f64,
    peak: f64,
}

/// The running state, apart from the settings: a restart is a fresh state.
#[derive(Debug, Clone)]
struct ZcState {
    /// Â of the previous sample.
    y: Option<f64>,
    lobe: Option<Lobe>,
    /// (end time, area) of the recent positive lobes.
    areas: VecDeque<(f64, f64)>,
    last_step: Option<f64>,
    period: f64,
}

impl ZcState {
    fn new(period: f64) -> Self {
        ZcState {
            y: None,
            lobe: None,
            areas: VecDeque::new(),
            last_step: None,
            period,
        }
    }
}

/// The detector's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ZeroCrossingDiagnostics {
    /// Interval between the last two steps (clamped to 0.2–1.5 s), s.
    pub period_s: f64,
    /// Time of the last step, s.
    pub last_step_t: Option<f64>,
    /// S_mean now, m/s (0 before the first lobe).
    pub s_mean: f64,
    /// Positive lobes seen since the detector was made.
    pub lobes: u64,
    /// Lobes refused (ratio, area floor or minimum interval).
    pub rejected: u64,
}

const DEFAULT_PERIOD_S: f64 = 1.0 / 1.8;

impl ZeroCrossing {
    /// A new detector.
    pub fn new(cfg: ZeroCrossingConfig) -> Self {
        ZeroCrossing {
            decay: libm::log(1.0 - cfg.alpha) / THESIS_DT_S,
            cfg,
            s: ZcState::new(DEFAULT_PERIOD_S),
            lobes: 0,
            rejected: 0,
        }
    }

    /// The settings.
    pub fn config(&self) -> &ZeroCrossingConfig {
        &self.cfg
    }

    /// Starts afresh (the onset look-back): the running state of a new detector, with the step
    /// period of the cadence found when there is one.
    pub fn restart(&mut self, cadence_hz: Option<f64>) {
        let period = cadence_hz
            .filter(|f| f.is_finite() && *f > 0.0)
            .map_or(DEFAULT_PERIOD_S, |f| (1.0 / f).clamp(0.2, 1.5));
        self.s = ZcState::new(period);
    }

    /// Forgets the signal (after a gap), keeping the step period.
    pub fn reset(&mut self) {
        self.s = ZcState::new(self.s.period);
    }

    fn s_mean(&self) -> f64 {
        let n = self.s.areas.len();
        if n == 0 {
            0.0
        } else {
            self.s.areas.iter().map(|a| a.1).sum::<f64>() / n as f64
        }
    }

    /// The current values.
    pub fn diagnostics(&self) -> ZeroCrossingDiagnostics {
        ZeroCrossingDiagnostics {
            period_s: self.s.period,
            last_step_t: self.s.last_step,
            s_mean: self.s_mean(),
            lobes: self.lobes,
            rejected: self.rejected,
        }
    }

    /// Feeds one vertical-acceleration sample; same contract as [`super::pll::Pll::push`]. A
    /// step is reported at the negative-going crossing that closes its lobe, with the time of
    /// the lobe's maximum.
    pub fn push(&mut self, x: &DetectorInput) -> Option<Candidate> {
        let a = x.up - x.mean; // eq. 4.3
        let dt = x.dt.max(0.0);
        // Eq. 4.8 with α rescaled to dt (α at dt = 0.02 s is the thesis's).
        let y = match self.s.y {
            None => a,
            Some(yp) => {
                let alpha = 1.0 - libm::exp(self.decay * dt);
                alpha * a + (1.0 - alpha) * yp
            }
        };
        let prev = self.s.y.replace(y);
        let mut out = None;
        if y > 0.0 {
            match &mut self.s.lobe {
                Some(l) => {
                    l.area += y * dt; // eq. 4.9
                    if y > l.peak {
                        l.peak = y;
                        l.peak_t = x.t;
                    }
                }
                // A positive-going crossing opens a lobe (not the first sample: its sign
                // alone is no crossing).
                None if prev.is_some_and(|p| p <= 0.0) => {
                    self.s.lobe = Some(Lobe {
                        area: y * dt,
                        peak_t: x.t,
                        peak: y,
                    });
                }
                None => {}
            }
        } else if let Some(l) = self.s.lobe.take() {
            out = self.close(l, x.t);
        }
        out
    }

    /// A negative-going crossing at `t` closes lobe `l`: S against S_mean.
    fn close(&mut self, l: Lobe, t: f64) -> Option<Candidate> {
        self.lobes += 1;
        self.s.areas.push_back((t, l.area));
        while self.s.areas.len() > MAX_LOBES
            || self
                .s
                .areas
                .front()
                .is_some_and(|f| f.0 < t - self.cfg.window_s)
        {
            self.s.areas.pop_front();
        }
        let s_mean = self.s_mean();
        let spaced = self
            .s
            .last_step
            .map_or(true, |ls| l.peak_t - ls >= self.cfg.min_interval_s);
        let valid = s_mean > 0.0
            && l.area >= self.cfg.ratio_min * s_mean
            && l.area >= self.cfg.area_min
            && spaced;
        if !valid {
            self.rejected += 1;
            return None;
        }
        if let Some(ls) = self.s.last_step {
            self.s.period = (l.peak_t - ls).clamp(0.2, 1.5);
        }
        self.s.last_step = Some(l.peak_t);
        Some(Candidate {
            t: l.peak_t,
            period_s: self.s.period,
            coherence: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::motion::Motion;

    fn input(t: f64, dt: f64, up: f64) -> DetectorInput {
        DetectorInput {
            t,
            dt,
            up,
            mean: 0.0,
            sigma: 1.0,
            motion: Motion::Walking,
            cadence_hz: None,
            pitch_deg: None,
            axis_tilt_sin: None,
            pocket: false,
        }
    }

    /// A 2 Hz sinusoid with a small second bump in each cycle: the area test keeps one step per
    /// cycle, at the big lobe's maximum.
    #[test]
    fn one_step_per_cycle_despite_a_small_bump() {
        let mut z = ZeroCrossing::new(ZeroCrossingConfig::default());
        let (f, dt) = (2.0, 0.01);
        let mut steps = Vec::new();
        for k in 0..1000 {
            let t = k as f64 * dt;
            let w = std::f64::consts::TAU * f * t;
            let up = 3.0 * libm::sin(w) + 1.2 * libm::sin(3.0 * w);
            steps.extend(z.push(&input(t, if k == 0 { 0.0 } else { dt }, up)));
        }
        // 10 s at 2 Hz: 20 cycles, the first may be missed while the filter settles.
        assert!((19..=20).contains(&steps.len()), "{}", steps.len());
        for w in steps.windows(2) {
            assert!((w[1].t - w[0].t - 0.5).abs() < 0.03, "{w:?}");
            assert!((w[1].period_s - 0.5).abs() < 0.03);
        }
        let d = z.diagnostics();
        assert!(d.lobes >= d.rejected && d.s_mean > 0.0);
    }

    #[test]
    fn alpha_is_the_thesis_at_50_hz() {
        let z = ZeroCrossing::new(ZeroCrossingConfig::default());
        let alpha = 1.0 - libm::exp(z.decay * 0.02);
        assert!((alpha - 0.3).abs() < 1e-12);
        let bad = ZeroCrossingConfig {
            alpha: 1.0,
            ..Default::default()
        };
        assert_eq!(bad.validate().unwrap_err().field, "detector.alpha");
    }

    #[test]
    fn noise_alone_is_refused_by_the_area_floor() {
        let mut z = ZeroCrossing::new(ZeroCrossingConfig::default());
        let mut n = 0;
        let mut seed = 1u64;
        for k in 0..4000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            n += z.push(&input(k as f64 * 0.005, 0.005, 0.2 * u)).is_some() as usize;
        }
        assert_eq!(n, 0);
        assert!(z.s.areas.len() <= MAX_LOBES);
    }
}
