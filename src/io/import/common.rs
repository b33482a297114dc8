//! Text helpers shared by the readers: bounded lines, CSV fields, numbers, capped warnings.
//! May import: `engine` and `io`.
//!
//! Every reader goes through [`each_line`] or [`Table`], which never hold more than
//! [`MAX_LINE`](crate::io::lines::MAX_LINE) bytes of one line, and through [`Warnings`], which
//! keeps the first [`MAX_WARNINGS`] skipped lines and only counts the rest. So a file of any size,
//! even binary junk without a line end, is read in bounded memory (besides the samples it yields).

use super::{field_error, file_error, fileset, number, FileSet, Log, Streams};
use crate::engine::types::{PressureSample, PRESSURE_RANGE_HPA};
use crate::io::lines::{each_line, read_line_capped, MAX_WARNINGS};
use crate::io::ParseError;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::io::BufRead;

/// Skipped lines of one file or log: the first [`MAX_WARNINGS`] kept, all counted.
#[derive(Debug, Default)]
pub(crate) struct Warnings {
    kept: Vec<ParseError>,
    count: u64,
}

impl Warnings {
    /// Records one skipped line.
    pub fn push(&mut self, e: ParseError) {
        self.count += 1;
        if self.kept.len() < MAX_WARNINGS {
            self.kept.push(e);
        }
    }

    /// Takes over another set.
    pub fn extend(&mut self, other: Warnings) {
        let extra = other.count - other.kept.len() as u64;
        for e in other.kept {
            self.push(e);
        }
        self.count += extra;
    }

    /// The first warning kept that satisfies `pred`.
    pub fn find(&self, pred: impl Fn(&ParseError) -> bool) -> Option<&ParseError> {
        self.kept.iter().find(|e| pred(e))
    }

    /// The first warning kept.
    pub fn first(&self) -> Option<&ParseError> {
        self.kept.first()
    }

    /// How many lines were skipped.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The warnings kept (the first [`MAX_WARNINGS`]).
    pub fn kept(&self) -> &[ParseError] {
        &self.kept
    }
}

/// Picks the field separator of a header line: the most frequent of tab, semicolon and comma
/// outside double quotes (comma when none occurs).
pub(crate) fn detect_delimiter(header: &str) -> u8 {
    let mut counts = [0usize; 3];
    let mut quoted = false;
    for b in header.bytes() {
        match b {
            b'"' => quoted = !quoted,
            b'\t' if !quoted => counts[0] += 1,
            b';' if !quoted => counts[1] += 1,
            b',' if !quoted => counts[2] += 1,
            _ => {}
        }
    }
    if counts[0] > 0 && counts[0] >= counts[1] && counts[0] >= counts[2] {
        b'\t'
    } else if counts[1] > counts[2] {
        b';'
    } else {
        b','
    }
}

/// Splits one line into fields with the CSV rules for one line (fields separated by
/// `delimiter`; a field in double quotes may hold the delimiter, `""` is a quote), trimmed.
/// Records never span lines here: no format we read needs it, and a stray quote in a damaged
/// file must not swallow the rest of it.
pub(crate) fn split_line(line: &str, delimiter: u8) -> Vec<String> {
    let mut rec = csv::StringRecord::new();
    split_into(line, delimiter, &mut rec);
    rec.iter().map(|s| s.trim().to_string()).collect()
}

/// [`split_line`] into a reused record (fields not trimmed).
pub(crate) fn split_into(line: &str, delimiter: u8, rec: &mut csv::StringRecord) {
    rec.clear();
    let d = delimiter as char;
    // Almost every line of a sensor log has no quote: split it at once (a third of a Sensor
    // Logger folder's reading time went to the character loop below).
    if !line.contains('"') {
        for f in line.split(d) {
            rec.push_field(f);
        }
        return;
    }
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    loop {
        field.clear();
        let quoted = chars.peek() == Some(&'"');
        if quoted {
            chars.next();
            while let Some(c) = chars.next() {
                if c == '"' {
                    if chars.peek() == Some(&'"') {
                        chars.next();
                        field.push('"');
                    } else {
                        break;
                    }
                } else {
                    field.push(c);
                }
            }
        }
        // Up to the next delimiter (after a closing quote, whatever follows it).
        let mut ended = true;
        for c in chars.by_ref() {
            if c == d {
                ended = false;
                break;
            }
            field.push(c);
        }
        rec.push_field(&field);
        if ended {
            return;
        }
    }
}

