//! WebAssembly entry points (wasm-bindgen): one file per class the page uses, and the choices it
//! offers. Errors become `JsError` here and only here ([`to_js`]).
//! May import: everything below it (`engine`, `io`, `plot`, `settings`, `live`, `analysis`,
//! `eval`, `demo`); nothing imports it.

mod analysis_view;
mod basemap;
mod blobs;
mod calibration;
mod canvas;
mod demo;
mod gesture;
mod live;
mod recipe_form;
mod recorder;
mod settings;
mod upload;
mod upload_page;

use wasm_bindgen::prelude::*;

/// A Rust error as the page sees it: the one conversion.
fn to_js(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A value for the page (objects for structs, `undefined` for `None`).
fn to_value<T: serde::Serialize + ?Sized>(v: &T) -> Result<JsValue, JsError> {
    serde_wasm_bindgen::to_value(v).map_err(to_js)
}

/// A value for the page as JSON would have it (maps as objects, `null` for `None`).
fn to_json_value<T: serde::Serialize + ?Sized>(v: &T) -> Result<JsValue, JsError> {
    v.serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(to_js)
}

/// The settings object the page passes (`{set: {"detector.kind": "peak", …}, profile}`, see
/// [`crate::settings::Settings`]); `undefined` or `null` is the defaults.
fn settings_from(v: JsValue) -> Result<crate::settings::Settings, JsError> {
    if v.is_undefined() || v.is_null() {
        return Ok(crate::settings::Settings::default());
    }
    serde_wasm_bindgen::from_value(v).map_err(|e| to_js(format!("settings: {e}")))
}
