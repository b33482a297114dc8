//! Upload mode's page side: one analysis, drawn and queried (picking, zoom, exports).
//! May import: `analysis`, `io`, `plot`.

use super::canvas::on_canvas;
use super::{to_js, to_json_value};
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// Upload mode, the page's side: one analysis, drawn and queried.
#[wasm_bindgen]
pub struct AnalysisView {
    a: crate::analysis::Analysis,
    frame: std::cell::Cell<crate::plot::upload::MapFrame>,
    /// The `(t0, t1)` the plots show, s (the log's clock): the whole log until zoomed.
    span: std::cell::Cell<(f64, f64)>,
    /// The span when the drag now panning the plots began.
    grabbed: std::cell::Cell<(f64, f64)>,
}

#[wasm_bindgen]
impl AnalysisView {
    /// Reads the bytes [`Upload::analyse`] made.
    pub fn from_bytes(bytes: &[u8]) -> Result<AnalysisView, JsError> {
        let a = crate::analysis::Analysis::from_bytes(bytes).map_err(to_js)?;
        let full = Self::full(&a);
        Ok(AnalysisView {
            a,
            frame: Default::default(),
            span: full.into(),
            grabbed: full.into(),
        })
    }

    /// `{source, format, steps, samples, t0, t1, fixes, truth_waypoints, truth_steps,
    /// steps_without_heading, step_lengths_m, warnings, score, floors, height_source,
    /// activities}`; `score` is the bench's result
    /// (`pdr eval --json` for this log); the track's distance counts only the steps with a
    /// heading, `step_lengths_m` all of them.
    pub fn summary(&self) -> Result<JsValue, JsError> {
        #[derive(serde::Serialize)]
        struct Summary<'a> {
            source: &'a str,
            format: &'a str,
            steps: usize,
            samples: usize,
            t0: Option<f64>,
            t1: Option<f64>,
            fixes: usize,
            truth_waypoints: usize,
            truth_steps: usize,
            steps_without_heading: usize,
            step_lengths_m: f64,
            warnings: &'a [String],
            score: &'a crate::eval::LogResult,
            floors: Vec<i32>,
            height_source: &'static str,
            activities: Vec<&'static str>,
        }
        let a = &self.a;
        to_json_value(&Summary {
            source: &a.source,
            format: &a.format,
            steps: a.steps.len(),
            samples: a.trace.t.len(),
            t0: a.trace.t.first().copied(),
            t1: a.trace.t.last().copied(),
            fixes: a.fixes.len(),
            truth_waypoints: a.truth_path.len(),
            truth_steps: a.truth_steps.len(),
            steps_without_heading: a.steps.iter().filter(|s| s.heading_rad.is_none()).count(),
            step_lengths_m: a.steps.iter().map(|s| s.length_m).sum(),
            warnings: &a.warnings,
            score: &a.score,
            floors: a.floors(),
            height_source: a.height_source(),
            activities: a.activities().iter().map(|x| x.as_str()).collect(),
        })
    }

    /// Draws the map; `bounds` `[min_e, max_e, min_n, max_n]` zooms (empty: fit all);
    /// `highlight` rings a step. Over the base map when it is on and the log has fixes.
    pub fn draw_map(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        bounds: Vec<f64>,
        highlight: Option<usize>,
    ) -> Result<(), JsError> {
        let b = (bounds.len() == 4).then(|| (bounds[0], bounds[1], bounds[2], bounds[3]));
        super::basemap::with_basemap(canvas, self.a.frame(), |basemap| {
            on_canvas(canvas, dark, dpr, |area, theme, scale| {
                crate::plot::upload::draw_map(area, &self.a, b, highlight, basemap, theme, scale)
                    .map(|f| self.frame.set(f))
            })
        })
    }

    /// Canvas pixel `[x, y]` of step `i` on the last map drawn.
    pub fn step_pixel(&self, i: usize) -> Option<Vec<f64>> {
        let (e, n) = self.a.step_position(i)?;
        let (x, y) = self.frame.get().to_pixel(e, n);
        Some(vec![x, y])
    }

    /// The figures shown under the map, a `dl.summary` view tree.
    pub fn figures(&self) -> Result<JsValue, JsError> {
        to_json_value(&crate::analysis::page::figures(&self.a.figures()))
    }

    /// Step `i` described for people.
    pub fn step_text(&self, i: usize) -> Result<String, JsError> {
        self.a
            .step_text(i)
            .ok_or_else(|| to_js(format!("no step {i}")))
    }

    /// Step `i`: `{index, t, t_rel_s, length_m, freq_hz, heading_deg, step_heading_deg, motion,
    /// activity, up_m, floor}`.
    pub fn step_info(&self, i: usize) -> Result<JsValue, JsError> {
        let s = self
            .a
            .steps
            .get(i)
            .ok_or_else(|| to_js(format!("no step {i}")))?;
        let deg = |r: Option<f64>| r.map(|r| r.to_degrees().rem_euclid(360.0));
        let v = serde_json::json!({
            "index": i,
            "t": s.t,
            "t_rel_s": s.t - self.a.trace.t.first().copied().unwrap_or(s.t),
            "length_m": s.length_m,
            "freq_hz": s.freq_hz,
            "heading_deg": deg(s.heading_rad),
            "step_heading_deg": deg(s.step_heading_rad),
            "motion": s.motion.as_str(),
            "activity": s.activity.as_str(),
            "up_m": s.up_m,
            "floor": s.floor,
        });
        to_json_value(&v)
    }

    /// Draws a diagnostics plot (`accel`, `sigma`, `height`, `heading`, `steps`, `gnss`, `fusion`)
    /// over the span shown ([`Self::span`]), with a cursor at `cursor` (s). Returns the canvas
    /// pixel columns of the span's ends, then the rows of the plot area's top and bottom.
    pub fn draw_plot(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        kind: &str,
        cursor: Option<f64>,
    ) -> Result<Vec<f64>, JsError> {
        let plot = crate::plot::upload::Plot::parse(kind)
            .ok_or_else(|| to_js(format!("no plot `{kind}`")))?;
        let span = self.span.get();
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::upload::draw_plot_area(area, &self.a, plot, span, cursor, theme, scale)
        })
        .map(|((left, right), (top, bottom))| [left, right, top, bottom].map(f64::from).to_vec())
    }

    /// The `[t0, t1]` the plots show, s (the log's clock).
    pub fn span(&self) -> Vec<f64> {
        let (t0, t1) = self.span.get();
        vec![t0, t1]
    }

    /// The whole log's `[t0, t1]`, s.
    pub fn full_span(&self) -> Vec<f64> {
        let (t0, t1) = Self::full(&self.a);
        vec![t0, t1]
    }

    /// Shows `[t0, t1]` on the plots, as a zoom would.
    pub fn set_span(&self, t0: f64, t1: f64) {
        self.span.set((t0, t1));
    }

    /// The CSS pixel from a plot canvas's left edge at time `t` (s, the log's clock), `axis` as
    /// for [`Self::axis_time_at`].
    pub fn axis_x_at(&self, axis: &[f64], t: f64) -> Result<f64, JsError> {
        Ok(self.time_axis(self.span.get(), axis)?.x_at(t))
    }

    /// Draws the stride ellipse ending at step `k`.
    pub fn draw_ellipse(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        k: usize,
    ) -> Result<(), JsError> {
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::upload::draw_ellipse(area, &self.a, k, theme, scale)
        })
    }

    /// The track exported as `what` (`gpx`, `geojson` or `csv`, see [`Self::gpx`]) for a file
    /// named `base` and its extension: `[text, file name, MIME type]`.
    pub fn export_file(&self, what: &str, base: &str) -> Result<JsValue, JsError> {
        let (text, ext, mime) = match what {
            "gpx" => (self.gpx(), "gpx", "application/gpx+xml"),
            "geojson" => (self.geojson(), "geojson", "application/geo+json"),
            "csv" => (self.steps_csv(), "steps.csv", "text/csv"),
            _ => return Err(to_js(format!("no export `{what}`"))),
        };
        super::to_value(&[text, format!("{base}.{ext}"), mime.to_string()])
    }
}

