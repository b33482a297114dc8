//! When a live walk with GNSS may refine the user's step-length profile (Basso 2021 §2.2.5,
//! [`crate::engine::calibration::refined_offset`]), and the refined profile; else why not, in
//! words the wizard shows.
//! May import: `calibration` and `fusion` (the filter's verdict).
//!
//! The fusion filter's step-length scale k is the ratio of the true step length to the
//! profile's, learnt from the fixes. It moves the profile's walking offset only when the filter
//! itself says the scale is known ([`GnssVerdict::Calibrated`]; never when it distrusts the
//! fixes), it used enough fixes, its standard deviation is small, and k differs from 1 by more
//! than its uncertainty: a scale the fixes did not make certain must not creep into a profile
//! over repeated walks.

use super::calibration::{refined_offset, ProfileFile};
use super::fusion::GnssVerdict;

/// What a live walk with GNSS says about the user's step length: the fusion filter's
/// step-length scale k and its standard deviation, its verdict on the fixes, the fixes
/// received and used, and the frequencies of the steps.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WalkEvidence {
    /// Fixes received during the walk.
    pub fixes: usize,
    /// Fixes the filter used (its `FixCounts::used`); 0 when not given.
    #[serde(default)]
    pub fixes_used: u64,
    /// The filter's verdict at the end of the walk; none without a filter (or not given).
    #[serde(default)]
    pub verdict: Option<GnssVerdict>,
    /// The filter's scale k and its standard deviation at the end of the walk.
    pub scale: Option<(f64, f64)>,
    /// f_k of every step, Hz.
    pub step_freqs_hz: Vec<f64>,
}

/// Refinement needs at least this many fixes used by the filter…
pub const REFINE_MIN_FIXES: usize = 20;
/// …and this many steps…
pub const REFINE_MIN_STEPS: usize = 50;
/// …a scale known to this standard deviation or better…
pub const REFINE_MAX_SCALE_SD: f64 = 0.03;
/// …and at least this many standard deviations away from 1 (else there is nothing to correct).
pub const REFINE_MIN_SIGMAS: f64 = 2.0;
/// The share of the way the offset moves on each walk (slow refinement over repeated walks).
pub const REFINE_RATE: f64 = 0.5;

/// A profile refined by one walk.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// The refined profile.
    pub file: ProfileFile,
    /// The walking offset before and after, m.
    pub offset_m: (f64, f64),
    /// The scale k that moved it.
    pub scale: f64,
    /// The cadence it was applied at (the walk's median step frequency), Hz.
    pub cadence_hz: f64,
}

/// Why a walk does not refine the profile.
#[derive(Debug, Clone, PartialEq)]
pub enum NotRefined {
    /// The filter never had a usable fix (or no verdict was given).
    NoGnss,
    /// The filter distrusted the fixes at the end of the walk.
    Distrusted,
    /// The filter had not made the scale and heading correction known: (k, sd).
    NotCalibrated(f64, f64),
    /// Too few fixes used: (used, needed).
    TooFewFixes(u64, usize),
    /// Too few steps: (steps, needed).
    TooFewSteps(usize, usize),
    /// The scale's standard deviation is above [`REFINE_MAX_SCALE_SD`]: (k, sd).
    Uncertain(f64, f64),
    /// The scale is within [`REFINE_MIN_SIGMAS`] standard deviations of 1: (k, sd).
    NothingToCorrect(f64, f64),
    /// The scale or the cadence is not plausible, or the refined profile not valid.
    Implausible(f64),
}

impl std::fmt::Display for NotRefined {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ks = |k: f64, sd: f64| format!("scale {k:.2} ± {sd:.2}");
        match *self {
            NotRefined::NoGnss => write!(f, "GNSS gave no usable fix during the walk"),
            NotRefined::Distrusted => write!(
                f,
                "GNSS disagreed with your steps at the end of the walk: it was not used to learn your step length"
            ),
            NotRefined::NotCalibrated(k, sd) => write!(
                f,
                "GNSS had not yet learnt your step length and heading: {}",
                ks(k, sd)
            ),
            NotRefined::TooFewFixes(n, need) => write!(
                f,
                "GNSS corrected the walk with {n} fixes; refinement needs {need}"
            ),
            NotRefined::TooFewSteps(n, need) => {
                write!(f, "the walk had {n} steps; refinement needs {need}")
            }
            NotRefined::Uncertain(k, sd) => write!(
                f,
                "GNSS was not certain enough of your step length: {}",
                ks(k, sd)
            ),
            NotRefined::NothingToCorrect(k, sd) => write!(
                f,
                "your steps match the profile within what GNSS can tell: {}",
                ks(k, sd)
            ),
            NotRefined::Implausible(k) => {
                write!(f, "the learnt scale {k:.2} is not a plausible correction")
            }
        }
    }
}

