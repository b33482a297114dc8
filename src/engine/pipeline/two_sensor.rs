//! The pipeline with two IMUs (Strozzi 2017 §4): a trunk or pocket sensor (`Record::Imu`) and a
//! foot-mounted one (`Record::Foot`). May import: the rest of `engine`.
//!
//! The first foot sample turns the pipeline to strides: the body's steps so far are dropped and
//! from then on the track is one record per stride, its length from foot mode
//! ([`crate::engine::foot`]), its heading from the hybrid stage ([`crate::engine::hybrid`],
//! [`crate::engine::PipelineConfig::hybrid`]) fed with the yaw of the trunk sensor's attitude
//! (the twist about the vertical) at every trunk sample. The body pipeline keeps running (its
//! orientation gives the trunk attitude; its motion state is shown) but emits no steps.

use super::{Pipeline, StepRecord};
use crate::engine::foot::placement::Placement;
use crate::engine::foot::Foot;
use crate::engine::heading::yaw_aid::device_twist;
use crate::engine::hybrid::{Hybrid, HybridStride};
use crate::engine::types::{ImuSample, InputError};
use nalgebra::UnitQuaternion;

/// Foot mode and the hybrid heading, once a foot sample has arrived.
pub(super) struct TwoSensor {
    foot: Foot,
    hybrid: Hybrid,
    last_t: Option<f64>,
    last_stride_t: Option<f64>,
}

impl Pipeline {
    /// Feeds one sample of the foot-mounted IMU. Returns the strides it completed.
    pub(super) fn push_foot_imu(&mut self, s: &ImuSample) -> Result<&[StepRecord], InputError> {
        if let Err(e) = s.check() {
            self.diag.rejected_non_finite += 1;
            return Err(e);
        }
        if s.gyro.is_none() {
            self.diag.rejected_missing_field += 1;
            return Err(InputError::MissingField {
                t: s.t,
                field: "gyro",
            });
        }
        if let Some(last) = self.two.as_ref().and_then(|w| w.last_t) {
            if s.t < last {
                self.diag.rejected_backwards += 1;
                return Err(InputError::TimeWentBackwards { t: s.t, last });
            }
        }
        if self.two.is_none() {
            // Validated with the configuration, so neither can fail here.
            let (Ok(foot), Ok(hybrid)) = (Foot::new(self.cfg.foot), Hybrid::new(self.cfg.hybrid))
            else {
                return Ok(&[]);
            };
            // The first IMU is the trunk's: it is never taken for a foot (`placement`).
            self.placement = Placement::Body;
            self.foot = None;
            self.pending = Vec::new();
            self.two = Some(TwoSensor {
                foot,
                hybrid,
                last_t: None,
                last_stride_t: None,
            });
            self.forget_body_steps();
        }
        let first = self.steps.len();
        let gap_s = self.cfg.gap_s;
        if let Some(two) = &mut self.two {
            let mut dt = two.last_t.map_or(0.0, |l| s.t - l);
            if dt > gap_s {
                two.foot.gap();
                dt = 0.0;
            }
            two.last_t = Some(s.t);
            if let Some(st) = two.foot.push(s, dt) {
                two.hybrid.push_stride(&st);
            }
        }
        self.drain_hybrid();
        Ok(&self.steps[first..])
    }

    /// The trunk sensor's attitude at `t` (every trunk sample), while there is a foot sensor.
    pub(super) fn push_trunk_attitude(&mut self, t: f64, q: Option<UnitQuaternion<f64>>) {
        let Some(two) = &mut self.two else {
            return;
        };
        if let Some(yaw) = q.as_ref().and_then(device_twist) {
            two.hybrid.push_heading(t, yaw);
        }
        self.drain_hybrid();
    }

    fn drain_hybrid(&mut self) {
        while let Some(h) = self.two.as_mut().and_then(|w| w.hybrid.pop()) {
            self.emit_hybrid(h);
        }
    }

    /// One step record per stride, at foot flat, with the hybrid's heading and position.
    fn emit_hybrid(&mut self, h: HybridStride) {
        let Some(two) = &mut self.two else {
            return;
        };
        let prev = two.last_stride_t.replace(h.stride.t_end);
        self.record_stride(&h.stride, prev, (h.east_m, h.north_m), h.heading_rad);
    }

    /// The hybrid stage's counters, with a foot sensor.
    pub(super) fn hybrid_diagnostics(&self) -> Option<crate::engine::hybrid::HybridDiagnostics> {
        self.two.as_ref().map(|w| w.hybrid.diagnostics())
    }
}
