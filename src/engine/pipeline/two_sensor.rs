//! The pipeline with two IMUs (Strozzi 2017 §4): a trunk or pocket sensor (`Record::Imu`) and a
//! foot-mounted one (`Record::Foot`). May import: the rest of `engine`.
//!
//! The first foot sample turns the pipeline to strides: the body's steps so far are dropped and
//! from then on the track is one record per stride, its length from foot mode
//! ([`crate::engine::foot`]), its heading from the hybrid stage ([`crate::engine::hybrid`],
//! [`crate::engine::PipelineConfig::hybrid`]) fed with the yaw of the trunk sensor's attitude
//! (the twist about the vertical) at every trunk sample. The body pipeline keeps running (its
//! orientation gives the trunk attitude; its motion state is shown) but emits no steps.

use super::track::stride_record;
use super::{Pipeline, PipelineConfig, StepRecord};
use crate::engine::foot::Foot;
use crate::engine::heading::yaw_aid::device_twist;
use crate::engine::hybrid::{Hybrid, HybridDiagnostics};
use crate::engine::types::{ImuSample, InputError};
use nalgebra::UnitQuaternion;

/// Foot mode and the hybrid heading, once a foot sample has arrived.
pub(super) struct TwoSensor {
    foot: Foot,
    hybrid: Hybrid,
    gap_s: f64,
    last_t: Option<f64>,
    last_stride_t: Option<f64>,
}

impl TwoSensor {
    /// The stages, with the pipeline's (validated) settings; `None` if they fail anyway.
    pub(super) fn new(cfg: &PipelineConfig) -> Option<Self> {
        Some(TwoSensor {
            foot: Foot::new(cfg.foot).ok()?,
            hybrid: Hybrid::new(cfg.hybrid).ok()?,
            gap_s: cfg.gap_s,
            last_t: None,
            last_stride_t: None,
        })
    }

    /// Feeds one sample of the foot-mounted IMU: its strides go to the hybrid stage.
    pub(super) fn push(&mut self, s: &ImuSample) {
        let mut dt = self.last_t.map_or(0.0, |l| s.t - l);
        if dt > self.gap_s {
            self.foot.gap();
            dt = 0.0;
        }
        self.last_t = Some(s.t);
        if let Some(st) = self.foot.push(s, dt) {
            self.hybrid.push_stride(&st);
        }
    }

    /// The trunk sensor's attitude at `t` (every trunk sample).
    pub(super) fn push_trunk(&mut self, t: f64, q: Option<UnitQuaternion<f64>>) {
        if let Some(yaw) = q.as_ref().and_then(device_twist) {
            self.hybrid.push_heading(t, yaw);
        }
    }

    /// The strides the hybrid stage has finished, one step record each, at foot flat, with the
    /// hybrid's heading and position.
    pub(super) fn drain(&mut self) -> Vec<StepRecord> {
        let mut out = Vec::new();
        while let Some(h) = self.hybrid.pop() {
            let prev = self.last_stride_t.replace(h.stride.t_end);
            out.push(stride_record(
                &h.stride,
                prev,
                (h.east_m, h.north_m),
                h.heading_rad,
            ));
        }
        out
    }

    /// The last sample's time, s.
    pub(super) fn last_t(&self) -> Option<f64> {
        self.last_t
    }

    /// The hybrid stage's counters.
    pub(super) fn diagnostics(&self) -> HybridDiagnostics {
        self.hybrid.diagnostics()
    }
}

/// Refuses a foot sample that is not finite, has no gyroscope or comes before `last`, s.
pub(super) fn check(s: &ImuSample, last: Option<f64>) -> Result<(), InputError> {
    s.check()?;
    if s.gyro.is_none() {
        return Err(InputError::MissingField {
            t: s.t,
            field: "gyro",
        });
    }
    match last {
        Some(last) if s.t < last => Err(InputError::TimeWentBackwards { t: s.t, last }),
        _ => Ok(()),
    }
}

impl Pipeline {
    /// Feeds one sample of the foot-mounted IMU. Returns the strides it completed.
    pub(super) fn push_foot_imu(&mut self, s: &ImuSample) -> Result<&[StepRecord], InputError> {
        let (strides, started) = match self.foot.push_foot_sensor(s, &self.cfg) {
            Ok(r) => r,
            Err(e) => return Err(self.refused(e)),
        };
        if started {
            self.forget_body_steps();
        }
        let first = self.track.len();
        for st in strides {
            self.place_stride(st);
        }
        Ok(&self.track.steps()[first..])
    }

    /// The trunk sensor's attitude at `t` (every trunk sample), while there is a foot sensor.
    pub(super) fn push_trunk_attitude(&mut self, t: f64, q: Option<UnitQuaternion<f64>>) {
        for st in self.foot.push_trunk(t, q) {
            self.place_stride(st);
        }
    }
}
