//! Step length.
//! May import: the rest of `engine`.
//!
//! - [`StepLengthProfile`]: Basso 2016 §II.D. Within a band of frequencies the step length is
//!   nearly linear in step frequency, SL = a·f + b, with one line for walking (about 1.5–2.2 Hz)
//!   and one for running (about 2.7–4.2 Hz): a piecewise-linear function. (Basso 2021 eq. 23 writes
//!   the same law as a·f − b.) The user's lines come from calibration by least squares
//!   ([`fit_line`], with f̄ by eq. 1 [`harmonic_mean_frequency`] and SL̄ = D/N by eq. 2).
//! - Weinberg (Analog Devices AN-602, cited by Basso 2016 as \[18\]): SL = K·(a_max − a_min)^¼ of
//!   the vertical acceleration over the step.
//! - Fuzzy (Ibarra 2015 §4.4.2): [`super::fuzzy_step_length`].
//!
//! # Default coefficients
//! The papers publish no numbers for the lines (Basso 2016 Fig. 4 shows two users only). The
//! defaults are a population placeholder until the user calibrates:
//! - walking SL = 0.25·f + 0.17 m: 0.545 m at 1.5 Hz, 0.62 m at 1.8 Hz, 0.67 m at 2.0 Hz,
//!   0.72 m at 2.2 Hz. The slope follows the speed–frequency law of human walking (cadence grows
//!   about as v^0.58, Bertram & Ruina 2001, so SL ∝ f^0.72 and dSL/df ≈ 0.72·SL/f ≈ 0.25 m/Hz
//!   near 1.9 Hz). The offset is set on the whole Microsoft indoor set (24 hand-held walks,
//!   ~2.0 Hz, true mean step 0.65 m between waypoints), in sample; its leave-one-out check and
//!   how the IPIN 2023 walks compare are in `docs/evaluation.md`.
//! - running SL = 0.90·f − 1.50 m: 0.93 m at 2.7 Hz (2.5 m/s), 1.47 m at 3.3 Hz (4.9 m/s);
//! - clamped to the physiological range 0.2–2.5 m.
//!
//! Between the bands the line is chosen by frequency, switching at the midpoint of the gap
//! (2.45 Hz by default); outside the bands each line is extrapolated, then clamped.

use super::carry::CarryMode;
use super::fuzzy_step_length::{vertical_variance, FuzzyConfig, FuzzyStep, FuzzyStepLength};
use super::heading::NavSample;
use super::pitch_step_length::{footfall_m, POCKET_SLOPE_M_PER_DEG, UNIVERSAL_SLOPE_M_PER_DEG};
use super::types::{positive, ConfigError};
use std::collections::VecDeque;

/// One line SL = a·f + b, valid over [f_lo, f_hi].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Line {
    /// Slope, m/Hz.
    pub a: f64,
    /// Offset, m.
    pub b: f64,
    /// Lower end of the band, Hz.
    pub f_lo: f64,
    /// Upper end of the band, Hz.
    pub f_hi: f64,
}

impl Line {
    /// SL at frequency `f`, m.
    pub fn eval(&self, f: f64) -> f64 {
        self.a * f + self.b
    }
}

/// A user's piecewise-linear step-length profile.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct StepLengthProfile {
    /// Walking line.
    pub walking: Line,
    /// Running line.
    pub running: Line,
    /// Smallest step length returned, m.
    pub min_m: f64,
    /// Largest step length returned, m.
    pub max_m: f64,
}

impl Default for StepLengthProfile {
    fn default() -> Self {
        StepLengthProfile {
            walking: Line {
                a: 0.25,
                b: 0.17,
                f_lo: 1.5,
                f_hi: 2.2,
            },
            running: Line {
                a: 0.90,
                b: -1.50,
                f_lo: 2.7,
                f_hi: 4.2,
            },
            min_m: 0.2,
            max_m: 2.5,
        }
    }
}

