//! Google GnssLogger `.txt`: comma-separated records of several kinds in one file.
//! May import: `engine` and `io`.
//!
//! `# ` header lines declare the columns of each kind (`# Accel,utcTimeMillis,elapsedRealtimeNanos,
//! AccelXMps2,…`); data lines start with the kind (`Accel,…`). Columns are found by these
//! declared names; a kind used without a declaration gets the layout of GnssLogger v3.
//!
//! Read: `Accel`, `Gyro`, `Mag` (calibrated), `UncalAccel`, `UncalGyro`, `UncalMag` (used, as
//! value − bias/drift, only for a sensor whose calibrated record is absent from the whole file),
//! `OrientationDeg` and `Fix`. Ignored: `Raw`, `Status`, `Nav`, `NMEA`, `Agc` and anything else.
//!
//! One clock per log: UTC Unix milliseconds (`utcTimeMillis` on sensor records, `UnixTimeMillis`
//! or the older `(UTC)TimeInMs` on fixes) become seconds.
//!
//! Fixes: when several providers are logged (`GPS`, `FLP`, `NLP`…), only the best one present
//! is kept, in the order GPS, fused (FLP), network (NLP), other; a fix without a positive
//! accuracy is skipped.
//!
//! `OrientationDeg` holds `SensorManager.getOrientation` angles in degrees: yaw (azimuth,
//! clockwise from magnetic north), pitch and roll. See [`orientation_quaternion`].

use super::common::{add_warnings, not_a_number, set_records, warn_count, Fields, Warnings};
use super::{file_error, number, Format, Log, Platform, Streams};
use crate::engine::types::GnssFix;
use crate::io::lines::each_line;
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::collections::HashMap;
use std::io::BufRead;

/// The record kinds we read.
const KINDS: [&str; 8] = [
    "Accel",
    "Gyro",
    "Mag",
    "UncalAccel",
    "UncalGyro",
    "UncalMag",
    "OrientationDeg",
    "Fix",
];

/// Kinds that, declared in a header line, mark a GnssLogger file.
const DECLARED: [&str; 13] = [
    "Raw",
    "Fix",
    "Status",
    "Nav",
    "NMEA",
    "Agc",
    "Accel",
    "Gyro",
    "Mag",
    "UncalAccel",
    "UncalGyro",
    "UncalMag",
    "OrientationDeg",
];

/// Whether the first bytes of a file look like a GnssLogger log: a `# Kind,…` declaration of
/// one of GnssLogger's record kinds.
pub fn looks_like(head: &str) -> bool {
    head.lines().any(|l| {
        let Some(rest) = l.trim_start_matches('\u{feff}').strip_prefix('#') else {
            return false;
        };
        let rest = rest.trim_start();
        DECLARED
            .iter()
            .any(|k| rest.strip_prefix(k).is_some_and(|r| r.starts_with(',')))
    })
}

/// The layout GnssLogger v3 writes, for a kind used without a declaration (column names after
/// the kind).
fn default_columns(kind: &str) -> &'static [&'static str] {
    match kind {
        "Accel" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "AccelXMps2",
            "AccelYMps2",
            "AccelZMps2",
        ],
        "Gyro" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "GyroXRadPerSec",
            "GyroYRadPerSec",
            "GyroZRadPerSec",
        ],
        "Mag" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "MagXMicroT",
            "MagYMicroT",
            "MagZMicroT",
        ],
        "UncalAccel" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "UncalAccelXMps2",
            "UncalAccelYMps2",
            "UncalAccelZMps2",
            "BiasXMps2",
            "BiasYMps2",
            "BiasZMps2",
        ],
        "UncalGyro" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "UncalGyroXRadPerSec",
            "UncalGyroYRadPerSec",
            "UncalGyroZRadPerSec",
            "DriftXRadPerSec",
            "DriftYRadPerSec",
            "DriftZRadPerSec",
        ],
        "UncalMag" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "UncalMagXMicroT",
            "UncalMagYMicroT",
            "UncalMagZMicroT",
            "BiasXMicroT",
            "BiasYMicroT",
            "BiasZMicroT",
        ],
        "OrientationDeg" => &[
            "utcTimeMillis",
            "elapsedRealtimeNanos",
            "yawDeg",
            "rollDeg",
            "pitchDeg",
        ],
        _ => &[
            "Provider",
            "LatitudeDegrees",
            "LongitudeDegrees",
            "AltitudeMeters",
            "SpeedMps",
            "AccuracyMeters",
            "BearingDegrees",
            "UnixTimeMillis",
            "SpeedAccuracyMps",
            "BearingAccuracyDegrees",
            "elapsedRealtimeNanos",
            "VerticalAccuracyMeters",
        ],
    }
}

