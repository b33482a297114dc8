//! Step-length calibration (Basso 2016 §II.D; the engine side of the calibration wizard).
//! May import: the rest of `engine`.
//!
//! The user walks known distances at several paces. Each walk gives one point
//! P = (f̄, SL̄): the harmonic mean of its step frequencies (eq. 1, [`harmonic_mean_frequency`])
//! and the distance over the number of steps (eq. 2, [`mean_step_length`]). A least-squares
//! line SL = a·f + b per band (walking, running) makes the piecewise-linear
//! [`StepLengthProfile`]. [`fit_band`] gives the line with its standard errors and R², and says
//! what is wrong with it ([`FitWarning`]).
//!
//! **Quick mode** ([`quick_line`]): one comfortable walk, with the slope fixed at the
//! population value and only the offset b fitted. Munoz Diaz et al. 2015 (§5, Fig. 8) found the
//! slope of the step-length line nearly the same for all 18 of their walkers (their line is in
//! the leg's pitch amplitude: people choose their step length at a speed by the same energy
//! optimum), while the offset is personal. We take that finding over to the frequency line
//! with the engine's default slope, 0.25 m/Hz: the speed–cadence law of human walking
//! (cadence ∝ v^0.58, Bertram & Ruina 2001) gives dSL/df ≈ 0.72·SL/f ≈ 0.25 m/Hz near 1.9 Hz
//! for a 0.65 m step (see [`crate::engine::step_length`]).
//!
//! **Refinement from GNSS** ([`refined_offset`]): Basso 2021 §2.2.5 corrects the model's
//! offset from the mean step length between fixes; the fusion filter's step-length scale k
//! ([`crate::engine::fusion`]) is that ratio, learnt over many fixes; when a walk may refine a
//! profile is [`crate::engine::refinement`]'s to say.

use super::step_length::{fit_line, harmonic_mean_frequency, mean_step_length, Line};
use super::step_length::{LineFit, StepLengthProfile};
use super::types::ConfigError;

/// Frequencies of one band must span at least this, Hz, for a slope to mean anything.
pub const MIN_SPAN_HZ: f64 = 0.3;

/// A point is an outlier when its residual is more than this many standard deviations of the
/// other points' residuals from the line fitted without it…
pub const OUTLIER_SIGMAS: f64 = 3.0;

/// …and more than this, m (a few centimetres are within what a count of ±1 step does).
pub const OUTLIER_MIN_M: f64 = 0.03;

/// The population slope of quick mode, m/Hz (see the module documentation).
pub const UNIVERSAL_SLOPE: f64 = 0.25;

/// One calibration walk: a known distance, and the step frequencies the engine counted (and,
/// when the caller has them, the steps' unscaled fuzzy lengths).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CalibrationWalk {
    /// Distance walked, m (typed by the user or measured from the fixes).
    pub distance_m: f64,
    /// f_k = 1/T_k of every step counted, Hz.
    pub step_freqs_hz: Vec<f64>,
    /// The fuzzy model's length of every step counted, at scale 1 (the centroid; Ibarra 2015,
    /// `live::LiveSession::fuzzy_lengths`), m; empty when not measured (older callers): the
    /// walk then fits the line only.
    #[serde(default)]
    pub fuzzy_lengths_m: Vec<f64>,
}

impl CalibrationWalk {
    /// Its point (f̄ by eq. 1, SL̄ by eq. 2), or `None` without steps or distance.
    pub fn point(&self) -> Option<(f64, f64)> {
        Some((
            harmonic_mean_frequency(&self.step_freqs_hz)?,
            mean_step_length(self.distance_m, self.step_freqs_hz.len())?,
        ))
    }
}

/// What is wrong with a band's fit, each with the explanation the wizard shows.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum FitWarning {
    /// Fewer than three points: a line through two points has no check.
    TooFewPoints {
        /// Points given.
        n: usize,
    },
    /// The paces are too alike for a slope.
    NarrowSpan {
        /// Span of the frequencies, Hz.
        span_hz: f64,
    },
    /// Step length falling with cadence: a walk was mismeasured or miscounted.
    NegativeSlope {
        /// The slope, m/Hz.
        a: f64,
    },
    /// A point far off the line the others make; the wizard offers to drop it.
    Outlier {
        /// Its index in the points.
        index: usize,
        /// Its residual from the line fitted without it, m.
        residual_m: f64,
    },
}

