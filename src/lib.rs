//! Pedestrian dead reckoning for a phone carried in a trouser pocket.
//! The crate root: it declares the layers below and imports nothing itself.
//!
//! Layers point down only (each module's first lines say what it may import; `tests/layers.rs`
//! checks it), from the bottom up:
//! - [`engine`]: pure maths and state (no files, no browsers). The papers' methods.
//! - [`view`]: a piece of the page as the engine describes it (elements, attributes, words).
//! - [`settings`]: the one front door for the engine's configuration.
//! - [`io`]: the project's own log format, the import of other formats, track exports.
//! - [`sim`]: a gait simulator with known truth, and its walks written in every format.
//! - [`eval`]: the evaluation bench (a log's run scored against its truth).
//! - [`live`]: browser sensor events into engine records (the platforms' quirks, in one place)
//!   and the live session.
//! - [`analysis`]: upload mode's analysis of a log (the engine run once, everything kept).
//! - [`plot`]: drawing, generic over the plotters backend.
//! - [`demo`]: the page's demo walks.
//! - `web` (wasm32 only): wasm-bindgen glue.
//!
//! # Conventions (one set, everywhere)
//! - Time: seconds (`f64`) on the log's own clock.
//! - Device frame: W3C / Android: x to the right of the screen, y to the top of the screen,
//!   z out of the screen. Right-handed.
//! - Navigation frame: local East-North-Up (ENU), metres. Headings are compass headings:
//!   radians clockwise from north (0 = north, π/2 = east).
//! - Acceleration: m/s², *specific force including gravity* as Android reports it: a phone lying
//!   face up at rest reads (0, 0, +9.81).
//! - Angular rate: rad/s, right-handed about the device axes. Magnetic field: µT.

pub mod analysis;
pub mod compare;
pub mod demo;
pub mod engine;
pub mod eval;
pub mod io;
pub mod live;
pub mod plot;
pub mod settings;
pub mod sim;
pub mod view;

#[cfg(target_arch = "wasm32")]
pub mod web;
