//! Upload mode's page words and pieces (`analysis::page`), exported: the progress and status
//! sentences, the banners after reading, and the result card and map box as view trees.
//! May import: `analysis`.

use super::to_json_value;
use crate::analysis::page;
use wasm_bindgen::prelude::*;

/// The status as `files` files are being opened ("reading 3 files…").
#[wasm_bindgen]
pub fn reading_text(files: usize) -> String {
    page::reading_text(files)
}

/// `[status, fraction of the bar]` while `done` of `total` bytes are parsed.
#[wasm_bindgen]
pub fn read_progress(done: f64, total: f64) -> Result<JsValue, JsError> {
    to_json_value(&page::read_progress(done, total))
}

/// `[status, fraction of the bar]` while log `index` of `logs` (`source`, `samples` long) goes
/// through the engine, `done` of `total` finished.
#[wasm_bindgen]
pub fn engine_progress(
    source: &str,
    samples: usize,
    done: f64,
    total: f64,
    index: usize,
    logs: usize,
) -> Result<JsValue, JsError> {
    to_json_value(&page::engine_progress(
        source,
        samples,
        (done, total),
        index,
        logs,
    ))
}

/// The status once done: `logs` read from `bytes` (0: not said) in `seconds`, `refused` files
/// refused.
#[wasm_bindgen]
pub fn loaded_text(logs: usize, bytes: f64, seconds: f64, refused: usize) -> String {
    page::loaded_text(logs, bytes, seconds, refused)
}

/// The banner when the user stops a load.
#[wasm_bindgen]
pub fn cancelled_text() -> String {
    page::CANCELLED.to_string()
}

/// The result card of log `index` (`source`, `hint`) as a view tree.
#[wasm_bindgen]
pub fn result_card(index: usize, source: &str, hint: &str) -> Result<JsValue, JsError> {
    to_json_value(&page::result_card(index, source, hint, &plot_list()))
}

/// The box of run `tag`'s map as a view tree.
#[wasm_bindgen]
pub fn map_box(tag: &str) -> Result<JsValue, JsError> {
    to_json_value(&page::map_box(tag))
}

/// The heading of run `tag`'s map, naming the configuration `label`; hidden unless there are
/// `two` maps.
#[wasm_bindgen]
pub fn config_label(tag: &str, label: &str, two: bool) -> Result<JsValue, JsError> {
    to_json_value(&page::config_label(tag, label, two))
}

/// The choices of a row's profile, option view trees: the built-in step length, then the saved
/// profiles `names`, sorted.
#[wasm_bindgen]
pub fn profile_options(names: Vec<String>) -> Result<JsValue, JsError> {
    to_json_value(&page::profile_options(&names))
}

/// The diagnostics plots in the page's order, `(kind, title)`: the kind
/// `AnalysisView.draw_plot` takes and the title people read (the canvas's label).
pub(super) fn plot_list() -> Vec<(&'static str, &'static str)> {
    use crate::plot::upload::Plot;
    Plot::ALL
        .iter()
        .map(|p| match p {
            Plot::Accel => ("accel", "Vertical acceleration, PLL output and steps"),
            Plot::Sigma => ("sigma", "σ of vertical acceleration and activity"),
            Plot::Height => ("height", "Height above the start and floor"),
            Plot::Heading => ("heading", "Heading per step"),
            Plot::Steps => ("steps", "Step frequency and length"),
            Plot::Gnss => ("gnss", "GNSS accuracy and innovations"),
            Plot::Fusion => (
                "fusion",
                "Fusion: estimated step-length scale and heading correction",
            ),
        })
        .collect()
}
