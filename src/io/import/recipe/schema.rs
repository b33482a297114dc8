//! The recipe's JSON schema (version [`RECIPE_VERSION`]) and its checks.
//! May import: `engine` and `io`.

use super::{glob, RecipeError};
use crate::io::import::fileset;
use serde::{Deserialize, Serialize};

/// The schema version this build reads and writes (`"recipe": 1`).
pub const RECIPE_VERSION: u32 = 1;

/// Most file entries a recipe may have.
pub const MAX_FILES: usize = 32;

/// Largest 1-based column number a recipe may name.
pub const MAX_COLUMN: usize = 1000;

/// A column mapping for the files of one recorder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recipe {
    /// Schema version, [`RECIPE_VERSION`].
    pub recipe: u32,
    /// A name for people ("my logger"), shown when it is applied.
    pub name: String,
    /// One entry per file of a recording.
    pub files: Vec<FileRule>,
}

/// How one file of a recording is read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileRule {
    /// The file's base name, or a pattern with `*` and `?` (case-insensitive).
    #[serde(rename = "match")]
    pub pattern: String,
    /// What the file holds.
    pub sensor: Sensor,
    /// The field separator.
    #[serde(default)]
    pub delimiter: Delimiter,
    /// Whether the first line (after `skip_lines`) is a header of column names.
    #[serde(default)]
    pub header: bool,
    /// Lines skipped at the top before anything else (a preamble).
    #[serde(default)]
    pub skip_lines: u32,
    /// Where the values are.
    pub columns: Columns,
    /// The unit of the time column.
    pub time_unit: TimeUnit,
    /// The unit of the values; the sensor's SI unit when absent (m/s², rad/s, µT, hPa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<ValueUnit>,
    /// The device axes in the file's terms, when the logger's axes differ from the engine's
    /// (x right, y top of the screen, z out of it): e.g. `["-y", "x", "z"]` means the engine's
    /// x is the file's −y. Vector sensors only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axes: Option<[String; 3]>,
    /// Whether a recording may lack this file.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub optional: bool,
}

/// A column: a 1-based number, or a header name (files with a header only).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged, try_from = "serde_json::Value")]
pub enum Column {
    /// 1-based column number.
    Number(usize),
    /// Header name (case-insensitive, trimmed).
    Name(String),
}

impl TryFrom<serde_json::Value> for Column {
    type Error = String;
    /// A whole number from 1, or a string; anything else is named in the error.
    fn try_from(v: serde_json::Value) -> Result<Self, String> {
        match &v {
            serde_json::Value::String(s) => Ok(Column::Name(s.clone())),
            serde_json::Value::Number(n) => match n.as_u64() {
                Some(i) if i >= 1 => Ok(Column::Number(i.min(usize::MAX as u64) as usize)),
                _ => Err(format!(
                    "a column is a 1-based number or a header name, not {v}"
                )),
            },
            _ => Err(format!(
                "a column is a 1-based number or a header name, not {v}"
            )),
        }
    }
}

impl std::fmt::Display for Column {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Column::Number(n) => write!(f, "column {n}"),
            Column::Name(s) => write!(f, "column `{s}`"),
        }
    }
}

/// The columns of one file. Which are needed depends on the sensor: `t` always; `x`, `y`, `z`
/// for vectors; `w`, `x`, `y`, `z` for a quaternion; `value` for pressure; `lat`, `lon`,
/// `accuracy` (and optionally `altitude`, `speed`, `bearing`) for GNSS.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Columns {
    /// Time.
    pub t: Option<Column>,
    /// x (vector or quaternion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<Column>,
    /// y (vector or quaternion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<Column>,
    /// z (vector or quaternion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<Column>,
    /// Quaternion w (scalar part).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub w: Option<Column>,
    /// Pressure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Column>,
    /// Latitude, WGS84 degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lat: Option<Column>,
    /// Longitude, WGS84 degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lon: Option<Column>,
    /// Horizontal accuracy, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<Column>,
    /// Altitude, m (optional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub altitude: Option<Column>,
    /// Ground speed, m/s (optional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<Column>,
    /// Course over ground, degrees from north (optional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bearing: Option<Column>,
}

