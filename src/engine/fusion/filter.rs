//! The per-step extended Kalman filter of the GNSS/PDR fusion (Basso 2021 §2.2.5–2.2.6; the
//! equations are ours, see the module documentation of [`crate::engine::fusion`]).
//! May import: the rest of `engine`.

use super::config::{FusionConfig, ACCURACY_PER_SIGMA};
use super::origin::largest_agreeing_group;
use super::output::{FixCounts, FixOutcome, FusedStep, GnssVerdict};
use super::schedule::Schedule;
use super::smoother::{Cov, Smoother, State, Stored, BIAS};
use crate::engine::math::{symmetric, wrap_pi};
use nalgebra::{Matrix2, Matrix2x6, Matrix6, Matrix6x2, Vector2};

/// The state's indices: east, north, step-length scale, heading correction, and the fixes'
/// correlated error east and north.
const E: usize = 0;
const N: usize = 1;
const K: usize = 2;
const B: usize = BIAS;
const FE: usize = 4;
const FN: usize = 5;

/// A fix waiting for the next step, in the local frame.
#[derive(Debug, Clone, Copy)]
struct PendingFix {
    t: f64,
    en: Vector2<f64>,
    /// Per-axis σ of the fix's whole error, from its reported accuracy, m.
    sigma: f64,
    /// The walker stands: the fix says nothing of the step length or the heading.
    standing: bool,
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
    /// The share of the fixes' error that is new at every fix, as measured on the walk
    /// (`Fusion::measure_white_share`; the configured floor until measured).
    pub white_share: f64,
}

/// The running filter.
#[derive(Debug, Clone)]
pub struct Fusion {
    cfg: FusionConfig,
    declination_rad: f64,
    x: State,
    p: Cov,
    // The time the state refers to (the fixes' correlated error decays with time).
    t_state: f64,
    // Per-axis σ of the fixes' whole error, from the latest fix's accuracy, m.
    fix_sigma: f64,
    started: bool,
    pending: Option<PendingFix>,
    // Innovations and variances of the fixes refused in a row by the gate.
    gated: Vec<(Vector2<f64>, f64)>,
    // Innovations and variances of the fixes held for a consensus.
    held: Vec<(Vector2<f64>, f64)>,
    last_step: Option<(f64, Vector2<f64>)>,
    velocity: Vector2<f64>,
    // The time of the first step of the current bout.
    walking_since: Option<f64>,
    // The PDR alone (declination applied, no correction) summed over the steps, east and north.
    dead_reckoned: Vector2<f64>,
    anchor: Option<Anchor>,
    schedule: Schedule,
    steps: Vec<FusedStep>,
    smoother: Smoother,
    counts: FixCounts,
    // Whether each of the last fixes offered to the gate was taken.
    recent: std::collections::VecDeque<bool>,
    // The last fix while walking (time, position, PDR alone then), the recent pairs' |δ|², 4σ²
    // and ρ, and the white share they imply (see `measure_white_share`).
    last_walking_fix: Option<(f64, Vector2<f64>, Vector2<f64>)>,
    pairs: std::collections::VecDeque<(f64, f64, f64)>,
    white_share: f64,
    // The floor `fix_error_from` set on the correlated error's variance at this step's update,
    // so that what the smoother stores as the prior is the prior the update used.
    prior_floor: Option<f64>,
}

mod learn;
use learn::Anchor;

/// How many recent fixes [`Fusion::verdict`] looks at.
pub const RECENT_FIXES: usize = 10;

