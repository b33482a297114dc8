//! What a recipe made of the files: a preview of the first rows in SI units, sanity checks that
//! catch a wrong unit or column, and a first guess of a recipe for files nobody has described.
//! May import: `engine` and `io`.

use super::read::{delimiter_of, split, time_s, FileData, Samples};
use super::schema::{
    Column, Columns, Delimiter, FileRule, Recipe, Sensor, TimeUnit, RECIPE_VERSION,
};
use crate::engine::orientation::G0;
use crate::io::import::{fileset, number, FileSet};
use crate::io::ParseError;

/// Accelerometer (with gravity) or gravity magnitude median outside this range, m/s², is
/// flagged: a phone carried by a walker averages 9.81 (0.3–0.4 m/s² either way from the walk).
pub const GRAVITY_RANGE: (f64, f64) = (8.0, 11.6);
/// Linear acceleration median magnitude above this, m/s², is flagged (gravity left in).
pub const LINEAR_MAX: f64 = 5.0;
/// The 95th percentile of the rotation rate above this, rad/s, is flagged: a walking phone
/// turns at under 5 rad/s (a swinging arm peaks near 10); deg/s read as rad/s gives 50+.
pub const RATE_MAX: f64 = 15.0;
/// Magnetic field magnitude median outside this range, µT, is flagged (the Earth's is 25–65).
pub const FIELD_RANGE: (f64, f64) = (10.0, 100.0);
/// Pressure median outside this range, hPa, is flagged (sea level ~1013; 300 is above 9 km).
pub const PRESSURE_RANGE: (f64, f64) = (300.0, 1100.0);
/// Sample rates outside this range, Hz, are flagged for sensors (GNSS: 0.01–100).
pub const RATE_HZ: (f64, f64) = (1.0, 2000.0);

/// What one file gave.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FileReport {
    /// The file's label.
    pub file: String,
    /// The sensor, as in the JSON.
    pub sensor: &'static str,
    /// The preview's column titles with their SI units.
    pub columns: Vec<&'static str>,
    /// The first rows as parsed.
    pub rows: Vec<Vec<f64>>,
    /// Samples read.
    pub samples: usize,
    /// Lines skipped, and the first few reasons.
    pub skipped: u64,
    /// The first few skipped lines, with file, line, column and field.
    pub errors: Vec<ParseError>,
    /// Median sample rate, Hz.
    pub rate_hz: Option<f64>,
    /// Median magnitude of the values (vectors, pressure), SI units.
    pub median: Option<f64>,
}

/// What a recipe made of a recording: per file, and the warnings of the sanity checks.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Report {
    /// The recipe's name.
    pub recipe: String,
    /// Per file, in the recipe's order.
    pub files: Vec<FileReport>,
    /// Sanity warnings, each naming the file: likely wrong units or columns.
    pub warnings: Vec<String>,
    /// Facts worth saying (pressure read but not used, gravity restored).
    pub notes: Vec<String>,
}

/// The preview's columns for a sensor, with SI units.
pub fn preview_columns(sensor: Sensor) -> Vec<&'static str> {
    match sensor {
        Sensor::Accelerometer | Sensor::LinearAccelerometer | Sensor::Gravity => {
            vec!["t s", "x m/s²", "y m/s²", "z m/s²"]
        }
        Sensor::Gyroscope => vec!["t s", "x rad/s", "y rad/s", "z rad/s"],
        Sensor::Magnetometer => vec!["t s", "x µT", "y µT", "z µT"],
        Sensor::Pressure => vec!["t s", "p hPa"],
        Sensor::Orientation => vec!["t s", "w", "x", "y", "z"],
        Sensor::Gnss => vec!["t s", "lat °", "lon °", "accuracy m"],
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return None;
    }
    crate::engine::sort::sort_by(&mut v, f64::total_cmp);
    Some(v[v.len() / 2])
}

fn percentile(mut v: Vec<f64>, p: f64) -> Option<f64> {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return None;
    }
    crate::engine::sort::sort_by(&mut v, f64::total_cmp);
    let k = ((v.len() - 1) as f64 * p).round() as usize;
    Some(v[k])
}

