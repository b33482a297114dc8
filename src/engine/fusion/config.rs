//! The fusion filter's settings ([`FusionConfig`]) and how the receiver is used ([`GnssMode`]).
//! May import: the rest of `engine`.

use crate::engine::types::{positive, ConfigError};

/// 68 % radius of a circular normal distribution in units of its per-axis σ.
pub const ACCURACY_PER_SIGMA: f64 = 1.509_596;

/// How the GNSS receiver is used.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum GnssMode {
    /// Every fix is used.
    BestPerformance,
    /// The receiver is on for `window_s` every `period_s`.
    EnergySaving {
        /// Time from the start of one window to the start of the next, s (default 60).
        #[serde(default = "default_period_s")]
        period_s: f64,
        /// How long each window lasts, s (default 10).
        #[serde(default = "default_window_s")]
        window_s: f64,
    },
    /// No fusion: the fixes are kept for display, and the first one is the track's geodetic
    /// origin.
    Off,
}

/// Energy saving's default period, s (Basso 2021 §3.1.2 chooses 60 s).
pub const DEFAULT_PERIOD_S: f64 = 60.0;
/// Energy saving's default window, s.
pub const DEFAULT_WINDOW_S: f64 = 10.0;

fn default_period_s() -> f64 {
    DEFAULT_PERIOD_S
}

fn default_window_s() -> f64 {
    DEFAULT_WINDOW_S
}

impl GnssMode {
    /// Energy saving with the defaults of the issue: 10 s every 60 s.
    pub const ENERGY_SAVING: GnssMode = GnssMode::EnergySaving {
        period_s: DEFAULT_PERIOD_S,
        window_s: DEFAULT_WINDOW_S,
    };
}

/// Where the magnetic declination comes from.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Declination {
    /// The World Magnetic Model at the first fix, for the log's date (Basso 2021 Remark 2).
    Wmm,
    /// A given value, degrees, positive when magnetic north is east of true north.
    Fixed {
        /// Declination, degrees.
        deg: f64,
    },
    /// The headings are already true (or the caller does not want the correction).
    None,
}

/// Settings of the fusion filter.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct FusionConfig {
    /// How the GNSS receiver is used.
    pub mode: GnssMode,
    /// Fixes with a reported accuracy worse than this are refused, m.
    pub max_accuracy_m: f64,
    /// Squared Mahalanobis distance above which a fix is refused (13.82: χ²₂ at 99.9 %).
    pub gate_chi2: f64,
    /// A fix older than this at the step it would update is refused as stale, s.
    pub max_fix_age_s: f64,
    /// After this many consecutive fixes refused by the gate, the position is reset to the
    /// fix.
    pub reset_after: u32,
    /// Random error of each step's length, as a share of it (1σ). 0.08: the spread of step
    /// lengths at a steady cadence (Basso 2016 Fig. 4).
    pub step_length_sd_rel: f64,
    /// Random error of each step's heading, degrees (1σ). 5°: the step-to-step scatter of the
    /// averaged tip-to-tail heading on pocket walks.
    pub heading_sd_deg: f64,
    /// Random walk of the scale per step (1σ).
    pub scale_rw: f64,
    /// Random walk of the heading correction per step, degrees (1σ).
    pub bias_rw_deg: f64,
    /// Uncertainty of the scale before the first fix (1σ).
    pub scale0_sd: f64,
    /// Uncertainty of the heading correction before the first fix, degrees (1σ).
    pub bias0_sd_deg: f64,
    /// Uncertainty of the walking velocity used to carry a fix to the step time, m/s (1σ).
    pub velocity_sd_mps: f64,
    /// When the prior position's standard deviation exceeds this, m, a single fix is not
    /// trusted: the gate would let an outlier through (20 m off is within 3.7σ of a 5 m prior
    /// plus a 3 m fix). Fixes are then held until [`FusionConfig::consensus_n`] agree.
    pub consensus_sd_m: f64,
    /// Fixes that must agree for a consensus.
    pub consensus_n: u32,
    /// A fix that comes this long after the last step, while the motion detector says still,
    /// finds the walker standing, s: it updates that step's estimate at once. Waiting for the next step would keep only the newest of
    /// the fixes that come meanwhile (one a second at a crossing). 2 s: twice the longest
    /// walking step (1 Hz).
    pub standing_after_s: f64,
    /// Energy saving: the scale is known when its standard deviation is below this.
    pub calibrated_scale_sd: f64,
    /// Energy saving: the heading correction is known when its standard deviation is below
    /// this, degrees.
    pub calibrated_bias_sd_deg: f64,
    /// Energy saving: the receiver stays on at most this long to learn them, s.
    pub max_calibration_s: f64,
    /// Magnetic declination.
    pub declination: Declination,
    /// The date of the log as Unix seconds, for the declination, when the log's clock is not
    /// Unix time (a phone's time since boot). `None`: taken from the fixes when they carry Unix
    /// time, else the start of the current model.
    pub date_unix_s: Option<f64>,
}

