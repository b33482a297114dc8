//! Sensor Logger (Android and iOS app by Kelvin Choi): a folder or zip of per-sensor CSVs, or
//! the app's JSON export.
//!
//! # Files
//! `Accelerometer.csv` (gravity removed), `Gravity.csv`, `TotalAcceleration.csv` (Android only,
//! gravity included), `Gyroscope.csv`, `Magnetometer.csv`, `Orientation.csv`, `Location.csv` and
//! `Metadata.csv`. Columns are matched by name (case-insensitive), never by position: the order
//! differs between versions and platforms (`time,seconds_elapsed,z,y,x`, older `time,z,y,x`,
//! `time,yaw,qx,qz,roll,qw,qy,pitch`, …).
//!
//! # Conversions
//! - Time: `time`, Unix epoch in nanoseconds, becomes seconds (split into whole seconds and the
//!   rest before converting, so no precision is lost beyond the final `f64`). A recording whose
//!   accelerometer file has no `time` column uses `seconds_elapsed` throughout instead.
//! - Acceleration: when `TotalAcceleration.csv` is present it is the accelerometer stream;
//!   otherwise total = `Accelerometer` + `Gravity`, each accelerometer sample paired with the
//!   gravity sample nearest in time (they usually share timestamps). Pairs further apart than
//!   [`HOLD_S`] are dropped and counted.
//! - Units: if the mean norm of gravity (or of the total acceleration when there is no gravity)
//!   is below 3, the acceleration files are in g and are multiplied by [`G0`]; otherwise m/s².
//! - Sign: iOS acceleration and gravity are negated ([`Platform::to_android`]), unless the
//!   recording was made with Sensor Logger's "Standardise Units & Frames" setting (a true
//!   `standardisation` column in `Metadata.csv`), which already gives Android conventions.
//!   The platform is decided by [`decide_platform`].
//! - Orientation: on Android (and standardised iOS) the quaternion is the rotation vector, device
//!   → East-North-Up, used as it is. On iOS it is Core Motion's attitude, which we take as the
//!   rotation from the device frame to Core Motion's reference frame with x towards magnetic
//!   north, z up, hence y west (`xMagneticNorthZVertical`); the device → ENU rotation is then
//!   a +90° turn about z applied after it (`q_enu = Rz(90°) · q_ios`), since ENU east = −y_ref,
//!   north = x_ref, up = z_ref. North stays magnetic (no declination is applied); a recording
//!   made with an arbitrary-x reference frame would carry an unknown heading offset.
//! - Gyroscope (rad/s) and magnetometer (µT) are used as they are on both platforms.
//! - Location: fixes with a negative `horizontalAccuracy` are invalid and skipped (each counted as
//!   a warning); a negative `speed` or `bearing` is an unknown value.
//!
//! # JSON export
//! An array of objects `{"sensor":"Accelerometer","time":"…","seconds_elapsed":"…","z":"…",…}`
//! whose values are strings (numbers are accepted too). It is read element by element with a
//! streaming deserializer; a file cut short keeps the elements before the cut (with a warning).

use super::common::{
    add_warnings, drop_non_finite, not_a_number, split_line, unit_quaternion, warn_count, Table,
    Warnings,
};
use super::{field_error, file_error, fileset, number, FileSet, Format, Log, Platform, Streams};
use crate::engine::orientation::{G0, HOLD_S};
use crate::engine::types::GnssFix;
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::cell::Cell;
use std::io::{self, BufRead, Read};

// ---------------------------------------------------------------------------------------------
// Sensor Logger.
// ---------------------------------------------------------------------------------------------

/// The Sensor Logger files (lower case) whose samples we use.
const FILES: [(&str, Kind); 8] = [
    ("metadata.csv", Kind::Metadata),
    ("totalacceleration.csv", Kind::Total),
    ("accelerometer.csv", Kind::Accel),
    ("gravity.csv", Kind::Gravity),
    ("gyroscope.csv", Kind::Gyro),
    ("magnetometer.csv", Kind::Mag),
    ("orientation.csv", Kind::Orientation),
    ("location.csv", Kind::Location),
];

