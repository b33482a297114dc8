//! A folder of header-less CSVs of a simulated walk, as many research and hobby loggers write
//! it: `acc.csv`, `gyr.csv`, `mag.csv`, `bar.csv`, each line `time in ms, x, y, z` (pressure:
//! `time, hPa`). No format sniffing recognises it; [`RECIPE_JSON`] reads it
//! ([`crate::io::import::recipe`]). May import: `engine` and `io`.

use super::{fixed, Walk};
use nalgebra::Vector3;
use std::fmt::Write as _;

/// The recipe that reads `Walk::plain_csv`'s folder (the example recipe of docs/recipes.md).
pub const RECIPE_JSON: &str = r#"{
  "recipe": 1,
  "name": "plain CSV, ms",
  "files": [
    {"match": "acc.csv", "sensor": "accelerometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
     "time_unit": "ms", "unit": "m/s2"},
    {"match": "gyr.csv", "sensor": "gyroscope", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
     "time_unit": "ms", "unit": "rad/s"},
    {"match": "mag.csv", "sensor": "magnetometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
     "time_unit": "ms", "unit": "uT", "optional": true},
    {"match": "bar.csv", "sensor": "pressure", "columns": {"t": 1, "value": 2},
     "time_unit": "ms", "unit": "hPa", "optional": true}
  ]
}
"#;

/// Pressure written to `bar.csv` for a walk without a barometer, hPa: the standard atmosphere
/// at 50 m, a still barometer (so the folder always has the recipe's pressure file).
pub const PRESSURE_HPA: f64 = 1007.26;

impl Walk<'_> {
    /// The folder `plain_<start>/`: `acc.csv` (m/s², including gravity, Android sign),
    /// `gyr.csv` (rad/s), `mag.csv` (µT) with a line per IMU sample that has the sensor, and
    /// `bar.csv` (hPa, 4 decimals): the walk's barometer readings, or, for a walk without them,
    /// [`PRESSURE_HPA`] at a tenth of the IMU rate; time in whole Unix milliseconds, 6 decimals,
    /// comma-separated, no header. No orientation nor GNSS (the engine falls back to its own
    /// attitude filter).
    pub(super) fn plain_csv(&self) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let dir = format!("plain_{}", self.name('-', '_', '-'));
        let mut files = Vec::new();
        let v3 = |text: &mut String, ms: i64, v: Vector3<f64>| {
            let _ = writeln!(
                text,
                "{ms},{},{},{}",
                fixed(v.x, 6),
                fixed(v.y, 6),
                fixed(v.z, 6)
            );
        };
        let (mut acc, mut gyr, mut mag, mut bar) =
            (String::new(), String::new(), String::new(), String::new());
        for (i, s) in imu.iter().enumerate() {
            let ms = self.unix_ms(s.t);
            v3(&mut acc, ms, s.accel);
            if let Some(g) = s.gyro {
                v3(&mut gyr, ms, g);
            }
            if let Some(m) = s.mag {
                v3(&mut mag, ms, m);
            }
            if self.pressure.is_empty() && i % 10 == 0 {
                let _ = writeln!(bar, "{ms},{}", fixed(PRESSURE_HPA, 2));
            }
        }
        for p in &self.pressure {
            let _ = writeln!(bar, "{},{}", self.unix_ms(p.t), fixed(p.hpa, 4));
        }
        for (name, text) in [("acc", acc), ("gyr", gyr), ("mag", mag), ("bar", bar)] {
            // acc.csv always (empty for a walk without samples); the others when they have any.
            if name == "acc" || !text.is_empty() {
                files.push((format!("{dir}/{name}.csv"), text.into_bytes()));
            }
        }
        files
    }
}
