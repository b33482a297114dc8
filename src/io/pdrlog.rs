//! The project's own recording format, `pdr-log`, version 1.
//! May import: `engine` and [`lines`](super::lines); not `import`, which reads pdr-logs through
//! this module (its tests also use a `sim` walk).
//!
//! A UTF-8 text file, one record per sensor event, so a recorder can append to it and a reader
//! can stream it. The first line is the version tag `# pdr-log 1`. Other lines starting with `#`
//! are comments. Every other line is a comma-separated record whose first field names its kind:
//!
//! ```text
//! # pdr-log 1
//! imu,t_s,ax,ay,az,gx,gy,gz,mx,my,mz,qw,qx,qy,qz
//! gnss,t_s,lat_deg,lon_deg,acc_m,alt_m,speed_mps,bearing_deg
//! gap,t0_s,t1_s
//! foot,t_s,ax,ay,az,gx,gy,gz,mx,my,mz,qw,qx,qy,qz
//! pressure,t_s,hpa
//! ```
//!
//! Units: `t_s` seconds on the recorder's clock (any origin, increasing); `a*` m/s², specific
//! force including gravity, Android sign (face up at rest: az = +9.81), device frame x right,
//! y top of screen, z out of screen; `g*` rad/s; `m*` µT; `q*` the unit quaternion taking
//! device vectors to East-North-Up; `lat_deg`/`lon_deg` WGS84 degrees; `acc_m` horizontal
//! accuracy, m; `alt_m` m; `speed_mps` m/s; `bearing_deg` degrees clockwise from true north.
//! An empty field is a missing value; the gyroscope, magnetometer and quaternion groups are
//! present or empty as a whole. `gap` records say the recorder saw no samples between two times
//! (for example while the page was hidden). `foot` records are the samples of a second IMU strapped on
//! a foot (Strozzi 2017 §4's two-sensor walks), with the fields of `imu` in the foot sensor's frame.
//! `pressure` records are barometer readings, `hpa` hectopascals (= mbar).
//!
//! A comment `# date_unix_s 1686729658` says when the recording was made, Unix seconds, for a log
//! whose clock is not Unix time (one converted from a format that counts from the start); the
//! World Magnetic Model needs the date for the declination. Optional; the first one counts.
//!
//! Reading is lenient per line: a bad line is reported with its file, line, column and field and
//! skipped; every good line before and after it is kept. A missing or unknown version tag is
//! fatal.

use super::lines::{try_each_line, MAX_WARNINGS};
use super::ParseError;
use crate::engine::types::{GnssFix, ImuSample};
use crate::engine::Record;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::fmt::Write as _;
use std::io::BufRead;
use std::ops::ControlFlow;

mod recover;
pub use recover::{recover, Recovered};

/// The version tag line.
pub const HEADER: &str = "# pdr-log 1";

const IMU_FIELDS: [&str; 15] = [
    "kind", "t_s", "ax", "ay", "az", "gx", "gy", "gz", "mx", "my", "mz", "qw", "qx", "qy", "qz",
];
const GNSS_FIELDS: [&str; 8] = [
    "kind",
    "t_s",
    "lat_deg",
    "lon_deg",
    "acc_m",
    "alt_m",
    "speed_mps",
    "bearing_deg",
];
const GAP_FIELDS: [&str; 3] = ["kind", "t0_s", "t1_s"];
const PRESSURE_FIELDS: [&str; 3] = ["kind", "t_s", "hpa"];

/// The text a new log starts with: the version tag and the schema as comments.
pub fn preamble() -> String {
    format!(
        "{HEADER}\n# {}\n# {}\n# {}\n# {}\n# units: s, m/s^2 (gravity included, Android sign, device x right/y up/z out), rad/s, uT, quaternion device->ENU, WGS84 deg, m, m/s, deg from north, hPa\n",
        IMU_FIELDS.join(","),
        GNSS_FIELDS.join(","),
        GAP_FIELDS.join(","),
        PRESSURE_FIELDS.join(",")
    )
}

fn opt(out: &mut String, v: Option<f64>) {
    out.push(',');
    if let Some(x) = v {
        let _ = write!(out, "{x}");
    }
}

