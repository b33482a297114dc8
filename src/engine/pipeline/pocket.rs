//! The pocket's own signal in the pipeline (Munoz Diaz 2015): the leg pitch of each sample,
//! the strides it shows, each stride's activity, the stairs' step length and the height with
//! the barometer. May import: the rest of `engine`.
//!
//! The leg pitch runs whenever the samples have a gyroscope and an attitude and a single swing
//! axis dominates; its strides count only once they show a thigh's swing
//! ([`LegPitch::push_stride`]: a phone in a trouser pocket, not in the hand). Strides come from
//! the pitch step detector: the configured one (`detector.kind=pitch`), or a second one beside
//! the configured detector, whose strides then give the activity, the height and the length of
//! that detector's steps.
//! Without a leg pitch the activity is the motion state's, a step's height change is unknown
//! (the barometer alone moves the height) and the step length is the configured model's.

use super::step_detector::{Detector, StepDetectorConfig};
use super::{Pipeline, PipelineConfig};
use crate::engine::activity::{Activity, ActivityClassifier};
use crate::engine::back_pocket::BackPocket;
use crate::engine::carry::CarryMode;
use crate::engine::detector::DetectorInput;
use crate::engine::leg_pitch::{LegPitch, LegPitchInput};
use crate::engine::motion::Motion;
use crate::engine::pitch_detector::{PitchDetector, PitchDetectorConfig, PitchStride};
use crate::engine::types::{ImuSample, InputError, PressureSample};
use crate::engine::vertical::{StepHeight, Vertical};

/// A stride's classification, kept for the steps that fall in it.
#[derive(Debug, Clone, Copy)]
pub(super) struct ClassifiedStride {
    stride: PitchStride,
    activity: Activity,
    thigh: bool,
}

/// What the pocket stages say about one step.
#[derive(Debug, Clone, Copy)]
pub(super) struct StepPocket {
    /// The step's activity.
    pub activity: Activity,
    /// Its stride's Δθ, degrees, when the leg pitch is known.
    pub amplitude_deg: Option<f64>,
}

/// The pocket stages of a pipeline.
pub(super) struct Pocket {
    pub leg: LegPitch,
    /// Which pocket: the back one's path lags the turns.
    pub side: BackPocket,
    /// Strides beside a detector that is not the pitch detector.
    pub strides: Option<PitchDetector>,
    pub activity: ActivityClassifier,
    pub vertical: Vertical,
    pub last: Option<ClassifiedStride>,
    /// The height after each of the last steps without a thigh, m.
    pub recent: std::collections::VecDeque<f64>,
    /// The leg pitch's sign at the last stride.
    pub sign: Option<f64>,
    /// The raw angle of the last sample ([`LegPitch::push`]).
    pub pitch: Option<f64>,
    /// The last barometer reading's time, s.
    last_pressure_t: Option<f64>,
    /// Barometer readings accepted.
    pub pressure_samples: u64,
}

impl Pocket {
    /// The stages, with the pipeline's settings.
    pub(super) fn new(cfg: &PipelineConfig) -> Self {
        Pocket {
            leg: LegPitch::new(cfg.leg_pitch),
            side: BackPocket::new(cfg.back_pocket),
            strides: (!matches!(cfg.detector, StepDetectorConfig::Pitch(_)))
                .then(|| PitchDetector::new(PitchDetectorConfig::default())),
            activity: ActivityClassifier::new(cfg.activity),
            vertical: Vertical::new(cfg.vertical),
            last: None,
            recent: std::collections::VecDeque::with_capacity(BARO_STAIR_STEPS),
            sign: None,
            pitch: None,
            last_pressure_t: None,
            pressure_samples: 0,
        }
    }

    /// Feeds one barometer reading to the height. Refused (state untouched) when out of range
    /// or earlier than the previous reading.
    pub(super) fn push_pressure(&mut self, p: &PressureSample) -> Result<(), InputError> {
        p.check()?;
        if let Some(last) = self.last_pressure_t.filter(|&last| p.t < last) {
            return Err(InputError::TimeWentBackwards { t: p.t, last });
        }
        self.last_pressure_t = Some(p.t);
        self.pressure_samples += 1;
        self.vertical.push_pressure(p.t, p.hpa);
        Ok(())
    }
}

/// Steps over which the barometric height's change tells stairs from level without a thigh.
const BARO_STAIR_STEPS: usize = 4;

/// A climb or descent of this much per step, m, is stairs: half a stair's 15–20 cm rise per
/// footfall, far above a ramp's (a 1:12 ramp rises 6 cm per 0.7 m step) and the barometer's
/// noise over four steps (about 0.1 m, 2.5 cm per step).
const BARO_STAIR_M_PER_STEP: f64 = 0.08;

/// Longest time after a stride's maximum that a step still belongs to it, s.
const STRIDE_HOLD_S: f64 = 1.5;

