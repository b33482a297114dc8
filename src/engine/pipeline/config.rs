//! The pipeline's configuration: every choice, with published defaults, and its validation.
//! May import: the rest of `engine`.

use super::StepDetectorConfig;
use crate::engine::activity::ActivityConfig;
use crate::engine::back_pocket::BackPocketConfig;
use crate::engine::carry::CarryConfig;
use crate::engine::foot::placement::Placement;
use crate::engine::foot::FootConfig;
use crate::engine::fusion::FusionConfig;
use crate::engine::handling::HandlingConfig;
use crate::engine::heading::{self, HeadingConfig};
use crate::engine::hybrid::HybridConfig;
use crate::engine::leg_pitch::LegPitchConfig;
use crate::engine::magnetic::MagneticConfig;
use crate::engine::motion::MotionConfig;
use crate::engine::orientation::OrientationSource;
use crate::engine::step_length::{StepLengthModel, ThighStepLength};
use crate::engine::types::{positive, ConfigError};
use crate::engine::vertical::VerticalConfig;

/// Every choice of the pipeline, with published defaults.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PipelineConfig {
    /// Orientation source.
    pub orientation: OrientationSource,
    /// Motion detector.
    pub motion: MotionConfig,
    /// Handling: the phone turned over in the hand is not a gait.
    pub handling: HandlingConfig,
    /// The carrying mode ([`crate::engine::carry`]).
    pub carry: CarryConfig,
    /// The magnetic guard ([`crate::engine::magnetic`]): where the field is disturbed, the yaw
    /// follows the gyroscope.
    pub magnetic: MagneticConfig,
    /// Step detector.
    pub detector: StepDetectorConfig,
    /// Heading method.
    pub heading: HeadingConfig,
    /// Step-length model.
    pub step_length: StepLengthModel,
    /// The frequency line's steps on a recognised thigh in a pocket: eq. 5 of Munoz Diaz 2015
    /// ([`crate::engine::step_length::ThighStepLength`]).
    pub thigh_step_length: ThighStepLength,
    /// How far back the step detector looks when a gait is confirmed, s (the onset look-back,
    /// see the module notes). Default 3 s, the span of the autocorrelation that confirms a
    /// periodic gait ([`crate::engine::motion::Periodicity`]): the gait began within it.
    pub onset_lookback_s: f64,
    /// In the onset look-back, the gait began after the last step whose cycle is
    /// anti-correlated with the oscillator ([`crate::engine::detector::Candidate::coherence`] below this): handling the
    /// phone or a bag before walking is not in phase with the walk. Default 0, the sign of the
    /// correlation; the first cycles of a walk follow the oscillator loosely, so a higher
    /// threshold refuses them.
    pub onset_coherence_min: f64,
    /// With the phone in a pocket (the carrying mode at the onset, or its latest evaluation
    /// while it is undecided: [`crate::engine::carry::Carry::provisional`]), the gait began after the last
    /// run of this many anti-correlated cycles in a row, not after the last one. Default 2: a
    /// thigh's single cycles dip below 0 while it walks (the far leg's steps, a turn), and one
    /// dip dropped every step before it; handling the phone before walking is not in a pocket.
    /// 1 cuts at every anti-correlated cycle, as off a pocket.
    pub onset_pocket_cycles: u32,
    /// How far back the step detector looks when a gait is confirmed with the phone in a pocket
    /// (the carrying mode at the onset), s; the PLL's phase is fitted to the last
    /// [`Self::onset_lookback_s`] of it alone, and a sample of a walk that has ended since is
    /// judged against that walk's σ_z. Default 3.5 s: in a pocket the motion detector confirms
    /// some gaits more than 3 s after they start (docs/methods/basso2016.md, "Every pocket,
    /// from its onset").
    pub onset_pocket_lookback_s: f64,
    /// GNSS/PDR fusion ([`crate::engine::fusion`]); its mode `off` keeps the fixes for display
    /// only.
    pub fusion: FusionConfig,
    /// Largest interval between samples that is not a gap, s. Default 0.5 s (well above the 67 ms
    /// of 15 Hz sampling, well below a step and a half).
    pub gap_s: f64,
    /// With a second, foot-mounted IMU (`Record::Foot`): how each stride's heading is taken
    /// (Strozzi 2017 §4, [`crate::engine::hybrid`]).
    pub hybrid: HybridConfig,
    /// Where the IMU is worn: `auto` (default; a foot is recognised from the signal,
    /// [`crate::engine::foot::placement`]), `body` or `foot`.
    pub placement: Placement,
    /// Foot mode ([`crate::engine::foot`]).
    pub foot: FootConfig,
    /// The leg pitch ([`crate::engine::leg_pitch`], Munoz Diaz 2015).
    pub leg_pitch: LegPitchConfig,
    /// Which pocket: a back pocket's path lags the turns ([`crate::engine::back_pocket`]).
    pub back_pocket: BackPocketConfig,
    /// The activities from the leg pitch ([`crate::engine::activity`]).
    pub activity: ActivityConfig,
    /// The height, the stairs and the floors ([`crate::engine::vertical`]).
    pub vertical: VerticalConfig,
}

impl Default for PipelineConfig {
    fn default() -> Self {
        PipelineConfig {
            orientation: OrientationSource::default(),
            motion: MotionConfig::default(),
            handling: HandlingConfig::default(),
            carry: CarryConfig::default(),
            magnetic: MagneticConfig::default(),
            detector: StepDetectorConfig::default(),
            heading: HeadingConfig::default(),
            step_length: StepLengthModel::default(),
            thigh_step_length: ThighStepLength::default(),
            onset_lookback_s: 3.0,
            onset_coherence_min: 0.0,
            onset_pocket_cycles: 2,
            onset_pocket_lookback_s: 3.5,
            fusion: FusionConfig::default(),
            gap_s: 0.5,
            hybrid: HybridConfig::default(),
            placement: Placement::Auto,
            foot: FootConfig::default(),
            leg_pitch: LegPitchConfig::default(),
            back_pocket: BackPocketConfig::default(),
            activity: ActivityConfig::default(),
            vertical: VerticalConfig::default(),
        }
    }
}

impl PipelineConfig {
    /// A configuration with the given heading method and every other value at its default.
    pub fn with_heading(method: heading::HeadingMethod) -> Self {
        PipelineConfig {
            heading: HeadingConfig {
                method,
                ..HeadingConfig::default()
            },
            ..Self::default()
        }
    }

    /// Checks every value; the error names the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.orientation.validate()?;
        self.motion.validate()?;
        self.handling.validate()?;
        self.carry.validate()?;
        self.magnetic.validate()?;
        match &self.detector {
            StepDetectorConfig::Pll(c) => c.validate()?,
            StepDetectorConfig::Peak(c) => c.validate()?,
            StepDetectorConfig::ZeroCrossing(c) => c.validate()?,
            StepDetectorConfig::Pitch(c) => c.validate()?,
        }
        self.leg_pitch.validate()?;
        self.back_pocket.validate()?;
        self.activity.validate()?;
        self.vertical.validate()?;
        self.heading.validate()?;
        self.step_length.validate()?;
        self.thigh_step_length.validate()?;
        self.fusion.validate()?;
        self.hybrid.validate()?;
        self.foot.validate()?;
        positive("onset_lookback_s", self.onset_lookback_s)?;
        positive("onset_pocket_lookback_s", self.onset_pocket_lookback_s)?;
        if self.onset_pocket_cycles == 0 {
            return Err(ConfigError::new(
                "onset_pocket_cycles",
                "must be at least 1",
            ));
        }
        positive("gap_s", self.gap_s)
    }
}