impl FitWarning {
    /// The explanation, for people.
    pub fn message(&self) -> String {
        match self {
            FitWarning::TooFewPoints { n } => format!(
                "{n} walk(s) in this band: walk at least three different paces so that the line can be checked"
            ),
            FitWarning::NarrowSpan { span_hz } => format!(
                "the paces differ by {span_hz:.2} Hz only: walk one pace clearly slower and one clearly faster (at least {MIN_SPAN_HZ} Hz apart)"
            ),
            FitWarning::NegativeSlope { a } => format!(
                "the steps come out shorter at faster paces ({a:.2} m/Hz): a distance or a walk is probably wrong; redo the odd one"
            ),
            FitWarning::Outlier { index, residual_m } => format!(
                "walk {} is {:.0} cm off the line the others make: was the distance right? Drop it or walk it again",
                index + 1,
                residual_m * 100.0
            ),
        }
    }
}

/// A band's fit: the line, its quality and its warnings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BandFit {
    /// The points (f̄, SL̄).
    pub points: Vec<(f64, f64)>,
    /// The least-squares line, when two distinct frequencies exist.
    pub fit: Option<LineFit>,
    /// Standard errors of the slope and the offset (m/Hz, m), with three points or more.
    pub se: Option<(f64, f64)>,
    /// What is wrong.
    pub warnings: Vec<FitWarning>,
}

/// Fits SL = a·f + b through a band's points by least squares, with the standard errors of a
/// and b (σ̂² = Σr²/(n−2); se(a) = σ̂/√Sff, se(b) = σ̂·√(1/n + f̄²/Sff)), and checks it.
pub fn fit_band(points: &[(f64, f64)]) -> BandFit {
    let n = points.len();
    let fit = fit_line(points);
    let mut warnings = Vec::new();
    if n < 3 {
        warnings.push(FitWarning::TooFewPoints { n });
    }
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
    if n >= 2 && hi - lo < MIN_SPAN_HZ {
        warnings.push(FitWarning::NarrowSpan { span_hz: hi - lo });
    }
    if let Some(f) = &fit {
        if f.a < 0.0 {
            warnings.push(FitWarning::NegativeSlope { a: f.a });
        }
    }
    let se = fit.as_ref().filter(|_| n >= 3).map(|f| {
        let nf = n as f64;
        let mf = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let sff: f64 = points.iter().map(|p| (p.0 - mf) * (p.0 - mf)).sum();
        let s2 = f.residuals.iter().map(|r| r * r).sum::<f64>() / (nf - 2.0);
        (
            libm::sqrt(s2 / sff),
            libm::sqrt(s2 * (1.0 / nf + mf * mf / sff)),
        )
    });
    if let Some(w) = outlier(points) {
        warnings.push(w);
    }
    BandFit {
        points: points.to_vec(),
        fit,
        se,
        warnings,
    }
}

/// The worst point by its residual from the line through the others, when it stands out (needs
/// four points: three left to fit and judge).
fn outlier(points: &[(f64, f64)]) -> Option<FitWarning> {
    if points.len() < 4 {
        return None;
    }
    (0..points.len())
        .filter_map(|i| {
            let others: Vec<(f64, f64)> = points
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, p)| *p)
                .collect();
            let f = fit_line(&others)?;
            let dof = (others.len() - 2).max(1) as f64;
            let s = libm::sqrt(f.residuals.iter().map(|r| r * r).sum::<f64>() / dof);
            let r = points[i].1 - (f.a * points[i].0 + f.b);
            (r.abs() > OUTLIER_MIN_M && r.abs() > OUTLIER_SIGMAS * s).then_some((i, r))
        })
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map(|(index, residual_m)| FitWarning::Outlier { index, residual_m })
}

/// Quick mode: the line with the population slope [`UNIVERSAL_SLOPE`] through one walk's point.
pub fn quick_line(point: (f64, f64), band: (f64, f64)) -> Line {
    Line {
        a: UNIVERSAL_SLOPE,
        b: point.1 - UNIVERSAL_SLOPE * point.0,
        f_lo: band.0,
        f_hi: band.1,
    }
}

