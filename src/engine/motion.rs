//! Motion detection by the standard deviation of vertical acceleration (Basso 2016 §II.B).
//! May import: the rest of `engine`.
//!
//! σ_z(t) = sqrt( (1/n₂) Σ_{t_k ∈ Φ₂(t)} (a_z(t_k) − μ_z(t))² ), Φ₂(t) = { t_k : t_k ≥ t − 2 },
//! kept up to date incrementally with a time-regulated buffer: the sums Σa and Σa² are updated with
//! the samples pushed in and pulled out. Thresholds: 1.5 m/s² between still and moving, 5 m/s²
//! between walking and running. Basso 2021 §2.2.2 uses the variance over 4 s with a threshold of
//! 1.5 m²/s⁴ instead; we follow the 2016 paper.

use super::math::OnePole;
use super::types::{positive, ConfigError};

/// Motion state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// σ below the still threshold: step detection disabled.
    Still,
    /// σ between the two thresholds.
    Walking,
    /// σ above the running threshold.
    Running,
}

impl Motion {
    /// Lower-case name, as written in track files.
    pub fn as_str(self) -> &'static str {
        match self {
            Motion::Still => "still",
            Motion::Walking => "walking",
            Motion::Running => "running",
        }
    }

    /// Whether steps are detected in this state.
    pub fn is_moving(self) -> bool {
        self != Motion::Still
    }
}

/// Settings of the motion detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct MotionConfig {
    /// Window length, seconds (Basso 2016: 2 s).
    pub window_s: f64,
    /// σ threshold between still and moving, m/s² (Basso 2016: 1.5).
    pub still_max: f64,
    /// σ threshold between walking and running, m/s² (Basso 2016: 5).
    pub walk_max: f64,
    /// Data span the window must cover before σ is trusted, seconds. Before that (start of a log,
    /// or after a gap) the previous state is kept. Our choice: half a second, about one step.
    pub min_span_s: f64,
    /// Departure from the paper: below [`MotionConfig::still_max`] the person is still moving
    /// when the vertical acceleration is periodic in the step band (see [`Periodicity`]) with at
    /// least this autocorrelation at the step period, and σ reaches
    /// [`MotionConfig::periodic_sigma_min`]. Basso's 1.5 m/s² is for a phone in a trouser
    /// pocket; a phone carried gently in the hand gives σ ≈ 0.9–1.3 m/s² while walking (Oxford
    /// Pixel_Jamie_Carpet_InHand_1/2), below it.
    pub periodic_score_min: f64,
    /// Smallest σ_z for the periodicity rule, m/s²: well above sensor noise (≈0.1 m/s² still).
    pub periodic_sigma_min: f64,
    /// Step frequency at and above which a periodic gait is running, Hz. Departure from the
    /// paper, which separates walking from running by σ_z ≥ 5 m/s²: σ depends on where the phone
    /// is (front pocket 4.5–5.5 m/s² at a 1.9 Hz walk on Oxford), cadence does not. 2.5 Hz lies
    /// between fast walking and slow running, inside the overlap of the two PLL bands
    /// (2.3–2.7 Hz). Without a periodicity estimate the σ rule decides.
    pub run_min_hz: f64,
    /// Smallest σ_z of a running gait, m/s². A rhythm at a running cadence with less is not
    /// running (Oxford Pixel_Jamie_Hard_Purse_2: a purse set down swings at 3.2–4 Hz with
    /// σ_z ≈ 0.6–1.2 m/s²); running shakes the body far more than walking, whose σ_z starts at
    /// about 1 m/s² for a phone held gently in the hand. 2 m/s²: twice that.
    pub run_sigma_min: f64,
    /// Highest step frequency of a walk, Hz (the top of the walking band, Basso 2016 §II.D
    /// 1.5–2.2 Hz with a margin). A faster rhythm without the σ_z of running is not a gait.
    pub walk_max_hz: f64,
    /// How long a moving state survives a lapse of periodicity while σ_z stays above
    /// [`MotionConfig::still_max`], s (walk/run then by Basso's σ rule). A gait change blurs the
    /// 3 s autocorrelation for about a second (simulated walk → run: 1 s without a verdict);
    /// 2 s leaves a margin. Without the lapse the state drops to "still" for a second at every
    /// walk ↔ run change. The Oxford figures are in `docs/methods/basso2016.md`.
    pub periodic_lapse_s: f64,
}