/// A CSV file with a header line, read record by record (one record per line, lines bounded
/// by [`MAX_LINE`](crate::io::lines::MAX_LINE)).
pub(crate) struct Table<R: BufRead> {
    /// The header fields, trimmed, quotes removed.
    pub header: Vec<String>,
    /// The header fields in lower case, for matching by name.
    pub lower: Vec<String>,
    /// 1-based line number of the header.
    pub header_line: u64,
    delimiter: u8,
    r: R,
}

impl<R: BufRead> Table<R> {
    /// Reads the header (the first non-empty line) and prepares the records after it. The
    /// separator is detected from the header when `delimiter` is `None`. `Ok(None)` for a file
    /// without any non-empty line.
    pub fn open(mut r: R, file: &str, delimiter: Option<u8>) -> Result<Option<Self>, ParseError> {
        let mut buf = Vec::new();
        let mut n = 0u64;
        let header = loop {
            let long = read_line_capped(&mut r, &mut buf)
                .map_err(|e| file_error(file, n + 1, format!("cannot read: {e}")))?;
            let Some(long) = long else {
                return Ok(None);
            };
            n += 1;
            if long {
                return Err(file_error(file, n, "header line too long: not a CSV file"));
            }
            let line = std::str::from_utf8(&buf)
                .map_err(|_| file_error(file, n, "header line is not UTF-8 text"))?;
            let line = line.trim_start_matches('\u{feff}').trim();
            if !line.is_empty() {
                break line.to_string();
            }
        };
        let delimiter = delimiter.unwrap_or_else(|| detect_delimiter(&header));
        let header = split_line(&header, delimiter);
        let lower = header.iter().map(|h| h.to_lowercase()).collect();
        Ok(Some(Table {
            header,
            lower,
            header_line: n,
            delimiter,
            r,
        }))
    }

    /// The index of the first column whose lower-case name satisfies `pred`.
    pub fn col(&self, pred: impl Fn(&str) -> bool) -> Option<usize> {
        self.lower.iter().position(|h| pred(h))
    }

    /// The index of the column named `name` (any case).
    pub fn named(&self, name: &str) -> Option<usize> {
        let name = name.to_lowercase();
        self.col(|h| h == name)
    }

    /// Calls `f(line, record)` for every non-empty record. Lines that are not UTF-8 text or are
    /// too long become warnings; a read failure of the input is fatal.
    pub fn rows(
        &mut self,
        file: &str,
        warnings: &mut Warnings,
        mut f: impl FnMut(u64, &csv::StringRecord),
    ) -> Result<(), ParseError> {
        let mut rec = csv::StringRecord::new();
        let (offset, delimiter) = (self.header_line, self.delimiter);
        each_line(&mut self.r, file, |n, line| match line {
            Ok(line) if !line.trim().is_empty() => {
                split_into(line, delimiter, &mut rec);
                f(offset + n, &rec);
            }
            Ok(_) => {}
            Err(mut e) => {
                e.line += offset;
                warnings.push(e);
            }
        })
    }
}

/// The fields of one line of a log with one record a line, with what errors name: its file and
/// line.
pub(crate) struct Fields<'a> {
    /// The fields, trimmed.
    pub fields: Vec<&'a str>,
    /// The file's label.
    pub file: &'a str,
    /// 1-based line number.
    pub line: u64,
}

impl Fields<'_> {
    /// Field `i` (0-based) as a number, named `name` in the error.
    pub fn num(&self, i: usize, name: &str) -> Result<f64, ParseError> {
        let s = self
            .fields
            .get(i)
            .ok_or_else(|| self.error(i + 1, name, "missing"))?;
        number(s).ok_or_else(|| self.error(i + 1, name, not_a_number(s)))
    }

    /// An error on column `col` (1-based) named `name` of this line.
    pub fn error(&self, col: usize, name: &str, message: impl Into<String>) -> ParseError {
        field_error(self.file, self.line, col, name, message)
    }
}