impl std::error::Error for NotRefined {}

/// Whether the walk may refine a profile: its verdict calibrated, enough fixes used and steps,
/// the scale certain and different from 1. Returns the scale k and its standard deviation.
pub fn refinable(walk: &WalkEvidence) -> Result<(f64, f64), NotRefined> {
    let (k, sd) = match (walk.verdict, walk.scale) {
        (None | Some(GnssVerdict::Waiting), _) | (_, None) => return Err(NotRefined::NoGnss),
        (Some(GnssVerdict::Distrusted), _) => return Err(NotRefined::Distrusted),
        (Some(GnssVerdict::Learning), Some((k, sd))) => {
            return Err(NotRefined::NotCalibrated(k, sd))
        }
        (Some(GnssVerdict::Calibrated), Some(ks)) => ks,
    };
    if walk.fixes_used < REFINE_MIN_FIXES as u64 {
        return Err(NotRefined::TooFewFixes(walk.fixes_used, REFINE_MIN_FIXES));
    }
    if walk.step_freqs_hz.len() < REFINE_MIN_STEPS {
        return Err(NotRefined::TooFewSteps(
            walk.step_freqs_hz.len(),
            REFINE_MIN_STEPS,
        ));
    }
    if !(sd <= REFINE_MAX_SCALE_SD) {
        return Err(NotRefined::Uncertain(k, sd));
    }
    if !(k.is_finite() && k > 0.5 && k < 1.5) {
        return Err(NotRefined::Implausible(k));
    }
    if (k - 1.0).abs() < REFINE_MIN_SIGMAS * sd {
        return Err(NotRefined::NothingToCorrect(k, sd));
    }
    Ok((k, sd))
}

