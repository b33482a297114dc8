//! Upload mode's worker side: the files read a slice at a time, parsed, and each log analysed
//! into bytes for the page.
//! May import: `analysis`, `engine`, `io`, `settings`.

use super::blobs;
use super::{settings_from, to_js, to_json_value, to_value};
use crate::analysis::page;
use crate::io::import::recipe::{self, Recipe};
use crate::io::import::FileSet as _;
use wasm_bindgen::prelude::*;

/// Upload mode, the web worker's side: files in, logs parsed, each analysed into bytes for the
/// page ([`AnalysisView`]).
#[wasm_bindgen]
pub struct Upload {
    files: Vec<(String, web_sys::Blob)>,
    logs: Vec<crate::io::import::Log>,
    engine_ms: f64,
    /// The user's saved recipes, tried on every folder before the formats are sniffed.
    recipes: Vec<Recipe>,
    /// Why saved recipes were left out (they do not read), for the banners.
    recipe_errors: Vec<String>,
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
            recipes: Vec::new(),
            recipe_errors: Vec::new(),
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
    /// warnings, recipe, checks, hint}], errors: [{file, line, column, field, message, text}],
    /// recipe_errors, banners: [[kind, text]]}` ([`page::Parsed`]; `hint` and `text` for people:
    /// [`log_hint`], [`error_text`]; the banners as [`page::banners`] words them). A file that fails is an
    /// error; the others still load. `progress(bytes_read)` is called as reading goes on.
    /// Workers only (it reads with `FileReaderSync`).
    pub fn parse(&mut self, progress: js_sys::Function) -> Result<JsValue, JsError> {
        let mut set = self.blob_set(progress)?;
        let mut out = page::Parsed {
            recipe_errors: self.recipe_errors.clone(),
            ..Default::default()
        };
        for r in crate::io::import::import_with(&mut set, &self.recipes) {
            match r {
                Ok(log) => {
                    out.logs.push(page::ParsedLog {
                        index: self.logs.len(),
                        source: log.source.clone(),
                        format: log.format.as_str(),
                        samples: log.imu_samples(),
                        duration_s: log.time_span().map_or(0.0, |(a, b)| b - a),
                        warnings: log.skipped as usize,
                        recipe: log.recipe.clone(),
                        checks: log.checks.clone(),
                        hint: log_hint(&log),
                    });
                    self.logs.push(log);
                }
                Err(e) => out.errors.push(page::ParsedError {
                    text: error_text(&e),
                    file: e.file,
                    line: e.line,
                    column: e.column,
                    field: e.field,
                    message: e.message,
                }),
            }
        }
        out.banners = page::banners(&out);
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

    /// Sets the recipes (JSON texts, as the page saved them) that [`Upload::parse`] tries on every
    /// folder before sniffing formats. Those that do not read are left out, and
    /// [`Upload::parse`] says why in its banners.
    pub fn set_recipes(&mut self, recipes: Vec<String>) {
        self.recipe_errors.clear();
        self.recipes = recipes
            .iter()
            .filter_map(|t| {
                Recipe::from_json(t)
                    .map_err(|e| self.recipe_errors.push(e.to_string()))
                    .ok()
            })
            .collect();
    }

    /// The files as the recipe form shows them: `{files: [{name, delimiter, header, columns,
    /// first}], draft}` ([`recipe::describe`]), reading only each file's first bytes; the page
    /// makes its form of it with [`RecipeForm`](super::recipe_form::RecipeForm).
    pub fn describe(&self, progress: js_sys::Function) -> Result<JsValue, JsError> {
        let mut set = self.blob_set(progress)?;
        to_json_value(&recipe::describe(&mut set))
    }

    /// What a recipe (JSON) makes of the files, reading at most [`PREVIEW_SAMPLES`] samples
    /// per file: `{report: {files: [{file, sensor, columns, rows, samples, skipped, errors,
    /// rate_hz, median}], warnings, notes}}`, or `{error}` for a recipe that does not read, does
    /// not match the files, or a file it cannot read; with either, as the form shows it
    /// ([`recipe::form_view::preview_view`]), `messages` (view trees of the list's items) and
    /// `tables` (a view tree per file).
    pub fn preview(
        &self,
        recipe_json: &str,
        progress: js_sys::Function,
    ) -> Result<JsValue, JsError> {
        #[derive(serde::Serialize)]
        struct Preview {
            report: Option<recipe::Report>,
            error: Option<String>,
            messages: Vec<crate::view::El>,
            tables: Vec<crate::view::El>,
        }
        let fail = |e: String| Preview {
            report: None,
            error: Some(e),
            messages: Vec::new(),
            tables: Vec::new(),
        };
        let out = match Recipe::from_json(recipe_json) {
            Err(e) => fail(e.to_string()),
            Ok(r) => {
                let mut set = self.blob_set(progress)?;
                let names = set.names().to_vec();
                let mut dirs: Vec<&str> = names
                    .iter()
                    .map(|n| crate::io::import::fileset::parent(n))
                    .collect();
                dirs.dedup();
                let found = dirs
                    .into_iter()
                    .find_map(|d| recipe::read_dir(&mut set, &names, d, &r, Some(PREVIEW_SAMPLES)));
                match found {
                    None => fail(format!(
                        "the mapping matches no folder: {}",
                        recipe::why_not(&set, &r)
                    )),
                    Some((_, Err(e))) => fail(e.to_string()),
                    Some((_, Ok((_, report)))) => Preview {
                        report: Some(report),
                        error: None,
                        messages: Vec::new(),
                        tables: Vec::new(),
                    },
                }
            }
        };
        let (messages, tables) = match (&out.report, &out.error) {
            (Some(r), _) => recipe::form_view::preview_view(Ok(r)),
            (None, e) => recipe::form_view::preview_view(Err(e.as_deref().unwrap_or_default())),
        };
        to_json_value(&Preview {
            messages,
            tables,
            ..out
        })
    }

    /// Log `index` in the project's own format (pdr-log).
    pub fn pdrlog(&self, index: usize) -> Result<String, JsError> {
        let log = self
            .logs
            .get(index)
            .ok_or_else(|| to_js(format!("no log {index}")))?;
        Ok(crate::io::pdrlog::to_string_dated(
            &log.records,
            log.date_unix_s,
        ))
    }
}

/// What the page says of a log under its name: its format, IMU samples, minutes, the lines
/// skipped and the recipe that read it ("Sensor Logger · 12,345 IMU samples · 4.2 min").
fn log_hint(log: &crate::io::import::Log) -> String {
    let minutes = log.time_span().map_or(0.0, |(a, b)| b - a) / 60.0;
    let mut s = format!(
        "{} · {} IMU samples · {minutes:.1} min",
        log.format.as_str(),
        crate::view::thousands(log.imu_samples() as u64)
    );
    if log.skipped > 0 {
        s += &format!(" · {} lines skipped", log.skipped);
    }
    if let Some(r) = &log.recipe {
        s += &format!(" · read with your recipe \"{r}\"");
    }
    s
}

/// A file the upload could not read, as the page's banner says it: `file:line:column (field):
/// message`, without a line or column that is not known.
fn error_text(e: &crate::io::ParseError) -> String {
    let mut s = e.file.clone();
    for n in [Some(e.line), e.column.map(|c| c as u64)]
        .into_iter()
        .flatten()
    {
        if n != 0 {
            s += &format!(":{n}");
        }
    }
    if let Some(f) = e.field.as_deref().filter(|f| !f.is_empty()) {
        s += &format!(" ({f})");
    }
    format!("{s}: {}", e.message)
}

/// Samples per file the recipe form's live preview reads (its checks look at these): 20 s at
/// 100 Hz, enough for a sample rate, a median gravity and a rotation rate, and quick to redo at
/// every change of the form.
pub const PREVIEW_SAMPLES: usize = 2000;

impl Upload {
    /// The files as a set read a slice at a time (workers only).
    fn blob_set(&self, progress: js_sys::Function) -> Result<blobs::BlobSet, JsError> {
        blobs::BlobSet::new(self.files.clone(), progress)
            .map_err(|_| JsError::new("FileReaderSync is missing: upload parsing runs in a worker"))
    }
}

impl Default for Upload {
    fn default() -> Self {
        Self::new()
    }
}
