//! phyphox CSV export: a folder or zip with one CSV per sensor (`Accelerometer.csv`,
//! `Gyroscope.csv`, `Magnetometer.csv`, `Location.csv`, or `Raw Data.csv` for single-sensor
//! experiments) and usually a `meta/` folder. May import: `engine` and `io`.
//!
//! Headers name the quantity and unit, e.g. `"Time (s)","Acceleration x (m/s^2)",…`,
//! `"Gyroscope x (rad/s)"`, `"Magnetic field x (µT)"`, and for location `"Latitude (°)"`,
//! `"Longitude (°)"`, `"Height (m)"`, `"Velocity (m/s)"`, `"Direction (°)"`,
//! `"Horizontal Accuracy (m)"`, and the barometer's `"Pressure (hPa)"` (phyphox's "Pressure"
//! experiment exports `Pressure.csv` with `"Time (s)","Pressure (hPa)"`; a `(kPa)`, `(Pa)` or
//! `(mbar)` unit in the header is converted to hPa, a reading outside the engine's range is
//! skipped with a warning). Columns are matched by these names, in any file and any order;
//! each quantity is taken from the first file (by name) that has it. The separator (comma, tab
//! or semicolon) is detected from the header line; a decimal comma is accepted; numbers may be
//! written like `9.364549000E-3`.
//!
//! Time is seconds from the start of the experiment, one clock for every sensor. The date
//! ([`Log::date_unix_s`]) is the `START` event's `system time` (Unix s) minus its
//! `experiment time` in `meta/time.csv`, when the export has it.
//!
//! phyphox has "Acceleration" (with g) and "Linear Acceleration" (without g). Only the first
//! is used, and only when its mean norm is that of gravity (between 5 and 20 m/s²): a log with
//! only linear acceleration is refused with an error saying so. phyphox writes acceleration with
//! the Android sign on both platforms (its iOS version converts Core Motion's g to m/s² with the
//! sign flipped), so no platform conversion is applied and the platform is left unknown.

use super::common::{
    add_warnings, cell, not_a_number, set_records, split_line, warn_count, Table, Warnings,
};
use super::{field_error, file_error, fileset, number, FileSet, Format, Log, Streams};
use crate::engine::types::GnssFix;
use crate::io::ParseError;
use nalgebra::Vector3;
use std::io::BufRead;

/// Whether a header's first field is phyphox's time column.
fn is_time(h: &str) -> bool {
    let h = h.trim().to_lowercase();
    h.starts_with("time (s)") || h == "time"
}

/// Column names (lower case, prefixes) of the quantities phyphox exports that we read.
const QUANTITIES: [&str; 6] = [
    "acceleration x",
    "linear acceleration x",
    "gyroscope x (rad/s)",
    "magnetic field x",
    "latitude",
    "pressure",
];

/// The factor to hPa of a phyphox pressure column, from the unit in its name (lower case):
/// `pressure (hpa)`, `pressure (kpa)`, `pressure (pa)`, `pressure (mbar)`, or `pressure` alone
/// (hPa, phyphox's unit). `None` for anything else (such as a sound pressure level).
fn pressure_factor(h: &str) -> Option<f64> {
    let rest = h.strip_prefix("pressure")?.trim();
    match rest {
        "" | "(hpa)" | "(mbar)" => Some(1.0),
        "(kpa)" => Some(10.0),
        "(pa)" => Some(0.01),
        _ => None,
    }
}

/// Whether the first line of a file is a phyphox header: `Time (s)` first, and one of the
/// quantities we read (which keeps out other `Time (s)` CSVs, such as x-io's, with
/// `Gyroscope X (deg/s)`).
fn is_phyphox_header(first: &str) -> bool {
    let first = first.trim_start_matches('\u{feff}');
    let d = super::common::detect_delimiter(first);
    let fields = split_line(first, d);
    fields.first().is_some_and(|f| is_time(f))
        && fields.iter().any(|f| {
            let f = f.to_lowercase();
            QUANTITIES.iter().any(|q| f.starts_with(q))
        })
}

