//! Live mode's class: browser events in, readouts, drawing and the recording out; and the replay
//! of a recording.
//! May import: `engine`, `io`, `live`, `plot`, `settings`.

use super::canvas::on_canvas;
use super::{settings_from, to_js, to_json_value, to_value};
use crate::live::display::Display;
use crate::live::{LiveSession, MotionEvent, OrientationEvent, Platform, SensorReading};
use crate::plot::{draw_live, draw_scope, LiveView};
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// A live session for the live page: browser events in, readouts, drawing and the recording
/// out. The events' fields are read here as the browser gives them; the conversions are in
/// [`crate::live`].
#[wasm_bindgen]
pub struct Live {
    session: LiveSession,
    display: Display,
}

fn platform(ios: bool) -> Platform {
    if ios {
        Platform::Ios
    } else {
        Platform::Android
    }
}

/// A number field of a JS object (`null`, `undefined` and non-numbers are `None`).
fn field(obj: &JsValue, name: &str) -> Option<f64> {
    js_sys::Reflect::get(obj, &JsValue::from_str(name))
        .ok()
        .and_then(|v| v.as_f64())
}

/// Three number fields, all or none.
fn fields3(obj: &JsValue, names: [&str; 3]) -> Option<[f64; 3]> {
    Some([
        field(obj, names[0])?,
        field(obj, names[1])?,
        field(obj, names[2])?,
    ])
}

#[wasm_bindgen]
impl Live {
    /// A session with `settings` (`{set, profile}`, see `choices()`; `undefined` for the
    /// defaults); `ios` selects Safari's conventions; `time_origin_ms` is
    /// `performance.timeOrigin` (event times are counted from it).
    #[wasm_bindgen(constructor)]
    pub fn new(settings: JsValue, ios: bool, time_origin_ms: f64) -> Result<Live, JsError> {
        let cfg = settings_from(settings)?.config().map_err(to_js)?;
        LiveSession::new(cfg, platform(ios), time_origin_ms)
            .map(|session| Live {
                session,
                display: Display::default(),
            })
            .map_err(to_js)
    }

    /// A session continuing a recording (pdr-log text) after a reload; the other arguments as
    /// for [`Live::new`].
    pub fn resume(
        settings: JsValue,
        ios: bool,
        time_origin_ms: f64,
        recorded: &str,
    ) -> Result<Live, JsError> {
        let cfg = settings_from(settings)?.config().map_err(to_js)?;
        LiveSession::resume(cfg, platform(ios), time_origin_ms, recorded)
            .map(|session| Live {
                session,
                display: Display::default(),
            })
            .map_err(to_js)
    }

    /// A `devicemotion` event. Returns the steps it completed, or `undefined` when the event
    /// carries no acceleration (Chromium without an accelerometer fires such events: no
    /// sample).
    pub fn push_motion(
        &mut self,
        e: &web_sys::DeviceMotionEvent,
    ) -> Result<Option<usize>, JsError> {
        let accel = e
            .acceleration_including_gravity()
            .and_then(|a| Some([a.x()?, a.y()?, a.z()?]));
        if accel.is_none() {
            return Ok(None);
        }
        let ev = MotionEvent {
            time_stamp_ms: e.time_stamp(),
            accel,
            rotation_rate_deg_s: e
                .rotation_rate()
                .and_then(|r| Some([r.alpha()?, r.beta()?, r.gamma()?])),
        };
        let steps = self.session.push_motion(&ev).map_err(to_js)?;
        self.display.changed();
        Ok(Some(steps))
    }

    /// A Generic Sensor API `Accelerometer` reading (m/s²) with the latest `Gyroscope` one
    /// (rad/s; its x, y, z are `null` before its first reading), at the accelerometer's
    /// `timestamp` (ms). Returns the steps it completed.
    pub fn push_sensor(&mut self, acc: &JsValue, gyr: &JsValue) -> Result<usize, JsError> {
        let r = SensorReading {
            timestamp_ms: field(acc, "timestamp").unwrap_or(f64::NAN),
            accel: fields3(acc, ["x", "y", "z"]).unwrap_or([f64::NAN; 3]),
            gyro_rad_s: fields3(gyr, ["x", "y", "z"]),
        };
        let steps = self.session.push_sensor(&r).map_err(to_js)?;
        self.display.changed();
        Ok(steps)
    }

