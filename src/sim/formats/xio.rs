//! An x-io Gait-Tracking CSV of a simulated walk, as [`crate::io::import::xio`] reads it.
//! May import: `engine` and `io`.

use super::{fixed, Walk};
use crate::engine::orientation::G0;
use std::fmt::Write as _;

impl Walk<'_> {
    /// x-io Gait-Tracking's `sensor_data.csv`: time in seconds since the start, gyroscope in
    /// deg/s, accelerometer in g (Android sign), 6 decimals. A sample without a gyroscope value
    /// is not written (the format needs all seven numbers). A walk with a foot-mounted IMU
    /// (`Record::Foot`, [`crate::sim::foot`]) writes that one, as the x-io sensor is on a foot.
    pub(super) fn xio(&self) -> Vec<(String, Vec<u8>)> {
        let mut out = String::from(
            "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),\
             Accelerometer X (g),Accelerometer Y (g),Accelerometer Z (g)\n",
        );
        let samples = if self.foot.is_empty() {
            self.imu()
        } else {
            self.foot.clone()
        };
        for s in samples {
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
