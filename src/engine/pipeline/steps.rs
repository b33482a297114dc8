//! From the step detector's candidates to steps: the onset look-back, and each step's heading,
//! activity, length, position and height. May import: the rest of `engine`.

use super::bout::{BoutStep, Held};
use super::{Pipeline, StepRecord};
use crate::engine::activity::Activity;
use crate::engine::back_pocket::BackPocketInput;
use crate::engine::carry::CarryMode;
use crate::engine::detector::{Candidate, DetectorInput};
use crate::engine::fusion;
use crate::engine::heading::{self, NavSample, Pose};
use crate::engine::motion::Motion;
use crate::engine::step_length::StepLengthInput;

impl Pipeline {
    /// Restarts the step detector at time `t` on the samples of the last
    /// [`crate::engine::PipelineConfig::onset_lookback_s`] (in a pocket
    /// [`crate::engine::PipelineConfig::onset_pocket_lookback_s`]) and returns the steps it finds in them. The PLL
    /// starts at the motion detector's cadence with its phase fitted to those samples (and
    /// gives back the steps it decides a cycle late, [`crate::engine::pll::Pll::take_late_step`]);
    /// the peak detector starts empty.
    pub(super) fn look_back(&mut self, t: f64, state: Motion) -> Vec<Candidate> {
        // The gait is confirmed about 3 s into a walk, when the carrying mode may not be decided
        // yet (its vote takes the first two evaluations, over windows still holding the
        // standing or the handling before): its latest evaluation, over the walk, stands in.
        let pocket = self.carry.provisional() == Some(CarryMode::Pocket);
        let span = if pocket {
            self.cfg.onset_pocket_lookback_s
        } else {
            self.cfg.onset_lookback_s
        };
        let since = t - span;
        let samples: Vec<&NavSample> = self.window.buf.iter().filter(|x| x.t >= since).collect();
        let m = self.motion.diagnostics();
        let ups: Vec<(f64, f64)> = samples.iter().map(|s| (s.t, s.up)).collect();
        // The phase is fitted to the last `onset_lookback_s` alone: a longer look-back reaches
        // the standing or handling before the gait, whose phase is not the gait's.
        let fit_from = t - self.cfg.onset_lookback_s.min(span);
        self.detector
            .restart(m.cadence_hz, &ups, m.mean_z, fit_from);
        let mut out = Vec::new();
        let mut last = None;
        for s in samples {
            let dt = last.map_or(0.0, |l| s.t - l);
            last = Some(s.t);
            let c = self.detector.push(&DetectorInput {
                t: s.t,
                dt,
                up: s.up,
                mean: m.mean_z,
                // In a pocket, each sample is judged against the larger of the σ_z now and when
                // it came, never more leniently than the live loop judged it: a walk's quiet
                // settling cycle, replayed by a gait confirmed soon after the stop, keeps the
                // walk's σ_z, not the stop's smaller one.
                sigma: if pocket {
                    m.sigma_z.max(s.sigma_z)
                } else {
                    m.sigma_z
                },
                motion: state,
                cadence_hz: m.cadence_hz,
                pitch_deg: s.pitch,
                axis_tilt_sin: s.axis_tilt_sin,
                pocket,
            });
            out.extend(self.detector.take_late_step());
            out.extend(c);
        }
        // A step held for a cycle the look-back has not reached is weighed with the rest.
        out.extend(self.detector.release_held());
        // The gait began after the last step that does not follow its rhythm: in a pocket, after
        // the last run of `onset_pocket_cycles` such steps.
        let run = if pocket {
            self.cfg.onset_pocket_cycles
        } else {
            1
        };
        let first = gait_start(&out, self.cfg.onset_coherence_min, run as usize);
        out.split_off(first)
    }