    /// A `deviceorientationabsolute` event (`absolute_stream`) or a `deviceorientation` one,
    /// with `screen.orientation.angle` (degrees): iOS's `webkitCompassHeading` is read here.
    pub fn push_orientation(
        &mut self,
        e: &web_sys::DeviceOrientationEvent,
        absolute_stream: bool,
        screen_angle_deg: f64,
    ) {
        let ev = OrientationEvent {
            time_stamp_ms: e.time_stamp(),
            alpha: e.alpha(),
            beta: e.beta(),
            gamma: e.gamma(),
            absolute: absolute_stream || e.absolute(),
            compass_heading_deg: if absolute_stream {
                None
            } else {
                field(e, "webkitCompassHeading")
            },
            screen_angle_deg,
        };
        self.session.push_orientation(&ev);
    }

    /// An `AbsoluteOrientationSensor` reading: its `quaternion` `[x, y, z, w]` at its
    /// `timestamp` (ms).
    pub fn push_quaternion(&mut self, sensor: &JsValue) {
        let q = js_sys::Reflect::get(sensor, &JsValue::from_str("quaternion"))
            .ok()
            .map(|q| js_sys::Array::from(&q));
        let at = |i: u32| {
            q.as_ref()
                .and_then(|q| q.get(i).as_f64())
                .unwrap_or(f64::NAN)
        };
        let t = field(sensor, "timestamp").unwrap_or(f64::NAN);
        self.session
            .push_quaternion(t, [at(0), at(1), at(2), at(3)]);
    }

    /// A geolocation position (`watchPosition`'s argument) that arrived at `time_ms` on the
    /// page's clock (`performance.now()`).
    pub fn push_fix(&mut self, time_ms: f64, position: &JsValue) -> Result<(), JsError> {
        let c = js_sys::Reflect::get(position, &JsValue::from_str("coords"))
            .map_err(|_| to_js("the position has no coords"))?;
        let f = crate::engine::GnssFix {
            t: time_ms * 1e-3,
            lat_deg: field(&c, "latitude").unwrap_or(f64::NAN),
            lon_deg: field(&c, "longitude").unwrap_or(f64::NAN),
            h_accuracy_m: field(&c, "accuracy").unwrap_or(f64::NAN),
            altitude_m: field(&c, "altitude"),
            speed_mps: field(&c, "speed"),
            bearing_deg: field(&c, "heading").filter(|h| h.is_finite()),
        };
        self.session.push_fix(&f).map_err(to_js)?;
        self.display.changed();
        Ok(())
    }

    /// A calibration walk toward `target_m`, measured by GNSS when `gnss` (see
    /// `live::wizard::walk_state`): `{text, distance_m, done}`.
    pub fn calibration_walk(&self, target_m: f64, gnss: bool) -> Result<JsValue, JsError> {
        to_value(&self.walk_state(target_m, gnss))
    }

    /// What the walk says about the user's step length (for `refine_profile`): `{fixes,
    /// fixes_used, verdict: "calibrated" | … | undefined, scale: [k, sd] | undefined,
    /// step_freqs_hz}`.
    pub fn walk_evidence(&self) -> Result<JsValue, JsError> {
        to_value(&self.session.walk_evidence())
    }

    /// The session starts at `now_ms` (the page's clock), running the fusion mode `gnss_mode`,
    /// `recorded` or not (a calibration walk), in a browser with or without `geolocation`.
    pub fn start(&mut self, now_ms: f64, gnss_mode: &str, recorded: bool, geolocation: bool) {
        self.display.start(now_ms, gnss_mode, recorded, geolocation);
    }

    /// The page was hidden (`hidden`) or shown at `now_ms`; returns whether it came back from
    /// hidden: the span it was hidden is marked as a gap, so that nothing bridges it.
    pub fn visibility(&mut self, hidden: bool, now_ms: f64) -> bool {
        let span = self.display.visibility(hidden, now_ms);
        if let Some((t0, t1)) = span {
            self.session.mark_gap(t0, t1);
        }
        span.is_some()
    }

    /// The geolocation watch failed, `denied` by the user or not: the key of the message to
    /// show (see `live::display::Display::location_failed`).
    pub fn location_failed(&mut self, denied: bool) -> String {
        self.display.location_failed(denied).to_string()
    }

    /// Draw at the next tick, however recent the last draw (a resize, the guard unlocked).
    pub fn redraw(&mut self) {
        self.display.redraw();
    }

