//! A recording of a calibration walk, read for the wizard with upload mode's module (the module
//! with the importers); the page's module adds the walk
//! ([`CalibrationWizard::recorded`](super::calibration::CalibrationWizard::recorded)).
//! May import: `engine`, `io`, `live`, `settings`.

use super::{settings_from, to_js};
use crate::engine::recorded_walk::RecordedWalk;
use wasm_bindgen::prelude::*;

/// The recording `file_name` (its `bytes`, read as upload mode reads a file) of a walk of
/// `distance_m` metres through the engine with `settings` (`{set, profile}`, as for `Live`)
/// ([`crate::engine::recorded_walk`]), as postcard bytes of `Result<RecordedWalk, String>`
/// for `CalibrationWizard.recorded`: the walk, or why there is none (the distance is missing,
/// the file is not one recording, the walk has too few steps; naming the file). postcard
/// keeps every f64 bit for bit: the NaN pitch amplitude of a step without one survives.
/// Settings that make no configuration are thrown.
#[wasm_bindgen]
pub fn read_recorded_walk(
    file_name: &str,
    bytes: Vec<u8>,
    distance_m: f64,
    settings: JsValue,
) -> Result<Vec<u8>, JsError> {
    let read = read(file_name, bytes, distance_m, settings)?;
    postcard::to_stdvec(&read).map_err(to_js)
}

fn read(
    file_name: &str,
    bytes: Vec<u8>,
    distance_m: f64,
    settings: JsValue,
) -> Result<Result<RecordedWalk, String>, JsError> {
    use crate::live::wizard::{message, recording_log};
    if !(distance_m.is_finite() && distance_m > 0.0) {
        return Ok(Err(message("distance", "").map_err(to_js)?));
    }
    let cfg = settings_from(settings)?.config().map_err(to_js)?;
    let mut set = crate::io::import::MemSet::new(vec![(file_name.to_string(), bytes)]);
    Ok(
        recording_log(file_name, crate::io::import::import_all(&mut set)).and_then(|log| {
            crate::engine::recorded_walk::recorded_walk(log.dated(&cfg), &log.records, distance_m)
                .map_err(|e| format!("{file_name}: {e}"))
        }),
    )
}