/// Where the values of one kind are on a data line (indices count the kind as field 0).
#[derive(Debug, Clone)]
enum Layout {
    Vector {
        t: usize,
        v: [usize; 3],
        bias: Option<[usize; 3]>,
    },
    Orientation {
        t: usize,
        yaw: usize,
        pitch: usize,
        roll: usize,
    },
    Fix(FixColumns),
}

/// Where the values of a `Fix` are on a data line.
#[derive(Debug, Clone, Copy)]
struct FixColumns {
    t: usize,
    provider: Option<usize>,
    lat: usize,
    lon: usize,
    acc: usize,
    alt: Option<usize>,
    speed: Option<usize>,
    bearing: Option<usize>,
}

/// The layout of a kind from its column names (after the kind); names the first missing one.
fn layout(kind: &str, columns: &[String]) -> Result<Layout, String> {
    let find = |names: &[&str]| {
        names.iter().find_map(|n| {
            columns
                .iter()
                .position(|c| c.eq_ignore_ascii_case(n))
                .map(|i| i + 1)
        })
    };
    let need = |names: &[&str]| find(names).ok_or_else(|| format!("column `{}` missing", names[0]));
    let time = [
        "utcTimeMillis",
        "UnixTimeMillis",
        "(UTC)TimeInMs",
        "TimeInMs",
    ];
    let vector = |value: &str, bias: Option<&str>| -> Result<Layout, String> {
        let axis = |pattern: &str, a: &str| pattern.replace('#', a);
        let v = [
            need(&[&axis(value, "X")])?,
            need(&[&axis(value, "Y")])?,
            need(&[&axis(value, "Z")])?,
        ];
        let bias = match bias {
            Some(b) => match (
                find(&[&axis(b, "X")]),
                find(&[&axis(b, "Y")]),
                find(&[&axis(b, "Z")]),
            ) {
                (Some(x), Some(y), Some(z)) => Some([x, y, z]),
                _ => None,
            },
            None => None,
        };
        Ok(Layout::Vector {
            t: need(&time)?,
            v,
            bias,
        })
    };
    match kind {
        "Accel" => vector("Accel#Mps2", None),
        "Gyro" => vector("Gyro#RadPerSec", None),
        "Mag" => vector("Mag#MicroT", None),
        "UncalAccel" => vector("UncalAccel#Mps2", Some("Bias#Mps2")),
        "UncalGyro" => vector("UncalGyro#RadPerSec", Some("Drift#RadPerSec")),
        "UncalMag" => vector("UncalMag#MicroT", Some("Bias#MicroT")),
        "OrientationDeg" => Ok(Layout::Orientation {
            t: need(&time)?,
            yaw: need(&["yawDeg", "azimuthDeg"])?,
            pitch: need(&["pitchDeg"])?,
            roll: need(&["rollDeg"])?,
        }),
        _ => Ok(Layout::Fix(FixColumns {
            t: need(&[
                "UnixTimeMillis",
                "(UTC)TimeInMs",
                "TimeInMs",
                "utcTimeMillis",
            ])?,
            provider: find(&["Provider"]),
            lat: need(&["LatitudeDegrees", "Latitude"])?,
            lon: need(&["LongitudeDegrees", "Longitude"])?,
            acc: need(&["AccuracyMeters", "Accuracy"])?,
            alt: find(&["AltitudeMeters", "Altitude"]),
            speed: find(&["SpeedMps", "Speed"]),
            bearing: find(&["BearingDegrees", "Bearing"]),
        })),
    }
}

