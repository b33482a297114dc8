//! A simple peak detector on vertical acceleration, in the same stage shape as the PLL, to
//! compare against (the "fixed cut-off plus threshold" family Basso 2016 §II.C argues against).
//!
//! The vertical acceleration is smoothed by two cascaded first-order low-pass filters
//! (cut-off [`PeakConfig::lpf_hz`]); a local maximum of the smoothed signal is a step when it is at
//! least [`PeakConfig::min_interval_s`] after the previous step and its rise from the preceding
//! trough reaches 2√2·`cycle_rms_min` (the peak-to-peak of a sinusoid of that RMS).

use super::math::OnePole;
use super::pll::Candidate;
use super::types::{positive, ConfigError};

/// Settings of the peak detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PeakConfig {
    /// Low-pass cut-off, Hz.
    pub lpf_hz: f64,
    /// Minimum time between steps, s (0.2 s admits 4.6 Hz running).
    pub min_interval_s: f64,
    /// Minimum RMS-equivalent amplitude of a cycle, m/s². 0.5 (a rise of 1.4 m/s²): on the
    /// Oxford traces 1.0 missed gentle hand-held walks whole (12.1 % count error), 0.4 and 0.6
    /// give 3.8 % and 3.1 %, 0.5 gives 2.7 %, the level of a textbook offline peak counter.
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

/// The peak detector's running state.
#[derive(Debug, Clone)]
pub struct PeakDetector {
    cfg: PeakConfig,
    lp: [OnePole; 2],
    prev: Option<(f64, f64)>,
    rising: bool,
    trough: f64,
    last_step: Option<f64>,
    period: f64,
}

impl PeakDetector {
    /// A new detector.
    pub fn new(cfg: PeakConfig) -> Self {
        PeakDetector {
            cfg,
            lp: [OnePole::with_cutoff_hz(cfg.lpf_hz); 2],
            prev: None,
            rising: false,
            trough: f64::INFINITY,
            last_step: None,
            period: 1.0 / 1.8,
        }
    }

    /// The settings.
    pub fn config(&self) -> &PeakConfig {
        &self.cfg
    }

    /// Forgets the signal history (after a gap).
    pub fn reset(&mut self) {
        *self = PeakDetector {
            period: self.period,
            ..PeakDetector::new(self.cfg)
        };
    }

    /// Feeds one vertical-acceleration sample; same contract as [`super::pll::Pll::push`].
    pub fn push(&mut self, t: f64, dt: f64, a: f64) -> Option<Candidate> {
        let y = self.lp[0].update(a, dt);
        let y = self.lp[1].update(y, dt);
        let mut out = None;
        if let Some((tp, yp)) = self.prev {
            if y < yp && self.rising {
                // (tp, yp) was a local maximum.
                let rise = yp - self.trough;
                let spaced = self
                    .last_step
                    .map_or(true, |ls| tp - ls >= self.cfg.min_interval_s);
                if spaced && rise >= 2.0 * std::f64::consts::SQRT_2 * self.cfg.cycle_rms_min {
                    if let Some(ls) = self.last_step {
                        self.period = (tp - ls).clamp(0.2, 1.5);
                    }
                    self.last_step = Some(tp);
                    out = Some(Candidate {
                        t: tp,
                        period_s: self.period,
                        coherence: 1.0,
                    });
                    self.trough = f64::INFINITY;
                }
            }
            self.rising = y > yp;
        }
        self.trough = self.trough.min(y);
        self.prev = Some((t, y));
        out
    }
}
