//! WebAssembly entry points (wasm-bindgen). Errors become `JsError` here and only here.

use crate::demo::{run_demo, run_fusion_demo, DemoSummary, FusionDemoSummary};
use crate::plot::{draw_fusion, draw_live, draw_scope, draw_track, FusionView, LiveView, Theme};
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

/// A live session for the live page: browser events in, readouts, drawing and the recording
/// out. Numbers cross the boundary as they come from the events; the conversions are in
/// [`crate::live`].
#[wasm_bindgen]
pub struct Live {
    session: crate::live::LiveSession,
}

/// The default configuration with the page's GNSS choice: `best` (every fix),
/// `energy-saving` (10 s every 60 s) or `off`.
fn live_config(gnss: &str) -> Result<crate::engine::PipelineConfig, JsError> {
    let mut c = crate::engine::PipelineConfig::default();
    match gnss {
        "best" => {}
        "energy-saving" => {
            if let Some(f) = &mut c.fusion {
                f.mode = crate::engine::fusion::GnssMode::ENERGY_SAVING;
            }
        }
        "off" => c.fusion = None,
        other => return Err(JsError::new(&format!("unknown GNSS mode `{other}`"))),
    }
    Ok(c)
}

fn platform(ios: bool) -> crate::live::Platform {
    if ios {
        crate::live::Platform::Ios
    } else {
        crate::live::Platform::Android
    }
}

