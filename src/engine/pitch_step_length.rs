//! The pitch step length (Munoz Diaz 2015 §5, eq. 5): S = a·Δθ_H + b, the stride's length from
//! the leg pitch amplitude, with a universal slope `a` and a personal offset `b` (§5.1's
//! calibration: one walk of a known distance at a comfortable pace).
//! May import: the rest of `engine`.
//!
//! # The universal slope
//! The paper fits `a` on 18 volunteers and does not print it. The number here comes from the
//! geometry of the stride instead: a leg of length L swinging through Δθ moves the hip about
//! L·Δθ (radians) per step, 2·L·Δθ per stride; with L = 0.9 m that is 0.0314 m per degree, and
//! Δθ_H ≈ 40° gives a 1.26 m stride (0.63 m steps) as people walk. Published gait data agree:
//! the thigh's sagittal range grows from about 35° at a 1.1 m stride to 50° at 1.6 m, a slope of
//! 0.033 m/°. The offset defaults to 0 until the wizard calibrates it
//! ([`crate::engine::calibration::pitch_offset`], saved in the profile as `pitch_offset_m`).
//!
//! Eq. 5's S is a stride (§1: the paper's "step" is two hits of the same foot); the engine's
//! steps are footfalls, so each of a stride's two steps is S/2.

/// Eq. 5's universal slope, m of stride per degree of Δθ_H (see the module documentation).
pub const UNIVERSAL_SLOPE_M_PER_DEG: f64 = 0.0314;

/// The slope the default frequency line uses on a recognised thigh's walking steps
/// ([`crate::engine::step_length::ThighStepLength`]), m of stride per degree of Δθ_H.
/// Measured on the front-pocket walks of the TyrEx set (two walkers, motion-capture truth,
/// `docs/methods/step-length-pocket.md`): each walker's stride over the truth's smoothed path
/// against the stride's Δθ, fitted through the origin, gives 0.0372 (Guillaume, 191 strides) and
/// 0.0356 (Jakob, 188); this is their mean. It is 16 % above the geometric slope: slow walkers'
/// thighs swing through 24–28° at 0.45–0.5 m steps, less than the gait data behind
/// [`UNIVERSAL_SLOPE_M_PER_DEG`] (35° at 0.55 m). Leave-one-walker-out, each walker's slope
/// put on the other's steps is within 4.5 % of their mean true step.
pub const POCKET_SLOPE_M_PER_DEG: f64 = 0.0364;

/// One footfall's length, m: half of eq. 5's stride S = a·Δθ_H + b (a in m/°, b in m, Δθ_H in
/// degrees). The settings and the fallback for steps without a pitch are the step-length
/// stage's ([`crate::engine::step_length::PitchStepLength`]).
pub fn footfall_m(a: f64, b: f64, amplitude_deg: f64) -> f64 {
    0.5 * (a * amplitude_deg + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::step_length::{PitchStepLength, StepLengthProfile};

    #[test]
    fn eq5_per_footfall() {
        let m = PitchStepLength::default();
        assert!((m.length(Some(40.0), 1.8) - 0.628).abs() < 1e-12);
        assert_eq!(
            m.length(None, 1.8),
            StepLengthProfile::default().length(1.8)
        );
        // A walker whose strides are 0.0314·Δθ + 0.1: 100 steps of Δθ 40° cover 67.8 m, and
        // the wizard's calibration gives that offset back.
        let steps = vec![40.0; 100];
        let d = 100.0 * 0.5 * (UNIVERSAL_SLOPE_M_PER_DEG * 40.0 + 0.1);
        let b = crate::engine::calibration::pitch_offset(d, &steps, UNIVERSAL_SLOPE_M_PER_DEG);
        assert!((b.unwrap() - 0.1).abs() < 1e-12);
    }
}