/// Recognises a phyphox export inside a file set and reads it. `dir` is a folder of `names`
/// (ending with `/`, or empty for the top). Returns the files it consumed (its CSVs and the
/// `meta/` folder) and the log, or `None` when no CSV directly in the folder starts with a
/// phyphox `Time (s)` header.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let mut files = Vec::new();
    for n in names {
        if fileset::parent(n) != dir || !n.to_ascii_lowercase().ends_with(".csv") {
            continue;
        }
        let Ok(head) = set.head(n) else { continue };
        if is_phyphox_header(head.lines().next().unwrap_or("")) {
            files.push(n.clone());
        }
    }
    if files.is_empty() {
        return None;
    }
    let meta = format!("{dir}meta/");
    let mut consumed = files.clone();
    consumed.extend(names.iter().filter(|n| n.starts_with(&meta)).cloned());
    let source = {
        let l = set.label(dir.trim_end_matches('/'));
        let l = l.trim_end_matches('/').to_string();
        if l.is_empty() {
            set.label(&files[0])
        } else {
            l
        }
    };
    let time_csv = format!("{meta}time.csv");
    let date = names
        .contains(&time_csv)
        .then(|| set.head(&time_csv).ok())
        .flatten()
        .and_then(|text| start_date(&text));
    let read = read_files(set, &files, &source).map(|mut log| {
        log.date_unix_s = date;
        log
    });
    Some((consumed, read))
}

/// The Unix time of the experiment's start from `meta/time.csv`: the `START` row's
/// `system time` minus its `experiment time`. `None` without such a row.
fn start_date(text: &str) -> Option<f64> {
    let mut lines = text.lines();
    let header = lines.next()?.trim_start_matches('\u{feff}');
    let d = super::common::detect_delimiter(header);
    let names: Vec<String> = split_line(header, d)
        .iter()
        .map(|h| h.trim().trim_matches('"').to_ascii_lowercase())
        .collect();
    let col = |n: &str| names.iter().position(|h| h == n);
    let (event, exp, sys) = (col("event")?, col("experiment time")?, col("system time")?);
    lines.find_map(|l| {
        let f = split_line(l, d);
        let is_start = f
            .get(event)
            .is_some_and(|e| e.trim().trim_matches('"').eq_ignore_ascii_case("start"));
        if !is_start {
            return None;
        }
        let t = number(f.get(sys)?)? - number(f.get(exp)?)?;
        t.is_finite().then_some(t)
    })
}

/// Column indices of one quantity group in a file.
#[derive(Debug, Clone, Copy)]
struct Location {
    lat: usize,
    lon: usize,
    acc: usize,
    alt: Option<usize>,
    speed: Option<usize>,
    bearing: Option<usize>,
}

/// Finds the x, y, z columns whose lower-case names start with `prefix x`, `prefix y`, …
fn xyz<R: BufRead>(t: &Table<R>, prefix: &str) -> Option<[usize; 3]> {
    let c = |axis: &str| {
        let p = format!("{prefix} {axis}");
        t.col(|h| h == p || h.starts_with(&format!("{p} ")) || h.starts_with(&format!("{p}(")))
    };
    Some([c("x")?, c("y")?, c("z")?])
}

/// Whether every cell of a group is empty (that sensor has no value on this row).
fn empty(rec: &csv::StringRecord, cols: &[usize]) -> bool {
    cols.iter().all(|&c| {
        rec.get(c)
            .map_or(true, |s| s.trim().trim_matches('"').trim().is_empty())
    })
}

