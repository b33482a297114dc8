//! The pipeline in foot mode: feeding the foot stage, recognising a foot, one step record per
//! stride. May import: the rest of `engine`.

use super::{Pipeline, StepRecord};
use crate::engine::activity::Activity;
use crate::engine::foot::placement::{Placement, Verdict, DECIDE_WITHIN_S};
use crate::engine::foot::Stride;
use crate::engine::fusion;
use crate::engine::motion::Motion;
use crate::engine::types::ImuSample;

/// The share of a gait cycle spent in swing (about 40 %, Perry's gait analysis), giving the
/// stride frequency of the first stride of a walk from its swing alone.
const SWING_SHARE: f64 = 0.4;

impl Pipeline {
    /// Feeds the foot stage, while it runs. Returns true when this sample made the pipeline
    /// recognise a foot: the steps so far were replaced by the strides.
    pub(super) fn push_foot(&mut self, s: &ImuSample, dt: f64) -> bool {
        // With a second, foot-mounted IMU the strides are that sensor's (`two_sensor`).
        let Some(foot) = self.foot.as_mut().filter(|_| self.two.is_none()) else {
            return false;
        };
        let stride = foot.push(s, dt);
        match self.placement {
            Placement::Foot => {
                if let Some(st) = stride {
                    self.emit_stride(st);
                }
                false
            }
            Placement::Auto => {
                let mut verdict = Verdict::Undecided;
                if let Some(st) = stride {
                    self.pending.push(st);
                    let steps_in_swing = self
                        .steps
                        .iter()
                        .rev()
                        .take_while(|k| k.t >= st.t_start)
                        .filter(|k| k.t <= st.t_end)
                        .count();
                    verdict = self.recogniser.push(&st, steps_in_swing);
                }
                let start = self.diag.time_span.map_or(s.t, |p| p.0);
                if verdict == Verdict::Foot {
                    self.become_foot();
                    return true;
                }
                if verdict == Verdict::Body || s.t - start > DECIDE_WITHIN_S {
                    self.placement = Placement::Body;
                    self.foot = None;
                    self.pending = Vec::new();
                }
                false
            }
            Placement::Body => false,
        }
    }

    /// The step detector's steps so far, their counts and the position they reached, forgotten:
    /// strides (foot mode, or a second, foot-mounted sensor) take their place.
    pub(super) fn forget_body_steps(&mut self) {
        self.steps.clear();
        self.held.clear();
        self.diag.steps = 0;
        self.diag.onset_steps = 0;
        self.diag.steps_without_heading = 0;
        self.diag.distance_m = 0.0;
        self.pos = (0.0, 0.0);
    }

    /// Foot recognised: the step detector's steps so far give way to the strides.
    fn become_foot(&mut self) {
        self.placement = Placement::Foot;
        self.forget_body_steps();
        for st in std::mem::take(&mut self.pending) {
            self.emit_stride(st);
        }
    }

    /// One step record per stride, at foot flat: the foot's position from the zero-velocity
    /// track, the stride's length and heading; it counts as two steps.
    fn emit_stride(&mut self, st: Stride) {
        let prev = self.last_stride_t.replace(st.t_end);
        self.record_stride(&st, prev, (st.east_m, st.north_m), st.heading_rad);
    }

    /// The step record of a stride that ends at foot flat, placed at `(east_m, north_m)` with
    /// `heading_rad` (foot mode's own, or the hybrid's); `prev_t` is the previous stride's foot
    /// flat. It counts as two steps, and goes to the fusion as one step.
    pub(super) fn record_stride(
        &mut self,
        st: &Stride,
        prev_t: Option<f64>,
        (east_m, north_m): (f64, f64),
        heading_rad: f64,
    ) {
        let period = prev_t
            .map(|l| st.t_end - l)
            .filter(|&p| p > 0.0 && p <= 3.0)
            .unwrap_or((st.t_end - st.t_start) / SWING_SHARE);
        self.pos = (east_m, north_m);
        self.steps.push(StepRecord {
            t: st.t_end,
            east_m,
            north_m,
            heading_rad: Some(heading_rad),
            step_heading_rad: Some(st.heading_rad),
            length_m: st.length_m,
            freq_hz: if period > 0.0 { 1.0 / period } else { 0.0 },
            motion: Motion::Walking,
            activity: Activity::Walking,
            up_m: 0.0,
            floor: 0,
            pitch_amplitude_deg: None,
            carry: None,
            gyro_heading: false,
        });
        if let Some(f) = &mut self.fusion {
            f.push_step(&fusion::StepInput {
                t: st.t_end,
                length_m: st.length_m,
                heading_rad: Some(heading_rad),
            });
        }
        self.diag.steps += 2;
        self.diag.strides += 1;
        self.diag.distance_m += st.length_m;
    }
}
