//! Fuzzy step length (Ibarra 2015 thesis, §4.4.2, Figs. 4.8–4.9; the inference of §2.2.1,
//! eqs. 2.22–2.29 and Table 2.1): a multiple-input single-output Mamdani system.
//! May import: the rest of `engine`.
//!
//! # What the thesis prints
//! - Three inputs: *step frequency* (slow, regular, fast), *pedestrian activity* (walking,
//!   walking fast, jogging, running) and *pedestrian height* (short, medium, high).
//! - One output, *step length*, with eight Gaussian sets: small (SM), normal (NL), little large
//!   (LL), medium large (ML), large (LG), very large (VL), giant (GT), very giant (VG).
//! - 36 rules (3 × 4 × 3), of which one is printed: "IF (step-freq is slow) AND (activity is
//!   walk) AND (height is short) THEN (step-length is small)".
//! - "min, max-product and centroid": AND is the minimum (the firing strength w_i, eq. 2.22),
//!   the inference is the max-product composition (each rule's output set scaled by w_i,
//!   μ_C'(z) = max_i w_i·μ_Ci(z), Table 2.1 and Fig. 2.5), and the crisp output is the centroid
//!   z* = ∫ z μ_C'(z) dz / ∫ μ_C'(z) dz.
//!
//! # What it does not print, and what we chose
//! - **The membership functions** are drawn in Figs. 4.8–4.9 without values (and the figures are
//!   not in the text we have). Ours are below ([`freq_memberships`], [`variance_memberships`],
//!   [`OUTPUT_CENTRES_M`], [`OUTPUT_SIGMA_M`]).
//! - **The rules**: only the one above. Ours extend it monotonically: the consequent of
//!   (frequency i, activity j, third input k) is output set i + j + k (0-based), so that
//!   (slow, walk, low) is SM, as printed, and (fast, run, high) is VG; the 36 rules then use
//!   exactly the eight output sets.
//! - **Height → acceleration variance.** The engine does not know the walker's height; it
//!   takes the variance of the vertical acceleration over the step as the third input,
//!   with three sets low, medium, high in place of short, medium, high. Unlike height it depends
//!   on where the phone is carried (a hand-held phone sees σ ≈ 1 m/s², a trouser pocket 2–5):
//!   see the figures in `docs/methods/ibarra2015.md`.
//! - **Activity.** The thesis classifies it with a wavelet + multilayer-perceptron network whose
//!   trained weights are not published. We use the engine's own view instead, [`activity`]:
//!   cadence and σ decide walk, fast walk, jog or run, crisp (the network's output is a class).
//! - **Output centres**: the engine's population line (Basso 2016 §II.D, the defaults of
//!   [`super::step_length`]) at the simulated walker's variance (medium), so that before any
//!   calibration the two models agree on that walker; a calibration walk sets
//!   [`FuzzyConfig::scale`].
//!
//! The output universe is sampled every [`OUTPUT_STEP_M`] over 0–[`OUTPUT_MAX_M`] m; the
//! Gaussians are tabulated once, so a step costs no transcendental function.

use super::heading::NavSample;
use super::types::{positive, ConfigError};
use std::collections::VecDeque;

/// Centres of the eight output sets SM, NL, LL, ML, LG, VL, GT, VG, m. Ours (see the module
/// docs): NL, LL, ML are the population walking line at 1.5, 1.85 and 2.2 Hz (0.25·f + 0.17),
/// LG at 2.4 Hz, VL and GT the running line at 2.6 and 2.7 Hz (0.90·f − 1.50), VG at 3.1 Hz;
/// SM one walking step (0.1 m) below NL.
pub const OUTPUT_CENTRES_M: [f64; 8] = [0.45, 0.545, 0.6325, 0.72, 0.77, 0.84, 0.93, 1.29];

/// Width σ of the output Gaussians, m (ours: about half the spacing of the walking centres).
pub const OUTPUT_SIGMA_M: f64 = 0.05;

/// Resolution of the output universe, m.
pub const OUTPUT_STEP_M: f64 = 0.005;

/// Upper end of the output universe, m.
pub const OUTPUT_MAX_M: f64 = 2.0;

const N_OUT: usize = (OUTPUT_MAX_M / OUTPUT_STEP_M) as usize + 1;

/// The four activities of the thesis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activity {
    /// Walking.
    Walk,
    /// Walking fast.
    FastWalk,
    /// Jogging.
    Jog,
    /// Running.
    Run,
}

impl Activity {
    /// Its index in the rule base (0–3).
    pub fn index(self) -> usize {
        self as usize
    }
}