/// The profile refined by a walk ([`refined_offset`] at the walk's median cadence,
/// [`REFINE_RATE`] of the way), when [`refinable`] allows it; else why not.
pub fn refine(file: &ProfileFile, walk: &WalkEvidence) -> Result<Refinement, NotRefined> {
    let (k, _) = refinable(walk)?;
    let mut f = walk.step_freqs_hz.clone();
    crate::engine::sort::sort_by(&mut f, f64::total_cmp);
    let cadence_hz = f[f.len() / 2];
    if !(cadence_hz.is_finite() && cadence_hz > 0.0) {
        return Err(NotRefined::Implausible(k));
    }
    let mut out = file.clone();
    let before = file.profile.walking.b;
    out.profile.walking.b = refined_offset(&file.profile.walking, k, cadence_hz, REFINE_RATE);
    out.profile
        .validate()
        .map_err(|_| NotRefined::Implausible(k))?;
    Ok(Refinement {
        offset_m: (before, out.profile.walking.b),
        file: out,
        scale: k,
        cadence_hz,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::calibration::PROFILE_VERSION;
    use crate::engine::StepLengthProfile;

    fn file() -> ProfileFile {
        ProfileFile {
            version: PROFILE_VERSION,
            name: "tester".to_string(),
            profile: StepLengthProfile::default(),
            walking_points: Vec::new(),
            running_points: Vec::new(),
            fuzzy_scale: None,
            pitch_offset_m: None,
        }
    }

    /// A walk the filter calibrated: scale 0.95 ± 0.01 over 40 fixes used, 100 steps at 1.8 Hz.
    fn good() -> WalkEvidence {
        WalkEvidence {
            fixes: 45,
            fixes_used: 40,
            verdict: Some(GnssVerdict::Calibrated),
            scale: Some((0.95, 0.01)),
            step_freqs_hz: vec![1.8; 100],
        }
    }

    #[test]
    fn a_calibrated_certain_walk_moves_the_offset_halfway() {
        let f = file();
        let r = refine(&f, &good()).unwrap();
        let sl = f.profile.walking.eval(1.8);
        let want = f.profile.walking.b + REFINE_RATE * (0.95 - 1.0) * sl;
        assert!((r.offset_m.1 - want).abs() < 1e-12, "{:?}", r.offset_m);
        assert_eq!(r.offset_m.0, f.profile.walking.b);
        assert_eq!((r.scale, r.cadence_hz), (0.95, 1.8));
    }

    #[test]
    fn only_the_calibrated_verdict_refines() {
        let f = file();
        for (verdict, want) in [
            (None, NotRefined::NoGnss),
            (Some(GnssVerdict::Waiting), NotRefined::NoGnss),
            (Some(GnssVerdict::Distrusted), NotRefined::Distrusted),
            (
                Some(GnssVerdict::Learning),
                NotRefined::NotCalibrated(0.95, 0.01),
            ),
        ] {
            let walk = WalkEvidence { verdict, ..good() };
            assert_eq!(refine(&f, &walk).unwrap_err(), want, "{verdict:?}");
        }
        // Distrusted never, however certain the scale.
        let walk = WalkEvidence {
            verdict: Some(GnssVerdict::Distrusted),
            scale: Some((0.9, 0.001)),
            ..good()
        };
        assert!(refine(&f, &walk).is_err());
    }

    #[test]
    fn fixes_used_not_received_count() {
        let walk = WalkEvidence {
            fixes: 400,
            fixes_used: 19,
            ..good()
        };
        assert_eq!(
            refine(&file(), &walk).unwrap_err(),
            NotRefined::TooFewFixes(19, REFINE_MIN_FIXES)
        );
        let walk = WalkEvidence {
            fixes_used: 20,
            ..walk
        };
        assert!(refine(&file(), &walk).is_ok());
    }

    #[test]
    fn an_uncertain_or_neutral_or_short_walk_says_why() {
        let f = file();
        let uncertain = WalkEvidence {
            scale: Some((0.81, 0.06)),
            ..good()
        };
        let e = refine(&f, &uncertain).unwrap_err();
        assert_eq!(e, NotRefined::Uncertain(0.81, 0.06));
        assert_eq!(
            e.to_string(),
            "GNSS was not certain enough of your step length: scale 0.81 ± 0.06"
        );
        let neutral = WalkEvidence {
            scale: Some((0.99, 0.01)),
            ..good()
        };
        assert_eq!(
            refine(&f, &neutral).unwrap_err(),
            NotRefined::NothingToCorrect(0.99, 0.01)
        );
        let short = WalkEvidence {
            step_freqs_hz: vec![1.8; 49],
            ..good()
        };
        assert_eq!(
            refine(&f, &short).unwrap_err(),
            NotRefined::TooFewSteps(49, REFINE_MIN_STEPS)
        );
        let wild = WalkEvidence {
            scale: Some((0.45, 0.01)),
            ..good()
        };
        assert_eq!(
            refine(&f, &wild).unwrap_err(),
            NotRefined::Implausible(0.45)
        );
        let nan = WalkEvidence {
            scale: Some((0.9, f64::NAN)),
            ..good()
        };
        assert!(matches!(
            refine(&f, &nan).unwrap_err(),
            NotRefined::Uncertain(..)
        ));
    }

    #[test]
    fn evidence_without_a_verdict_reads_and_is_refused() {
        // What an older page sends: no verdict, no fixes used.
        let old: WalkEvidence =
            serde_json::from_str(r#"{"fixes": 40, "scale": [0.95, 0.01], "step_freqs_hz": [1.8]}"#)
                .unwrap();
        assert_eq!(old.verdict, None);
        assert_eq!(refine(&file(), &old).unwrap_err(), NotRefined::NoGnss);
        let new: WalkEvidence = serde_json::from_str(
            r#"{"fixes": 40, "fixes_used": 40, "verdict": "calibrated", "scale": [0.95, 0.01], "step_freqs_hz": []}"#,
        )
        .unwrap();
        assert_eq!(new.verdict, Some(GnssVerdict::Calibrated));
    }
}