    /// Emits a step. `judged_at`: for a step the step detector held for a cycle
    /// ([`crate::engine::pll::Pll::take_late_step`]), the heading stage's pose when it was judged,
    /// which its heading takes, as an on-time step's takes the latest. The onset look-back's
    /// steps keep the latest (docs/methods/first-and-last-steps.md, "The pocket's lone last jolt":
    /// giving them theirs was measured, and mixed).
    pub(super) fn emit(&mut self, c: Candidate, state: Motion, judged_at: Option<Pose>) {
        if self.foot.two_sensor() {
            // With a foot sensor, the track is its strides (see `two_sensor`).
            return;
        }
        let BoutStep {
            window: w,
            continued: cont,
            period_s: period,
        } = self.bout.window(&c);
        let has_heading = self.orientation.has_heading();
        let attitude = judged_at.map_or(self.attitude, |p| p.attitude);
        let behind_hip = self.pocket.side.push(&BackPocketInput {
            share: self.pocket.leg.swing_share(),
            pocket: self.carry.mode() == Some(CarryMode::Pocket),
            walking: state == Motion::Walking,
        });
        let h = self.heading.push(&heading::StepInput {
            buf: &self.window.buf,
            window: w,
            continued: cont.is_some(),
            has_heading,
            carry: self.carry.mode(),
            limb_forward: self.pocket.leg.forward_axis().zip(attitude).map(|(a, q)| {
                // ẑ × L, L the forward swing axis in the world (east, north, up).
                let l = q * a;
                (-l.y, l.x)
            }),
            judged_at,
            behind_hip,
        });
        let heading_used = h.used;
        let pocket = self.step_pocket(c.t, state);
        let freq = 1.0 / period;
        let modelled = self.step_length.push(&StepLengthInput {
            freq_hz: freq,
            buf: &self.window.buf,
            t0: w.t_km1,
            t1: c.t,
            // Eq. 5 is a line for level walking (Munoz Diaz 2015 §5).
            pitch_amplitude_deg: pocket
                .amplitude_deg
                .filter(|_| pocket.activity == Activity::Walking),
            carry: self.carry.mode(),
        });
        // Stairs: a tread per footfall, whatever the model (the line is for level ground).
        let length = match pocket.activity {
            Activity::Upstairs | Activity::Downstairs => self.cfg.vertical.stair_tread_m,
            _ => modelled,
        };
        let step = StepRecord {
            t: c.t,
            east_m: 0.0,
            north_m: 0.0,
            heading_rad: heading_used,
            step_heading_rad: h.single,
            length_m: length,
            freq_hz: freq,
            motion: if state.is_moving() {
                state
            } else {
                Motion::Walking
            },
            activity: pocket.activity,
            up_m: self.pocket.vertical.up_m(),
            floor: self.pocket.vertical.floor(),
            pitch_amplitude_deg: pocket.amplitude_deg,
            carry: self.carry.mode(),
            gyro_heading: self.magnetic.diagnostics().disturbed,
        };
        // The fusion keeps the magnetometer's yaw: its heading correction is one constant,
        // which a yaw held on the gyroscope does not have.
        let unguarded = heading_used.map(|u| self.magnetic.unguarded(u, h.guard_then));
        if let Some(turn) = h.release {
            self.release_held(turn);
        }
        if h.held {
            self.bout.hold(Held::Step(step, unguarded));
        } else {
            self.place(step, unguarded);
        }
        // Counted now, held or not: the live count does not wait for the side.
        self.track.count_step();
        self.bout.push(c.t, cont);
    }

    /// Puts a step on the track, after the last, and gives it to the fusion (with `unguarded`,
    /// its heading in the magnetometer's yaw).
    fn place(&mut self, step: StepRecord, unguarded: Option<f64>) {
        self.gnss.fuse_step(&fusion::StepInput {
            t: step.t,
            length_m: step.length_m,
            heading_rad: unguarded,
        });
        self.track.place(step);
    }

    /// Places the steps the heading stage held at the bout's opening
    /// ([`crate::engine::heading::opening`]), turned by 180° when `turn`, and gives the fusion
    /// the fixes that came meanwhile, in their order.
    pub(super) fn release_held(&mut self, turn: bool) {
        for held in self.bout.release(turn) {
            match held {
                Held::Step(step, unguarded) => self.place(step, unguarded),
                Held::Fix(f) => self.gnss.fuse_fix(&f),
            }
        }
    }

    /// Releases the steps held at a bout's opening as the pelvis voted, when the bout ended
    /// without a step that says their side (a stop, a gap, the end of the input).
    pub(super) fn release_opening(&mut self) {
        if let Some(turn) = self.heading.release_held() {
            self.release_held(turn);
        }
    }

    /// What the step-length stage was given for `step`, one of this pipeline's steps just
    /// returned by [`push`](Self::push) (before the next sample moves the buffer): its
    /// frequency, the recent samples and the step's span, T_k = 1/f_k back from its time. Lets a
    /// caller ask another step-length model about the same step (the calibration wizard's fuzzy
    /// lengths) without a second pipeline.
    pub fn step_length_input(&self, step: &StepRecord) -> StepLengthInput<'_> {
        StepLengthInput {
            freq_hz: step.freq_hz,
            buf: &self.window.buf,
            t0: step.t - 1.0 / step.freq_hz,
            t1: step.t,
            pitch_amplitude_deg: step.pitch_amplitude_deg,
            carry: step.carry,
        }
    }
}

/// Where the gait began among the look-back's candidates `c`: after the last run of `run`
/// candidates in a row whose coherence is below `min` (0 when there is none).
fn gait_start(c: &[Candidate], min: f64, run: usize) -> usize {
    let mut in_row = 0;
    let mut start = 0;
    for (i, x) in c.iter().enumerate() {
        in_row = if x.coherence < min { in_row + 1 } else { 0 };
        if in_row >= run {
            start = i + 1;
        }
    }
    start
}

#[cfg(test)]
mod tests {
    use super::gait_start;
    use crate::engine::detector::Candidate;

    fn cands(coherences: &[f64]) -> Vec<Candidate> {
        coherences
            .iter()
            .enumerate()
            .map(|(i, &coherence)| Candidate {
                t: i as f64 * 0.5,
                period_s: 0.5,
                coherence,
            })
            .collect()
    }

    #[test]
    fn one_anti_correlated_cycle_cuts_before_it_when_one_is_enough() {
        let c = cands(&[0.4, -0.2, 0.5, 0.6]);
        assert_eq!(gait_start(&c, 0.0, 1), 2);
        assert_eq!(gait_start(&c, 0.0, 2), 0);
    }

    #[test]
    fn a_run_cuts_after_its_last_cycle() {
        let c = cands(&[-0.3, -0.1, 0.5, -0.4, 0.7, 0.8]);
        assert_eq!(gait_start(&c, 0.0, 2), 2);
        assert_eq!(gait_start(&c, 0.0, 1), 4);
        assert_eq!(gait_start(&c, 0.0, 3), 0);
        assert_eq!(gait_start(&[], 0.0, 2), 0);
    }
}