/// What one Sensor Logger file (or JSON `sensor`) holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Metadata,
    Total,
    Accel,
    Gravity,
    Gyro,
    Mag,
    Orientation,
    Location,
}

impl Kind {
    fn from_sensor(name: &str) -> Option<Kind> {
        let name = name.trim().to_lowercase();
        FILES
            .iter()
            .find(|(f, _)| f.strip_suffix(".csv") == Some(name.as_str()))
            .map(|&(_, k)| k)
    }

    /// Columns a file of this kind must have (besides the clock).
    fn required(self) -> &'static [&'static str] {
        match self {
            Kind::Metadata => &[],
            Kind::Total | Kind::Accel | Kind::Gravity | Kind::Gyro | Kind::Mag => &["x", "y", "z"],
            Kind::Orientation => &["qw", "qx", "qy", "qz"],
            Kind::Location => &["latitude", "longitude", "horizontalaccuracy"],
        }
    }

    /// Whether an unreadable file of this kind makes the log unreadable. (An unreadable
    /// `Gravity.csv` is a warning here, and fatal later only when gravity is needed.)
    fn essential(self) -> bool {
        matches!(self, Kind::Total | Kind::Accel)
    }
}

/// Which column is the log's clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Clock {
    /// `time`, Unix epoch ns.
    EpochNs,
    /// `seconds_elapsed`, s since the recording started.
    Elapsed,
}

impl Clock {
    fn column(self) -> &'static str {
        match self {
            Clock::EpochNs => "time",
            Clock::Elapsed => "seconds_elapsed",
        }
    }

    fn seconds(self, s: &str) -> Option<f64> {
        match self {
            Clock::EpochNs => ns_to_s(s),
            Clock::Elapsed => number(s),
        }
    }
}

/// Unix nanoseconds as text → seconds: integers are split into whole seconds and the rest
/// before converting; other numbers are scaled.
fn ns_to_s(s: &str) -> Option<f64> {
    let t = s.trim().trim_matches('"').trim();
    if let Ok(ns) = t.parse::<i64>() {
        let (q, r) = (ns.div_euclid(1_000_000_000), ns.rem_euclid(1_000_000_000));
        return Some(q as f64 + r as f64 * 1e-9);
    }
    number(t).map(|v| v * 1e-9)
}

/// One row of a Sensor Logger file or JSON element: values by lower-case name.
trait Fields {
    fn value(&self, key: &str) -> Option<&str>;
    fn error(&self, key: &str, message: String) -> ParseError;
}

struct CsvRow<'a> {
    rec: &'a csv::StringRecord,
    lower: &'a [String],
    header: &'a [String],
    file: &'a str,
    line: u64,
}

impl Fields for CsvRow<'_> {
    fn value(&self, key: &str) -> Option<&str> {
        let i = self.lower.iter().position(|h| h == key)?;
        self.rec.get(i)
    }
    fn error(&self, key: &str, message: String) -> ParseError {
        match self.lower.iter().position(|h| h == key) {
            Some(i) => field_error(self.file, self.line, i + 1, &self.header[i], message),
            None => file_error(self.file, self.line, format!("column `{key}`: {message}")),
        }
    }
}

struct JsonRow<'a> {
    pairs: Vec<(String, String)>,
    file: &'a str,
    line: u64,
    column: usize,
    index: u64,
}

impl Fields for JsonRow<'_> {
    fn value(&self, key: &str) -> Option<&str> {
        self.pairs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn error(&self, key: &str, message: String) -> ParseError {
        let mut e = field_error(
            self.file,
            self.line,
            self.column,
            key,
            format!("array element {}: {message}", self.index),
        );
        if key.is_empty() {
            e.field = None;
        }
        e
    }
}

