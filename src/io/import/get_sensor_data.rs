//! GetSensorData (the Android app of the IPIN competitions) `.txt`: semicolon-separated records,
//! comment lines starting with `%`. May import: `engine` and `io`.
//!
//! Read:
//! - `ACCE;AppTs;SensorTs;Acc_X;Acc_Y;Acc_Z;Accuracy` (m/s², gravity included, Android axes),
//!   `GYRO;…` (rad/s), `MAGN;…` (µT; the header comment shows a stray `;;`, data lines have
//!   three values);
//! - `AHRS;AppTs;SensorTs;PitchX(deg);RollY(deg);YawZ(deg);Quat(2);Quat(3);Quat(4);Accuracy`:
//!   the rotation vector x, y, z of Android's `TYPE_ROTATION_VECTOR` (device → ENU, w implied)
//!   is the orientation; the angles are not used. Lines with four quaternion values right after
//!   the timestamps (`x;y;z;w`, an older variant) are read too;
//! - `GNSS;AppTs;SensorTs;Latit;Long;Altitude;Bearing;Accuracy;Speed;SatInView;SatInUse`: each fix
//!   may be written twice; repeats of the same (SensorTs, latitude, longitude) are dropped;
//! - `PRES;AppTs;SensorTs;Pres(mbar);Accuracy`: the barometer (1 mbar = 1 hPa), one
//!   [`PressureSample`](crate::engine::PressureSample) per line, placed on the app clock as the
//!   inertial sensors are (below); a reading outside the engine's range is skipped with a
//!   warning;
//! - `POSI;Timestamp;Counter;Latitude;Longitude;floorID;buildingID`: ground-truth landmarks,
//!   turned into [`Waypoint`]s in metres east/north of the first `POSI` (WGS84 → local ENU
//!   tangent plane), each keeping its floor ID (an integer; a landmark whose floor field is
//!   missing or not an integer has no floor, with a warning when the field is there but bad).
//!   The building is not kept.
//!
//! Everything else (`WIFI`, `BLE4`, `LIGH`, `SOUN`, …) is ignored.
//!
//! # Date
//! The header's `% Date of creation: Wed Jun 14 10:00:58 GMT+02:00 2023` (Java's
//! `Date.toString`, see [`super::date::java_date`]) is the log's [`Log::date_unix_s`]. Without
//! it, a `GNSS` line whose `SensorTimeStamp` is Unix time (the fix's own time, as the app
//! writes it) gives the date as that time minus the line's `AppTimestamp`.
//!
//! # Clock
//! The log's clock is `AppTimestamp` (s since the app started; `POSI` and `GNSS` use it). It is
//! stamped when the app reads a sample, so it carries delivery jitter; `SensorTimestamp` is
//! stamped by the sensor and spaces samples accurately. Each sensor (ACCE, GYRO, MAGN, AHRS,
//! PRES) is therefore placed on the app clock by one constant offset: `t = SensorTs + offset`,
//! with `offset` the smallest `AppTs − SensorTs` of that sensor among the samples within
//! [`WINDOW_S`] below the median difference (the least-delayed delivery; the window keeps a
//! sample with a corrupt SensorTs from setting it). Samples whose difference is more than
//! [`OUTLIER_S`] from the median are skipped as corrupt. When the differences themselves spread
//! over more than [`OUTLIER_S`] (a sensor clock that does not advance with the app clock), that
//! sensor falls back to `AppTs`, with a warning.

use super::common::{
    add_warnings, drop_non_finite, pressure, rotation_vector, warn_count, Fields, Warnings,
};
use super::{file_error, number, Format, Log, Platform, Streams, Waypoint};
use crate::engine::fusion::declination::is_unix_time_s;
use crate::engine::geo::LocalFrame;
use crate::engine::types::GnssFix;
use crate::io::lines::each_line;
use crate::io::ParseError;
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::HashSet;
use std::io::BufRead;

/// Width of the window below the median `AppTs − SensorTs` searched for the offset, s.
pub const WINDOW_S: f64 = 1.0;

/// A sample whose `AppTs − SensorTs` is further than this from the median is skipped, s.
pub const OUTLIER_S: f64 = 5.0;

const RECORDS: [&str; 7] = ["ACCE", "GYRO", "MAGN", "AHRS", "GNSS", "POSI", "WIFI"];

/// Whether the first bytes of a file look like a GetSensorData log: a data line of one of its
/// records, or a `%` comment quoting one or naming the app.
pub fn looks_like(head: &str) -> bool {
    head.lines().any(|l| {
        let l = l.trim_start_matches('\u{feff}');
        if l.starts_with('%') {
            return l.contains("GetSensorData") || l.contains("'ACCE;");
        }
        RECORDS
            .iter()
            .any(|r| l.strip_prefix(r).is_some_and(|rest| rest.starts_with(';')))
    })
}

