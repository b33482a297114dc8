//! Sensor Logger's CSV folder and JSON export of a simulated walk, on Android or iOS, as
//! [`crate::io::import::sensor_logger`] reads them. May import: `engine` and `io`.

use super::{
    canonical, enu_to_core_motion, fixed, get_orientation, js, js_float, round_i64,
    standard_height_m, Item, Walk,
};
use crate::engine::math::OnePole;
use crate::engine::orientation::G0;
use crate::engine::types::{GnssFix, ImuSample, PressureSample};
use crate::io::import::Platform;
use nalgebra::{UnitQuaternion, Vector3};
use std::fmt::Write as _;

/// Yaw, pitch and roll as apps that show angles write them (rad): yaw counter-clockwise about
/// z, `R = Rz(yaw)·Rx(pitch)·Ry(roll)`.
fn yaw_pitch_roll(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let (a, p, r) = get_orientation(q);
    (-a, -p, r)
}

/// Core Motion's attitude (device → reference frame x magnetic north, y west, z up) of a
/// device → ENU rotation: `Rz(−90°)·q`, the inverse of the iOS reader's `Rz(+90°)`.
fn ios_attitude(q: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    enu_to_core_motion() * q
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

/// A JSON string literal.
fn json_string(s: &str) -> String {
    serde_json::Value::String(s.to_string()).to_string()
}

impl Walk<'_> {
    /// Mean sampling interval of the IMU, ms (0 with fewer than two samples).
    fn interval_ms(&self, imu: &[&ImuSample]) -> i64 {
        match (imu.first(), imu.last()) {
            (Some(a), Some(b)) if imu.len() > 1 => {
                round_i64((b.t - a.t) / (imu.len() - 1) as f64 * 1e3)
            }
            _ => 0,
        }
    }

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

    /// A barometer reading as Sensor Logger's `Barometer` columns ([`SL_BAROMETER`]): the
    /// pressure in hPa (expo-sensors' unit on both platforms; a 32-bit float on Android) and the
    /// altitude relative to the first reading in the standard atmosphere, m.
    fn sl_pressure(&self, p: &PressureSample, platform: Platform) -> Vec<String> {
        let num = |v: f64| {
            if platform == Platform::Ios {
                js(v)
            } else {
                js_float(v)
            }
        };
        let first = self.pressure.first().map_or(p.hpa, |f| f.hpa);
        vec![
            self.unix_ns(p.t).to_string(),
            fixed(self.rel(p.t), 9),
            num(standard_height_m(p.hpa) - standard_height_m(first)),
            num(p.hpa),
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
    /// eleven columns; the barometer's `relativeAltitude,pressure`). Android: m/s² with gravity in `TotalAcceleration.csv` and `Gravity.csv`,
    /// without in `Accelerometer.csv`; the orientation is the rotation vector. iOS: no total,
    /// user acceleration and gravity in g with Core Motion's sign, the attitude in the
    /// magnetic-north reference frame.
    pub(super) fn sensor_logger_csv(&self, platform: Platform) -> Vec<(String, Vec<u8>)> {
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
        if !self.pressure.is_empty() {
            let mut text = SL_BAROMETER.join(",") + "\n";
            for p in &self.pressure {
                text.push_str(&self.sl_pressure(p, platform).join(","));
                text.push('\n');
            }
            files.push((format!("{dir}/Barometer.csv"), text.into_bytes()));
            sensors.push("Barometer");
        }
        let (cols, values) = self.sl_metadata(&imu, platform, &sensors);
        let text = format!("{}\n{}\n", cols.join(","), values.join(","));
        files.push((format!("{dir}/Metadata.csv"), text.into_bytes()));
        crate::engine::sort::sort(&mut files);
        files
    }

    /// Sensor Logger's JSON export: an array with one object per reading, every value a string,
    /// in time order, the metadata first. Written as an app version without the
    /// `TotalAcceleration` sensor (the reader adds `Accelerometer` and `Gravity`).
    pub(super) fn sensor_logger_json(&self, platform: Platform) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let gravity = gravity(&imu);
        let mut sensors = self.sl_sensors(&imu, platform, false);
        if !self.fixes().is_empty() {
            sensors.push("Location");
        }
        if !self.pressure.is_empty() {
            sensors.push("Barometer");
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
        let mut pressure = self.pressure.iter().peekable();
        for item in &self.items {
            let t = item.t();
            while let Some(p) = pressure.next_if(|p| p.t <= t) {
                out.push_str(",\n");
                out.push_str(&element(
                    "Barometer",
                    &SL_BAROMETER,
                    &self.sl_pressure(p, platform),
                ));
            }
            match item {
                Item::Imu(s) => {
                    let g = gravity.get(k).copied().unwrap_or_default();
                    k += 1;
                    for &sensor in &sensors {
                        if sensor == "Location" || sensor == "Barometer" {
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
        for p in pressure {
            out.push_str(",\n");
            out.push_str(&element(
                "Barometer",
                &SL_BAROMETER,
                &self.sl_pressure(p, platform),
            ));
        }
        out.push_str("]\n");
        vec![(
            format!("{}.json", self.name('-', '_', '-')),
            out.into_bytes(),
        )]
    }
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

/// Sensor Logger's columns of `Barometer.csv`.
const SL_BAROMETER: [&str; 4] = ["time", "seconds_elapsed", "relativeAltitude", "pressure"];

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
