//! The evaluation data sets of `../shared/data`, read directly: Oxford Step Counter trace
//! folders, Microsoft Indoor Location Competition 2.0 traces and the x-io foot-mounted CSVs.

use super::common::{add_warnings, set_records, Warnings};
use super::{
    field_error, file_error, fileset, number, FileSet, Format, Log, Platform, Streams, TrueStep,
    Waypoint,
};
use crate::engine::orientation::G0;
use crate::io::lines::each_line;
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::io::BufRead;

/// The files of an Oxford trace folder that the reader consumes.
pub const OXFORD_FILES: [&str; 3] = ["accelerometer.csv", "stepcounter.csv", "stats.csv"];

/// Parses fields `[from, from + N)` of a split line as numbers, naming the first bad one.
fn numbers<const N: usize>(
    fields: &[&str],
    from: usize,
    names: [&str; N],
    file: &str,
    line: u64,
) -> Result<[f64; N], ParseError> {
    let mut out = [0.0; N];
    for (k, name) in names.iter().enumerate() {
        let col = from + k;
        let s = fields
            .get(col)
            .ok_or_else(|| field_error(file, line, col + 1, name, "missing"))?;
        out[k] = number(s).ok_or_else(|| {
            field_error(file, line, col + 1, name, format!("not a number: {s:?}"))
        })?;
    }
    Ok(out)
}

/// An Oxford Step Counter trace folder (`dir` ends with `/` or is empty): `accelerometer.csv`
/// (time ns since boot, sensor code, ax, ay, az in m/s², Android axes) and the truth device's
/// `stepcounter.csv` (time ns, one 0/1 contact column per foot; each 0→1 change is a step).
pub fn read_oxford(set: &mut dyn FileSet, dir: &str) -> Result<Log, ParseError> {
    let source = set.label(dir.trim_end_matches('/'));
    let mut log = Log::new(source, Format::OxfordSteps);
    log.platform = Some(Platform::Android);
    // `<Phone>_<Walker>_<Surface>_<Position>_<n>`.
    log.group = fileset::base(dir.trim_end_matches('/'))
        .split('_')
        .nth(3)
        .map(str::to_string);
    let name = format!("{dir}accelerometer.csv");
    let label = set.label(&name);
    let mut streams = Streams::default();
    let reader = set
        .open(&name)
        .map_err(|e| file_error(&label, 0, e.to_string()))?;
    let mut warnings = Warnings::default();
    each_line(reader, &label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return warnings.push(e),
        };
        if line.trim().is_empty() {
            return;
        }
        let f: Vec<&str> = line.split(',').collect();
        match numbers(&f, 0, ["time_ns"], &label, n)
            .and_then(|[t]| Ok((t, numbers(&f, 2, ["ax", "ay", "az"], &label, n)?)))
        {
            Ok((t, a)) => streams
                .accel
                .push((t * 1e-9, Vector3::new(a[0], a[1], a[2]))),
            Err(e) => warnings.push(e),
        }
    })?;
    if streams.accel.is_empty() {
        return Err(file_error(&label, 0, "no accelerometer samples"));
    }
    let name = format!("{dir}stepcounter.csv");
    let label = set.label(&name);
    let reader = set
        .open(&name)
        .map_err(|e| file_error(&label, 0, e.to_string()))?;
    let mut prev: Option<[f64; 2]> = None;
    let mut events = Vec::new();
    each_line(reader, &label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return warnings.push(e),
        };
        if line.trim().is_empty() {
            return;
        }
        let f: Vec<&str> = line.split(',').collect();
        match numbers(&f, 0, ["time_ns", "left", "right"], &label, n) {
            Ok([t, l, r]) => {
                let c = [l, r];
                if let Some(p) = prev {
                    for foot in 0..2u8 {
                        let k = usize::from(foot);
                        if p[k] < 0.5 && c[k] >= 0.5 {
                            events.push(TrueStep {
                                t: t * 1e-9,
                                foot: Some(foot),
                            });
                        }
                    }
                }
                prev = Some(c);
            }
            Err(e) => warnings.push(e),
        }
    })?;
    events.sort_by(|a, b| a.t.total_cmp(&b.t));
    log.truth.steps = Some(events.len() as u64);
    log.truth.step_events = events;
    set_records(&mut log, streams, &label);
    add_warnings(&mut log, warnings);
    Ok(log)
}

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
    waypoints.sort_by(|a, b| a.t.total_cmp(&b.t));
    log.truth.waypoints = waypoints;
    set_records(&mut log, s, label);
    add_warnings(&mut log, warnings);
    Ok(log)
}

/// The x-io Gait-Tracking CSV: `Time (s)`, gyroscope in deg/s, accelerometer in g (specific
/// force, Android sign). The walker ends where they started (loop closure).
pub fn read_xio(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let mut log = Log::new(label, Format::XioFoot);
    log.truth.loop_closure = true;
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    const NAMES: [&str; 7] = [
        "Time (s)",
        "Gyroscope X (deg/s)",
        "Gyroscope Y (deg/s)",
        "Gyroscope Z (deg/s)",
        "Accelerometer X (g)",
        "Accelerometer Y (g)",
        "Accelerometer Z (g)",
    ];
    let mut cols: Option<[usize; 7]> = None;
    let mut fatal = None;
    each_line(r, label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return warnings.push(e),
        };
        if line.trim().is_empty() || fatal.is_some() {
            return;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        let Some(cols) = cols else {
            let mut c = [0; 7];
            for (k, name) in NAMES.iter().enumerate() {
                match f.iter().position(|h| h == name) {
                    Some(i) => c[k] = i,
                    None => {
                        fatal = Some(file_error(label, n, format!("column `{name}` missing")));
                        return;
                    }
                }
            }
            cols = Some(c);
            return;
        };
        let mut v = [0.0; 7];
        for (k, &c) in cols.iter().enumerate() {
            match f.get(c).and_then(|x| number(x)) {
                Some(x) => v[k] = x,
                None => {
                    warnings.push(field_error(label, n, c + 1, NAMES[k], "not a number"));
                    return;
                }
            }
        }
        let d = std::f64::consts::PI / 180.0;
        s.gyro.push((v[0], Vector3::new(v[1], v[2], v[3]) * d));
        s.accel.push((v[0], Vector3::new(v[4], v[5], v[6]) * G0));
    })?;
    if let Some(e) = fatal {
        return Err(e);
    }
    if s.accel.is_empty() {
        return Err(warnings
            .first()
            .cloned()
            .unwrap_or_else(|| file_error(label, 0, "no samples")));
    }
    set_records(&mut log, s, label);
    add_warnings(&mut log, warnings);
    Ok(log)
}