/// Parses fields `[from, from + N)` of a split line as numbers, naming the first bad one.
pub(crate) fn numbers<const N: usize>(
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

/// Reads a file of records, one per line: its fields, split at `sep` (at runs of whitespace
/// when `None`), handed to `f(file label, line, fields)`. Empty lines are skipped; an unreadable
/// line, or an `Err` from `f`, is a warning. A file that cannot be opened is an error naming it.
/// Lines are streamed ([`each_line`]): memory stays bounded whatever the file's size.
pub(crate) fn read_lines(
    set: &mut dyn FileSet,
    name: &str,
    sep: Option<char>,
    warnings: &mut Warnings,
    mut f: impl FnMut(&str, u64, &[&str]) -> Result<(), ParseError>,
) -> Result<(), ParseError> {
    let label = set.label(name);
    let reader = open(set, name, &label)?;
    each_record(reader, &label, sep, warnings, |n, fields| {
        f(&label, n, fields)
    })
}

/// Opens file `name` of a set, labelled `label`; when it cannot be, an error naming it.
pub(crate) fn open<'a>(
    set: &'a mut dyn FileSet,
    name: &str,
    label: &str,
) -> Result<Box<dyn BufRead + 'a>, ParseError> {
    set.open(name)
        .map_err(|e| file_error(label, 0, format!("cannot open: {e}")))
}

/// [`read_lines`] of an open file labelled `label`: each non-empty line's fields handed to
/// `f(line, fields)`; an unreadable line, or an `Err` from `f`, is a warning.
pub(crate) fn each_record(
    reader: impl BufRead,
    label: &str,
    sep: Option<char>,
    warnings: &mut Warnings,
    mut f: impl FnMut(u64, &[&str]) -> Result<(), ParseError>,
) -> Result<(), ParseError> {
    each_line(reader, label, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) => return warnings.push(e),
        };
        if line.trim().is_empty() {
            return;
        }
        let fields: Vec<&str> = match sep {
            Some(c) => line.split(c).collect(),
            None => line.split_whitespace().collect(),
        };
        if let Err(e) = f(n, &fields) {
            warnings.push(e);
        }
    })
}

/// [`read_lines`] of samples: each line's first `N` fields as numbers named `names` (fields
/// after them are ignored), handed to `f(file label, line, values)`; a bad number is a warning
/// naming file, line, column and field.
pub(crate) fn read_samples<const N: usize>(
    set: &mut dyn FileSet,
    name: &str,
    sep: Option<char>,
    names: [&str; N],
    warnings: &mut Warnings,
    mut f: impl FnMut(&str, u64, [f64; N]) -> Result<(), ParseError>,
) -> Result<(), ParseError> {
    read_lines(set, name, sep, warnings, |label, n, fields| {
        numbers(fields, 0, names, label, n).and_then(|v| f(label, n, v))
    })
}

/// Rz(+90°): Core Motion's attitude reference (x magnetic north, y west, z up) → East-North-Up,
/// for iOS attitudes (device → reference) read as device → ENU.
pub(crate) fn core_motion_to_enu() -> UnitQuaternion<f64> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(h, 0.0, 0.0, h))
}

/// The name of a recording folder `dir` (ending with `/`, or empty for the top of the set) for
/// reports: the folder's label without its trailing `/`, or `file`'s label when the folder has
/// none (files given on their own, as in an upload).
pub(crate) fn folder_label(set: &dyn FileSet, dir: &str, file: &str) -> String {
    let l = set.label(dir.trim_end_matches('/'));
    let l = l.trim_end_matches('/');
    if l.is_empty() {
        set.label(file)
    } else {
        l.to_string()
    }
}

/// The folder's own name (the last part of [`folder_label`]), empty when it has none.
pub(crate) fn folder_name(set: &dyn FileSet, dir: &str) -> String {
    let l = set.label(dir.trim_end_matches('/'));
    fileset::base(l.trim_end_matches('/')).to_string()
}

