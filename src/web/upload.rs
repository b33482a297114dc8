//! Upload mode's worker side: the files read a slice at a time, parsed, and each log analysed
//! into bytes for the page.
//! May import: `analysis`, `engine`, `io`, `settings`.

use super::blobs;
use super::{settings_from, to_js, to_value};
use wasm_bindgen::prelude::*;

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
        to_value(&out)
    }

    /// Runs the engine over log `index` with `settings` (`{set, profile}`, as for `Live`);
    /// `progress(done, total)` is called as records go through. Returns the analysis as bytes
    /// for [`AnalysisView::from_bytes`](super::analysis_view::AnalysisView::from_bytes).
    pub fn analyse(
        &mut self,
        index: usize,
        settings: JsValue,
        progress: &js_sys::Function,
    ) -> Result<Vec<u8>, JsError> {
        let log = self
            .logs
            .get(index)
            .ok_or_else(|| to_js(format!("no log {index}")))?;
        let cfg = settings_from(settings)?.config().map_err(to_js)?;
        let t0 = js_sys::Date::now();
        let a = crate::analysis::analyse(log, &cfg, &mut |done, total| {
            let _ = progress.call2(
                &JsValue::NULL,
                &(done as f64).into(),
                &(total as f64).into(),
            );
        })
        .map_err(to_js)?;
        self.engine_ms = js_sys::Date::now() - t0;
        a.to_bytes().map_err(to_js)
    }

    /// Log `index` in the project's own format (pdr-log).
    pub fn pdrlog(&self, index: usize) -> Result<String, JsError> {
        let log = self
            .logs
            .get(index)
            .ok_or_else(|| to_js(format!("no log {index}")))?;
        Ok(crate::io::pdrlog::to_string(&log.records))
    }
}

impl Default for Upload {
    fn default() -> Self {
        Self::new()
    }
}
