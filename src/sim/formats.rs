//! A simulated walk written in every format the import reads, as the recording app writes it.
//!
//! [`write`] turns a [`Simulation`] into the files an app (or a data set) would have produced for
//! the same walk: file and folder names, header lines, column names and order, units, clocks,
//! sign and quaternion conventions. The readers of [`crate::io::import`] are the specification:
//! every recording written here reads back through [`crate::io::import::import_all`] without a
//! warning, one IMU record per simulated IMU sample, with the values of the simulation to the
//! precision the format writes. The tests in `tests/formats.rs` hold both ends together.
//!
//! # What each format carries
//! | Format | Files | IMU | Orientation | GNSS | Truth |
//! |---|---|---|---|---|---|
//! | Sensor Logger (Android) | folder | total, linear, gravity, gyro, mag | rotation vector | `Location.csv` | – |
//! | Sensor Logger (iOS) | folder | user accel. and gravity in g, iOS sign; gyro, mag | Core Motion attitude | `Location.csv` | – |
//! | Sensor Logger JSON | file | as the folder, without `TotalAcceleration` | as the folder | `Location` | – |
//! | phyphox | folder | accel., gyro, mag | none | `Location.csv` | – |
//! | GnssLogger | file | `Accel`, `Gyro`, `Mag` | `OrientationDeg` | `Fix` | – |
//! | GetSensorData | file | `ACCE`, `GYRO`, `MAGN` | `AHRS` rotation vector | `GNSS` (twice) | `POSI` landmarks |
//! | Oxford Step Counter | folder | accelerometer only | none | none | foot contacts |
//! | Microsoft Indoor 2.0 | file | accel., gyro, mag | rotation vector | none | `TYPE_WAYPOINT` |
//! | x-io Gait-Tracking | file | gyro (deg/s), accel. (g) | none | none | (loop closure, claimed by the reader) |
//! | pdr-log | file | everything, lossless | | | |
//!
//! Where a format has no place for something the simulation has, it is left out: phyphox, Oxford
//! and x-io have no OS orientation (the engine then falls back to Madgwick or the gravity
//! low-pass), Oxford has no gyroscope nor magnetometer, Microsoft Indoor, Oxford and x-io have no
//! GNSS. The x-io reader always claims a loop closure: only a closed walk (the square) makes that
//! claim true. `gap` records and the simulation's per-step truth beyond what the format can hold
//! (lengths, headings) are not written. An IMU sample with a non-finite value, or a fix that
//! fails [`GnssFix::check`], is skipped (the simulator never makes one).
//!
//! # Truth
//! - Oxford `stepcounter.csv`: one row per accelerometer sample, `left` and `right` contact
//!   states. The feet alternate over the true steps; each foot is off the ground (0) during the
//!   swing before its landing, [`SWING_SHARE`] of its stride, and down (1) otherwise, so each true
//!   step is one 0 → 1 change, read at the first sample at or after the true step time.
//! - Microsoft `TYPE_WAYPOINT` and GetSensorData `POSI`: the true position at the start of the
//!   walk, every [`WAYPOINT_INTERVAL_S`] after it, and at the end. Microsoft waypoints are metres
//!   east and north of the start; `POSI` landmarks are WGS84, in the simulation's geodetic frame
//!   when it has GNSS, else around [`GnssSim`]'s default origin.
//!
//! # Clocks
//! Every format keeps the simulation's sample spacing; the origin is the format's own:
//! - Unix time (Sensor Logger ns, GnssLogger and Microsoft ms): the simulation's times when they
//!   already are Unix times (a scenario with [`crate::sim::Scenario::clock_offset_s`] set), else
//!   [`DEFAULT_UNIX_START_S`] plus the simulation time;
//! - time since the start of the recording (phyphox, x-io, GetSensorData's app clock), the start
//!   being the first record (or the start of the true path when that is earlier);
//! - time since boot (Oxford ns; GnssLogger `elapsedRealtimeNanos`, GetSensorData
//!   `SensorTimestamp`), starting at [`BOOT_NS`].
//!
//! [`Recording::clock_offset_s`] says how the reader's clock relates to the simulation's.
//!
//! Output is deterministic: the same simulation gives the same bytes, natively and in wasm.

use super::{GnssSim, Simulation};
use crate::engine::math::OnePole;
use crate::engine::orientation::G0;
use crate::engine::pipeline::Record;
use crate::engine::types::{GnssFix, ImuSample};
use crate::io::import::{Format, Platform};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::fmt::Write as _;

/// The Unix time given to the start of a simulation whose clock is not a Unix time, s
/// (2026-01-01 00:00:00 UTC).
pub const DEFAULT_UNIX_START_S: i64 = 1_767_225_600;

/// Time since boot at the start of the recording, ns (the clocks `elapsedRealtimeNanos` and
/// Android sensor timestamps count from boot).
pub const BOOT_NS: i64 = 263_239_144_000_000;

/// Interval between ground-truth waypoints (Microsoft) and landmarks (GetSensorData), s.
pub const WAYPOINT_INTERVAL_S: f64 = 10.0;

/// Share of a stride (two steps) each foot spends in the air before it lands (Oxford contacts).
pub const SWING_SHARE: f64 = 0.4;

/// A simulated walk written as one app writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// Every file, as (path relative to where the app would put the recording, bytes). Folder
    /// formats put their files in a folder named as the app names the recording.
    pub files: Vec<(String, Vec<u8>)>,
    /// What the reader's clock reads at simulation time 0: a sample at simulation time `t` reads
    /// back at `t + clock_offset_s` (to the format's time precision).
    pub clock_offset_s: f64,
}

/// Whether a format is a folder of files (Sensor Logger CSVs, phyphox, Oxford) rather than one
/// file.
pub fn is_folder(format: Format) -> bool {
    matches!(
        format,
        Format::SensorLogger | Format::Phyphox | Format::OxfordSteps
    )
}

/// Writes a simulated walk as `format` (see the module documentation for what each one
/// carries). `platform` chooses between Sensor Logger's Android and iOS conventions (its CSV
/// folder and JSON export); the other formats come from Android apps or fixed devices and ignore
/// it. Never fails: a walk without records gives files with headers only.
pub fn write(sim: &Simulation, format: Format, platform: Platform) -> Recording {
    let w = Walk::new(sim);
    let unix_offset = if w.unix {
        0.0
    } else {
        DEFAULT_UNIX_START_S as f64
    };
    let relative = -w.start;
    let (files, clock_offset_s) = match format {
        Format::PdrLog => (
            vec![(
                format!("{}.pdrlog", w.name('-', '_', '-')),
                crate::io::pdrlog::to_string(&sim.records).into_bytes(),
            )],
            0.0,
        ),
        Format::SensorLogger => (w.sensor_logger_csv(platform), unix_offset),
        Format::SensorLoggerJson => (w.sensor_logger_json(platform), unix_offset),
        Format::Phyphox => (w.phyphox(), relative),
        Format::GnssLogger => (w.gnss_logger(), unix_offset),
        Format::GetSensorData => (w.get_sensor_data(sim), relative),
        Format::OxfordSteps => (w.oxford(sim), BOOT_NS as f64 * 1e-9 - w.start),
        Format::MsIndoor => (w.ms_indoor(sim), unix_offset),
        Format::XioFoot => (w.xio(), relative),
    };
    Recording {
        files,
        clock_offset_s,
    }
}

