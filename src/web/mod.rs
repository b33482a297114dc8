//! WebAssembly entry points (wasm-bindgen): one file per class the page uses, and the choices it
//! offers. Errors become `JsError` here and only here (`to_js`).
//! May import: everything below it (`engine`, `io`, `plot`, `settings`, `live`, `analysis`,
//! `eval`, `demo`); nothing imports it.

// Both modules draw on canvases, and both draw maps (upload mode's on its analyses' maps), each
// module with its own base map setting.
#[cfg(any(feature = "page", feature = "upload"))]
mod basemap;
#[cfg(any(feature = "page", feature = "upload"))]
mod canvas;

// The page's module (feature `page`): what the page's thread calls before upload mode is used.
#[cfg(feature = "page")]
mod calibration;
#[cfg(feature = "page")]
mod demo;
#[cfg(feature = "page")]
mod live;
#[cfg(feature = "page")]
mod recorder;
#[cfg(feature = "page")]
mod settings;
#[cfg(feature = "page")]
mod upload_page;

// Upload mode's module (feature `upload`): the files read and analysed (in the upload worker),
// and the analyses' views, their gestures and the recipe form (on the page, loaded when files
// are opened).
#[cfg(feature = "upload")]
mod analysis_view;
#[cfg(feature = "upload")]
mod blobs;
#[cfg(feature = "upload")]
mod gesture;
#[cfg(feature = "upload")]
mod recipe_form;
#[cfg(feature = "upload")]
mod recording;
#[cfg(feature = "upload")]
mod upload;

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

/// A value the page passes, read as JSON reads it (`JSON.stringify`, then `serde_json`): one
/// deserializer for every type in the module, where `serde_wasm_bindgen`'s would add a second
/// copy of each type's code (the page's module is what a phone loads before the first track).
/// `undefined` is `null`; a field left `undefined` is missing.
fn from_js<T: serde::de::DeserializeOwned>(v: &JsValue) -> Result<T, String> {
    let text = js_sys::JSON::stringify(v)
        .map_err(|_| "not a JSON value".to_string())?
        .as_string()
        .unwrap_or_else(|| "null".to_string());
    serde_json::from_str(&text).map_err(|e| e.to_string())
}

/// The settings object the page passes (`{set: {"detector.kind": "peak", …}, profile}`, see
/// [`crate::settings::Settings`]); `undefined` or `null` is the defaults.
fn settings_from(v: JsValue) -> Result<crate::settings::Settings, JsError> {
    if v.is_undefined() || v.is_null() {
        return Ok(crate::settings::Settings::default());
    }
    from_js(&v).map_err(|e| to_js(format!("settings: {e}")))
}
