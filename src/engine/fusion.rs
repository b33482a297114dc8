//! GNSS/PDR fusion: a Kalman filter that advances once per detected step (Basso 2021 §2.2.6),
//! with the systematic errors of §2.2.5 and §3.1.2 in its state, an energy-saving GNSS duty
//! cycle, and a Rauch–Tung–Striebel smoother for whole logs (ours; none of the papers has one).
//!
//! # State and models
//! The paper names the pieces (a multi-rate, step-triggered, size-varying filter; compensation of
//! the step-length and heading errors between GNSS windows) but gives no equations. Ours:
//! - State x = [E, N, k, β]: position east and north in the local tangent plane of the first fix
//!   (m), the step-length scale k (true length = k · PDR length) and the heading correction β
//!   (true heading = PDR heading + declination + β, rad).
//! - **Prediction at each step** with PDR length L and heading θ (φ = θ + D + β, D the magnetic
//!   declination): E ← E + k L sin φ, N ← N + k L cos φ; k and β are random walks. This is Basso
//!   2021 eq. 24 with the corrections applied (an extended Kalman filter: the Jacobian F is taken
//!   at the prior estimate). The per-step noise comes from an uncorrelated step-length error
//!   ([`FusionConfig::step_length_sd_rel`]) and heading error ([`FusionConfig::heading_sd_deg`]),
//!   mapped through the Jacobian of the displacement.
//! - **Update** with the newest fix not yet used (size-varying: no fix, no update). The fix is
//!   associated with the step time by extrapolating it along the fused walking velocity over the
//!   interval between the fix and the step ("an extrapolation technique", §2.2.6), and its
//!   covariance is widened by the extrapolation's uncertainty. R = σ² I with σ = accuracy / 1.5096:
//!   Android and iOS report the radius of 68 % confidence, and for a circular normal distribution
//!   P(r ≤ a) = 1 − exp(−a²/2σ²) = 0.68 gives a = 1.5096 σ.
//! - **Standing** (our addition): a fix that comes [`FusionConfig::standing_after_s`] or more
//!   after the last step, while the motion detector says still, updates that step's estimate at
//!   once. The paper's step trigger would keep only the newest of the fixes that come while the
//!   walker waits at a crossing (a test measures the difference).
//! - **Gating**: a fix is refused when its accuracy is worse than [`FusionConfig::max_accuracy_m`],
//!   when it is older than [`FusionConfig::max_fix_age_s`] at the step, or when its squared
//!   Mahalanobis distance exceeds [`FusionConfig::gate_chi2`] (χ² with 2 degrees of freedom).
//!   Each reason is counted. After [`FusionConfig::reset_after`] consecutive gated fixes the
//!   filter believes the GNSS again (the PDR has drifted, after an outage for example): the
//!   position is reset to the fix.
//! - The covariance update is in Joseph form and symmetrised, so it stays symmetric and positive
//!   definite (a test checks it on every step of a long walk).
//!
//! # Modes
//! - [`GnssMode::BestPerformance`]: every fix is offered to the filter (§3.1.1).
//! - [`GnssMode::EnergySaving`]: the receiver is on for `window_s` every `period_s` (§3.1.2, 60 s
//!   in the paper). Fixes outside the windows are ignored, as if the receiver were off; live
//!   mode stops the geolocation watch then ([`Fusion::gnss_wanted`]). Between windows the scale
//!   and heading correction estimated so far keep correcting every step, which is the paper's
//!   compensation of systematic errors. Our addition: the duty cycle starts only once those two
//!   are known (the receiver stays on until then, at most [`FusionConfig::max_calibration_s`]);
//!   measured on the simulated city walk, starting it at the first fix left the first minutes
//!   uncorrected (p75 2.2–6.2 m against 1.0–1.5 m in best-performance mode).

use super::geo::LocalFrame;
use super::math::wrap_pi;
use super::types::{positive, ConfigError};
use nalgebra::{Matrix2, Matrix4, Vector2, Vector4};

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

/// What happened to a fix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FixOutcome {
    /// It updated the filter.
    Used,
    /// It started the filter (the first usable fix).
    Started,
    /// Its reported accuracy was worse than the limit.
    TooInaccurate,
    /// It was older than the limit when the next step came.
    Stale,
    /// The Mahalanobis gate refused it.
    Gated,
    /// It reset the position after repeated gating.
    Reset,
    /// The receiver was off (energy saving).
    ReceiverOff,
    /// Held for a consensus of fixes (the prior was too wide to gate one fix alone).
    Held,
}