// ---------------------------------------------------------------------------------------------
// The walk, its clocks, number formats.
// ---------------------------------------------------------------------------------------------

/// One record worth writing.
#[derive(Clone, Copy)]
enum Item<'a> {
    Imu(&'a ImuSample),
    Fix(&'a GnssFix),
}

/// The records of a simulation with the clocks of the formats.
struct Walk<'a> {
    items: Vec<Item<'a>>,
    /// Simulation time of the start of the recording, s.
    start: f64,
    /// Whether the simulation's clock is a Unix time.
    unix: bool,
    /// Unix time of `start`, ns.
    unix_start_ns: i64,
}

/// Nearest integer, saturating (0 for a non-finite value).
fn round_i64(x: f64) -> i64 {
    if x.is_finite() {
        x.round() as i64
    } else {
        0
    }
}

/// Shortest text that reads back as the same `f64`, as JavaScript prints numbers (`0.5`, `3`,
/// `1.5e-7`, `1e+21`).
fn js(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-6..1e21).contains(&a) {
        let s = format!("{v:e}");
        return match s.split_once('e') {
            Some((m, e)) if !e.starts_with('-') => format!("{m}e+{e}"),
            _ => s,
        };
    }
    format!("{v}")
}

/// The value as a 32-bit float, printed as Java's `Float.toString` does (`9.81`, `1.0`,
/// `1.5E-4`): what Android apps that print sensor values write.
fn java_float(v: f64) -> String {
    let f = v as f32;
    if !f.is_finite() {
        return js(v);
    }
    if f == 0.0 {
        return if f.is_sign_negative() { "-0.0" } else { "0.0" }.to_string();
    }
    if (1e-3..1e7).contains(&f.abs()) {
        let s = format!("{f}");
        return if s.contains('.') { s } else { s + ".0" };
    }
    let s = format!("{f:e}");
    let (m, e) = s.split_once('e').unwrap_or((s.as_str(), "0"));
    if m.contains('.') {
        format!("{m}E{e}")
    } else {
        format!("{m}.0E{e}")
    }
}

/// The value as a 32-bit float widened to a double, printed shortest (a float sensor value that
/// went through JavaScript, as in Sensor Logger on Android).
fn js_float(v: f64) -> String {
    let f = v as f32;
    if f.is_finite() {
        js(f64::from(f))
    } else {
        js(v)
    }
}

/// `v` with `d` decimals.
fn fixed(v: f64, d: usize) -> String {
    format!("{v:.d$}")
}

/// phyphox's number format (Java `DecimalFormat("0.000000000E0")`): `4.376956040E1`.
fn sci9(v: f64) -> String {
    format!("{v:.9E}")
}

/// Seconds given in whole milliseconds, with three decimals.
fn ms_text(ms: i64) -> String {
    let sign = if ms < 0 { "-" } else { "" };
    let a = ms.unsigned_abs();
    format!("{sign}{}.{:03}", a / 1000, a % 1000)
}

/// Calendar date and time of a Unix time (UTC): (year, month, day, hour, minute, second,
/// weekday with 0 = Sunday).
fn civil(unix_s: i64) -> (i64, u32, u32, u32, u32, u32, u32) {
    let days = unix_s.div_euclid(86_400);
    let secs = unix_s.rem_euclid(86_400);
    // Howard Hinnant's days → civil date.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    let weekday = (days + 4).rem_euclid(7) as u32;
    (
        y,
        m,
        d,
        (secs / 3600) as u32,
        (secs / 60 % 60) as u32,
        (secs % 60) as u32,
        weekday,
    )
}

/// Android `SensorManager.getOrientation` of a device → ENU rotation: (azimuth, pitch, roll),
/// rad (see `gnss_logger::orientation_quaternion`, its inverse).
///
/// At pitch ±90° (the phone's top straight up or down, as the simulated phone stands in the
/// pocket while the walker stands still) azimuth and roll turn about the same axis and
/// getOrientation's formulas divide noise by noise; only azimuth ∓ roll is defined there, and it
/// is all put in the azimuth (roll 0), so the angles still describe the rotation.
fn get_orientation(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let r = q.to_rotation_matrix();
    let m = r.matrix();
    let pitch = libm::asin((-m[(2, 1)]).clamp(-1.0, 1.0));
    if libm::hypot(m[(0, 1)], m[(1, 1)]) < 1e-9 {
        // R = Rz(−a)·Rx(∓90°)·Ry(r): R00 = cos(a ∓ r), R02 = ∓sin(a ∓ r).
        let azimuth = if pitch < 0.0 {
            libm::atan2(-m[(0, 2)], m[(0, 0)])
        } else {
            libm::atan2(m[(0, 2)], m[(0, 0)])
        };
        return (azimuth, pitch, 0.0);
    }
    (
        libm::atan2(m[(0, 1)], m[(1, 1)]),
        pitch,
        libm::atan2(-m[(2, 0)], m[(2, 2)]),
    )
}

/// Yaw, pitch and roll as apps that show angles write them (rad): yaw counter-clockwise about
/// z, `R = Rz(yaw)·Rx(pitch)·Ry(roll)`.
fn yaw_pitch_roll(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let (a, p, r) = get_orientation(q);
    (-a, -p, r)
}

/// The quaternion with w ≥ 0 (the same rotation; Android's rotation vector has w = cos(θ/2)).
fn canonical(q: &UnitQuaternion<f64>) -> Quaternion<f64> {
    let q = *q.quaternion();
    if q.w < 0.0 {
        -q
    } else {
        q
    }
}

/// Core Motion's attitude (device → reference frame x magnetic north, y west, z up) of a
/// device → ENU rotation: `Rz(−90°)·q`, the inverse of the iOS reader's `Rz(+90°)`.
fn ios_attitude(q: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, -h)) * q
}

/// Gravity as a device-frame specific force (Android sign, m/s²) for each IMU sample: from the
/// OS attitude when the sample has one (the simulator's attitude is exact in tilt), else from a
/// one-second low-pass of the accelerometer.
fn gravity(imu: &[&ImuSample]) -> Vec<Vector3<f64>> {
    let mut lp = [OnePole::new(1.0); 3];
    let mut last_t: Option<f64> = None;
    imu.iter()
        .map(|s| {
            let dt = last_t.map_or(0.0, |t| (s.t - t).clamp(0.0, 1.0));
            last_t = Some(s.t);
            match s.orientation {
                Some(q) => {
                    let g = q.inverse() * Vector3::new(0.0, 0.0, G0);
                    // The low-pass goes on from the attitude's gravity.
                    for (f, v) in lp.iter_mut().zip(g.iter()) {
                        f.reset();
                        f.update(*v, 0.0);
                    }
                    g
                }
                None => Vector3::from_fn(|k, _| lp[k].update(s.accel[k], dt)),
            }
        })
        .collect()
}

