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
    add_warnings, cell, folder_label, not_a_number, open, set_records, split_line, warn_count,
    Table, Warnings,
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
    let source = folder_label(set, dir, &files[0]);
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
    let mut reading = Reading::default();
    for name in files {
        reading.file(set, name)?;
    }
    reading.into_log(source)
}

/// The columns of one file to read: its time and each quantity not yet taken from another file.
struct Columns {
    t: usize,
    accel: Option<[usize; 3]>,
    gyro: Option<[usize; 3]>,
    mag: Option<[usize; 3]>,
    loc: Option<Location>,
    /// The pressure column and its factor to hPa.
    pres: Option<(usize, f64)>,
}

/// One record of a file, with what errors name: file label, line and column names.
struct Row<'a> {
    rec: &'a csv::StringRecord,
    header: &'a [String],
    label: &'a str,
    line: u64,
}

impl Row<'_> {
    /// Column `c` as a number.
    fn cell(&self, c: usize) -> Result<f64, ParseError> {
        cell(self.rec, c, &self.header[c], self.label, self.line)
    }

    /// Columns `cols` as a vector.
    fn vector(&self, cols: [usize; 3]) -> Result<Vector3<f64>, ParseError> {
        let mut v = Vector3::zeros();
        for (k, &c) in cols.iter().enumerate() {
            v[k] = self.cell(c)?;
        }
        Ok(v)
    }

    /// An optional column as a number: `None` when the file has no such column or the cell is
    /// empty or `NaN` (phyphox writes NaN for a value the platform did not give).
    fn optional(&self, c: Option<usize>) -> Result<Option<f64>, ParseError> {
        let Some(c) = c else { return Ok(None) };
        let v = self
            .rec
            .get(c)
            .unwrap_or("")
            .trim()
            .trim_matches('"')
            .trim();
        if v.is_empty() || v.eq_ignore_ascii_case("nan") {
            return Ok(None);
        }
        number(v).map(Some).ok_or_else(|| {
            field_error(
                self.label,
                self.line,
                c + 1,
                &self.header[c],
                not_a_number(v),
            )
        })
    }
}

/// The log being read from the files of an export, one after the other.
#[derive(Default)]
struct Reading {
    s: Streams,
    warnings: Warnings,
    have_gyro: bool,
    have_mag: bool,
    have_loc: bool,
    have_pres: bool,
    /// Why there may be no acceleration: only linear acceleration was exported.
    linear_only: Option<ParseError>,
    /// Why there may be no acceleration: its norm was not that of gravity.
    rejected: Option<ParseError>,
    /// Why there may be no acceleration: the first file that could not be read.
    unreadable: Option<ParseError>,
    /// Fixes with a negative accuracy, and the file of the last one.
    invalid_fixes: u64,
    invalid_file: String,
}

impl Reading {
    /// Reads file `name`. A damaged file is a warning: the others may still make a log.
    fn file(&mut self, set: &mut dyn FileSet, name: &str) -> Result<(), ParseError> {
        let label = set.label(name);
        let r = open(set, name, &label)?;
        let mut table = match Table::open(r, &label, None) {
            Ok(Some(t)) => t,
            Ok(None) => return Ok(()),
            Err(e) => {
                self.unreadable.get_or_insert_with(|| e.clone());
                self.warnings.push(e);
                return Ok(());
            }
        };
        let Some(cols) = self.columns(&table, &label) else {
            return Ok(());
        };
        let header = table.header.clone();
        let mut file_accel = Vec::new();
        let mut csv_warnings = Warnings::default();
        table.rows(&label, &mut csv_warnings, |line, rec| {
            let row = Row {
                rec,
                header: &header,
                label: &label,
                line,
            };
            self.row(&row, &cols, &mut file_accel);
        })?;
        self.warnings.extend(csv_warnings);
        if cols.accel.is_some() {
            self.accel(file_accel, &label, table.header_line);
        }
        self.have_gyro |= cols.gyro.is_some();
        self.have_mag |= cols.mag.is_some();
        self.have_loc |= cols.loc.is_some();
        self.have_pres |= cols.pres.is_some();
        Ok(())
    }

    /// The columns of a file to read; `None` when it has no time column or nothing new.
    fn columns<R: BufRead>(&mut self, table: &Table<R>, label: &str) -> Option<Columns> {
        let t = table.col(is_time)?;
        let accel = if self.s.accel.is_empty() {
            xyz(table, "acceleration")
        } else {
            None
        };
        if let (None, Some(_)) = (accel, xyz(table, "linear acceleration")) {
            if self.linear_only.is_none() {
                self.linear_only = Some(file_error(
                    label,
                    table.header_line,
                    "only linear acceleration (gravity removed) was exported; record phyphox's \
                     \"Acceleration (with g)\" sensor instead",
                ));
            }
        }
        let gyro = (!self.have_gyro).then(|| xyz(table, "gyroscope")).flatten();
        let mag = (!self.have_mag)
            .then(|| xyz(table, "magnetic field"))
            .flatten();
        let loc = if self.have_loc {
            None
        } else {
            self.location(table, label)
        };
        let pres = if self.have_pres {
            None
        } else {
            table
                .lower
                .iter()
                .enumerate()
                .find_map(|(i, h)| pressure_factor(h).map(|f| (i, f)))
        };
        if accel.is_none() && gyro.is_none() && mag.is_none() && loc.is_none() && pres.is_none() {
            return None;
        }
        Some(Columns {
            t,
            accel,
            gyro,
            mag,
            loc,
            pres,
        })
    }