/// Samples of one inertial sensor on its two clocks: (AppTs, SensorTs, value).
type Dual<T> = Vec<(f64, f64, T)>;

/// What mapping one sensor onto the app clock did.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mapping {
    /// `t = SensorTs + offset`; the count of outliers skipped.
    Offset(f64, u64),
    /// SensorTs unusable: AppTs used.
    AppClock,
}

/// Places one sensor's samples on the app clock (see the module documentation).
fn to_app_clock<T: Copy>(samples: &Dual<T>) -> (Vec<(f64, T)>, Mapping) {
    if samples.is_empty() {
        return (Vec::new(), Mapping::Offset(0.0, 0));
    }
    let mut d: Vec<f64> = samples.iter().map(|(a, s, _)| a - s).collect();
    crate::engine::sort::sort_by(&mut d, f64::total_cmp);
    let median = d[d.len() / 2];
    let q = |p: f64| d[((d.len() - 1) as f64 * p) as usize];
    if !(q(0.95) - q(0.05) <= OUTLIER_S) {
        return (
            samples.iter().map(|&(a, _, v)| (a, v)).collect(),
            Mapping::AppClock,
        );
    }
    let offset = d
        .iter()
        .copied()
        .find(|&x| x >= median - WINDOW_S)
        .unwrap_or(median);
    let mut out = Vec::with_capacity(samples.len());
    let mut outliers = 0;
    for &(a, s, v) in samples {
        if ((a - s) - median).abs() > OUTLIER_S {
            outliers += 1;
        } else {
            out.push((s + offset, v));
        }
    }
    (out, Mapping::Offset(offset, outliers))
}

/// Reads a GetSensorData log (see the module documentation).
pub fn read(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let mut lines = Lines::default();
    each_line(r, label, |n, line| match line {
        Ok(line) => lines.line(label, n, line),
        Err(e) => lines.warnings.push(e),
    })?;
    if lines.accel.is_empty() {
        return Err(file_error(
            label,
            0,
            "no readable ACCE records: nothing to track",
        ));
    }
    lines.into_log(label)
}

/// The records of a log as read, each sensor still on its two clocks.
#[derive(Default)]
struct Lines {
    accel: Dual<Vector3<f64>>,
    gyro: Dual<Vector3<f64>>,
    mag: Dual<Vector3<f64>>,
    ahrs: Dual<UnitQuaternion<f64>>,
    pres: Dual<f64>,
    fixes: Vec<GnssFix>,
    /// (SensorTs, latitude, longitude) of the fixes kept, to drop repeats.
    seen_fixes: HashSet<[u64; 3]>,
    /// Landmarks: (Timestamp, latitude °, longitude °, floor).
    posi: Vec<(f64, f64, f64, Option<i32>)>,
    warnings: Warnings,
    /// The header's date of creation, Unix s.
    created: Option<f64>,
    /// The date given by the first fix on Unix time, Unix s.
    fix_date: Option<f64>,
}

/// The (AppTimestamp, SensorTimestamp) of a sensor record.
fn clocks(f: &Fields) -> Result<(f64, f64), ParseError> {
    Ok((f.num(1, "AppTimestamp")?, f.num(2, "SensorTimestamp")?))
}

impl Lines {
    /// Reads line `n`: a comment (which may hold the date), or a record; a bad record is a
    /// warning.
    fn line(&mut self, label: &str, n: u64, line: &str) {
        if line.starts_with('%') || line.trim().is_empty() {
            if let Some(d) = line.split_once("Date of creation:") {
                self.created = self.created.or_else(|| super::date::java_date(d.1));
            }
            return;
        }
        let mut f: Vec<&str> = line.split(';').map(str::trim).collect();
        while f.len() > 1 && f.last() == Some(&"") {
            f.pop();
        }
        let f = Fields {
            fields: f,
            file: label,
            line: n,
        };
        let res = match f.fields[0] {
            "POSI" => self.posi(&f),
            "PRES" => self.pres(&f),
            "GNSS" => self.gnss(&f),
            "AHRS" => self.ahrs(&f),
            "ACCE" | "GYRO" | "MAGN" => self.vector(&f),
            _ => Ok(()),
        };
        if let Err(e) = res {
            self.warnings.push(e);
        }
    }

