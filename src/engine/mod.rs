//! The engine: pure Rust, no web types, streaming and driven by timestamps.
//! May import: nothing above it (no `io`, `sim`, `plot`, `live`, `web`, …); only crates.
//!
//! One file per method of the papers:
//! - [`orientation`]: OS quaternion, Madgwick (Basso 2021 §2.2.1), gravity low-pass;
//!   [`orientation::kf_nfa`]: the KF-NFA (Ibarra 2015 ch. 3, fuzzy covariance matching of R).
//! - [`motion`]: σ_z motion detection (Basso 2016 §II.B); [`handling`]: the phone turned over in
//!   the hand is not a gait (ours); [`back_pocket`]: a back pocket told from a front one by the
//!   leg pitch's swing axis, its path lagging the turns (ours).
//! - [`pll`]: PLL step detection (Basso 2016 §II.C, Basso 2021 §2.2.2); [`peak`]: the comparison;
//!   [`zero_crossing`]: zero crossings + area (Ibarra 2015 §4.4.1, eqs. 4.8–4.9);
//!   [`detector`]: what all three are fed and find.
//! - [`heading::tip_to_tail`]: Basso 2016 Algorithm 1; [`heading::closed_form`]: Basso 2021
//!   eqs. 6–22; [`heading::pca`]: the PCA baseline.
//! - [`step_length`]: Basso 2016 §II.D and eqs. 1–2; Weinberg; [`fuzzy_step_length`]: Ibarra
//!   2015 §4.4.2's fuzzy system.
//! - [`calibration`]: fitting a user's profile (Basso 2016 §II.D), quick mode, profile files.
//! - [`recorded_walk`]: a recorded walk of known distance as a calibration walk.
//! - [`refinement`]: when a live walk's GNSS may refine a profile (the filter's verdict and
//!   scale), and the refined profile.
//! - [`pipeline`]: the one pipeline and dead reckoning (Basso 2021 eq. 24); [`replay`](fn@replay): the one
//!   loop that feeds a log through it.
//! - [`fusion`]: the per-step GNSS/PDR Kalman filter (Basso 2021 §2.2.5–2.2.6, §3), energy
//!   saving, the magnetic declination, and a Rauch–Tung–Striebel smoother.
//! - [`foot`]: foot mode (Strozzi 2017 §3.2): stance detection, strapdown with zero-velocity
//!   updates in an error-state Kalman filter (Foxlin 2005, OpenShoe), a stride per stance.
//! - [`hybrid`]: Strozzi 2017 §4's hybrid: each foot stride's length with the trunk's heading,
//!   sampled at mid-swing (eq. 3) or where it crosses its FIR-filtered self.
//! - [`geo`]: WGS84 ↔ local ENU, haversine.
//! - [`sort`]: the crate's one stable sort, compiled once for every element type.
//!
//! # The stage shape
//! Every stage has settings with `Default` and `validate()` (the fields of [`PipelineConfig`]),
//! `new(settings)`, `push(input)` and `diagnostics()` (a small `Copy` struct, read-only).
//!
//! | Stage | Settings | `push` takes | gives | Diagnostics |
//! |---|---|---|---|---|
//! | [`orientation::Orientation`] | [`OrientationSource`] | a sample and its dt | the sample in the navigation frame | source, heading or not, KF-NFA R scale and mismatch |
//! | [`magnetic::Magnetic`] | [`magnetic::MagneticConfig`] | a sample, its dt and the orientation's output | that output with the yaw held on the gyroscope where the field is bent | disturbed or not, time disturbed, reference field, yaw correction |
//! | [`motion::MotionDetector`] | [`MotionConfig`] | t, vertical acceleration | the motion state | σ_z, μ_z, cadence |
//! | [`handling::Handling`] | [`handling::HandlingConfig`] | t, angular rate, motion state | handled or not | rate, axis share, time handled |
//! | [`carry::Carry`] | [`carry::CarryConfig`] | t, specific force, vertical acceleration, angular rate, handled | the carrying mode | features, raw answer, evaluations, switches |
//! | [`pll::Pll`], [`peak::PeakDetector`], [`zero_crossing::ZeroCrossing`] | [`pll::PllConfig`], [`peak::PeakConfig`], [`zero_crossing::ZeroCrossingConfig`] | [`detector::DetectorInput`] | `Option<`[`detector::Candidate`]`>` | frequency, lock; period |
//! | [`back_pocket::BackPocket`] | [`back_pocket::BackPocketConfig`] | [`back_pocket::BackPocketInput`] (a step: the swing axis's share, pocket, walking) | whether the phone rides behind the hip | mean share, behind |
//! | [`heading::Heading`] | [`HeadingConfig`] | [`heading::StepInput`] (and each sample's attitude, `push_attitude`) | [`heading::StepHeading`] | last heading, yaw offset |
//! | [`step_length::StepLength`] | [`StepLengthModel`] | [`step_length::StepLengthInput`] | the length, m | last length |
//! | [`foot::Foot`] | [`foot::FootConfig`] | a sample and its dt | `Option<`[`foot::Stride`]`>` (T_min late) | stances, strides, distance |
//! | [`fusion::Fusion`] | [`fusion::FusionConfig`] | [`fusion::FixInput`] (`push_fix`), [`fusion::StepInput`] (`push_step`) | the fix's outcome; `Option<`[`fusion::FusedStep`]`>` | fix counts, receiver time, last step |
//!
//! Where a stage departs from the shape, and why:
//! - The detectors split their settings from their running state (`restart()` is a fresh state,
//!   as the onset look-back needs); the other stages are never restarted mid-log and keep both
//!   together.
//! - The motion detector and the orientation give an output for every sample, not an `Option`.
//!   So does the step-length stage for every step: its models keep nothing between steps.
//! - The heading stage and the fusion filter take two inputs at two rates (samples and steps;
//!   fixes and steps), each with its own `push_*`.
//! - The heading methods themselves ([`heading::tip_to_tail`], [`heading::closed_form`],
//!   [`heading::pca`]) are pure functions of a window of samples: the state around them (the
//!   two-step average, the yaw aid) is the heading stage's.
//! - The Rauch–Tung–Striebel smoother ([`fusion::smoother::Smoother`]) is a backward pass over
//!   the whole walk: the filter pushes each step's prediction and estimate into it, and
//!   [`fusion::Fusion::smoothed`] runs the pass. Energy saving's schedule
//!   ([`fusion::schedule::Schedule`]) is pushed the time of each fix and step.
//! - [`calibration`] fits lines to whole walks; it is a set of functions, not a stage.

pub mod activity;
pub mod back_pocket;
pub mod calibration;
pub mod carry;
pub mod detector;
pub mod foot;
pub mod fusion;
pub mod fuzzy_step_length;
pub mod geo;
pub mod handling;
pub mod heading;
pub mod hybrid;
pub mod leg_pitch;
pub mod magnetic;
pub mod math;
pub mod motion;
pub mod orientation;
pub mod peak;
pub mod pipeline;
pub mod pitch_detector;
pub mod pitch_step_length;
pub mod pll;
pub mod recorded_walk;
pub mod refinement;
pub mod replay;
pub mod sort;
pub mod step_length;
pub mod types;
pub mod vertical;
pub mod zero_crossing;

pub use activity::Activity;
pub use heading::{HeadingConfig, HeadingMethod};
pub use motion::{Motion, MotionConfig};
pub use orientation::OrientationSource;
pub use pipeline::{
    Diagnostics, Now, Pipeline, PipelineConfig, Stage, StageClock, StepDetectorConfig, StepRecord,
};
pub use replay::{replay, Replay};
pub use step_length::{StepLengthModel, StepLengthProfile};
pub use types::{ConfigError, GnssFix, ImuSample, InputError, PressureSample, Record};