impl Fusion {
    /// A filter with a validated configuration and the declination at the origin, radians.
    pub fn new(cfg: FusionConfig, declination_rad: f64) -> Self {
        Fusion {
            cfg,
            declination_rad,
            x: State::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0),
            p: Cov::zeros(),
            t_state: 0.0,
            fix_sigma: 0.0,
            started: false,
            pending: None,
            gated: Vec::new(),
            held: Vec::new(),
            last_step: None,
            velocity: Vector2::zeros(),
            walking_since: None,
            dead_reckoned: Vector2::zeros(),
            anchor: None,
            schedule: Schedule::new(&cfg),
            steps: Vec::new(),
            smoother: Smoother::default(),
            counts: FixCounts::default(),
            recent: std::collections::VecDeque::with_capacity(RECENT_FIXES),
            last_walking_fix: None,
            pairs: std::collections::VecDeque::new(),
            white_share: cfg.fix_white_share,
            prior_floor: None,
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
    /// Energy saving's duty cycle starts once the heading correction is known and the scale
    /// is known too, or can only come from baselines (fixes whose errors persist: waiting for
    /// it would keep the receiver on for the whole of most walks).
    fn schedule(&mut self, t: f64) {
        let ready = self.calibrated() || (self.bias_known() && self.baselines_only());
        self.schedule.push(t, ready);
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
        let last_step_t = self.steps.last().map(|s| s.t).filter(|_| self.started);
        let standing = last_step_t.filter(|&ts| still && t - ts >= self.cfg.standing_after_s);
        let fix = PendingFix {
            t,
            en: Vector2::new(east, north),
            sigma: accuracy_m / ACCURACY_PER_SIGMA,
            standing: standing.is_some(),
        };
        if let Some(t_step) = standing {
            // The walker has not moved since the last step: the fix updates that step's
            // estimate (and what the smoother stored of it) now, as if it had come then. Only
            // the fixes' own error has moved on meanwhile.
            self.velocity = Vector2::zeros();
            self.walking_since = None;
            let (x, p, _) = self.predict(t, 0.0, None);
            self.x = x;
            self.p = p;
            self.t_state = self.t_state.max(t);
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
        if self.walking_since.is_none() {
            self.walking_since = Some(t);
        }
        if !self.started {
            let p = self.pending.take()?;
            if t - p.t > self.cfg.max_fix_age_s {
                self.counts.stale += 1;
                return None;
            }
            self.start(t, &p);
            self.counts.used += 1;
            self.last_step = Some((t, p.en));
            let rec = self.record(t, None, Some(FixOutcome::Started));
            self.remember(FixOutcome::Started);
            self.smoother.push(Stored {
                x_pred: self.x,
                p_pred: self.p,
                f: Cov::identity(),
                x: self.x,
                p: self.p,
            });
            return Some(rec);
        }
        if let Some(theta) = heading_rad.filter(|_| length_m > 0.0) {
            let (s, c) = libm::sincos(theta + self.declination_rad);
            self.dead_reckoned += Vector2::new(s, c) * length_m;
        }
        let (x_pred, mut p_pred, f) = self.predict(t, length_m, heading_rad);
        self.x = x_pred;
        self.p = p_pred;
        self.t_state = self.t_state.max(t);
        let mut innovation = None;
        let mut outcome = None;
        if let Some(fix) = self.pending.take() {
            let (o, nu) = self.update(t, fix);
            outcome = Some(o);
            innovation = nu;
        }
        if let Some(b2) = self.prior_floor.take() {
            for i in [FE, FN] {
                p_pred[(i, i)] = p_pred[(i, i)].max(b2);
            }
        }
        let en = Vector2::new(self.x[E], self.x[N]);
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

    /// The filter's first state, at the first usable fix: there, with the prior scale and
    /// heading correction. One fix may be an outlier: the position starts wide, so that the
    /// next fixes are taken by consensus (see `consensus_sd_m`).
    fn start(&mut self, t: f64, p: &PendingFix) {
        self.fix_sigma = p.sigma;
        let s2 = sq(p.sigma).max(4.0 * sq(self.cfg.consensus_sd_m));
        let b2 = self.correlated_var();
        self.x = State::new(p.en.x, p.en.y, 1.0, 0.0, 0.0, 0.0);
        self.p = Cov::from_diagonal(&State::new(
            s2,
            s2,
            sq(self.cfg.scale0_sd),
            sq(self.cfg.bias0_sd_deg.to_radians()),
            b2,
            b2,
        ));
        self.t_state = t;
        self.started = true;
    }

    /// Marks the end of a bout (a stop or a gap): the walking velocity used to carry fixes to
    /// the next step is forgotten.
    pub fn end_bout(&mut self) {
        self.velocity = Vector2::zeros();
        self.last_step = None;
        self.walking_since = None;
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
            east_m: self.x[E],
            north_m: self.x[N],
            cov: [self.p[(E, E)], self.p[(E, N)], self.p[(N, N)]],
            scale: self.x[K],
            bias_rad: self.x[B],
            scale_bias_sd: [self.p[(K, K)].sqrt(), self.p[(B, B)].sqrt()],
            innovation,
            fix,
        }
    }

    /// Variance per axis of the fixes' correlated error ([`FusionConfig::fix_error_tau_s`],
    /// [`FusionConfig::fix_white_share`]) at the latest fix's accuracy, m².
    fn correlated_var(&self) -> f64 {
        if self.cfg.fix_error_tau_s > 0.0 {
            (1.0 - self.white_share) * sq(self.fix_sigma)
        } else {
            0.0
        }
    }

    /// The state at time `t` after a step of PDR length `length` and heading `heading` (none:
    /// time alone passes): the prediction, its covariance and the transition's Jacobian.
    /// - The step: E ← E + k L sin φ, N ← N + k L cos φ, φ = θ + D + β.
    /// - The fixes' correlated error decays as a first-order Gauss–Markov process,
    ///   b ← e^(−Δt/τ) b, its variance restored by the process noise σ_b²(1 − e^(−2Δt/τ)).
    /// - Without evidence the scale and the heading correction return to their priors (1, 0)
    ///   as first-order Gauss–Markov processes with time constant
    ///   [`FusionConfig::correction_tau_s`] and the priors' spread.
    fn predict(&self, t: f64, length: f64, heading: Option<f64>) -> (State, Cov, Cov) {
        let (k, beta) = (self.x[K], self.x[B]);
        let mut x = self.x;
        let mut f = Cov::identity();
        let mut q = Cov::zeros();
        if let Some(theta) = heading.filter(|_| length > 0.0) {
            let phi = theta + self.declination_rad + beta;
            let (s, c) = libm::sincos(phi);
            x[E] += k * length * s;
            x[N] += k * length * c;
            f[(E, K)] = length * s;
            f[(E, B)] = k * length * c;
            f[(N, K)] = length * c;
            f[(N, B)] = -k * length * s;
            // Displacement noise from the step's own length and heading errors.
            let sl = self.cfg.step_length_sd_rel * length;
            let sh = self.cfg.heading_sd_deg.to_radians();
            let g = Matrix2::new(k * s, k * length * c, k * c, -k * length * s);
            let qd = g * Matrix2::from_diagonal(&Vector2::new(sl * sl, sh * sh)) * g.transpose();
            q.fixed_view_mut::<2, 2>(E, E).copy_from(&qd);
            q[(K, K)] = sq(self.cfg.scale_rw);
            q[(B, B)] = sq(self.cfg.bias_rw_deg.to_radians());
        }
        let dt = (t - self.t_state).max(0.0);
        if self.cfg.correction_tau_s > 0.0 && dt > 0.0 {
            let phi = libm::exp(-dt / self.cfg.correction_tau_s);
            x[K] = 1.0 + phi * (x[K] - 1.0);
            x[B] *= phi;
            f[(K, K)] = phi;
            f[(B, B)] = phi;
            q[(K, K)] += sq(self.cfg.scale0_sd) * (1.0 - phi * phi);
            q[(B, B)] += sq(self.cfg.bias0_sd_deg.to_radians()) * (1.0 - phi * phi);
        }
        let tau = self.cfg.fix_error_tau_s;
        let decay = if tau > 0.0 { libm::exp(-dt / tau) } else { 0.0 };
        let b2 = self.correlated_var();
        for i in [FE, FN] {
            f[(i, i)] = decay;
            x[i] *= decay;
            q[(i, i)] = b2 * (1.0 - decay * decay);
        }
        let p = symmetric(f * self.p * f.transpose() + q);
        x[B] = wrap_pi(x[B]);
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
        self.fix_error_from(fix.sigma);
        let learn = self.teaches(t, &fix);
        if learn {
            self.measure_white_share(fix.t, fix.en, fix.sigma);
        }
        // Carry the fix to the step time along the walking velocity, and by the receiver's
        // latency.
        let carry = age + self.cfg.fix_latency_s;
        let z = fix.en + self.velocity * carry;
        let ext = self.cfg.velocity_sd_mps * carry;
        let r = sq(fix.sigma) - self.correlated_var() + ext * ext;
        let nu = z - self.predicted_fix();
        let hph = self.hph();
        let prior_sd = (0.5 * (self.p[(E, E)] + self.p[(N, N)])).sqrt();
        if prior_sd > self.cfg.consensus_sd_m {
            return self.consensus(nu, r, learn);
        }
        let Some(s_inv) = (hph + Matrix2::identity() * r).try_inverse() else {
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
            // Forget the position's correlations (its error is not what P said) and the fixes'
            // correlated error.
            let b2 = self.correlated_var();
            for i in [E, N, FE, FN] {
                for j in 0..6 {
                    self.p[(i, j)] = 0.0;
                    self.p[(j, i)] = 0.0;
                }
            }
            for i in [E, N] {
                self.p[(i, i)] = sq(self.cfg.consensus_sd_m) * 4.0;
            }
            for i in [FE, FN] {
                self.p[(i, i)] = b2;
                self.x[i] = 0.0;
            }
            let (_, nu_used) = self.consensus_update(learn);
            return (FixOutcome::Reset, nu_used.or(Some([nu.x, nu.y])));
        }
        self.gated.clear();
        self.held.clear();
        self.apply(nu, r, learn);
        self.counts.used += 1;
        if learn {
            self.baseline(z, fix.sigma);
        }
        (FixOutcome::Used, Some([nu.x, nu.y]))
    }

    /// The fixes' error follows the receiver's reported accuracy: when it reports a worse one
    /// than the correlated error's variance now allows, that variance grows to it at once (a
    /// courtyard's multipath does not wait for the Gauss–Markov process to build up).
    fn fix_error_from(&mut self, sigma: f64) {
        self.fix_sigma = sigma;
        let b2 = self.correlated_var();
        self.prior_floor = Some(b2);
        for i in [FE, FN] {
            if self.p[(i, i)] < b2 {
                self.p[(i, i)] = b2;
            }
        }
    }

    /// Where the filter expects the next fix: the position plus the fixes' correlated error.
    fn predicted_fix(&self) -> Vector2<f64> {
        Vector2::new(self.x[E] + self.x[FE], self.x[N] + self.x[FN])
    }

    /// The measurement matrix H: a fix sees the position plus its correlated error.
    fn h() -> Matrix2x6<f64> {
        let mut h = Matrix2x6::zeros();
        h[(0, E)] = 1.0;
        h[(1, N)] = 1.0;
        h[(0, FE)] = 1.0;
        h[(1, FN)] = 1.0;
        h
    }

    /// H P Hᵀ: the covariance of the predicted fix.
    fn hph(&self) -> Matrix2<f64> {
        let h = Self::h();
        h * self.p * h.transpose()
    }

    /// A fix while the prior is too wide for the Mahalanobis gate to tell an outlier (at the
    /// start, after an outage, at the start of an energy-saving window): it is held, and the
    /// filter is updated once [`FusionConfig::consensus_n`] held fixes agree with each other.
    fn consensus(
        &mut self,
        nu: Vector2<f64>,
        r: f64,
        learn: bool,
    ) -> (FixOutcome, Option<[f64; 2]>) {
        self.held.push((nu, r));
        let (outcome, _) = self.consensus_update(learn);
        (outcome, Some([nu.x, nu.y]))
    }

    /// Looks for the largest group of held fixes that agree pairwise-with-one-of-them (each
    /// innovation was taken at its own step; between those steps the prediction moved with the
    /// walker, so agreeing fixes see one offset). Two innovations agree when their difference
    /// is within the gate for their summed variances (the fixes' whole error, correlated part
    /// included). With [`FusionConfig::consensus_n`] in the group, one update with their mean
    /// innovation; otherwise the fixes wait (at most twice that many, oldest dropped). Returns
    /// the outcome and the innovation used.
    fn consensus_update(&mut self, learn: bool) -> (FixOutcome, Option<[f64; 2]>) {
        let need = self.cfg.consensus_n as usize;
        let b2 = self.correlated_var();
        let held = &self.held;
        let best = largest_agreeing_group(held.len(), |i, j| {
            let (a, b) = (held[i], held[j]);
            (a.0 - b.0).norm_squared() / (a.1 + b.1 + 2.0 * b2) <= self.cfg.gate_chi2
        });
        if best.len() < need {
            if self.held.len() >= 2 * need {
                self.held.remove(0);
                self.counts.gated += 1;
            }
            return (FixOutcome::Held, None);
        }
        let held = std::mem::take(&mut self.held);
        self.counts.gated += (held.len() - best.len()) as u64;
        // One update with the mean innovation; its white part is that of a mean of
        // independent errors, the correlated part is in the state.
        let n = best.len() as f64;
        let nu = best.iter().fold(Vector2::zeros(), |a, &i| a + held[i].0) / n;
        let r = best.iter().map(|&i| held[i].1).sum::<f64>() / (n * n);
        self.apply(nu, r, learn);
        self.counts.used += best.len() as u64;
        self.gated.clear();
        (FixOutcome::Used, Some([nu.x, nu.y]))
    }

    /// The Kalman update with innovation `nu` of the fix (H = [I₂ 0 0 I₂]) and white noise
    /// variance `r` per axis, in Joseph form (valid for any gain). When the fix may not teach
    /// the corrections (`learn` false: see [`Fusion::teaches`]), the gain's scale and
    /// heading-correction rows are zero. The corrections are then held within their physical
    /// bounds ([`FusionConfig::scale_bounds`], [`FusionConfig::bias_bound_deg`]).
    fn apply(&mut self, nu: Vector2<f64>, r: f64, learn: bool) {
        let h = Self::h();
        let rm = Matrix2::identity() * r;
        let s = h * self.p * h.transpose() + rm;
        let Some(s_inv) = s.try_inverse() else {
            return;
        };
        let mut k: Matrix6x2<f64> = self.p * h.transpose() * s_inv;
        if !learn || self.baselines_only() {
            k.row_mut(K).fill(0.0);
        }
        if !learn {
            k.row_mut(B).fill(0.0);
        }
        self.x += k * nu;
        self.bound();
        // P = (I − KH) P (I − KH)ᵀ + K R Kᵀ.
        let ikh = Matrix6::identity() - k * h;
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
            white_share: self.white_share,
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
        self.bias_known() && self.p[(K, K)].sqrt() <= self.cfg.calibrated_scale_sd
    }

    /// The heading correction is known well enough.
    fn bias_known(&self) -> bool {
        self.started && self.p[(B, B)].sqrt() <= self.cfg.calibrated_bias_sd_deg.to_radians()
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
        let consider: &[usize] = if self.baselines_only() { &[K] } else { &[] };
        self.smoother.smooth(&self.steps, consider)
    }

    /// The current state covariance (diagnostics and tests).
    pub fn covariance(&self) -> Cov {
        self.p
    }
}

pub(super) fn sq(x: f64) -> f64 {
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

    #[test]
    fn fixes_while_standing_teach_no_correction() {
        // A walk north with good fixes, then two minutes standing while the fixes wander 30 m
        // east: the position may follow a little, the scale and heading correction not at all.
        let mut f = Fusion::new(FusionConfig::default(), 0.0);
        let mut north = 0.0;
        for i in 0..300 {
            let t = i as f64 * 0.55;
            north += 0.7;
            if i % 2 == 0 {
                f.push_fix(&FixInput {
                    t,
                    east_m: 0.0,
                    north_m: north,
                    accuracy_m: 4.0,
                    still: false,
                });
            }
            f.push_step(&StepInput {
                t,
                length_m: 0.7,
                heading_rad: Some(0.0),
            });
        }
        let before = *f.steps().last().unwrap();
        for i in 0..120 {
            let t = 300.0 * 0.55 + 3.0 + i as f64;
            let out = f.push_fix(&FixInput {
                t,
                east_m: 0.25 * i as f64,
                north_m: north,
                accuracy_m: 4.0,
                still: true,
            });
            assert!(out.is_some(), "a fix while standing is used at once");
        }
        let after = *f.steps().last().unwrap();
        assert_eq!(after.scale, before.scale);
        assert_eq!(after.bias_rad, before.bias_rad);
    }
}