impl Default for FusionConfig {
    fn default() -> Self {
        FusionConfig {
            mode: GnssMode::BestPerformance,
            max_accuracy_m: 50.0,
            gate_chi2: 13.82,
            max_fix_age_s: 2.0,
            reset_after: 5,
            step_length_sd_rel: 0.08,
            heading_sd_deg: 5.0,
            scale_rw: 0.001,
            bias_rw_deg: 0.05,
            scale0_sd: 0.15,
            bias0_sd_deg: 20.0,
            velocity_sd_mps: 0.3,
            consensus_sd_m: 5.0,
            consensus_n: 3,
            standing_after_s: 2.0,
            calibrated_scale_sd: 0.02,
            calibrated_bias_sd_deg: 1.5,
            max_calibration_s: 300.0,
            declination: Declination::Wmm,
            date_unix_s: None,
        }
    }
}

impl FusionConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("fusion.max_accuracy_m", self.max_accuracy_m)?;
        positive("fusion.gate_chi2", self.gate_chi2)?;
        positive("fusion.max_fix_age_s", self.max_fix_age_s)?;
        positive("fusion.step_length_sd_rel", self.step_length_sd_rel)?;
        positive("fusion.heading_sd_deg", self.heading_sd_deg)?;
        positive("fusion.scale_rw", self.scale_rw)?;
        positive("fusion.bias_rw_deg", self.bias_rw_deg)?;
        positive("fusion.scale0_sd", self.scale0_sd)?;
        positive("fusion.bias0_sd_deg", self.bias0_sd_deg)?;
        positive("fusion.velocity_sd_mps", self.velocity_sd_mps)?;
        positive("fusion.consensus_sd_m", self.consensus_sd_m)?;
        positive("fusion.standing_after_s", self.standing_after_s)?;
        positive("fusion.calibrated_scale_sd", self.calibrated_scale_sd)?;
        positive("fusion.calibrated_bias_sd_deg", self.calibrated_bias_sd_deg)?;
        positive("fusion.max_calibration_s", self.max_calibration_s)?;
        if self.consensus_n < 2 {
            return Err(ConfigError::new("fusion.consensus_n", "must be at least 2"));
        }
        if self.reset_after == 0 {
            return Err(ConfigError::new("fusion.reset_after", "must be at least 1"));
        }
        if let GnssMode::EnergySaving { period_s, window_s } = self.mode {
            positive("fusion.mode.period_s", period_s)?;
            positive("fusion.mode.window_s", window_s)?;
            if window_s > period_s {
                return Err(ConfigError::new(
                    "fusion.mode.window_s",
                    "must not exceed fusion.mode.period_s",
                ));
            }
        }
        if let Declination::Fixed { deg } = self.declination {
            if !deg.is_finite() || deg.abs() > 180.0 {
                return Err(ConfigError::new(
                    "fusion.declination.deg",
                    "must be within ±180",
                ));
            }
        }
        Ok(())
    }
}