    /// The location columns of a file, when it has latitude, longitude and accuracy (a warning
    /// when only the accuracy is missing).
    fn location<R: BufRead>(&mut self, table: &Table<R>, label: &str) -> Option<Location> {
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
                self.warnings.push(file_error(
                    label,
                    table.header_line,
                    "location without a horizontal accuracy column: fixes not used",
                ));
                None
            }
            _ => None,
        }
    }

    /// Reads one record; its first bad value is a warning.
    fn row(&mut self, row: &Row, c: &Columns, file_accel: &mut Vec<(f64, Vector3<f64>)>) {
        let t = match row.cell(c.t) {
            Ok(t) => t,
            Err(e) => return self.warnings.push(e),
        };
        let mut first_error = None;
        for (cols, out) in [
            (c.accel, file_accel),
            (c.gyro, &mut self.s.gyro),
            (c.mag, &mut self.s.mag),
        ] {
            let Some(cols) = cols else { continue };
            if empty(row.rec, &cols) {
                continue;
            }
            match row.vector(cols) {
                Ok(v) => out.push((t, v)),
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
        }
        if let Some(l) = c.loc {
            if !empty(row.rec, &[l.lat, l.lon]) {
                if let Err(e) = self.fix(row, &l, t) {
                    first_error.get_or_insert(e);
                }
            }
        }
        if let Some((col, factor)) = c.pres {
            if !empty(row.rec, &[col]) {
                let p = row.cell(col).and_then(|v| {
                    super::common::pressure(t, v * factor)
                        .map_err(|m| field_error(row.label, row.line, col + 1, &row.header[col], m))
                });
                match p {
                    Ok(p) => self.s.pressure.push(p),
                    Err(e) => {
                        first_error.get_or_insert(e);
                    }
                }
            }
        }
        if let Some(e) = first_error {
            self.warnings.push(e);
        }
    }

    /// Reads the location fix at time `t` of a record; one with a negative accuracy is counted.
    fn fix(&mut self, row: &Row, l: &Location, t: f64) -> Result<(), ParseError> {
        let lat = row.cell(l.lat)?;
        let lon = row.cell(l.lon)?;
        let acc = row.cell(l.acc)?;
        if acc < 0.0 {
            self.invalid_fixes += 1;
            self.invalid_file = row.label.to_string();
            return Ok(());
        }
        let fix = GnssFix {
            t,
            lat_deg: lat,
            lon_deg: lon,
            h_accuracy_m: acc,
            altitude_m: row.optional(l.alt)?,
            speed_mps: row.optional(l.speed)?.filter(|v| *v >= 0.0),
            bearing_deg: row.optional(l.bearing)?.filter(|v| *v >= 0.0),
        };
        if fix.check().is_err() {
            return Err(file_error(
                row.label,
                row.line,
                "latitude or longitude out of range",
            ));
        }
        self.s.fixes.push(fix);
        Ok(())
    }

    /// Takes a file's "Acceleration" when its mean norm is that of gravity.
    fn accel(&mut self, file_accel: Vec<(f64, Vector3<f64>)>, label: &str, header_line: u64) {
        let n = file_accel.len().max(1) as f64;
        let mean = file_accel.iter().map(|(_, v)| v.norm()).sum::<f64>() / n;
        if (5.0..=20.0).contains(&mean) {
            self.s.accel = file_accel;
        } else if !file_accel.is_empty() && self.rejected.is_none() {
            self.rejected = Some(file_error(
                label,
                header_line,
                format!(
                    "\"Acceleration\" averages {mean:.2} m/s² in norm, not about 9.8: it is \
                     not acceleration with gravity"
                ),
            ));
        }
    }

    /// The log, or why there is none (no usable acceleration).
    fn into_log(self, source: &str) -> Result<Log, ParseError> {
        if self.s.accel.is_empty() {
            return Err(self
                .rejected
                .or(self.linear_only)
                .or(self.unreadable)
                .unwrap_or_else(|| {
                    file_error(
                        source,
                        0,
                        "no acceleration: none of the phyphox CSVs has \"Acceleration x/y/z\" \
                         columns with readable values",
                    )
                }));
        }
        let mut log = Log::new(source, Format::Phyphox);
        add_warnings(&mut log, self.warnings);
        warn_count(
            &mut log,
            self.invalid_fixes,
            file_error(
                &self.invalid_file,
                0,
                format!(
                    "{} location fix(es) with a negative accuracy, skipped",
                    self.invalid_fixes
                ),
            ),
        );
        set_records(&mut log, self.s, source);
        Ok(log)
    }
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
