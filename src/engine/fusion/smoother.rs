//! The Rauch–Tung–Striebel smoother over the filter's stored steps (ours; none of the papers
//! has one): each step's estimate corrected backwards by the later fixes.
//! May import: the rest of `engine`.

use super::output::{FixOutcome, FusedStep};
use crate::engine::math::{symmetric, wrap_pi};
use nalgebra::{Matrix6, Vector6};

/// The filter's state: east, north (m), step-length scale, heading correction (rad), and the
/// fixes' correlated error east and north (m).
pub type State = Vector6<f64>;
/// Its covariance.
pub type Cov = Matrix6<f64>;
/// Index of the heading correction in [`State`] (an angle: differences are wrapped).
pub const BIAS: usize = 3;

/// What the smoother needs of each step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stored {
    pub x_pred: State,
    pub p_pred: Cov,
    pub f: Cov,
    pub x: State,
    pub p: Cov,
}

/// What the filter stored of every step, and the backward pass over it.
#[derive(Debug, Clone, Default)]
pub struct Smoother {
    stored: Vec<Stored>,
}

impl Smoother {
    /// Keeps a step's prediction, its Jacobian and its estimate.
    pub(super) fn push(&mut self, s: Stored) {
        self.stored.push(s);
    }

    /// The last step stored (a fix while standing updates it).
    pub(super) fn last_mut(&mut self) -> Option<&mut Stored> {
        self.stored.last_mut()
    }

    /// The Rauch–Tung–Striebel smoothed estimate at every fused step: the filter's estimates
    /// corrected backwards by the later fixes (x̂ₖˢ = x̂ₖ + Cₖ(x̂ₖ₊₁ˢ − x̂ₖ₊₁⁻),
    /// Cₖ = Pₖ Fₖ₊₁ᵀ (Pₖ₊₁⁻)⁻¹, Pₖˢ = Pₖ + Cₖ(Pₖ₊₁ˢ − Pₖ₊₁⁻)Cₖᵀ). A reset starts a new segment:
    /// nothing is carried back across it.
    ///
    /// `steps` are the filter's results, one per stored step. `consider` are the states the
    /// filter did not learn from single fixes (a Schmidt "consider" state: zero gain): the
    /// backward pass leaves them as the filter had them, or it would learn from the fixes what
    /// the filter was built not to.
    pub fn smooth(&self, steps: &[FusedStep], consider: &[usize]) -> Vec<FusedStep> {
        let n = self.stored.len();
        let mut out = steps.to_vec();
        if n == 0 {
            return out;
        }
        let mut xs = self.stored[n - 1].x;
        let mut ps = self.stored[n - 1].p;
        for k in (0..n - 1).rev() {
            let next = &self.stored[k + 1];
            let cur = &self.stored[k];
            let reset = matches!(steps[k + 1].fix, Some(FixOutcome::Reset));
            // Without the fixes' correlated error (τ = 0) its rows are zero: the
            // pseudo-inverse leaves them out.
            let inverse = next
                .p_pred
                .try_inverse()
                .or_else(|| next.p_pred.pseudo_inverse(1e-12).ok());
            match inverse.filter(|_| !reset) {
                Some(inv) => {
                    let mut c = cur.p * next.f.transpose() * inv;
                    for &i in consider {
                        c.row_mut(i).fill(0.0);
                    }
                    let mut dx = xs - next.x_pred;
                    dx[BIAS] = wrap_pi(dx[BIAS]);
                    xs = cur.x + c * dx;
                    ps = symmetric(cur.p + c * (ps - next.p_pred) * c.transpose());
                }
                None => {
                    xs = cur.x;
                    ps = cur.p;
                }
            }
            let o = &mut out[k];
            o.east_m = xs[0];
            o.north_m = xs[1];
            o.cov = [ps[(0, 0)], ps[(0, 1)], ps[(1, 1)]];
            o.scale = xs[2];
            o.bias_rad = wrap_pi(xs[BIAS]);
            o.scale_bias_sd = [ps[(2, 2)].sqrt(), ps[(3, 3)].sqrt()];
        }
        out
    }
}