impl Columns {
    /// Every column given, with its field name.
    pub fn named(&self) -> Vec<(&'static str, &Column)> {
        [
            ("t", &self.t),
            ("x", &self.x),
            ("y", &self.y),
            ("z", &self.z),
            ("w", &self.w),
            ("value", &self.value),
            ("lat", &self.lat),
            ("lon", &self.lon),
            ("accuracy", &self.accuracy),
            ("altitude", &self.altitude),
            ("speed", &self.speed),
            ("bearing", &self.bearing),
        ]
        .into_iter()
        .filter_map(|(n, c)| c.as_ref().map(|c| (n, c)))
        .collect()
    }
}

/// What a file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sensor {
    /// Accelerometer including gravity (specific force: face up at rest z = +9.81).
    Accelerometer,
    /// Accelerometer with gravity removed ("linear acceleration"); needs a `gravity` or an
    /// `orientation` file to restore gravity.
    LinearAccelerometer,
    /// Gravity vector in the device frame (pairs with a linear accelerometer).
    Gravity,
    /// Gyroscope.
    Gyroscope,
    /// Magnetometer.
    Magnetometer,
    /// Barometric pressure: read and checked, not yet used by the engine.
    Pressure,
    /// Orientation quaternion, rotating device vectors to East-North-Up.
    Orientation,
    /// GNSS fixes.
    Gnss,
}

impl Sensor {
    /// Every sensor, in the order the form lists them.
    pub const ALL: [Sensor; 8] = [
        Sensor::Accelerometer,
        Sensor::LinearAccelerometer,
        Sensor::Gravity,
        Sensor::Gyroscope,
        Sensor::Magnetometer,
        Sensor::Pressure,
        Sensor::Orientation,
        Sensor::Gnss,
    ];

    /// The name in the JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Sensor::Accelerometer => "accelerometer",
            Sensor::LinearAccelerometer => "linear-accelerometer",
            Sensor::Gravity => "gravity",
            Sensor::Gyroscope => "gyroscope",
            Sensor::Magnetometer => "magnetometer",
            Sensor::Pressure => "pressure",
            Sensor::Orientation => "orientation",
            Sensor::Gnss => "gnss",
        }
    }

    /// The value columns it needs (besides `t`).
    pub fn needs(self) -> &'static [&'static str] {
        match self {
            Sensor::Accelerometer
            | Sensor::LinearAccelerometer
            | Sensor::Gravity
            | Sensor::Gyroscope
            | Sensor::Magnetometer => &["x", "y", "z"],
            Sensor::Pressure => &["value"],
            Sensor::Orientation => &["w", "x", "y", "z"],
            Sensor::Gnss => &["lat", "lon", "accuracy"],
        }
    }

    /// The value columns it may have besides those it needs.
    fn may(self) -> &'static [&'static str] {
        match self {
            Sensor::Gnss => &["altitude", "speed", "bearing"],
            _ => &[],
        }
    }

    /// Whether its samples are 3-vectors (axes may be remapped).
    pub fn is_vector(self) -> bool {
        self.needs() == ["x", "y", "z"]
    }

    /// The units it may be given in; the first is the SI unit the import uses.
    pub fn units(self) -> &'static [ValueUnit] {
        use ValueUnit::*;
        match self {
            Sensor::Accelerometer | Sensor::LinearAccelerometer | Sensor::Gravity => &[MS2, G],
            Sensor::Gyroscope => &[RadS, DegS],
            Sensor::Magnetometer => &[UT, NT, Gauss],
            Sensor::Pressure => &[HPa, Pa],
            Sensor::Orientation | Sensor::Gnss => &[],
        }
    }
}

/// The field separator of a file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Delimiter {
    /// The most frequent of tab, semicolon and comma on the first line; runs of spaces when
    /// none occurs.
    #[default]
    Auto,
    /// `,`
    Comma,
    /// Tab.
    Tab,
    /// `;`
    Semicolon,
    /// Runs of spaces or tabs.
    Whitespace,
}