/// The walking offset corrected by the fusion filter's step-length scale `k` at the user's usual
/// cadence `f` (Basso 2021 §2.2.5): the line is moved so that SL(f) becomes k·SL(f); the slope
/// stays. `rate` in (0, 1] moves only part of the way (slow refinement over repeated walks).
pub fn refined_offset(line: &Line, k: f64, f: f64, rate: f64) -> f64 {
    let sl = line.eval(f);
    line.b + rate.clamp(0.0, 1.0) * (k - 1.0) * sl
}

/// A saved profile: a name, the profile, and the points it was fitted from. The `version` field
/// lets later versions read older files.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProfileFile {
    /// Format version, [`PROFILE_VERSION`].
    pub version: u32,
    /// The user's name for it.
    pub name: String,
    /// The profile.
    pub profile: StepLengthProfile,
    /// Calibration points (f̄ Hz, SL̄ m) of the walking band.
    #[serde(default)]
    pub walking_points: Vec<(f64, f64)>,
    /// Calibration points of the running band.
    #[serde(default)]
    pub running_points: Vec<(f64, f64)>,
    /// The fuzzy step length's output scale k ([`fuzzy_scale`]), when a calibration walk was
    /// made with that model; absent from files that have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fuzzy_scale: Option<f64>,
    /// The pitch step length's personal offset b, m per stride ([`pitch_offset`], Munoz Diaz
    /// 2015 §5.1), when a calibration walk had a leg pitch; absent from files that have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_offset_m: Option<f64>,
}

/// The fuzzy step length's output scale from a calibration walk (Ibarra 2015 §4.4.2 has no
/// calibration; ours, as the line's eq. 2 does for SL̄): the walk's known distance over the
/// sum of the step lengths the fuzzy system gave with scale `current`, times `current`:
/// k = current · D / Σ SL_k. Refused like a wizard walk: a distance that is not a positive
/// number of metres, fewer than [`MIN_STEPS`] steps, or lengths that are not finite and
/// positive.
pub fn fuzzy_scale(distance_m: f64, lengths_m: &[f64], current: f64) -> Result<f64, WalkError> {
    if !(distance_m.is_finite() && distance_m > 0.0) {
        return Err(WalkError::Distance(distance_m));
    }
    let sum: f64 = lengths_m.iter().sum();
    if lengths_m.len() < MIN_STEPS
        || !(sum.is_finite() && sum > 0.0)
        || !(current.is_finite() && current > 0.0)
    {
        return Err(WalkError::TooFewSteps(lengths_m.len()));
    }
    Ok(current * distance_m / sum)
}

/// The personal offset b of the pitch step length (Munoz Diaz 2015 §5.1's one-walk
/// calibration): the user walks a known distance D at a comfortable pace; with the universal
/// slope a (m/° per stride), each stride is S = a·Δθ + b (eq. 5), so each of its two steps is
/// (a·Δθ + b)/2, Δθ being the stride's leg pitch amplitude (both steps carry it). Summed over
/// the N steps, D = (a/2)·Σ Δθ_k + N·b/2, so b = (2·D − a·Σ Δθ_k) / N, m per stride.
/// `amplitudes_deg` is each step's Δθ; steps without one (not finite or not positive: no leg
/// pitch) are left out of N and the sum. Refused: a distance that is not a positive number of
/// metres, fewer than [`MIN_STEPS`] steps with a pitch, or a slope that is not finite.
pub fn pitch_offset(
    distance_m: f64,
    amplitudes_deg: &[f64],
    slope_m_per_deg: f64,
) -> Result<f64, WalkError> {
    if !(distance_m.is_finite() && distance_m > 0.0) {
        return Err(WalkError::Distance(distance_m));
    }
    let (n, sum) = amplitudes_deg
        .iter()
        .filter(|d| d.is_finite() && **d > 0.0)
        .fold((0usize, 0.0), |(n, s), d| (n + 1, s + d));
    if n < MIN_STEPS || !slope_m_per_deg.is_finite() {
        return Err(WalkError::TooFewSteps(n));
    }
    Ok((2.0 * distance_m - slope_m_per_deg * sum) / n as f64)
}