impl Default for MotionConfig {
    fn default() -> Self {
        MotionConfig {
            window_s: 2.0,
            still_max: 1.5,
            walk_max: 5.0,
            min_span_s: 0.5,
            periodic_score_min: 0.5,
            periodic_sigma_min: 0.5,
            run_min_hz: 2.5,
            run_sigma_min: 2.0,
            walk_max_hz: 2.7,
            periodic_lapse_s: 2.0,
        }
    }
}

impl MotionConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("motion.window_s", self.window_s)?;
        positive("motion.still_max", self.still_max)?;
        positive("motion.min_span_s", self.min_span_s)?;
        positive("motion.periodic_score_min", self.periodic_score_min)?;
        positive("motion.periodic_sigma_min", self.periodic_sigma_min)?;
        positive("motion.run_min_hz", self.run_min_hz)?;
        positive("motion.run_sigma_min", self.run_sigma_min)?;
        if !(self.walk_max_hz >= self.run_min_hz) {
            return Err(ConfigError::new(
                "motion.walk_max_hz",
                "must be at least motion.run_min_hz",
            ));
        }
        positive("motion.periodic_lapse_s", self.periodic_lapse_s)?;
        if !(self.walk_max > self.still_max) {
            return Err(ConfigError::new(
                "motion.walk_max",
                "must exceed motion.still_max",
            ));
        }
        if self.min_span_s > self.window_s {
            return Err(ConfigError::new(
                "motion.min_span_s",
                "must not exceed motion.window_s",
            ));
        }
        Ok(())
    }
}

/// The detector's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MotionDiagnostics {
    /// The state.
    pub state: Motion,
    /// σ_z over the window, m/s².
    pub sigma_z: f64,
    /// μ_z over the window, m/s².
    pub mean_z: f64,
    /// The cadence of the periodic gait in the window, Hz ([`MotionDetector::cadence_hz`]).
    pub cadence_hz: Option<f64>,
}

/// Samples that have left the window are dropped from the front of its buffer once there are
/// this many (and at least as many as are still in it): a move of the window, rarely.
const DROP_AT: usize = 1024;

/// The running detector.
#[derive(Debug, Clone)]
pub struct MotionDetector {
    cfg: MotionConfig,
    // The window's samples (t, a) are `buf[first..]`: a sample leaves by a step of `first`, and
    // those gone are dropped now and then.
    buf: Vec<(f64, f64)>,
    first: usize,
    sum: f64,
    sum_sq: f64,
    pops: u32,
    state: Motion,
    sigma: f64,
    mean: f64,
    last_t: Option<f64>,
    last_periodic_t: Option<f64>,
    periodicity: Periodicity,
}

impl MotionDetector {
    /// A detector in the still state.
    pub fn new(cfg: MotionConfig) -> Self {
        MotionDetector {
            cfg,
            buf: Vec::new(),
            first: 0,
            sum: 0.0,
            sum_sq: 0.0,
            pops: 0,
            state: Motion::Still,
            sigma: 0.0,
            mean: 0.0,
            last_t: None,
            last_periodic_t: None,
            periodicity: Periodicity::new(),
        }
    }

    /// Adds a vertical-acceleration sample (m/s², gravity removed) and returns the state.
    pub fn push(&mut self, t: f64, a: f64) -> Motion {
        self.buf.push((t, a));
        self.sum += a;
        self.sum_sq += a * a;
        while let Some(&(t0, a0)) = self.buf.get(self.first) {
            if t0 >= t - self.cfg.window_s {
                break;
            }
            self.first += 1;
            self.sum -= a0;
            self.sum_sq -= a0 * a0;
            self.pops += 1;
        }
        if self.first >= DROP_AT && 2 * self.first >= self.buf.len() {
            self.buf.drain(..self.first);
            self.first = 0;
        }
        let window = &self.buf[self.first..];
        // Re-sum now and then so rounding in the running sums cannot accumulate.
        if self.pops >= 4096 {
            self.pops = 0;
            self.sum = window.iter().map(|p| p.1).sum();
            self.sum_sq = window.iter().map(|p| p.1 * p.1).sum();
        }
        let n = window.len() as f64;
        self.mean = self.sum / n;
        self.sigma = (self.sum_sq / n - self.mean * self.mean).max(0.0).sqrt();
        let span = t - window.first().map_or(t, |p| p.0);
        let dt = self.last_t.map_or(0.0, |l| t - l);
        self.last_t = Some(t);
        self.periodicity.push(t, dt, a);
        if span >= self.cfg.min_span_s {
            // A rhythm faster than walking without the σ_z of running is not a gait (see
            // [`MotionConfig::run_sigma_min`]).
            let cadence = self.cadence_hz().filter(|&f| {
                self.sigma >= self.cfg.periodic_sigma_min
                    && (f <= self.cfg.walk_max_hz || self.sigma >= self.cfg.run_sigma_min)
            });
            if cadence.is_some() {
                self.last_periodic_t = Some(t);
            }
            // A change of gait (walk ↔ run, a turn) blurs the periodicity for a second or so;
            // Basso's σ rule carries a moving state across such a lapse.
            let lapse = self.state.is_moving()
                && self.sigma >= self.cfg.still_max
                && self
                    .last_periodic_t
                    .is_some_and(|l| t - l <= self.cfg.periodic_lapse_s);
            self.state = match cadence {
                Some(f) if f >= self.cfg.run_min_hz && self.sigma >= self.cfg.run_sigma_min => {
                    Motion::Running
                }
                Some(_) => Motion::Walking,
                None if !lapse => Motion::Still,
                // Across a lapse Basso's σ_z rule may end a run, but never starts one: a
                // swinging purse gives σ_z ≈ 6 m/s² while walking (Oxford
                // Pixel_Jamie_Hard_Purse_2).
                None if self.state == Motion::Running && self.sigma >= self.cfg.walk_max => {
                    Motion::Running
                }
                None => Motion::Walking,
            };
        }
        self.state
    }