/// The unit of a time column. Times become seconds (on the file's own clock: no origin is
/// subtracted, so files of one recording stay on one clock).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum TimeUnit {
    /// Seconds.
    #[serde(rename = "s")]
    S,
    /// Milliseconds.
    #[serde(rename = "ms")]
    Ms,
    /// Microseconds (`us` or `µs`).
    #[serde(rename = "us", alias = "µs")]
    Us,
    /// Nanoseconds.
    #[serde(rename = "ns")]
    Ns,
}

impl TimeUnit {
    /// Every unit, in the order the form lists them.
    pub const ALL: [TimeUnit; 4] = [TimeUnit::S, TimeUnit::Ms, TimeUnit::Us, TimeUnit::Ns];

    /// Powers of ten per second.
    pub fn exponent(self) -> u32 {
        match self {
            TimeUnit::S => 0,
            TimeUnit::Ms => 3,
            TimeUnit::Us => 6,
            TimeUnit::Ns => 9,
        }
    }

    /// Ticks per second.
    pub fn per_second(self) -> f64 {
        match self {
            TimeUnit::S => 1.0,
            TimeUnit::Ms => 1e3,
            TimeUnit::Us => 1e6,
            TimeUnit::Ns => 1e9,
        }
    }

    /// The name in the JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            TimeUnit::S => "s",
            TimeUnit::Ms => "ms",
            TimeUnit::Us => "us",
            TimeUnit::Ns => "ns",
        }
    }
}

/// The unit of a sensor's values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ValueUnit {
    /// m/s².
    #[serde(rename = "m/s2", alias = "m/s²")]
    MS2,
    /// Standard gravities (9.80665 m/s²).
    #[serde(rename = "g")]
    G,
    /// Radians per second.
    #[serde(rename = "rad/s")]
    RadS,
    /// Degrees per second.
    #[serde(rename = "deg/s", alias = "°/s")]
    DegS,
    /// Microtesla.
    #[serde(rename = "uT", alias = "µT")]
    UT,
    /// Nanotesla.
    #[serde(rename = "nT")]
    NT,
    /// Gauss (100 µT).
    #[serde(rename = "G")]
    Gauss,
    /// Hectopascal (millibar).
    #[serde(rename = "hPa")]
    HPa,
    /// Pascal.
    #[serde(rename = "Pa")]
    Pa,
}

impl ValueUnit {
    /// The factor to the sensor's SI unit (m/s², rad/s, µT, hPa).
    pub fn factor(self) -> f64 {
        match self {
            ValueUnit::MS2 | ValueUnit::RadS | ValueUnit::UT | ValueUnit::HPa => 1.0,
            ValueUnit::G => crate::engine::orientation::G0,
            ValueUnit::DegS => std::f64::consts::PI / 180.0,
            ValueUnit::NT => 1e-3,
            ValueUnit::Gauss => 100.0,
            ValueUnit::Pa => 0.01,
        }
    }

    /// The name in the JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            ValueUnit::MS2 => "m/s2",
            ValueUnit::G => "g",
            ValueUnit::RadS => "rad/s",
            ValueUnit::DegS => "deg/s",
            ValueUnit::UT => "uT",
            ValueUnit::NT => "nT",
            ValueUnit::Gauss => "G",
            ValueUnit::HPa => "hPa",
            ValueUnit::Pa => "Pa",
        }
    }
}

impl FileRule {
    /// The unit the values are in (the SI unit when not given).
    pub fn value_unit(&self) -> Option<ValueUnit> {
        self.unit.or_else(|| self.sensor.units().first().copied())
    }

    /// The engine axis `i` as (file axis 0–2, sign), from `axes` (identity when absent).
    /// Checked by [`Recipe::check`].
    pub fn axis(&self, i: usize) -> (usize, f64) {
        let Some(axes) = &self.axes else {
            return (i, 1.0);
        };
        parse_axis(&axes[i]).unwrap_or((i, 1.0))
    }

