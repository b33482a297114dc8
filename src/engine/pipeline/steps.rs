//! From the step detector's candidates to steps: the onset look-back, and each step's heading,
//! activity, length, position and height. May import: the rest of `engine`.

use super::{Held, Pipeline, StepRecord};
use crate::engine::activity::Activity;
use crate::engine::detector::{Candidate, DetectorInput};
use crate::engine::fusion;
use crate::engine::heading::{self, NavSample, Pose, StepWindow};
use crate::engine::motion::Motion;
use crate::engine::step_length::StepLengthInput;

impl Pipeline {
    /// Restarts the step detector at time `t` on the samples of the last
    /// [`PipelineConfig::onset_lookback_s`] and returns the steps it finds in them. The PLL
    /// starts at the motion detector's cadence with its phase fitted to those samples (and
    /// gives back the steps it decides a cycle late, [`crate::engine::pll::Pll::take_late_step`]);
    /// the peak detector starts empty.
    pub(super) fn look_back(&mut self, t: f64, state: Motion) -> Vec<Candidate> {
        let since = t - self.cfg.onset_lookback_s;
        let samples: Vec<&NavSample> = self.buf.iter().filter(|x| x.t >= since).collect();
        let m = self.motion.diagnostics();
        let ups: Vec<(f64, f64)> = samples.iter().map(|s| (s.t, s.up)).collect();
        self.detector.restart(m.cadence_hz, &ups, m.mean_z);
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
                sigma: m.sigma_z,
                motion: state,
                cadence_hz: m.cadence_hz,
                pitch_deg: s.pitch,
                axis_tilt_deg: s.axis_tilt,
            });
            out.extend(self.detector.take_late_step());
            out.extend(c);
        }
        // A step held for a cycle the look-back has not reached is weighed with the rest.
        out.extend(self.detector.release_held());
        // The gait began after the last step that does not follow its rhythm.
        let first = out
            .iter()
            .rposition(|c| c.coherence < self.cfg.onset_coherence_min)
            .map_or(0, |i| i + 1);
        out.split_off(first)
    }

    /// Emits a step. `judged_at`: for a step the step detector held for a cycle
    /// ([`crate::engine::pll::Pll::take_late_step`]), the heading stage's pose when it was judged,
    /// which its heading takes, as an on-time step's takes the latest. The onset look-back's
    /// steps keep the latest (README, "The pocket's lone last jolt": giving them theirs was
    /// measured, and mixed).
    pub(super) fn emit(&mut self, c: Candidate, state: Motion, judged_at: Option<Pose>) {
        if self.two.is_some() {
            // With a foot sensor, the track is its strides (see `two_sensor`).
            return;
        }
        // Continuous with the previous step unless a cycle was skipped or a stop intervened.
        let cont = self
            .t_km1
            .filter(|&p| c.t - p > 0.0 && c.t - p < 1.6 * c.period_s);
        let period = cont.map_or(c.period_s, |p| c.t - p);
        let t_km1 = c.t - period;
        let t_km2 = match (cont, self.t_km2) {
            (Some(p1), Some(p2)) if p1 - p2 > 0.0 && p1 - p2 < 1.6 * c.period_s => p2,
            _ => t_km1 - period,
        };
        let w = StepWindow {
            t_km2,
            t_km1,
            t_k: c.t,
        };
        let has_heading = self.orientation.has_heading();
        let attitude = judged_at.map_or(self.attitude, |p| p.attitude);
        let h = self.heading.push(&heading::StepInput {
            buf: &self.buf,
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
        });
        let heading_used = h.used;
        let pocket = self.step_pocket(c.t, state);
        let freq = 1.0 / period;
        let modelled = self.step_length.push(&StepLengthInput {
            freq_hz: freq,
            buf: &self.buf,
            t0: t_km1,
            t1: c.t,
            // Eq. 5 is a line for level walking (Munoz Diaz 2015 §5).
            pitch_amplitude_deg: pocket
                .amplitude_deg
                .filter(|_| pocket.activity == Activity::Walking),
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
        let unguarded = heading_used.map(|h| self.magnetic.unguarded(h));
        if let Some(turn) = h.release {
            self.release_held(turn);
        }
        if h.held {
            self.held.push(Held::Step(step, unguarded));
        } else {
            self.place(step, unguarded);
        }
        // Counted now, held or not: the live count does not wait for the side.
        self.diag.steps += 1;
        self.t_km2 = cont;
        self.t_km1 = Some(c.t);
    }

    /// Puts a step on the track, after the last, and gives it to the fusion (with `unguarded`,
    /// its heading in the magnetometer's yaw).
    fn place(&mut self, mut step: StepRecord, unguarded: Option<f64>) {
        match step.heading_rad {
            Some(h) => {
                let (sh, ch) = libm::sincos(h);
                self.pos.0 += step.length_m * sh;
                self.pos.1 += step.length_m * ch;
                self.diag.distance_m += step.length_m;
            }
            None => self.diag.steps_without_heading += 1,
        }
        (step.east_m, step.north_m) = self.pos;
        if let Some(f) = &mut self.fusion {
            f.push_step(&fusion::StepInput {
                t: step.t,
                length_m: step.length_m,
                heading_rad: unguarded,
            });
        }
        self.steps.push(step);
    }

    /// Places the steps the heading stage held at the bout's opening
    /// ([`crate::engine::heading::opening`]), turned by 180° when `turn`, and gives the fusion
    /// the fixes that came meanwhile, in their order.
    pub(super) fn release_held(&mut self, turn: bool) {
        let back = |h: f64| crate::engine::math::wrap_2pi(h + std::f64::consts::PI);
        let back_if = |h: Option<f64>| h.map(|h| if turn { back(h) } else { h });
        for held in std::mem::take(&mut self.held) {
            match held {
                Held::Step(mut step, unguarded) => {
                    step.heading_rad = back_if(step.heading_rad);
                    step.step_heading_rad = back_if(step.step_heading_rad);
                    self.place(step, back_if(unguarded));
                }
                Held::Fix(f) => {
                    if let Some(fusion) = &mut self.fusion {
                        fusion.push_fix(&f);
                    }
                }
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
            buf: &self.buf,
            t0: step.t - 1.0 / step.freq_hz,
            t1: step.t,
            pitch_amplitude_deg: step.pitch_amplitude_deg,
        }
    }
}
