//! TyrEx recording folders (the attitude benchmark of Michel et al., PerCom 2017, one of the
//! evaluation data sets of `../shared/data`), Android or iOS layout, read directly.
//! May import: `engine` and `io`.
//!
//! # Files
//! Space-separated text, one sample per line, the time first: seconds on the phone's own clock
//! (Android: since the recording started; iOS: since the phone booted). Times are kept as they
//! are, with no offset.
//! - Android (marked by `record.properties`): `accelerometer.txt` `t ax ay az` (m/s², gravity
//!   included, Android sign), `gyroscope-calibrated.txt` `t wx wy wz` (rad/s; `gyroscope.txt`
//!   when only that one exists), `magnetometer-calibrated.txt` `t mx my mz` (µT;
//!   `magnetometer.txt` when only that one exists), `rotation-vector.txt` `t x y z w accuracy`:
//!   the Android rotation vector, device → ENU, read as the OS orientation. `record.properties`'
//!   `StartTime` (Unix seconds) is the recording's date.
//! - iOS (marked by `description.txt` with its `BootTime`): `accelerometer.txt` in **g** with
//!   Core Motion's sign (−1 g up at rest), multiplied by −[`G0`] into the Android sign;
//!   `gyroscope.txt` (rad/s, the same device axes as Android); `magnetometer-calibrated.txt`
//!   (µT, a fifth column, the calibration accuracy, ignored; the raw `magnetometer.txt` of Core
//!   Motion keeps the phone's hard-iron offset and is not read); `attitude.txt` `t w x y z`: Core
//!   Motion's attitude quaternion, device → reference, the reference being x magnetic north,
//!   y west, z up, turned into device → ENU by Rz(+90°) as Sensor Logger's iOS attitude is
//!   (`sensor_logger::conventions`).
//! - `truth.csv` (optional: a user's own recording has none): `t_s,x_m,y_m,z_m,qw,qx,qy,qz` at
//!   60 Hz on the phone's clock, the motion-capture position of the phone in the room's frame
//!   (metres, z up, x and y not north): [`Truth::trajectory`](super::Truth::trajectory). Rows
//!   with empty position fields are where the cameras lost the phone: holes, skipped without a
//!   warning (the reader counts them, [`TruthTrack::holes`]). The quaternion columns are not read.
//!
//! The sensors do not start together (the gyroscope often 0.2–0.7 s after the accelerometer):
//! every sample is kept as it is and [`Streams::into_records`] merges them.
//!
//! # Checked on the 33 walks of `../shared/data/tyrex-pocket`
//! - The accelerometer turned into ENU by the orientation stream points up: over the first
//!   second of every walk (the walker standing) its mean vertical component is +9.1 to
//!   +10.3 m/s² on all 22 Android walks (rotation vector as written) and +9.5 to +9.8 m/s² on
//!   all 11 iOS walks (−G0 × the reading, attitude turned by Rz(+90°)). With the conjugate
//!   quaternion instead, the whole walk's mean is between −0.7 and +2.2 m/s² (except when
//!   texting: the phone lies nearly flat and both read about +9.5).
//! - The calibrated magnetometer turned into ENU the same way points north and down: on 17 of
//!   the 18 walks without placed magnets the mean east component is within 1.1 µT of zero
//!   (north 20–23 µT, down 27–38 µT, an inclination of 52–61°), on both layouts; the iPhone's
//!   running walk reads 5.8 µT east (16°). So Core Motion's reference here is x magnetic north
//!   (not an arbitrary x), and the Android rotation vector is referred to magnetic north too.
//! - On 6 of the 33 walks both the gyroscope and the orientation start more than
//!   [`HOLD_S`](super::HOLD_S) after the accelerometer, so the first records carry neither; the
//!   samples are kept as they are, and the engine's `auto` orientation moves up when the
//!   streams begin.
//! - `truth.csv` starts up to 1.1 s before the phone's first sample on 5 walks, and ends 1.5 to
//!   11 s before its last one on every walk.
//!
//! # Group
//! [`Log::group`] is the carrying mode, the last part of a folder named
//! `<Walker>_<Phone>_<Dist|NoDist>_<Mode>` (`FrontPocket`, `BackPocket`, `Swinging`, `Phoning`,
//! `Texting`, `RunningPocket`); `None` for a folder named otherwise.

use super::common::{
    add_warnings, cell, core_motion_to_enu, file_in, folder_label, folder_name, open, read_samples,
    rotation_vector, set_records, unit_quaternion, Table, Warnings,
};
use super::{field_error, file_error, FileSet, Format, Log, Platform, Streams, TruePosition, G0};
use crate::engine::carry::CarryMode;
use crate::io::ParseError;
use nalgebra::{UnitQuaternion, Vector3};
use std::io::BufRead;