/// One record as a line (with its newline). Floats are written in Rust's shortest round-trip
/// form, so reading the line back gives the same bits.
pub fn line(r: &Record) -> String {
    let mut s = String::with_capacity(96);
    match r {
        Record::Imu(i) | Record::Foot(i) => {
            let kind = if matches!(r, Record::Foot(_)) {
                "foot"
            } else {
                "imu"
            };
            let _ = write!(
                s,
                "{kind},{},{},{},{}",
                i.t, i.accel.x, i.accel.y, i.accel.z
            );
            for v in [i.gyro, i.mag] {
                for k in 0..3 {
                    opt(&mut s, v.map(|v| v[k]));
                }
            }
            let q = i.orientation.map(|q| q.into_inner());
            for v in [
                q.map(|q| q.w),
                q.map(|q| q.i),
                q.map(|q| q.j),
                q.map(|q| q.k),
            ] {
                opt(&mut s, v);
            }
        }
        Record::Gnss(g) => {
            let _ = write!(
                s,
                "gnss,{},{},{},{}",
                g.t, g.lat_deg, g.lon_deg, g.h_accuracy_m
            );
            for v in [g.altitude_m, g.speed_mps, g.bearing_deg] {
                opt(&mut s, v);
            }
        }
        Record::Gap(a, b) => {
            let _ = write!(s, "gap,{a},{b}");
        }
        Record::Pressure(p) => {
            let _ = write!(s, "pressure,{},{}", p.t, p.hpa);
        }
    }
    s.push('\n');
    s
}

/// The comment that gives the recording's date (see the module documentation).
pub const DATE_TAG: &str = "# date_unix_s ";

/// A whole log as text.
pub fn to_string(records: &[Record]) -> String {
    to_string_dated(records, None)
}

/// A whole log as text, with its date (Unix seconds) when known.
pub fn to_string_dated(records: &[Record], date_unix_s: Option<f64>) -> String {
    let mut s = preamble();
    if let Some(d) = date_unix_s.filter(|d| d.is_finite()) {
        let _ = writeln!(s, "{DATE_TAG}{d}");
    }
    for r in records {
        s.push_str(&line(r));
    }
    s
}

/// What reading a log produced: every good record, and the bad lines.
#[derive(Debug, Default)]
pub struct Parsed {
    /// Records in file order.
    pub records: Vec<Record>,
    /// The first [`MAX_WARNINGS`] lines that were skipped.
    pub errors: Vec<ParseError>,
    /// How many lines were skipped in all (`errors` may hold one more entry: the notice that
    /// records were put back in time order).
    pub skipped: u64,
    /// When the recording was made, Unix seconds, from its `# date_unix_s` line.
    pub date_unix_s: Option<f64>,
}

/// How many IMU samples a pdr-log's text holds (its `imu,` lines), without parsing them.
pub fn count_imu_lines(text: &str) -> usize {
    text.lines().filter(|l| l.starts_with("imu,")).count()
}

/// Reads a pdr-log stream. `file` names the source in errors. Lines are bounded
/// ([`crate::io::lines::MAX_LINE`]), so a file of any size is read in memory proportional to
/// its records.
pub fn read(input: impl BufRead, file: &str) -> Result<Parsed, ParseError> {
    read_sized(input, file, 0)
}

/// [`read`], with room made for `records` records at once: a large upload then needs no
/// reallocation of its records, whose doubling would otherwise hold them twice for a moment.
pub fn read_sized(input: impl BufRead, file: &str, records: usize) -> Result<Parsed, ParseError> {
    let mut out = Parsed::default();
    // An estimate too large to allocate is ignored: the records then grow as they are read.
    let _ = out.records.try_reserve(records);
    let mut fatal = None;
    let mut saw_header = false;
    try_each_line(input, file, |n, line| {
        let line = match line {
            Ok(l) => l,
            Err(e) if n == 1 => {
                fatal = Some(e);
                return ControlFlow::Break(());
            }
            Err(e) => {
                skip(&mut out, e);
                return ControlFlow::Continue(());
            }
        };
        if n == 1 {
            if line != HEADER {
                fatal = Some(err(
                    file,
                    1,
                    None,
                    None,
                    format!(
                        "not a pdr-log version 1 file: the first line must be `{HEADER}`, found `{}`",
                        line.chars().take(60).collect::<String>()
                    ),
                ));
                return ControlFlow::Break(());
            }
            saw_header = true;
            return ControlFlow::Continue(());
        }
        read_line(&mut out, file, n, line);
        ControlFlow::Continue(())
    })?;
    put_in_time_order(&mut out, file);
    match fatal {
        Some(e) => Err(e),
        None if !saw_header => Err(err(
            file,
            1,
            None,
            None,
            format!("empty file: a pdr-log starts with `{HEADER}`"),
        )),
        None => Ok(out),
    }
}

/// An error of `file`.
fn err(
    file: &str,
    line: u64,
    column: Option<usize>,
    field: Option<&str>,
    message: String,
) -> ParseError {
    ParseError {
        file: file.to_string(),
        line,
        column,
        field: field.map(str::to_string),
        message,
    }
}

