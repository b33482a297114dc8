//! WeAllWalk walks (Flores & Manduchi, ACM TACCESS 2018: two iPhones in the trouser pockets,
//! heel strikes and turns), one of the evaluation data sets of `../shared/data`, read directly.
//! May import: `engine` and `io`.
//!
//! # Files
//! One folder per walk and phone, `T<path>_ID<subject>_<1L|2R>/`:
//! - `sensors.csv`: the recording app's 41 comma-separated columns, no header, iOS Core Motion
//!   at 25 Hz. Column 1 is the time in seconds (kept as it is, no offset). Read:
//!   - acceleration = user acceleration (columns 21–23) + gravity (24–26), both in g with Core
//!     Motion's sign (gravity points down), multiplied by −[`G0`] into the Android sign in
//!     m/s². Not the raw accelerometer (31–33), which runs one row ahead of the Core Motion
//!     columns;
//!   - gyroscope = the rotation rate (18–20), rad/s, device axes;
//!   - orientation = the quaternion (14–17, in the order x, y, z, w; device → reference), the
//!     reference taken as Core Motion's x magnetic north, y west, z up and turned into device →
//!     ENU by Rz(+90°), as Sensor Logger's iOS attitude (`sensor_logger::conventions`);
//!   - no magnetometer: the calibrated field (27–30) is all zero and the raw one (37–39) carries
//!     hard-iron offsets of hundreds of µT.
//!
//!   Roll, pitch, yaw and the rotation matrix (2–13) repeat the quaternion; the raw gyroscope
//!   (34–36) and the app's flags (40–41) are not read.
//! - `steps.csv`: `t_s,foot`, every heel strike of both feet (shoe-mounted sensors), on the
//!   same clock: [`Truth::step_events`](super::Truth::step_events) (`L` foot 0, `R` foot 1) and
//!   [`Truth::steps`](super::Truth::steps), their number.
//! - `segments.csv`: `segment,spatial_segment,start_s,end_s,direction,turn_time_s,turn_deg,steps`,
//!   the path's straights and turns; a row with a `turn_deg` (counter-clockwise positive, as
//!   [`TrueTurn::angle_deg`]) is a turn from `start_s` to `end_s`:
//!   [`Truth::turns`](super::Truth::turns).
//! - The `.xml` beside them (the original annotation, with the obstacles) is not read.
//!
//! [`Log::group`] is the pocket: `LeftPocket` for a folder ending `_1L`, `RightPocket` for
//! `_2R`.
//!
//! # Checked on the 36 walks of `../shared/data/weallwalk`
//! Core Motion's own gravity (24–26) turned by the quaternion as written points straight down in
//! the reference frame (mean vertical component of the unit vector 1.00000 on every walk, the
//! worst sample 0.981), so the quaternion is device → reference as the data set says; the
//! acceleration turned into ENU by the converted orientation points up (mean vertical
//! component +9.56 to +9.98 m/s² over each whole walk). The heading reference cannot be checked
//! here (no usable magnetometer): whether Core Motion's x was magnetic north or an arbitrary
//! direction, the turns of the path are the same.

use super::common::{
    add_warnings, cell, core_motion_to_enu, file_in, folder_label, folder_name, numbers, open,
    read_lines, set_records, unit_quaternion, Table, Warnings,
};
use super::{
    field_error, file_error, FileSet, Format, Log, Platform, Streams, TrueStep, TrueTurn, G0,
};
use crate::io::ParseError;
use nalgebra::Vector3;

/// The files of a walk folder that the reader consumes (and every `.xml` beside them).
pub const WEALLWALK_FILES: [&str; 3] = ["sensors.csv", "steps.csv", "segments.csv"];

/// Columns of `sensors.csv`.
pub const SENSOR_COLUMNS: usize = 41;

/// The start of `segments.csv`'s header.
const SEGMENTS_HEADER: &str = "segment,spatial_segment,start_s,end_s";