/// The samples of a recording as written, before units, signs and frames are settled.
#[derive(Default)]
struct Raw {
    accel: Vec<(f64, Vector3<f64>)>,
    gravity: Vec<(f64, Vector3<f64>)>,
    total: Vec<(f64, Vector3<f64>)>,
    gyro: Vec<(f64, Vector3<f64>)>,
    mag: Vec<(f64, Vector3<f64>)>,
    orientation: Vec<(f64, UnitQuaternion<f64>)>,
    fixes: Vec<GnssFix>,
    platform: Option<Platform>,
    standardised: bool,
    warnings: Warnings,
    /// Where the acceleration came from, for messages.
    accel_file: String,
}

fn get(row: &dyn Fields, key: &str) -> Result<f64, ParseError> {
    match row.value(key) {
        None => Err(row.error(key, "missing".into())),
        Some(s) => number(s).ok_or_else(|| row.error(key, not_a_number(s))),
    }
}

fn opt(row: &dyn Fields, key: &str) -> Result<Option<f64>, ParseError> {
    match row.value(key).map(str::trim) {
        None | Some("") => Ok(None),
        Some(s) => number(s)
            .map(Some)
            .ok_or_else(|| row.error(key, not_a_number(s))),
    }
}

impl Raw {
    /// Makes room for `n` samples of `kind` at once, so that a long recording's streams are not
    /// grown by doubling (which copies them and, in wasm, leaves the memory up to twice their
    /// size).
    /// An estimate too large to allocate is ignored (the stream then grows as it is read).
    fn reserve(&mut self, kind: Kind, n: usize) {
        let _ = match kind {
            Kind::Total => self.total.try_reserve_exact(n),
            Kind::Accel => self.accel.try_reserve_exact(n),
            Kind::Gravity => self.gravity.try_reserve_exact(n),
            Kind::Gyro => self.gyro.try_reserve_exact(n),
            Kind::Mag => self.mag.try_reserve_exact(n),
            Kind::Orientation => self.orientation.try_reserve_exact(n),
            Kind::Metadata | Kind::Location => Ok(()),
        };
    }

    fn metadata(&mut self, row: &dyn Fields) {
        if let Some(p) = row.value("platform") {
            let p = p.trim().to_lowercase();
            if p.contains("ios") || p.contains("iphone") || p.contains("watch") {
                self.platform = Some(Platform::Ios);
            } else if p.contains("android") {
                self.platform = Some(Platform::Android);
            }
        }
        for key in [
            "standardisation",
            "standardization",
            "standardise",
            "standardize",
        ] {
            if let Some(v) = row.value(key) {
                let v = v.trim().to_lowercase();
                self.standardised = matches!(v.as_str(), "true" | "1" | "yes" | "on");
            }
        }
    }