/// Counters of the fixes by outcome.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct FixCounts {
    /// Used in an update.
    pub used: u64,
    /// Refused for their accuracy.
    pub too_inaccurate: u64,
    /// Refused as stale.
    pub stale: u64,
    /// Refused by the gate.
    pub gated: u64,
    /// Position resets after repeated gating.
    pub resets: u64,
    /// Ignored while the receiver was off.
    pub receiver_off: u64,
    /// Replaced by a newer fix before a step came.
    pub superseded: u64,
}

/// The filter's result at one step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FusedStep {
    /// Time of the step, s.
    pub t: f64,
    /// Fused position, east and north, m (local tangent plane of the first fix).
    pub east_m: f64,
    /// See `east_m`.
    pub north_m: f64,
    /// Position covariance (ee, en, nn), m².
    pub cov: [f64; 3],
    /// Step-length scale.
    pub scale: f64,
    /// Heading correction, rad.
    pub bias_rad: f64,
    /// Standard deviations of the scale and the heading correction (rad).
    pub scale_bias_sd: [f64; 2],
    /// Innovation of the fix used or refused at this step (east, north), m.
    pub innovation: Option<[f64; 2]>,
    /// What happened to the fix offered at this step, if any.
    pub fix: Option<FixOutcome>,
}

/// A fix waiting for the next step, in the local frame.
#[derive(Debug, Clone, Copy)]
struct PendingFix {
    t: f64,
    en: Vector2<f64>,
    sigma: f64,
}

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

/// What the smoother needs of each step.
#[derive(Debug, Clone, Copy)]
struct Stored {
    x_pred: Vector4<f64>,
    p_pred: Matrix4<f64>,
    f: Matrix4<f64>,
    x: Vector4<f64>,
    p: Matrix4<f64>,
}

/// The running filter.
#[derive(Debug, Clone)]
pub struct Fusion {
    cfg: FusionConfig,
    declination_rad: f64,
    x: Vector4<f64>,
    p: Matrix4<f64>,
    started: bool,
    pending: Option<PendingFix>,
    // Innovations and variances of the fixes refused in a row by the gate.
    gated: Vec<(Vector2<f64>, f64)>,
    // Innovations and variances of the fixes held for a consensus.
    held: Vec<(Vector2<f64>, f64)>,
    last_step: Option<(f64, Vector2<f64>)>,
    velocity: Vector2<f64>,
    first_fix_t: Option<f64>,
    duty: Duty,
    on_s: f64,
    last_t: Option<f64>,
    steps: Vec<FusedStep>,
    stored: Vec<Stored>,
    counts: FixCounts,
}

impl Fusion {
    /// A filter with a validated configuration and the declination at the origin, radians.
    pub fn new(cfg: FusionConfig, declination_rad: f64) -> Self {
        Fusion {
            cfg,
            declination_rad,
            x: Vector4::new(0.0, 0.0, 1.0, 0.0),
            p: Matrix4::zeros(),
            started: false,
            pending: None,
            gated: Vec::new(),
            held: Vec::new(),
            last_step: None,
            velocity: Vector2::zeros(),
            first_fix_t: None,
            duty: Duty::Calibrating,
            on_s: 0.0,
            last_t: None,
            steps: Vec::new(),
            stored: Vec::new(),
            counts: FixCounts::default(),
        }
    }

    /// The configuration.
    pub fn config(&self) -> &FusionConfig {
        &self.cfg
    }

    /// The declination applied, radians.
    pub fn declination_rad(&self) -> f64 {
        self.declination_rad
    }

    /// Whether the receiver should be on at time `t`. Always in best-performance mode. In
    /// energy-saving mode it stays on from the first fix until the scale and the heading
    /// correction are known ([`FusionConfig::calibrated_scale_sd`],
    /// [`FusionConfig::calibrated_bias_sd_deg`], at most [`FusionConfig::max_calibration_s`]):
    /// compensating systematic errors between windows needs them first. Then it is on for
    /// `window_s` at the start of every `period_s`.
    pub fn gnss_wanted(&self, t: f64) -> bool {
        match self.duty {
            Duty::Off { next_on } => t >= next_on,
            _ => true,
        }
    }