impl<'a> Walk<'a> {
    fn new(sim: &'a Simulation) -> Self {
        let items: Vec<Item<'a>> = sim
            .records
            .iter()
            .filter_map(|r| match r {
                Record::Imu(s) if s.check_finite().is_ok() => Some(Item::Imu(s)),
                Record::Gnss(f) if f.check().is_ok() => Some(Item::Fix(f)),
                _ => None,
            })
            .collect();
        let first = items.first().map(|i| match i {
            Item::Imu(s) => s.t,
            Item::Fix(f) => f.t,
        });
        let path_start = sim
            .truth
            .path
            .first()
            .map(|p| p.0)
            .filter(|t| t.is_finite());
        let start = match (first, path_start) {
            (Some(a), Some(b)) => a.min(b),
            (a, b) => a.or(b).unwrap_or(0.0),
        };
        let unix = start >= 1e9;
        let unix_start_ns = if unix {
            let whole = start.floor();
            (whole as i64)
                .saturating_mul(1_000_000_000)
                .saturating_add(round_i64((start - whole) * 1e9))
        } else {
            DEFAULT_UNIX_START_S
                .saturating_mul(1_000_000_000)
                .saturating_add(round_i64(start * 1e9))
        };
        Walk {
            items,
            start,
            unix,
            unix_start_ns,
        }
    }

