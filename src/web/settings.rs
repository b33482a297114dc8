//! The choices the page offers, by the configuration's own names, and how a configuration is
//! described.
//! May import: `settings`.

use super::{to_js, to_json_value, to_value};
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

/// What upload mode runs for a row of its form: the choices `set` (`{"detector.kind": …}`) and
/// the chosen profile (JSON, or `undefined` for the built-in line), as `{settings: {set,
/// profile}, label}`. The profile goes with the line in frequency, and with the fuzzy model
/// when the wizard's walks measured its scale; every other model runs without it (the fuzzy
/// model unscaled). An error names the setting that is wrong.
#[wasm_bindgen]
pub fn upload_config(set: JsValue, profile: Option<String>) -> Result<JsValue, JsError> {
    use crate::engine::calibration::ProfileFile;
    use crate::engine::StepLengthModel;
    let mut settings = crate::settings::Settings {
        set: super::from_js(&set).map_err(|e| to_js(format!("settings: {e}")))?,
        profile: None,
    };
    let takes_profile = match settings.config().map(|c| c.step_length) {
        Ok(StepLengthModel::Frequency(_)) => true,
        Ok(StepLengthModel::Fuzzy(_)) => profile
            .as_deref()
            .and_then(|t| ProfileFile::from_json(t).ok())
            .is_some_and(|f| f.fuzzy_scale.is_some()),
        _ => false,
    };
    settings.profile = profile.filter(|_| takes_profile);
    #[derive(serde::Serialize)]
    struct Config {
        settings: crate::settings::Settings,
        label: String,
    }
    let label = settings.label().map_err(to_js)?;
    to_json_value(&Config { settings, label })
}
