//! The choices the page offers, by the configuration's own names, and how a configuration is
//! described.
//! May import: `settings`.

use super::{settings_from, to_js, to_json_value, to_value};
use crate::settings::{compare_preset, CHOICES};
use wasm_bindgen::prelude::*;

/// The choices offered by name: `[{key, title, flag, options: [[value, label], …]}]`, each
/// `key` a dotted path of the configuration and each `value` its own name.
#[wasm_bindgen]
pub fn choices() -> Result<JsValue, JsError> {
    to_value(CHOICES)
}

/// The settings upload mode's second configuration starts with (`{set, profile}`).
#[wasm_bindgen]
pub fn compare_settings() -> Result<JsValue, JsError> {
    to_json_value(&compare_preset())
}

/// How a configuration is described to people ("PLL (Basso 2016), tip-to-tail (2016), …"), or
/// an error naming the setting that is wrong.
#[wasm_bindgen]
pub fn settings_label(settings: JsValue) -> Result<String, JsError> {
    settings_from(settings)?.label().map_err(to_js)
}
