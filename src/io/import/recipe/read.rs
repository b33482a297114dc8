//! Reading one file by its recipe entry: lines split by the entry's separator, the mapped
//! columns parsed and converted to SI units and the engine's axes.
//! May import: `engine` and `io`.

use super::schema::{Column, Delimiter, FileRule, Sensor, TimeUnit};
use crate::engine::types::GnssFix;
use crate::io::import::common::{
    cell, detect_delimiter, not_a_number, split_into, unit_quaternion, Warnings,
};
use crate::io::import::{field_error, file_error, number};
use crate::io::lines::try_each_line;
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::io::BufRead;
use std::ops::ControlFlow;

/// Rows of each file kept for the preview.
pub const PREVIEW_ROWS: usize = 5;

/// The samples of one file, in SI units (s, m/s², rad/s, µT, hPa), the engine's axes.
#[derive(Debug, Clone)]
pub enum Samples {
    /// Accelerometer (with or without gravity), gravity, gyroscope, magnetometer.
    Vectors(Vec<(f64, Vector3<f64>)>),
    /// Orientation, device → ENU.
    Quaternions(Vec<(f64, UnitQuaternion<f64>)>),
    /// Pressure, hPa.
    Scalars(Vec<(f64, f64)>),
    /// GNSS fixes.
    Fixes(Vec<GnssFix>),
}

impl Samples {
    fn len(&self) -> usize {
        match self {
            Samples::Vectors(v) => v.len(),
            Samples::Quaternions(v) => v.len(),
            Samples::Scalars(v) => v.len(),
            Samples::Fixes(v) => v.len(),
        }
    }
}

/// One file read by its rule.
#[derive(Debug)]
pub struct FileData {
    /// The file's label.
    pub file: String,
    /// What it holds, by the rule.
    pub sensor: Sensor,
    /// Its samples, in file order.
    pub samples: Samples,
    /// The first [`PREVIEW_ROWS`] rows as parsed, SI units, in the order of
    /// [`check::preview_columns`](super::check::preview_columns).
    pub preview: Vec<Vec<f64>>,
    /// Lines skipped.
    pub(crate) warnings: Warnings,
    /// How many samples have a time before the previous one, and the line of the first.
    pub backwards: (u64, Option<u64>),
}

/// Time text in `unit` → seconds. Integers in ms, µs or ns are split into whole seconds and the
/// rest before converting (a Unix time in ns keeps its precision up to the final `f64`).
pub fn time_s(s: &str, unit: TimeUnit) -> Option<f64> {
    let e = unit.exponent();
    let t = s.trim().trim_matches('"').trim();
    if e > 0 {
        if let Ok(n) = t.parse::<i64>() {
            let d = 10i64.pow(e);
            return Some(n.div_euclid(d) as f64 + n.rem_euclid(d) as f64 / d as f64);
        }
    }
    number(t)
        .map(|v| v / unit.per_second())
        .filter(|v| v.is_finite())
}

/// The columns of a rule as 0-based indices, by field name, once the header (if any) is known.
struct Layout {
    fields: Vec<(&'static str, usize)>,
}

impl Layout {
    fn new(
        rule: &FileRule,
        header: Option<&[String]>,
        file: &str,
        line: u64,
    ) -> Result<Self, ParseError> {
        let mut fields = Vec::new();
        for (name, c) in rule.columns.named() {
            let i = match c {
                Column::Number(n) => n - 1,
                Column::Name(want) => {
                    let h = header.unwrap_or(&[]);
                    h.iter()
                        .position(|h| h.trim().eq_ignore_ascii_case(want.trim()))
                        .ok_or_else(|| {
                            let list: Vec<&str> = h.iter().map(String::as_str).take(20).collect();
                            file_error(
                                file,
                                line,
                                format!(
                                    "`{name}`: no column named {want:?} in the header (columns: {})",
                                    list.join(", ")
                                ),
                            )
                        })?
                }
            };
            fields.push((name, i));
        }
        Ok(Layout { fields })
    }

    fn get(&self, name: &str) -> Option<usize> {
        self.fields
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, i)| i)
    }
}

