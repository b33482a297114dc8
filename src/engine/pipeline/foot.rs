//! Foot mode in the pipeline: feeding the foot stage, recognising a foot, one step record per
//! stride; and with a second, foot-mounted IMU, that sensor's strides ([`super::two_sensor`]).
//! May import: the rest of `engine`.

use super::track::stride_record;
use super::two_sensor::{check, TwoSensor};
use super::{Pipeline, PipelineConfig, StepRecord};
use crate::engine::foot::placement::{Placement, Recogniser, Verdict, DECIDE_WITHIN_S};
use crate::engine::foot::{Foot, FootDiagnostics, Stride};
use crate::engine::hybrid::HybridDiagnostics;
use crate::engine::types::{ConfigError, ImuSample, InputError};
use nalgebra::UnitQuaternion;

/// What foot mode made of one body sample ([`FootMode::push`]).
#[derive(Debug, Clone)]
pub(super) enum FootOutcome {
    /// Nothing for the track.
    None,
    /// A stride's record, in foot mode.
    Stride(StepRecord),
    /// A foot was recognised: the strides so far replace the steps.
    Recognised(Vec<StepRecord>),
}

/// Where the IMU is worn and, on a foot, its strides: the foot stage (while foot mode runs or
/// the placement is undecided), the placement resolved, the strides held while undecided; and
/// the second, foot-mounted sensor once one has sent a sample.
pub(super) struct FootMode {
    foot: Option<Foot>,
    placement: Placement,
    recogniser: Recogniser,
    pending: Vec<Stride>,
    last_stride_t: Option<f64>,
    pub(super) two: Option<TwoSensor>,
}

impl FootMode {
    /// The stage, with the pipeline's settings.
    pub(super) fn new(cfg: &PipelineConfig) -> Result<Self, ConfigError> {
        Ok(FootMode {
            foot: match cfg.placement {
                Placement::Body => None,
                _ => Some(Foot::new(cfg.foot)?),
            },
            placement: cfg.placement,
            recogniser: Recogniser::default(),
            pending: Vec::new(),
            last_stride_t: None,
            two: None,
        })
    }

    /// Feeds the foot stage one body sample, while it runs. `steps` are the body's steps so far
    /// (a stride with a step in its swing is no foot's) and `start` the first sample's time, s.
    pub(super) fn push(
        &mut self,
        s: &ImuSample,
        dt: f64,
        steps: &[StepRecord],
        start: f64,
    ) -> FootOutcome {
        // With a second, foot-mounted IMU the strides are that sensor's (`two_sensor`).
        let Some(foot) = self.foot.as_mut().filter(|_| self.two.is_none()) else {
            return FootOutcome::None;
        };
        let stride = foot.push(s, dt);
        match self.placement {
            Placement::Foot => match stride {
                Some(st) => FootOutcome::Stride(self.stride_record(st)),
                None => FootOutcome::None,
            },
            Placement::Auto => {
                let mut verdict = Verdict::Undecided;
                if let Some(st) = stride {
                    self.pending.push(st);
                    let steps_in_swing = steps
                        .iter()
                        .rev()
                        .take_while(|k| k.t >= st.t_start)
                        .filter(|k| k.t <= st.t_end)
                        .count();
                    verdict = self.recogniser.push(&st, steps_in_swing);
                }
                if verdict == Verdict::Foot {
                    // The step detector's steps so far give way to the strides.
                    self.placement = Placement::Foot;
                    let pending = std::mem::take(&mut self.pending);
                    return FootOutcome::Recognised(
                        pending
                            .into_iter()
                            .map(|st| self.stride_record(st))
                            .collect(),
                    );
                }
                if verdict == Verdict::Body || s.t - start > DECIDE_WITHIN_S {
                    self.become_body();
                }
                FootOutcome::None
            }
            Placement::Body => FootOutcome::None,
        }
    }

    /// The IMU is the body's: foot mode stops.
    pub(super) fn become_body(&mut self) {
        self.placement = Placement::Body;
        self.foot = None;
        self.pending = Vec::new();
    }

