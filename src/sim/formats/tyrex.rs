//! A TyrEx recording folder of a simulated walk, Android or iOS layout, with the motion-capture
//! truth, as [`crate::io::import::tyrex`] reads it. May import: `engine` and `io`.

use super::{canonical, enu_to_core_motion, fixed, java_float, Walk, BOOT_NS};
use crate::engine::orientation::G0;
use crate::engine::types::ImuSample;
use crate::io::import::Platform;
use crate::sim::Simulation;
use nalgebra::{Quaternion, Vector3};
use std::fmt::Write as _;

/// Motion-capture rate of `truth.csv`, Hz.
pub const TRUTH_RATE_HZ: f64 = 60.0;

/// Height of the phone in the pocket above the floor, m (`truth.csv`'s z on level ground).
pub const POCKET_HEIGHT_M: f64 = 0.9;

/// Heading accuracy written in the rotation vector's last column, rad (10°, what the Nexus 5
/// of the data set reports).
const HEADING_ACCURACY_RAD: f64 = 0.174_532_92;

/// The phone's clock on iOS at the start of the recording, s since boot.
pub fn ios_boot_clock_s() -> f64 {
    BOOT_NS as f64 * 1e-9
}

impl Walk<'_> {
    /// A TyrEx recording folder named `Sim_<Phone>_NoDist_FrontPocket` (walker, phone, no
    /// magnetic disturbance, carrying mode).
    ///
    /// - Android (`Sim_Nexus5_…`): time in seconds since the start of the recording with 9
    ///   decimals, values as Java prints floats: `accelerometer.txt` (m/s², Android sign),
    ///   `gyroscope-calibrated.txt` (rad/s), `magnetometer-calibrated.txt` (µT),
    ///   `rotation-vector.txt` (`x y z w` with w ≥ 0, then the heading accuracy), and
    ///   `record.properties` with the device and the start as Unix seconds.
    /// - iOS (`Sim_iPhone5_…`): time since boot (starting at [`BOOT_NS`]) and values with 4
    ///   decimals as the iPhone app writes them: `accelerometer.txt` (g, Core Motion's sign),
    ///   `gyroscope.txt` (rad/s), `magnetometer-calibrated.txt` (µT, then a calibration
    ///   accuracy of 2), `attitude.txt` (`w x y z`, device → Core Motion's x-north, z-up
    ///   reference) and `description.txt` with the boot clock at the start.
    ///
    /// `truth.csv`: `t_s,x_m,y_m,z_m,qw,qx,qy,qz` every 1/[`TRUTH_RATE_HZ`] s over the true path,
    /// on the phone's clock (4 decimals): x and y the true position east and north (m, 5
    /// decimals), z [`POCKET_HEIGHT_M`] above the ground under the walker, q the phone's
    /// orientation (device → the room frame, here ENU) of the latest IMU sample (identity before
    /// the first one). The cameras never lose the phone: the file has no holes.
    pub(super) fn tyrex(&self, sim: &Simulation, platform: Platform) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let ios = platform == Platform::Ios;
        let dir = if ios {
            "Sim_iPhone5_NoDist_FrontPocket"
        } else {
            "Sim_Nexus5_NoDist_FrontPocket"
        };
        let time = |t: f64| {
            if ios {
                fixed(ios_boot_clock_s() + self.rel(t), 4)
            } else {
                fixed(self.rel(t), 9)
            }
        };
        let num = |v: f64| if ios { fixed(v, 4) } else { java_float(v) };
        let line = |text: &mut String, t: f64, v: Vector3<f64>, extra: &str| {
            let _ = writeln!(
                text,
                "{} {} {} {}{extra}",
                time(t),
                num(v.x),
                num(v.y),
                num(v.z)
            );
        };
        let (mut acc, mut gyr, mut mag, mut ori) =
            (String::new(), String::new(), String::new(), String::new());
        let to_reference = enu_to_core_motion();
        for s in &imu {
            let a = if ios { -s.accel / G0 } else { s.accel };
            line(&mut acc, s.t, a, "");
            if let Some(g) = s.gyro {
                line(&mut gyr, s.t, g, "");
            }
            if let Some(m) = s.mag {
                line(&mut mag, s.t, m, if ios { " 2" } else { "" });
            }
            if let Some(q) = s.orientation {
                if ios {
                    let c = canonical(&(to_reference * q));
                    let _ = writeln!(
                        ori,
                        "{} {} {} {} {}",
                        time(s.t),
                        num(c.w),
                        num(c.i),
                        num(c.j),
                        num(c.k)
                    );
                } else {
                    let c = canonical(&q);
                    let _ = writeln!(
                        ori,
                        "{} {} {} {} {} {}",
                        time(s.t),
                        num(c.i),
                        num(c.j),
                        num(c.k),
                        num(c.w),
                        java_float(HEADING_ACCURACY_RAD)
                    );
                }
            }
        }
        let file = |name: &str, text: String| (format!("{dir}/{name}"), text.into_bytes());
        let mut files = vec![file("accelerometer.txt", acc)];
        if ios {
            files.push(file("gyroscope.txt", gyr));
            files.push(file("magnetometer-calibrated.txt", mag));
            files.push(file("attitude.txt", ori));
            files.push(file(
                "description.txt",
                format!("[Time]\nBootTime = {}", fixed(ios_boot_clock_s(), 4)),
            ));
        } else {
            files.push(file("gyroscope-calibrated.txt", gyr));
            files.push(file("magnetometer-calibrated.txt", mag));
            files.push(file("rotation-vector.txt", ori));
            files.push(file(
                "record.properties",
                format!(
                    "[Device]\nManufacturer = pdr\nModel = simulator\nOSVersion = 23\n\
                     ID = 0000000000000000\n\n[Time]\nStartTime = {}",
                    self.unix_start_ns.div_euclid(1_000_000_000)
                ),
            ));
        }
        files.push(file("truth.csv", self.tyrex_truth(sim, &imu, &time)));
        crate::engine::sort::sort_by(&mut files, |a, b| a.0.cmp(&b.0));
        files
    }

    /// `truth.csv` (see [`Walk::tyrex`]).
    fn tyrex_truth(
        &self,
        sim: &Simulation,
        imu: &[&ImuSample],
        time: &dyn Fn(f64) -> String,
    ) -> String {
        let mut out = String::from("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n");
        let path = &sim.truth.path;
        let (Some(&first), Some(&last)) = (path.first(), path.last()) else {
            return out;
        };
        if !(first.0.is_finite() && last.0.is_finite()) {
            return out;
        }
        let mut next = 0usize;
        for k in 0u64.. {
            let t = first.0 + k as f64 / TRUTH_RATE_HZ;
            if t > last.0 + 1e-9 {
                break;
            }
            let (e, n) = sim.truth.position_at(t);
            let z = POCKET_HEIGHT_M + sim.truth.height_at(t);
            while next < imu.len() && imu[next].t <= t {
                next += 1;
            }
            let q = next
                .checked_sub(1)
                .and_then(|i| imu[i].orientation)
                .map_or(Quaternion::identity(), |q| canonical(&q));
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{}",
                time(t),
                fixed(e, 5),
                fixed(n, 5),
                fixed(z, 5),
                fixed(q.w, 6),
                fixed(q.i, 6),
                fixed(q.j, 6),
                fixed(q.k, 6)
            );
        }
        out
    }
}