/// The file of folder `dir` whose base name is `base` (any case), among `names`.
pub(crate) fn file_in(names: &[String], dir: &str, base: &str) -> Option<String> {
    names
        .iter()
        .find(|n| fileset::parent(n) == dir && fileset::base(n).eq_ignore_ascii_case(base))
        .cloned()
}

/// Parses field `col` of a record as a number, naming the column on failure.
pub(crate) fn cell(
    rec: &csv::StringRecord,
    col: usize,
    name: &str,
    file: &str,
    line: u64,
) -> Result<f64, ParseError> {
    let s = rec
        .get(col)
        .ok_or_else(|| field_error(file, line, col + 1, name, "missing"))?;
    number(s).ok_or_else(|| field_error(file, line, col + 1, name, not_a_number(s)))
}

/// "not a number: …" with the text cut to a readable length.
pub(crate) fn not_a_number(s: &str) -> String {
    let s: String = s.trim().chars().take(40).collect();
    if s.is_empty() {
        "empty".to_string()
    } else {
        format!("not a number: {s:?}")
    }
}

/// A unit quaternion from components, when their norm is within 10 % of 1 (a rotation written
/// with limited precision); `None` for anything else (zero, huge, non-finite).
pub(crate) fn unit_quaternion(w: f64, x: f64, y: f64, z: f64) -> Option<UnitQuaternion<f64>> {
    let q = Quaternion::new(w, x, y, z);
    let n = q.norm();
    (n.is_finite() && (n - 1.0).abs() <= 0.1).then(|| UnitQuaternion::from_quaternion(q))
}

/// An Android rotation vector (x, y, z, and w when given) as the device → ENU quaternion. With
/// w absent it is `sqrt(1 − |xyz|²)` (the rotation angle is at most π). `None` when the vector
/// is longer than 1 (beyond rounding) or not finite.
pub(crate) fn rotation_vector(
    x: f64,
    y: f64,
    z: f64,
    w: Option<f64>,
) -> Option<UnitQuaternion<f64>> {
    let w = match w {
        Some(w) => w,
        None => {
            let w2 = 1.0 - (x * x + y * y + z * z);
            if !(w2 >= -1e-3) {
                return None;
            }
            w2.max(0.0).sqrt()
        }
    };
    unit_quaternion(w, x, y, z)
}

/// Pairs each sample of `a` with the sample of `b` nearest in time (both sorted by time), when
/// it is at most `max_dt` away, and combines them with `f`; returns the combined samples and how
/// many of `a` had no partner. Sensor Logger's linear acceleration + gravity, and a recipe's
/// linear accelerometer + gravity or orientation, are made whole so; Sensor Logger's platform
/// guess turns its gravity by the attitude nearest each sample so.
pub(crate) fn pair_nearest<T: Copy, U>(
    a: &[(f64, Vector3<f64>)],
    b: &[(f64, T)],
    max_dt: f64,
    mut f: impl FnMut(Vector3<f64>, T) -> U,
) -> (Vec<(f64, U)>, u64) {
    let mut out = Vec::with_capacity(a.len());
    let mut unpaired = 0u64;
    let mut j = 0usize;
    for &(t, v) in a {
        while j + 1 < b.len() && b[j + 1].0 <= t {
            j += 1;
        }
        let best = [j, j + 1]
            .into_iter()
            .filter(|&k| k < b.len())
            .min_by(|&p, &q| (b[p].0 - t).abs().total_cmp(&(b[q].0 - t).abs()));
        match best {
            Some(k) if (b[k].0 - t).abs() <= max_dt => out.push((t, f(v, b[k].1))),
            _ => unpaired += 1,
        }
    }
    (out, unpaired)
}