/// The files of a TyrEx recording folder that the reader consumes (read, or known and not
/// needed: `timeAlignment.txt`, the raw sensor files when the calibrated ones exist); the
/// sensor files of either layout first.
pub const TYREX_FILES: [&str; 11] = [
    "accelerometer.txt",
    "gyroscope-calibrated.txt",
    "gyroscope.txt",
    "magnetometer-calibrated.txt",
    "magnetometer.txt",
    "rotation-vector.txt",
    "attitude.txt",
    "record.properties",
    "description.txt",
    "timeAlignment.txt",
    "truth.csv",
];

/// The sensor files of either layout: a folder holds at least one of them.
const SENSOR_FILES: &[&str] = TYREX_FILES.split_at(7).0;

/// Recognises a TyrEx recording folder inside a file set and reads it. `dir` is a folder of
/// `names` (ending with `/`, or empty for the top). Returns the files it consumed and the log, or
/// `None` when the folder is not a TyrEx recording: it needs `record.properties` (with a
/// `[Device]` section or a `StartTime`) or `description.txt` (with a `BootTime`), one of the
/// sensor files, and, when `accelerometer.txt` has lines, one of its first lines (in the first
/// [`HEAD_BYTES`](super::fileset::HEAD_BYTES)) made of at least four numbers separated by
/// spaces: a damaged first line is a warning, not a reason to ignore the recording.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let platform = layout(set, names, dir)?;
    if !SENSOR_FILES
        .iter()
        .any(|f| file_in(names, dir, f).is_some())
    {
        return None;
    }
    if let Some(acc) = file_in(names, dir, "accelerometer.txt") {
        let head = set.head(&acc).ok()?;
        // The complete lines of the head (the last one may be cut).
        let complete = head.rfind('\n').map_or("", |i| &head[..i]);
        let mut lines = complete.lines().filter(|l| !l.trim().is_empty()).peekable();
        let sample = |l: &str| {
            let fields: Vec<&str> = l.split_whitespace().collect();
            fields.len() >= 4 && fields.iter().all(|f| super::number(f).is_some())
        };
        if lines.peek().is_some() && !lines.any(sample) {
            return None;
        }
    }
    let consumed: Vec<String> = TYREX_FILES
        .iter()
        .filter_map(|f| file_in(names, dir, f))
        .collect();
    Some((consumed, read(set, names, dir, platform)))
}

/// The layout of a folder from its marker file: `description.txt` with a `BootTime` (iOS), or
/// `record.properties` with a `[Device]` section or a `StartTime` (Android). With both, the
/// orientation file decides (`attitude.txt`: iOS).
fn layout(set: &mut dyn FileSet, names: &[String], dir: &str) -> Option<Platform> {
    let mut head = |base: &str| file_in(names, dir, base).and_then(|n| set.head(&n).ok());
    let ios = head("description.txt").is_some_and(|h| h.contains("BootTime"));
    let android = head("record.properties")
        .is_some_and(|h| h.contains("[Device]") || h.contains("StartTime"));
    match (android, ios) {
        (true, true) if file_in(names, dir, "attitude.txt").is_some() => Some(Platform::Ios),
        (true, _) => Some(Platform::Android),
        (false, true) => Some(Platform::Ios),
        (false, false) => None,
    }
}

/// Reads a file of `t x y z` lines (a gyroscope's or a magnetometer's, as written) into `out`.
fn read_vectors(
    set: &mut dyn FileSet,
    name: &str,
    fields: [&str; 4],
    warnings: &mut Warnings,
    out: &mut Vec<(f64, Vector3<f64>)>,
) -> Result<(), ParseError> {
    read_samples(set, name, None, fields, warnings, |_, _, [t, x, y, z]| {
        out.push((t, Vector3::new(x, y, z)));
        Ok(())
    })
}