    fn imu(&self) -> Vec<&'a ImuSample> {
        self.items
            .iter()
            .filter_map(|i| match i {
                Item::Imu(s) => Some(*s),
                Item::Fix(_) => None,
            })
            .collect()
    }

    fn fixes(&self) -> Vec<&'a GnssFix> {
        self.items
            .iter()
            .filter_map(|i| match i {
                Item::Fix(f) => Some(*f),
                Item::Imu(_) => None,
            })
            .collect()
    }

    /// Seconds since the start of the recording.
    fn rel(&self, t: f64) -> f64 {
        t - self.start
    }

    fn unix_ns(&self, t: f64) -> i64 {
        self.unix_start_ns
            .saturating_add(round_i64(self.rel(t) * 1e9))
    }

    fn unix_ms(&self, t: f64) -> i64 {
        self.unix_ns(t)
            .saturating_add(500_000)
            .div_euclid(1_000_000)
    }

    fn boot_ns(&self, t: f64) -> i64 {
        BOOT_NS.saturating_add(round_i64(self.rel(t) * 1e9))
    }

    /// Whole milliseconds since the start.
    fn rel_ms(&self, t: f64) -> i64 {
        round_i64(self.rel(t) * 1e3)
    }

    /// The start as `YYYY<d>MM<d>DD<s>hh<t>mm<t>ss` (UTC).
    fn name(&self, date: char, sep: char, time: char) -> String {
        let (y, mo, d, h, mi, s, _) = civil(self.unix_start_ns.div_euclid(1_000_000_000));
        format!("{y:04}{date}{mo:02}{date}{d:02}{sep}{h:02}{time}{mi:02}{time}{s:02}")
    }

    /// Mean sampling interval of the IMU, ms (0 with fewer than two samples).
    fn interval_ms(&self, imu: &[&ImuSample]) -> i64 {
        match (imu.first(), imu.last()) {
            (Some(a), Some(b)) if imu.len() > 1 => {
                round_i64((b.t - a.t) / (imu.len() - 1) as f64 * 1e3)
            }
            _ => 0,
        }
    }

    // -----------------------------------------------------------------------------------------
    // Sensor Logger.
    // -----------------------------------------------------------------------------------------

    /// Values of one Sensor Logger sensor for one IMU sample, in the column order of
    /// [`SL_VECTOR`] or [`SL_ORIENTATION`]; `None` when the sample has no such value.
    fn sl_imu(
        &self,
        sensor: &str,
        s: &ImuSample,
        gravity: Vector3<f64>,
        platform: Platform,
    ) -> Option<Vec<String>> {
        let ios = platform == Platform::Ios;
        let num = |v: f64| if ios { js(v) } else { js_float(v) };
        let vector = |v: Vector3<f64>| {
            Some(vec![
                self.unix_ns(s.t).to_string(),
                fixed(self.rel(s.t), 9),
                num(v.z),
                num(v.y),
                num(v.x),
            ])
        };
        // Core Motion: acceleration in g with the opposite sign.
        let to_platform = |v: Vector3<f64>| if ios { -v / G0 } else { v };
        match sensor {
            "TotalAcceleration" => vector(s.accel),
            "Accelerometer" => vector(to_platform(s.accel - gravity)),
            "Gravity" => vector(to_platform(gravity)),
            "Gyroscope" => vector(s.gyro?),
            "Magnetometer" => vector(s.mag?),
            _ => {
                let q = s.orientation?;
                let q = if ios { ios_attitude(&q) } else { q };
                let (yaw, pitch, roll) = yaw_pitch_roll(&q);
                let c = canonical(&q);
                Some(vec![
                    self.unix_ns(s.t).to_string(),
                    fixed(self.rel(s.t), 9),
                    num(c.k),
                    num(c.j),
                    num(c.i),
                    num(c.w),
                    num(roll),
                    num(pitch),
                    num(yaw),
                ])
            }
        }
    }

    /// A fix as Sensor Logger's `Location` columns ([`SL_LOCATION`]); −1 is an unknown speed or
    /// bearing, as Android and Core Location report them.
    fn sl_fix(&self, f: &GnssFix) -> Vec<String> {
        let unknown = |v: Option<f64>| v.map_or("-1".to_string(), js);
        vec![
            self.unix_ns(f.t).to_string(),
            fixed(self.rel(f.t), 9),
            "0".into(),
            "0".into(),
            js_float(1.5 * f.h_accuracy_m),
            js_float(f.h_accuracy_m),
            unknown(f.speed_mps),
            unknown(f.bearing_deg),
            f.altitude_m.map_or(String::new(), js),
            js(f.lon_deg),
            js(f.lat_deg),
        ]
    }

    /// The sensors a Sensor Logger recording holds, in file order.
    fn sl_sensors(&self, imu: &[&ImuSample], platform: Platform, total: bool) -> Vec<&'static str> {
        let mut out = Vec::new();
        if total && platform == Platform::Android {
            out.push("TotalAcceleration");
        }
        out.extend(["Accelerometer", "Gravity"]);
        if imu.iter().any(|s| s.gyro.is_some()) {
            out.push("Gyroscope");
        }
        if imu.iter().any(|s| s.mag.is_some()) {
            out.push("Magnetometer");
        }
        if imu.iter().any(|s| s.orientation.is_some()) {
            out.push("Orientation");
        }
        out
    }

    /// `Metadata.csv` (columns, values).
    fn sl_metadata(
        &self,
        imu: &[&ImuSample],
        platform: Platform,
        sensors: &[&str],
    ) -> (Vec<&'static str>, Vec<String>) {
        let ios = platform == Platform::Ios;
        (
            vec![
                "version",
                "device name",
                "recording epoch time",
                "recording time",
                "recording timezone",
                "platform",
                "appVersion",
                "sensors",
                "sampleRateMs",
                "standardisation",
            ],
            vec![
                "3".into(),
                if ios {
                    "pdr simulated iPhone"
                } else {
                    "pdr simulated Android phone"
                }
                .into(),
                self.unix_start_ns.div_euclid(1_000_000).to_string(),
                self.name('-', '_', '-'),
                "UTC".into(),
                if ios { "ios" } else { "android" }.into(),
                "1.38.0".into(),
                sensors.join("|"),
                self.interval_ms(imu).to_string(),
                "false".into(),
            ],
        )
    }

    /// Sensor Logger's CSV folder: one file per sensor, columns `time` (Unix ns),
    /// `seconds_elapsed`, then the values (`z,y,x`; `qz,qy,qx,qw,roll,pitch,yaw`; the location's
    /// eleven columns). Android: m/s² with gravity in `TotalAcceleration.csv` and `Gravity.csv`,
    /// without in `Accelerometer.csv`; the orientation is the rotation vector. iOS: no total,
    /// user acceleration and gravity in g with Core Motion's sign, the attitude in the
    /// magnetic-north reference frame.
    fn sensor_logger_csv(&self, platform: Platform) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let gravity = gravity(&imu);
        let fixes = self.fixes();
        let dir = self.name('-', '_', '-');
        let mut sensors = self.sl_sensors(&imu, platform, true);
        let mut files = Vec::new();
        for &sensor in &sensors {
            let cols: &[&str] = if sensor == "Orientation" {
                &SL_ORIENTATION
            } else {
                &SL_VECTOR
            };
            let mut text = cols.join(",") + "\n";
            for (s, g) in imu.iter().zip(&gravity) {
                if let Some(v) = self.sl_imu(sensor, s, *g, platform) {
                    text.push_str(&v.join(","));
                    text.push('\n');
                }
            }
            files.push((format!("{dir}/{sensor}.csv"), text.into_bytes()));
        }
        if !fixes.is_empty() {
            let mut text = SL_LOCATION.join(",") + "\n";
            for f in &fixes {
                text.push_str(&self.sl_fix(f).join(","));
                text.push('\n');
            }
            files.push((format!("{dir}/Location.csv"), text.into_bytes()));
            sensors.push("Location");
        }
        let (cols, values) = self.sl_metadata(&imu, platform, &sensors);
        let text = format!("{}\n{}\n", cols.join(","), values.join(","));
        files.push((format!("{dir}/Metadata.csv"), text.into_bytes()));
        files.sort();
        files
    }

    /// Sensor Logger's JSON export: an array with one object per reading, every value a string,
    /// in time order, the metadata first. Written as an app version without the
    /// `TotalAcceleration` sensor (the reader adds `Accelerometer` and `Gravity`).
    fn sensor_logger_json(&self, platform: Platform) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let gravity = gravity(&imu);
        let mut sensors = self.sl_sensors(&imu, platform, false);
        if !self.fixes().is_empty() {
            sensors.push("Location");
        }
        let element = |sensor: &str, cols: &[&str], values: &[String]| {
            let mut e = String::with_capacity(160);
            e.push_str("{\"sensor\":");
            e.push_str(&json_string(sensor));
            for (c, v) in cols.iter().zip(values) {
                let _ = write!(e, ",{}:{}", json_string(c), json_string(v));
            }
            e.push('}');
            e
        };
        let (cols, values) = self.sl_metadata(&imu, platform, &sensors);
        let mut out = String::from("[");
        out.push_str(&element("Metadata", &cols, &values));
        let mut k = 0;
        for item in &self.items {
            match item {
                Item::Imu(s) => {
                    let g = gravity.get(k).copied().unwrap_or_default();
                    k += 1;
                    for &sensor in &sensors {
                        if sensor == "Location" {
                            continue;
                        }
                        let cols: &[&str] = if sensor == "Orientation" {
                            &SL_ORIENTATION
                        } else {
                            &SL_VECTOR
                        };
                        if let Some(v) = self.sl_imu(sensor, s, g, platform) {
                            out.push_str(",\n");
                            out.push_str(&element(sensor, cols, &v));
                        }
                    }
                }
                Item::Fix(f) => {
                    out.push_str(",\n");
                    out.push_str(&element("Location", &SL_LOCATION, &self.sl_fix(f)));
                }
            }
        }
        out.push_str("]\n");
        vec![(
            format!("{}.json", self.name('-', '_', '-')),
            out.into_bytes(),
        )]
    }

    // -----------------------------------------------------------------------------------------
    // phyphox.
    // -----------------------------------------------------------------------------------------

    /// phyphox's CSV export of a multi-sensor experiment: `Accelerometer.csv` ("Acceleration
    /// with g", m/s², Android sign on both platforms), `Gyroscope.csv`, `Magnetometer.csv`,
    /// `Location.csv` and `meta/`; time in seconds since the start; every number in
    /// `0.000000000E0` form. An unknown velocity or direction is left empty (phyphox itself
    /// writes `NaN` there; the reader takes both as unknown, and nothing here writes NaN).
    fn phyphox(&self) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let fixes = self.fixes();
        let dir = format!("Walk {}", self.name('-', ' ', '-'));
        let mut files = Vec::new();
        let mut table = |name: &str,
                         unit: &str,
                         q: &str,
                         abs: &str,
                         get: &dyn Fn(&ImuSample) -> Option<Vector3<f64>>| {
            if !imu.iter().any(|s| get(s).is_some()) {
                return;
            }
            let mut text = format!(
                "\"Time (s)\",\"{q} x ({unit})\",\"{q} y ({unit})\",\"{q} z ({unit})\",\"{abs} ({unit})\"\n"
            );
            for s in &imu {
                if let Some(v) = get(s) {
                    let _ = writeln!(
                        text,
                        "{},{},{},{},{}",
                        sci9(self.rel(s.t)),
                        sci9(v.x),
                        sci9(v.y),
                        sci9(v.z),
                        sci9(v.norm())
                    );
                }
            }
            files.push((format!("{dir}/{name}"), text.into_bytes()));
        };
        table(
            "Accelerometer.csv",
            "m/s^2",
            "Acceleration",
            "Absolute acceleration",
            &|s| Some(s.accel),
        );
        table("Gyroscope.csv", "rad/s", "Gyroscope", "Absolute", &|s| {
            s.gyro
        });
        table(
            "Magnetometer.csv",
            "µT",
            "Magnetic field",
            "Absolute field",
            &|s| s.mag,
        );
        if !fixes.is_empty() {
            let mut text = String::from(
                "\"Time (s)\",\"Latitude (°)\",\"Longitude (°)\",\"Height (m)\",\"Velocity (m/s)\",\
                 \"Direction (°)\",\"Horizontal Accuracy (m)\",\"Vertical Accuracy (m)\"\n",
            );
            let opt = |v: Option<f64>| v.map_or(String::new(), sci9);
            for f in &fixes {
                let _ = writeln!(
                    text,
                    "{},{},{},{},{},{},{},{}",
                    sci9(self.rel(f.t)),
                    sci9(f.lat_deg),
                    sci9(f.lon_deg),
                    opt(f.altitude_m),
                    opt(f.speed_mps),
                    opt(f.bearing_deg),
                    sci9(f.h_accuracy_m),
                    sci9(1.5 * f.h_accuracy_m)
                );
            }
            files.push((format!("{dir}/Location.csv"), text.into_bytes()));
        }
        let device = "\"property\",\"value\"\n\"version\",\"1.1.16\"\n\"build\",\"1011608\"\n\
                      \"fileFormat\",\"1.18\"\n\"deviceModel\",\"pdr simulator\"\n\
                      \"deviceBrand\",\"pdr\"\n\"deviceBoard\",\"sim\"\n\"deviceManufacturer\",\"pdr\"\n";
        files.push((format!("{dir}/meta/device.csv"), device.as_bytes().to_vec()));
        let end = self.items.last().map_or(self.start, |i| match i {
            Item::Imu(s) => s.t,
            Item::Fix(f) => f.t,
        });
        let stamp = |t: f64| {
            let ms = self.unix_ms(t);
            let (y, mo, d, h, mi, s, _) = civil(ms.div_euclid(1000));
            (
                system_time(ms),
                format!(
                    "{y:04}-{mo:02}-{d:02} {h:02}:{mi:02}:{s:02}.{:03} UTC+00:00",
                    ms.rem_euclid(1000)
                ),
            )
        };
        let (s0, s0_text) = stamp(self.start);
        let (s1, s1_text) = stamp(end);
        let time = format!(
            "\"event\",\"experiment time\",\"system time\",\"system time text\"\n\
             \"START\",{},{s0},\"{s0_text}\"\n\"PAUSE\",{},{s1},\"{s1_text}\"\n",
            sci9(0.0),
            sci9(self.rel(end)),
        );
        files.push((format!("{dir}/meta/time.csv"), time.into_bytes()));
        files.sort();
        files
    }

    // -----------------------------------------------------------------------------------------
    // GnssLogger.
    // -----------------------------------------------------------------------------------------

    /// Google GnssLogger v3: the `# Kind,…` declarations, then `Accel`, `Gyro`, `Mag` (values as
    /// Java prints floats), `OrientationDeg` (getOrientation's azimuth, roll and pitch in
    /// degrees) and `Fix` lines in time order; `utcTimeMillis` Unix ms, `elapsedRealtimeNanos`
    /// since boot. A fix's unknown speed and bearing are empty.
    fn gnss_logger(&self) -> Vec<(String, Vec<u8>)> {
        let mut out = String::from(GNSS_LOGGER_HEADER);
        for item in &self.items {
            match item {
                Item::Imu(s) => {
                    let (ms, ns) = (self.unix_ms(s.t), self.boot_ns(s.t));
                    for (kind, v) in [("Accel", Some(s.accel)), ("Gyro", s.gyro), ("Mag", s.mag)] {
                        if let Some(v) = v {
                            let _ = writeln!(
                                out,
                                "{kind},{ms},{ns},{},{},{}",
                                java_float(v.x),
                                java_float(v.y),
                                java_float(v.z)
                            );
                        }
                    }
                    if let Some(q) = s.orientation {
                        let (a, p, r) = get_orientation(&q);
                        let _ = writeln!(
                            out,
                            "OrientationDeg,{ms},{ns},{},{},{}",
                            java_float(a.to_degrees()),
                            java_float(r.to_degrees()),
                            java_float(p.to_degrees())
                        );
                    }
                }
                Item::Fix(f) => {
                    let opt = |v: Option<f64>| v.map_or(String::new(), java_float);
                    let _ = writeln!(
                        out,
                        "Fix,GPS,{},{},{},{},{},{},{},,,{},{},0,24,,",
                        js(f.lat_deg),
                        js(f.lon_deg),
                        f.altitude_m.map_or(String::new(), js),
                        opt(f.speed_mps),
                        java_float(f.h_accuracy_m),
                        opt(f.bearing_deg),
                        self.unix_ms(f.t),
                        self.boot_ns(f.t),
                        java_float(1.5 * f.h_accuracy_m),
                    );
                }
            }
        }
        vec![(
            format!("gnss_log_{}.txt", self.name('_', '_', '_')),
            out.into_bytes(),
        )]
    }

    // -----------------------------------------------------------------------------------------
    // GetSensorData.
    // -----------------------------------------------------------------------------------------

    /// GetSensorData (IPIN): the `%` header, then `ACCE`, `GYRO`, `MAGN` (5 decimals), `AHRS`
    /// (getOrientation's pitch, roll and azimuth in degrees, then the rotation vector x, y, z with
    /// w ≥ 0 implied, 8 decimals), `GNSS` (each fix twice, 1 ms apart, as the app does; Android
    /// reports an unknown speed or bearing as 0) and `POSI` landmarks, in `AppTimestamp` order.
    /// `AppTimestamp` is seconds since the start of the recording plus a delivery delay of
    /// 0–10 ms that varies from sample to sample and is 0 for every eleventh; `SensorTimestamp`
    /// is seconds since boot. The reader's least-delay offset therefore puts each sample back at
    /// its time since the start.
    fn get_sensor_data(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let mut lines: Vec<(i64, String)> = Vec::new();
        let boot_ms = BOOT_NS.div_euclid(1_000_000);
        let mut k = 0i64;
        for item in &self.items {
            match item {
                Item::Imu(s) => {
                    let rel = self.rel_ms(s.t);
                    let app = rel + (k * 7) % 11;
                    k += 1;
                    let (a, st) = (ms_text(app), ms_text(boot_ms.saturating_add(rel)));
                    for (kind, v) in [("ACCE", Some(s.accel)), ("GYRO", s.gyro), ("MAGN", s.mag)] {
                        if let Some(v) = v {
                            lines.push((
                                app,
                                format!(
                                    "{kind};{a};{st};{};{};{};3",
                                    fixed(v.x, 5),
                                    fixed(v.y, 5),
                                    fixed(v.z, 5)
                                ),
                            ));
                        }
                    }
                    if let Some(q) = s.orientation {
                        let (az, p, r) = get_orientation(&q);
                        let c = canonical(&q);
                        lines.push((
                            app,
                            format!(
                                "AHRS;{a};{st};{};{};{};{};{};{};3",
                                fixed(p.to_degrees(), 2),
                                fixed(r.to_degrees(), 2),
                                fixed(az.to_degrees(), 2),
                                fixed(c.i, 8),
                                fixed(c.j, 8),
                                fixed(c.k, 8)
                            ),
                        ));
                    }
                }
                Item::Fix(f) => {
                    let app = self.rel_ms(f.t);
                    let line = |app: i64| {
                        format!(
                            "GNSS;{};{};{};{};{};{};{};{};12;9",
                            ms_text(app),
                            ms_text(self.unix_ms(f.t)),
                            fixed(f.lat_deg, 8),
                            fixed(f.lon_deg, 8),
                            fixed(f.altitude_m.unwrap_or(0.0), 1),
                            fixed(f.bearing_deg.unwrap_or(0.0), 1),
                            fixed(f.h_accuracy_m, 1),
                            fixed(f.speed_mps.unwrap_or(0.0), 1)
                        )
                    };
                    lines.push((app, line(app)));
                    lines.push((app + 1, line(app + 1)));
                }
            }
        }
        let frame = geodetic_frame(sim);
        for (i, (t, e, n)) in waypoints(sim).into_iter().enumerate() {
            let (lat, lon, _) = frame.to_geodetic([e, n, 0.0]);
            let app = self.rel_ms(t);
            lines.push((
                app,
                format!(
                    "POSI;{};{};{};{};0;0",
                    ms_text(app),
                    i + 1,
                    fixed(lat, 7),
                    fixed(lon, 7)
                ),
            ));
        }
        lines.sort_by_key(|l| l.0);
        let (y, mo, d, h, mi, s, wd) = civil(self.unix_start_ns.div_euclid(1_000_000_000));
        const DAYS: [&str; 7] = ["Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat"];
        const MONTHS: [&str; 12] = [
            "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
        ];
        let mut out = String::from(
            "% LogFile created by the 'GetSensorData' App for Android.\n% Date of creation: ",
        );
        let _ = writeln!(
            out,
            "{} {} {d:02} {h:02}:{mi:02}:{s:02} UTC {y}",
            DAYS[wd as usize % 7],
            MONTHS[(mo as usize + 11) % 12]
        );
        out.push_str(GET_SENSOR_DATA_HEADER);
        for (_, l) in lines {
            out.push_str(&l);
            out.push('\n');
        }
        vec![(
            format!("logfile_{}.txt", self.name('_', '_', '_')),
            out.into_bytes(),
        )]
    }

    // -----------------------------------------------------------------------------------------
    // Oxford Step Counter.
    // -----------------------------------------------------------------------------------------

    /// An Oxford Step Counter trace folder, `Pixel_Sim_Hard_FrontPocket_1/` (phone, walker,
    /// surface, placement, take): `accelerometer.csv` (`ns since boot,3,x,y,z`, m/s², 6
    /// decimals) and `stepcounter.csv` (`ns since boot,left,right`, one row per accelerometer
    /// sample; see the module documentation for the contact model).
    fn oxford(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let dir = "Pixel_Sim_Hard_FrontPocket_1";
        // Each foot's swing windows [lift, land), feet alternating over the true steps.
        let mut windows: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
        for (i, st) in sim.truth.steps.iter().enumerate() {
            if !(st.t.is_finite() && st.freq_hz > 0.0) {
                continue;
            }
            let swing = SWING_SHARE * 2.0 / st.freq_hz;
            windows[i % 2].push((st.t - swing, st.t));
        }
        let mut next = [0usize; 2];
        let mut accel = String::new();
        let mut steps = String::new();
        for s in &imu {
            let ns = self.boot_ns(s.t);
            let _ = writeln!(
                accel,
                "{ns},3,{},{},{}",
                fixed(s.accel.x, 6),
                fixed(s.accel.y, 6),
                fixed(s.accel.z, 6)
            );
            let mut contact = [1u8; 2];
            for foot in 0..2 {
                let w = &windows[foot];
                while next[foot] < w.len() && w[next[foot]].1 <= s.t {
                    next[foot] += 1;
                }
                if w.get(next[foot]).is_some_and(|&(lift, _)| lift <= s.t) {
                    contact[foot] = 0;
                }
            }
            let _ = writeln!(steps, "{ns},{},{}", contact[0], contact[1]);
        }
        vec![
            (format!("{dir}/accelerometer.csv"), accel.into_bytes()),
            (format!("{dir}/stepcounter.csv"), steps.into_bytes()),
        ]
    }

    // -----------------------------------------------------------------------------------------
    // Microsoft Indoor Location 2.0.
    // -----------------------------------------------------------------------------------------

    /// A Microsoft Indoor Location Competition 2.0 trace: `#\t` header lines (start time, site,
    /// phone, sensors), then tab-separated `unix_ms TYPE_… values accuracy` lines in time order
    /// (values as Java prints floats; the rotation vector's x, y, z with w ≥ 0 implied), the
    /// `TYPE_WAYPOINT` truth in metres east and north of the start, and `#\tendTime`.
    fn ms_indoor(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let mut lines: Vec<(i64, String)> = Vec::new();
        for item in &self.items {
            let Item::Imu(s) = item else { continue };
            let ms = self.unix_ms(s.t);
            for (kind, v) in [
                ("TYPE_ACCELEROMETER", Some(s.accel)),
                ("TYPE_MAGNETIC_FIELD", s.mag),
                ("TYPE_GYROSCOPE", s.gyro),
            ] {
                if let Some(v) = v {
                    lines.push((
                        ms,
                        format!(
                            "{ms}\t{kind}\t{}\t{}\t{}\t3",
                            java_float(v.x),
                            java_float(v.y),
                            java_float(v.z)
                        ),
                    ));
                }
            }
            if let Some(q) = s.orientation {
                let c = canonical(&q);
                lines.push((
                    ms,
                    format!(
                        "{ms}\tTYPE_ROTATION_VECTOR\t{}\t{}\t{}\t3",
                        java_float(c.i),
                        java_float(c.j),
                        java_float(c.k)
                    ),
                ));
            }
        }
        for (t, e, n) in waypoints(sim) {
            let ms = self.unix_ms(t);
            lines.push((
                ms,
                format!("{ms}\tTYPE_WAYPOINT\t{}\t{}", java_float(e), java_float(n)),
            ));
        }
        lines.sort_by_key(|l| l.0);
        let start_ms = self.unix_start_ns.div_euclid(1_000_000);
        let end_ms = lines.last().map_or(start_ms, |l| l.0);
        let id = format!("5d{:022x}", start_ms);
        let mut out = String::new();
        let _ = writeln!(out, "#\tstartTime:{start_ms}");
        let _ = writeln!(
            out,
            "#\tSiteID:5a0546857ecc773753327266\tSiteName:pdr simulation\t\
             FloorId:46cecbd5ac5ae9b24b6aa4b1\tFloorName:F1"
        );
        out.push_str(MS_INDOOR_SENSORS);
        for (_, l) in lines {
            out.push_str(&l);
            out.push('\n');
        }
        let _ = writeln!(out, "#\tendTime:{end_ms}");
        vec![(format!("{id}.txt"), out.into_bytes())]
    }

    // -----------------------------------------------------------------------------------------
    // x-io.
    // -----------------------------------------------------------------------------------------

    /// x-io Gait-Tracking's `sensor_data.csv`: time in seconds since the start, gyroscope in
    /// deg/s, accelerometer in g (Android sign), 6 decimals. A sample without a gyroscope value
    /// is not written (the format needs all seven numbers).
    fn xio(&self) -> Vec<(String, Vec<u8>)> {
        let mut out = String::from(
            "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),\
             Accelerometer X (g),Accelerometer Y (g),Accelerometer Z (g)\n",
        );
        for s in self.imu() {
            let Some(g) = s.gyro else { continue };
            let (g, a) = (g.map(f64::to_degrees), s.accel / G0);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{}",
                fixed(self.rel(s.t), 6),
                fixed(g.x, 6),
                fixed(g.y, 6),
                fixed(g.z, 6),
                fixed(a.x, 6),
                fixed(a.y, 6),
                fixed(a.z, 6)
            );
        }
        vec![("sensor_data.csv".to_string(), out.into_bytes())]
    }
}