    /// Step frequency of the periodic gait in the window, Hz, when its periodicity score reaches
    /// [`MotionConfig::periodic_score_min`].
    pub fn cadence_hz(&self) -> Option<f64> {
        let p = &self.periodicity;
        (p.frequency() > 0.0 && p.score() >= self.cfg.periodic_score_min).then_some(p.frequency())
    }

    /// The periodicity estimator (diagnostics).
    pub fn periodicity(&self) -> &Periodicity {
        &self.periodicity
    }

    /// Drops the window (after a gap). The state is kept until the window refills.
    pub fn clear_window(&mut self) {
        self.buf.clear();
        self.first = 0;
        self.sum = 0.0;
        self.sum_sq = 0.0;
        self.last_t = None;
        self.last_periodic_t = None;
        self.periodicity.clear();
    }

    /// σ_z over the window, m/s².
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// μ_z over the window, m/s².
    pub fn mean(&self) -> f64 {
        self.mean
    }

    /// Current state.
    pub fn state(&self) -> Motion {
        self.state
    }

    /// The current values.
    pub fn diagnostics(&self) -> MotionDiagnostics {
        MotionDiagnostics {
            state: self.state,
            sigma_z: self.sigma,
            mean_z: self.mean,
            cadence_hz: self.cadence_hz(),
        }
    }
}

/// Sampling interval of the periodicity estimator's decimated signal, s (20 Hz: Nyquist 10 Hz,
/// twice the highest step frequency of interest, 4.6 Hz; coarse lags are refined by parabolic
/// interpolation). The rate is fixed whatever the input rate (15–400 Hz), so the cost per input
/// sample falls as the input rate rises.
const AC_DT: f64 = 0.05;
/// Autocorrelation window, decimated samples (3 s: five to six steps at 1.8 Hz).
const AC_N: usize = 60;
/// Largest lag, decimated samples (1.8 s: a stride at 1.1 Hz steps).
const AC_L: usize = 36;
/// The autocorrelation is examined every this many resampled points (0.2 s), which keeps the
/// estimator's cost at a few ns per input sample at 100 Hz.
const AC_EVAL_EVERY: usize = 4;
/// Smallest lag examined, decimated samples (0.2 s: 5 Hz steps).
const AC_LAG_MIN: usize = 4;
/// Largest lag that can be a step period, s (1.2 Hz, the bottom of the walking band).
const AC_STEP_MAX_S: f64 = 1.0 / 1.15;

