//! GNSS/PDR fusion: a Kalman filter that advances once per detected step (Basso 2021 §2.2.6),
//! with the systematic errors of §2.2.5 and §3.1.2 in its state, an energy-saving GNSS duty
//! cycle, and a Rauch–Tung–Striebel smoother for whole logs (ours; none of the papers has one).
//! May import: the rest of `engine`.
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
//!   on the simulated city walk, starting it at the first fix left the first minutes
//!   uncorrected (figures in `docs/methods/basso2021.md`).
//!
//! # Rooms
//! - [`config`]: the settings and the GNSS modes;
//! - [`filter`]: the per-step extended Kalman filter (`filter/learn.rs`: how it learns the
//!   scale and the heading correction, and the fixes' white share);
//! - [`output`]: what it reports per step and per fix;
//! - [`schedule`]: energy saving's receiver schedule;
//! - [`smoother`]: the Rauch–Tung–Striebel smoother;
//! - [`declination`]: the World Magnetic Model's declination at the origin;
//! - [`origin`]: the track's origin, the first of agreeing fixes.

pub mod config;
pub mod declination;
pub mod filter;
pub mod origin;
pub mod output;
pub mod schedule;
pub mod smoother;

pub use config::{
    Declination, FusionConfig, GnssMode, ACCURACY_PER_SIGMA, DEFAULT_PERIOD_S, DEFAULT_WINDOW_S,
};
pub use declination::{declination_for, wmm_declination_deg, DeclinationNote};
pub use filter::{FixInput, Fusion, FusionDiagnostics, StepInput};
pub use origin::OriginVote;
pub use output::{FixCounts, FixOutcome, FusedStep, GnssVerdict};