impl StepLengthProfile {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        for (l, name) in [
            (self.walking, "step_length.walking"),
            (self.running, "step_length.running"),
        ] {
            if ![l.a, l.b, l.f_lo, l.f_hi].iter().all(|v| v.is_finite())
                || !(l.f_hi > l.f_lo)
                || l.f_lo <= 0.0
            {
                return Err(ConfigError::new(
                    name,
                    "coefficients must be finite and the band increasing and positive",
                ));
            }
        }
        if !(self.running.f_lo >= self.walking.f_hi) {
            return Err(ConfigError::new(
                "step_length.running",
                "running band must lie above the walking band",
            ));
        }
        positive("step_length.min_m", self.min_m)?;
        if !(self.max_m > self.min_m) {
            return Err(ConfigError::new("step_length.max_m", "must exceed min_m"));
        }
        Ok(())
    }

    /// Step length at step frequency `f` (Hz), m.
    pub fn length(&self, f: f64) -> f64 {
        let split = 0.5 * (self.walking.f_hi + self.running.f_lo);
        let line = if f < split {
            &self.walking
        } else {
            &self.running
        };
        line.eval(f).clamp(self.min_m, self.max_m)
    }
}

/// Settings of the pitch step length (Munoz Diaz 2015 eq. 5, [`super::pitch_step_length`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PitchStepLength {
    /// a, m of stride per degree. Default [`UNIVERSAL_SLOPE_M_PER_DEG`].
    pub a: f64,
    /// b, m of stride: the walker's own offset (the wizard's calibration). Default 0.
    pub b: f64,
    /// The line in frequency for steps without a leg pitch (a phone taken out of the pocket,
    /// no gyroscope): the default profile unless a profile is given.
    pub fallback: StepLengthProfile,
}

impl Default for PitchStepLength {
    fn default() -> Self {
        PitchStepLength {
            a: UNIVERSAL_SLOPE_M_PER_DEG,
            b: 0.0,
            fallback: StepLengthProfile::default(),
        }
    }
}

impl PitchStepLength {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("step_length.a", self.a)?;
        if !(self.b.is_finite() && self.b.abs() < 1.0) {
            return Err(ConfigError::new(
                "step_length.b",
                "must be a finite offset within ±1 m",
            ));
        }
        self.fallback.validate()
    }

    /// One footfall's length, m: half of eq. 5's stride for amplitude Δθ (degrees), within the
    /// fallback profile's physiological range; the fallback line at `freq_hz` without Δθ.
    pub fn length(&self, amplitude_deg: Option<f64>, freq_hz: f64) -> f64 {
        match amplitude_deg {
            Some(d) => {
                footfall_m(self.a, self.b, d).clamp(self.fallback.min_m, self.fallback.max_m)
            }
            None => self.fallback.length(freq_hz),
        }
    }
}

/// The frequency line's steps in a trouser pocket: Munoz Diaz 2015 eq. 5 (stride S = a·Δθ_H,
/// [`super::pitch_step_length`]) instead of the line, for a walking step whose stride showed a
/// recognised thigh's swing ([`crate::engine::leg_pitch::LegPitch::push_stride`]) while the
/// carrying mode reads a pocket. The thigh's swing measures the stride itself, where the line
/// only knows the cadence: on TyrEx's front-pocket walks (slow loops with frequent turns in a
/// 5 × 6 m room) the line gives 0.55–0.6 m per step at 1.5–1.7 Hz against 0.45–0.5 m true
/// (`docs/methods/step-length-pocket.md`). The pocket's other steps (strides the leg pitch did
/// not recognise as a thigh's, often a third or more of a slow walk's) take the line scaled by
/// what the thigh's steps so far measured against it: Σ eq. 5 / Σ line over them, once there
/// are [`Self::min_steps`]. The other models keep their own rule (the pitch model already uses
/// eq. 5 on every such step).
///
/// Off by default: the simulated pocket walks give their thigh the law stride = 0.030·Δθ + 0.06 m
/// (`sim::thigh`), on which the default's 0.0364 reads 16 % long, and the fusion's tests are
/// built on the line being the engine's length in the pocket (the city walk's walker steps 1/1.1
/// of it). On, it takes TyrEx's front-pocket median distance ratio from 1.26 to 1.10.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ThighStepLength {
    /// Whether the rule runs. Default off (see above).
    pub on: bool,
    /// a, m of stride per degree of Δθ_H. Default [`POCKET_SLOPE_M_PER_DEG`]. No offset: the
    /// line's default is not a walker's either.
    pub a: f64,
    /// The thigh's steps needed before the pocket's other steps take the line scaled by them;
    /// 0 never scales. Default 8 (four strides): on TyrEx's front pockets 4 and 10 give the
    /// same ratios, 20 waits too long on walks where the thigh shows late.
    pub min_steps: u32,
}

