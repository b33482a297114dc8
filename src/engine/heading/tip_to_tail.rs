//! Basso 2016, Algorithm 1: average heading estimation (A-HE) from the tip-to-tail vector.
//!
//! At the end t_k of each step, with the stride period T_k = t_k − t_{k−2} (Basso 2016 §III):
//! a) the unbiased second-order Fourier approximation of the planar acceleration over the stride,
//!    a⁽²⁾(t) = Σ_{n=1,2} [α_n cos(2πnt/T_k) + β_n sin(2πnt/T_k)], α_n, β_n = (2/T_k)∫ a cos/sin;
//! b) its magnitude |a⁽²⁾(t)| on the last step (t_{k−1}, t_k);
//! c) the two peaks of that magnitude are the tip and the tail;
//! d) Δa = a(t_tip) − a(t_tail), θ_k = atan2(Δa_y, Δa_x) with x north and y east (so θ is a
//!    compass heading);
//! e) A-HE averages θ_k and θ_{k−1} (done by the pipeline, as a circular mean).
//!
//! Decisions where the paper is silent:
//! - The peaks are found by evaluating the trigonometric polynomial at 64 points of the last step
//!   and refining each local maximum by a parabola. If fewer than two local maxima fall in the last
//!   step (a very irregular step), the two largest local maxima over the whole stride are used.
//! - Which peak is the tip (the "acceleration phase") is decided by [`super::forward_sign`] on the
//!   second harmonic, which is at the step frequency; see the module documentation of
//!   [`super`].

use super::{forward_sign, fourier, NavSample, StepWindow};
use crate::engine::math::heading_of;
use std::collections::VecDeque;
use std::f64::consts::TAU;

const GRID: usize = 64;

/// Single-step tip-to-tail direction θ_k, radians from north, or `None` when the window is not
/// covered by data or the ellipse is degenerate.
pub fn heading(buf: &VecDeque<NavSample>, w: StepWindow) -> Option<f64> {
    let (t0, t1) = (w.t_km2, w.t_k);
    let period = t1 - t0;
    let h = fourier(buf, t0, t1)?;
    let eval = |tau: f64| -> (f64, f64) {
        let x = TAU * tau / period;
        let (s1, c1) = libm::sincos(x);
        let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
        let e = h[0].alpha[0] * c1 + h[0].beta[0] * s1 + h[1].alpha[0] * c2 + h[1].beta[0] * s2;
        let n = h[0].alpha[1] * c1 + h[0].beta[1] * s1 + h[1].alpha[1] * c2 + h[1].beta[1] * s2;
        (e, n)
    };
    let mag2 = |tau: f64| {
        let (e, n) = eval(tau);
        e * e + n * n
    };
    // Local maxima of |a⁽²⁾|² on the periodic stride grid.
    let n_grid = 2 * GRID;
    let step = period / n_grid as f64;
    let vals: Vec<f64> = (0..n_grid).map(|i| mag2(i as f64 * step)).collect();
    let mut peaks: Vec<(f64, f64)> = Vec::with_capacity(8);
    for i in 0..n_grid {
        let (l, c, r) = (vals[(i + n_grid - 1) % n_grid], vals[i], vals[(i + 1) % n_grid]);
        if c > l && c >= r {
            // Parabolic refinement of the peak position.
            let denom = l - 2.0 * c + r;
            let off = if denom < 0.0 { 0.5 * (l - r) / denom } else { 0.0 };
            let tau = (i as f64 + off) * step;
            peaks.push((tau.rem_euclid(period), mag2(tau)));
        }
    }
    let mid = w.t_km1 - t0;
    let mut in_step: Vec<(f64, f64)> = peaks.iter().copied().filter(|p| p.0 >= mid).collect();
    if in_step.len() < 2 {
        in_step = peaks;
    }
    if in_step.len() < 2 {
        return None;
    }
    in_step.sort_by(|a, b| b.1.total_cmp(&a.1));
    let (pa, pb) = (eval(in_step[0].0), eval(in_step[1].0));
    let (de, dn) = (pa.0 - pb.0, pa.1 - pb.1);
    let norm = de.hypot(dn);
    if !(norm > 1e-9) {
        return None;
    }
    let u = (de / norm, dn / norm);
    // The step frequency is the second harmonic of the stride window.
    let s = forward_sign(&h[1], u);
    Some(heading_of(s * u.0, s * u.1))
}