    /// Adds one sample of a file of kind `kind`.
    fn sample(&mut self, kind: Kind, clock: Clock, row: &dyn Fields) -> Result<(), ParseError> {
        if kind == Kind::Metadata {
            self.metadata(row);
            return Ok(());
        }
        let key = clock.column();
        let t = match row.value(key) {
            None => return Err(row.error(key, "missing".into())),
            Some(s) => clock
                .seconds(s)
                .ok_or_else(|| row.error(key, not_a_number(s)))?,
        };
        let v3 = |row: &dyn Fields| -> Result<Vector3<f64>, ParseError> {
            Ok(Vector3::new(get(row, "x")?, get(row, "y")?, get(row, "z")?))
        };
        match kind {
            Kind::Metadata => {}
            Kind::Total => self.total.push((t, v3(row)?)),
            Kind::Accel => self.accel.push((t, v3(row)?)),
            Kind::Gravity => self.gravity.push((t, v3(row)?)),
            Kind::Gyro => self.gyro.push((t, v3(row)?)),
            Kind::Mag => self.mag.push((t, v3(row)?)),
            Kind::Orientation => {
                let [w, x, y, z] = [
                    get(row, "qw")?,
                    get(row, "qx")?,
                    get(row, "qy")?,
                    get(row, "qz")?,
                ];
                let q = unit_quaternion(w, x, y, z).ok_or_else(|| {
                    let n = Quaternion::new(w, x, y, z).norm();
                    row.error("qw", format!("quaternion norm is {n:.4}, not 1"))
                })?;
                self.orientation.push((t, q));
            }
            Kind::Location => {
                let lat = get(row, "latitude")?;
                let lon = get(row, "longitude")?;
                let acc = get(row, "horizontalaccuracy")?;
                if acc < 0.0 {
                    return Err(row.error(
                        "horizontalaccuracy",
                        format!("negative accuracy {acc}: fix marked invalid, skipped"),
                    ));
                }
                let fix = GnssFix {
                    t,
                    lat_deg: lat,
                    lon_deg: lon,
                    h_accuracy_m: acc,
                    altitude_m: opt(row, "altitude")?,
                    speed_mps: opt(row, "speed")?.filter(|v| *v >= 0.0),
                    bearing_deg: opt(row, "bearing")?.filter(|v| *v >= 0.0),
                };
                if let Err(e) = fix.check() {
                    return Err(row.error("latitude", format!("invalid fix: {e}")));
                }
                self.fixes.push(fix);
            }
        }
        Ok(())
    }

    /// Reads one CSV file of kind `kind` into the raw streams.
    fn csv_file(
        &mut self,
        r: impl BufRead,
        label: &str,
        kind: Kind,
        clock: Clock,
    ) -> Result<(), ParseError> {
        let table = match Table::open(r, label, Some(b',')) {
            Ok(t) => t,
            Err(e) if !kind.essential() => {
                self.warnings.push(e);
                return Ok(());
            }
            Err(e) => return Err(e),
        };
        let Some(mut table) = table else {
            if kind.essential() {
                return Err(file_error(label, 0, "empty file"));
            }
            return Ok(());
        };
        let mut missing: Vec<&str> = kind
            .required()
            .iter()
            .copied()
            .filter(|c| table.named(c).is_none())
            .collect();
        if kind != Kind::Metadata && table.named(clock.column()).is_none() {
            missing.insert(0, clock.column());
        }
        if !missing.is_empty() {
            let e = file_error(
                label,
                table.header_line,
                format!(
                    "not a Sensor Logger file: column{} `{}` missing from the header",
                    if missing.len() > 1 { "s" } else { "" },
                    missing.join("`, `")
                ),
            );
            if kind.essential() {
                return Err(e);
            }
            self.warnings.push(e);
            return Ok(());
        }
        let (header, lower) = (table.header.clone(), table.lower.clone());
        let mut warnings = Warnings::default();
        table.rows(label, &mut warnings, |line, rec| {
            let row = CsvRow {
                rec,
                lower: &lower,
                header: &header,
                file: label,
                line,
            };
            if let Err(e) = self.sample(kind, clock, &row) {
                self.warnings.push(e);
            }
        })?;
        self.warnings.extend(warnings);
        Ok(())
    }

