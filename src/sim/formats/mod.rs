//! A simulated walk written in every format the import reads, as the recording app writes it.
//! May import: `engine` and `io`.
//!
//! [`write`](fn@write) turns a [`Simulation`] into the files an app (or a data set) would have produced for
//! the same walk: file and folder names, header lines, column names and order, units, clocks,
//! sign and quaternion conventions. The readers of [`crate::io::import`] are the specification:
//! every recording written here reads back through [`crate::io::import::import_all`] (the plain
//! CSV folder through [`PLAIN_CSV_RECIPE`] with [`crate::io::import::import_with`]) without a
//! warning, one IMU record per simulated IMU sample, with the values of the simulation to the
//! precision the format writes. The tests in `tests/formats.rs` hold both ends together.
//!
//! # What each format carries
//! | Format | Files | IMU | Orientation | GNSS | Barometer | Truth |
//! |---|---|---|---|---|---|---|
//! | Sensor Logger (Android) | folder | total, linear, gravity, gyro, mag | rotation vector | `Location.csv` | `Barometer.csv` (hPa, float) | – |
//! | Sensor Logger (iOS) | folder | user accel. and gravity in g, iOS sign; gyro, mag | Core Motion attitude | `Location.csv` | `Barometer.csv` (hPa) | – |
//! | Sensor Logger JSON | file | as the folder, without `TotalAcceleration` | as the folder | `Location` | `Barometer` | – |
//! | phyphox | folder | accel., gyro, mag | none | `Location.csv` | `Pressure.csv` (hPa) | – |
//! | GnssLogger | file | `Accel`, `Gyro`, `Mag` | `OrientationDeg` | `Fix` | none | – |
//! | GetSensorData | file | `ACCE`, `GYRO`, `MAGN` | `AHRS` rotation vector | `GNSS` (twice) | `PRES` (mbar, 4 decimals) | `POSI` landmarks with floor |
//! | Oxford Step Counter | folder | accelerometer only | none | none | none | foot contacts |
//! | Microsoft Indoor 2.0 | file | accel., gyro, mag | rotation vector | none | none | `TYPE_WAYPOINT` |
//! | x-io Gait-Tracking | file | gyro (deg/s), accel. (g): the foot IMU's when the walk has one | none | none | none | (loop closure, claimed by the reader) |
//! | TyrEx (Android) | folder | accel., calibrated gyro and mag | rotation vector | none | none | `truth.csv` trajectory, 60 Hz |
//! | TyrEx (iOS) | folder | accel. in g, iOS sign; gyro, mag (4 decimals) | Core Motion attitude | none | none | `truth.csv` trajectory, 60 Hz |
//! | UbiComp 2013 | folder | `acc`, `gyr`, `mag` | none | none | none | `truth.json` step count and walk window |
//! | WeAllWalk | folder | user accel. + gravity in g, iOS sign; rotation rate | Core Motion quaternion | none | none | heel strikes; straights and turns |
//! | plain CSV (read by a recipe) | folder | `acc`, `gyr`, `mag` (ms, no header) | none | none | `bar` (hPa, 4 decimals; a still one without a barometer) | – |
//! | pdr-log | file | everything, lossless | | | | |
//!
//! Where a format has no place for something the simulation has, it is left out: phyphox, Oxford,
//! x-io and UbiComp 2013 have no OS orientation (the engine then falls back to Madgwick or the
//! gravity low-pass), Oxford has no gyroscope nor magnetometer, WeAllWalk no usable
//! magnetometer (it writes one, as the data set's unusable raw columns, and the reader ignores
//! it); Microsoft Indoor, Oxford, x-io, TyrEx, UbiComp 2013 and WeAllWalk have no GNSS;
//! GnssLogger, Microsoft Indoor, Oxford, x-io, TyrEx, UbiComp 2013 and WeAllWalk have no
//! barometer ([`holds_pressure`]). The x-io reader always claims a loop closure: only a closed walk (the square) makes that
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
//!   when it has GNSS, else around [`GnssSim`](crate::sim::GnssSim)'s default origin.
//! - TyrEx `truth.csv`: the true position (east, north) every 1/[`TRUTH_RATE_HZ`] s over the
//!   true path, [`POCKET_HEIGHT_M`] above the ground, without holes.
//! - UbiComp 2013 `truth.json`: the number of true steps and a walk window from the start of the
//!   first moving segment to the end of the last one.
//! - WeAllWalk `steps.csv`: every true step, the feet alternating; `segments.csv`: the
//!   straights and turns of [`path_segments`] (derived from the true steps' headings).
//!
//! # Clocks
//! Every format keeps the simulation's sample spacing; the origin is the format's own:
//! - Unix time (Sensor Logger ns, GnssLogger and Microsoft ms): the simulation's times when they
//!   already are Unix times (a scenario with [`crate::sim::Scenario::clock_offset_s`] set), else
//!   [`DEFAULT_UNIX_START_S`] plus the simulation time;
//! - time since the start of the recording (phyphox, x-io, GetSensorData's app clock, TyrEx
//!   Android, WeAllWalk), the start being the first record (or the start of the true path when
//!   that is earlier);
//! - time since boot (Oxford ns; GnssLogger `elapsedRealtimeNanos`, GetSensorData
//!   `SensorTimestamp`, TyrEx iOS, UbiComp 2013), starting at [`BOOT_NS`].
//!
//! [`Recording::clock_offset_s`] says how the reader's clock relates to the simulation's.
//!
//! Output is deterministic: the same simulation gives the same bytes, natively and in wasm.

