//! Basso 2016, Algorithm 1: average heading estimation (A-HE) from the tip-to-tail vector.
//! May import: the rest of `engine`.
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
//! - The peaks are found by evaluating the trigonometric polynomial at 32 points of each step
//!   and refining each local maximum by a parabola. If fewer than two local maxima fall in the last
//!   step (a very irregular step), the two largest local maxima over the whole stride are used.
//! - Which peak is the tip (the "acceleration phase") is decided by [`super::forward_sign`] on the
//!   second harmonic, which is at the step frequency; see the module documentation of
//!   [`super`].

use super::{forward_sign, fourier, NavSample, StepWindow};
use crate::engine::math::heading_of;
use std::collections::VecDeque;
use std::f64::consts::TAU;

const GRID: usize = 32;

/// Single-step tip-to-tail direction θ_k, radians from north, or `None` when the window is not
/// covered by data or the ellipse is degenerate.
pub fn heading(buf: &VecDeque<NavSample>, w: StepWindow) -> Option<f64> {
    let (t0, t1) = (w.t_km2, w.t_k);
    let period = t1 - t0;
    let h = fourier(buf, t0, t1)?;
    let at = |c1: f64, s1: f64| -> (f64, f64) {
        let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
        let e = h[0].alpha[0] * c1 + h[0].beta[0] * s1 + h[1].alpha[0] * c2 + h[1].beta[0] * s2;
        let n = h[0].alpha[1] * c1 + h[0].beta[1] * s1 + h[1].alpha[1] * c2 + h[1].beta[1] * s2;
        (e, n)
    };
    let eval = |tau: f64| {
        let (s1, c1) = libm::sincos(TAU * tau / period);
        at(c1, s1)
    };
    // Local maxima of |a⁽²⁾|² on the periodic stride grid; the grid's phasor is advanced by
    // rotation, one multiplication per point instead of a sincos.
    let n_grid = 2 * GRID;
    let step = period / n_grid as f64;
    let (ds, dc) = libm::sincos(TAU / n_grid as f64);
    let mut ph = (1.0f64, 0.0f64);
    let mut vals = [0.0f64; 2 * GRID];
    for v in vals.iter_mut() {
        let (e, n) = at(ph.0, ph.1);
        *v = e * e + n * n;
        ph = (ph.0 * dc - ph.1 * ds, ph.1 * dc + ph.0 * ds);
    }
    // At most a handful of local maxima: keep them in a fixed array, no allocation per step.
    let mut peaks = [(0.0f64, 0.0f64); 8];
    let mut n_peaks = 0;
    for i in 0..n_grid {
        let (l, c, r) = (
            vals[(i + n_grid - 1) % n_grid],
            vals[i],
            vals[(i + 1) % n_grid],
        );
        if c > l && c >= r && n_peaks < peaks.len() {
            // Parabolic refinement of the peak position and height.
            let denom = l - 2.0 * c + r;
            let off = if denom < 0.0 {
                0.5 * (l - r) / denom
            } else {
                0.0
            };
            let height = c - 0.25 * (l - r) * off;
            peaks[n_peaks] = (((i as f64 + off) * step).rem_euclid(period), height);
            n_peaks += 1;
        }
    }
    let mid = w.t_km1 - t0;
    let mut best = [(0.0f64, f64::NEG_INFINITY); 2];
    let mut pick = |in_last_step_only: bool| {
        best = [(0.0, f64::NEG_INFINITY); 2];
        for &p in &peaks[..n_peaks] {
            if in_last_step_only && p.0 < mid {
                continue;
            }
            if p.1 > best[0].1 {
                best = [p, best[0]];
            } else if p.1 > best[1].1 {
                best[1] = p;
            }
        }
        best[1].1 > f64::NEG_INFINITY
    };
    if !pick(true) && !pick(false) {
        return None;
    }
    let (pa, pb) = (eval(best[0].0), eval(best[1].0));
    let (de, dn) = (pa.0 - pb.0, pa.1 - pb.1);
    let norm = libm::hypot(de, dn);
    if !(norm > 1e-9) {
        return None;
    }
    let u = (de / norm, dn / norm);
    // The step frequency is the second harmonic of the stride window.
    let s = forward_sign(&h[1], u);
    Some(heading_of(s * u.0, s * u.1))
}
