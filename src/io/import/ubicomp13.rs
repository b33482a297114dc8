//! The UbiComp 2013 step-counting walks (Brajdic & Harle, "Walk detection and step counting on
//! unconstrained smartphones"), one of the evaluation data sets of `../shared/data`, read
//! directly. May import: `engine` and `io`.
//!
//! # Files
//! One folder per walk:
//! - `acc.csv`, `gyr.csv`, `mag.csv`: `t_s,x,y,z`, no header, one line per Android sensor event:
//!   the event time in seconds (the Android timestamp, ns since boot, divided by 10⁹: kept as it
//!   is), then m/s² with gravity, rad/s and µT, Android axes and sign. Only `acc.csv` is required.
//!   The phones read gravity about 4 % low at rest; that is left as recorded (the engine's step
//!   detection does not depend on the scale). The magnetometer's value repeats until it updates:
//!   every line is kept.
//! - `truth.json`: `steps` (counted from video) → [`Truth::steps`](super::Truth::steps);
//!   `walk_start_s`, `walk_end_s` (the annotated walk, on the sensors' clock; the phone is
//!   handled outside it) → [`Truth::step_window`](super::Truth::step_window); `placement`
//!   (`front pocket`, `back pocket`) → [`Log::group`] (`FrontPocket`, `BackPocket`). Its other
//!   fields (person, run, age, …) are not read.
//!
//! A folder is taken for a walk of this set only when its `truth.json` has a `walk_start_s`: a
//! folder of `acc.csv`, `gyr.csv` and `mag.csv` alone is any logger's, read by a user's recipe.

use super::common::{add_warnings, file_in, folder_label, read_samples, set_records, Warnings};
use super::{file_error, FileSet, Format, Log, Platform, Streams};
use crate::io::ParseError;
use nalgebra::Vector3;
use std::io::Read;

/// The files of a walk folder that the reader consumes.
pub const UBICOMP13_FILES: [&str; 4] = ["acc.csv", "gyr.csv", "mag.csv", "truth.json"];

/// Largest `truth.json` read, bytes (the set's are under 1 kB).
const MAX_TRUTH_BYTES: u64 = 1 << 20;

/// The fields of `truth.json` the reader uses.
#[derive(serde::Deserialize)]
struct TruthJson {
    steps: Option<u64>,
    walk_start_s: f64,
    walk_end_s: f64,
    placement: Option<String>,
}

/// Recognises a walk folder of the set inside a file set and reads it. `dir` is a folder of
/// `names` (ending with `/`, or empty for the top). Returns the files it consumed and the log, or
/// `None` when the folder has no `truth.json` whose first bytes hold a `"walk_start_s"` key.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let truth = file_in(names, dir, "truth.json")?;
    if !set.head(&truth).ok()?.contains("\"walk_start_s\"") {
        return None;
    }
    let consumed = UBICOMP13_FILES
        .iter()
        .filter_map(|f| file_in(names, dir, f))
        .collect();
    Some((consumed, read(set, names, dir, &truth)))
}

/// Reads a recognised folder.
fn read(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
    truth_name: &str,
) -> Result<Log, ParseError> {
    let acc_name = format!("{dir}acc.csv");
    let mut log = Log::new(folder_label(set, dir, &acc_name), Format::Ubicomp13);
    log.platform = Some(Platform::Android);
    let truth = read_truth(set, truth_name)?;
    log.truth.steps = truth.steps;
    log.truth.step_window = Some((truth.walk_start_s, truth.walk_end_s));
    log.group = truth.placement.as_deref().and_then(camel_case);
    // Every walk of the set is in a trouser pocket, front or back.
    log.truth.carry = Some(crate::engine::carry::CarryMode::Pocket);
    let Some(acc) = file_in(names, dir, "acc.csv") else {
        return Err(file_error(
            &set.label(&acc_name),
            0,
            "missing: a walk folder needs its acc.csv",
        ));
    };
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    read_samples(
        set,
        &acc,
        Some(','),
        ["t_s", "x", "y", "z"],
        &mut warnings,
        |_, _, [t, x, y, z]| {
            s.accel.push((t, Vector3::new(x, y, z)));
            Ok(())
        },
    )?;
    let acc_label = set.label(&acc);
    if s.accel.is_empty() {
        return Err(file_error(&acc_label, 0, "no accelerometer samples"));
    }
    for (file, stream) in [("gyr.csv", &mut s.gyro), ("mag.csv", &mut s.mag)] {
        if let Some(name) = file_in(names, dir, file) {
            read_samples(
                set,
                &name,
                Some(','),
                ["t_s", "x", "y", "z"],
                &mut warnings,
                |_, _, [t, x, y, z]| {
                    stream.push((t, Vector3::new(x, y, z)));
                    Ok(())
                },
            )?;
        }
    }
    set_records(&mut log, s, &acc_label);
    add_warnings(&mut log, warnings);
    Ok(log)
}

/// Reads `truth.json`; an error names the file (and the line and column serde_json gives).
fn read_truth(set: &mut dyn FileSet, name: &str) -> Result<TruthJson, ParseError> {
    let label = set.label(name);
    let mut text = String::new();
    set.open(name)
        .and_then(|r| r.take(MAX_TRUTH_BYTES).read_to_string(&mut text))
        .map_err(|e| file_error(&label, 0, format!("cannot read: {e}")))?;
    let truth: TruthJson = serde_json::from_str(&text)
        .map_err(|e| file_error(&label, e.line() as u64, format!("not a truth file: {e}")))?;
    if !(truth.walk_start_s <= truth.walk_end_s) {
        return Err(file_error(
            &label,
            0,
            format!(
                "walk_end_s {} is before walk_start_s {}",
                truth.walk_end_s, truth.walk_start_s
            ),
        ));
    }
    Ok(truth)
}

/// `front pocket` → `FrontPocket`: the words of a placement, each capitalised, joined. `None`
/// for a placement without a word.
fn camel_case(placement: &str) -> Option<String> {
    let out: String = placement
        .split_whitespace()
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_uppercase().chain(c).collect::<String>())
                .unwrap_or_default()
        })
        .collect();
    (!out.is_empty()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::camel_case;

    #[test]
    fn placements_become_groups() {
        assert_eq!(camel_case("front pocket").as_deref(), Some("FrontPocket"));
        assert_eq!(camel_case("back pocket").as_deref(), Some("BackPocket"));
        assert_eq!(camel_case("  "), None);
    }
}
