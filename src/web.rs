//! WebAssembly entry points (wasm-bindgen). Errors become `JsError` here and only here.

use crate::demo::{run_demo, run_fusion_demo, DemoSummary, FusionDemoSummary};
use crate::plot::{draw_fusion, draw_live, draw_scope, draw_track, FusionView, LiveView, Theme};
use plotters::prelude::IntoDrawingArea;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};
use plotters_canvas::CanvasBackend;
use serde::Serialize;
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

mod blobs;

/// plotters' canvas backend, with text measured by the canvas itself (`measureText`): plotters'
/// own web measurement puts a styled `<span>` in the page, which the page's Content Security
/// Policy (no inline styles) refuses, and which would measure the wrong font anyway.
struct Canvas {
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

type CanvasArea = plotters::drawing::DrawingArea<Canvas, plotters::coord::Shift>;

/// Runs `draw` on `canvas` (backing store sized by the caller to CSS size × `dpr`) with the
/// scheme's theme and the pixel ratio as the drawing scale, then presents it.
fn on_canvas<T, E: std::fmt::Display>(
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
    let out = draw(&area, &theme, dpr.clamp(1.0, 4.0)).map_err(|e| JsError::new(&e.to_string()))?;
    area.present().map_err(|e| JsError::new(&e.to_string()))?;
    Ok(out)
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

/// A profile file's JSON, read and checked (the error names the field).
fn read_profile(text: &str) -> Result<crate::engine::calibration::ProfileFile, JsError> {
    crate::engine::calibration::ProfileFile::from_json(text)
        .map_err(|e| JsError::new(&e.to_string()))
}

/// The default configuration with the page's GNSS choice — `best` (every fix),
/// `energy-saving` (the receiver on for `window_s` every `period_s`, s; `None`: 10 s every 60 s)
/// or `off` — and the selected step-length profile (JSON).
fn live_config(
    gnss: &str,
    profile: Option<String>,
    period_s: Option<f64>,
    window_s: Option<f64>,
) -> Result<crate::engine::PipelineConfig, JsError> {
    let mut c = crate::engine::PipelineConfig::default();
    if let Some(p) = profile {
        c.step_length = crate::engine::StepLengthModel::Frequency(read_profile(&p)?.profile);
    }
    match gnss {
        "best" => {}
        "energy-saving" => {
            use crate::engine::fusion::{GnssMode, DEFAULT_PERIOD_S, DEFAULT_WINDOW_S};
            c.fusion.mode = GnssMode::EnergySaving {
                period_s: period_s.unwrap_or(DEFAULT_PERIOD_S),
                window_s: window_s.unwrap_or(DEFAULT_WINDOW_S),
            };
        }
        "off" => c.fusion.mode = crate::engine::fusion::GnssMode::Off,
        other => return Err(JsError::new(&format!("unknown GNSS mode `{other}`"))),
    }
    c.validate().map_err(|e| JsError::new(&e.to_string()))?;
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
    /// A session with the default configuration, GNSS mode `gnss` (`best`, `energy-saving`,
    /// `off`) and the step-length profile `profile` (a profile file's JSON, or the default);
    /// `ios` selects Safari's conventions; `time_origin_ms` is `performance.timeOrigin` (event
    /// times are counted from it). In energy-saving mode the receiver is on for `window_s`
    /// every `period_s` (default 10 s every 60 s).
    #[wasm_bindgen(constructor)]
    pub fn new(
        ios: bool,
        time_origin_ms: f64,
        gnss: &str,
        profile: Option<String>,
        period_s: Option<f64>,
        window_s: Option<f64>,
    ) -> Result<Live, JsError> {
        let cfg = live_config(gnss, profile, period_s, window_s)?;
        crate::live::LiveSession::new(cfg, platform(ios), time_origin_ms)
            .map(|session| Live { session })
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// A session continuing a recording (pdr-log text) after a reload; the other arguments as
    /// for [`Live::new`].
    pub fn resume(
        ios: bool,
        time_origin_ms: f64,
        gnss: &str,
        profile: Option<String>,
        recorded: &str,
        period_s: Option<f64>,
        window_s: Option<f64>,
    ) -> Result<Live, JsError> {
        crate::live::LiveSession::resume(
            live_config(gnss, profile, period_s, window_s)?,
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

    /// The frequencies of the steps counted so far (a calibration walk's f_k), Hz.
    pub fn step_freqs(&self) -> Vec<f64> {
        self.session.step_freqs()
    }

    /// The distance along the fixes no worse than `max_accuracy_m`, m.
    pub fn fix_path_m(&self, max_accuracy_m: f64) -> f64 {
        self.session.fix_path_m(max_accuracy_m)
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

    /// Draws the map.
    pub fn draw(
        &mut self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
    ) -> Result<(), JsError> {
        let d = self.session.map_data();
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

/// Replays a pdr-log (a live recording) through the default engine with the step-length
/// profile `profile` (JSON, or the default): `{steps, distance_m, samples, skipped_lines}`.
#[wasm_bindgen]
pub fn replay_log(text: &str, profile: Option<String>) -> Result<JsValue, JsError> {
    let parsed = crate::io::pdrlog::read(text.as_bytes(), "recording")
        .map_err(|e| JsError::new(&e.to_string()))?;
    let r =
        crate::engine::pipeline::replay(live_config("best", profile, None, None)?, &parsed.records)
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

/// The calibration wizard's engine side: the walks, the fits, the profile and its chart.
#[wasm_bindgen]
pub struct CalibrationWizard {
    wizard: crate::engine::calibration::Wizard,
}

fn band(name: &str) -> Result<crate::engine::calibration::Band, JsError> {
    match name {
        "walking" => Ok(crate::engine::calibration::Band::Walking),
        "running" => Ok(crate::engine::calibration::Band::Running),
        other => Err(JsError::new(&format!("unknown band `{other}`"))),
    }
}

#[wasm_bindgen]
impl CalibrationWizard {
    /// No walks yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> CalibrationWizard {
        CalibrationWizard {
            wizard: Default::default(),
        }
    }

    /// Adds a walk of `distance_m` whose steps had the frequencies `step_freqs_hz`; returns
    /// its `{band, pace, distance_m, steps, f_mean_hz, sl_mean_m}`.
    pub fn add_walk(
        &mut self,
        band_name: &str,
        pace: &str,
        distance_m: f64,
        step_freqs_hz: Vec<f64>,
    ) -> Result<JsValue, JsError> {
        let walk = crate::engine::calibration::CalibrationWalk {
            distance_m,
            step_freqs_hz,
        };
        let w = self
            .wizard
            .add(band(band_name)?, pace, &walk)
            .map_err(|e| JsError::new(&e.to_string()))?;
        serde_wasm_bindgen::to_value(w).map_err(|e| JsError::new(&e.to_string()))
    }

    /// Removes walk `index` (an outlier the user drops).
    pub fn remove_walk(&mut self, index: usize) {
        if index < self.wizard.walks.len() {
            self.wizard.walks.remove(index);
        }
    }

    /// The walks, each band's fit with its warnings (explained, with the walk index of an
    /// outlier), and the profile's notes: `{walks, walking, running, notes}`.
    pub fn state(&self) -> Result<JsValue, JsError> {
        use crate::engine::calibration::{fit_band, Band, FitWarning};
        #[derive(serde::Serialize)]
        struct Warning {
            kind: &'static str,
            message: String,
            walk: Option<usize>,
        }
        #[derive(serde::Serialize)]
        struct Fit {
            points: usize,
            a: Option<f64>,
            b: Option<f64>,
            r2: Option<f64>,
            se: Option<(f64, f64)>,
            warnings: Vec<Warning>,
        }
        let fit = |b: Band| {
            // Indices of this band's walks among all walks, to name an outlier's walk.
            let idx: Vec<usize> = (0..self.wizard.walks.len())
                .filter(|&i| self.wizard.walks[i].band == b)
                .collect();
            let f = fit_band(&self.wizard.points(b));
            Fit {
                points: f.points.len(),
                a: f.fit.as_ref().map(|x| x.a),
                b: f.fit.as_ref().map(|x| x.b),
                r2: f.fit.as_ref().map(|x| x.r2),
                se: f.se,
                warnings: f
                    .warnings
                    .iter()
                    .map(|w| Warning {
                        kind: match w {
                            FitWarning::TooFewPoints { .. } => "too_few_points",
                            FitWarning::NarrowSpan { .. } => "narrow_span",
                            FitWarning::NegativeSlope { .. } => "negative_slope",
                            FitWarning::Outlier { .. } => "outlier",
                        },
                        message: w.message(),
                        walk: match w {
                            FitWarning::Outlier { index, .. } => idx.get(*index).copied(),
                            _ => None,
                        },
                    })
                    .collect(),
            }
        };
        #[derive(serde::Serialize)]
        struct State<'a> {
            walks: &'a [crate::engine::calibration::WizardWalk],
            walking: Fit,
            running: Fit,
            notes: Vec<String>,
        }
        let (_, notes) = self.wizard.profile(&Default::default());
        serde_wasm_bindgen::to_value(&State {
            walks: &self.wizard.walks,
            walking: fit(Band::Walking),
            running: fit(Band::Running),
            notes,
        })
        .map_err(|e| JsError::new(&e.to_string()))
    }

    /// The profile file (JSON) the walks make, named `name`.
    pub fn profile_json(&self, name: &str) -> String {
        use crate::engine::calibration::{Band, ProfileFile, PROFILE_VERSION};
        let (profile, _) = self.wizard.profile(&Default::default());
        ProfileFile {
            version: PROFILE_VERSION,
            name: name.to_string(),
            profile,
            walking_points: self.wizard.points(Band::Walking),
            running_points: self.wizard.points(Band::Running),
        }
        .to_json()
    }

    /// Draws a band's points, line and residuals.
    pub fn draw(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        band_name: &str,
    ) -> Result<(), JsError> {
        let b = band(band_name)?;
        let (profile, _) = self.wizard.profile(&Default::default());
        let line = match b {
            crate::engine::calibration::Band::Walking => profile.walking,
            crate::engine::calibration::Band::Running => profile.running,
        };
        let fit = crate::engine::calibration::fit_band(&self.wizard.points(b));
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::draw_calibration(area, &fit, &line, band_name, theme, scale)
        })
    }
}

impl Default for CalibrationWizard {
    fn default() -> Self {
        Self::new()
    }
}

/// Reads a profile file (JSON) and returns `{name, walking: {a, b}, running: {a, b}}`, or an
/// error naming the field that is wrong.
#[wasm_bindgen]
pub fn profile_summary(text: &str) -> Result<JsValue, JsError> {
    let p = read_profile(text)?;
    #[derive(serde::Serialize)]
    struct Summary<'a> {
        name: &'a str,
        walking: (f64, f64),
        running: (f64, f64),
        walking_points: usize,
        running_points: usize,
    }
    serde_wasm_bindgen::to_value(&Summary {
        name: &p.name,
        walking: (p.profile.walking.a, p.profile.walking.b),
        running: (p.profile.running.a, p.profile.running.b),
        walking_points: p.walking_points.len(),
        running_points: p.running_points.len(),
    })
    .map_err(|e| JsError::new(&e.to_string()))
}

/// Automatic refinement (Basso 2021 §2.2.5): the profile with its walking offset moved by the
/// fusion filter's step-length scale `k` at the cadence `f_hz`, a fraction `rate` of the way.
#[wasm_bindgen]
pub fn refine_profile(text: &str, k: f64, f_hz: f64, rate: f64) -> Result<String, JsError> {
    let mut p = read_profile(text)?;
    if !(k.is_finite() && k > 0.5 && k < 1.5 && f_hz.is_finite() && f_hz > 0.0) {
        return Err(JsError::new(&format!(
            "no refinement from a scale of {k} at {f_hz} Hz"
        )));
    }
    p.profile.walking.b =
        crate::engine::calibration::refined_offset(&p.profile.walking, k, f_hz, rate);
    p.profile
        .validate()
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(p.to_json())
}

impl Default for Demo {
    fn default() -> Self {
        Self::new()
    }
}

/// Upload mode, the web worker's side: files in, logs parsed, each analysed into bytes for the
/// page ([`AnalysisView`]).
#[wasm_bindgen]
pub struct Upload {
    files: Vec<(String, web_sys::Blob)>,
    logs: Vec<crate::io::import::Log>,
    engine_ms: f64,
}

#[wasm_bindgen]
impl Upload {
    /// No files yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Upload {
        Upload {
            files: Vec::new(),
            logs: Vec::new(),
            engine_ms: 0.0,
        }
    }

    /// How long the last [`Upload::analyse`] spent in the engine itself, ms: the records
    /// through the pipeline with the plots' signals kept, without the configuration, the
    /// serialisation and the copy out (for the benchmark's throughput).
    #[wasm_bindgen(getter)]
    pub fn engine_ms(&self) -> f64 {
        self.engine_ms
    }

    /// Adds a file: its name (with its folder path for a folder upload) and the `File`. Its bytes
    /// are read only while parsing, a slice at a time ([`blobs::BlobSet`]).
    pub fn add_file(&mut self, name: String, file: web_sys::Blob) {
        self.files.push((name, file));
    }

    /// Reads every log in the files: `{logs: [{index, source, format, samples, duration_s,
    /// warnings}], errors: [{file, line, column, field, message}]}`. A file that fails is an
    /// error; the others still load. `progress(bytes_read)` is called as reading goes on.
    /// Workers only (it reads with `FileReaderSync`).
    pub fn parse(&mut self, progress: js_sys::Function) -> Result<JsValue, JsError> {
        #[derive(serde::Serialize)]
        struct Info {
            index: usize,
            source: String,
            format: &'static str,
            samples: usize,
            duration_s: f64,
            warnings: usize,
        }
        #[derive(serde::Serialize)]
        struct Parsed {
            logs: Vec<Info>,
            errors: Vec<crate::io::ParseError>,
        }
        let mut set =
            blobs::BlobSet::new(std::mem::take(&mut self.files), progress).map_err(|_| {
                JsError::new("FileReaderSync is missing: upload parsing runs in a worker")
            })?;
        let mut out = Parsed {
            logs: Vec::new(),
            errors: Vec::new(),
        };
        for r in crate::io::import::import_all(&mut set) {
            match r {
                Ok(log) => {
                    out.logs.push(Info {
                        index: self.logs.len(),
                        source: log.source.clone(),
                        format: log.format.as_str(),
                        samples: log.imu_samples(),
                        duration_s: log.time_span().map_or(0.0, |(a, b)| b - a),
                        warnings: log.skipped as usize,
                    });
                    self.logs.push(log);
                }
                Err(e) => out.errors.push(e),
            }
        }
        serde_wasm_bindgen::to_value(&out).map_err(|e| JsError::new(&e.to_string()))
    }

    /// Runs the engine over log `index` with the default configuration changed by `sets`
    /// (`key=value`, as `pdr eval --set`), the step-length profile `profile` (JSON) and the
    /// GNSS mode; `progress(done, total)` is called as records go through. Returns the
    /// analysis as bytes for [`AnalysisView::from_bytes`].
    pub fn analyse(
        &mut self,
        index: usize,
        sets: Vec<String>,
        profile: Option<String>,
        gnss: &str,
        progress: &js_sys::Function,
    ) -> Result<Vec<u8>, JsError> {
        let log = self
            .logs
            .get(index)
            .ok_or_else(|| JsError::new(&format!("no log {index}")))?;
        let cfg = crate::eval::apply_overrides(&live_config(gnss, profile, None, None)?, &sets)
            .map_err(|e| JsError::new(&e))?;
        let t0 = js_sys::Date::now();
        let a = crate::analysis::analyse(log, &cfg, &mut |done, total| {
            let _ = progress.call2(
                &JsValue::NULL,
                &(done as f64).into(),
                &(total as f64).into(),
            );
        })
        .map_err(|e| JsError::new(&e.to_string()))?;
        self.engine_ms = js_sys::Date::now() - t0;
        Ok(a.to_bytes())
    }

    /// Log `index` in the project's own format (pdr-log).
    pub fn pdrlog(&self, index: usize) -> Result<String, JsError> {
        let log = self
            .logs
            .get(index)
            .ok_or_else(|| JsError::new(&format!("no log {index}")))?;
        Ok(crate::io::pdrlog::to_string(&log.records))
    }
}

impl Default for Upload {
    fn default() -> Self {
        Self::new()
    }
}

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
            a: crate::analysis::Analysis::from_bytes(bytes).map_err(|e| JsError::new(&e))?,
            frame: Default::default(),
        })
    }

    /// `{source, format, steps, samples, t0, t1, fixes, truth_waypoints, truth_steps,
    /// steps_without_heading, step_lengths_m, warnings, score}`; `score` is the bench's result
    /// (`pdr eval --json` for this log); the track's distance counts only the steps with a
    /// heading, `step_lengths_m` all of them.
    pub fn summary(&self) -> Result<JsValue, JsError> {
        let a = &self.a;
        let score: serde_json::Value =
            serde_json::from_str(&a.score_json).unwrap_or(serde_json::Value::Null);
        let v = serde_json::json!({
            "source": a.source,
            "format": a.format,
            "steps": a.steps.len(),
            "samples": a.trace.t.len(),
            "t0": a.trace.t.first(),
            "t1": a.trace.t.last(),
            "fixes": a.fixes.len(),
            "truth_waypoints": a.truth_path.len(),
            "truth_steps": a.truth_steps.len(),
            "steps_without_heading": a.steps.iter().filter(|s| s.heading_rad.is_none()).count(),
            "step_lengths_m": a.steps.iter().map(|s| s.length_m).sum::<f64>(),
            "warnings": a.warnings,
            "score": score,
        });
        v.serialize(&serde_wasm_bindgen::Serializer::json_compatible())
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// Draws the map; `bounds` `[min_e, max_e, min_n, max_n]` zooms (empty: fit all);
    /// `highlight` rings a step.
    pub fn draw_map(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        bounds: Vec<f64>,
        highlight: Option<usize>,
    ) -> Result<(), JsError> {
        let b = (bounds.len() == 4).then(|| (bounds[0], bounds[1], bounds[2], bounds[3]));
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::upload::draw_map(area, &self.a, b, highlight, theme, scale)
                .map(|f| self.frame.set(f))
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

    /// The step nearest to time `t` (s, the log's clock).
    pub fn step_near_time(&self, t: f64) -> Option<usize> {
        self.a.step_near_time(t)
    }

    /// Step `i`: `{index, t, t_rel_s, length_m, freq_hz, heading_deg, step_heading_deg, motion}`.
    pub fn step_info(&self, i: usize) -> Result<JsValue, JsError> {
        let s = self
            .a
            .steps
            .get(i)
            .ok_or_else(|| JsError::new(&format!("no step {i}")))?;
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
        });
        v.serialize(&serde_wasm_bindgen::Serializer::json_compatible())
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// Draws diagnostics plot `kind` (`accel`, `sigma`, `heading`, `steps`, `gnss`, `fusion`)
    /// between `t0` and `t1` (s), with a cursor at `cursor`. Returns the canvas pixel columns
    /// of `t0` and `t1`.
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
            .ok_or_else(|| JsError::new(&format!("no plot `{kind}`")))?;
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::upload::draw_plot(area, &self.a, plot, (t0, t1), cursor, theme, scale)
        })
        .map(|(left, right)| vec![f64::from(left), f64::from(right)])
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
            _ => Err(JsError::new(&format!(
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