impl Pipeline {
    /// The leg pitch of sample `s` (its attitude just computed), and the stride finder beside
    /// the configured detector.
    pub(super) fn pocket_sample(
        &mut self,
        s: &ImuSample,
        dt: f64,
        state: Motion,
        x: &DetectorInput,
    ) {
        let p = &mut self.pocket;
        p.pitch = p.leg.push(&LegPitchInput {
            dt,
            gyro: s.gyro,
            attitude: self.attitude,
            moving: state.is_moving(),
        });
        if let Some(d) = &mut p.strides {
            d.push(&DetectorInput {
                pitch_deg: p.pitch,
                ..*x
            });
        }
        if !state.is_moving() {
            let signed = p.pitch.map(|r| p.leg.signed(r));
            p.activity.push_still(signed);
        }
    }

    /// The strides the stride finder found since the last one classified, oldest first; before
    /// any was, the newest alone (the leg pitch's sign is voted from the walk's strides, not
    /// from the standing and handling before the first step).
    fn new_strides(&self) -> Vec<PitchStride> {
        let d = match (&self.detector, &self.pocket.strides) {
            (Detector::Pitch(d), _) => d,
            (_, Some(d)) => d,
            _ => return Vec::new(),
        };
        match self.pocket.last {
            Some(l) => d.strides_after(Some(l.stride.t_max)).copied().collect(),
            None => d.last_stride().into_iter().collect(),
        }
    }

    /// Classifies stride `st` (Munoz Diaz 2015 §4.3), gives its height change to the height
    /// stage and its mean attitude, if level, to the leg pitch's reference.
    fn classify_stride(&mut self, st: PitchStride, state: Motion) {
        let p = &mut self.pocket;
        // Which strides vote on the thigh's sign. Not a swinging hand's: it passes for a
        // thigh (one axis, a leg's amplitude) but its swing is symmetric, and its votes,
        // near zero, diluted the thigh's below clearness for 12 s after the phone was
        // pocketed. Nor, while the mode says a hand, the ear or a bag, a stride that
        // swings less than a thigh: a bag's did the same after a move into the pocket.
        // (Votes only in the pocket or before a mode: the pocket walks' own flickers
        // into the bag or the ear then cost them 12.9 → 13.6°.)
        let votes = match self.carry.mode() {
            Some(CarryMode::Swinging) => false,
            None | Some(CarryMode::Pocket) => true,
            Some(_) => st.amplitude_deg >= self.cfg.leg_pitch.thigh_min_amplitude_deg,
        };
        let thigh = p.leg.push_stride(&st, votes);
        let sign = p.leg.sign();
        if p.sign.replace(sign).is_some_and(|s| s != sign) {
            p.activity.reset();
        }
        let activity = if !thigh {
            // Not a thigh's swing (a phone in the hand): the motion state's word.
            p.activity.push_step(state == Motion::Running)
        } else if state == Motion::Running {
            p.activity.push_step(true)
        } else {
            let (max, min) = p.leg.signed_extremes(st.max_deg, st.min_deg);
            p.activity.push_stride(max, min, st.amplitude_deg)
        };
        if activity == Activity::Walking {
            p.leg.commit_level_stride();
        } else {
            p.leg.skip_stride();
        }
        if thigh {
            let dz = self
                .cfg
                .vertical
                .stride_height_m(activity, st.amplitude_deg);
            p.vertical.push_step(StepHeight::Pitch(dz));
        }
        p.last = Some(ClassifiedStride {
            stride: st,
            activity,
            thigh,
        });
    }

    /// The activity and stride amplitude of a step at `t`: every stride found since the last
    /// step is classified ([`Self::classify_stride`]), not only the newest: the steps of an
    /// onset's look-back come at once, and each stride they span changes the height.
    pub(super) fn step_pocket(&mut self, t: f64, state: Motion) -> StepPocket {
        for st in self.new_strides() {
            self.classify_stride(st, state);
        }
        match self
            .pocket
            .last
            .filter(|l| l.thigh && (t - l.stride.t_max).abs() <= STRIDE_HOLD_S)
        {
            Some(l) => StepPocket {
                activity: l.activity,
                amplitude_deg: Some(l.stride.amplitude_deg),
            },
            None => {
                let p = &mut self.pocket;
                let z = p.vertical.push_step(StepHeight::Unknown);
                // Without a thigh, the barometer alone tells stairs: a climb of a stair's
                // height per step over the last steps.
                if p.recent.len() == BARO_STAIR_STEPS {
                    p.recent.pop_front();
                }
                p.recent.push_back(z);
                let per_step = (z - p.recent[0]) / BARO_STAIR_STEPS as f64;
                let activity = if !p.vertical.has_barometer() || state == Motion::Running {
                    p.activity.push_step(state == Motion::Running)
                } else if per_step > BARO_STAIR_M_PER_STEP {
                    Activity::Upstairs
                } else if per_step < -BARO_STAIR_M_PER_STEP {
                    Activity::Downstairs
                } else {
                    p.activity.push_step(false)
                };
                StepPocket {
                    activity,
                    amplitude_deg: None,
                }
            }
        }
    }
}