/// Splits a line by the separator (runs of blanks for [`Delimiter::Whitespace`]).
pub(crate) fn split(line: &str, delimiter: Option<u8>, rec: &mut csv::StringRecord) {
    match delimiter {
        Some(d) => split_into(line, d, rec),
        None => {
            rec.clear();
            for f in line.split_whitespace() {
                rec.push_field(f);
            }
        }
    }
}

/// The separator of a file: the rule's, or detected from a line (`None`: whitespace).
pub(crate) fn delimiter_of(d: Delimiter, line: &str) -> Option<u8> {
    match d {
        Delimiter::Comma => Some(b','),
        Delimiter::Tab => Some(b'\t'),
        Delimiter::Semicolon => Some(b';'),
        Delimiter::Whitespace => None,
        Delimiter::Auto => {
            if line.contains(['\t', ';', ',']) {
                Some(detect_delimiter(line))
            } else {
                None
            }
        }
    }
}

/// Reads one file by its rule; at most `limit` samples when given (the page's live preview).
/// A line that does not parse is skipped with a warning naming the file, line, column and
/// field; a file with no good line at all is an error (its first bad line's).
pub fn read_file(
    r: impl BufRead,
    file: &str,
    rule: &FileRule,
    limit: Option<usize>,
) -> Result<FileData, ParseError> {
    let mut data = FileData {
        file: file.to_string(),
        sensor: rule.sensor,
        samples: match rule.sensor {
            Sensor::Orientation => Samples::Quaternions(Vec::new()),
            Sensor::Pressure => Samples::Scalars(Vec::new()),
            Sensor::Gnss => Samples::Fixes(Vec::new()),
            _ => Samples::Vectors(Vec::new()),
        },
        preview: Vec::new(),
        warnings: Warnings::default(),
        backwards: (0, None),
    };
    let factor = rule.value_unit().map_or(1.0, |u| u.factor());
    let mut layout: Option<Layout> = None;
    let mut delimiter: Option<Option<u8>> = None;
    let mut fatal: Option<ParseError> = None;
    let mut rec = csv::StringRecord::new();
    let mut last_t = f64::NEG_INFINITY;
    let mut count = 0usize;
    try_each_line(r, file, |n, line| {
        if n <= u64::from(rule.skip_lines) {
            return ControlFlow::Continue(());
        }
        let line = match line {
            Ok(l) if l.trim().is_empty() => return ControlFlow::Continue(()),
            Ok(l) => l,
            Err(e) => {
                data.warnings.push(e);
                return ControlFlow::Continue(());
            }
        };
        let d = *delimiter.get_or_insert_with(|| delimiter_of(rule.delimiter, line));
        if layout.is_none() {
            let header = if rule.header {
                split(line, d, &mut rec);
                Some(
                    rec.iter()
                        .map(|s| s.trim().trim_matches('"').to_string())
                        .collect::<Vec<_>>(),
                )
            } else {
                None
            };
            match Layout::new(rule, header.as_deref(), file, n) {
                Ok(l) => layout = Some(l),
                Err(e) => {
                    fatal = Some(e);
                    return ControlFlow::Break(());
                }
            }
            if rule.header {
                return ControlFlow::Continue(());
            }
        }
        let Some(lay) = &layout else {
            return ControlFlow::Break(());
        };
        split(line, d, &mut rec);
        match row(&rec, lay, rule, factor, file, n) {
            Ok((t, values, sample)) => {
                if t < last_t {
                    data.backwards.0 += 1;
                    data.backwards.1.get_or_insert(n);
                }
                last_t = t;
                if data.preview.len() < PREVIEW_ROWS {
                    let mut r = vec![t];
                    r.extend(values);
                    data.preview.push(r);
                }
                push(&mut data.samples, sample);
                count += 1;
                if limit.is_some_and(|l| count >= l) {
                    return ControlFlow::Break(());
                }
            }
            Err(e) => data.warnings.push(e),
        }
        ControlFlow::Continue(())
    })?;
    if let Some(e) = fatal {
        return Err(e);
    }
    if data.samples.len() == 0 {
        return Err(match data.warnings.first() {
            Some(e) => e.clone(),
            None => file_error(file, 0, "no data rows"),
        });
    }
    Ok(data)
}

