//! The per-step extended Kalman filter of the GNSS/PDR fusion (Basso 2021 §2.2.5–2.2.6; the
//! equations are ours, see the module documentation of [`crate::engine::fusion`]).
//! May import: the rest of `engine`.

use super::config::{FusionConfig, ACCURACY_PER_SIGMA};
use super::output::{FixCounts, FixOutcome, FusedStep, GnssVerdict};
use super::schedule::Schedule;
use super::smoother::{Smoother, Stored};
use crate::engine::math::{symmetric, wrap_pi};
use nalgebra::{Matrix2, Matrix4, Vector2, Vector4};

/// A fix waiting for the next step, in the local frame.
#[derive(Debug, Clone, Copy)]
struct PendingFix {
    t: f64,
    en: Vector2<f64>,
    sigma: f64,
}

/// A fix offered to the filter ([`Fusion::push_fix`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixInput {
    /// Time of the fix, s.
    pub t: f64,
    /// Position east in the local frame, m.
    pub east_m: f64,
    /// Position north in the local frame, m.
    pub north_m: f64,
    /// Reported horizontal accuracy (68 % radius), m.
    pub accuracy_m: f64,
    /// The motion detector says the walker is still.
    pub still: bool,
}

/// One PDR step ([`Fusion::push_step`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInput {
    /// Time of the step's end, s.
    pub t: f64,
    /// The PDR's step length, m.
    pub length_m: f64,
    /// The PDR's heading (compass, from the engine's orientation source), rad; `None` moves
    /// nothing.
    pub heading_rad: Option<f64>,
}

/// The filter's counters and current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FusionDiagnostics {
    /// The declination applied, radians.
    pub declination_rad: f64,
    /// What happened to the fixes.
    pub counts: FixCounts,
    /// How long the receiver was (or would have been) on since the first fix, and that span, s.
    pub gnss_on_s: Option<(f64, f64)>,
    /// The last fused step, once the filter has started.
    pub last: Option<FusedStep>,
    /// What the filter makes of the GNSS now.
    pub verdict: GnssVerdict,
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
    schedule: Schedule,
    steps: Vec<FusedStep>,
    smoother: Smoother,
    counts: FixCounts,
    // Whether each of the last fixes offered to the gate was taken.
    recent: std::collections::VecDeque<bool>,
}

/// How many recent fixes [`Fusion::verdict`] looks at.
pub const RECENT_FIXES: usize = 10;

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
            schedule: Schedule::new(&cfg),
            steps: Vec::new(),
            smoother: Smoother::default(),
            counts: FixCounts::default(),
            recent: std::collections::VecDeque::with_capacity(RECENT_FIXES),
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

    /// Whether the receiver should be on at time `t` ([`Schedule::wanted`]).
    pub fn gnss_wanted(&self, t: f64) -> bool {
        self.schedule.wanted(t)
    }

    /// How long the receiver was on from the first fix to the last step or fix, and that span,
    /// s.
    pub fn gnss_on_s(&self) -> Option<(f64, f64)> {
        self.schedule.on_s()
    }

    /// Moves the receiver schedule to time `t`.
    fn schedule(&mut self, t: f64) {
        let calibrated = self.calibrated();
        self.schedule.push(t, calibrated);
    }

    /// Offers a fix. It is kept for the next step, replacing an older unused one, unless the
    /// walker stands: [`FixInput::still`] and no step for [`FusionConfig::standing_after_s`].
    /// Then it updates the last step's estimate at once. Returns what happened to it, unless it
    /// waits for the next step.
    pub fn push_fix(&mut self, fix: &FixInput) -> Option<FixOutcome> {
        let FixInput {
            t,
            east_m: east,
            north_m: north,
            accuracy_m,
            still,
        } = *fix;
        self.schedule.fix(t);
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
            if let (Some(stored), Some(last)) = (self.smoother.last_mut(), self.steps.last_mut()) {
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

    /// Advances the filter by one PDR step, then updates it with the pending fix. Steps before
    /// the first usable fix only wait for it. Returns the fused step once the filter has
    /// started.
    pub fn push_step(&mut self, step: &StepInput) -> Option<FusedStep> {
        let StepInput {
            t,
            length_m,
            heading_rad,
        } = *step;
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
            self.smoother.push(Stored {
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
        self.smoother.push(Stored {
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
        let (outcome, nu) = self.update_inner(t, fix);
        self.remember(outcome);
        (outcome, nu)
    }

    fn update_inner(&mut self, t: f64, fix: PendingFix) -> (FixOutcome, Option<[f64; 2]>) {
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

    /// Counters and current values.
    pub fn diagnostics(&self) -> FusionDiagnostics {
        FusionDiagnostics {
            declination_rad: self.declination_rad,
            counts: self.counts,
            gnss_on_s: self.gnss_on_s(),
            last: self.steps.last().copied(),
            verdict: self.verdict(),
        }
    }

    /// What the filter makes of the GNSS now: distrusted when at least half of the last
    /// [`RECENT_FIXES`] fixes offered were refused by the gate or held; calibrated when the
    /// scale and the heading correction are known.
    pub fn verdict(&self) -> GnssVerdict {
        if !self.started {
            return GnssVerdict::Waiting;
        }
        let refused = self.recent.iter().filter(|&&ok| !ok).count();
        if self.recent.len() >= RECENT_FIXES / 2 && 2 * refused >= self.recent.len() {
            return GnssVerdict::Distrusted;
        }
        if self.calibrated() {
            GnssVerdict::Calibrated
        } else {
            GnssVerdict::Learning
        }
    }

    /// The scale and the heading correction are known well enough.
    fn calibrated(&self) -> bool {
        self.started
            && self.p[(2, 2)].sqrt() <= self.cfg.calibrated_scale_sd
            && self.p[(3, 3)].sqrt() <= self.cfg.calibrated_bias_sd_deg.to_radians()
    }

    /// Remembers whether a fix offered to the gate was taken.
    fn remember(&mut self, outcome: FixOutcome) {
        let ok = match outcome {
            FixOutcome::Used | FixOutcome::Started | FixOutcome::Reset => true,
            FixOutcome::Gated | FixOutcome::Held => false,
            FixOutcome::TooInaccurate | FixOutcome::Stale | FixOutcome::ReceiverOff => return,
        };
        if self.recent.len() == RECENT_FIXES {
            self.recent.pop_front();
        }
        self.recent.push_back(ok);
    }

    /// The Rauch–Tung–Striebel smoothed estimate at every fused step ([`Smoother`]).
    pub fn smoothed(&self) -> Vec<FusedStep> {
        self.smoother.smooth(&self.steps)
    }

    /// The current state covariance (diagnostics and tests).
    pub fn covariance(&self) -> Matrix4<f64> {
        self.p
    }
}

fn sq(x: f64) -> f64 {
    x * x
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

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
                f.push_fix(&FixInput {
                    t,
                    east_m: truth.x + 6.0 * noise(),
                    north_m: truth.y + 6.0 * noise(),
                    accuracy_m: 4.0,
                    still: false,
                });
            }
            f.push_step(&StepInput {
                t,
                length_m: 0.77,
                heading_rad: Some(8f64.to_radians()),
            });
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
