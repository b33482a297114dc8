//! The swinging hand's way forward (ours): the pelvis's sign rule with the arm's
//! pendulum taken out of the vertical acceleration.
//! May import: the rest of `engine`.
//!
//! The acceleration heading's 180° is resolved from the pelvis ([`super::forward_sign`]): its
//! vertical acceleration at the step frequency peaks at double support. A phone in a swinging
//! hand rides a pendulum of length L below the shoulder, at the swing angle θ from its mean
//! (θ = A cos(πft) for cadence f: the arm is at an end of its swing at each heel strike). The
//! phone then sits L·(1 − cos θ) ≈ L·θ²/2 above the swing's lowest point, highest at the ends of
//! the swing, so the arm adds d²/dt²(L·θ²/2) = −L·A²·(πf)²·cos(2πft) to the vertical: a term at
//! the step frequency, lowest at double support, in antiphase with the pelvis's. At
//! A = 30° and L = 0.65 m it is 5.7 m/s², about twice a pelvis's, and the rule turns the heading
//! over (the simulated swinging hand walked 175° off, every seed); at A = 15° it is 1.4 m/s² and
//! the sum's phase is anybody's.
//!
//! So in a swinging hand the rule is given the pelvis's part: the harmonic at the step frequency
//! of the vertical acceleration less the arm's, which the leg pitch's angle about the swing axis
//! ([`crate::engine::leg_pitch`], θ in [`NavSample::pitch`]) gives without a derivative: for a
//! periodic g over the stride, the n-th Fourier coefficient of g̈ is −(nω)² times g's, so the
//! arm's coefficient is −(2ω)²·L times that of θ²/2. L is [`ARM_LEVER_M`], the shoulder to the
//! grip of an adult (about 0.36 of the stature); 20 % off it leaves a fifth of the arm's term.

use super::{fourier_of, NavSample, StepWindow};
use std::collections::VecDeque;
use std::f64::consts::TAU;

/// The shoulder to the phone in a hanging hand, m.
pub const ARM_LEVER_M: f64 = 0.65;

/// [`super::forwardness`] of the horizontal unit vector `u` (east, north) with the arm's
/// pendulum taken out: positive when `u` points forward; `None` when the stride window lacks
/// the data or a sample in it has no swing angle.
pub fn forwardness(buf: &VecDeque<NavSample>, w: StepWindow, u: (f64, f64)) -> Option<f64> {
    let (t0, t1) = (w.t_km2, w.t_k);
    // The step frequency is the stride window's second harmonic; the Fourier coefficients are
    // linear, so the arm's term is taken out sample by sample, in the same pass.
    let w2 = 2.0 * TAU / (t1 - t0);
    let k = w2 * w2 * ARM_LEVER_M;
    let pelvis = |p: &NavSample| {
        let th = p.pitch.map_or(f64::NAN, f64::to_radians);
        [p.e, p.n, p.up + k * 0.5 * th * th]
    };
    let h = fourier_of(buf, t0, t1, pelvis)?;
    let (c, d) = (h[1].alpha[2], h[1].beta[2]);
    if !(c.is_finite() && d.is_finite()) {
        return None;
    }
    Some(super::forwardness(&h[1], u))
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::super::fourier;
    use super::*;

    /// A stride of a walker going north: the pelvis's vertical cos(2ωt) (peaks at double
    /// support, t = 0 and T/2), its forward −sin(2ωt); a hand swinging ±`arm_deg` on the lever,
    /// at an end of its swing at t = 0, adds −L·A²·ω²·cos(2ωt) (2.3 times the pelvis's at 30°).
    fn stride(arm_deg: f64, pitch: bool) -> (VecDeque<NavSample>, StepWindow) {
        let period = 1.1;
        let w = TAU / period;
        let a = arm_deg.to_radians();
        let mut buf = VecDeque::new();
        for i in -20..=240 {
            let t = i as f64 * 0.005;
            let theta = a * (w * t).cos();
            buf.push_back(NavSample {
                n: -(2.0 * w * t).sin() + 3.0 * (w * t).sin(),
                up: (2.0 * w * t).cos() - ARM_LEVER_M * a * a * w * w * (2.0 * w * t).cos(),
                pitch: pitch.then_some(theta.to_degrees()),
                ..NavSample::empty(t)
            });
        }
        let win = StepWindow {
            t_km2: 0.0,
            t_km1: 0.5 * period,
            t_k: period,
        };
        (buf, win)
    }

    #[test]
    fn the_arm_taken_out_the_pelvis_points_forward() {
        for arm_deg in [0.0, 15.0, 30.0, 40.0] {
            let (buf, win) = stride(arm_deg, true);
            assert!(
                forwardness(&buf, win, (0.0, 1.0)).unwrap() > 0.0,
                "{arm_deg}°"
            );
            assert!(
                forwardness(&buf, win, (0.0, -1.0)).unwrap() < 0.0,
                "{arm_deg}°"
            );
        }
        // Without the correction the arm's term turns the pelvis's rule over.
        let (buf, _) = stride(30.0, true);
        let h = fourier(&buf, 0.0, 1.1).unwrap();
        assert_eq!(super::super::forward_sign(&h[1], (0.0, 1.0)), -1.0);
    }

    #[test]
    fn no_swing_angle_no_answer() {
        let (buf, win) = stride(30.0, false);
        assert_eq!(forwardness(&buf, win, (0.0, 1.0)), None);
    }
}