/// The fuzzy scale that fits several calibration walks, each `(D_i, L_i)`: its known distance
/// and the sum of its steps' unscaled fuzzy lengths, m. Least squares through the origin,
/// D_i ≈ k·L_i: k = Σ D_i·L_i / Σ L_i² (ours; Ibarra 2015 has no calibration; for one walk it is
/// [`fuzzy_scale`]'s D / Σ SL_k at scale 1). Errors: no walk, or sums that are not finite and
/// positive ([`WalkError::FuzzyLengths`]), never an infinite k.
pub fn fit_fuzzy_scale(walks: &[(f64, f64)]) -> Result<f64, WalkError> {
    if walks.is_empty() {
        return Err(WalkError::NoFuzzyWalks);
    }
    for &(d, l) in walks {
        if !(d.is_finite() && d > 0.0) {
            return Err(WalkError::Distance(d));
        }
        if !(l.is_finite() && l > 0.0) {
            return Err(WalkError::FuzzyLengths(l));
        }
    }
    let dl: f64 = walks.iter().map(|(d, l)| d * l).sum();
    let ll: f64 = walks.iter().map(|(_, l)| l * l).sum();
    let k = dl / ll;
    if k.is_finite() && k > 0.0 {
        Ok(k)
    } else {
        Err(WalkError::FuzzyLengths(ll))
    }
}

/// The current profile file version.
pub const PROFILE_VERSION: u32 = 1;

impl ProfileFile {
    /// Reads a profile from JSON, checking the version and the values; the error names the
    /// field.
    pub fn from_json(text: &str) -> Result<Self, ConfigError> {
        let p: ProfileFile = serde_json::from_str(text)
            .map_err(|e| ConfigError::new("profile", format!("not a profile file: {e}")))?;
        if p.version != PROFILE_VERSION {
            return Err(ConfigError::new(
                "profile.version",
                format!(
                    "version {} is not one this app reads ({PROFILE_VERSION})",
                    p.version
                ),
            ));
        }
        p.profile.validate()?;
        if let Some(k) = p.fuzzy_scale {
            super::types::positive("profile.fuzzy_scale", k)?;
        }
        Ok(p)
    }

    /// The profile as JSON.
    pub fn to_json(&self) -> Result<String, ConfigError> {
        serde_json::to_string_pretty(self)
            .map_err(|e| ConfigError::new("profile", format!("cannot be written: {e}")))
    }

    /// Its lines for people: "Walking SL = 0.298·f + 0.203 m (3 walks); running SL = … Fuzzy
    /// scale k = 1.226." (the last sentence when it has one).
    pub fn describe(&self) -> String {
        let line = |l: &Line| {
            let sign = if l.b >= 0.0 { '+' } else { '−' };
            format!("SL = {:.3}·f {sign} {:.3} m", l.a, l.b.abs())
        };
        let fuzzy = self
            .fuzzy_scale
            .map_or(String::new(), |k| format!(" Fuzzy scale k = {k:.3}."));
        format!(
            "Walking {} ({} walks); running {} ({} runs).{fuzzy}",
            line(&self.profile.walking),
            self.walking_points.len(),
            line(&self.profile.running),
            self.running_points.len()
        )
    }
}

/// The built-in lines for people: "Built-in: walking SL = 0.25·f + 0.17 m, running SL = …".
pub fn describe_builtin() -> String {
    let p = StepLengthProfile::default();
    let line = |l: &Line| {
        let sign = if l.b >= 0.0 { '+' } else { '−' };
        format!("SL = {:.2}·f {sign} {:.2} m", l.a, l.b.abs())
    };
    format!(
        "Built-in: walking {}, running {}.",
        line(&p.walking),
        line(&p.running)
    )
}

/// The wizard offers GNSS as the distance of a calibration walk while the reported accuracy is
/// this good or better, m; its distance then counts fixes this good only.
pub const GNSS_MAX_ACCURACY_M: f64 = 10.0;

/// The band a calibration walk belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Band {
    /// Slow, normal and fast walking.
    Walking,
    /// Jogging and running.
    Running,
}