impl Default for ThighStepLength {
    fn default() -> Self {
        ThighStepLength {
            on: false,
            a: POCKET_SLOPE_M_PER_DEG,
            min_steps: 8,
        }
    }
}

impl ThighStepLength {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(self.a.is_finite() && self.a > 0.0 && self.a < 0.1) {
            return Err(ConfigError::new(
                "thigh_step_length.a",
                "must be a slope above 0 and below 0.1 m per degree",
            ));
        }
        Ok(())
    }

    /// One footfall's length, m, for a step of the frequency line: eq. 5's half stride within
    /// the profile's range when the rule is on and the step is in a pocket with a thigh's Δθ
    /// (degrees); `None` otherwise (the line applies).
    pub fn length(
        &self,
        profile: &StepLengthProfile,
        carry: Option<CarryMode>,
        amplitude_deg: Option<f64>,
    ) -> Option<f64> {
        match (carry, amplitude_deg) {
            (Some(CarryMode::Pocket), Some(d)) if self.on && d.is_finite() => {
                Some(footfall_m(self.a, 0.0, d).clamp(profile.min_m, profile.max_m))
            }
            _ => None,
        }
    }
}

/// What the thigh's steps measured against the frequency line so far
/// ([`ThighStepLength`]).
#[derive(Debug, Clone, Copy, Default)]
struct ThighScale {
    /// Σ eq. 5 over the thigh's steps, m.
    eq5_m: f64,
    /// Σ line over the same steps, m.
    line_m: f64,
    /// How many.
    steps: u32,
}

impl ThighScale {
    /// Σ eq. 5 / Σ line once `min_steps` (at least 1) thigh steps are in.
    fn scale(&self, min_steps: u32) -> Option<f64> {
        (min_steps > 0 && self.steps >= min_steps && self.line_m > 0.0)
            .then(|| self.eq5_m / self.line_m)
    }
}

/// How step length is computed.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum StepLengthModel {
    /// Basso 2016 piecewise-linear in frequency.
    Frequency(StepLengthProfile),
    /// Weinberg: K·(a_max − a_min)^¼.
    Weinberg {
        /// K, m/(m/s²)^¼. Default [`WEINBERG_K`].
        #[serde(default = "weinberg_k")]
        k: f64,
    },
    /// Ibarra 2015's fuzzy system on step frequency, activity and the variance of the vertical
    /// acceleration over the step, times a calibrated scale.
    Fuzzy(FuzzyConfig),
    /// Munoz Diaz 2015 eq. 5 on the leg pitch amplitude ([`super::pitch_step_length`]).
    Pitch(PitchStepLength),
}

/// Weinberg's K when none is given: 0.47 gives 0.70 m at a 5 m/s² peak-to-peak.
pub const WEINBERG_K: f64 = 0.47;

fn weinberg_k() -> f64 {
    WEINBERG_K
}

impl Default for StepLengthModel {
    fn default() -> Self {
        StepLengthModel::Frequency(StepLengthProfile::default())
    }
}

