//! Live mode's class: browser events in, readouts, drawing and the recording out; and the replay
//! of a recording.
//! May import: `engine`, `io`, `live`, `plot`, `settings`.

use super::calibration::read_profile;
use super::canvas::on_canvas;
use crate::plot::{draw_live, draw_scope, LiveView};
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// A live session for the live page: browser events in, readouts, drawing and the recording
/// out. Numbers cross the boundary as they come from the events; the conversions are in
/// [`crate::live`].
#[wasm_bindgen]
pub struct Live {
    session: crate::live::LiveSession,
}

/// The default configuration with the page's GNSS choice — `best` (every fix),
/// `energy-saving` (the receiver on for `window_s` every `period_s`, s; `None`: 10 s every 60 s)
/// or `off` — and the selected step-length profile (JSON).
pub(super) fn live_config(
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