/// One walk of the wizard: its band, the pace the user was asked for, the walk and its point.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WizardWalk {
    /// Walking or running.
    pub band: Band,
    /// The pace asked for (`slow`, `normal`, `fast`, `jog`, `run`).
    pub pace: String,
    /// Distance, m.
    pub distance_m: f64,
    /// Steps counted.
    pub steps: usize,
    /// f̄ by eq. 1, Hz.
    pub f_mean_hz: f64,
    /// SL̄ = D/N by eq. 2, m.
    pub sl_mean_m: f64,
    /// Σ of the steps' unscaled fuzzy lengths, m, when the walk measured them.
    pub fuzzy_sum_m: Option<f64>,
}

/// Why a walk cannot be a calibration point.
#[derive(Debug, Clone, PartialEq)]
pub enum WalkError {
    /// The distance is not a positive number of metres.
    Distance(f64),
    /// Too few steps were counted for a mean.
    TooFewSteps(usize),
    /// The fuzzy lengths are not one finite, non-negative length per step with a positive sum
    /// (the value is their sum, or their count when it is not the steps').
    FuzzyLengths(f64),
    /// No walk of the walking band measured fuzzy lengths.
    NoFuzzyWalks,
}

impl std::fmt::Display for WalkError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WalkError::Distance(d) => write!(f, "the distance must be a positive number of metres, not {d}"),
            WalkError::TooFewSteps(n) => write!(
                f,
                "only {n} steps were counted: walk at least {MIN_STEPS} steps with the phone in the pocket"
            ),
            WalkError::FuzzyLengths(x) => write!(
                f,
                "the walk's fuzzy step lengths are unusable ({x}): they must be one positive length per step; walk it again"
            ),
            WalkError::NoFuzzyWalks => write!(
                f,
                "no walking walk measured fuzzy step lengths: the fuzzy scale needs one"
            ),
        }
    }
}

impl std::error::Error for WalkError {}

/// The fewest steps a calibration walk needs (a count off by one is then within 5 %).
pub const MIN_STEPS: usize = 20;

/// The wizard's state: the walks so far, and the profile they make.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Wizard {
    /// The walks, in the order walked.
    pub walks: Vec<WizardWalk>,
}

impl Wizard {
    /// Adds a walk from its distance and the frequencies of the steps counted.
    pub fn add(
        &mut self,
        band: Band,
        pace: &str,
        walk: &CalibrationWalk,
    ) -> Result<&WizardWalk, WalkError> {
        if !(walk.distance_m.is_finite() && walk.distance_m > 0.0) {
            return Err(WalkError::Distance(walk.distance_m));
        }
        if walk.step_freqs_hz.len() < MIN_STEPS {
            return Err(WalkError::TooFewSteps(walk.step_freqs_hz.len()));
        }
        let (f, sl) = walk
            .point()
            .ok_or(WalkError::TooFewSteps(walk.step_freqs_hz.len()))?;
        let fuzzy_sum_m = match walk.fuzzy_lengths_m.as_slice() {
            [] => None,
            l if l.len() != walk.step_freqs_hz.len() => {
                return Err(WalkError::FuzzyLengths(l.len() as f64))
            }
            l => {
                let sum: f64 = l.iter().sum();
                if l.iter().any(|x| !(x.is_finite() && *x >= 0.0))
                    || !(sum > 0.0 && sum.is_finite())
                {
                    return Err(WalkError::FuzzyLengths(sum));
                }
                Some(sum)
            }
        };
        self.walks.push(WizardWalk {
            band,
            pace: pace.to_string(),
            distance_m: walk.distance_m,
            steps: walk.step_freqs_hz.len(),
            f_mean_hz: f,
            sl_mean_m: sl,
            fuzzy_sum_m,
        });
        Ok(&self.walks[self.walks.len() - 1])
    }

    /// The profile file the walks make ([`Self::profile`] from the built-in lines, the bands'
    /// points, the fuzzy scale when walks measured one), named `name`, with the leg-pitch step
    /// length's offset `pitch_offset_m` (m per stride) when a walk gave one: the file the wizard
    /// saves and `pdr calibrate` writes.
    pub fn profile_file(&self, name: &str, pitch_offset_m: Option<f64>) -> ProfileFile {
        let (profile, _) = self.profile(&Default::default());
        ProfileFile {
            version: PROFILE_VERSION,
            name: name.to_string(),
            profile,
            walking_points: self.points(Band::Walking),
            running_points: self.points(Band::Running),
            fuzzy_scale: self.fuzzy_scale(),
            pitch_offset_m,
        }
    }

