//! plotters' canvas backend for the page's canvases, and the one way the classes draw on one.
//! May import: `plot`.

use super::to_js;
use crate::plot::Theme;
use plotters::prelude::IntoDrawingArea;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};
use plotters_canvas::CanvasBackend;
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// plotters' canvas backend, with text measured by the canvas itself (`measureText`): plotters'
/// own web measurement puts a styled `<span>` in the page, which the page's Content Security
/// Policy (no inline styles) refuses, and which would measure the wrong font anyway.
pub(super) struct Canvas {
    inner: CanvasBackend,
    ctx: web_sys::CanvasRenderingContext2d,
}

impl plotters::prelude::DrawingBackend for Canvas {
    type ErrorType = <CanvasBackend as plotters::prelude::DrawingBackend>::ErrorType;
    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(
        &mut self,
        p: BackendCoord,
        c: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(p, c)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(a, b, s)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(a, b, s, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, s)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        c: BackendCoord,
        r: u32,
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(c, r, s, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(path, s)
    }
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        s: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_text(text, s, pos)
    }
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        s: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        self.ctx.set_font(&format!(
            "{} {}px {}",
            s.style().as_str(),
            s.size(),
            s.family().as_str()
        ));
        let w = self.ctx.measure_text(text).map_or(0.0, |m| m.width());
        let (w, h) = (w.ceil() as u32, (s.size() * 1.2).ceil() as u32);
        Ok(match s.transform() {
            FontTransform::Rotate90 | FontTransform::Rotate270 => (h, w),
            _ => (w, h),
        })
    }
}

pub(super) type CanvasArea = plotters::drawing::DrawingArea<Canvas, plotters::coord::Shift>;

/// Runs `draw` on `canvas` (backing store sized by the caller to CSS size × `dpr`) with the
/// scheme's theme and the pixel ratio as the drawing scale, then presents it.
pub(super) fn on_canvas<T, E: std::fmt::Display>(
    canvas: &HtmlCanvasElement,
    dark: bool,
    dpr: f64,
    draw: impl FnOnce(&CanvasArea, &Theme, f64) -> Result<T, E>,
) -> Result<T, JsError> {
    use wasm_bindgen::JsCast;
    let no_2d = || JsError::new("the canvas has no 2D context");
    let ctx = canvas
        .get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<web_sys::CanvasRenderingContext2d>().ok())
        .ok_or_else(no_2d)?;
    let inner = CanvasBackend::with_canvas_object(canvas.clone()).ok_or_else(no_2d)?;
    let area = Canvas { inner, ctx }.into_drawing_area();
    let theme = if dark { Theme::DARK } else { Theme::LIGHT };
    let out = draw(&area, &theme, dpr.clamp(1.0, 4.0)).map_err(to_js)?;
    area.present().map_err(to_js)?;
    Ok(out)
}
