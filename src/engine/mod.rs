//! The engine: pure Rust, no web types, streaming and driven by timestamps.
//! May import: nothing above it (no `io`, `sim`, `plot`, `live`, `web`, …); only crates.
//!
//! One file per method of the papers:
//! - [`orientation`]: OS quaternion, Madgwick (Basso 2021 §2.2.1), gravity low-pass.
//! - [`motion`]: σ_z motion detection (Basso 2016 §II.B).
//! - [`pll`]: PLL step detection (Basso 2016 §II.C, Basso 2021 §2.2.2); [`peak`]: the comparison;
//!   [`detector`]: what both are fed and find.
//! - [`heading::tip_to_tail`]: Basso 2016 Algorithm 1; [`heading::closed_form`]: Basso 2021
//!   eqs. 6–22; [`heading::pca`]: the PCA baseline.
//! - [`step_length`]: Basso 2016 §II.D and eqs. 1–2; Weinberg.
//! - [`calibration`]: fitting a user's profile (Basso 2016 §II.D), quick mode, profile files.
//! - [`pipeline`]: the one pipeline and dead reckoning (Basso 2021 eq. 24); [`replay`]: the one
//!   loop that feeds a log through it.
//! - [`fusion`]: the per-step GNSS/PDR Kalman filter (Basso 2021 §2.2.5–2.2.6, §3), energy
//!   saving, the magnetic declination, and a Rauch–Tung–Striebel smoother.
//! - [`geo`]: WGS84 ↔ local ENU, haversine.

pub mod calibration;
pub mod detector;
pub mod fusion;
pub mod geo;
pub mod heading;
pub mod math;
pub mod motion;
pub mod orientation;
pub mod peak;
pub mod pipeline;
pub mod pll;
pub mod replay;
pub mod step_length;
pub mod types;

pub use heading::{HeadingConfig, HeadingMethod};
pub use motion::{Motion, MotionConfig};
pub use orientation::OrientationSource;
pub use pipeline::{Diagnostics, Pipeline, PipelineConfig, StepDetectorConfig, StepRecord};
pub use replay::{replay, Replay};
pub use step_length::{StepLengthModel, StepLengthProfile};
pub use types::{ConfigError, GnssFix, ImuSample, InputError, Record};
