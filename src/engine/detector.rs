//! What every step detector is fed per sample ([`DetectorInput`]) and what it finds
//! ([`Candidate`]): the PLL ([`crate::engine::pll`]), the peak counter ([`crate::engine::peak`])
//! and the zero crossings ([`crate::engine::zero_crossing`]) have the same contract, so the
//! pipeline can run any of them (`engine/pipeline/step_detector.rs`).
//! May import: the rest of `engine`.

use super::motion::Motion;

/// One vertical-acceleration sample with the motion detector's view of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetectorInput {
    /// Time, s.
    pub t: f64,
    /// Time since the previous sample, s (0 after a gap).
    pub dt: f64,
    /// Vertical linear acceleration, m/s², up positive.
    pub up: f64,
    /// Mean of the vertical acceleration over the motion detector's window, m/s².
    pub mean: f64,
    /// Its standard deviation σ_z, m/s².
    pub sigma: f64,
    /// The motion state.
    pub motion: Motion,
    /// The cadence of the periodic gait the motion detector sees, Hz.
    pub cadence_hz: Option<f64>,
    /// The leg pitch's raw angle about the swing axis, degrees, when known
    /// ([`super::leg_pitch::LegPitch::push`]; its sign is arbitrary).
    pub pitch_deg: Option<f64>,
    /// The sine of how far the swing axis of the thigh the phone rides on is tilted from the
    /// horizontal, |a·u| (unit), when the leg pitch knows it is on a thigh
    /// ([`super::leg_pitch::LegPitch::axis_tilt_sin`]). A sine rather than the angle: the
    /// step detector wants the largest tilt of a cycle, and the arcsine of the largest sine is
    /// that, one arcsine per cycle instead of one per sample.
    pub axis_tilt_sin: Option<f64>,
    /// Whether the carrying mode says the phone is in a pocket ([`super::carry::CarryMode::Pocket`]).
    pub pocket: bool,
}

/// A step candidate from a detector: its time, and the detector's period estimate for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    /// Step time, seconds.
    pub t: f64,
    /// The detector's current period estimate, seconds.
    pub period_s: f64,
    /// How well the step's cycle of vertical acceleration follows the detector's rhythm: for
    /// the PLL the correlation of the input with the oscillator output cos φ over the cycle
    /// (1 for a sinusoid in phase, ≈ 0 for noise); 1 for the peak detector.
    pub coherence: f64,
}