/// A Unix time in ms as phyphox writes the system time: `1.698745673473E9` (s).
fn system_time(ms: i64) -> String {
    let digits = ms.to_string();
    if ms < 1000 {
        return sci9(ms as f64 * 1e-3);
    }
    let (first, rest) = digits.split_at(1);
    format!("{first}.{rest}E{}", digits.len() - 4)
}

/// A JSON string literal.
fn json_string(s: &str) -> String {
    serde_json::Value::String(s.to_string()).to_string()
}

/// The geodetic frame of the true path: the simulation's, or one at [`GnssSim`]'s default
/// origin for a walk without GNSS.
fn geodetic_frame(sim: &Simulation) -> crate::engine::geo::LocalFrame {
    sim.truth.frame.unwrap_or_else(|| {
        let o = GnssSim::default().origin;
        crate::engine::geo::LocalFrame::new(o.0, o.1, o.2)
    })
}

/// Ground-truth waypoints (t, east, north) of a walk: its start, every
/// [`WAYPOINT_INTERVAL_S`], and its end.
pub fn waypoints(sim: &Simulation) -> Vec<(f64, f64, f64)> {
    let path = &sim.truth.path;
    let (Some(&first), Some(&last)) = (path.first(), path.last()) else {
        return Vec::new();
    };
    if !(first.0.is_finite() && last.0.is_finite()) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut k = 0u32;
    loop {
        let t = first.0 + f64::from(k) * WAYPOINT_INTERVAL_S;
        if t >= last.0 - 1e-6 || k == u32::MAX {
            break;
        }
        let (e, n) = sim.truth.position_at(t);
        out.push((t, e, n));
        k += 1;
    }
    out.push(last);
    out
}