/// Records a skipped line (the first [`MAX_WARNINGS`] are kept).
fn skip(out: &mut Parsed, e: ParseError) {
    out.skipped += 1;
    if out.errors.len() < MAX_WARNINGS {
        out.errors.push(e);
    }
}

/// Reads line `n` after the version tag: the date comment, another comment, or a record.
fn read_line(out: &mut Parsed, file: &str, n: u64, line: &str) {
    if let Some(d) = line.strip_prefix(DATE_TAG) {
        match d.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => {
                out.date_unix_s.get_or_insert(v);
            }
            _ => skip(
                out,
                err(
                    file,
                    n,
                    Some(2),
                    Some("date_unix_s"),
                    format!("`{}` is not a number of seconds", d.trim()),
                ),
            ),
        }
        return;
    }
    if line.trim().is_empty() || line.starts_with('#') {
        return;
    }
    // At most 15 fields are meaningful (imu); more is an error that names the count.
    let mut fields = [""; 16];
    let mut len = 0;
    for (i, x) in line.split(',').enumerate() {
        if let Some(slot) = fields.get_mut(i) {
            *slot = x;
        }
        len = i + 1;
    }
    let parsed = if len > fields.len() {
        Err((
            None,
            None,
            format!("{len} fields: no record has more than 15"),
        ))
    } else {
        parse_record(&fields[..len])
    };
    match parsed {
        Ok(r) => out.records.push(r),
        Err((col, field, msg)) => skip(out, err(file, n, col, field, msg)),
    }
}

/// Puts the records in time order (a damaged or hand-edited file; the engine needs it), with a
/// notice saying how many were out of it.
fn put_in_time_order(out: &mut Parsed, file: &str) {
    let mut latest = f64::NEG_INFINITY;
    let mut late = 0u64;
    for r in &out.records {
        let t = r.t();
        if t < latest {
            late += 1;
        }
        latest = latest.max(t);
    }
    if late > 0 {
        crate::engine::sort::sort_by(&mut out.records, |a, b| a.t().total_cmp(&b.t()));
        // A notice, not a skipped line: nothing is lost.
        out.errors.push(err(
            file,
            0,
            None,
            Some("t_s"),
            format!("{late} record(s) earlier than a record before them, put back in time order"),
        ));
    }
}

type FieldErr = (Option<usize>, Option<&'static str>, String);

/// One record's fields (split at commas), checked against its kind's field names.
fn parse_record(rec: &[&str]) -> Result<Record, FieldErr> {
    let kind = rec.first().copied().unwrap_or("").trim();
    let names: &[&'static str] = match kind {
        "imu" | "foot" => &IMU_FIELDS,
        "gnss" => &GNSS_FIELDS,
        "gap" => &GAP_FIELDS,
        "pressure" => &PRESSURE_FIELDS,
        other => {
            return Err((
                Some(1),
                Some("kind"),
                format!(
                    "unknown record kind `{other}` (expected imu, foot, gnss, gap or pressure)"
                ),
            ))
        }
    };
    if rec.len() != names.len() {
        return Err((
            None,
            None,
            format!(
                "a `{kind}` record has {} fields, found {}",
                names.len(),
                rec.len()
            ),
        ));
    }
    let v = Values { rec, names };
    Ok(match kind {
        "imu" | "foot" => {
            let s = imu_sample(&v)?;
            if kind == "foot" {
                Record::Foot(s)
            } else {
                Record::Imu(s)
            }
        }
        "gnss" => Record::Gnss(GnssFix {
            t: v.req(1)?,
            lat_deg: v.req(2)?,
            lon_deg: v.req(3)?,
            h_accuracy_m: v.req(4)?,
            altitude_m: v.num(5)?,
            speed_mps: v.num(6)?,
            bearing_deg: v.num(7)?,
        }),
        "pressure" => Record::Pressure(crate::engine::PressureSample {
            t: v.req(1)?,
            hpa: v.req(2)?,
        }),
        _ => Record::Gap(v.req(1)?, v.req(2)?),
    })
}

/// The fields of a record and their names, as many of each.
struct Values<'a> {
    rec: &'a [&'a str],
    names: &'a [&'static str],
}