    fn check(&self, k: usize) -> Result<(), String> {
        let at = |msg: String| format!("files[{k}] ({:?}): {msg}", self.pattern);
        if self.pattern.trim().is_empty() || self.pattern.contains('/') {
            return Err(at(
                "`match` must be a file name or pattern, without a folder".into(),
            ));
        }
        let cols = self.columns.named();
        if self.columns.t.is_none() {
            return Err(at("`columns.t` (the time column) is missing".into()));
        }
        for need in self.sensor.needs() {
            if !cols.iter().any(|(n, _)| n == need) {
                return Err(at(format!(
                    "a {} file needs `columns.{need}`",
                    self.sensor.as_str()
                )));
            }
        }
        for (n, c) in &cols {
            if *n != "t" && !self.sensor.needs().contains(n) && !self.sensor.may().contains(n) {
                return Err(at(format!(
                    "`columns.{n}` does not apply to a {} file",
                    self.sensor.as_str()
                )));
            }
            match c {
                Column::Number(i) if !(1..=MAX_COLUMN).contains(i) => {
                    return Err(at(format!(
                    "`columns.{n}`: column numbers start at 1 and go up to {MAX_COLUMN}, not {i}"
                )))
                }
                Column::Name(s) if !self.header => {
                    return Err(at(format!(
                        "`columns.{n}` is the name {s:?}, but the file has no header \
                         (`\"header\": false`): give a 1-based column number"
                    )))
                }
                Column::Name(s) if s.trim().is_empty() => {
                    return Err(at(format!("`columns.{n}` is an empty name")))
                }
                _ => {}
            }
        }
        if let Some(u) = self.unit {
            if !self.sensor.units().contains(&u) {
                let allowed: Vec<&str> = self.sensor.units().iter().map(|u| u.as_str()).collect();
                return Err(at(if allowed.is_empty() {
                    format!("a {} file takes no `unit`", self.sensor.as_str())
                } else {
                    format!(
                        "unit {:?} does not fit a {} (use {})",
                        u.as_str(),
                        self.sensor.as_str(),
                        allowed.join(", ")
                    )
                }));
            }
        }
        if let Some(axes) = &self.axes {
            if !self.sensor.is_vector() {
                return Err(at(format!(
                    "a {} file takes no `axes`",
                    self.sensor.as_str()
                )));
            }
            let mut seen = [false; 3];
            for a in axes {
                let (i, _) = parse_axis(a).ok_or_else(|| {
                    at(format!("`axes`: {a:?} is not one of x, y, z, -x, -y, -z"))
                })?;
                if std::mem::replace(&mut seen[i], true) {
                    return Err(at(format!("`axes` names the file's axis {a:?} twice")));
                }
            }
        }
        if self.skip_lines > 1_000_000 {
            return Err(at("`skip_lines` over 1000000".into()));
        }
        Ok(())
    }
}

fn parse_axis(a: &str) -> Option<(usize, f64)> {
    let a = a.trim();
    let (sign, name) = match a.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, a.strip_prefix('+').unwrap_or(a)),
    };
    let i = ["x", "y", "z"]
        .iter()
        .position(|&n| n.eq_ignore_ascii_case(name))?;
    Some((i, sign))
}

impl Recipe {
    /// Reads and checks a recipe: JSON with no unknown field, the supported version, and every
    /// file entry consistent ([`Recipe::check`]). The error names the entry and field.
    pub fn from_json(text: &str) -> Result<Recipe, RecipeError> {
        let r: Recipe = serde_json::from_str(text).map_err(|e| RecipeError::Json(e.to_string()))?;
        r.check()?;
        Ok(r)
    }

    /// The recipe as pretty JSON (what the page offers to download and the CLI reads).
    pub fn to_json(&self) -> Result<String, RecipeError> {
        serde_json::to_string_pretty(self).map_err(|e| RecipeError::Write(e.to_string()))
    }

