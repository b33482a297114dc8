//! Energy saving's receiver schedule (Basso 2021 §3.1.2): the receiver on for `window_s` at the
//! start of every `period_s`, once the filter knows the systematic errors, and the time it was on.
//! May import: the rest of `engine`.

use super::config::{FusionConfig, GnssMode};

/// The receiver's schedule in energy-saving mode.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Duty {
    /// On until the systematic errors are known.
    Calibrating,
    /// On since a time.
    On { since: f64 },
    /// Off until a time.
    Off { next_on: f64 },
}

/// The receiver's schedule and the time it was on, driven by the times of the fixes and steps.
#[derive(Debug, Clone)]
pub struct Schedule {
    mode: GnssMode,
    max_calibration_s: f64,
    duty: Duty,
    on_s: f64,
    last_t: Option<f64>,
    first_fix_t: Option<f64>,
}

impl Schedule {
    /// The receiver on, waiting for the first fix.
    pub fn new(cfg: &FusionConfig) -> Self {
        Schedule {
            mode: cfg.mode,
            max_calibration_s: cfg.max_calibration_s,
            duty: Duty::Calibrating,
            on_s: 0.0,
            last_t: None,
            first_fix_t: None,
        }
    }

    /// A fix came at time `t`: the first one starts the count of the time on.
    pub fn fix(&mut self, t: f64) {
        if self.first_fix_t.is_none() {
            self.first_fix_t = Some(t);
        }
    }

    /// Whether the receiver should be on at time `t`. Always in best-performance mode. In
    /// energy-saving mode it stays on from the first fix until the scale and the heading
    /// correction are known (at most [`FusionConfig::max_calibration_s`]): compensating
    /// systematic errors between windows needs them first. Then it is on for `window_s` at the
    /// start of every `period_s`.
    pub fn wanted(&self, t: f64) -> bool {
        match self.duty {
            Duty::Off { next_on } => t >= next_on,
            _ => true,
        }
    }

    /// How long the receiver was on from the first fix to the last step or fix, and that span,
    /// s.
    pub fn on_s(&self) -> Option<(f64, f64)> {
        let t0 = self.first_fix_t?;
        Some((self.on_s, self.last_t.unwrap_or(t0) - t0))
    }

    /// Moves the schedule to time `t`; `calibrated`: the filter knows the step-length scale
    /// and the heading correction well enough ([`FusionConfig::calibrated_scale_sd`],
    /// [`FusionConfig::calibrated_bias_sd_deg`]).
    pub fn push(&mut self, t: f64, calibrated: bool) {
        if let Some(last) = self.last_t {
            if self.wanted(last) && t > last {
                self.on_s += t - last;
            }
        }
        self.last_t = Some(self.last_t.map_or(t, |l| l.max(t)));
        let GnssMode::EnergySaving { period_s, window_s } = self.mode else {
            return;
        };
        self.duty = match self.duty {
            Duty::Calibrating => {
                let too_long = self
                    .first_fix_t
                    .is_some_and(|t0| t - t0 >= self.max_calibration_s);
                if calibrated || too_long {
                    Duty::Off {
                        next_on: t + period_s - window_s,
                    }
                } else {
                    Duty::Calibrating
                }
            }
            Duty::On { since } if t - since >= window_s => Duty::Off {
                next_on: since + period_s,
            },
            Duty::Off { next_on } if t >= next_on => Duty::On { since: next_on },
            unchanged => unchanged,
        };
    }
}