    /// One step record per stride, at foot flat: the foot's position from the zero-velocity
    /// track, the stride's length and heading.
    fn stride_record(&mut self, st: Stride) -> StepRecord {
        let prev = self.last_stride_t.replace(st.t_end);
        stride_record(&st, prev, (st.east_m, st.north_m), st.heading_rad)
    }

    /// After a gap.
    pub(super) fn gap(&mut self) {
        if let Some(f) = &mut self.foot {
            f.gap();
        }
    }

    /// Whether foot mode runs on the IMU (its strides are the track).
    pub(super) fn on_foot(&self) -> bool {
        self.placement == Placement::Foot
    }

    /// Whether a second, foot-mounted sensor gives the track.
    pub(super) fn two_sensor(&self) -> bool {
        self.two.is_some()
    }

    /// The placement: `body` or `foot`, `auto` while undecided.
    pub(super) fn placement(&self) -> Placement {
        self.placement
    }

    /// The foot stage's values, while it runs.
    pub(super) fn diagnostics(&self) -> Option<FootDiagnostics> {
        self.foot.as_ref().map(Foot::diagnostics)
    }

    /// The hybrid stage's counters, with a foot sensor.
    pub(super) fn hybrid_diagnostics(&self) -> Option<HybridDiagnostics> {
        self.two.as_ref().map(TwoSensor::diagnostics)
    }
}

impl FootMode {
    /// Feeds one sample of the foot-mounted IMU; returns the strides it completed, and whether
    /// it was the first (the body's steps so far give way to the strides then). Refused (state
    /// untouched) when not finite, without a gyroscope or earlier than the previous one.
    pub(super) fn push_foot_sensor(
        &mut self,
        s: &ImuSample,
        cfg: &PipelineConfig,
    ) -> Result<(Vec<StepRecord>, bool), InputError> {
        check(s, self.two.as_ref().and_then(TwoSensor::last_t))?;
        let first = self.two.is_none();
        if first {
            let Some(two) = TwoSensor::new(cfg) else {
                // Validated with the configuration, so this cannot happen.
                return Ok((Vec::new(), false));
            };
            // The first IMU is the trunk's: it is never taken for a foot (`placement`).
            self.become_body();
            self.two = Some(two);
        }
        let Some(two) = &mut self.two else {
            return Ok((Vec::new(), first));
        };
        two.push(s);
        Ok((two.drain(), first))
    }

    /// The trunk sensor's attitude at `t` (every trunk sample), while there is a foot sensor;
    /// returns the strides the hybrid stage finished.
    pub(super) fn push_trunk(&mut self, t: f64, q: Option<UnitQuaternion<f64>>) -> Vec<StepRecord> {
        let Some(two) = &mut self.two else {
            return Vec::new();
        };
        two.push_trunk(t, q);
        two.drain()
    }
}

impl Pipeline {
    /// Feeds foot mode one body sample. Returns true when this sample made the pipeline
    /// recognise a foot: the steps so far were replaced by the strides.
    pub(super) fn push_foot(&mut self, s: &ImuSample, dt: f64) -> bool {
        let start = self.diag.time_span.map_or(s.t, |p| p.0);
        match self.foot.push(s, dt, self.track.steps(), start) {
            FootOutcome::None => false,
            FootOutcome::Stride(st) => {
                self.place_stride(st);
                false
            }
            FootOutcome::Recognised(strides) => {
                self.forget_body_steps();
                for st in strides {
                    self.place_stride(st);
                }
                true
            }
        }
    }

    /// The step detector's steps so far, their counts and the position they reached, forgotten:
    /// strides (foot mode, or a second, foot-mounted sensor) take their place.
    pub(super) fn forget_body_steps(&mut self) {
        self.track.forget_steps();
        self.bout.forget();
    }

    /// Puts a stride's record on the track; it counts as two steps, and goes to the fusion as
    /// one step.
    pub(super) fn place_stride(&mut self, st: StepRecord) {
        self.gnss.fuse_step(&crate::engine::fusion::StepInput {
            t: st.t,
            length_m: st.length_m,
            heading_rad: st.heading_rad,
        });
        self.track.place_stride(st);
    }
}