impl StepLengthModel {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        match self {
            StepLengthModel::Frequency(p) => p.validate(),
            StepLengthModel::Weinberg { k } => positive("step_length.k", *k),
            StepLengthModel::Fuzzy(c) => c.validate(),
            StepLengthModel::Pitch(p) => p.validate(),
        }
    }
}

/// Weinberg's step length, m: K·(a_max − a_min)^¼ of the vertical acceleration's peak-to-peak
/// over the step (m/s²), clamped to 0.2–2.5 m.
pub fn weinberg(k: f64, peak_to_peak: f64) -> f64 {
    (k * libm::sqrt(libm::sqrt(peak_to_peak.max(0.0)))).clamp(0.2, 2.5)
}

/// Weinberg's input: the peak-to-peak of the vertical acceleration between `t0` and `t1`, m/s²
/// (0 without a sample there).
pub fn peak_to_peak(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> f64 {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in buf
        .iter()
        .rev()
        .take_while(|s| s.t >= t0)
        .filter(|s| s.t <= t1)
    {
        lo = lo.min(s.up);
        hi = hi.max(s.up);
    }
    if hi >= lo {
        hi - lo
    } else {
        0.0
    }
}

/// What the step-length stage is given at each step.
#[derive(Debug, Clone, Copy)]
pub struct StepLengthInput<'a> {
    /// The step frequency f_k = 1/T_k, Hz.
    pub freq_hz: f64,
    /// The recent samples in the navigation frame (Weinberg's amplitude is taken from them).
    pub buf: &'a VecDeque<NavSample>,
    /// The start of the step, s.
    pub t0: f64,
    /// The end of the step, s.
    pub t1: f64,
    /// The leg pitch amplitude Δθ of the step's stride, degrees, when known.
    pub pitch_amplitude_deg: Option<f64>,
    /// The carrying mode at the step, when known.
    pub carry: Option<CarryMode>,
}

/// The step-length stage's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StepLengthDiagnostics {
    /// The last step's length, m.
    pub last_m: Option<f64>,
}

/// The step-length stage: the configured model at each step. The models keep nothing from step
/// to step, so every step gets a length (there is no `None` to return).
#[derive(Debug, Clone)]
pub struct StepLength {
    model: StepLengthModel,
    thigh: ThighStepLength,
    thigh_scale: ThighScale,
    fuzzy: Option<FuzzyStepLength>,
    last_m: Option<f64>,
}

impl StepLength {
    /// A stage with a validated model and the pocket's rule for the frequency line.
    pub fn new(model: StepLengthModel, thigh: ThighStepLength) -> Self {
        StepLength {
            thigh,
            thigh_scale: ThighScale::default(),
            fuzzy: match &model {
                StepLengthModel::Fuzzy(c) => Some(FuzzyStepLength::new(*c)),
                _ => None,
            },
            model,
            last_m: None,
        }
    }

    /// The model.
    pub fn config(&self) -> &StepLengthModel {
        &self.model
    }

    /// The length of one step, m.
    pub fn push(&mut self, step: &StepLengthInput) -> f64 {
        let m = match &self.model {
            StepLengthModel::Frequency(p) => {
                let line = p.length(step.freq_hz);
                match self.thigh.length(p, step.carry, step.pitch_amplitude_deg) {
                    Some(m) => {
                        let s = &mut self.thigh_scale;
                        s.eq5_m += m;
                        s.line_m += line;
                        s.steps += 1;
                        m
                    }
                    None => match (step.carry, self.thigh_scale.scale(self.thigh.min_steps)) {
                        (Some(CarryMode::Pocket), Some(k)) => (k * line).clamp(p.min_m, p.max_m),
                        _ => line,
                    },
                }
            }
            StepLengthModel::Weinberg { k } => {
                weinberg(*k, peak_to_peak(step.buf, step.t0, step.t1))
            }
            StepLengthModel::Fuzzy(_) => self
                .fuzzy
                .as_ref()
                .map_or(0.2, |z| fuzzy_step(z, step).length_m),
            StepLengthModel::Pitch(p) => p.length(step.pitch_amplitude_deg, step.freq_hz),
        };
        self.last_m = Some(m);
        m
    }

