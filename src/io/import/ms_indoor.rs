//! Microsoft Indoor Location Competition 2.0 traces, one of the evaluation data sets of
//! `../shared/data`, read directly. May import: `engine` and `io`.

use super::common::{add_warnings, numbers, set_records, Warnings};
use super::{field_error, file_error, number, Format, Log, Platform, Streams, Waypoint};
use crate::io::lines::each_line;
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::io::BufRead;

/// A Microsoft Indoor Location Competition 2.0 trace: tab-separated `unix_ms TYPE_… values`,
/// `#` header lines. Reads the calibrated accelerometer, gyroscope and magnetometer, the
/// rotation vector (x, y, z with w implied, device → ENU as on every Android phone) and the
/// `TYPE_WAYPOINT` ground truth (plan-frame metres). Wi-Fi, beacons and the rest are ignored.
pub fn read_ms_indoor(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let mut log = Log::new(label, Format::MsIndoor);
    log.platform = Some(Platform::Android);
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    let mut waypoints = Vec::new();
    each_line(r, label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return warnings.push(e),
        };
        if line.starts_with('#') || line.trim().is_empty() {
            return;
        }
        let mut it = line.split('\t');
        let (Some(t), Some(kind)) = (it.next(), it.next()) else {
            warnings.push(file_error(label, n, "expected `time<TAB>TYPE_…`"));
            return;
        };
        let wanted = matches!(
            kind,
            "TYPE_ACCELEROMETER"
                | "TYPE_GYROSCOPE"
                | "TYPE_MAGNETIC_FIELD"
                | "TYPE_ROTATION_VECTOR"
                | "TYPE_WAYPOINT"
        );
        if !wanted {
            return;
        }
        let Some(t) = number(t) else {
            warnings.push(field_error(
                label,
                n,
                1,
                "time_ms",
                format!("not a number: {t:?}"),
            ));
            return;
        };
        let t = t * 1e-3;
        let f: Vec<&str> = it.collect();
        let res = if kind == "TYPE_WAYPOINT" {
            numbers(&f, 0, ["x", "y"], label, n).map(|[x, y]| {
                waypoints.push(Waypoint {
                    t,
                    x_m: x,
                    y_m: y,
                    geo: None,
                    floor: None,
                    height_m: None,
                });
            })
        } else {
            numbers(&f, 0, ["x", "y", "z"], label, n).and_then(|v| {
                let v3 = Vector3::new(v[0], v[1], v[2]);
                match kind {
                    "TYPE_ACCELEROMETER" => s.accel.push((t, v3)),
                    "TYPE_GYROSCOPE" => s.gyro.push((t, v3)),
                    "TYPE_MAGNETIC_FIELD" => s.mag.push((t, v3)),
                    _ => {
                        let w2 = 1.0 - v3.norm_squared();
                        if w2 < -1e-3 {
                            return Err(field_error(
                                label,
                                n,
                                3,
                                "x",
                                "rotation vector longer than 1",
                            ));
                        }
                        let q = Quaternion::new(w2.max(0.0).sqrt(), v[0], v[1], v[2]);
                        s.orientation.push((t, UnitQuaternion::from_quaternion(q)));
                    }
                }
                Ok(())
            })
        };
        if let Err(e) = res {
            warnings.push(e);
        }
    })?;
    if s.accel.is_empty() {
        return Err(file_error(
            label,
            0,
            "no TYPE_ACCELEROMETER samples: not a readable trace",
        ));
    }
    crate::engine::sort::sort_by(&mut waypoints, |a, b| a.t.total_cmp(&b.t));
    log.truth.waypoints = waypoints;
    set_records(&mut log, s, label);
    add_warnings(&mut log, warnings);
    Ok(log)
}