/// Periodicity of the vertical acceleration in the step band, by autocorrelation.
///
/// The input is band-passed (one-pole high-pass at 0.5 Hz, two one-pole low-passes at 5 Hz),
/// resampled at fixed times every `AC_DT` by linear interpolation (so dt comes from the
/// timestamps and any input rate works), and the lagged products Σ x\[n\]·x\[n−τ\] over the last
/// `AC_N` resampled points are kept as running sums for every lag τ ≤ `AC_L` (two
/// multiply-adds per lag per resampled point). R(τ) = S(τ)/S(0).
///
/// The step period is the smallest lag whose local maximum of R reaches
/// [`PERIODIC_PEAK_SHARE`] of the largest local maximum up to `AC_L` (which may be the stride,
/// two steps, for a phone on the thigh), and which is no longer than `AC_STEP_MAX_S`. Its R is
/// the periodicity score: near 1 for a steady gait, near 0 for noise or slow handling.
#[derive(Debug, Clone)]
pub struct Periodicity {
    hp: OnePole,
    lp: [OnePole; 2],
    // The last interval, s, and the high- and low-pass gains of a step of it.
    gains: (f64, f64, f64),
    prev: Option<(f64, f64)>,
    next_t: f64,
    // History of the resampled signal, newest first, as a mirrored ring: every point is written
    // at `pos` and `pos + M`, so `hist[pos..pos + M]` is the whole window without copying.
    hist: [f64; 2 * (AC_N + AC_L + 1)],
    pos: usize,
    sums: [f64; AC_L + 1],
    count: usize,
    since_resum: u32,
    freq: f64,
    score: f64,
    half: f64,
    ms: Option<f64>,
}

/// Smoothing factor of the gain control's mean square per resampled point: time constant
/// 0.75 s (about one and a half steps at 1.8 Hz).
const AGC_ALPHA: f64 = AC_DT / (0.75 + AC_DT);

/// R at half the lag above which the lag is taken for a stride (two steps) rather than a step.
pub const STRIDE_HALF_MIN: f64 = 0.0;

/// Share of the largest autocorrelation peak that the step-period peak must reach. A phone on
/// the thigh correlates better over a stride (two steps) than over a step; the step peak is the
/// first one that is still strong.
pub const PERIODIC_PEAK_SHARE: f64 = 0.6;

impl Default for Periodicity {
    fn default() -> Self {
        Self::new()
    }
}

impl Periodicity {
    /// An empty estimator.
    pub fn new() -> Self {
        Periodicity {
            hp: OnePole::with_cutoff_hz(0.5),
            lp: [OnePole::with_cutoff_hz(5.0); 2],
            gains: (f64::NAN, 0.0, 0.0),
            prev: None,
            next_t: 0.0,
            hist: [0.0; 2 * (AC_N + AC_L + 1)],
            pos: 0,
            sums: [0.0; AC_L + 1],
            count: 0,
            since_resum: 0,
            freq: 0.0,
            score: 0.0,
            half: 0.0,
            ms: None,
        }
    }

    /// Forgets everything (after a gap).
    pub fn clear(&mut self) {
        *self = Self::new();
    }

    /// Adds a vertical-acceleration sample taken `dt` s after the previous one.
    pub fn push(&mut self, t: f64, dt: f64, a: f64) {
        // Computed again only when the interval changes.
        if dt != self.gains.0 {
            self.gains = (dt, self.hp.gain(dt), self.lp[0].gain(dt));
        }
        let slow = self.hp.update_with_gain(a, self.gains.1);
        // The two low-pass stages share one τ, so one gain.
        let k = self.gains.2;
        let y = self.lp[0].update_with_gain(a - slow, k);
        let y = self.lp[1].update_with_gain(y, k);
        let Some((t0, y0)) = self.prev else {
            self.prev = Some((t, y));
            self.next_t = t + AC_DT;
            return;
        };
        while self.next_t <= t {
            let x = if t > t0 {
                y0 + (y - y0) * (self.next_t - t0) / (t - t0)
            } else {
                y
            };
            self.add(x);
            self.next_t += AC_DT;
        }
        self.prev = Some((t, y));
    }

    fn add(&mut self, x: f64) {
        // Automatic gain control: each point is divided by the RMS of the last second or so,
        // so that every part of the window weighs alike. Without it a loud half-second (the end
        // of a run, σ ≈ 7 m/s²) outweighs seconds of walking (σ ≈ 2 m/s²) and the estimate
        // lags gait changes (the simulated run → walk change took over 2.5 s).
        let ms = match self.ms {
            None => x * x,
            Some(m) => m + AGC_ALPHA * (x * x - m),
        };
        self.ms = Some(ms);
        let x = x / libm::sqrt(ms + 1e-4);
        const M: usize = AC_N + AC_L + 1;
        self.pos = if self.pos == 0 { M - 1 } else { self.pos - 1 };
        self.hist[self.pos] = x;
        self.hist[self.pos + M] = x;
        let h = &self.hist[self.pos..self.pos + M];
        let (new, old) = h.split_at(AC_N);
        for ((s, a), b) in self.sums.iter_mut().zip(&new[..=AC_L]).zip(&old[..=AC_L]) {
            *s += x * a - old[0] * b;
        }
        self.count += 1;
        self.since_resum += 1;
        if self.since_resum >= 2048 {
            // Re-sum now and then so rounding in the running sums cannot accumulate.
            self.since_resum = 0;
            for (tau, s) in self.sums.iter_mut().enumerate() {
                *s = (0..AC_N).map(|k| h[k] * h[k + tau]).sum();
            }
        }
        // Evaluated every [`AC_EVAL_EVERY`] points (0.2 s): the verdict is meant for a 3 s window.
        if self.count >= AC_N / 2 && self.count % AC_EVAL_EVERY == 0 {
            self.evaluate();
        }
    }