/// The median rate of increasing times, Hz.
fn rate(times: &[f64]) -> Option<f64> {
    let dt: Vec<f64> = times
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .collect();
    median(dt).map(|d| 1.0 / d).filter(|r| r.is_finite())
}

/// The report of the files read by a recipe: preview, counts, and the sanity checks.
pub(crate) fn report(recipe: &Recipe, files: &[(&FileRule, FileData)]) -> Report {
    let mut out = Report {
        recipe: recipe.name.clone(),
        files: Vec::new(),
        warnings: Vec::new(),
        notes: Vec::new(),
    };
    for (rule, f) in files {
        let name = fileset::base(&f.file).to_string();
        let times: Vec<f64> = match &f.samples {
            Samples::Vectors(v) => v.iter().map(|s| s.0).collect(),
            Samples::Quaternions(v) => v.iter().map(|s| s.0).collect(),
            Samples::Scalars(v) => v.iter().map(|s| s.0).collect(),
            Samples::Fixes(v) => v.iter().map(|s| s.t).collect(),
        };
        let hz = rate(&times);
        let mags: Vec<f64> = match &f.samples {
            Samples::Vectors(v) => v.iter().map(|s| s.1.norm()).collect(),
            Samples::Scalars(v) => v.iter().map(|s| s.1).collect(),
            _ => Vec::new(),
        };
        let med = median(mags.clone());
        let warnings = time_warnings(rule, f, times.len(), hz)
            .into_iter()
            .chain(value_warnings(rule, med, mags));
        out.warnings
            .extend(warnings.map(|m| format!("{name}: {m}")));
        if rule.sensor == Sensor::Pressure {
            out.notes.push(format!(
                "{name}: {} pressure samples read and checked; the engine uses them for the height and floor changes",
                times.len()
            ));
        }
        out.files.push(FileReport {
            file: f.file.clone(),
            sensor: rule.sensor.as_str(),
            columns: preview_columns(rule.sensor),
            rows: f.preview.clone(),
            samples: times.len(),
            skipped: f.warnings.count(),
            errors: f.warnings.kept().iter().take(5).cloned().collect(),
            rate_hz: hz,
            median: med,
        });
    }
    out
}

/// The checks of a file's time column: it goes forward, and at a plausible rate (`hz`, the
/// median rate of its `samples` samples) for the time unit the recipe says.
fn time_warnings(rule: &FileRule, f: &FileData, samples: usize, hz: Option<f64>) -> Vec<String> {
    let mut out = Vec::new();
    let time_unit = rule.time_unit.as_str();
    if let (n, Some(line)) = f.backwards {
        out.push(format!(
            "time goes backwards {n} time(s), first at line {line}: is the time column right?"
        ));
    }
    if samples >= 2 && hz.is_none() {
        out.push("time does not increase: is the time column right?".into());
    }
    let (lo, hi) = if rule.sensor == Sensor::Gnss {
        (0.01, 100.0)
    } else {
        RATE_HZ
    };
    if let Some(hz) = hz.filter(|h| !(lo..=hi).contains(h)) {
        out.push(format!(
            "{} samples per second is implausible: is the time unit ({time_unit}) right?",
            sig(hz)
        ));
    }
    out
}