/// Reads a recognised folder of the given layout.
fn read(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
    platform: Platform,
) -> Result<Log, ParseError> {
    let acc_name = format!("{dir}accelerometer.txt");
    let source = folder_label(set, dir, &acc_name);
    let mut log = Log::new(source, Format::Tyrex);
    log.platform = Some(platform);
    log.group = carrying_mode(&folder_name(set, dir));
    log.truth.carry = log.group.as_deref().and_then(carry_of);
    let ios = platform == Platform::Ios;
    let mut s = Streams::default();
    let mut warnings = Warnings::default();
    let Some(acc) = file_in(names, dir, "accelerometer.txt") else {
        return Err(file_error(
            &set.label(&acc_name),
            0,
            "missing: a TyrEx recording needs its accelerometer.txt",
        ));
    };
    let scale = if ios { -G0 } else { 1.0 };
    read_samples(
        set,
        &acc,
        None,
        ["t_s", "ax", "ay", "az"],
        &mut warnings,
        |_, _, [t, x, y, z]| {
            s.accel.push((t, Vector3::new(x, y, z) * scale));
            Ok(())
        },
    )?;
    let acc_label = set.label(&acc);
    if s.accel.is_empty() {
        return Err(file_error(&acc_label, 0, "no accelerometer samples"));
    }
    let gyro = file_in(names, dir, "gyroscope-calibrated.txt")
        .or_else(|| file_in(names, dir, "gyroscope.txt"));
    if let Some(name) = gyro {
        let fields = ["t_s", "wx", "wy", "wz"];
        read_vectors(set, &name, fields, &mut warnings, &mut s.gyro)?;
    }
    let mut mag = file_in(names, dir, "magnetometer-calibrated.txt");
    if mag.is_none() && !ios {
        mag = file_in(names, dir, "magnetometer.txt");
    }
    if let Some(name) = mag {
        let fields = ["t_s", "mx", "my", "mz"];
        read_vectors(set, &name, fields, &mut warnings, &mut s.mag)?;
    }
    read_orientation(set, names, dir, ios, &mut warnings, &mut s.orientation)?;
    if !ios {
        if let Some(name) = file_in(names, dir, "record.properties") {
            log.date_unix_s = set.head(&name).ok().and_then(|h| start_time(&h));
        }
    }
    if let Some(name) = file_in(names, dir, "truth.csv") {
        log.truth.trajectory = read_truth_file(set, &name, &mut warnings)?;
    }
    set_records(&mut log, s, &acc_label);
    add_warnings(&mut log, warnings);
    Ok(log)
}

/// Reads the orientation of a folder into `out`: Core Motion's attitude (`attitude.txt`,
/// turned to ENU) on iOS, Android's rotation vector (`rotation-vector.txt`) otherwise.
fn read_orientation(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
    ios: bool,
    warnings: &mut Warnings,
    out: &mut Vec<(f64, UnitQuaternion<f64>)>,
) -> Result<(), ParseError> {
    if ios {
        let Some(name) = file_in(names, dir, "attitude.txt") else {
            return Ok(());
        };
        let to_enu = core_motion_to_enu();
        read_samples(
            set,
            &name,
            None,
            ["t_s", "qw", "qx", "qy", "qz"],
            warnings,
            |label, n, [t, w, x, y, z]| {
                let q = unit_quaternion(w, x, y, z).ok_or_else(|| {
                    field_error(label, n, 2, "qw", "not a unit quaternion, skipped")
                })?;
                out.push((t, to_enu * q));
                Ok(())
            },
        )
    } else {
        let Some(name) = file_in(names, dir, "rotation-vector.txt") else {
            return Ok(());
        };
        read_samples(
            set,
            &name,
            None,
            ["t_s", "x", "y", "z", "w"],
            warnings,
            |label, n, [t, x, y, z, w]| {
                let q = rotation_vector(x, y, z, Some(w)).ok_or_else(|| {
                    field_error(label, n, 2, "x", "not a unit rotation vector, skipped")
                })?;
                out.push((t, q));
                Ok(())
            },
        )
    }
}

/// Reads the folder's `truth.csv` (file `name`) with [`read_truth`].
fn read_truth_file(
    set: &mut dyn FileSet,
    name: &str,
    warnings: &mut Warnings,
) -> Result<Vec<TruePosition>, ParseError> {
    let label = set.label(name);
    let reader = open(set, name, &label)?;
    Ok(read_truth(reader, &label, warnings)?.trajectory)
}

/// The carrying mode of a folder named `<Walker>_<Phone>_<Dist|NoDist>_<Mode>`.
fn carrying_mode(name: &str) -> Option<String> {
    match name.split('_').collect::<Vec<_>>().as_slice() {
        [walker, phone, "Dist" | "NoDist", mode]
            if !walker.is_empty() && !phone.is_empty() && !mode.is_empty() =>
        {
            Some(mode.to_string())
        }
        _ => None,
    }
}

/// The engine's carrying mode for a TyrEx mode: the trouser pockets (walking or running) are
/// the pocket, `Swinging` the swinging hand, `Phoning` the ear, `Texting` the hand.
fn carry_of(mode: &str) -> Option<CarryMode> {
    match mode {
        "FrontPocket" | "BackPocket" | "RunningPocket" => Some(CarryMode::Pocket),
        "Swinging" => Some(CarryMode::Swinging),
        "Phoning" => Some(CarryMode::Ear),
        "Texting" => Some(CarryMode::Hand),
        _ => None,
    }
}

