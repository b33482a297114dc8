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

use super::step_length::StepLengthProfile;
use super::types::{positive, ConfigError};

/// Eq. 5's universal slope, m of stride per degree of Δθ_H (see the module documentation).
pub const UNIVERSAL_SLOPE_M_PER_DEG: f64 = 0.0314;

/// Settings of the pitch step length.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PitchStepLength {
    /// a, m of stride per degree. Default [`UNIVERSAL_SLOPE_M_PER_DEG`].
    pub a: f64,
    /// b, m of stride: the walker's own offset (the wizard's calibration). Default 0.
    pub b: f64,
    /// The line in frequency for steps without a leg pitch (a phone taken out of the pocket,
    /// no gyroscope): the default profile unless a profile is given.
    pub fallback: StepLengthProfile,
}

impl Default for PitchStepLength {
    fn default() -> Self {
        PitchStepLength {
            a: UNIVERSAL_SLOPE_M_PER_DEG,
            b: 0.0,
            fallback: StepLengthProfile::default(),
        }
    }
}

impl PitchStepLength {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("step_length.a", self.a)?;
        if !(self.b.is_finite() && self.b.abs() < 1.0) {
            return Err(ConfigError::new(
                "step_length.b",
                "must be a finite offset within ±1 m",
            ));
        }
        self.fallback.validate()
    }

    /// One footfall's length, m: half of eq. 5's stride for amplitude Δθ (degrees), within the
    /// fallback profile's physiological range; the fallback line at `freq_hz` without Δθ.
    pub fn length(&self, amplitude_deg: Option<f64>, freq_hz: f64) -> f64 {
        match amplitude_deg {
            Some(d) => {
                (0.5 * (self.a * d + self.b)).clamp(self.fallback.min_m, self.fallback.max_m)
            }
            None => self.fallback.length(freq_hz),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