/// The checks of a file's values: their median magnitude `med` (and the magnitudes `mags`, for
/// the gyroscope's 95th percentile) in the range the sensor gives a walker, else a likely
/// wrong unit or column.
fn value_warnings(rule: &FileRule, med: Option<f64>, mags: Vec<f64>) -> Vec<String> {
    let mut out = Vec::new();
    let unit = rule.value_unit().map_or("", |u| u.as_str());
    match (rule.sensor, med) {
        (Sensor::Accelerometer | Sensor::Gravity, Some(m))
            if !(GRAVITY_RANGE.0..=GRAVITY_RANGE.1).contains(&m) =>
        {
            let hint = if (m / G0 - 9.81).abs() < 2.0 {
                " (it looks like m/s² read as g)"
            } else if (m * G0 - 9.81).abs() < 2.0 {
                " (it looks like g read as m/s²)"
            } else {
                ""
            };
            out.push(format!(
                "the median acceleration is {} m/s², not near 9.81: is the unit ({unit}) right?{hint}",
                sig(m)
            ));
        }
        (Sensor::LinearAccelerometer, Some(m)) if m > LINEAR_MAX => out.push(format!(
            "the median linear acceleration is {} m/s²: does it include gravity (then it is an \
             accelerometer), or is the unit ({unit}) wrong?",
            sig(m)
        )),
        (Sensor::Magnetometer, Some(m)) if !(FIELD_RANGE.0..=FIELD_RANGE.1).contains(&m) => out
            .push(format!(
                "the median field is {} µT, outside {}–{} µT: is the unit ({unit}) right?",
                sig(m),
                FIELD_RANGE.0,
                FIELD_RANGE.1
            )),
        (Sensor::Pressure, Some(m)) if !(PRESSURE_RANGE.0..=PRESSURE_RANGE.1).contains(&m) => out
            .push(format!(
                "the median pressure is {} hPa, outside {}–{} hPa: is the unit ({unit}) right?",
                sig(m),
                PRESSURE_RANGE.0,
                PRESSURE_RANGE.1
            )),
        _ => {}
    }
    if rule.sensor == Sensor::Gyroscope {
        if let Some(p95) = percentile(mags, 0.95).filter(|p| *p > RATE_MAX) {
            out.push(format!(
                "rotation rates reach {} rad/s (95th percentile), implausibly fast for a walk: \
                 is the unit ({unit}) right? (°/s read as rad/s?)",
                sig(p95)
            ));
        }
    }
    out
}

/// A number with 3 significant digits, for messages.
fn sig(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - libm::log10(v.abs()).floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// One file of an upload as the form shows it.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct FileGuess {
    /// The file's name in the set.
    pub name: String,
    /// The separator found (`comma`, `tab`, `semicolon`, `whitespace`).
    pub delimiter: Delimiter,
    /// Whether the first line looks like a header (a field that is not a number).
    pub header: bool,
    /// The columns: header names, or `"1"`, `"2"`, … for a file without a header.
    pub columns: Vec<String>,
    /// The first rows, split (at most 3).
    pub first: Vec<Vec<String>>,
}

/// The files of an unrecognised upload, described for the form, and a first recipe to edit.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Description {
    /// Per file, in the recipe's order.
    pub files: Vec<FileGuess>,
    /// A recipe guessed from the file names and first values (sensor from the name: `acc`,
    /// `gyr`, `mag`, `bar`/`press`, `gps`/`loc`, `ori`/`quat`, `grav`, `lin`; time unit from the
    /// spacing of the first times; columns in file order). Files whose sensor cannot be
    /// guessed are left out. `None` when no file could be split into columns.
    pub draft: Option<Recipe>,
}

/// Most files [`describe`] looks at.
pub const DESCRIBE_FILES: usize = 16;