    /// The points (f̄, SL̄) of a band.
    pub fn points(&self, band: Band) -> Vec<(f64, f64)> {
        self.walks
            .iter()
            .filter(|w| w.band == band)
            .map(|w| (w.f_mean_hz, w.sl_mean_m))
            .collect()
    }

    /// The fuzzy step length's output scale the walking band's walks make ([`fit_fuzzy_scale`]
    /// over the walks that measured fuzzy lengths); `None` when none did.
    pub fn fuzzy_scale(&self) -> Option<f64> {
        let walks: Vec<(f64, f64)> = self
            .walks
            .iter()
            .filter(|w| w.band == Band::Walking)
            .filter_map(|w| Some((w.distance_m, w.fuzzy_sum_m?)))
            .collect();
        fit_fuzzy_scale(&walks).ok()
    }

    /// The profile the walks make, starting from `base` (the bands' limits and any band without
    /// walks stay as they are), and a note per band saying how its line was made:
    /// - two or more points whose fit has a positive slope: the least-squares line (Basso 2016
    ///   §II.D);
    /// - otherwise (one point, or a slope that cannot be right): quick mode, the base line's slope
    ///   through the mean point (for walking the base slope is the population's,
    ///   [`UNIVERSAL_SLOPE`] by default; Munoz Diaz 2015 §5.1).
    pub fn profile(&self, base: &StepLengthProfile) -> (StepLengthProfile, Vec<String>) {
        let mut p = base.clone();
        let mut notes = Vec::new();
        for (band, line, name) in [
            (Band::Walking, &mut p.walking, "walking"),
            (Band::Running, &mut p.running, "running"),
        ] {
            let pts = self.points(band);
            if pts.is_empty() {
                notes.push(format!(
                    "{name}: no walks, the line stays SL = {:.3}·f {:+.3} m",
                    line.a, line.b
                ));
                continue;
            }
            match fit_line(&pts).filter(|f| f.a > 0.0) {
                Some(f) => {
                    line.a = f.a;
                    line.b = f.b;
                    notes.push(format!(
                        "{name}: least-squares line through {} walks, SL = {:.3}·f {:+.3} m (R² {:.3})",
                        pts.len(),
                        f.a,
                        f.b,
                        f.r2
                    ));
                }
                None => {
                    let n = pts.len() as f64;
                    let mean = (
                        pts.iter().map(|p| p.0).sum::<f64>() / n,
                        pts.iter().map(|p| p.1).sum::<f64>() / n,
                    );
                    line.b = mean.1 - line.a * mean.0;
                    notes.push(format!(
                        "{name}: quick mode, slope {:.2} m/Hz kept, offset from {} walk(s): SL = {:.3}·f {:+.3} m",
                        line.a,
                        pts.len(),
                        line.a,
                        line.b
                    ));
                }
            }
        }
        let n = self
            .walks
            .iter()
            .filter(|w| w.band == Band::Walking && w.fuzzy_sum_m.is_some())
            .count();
        if let Some(k) = self.fuzzy_scale() {
            notes.push(format!(
                "fuzzy step length (Ibarra 2015): scale k = {k:.3}, least squares over {n} walking walk(s)"
            ));
        }
        (p, notes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_errors_and_warnings() {
        // A noisy line: the standard errors are positive and the true values within 3 of them.
        let pts = [(1.5, 0.67), (1.7, 0.695), (1.9, 0.745), (2.1, 0.79)];
        let f = fit_band(&pts);
        let (a, b) = (f.fit.as_ref().unwrap().a, f.fit.as_ref().unwrap().b);
        let (sa, sb) = f.se.unwrap();
        assert!(sa > 0.0 && sb > 0.0);
        assert!((a - 0.2).abs() < 3.0 * sa + 0.01 && (b - 0.37).abs() < 3.0 * sb + 0.02);
        assert!(f.warnings.is_empty(), "{:?}", f.warnings);
        // The bad cases.
        let two = fit_band(&[(1.5, 0.6), (2.0, 0.7)]);
        assert!(matches!(two.warnings[0], FitWarning::TooFewPoints { n: 2 }));
        let narrow = fit_band(&[(1.8, 0.6), (1.85, 0.61), (1.9, 0.62)]);
        assert!(narrow
            .warnings
            .iter()
            .any(|w| matches!(w, FitWarning::NarrowSpan { .. })));
        let down = fit_band(&[(1.5, 0.8), (1.8, 0.7), (2.1, 0.6)]);
        assert!(down
            .warnings
            .iter()
            .any(|w| matches!(w, FitWarning::NegativeSlope { .. })));
        let odd = fit_band(&[
            (1.5, 0.6),
            (1.7, 0.65),
            (1.9, 0.80),
            (2.1, 0.75),
            (2.2, 0.775),
        ]);
        assert!(
            odd.warnings
                .iter()
                .any(|w| matches!(w, FitWarning::Outlier { index: 2, .. })),
            "{:?}",
            odd.warnings
        );
        for w in odd.warnings.iter().chain(&narrow.warnings) {
            assert!(!w.message().is_empty());
        }
    }

    #[test]
    fn quick_mode_and_refinement() {
        let l = quick_line((1.9, 0.7), (1.5, 2.2));
        assert!((l.eval(1.9) - 0.7).abs() < 1e-12 && l.a == UNIVERSAL_SLOPE);
        // The filter says steps are 5 % shorter at 1.9 Hz: the whole correction moves SL(1.9)
        // to 0.665 m.
        let b = refined_offset(&l, 0.95, 1.9, 1.0);
        assert!(((Line { b, ..l }).eval(1.9) - 0.665).abs() < 1e-12);
    }

    #[test]
    fn fuzzy_scale_least_squares_and_refusals() {
        // D_i = 1.2·L_i exactly: k = 1.2; with noise, Σ D·L / Σ L².
        assert!((fit_fuzzy_scale(&[(60.0, 50.0), (36.0, 30.0)]).unwrap() - 1.2).abs() < 1e-12);
        let k = fit_fuzzy_scale(&[(10.0, 10.0), (20.0, 10.0)]).unwrap();
        assert!((k - 1.5).abs() < 1e-12);
        for bad in [
            &[][..],
            &[(10.0, 0.0)],
            &[(10.0, f64::NAN)],
            &[(f64::INFINITY, 1.0)],
        ] {
            assert!(fit_fuzzy_scale(bad).is_err(), "{bad:?}");
        }
        let walk = |l: Vec<f64>| CalibrationWalk {
            distance_m: 30.0,
            step_freqs_hz: vec![1.8; 40],
            fuzzy_lengths_m: l,
        };
        let mut w = Wizard::default();
        for l in [
            vec![0.7; 39],
            vec![0.0; 40],
            vec![f64::NAN; 40],
            vec![-0.1; 40],
        ] {
            let e = w.add(Band::Walking, "normal", &walk(l)).unwrap_err();
            assert!(matches!(e, WalkError::FuzzyLengths(_)) && !e.to_string().is_empty());
        }
        assert!(w.walks.is_empty() && w.fuzzy_scale().is_none());
        // Old callers (no lengths) fit the line only; a running walk does not count.
        w.add(Band::Walking, "normal", &walk(vec![])).unwrap();
        assert!(w.fuzzy_scale().is_none());
        w.add(Band::Running, "jog", &walk(vec![1.0; 40])).unwrap();
        assert!(w.fuzzy_scale().is_none());
        w.add(Band::Walking, "fast", &walk(vec![0.6; 40])).unwrap();
        assert!((w.fuzzy_scale().unwrap() - 1.25).abs() < 1e-12);
        assert!(w.profile(&Default::default()).1[2].contains("scale k = 1.250"));
    }

    #[test]
    fn profile_file_round_trip_and_errors() {
        let p = ProfileFile {
            version: PROFILE_VERSION,
            name: "me".into(),
            profile: StepLengthProfile::default(),
            walking_points: vec![(1.6, 0.6), (1.9, 0.68)],
            running_points: vec![],
            fuzzy_scale: None,
            pitch_offset_m: None,
        };
        assert_eq!(ProfileFile::from_json(&p.to_json().unwrap()).unwrap(), p);
        let old = p
            .to_json()
            .unwrap()
            .replace("\"version\": 1", "\"version\": 7");
        assert_eq!(
            ProfileFile::from_json(&old).unwrap_err().field,
            "profile.version"
        );
        assert!(ProfileFile::from_json("{").is_err());
    }
}