/// A barometer reading, when [`PressureSample::check`] accepts it; otherwise why not, for a
/// warning on the pressure field (out of [`PRESSURE_RANGE_HPA`], or a time out of range).
pub(crate) fn pressure(t: f64, hpa: f64) -> Result<PressureSample, String> {
    let p = PressureSample { t, hpa };
    match p.check() {
        Ok(()) => Ok(p),
        Err(_) if !(hpa >= PRESSURE_RANGE_HPA.0 && hpa <= PRESSURE_RANGE_HPA.1) => Err(format!(
            "pressure {hpa} hPa outside {}–{} hPa, skipped",
            PRESSURE_RANGE_HPA.0, PRESSURE_RANGE_HPA.1
        )),
        Err(e) => Err(format!("time out of range ({e}), skipped")),
    }
}

/// Drops samples with a non-finite value (sums and unit conversions of huge numbers can
/// overflow) and returns how many were dropped.
pub(crate) fn drop_non_finite(s: &mut Streams) -> u64 {
    let count = |s: &Streams| {
        s.accel.len()
            + s.gyro.len()
            + s.mag.len()
            + s.orientation.len()
            + s.fixes.len()
            + s.pressure.len()
    };
    let before = count(s);
    let ok = |t: f64, v: &Vector3<f64>| t.is_finite() && v.iter().all(|x| x.is_finite());
    s.accel.retain(|(t, v)| ok(*t, v));
    s.gyro.retain(|(t, v)| ok(*t, v));
    s.mag.retain(|(t, v)| ok(*t, v));
    s.orientation
        .retain(|(t, q)| t.is_finite() && q.coords.iter().all(|x| x.is_finite()));
    s.fixes.retain(|f| f.check().is_ok());
    s.pressure.retain(|p| p.check().is_ok());
    let after = count(s);
    (before - after) as u64
}

/// Adds warnings (one per skipped line) to a log.
pub(crate) fn add_warnings(log: &mut Log, warnings: Warnings) {
    let extra = warnings.count - warnings.kept.len() as u64;
    for w in warnings.kept {
        log.warn(w);
    }
    log.skipped += extra;
}

/// Sets the log's records from the streams, dropping samples that unit conversions made
/// non-finite (with one counted warning naming `file`).
pub(crate) fn set_records(log: &mut Log, mut s: Streams, file: &str) {
    let dropped = drop_non_finite(&mut s);
    log.records = s.into_records();
    warn_count(
        log,
        dropped,
        file_error(
            file,
            0,
            format!("{dropped} sample(s) with a non-finite value, skipped"),
        ),
    );
}

/// Records `count` items skipped for one reason as a single warning that counts them all.
pub(crate) fn warn_count(log: &mut Log, count: u64, e: ParseError) {
    if count > 0 {
        log.warn(e);
        log.skipped += count - 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delimiter_from_header() {
        assert_eq!(
            detect_delimiter("\"Time (s)\";\"Acceleration x (m/s^2)\""),
            b';'
        );
        assert_eq!(detect_delimiter("Time (s)\tAcceleration x (m/s^2)"), b'\t');
        assert_eq!(detect_delimiter("\"a;b\",c,d"), b',');
        assert_eq!(detect_delimiter("time"), b',');
    }

    #[test]
    fn fields_split_on_one_line_only() {
        let f = |l: &str| split_line(l, b',');
        assert_eq!(f("a, b ,c"), ["a", "b", "c"]);
        assert_eq!(f("\"x,y\",2"), ["x,y", "2"]);
        assert_eq!(f("\"say \"\"hi\"\"\",1"), ["say \"hi\"", "1"]);
        assert_eq!(f("\"open,2,3"), ["open,2,3"]);
        assert_eq!(f(""), [""]);
        assert_eq!(f("1,,3,"), ["1", "", "3", ""]);
    }

    #[test]
    fn warnings_keep_the_first_and_count_all() {
        let mut w = Warnings::default();
        for i in 0..(MAX_WARNINGS as u64 + 50) {
            w.push(file_error("f", i + 1, "bad"));
        }
        let mut log = Log::new("f", super::super::Format::PdrLog);
        add_warnings(&mut log, w);
        assert_eq!(log.warnings.len(), MAX_WARNINGS);
        assert_eq!(log.skipped, MAX_WARNINGS as u64 + 50);
        assert_eq!(log.warnings[0].line, 1);
    }
}