/// Describes the text files of a set for the form ([`Description`]). Reads only each file's
/// first bytes ([`fileset::HEAD_BYTES`]).
pub fn describe(set: &mut dyn FileSet) -> Description {
    let names = set.names().to_vec();
    let mut files = Vec::new();
    let mut rules = Vec::new();
    for name in names.iter().take(DESCRIBE_FILES) {
        let Ok(head) = set.head(name) else { continue };
        if head.contains('\0') {
            continue;
        }
        let lines: Vec<&str> = head
            .lines()
            .map(|l| l.trim_start_matches('\u{feff}').trim_end_matches('\r'))
            .filter(|l| !l.trim().is_empty())
            .take(5)
            .collect();
        let Some(first) = lines.first() else { continue };
        let d = delimiter_of(Delimiter::Auto, first);
        let mut rec = csv::StringRecord::new();
        let mut rows: Vec<Vec<String>> = lines
            .iter()
            .map(|l| {
                split(l, d, &mut rec);
                rec.iter()
                    .map(|s| s.trim().trim_matches('"').to_string())
                    .collect()
            })
            .collect();
        if rows[0].len() < 2 {
            continue;
        }
        let header = rows[0].iter().any(|f| number(f).is_none());
        let columns = if header {
            rows.remove(0)
        } else {
            (1..=rows[0].len()).map(|i| i.to_string()).collect()
        };
        // A file without a data row holding a number (a note, a README) is not offered.
        if !rows.iter().any(|r| r.iter().any(|f| number(f).is_some())) {
            continue;
        }
        rows.truncate(3);
        let delimiter = match d {
            Some(b'\t') => Delimiter::Tab,
            Some(b';') => Delimiter::Semicolon,
            Some(_) => Delimiter::Comma,
            None => Delimiter::Whitespace,
        };
        if let Some(sensor) = guess_sensor(fileset::base(name)) {
            rules.push(draft_rule(name, sensor, delimiter, header, &columns, &rows));
        }
        files.push(FileGuess {
            name: name.clone(),
            delimiter,
            header,
            columns,
            first: rows,
        });
    }
    let draft = (!files.is_empty()).then(|| Recipe {
        recipe: RECIPE_VERSION,
        name: "my logger".into(),
        files: rules,
    });
    Description { files, draft }
}

/// The sensor a file name suggests.
pub fn guess_sensor(base: &str) -> Option<Sensor> {
    let b = base.to_lowercase();
    let has = |k: &[&str]| k.iter().any(|k| b.contains(k));
    Some(if has(&["lin"]) {
        Sensor::LinearAccelerometer
    } else if has(&["grav"]) {
        Sensor::Gravity
    } else if has(&["acc"]) {
        Sensor::Accelerometer
    } else if has(&["gyr", "rot_rate", "rate"]) {
        Sensor::Gyroscope
    } else if has(&["mag", "compass"]) {
        Sensor::Magnetometer
    } else if has(&["bar", "press"]) {
        Sensor::Pressure
    } else if has(&["ori", "quat", "att", "rot"]) {
        Sensor::Orientation
    } else if has(&["gps", "gnss", "loc", "fix"]) {
        Sensor::Gnss
    } else {
        return None;
    })
}

/// The time unit that gives the first times a sample rate between 1 and 2000 Hz (ms when none
/// does).
fn guess_time_unit(first_times: &[f64]) -> TimeUnit {
    let dt: Vec<f64> = first_times
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .collect();
    let Some(dt) = median(dt) else {
        return TimeUnit::Ms;
    };
    TimeUnit::ALL
        .into_iter()
        .find(|u| {
            let hz = u.per_second() / dt;
            (RATE_HZ.0..=RATE_HZ.1).contains(&hz)
        })
        .unwrap_or(TimeUnit::Ms)
}

fn draft_rule(
    name: &str,
    sensor: Sensor,
    delimiter: Delimiter,
    header: bool,
    columns: &[String],
    rows: &[Vec<String>],
) -> FileRule {
    let col = |i: usize| {
        if header {
            columns.get(i).map(|c| Column::Name(c.clone()))
        } else {
            (i < columns.len()).then_some(Column::Number(i + 1))
        }
    };
    let mut c = Columns {
        t: col(0),
        ..Columns::default()
    };
    let order: &[&str] = sensor.needs();
    for (k, f) in order.iter().enumerate() {
        let v = col(k + 1);
        match *f {
            "x" => c.x = v,
            "y" => c.y = v,
            "z" => c.z = v,
            "w" => c.w = v,
            "value" => c.value = v,
            "lat" => c.lat = v,
            "lon" => c.lon = v,
            "accuracy" => c.accuracy = v,
            _ => {}
        }
    }
    let times: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.first().and_then(|s| time_s(s, TimeUnit::S)))
        .collect();
    FileRule {
        pattern: fileset::base(name).to_string(),
        sensor,
        delimiter,
        header,
        skip_lines: 0,
        columns: c,
        time_unit: guess_time_unit(&times),
        unit: sensor.units().first().copied(),
        axes: None,
        optional: false,
    }
}
