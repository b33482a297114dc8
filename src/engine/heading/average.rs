//! The two-step average of the single-step directions (A-HE, Basso 2016 Algorithm 1 step e;
//! Basso 2021 end of §2.2.3). May import: the rest of `engine`.

use crate::engine::math::circular_mean2;

/// The last single-step direction, which the next is averaged with.
#[derive(Debug, Clone, Default)]
pub struct Average {
    /// The last step's single direction, rad from north.
    pub last: Option<f64>,
    // Whether the limb gave that direction's sign.
    last_by_limb: bool,
}

impl Average {
    /// The circular mean of `theta` and the last direction, rad from north, and whether it is
    /// one (`enabled` and the step `continued` the last); `limb_mode`: the carrying mode takes
    /// its sign from a limb, when a direction the limb signed (`by_limb`) is not averaged with
    /// one it did not sign, nor one the limb turned against the last (`flipped`): they may
    /// point opposite ways.
    pub fn push(
        &self,
        enabled: bool,
        theta: Option<f64>,
        continued: bool,
        (limb_mode, by_limb, flipped): (bool, bool, bool),
    ) -> (Option<f64>, bool) {
        let comparable = !limb_mode || (by_limb == self.last_by_limb && !flipped);
        match (theta, self.last) {
            (Some(th), Some(prev)) if enabled && continued && comparable => {
                (Some(circular_mean2(prev, th)), true)
            }
            (th, _) => (th, false),
        }
    }

    /// The step's own direction, once known, becomes the last.
    pub fn remember(&mut self, theta: Option<f64>, by_limb: bool) {
        if theta.is_some() {
            self.last = theta;
            self.last_by_limb = by_limb;
        }
    }
}
