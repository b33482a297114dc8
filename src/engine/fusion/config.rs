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
    /// Energy saving with the suggested schedule: 10 s every 60 s (Basso 2021 §3.1.2's period).
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
    /// Random error of each step's length, as a share of it (1σ). 0.15: twice the spread of
    /// step lengths at a steady cadence (Basso 2016 Fig. 4, 0.08), for hand-held phones and
    /// cadence changes; chosen on IPIN 2023 (the leave-one-route-out check is in
    /// `docs/methods/basso2021.md`).
    pub step_length_sd_rel: f64,
    /// Random error of each step's heading, degrees (1σ). 10°: twice the step-to-step scatter
    /// of the averaged tip-to-tail heading on pocket walks (5°), for hand-held phones; chosen on
    /// IPIN 2023 (the leave-one-route-out check is in `docs/methods/basso2021.md`).
    pub heading_sd_deg: f64,
    /// Time constant of the fixes' correlated error, s: a fix's error persists from fix to fix
    /// (multipath, the receiver's own filter) and decays as a first-order Gauss–Markov process
    /// with this time constant, estimated in the state. 0 treats every fix's error as new.
    /// Measured on the IPIN 2023 phone fixes against their landmarks (`examples/gnss_errors`):
    /// the errors' autocorrelation is about e^(−Δt/14 s) up to 20 s apart, 0.79 within 5 s.
    /// The filter is better on IPIN with 6 s than with 14 s, and leave-one-route-out picks 6 s
    /// for most routes (the figures are in `docs/methods/basso2021.md`): a Gauss–Markov process
    /// is a poor fit to the long tail, and a shorter τ lets the filter follow a fix error that
    /// has settled.
    pub fix_error_tau_s: f64,
    /// The share of a fix's error variance that is new at every fix (white); the rest is the
    /// correlated error above. With [`FusionConfig::white_share_window`], the floor of the share
    /// measured on the walk. 0.3: IPIN's errors 1 s apart correlate at about 0.8 (≈ 0.7 ·
    /// e^(−1/14) + the rest new).
    pub fix_white_share: f64,
    /// Pairs of consecutive walking fixes over which the white share is measured on the walk
    /// (`Fusion::measure_white_share`); [`FusionConfig::fix_white_share`] is then its floor. 0:
    /// the configured share holds.
    pub white_share_window: u32,
    /// How late the receiver reports where the walker was, s: a fix is carried forward along
    /// the walking velocity by this much more than its age.
    pub fix_latency_s: f64,
    /// Fixes teach the scale and the heading correction only after this long walking, s: a
    /// phone's receiver holds the standing position for 5–10 s after the walker sets off, then
    /// jumps; and fixes while standing say nothing of steps.
    pub learn_after_walking_s: f64,
    /// The step-length scale is learnt from baselines between two fixes at least this far
    /// apart along the walk, m, comparing the displacement the fixes show with the PDR's (see
    /// `Fusion::baseline`); a fix alone then corrects the position only. 0: every fix corrects
    /// the scale through the filter's correlations.
    pub baseline_min_m: f64,
    /// A baseline must also be this many times longer than its ends' error (1σ per axis, both
    /// ends summed).
    pub baseline_sigmas: f64,
    /// Only fixes this accurate or better end a baseline, m.
    pub baseline_max_accuracy_m: f64,
    /// Without evidence, the scale and the heading correction return to 1 and 0 with this time
    /// constant, s (first-order Gauss–Markov processes whose spread is their priors',
    /// [`FusionConfig::scale0_sd`] and [`FusionConfig::bias0_sd_deg`]). 0: they keep what they
    /// learnt.
    pub correction_tau_s: f64,
    /// The step-length scale is held within these bounds: a person's stride is not half, nor
    /// one and a half times, what a calibrated engine measures.
    pub scale_bounds: (f64, f64),
    /// The heading correction is held within ± this, degrees.
    pub bias_bound_deg: f64,
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
            step_length_sd_rel: 0.15,
            heading_sd_deg: 10.0,
            fix_error_tau_s: 6.0,
            fix_white_share: 0.3,
            white_share_window: 30,
            fix_latency_s: 0.0,
            learn_after_walking_s: 10.0,
            correction_tau_s: 0.0,
            baseline_min_m: 40.0,
            baseline_sigmas: 5.0,
            baseline_max_accuracy_m: 15.0,
            scale_bounds: (0.8, 1.25),
            bias_bound_deg: 25.0,
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
        for (v, name) in [
            (self.fix_error_tau_s, "fusion.fix_error_tau_s"),
            (self.fix_latency_s, "fusion.fix_latency_s"),
            (self.learn_after_walking_s, "fusion.learn_after_walking_s"),
            (self.correction_tau_s, "fusion.correction_tau_s"),
            (self.baseline_min_m, "fusion.baseline_min_m"),
            (self.baseline_sigmas, "fusion.baseline_sigmas"),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(ConfigError::new(name, "must be a finite number, 0 or more"));
            }
        }
        positive(
            "fusion.baseline_max_accuracy_m",
            self.baseline_max_accuracy_m,
        )?;
        if !(self.fix_white_share > 0.0 && self.fix_white_share <= 1.0) {
            return Err(ConfigError::new(
                "fusion.fix_white_share",
                "must be in (0, 1]",
            ));
        }
        let (lo, hi) = self.scale_bounds;
        if !(lo > 0.0 && lo <= 1.0 && hi >= 1.0 && hi.is_finite()) {
            return Err(ConfigError::new(
                "fusion.scale_bounds",
                "must be (low, high) with 0 < low <= 1 <= high",
            ));
        }
        if !(self.bias_bound_deg > 0.0 && self.bias_bound_deg <= 180.0) {
            return Err(ConfigError::new(
                "fusion.bias_bound_deg",
                "must be in (0, 180]",
            ));
        }
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
