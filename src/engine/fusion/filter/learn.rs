//! How the filter learns the step-length scale and the heading correction, and how much it
//! trusts single fixes for them: only while walking, from baselines when the fixes' errors
//! persist, within physical bounds; and the white share of the fixes' error measured on the walk
//! (ours; Basso 2021 §2.2.5 corrects the step length from the distance between fixes).
//! May import: the rest of `engine`.

use super::{sq, Fusion, PendingFix, B, K};
use crate::engine::fusion::config::ACCURACY_PER_SIGMA;
use crate::engine::math::{symmetric, wrap_pi};
use nalgebra::{Matrix2, Matrix2x6, Matrix6, Matrix6x2, Vector2};

/// Fixes whose measured white share is at least this teach the scale one by one.
pub(super) const WHITE_FIXES: f64 = 0.5;

/// Two fixes further apart than this, s, say nothing of how fast their error changes.
pub(super) const WHITE_PAIR_S: f64 = 2.5;

/// One end of a baseline: a fix that taught the filter while walking, and where the PDR alone
/// (declination applied, no correction) had got to then.
#[derive(Debug, Clone, Copy)]
pub(super) struct Anchor {
    fix: Vector2<f64>,
    dead_reckoned: Vector2<f64>,
    sigma: f64,
}

impl Fusion {
    /// Whether a fix may teach the scale and the heading correction: the walker must be
    /// walking, and for long enough that the receiver has caught up (phones' receivers hold
    /// the standing position for 5–10 s after the walker sets off, then jump:
    /// [`FusionConfig::learn_after_walking_s`](crate::engine::fusion::FusionConfig::learn_after_walking_s)).
    pub(super) fn teaches(&self, t: f64, fix: &PendingFix) -> bool {
        !fix.standing
            && self
                .walking_since
                .is_some_and(|t0| t - t0 >= self.cfg.learn_after_walking_s)
    }

    /// A fix that may teach ends a baseline when the walk since the last one is long against
    /// the fixes' error: the displacement the fixes show, g, against the PDR's alone, d,
    /// observes the scale |g|/|d| and the heading correction ∠g − ∠d, each with the standard
    /// deviation σ/|d| (σ² the two ends' variances summed; Basso 2021 §2.2.5 corrects the step
    /// length from the distance between fixes). A chord between two fixes is not shortened by
    /// the receiver's smoothing of the path between them, only by errors at its ends. A
    /// baseline that disagrees with the estimate by more than the gate is dropped. The fix then
    /// starts the next one.
    pub(super) fn baseline(&mut self, z: Vector2<f64>, sigma: f64) {
        if self.cfg.baseline_min_m <= 0.0
            || sigma * ACCURACY_PER_SIGMA > self.cfg.baseline_max_accuracy_m
        {
            return;
        }
        let here = Anchor {
            fix: z,
            dead_reckoned: self.dead_reckoned,
            sigma,
        };
        let Some(a) = self.anchor else {
            self.anchor = Some(here);
            return;
        };
        let d = self.dead_reckoned - a.dead_reckoned;
        let g = z - a.fix;
        let pair = (sq(a.sigma) + sq(sigma)).sqrt();
        let len = d.norm();
        if len < self.cfg.baseline_min_m || len < self.cfg.baseline_sigmas * pair {
            return;
        }
        self.anchor = Some(here);
        let heading = |v: Vector2<f64>| libm::atan2(v.x, v.y);
        let obs = Vector2::new(g.norm() / len, wrap_pi(heading(g) - heading(d)));
        let sd = pair / len;
        let mut h = Matrix2x6::zeros();
        h[(0, K)] = 1.0;
        h[(1, B)] = 1.0;
        let nu = Vector2::new(obs.x - self.x[K], wrap_pi(obs.y - self.x[B]));
        let rm = Matrix2::new(sq(sd), 0.0, 0.0, sq(sd));
        let s = h * self.p * h.transpose() + rm;
        let Some(s_inv) = s.try_inverse() else {
            return;
        };
        if !((nu.transpose() * s_inv * nu)[(0, 0)] <= self.cfg.gate_chi2) {
            self.counts.baselines_gated += 1;
            return;
        }
        let k: Matrix6x2<f64> = self.p * h.transpose() * s_inv;
        self.x += k * nu;
        self.bound();
        let ikh = Matrix6::identity() - k * h;
        self.p = symmetric(ikh * self.p * ikh.transpose() + k * rm * k.transpose());
        self.counts.baselines += 1;
    }