    fn evaluate(&mut self) {
        self.score = 0.0;
        self.freq = 0.0;
        let s0 = self.sums[0];
        if !(s0 > 0.0) {
            return;
        }
        let inv = 1.0 / s0;
        let mut rr = [0.0; AC_L + 1];
        for (r, s) in rr.iter_mut().zip(&self.sums) {
            *r = s * inv;
        }
        let r = |k: usize| rr[k];
        let is_peak = |k: usize| r(k) >= r(k - 1) && r(k) > r(k + 1);
        let mut best = f64::NEG_INFINITY;
        for k in AC_LAG_MIN..AC_L {
            if is_peak(k) {
                best = best.max(r(k));
            }
        }
        if !(best > 0.0) {
            return;
        }
        let Some(k) =
            (AC_LAG_MIN..AC_L).find(|&k| is_peak(k) && r(k) >= PERIODIC_PEAK_SHARE * best)
        else {
            return;
        };
        // Parabolic refinement of the lag.
        let refine = |k: usize| {
            let (a, b, c) = (r(k - 1), r(k), r(k + 1));
            let den = a - 2.0 * b + c;
            if den < 0.0 {
                k as f64 + (0.5 * (a - c) / den).clamp(-0.5, 0.5)
            } else {
                k as f64
            }
        };
        let mut lag = refine(k);
        // Step or stride? Half a step period apart the vertical acceleration is in anti-phase, so
        // R is strongly negative there; half a stride apart lies the other foot's step, so R is
        // not. (Linear interpolation of R at lag/2.)
        let at = |x: f64| {
            let (i, f) = (x.floor() as usize, x - x.floor());
            r(i) + f * (r(i + 1) - r(i))
        };
        let h = 0.5 * lag;
        self.half = at(h);
        let bump = self.half > 0.5 * (at(0.5 * h) + at(1.5 * h));
        let stride = lag * AC_DT > AC_STEP_MAX_S || (self.half > STRIDE_HALF_MIN && bump);
        if stride && h >= AC_LAG_MIN as f64 {
            lag = h;
        }
        if lag * AC_DT > AC_STEP_MAX_S {
            return;
        }
        self.freq = 1.0 / (lag * AC_DT);
        self.score = r(k);
    }

    /// Step frequency of the last evaluation, Hz (0 when nothing periodic was found).
    pub fn frequency(&self) -> f64 {
        self.freq
    }

    /// Normalised autocorrelation R(τ) for τ = 0, `AC_DT`, … (diagnostics).
    pub fn autocorrelation(&self) -> Vec<f64> {
        let s0 = self.sums[0];
        self.sums.iter().map(|s| s / s0).collect()
    }

    /// R at half the lag of the periodicity found (diagnostics).
    pub fn half_lag_r(&self) -> f64 {
        self.half
    }

    /// Autocorrelation at the step period (0 when nothing periodic was found).
    pub fn score(&self) -> f64 {
        self.score
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn sigma_matches_direct_computation() {
        let mut d = MotionDetector::new(MotionConfig::default());
        let mut all = Vec::new();
        for i in 0..1000 {
            let t = i as f64 * 0.013;
            let a = (t * 7.0).sin() * 3.0 + 0.5;
            d.push(t, a);
            all.push((t, a));
        }
        let t_end = all.last().unwrap().0;
        let w: Vec<f64> = all
            .iter()
            .filter(|p| p.0 >= t_end - 2.0)
            .map(|p| p.1)
            .collect();
        let m = w.iter().sum::<f64>() / w.len() as f64;
        let s = (w.iter().map(|a| (a - m) * (a - m)).sum::<f64>() / w.len() as f64).sqrt();
        assert!((d.sigma() - s).abs() < 1e-9 && (d.mean() - m).abs() < 1e-12);
    }
}
