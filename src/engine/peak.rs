//! A simple peak detector on vertical acceleration, in the same stage shape as the PLL, to
//! compare against (the "fixed cut-off plus threshold" family Basso 2016 §II.C argues against).
//! May import: the rest of `engine`.
//!
//! The vertical acceleration is smoothed by two cascaded first-order low-pass filters
//! (cut-off [`PeakConfig::lpf_hz`]); a local maximum of the smoothed signal is a step when it is at
//! least [`PeakConfig::min_interval_s`] after the previous step and its rise from the preceding
//! trough reaches 2√2·`cycle_rms_min` (the peak-to-peak of a sinusoid of that RMS).

use super::detector::{Candidate, DetectorInput};
use super::math::OnePole;
use super::types::{positive, ConfigError};

/// Settings of the peak detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PeakConfig {
    /// Low-pass cut-off, Hz.
    pub lpf_hz: f64,
    /// Minimum time between steps, s (0.2 s admits 4.6 Hz running).
    pub min_interval_s: f64,
    /// Minimum RMS-equivalent amplitude of a cycle, m/s². 0.5 (a rise of 1.4 m/s²): a higher
    /// floor misses gentle hand-held walks whole, a lower one counts more than the steps. The
    /// figures on the Oxford set are in `docs/evaluation.md`.
    pub cycle_rms_min: f64,
}

impl Default for PeakConfig {
    fn default() -> Self {
        PeakConfig {
            lpf_hz: 3.0,
            min_interval_s: 0.2,
            cycle_rms_min: 0.5,
        }
    }
}

impl PeakConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("peak.lpf_hz", self.lpf_hz)?;
        positive("peak.min_interval_s", self.min_interval_s)?;
        positive("peak.cycle_rms_min", self.cycle_rms_min)
    }
}

/// The peak detector: its settings and its running state.
#[derive(Debug, Clone)]
pub struct PeakDetector {
    cfg: PeakConfig,
    s: PeakState,
}

/// The running state, apart from the settings: a restart is a fresh state.
#[derive(Debug, Clone)]
struct PeakState {
    lp: [OnePole; 2],
    prev: Option<(f64, f64)>,
    rising: bool,
    trough: f64,
    last_step: Option<f64>,
    period: f64,
}

impl PeakState {
    fn new(cfg: &PeakConfig) -> Self {
        PeakState {
            lp: [OnePole::with_cutoff_hz(cfg.lpf_hz); 2],
            prev: None,
            rising: false,
            trough: f64::INFINITY,
            last_step: None,
            period: 1.0 / 1.8,
        }
    }
}

/// The detector's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PeakDiagnostics {
    /// Interval between the last two steps (clamped to 0.2–1.5 s), s.
    pub period_s: f64,
    /// Time of the last step, s.
    pub last_step_t: Option<f64>,
}

impl PeakDetector {
    /// A new detector.
    pub fn new(cfg: PeakConfig) -> Self {
        PeakDetector {
            s: PeakState::new(&cfg),
            cfg,
        }
    }

    /// The settings.
    pub fn config(&self) -> &PeakConfig {
        &self.cfg
    }

    /// Starts afresh: the running state of a new detector, the settings kept.
    pub fn restart(&mut self) {
        self.s = PeakState::new(&self.cfg);
    }

    /// Forgets the signal history (after a gap), keeping the step period.
    pub fn reset(&mut self) {
        self.s = PeakState {
            period: self.s.period,
            ..PeakState::new(&self.cfg)
        };
    }

    /// The current values.
    pub fn diagnostics(&self) -> PeakDiagnostics {
        PeakDiagnostics {
            period_s: self.s.period,
            last_step_t: self.s.last_step,
        }
    }

    /// Feeds one vertical-acceleration sample (it uses the time and the acceleration alone);
    /// same contract as [`super::pll::Pll::push`].
    pub fn push(&mut self, x: &DetectorInput) -> Option<Candidate> {
        let (t, dt, a) = (x.t, x.dt, x.up);
        let y = self.s.lp[0].update(a, dt);
        let y = self.s.lp[1].update(y, dt);
        let mut out = None;
        if let Some((tp, yp)) = self.s.prev {
            if y < yp && self.s.rising {
                // (tp, yp) was a local maximum.
                let rise = yp - self.s.trough;
                let spaced = self
                    .s
                    .last_step
                    .map_or(true, |ls| tp - ls >= self.cfg.min_interval_s);
                if spaced && rise >= 2.0 * std::f64::consts::SQRT_2 * self.cfg.cycle_rms_min {
                    if let Some(ls) = self.s.last_step {
                        self.s.period = (tp - ls).clamp(0.2, 1.5);
                    }
                    self.s.last_step = Some(tp);
                    out = Some(Candidate {
                        t: tp,
                        period_s: self.s.period,
                        coherence: 1.0,
                    });
                    self.s.trough = f64::INFINITY;
                }
            }
            self.s.rising = y > yp;
        }
        self.s.trough = self.s.trough.min(y);
        self.s.prev = Some((t, y));
        out
    }
}