    /// How long the receiver was on from the first fix to the last step or fix, and that span,
    /// s.
    pub fn gnss_on_s(&self) -> Option<(f64, f64)> {
        let t0 = self.first_fix_t?;
        Some((self.on_s, self.last_t.unwrap_or(t0) - t0))
    }

    /// Moves the receiver schedule to time `t` (energy-saving mode).
    fn schedule(&mut self, t: f64) {
        if let Some(last) = self.last_t {
            if self.gnss_wanted(last) && t > last {
                self.on_s += t - last;
            }
        }
        self.last_t = Some(self.last_t.map_or(t, |l| l.max(t)));
        let GnssMode::EnergySaving { period_s, window_s } = self.cfg.mode else {
            return;
        };
        self.duty = match self.duty {
            Duty::Calibrating => {
                let known = self.started
                    && self.p[(2, 2)].sqrt() <= self.cfg.calibrated_scale_sd
                    && self.p[(3, 3)].sqrt() <= self.cfg.calibrated_bias_sd_deg.to_radians();
                let too_long = self
                    .first_fix_t
                    .is_some_and(|t0| t - t0 >= self.cfg.max_calibration_s);
                if known || too_long {
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

    /// Offers a fix at time `t`, already in the local frame (east, north, m), with its reported
    /// accuracy (m). It is kept for the next step, replacing an older unused one, unless the
    /// walker stands: `still` (the motion detector says so) and no step for
    /// [`FusionConfig::standing_after_s`]. Then it updates the last step's estimate at once.
    pub fn offer_fix(
        &mut self,
        t: f64,
        east: f64,
        north: f64,
        accuracy_m: f64,
        still: bool,
    ) -> Option<FixOutcome> {
        if self.first_fix_t.is_none() {
            self.first_fix_t = Some(t);
        }
        self.schedule(t);
        if !self.gnss_wanted(t) {
            self.counts.receiver_off += 1;
            return Some(FixOutcome::ReceiverOff);
        }
        if !(accuracy_m <= self.cfg.max_accuracy_m) || !(accuracy_m > 0.0) {
            self.counts.too_inaccurate += 1;
            return Some(FixOutcome::TooInaccurate);
        }
        let fix = PendingFix {
            t,
            en: Vector2::new(east, north),
            sigma: accuracy_m / ACCURACY_PER_SIGMA,
        };
        let last_step_t = self.steps.last().map(|s| s.t).filter(|_| self.started);
        let standing = last_step_t.filter(|&ts| still && t - ts >= self.cfg.standing_after_s);
        if let Some(t_step) = standing {
            // The walker has not moved since the last step: the fix updates that step's
            // estimate (and what the smoother stored of it) now, as if it had come then.
            self.velocity = Vector2::zeros();
            let (outcome, innovation) = self.update(t, fix);
            let rec = self.snapshot(t_step, innovation, Some(outcome));
            if let (Some(stored), Some(last)) = (self.stored.last_mut(), self.steps.last_mut()) {
                stored.x = self.x;
                stored.p = self.p;
                *last = rec;
            }
            return Some(outcome);
        }
        if self.pending.is_some() {
            self.counts.superseded += 1;
        }
        self.pending = Some(fix);
        None
    }

    /// Advances the filter by one step of PDR length `length_m` and heading `heading_rad`
    /// (compass, from the engine's orientation source) ending at time `t`, then updates it with
    /// the pending fix. Steps before the first usable fix only wait for it. Returns the fused
    /// step once the filter has started.
    pub fn step(&mut self, t: f64, length_m: f64, heading_rad: Option<f64>) -> Option<FusedStep> {
        if !self.started {
            let p = self.pending.take()?;
            if t - p.t > self.cfg.max_fix_age_s {
                self.counts.stale += 1;
                return None;
            }
            self.x = Vector4::new(p.en.x, p.en.y, 1.0, 0.0);
            // One fix may be an outlier: start wide, so that the next fixes are taken by
            // consensus (see `consensus_sd_m`).
            let s2 = (p.sigma * p.sigma).max(4.0 * sq(self.cfg.consensus_sd_m));
            self.p = Matrix4::from_diagonal(&Vector4::new(
                s2,
                s2,
                self.cfg.scale0_sd * self.cfg.scale0_sd,
                sq(self.cfg.bias0_sd_deg.to_radians()),
            ));
            self.started = true;
            self.counts.used += 1;
            self.last_step = Some((t, p.en));
            let rec = self.record(t, None, Some(FixOutcome::Started));
            self.stored.push(Stored {
                x_pred: self.x,
                p_pred: self.p,
                f: Matrix4::identity(),
                x: self.x,
                p: self.p,
            });
            return Some(rec);
        }
        let (x_pred, p_pred, f) = self.predict(length_m, heading_rad);
        self.x = x_pred;
        self.p = p_pred;
        let mut innovation = None;
        let mut outcome = None;
        if let Some(fix) = self.pending.take() {
            let (o, nu) = self.update(t, fix);
            outcome = Some(o);
            innovation = nu;
        }
        let en = Vector2::new(self.x[0], self.x[1]);
        if let Some((t0, p0)) = self.last_step {
            let dt = t - t0;
            if dt > 0.0 && dt < 2.0 {
                self.velocity = (en - p0) / dt;
            } else {
                self.velocity = Vector2::zeros();
            }
        }
        self.last_step = Some((t, en));
        self.schedule(t);
        self.stored.push(Stored {
            x_pred,
            p_pred,
            f,
            x: self.x,
            p: self.p,
        });
        Some(self.record(t, innovation, outcome))
    }

    /// Marks the end of a bout (a stop or a gap): the walking velocity used to carry fixes to
    /// the next step is forgotten.
    pub fn end_bout(&mut self) {
        self.velocity = Vector2::zeros();
        self.last_step = None;
    }

    fn record(
        &mut self,
        t: f64,
        innovation: Option<[f64; 2]>,
        fix: Option<FixOutcome>,
    ) -> FusedStep {
        let r = self.snapshot(t, innovation, fix);
        self.steps.push(r);
        r
    }

    /// The filter's state as a step's result.
    fn snapshot(&self, t: f64, innovation: Option<[f64; 2]>, fix: Option<FixOutcome>) -> FusedStep {
        FusedStep {
            t,
            east_m: self.x[0],
            north_m: self.x[1],
            cov: [self.p[(0, 0)], self.p[(0, 1)], self.p[(1, 1)]],
            scale: self.x[2],
            bias_rad: self.x[3],
            scale_bias_sd: [self.p[(2, 2)].sqrt(), self.p[(3, 3)].sqrt()],
            innovation,
            fix,
        }
    }

    fn predict(
        &self,
        length: f64,
        heading: Option<f64>,
    ) -> (Vector4<f64>, Matrix4<f64>, Matrix4<f64>) {
        let (k, beta) = (self.x[2], self.x[3]);
        let mut x = self.x;
        let mut f = Matrix4::identity();
        let mut q = Matrix4::zeros();
        if let Some(theta) = heading.filter(|_| length > 0.0) {
            let phi = theta + self.declination_rad + beta;
            let (s, c) = libm::sincos(phi);
            x[0] += k * length * s;
            x[1] += k * length * c;
            f[(0, 2)] = length * s;
            f[(0, 3)] = k * length * c;
            f[(1, 2)] = length * c;
            f[(1, 3)] = -k * length * s;
            // Displacement noise from the step's own length and heading errors.
            let sl = self.cfg.step_length_sd_rel * length;
            let sh = self.cfg.heading_sd_deg.to_radians();
            let g = nalgebra::Matrix2::new(k * s, k * length * c, k * c, -k * length * s);
            let qd = g * Matrix2::from_diagonal(&Vector2::new(sl * sl, sh * sh)) * g.transpose();
            q.fixed_view_mut::<2, 2>(0, 0).copy_from(&qd);
        }
        q[(2, 2)] = self.cfg.scale_rw * self.cfg.scale_rw;
        q[(3, 3)] = sq(self.cfg.bias_rw_deg.to_radians());
        let p = symmetric(f * self.p * f.transpose() + q);
        x[3] = wrap_pi(x[3]);
        (x, p, f)
    }

    fn update(&mut self, t: f64, fix: PendingFix) -> (FixOutcome, Option<[f64; 2]>) {
        let age = t - fix.t;
        if age > self.cfg.max_fix_age_s || age < -self.cfg.max_fix_age_s {
            self.counts.stale += 1;
            return (FixOutcome::Stale, None);
        }
        // Carry the fix to the step time along the walking velocity.
        let z = fix.en + self.velocity * age;
        let ext = self.cfg.velocity_sd_mps * age;
        let r = fix.sigma * fix.sigma + ext * ext;
        let nu = z - Vector2::new(self.x[0], self.x[1]);
        let p_pos = self.p.fixed_view::<2, 2>(0, 0).into_owned();
        let prior_sd = (0.5 * p_pos.trace()).sqrt();
        if prior_sd > self.cfg.consensus_sd_m {
            return self.consensus(nu, r);
        }
        let Some(s_inv) = (p_pos + Matrix2::identity() * r).try_inverse() else {
            self.counts.gated += 1;
            return (FixOutcome::Gated, Some([nu.x, nu.y]));
        };
        let d2 = (nu.transpose() * s_inv * nu)[(0, 0)];
        if !(d2 <= self.cfg.gate_chi2) {
            self.gated.push((nu, r));
            if self.gated.len() < self.cfg.reset_after as usize {
                self.counts.gated += 1;
                return (FixOutcome::Gated, Some([nu.x, nu.y]));
            }
            // The GNSS has disagreed for a while (the PDR drifted in a way its covariance did
            // not foresee): believe it, by the same consensus as after a wide prior.
            let held = std::mem::take(&mut self.gated);
            self.counts.resets += 1;
            self.held = held;
            // Forget the position's correlations: its error is not what P said.
            for i in 0..2 {
                for j in 0..4 {
                    self.p[(i, j)] = 0.0;
                    self.p[(j, i)] = 0.0;
                }
                self.p[(i, i)] = sq(self.cfg.consensus_sd_m) * 4.0;
            }
            let (_, nu_used) = self.consensus_update();
            return (FixOutcome::Reset, nu_used.or(Some([nu.x, nu.y])));
        }
        self.gated.clear();
        self.held.clear();
        self.apply(nu, r);
        self.counts.used += 1;
        (FixOutcome::Used, Some([nu.x, nu.y]))
    }

    /// A fix while the prior is too wide for the Mahalanobis gate to tell an outlier (at the
    /// start, after an outage, at the start of an energy-saving window): it is held, and the
    /// filter is updated once [`FusionConfig::consensus_n`] held fixes agree with each other.
    fn consensus(&mut self, nu: Vector2<f64>, r: f64) -> (FixOutcome, Option<[f64; 2]>) {
        self.held.push((nu, r));
        let (outcome, _) = self.consensus_update();
        (outcome, Some([nu.x, nu.y]))
    }

    /// Looks for the largest group of held fixes that agree pairwise-with-one-of-them (each
    /// innovation was taken at its own step; between those steps the prediction moved with the
    /// walker, so agreeing fixes see one offset). Two innovations agree when their difference
    /// is within the gate for their summed variances. With [`FusionConfig::consensus_n`] in
    /// the group, one update with their mean innovation; otherwise the fixes wait (at most
    /// twice that many, oldest dropped). Returns the outcome and the innovation used.
    fn consensus_update(&mut self) -> (FixOutcome, Option<[f64; 2]>) {
        let need = self.cfg.consensus_n as usize;
        let agree = |a: &(Vector2<f64>, f64), b: &(Vector2<f64>, f64)| {
            (a.0 - b.0).norm_squared() / (a.1 + b.1) <= self.cfg.gate_chi2
        };
        let best = (0..self.held.len())
            .map(|i| {
                let group: Vec<usize> = (0..self.held.len())
                    .filter(|&j| agree(&self.held[i], &self.held[j]))
                    .collect();
                group
            })
            .max_by_key(|g| g.len())
            .unwrap_or_default();
        if best.len() < need {
            if self.held.len() >= 2 * need {
                self.held.remove(0);
                self.counts.gated += 1;
            }
            return (FixOutcome::Held, None);
        }
        let held = std::mem::take(&mut self.held);
        self.counts.gated += (held.len() - best.len()) as u64;
        // One update with the mean innovation; its variance is that of a mean of independent
        // fixes.
        let n = best.len() as f64;
        let nu = best.iter().fold(Vector2::zeros(), |a, &i| a + held[i].0) / n;
        let r = best.iter().map(|&i| held[i].1).sum::<f64>() / (n * n);
        self.apply(nu, r);
        self.counts.used += best.len() as u64;
        self.gated.clear();
        (FixOutcome::Used, Some([nu.x, nu.y]))
    }

    /// The Kalman update with innovation `nu` of the position and noise variance `r` per axis
    /// (H = [I₂ 0]), in Joseph form.
    fn apply(&mut self, nu: Vector2<f64>, r: f64) {
        let rm = Matrix2::identity() * r;
        let s = self.p.fixed_view::<2, 2>(0, 0) + rm;
        let Some(s_inv) = s.try_inverse() else {
            return;
        };
        let pht = self.p.fixed_view::<4, 2>(0, 0).into_owned();
        let k = pht * s_inv;
        self.x += k * nu;
        self.x[3] = wrap_pi(self.x[3]);
        // P = (I − KH) P (I − KH)ᵀ + K R Kᵀ.
        let mut ikh = Matrix4::identity();
        let mut block = ikh.fixed_view_mut::<4, 2>(0, 0);
        block -= k;
        self.p = symmetric(ikh * self.p * ikh.transpose() + k * rm * k.transpose());
    }

    /// Every fused step so far.
    pub fn steps(&self) -> &[FusedStep] {
        &self.steps
    }

    /// Fix counters.
    pub fn counts(&self) -> FixCounts {
        self.counts
    }

    /// The Rauch–Tung–Striebel smoothed estimate at every fused step: the filter's estimates
    /// corrected backwards by the later fixes (x̂ₖˢ = x̂ₖ + Cₖ(x̂ₖ₊₁ˢ − x̂ₖ₊₁⁻),
    /// Cₖ = Pₖ Fₖ₊₁ᵀ (Pₖ₊₁⁻)⁻¹, Pₖˢ = Pₖ + Cₖ(Pₖ₊₁ˢ − Pₖ₊₁⁻)Cₖᵀ). A reset starts a new segment:
    /// nothing is carried back across it.
    pub fn smoothed(&self) -> Vec<FusedStep> {
        let n = self.stored.len();
        let mut out = self.steps.clone();
        if n == 0 {
            return out;
        }
        let mut xs = self.stored[n - 1].x;
        let mut ps = self.stored[n - 1].p;
        for k in (0..n - 1).rev() {
            let next = &self.stored[k + 1];
            let cur = &self.stored[k];
            let reset = matches!(self.steps[k + 1].fix, Some(FixOutcome::Reset));
            match next.p_pred.try_inverse().filter(|_| !reset) {
                Some(inv) => {
                    let c = cur.p * next.f.transpose() * inv;
                    let mut dx = xs - next.x_pred;
                    dx[3] = wrap_pi(dx[3]);
                    xs = cur.x + c * dx;
                    ps = symmetric(cur.p + c * (ps - next.p_pred) * c.transpose());
                }
                None => {
                    xs = cur.x;
                    ps = cur.p;
                }
            }
            let o = &mut out[k];
            o.east_m = xs[0];
            o.north_m = xs[1];
            o.cov = [ps[(0, 0)], ps[(0, 1)], ps[(1, 1)]];
            o.scale = xs[2];
            o.bias_rad = wrap_pi(xs[3]);
            o.scale_bias_sd = [ps[(2, 2)].sqrt(), ps[(3, 3)].sqrt()];
        }
        out
    }

    /// The current state covariance (diagnostics and tests).
    pub fn covariance(&self) -> Matrix4<f64> {
        self.p
    }
}

fn sq(x: f64) -> f64 {
    x * x
}

fn symmetric(p: Matrix4<f64>) -> Matrix4<f64> {
    (p + p.transpose()) * 0.5
}

/// The magnetic declination at a point, degrees (positive east), from the World Magnetic Model
/// (WMM2020 for 2020–2024, WMM2025 for 2025–2029; dates outside are clamped into that span), and
/// whether the date was inside it. `unix_s` is the date as Unix seconds; `None` takes
/// 2025-01-01.
pub fn wmm_declination_deg(
    lat_deg: f64,
    lon_deg: f64,
    h_m: f64,
    unix_s: Option<f64>,
) -> Option<(f64, bool)> {
    use world_magnetic_model::time::{Date, Month, OffsetDateTime};
    use world_magnetic_model::uom::si::angle::degree;
    use world_magnetic_model::uom::si::f32::{Angle, Length};
    use world_magnetic_model::uom::si::length::meter;
    let first = Date::from_calendar_date(2020, Month::January, 1).ok()?;
    let last = Date::from_calendar_date(2029, Month::December, 31).ok()?;
    let default = Date::from_calendar_date(2025, Month::January, 1).ok()?;
    let date = unix_s
        .filter(|s| s.is_finite())
        .and_then(|s| OffsetDateTime::from_unix_timestamp(s as i64).ok())
        .map_or(default, |d| d.date());
    let inside = date >= first && date <= last;
    let date = date.clamp(first, last);
    let field = world_magnetic_model::GeomagneticField::new(
        Length::new::<meter>(h_m as f32),
        Angle::new::<degree>(lat_deg as f32),
        Angle::new::<degree>(lon_deg as f32),
        date,
    )
    .ok()?;
    let d = f64::from(field.declination().get::<degree>());
    d.is_finite().then_some((d, inside && unix_s.is_some()))
}

/// The declination a configuration asks for at a frame's origin, radians, and a note when the
/// model was used without a known date.
pub fn declination_for(
    cfg: &FusionConfig,
    frame: &LocalFrame,
    fix_t: f64,
) -> (f64, Option<String>) {
    match cfg.declination {
        Declination::None => (0.0, None),
        Declination::Fixed { deg } => (deg.to_radians(), None),
        Declination::Wmm => {
            // A fix time between 2017 and 2096 is taken for Unix time.
            let date = if (1.5e9..4.0e9).contains(&fix_t) {
                Some(fix_t)
            } else {
                cfg.date_unix_s
            };
            match wmm_declination_deg(frame.lat0_deg, frame.lon0_deg, frame.h0_m, date) {
                Some((d, true)) => (d.to_radians(), None),
                Some((d, false)) => (
                    d.to_radians(),
                    Some(format!(
                        "declination {d:.2}° from the World Magnetic Model without a known date in 2020–2029"
                    )),
                ),
                None => (0.0, Some("declination unavailable; headings used as they are".into())),
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn declination_from_the_world_magnetic_model() {
        // Florence, 2021: Basso 2021 Remark 2 gives +3.20° (magnetic-declination.com).
        let unix_2021 = 1_639_526_400.0; // 2021-12-15
        let (d, known) = wmm_declination_deg(43.77, 11.25, 50.0, Some(unix_2021)).unwrap();
        assert!(known);
        assert!((d - 3.2).abs() < 0.4, "{d}");
        // Seattle is about 15° east.
        let (d, _) = wmm_declination_deg(47.6, -122.3, 0.0, Some(1.75e9)).unwrap();
        assert!((d - 15.0).abs() < 1.5, "{d}");
    }

    #[test]
    fn straight_walk_with_fixes_recovers_scale_and_bias() {
        // Truth: 0.7 m steps due north. PDR: lengths 10 % long, headings 8° east of truth.
        let mut f = Fusion::new(FusionConfig::default(), 0.0);
        let mut truth = Vector2::new(0.0, 0.0);
        let mut rng = 12345u64;
        let mut noise = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for i in 0..600 {
            let t = i as f64 * 0.55;
            truth.y += 0.7;
            if i % 2 == 0 {
                f.offer_fix(
                    t,
                    truth.x + 6.0 * noise(),
                    truth.y + 6.0 * noise(),
                    4.0,
                    false,
                );
            }
            f.step(t, 0.77, Some(8f64.to_radians()));
            let p = f.covariance();
            assert!((p - p.transpose()).norm() < 1e-9);
            assert!(p.cholesky().is_some(), "not positive definite at step {i}");
        }
        let last = f.steps().last().unwrap();
        assert!((last.scale - 1.0 / 1.1).abs() < 0.02, "{}", last.scale);
        assert!(
            (last.bias_rad.to_degrees() + 8.0).abs() < 2.0,
            "{}",
            last.bias_rad.to_degrees()
        );
    }
}