/// One parsed sample, before it is stored.
enum Sample {
    V(f64, Vector3<f64>),
    Q(f64, UnitQuaternion<f64>),
    S(f64, f64),
    F(GnssFix),
}

fn push(samples: &mut Samples, s: Sample) {
    match (samples, s) {
        (Samples::Vectors(v), Sample::V(t, x)) => v.push((t, x)),
        (Samples::Quaternions(v), Sample::Q(t, q)) => v.push((t, q)),
        (Samples::Scalars(v), Sample::S(t, p)) => v.push((t, p)),
        (Samples::Fixes(v), Sample::F(f)) => v.push(f),
        _ => {}
    }
}

/// Parses one row: its time (s), its values as the preview shows them, and the sample.
fn row(
    rec: &csv::StringRecord,
    lay: &Layout,
    rule: &FileRule,
    factor: f64,
    file: &str,
    line: u64,
) -> Result<(f64, Vec<f64>, Sample), ParseError> {
    let num = |name: &str| -> Result<f64, ParseError> {
        let i = lay.get(name).unwrap_or(usize::MAX);
        cell(rec, i, name, file, line)
    };
    let opt = |name: &str| -> Result<Option<f64>, ParseError> {
        match lay.get(name) {
            None => Ok(None),
            Some(i) => match rec.get(i).map(str::trim) {
                None | Some("") => Ok(None),
                Some(s) => number(s)
                    .map(Some)
                    .ok_or_else(|| field_error(file, line, i + 1, name, not_a_number(s))),
            },
        }
    };
    let ti = lay.get("t").unwrap_or(usize::MAX);
    let ts = rec
        .get(ti)
        .ok_or_else(|| field_error(file, line, ti + 1, "t", "missing"))?;
    let t = time_s(ts, rule.time_unit)
        .ok_or_else(|| field_error(file, line, ti + 1, "t", not_a_number(ts)))?;
    Ok(match rule.sensor {
        Sensor::Orientation => {
            let [w, x, y, z] = [num("w")?, num("x")?, num("y")?, num("z")?];
            let q = unit_quaternion(w, x, y, z).ok_or_else(|| {
                let n = Quaternion::new(w, x, y, z).norm();
                field_error(
                    file,
                    line,
                    lay.get("w").unwrap_or(0) + 1,
                    "w",
                    format!("quaternion norm is {n:.4}, not 1"),
                )
            })?;
            let c = q.quaternion();
            (t, vec![c.w, c.i, c.j, c.k], Sample::Q(t, q))
        }
        Sensor::Pressure => {
            let p = num("value")? * factor;
            (t, vec![p], Sample::S(t, p))
        }
        Sensor::Gnss => {
            let fix = GnssFix {
                t,
                lat_deg: num("lat")?,
                lon_deg: num("lon")?,
                h_accuracy_m: num("accuracy")?,
                altitude_m: opt("altitude")?,
                speed_mps: opt("speed")?.filter(|v| *v >= 0.0),
                bearing_deg: opt("bearing")?.filter(|v| *v >= 0.0),
            };
            fix.check().map_err(|e| {
                field_error(
                    file,
                    line,
                    lay.get("lat").unwrap_or(0) + 1,
                    "lat",
                    format!("invalid fix: {e}"),
                )
            })?;
            (
                t,
                vec![fix.lat_deg, fix.lon_deg, fix.h_accuracy_m],
                Sample::F(fix),
            )
        }
        _ => {
            let raw = [num("x")? * factor, num("y")? * factor, num("z")? * factor];
            let v = Vector3::from_fn(|i, _| {
                let (k, sign) = rule.axis(i);
                sign * raw[k]
            });
            if !v.iter().all(|c| c.is_finite()) {
                return Err(file_error(
                    file,
                    line,
                    "value too large after unit conversion",
                ));
            }
            (t, vec![v.x, v.y, v.z], Sample::V(t, v))
        }
    })
}
