//! Live input: browser sensor events into the engine's records ([`events`], the one place where
//! the platforms' quirks are converted), and the live session around the one pipeline uploaded
//! logs also go through ([`session`]). Pure Rust (the wasm glue in `crate::web` only reads the
//! events' fields), so it is tested natively and in the browser alike. The step-length
//! calibration wizard's words and fits box are here too ([`wizard`]): its walks are live walks.
//! May import: `engine`, `io`, `view`.
//!
//! # `devicemotion`, as browsers deliver it
//! - `accelerationIncludingGravity`, m/s², device frame (x right, y top, z out of the screen).
//!   Chromium follows the specification: a phone lying face up reads z = +9.81. Safari on iOS
//!   reports the opposite sign (z = −9.81 face up), so iOS values are negated
//!   ([`Platform::to_android`]).
//! - `rotationRate`, **degrees** per second: `alpha` about the device x axis, `beta` about y,
//!   `gamma` about z (w3c/deviceorientation #44). Checked in headless Chromium with its virtual
//!   gyroscope: a reading of (1, 0.5, 0.25) rad/s arrives as alpha 57.3, beta 28.6, gamma 14.3
//!   (`tests/e2e`). Converted to rad/s.
//! - `interval`: milliseconds in Chromium (a fixed 16 on desktop), **seconds** on iOS. It is not
//!   used: the time of a sample is `event.timeStamp` (ms on the page's clock), converted to
//!   seconds.
//!
//! # `deviceorientation(absolute)`
//! `alpha`, `beta`, `gamma` in degrees are the intrinsic Z-X'-Y'' angles of the W3C
//! specification: the device → earth rotation is R = Rz(α)·Rx(β)·Ry(γ), the earth frame being
//! East-North-Up when the event is absolute (alpha = 0 with the top of the device to the north;
//! alpha grows counter-clockwise, so the compass heading of the top is 360° − α).
//!
//! # iOS's compass
//! Safari's `deviceorientation` is relative; its `webkitCompassHeading` (when calibrated, ≥ 0)
//! gives the absolute `alpha` ([`ios_compass_alpha`]), and wins over `alpha` when present.

pub mod controls;
pub mod display;
pub mod events;
pub mod messages;
pub mod readout_text;
pub mod recorder;
pub mod session;
pub mod wizard;

pub use events::{
    browser_events, ios_compass_alpha, is_ios, normalise_motion, orientation_angles,
    orientation_quaternion, BrowserEvent, EventError, MotionEvent, OrientationEvent, Platform,
    SensorReading,
};
pub use recorder::{Chunk, Recorder, Saved};
pub use session::{
    GapMark, LiveError, LiveSession, MapData, Readouts, ScopeData, ScopeSample, NO_MOTION_MS,
    SCOPE_S,
};