    /// Settles units, signs and frames and builds the log.
    fn finish(mut self, mut log: Log, source_for_errors: &str) -> Result<Log, ParseError> {
        for v in [
            &mut self.accel,
            &mut self.gravity,
            &mut self.total,
            &mut self.gyro,
            &mut self.mag,
        ] {
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        self.orientation.sort_by(|a, b| a.0.total_cmp(&b.0));
        let accel_file = if self.accel_file.is_empty() {
            source_for_errors.to_string()
        } else {
            self.accel_file.clone()
        };
        if self.total.is_empty() && self.accel.is_empty() {
            return Err(file_error(
                &accel_file,
                0,
                "no accelerometer samples (Accelerometer or TotalAcceleration)",
            ));
        }
        if self.total.is_empty() && self.gravity.is_empty() {
            let gravity_problem = self
                .warnings
                .find(|w| w.column.is_none() && w.file.to_lowercase().ends_with("gravity.csv"));
            if let Some(e) = gravity_problem {
                return Err(e.clone());
            }
            return Err(file_error(
                &accel_file,
                0,
                "Accelerometer has gravity removed, and there is no Gravity or TotalAcceleration \
                 to restore it",
            ));
        }
        // Units: g or m/s², from the size of gravity.
        let reference = if self.gravity.is_empty() {
            &self.total
        } else {
            &self.gravity
        };
        let mean_norm =
            reference.iter().map(|(_, v)| v.norm()).sum::<f64>() / reference.len().max(1) as f64;
        let scale = if mean_norm < 3.0 { G0 } else { 1.0 };
        let platform = decide_platform(
            self.platform,
            !self.total.is_empty(),
            scale != 1.0,
            &self.gravity,
            &self.orientation,
            reference,
        );
        log.platform = platform;
        // Conventions of the values as written.
        let ios_frames = platform == Some(Platform::Ios) && !self.standardised;
        let sign = if ios_frames { -scale } else { scale };
        let mut s = Streams::default();
        let mut unpaired = 0u64;
        if !self.total.is_empty() {
            s.accel = self.total.iter().map(|&(t, v)| (t, v * sign)).collect();
        } else {
            let g = &self.gravity;
            let mut j = 0usize;
            for &(t, a) in &self.accel {
                while j + 1 < g.len() && g[j + 1].0 <= t {
                    j += 1;
                }
                let best = [j, j + 1]
                    .into_iter()
                    .filter(|&k| k < g.len())
                    .min_by(|&p, &q| (g[p].0 - t).abs().total_cmp(&(g[q].0 - t).abs()));
                match best {
                    Some(k) if (g[k].0 - t).abs() <= HOLD_S => {
                        s.accel.push((t, (a + g[k].1) * sign));
                    }
                    _ => unpaired += 1,
                }
            }
        }
        s.gyro = std::mem::take(&mut self.gyro);
        s.mag = std::mem::take(&mut self.mag);
        let to_enu = if ios_frames {
            // Rz(+90°): Core Motion's (north, west, up) reference → (east, north, up).
            let h = std::f64::consts::FRAC_1_SQRT_2;
            UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, h))
        } else {
            UnitQuaternion::identity()
        };
        s.orientation = self
            .orientation
            .iter()
            .map(|&(t, q)| (t, to_enu * q))
            .collect();
        s.fixes = std::mem::take(&mut self.fixes);
        let dropped = drop_non_finite(&mut s);
        if s.accel.is_empty() {
            return Err(file_error(
                &accel_file,
                0,
                "no usable accelerometer samples (no gravity sample within 0.2 s of any)",
            ));
        }
        log.records = s.into_records();
        add_warnings(&mut log, std::mem::take(&mut self.warnings));
        warn_count(
            &mut log,
            unpaired,
            file_error(
                &accel_file,
                0,
                format!(
                    "{unpaired} accelerometer sample(s) without a gravity sample within {HOLD_S} s, \
                     skipped"
                ),
            ),
        );
        warn_count(
            &mut log,
            dropped,
            file_error(
                source_for_errors,
                0,
                format!("{dropped} sample(s) overflowed to a non-finite value, skipped"),
            ),
        );
        Ok(log)
    }
}