/// `StartTime = <Unix seconds>` of `record.properties`, when it is a plausible Unix time
/// (2001–2096).
fn start_time(properties: &str) -> Option<f64> {
    properties.lines().find_map(|l| {
        let (k, v) = l.split_once('=')?;
        (k.trim() == "StartTime")
            .then(|| super::number(v))
            .flatten()
            .filter(|t| (1.0e9..4.0e9).contains(t))
    })
}

/// A motion-capture trajectory read from `truth.csv`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TruthTrack {
    /// The positions, in time order.
    pub trajectory: Vec<TruePosition>,
    /// Rows skipped because the cameras lost the phone (empty position fields).
    pub holes: u64,
}

/// Reads a TyrEx `truth.csv`: a header naming `t_s`, `x_m`, `y_m`, `z_m` (any order, other
/// columns ignored), then one row per motion-capture frame. A row with an empty position field
/// is a hole, counted in [`TruthTrack::holes`] and not warned about; a row with a field that is
/// not a number is a warning naming file, line, column and field. A file without those columns
/// is an error naming it.
pub(crate) fn read_truth(
    r: impl BufRead,
    label: &str,
    warnings: &mut Warnings,
) -> Result<TruthTrack, ParseError> {
    let mut out = TruthTrack::default();
    let Some(mut table) = Table::open(r, label, Some(b','))? else {
        return Ok(out);
    };
    let cols = ["t_s", "x_m", "y_m", "z_m"].map(|c| table.named(c));
    let [Some(ct), Some(cx), Some(cy), Some(cz)] = cols else {
        return Err(file_error(
            label,
            table.header_line,
            "header lacks t_s, x_m, y_m or z_m: not a TyrEx truth file",
        ));
    };
    let mut bad = Warnings::default();
    table.rows(label, warnings, |n, rec| {
        let empty = |c: usize| rec.get(c).map_or(true, |f| f.trim().is_empty());
        if !empty(ct) && (empty(cx) || empty(cy) || empty(cz)) {
            out.holes += 1;
            return;
        }
        let row = (|| {
            Ok::<_, ParseError>(TruePosition {
                t: cell(rec, ct, "t_s", label, n)?,
                x_m: cell(rec, cx, "x_m", label, n)?,
                y_m: cell(rec, cy, "y_m", label, n)?,
                z_m: cell(rec, cz, "z_m", label, n)?,
            })
        })();
        match row {
            Ok(p) => out.trajectory.push(p),
            Err(e) => bad.push(e),
        }
    })?;
    warnings.extend(bad);
    crate::engine::sort::sort_by(&mut out.trajectory, |a, b| a.t.total_cmp(&b.t));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mode_from_the_folder_name() {
        assert_eq!(
            carrying_mode("Guillaume_Nexus5_NoDist_FrontPocket").as_deref(),
            Some("FrontPocket")
        );
        assert_eq!(
            carrying_mode("Jakob_iPhone5_Dist_Texting").as_deref(),
            Some("Texting")
        );
        assert_eq!(carrying_mode("my_walk"), None);
        assert_eq!(carrying_mode("a_b_Maybe_Texting"), None);
        assert_eq!(carrying_mode("a_b_Dist_Texting_2"), None);
        assert_eq!(carrying_mode(""), None);
    }

    #[test]
    fn start_time_from_the_properties() {
        let p = "[Device]\nModel = Nexus 5\n\n[Time]\nStartTime = 1464871900";
        assert_eq!(start_time(p), Some(1_464_871_900.0));
        assert_eq!(start_time("[Time]\nStartTime = 12"), None);
        assert_eq!(start_time("[Device]"), None);
    }

    #[test]
    fn truth_holes_are_counted_not_warned() {
        let text = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n\
                    1.0,0.5,1.5,0.9,1,0,0,0\n\
                    1.0167,,,,,,,\n\
                    1.0333,0.6,x,0.9,1,0,0,0\n\
                    1.05,0.7,1.7,0.9,,,,\n";
        let mut w = Warnings::default();
        let t = read_truth(text.as_bytes(), "truth.csv", &mut w).unwrap();
        assert_eq!(t.holes, 1);
        assert_eq!(t.trajectory.len(), 2);
        assert_eq!(t.trajectory[1].x_m, 0.7);
        assert_eq!(w.count(), 1);
        let e = w.first().unwrap();
        assert_eq!(
            (e.line, e.column, e.field.as_deref()),
            (4, Some(3), Some("y_m"))
        );
    }

    #[test]
    fn a_truth_without_positions_is_an_error() {
        let mut w = Warnings::default();
        let e = read_truth("t,x,y\n1,2,3\n".as_bytes(), "d/truth.csv", &mut w).unwrap_err();
        assert_eq!(e.file, "d/truth.csv");
    }
}