    /// Whether only baselines teach the scale: when the fixes' errors persist (their white
    /// share, measured on the walk, is below [`WHITE_FIXES`]), a run of fixes is one piece of
    /// evidence, not many, and a receiver that lags or holds its position shortens every
    /// short displacement. Fixes whose errors are white teach it one by one.
    pub(super) fn baselines_only(&self) -> bool {
        self.cfg.baseline_min_m > 0.0 && self.white_share < WHITE_FIXES
    }

    /// Holds the corrections within their physical bounds
    /// ([`FusionConfig::scale_bounds`](crate::engine::fusion::FusionConfig::scale_bounds),
    /// [`FusionConfig::bias_bound_deg`](crate::engine::fusion::FusionConfig::bias_bound_deg)).
    pub(super) fn bound(&mut self) {
        self.x[B] = wrap_pi(self.x[B]);
        let (lo, hi) = self.cfg.scale_bounds;
        self.x[K] = self.x[K].clamp(lo, hi);
        let bound = self.cfg.bias_bound_deg.to_radians();
        self.x[B] = self.x[B].clamp(-bound, bound);
    }

    /// How much of the fixes' error is new at every fix, measured on the walk: for two fixes
    /// taken while walking at most [`WHITE_PAIR_S`] apart, the change of their error is
    /// δ = (z₂ − z₁) − k R(β) (d₂ − d₁), d the PDR alone. Its expected square is
    /// 4σ²(w + (1 − w)(1 − ρ)), ρ = e^(−Δt/τ): 4σ² for white errors (a simulator's), far less
    /// for a phone's, whose error persists. Over the last
    /// [`FusionConfig::white_share_window`](crate::engine::fusion::FusionConfig::white_share_window)
    /// pairs, q = Σ|δ|² / Σ4σ² gives w = (q − (1 − ρ)) / ρ, held within
    /// [[`FusionConfig::fix_white_share`](crate::engine::fusion::FusionConfig::fix_white_share),
    /// 1]. Until the window is half full, the configured share holds.
    pub(super) fn measure_white_share(&mut self, t: f64, z: Vector2<f64>, sigma: f64) {
        let n = self.cfg.white_share_window as usize;
        let here = (t, z, self.dead_reckoned);
        let Some((t0, z0, d0)) = self.last_walking_fix.replace(here) else {
            return;
        };
        let dt = t - t0;
        if n == 0 || !(dt > 0.0 && dt <= WHITE_PAIR_S) || self.cfg.fix_error_tau_s <= 0.0 {
            return;
        }
        let (s, c) = libm::sincos(self.x[B]);
        let d = self.dead_reckoned - d0;
        // Rotate the PDR's displacement by the heading correction (clockwise, compass sense).
        let pdr = Vector2::new(c * d.x + s * d.y, -s * d.x + c * d.y) * self.x[K];
        let delta = (z - z0) - pdr;
        let rho = libm::exp(-dt / self.cfg.fix_error_tau_s);
        if self.pairs.len() == n {
            self.pairs.pop_front();
        }
        self.pairs
            .push_back((delta.norm_squared(), 4.0 * sq(sigma), rho));
        if self.pairs.len() < n / 2 {
            return;
        }
        let (num, den, rho_sum) = self
            .pairs
            .iter()
            .fold((0.0, 0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1, a.2 + p.2));
        let rho = rho_sum / self.pairs.len() as f64;
        let q = num / den;
        let w = (q - (1.0 - rho)) / rho;
        self.white_share = w.clamp(self.cfg.fix_white_share, 1.0);
    }
}