impl Values<'_> {
    /// Field `i`: `None` when empty, an error naming it when not a finite number.
    fn num(&self, i: usize) -> Result<Option<f64>, FieldErr> {
        let s = self.rec[i].trim();
        if s.is_empty() {
            return Ok(None);
        }
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            Ok(_) => Err((
                Some(i + 1),
                Some(self.names[i]),
                format!("`{s}` is not a finite number"),
            )),
            Err(_) => Err((
                Some(i + 1),
                Some(self.names[i]),
                format!("`{s}` is not a number"),
            )),
        }
    }

    /// Field `i`, which must not be empty.
    fn req(&self, i: usize) -> Result<f64, FieldErr> {
        self.num(i)?.ok_or((
            Some(i + 1),
            Some(self.names[i]),
            "required value is empty".to_string(),
        ))
    }

    /// Fields `i..i + 3`, all present or all empty.
    fn group(&self, i: usize) -> Result<Option<[f64; 3]>, FieldErr> {
        match (self.num(i)?, self.num(i + 1)?, self.num(i + 2)?) {
            (Some(a), Some(b), Some(c)) => Ok(Some([a, b, c])),
            (None, None, None) => Ok(None),
            _ => Err((
                Some(i + 1),
                Some(self.names[i]),
                format!(
                    "the group {}..{} must be all present or all empty",
                    self.names[i],
                    self.names[i + 2]
                ),
            )),
        }
    }
}

/// The sample of an `imu` or `foot` record.
fn imu_sample(v: &Values) -> Result<ImuSample, FieldErr> {
    let q = match (v.num(11)?, v.group(12)?) {
        (Some(w), Some([x, y, z])) => {
            let q = Quaternion::new(w, x, y, z);
            let n = q.norm();
            if (n - 1.0).abs() > 0.01 {
                return Err((
                    Some(12),
                    Some("qw"),
                    format!("quaternion norm is {n:.4}, not 1"),
                ));
            }
            // Keep a quaternion written by us bit for bit; renormalise anything else.
            Some(if (n - 1.0).abs() < 1e-12 {
                UnitQuaternion::new_unchecked(q)
            } else {
                UnitQuaternion::from_quaternion(q)
            })
        }
        (None, None) => None,
        _ => {
            return Err((
                Some(12),
                Some("qw"),
                "the group qw..qz must be all present or all empty".into(),
            ))
        }
    };
    Ok(ImuSample {
        t: v.req(1)?,
        accel: Vector3::new(v.req(2)?, v.req(3)?, v.req(4)?),
        gyro: v.group(5)?.map(Vector3::from),
        mag: v.group(8)?.map(Vector3::from),
        orientation: q,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::scenarios;

    #[test]
    fn round_trip_is_exact() {
        let mut sim = scenarios::straight_walk(1.8, 3.0).generate();
        // A fix and a gap where they belong in time (the reader keeps records in time order).
        let at = |t: f64, rs: &[Record]| {
            rs.iter()
                .position(|r| matches!(r, Record::Imu(s) if s.t > t))
                .unwrap_or(rs.len())
        };
        let i = at(5.0, &sim.records);
        sim.records.insert(
            i,
            Record::Gnss(GnssFix {
                t: 5.0,
                lat_deg: 43.77,
                lon_deg: 11.25,
                h_accuracy_m: 4.5,
                altitude_m: None,
                speed_mps: Some(1.3),
                bearing_deg: None,
            }),
        );
        let i = at(6.0, &sim.records);
        sim.records.insert(i, Record::Gap(6.0, 6.6));
        let text = to_string(&sim.records);
        let back = read(text.as_bytes(), "mem").unwrap();
        assert!(back.errors.is_empty(), "{:?}", back.errors);
        assert_eq!(back.records.len(), sim.records.len());
        let first_diff = back
            .records
            .iter()
            .zip(&sim.records)
            .position(|(a, b)| a != b);
        assert_eq!(first_diff, None, "records differ after a round trip");
    }

    #[test]
    fn bad_lines_are_reported_and_skipped() {
        let text = format!("{HEADER}\nimu,0.0,0,0,9.8,,,,,,,,,,\nimu,0.01,0,x,9.8,,,,,,,,,,\ngnss,1,2\nimu,0.02,0,0,9.8,1,2,,,,,,,,\nwat,1\nimu,0.03,0,0,9.8,,,,,,,,,,\n");
        let p = read(text.as_bytes(), "walk.pdrlog").unwrap();
        assert_eq!(p.records.len(), 2);
        let msgs: Vec<String> = p.errors.iter().map(|e| e.to_string()).collect();
        assert_eq!(msgs[0], "walk.pdrlog:3:4 field `ay`: `x` is not a number");
        assert!(
            msgs[1].starts_with("walk.pdrlog:4: a `gnss` record has 8 fields"),
            "{}",
            msgs[1]
        );
        assert!(
            msgs[2].starts_with("walk.pdrlog:5:6 field `gx`"),
            "{}",
            msgs[2]
        );
        assert!(
            msgs[3].starts_with("walk.pdrlog:6:1 field `kind`"),
            "{}",
            msgs[3]
        );
        assert!(read("imu,0,0,0,9.8\n".as_bytes(), "x").is_err());
    }
}