mod get_sensor_data;
mod gnss_logger;
mod ms_indoor;
mod oxford;
mod phyphox;
mod plain_csv;
mod sensor_logger;
mod tyrex;
mod ubicomp13;
mod weallwalk;
mod xio;

pub use plain_csv::RECIPE_JSON as PLAIN_CSV_RECIPE;
pub use tyrex::{ios_boot_clock_s, POCKET_HEIGHT_M, TRUTH_RATE_HZ};
pub use weallwalk::{path_segments, PathSegment, MIN_TURN_DEG, TURN_RATE_DEG_PER_STEP};

use super::Simulation;
use crate::engine::types::{GnssFix, ImuSample, PressureSample};
use crate::engine::Record;
use crate::io::import::{Format, Platform};
use nalgebra::{Quaternion, UnitQuaternion};

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

/// Whether a format is a folder of files (Sensor Logger CSVs, phyphox, Oxford, TyrEx, UbiComp
/// 2013, WeAllWalk) rather than one file.
pub fn is_folder(format: Format) -> bool {
    matches!(
        format,
        Format::SensorLogger
            | Format::Phyphox
            | Format::OxfordSteps
            | Format::Recipe
            | Format::Tyrex
            | Format::Ubicomp13
            | Format::WeAllWalk
    )
}

/// Whether `format`, as written here, carries the walk's barometer readings
/// (`Record::Pressure`). GnssLogger, Microsoft Indoor, Oxford and x-io have no place for them.
pub fn holds_pressure(format: Format) -> bool {
    matches!(
        format,
        Format::PdrLog
            | Format::SensorLogger
            | Format::SensorLoggerJson
            | Format::Phyphox
            | Format::GetSensorData
            | Format::Recipe
    )
}

/// Writes a simulated walk as `format` (see the module documentation for what each one
/// carries). `platform` chooses between Sensor Logger's Android and iOS conventions (its CSV
/// folder and JSON export) and TyrEx's Android and iOS layouts; the other formats come from one
/// platform (WeAllWalk from iPhones, the rest from Android apps or fixed devices) and ignore it. Never fails: a walk without records gives files with headers only.
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
        Format::Recipe => (w.plain_csv(), unix_offset),
        Format::Tyrex => (
            w.tyrex(sim, platform),
            match platform {
                Platform::Android => relative,
                Platform::Ios => tyrex::ios_boot_clock_s() - w.start,
            },
        ),
        Format::Ubicomp13 => (w.ubicomp13(sim), BOOT_NS as f64 * 1e-9 - w.start),
        Format::WeAllWalk => (w.weallwalk(sim), relative),
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

impl Item<'_> {
    /// The record's time (the simulation's clock), s.
    fn t(&self) -> f64 {
        match self {
            Item::Imu(s) => s.t,
            Item::Fix(f) => f.t,
        }
    }
}

/// The records of a simulation with the clocks of the formats.
struct Walk<'a> {
    items: Vec<Item<'a>>,
    /// The samples of a foot-mounted IMU (`Record::Foot`), if the walk has one.
    foot: Vec<&'a ImuSample>,
    /// The barometer readings (`Record::Pressure`), if the walk has them, in time order.
    pressure: Vec<&'a PressureSample>,
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

/// A Unix time in ms as phyphox writes the system time: `1.698745673473E9` (s).
fn system_time(ms: i64) -> String {
    let digits = ms.to_string();
    if ms < 1000 {
        return sci9(ms as f64 * 1e-3);
    }
    let (first, rest) = digits.split_at(1);
    format!("{first}.{rest}E{}", digits.len() - 4)
}

/// Calendar date and time of a Unix time (UTC): (year, month, day, hour, minute, second,
/// weekday with 0 = Sunday).
fn civil(unix_s: i64) -> (i64, u32, u32, u32, u32, u32, u32) {
    let days = unix_s.div_euclid(86_400);
    let secs = unix_s.rem_euclid(86_400);
    let (y, m, d) = crate::io::import::date::civil_of_days(days);
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

/// Rz(−90°): ENU → Core Motion's (north, west, up) reference (the iOS writers' attitudes).
fn enu_to_core_motion() -> UnitQuaternion<f64> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, -h))
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
        let pressure: Vec<&'a PressureSample> = sim
            .records
            .iter()
            .filter_map(|r| match r {
                Record::Pressure(p) if p.check().is_ok() => Some(p),
                _ => None,
            })
            .collect();
        let first_item = items.first().map(Item::t);
        let first = match (first_item, pressure.first().map(|p| p.t)) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
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
        let foot = sim
            .records
            .iter()
            .filter_map(|r| match r {
                Record::Foot(s) if s.check_finite().is_ok() => Some(s),
                _ => None,
            })
            .collect();
        Walk {
            items,
            foot,
            pressure,
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
}

/// Height above sea level of a pressure in the standard atmosphere, m (the troposphere's
/// formula, sea level 1013.25 hPa, 15 °C): what a phone shows as the barometric altitude.
fn standard_height_m(hpa: f64) -> f64 {
    44_330.77 * (1.0 - libm::pow(hpa / 1013.25, 0.190_263))
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