    /// The current values.
    pub fn diagnostics(&self) -> StepLengthDiagnostics {
        StepLengthDiagnostics {
            last_m: self.last_m,
        }
    }
}

/// The fuzzy system's inference for one step of the step-length stage: the variance of the
/// vertical acceleration over the step, the activity's σ the step's own (its square root). The
/// one place the fuzzy model reads a step, for the stage and for the calibration wizard's walks
/// (`live::LiveSession::fuzzy_lengths`).
pub fn fuzzy_step(z: &FuzzyStepLength, step: &StepLengthInput) -> FuzzyStep {
    let v = vertical_variance(step.buf, step.t0, step.t1).map_or(0.0, |m| m.1);
    z.infer(step.freq_hz, libm::sqrt(v), v)
}

/// Basso 2016 eq. 1: the mean step frequency of a calibration walk, the harmonic mean
/// f̄ = (1/N Σ 1/f_k)⁻¹ (equivalently N / Σ T_k). `None` for an empty or non-positive input.
pub fn harmonic_mean_frequency(freqs: &[f64]) -> Option<f64> {
    if freqs.is_empty() || freqs.iter().any(|f| !(*f > 0.0)) {
        return None;
    }
    Some(freqs.len() as f64 / freqs.iter().map(|f| 1.0 / f).sum::<f64>())
}

/// Basso 2016 eq. 2: SL̄ = D/N.
pub fn mean_step_length(distance_m: f64, steps: usize) -> Option<f64> {
    (steps > 0 && distance_m.is_finite() && distance_m > 0.0).then(|| distance_m / steps as f64)
}

/// A least-squares line fit with its quality.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LineFit {
    /// Slope, m/Hz.
    pub a: f64,
    /// Offset, m.
    pub b: f64,
    /// Coefficient of determination.
    pub r2: f64,
    /// Residuals SL_i − (a f_i + b), m.
    pub residuals: Vec<f64>,
}

