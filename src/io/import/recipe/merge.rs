//! A recording read by a recipe: the files it matches in a folder, each read by its entry
//! ([`super::read`]; pressure becomes [`Record::Pressure`](crate::engine::Record) readings),
//! merged into one log through [`Streams::into_records`] with the report
//! ([`super::check`]). May import: `engine` and `io`.

use super::check::{self, Report};
use super::read::{read_file, FileData, Samples};
use super::schema::{FileRule, Recipe, Sensor};
use crate::engine::orientation::{G0, HOLD_S};
use crate::engine::types::PRESSURE_RANGE_HPA;
use crate::io::import::common::{add_warnings, pair_nearest, pressure, set_records, warn_count};
use crate::io::import::{file_error, fileset, FileSet, Format, Log, Streams};
use crate::io::ParseError;
use nalgebra::Vector3;

/// A log read by a recipe, with its report; or why it could not be read.
pub type RecipeLog = Result<(Log, Report), ParseError>;

/// Reads the files of the folder `dir` that the recipe matches into one log, with the report
/// (preview and sanity warnings). `None` when the recipe does not match the folder
/// ([`Recipe::match_dir`]); otherwise the files it consumed and the log. `limit` reads at most
/// that many samples per file (the page's live preview).
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
    recipe: &Recipe,
    limit: Option<usize>,
) -> Option<(Vec<String>, RecipeLog)> {
    let matched = recipe.match_dir(names, dir).ok()?;
    let mut consumed: Vec<String> = matched
        .iter()
        .flatten()
        .map(|&i| names[i].clone())
        .collect();
    consumed.dedup();
    let source = {
        let l = set.label(dir.trim_end_matches('/'));
        if l.trim_end_matches('/').is_empty() {
            consumed.first().map(|n| set.label(n)).unwrap_or_default()
        } else {
            l.trim_end_matches('/').to_string()
        }
    };
    let read = (|| {
        let mut files = Vec::new();
        for (rule, idx) in recipe.files.iter().zip(&matched) {
            let Some(i) = idx else { continue };
            let name = &names[*i];
            let label = set.label(name);
            let r = set
                .open(name)
                .map_err(|e| file_error(&label, 0, format!("cannot open: {e}")))?;
            files.push((rule, read_file(r, &label, rule, limit)?));
        }
        build(recipe, &source, files)
    })();
    Some((consumed, read))
}

/// Reads every folder of a file set that the recipe matches. An empty list when it matches
/// none; use [`Recipe::match_dir`] to say why.
pub fn read_set(set: &mut dyn FileSet, recipe: &Recipe) -> Vec<RecipeLog> {
    let names = set.names().to_vec();
    let mut dirs: Vec<&str> = names.iter().map(|n| fileset::parent(n)).collect();
    dirs.sort_unstable();
    dirs.dedup();
    dirs.into_iter()
        .filter_map(|d| read_dir(set, &names, d, recipe, None).map(|(_, r)| r))
        .collect()
}

/// Merges the files' samples into a log ([`Streams::into_records`]), restoring gravity to a
/// linear accelerometer from a gravity file (nearest sample within [`HOLD_S`]) or from the
/// orientation (`q⁻¹ · (0, 0, g)`), and writes the report.
fn build(
    recipe: &Recipe,
    source: &str,
    files: Vec<(&FileRule, FileData)>,
) -> Result<(Log, Report), ParseError> {
    let mut report = check::report(recipe, &files);
    let mut log = Log::new(source, Format::Recipe);
    log.recipe = Some(recipe.name.clone());
    let mut s = Streams::default();
    let (mut linear, mut gravity) = (Vec::new(), Vec::new());
    let mut accel_file = source.to_string();
    for (_, f) in files {
        add_warnings(&mut log, f.warnings);
        match (f.sensor, f.samples) {
            (Sensor::Accelerometer, Samples::Vectors(v)) => {
                accel_file = f.file.clone();
                s.accel.extend(v);
            }
            (Sensor::LinearAccelerometer, Samples::Vectors(v)) => {
                if s.accel.is_empty() {
                    accel_file = f.file.clone();
                }
                linear.extend(v);
            }
            (Sensor::Gravity, Samples::Vectors(v)) => gravity.extend(v),
            (Sensor::Gyroscope, Samples::Vectors(v)) => s.gyro.extend(v),
            (Sensor::Magnetometer, Samples::Vectors(v)) => s.mag.extend(v),
            (Sensor::Orientation, Samples::Quaternions(v)) => s.orientation.extend(v),
            (Sensor::Gnss, Samples::Fixes(v)) => s.fixes.extend(v),
            (Sensor::Pressure, Samples::Scalars(v)) => {
                // The file's unit is already converted to hPa; a reading out of the engine's
                // range (a wrong unit, which the report's check names) is skipped and counted.
                let mut refused = 0u64;
                for (t, hpa) in v {
                    match pressure(t, hpa) {
                        Ok(p) => s.pressure.push(p),
                        Err(_) => refused += 1,
                    }
                }
                warn_count(
                    &mut log,
                    refused,
                    file_error(
                        &f.file,
                        0,
                        format!(
                            "pressure: {refused} sample(s) outside {}–{} hPa, skipped (is the \
                             file's unit right?)",
                            PRESSURE_RANGE_HPA.0, PRESSURE_RANGE_HPA.1
                        ),
                    ),
                );
            }
            _ => {}
        }
    }
    if s.accel.is_empty() && !linear.is_empty() {
        let by_t = |a: &(f64, Vector3<f64>), b: &(f64, Vector3<f64>)| a.0.total_cmp(&b.0);
        crate::engine::sort::sort_by(&mut linear, by_t);
        let (total, unpaired, with) = if !gravity.is_empty() {
            crate::engine::sort::sort_by(&mut gravity, by_t);
            let (v, n) = pair_nearest(&linear, &gravity, HOLD_S, |a, g| a + g);
            (v, n, "gravity")
        } else {
            let mut q = s.orientation.clone();
            crate::engine::sort::sort_by(&mut q, |a, b| a.0.total_cmp(&b.0));
            let up = Vector3::new(0.0, 0.0, G0);
            let (v, n) = pair_nearest(&linear, &q, HOLD_S, |a, q| a + q.inverse() * up);
            (v, n, "orientation")
        };
        s.accel = total;
        warn_count(
            &mut log,
            unpaired,
            file_error(
                &accel_file,
                0,
                format!("{unpaired} linear acceleration sample(s) without a {with} sample within {HOLD_S} s, skipped"),
            ),
        );
        report.notes.push(format!(
            "gravity restored to the linear acceleration from the {with} file"
        ));
    }
    if s.accel.is_empty() {
        return Err(file_error(
            &accel_file,
            0,
            "no usable accelerometer samples (none with a gravity or orientation sample within 0.2 s)",
        ));
    }
    set_records(&mut log, s, &accel_file);
    log.checks = report.warnings.clone();
    Ok((log, report))
}
