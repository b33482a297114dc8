//! Which cycles' steps count: the judgement at the end of each cycle of the loop (the module's
//! "Which peaks count"), and the steps it gives late (a quiet cycle between two steps, a step
//! refused for the thigh's tilt).
//! May import: the rest of `engine`.

use super::{Pll, FIRST_SWING_MIN_DEG};
use crate::engine::detector::{Candidate, DetectorInput};

impl Pll {
    /// Whether the step of the cycle just ended counts, from the cycle's sum of squares `sq`
    /// and RMS `rms` (m/s²) and whether the phone just left the thigh; returns the step given
    /// now (a step held for the next cycle, or handed back late, goes by the state).
    pub(super) fn judge(
        &mut self,
        x: &DetectorInput,
        sq: f64,
        rms: f64,
        left_thigh: bool,
        level: bool,
    ) -> Option<Candidate> {
        let (t_peak, period_s) = self.s.pending.take()?;
        let (same_leg, same_leg_counted) = self.s.prev_cycles[1];
        // On a thigh, or in a pocket by the carrying mode before the leg pitch knows the thigh
        // (and in a back pocket, which it never does).
        let pocket = x.axis_tilt_sin.is_some() || x.pocket;
        let peak_share = if pocket {
            self.cfg.thigh_peak_share_min
        } else {
            self.cfg.peak_share_min
        };
        let stepped = rms >= self.cfg.cycle_rms_min && self.s.peak_max >= peak_share * rms;
        let moving = stepped && !left_thigh;
        let loud = rms >= self.cfg.cycle_rms_rel * x.sigma
            || (same_leg_counted && rms >= self.cfg.same_leg_rel * same_leg);
        let counts = moving && loud;
        self.follow_tilted(level);
        // The step held on the cycle before counts unless this one moved without a step's peak.
        if let Some(h) = self.s.held.take() {
            if moving || rms < self.cfg.cycle_rms_min {
                self.s.late = Some(h);
            } else {
                self.s.prev_cycles[0].1 = false;
            }
        }
        let between = self.follow_between(counts) && moving && !counts && {
            self.s.counted && pocket && rms >= self.cfg.between_steps_rel * x.sigma
        };
        let after_still = self.s.prev_cycles[0].0 < self.cfg.cycle_rms_min;
        self.s.prev_cycles = [(rms, counts), self.s.prev_cycles[0]];
        let den = self.s.cycle_cc * sq;
        let c = Candidate {
            t: t_peak,
            period_s,
            coherence: if den > 0.0 {
                self.s.cycle_xc / libm::sqrt(den)
            } else {
                0.0
            },
        };
        let swing = self
            .s
            .cycle_pitch
            .map(|(lo, hi)| hi - lo)
            .filter(|s| *s >= 0.0);
        if between {
            self.s.between = Some(c);
        }
        if left_thigh && stepped && loud && self.s.counted && x.motion.is_moving() {
            self.s.tilt_held = Some(c);
        }
        let mut out = None;
        if counts {
            if !self.s.counted {
                // The first step counted since the restart: the quiet one before it, if the
                // limb swung over it nearly as much.
                self.s.late = self
                    .s
                    .quiet
                    .zip(swing)
                    .filter(|&((_, q), s)| {
                        self.cfg.first_swing_rel > 0.0
                            && s >= FIRST_SWING_MIN_DEG
                            && q >= self.cfg.first_swing_rel * s
                    })
                    .map(|(q, _)| q.0);
            }
            // Held only while a gait is seen: the pipeline drops a step judged without one, and
            // takes a held step whenever it is given back.
            if self.s.counted
                && after_still
                && x.motion.is_moving()
                && x.axis_tilt_sin.is_some()
                && self.cfg.lone_step_confirm
            {
                self.s.held = Some(c);
            } else {
                out = Some(c);
            }
            self.s.counted = true;
        }
        self.s.quiet = swing
            .filter(|_| moving && !counts && !self.s.counted)
            .map(|s| (c, s));
        out
    }

    /// The step refused for the tilt of the cycle before ([`PllConfig::axis_tilt_max_deg`](super::PllConfig::axis_tilt_max_deg))
    /// counts, late, when this cycle is `level` again: the phone is still on the thigh.
    fn follow_tilted(&mut self, level: bool) {
        if let Some(h) = self.s.tilt_held.take().filter(|_| level) {
            self.s.late = self.s.late.or(Some(h));
            self.s.prev_cycles[0].1 = true;
        }
    }

    /// The quiet cycle before this one ([`PllConfig::between_steps_rel`](super::PllConfig::between_steps_rel)) counts, late, when
    /// this one `counts`. Returns whether the cycle before this one counted (now), which a
    /// quiet cycle needs to wait for the next.
    fn follow_between(&mut self, counts: bool) -> bool {
        if let Some(b) = self.s.between.take() {
            if counts {
                self.s.late = Some(b);
                self.s.prev_cycles[0].1 = true;
            }
        }
        self.s.prev_cycles[0].1
    }
}