/// Unix milliseconds as text → seconds (integers split before converting).
fn ms_to_s(s: &str) -> Option<f64> {
    let t = s.trim();
    if let Ok(ms) = t.parse::<i64>() {
        return Some(ms.div_euclid(1000) as f64 + ms.rem_euclid(1000) as f64 * 1e-3);
    }
    number(t).map(|v| v * 1e-3)
}

/// The device → ENU quaternion of Android `SensorManager.getOrientation` angles (radians).
///
/// `getOrientation` reads the rotation matrix `R` (device → world, world = East-North-Up) as
/// `azimuth = atan2(R01, R11)`, `pitch = asin(−R21)`, `roll = atan2(−R20, R22)`. Multiplying out
/// `Rz(α)·Rx(β)·Ry(γ)` gives `R01 = −sin α cos β`, `R11 = cos α cos β`, `R21 = sin β`,
/// `R20 = −cos β sin γ`, `R22 = cos β cos γ`, so the angles are `(−α, −β, γ)`: the rotation is
/// `R = Rz(−azimuth) · Rx(−pitch) · Ry(roll)`. A phone face up with its top to the north is the
/// identity; top to the east is azimuth +90°; top tilted down is positive pitch.
pub fn orientation_quaternion(azimuth: f64, pitch: f64, roll: f64) -> UnitQuaternion<f64> {
    let (sa, ca) = libm::sincos(-azimuth / 2.0);
    let (sp, cp) = libm::sincos(-pitch / 2.0);
    let (sr, cr) = libm::sincos(roll / 2.0);
    let qz = Quaternion::new(ca, 0.0, 0.0, sa);
    let qx = Quaternion::new(cp, sp, 0.0, 0.0);
    let qy = Quaternion::new(cr, 0.0, sr, 0.0);
    UnitQuaternion::from_quaternion(qz * qx * qy)
}

/// Provider preference: lower is better.
fn provider_rank(p: &str) -> u8 {
    match p.trim().to_ascii_lowercase().as_str() {
        "gps" => 0,
        "flp" | "fused" => 1,
        "nlp" | "network" => 2,
        _ => 3,
    }
}

/// What the records of a log hold, as they are read.
#[derive(Default)]
struct Collected {
    vectors: HashMap<&'static str, Vec<(f64, Vector3<f64>)>>,
    orientation: Vec<(f64, UnitQuaternion<f64>)>,
    /// Fixes with their provider's rank ([`provider_rank`]).
    fixes: Vec<(u8, GnssFix)>,
    warnings: Warnings,
    /// Fixes without a positive accuracy.
    invalid_fixes: u64,
}

/// Reads a GnssLogger log (see the module documentation).
pub fn read(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let mut layouts: HashMap<&'static str, Result<Layout, String>> = HashMap::new();
    let mut c = Collected::default();
    each_line(r, label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return c.warnings.push(e),
        };
        if let Some(decl) = line.strip_prefix('#') {
            return declare(&mut layouts, decl, label, n, &mut c.warnings);
        }
        let f = Fields {
            fields: line.split(',').map(str::trim).collect(),
            file: label,
            line: n,
        };
        let Some(&kind) = KINDS.iter().find(|k| **k == f.fields[0]) else {
            return;
        };
        let l = layouts.entry(kind).or_insert_with(|| {
            let cols: Vec<String> = default_columns(kind)
                .iter()
                .map(|s| s.to_string())
                .collect();
            layout(kind, &cols)
        });
        let Ok(l) = &*l else { return };
        if let Err(e) = c.record(kind, l, &f) {
            c.warnings.push(e);
        }
    })?;
    c.into_log(label)
}

/// Reads a `# Kind,column,…` declaration line (`decl` after the `#`) into `layouts`; one of a
/// kind we read whose columns are unusable is a warning.
fn declare(
    layouts: &mut HashMap<&'static str, Result<Layout, String>>,
    decl: &str,
    label: &str,
    n: u64,
    warnings: &mut Warnings,
) {
    let fields: Vec<String> = decl.split(',').map(|s| s.trim().to_string()).collect();
    if fields.len() < 2 {
        return;
    }
    if let Some(&kind) = KINDS.iter().find(|k| **k == fields[0]) {
        let l = layout(kind, &fields[1..]);
        if let Err(m) = &l {
            warnings.push(file_error(
                label,
                n,
                format!("`{kind}` declaration unusable: {m}; its records are skipped"),
            ));
        }
        layouts.insert(kind, l);
    }
}

