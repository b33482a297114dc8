//! Upload mode's canvases read pointers here: the page forwards each event's numbers to a
//! [`Gesture`] (one per canvas) through the analysis it shows, and is answered what to redraw or
//! which step to select (the rules: `plot::gesture`).
//! May import: `plot`.

use super::analysis_view::AnalysisView;
use super::{to_js, to_json_value};
use crate::plot::gesture::{self, Action, Input, Surface};
use wasm_bindgen::prelude::*;

/// The pointers on one canvas of upload mode: the map's (`map`) or a plot's (`plot`).
#[wasm_bindgen]
pub struct Gesture(gesture::Gesture);

#[wasm_bindgen]
impl Gesture {
    /// No pointer down on a `map` or a `plot` canvas.
    #[wasm_bindgen(constructor)]
    pub fn new(surface: &str) -> Result<Gesture, JsError> {
        let s = match surface {
            "map" => Surface::Map,
            "plot" => Surface::Axis,
            _ => return Err(to_js(format!("no gesture surface `{surface}`"))),
        };
        Ok(Gesture(gesture::Gesture::new(s)))
    }
}

/// An event's numbers as the page passes them: `kind` its type (`pointerdown`, `pointermove`,
/// `pointerup`, `pointercancel`, `wheel`, `dblclick`), `id` its pointer, `mouse` whether that is
/// a mouse, (`x`, `y`) where it is on the canvas (canvas pixels for the map, CSS pixels for the
/// plots), `delta_y` the wheel's turn, `scale` canvas pixels per CSS pixel.
#[derive(serde::Deserialize)]
struct Event {
    kind: String,
    #[serde(default)]
    id: i32,
    #[serde(default)]
    mouse: bool,
    x: f64,
    #[serde(default)]
    y: f64,
    #[serde(default)]
    delta_y: f64,
    #[serde(default = "one")]
    scale: f64,
}

fn one() -> f64 {
    1.0
}

impl Event {
    fn read(v: JsValue) -> Result<(Event, Input), JsError> {
        let e: Event = super::from_js(&v).map_err(|e| to_js(format!("event: {e}")))?;
        let (id, at) = (e.id, (e.x, e.y));
        let input = match e.kind.as_str() {
            "pointerdown" => Input::Down { id, at },
            "pointermove" => Input::Move {
                id,
                at,
                mouse: e.mouse,
            },
            "pointerup" => Input::Up { id, at },
            "pointercancel" => Input::Cancel { id },
            "wheel" => Input::Wheel {
                at,
                delta_y: e.delta_y,
            },
            "dblclick" => Input::DoubleClick,
            k => return Err(to_js(format!("no gesture event `{k}`"))),
        };
        Ok((e, input))
    }
}

/// What the page does after an event: select `step`, show the map's `bounds` (empty: fit all),
/// redraw the plots.
#[derive(serde::Serialize, Default)]
struct Answer {
    step: Option<usize>,
    bounds: Option<Vec<f64>>,
    redraw: bool,
}

#[wasm_bindgen]
impl AnalysisView {
    /// An event on this analysis's map through `gesture`: a mouse over it picks the step within
    /// 12 CSS pixels (unless it is `selected`), a tap the one within 24, a drag pans, two
    /// pointers or the wheel zoom, a double-click fits all. Answers `{step, bounds, redraw}`.
    pub fn map_gesture(
        &self,
        gesture: &mut Gesture,
        event: JsValue,
        selected: Option<usize>,
    ) -> Result<JsValue, JsError> {
        let (e, input) = Event::read(event)?;
        let mut out = Answer::default();
        match gesture.0.event(input) {
            Action::Hover((x, y)) => {
                out.step = self
                    .pick(x, y, gesture::HOVER_RADIUS_CSS_PX * e.scale)
                    .filter(|&i| Some(i) != selected);
            }
            Action::Tap((x, y)) => out.step = self.pick(x, y, gesture::TAP_RADIUS_CSS_PX * e.scale),
            Action::Pan { from, to } => {
                out.bounds = Some(self.map_pan(to.0 - from.0, to.1 - from.1))
            }
            Action::Pinch { prev, now, other } => {
                out.bounds = self.map_pinch(prev.0, prev.1, now.0, now.1, other.0, other.1);
            }
            Action::Zoom { at, delta_y } => out.bounds = Some(self.map_wheel(at.0, at.1, delta_y)),
            Action::Reset => out.bounds = Some(Vec::new()),
            Action::Grab | Action::None => {}
        }
        to_json_value(&out)
    }

    /// An event on one of the plots through `gesture`, `axis` the `[left, right]` of its time
    /// axis (CSS pixels): a tap picks the step nearest that time, a drag pans the span, two
    /// pointers or the wheel zoom it, a double-click shows the whole log. Answers `{step, bounds,
    /// redraw}`.
    pub fn plot_gesture(
        &self,
        gesture: &mut Gesture,
        event: JsValue,
        axis: Vec<f64>,
    ) -> Result<JsValue, JsError> {
        let (_, input) = Event::read(event)?;
        let mut out = Answer::default();
        match gesture.0.event(input) {
            Action::Grab => self.axis_grab(),
            Action::Tap((x, _)) => out.step = self.step_near_time(self.axis_time_at(&axis, x)?),
            Action::Pan { from, to } => {
                self.axis_pan(&axis, from.0, to.0)?;
                out.redraw = true;
            }
            Action::Pinch { prev, now, other } => {
                out.redraw = self.axis_pinch(&axis, prev.0, now.0, other.0)?;
            }
            Action::Zoom { at, delta_y } => {
                self.axis_wheel(&axis, at.0, delta_y)?;
                out.redraw = true;
            }
            Action::Reset => {
                self.reset_span();
                out.redraw = true;
            }
            Action::Hover(_) | Action::None => {}
        }
        to_json_value(&out)
    }
}