/// Sensor Logger's columns of a three-axis sensor.
const SL_VECTOR: [&str; 5] = ["time", "seconds_elapsed", "z", "y", "x"];

/// Sensor Logger's columns of `Orientation.csv`.
const SL_ORIENTATION: [&str; 9] = [
    "time",
    "seconds_elapsed",
    "qz",
    "qy",
    "qx",
    "qw",
    "roll",
    "pitch",
    "yaw",
];

/// Sensor Logger's columns of `Location.csv`.
const SL_LOCATION: [&str; 11] = [
    "time",
    "seconds_elapsed",
    "bearingAccuracy",
    "speedAccuracy",
    "verticalAccuracy",
    "horizontalAccuracy",
    "speed",
    "bearing",
    "altitude",
    "longitude",
    "latitude",
];

const GNSS_LOGGER_HEADER: &str = "# \n# Header Description:\n# \n\
# Version: v3.0.6.0 Platform: 14 Manufacturer: pdr Model: simulator GnssHardwareModelName: pdr-sim\n# \n\
# Raw,utcTimeMillis,TimeNanos,LeapSecond,TimeUncertaintyNanos,FullBiasNanos,BiasNanos,BiasUncertaintyNanos,DriftNanosPerSecond,DriftUncertaintyNanosPerSecond,HardwareClockDiscontinuityCount,Svid,TimeOffsetNanos,State,ReceivedSvTimeNanos,ReceivedSvTimeUncertaintyNanos,Cn0DbHz,PseudorangeRateMetersPerSecond,PseudorangeRateUncertaintyMetersPerSecond\n# \n\
# UncalAccel,utcTimeMillis,elapsedRealtimeNanos,UncalAccelXMps2,UncalAccelYMps2,UncalAccelZMps2,BiasXMps2,BiasYMps2,BiasZMps2\n# \n\
# UncalGyro,utcTimeMillis,elapsedRealtimeNanos,UncalGyroXRadPerSec,UncalGyroYRadPerSec,UncalGyroZRadPerSec,DriftXRadPerSec,DriftYRadPerSec,DriftZRadPerSec\n# \n\
# UncalMag,utcTimeMillis,elapsedRealtimeNanos,UncalMagXMicroT,UncalMagYMicroT,UncalMagZMicroT,BiasXMicroT,BiasYMicroT,BiasZMicroT\n# \n\
# Fix,Provider,LatitudeDegrees,LongitudeDegrees,AltitudeMeters,SpeedMps,AccuracyMeters,BearingDegrees,UnixTimeMillis,SpeedAccuracyMps,BearingAccuracyDegrees,elapsedRealtimeNanos,VerticalAccuracyMeters,MockLocation,NumberOfUsedSignals,VerticalSpeedAccuracyMps,SolutionType\n# \n\
# Status,UnixTimeMillis,SignalCount,SignalIndex,ConstellationType,Svid,CarrierFrequencyHz,Cn0DbHz,AzimuthDegrees,ElevationDegrees,UsedInFix,HasAlmanacData,HasEphemerisData,BasebandCn0DbHz\n# \n\
# OrientationDeg,utcTimeMillis,elapsedRealtimeNanos,yawDeg,rollDeg,pitchDeg\n# \n\
# Accel,utcTimeMillis,elapsedRealtimeNanos,AccelXMps2,AccelYMps2,AccelZMps2\n# \n\
# Gyro,utcTimeMillis,elapsedRealtimeNanos,GyroXRadPerSec,GyroYRadPerSec,GyroZRadPerSec\n# \n\
# Mag,utcTimeMillis,elapsedRealtimeNanos,MagXMicroT,MagYMicroT,MagZMicroT\n# \n";