    /// What the page does at a display tick at `now_ms` (see `live::display::Tick`): `{texts,
    /// titles, notice, verdict, messages: [[key, shown, kind]], gnss: "on" | "off" | undefined,
    /// draw}`, or `undefined` when there is nothing to do. `source` names the motion
    /// source; `guard_hidden`: the pocket guard is off (the plots can be seen).
    pub fn tick(
        &mut self,
        now_ms: f64,
        source: &str,
        guard_hidden: bool,
    ) -> Result<JsValue, JsError> {
        let r = self.session.readouts();
        to_value(&self.display.tick(now_ms, &r, source, guard_hidden))
    }

    /// The recording has stopped: places the steps still held at a bout's opening (see
    /// `live::LiveSession::finish`); returns how many. The display ticks only for a change from
    /// now on.
    pub fn finish(&mut self) -> usize {
        self.display.end();
        self.session.finish()
    }

    /// The recording since the last call, as pdr-log lines.
    pub fn take_log(&mut self) -> String {
        self.session.take_log()
    }

    /// Takes the recording since the last call as `recorder`'s next chunk, with the samples
    /// and steps counted so far.
    pub fn log_to(&mut self, recorder: &mut super::recorder::Recorder) {
        let text = self.session.take_log();
        let r = self.session.readouts();
        recorder.inner.push(text, r.samples, r.steps);
    }

    /// The readouts (see `live::Readouts`).
    pub fn readouts(&self) -> Result<JsValue, JsError> {
        to_value(&self.session.readouts())
    }

    /// Draws the map (over the base map when it is on and a fix has placed the walk).
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
        super::basemap::with_basemap(canvas, d.origin, |basemap| {
            on_canvas(canvas, dark, dpr, |area, theme, scale| {
                draw_live(area, &view, basemap, theme, scale)
            })
        })
    }

    /// Draws the last ten seconds of vertical acceleration, PLL output and steps.
    pub fn draw_scope(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
    ) -> Result<(), JsError> {
        let d = self.session.scope_data();
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            draw_scope(
                area,
                &d.samples,
                &d.steps,
                d.now,
                crate::live::SCOPE_S,
                theme,
                scale,
            )
        })
    }
}

impl Live {
    /// The session (for the calibration wizard, which reads a walk's steps).
    pub(super) fn session(&self) -> &LiveSession {
        &self.session
    }

    /// A calibration walk toward `target_m`; with `gnss`, its distance is the path of the fixes
    /// no worse than the wizard's limit (`engine::calibration::GNSS_MAX_ACCURACY_M`).
    pub(super) fn walk_state(
        &self,
        target_m: f64,
        gnss: bool,
    ) -> crate::live::wizard::WalkProgress {
        let limit_m = crate::engine::calibration::GNSS_MAX_ACCURACY_M;
        let path = gnss.then(|| self.session.fix_path_m(limit_m));
        crate::live::wizard::walk_state(self.session.readouts().steps, path, target_m)
    }
}

/// Live mode's message for `key` (see `live::messages`), or an error for an unknown key.
#[wasm_bindgen]
pub fn live_message(key: &str) -> Result<String, JsError> {
    crate::live::messages::message(key)
        .map(str::to_string)
        .ok_or_else(|| to_js(format!("no live message `{key}`")))
}

/// The keys of the messages a new start clears (see `live::messages::CLEARED_AT_START`).
#[wasm_bindgen]
pub fn live_messages_cleared() -> Vec<String> {
    crate::live::messages::CLEARED_AT_START
        .map(str::to_string)
        .to_vec()
}

/// The recovery offer's sentence (see `live::messages::recovery_offer`).
#[wasm_bindgen]
pub fn recovery_offer(started: &str, samples: usize, steps: Option<usize>, damage: &str) -> String {
    crate::live::messages::recovery_offer(started, samples, steps, damage)
}

/// What the page says about its stored list of `what` that cannot be read: kept aside under the
/// keys `kept`, or (none kept) it cannot even be moved aside.
#[wasm_bindgen]
pub fn stored_unreadable(what: &str, kept: Vec<String>) -> String {
    if kept.is_empty() {
        crate::live::messages::stored_unreadable(what)
    } else {
        crate::live::messages::kept_aside(what, &kept)
    }
}

/// Why a change to the page's stored list of `what` is refused: it can neither be read nor
/// kept aside.
#[wasm_bindgen]
pub fn stored_not_saved(what: &str) -> String {
    crate::live::messages::not_saved(what)
}

