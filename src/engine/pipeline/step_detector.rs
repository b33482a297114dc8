//! The step detector the configuration chooses, and the one enum the pipeline runs it through:
//! the PLL ([`crate::engine::pll`]), the peak counter ([`crate::engine::peak`]) and the zero
//! crossings with areas ([`crate::engine::zero_crossing`]) share one contract
//! ([`crate::engine::detector`]).
//! May import: the rest of `engine`.

use crate::engine::detector::{Candidate, DetectorInput};
use crate::engine::peak::{PeakConfig, PeakDetector};
use crate::engine::pitch_detector::{PitchDetector, PitchDetectorConfig};
use crate::engine::pll::{Pll, PllConfig};
use crate::engine::zero_crossing::{ZeroCrossing, ZeroCrossingConfig};

/// Which step detector to use.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum StepDetectorConfig {
    /// Basso's phase-locked loop.
    Pll(PllConfig),
    /// The comparison peak detector.
    Peak(PeakConfig),
    /// Ibarra 2015's zero crossings with the area under each lobe.
    ZeroCrossing(ZeroCrossingConfig),
    /// Munoz Diaz 2015's maxima of the leg pitch. Needs a gyroscope: on a log without one the
    /// pipeline runs the PLL instead and says so ([`crate::engine::Diagnostics::detector_fallback`]).
    Pitch(PitchDetectorConfig),
}

impl Default for StepDetectorConfig {
    fn default() -> Self {
        StepDetectorConfig::Pll(PllConfig::default())
    }
}

/// The step detector the configuration chose. One per pipeline, used on every sample: kept
/// inline rather than boxed.
#[allow(clippy::large_enum_variant)]
pub(super) enum Detector {
    Pll(Pll),
    Peak(PeakDetector),
    ZeroCrossing(ZeroCrossing),
    Pitch(PitchDetector),
}

impl Detector {
    pub(super) fn new(cfg: StepDetectorConfig) -> Self {
        match cfg {
            StepDetectorConfig::Pll(c) => Detector::Pll(Pll::new(c)),
            StepDetectorConfig::Peak(c) => Detector::Peak(PeakDetector::new(c)),
            StepDetectorConfig::ZeroCrossing(c) => Detector::ZeroCrossing(ZeroCrossing::new(c)),
            StepDetectorConfig::Pitch(c) => Detector::Pitch(PitchDetector::new(c)),
        }
    }

    pub(super) fn push(&mut self, x: &DetectorInput) -> Option<Candidate> {
        match self {
            Detector::Pll(p) => p.push(x),
            Detector::Peak(p) => p.push(x),
            Detector::ZeroCrossing(z) => z.push(x),
            Detector::Pitch(p) => p.push(x),
        }
    }

    /// The PLL's step decided only with a later cycle, earlier than the step its push gave
    /// ([`Pll::take_late_step`]); the other detectors have none.
    pub(super) fn take_late_step(&mut self) -> Option<Candidate> {
        match self {
            Detector::Pll(p) => p.take_late_step(),
            _ => None,
        }
    }

    /// Whether the PLL holds a step for the next cycle's judgement ([`Pll::holding`]).
    pub(super) fn holding(&self) -> bool {
        matches!(self, Detector::Pll(p) if p.holding())
    }

    /// The PLL's step held for the next cycle, given up undecided ([`Pll::release_held`]); the
    /// other detectors hold none.
    pub(super) fn release_held(&mut self) -> Option<Candidate> {
        match self {
            Detector::Pll(p) => p.release_held(),
            _ => None,
        }
    }

    /// Starts afresh on a gait already under way: the PLL at the motion detector's cadence with
    /// its phase fitted to the `samples` (time, vertical acceleration) from `fit_from` s on,
    /// about their mean `mean`; the peak detector empty.
    pub(super) fn restart(
        &mut self,
        cadence_hz: Option<f64>,
        samples: &[(f64, f64)],
        mean: f64,
        fit_from: f64,
    ) {
        match self {
            Detector::Pll(p) => {
                p.restart();
                if let Some(f) = cadence_hz {
                    p.start_on(f, samples, mean, fit_from);
                }
            }
            Detector::Peak(p) => p.restart(),
            Detector::ZeroCrossing(z) => z.restart(cadence_hz),
            Detector::Pitch(p) => p.restart(),
        }
    }

    /// After a gap: the PLL's oscillator restarts at a peak; the peak detector forgets the
    /// signal.
    pub(super) fn gap(&mut self) {
        match self {
            Detector::Pll(p) => p.reset_phase(),
            Detector::Peak(p) => p.reset(),
            Detector::ZeroCrossing(z) => z.reset(),
            Detector::Pitch(p) => p.restart(),
        }
    }
}
