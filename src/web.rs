//! WebAssembly entry points (wasm-bindgen). Errors become `JsError` here and only here.

use crate::demo::{run_demo, run_fusion_demo, DemoSummary, FusionDemoSummary};
use crate::plot::{draw_fusion, draw_track, FusionView, Theme};
use plotters::prelude::IntoDrawingArea;
use plotters_canvas::CanvasBackend;
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

type CanvasArea = plotters::drawing::DrawingArea<CanvasBackend, plotters::coord::Shift>;

/// Runs `draw` on `canvas` (backing store sized by the caller to CSS size × `dpr`) with the
/// scheme's theme and the pixel ratio as the drawing scale, then presents it.
fn on_canvas<E: std::fmt::Display>(
    canvas: &HtmlCanvasElement,
    dark: bool,
    dpr: f64,
    draw: impl FnOnce(&CanvasArea, &Theme, f64) -> Result<(), E>,
) -> Result<(), JsError> {
    let backend = CanvasBackend::with_canvas_object(canvas.clone())
        .ok_or_else(|| JsError::new("the canvas has no 2D context"))?;
    let area = backend.into_drawing_area();
    let theme = if dark { Theme::DARK } else { Theme::LIGHT };
    draw(&area, &theme, dpr.clamp(1.0, 4.0)).map_err(|e| JsError::new(&e.to_string()))?;
    area.present().map_err(|e| JsError::new(&e.to_string()))
}

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
        serde_wasm_bindgen::to_value(&self.summary).map_err(|e| JsError::new(&e.to_string()))
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
        serde_wasm_bindgen::to_value(&self.summary).map_err(|e| JsError::new(&e.to_string()))
    }

    /// Draws fixes, PDR-only, fused and smoothed tracks and the truth on `canvas`.
    pub fn draw(&self, canvas: &HtmlCanvasElement, dark: bool, dpr: f64) -> Result<(), JsError> {
        let s = &self.summary;
        let view = FusionView {
            truth: Some(&s.truth),
            fixes: &s.fix_points,
            pdr: &s.pdr,
            fused: &s.fused,
            smoothed: &s.smoothed,
        };
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            draw_fusion(area, &view, theme, scale)
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
