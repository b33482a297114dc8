//! Sensor Logger (Android and iOS app by Kelvin Choi): a folder or zip of per-sensor CSVs, or
//! the app's JSON export. May import: `engine` and `io`.
//!
//! # Files
//! `Accelerometer.csv` (gravity removed), `Gravity.csv`, `TotalAcceleration.csv` (Android only,
//! gravity included), `Gyroscope.csv`, `Magnetometer.csv`, `Orientation.csv`, `Location.csv`,
//! `Barometer.csv` and `Metadata.csv`. Columns are matched by name (case-insensitive), never by position: the order
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
//!   [`HOLD_S`](crate::engine::orientation::HOLD_S) are dropped and counted.
//! - Units: if the mean norm of gravity (or of the total acceleration when there is no gravity)
//!   is below 3, the acceleration files are in g and are multiplied by
//!   [`G0`](crate::engine::orientation::G0); otherwise m/s².
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
//! - Barometer (`time`, `seconds_elapsed`, `relativeAltitude`, `pressure`): Sensor Logger is an
//!   Expo app, and expo-sensors' `Barometer` reports `pressure` in hPa on both platforms (it
//!   converts Core Motion's kPa); `relativeAltitude` (m, iOS only) is not used. A `pressure`
//!   below [`KPA_BELOW`] is nonetheless taken as kPa and multiplied by 10 (no one walks where
//!   the air is below 200 hPa, about 12 km up; 101.3 kPa read as hPa would pass the engine's
//!   range check and be wrong). A reading outside the engine's range is skipped with a warning.
//! - Location: fixes with a negative `horizontalAccuracy` are invalid and skipped (each counted as
//!   a warning); a negative `speed` or `bearing` is an unknown value.
//!
//! # JSON export
//! An array of objects `{"sensor":"Accelerometer","time":"…","seconds_elapsed":"…","z":"…",…}`
//! whose values are strings (numbers are accepted too). It is read element by element with a
//! streaming deserializer; a file cut short keeps the elements before the cut (with a warning).

mod conventions;
mod folder;
mod json;

pub use conventions::decide_platform;
pub use folder::read_dir;
pub use json::{looks_like_json, read_json};

use super::common::{not_a_number, unit_quaternion, Warnings};
use super::{number, Platform};
use crate::engine::types::{GnssFix, PressureSample};
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// A Sensor Logger `pressure` below this is in kPa (see the module documentation), hPa.
pub const KPA_BELOW: f64 = 200.0;

/// The Sensor Logger files (lower case) whose samples we use.
const FILES: [(&str, Kind); 9] = [
    ("metadata.csv", Kind::Metadata),
    ("totalacceleration.csv", Kind::Total),
    ("accelerometer.csv", Kind::Accel),
    ("gravity.csv", Kind::Gravity),
    ("gyroscope.csv", Kind::Gyro),
    ("magnetometer.csv", Kind::Mag),
    ("orientation.csv", Kind::Orientation),
    ("location.csv", Kind::Location),
    ("barometer.csv", Kind::Barometer),
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
    Barometer,
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
            Kind::Barometer => &["pressure"],
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
    pressure: Vec<PressureSample>,
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
            Kind::Barometer => self.pressure.try_reserve_exact(n),
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
            Kind::Barometer => {
                let raw = get(row, "pressure")?;
                let hpa = if raw.abs() < KPA_BELOW {
                    raw * 10.0
                } else {
                    raw
                };
                let p = super::common::pressure(t, hpa).map_err(|m| row.error("pressure", m))?;
                self.pressure.push(p);
            }
        }
        Ok(())
    }
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
}