/// Recognises a walk folder of the set inside a file set and reads it. `dir` is a folder of
/// `names` (ending with `/`, or empty for the top). Returns the files it consumed and the log, or
/// `None` when the folder has neither a `sensors.csv` whose first line is 41 numbers nor a
/// `segments.csv` with the set's header.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let first_line = |set: &mut dyn FileSet, base: &str| {
        let name = file_in(names, dir, base)?;
        let head = set.head(&name).ok()?;
        Some(
            head.lines()
                .find(|l| !l.trim().is_empty())
                .unwrap_or("")
                .trim_start_matches('\u{feff}')
                .trim()
                .to_string(),
        )
    };
    let sensors = first_line(set, "sensors.csv").is_some_and(|l| {
        let f: Vec<&str> = l.split(',').collect();
        f.len() == SENSOR_COLUMNS && f.iter().all(|x| super::number(x).is_some())
    });
    let segments = first_line(set, "segments.csv").is_some_and(|l| l.starts_with(SEGMENTS_HEADER));
    if !(sensors || segments) {
        return None;
    }
    let consumed = names
        .iter()
        .filter(|n| {
            super::fileset::parent(n) == dir && {
                let b = super::fileset::base(n);
                WEALLWALK_FILES.iter().any(|f| b.eq_ignore_ascii_case(f))
                    || b.to_ascii_lowercase().ends_with(".xml")
            }
        })
        .cloned()
        .collect();
    Some((consumed, read(set, names, dir)))
}

/// Reads a recognised folder.
fn read(set: &mut dyn FileSet, names: &[String], dir: &str) -> Result<Log, ParseError> {
    let sensors_name = format!("{dir}sensors.csv");
    let mut log = Log::new(folder_label(set, dir, &sensors_name), Format::WeAllWalk);
    log.platform = Some(Platform::Ios);
    let folder = folder_name(set, dir);
    log.group = if folder.ends_with("_1L") {
        Some("LeftPocket".to_string())
    } else if folder.ends_with("_2R") {
        Some("RightPocket".to_string())
    } else {
        None
    };
    // The set's phones are in trouser pockets, left or right.
    log.truth.carry = Some(crate::engine::carry::CarryMode::Pocket);
    let Some(sensors) = file_in(names, dir, "sensors.csv") else {
        return Err(file_error(
            &set.label(&sensors_name),
            0,
            "missing: a WeAllWalk walk needs its sensors.csv",
        ));
    };
    let label = set.label(&sensors);
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    let to_enu = core_motion_to_enu();
    read_lines(set, &sensors, Some(','), &mut warnings, |label, n, f| {
        let [t] = numbers(f, 0, ["time_s"], label, n)?;
        let [qx, qy, qz, qw] = numbers(f, 13, ["quat_x", "quat_y", "quat_z", "quat_w"], label, n)?;
        let rate = ["rotation_rate_x", "rotation_rate_y", "rotation_rate_z"];
        let w = numbers(f, 17, rate, label, n)?;
        let user = ["user_accel_x", "user_accel_y", "user_accel_z"];
        let u = numbers(f, 20, user, label, n)?;
        let g = numbers(f, 23, ["gravity_x", "gravity_y", "gravity_z"], label, n)?;
        let q = unit_quaternion(qw, qx, qy, qz)
            .ok_or_else(|| field_error(label, n, 14, "quat_x", "not a unit quaternion, skipped"))?;
        let total = Vector3::new(u[0] + g[0], u[1] + g[1], u[2] + g[2]);
        s.accel.push((t, total * -G0));
        s.gyro.push((t, Vector3::from(w)));
        s.orientation.push((t, to_enu * q));
        Ok(())
    })?;
    if s.accel.is_empty() {
        return Err(file_error(&label, 0, "no sensor samples"));
    }
    if let Some(name) = file_in(names, dir, "steps.csv") {
        let steps = read_steps(set, &name, &mut warnings)?;
        log.truth.steps = Some(steps.len() as u64);
        log.truth.step_events = steps;
    }
    if let Some(name) = file_in(names, dir, "segments.csv") {
        log.truth.turns = read_turns(set, &name, &mut warnings)?;
    }
    set_records(&mut log, s, &label);
    add_warnings(&mut log, warnings);
    Ok(log)
}