/// Field `i` of a line as a number, `None` when absent, empty or not a number.
fn optional(f: &Fields, i: Option<usize>) -> Option<f64> {
    i.and_then(|i| f.fields.get(i)).and_then(|s| number(s))
}

/// Field `i` of a line as a time: Unix milliseconds → s.
fn time(f: &Fields, i: usize) -> Result<f64, ParseError> {
    let s = f
        .fields
        .get(i)
        .ok_or_else(|| f.error(i + 1, "time", "missing"))?;
    ms_to_s(s).ok_or_else(|| f.error(i + 1, "time", not_a_number(s)))
}

impl Collected {
    /// Reads one data line of `kind`, whose values are placed as `layout` says.
    fn record(
        &mut self,
        kind: &'static str,
        layout: &Layout,
        f: &Fields,
    ) -> Result<(), ParseError> {
        match layout {
            Layout::Vector { t, v, bias } => {
                let t = time(f, *t)?;
                let mut x = Vector3::new(f.num(v[0], "x")?, f.num(v[1], "y")?, f.num(v[2], "z")?);
                if let Some(b) = bias {
                    // A bias left empty means none was estimated.
                    x -= Vector3::new(
                        optional(f, Some(b[0])).unwrap_or(0.0),
                        optional(f, Some(b[1])).unwrap_or(0.0),
                        optional(f, Some(b[2])).unwrap_or(0.0),
                    );
                }
                self.vectors.entry(kind).or_default().push((t, x));
            }
            Layout::Orientation {
                t,
                yaw,
                pitch,
                roll,
            } => {
                let t = time(f, *t)?;
                let d = std::f64::consts::PI / 180.0;
                let q = orientation_quaternion(
                    f.num(*yaw, "yawDeg")? * d,
                    f.num(*pitch, "pitchDeg")? * d,
                    f.num(*roll, "rollDeg")? * d,
                );
                self.orientation.push((t, q));
            }
            Layout::Fix(c) => self.fix(c, f)?,
        }
        Ok(())
    }

    /// Reads a `Fix` line; one without a positive accuracy is counted.
    fn fix(&mut self, c: &FixColumns, f: &Fields) -> Result<(), ParseError> {
        let FixColumns {
            t,
            provider,
            lat,
            lon,
            acc,
            alt,
            speed,
            bearing,
        } = *c;
        let t = time(f, t)?;
        let acc_m = match f.fields.get(acc).map(|s| s.trim()) {
            None | Some("") => None,
            Some(_) => Some(f.num(acc, "Accuracy")?),
        };
        let Some(acc_m) = acc_m.filter(|a| *a > 0.0) else {
            self.invalid_fixes += 1;
            return Ok(());
        };
        let fix = GnssFix {
            t,
            lat_deg: f.num(lat, "Latitude")?,
            lon_deg: f.num(lon, "Longitude")?,
            h_accuracy_m: acc_m,
            altitude_m: optional(f, alt),
            speed_mps: optional(f, speed).filter(|v| *v >= 0.0),
            bearing_deg: optional(f, bearing).filter(|v| *v >= 0.0),
        };
        fix.check()
            .map_err(|e| f.error(lat + 1, "Latitude", format!("invalid fix: {e}")))?;
        let rank = provider
            .and_then(|p| f.fields.get(p))
            .map_or(3, |p| provider_rank(p));
        self.fixes.push((rank, fix));
        Ok(())
    }

