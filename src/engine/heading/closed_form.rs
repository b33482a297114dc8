//! Basso 2021 §2.2.3–2.2.4: closed-form heading from the first harmonic over the last step.
//! May import: the rest of `engine`.
//!
//! With T_k = t_k − t_{k−1} (eq. 7) and ω_k = 2π/T_k (eq. 11), the first-harmonic coefficients of
//! the north and east acceleration over the step (eq. 13) give the ellipse
//! a¹(t) = α cos ω_k t + β sin ω_k t (eqs. 10, 12, 14). The heading is the direction of a¹ at t*,
//! the time of maximal planar acceleration (Fig. 7), by the summary of §2.2.4:
//! (a) A_k, B_k; (b) t* from the arctangent; (c) if t* < 0 add T_k/4; (d) if the second derivative
//! of ‖a‖² at t* is not negative add T_k/4; (e) θ_k from the vector at t*.
//!
//! # Where we depart from the printed equations, and why
//! - **Eqs. 17 and 19 are wrong by a factor −1/2.** Expanding eq. 15 with cos² = (1 + cos 2x)/2,
//!   sin² = (1 − cos 2x)/2 and 2 sin cos = sin 2x gives
//!   ‖a‖² = C + (P/2) cos 2ωt + B sin 2ωt with P = α_N² + α_E² − β_N² − β_E² = −A,
//!   not A cos 2ωt + B sin 2ωt + C. Setting the derivative to zero gives
//!   tan(2ωt*) = 2B/P = −2B/A, not B/A (eq. 19). The printed form picks a wrong t* whenever
//!   B ≠ 0; the test `published_formula_misses_the_maximum` shows it. We use
//!   t* = (T/4π)·atan(2B/P) and keep the paper's quarter-period rules (c) and (d), with the second
//!   derivative −4ω²[(P/2) cos 2ωt* + B sin 2ωt*] of the corrected expression.
//! - **Eq. 22 is written atan2(a_N, a_E)**, which measures the angle from east towards north. The
//!   2016 paper's θ = atan2(Δa_y, Δa_x) (x north, y east) is a compass heading; we return the
//!   compass heading atan2(a_E, a_N).
//! - **The two maxima** at t* and t* + T/2 are opposite vectors; which one rules (c)–(d) pick
//!   depends on where the step window starts. We resolve the direction with
//!   [`super::forward_sign`] on the same first harmonic (see the module documentation of
//!   [`super`]).

use super::{forward_sign, fourier, NavSample, StepWindow};
use crate::engine::math::heading_of;
use std::collections::VecDeque;
use std::f64::consts::{PI, TAU};

/// The time of maximal planar acceleration t* ∈ [0, T/2) over one step, by rules (b)–(d) of
/// Basso 2021 §2.2.4 on the corrected expression. `alpha`, `beta` are the (east, north)
/// first-harmonic coefficients.
pub fn t_star(alpha: (f64, f64), beta: (f64, f64), period: f64) -> f64 {
    let w = TAU / period;
    let p = alpha.0 * alpha.0 + alpha.1 * alpha.1 - beta.0 * beta.0 - beta.1 * beta.1;
    let b = alpha.0 * beta.0 + alpha.1 * beta.1;
    // (b) t* = T/(4π) atan(2B/P); atan of ±∞ is ±π/2 when P = 0.
    let mut t = period / (4.0 * PI) * libm::atan(2.0 * b / p);
    if t.is_nan() {
        t = 0.0; // P = B = 0: a circle, every t is a maximum.
    }
    // (c) negative t*: add a quarter period.
    if t < 0.0 {
        t += period / 4.0;
    }
    // (d) not a maximum: add a quarter period.
    let second = -4.0 * w * w * (0.5 * p * libm::cos(2.0 * w * t) + b * libm::sin(2.0 * w * t));
    if second >= 0.0 {
        t += period / 4.0;
    }
    t
}

/// Single-step closed-form direction θ_k, radians from north.
pub fn heading(buf: &VecDeque<NavSample>, w: StepWindow) -> Option<f64> {
    let period = w.t_k - w.t_km1;
    let h = fourier(buf, w.t_km1, w.t_k)?;
    let alpha = (h[0].alpha[0], h[0].alpha[1]);
    let beta = (h[0].beta[0], h[0].beta[1]);
    let ts = t_star(alpha, beta, period);
    let (s, c) = libm::sincos(TAU * ts / period);
    let v = (alpha.0 * c + beta.0 * s, alpha.1 * c + beta.1 * s);
    let norm = libm::hypot(v.0, v.1);
    if !(norm > 1e-9) {
        return None;
    }
    let u = (v.0 / norm, v.1 / norm);
    let sign = forward_sign(&h[0], u);
    Some(heading_of(sign * u.0, sign * u.1))
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    fn norm2(alpha: (f64, f64), beta: (f64, f64), period: f64, t: f64) -> f64 {
        let (s, c) = libm::sincos(TAU * t / period);
        let v = (alpha.0 * c + beta.0 * s, alpha.1 * c + beta.1 * s);
        v.0 * v.0 + v.1 * v.1
    }

    fn brute_max(alpha: (f64, f64), beta: (f64, f64), period: f64) -> f64 {
        (0..10_000)
            .map(|i| norm2(alpha, beta, period, i as f64 * period / 10_000.0))
            .fold(0.0, f64::max)
    }

    #[test]
    fn corrected_formula_finds_the_maximum() {
        for (alpha, beta) in [
            ((1.0, 0.3), (0.4, -0.8)),
            ((0.0, 2.0), (1.0, 0.5)),
            ((-0.3, 0.2), (0.9, 0.9)),
            ((1.0, 0.0), (0.0, 0.2)),
        ] {
            let t = t_star(alpha, beta, 0.55);
            let got = norm2(alpha, beta, 0.55, t);
            assert!(
                (got - brute_max(alpha, beta, 0.55)).abs() < 1e-6,
                "{alpha:?} {beta:?}"
            );
        }
    }

    #[test]
    fn published_formula_misses_the_maximum() {
        // Eq. 19 as printed: tan(2ωt*) = B/A with A = |β|² − |α|², same rules (c)–(d) with the
        // printed second derivative of eq. 21.
        let (alpha, beta, period): ((f64, f64), (f64, f64), f64) = ((1.0, 0.3), (0.4, -0.8), 0.55);
        let w = TAU / period;
        let a = beta.0 * beta.0 + beta.1 * beta.1 - alpha.0 * alpha.0 - alpha.1 * alpha.1;
        let b = alpha.0 * beta.0 + alpha.1 * beta.1;
        let mut t = period / (4.0 * PI) * (b / a).atan();
        if t < 0.0 {
            t += period / 4.0;
        }
        if -4.0 * w * w * (a * (2.0 * w * t).cos() + b * (2.0 * w * t).sin()) >= 0.0 {
            t += period / 4.0;
        }
        let printed = norm2(alpha, beta, period, t);
        let max = brute_max(alpha, beta, period);
        assert!(printed < 0.97 * max, "printed {printed} vs max {max}");
    }
}
