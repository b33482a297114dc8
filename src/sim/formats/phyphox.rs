//! phyphox's CSV export of a simulated walk, as [`crate::io::import::phyphox`] reads it.
//! May import: `engine` and `io`.

use super::{civil, sci9, system_time, Item, Walk};
use crate::engine::types::ImuSample;
use nalgebra::Vector3;
use std::fmt::Write as _;

impl Walk<'_> {
    /// phyphox's CSV export of a multi-sensor experiment: `Accelerometer.csv` ("Acceleration
    /// with g", m/s², Android sign on both platforms), `Gyroscope.csv`, `Magnetometer.csv`,
    /// `Location.csv`, `Pressure.csv` (the barometer, hPa, as phyphox's pressure sensor
    /// exports it) and `meta/`; time in seconds since the start; every number in
    /// `0.000000000E0` form. An unknown velocity or direction is left empty (phyphox itself
    /// writes `NaN` there; the reader takes both as unknown, and nothing here writes NaN).
    pub(super) fn phyphox(&self) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let dir = format!("Walk {}", self.name('-', ' ', '-'));
        let mut files = Vec::new();
        let vectors: [VectorTable; 3] = [
            (
                "Accelerometer.csv",
                "m/s^2",
                "Acceleration",
                "Absolute acceleration",
                &|s| Some(s.accel),
            ),
            ("Gyroscope.csv", "rad/s", "Gyroscope", "Absolute", &|s| {
                s.gyro
            }),
            (
                "Magnetometer.csv",
                "µT",
                "Magnetic field",
                "Absolute field",
                &|s| s.mag,
            ),
        ];
        for (name, unit, q, abs, get) in vectors {
            if let Some(text) = self.phyphox_vectors(&imu, unit, q, abs, get) {
                files.push((format!("{dir}/{name}"), text.into_bytes()));
            }
        }
        if let Some(text) = self.phyphox_location() {
            files.push((format!("{dir}/Location.csv"), text.into_bytes()));
        }
        if let Some(text) = self.phyphox_pressure() {
            files.push((format!("{dir}/Pressure.csv"), text.into_bytes()));
        }
        files.push((
            format!("{dir}/meta/device.csv"),
            PHYPHOX_DEVICE.as_bytes().to_vec(),
        ));
        files.push((
            format!("{dir}/meta/time.csv"),
            self.phyphox_time().into_bytes(),
        ));
        crate::engine::sort::sort(&mut files);
        files
    }

    /// One sensor's table of vectors (`get` of each IMU sample that has one) with their norm:
    /// the column names are `{q} x ({unit})`, … and `{abs} ({unit})`. `None` when no sample has
    /// the sensor (phyphox writes no file for it).
    fn phyphox_vectors(
        &self,
        imu: &[&ImuSample],
        unit: &str,
        q: &str,
        abs: &str,
        get: &dyn Fn(&ImuSample) -> Option<Vector3<f64>>,
    ) -> Option<String> {
        if !imu.iter().any(|s| get(s).is_some()) {
            return None;
        }
        let mut text = format!(
            "\"Time (s)\",\"{q} x ({unit})\",\"{q} y ({unit})\",\"{q} z ({unit})\",\"{abs} ({unit})\"\n"
        );
        for s in imu {
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
        Some(text)
    }

    /// `Location.csv`, the GNSS fixes; `None` for a walk without any.
    fn phyphox_location(&self) -> Option<String> {
        let fixes = self.fixes();
        if fixes.is_empty() {
            return None;
        }
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
        Some(text)
    }

    /// `Pressure.csv`, the barometer; `None` for a walk without one.
    fn phyphox_pressure(&self) -> Option<String> {
        if self.pressure.is_empty() {
            return None;
        }
        let mut text = String::from("\"Time (s)\",\"Pressure (hPa)\"\n");
        for p in &self.pressure {
            let _ = writeln!(text, "{},{}", sci9(self.rel(p.t)), sci9(p.hpa));
        }
        Some(text)
    }

    /// `meta/time.csv`: the experiment's start and its pause at the last record, each with its
    /// system time.
    fn phyphox_time(&self) -> String {
        let end = self.items.last().map_or(self.start, Item::t);
        let end = self.pressure.last().map_or(end, |p| end.max(p.t));
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
        format!(
            "\"event\",\"experiment time\",\"system time\",\"system time text\"\n\
             \"START\",{},{s0},\"{s0_text}\"\n\"PAUSE\",{},{s1},\"{s1_text}\"\n",
            sci9(0.0),
            sci9(self.rel(end)),
        )
    }
}

/// One sensor's table: file name, unit, column name, norm's column name, and the sensor's
/// vector in an IMU sample.
type VectorTable<'f> = (
    &'static str,
    &'static str,
    &'static str,
    &'static str,
    &'f dyn Fn(&ImuSample) -> Option<Vector3<f64>>,
);

/// `meta/device.csv`: the app's version and the device.
const PHYPHOX_DEVICE: &str = "\"property\",\"value\"\n\"version\",\"1.1.16\"\n\"build\",\"1011608\"\n\
                              \"fileFormat\",\"1.18\"\n\"deviceModel\",\"pdr simulator\"\n\
                              \"deviceBrand\",\"pdr\"\n\"deviceBoard\",\"sim\"\n\"deviceManufacturer\",\"pdr\"\n";
