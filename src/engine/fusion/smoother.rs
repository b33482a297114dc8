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
    /// the filter was built not to. It smooths the other states given them: every covariance
    /// is conditioned on the consider states (the Schur complement, `condition`), which keeps
    /// the recursion an exact RTS pass over the other states; the smoothed covariance then gets
    /// back the share the consider states' own uncertainty adds, as the filter had it. (Only
    /// zeroing their rows of Cₖ would leave Pₖˢ without meaning: it can turn negative.)
    pub fn smooth(&self, steps: &[FusedStep], consider: &[usize]) -> Vec<FusedStep> {
        let n = self.stored.len();
        let mut out = steps.to_vec();
        if n == 0 {
            return out;
        }
        let last = &self.stored[n - 1];
        let mut xs = last.x;
        let mut ps = condition(&last.p, consider).0;
        for k in (0..n - 1).rev() {
            let next = &self.stored[k + 1];
            let cur = &self.stored[k];
            let (p_cur, from_consider) = condition(&cur.p, consider);
            let reset = matches!(steps[k + 1].fix, Some(FixOutcome::Reset));
            // Without the fixes' correlated error (τ = 0), or given the consider states, some
            // rows are zero: the pseudo-inverse leaves them out.
            let p_pred = condition(&next.p_pred, consider).0;
            let inverse = p_pred
                .try_inverse()
                .or_else(|| p_pred.pseudo_inverse(1e-12).ok());
            match inverse.filter(|_| !reset) {
                Some(inv) => {
                    let c = p_cur * next.f.transpose() * inv;
                    let mut dx = xs - next.x_pred;
                    dx[BIAS] = wrap_pi(dx[BIAS]);
                    xs = cur.x + c * dx;
                    ps = symmetric(p_cur + c * (ps - p_pred) * c.transpose());
                }
                None => {
                    xs = cur.x;
                    ps = p_cur;
                }
            }
            let full = ps + from_consider;
            let o = &mut out[k];
            o.east_m = xs[0];
            o.north_m = xs[1];
            o.cov = [full[(0, 0)], full[(0, 1)], full[(1, 1)]];
            o.scale = xs[2];
            o.bias_rad = wrap_pi(xs[BIAS]);
            o.scale_bias_sd = [full[(2, 2)].max(0.0).sqrt(), full[(3, 3)].max(0.0).sqrt()];
        }
        out
    }
}

/// The covariance `p` given the states `given` (their rows and columns become zero), and what
/// their uncertainty adds to it (the two sum to `p`): P − P₍·g₎ P₍gg₎⁻¹ P₍g·₎, one state at a
/// time.
fn condition(p: &Cov, given: &[usize]) -> (Cov, Cov) {
    let mut c = *p;
    for &g in given {
        let var = c[(g, g)];
        if var > 0.0 {
            let col = c.column(g).into_owned();
            c -= col * col.transpose() / var;
        }
        c.row_mut(g).fill(0.0);
        c.column_mut(g).fill(0.0);
    }
    let c = symmetric(c);
    (c, p - c)
}
