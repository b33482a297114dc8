//! Drawing, generic over the plotters
//! [`DrawingBackend`](plotters::prelude::DrawingBackend), so the same code draws on a browser
//! canvas and, in tests, into a bitmap.
//! May import: `engine`, `analysis`; never `web`, `live` or `eval`.
//!
//! One file per drawing: [`Theme`] (`theme`), the map frame every map shares and [`MapFrame`]
//! (`frame`), the demo's track (`track`), the fusion map (`fusion`), the live map (`live`), the
//! live scope (`scope`), the calibration chart (`calibration`), upload mode's plots
//! ([`upload`]), and the opt-in base map under the maps (`basemap`, with the Web Mercator tile
//! maths in [`tiles`] and the page's setting in [`basemap_setting`]). Plot imports `engine` and `analysis` only, never `web`, `live` or `eval`.

mod basemap;
pub mod basemap_setting;
mod calibration;
mod frame;
mod fusion;
pub mod gesture;
mod live;
mod scope;
mod theme;
pub mod tiles;
mod track;
pub mod upload;

#[cfg(test)]
mod pixels;
#[cfg(test)]
pub(crate) mod raster;

pub use basemap::{Basemap, Shown, TileState};
pub use calibration::draw_calibration;
pub use frame::{scale_bar_length, wheel_factor, MapFrame};
pub use fusion::{draw_fusion, FusionView};
pub use live::{draw_live, LiveView};
pub use scope::{draw_scope, ScopePoint};
pub use theme::Theme;
pub use track::draw_track;
