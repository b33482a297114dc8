//! The step bout: the last two step times, from which each step's window is taken, and the
//! steps (and fixes) a bout's opening holds off the track ([`crate::engine::heading::opening`]).
//! May import: the rest of `engine`.

use super::StepRecord;
use crate::engine::detector::Candidate;
use crate::engine::fusion::FixInput;
use crate::engine::heading::{Pose, StepWindow};
use crate::engine::math::wrap_2pi;

/// What waits while a bout's opening is held ([`crate::engine::heading::opening`]).
#[derive(Debug, Clone, Copy)]
pub(super) enum Held {
    /// A step, with its heading in the magnetometer's yaw for the fusion.
    Step(StepRecord, Option<f64>),
    /// A fix for the fusion: it gets steps and fixes in the order they came.
    Fix(FixInput),
}

/// A step's place in its bout ([`Bout::window`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct BoutStep {
    /// The step's boundaries t_{k−2}, t_{k−1}, t_k.
    pub window: StepWindow,
    /// The previous step's time, when this step continues it (no cycle skipped, no stop).
    pub continued: Option<f64>,
    /// The step's period T_k, s.
    pub period_s: f64,
}

/// The current bout of steps.
#[derive(Debug, Clone, Default)]
pub(super) struct Bout {
    // The ends of the last two steps of the bout, t_{k−1} and t_{k−2}, s.
    t_km1: Option<f64>,
    t_km2: Option<f64>,
    // Steps held at the bout's opening (at most `heading.opening_steps`), and the fixes for
    // the fusion that came meanwhile, in their order.
    held: Vec<Held>,
    // The heading stage's pose when the step detector began to hold a step for the next cycle.
    held_pose: Option<Pose>,
}

impl Bout {
    /// The window of step `c`: continuous with the previous step unless a cycle was skipped or
    /// a stop intervened; t_{k−1} and t_{k−2} are then the step's own period back.
    pub(super) fn window(&self, c: &Candidate) -> BoutStep {
        let cont = self
            .t_km1
            .filter(|&p| c.t - p > 0.0 && c.t - p < 1.6 * c.period_s);
        let period = cont.map_or(c.period_s, |p| c.t - p);
        let t_km1 = c.t - period;
        let t_km2 = match (cont, self.t_km2) {
            (Some(p1), Some(p2)) if p1 - p2 > 0.0 && p1 - p2 < 1.6 * c.period_s => p2,
            _ => t_km1 - period,
        };
        BoutStep {
            window: StepWindow {
                t_km2,
                t_km1,
                t_k: c.t,
            },
            continued: cont,
            period_s: period,
        }
    }

    /// The step at `t` was counted (`continued`: as [`BoutStep::continued`]).
    pub(super) fn push(&mut self, t: f64, continued: Option<f64>) {
        self.t_km2 = continued;
        self.t_km1 = Some(t);
    }

    /// Whether the onset look-back's step `c` comes after the bout's last step (by more than
    /// half its period).
    pub(super) fn is_new(&self, c: &Candidate) -> bool {
        self.t_km1.map_or(true, |l| c.t > l + 0.5 * c.period_s)
    }

    /// The bout ended: the next step starts a new one.
    pub(super) fn end(&mut self) {
        self.t_km1 = None;
        self.t_km2 = None;
    }

    /// Whether anything is held at the bout's opening.
    pub(super) fn holding(&self) -> bool {
        !self.held.is_empty()
    }

    /// Holds a step or a fix behind those held.
    pub(super) fn hold(&mut self, h: Held) {
        self.held.push(h);
    }

    /// The steps held, in order.
    pub(super) fn held_steps(&self) -> impl Iterator<Item = &StepRecord> {
        self.held.iter().filter_map(|h| match h {
            Held::Step(s, _) => Some(s),
            Held::Fix(_) => None,
        })
    }

    /// Whether the bout's opening holds a step and has had none for two strides before `t`, s:
    /// the bout has ended (the step detector gives a step up to two periods after its time).
    pub(super) fn stalled(&self, t: f64) -> bool {
        self.held_steps()
            .last()
            .is_some_and(|k| t - k.t > 4.0 / k.freq_hz)
    }

    /// Everything held, in order, the steps turned by 180° when `turn`; the opening is empty
    /// then.
    pub(super) fn release(&mut self, turn: bool) -> Vec<Held> {
        let back = |h: f64| wrap_2pi(h + std::f64::consts::PI);
        let back_if = |h: Option<f64>| h.map(|h| if turn { back(h) } else { h });
        let mut held = std::mem::take(&mut self.held);
        for h in &mut held {
            if let Held::Step(step, unguarded) = h {
                step.heading_rad = back_if(step.heading_rad);
                step.step_heading_rad = back_if(step.step_heading_rad);
                *unguarded = back_if(*unguarded);
            }
        }
        held
    }

    /// Drops what is held: strides take the steps' place.
    pub(super) fn forget(&mut self) {
        self.held.clear();
    }

    /// Follows the step detector: `holding`, whether it holds a step for the next cycle, at
    /// heading `pose`; `late`, whether it gave one back now. Returns the pose a late step was
    /// held at, which its heading takes.
    pub(super) fn follow_detector(
        &mut self,
        late: bool,
        holding: bool,
        pose: impl FnOnce() -> Pose,
    ) -> Option<Pose> {
        let late_pose = if late { self.held_pose.take() } else { None };
        if holding != self.held_pose.is_some() {
            self.held_pose = holding.then(pose);
        }
        late_pose
    }
}
