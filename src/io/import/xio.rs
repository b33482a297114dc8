//! The x-io foot-mounted CSVs (Gait-Tracking), one of the evaluation data sets of
//! `../shared/data`, read directly. May import: `engine` and `io`.

use super::common::{add_warnings, set_records, Warnings};
use super::{field_error, file_error, number, Format, Log, Streams};
use crate::engine::orientation::G0;
use crate::io::lines::each_line;
use crate::io::ParseError;
use nalgebra::Vector3;
use std::io::BufRead;

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
