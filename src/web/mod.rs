//! WebAssembly entry points (wasm-bindgen): one file per class the page uses. Errors become
//! `JsError` here and only here.
//! May import: everything below it (`engine`, `io`, `plot`, `settings`, `live`, `analysis`,
//! `eval`, `demo`); nothing imports it.

mod analysis_view;
mod blobs;
mod calibration;
mod canvas;
mod demo;
mod live;
mod upload;