const GET_SENSOR_DATA_HEADER: &str = "% Developed by LOPSI research group at CAR-CSIC, Spain (http://www.car.upm-csic.es/lopsi)\n\
% Version 2.1 January 2018\n\
% The 'GetSensorData' program stores information from Smartphone/Tablet internal sensors (Accelerometers, Gyroscopes, Magnetometers, Pressure, Ambient Light, Orientation, Sound level, GPS/GNSS position, WiFi RSS, Cellular/GSM/3G signal strength,...)\n\
%\n\
% Phone used for this logfile:\n\
% Manufacturer:            \tpdr\n\
% Model:                   \tsimulator\n\
% API Android version:     \t29\n\
%\n\
% LogFile Data format:\n\
% Accelerometer data: \t'ACCE;AppTimestamp(s);SensorTimestamp(s);Acc_X(m/s^2);Acc_Y(m/s^2);Acc_Z(m/s^2);Accuracy(integer)'\n\
% Gyroscope data:     \t'GYRO;AppTimestamp(s);SensorTimestamp(s);Gyr_X(rad/s);Gyr_Y(rad/s);Gyr_Z(rad/s);Accuracy(integer)'\n\
% Magnetometer data:  \t'MAGN;AppTimestamp(s);SensorTimestamp(s);Mag_X(uT);;Mag_Y(uT);Mag_Z(uT);Accuracy(integer)'\n\
% Pressure data:      \t'PRES;AppTimestamp(s);SensorTimestamp(s);Pres(mbar);Accuracy(integer)'\n\
% Light data:         \t'LIGH;AppTimestamp(s);SensorTimestamp(s);Light(lux);Accuracy(integer)'\n\
% Orientation data:   \t'AHRS;AppTimestamp(s);SensorTimestamp(s);PitchX(deg);RollY(deg);YawZ(deg);Quat(2);Quat(3);Quat(4);Accuracy(int)'\n\
% GNSS data:          \t'GNSS;AppTimestamp(s);SensorTimeStamp(s);Latit(deg);Long(deg);Altitude(m);Bearing(deg);Accuracy(m);Speed(m/s);SatInView;SatInUse'\n\
% WIFI data:          \t'WIFI;AppTimestamp(s);SensorTimeStamp(s);Name_SSID;MAC_BSSID;Frequency;RSS(dBm);'\n\
% BLE 4.0 data:       \t'BLE4;AppTimestamp(s);iBeacon;MAC;RSSI(dBm);MajorID;MinorID;'\n\
% Sound data:         \t'SOUN;AppTimestamp(s);RMS;Pressure(Pa);SPL(dB);'\n\
% Ground truth data:  \t'POSI;Timestamp(s);Counter;Latitude(degrees); Longitude(degrees);floor ID(0,1,2..4);Building ID(0,1,2..3)'\n\
%\n\
% Note that there are two timestamps:\n\
%  -'AppTimestamp' is set by the Android App as data is read. It is not representative of when data is actually captured by the sensor (but has a common time reference for all sensors)\n\
%  -'SensorTimestamp' is set by the sensor itself (the delta_time=SensorTimestamp(k)-SensorTimestamp(k-1) between two consecutive samples is an accurate estimate of the sampling interval). This timestamp is better for integrating inertial data.\n";