    /// Checks what serde cannot: the version, a name, 1 to `MAX_FILES` file entries, the
    /// columns each sensor needs and no others, column numbers from 1, names only with a
    /// header, units that fit the sensor, an accelerometer (the engine counts steps from
    /// acceleration) and something to restore gravity to a linear accelerometer.
    pub fn check(&self) -> Result<(), RecipeError> {
        self.check_rules().map_err(RecipeError::Invalid)
    }

    /// [`Recipe::check`]'s rules, the message naming the entry and field.
    fn check_rules(&self) -> Result<(), String> {
        if self.recipe != RECIPE_VERSION {
            return Err(format!(
                "recipe: version {} is not supported (this build reads \"recipe\": {RECIPE_VERSION})",
                self.recipe
            ));
        }
        if self.name.trim().is_empty() || self.name.chars().count() > 100 {
            return Err("recipe: `name` must be 1 to 100 characters".into());
        }
        if self.files.is_empty() || self.files.len() > MAX_FILES {
            return Err(format!(
                "recipe: `files` must have 1 to {MAX_FILES} entries"
            ));
        }
        for (k, f) in self.files.iter().enumerate() {
            f.check(k)
                .map_err(|e| format!("recipe {:?}: {e}", self.name))?;
        }
        let has = |s: Sensor| self.files.iter().any(|f| f.sensor == s);
        if !has(Sensor::Accelerometer) && !has(Sensor::LinearAccelerometer) {
            return Err(format!(
                "recipe {:?}: no accelerometer file: the engine counts steps from acceleration",
                self.name
            ));
        }
        if !has(Sensor::Accelerometer) && !has(Sensor::Gravity) && !has(Sensor::Orientation) {
            return Err(format!(
                "recipe {:?}: a linear accelerometer (gravity removed) needs a gravity or an \
                 orientation file to restore gravity",
                self.name
            ));
        }
        Ok(())
    }

    /// Which file of the folder `dir` each entry reads (by index of `names`; `None` for an
    /// optional entry without a file). Several entries may read one file when their sensors
    /// differ (a file of accelerometer and gyroscope columns). `Err` says why the recipe does not
    /// match the folder: an entry that is not optional matches no file there, an entry matches
    /// several, or two entries read one file as the same sensor.
    pub fn match_dir(
        &self,
        names: &[String],
        dir: &str,
    ) -> Result<Vec<Option<usize>>, RecipeError> {
        self.match_dir_words(names, dir)
            .map_err(RecipeError::NoMatch)
    }

    /// [`Recipe::match_dir`], the error in words.
    fn match_dir_words(&self, names: &[String], dir: &str) -> Result<Vec<Option<usize>>, String> {
        let mut out = Vec::with_capacity(self.files.len());
        for f in &self.files {
            let hits: Vec<usize> = names
                .iter()
                .enumerate()
                .filter(|(_, n)| fileset::parent(n) == dir && glob(&f.pattern, fileset::base(n)))
                .map(|(i, _)| i)
                .collect();
            match hits.as_slice() {
                [] if f.optional => out.push(None),
                [] => return Err(format!("no file matches {:?}", f.pattern)),
                [i] => {
                    // One file may hold several sensors (t, ax, ay, az, gx, gy, gz): an entry
                    // per sensor. Two entries of one sensor on one file are a mistake.
                    let same = out
                        .iter()
                        .zip(&self.files)
                        .position(|(o, g)| *o == Some(*i) && g.sensor == f.sensor);
                    if let Some(k) = same {
                        return Err(format!(
                            "{:?} and {:?} both read {} as {}: make the patterns narrower",
                            self.files[k].pattern,
                            f.pattern,
                            fileset::base(&names[*i]),
                            f.sensor.as_str()
                        ));
                    }
                    out.push(Some(*i))
                }
                [a, b, ..] => {
                    return Err(format!(
                        "{:?} matches several files ({}, {}): make the pattern narrower",
                        f.pattern,
                        fileset::base(&names[*a]),
                        fileset::base(&names[*b])
                    ))
                }
            }
        }
        Ok(out)
    }
}