/// What the engine's own gesture rules ([`super::gesture`]) and exports call.
impl AnalysisView {
    /// The step nearest to canvas pixel (x, y) on the last map, within `radius` pixels.
    pub fn pick(&self, x: f64, y: f64, radius: f64) -> Option<usize> {
        crate::plot::upload::pick_step(&self.a, &self.frame.get(), x, y, radius)
    }
    /// The wheel turned by `delta_y` (the wheel event's) at canvas pixel (x, y) of the last map:
    /// the bounds `[min_e, max_e, min_n, max_n]` zoomed about that point, for [`Self::draw_map`].
    pub fn map_wheel(&self, x: f64, y: f64, delta_y: f64) -> Vec<f64> {
        let f = crate::plot::wheel_factor(delta_y);
        let (e0, e1, n0, n1) = self.frame.get().zoomed(x, y, f);
        vec![e0, e1, n0, n1]
    }
    /// A pinch on the last map: one pointer moved from canvas pixel (prev_x, prev_y) to (x, y)
    /// while the other stays at (other_x, other_y). The bounds zoomed about their middle, or
    /// nothing when two of the points coincide.
    pub fn map_pinch(
        &self,
        prev_x: f64,
        prev_y: f64,
        x: f64,
        y: f64,
        other_x: f64,
        other_y: f64,
    ) -> Option<Vec<f64>> {
        let f = self.frame.get();
        let (e0, e1, n0, n1) = f.pinched((prev_x, prev_y), (x, y), (other_x, other_y))?;
        Some(vec![e0, e1, n0, n1])
    }
    /// A drag of (dx, dy) canvas pixels on the last map: the bounds panned with the pointer.
    pub fn map_pan(&self, dx: f64, dy: f64) -> Vec<f64> {
        let (e0, e1, n0, n1) = self.frame.get().panned(dx, dy);
        vec![e0, e1, n0, n1]
    }
    /// The step nearest to time `t` (s, the log's clock).
    pub fn step_near_time(&self, t: f64) -> Option<usize> {
        self.a.step_near_time(t)
    }
    /// Shows the whole log again (a double-click).
    pub fn reset_span(&self) {
        self.span.set(Self::full(&self.a));
    }
    /// The time (s) at CSS pixel `x` from a plot canvas's left edge, within the span shown.
    /// `axis` is the `[left, right]` of the time axis (the columns [`Self::draw_plot`]
    /// returned, divided by the pixel ratio).
    pub fn axis_time_at(&self, axis: &[f64], x: f64) -> Result<f64, JsError> {
        Ok(self.time_axis(self.span.get(), axis)?.time_at(x))
    }
    /// The wheel turned by `delta_y` at CSS pixel `x` of a plot: the span zoomed about the
    /// pointer.
    pub fn axis_wheel(&self, axis: &[f64], x: f64, delta_y: f64) -> Result<(), JsError> {
        let k = crate::plot::wheel_factor(delta_y);
        let next = self.time_axis(self.span.get(), axis)?.zoomed_at(x, k);
        self.span.set(next);
        Ok(())
    }
    /// A pinch on a plot: one finger moved from CSS pixel `prev` to `x` while the other stays at
    /// `other`. Whether the span changed (not while the fingers are too close).
    pub fn axis_pinch(&self, axis: &[f64], prev: f64, x: f64, other: f64) -> Result<bool, JsError> {
        let next = self
            .time_axis(self.span.get(), axis)?
            .pinched(prev, x, other);
        if let Some(next) = next {
            self.span.set(next);
        }
        Ok(next.is_some())
    }
    /// A drag begins (or goes on with the finger left after a pinch): the span it pans from.
    pub fn axis_grab(&self) {
        self.grabbed.set(self.span.get());
    }
    /// A drag on a plot from CSS pixel `from` (where [`Self::axis_grab`] was called) to `x`:
    /// the span panned.
    pub fn axis_pan(&self, axis: &[f64], from: f64, x: f64) -> Result<(), JsError> {
        let next = self.time_axis(self.grabbed.get(), axis)?.panned(from, x);
        self.span.set(next);
        Ok(())
    }
    /// The track as GPX (geodetic when the log has fixes; see `io::export::track_gpx`).
    pub fn gpx(&self) -> String {
        crate::io::export::track_gpx(&self.a.steps, self.a.frame().as_ref())
    }
    /// The track as GeoJSON.
    pub fn geojson(&self) -> String {
        crate::io::export::track_geojson(&self.a.steps, self.a.frame().as_ref()).to_string()
    }
    /// One row per step, CSV.
    pub fn steps_csv(&self) -> String {
        crate::io::export::track_csv(&self.a.steps, self.a.frame().as_ref())
    }

    /// The whole log's span, s: its first and last samples' times.
    fn full(a: &crate::analysis::Analysis) -> (f64, f64) {
        (
            a.trace.t.first().copied().unwrap_or(0.0),
            a.trace.t.last().copied().unwrap_or(1.0),
        )
    }

    /// The plots' time axis showing `span`, its ends at the CSS pixels `axis` (two numbers).
    fn time_axis(
        &self,
        span: (f64, f64),
        axis: &[f64],
    ) -> Result<crate::plot::upload::TimeAxis, JsError> {
        let [left, right] = *axis else {
            return Err(to_js(format!(
                "`axis` needs two numbers, not {}",
                axis.len()
            )));
        };
        Ok(crate::plot::upload::TimeAxis {
            span,
            full: Self::full(&self.a),
            px: (left, right),
        })
    }
}