/// Decides the platform of a Sensor Logger recording, in this order:
/// 1. `platform` in `Metadata.csv` (`ios` or `android`) when given;
/// 2. a `TotalAcceleration.csv` exists: Android (iOS has no such file);
/// 3. acceleration in g (mean |gravity| < 3): iOS (Android always writes m/s²);
/// 4. gravity and orientation both present: gravity turned into the reference frame by the
///    orientation points up on Android (the reading is the reaction to gravity) and down on iOS
///    (Core Motion's gravity vector), in both cases whatever the pose, because both reference
///    frames have z up. The mean of the vertical component of the unit gravity vector decides
///    when it exceeds 0.5 in size;
/// 5. otherwise [`Platform::guess`] on the mean gravity (or total acceleration): the sign on the
///    axis with the largest mean, positive meaning Android. This last rule fails for a phone
///    carried upside down, which rules 1–4 do not depend on.
///
/// `None` only when nothing is left to decide from.
pub fn decide_platform(
    metadata: Option<Platform>,
    has_total: bool,
    in_g: bool,
    gravity: &[(f64, Vector3<f64>)],
    orientation: &[(f64, UnitQuaternion<f64>)],
    reference: &[(f64, Vector3<f64>)],
) -> Option<Platform> {
    if metadata.is_some() {
        return metadata;
    }
    if has_total {
        return Some(Platform::Android);
    }
    if in_g {
        return Some(Platform::Ios);
    }
    if !gravity.is_empty() && !orientation.is_empty() {
        let (mut sum, mut n) = (0.0, 0usize);
        let mut j = 0usize;
        for &(t, g) in gravity {
            while j + 1 < orientation.len() && orientation[j + 1].0 <= t {
                j += 1;
            }
            let best = [j, j + 1]
                .into_iter()
                .filter(|&k| k < orientation.len())
                .min_by(|&p, &q| {
                    (orientation[p].0 - t)
                        .abs()
                        .total_cmp(&(orientation[q].0 - t).abs())
                });
            let norm = g.norm();
            if let Some(k) = best {
                if (orientation[k].0 - t).abs() <= HOLD_S && norm > 0.0 && norm.is_finite() {
                    sum += (orientation[k].1 * g).z / norm;
                    n += 1;
                }
            }
        }
        if n > 0 {
            let mean = sum / n as f64;
            if mean > 0.5 {
                return Some(Platform::Android);
            }
            if mean < -0.5 {
                return Some(Platform::Ios);
            }
        }
    }
    if reference.is_empty() {
        return None;
    }
    let mean = reference
        .iter()
        .fold(Vector3::zeros(), |acc, (_, v)| acc + v)
        / reference.len() as f64;
    Platform::guess(mean)
}

fn is_csv(name: &str) -> bool {
    name.to_ascii_lowercase().ends_with(".csv")
}

/// Recognises a Sensor Logger folder inside a file set and reads it. `dir` is a folder of
/// `names` (ending with `/`, or empty for the top). Returns the files it consumed (every CSV
/// directly in the folder) and the log, or `None` when the folder is not a Sensor Logger
/// recording: it needs `Accelerometer.csv` or `TotalAcceleration.csv` whose header has a `time`
/// or `seconds_elapsed` column and `x`, `y`, `z`.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let in_dir: Vec<&String> = names
        .iter()
        .filter(|n| fileset::parent(n) == dir && is_csv(n))
        .collect();
    let find = |base: &str| {
        in_dir
            .iter()
            .find(|n| fileset::base(n).eq_ignore_ascii_case(base))
            .map(|n| n.to_string())
    };
    let accel = find("TotalAcceleration.csv").or_else(|| find("Accelerometer.csv"))?;
    let head = set.head(&accel).ok()?;
    let first = head
        .lines()
        .next()
        .unwrap_or("")
        .trim_start_matches('\u{feff}');
    let cols: Vec<String> = split_line(first, b',')
        .into_iter()
        .map(|c| c.to_lowercase())
        .collect();
    let has = |c: &str| cols.iter().any(|h| h == c);
    if !((has("time") || has("seconds_elapsed")) && has("x") && has("y") && has("z")) {
        return None;
    }
    let consumed: Vec<String> = in_dir.iter().map(|n| n.to_string()).collect();
    let clock = if has("time") {
        Clock::EpochNs
    } else {
        Clock::Elapsed
    };
    let source = {
        let l = set.label(dir.trim_end_matches('/'));
        let l = l.trim_end_matches('/').to_string();
        if l.is_empty() {
            set.label(&accel)
        } else {
            l
        }
    };
    let log = Log::new(source.clone(), Format::SensorLogger);
    let read = (|| {
        let mut raw = Raw {
            accel_file: set.label(&accel),
            ..Raw::default()
        };
        let has_total = find("TotalAcceleration.csv").is_some();
        for (base, kind) in FILES {
            if kind == Kind::Accel && has_total {
                continue;
            }
            let Some(name) = in_dir
                .iter()
                .find(|n| fileset::base(n).to_ascii_lowercase() == base)
            else {
                continue;
            };
            let label = set.label(name);
            if let (Some(size), Ok(head)) = (set.size(name), set.head(name)) {
                raw.reserve(kind, crate::io::lines::estimate_records(&head, size));
            }
            let r = set
                .open(name)
                .map_err(|e| file_error(&label, 0, format!("cannot open: {e}")))?;
            raw.csv_file(r, &label, kind, clock)?;
        }
        raw.finish(log, &source)
    })();
    Some((consumed, read))
}

