//! The acceleration heading's 180° from the limb the phone rides (ours,
//! [`super::HeadingConfig::limb_sign`]): the first stage of the heading's chain.
//! May import: the rest of `engine`.

use super::{arm, StepInput};
use crate::engine::carry::CarryMode;
use crate::engine::math::wrap_2pi;

/// The weight a swinging hand's forward vote keeps per step (the last 2–3 steps count).
const ARM_KEEP: f64 = 0.5;

/// A step's direction, signed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Signed {
    /// The single-step direction, rad from north.
    pub theta: Option<f64>,
    /// Whether the limb gave its sign.
    pub by_limb: bool,
}

/// What the limb said over the last steps.
#[derive(Debug, Clone, Default)]
pub struct LimbSign {
    // The swinging arm's forward vote, east and north.
    arm_vote: (f64, f64),
    // Steps in that vote.
    arm_steps: u32,
    // The way forward the limb last gave (east, north), and whether the last step's turned
    // against it.
    limb_forward: Option<(f64, f64)>,
    flipped: bool,
}

impl LimbSign {
    /// The step's `theta` (rad from north) with its 180° from the limb the phone rides when
    /// `enabled`, and whether the limb gave it:
    /// - the thigh's swing ([`StepInput::limb_forward`]) while the mode is the pocket or not yet known (a
    ///   swinging arm passes for a thigh, one axis and a leg's amplitude, but its swing says
    ///   nothing of the way forward);
    /// - in a swinging hand, the pelvis with the arm's pendulum taken out ([`arm`]), voted over
    ///   the last steps (`ARM_KEEP`): the phone is moved into the hand over seconds, and one
    ///   stride of it can point back.
    ///
    /// `keep`: while a heading is carried across a change ([`super::continuity`]), the heading
    /// last walked, whose side a limb's mode keeps until the limb says.
    pub fn push(
        &mut self,
        enabled: bool,
        step: &StepInput,
        theta: Option<f64>,
        keep: Option<f64>,
    ) -> Signed {
        self.flipped = false;
        match theta {
            Some(th) if enabled => {
                let (theta, by_limb) = self.sign(step, th, keep);
                Signed { theta, by_limb }
            }
            theta => Signed {
                theta,
                by_limb: false,
            },
        }
    }

    fn sign(&mut self, step: &StepInput, theta: f64, keep: Option<f64>) -> (Option<f64>, bool) {
        let (carry, limb_forward) = (step.carry, step.limb_forward);
        let (s, c) = libm::sincos(theta);
        let turned = |back: bool| {
            Some(if back {
                wrap_2pi(theta + std::f64::consts::PI)
            } else {
                theta
            })
        };
        if carry != Some(CarryMode::Swinging) {
            self.arm_vote = (0.0, 0.0);
            self.arm_steps = 0;
        }
        // While a heading is carried across a change (and only then: on stairs the limb can
        // stay silent for long, through turns), a limb's mode keeps the side of the heading
        // last walked until the limb says.
        let kept = || match keep {
            Some(l) => (turned(libm::cos(theta - l) < 0.0), true),
            None => (Some(theta), false),
        };
        let mut gave = |f: (f64, f64)| {
            if let Some(l) = self.limb_forward.replace(f) {
                self.flipped = l.0 * f.0 + l.1 * f.1 < 0.0;
            }
        };
        match (carry, limb_forward) {
            (None | Some(CarryMode::Pocket), Some((e, n))) => {
                gave((e, n));
                (turned(s * e + c * n < 0.0), true)
            }
            (Some(CarryMode::Pocket), None) => kept(),
            (Some(CarryMode::Swinging), _) => match arm::forwardness(step.buf, step.window, (s, c))
            {
                Some(f) => {
                    self.arm_steps = self.arm_steps.saturating_add(1);
                    let v = &mut self.arm_vote;
                    *v = (v.0 * ARM_KEEP + f * s, v.1 * ARM_KEEP + f * c);
                    let v = *v;
                    gave(v);
                    (turned(s * v.0 + c * v.1 < 0.0), true)
                }
                None => kept(),
            },
            _ => (Some(theta), false),
        }
    }

    /// Whether the last step's limb turned its way forward against the step's before.
    pub fn flipped(&self) -> bool {
        self.flipped
    }

    /// Steps in the swinging arm's vote.
    pub fn arm_steps(&self) -> u32 {
        self.arm_steps
    }
}