/// Cadence above which a walk is a fast walk, Hz: the top of Basso 2016's walking band
/// (1.5–2.2 Hz, [`super::step_length::StepLengthProfile`]).
pub const FAST_WALK_HZ: f64 = 2.2;
/// Cadence and σ of a running gait (the motion detector's defaults, `motion.run_min_hz` and
/// `motion.run_sigma_min`): below, any gait is a walk.
pub const JOG_HZ: f64 = 2.5;
/// σ_z of a running gait, m/s² (as `motion.run_sigma_min`).
pub const JOG_SIGMA: f64 = 2.0;
/// Cadence above which a jog is a run, Hz (ours: between the 2.7 Hz of the running band's
/// foot and the 3.1 Hz of a steady run).
pub const RUN_HZ: f64 = 2.9;

/// The activity class from cadence (Hz) and σ of the vertical acceleration (m/s²): the engine's
/// stand-in for the thesis's wavelet + neural-network classifier (§4.2–4.3), whose weights are
/// not published. Running (jog or run) as the motion detector decides it: cadence ≥ 2.5 Hz and
/// σ ≥ 2 m/s²; a jog below 2.9 Hz. A walk is fast above 2.2 Hz.
pub fn activity(cadence_hz: f64, sigma: f64) -> Activity {
    if cadence_hz >= JOG_HZ && sigma >= JOG_SIGMA {
        if cadence_hz >= RUN_HZ {
            Activity::Run
        } else {
            Activity::Jog
        }
    } else if cadence_hz > FAST_WALK_HZ {
        Activity::FastWalk
    } else {
        Activity::Walk
    }
}

/// A falling shoulder: 1 up to `a`, 0 from `b`, linear between.
fn down(x: f64, a: f64, b: f64) -> f64 {
    ((b - x) / (b - a)).clamp(0.0, 1.0)
}

/// A rising shoulder: 0 up to `a`, 1 from `b`.
fn up(x: f64, a: f64, b: f64) -> f64 {
    ((x - a) / (b - a)).clamp(0.0, 1.0)
}

/// A triangle with feet `a`, `c` and top `b`.
fn tri(x: f64, a: f64, b: f64, c: f64) -> f64 {
    up(x, a, b).min(down(x, b, c))
}

/// Memberships of the step frequency (Hz) in slow, regular and fast (ours: shoulders and a
/// triangle over Basso 2016's walking band, 1.5–1.85–2.2 Hz; they sum to 1).
pub fn freq_memberships(f: f64) -> [f64; 3] {
    [down(f, 1.5, 1.85), tri(f, 1.5, 1.85, 2.2), up(f, 1.85, 2.2)]
}

/// Memberships of the variance of the vertical acceleration over the step (m²/s⁴) in low,
/// medium and high (ours: medium peaks at 5 m²/s⁴, the simulated walker's at 1.8 Hz, σ = 2.3
/// m/s²; low is a hand-held phone's σ ≤ 1 m/s², high a run's σ ≥ 5 m/s²; they sum to 1).
pub fn variance_memberships(v: f64) -> [f64; 3] {
    [down(v, 1.0, 5.0), tri(v, 1.0, 5.0, 25.0), up(v, 5.0, 25.0)]
}

/// Settings of the fuzzy step length.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct FuzzyConfig {
    /// Output scale k: the crisp output times k. 1 until a calibration walk sets it
    /// ([`super::calibration::fuzzy_scale`]).
    pub scale: f64,
}

impl Default for FuzzyConfig {
    fn default() -> Self {
        FuzzyConfig { scale: 1.0 }
    }
}

impl FuzzyConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("step_length.scale", self.scale)
    }
}

/// One step's inference: the inputs as fuzzified and the output.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FuzzyStep {
    /// The activity used.
    pub activity: Activity,
    /// Variance of the vertical acceleration over the step, m²/s⁴.
    pub variance: f64,
    /// The centroid before the scale, m.
    pub centroid_m: f64,
    /// The step length (scale × centroid, clamped to 0.2–2.5 m), m.
    pub length_m: f64,
}

/// The fuzzy system: its settings and the tabulated output sets.
#[derive(Debug, Clone)]
pub struct FuzzyStepLength {
    cfg: FuzzyConfig,
    /// μ of each output set at each point of the universe.
    sets: Vec<[f64; 8]>,
}

impl FuzzyStepLength {
    /// A system with the given settings.
    pub fn new(cfg: FuzzyConfig) -> Self {
        let sets = (0..N_OUT)
            .map(|i| {
                let z = i as f64 * OUTPUT_STEP_M;
                OUTPUT_CENTRES_M.map(|c| {
                    let u = (z - c) / OUTPUT_SIGMA_M;
                    libm::exp(-0.5 * u * u)
                })
            })
            .collect();
        FuzzyStepLength { cfg, sets }
    }

    /// The settings.
    pub fn config(&self) -> &FuzzyConfig {
        &self.cfg
    }