#[wasm_bindgen]
impl Live {
    /// A session with the default configuration and GNSS mode `gnss` (`best`,
    /// `energy-saving`, `off`); `ios` selects Safari's conventions; `time_origin_ms` is
    /// `performance.timeOrigin` (event times are counted from it).
    #[wasm_bindgen(constructor)]
    pub fn new(ios: bool, time_origin_ms: f64, gnss: &str) -> Result<Live, JsError> {
        crate::live::LiveSession::new(live_config(gnss)?, platform(ios), time_origin_ms)
            .map(|session| Live { session })
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// A session continuing a recording (pdr-log text) after a reload.
    pub fn resume(
        ios: bool,
        time_origin_ms: f64,
        gnss: &str,
        recorded: &str,
    ) -> Result<Live, JsError> {
        crate::live::LiveSession::resume(
            live_config(gnss)?,
            platform(ios),
            time_origin_ms,
            recorded,
        )
        .map(|session| Live { session })
        .map_err(|e| JsError::new(&e))
    }

    /// A `devicemotion` event: `event.timeStamp` (ms), `accelerationIncludingGravity`,
    /// `rotationRate` (deg/s; all three or none) and `interval`. Returns the steps it completed.
    pub fn push_motion(
        &mut self,
        time_stamp_ms: f64,
        ax: Option<f64>,
        ay: Option<f64>,
        az: Option<f64>,
        alpha: Option<f64>,
        beta: Option<f64>,
        gamma: Option<f64>,
        interval: Option<f64>,
    ) -> Result<usize, JsError> {
        let ev = crate::live::MotionEvent {
            time_stamp_ms,
            accel: ax.zip(ay).zip(az).map(|((x, y), z)| [x, y, z]),
            rotation_rate_deg_s: alpha.zip(beta).zip(gamma).map(|((a, b), g)| [a, b, g]),
            interval,
        };
        self.session
            .push_motion(&ev)
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// A Generic Sensor API `Accelerometer` reading (m/s²) with the latest `Gyroscope` one
    /// (rad/s, all three or none), at the accelerometer's `timestamp` (ms).
    pub fn push_sensor(
        &mut self,
        timestamp_ms: f64,
        ax: f64,
        ay: f64,
        az: f64,
        gx: Option<f64>,
        gy: Option<f64>,
        gz: Option<f64>,
    ) -> Result<usize, JsError> {
        let gyro = gx.zip(gy).zip(gz).map(|((x, y), z)| [x, y, z]);
        self.session
            .push_sensor(timestamp_ms, [ax, ay, az], gyro)
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// A `deviceorientation(absolute)` event, degrees.
    pub fn push_orientation(
        &mut self,
        time_stamp_ms: f64,
        alpha: f64,
        beta: f64,
        gamma: f64,
        absolute: bool,
    ) {
        self.session
            .push_orientation(time_stamp_ms, alpha, beta, gamma, absolute);
    }

    /// An iOS `deviceorientation` event with `webkitCompassHeading` (degrees), and
    /// `screen.orientation.angle`.
    pub fn push_compass(
        &mut self,
        time_stamp_ms: f64,
        compass_heading_deg: f64,
        beta: f64,
        gamma: f64,
        screen_angle_deg: f64,
    ) {
        let alpha = crate::live::ios_compass_alpha(compass_heading_deg, screen_angle_deg);
        self.session
            .push_orientation(time_stamp_ms, alpha, beta, gamma, true);
    }

    /// An `AbsoluteOrientationSensor` quaternion `[x, y, z, w]`.
    pub fn push_quaternion(&mut self, timestamp_ms: f64, x: f64, y: f64, z: f64, w: f64) {
        self.session.push_quaternion(timestamp_ms, [x, y, z, w]);
    }

    /// A geolocation fix; `time_ms` on the page's clock (`performance.now()` at arrival).
    pub fn push_fix(
        &mut self,
        time_ms: f64,
        lat: f64,
        lon: f64,
        accuracy_m: f64,
        altitude_m: Option<f64>,
        speed_mps: Option<f64>,
        heading_deg: Option<f64>,
    ) -> Result<(), JsError> {
        let f = crate::engine::GnssFix {
            t: time_ms * 1e-3,
            lat_deg: lat,
            lon_deg: lon,
            h_accuracy_m: accuracy_m,
            altitude_m,
            speed_mps,
            bearing_deg: heading_deg,
        };
        self.session
            .push_fix(&f)
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// The page was hidden between two times (ms, page clock).
    pub fn mark_gap(&mut self, t0_ms: f64, t1_ms: f64) {
        self.session.mark_gap(t0_ms, t1_ms);
    }

    /// The recording since the last call, as pdr-log lines.
    pub fn take_log(&mut self) -> String {
        self.session.take_log()
    }

    /// The readouts (see `live::Readouts`).
    pub fn readouts(&self) -> Result<JsValue, JsError> {
        serde_wasm_bindgen::to_value(&self.session.readouts())
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// Draws the map; `ended` adds the smoothed track (after Stop).
    pub fn draw(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        ended: bool,
    ) -> Result<(), JsError> {
        let d = self.session.map_data(ended);
        let view = LiveView {
            pdr: &d.pdr,
            fused: &d.fused,
            smoothed: &d.smoothed,
            fixes: &d.fixes,
            gaps: &d.gaps,
            heading_rad: d.heading_rad,
        };
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            draw_live(area, &view, theme, scale)
        })
    }

    /// Draws the last ten seconds of vertical acceleration, PLL output and steps.
    pub fn draw_scope(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
    ) -> Result<(), JsError> {
        let (samples, steps, now) = self.session.scope_data();
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            draw_scope(
                area,
                &samples,
                &steps,
                now,
                crate::live::SCOPE_S,
                theme,
                scale,
            )
        })
    }
}

/// Replays a pdr-log (a live recording) through the default engine: `{steps, distance_m,
/// samples, errors}`.
#[wasm_bindgen]
pub fn replay_log(text: &str) -> Result<JsValue, JsError> {
    let parsed = crate::io::pdrlog::read(text.as_bytes(), "recording")
        .map_err(|e| JsError::new(&e.to_string()))?;
    let r =
        crate::engine::pipeline::replay(crate::engine::PipelineConfig::default(), &parsed.records)
            .map_err(|e| JsError::new(&e.to_string()))?;
    let d = r.pipeline.diagnostics();
    #[derive(serde::Serialize)]
    struct Summary {
        steps: usize,
        distance_m: f64,
        samples: u64,
        skipped_lines: u64,
    }
    serde_wasm_bindgen::to_value(&Summary {
        steps: r.pipeline.track().len(),
        distance_m: d.distance_m,
        samples: d.samples,
        skipped_lines: parsed.skipped,
    })
    .map_err(|e| JsError::new(&e.to_string()))
}

impl Default for Demo {
    fn default() -> Self {
        Self::new()
    }
}
