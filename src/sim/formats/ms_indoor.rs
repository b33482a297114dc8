//! A Microsoft Indoor Location 2.0 trace of a simulated walk, with `TYPE_WAYPOINT` truth, as
//! [`crate::io::import::ms_indoor`] reads it. May import: `engine` and `io`.

use super::{canonical, java_float, waypoints, Item, Walk};
use crate::sim::Simulation;
use std::fmt::Write as _;

impl Walk<'_> {
    /// A Microsoft Indoor Location Competition 2.0 trace: `#\t` header lines (start time, site,
    /// phone, sensors), then tab-separated `unix_ms TYPE_… values accuracy` lines in time order
    /// (values as Java prints floats; the rotation vector's x, y, z with w ≥ 0 implied), the
    /// `TYPE_WAYPOINT` truth in metres east and north of the start, and `#\tendTime`.
    pub(super) fn ms_indoor(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
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
        crate::engine::sort::sort_by_key(&mut lines, |l| l.0);
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
}

const MS_INDOOR_SENSORS: &str = "#\tBrand:pdr\tModel:simulator\tAndroidName:10\tAPILevel:29\t\n\
#\ttype:1\tname:Accelerometer\tversion:1\tvendor:pdr\tresolution:0.0023956299\tpower:0.15\tmaximumRange:78.4532\n\
#\ttype:4\tname:Gyroscope\tversion:1\tvendor:pdr\tresolution:0.0012217305\tpower:0.9\tmaximumRange:34.906586\n\
#\ttype:2\tname:Magnetometer\tversion:1\tvendor:pdr\tresolution:0.15\tpower:1.1\tmaximumRange:4912.0503\n\
#\ttype:11\tname:Rotation Vector\tversion:1\tvendor:pdr\tresolution:5.9604645E-8\tpower:1.1\tmaximumRange:1.0\n";