/// Whether the browser follows iOS's conventions for motion events (see `live::is_ios`), from
/// `navigator.userAgent` and `navigator.maxTouchPoints`.
#[wasm_bindgen]
pub fn is_ios(user_agent: &str, max_touch_points: f64) -> bool {
    crate::live::is_ios(user_agent, max_touch_points)
}

/// Live mode's buttons in `state` (`idle`, `recording`, `stopped`): `[[id, hidden]]`.
#[wasm_bindgen]
pub fn live_controls(state: &str) -> Result<JsValue, JsError> {
    to_value(&crate::live::controls::controls(state))
}

/// Replays a pdr-log (a live recording) through the engine with `settings` (`{set, profile}`;
/// `undefined` for the defaults): `{steps, distance_m, samples, skipped_lines}`.
#[wasm_bindgen]
pub fn replay_log(text: &str, settings: JsValue) -> Result<JsValue, JsError> {
    let mut cfg = settings_from(settings)?.config().map_err(to_js)?;
    let parsed = crate::io::pdrlog::read(text.as_bytes(), "recording").map_err(to_js)?;
    if cfg.fusion.date_unix_s.is_none() {
        cfg.fusion.date_unix_s = parsed.date_unix_s.or_else(|| {
            crate::io::import::date::from_clock(
                parsed.records.first().map(crate::engine::Record::t),
            )
        });
    }
    let r = crate::engine::replay::replay(cfg, &parsed.records).map_err(to_js)?;
    let d = r.pipeline.diagnostics();
    #[derive(serde::Serialize)]
    struct Summary {
        steps: usize,
        distance_m: f64,
        samples: u64,
        skipped_lines: u64,
    }
    to_value(&Summary {
        steps: r.pipeline.track().len(),
        distance_m: d.distance_m,
        samples: d.samples,
        skipped_lines: parsed.skipped,
    })
}

/// What can be read of a live recording stored in pieces (`[{seq, text}]`, as IndexedDB holds
/// them), for the recovery offer and the download: `{text, samples, steps, skipped_lines,
/// missing_pieces, notes, damage}` (`steps`: what the page counted when the last piece that
/// says was taken, `null` when none does). `text` is `null` when the pieces joined in the order given
/// are a whole, good log (use them as they are), else the log of every good line (see
/// `io::pdrlog::recover`); `damage` is the offer's sentence about a damaged one, or "". Never
/// throws: anything that is not a piece is noted and skipped.
#[wasm_bindgen]
pub fn recover_recording(pieces: &JsValue) -> Result<JsValue, JsError> {
    let get = |o: &JsValue, k: &str| js_sys::Reflect::get(o, &JsValue::from_str(k)).ok();
    let mut bad = Vec::new();
    let mut owned: Vec<(u64, Option<String>)> = Vec::new();
    let mut steps = None;
    if let Some(arr) = pieces.dyn_ref::<js_sys::Array>() {
        for (i, p) in arr.iter().enumerate() {
            let n = get(&p, "steps").and_then(|v| v.as_f64());
            steps = n.filter(|n| n.is_finite()).or(steps);
            match get(&p, "seq").and_then(|v| v.as_f64()) {
                Some(seq) if seq >= 0.0 && seq.fract() == 0.0 && seq < 1e15 => {
                    owned.push((seq as u64, get(&p, "text").and_then(|t| t.as_string())));
                }
                _ => bad.push(format!("stored piece {i} has no number: skipped")),
            }
        }
    } else {
        bad.push("the stored recording is not a list of pieces".to_string());
    }
    let borrowed: Vec<(u64, Option<&str>)> =
        owned.iter().map(|(s, t)| (*s, t.as_deref())).collect();
    let r = crate::io::pdrlog::recover(&borrowed);
    #[derive(serde::Serialize)]
    struct Summary {
        text: Option<String>,
        samples: usize,
        skipped_lines: u64,
        missing_pieces: u64,
        steps: Option<f64>,
        notes: Vec<String>,
        damage: String,
    }
    let whole = r.whole && bad.is_empty();
    let skipped_lines = r.skipped_lines + bad.len() as u64;
    let notes: Vec<String> = bad.into_iter().chain(r.notes).collect();
    to_json_value(&Summary {
        text: (!whole).then(|| crate::io::pdrlog::to_string(&r.records)),
        samples: r.samples,
        skipped_lines,
        missing_pieces: r.missing_pieces,
        steps,
        damage: crate::live::messages::damage(skipped_lines, r.missing_pieces, &notes),
        notes,
    })
}