/// Least-squares fit of SL = a·f + b through the calibration points P_i = (f̄_i, SL̄_i)
/// (Basso 2016 §II.D). Needs two distinct frequencies.
pub fn fit_line(points: &[(f64, f64)]) -> Option<LineFit> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mf = points.iter().map(|p| p.0).sum::<f64>() / n;
    let ms = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sff: f64 = points.iter().map(|p| (p.0 - mf) * (p.0 - mf)).sum();
    let sfs: f64 = points.iter().map(|p| (p.0 - mf) * (p.1 - ms)).sum();
    if !(sff > 1e-12) {
        return None;
    }
    let a = sfs / sff;
    let b = ms - a * mf;
    let residuals: Vec<f64> = points.iter().map(|p| p.1 - (a * p.0 + b)).collect();
    let ss_res: f64 = residuals.iter().map(|r| r * r).sum();
    let ss_tot: f64 = points.iter().map(|p| (p.1 - ms) * (p.1 - ms)).sum();
    let r2 = if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else {
        1.0
    };
    Some(LineFit {
        a,
        b,
        r2,
        residuals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn piecewise_and_clamped() {
        let p = StepLengthProfile::default();
        // The documented default walking line: 0.62 m at 1.8 Hz, 0.67 m at 2.0 Hz.
        assert!((p.length(1.8) - 0.62).abs() < 1e-9);
        assert!((p.length(2.0) - 0.67).abs() < 1e-9);
        assert!(p.length(3.0) > p.length(2.2));
        assert_eq!(p.length(20.0), p.max_m);
        assert_eq!(p.length(0.01), p.min_m);
    }

    /// The pocket's rule, on, with its default slope.
    const ON: ThighStepLength = ThighStepLength {
        on: true,
        a: POCKET_SLOPE_M_PER_DEG,
        min_steps: 8,
    };

    /// A fresh stage's length for one step (the pocket's rule on), and the default line's at `freq_hz`.
    fn pocket_step(freq_hz: f64, deg: Option<f64>, carry: Option<CarryMode>) -> (f64, f64) {
        let buf = VecDeque::new();
        let mut stage = StepLength::new(StepLengthModel::default(), ON);
        let input = StepLengthInput {
            freq_hz,
            buf: &buf,
            t0: 0.0,
            t1: 0.6,
            pitch_amplitude_deg: deg,
            carry,
        };
        (
            stage.push(&input),
            StepLengthProfile::default().length(freq_hz),
        )
    }

    #[test]
    fn thigh_steps_in_a_pocket_take_eq5() {
        let pocket = Some(CarryMode::Pocket);
        // A thigh's 26° in a pocket: half of 0.0364 · 26 = 0.4732 m, not the line's 0.57 m.
        let (m, line) = pocket_step(1.6, Some(26.0), pocket);
        assert!((m - 0.5 * POCKET_SLOPE_M_PER_DEG * 26.0).abs() < 1e-12 && line > 0.55);
        // A swinging hand's Δθ, or no Δθ: the line.
        assert_eq!(
            pocket_step(1.6, Some(60.0), Some(CarryMode::Swinging)).0,
            line
        );
        assert_eq!(pocket_step(1.6, None, pocket).0, line);
        // Off (the default): the line everywhere.
        let off = ThighStepLength::default();
        assert_eq!(
            off.length(&StepLengthProfile::default(), pocket, Some(26.0)),
            None
        );
        let buf = VecDeque::new();
        let mut stage = StepLength::new(StepLengthModel::default(), off);
        let input = StepLengthInput {
            freq_hz: 1.6,
            buf: &buf,
            t0: 0.0,
            t1: 0.6,
            pitch_amplitude_deg: Some(26.0),
            carry: pocket,
        };
        assert_eq!(stage.push(&input), line);
        assert!(ThighStepLength { a: f64::NAN, ..ON }.validate().is_err());
        assert!(ThighStepLength { a: 0.0, ..ON }.validate().is_err());
        assert!(off.validate().is_ok());
    }

    #[test]
    fn the_thigh_scales_the_pockets_other_steps() {
        let buf = VecDeque::new();
        let mut stage = StepLength::new(StepLengthModel::default(), ON);
        let step = |deg: Option<f64>| StepLengthInput {
            freq_hz: 1.8,
            buf: &buf,
            t0: 0.0,
            t1: 0.55,
            pitch_amplitude_deg: deg,
            carry: Some(CarryMode::Pocket),
        };
        let line = StepLengthProfile::default().length(1.8);
        // Before 8 thigh steps the other steps keep the line.
        for _ in 0..7 {
            stage.push(&step(Some(25.0)));
        }
        assert_eq!(stage.push(&step(None)), line);
        let thigh = stage.push(&step(Some(25.0)));
        // Now Σ eq. 5 / Σ line over the 8 thigh steps scales the line.
        let scaled = stage.push(&step(None));
        assert!((scaled - line * thigh / line).abs() < 1e-12 && scaled < line);
        // Out of the pocket, the line.
        let hand = StepLengthInput {
            carry: Some(CarryMode::Hand),
            ..step(None)
        };
        assert_eq!(stage.push(&hand), line);
    }

    #[test]
    fn calibration_equations() {
        // Eq. 1: steps of 0.5 s and 0.6 s: 2 steps in 1.1 s.
        assert!((harmonic_mean_frequency(&[2.0, 1.0 / 0.6]).unwrap() - 2.0 / 1.1).abs() < 1e-12);
        assert_eq!(mean_step_length(70.0, 100), Some(0.7));
        let fit = fit_line(&[(1.5, 0.6), (1.8, 0.7), (2.1, 0.8)]).unwrap();
        assert!((fit.a - 1.0 / 3.0).abs() < 1e-9 && (fit.r2 - 1.0).abs() < 1e-9);
    }
}