/// Reads the given phyphox CSVs as one log.
fn read_files(set: &mut dyn FileSet, files: &[String], source: &str) -> Result<Log, ParseError> {
    let mut log = Log::new(source, Format::Phyphox);
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    let (mut have_gyro, mut have_mag, mut have_loc, mut have_pres) = (false, false, false, false);
    let mut linear_only: Option<ParseError> = None;
    let mut rejected: Option<ParseError> = None;
    let mut unreadable: Option<ParseError> = None;
    let mut invalid_fixes = 0u64;
    let mut invalid_file = String::new();
    for name in files {
        let label = set.label(name);
        let r = set
            .open(name)
            .map_err(|e| file_error(&label, 0, format!("cannot open: {e}")))?;
        // A damaged file is a warning: the others may still make a log.
        let mut table = match Table::open(r, &label, None) {
            Ok(Some(t)) => t,
            Ok(None) => continue,
            Err(e) => {
                unreadable.get_or_insert_with(|| e.clone());
                warnings.push(e);
                continue;
            }
        };
        let Some(t_col) = table.col(is_time) else {
            continue;
        };
        let accel = if s.accel.is_empty() {
            xyz(&table, "acceleration")
        } else {
            None
        };
        if let (None, Some(_)) = (accel, xyz(&table, "linear acceleration")) {
            if linear_only.is_none() {
                linear_only = Some(file_error(
                    &label,
                    table.header_line,
                    "only linear acceleration (gravity removed) was exported; record phyphox's \
                     \"Acceleration (with g)\" sensor instead",
                ));
            }
        }
        let gyro = (!have_gyro).then(|| xyz(&table, "gyroscope")).flatten();
        let mag = (!have_mag).then(|| xyz(&table, "magnetic field")).flatten();
        let loc = if have_loc {
            None
        } else {
            let lat = table.col(|h| h.starts_with("latitude"));
            let lon = table.col(|h| h.starts_with("longitude"));
            let acc = table.col(|h| h.starts_with("horizontal accuracy"));
            match (lat, lon, acc) {
                (Some(lat), Some(lon), Some(acc)) => Some(Location {
                    lat,
                    lon,
                    acc,
                    alt: table.col(|h| h.starts_with("height") || h.starts_with("altitude")),
                    speed: table.col(|h| h.starts_with("velocity") || h.starts_with("speed")),
                    bearing: table.col(|h| h.starts_with("direction") || h.starts_with("bearing")),
                }),
                (Some(_), Some(_), None) => {
                    warnings.push(file_error(
                        &label,
                        table.header_line,
                        "location without a horizontal accuracy column: fixes not used",
                    ));
                    None
                }
                _ => None,
            }
        };
        let pres = if have_pres {
            None
        } else {
            table
                .lower
                .iter()
                .enumerate()
                .find_map(|(i, h)| pressure_factor(h).map(|f| (i, f)))
        };
        if accel.is_none() && gyro.is_none() && mag.is_none() && loc.is_none() && pres.is_none() {
            continue;
        }
        let header = table.header.clone();
        let mut file_accel = Vec::new();
        let mut csv_warnings = Warnings::default();
        table.rows(&label, &mut csv_warnings, |line, rec| {
            let t = match cell(rec, t_col, &header[t_col], &label, line) {
                Ok(t) => t,
                Err(e) => {
                    warnings.push(e);
                    return;
                }
            };
            let v3 = |cols: [usize; 3]| -> Result<Vector3<f64>, ParseError> {
                let mut v = Vector3::zeros();
                for (k, &c) in cols.iter().enumerate() {
                    v[k] = cell(rec, c, &header[c], &label, line)?;
                }
                Ok(v)
            };
            let mut first_error = None;
            for (cols, out) in [
                (accel, &mut file_accel),
                (gyro, &mut s.gyro),
                (mag, &mut s.mag),
            ] {
                let Some(cols) = cols else { continue };
                if empty(rec, &cols) {
                    continue;
                }
                match v3(cols) {
                    Ok(v) => out.push((t, v)),
                    Err(e) => {
                        first_error.get_or_insert(e);
                    }
                }
            }
            if let Some(l) = loc {
                if !empty(rec, &[l.lat, l.lon]) {
                    let opt = |c: Option<usize>| -> Result<Option<f64>, ParseError> {
                        let Some(c) = c else { return Ok(None) };
                        let v = rec.get(c).unwrap_or("").trim().trim_matches('"').trim();
                        // phyphox writes NaN for a value the platform did not give.
                        if v.is_empty() || v.eq_ignore_ascii_case("nan") {
                            return Ok(None);
                        }
                        number(v).map(Some).ok_or_else(|| {
                            field_error(&label, line, c + 1, &header[c], not_a_number(v))
                        })
                    };
                    let fix = (|| -> Result<Option<GnssFix>, ParseError> {
                        let lat = cell(rec, l.lat, &header[l.lat], &label, line)?;
                        let lon = cell(rec, l.lon, &header[l.lon], &label, line)?;
                        let acc = cell(rec, l.acc, &header[l.acc], &label, line)?;
                        if acc < 0.0 {
                            return Ok(None);
                        }
                        Ok(Some(GnssFix {
                            t,
                            lat_deg: lat,
                            lon_deg: lon,
                            h_accuracy_m: acc,
                            altitude_m: opt(l.alt)?,
                            speed_mps: opt(l.speed)?.filter(|v| *v >= 0.0),
                            bearing_deg: opt(l.bearing)?.filter(|v| *v >= 0.0),
                        }))
                    })();
                    match fix {
                        Ok(Some(f)) if f.check().is_ok() => s.fixes.push(f),
                        Ok(Some(_)) => {
                            first_error.get_or_insert(file_error(
                                &label,
                                line,
                                "latitude or longitude out of range",
                            ));
                        }
                        Ok(None) => {
                            invalid_fixes += 1;
                            invalid_file.clone_from(&label);
                        }
                        Err(e) => {
                            first_error.get_or_insert(e);
                        }
                    }
                }
            }
            if let Some((c, factor)) = pres {
                if !empty(rec, &[c]) {
                    let p = cell(rec, c, &header[c], &label, line).and_then(|v| {
                        super::common::pressure(t, v * factor)
                            .map_err(|m| field_error(&label, line, c + 1, &header[c], m))
                    });
                    match p {
                        Ok(p) => s.pressure.push(p),
                        Err(e) => {
                            first_error.get_or_insert(e);
                        }
                    }
                }
            }
            if let Some(e) = first_error {
                warnings.push(e);
            }
        })?;
        warnings.extend(csv_warnings);
        if accel.is_some() {
            let n = file_accel.len().max(1) as f64;
            let mean = file_accel.iter().map(|(_, v)| v.norm()).sum::<f64>() / n;
            if (5.0..=20.0).contains(&mean) {
                s.accel = file_accel;
            } else if !file_accel.is_empty() && rejected.is_none() {
                rejected = Some(file_error(
                    &label,
                    table.header_line,
                    format!(
                        "\"Acceleration\" averages {mean:.2} m/s² in norm, not about 9.8: it is \
                         not acceleration with gravity"
                    ),
                ));
            }
        }
        have_gyro |= gyro.is_some();
        have_mag |= mag.is_some();
        have_loc |= loc.is_some();
        have_pres |= pres.is_some();
    }
    if s.accel.is_empty() {
        return Err(rejected.or(linear_only).or(unreadable).unwrap_or_else(|| {
            file_error(
                source,
                0,
                "no acceleration: none of the phyphox CSVs has \"Acceleration x/y/z\" columns \
                 with readable values",
            )
        }));
    }
    add_warnings(&mut log, warnings);
    warn_count(
        &mut log,
        invalid_fixes,
        file_error(
            &invalid_file,
            0,
            format!("{invalid_fixes} location fix(es) with a negative accuracy, skipped"),
        ),
    );
    set_records(&mut log, s, source);
    Ok(log)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_recognition() {
        assert!(is_phyphox_header(
            "\"Time (s)\",\"Acceleration x (m/s^2)\",\"Acceleration y (m/s^2)\""
        ));
        assert!(is_phyphox_header("Time (s)\tGyroscope x (rad/s)"));
        assert!(is_phyphox_header("\u{feff}\"Time (s)\";\"Latitude (°)\""));
        assert!(!is_phyphox_header("time,seconds_elapsed,z,y,x"));
        assert!(!is_phyphox_header("Time (s)"));
        assert!(is_phyphox_header("\"Time (s)\",\"Pressure (hPa)\""));
        assert_eq!(pressure_factor("pressure (hpa)"), Some(1.0));
        assert_eq!(pressure_factor("pressure (kpa)"), Some(10.0));
        assert_eq!(pressure_factor("pressure (pa)"), Some(0.01));
        assert_eq!(pressure_factor("pressure level (db)"), None);
        assert!(!is_phyphox_header(
            "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g)"
        ));
    }
}