    /// The log: calibrated sensors (uncalibrated ones in their absence) and the fixes of the
    /// best provider.
    fn into_log(mut self, label: &str) -> Result<Log, ParseError> {
        let mut take = |calibrated: &str, uncal: &str| -> Vec<(f64, Vector3<f64>)> {
            match self.vectors.remove(calibrated) {
                Some(v) if !v.is_empty() => v,
                _ => self.vectors.remove(uncal).unwrap_or_default(),
            }
        };
        let mut s = Streams {
            accel: take("Accel", "UncalAccel"),
            gyro: take("Gyro", "UncalGyro"),
            mag: take("Mag", "UncalMag"),
            orientation: self.orientation,
            fixes: Vec::new(),
            pressure: Vec::new(),
        };
        if let Some(best) = self.fixes.iter().map(|(r, _)| *r).min() {
            s.fixes = self
                .fixes
                .into_iter()
                .filter(|(r, _)| *r == best)
                .map(|(_, f)| f)
                .collect();
        }
        if s.accel.is_empty() {
            return Err(no_accel(&self.warnings, label));
        }
        let mut log = Log::new(label, Format::GnssLogger);
        log.platform = Some(Platform::Android);
        add_warnings(&mut log, self.warnings);
        let invalid = self.invalid_fixes;
        warn_count(
            &mut log,
            invalid,
            file_error(
                label,
                0,
                format!("{invalid} fix(es) without a positive accuracy, skipped"),
            ),
        );
        set_records(&mut log, s, label);
        Ok(log)
    }
}

/// The error of a log without accelerometer samples: the first problem with a record, when
/// there was one.
fn no_accel(warnings: &Warnings, label: &str) -> ParseError {
    warnings
        .find(|e| e.line > 0 && e.column.is_some())
        .cloned()
        .map_or_else(
            || {
                file_error(
                    label,
                    0,
                    "no Accel or UncalAccel records: nothing to track (was the accelerometer \
                     logged?)",
                )
            },
            |e| ParseError {
                message: format!(
                    "no readable accelerometer record; first problem: {}",
                    e.message
                ),
                ..e
            },
        )
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    /// `SensorManager.getOrientation` as Android implements it, on a device → ENU rotation.
    fn get_orientation(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
        let r = q.to_rotation_matrix();
        let r = r.matrix();
        (
            r[(0, 1)].atan2(r[(1, 1)]),
            (-r[(2, 1)]).asin(),
            (-r[(2, 0)]).atan2(r[(2, 2)]),
        )
    }

    #[test]
    fn orientation_matches_get_orientation() {
        // A deterministic spread of rotations (pitch within ±90°, where getOrientation is unique).
        let mut seed = 0x9e3779b97f4a7c15u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..500 {
            let (a, p, r) = (
                (rnd() - 0.5) * 2.0 * std::f64::consts::PI,
                (rnd() - 0.5) * 0.98 * std::f64::consts::PI,
                (rnd() - 0.5) * 2.0 * std::f64::consts::PI,
            );
            let q = orientation_quaternion(a, p, r);
            let (a2, p2, r2) = get_orientation(&q);
            let wrap = |x: f64| {
                (x + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                    - std::f64::consts::PI
            };
            assert!(wrap(a2 - a).abs() < 1e-9, "azimuth {a} -> {a2}");
            assert!((p2 - p).abs() < 1e-9, "pitch {p} -> {p2}");
            assert!(wrap(r2 - r).abs() < 1e-9, "roll {r} -> {r2}");
        }
    }

    #[test]
    fn orientation_poses() {
        let d = std::f64::consts::PI / 180.0;
        // Face up, top to the north: identity.
        assert!(orientation_quaternion(0.0, 0.0, 0.0).angle() < 1e-12);
        // Face up, top to the east: azimuth 90°, the top (device y) points east.
        let q = orientation_quaternion(90.0 * d, 0.0, 0.0);
        assert!((q * Vector3::y() - Vector3::x()).norm() < 1e-12);
        assert!((q * Vector3::z() - Vector3::z()).norm() < 1e-12);
        // Top tilted towards the ground: positive pitch.
        let q = orientation_quaternion(0.0, 30.0 * d, 0.0);
        assert!((q * Vector3::y()).z < -0.49);
    }

    #[test]
    fn sniffing() {
        assert!(looks_like(
            "# \n# Header Description:\n#\n# Fix,Provider,LatitudeDegrees\n"
        ));
        assert!(looks_like("#Raw,utcTimeMillis,TimeNanos\n"));
        assert!(!looks_like("Fix,gps,1,2\n"));
        assert!(!looks_like("# pdr-log 1\n"));
    }
}