/// Whether the first bytes of a file look like Sensor Logger's JSON export: an array whose
/// first object has a `"sensor"` key.
pub fn looks_like_json(head: &str) -> bool {
    let h = head.trim_start_matches('\u{feff}').trim_start();
    h.starts_with('[') && h.contains("\"sensor\"")
}

/// Largest JSON element read, bytes (a reading is about 200 bytes). A larger one (a file
/// that is one huge string, junk) stops the reading instead of being held in memory.
const MAX_ELEMENT: u64 = super::MAX_LINE as u64;

/// A reader that counts lines and columns of the bytes it passes on, and refuses to pass on
/// more than [`MAX_ELEMENT`] bytes after the start of the current element (`element`, a byte
/// offset the visitor moves forward after each element).
struct Counting<'a, R> {
    inner: R,
    pos: &'a Cell<(u64, usize)>,
    read: &'a Cell<u64>,
    element: &'a Cell<u64>,
    too_long: &'a Cell<bool>,
}

impl<R: Read> Read for Counting<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let room = (self.element.get() + MAX_ELEMENT).saturating_sub(self.read.get());
        if room == 0 {
            self.too_long.set(true);
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("an element longer than {MAX_ELEMENT} bytes"),
            ));
        }
        let cap = buf.len().min(usize::try_from(room).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..cap])?;
        self.read.set(self.read.get() + n as u64);
        let (mut line, mut col) = self.pos.get();
        for &b in &buf[..n] {
            if b == b'\n' {
                line += 1;
                col = 0;
            } else {
                col += 1;
            }
        }
        self.pos.set((line, col));
        Ok(n)
    }
}

/// Visits the top-level array element by element.
struct Elements<'a> {
    raw: &'a mut Raw,
    label: &'a str,
    pos: &'a Cell<(u64, usize)>,
    count: &'a Cell<u64>,
    element: &'a Cell<u64>,
    read: &'a Cell<u64>,
}

impl<'de> serde::de::Visitor<'de> for Elements<'_> {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("an array of Sensor Logger readings")
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while let Some(v) = seq.next_element::<serde_json::Value>()? {
            // The next element may take MAX_ELEMENT bytes from here (the reader runs ahead by
            // at most its buffer).
            self.element.set(self.read.get());
            let index = self.count.get() + 1;
            self.count.set(index);
            let (line, column) = self.pos.get();
            let mut row = JsonRow {
                pairs: Vec::new(),
                file: self.label,
                line,
                column: column.max(1),
                index,
            };
            let serde_json::Value::Object(map) = v else {
                self.raw
                    .warnings
                    .push(row.error("", "not an object".to_string()));
                continue;
            };
            for (k, v) in map {
                let v = match v {
                    serde_json::Value::String(s) => s,
                    serde_json::Value::Number(n) => n.to_string(),
                    serde_json::Value::Bool(b) => b.to_string(),
                    _ => continue,
                };
                row.pairs.push((k.to_lowercase(), v));
            }
            let Some(sensor) = row.value("sensor") else {
                self.raw
                    .warnings
                    .push(row.error("sensor", "missing".to_string()));
                continue;
            };
            // Sensors we do not use (Barometer, Pedometer, …) are ignored silently.
            let Some(kind) = Kind::from_sensor(sensor) else {
                continue;
            };
            if let Err(e) = self.raw.sample(kind, Clock::EpochNs, &row) {
                self.raw.warnings.push(e);
            }
        }
        Ok(())
    }
}

