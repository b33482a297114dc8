//! A UbiComp 2013 walk folder of a simulated walk, with its step count and walk window, as
//! [`crate::io::import::ubicomp13`] reads it. May import: `engine` and `io`.

use super::{java_float, Walk};
use crate::sim::Simulation;
use nalgebra::Vector3;
use std::fmt::Write as _;

impl Walk<'_> {
    /// The folder `p0.1_Female_20-29_170-179cm_Trousers_front_pocket/` (person and run, gender,
    /// age, height, clothing, placement): `acc.csv` (m/s², Android sign), `gyr.csv` (rad/s) and
    /// `mag.csv` (µT), each line `t_s,x,y,z` with no header, the time the Android event clock
    /// (ns since boot, from [`super::BOOT_NS`]) in seconds with 9 decimals, the values as Java
    /// prints floats; and `truth.json`: the number of true steps, and the walk window
    /// `walk_start_s`, `walk_end_s` from the start of the first moving segment of the walk to
    /// the end of the last one (the whole recording when nothing moves), with the sample
    /// numbers of `acc.csv` (0-based) at those times, the placement and the person.
    pub(super) fn ubicomp13(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let dir = "p0.1_Female_20-29_170-179cm_Trousers_front_pocket";
        let time = |t: f64| {
            let ns = self.boot_ns(t);
            format!(
                "{}.{:09}",
                ns.div_euclid(1_000_000_000),
                ns.rem_euclid(1_000_000_000)
            )
        };
        let line = |text: &mut String, t: f64, v: Vector3<f64>| {
            let _ = writeln!(
                text,
                "{},{},{},{}",
                time(t),
                java_float(v.x),
                java_float(v.y),
                java_float(v.z)
            );
        };
        let (mut acc, mut gyr, mut mag) = (String::new(), String::new(), String::new());
        for s in &imu {
            line(&mut acc, s.t, s.accel);
            if let Some(g) = s.gyro {
                line(&mut gyr, s.t, g);
            }
            if let Some(m) = s.mag {
                line(&mut mag, s.t, m);
            }
        }
        let moving: Vec<&(f64, f64, crate::sim::Gait)> = sim
            .truth
            .segments
            .iter()
            .filter(|s| s.2.moving() && s.0.is_finite() && s.1.is_finite())
            .collect();
        let (start, end) = match (moving.first(), moving.last()) {
            (Some(a), Some(b)) => (a.0, b.1),
            _ => (
                imu.first().map_or(self.start, |s| s.t),
                imu.last().map_or(self.start, |s| s.t),
            ),
        };
        // Correctly rounded, so that the JSON shows the 9 decimals of the ns clock.
        let clock = |t: f64| self.boot_ns(t) as f64 / 1e9;
        let sample = |t: f64| imu.partition_point(|s| s.t < t);
        let truth = serde_json::json!({
            "steps": sim.truth.steps.len(),
            "walk_start_s": clock(start),
            "walk_end_s": clock(end),
            "walk_start_sample": sample(start),
            "walk_end_sample": sample(end),
            "placement": "front pocket",
            "person": "p0",
            "run": "p0.1",
            "gender": "Female",
            "age": "20-29",
            "height_cm": "170-179",
            "pace": "simulated",
            "units": {
                "acc": "m/s^2 (with gravity, Android axes)",
                "gyr": "rad/s",
                "mag": "uT"
            },
            "clock": "Android SensorEvent timestamp (ns since boot) in seconds",
            "source": "pdr simulate"
        });
        let json = serde_json::to_string_pretty(&truth).unwrap_or_default() + "\n";
        let mut files = vec![(format!("{dir}/acc.csv"), acc.into_bytes())];
        for (name, text) in [("gyr.csv", gyr), ("mag.csv", mag)] {
            if !text.is_empty() {
                files.push((format!("{dir}/{name}"), text.into_bytes()));
            }
        }
        files.push((format!("{dir}/truth.json"), json.into_bytes()));
        files
    }
}