    /// The firing strength of each output set: for each of the 36 rules w = min of its
    /// antecedents' memberships (eq. 2.22), the strongest rule per consequent set.
    pub fn strengths(f: f64, act: Activity, variance: f64) -> [f64; 8] {
        let mf = freq_memberships(if f.is_finite() { f } else { 1.85 });
        let mv = variance_memberships(if variance.is_finite() { variance } else { 0.0 });
        let mut w = [0.0; 8];
        for (i, a) in mf.iter().enumerate() {
            for (k, b) in mv.iter().enumerate() {
                let j = i + act.index() + k;
                w[j] = f64::max(w[j], a.min(*b));
            }
        }
        w
    }

    /// One step: frequency (Hz), σ of the vertical acceleration for the activity (m/s²), and the
    /// variance over the step (m²/s⁴). Max-product inference and the centroid.
    pub fn infer(&self, f: f64, sigma: f64, variance: f64) -> FuzzyStep {
        let act = activity(f, sigma);
        let w = Self::strengths(f, act, variance);
        let (mut num, mut den) = (0.0, 0.0);
        for (i, mu) in self.sets.iter().enumerate() {
            let m = (0..8).map(|j| w[j] * mu[j]).fold(0.0, f64::max);
            num += i as f64 * OUTPUT_STEP_M * m;
            den += m;
        }
        // The sets cover every input (the memberships sum to 1), so den > 0; the guard keeps a
        // finite answer regardless: the middle of the output sets.
        let centroid = if den > 0.0 && num.is_finite() {
            num / den
        } else {
            OUTPUT_CENTRES_M[3]
        };
        FuzzyStep {
            activity: act,
            variance,
            centroid_m: centroid,
            length_m: (self.cfg.scale * centroid).clamp(0.2, 2.5),
        }
    }
}

/// Mean and variance of the vertical acceleration between `t0` and `t1` (m/s², m²/s⁴); `None`
/// without a sample there.
pub fn vertical_variance(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> Option<(f64, f64)> {
    let (mut n, mut s, mut s2) = (0usize, 0.0, 0.0);
    for x in buf
        .iter()
        .rev()
        .take_while(|x| x.t >= t0)
        .filter(|x| x.t <= t1)
    {
        n += 1;
        s += x.up;
        s2 += x.up * x.up;
    }
    (n > 0).then(|| {
        let m = s / n as f64;
        (m, (s2 / n as f64 - m * m).max(0.0))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memberships_partition_and_the_printed_rule() {
        for k in 0..=400 {
            let x = k as f64 * 0.01;
            assert!((freq_memberships(x).iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let v = k as f64 * 0.1;
            assert!((variance_memberships(v).iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
        // IF slow AND walk AND short(low) THEN small: all the strength on SM.
        let w = FuzzyStepLength::strengths(1.2, Activity::Walk, 0.5);
        assert_eq!(w, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        let z = FuzzyStepLength::new(FuzzyConfig::default());
        let s = z.infer(1.2, 0.7, 0.5);
        assert!((s.centroid_m - OUTPUT_CENTRES_M[0]).abs() < 1e-3, "{s:?}");
        // Fast, run, high: very giant.
        let s = z.infer(3.5, 8.0, 60.0);
        assert_eq!(s.activity, Activity::Run);
        assert!((s.centroid_m - OUTPUT_CENTRES_M[7]).abs() < 1e-3, "{s:?}");
    }

    #[test]
    fn activity_from_cadence_and_sigma() {
        assert_eq!(activity(1.8, 2.0), Activity::Walk);
        assert_eq!(activity(2.3, 2.0), Activity::FastWalk);
        // A purse swinging at 3.2 Hz with σ 1 is no run.
        assert_eq!(activity(3.2, 1.0), Activity::FastWalk);
        assert_eq!(activity(2.7, 6.0), Activity::Jog);
        assert_eq!(activity(3.2, 6.0), Activity::Run);
    }

    #[test]
    fn finite_and_scaled_for_any_input() {
        let z = FuzzyStepLength::new(FuzzyConfig { scale: 1.1 });
        let z1 = FuzzyStepLength::new(FuzzyConfig::default());
        for f in [f64::NAN, -1.0, 0.0, 0.5, 1.9, 2.4, 3.0, 9.0, f64::INFINITY] {
            for v in [f64::NAN, -1.0, 0.0, 3.0, 12.0, 1e9] {
                for sigma in [0.0, 1.0, 5.0, f64::NAN] {
                    let s = z.infer(f, sigma, v);
                    assert!(s.length_m.is_finite() && (0.2..=2.5).contains(&s.length_m));
                    let s1 = z1.infer(f, sigma, v);
                    assert!((s.centroid_m - s1.centroid_m).abs() < 1e-12);
                }
            }
        }
        // Monotone in frequency along a walk at medium variance.
        let mut last = 0.0;
        for k in 0..=14 {
            let s = z1.infer(1.5 + 0.05 * k as f64, 2.2, 5.0);
            assert!(s.centroid_m >= last - 1e-9, "{k}: {s:?}");
            last = s.centroid_m;
        }
    }
}