/// Reads Sensor Logger's JSON export (see the module documentation).
pub fn read_json(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let pos = Cell::new((1u64, 0usize));
    let count = Cell::new(0u64);
    let mut raw = Raw {
        accel_file: label.to_string(),
        ..Raw::default()
    };
    let (read, element, too_long) = (Cell::new(0u64), Cell::new(0u64), Cell::new(false));
    let counting = Counting {
        inner: r,
        pos: &pos,
        read: &read,
        element: &element,
        too_long: &too_long,
    };
    let mut de = serde_json::Deserializer::from_reader(counting);
    let parsed = serde::Deserializer::deserialize_seq(
        &mut de,
        Elements {
            raw: &mut raw,
            label,
            pos: &pos,
            count: &count,
            element: &element,
            read: &read,
        },
    )
    .and_then(|()| de.end());
    if let Err(e) = parsed {
        let err = ParseError {
            file: label.to_string(),
            line: e.line() as u64,
            column: Some(e.column()),
            field: None,
            message: format!("JSON: {e}"),
        };
        if e.is_io() && !too_long.get() {
            return Err(err);
        }
        if count.get() == 0 {
            return Err(ParseError {
                message: format!("not a Sensor Logger JSON export: {e}"),
                ..err
            });
        }
        // Cut short or damaged after some elements: keep what was read.
        raw.warnings.push(ParseError {
            message: format!(
                "JSON damaged after {} element(s), rest ignored: {e}",
                count.get()
            ),
            ..err
        });
    }
    raw.finish(Log::new(label, Format::SensorLoggerJson), label)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nanoseconds_to_seconds() {
        assert_eq!(ns_to_s("1698745673473000000"), Some(1698745673.473));
        assert_eq!(ns_to_s("-1500000000"), Some(-1.5));
        assert_eq!(ns_to_s("1.5e9"), Some(1.5));
        assert_eq!(ns_to_s("x"), None);
    }

    #[test]
    fn ios_attitude_to_enu() {
        // Face up, top pointing north: the device's x (right) points east, which is −y of
        // Core Motion's (north, west, up) frame, so the attitude is a −90° turn about z.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q_ios = UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, -h));
        let top = q_ios * Vector3::y();
        assert!(
            (top - Vector3::x()).norm() < 1e-12,
            "top points to ref x = north"
        );
        let to_enu = UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, h));
        let q = to_enu * q_ios;
        assert!(q.angle() < 1e-12, "device frame = ENU: {q:?}");
    }

    #[test]
    fn platform_from_gravity_and_orientation() {
        // A phone upside down in a pocket (top pointing down): Android gravity reads −9.8 on y,
        // which the axis rule would take for iOS; the orientation settles it.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // Device → ENU: top (y) pointing down = rotation of −90° about x.
        let q = UnitQuaternion::new_unchecked(Quaternion::new(h, -h, 0.0, 0.0));
        let g = [(0.0, Vector3::new(0.0, -9.8, 0.0))];
        let o = [(0.0, q)];
        assert_eq!(
            decide_platform(None, false, false, &g, &o, &g),
            Some(Platform::Android)
        );
        let g_ios = [(0.0, Vector3::new(0.0, 9.8, 0.0))];
        assert_eq!(
            decide_platform(None, false, false, &g_ios, &o, &g_ios),
            Some(Platform::Ios)
        );
        assert_eq!(
            decide_platform(None, false, false, &g, &[], &g),
            Some(Platform::Ios),
            "the axis rule alone gets this pose wrong"
        );
    }
}