    fn posi(&mut self, f: &Fields) -> Result<(), ParseError> {
        let t = f.num(1, "Timestamp")?;
        let (lat, lon) = (f.num(3, "Latitude")?, f.num(4, "Longitude")?);
        if lat.abs() > 90.0 || lon.abs() > 180.0 {
            return Err(f.error(4, "Latitude", "out of range"));
        }
        // The floor ID is an integer (0, −1, 2, …); written `1.0` by some tools.
        let floor = match f.fields.get(5).filter(|s| !s.is_empty()) {
            None => None,
            Some(s) => match number(s).filter(|v| v.fract() == 0.0 && v.abs() < 1e6) {
                Some(v) => Some(v as i32),
                None => {
                    self.warnings.push(f.error(
                        6,
                        "floorID",
                        format!("{}: landmark kept without a floor", not_an_integer(s)),
                    ));
                    None
                }
            },
        };
        self.posi.push((t, lat, lon, floor));
        Ok(())
    }

    fn pres(&mut self, f: &Fields) -> Result<(), ParseError> {
        let (app, sensor) = clocks(f)?;
        let hpa = f.num(3, "Pres")?;
        // Checked here (range) and again on the app clock (time).
        pressure(app, hpa).map_err(|m| f.error(4, "Pres", m))?;
        self.pres.push((app, sensor, hpa));
        Ok(())
    }

    fn gnss(&mut self, f: &Fields) -> Result<(), ParseError> {
        let (app, sensor) = clocks(f)?;
        let fix = GnssFix {
            t: app,
            lat_deg: f.num(3, "Latit")?,
            lon_deg: f.num(4, "Long")?,
            altitude_m: Some(f.num(5, "Altitude")?),
            bearing_deg: Some(f.num(6, "Bearing")?).filter(|b| *b >= 0.0),
            h_accuracy_m: f.num(7, "Accuracy")?,
            speed_mps: Some(f.num(8, "Speed")?).filter(|v| *v >= 0.0),
        };
        fix.check()
            .map_err(|e| f.error(4, "Latit", format!("invalid fix: {e}")))?;
        let key = [
            sensor.to_bits(),
            fix.lat_deg.to_bits(),
            fix.lon_deg.to_bits(),
        ];
        if self.fix_date.is_none() && is_unix_time_s(sensor) {
            self.fix_date = Some(sensor - app);
        }
        // The app writes most fixes twice; a repeat is expected, not a problem.
        if self.seen_fixes.insert(key) {
            self.fixes.push(fix);
        }
        Ok(())
    }

    fn ahrs(&mut self, f: &Fields) -> Result<(), ParseError> {
        let (app, sensor) = clocks(f)?;
        let len = f.fields.len();
        let (from, w) = if len >= 10 {
            (6, None)
        } else if (7..=9).contains(&len) {
            (3, Some(f.num(6, "w")?))
        } else {
            return Err(file_error(
                f.file,
                f.line,
                format!("an AHRS record has 10 fields, found {len}"),
            ));
        };
        let (x, y, z) = (
            f.num(from, "Quat(2)")?,
            f.num(from + 1, "Quat(3)")?,
            f.num(from + 2, "Quat(4)")?,
        );
        let q = rotation_vector(x, y, z, w)
            .ok_or_else(|| f.error(from + 1, "Quat(2)", "not a rotation vector (norm > 1)"))?;
        self.ahrs.push((app, sensor, q));
        Ok(())
    }

    /// An `ACCE`, `GYRO` or `MAGN` record.
    fn vector(&mut self, f: &Fields) -> Result<(), ParseError> {
        let (app, sensor) = clocks(f)?;
        let (names, samples) = match f.fields[0] {
            "ACCE" => (["Acc_X", "Acc_Y", "Acc_Z"], &mut self.accel),
            "GYRO" => (["Gyr_X", "Gyr_Y", "Gyr_Z"], &mut self.gyro),
            _ => (["Mag_X", "Mag_Y", "Mag_Z"], &mut self.mag),
        };
        let v = Vector3::new(
            f.num(3, names[0])?,
            f.num(4, names[1])?,
            f.num(5, names[2])?,
        );
        samples.push((app, sensor, v));
        Ok(())
    }

