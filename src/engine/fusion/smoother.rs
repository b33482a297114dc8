//! The Rauch–Tung–Striebel smoother over the filter's stored steps (ours; none of the papers
//! has one): each step's estimate corrected backwards by the later fixes.
//! May import: the rest of `engine`.

use super::output::{FixOutcome, FusedStep};
use crate::engine::math::{symmetric, wrap_pi};
use nalgebra::{Matrix4, Vector4};

/// What the smoother needs of each step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stored {
    pub x_pred: Vector4<f64>,
    pub p_pred: Matrix4<f64>,
    pub f: Matrix4<f64>,
    pub x: Vector4<f64>,
    pub p: Matrix4<f64>,
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
    /// `steps` are the filter's results, one per stored step.
    pub fn smooth(&self, steps: &[FusedStep]) -> Vec<FusedStep> {
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
            match next.p_pred.try_inverse().filter(|_| !reset) {
                Some(inv) => {
                    let c = cur.p * next.f.transpose() * inv;
                    let mut dx = xs - next.x_pred;
                    dx[3] = wrap_pi(dx[3]);
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
            o.bias_rad = wrap_pi(xs[3]);
            o.scale_bias_sd = [ps[(2, 2)].sqrt(), ps[(3, 3)].sqrt()];
        }
        out
    }
}
