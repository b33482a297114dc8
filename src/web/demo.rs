//! The page's demo walks: simulated once, run through the engine, drawn on demand.
//! May import: `demo`, `plot`, `engine` (the demo's geodetic origin).

use super::canvas::on_canvas;
use super::to_value;
use crate::demo::{run_demo, run_fusion_demo, DemoSummary, FusionDemoSummary};
use crate::plot::{draw_fusion, draw_track, FusionView};
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// The embedded demo walk, processed once and drawn on demand.
#[wasm_bindgen]
pub struct Demo {
    summary: DemoSummary,
}

#[wasm_bindgen]
impl Demo {
    /// Simulates the demo walk and runs it through the engine.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Demo {
        Demo {
            summary: run_demo(),
        }
    }

    /// The figures: `{steps, truth_steps, distance_m, truth_distance_m, end_error_m, duration_s,
    /// samples}`.
    pub fn summary(&self) -> Result<JsValue, JsError> {
        to_value(&self.summary)
    }

    /// The figures in words for the page's elements: `[[id, text]]`.
    pub fn texts(&self) -> Result<JsValue, JsError> {
        to_value(&self.summary.texts())
    }

    /// Draws the track on `canvas`, whose backing store the caller has sized to CSS size × `dpr`.
    pub fn draw(&self, canvas: &HtmlCanvasElement, dark: bool, dpr: f64) -> Result<(), JsError> {
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            draw_track(
                area,
                &self.summary.track,
                Some(&self.summary.truth_path),
                theme,
                scale,
            )
        })
    }
}

/// The GNSS demo walk (fusion filter and smoother), processed once and drawn on demand.
#[wasm_bindgen]
pub struct FusionDemo {
    summary: FusionDemoSummary,
}

#[wasm_bindgen]
impl FusionDemo {
    /// Simulates the GNSS demo walk and runs it through the engine.
    #[wasm_bindgen(constructor)]
    pub fn new() -> FusionDemo {
        FusionDemo {
            summary: run_fusion_demo(),
        }
    }

    /// The figures (see `FusionDemoSummary`).
    pub fn summary(&self) -> Result<JsValue, JsError> {
        to_value(&self.summary)
    }

    /// The figures and caption in words for the page's elements: `[[id, text]]`.
    pub fn texts(&self) -> Result<JsValue, JsError> {
        to_value(&self.summary.texts())
    }

    /// Draws fixes, PDR-only, fused and smoothed tracks and the truth on `canvas`, over the base
    /// map when it is on (the walk is placed in Florence).
    pub fn draw(&self, canvas: &HtmlCanvasElement, dark: bool, dpr: f64) -> Result<(), JsError> {
        let s = &self.summary;
        let view = FusionView {
            truth: Some(&s.truth),
            fixes: &s.fix_points,
            pdr: &s.pdr,
            fused: &s.fused,
            smoothed: &s.smoothed,
        };
        let (lat, lon, h) = s.origin;
        let origin = crate::engine::geo::LocalFrame::new(lat, lon, h);
        super::basemap::with_basemap(canvas, Some(origin), |basemap| {
            on_canvas(canvas, dark, dpr, |area, theme, scale| {
                draw_fusion(area, &view, basemap, theme, scale)
            })
        })
    }
}

impl Default for FusionDemo {
    fn default() -> Self {
        Self::new()
    }
}

impl Default for Demo {
    fn default() -> Self {
        Self::new()
    }
}