    /// The log: every sensor on the app clock, the landmarks as waypoints.
    fn into_log(mut self, label: &str) -> Result<Log, ParseError> {
        let mut log = Log::new(label, Format::GetSensorData);
        log.platform = Some(Platform::Android);
        let mut s = Streams::default();
        let warnings = &mut self.warnings;
        s.accel = on_app_clock(&self.accel, "ACCE", label, warnings);
        s.gyro = on_app_clock(&self.gyro, "GYRO", label, warnings);
        s.mag = on_app_clock(&self.mag, "MAGN", label, warnings);
        s.orientation = on_app_clock(&self.ahrs, "AHRS", label, warnings);
        // A reading the app clock put out of range is dropped and counted with the non-finite
        // ones.
        s.pressure = on_app_clock(&self.pres, "PRES", label, warnings)
            .into_iter()
            .map(|(t, hpa)| crate::engine::PressureSample { t, hpa })
            .collect();
        s.fixes = self.fixes;
        log.truth.waypoints = waypoints(&self.posi);
        let dropped = drop_non_finite(&mut s);
        if s.accel.is_empty() {
            return Err(file_error(label, 0, "no usable ACCE samples"));
        }
        log.records = s.into_records();
        log.date_unix_s = self.created.or(self.fix_date);
        add_warnings(&mut log, self.warnings);
        warn_count(
            &mut log,
            dropped,
            file_error(
                label,
                0,
                format!("{dropped} sample(s) with a non-finite value, skipped"),
            ),
        );
        Ok(log)
    }
}

/// One sensor's samples on the app clock ([`to_app_clock`]), with a warning when its
/// SensorTimestamp was unusable or some samples were skipped.
fn on_app_clock<T: Copy>(
    samples: &Dual<T>,
    name: &str,
    label: &str,
    warnings: &mut Warnings,
) -> Vec<(f64, T)> {
    let (v, m) = to_app_clock(samples);
    match m {
        Mapping::AppClock => warnings.push(file_error(
            label,
            0,
            format!(
                "{name}: SensorTimestamp does not advance with AppTimestamp; AppTimestamp used"
            ),
        )),
        Mapping::Offset(_, 0) => {}
        Mapping::Offset(_, k) => warnings.push(file_error(
            label,
            0,
            format!(
                "{name}: {k} sample(s) with a SensorTimestamp more than {OUTLIER_S} s off, skipped"
            ),
        )),
    }
    v
}

/// The landmarks as waypoints in metres east/north of the first, sorted by time.
fn waypoints(posi: &[(f64, f64, f64, Option<i32>)]) -> Vec<Waypoint> {
    let Some(&(_, lat0, lon0, _)) = posi.first() else {
        return Vec::new();
    };
    let frame = LocalFrame::new(lat0, lon0, 0.0);
    let mut w: Vec<Waypoint> = posi
        .iter()
        .map(|&(t, lat, lon, floor)| {
            let e = frame.to_enu(lat, lon, 0.0);
            Waypoint {
                t,
                x_m: e[0],
                y_m: e[1],
                geo: Some((lat, lon)),
                floor,
                height_m: None,
            }
        })
        .filter(|w| w.t.is_finite() && w.x_m.is_finite() && w.y_m.is_finite())
        .collect();
    crate::engine::sort::sort_by(&mut w, |a, b| a.t.total_cmp(&b.t));
    w
}

/// "not an integer: …" with the text cut to a readable length.
fn not_an_integer(s: &str) -> String {
    let s: String = s.trim().chars().take(40).collect();
    format!("not an integer: {s:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sensor_clock_mapped_by_least_delay() {
        // Sensor at 100 Hz from 5000 s since boot; the app reads with 2–12 ms of jitter,
        // starting at app time 1.0.
        let mut samples = Vec::new();
        for k in 0..200 {
            let sensor = 5000.0 + k as f64 * 0.01;
            let delay = 0.002 + ((k * 7) % 11) as f64 * 0.001;
            samples.push((1.0 + k as f64 * 0.01 + delay, sensor, k));
        }
        // One corrupt SensorTimestamp.
        samples.push((1.5, 9999.0, 999));
        let (out, m) = to_app_clock(&samples);
        let Mapping::Offset(offset, outliers) = m else {
            panic!("{m:?}")
        };
        assert_eq!(outliers, 1);
        assert!((offset - (1.002 - 5000.0)).abs() < 1e-9, "{offset}");
        // Spacing comes from the sensor clock: exactly 10 ms.
        for w in out.windows(2) {
            assert!(((w[1].0 - w[0].0) - 0.01).abs() < 1e-9);
        }
    }

    #[test]
    fn sensor_clock_not_advancing_falls_back() {
        let samples: Dual<u8> = (0..100).map(|k| (k as f64 * 0.1, 0.0, 0)).collect();
        let (out, m) = to_app_clock(&samples);
        assert_eq!(m, Mapping::AppClock);
        assert_eq!(out[99].0, 9.9);
    }

    #[test]
    fn sniffing() {
        assert!(looks_like(
            "% LogFile created by the 'GetSensorData' App for Android.\n"
        ));
        assert!(looks_like("ACCE;0.015;17292.410;-0.61;5.92;7.96;3\n"));
        assert!(!looks_like("Accel,1,2,3\n"));
    }
}