/// Opens a headed CSV of the truth; an error names the file.
fn open_table<'a>(
    set: &'a mut dyn FileSet,
    name: &str,
    label: &str,
) -> Result<Option<Table<Box<dyn std::io::BufRead + 'a>>>, ParseError> {
    let reader = open(set, name, label)?;
    Table::open(reader, label, Some(b','))
}

/// The heel strikes of `steps.csv` (`t_s,foot`, `L` or `R`), in time order.
fn read_steps(
    set: &mut dyn FileSet,
    name: &str,
    warnings: &mut Warnings,
) -> Result<Vec<TrueStep>, ParseError> {
    let label = set.label(name);
    let mut out = Vec::new();
    let Some(mut table) = open_table(set, name, &label)? else {
        return Ok(out);
    };
    let (Some(ct), Some(cf)) = (table.named("t_s"), table.named("foot")) else {
        return Err(file_error(
            &label,
            table.header_line,
            "header lacks t_s or foot: not a WeAllWalk steps file",
        ));
    };
    let mut bad = Warnings::default();
    table.rows(&label, warnings, |n, rec| {
        let step = cell(rec, ct, "t_s", &label, n).and_then(|t| {
            let foot = match rec.get(cf).map(str::trim) {
                Some(f) if f.eq_ignore_ascii_case("L") => 0,
                Some(f) if f.eq_ignore_ascii_case("R") => 1,
                other => {
                    return Err(field_error(
                        &label,
                        n,
                        cf + 1,
                        "foot",
                        format!("not L or R: {:?}", other.unwrap_or("")),
                    ))
                }
            };
            Ok(TrueStep {
                t,
                foot: Some(foot),
            })
        });
        match step {
            Ok(s) => out.push(s),
            Err(e) => bad.push(e),
        }
    })?;
    warnings.extend(bad);
    crate::engine::sort::sort_by(&mut out, |a, b| a.t.total_cmp(&b.t));
    Ok(out)
}

/// The turns of `segments.csv` (the rows with a `turn_deg`), in time order.
fn read_turns(
    set: &mut dyn FileSet,
    name: &str,
    warnings: &mut Warnings,
) -> Result<Vec<TrueTurn>, ParseError> {
    let label = set.label(name);
    let mut out = Vec::new();
    let Some(mut table) = open_table(set, name, &label)? else {
        return Ok(out);
    };
    let cols = ["start_s", "end_s", "turn_deg"].map(|c| table.named(c));
    let [Some(cs), Some(ce), Some(cd)] = cols else {
        return Err(file_error(
            &label,
            table.header_line,
            "header lacks start_s, end_s or turn_deg: not a WeAllWalk segments file",
        ));
    };
    let mut bad = Warnings::default();
    table.rows(&label, warnings, |n, rec| {
        if rec.get(cd).map_or(true, |d| d.trim().is_empty()) {
            return; // A straight.
        }
        let turn = (|| {
            Ok::<_, ParseError>(TrueTurn {
                t_start: cell(rec, cs, "start_s", &label, n)?,
                t_end: cell(rec, ce, "end_s", &label, n)?,
                angle_deg: cell(rec, cd, "turn_deg", &label, n)?,
            })
        })();
        match turn {
            Ok(t) => out.push(t),
            Err(e) => bad.push(e),
        }
    })?;
    warnings.extend(bad);
    crate::engine::sort::sort_by(&mut out, |a, b| a.t_start.total_cmp(&b.t_start));
    Ok(out)
}
