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
}

#[wasm_bindgen]
impl AnalysisView {
    /// Reads the bytes [`Upload::analyse`] made.
    pub fn from_bytes(bytes: &[u8]) -> Result<AnalysisView, JsError> {
        Ok(AnalysisView {
            a: crate::analysis::Analysis::from_bytes(bytes).map_err(to_js)?,
            frame: Default::default(),
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

    /// The metres the last map showed, `[min_e, max_e, min_n, max_n]`, and metres per canvas
    /// pixel.
    pub fn map_view(&self) -> Vec<f64> {
        let f = self.frame.get();
        vec![f.m.0, f.m.1, f.m.2, f.m.3, f.metres_per_px()]
    }

    /// The point (east, north) under canvas pixel (x, y) on the last map drawn.
    pub fn to_metres(&self, x: f64, y: f64) -> Vec<f64> {
        let (e, n) = self.frame.get().to_metres(x, y);
        vec![e, n]
    }

    /// The step nearest to canvas pixel (x, y) on the last map, within `radius` pixels.
    pub fn pick(&self, x: f64, y: f64, radius: f64) -> Option<usize> {
        crate::plot::upload::pick_step(&self.a, &self.frame.get(), x, y, radius)
    }

    /// Canvas pixel `[x, y]` of step `i` on the last map drawn.
    pub fn step_pixel(&self, i: usize) -> Option<Vec<f64>> {
        let (e, n) = self.a.step_position(i)?;
        let (x, y) = self.frame.get().to_pixel(e, n);
        Some(vec![x, y])
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

    /// The figures shown under the map: `[[label, text], …]`.
    pub fn figures(&self) -> Result<JsValue, JsError> {
        to_json_value(&self.a.figures())
    }

    /// Step `i` described for people.
    pub fn step_text(&self, i: usize) -> Result<String, JsError> {
        self.a
            .step_text(i)
            .ok_or_else(|| to_js(format!("no step {i}")))
    }

    /// The step nearest to time `t` (s, the log's clock).
    pub fn step_near_time(&self, t: f64) -> Option<usize> {
        self.a.step_near_time(t)
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

    /// Draws diagnostics plot `kind` (`accel`, `sigma`, `height`, `heading`, `steps`, `gnss`,
    /// `fusion`)
    /// between `t0` and `t1` (s), with a cursor at `cursor`. Returns the canvas pixel columns
    /// of `t0` and `t1`, then the rows of the plot area's top and bottom.
    pub fn draw_plot(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        kind: &str,
        t0: f64,
        t1: f64,
        cursor: Option<f64>,
    ) -> Result<Vec<f64>, JsError> {
        let plot = crate::plot::upload::Plot::parse(kind)
            .ok_or_else(|| to_js(format!("no plot `{kind}`")))?;
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::upload::draw_plot_area(area, &self.a, plot, (t0, t1), cursor, theme, scale)
        })
        .map(|((left, right), (top, bottom))| [left, right, top, bottom].map(f64::from).to_vec())
    }

    /// The time (s) at CSS pixel `x` from a plot canvas's left edge, within the span shown.
    /// `span` is the `[t0, t1]` shown, `full` the whole log's, `axis` the `[left, right]` of the
    /// time axis (the columns [`Self::draw_plot`] returned, divided by the pixel ratio).
    pub fn axis_time_at(
        &self,
        span: &[f64],
        full: &[f64],
        axis: &[f64],
        x: f64,
    ) -> Result<f64, JsError> {
        Ok(Self::time_axis(span, full, axis)?.time_at(x))
    }

    /// The wheel turned by `delta_y` at CSS pixel `x` of a plot: the next `[t0, t1]`, zoomed
    /// about the pointer.
    pub fn axis_wheel(
        &self,
        span: &[f64],
        full: &[f64],
        axis: &[f64],
        x: f64,
        delta_y: f64,
    ) -> Result<Vec<f64>, JsError> {
        let k = crate::plot::wheel_factor(delta_y);
        let (t0, t1) = Self::time_axis(span, full, axis)?.zoomed_at(x, k);
        Ok(vec![t0, t1])
    }

    /// A pinch on a plot: one finger moved from CSS pixel `prev` to `x` while the other stays at
    /// `other`. The next `[t0, t1]`, or nothing while the fingers are too close.
    pub fn axis_pinch(
        &self,
        span: &[f64],
        full: &[f64],
        axis: &[f64],
        prev: f64,
        x: f64,
        other: f64,
    ) -> Result<Option<Vec<f64>>, JsError> {
        let next = Self::time_axis(span, full, axis)?.pinched(prev, x, other);
        Ok(next.map(|(t0, t1)| vec![t0, t1]))
    }

    /// A drag on a plot from CSS pixel `from` to `x`, `span` being the one shown when the drag
    /// began: the next `[t0, t1]`.
    pub fn axis_pan(
        &self,
        span: &[f64],
        full: &[f64],
        axis: &[f64],
        from: f64,
        x: f64,
    ) -> Result<Vec<f64>, JsError> {
        let (t0, t1) = Self::time_axis(span, full, axis)?.panned(from, x);
        Ok(vec![t0, t1])
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
}

impl AnalysisView {
    /// The plots' time axis from the page's `span`, `full` and `axis`, two numbers each.
    fn time_axis(
        span: &[f64],
        full: &[f64],
        axis: &[f64],
    ) -> Result<crate::plot::upload::TimeAxis, JsError> {
        let pair = |v: &[f64], name: &str| match *v {
            [a, b] => Ok((a, b)),
            _ => Err(to_js(format!(
                "`{name}` needs two numbers, not {}",
                v.len()
            ))),
        };
        Ok(crate::plot::upload::TimeAxis {
            span: pair(span, "span")?,
            full: pair(full, "full")?,
            px: pair(axis, "axis")?,
        })
    }
}