const MS_INDOOR_SENSORS: &str = "#\tBrand:pdr\tModel:simulator\tAndroidName:10\tAPILevel:29\t\n\
#\ttype:1\tname:Accelerometer\tversion:1\tvendor:pdr\tresolution:0.0023956299\tpower:0.15\tmaximumRange:78.4532\n\
#\ttype:4\tname:Gyroscope\tversion:1\tvendor:pdr\tresolution:0.0012217305\tpower:0.9\tmaximumRange:34.906586\n\
#\ttype:2\tname:Magnetometer\tversion:1\tvendor:pdr\tresolution:0.15\tpower:1.1\tmaximumRange:4912.0503\n\
#\ttype:11\tname:Rotation Vector\tversion:1\tvendor:pdr\tresolution:5.9604645E-8\tpower:1.1\tmaximumRange:1.0\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calendar() {
        assert_eq!(civil(0), (1970, 1, 1, 0, 0, 0, 4));
        assert_eq!(civil(DEFAULT_UNIX_START_S), (2026, 1, 1, 0, 0, 0, 4));
        assert_eq!(civil(1_780_272_000 + 3661), (2026, 6, 1, 1, 1, 1, 1));
        assert_eq!(civil(951_782_400), (2000, 2, 29, 0, 0, 0, 2));
    }

    #[test]
    fn number_formats() {
        assert_eq!(java_float(9.81), "9.81");
        assert_eq!(java_float(1.0), "1.0");
        assert_eq!(java_float(0.0), "0.0");
        assert_eq!(java_float(1.5e-4), "1.5E-4");
        assert_eq!(java_float(-2e-5), "-2.0E-5");
        assert_eq!(sci9(43.7695604), "4.376956040E1");
        assert_eq!(sci9(0.3), "3.000000000E-1");
        assert_eq!(ms_text(17_292_410), "17292.410");
        assert_eq!(ms_text(-1), "-0.001");
        assert_eq!(js_float(9.81), "9.8100004196167");
        assert_eq!(js(3.0), "3");
        assert_eq!(js(-1.7763568394002505e-15), "-1.7763568394002505e-15");
        assert_eq!(js(2e21), "2e+21");
        assert_eq!(js(0.000001), "0.000001");
        assert_eq!(system_time(1_698_745_673_473), "1.698745673473E9");
    }

    #[test]
    fn get_orientation_inverts_the_reader() {
        let q = crate::io::import::gnss_logger::orientation_quaternion(0.7, -1.2, 2.1);
        let (a, p, r) = get_orientation(&q);
        assert!((a - 0.7).abs() < 1e-12 && (p + 1.2).abs() < 1e-12 && (r - 2.1).abs() < 1e-12);
        // Gimbal lock, top straight up or down: the angles still give the rotation back.
        let h = std::f64::consts::FRAC_PI_2;
        for (a0, p0, r0) in [(0.3, -h, 0.5), (-2.0, h, 1.0), (1.0, -h, 0.0)] {
            let q = crate::io::import::gnss_logger::orientation_quaternion(a0, p0, r0);
            let (a, p, r) = get_orientation(&q);
            let back = crate::io::import::gnss_logger::orientation_quaternion(a, p, r);
            assert!(back.angle_to(&q) < 1e-7, "{a0} {p0} {r0}: {a} {p} {r}");
        }
    }
}
