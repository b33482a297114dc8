//! Import of every format: the project's pdr-log, the phone recorders' formats (Sensor Logger
//! folder, zip and JSON, phyphox, GnssLogger, GetSensorData) and the evaluation data sets' own
//! layouts (Oxford step-counter trace folders, Microsoft indoor traces, x-io foot CSVs).
//! Fixtures are small hand-made recordings under `tests/fixtures/import/`; damaged, huge and
//! late-starting files are `tests/import_robustness.rs`'s.

// Expected values computed with std's `sin` are fine in tests (see clippy.toml).
#![allow(clippy::disallowed_methods)]

mod common;
use common::import::*;
use common::{fixes, imu};
use nalgebra::Vector3;
use pdr::engine::Record;
use pdr::io::import::{import_all, Format, Platform, ZipSet};
use pdr::io::pdrlog;
use std::io::Cursor;

// ------------------------------------------------------------------------------------------
// Sensor Logger
// ------------------------------------------------------------------------------------------

#[test]
fn sensor_logger_android_folder() {
    let log = one(import_mem(load("sensor_logger_android", "rec/")));
    assert_eq!(log.format, Format::SensorLogger);
    assert_eq!(log.platform, Some(Platform::Android));
    assert_eq!(log.source, "rec");
    let s = imu(&log.records);
    assert_eq!(s.len(), 40, "40 good accelerometer lines, one bad");
    // ns → s, on the `time` clock with no offset.
    assert!(close(s[0].t, 1698745673.473, 1e-6), "{}", s[0].t);
    assert!(close(s[1].t - s[0].t, 0.01, 1e-6));
    // Total = Accelerometer (gravity removed) + Gravity; first sample: linear (x, y, z) =
    // (0.35 sin 0.4, 0, 0), gravity (0.31, 1.27, 9.72).
    let expect = Vector3::new(0.35 * 0.4f64.sin() + 0.31, 1.27, 9.72);
    assert!((s[0].accel - expect).norm() < 1e-5, "{:?}", s[0].accel);
    // The first gyroscope sample comes 2 ms later: it is not carried back to the first record
    // (the engine moves up to it when it comes), and every later record has it.
    assert!(s[0].gyro.is_none());
    assert!(s[1..].iter().all(|x| x.gyro.is_some()));
    assert!(s[5].mag.is_some());
    assert!(s[0].orientation.is_some());
    // Location: one fix of three has a negative accuracy.
    let f = fixes(&log.records);
    assert_eq!(f.len(), 2);
    assert_eq!(f[0].h_accuracy_m, 4.7);
    assert_eq!(f[0].bearing_deg, Some(271.5));
    assert_eq!(f[1].bearing_deg, None, "negative bearing is unknown");
    // The bad line: header is line 1, the bad one line 19, `abc` in column 3 (`z`).
    assert!(
        has_warning(&log, "rec/Accelerometer.csv", 19, Some(3)),
        "{:#?}",
        log.warnings
    );
    let w = log.warnings.iter().find(|w| w.line == 19).unwrap();
    assert_eq!(w.field.as_deref(), Some("z"));
    assert!(
        has_warning(&log, "rec/Location.csv", 3, Some(6)),
        "{:#?}",
        log.warnings
    );
    assert_eq!(log.skipped, 2);
    assert_round_trip(&log);
}

#[test]
fn sensor_logger_columns_matched_by_name() {
    let files = load("sensor_logger_android", "");
    let reference = one(import_mem(files.clone()));
    // Reorder the columns of every file (reverse them): the result must not change.
    let shuffled: Vec<(String, Vec<u8>)> = files
        .into_iter()
        .map(|(n, b)| {
            let text = String::from_utf8(b).unwrap();
            let out: String = text
                .lines()
                .map(|l| {
                    let mut f: Vec<&str> = l.split(',').collect();
                    f.reverse();
                    f.join(",") + "\n"
                })
                .collect();
            (n, out.into_bytes())
        })
        .collect();
    let log = one(import_mem(shuffled));
    assert_eq!(log.records, reference.records);
}

#[test]
fn sensor_logger_ios_g_units_flipped_to_android() {
    let log = one(import_mem(load("sensor_logger_ios", "")));
    assert_eq!(log.platform, Some(Platform::Ios));
    let s = imu(&log.records);
    assert_eq!(s.len(), 30);
    // iOS gravity face up is −1 g on z; with user acceleration −(0.35 sin 0.4) g/9.80665 on x.
    // After import: Android sign, m/s²: z = +9.80665.
    assert!(close(s[0].accel.z, 9.80665, 1e-5), "{:?}", s[0].accel);
    assert!(
        close(s[0].accel.x, 0.35 * 0.4f64.sin(), 1e-5),
        "{:?}",
        s[0].accel
    );
    for x in &s {
        assert!(close(x.accel.norm(), 9.8, 1.5));
    }
    // Face up, top north in Core Motion's (north, west, up) frame → identity in ENU.
    let q = s[0].orientation.unwrap();
    assert!(q.angle() < 1e-6, "{q:?}");
    // The NaN gyroscope line is skipped with a warning naming it.
    assert!(
        has_warning(&log, "Gyroscope.csv", 12, Some(4)),
        "{:#?}",
        log.warnings
    );
    // Rad/s as they are.
    assert!(close(s[1].gyro.unwrap().x, 0.01, 1e-12));
    assert_round_trip(&log);
}

#[test]
fn sensor_logger_ios_platform_detected_without_metadata() {
    let files: Vec<_> = load("sensor_logger_ios", "")
        .into_iter()
        .filter(|(n, _)| n != "Metadata.csv")
        .collect();
    let log = one(import_mem(files));
    assert_eq!(log.platform, Some(Platform::Ios), "g units mean iOS");
    assert!(close(imu(&log.records)[0].accel.z, 9.80665, 1e-5));
}

#[test]
fn sensor_logger_total_acceleration_and_old_header() {
    // Android with TotalAcceleration.csv and the older `time,z,y,x` header; no Metadata.
    let mut text = String::from("time,z,y,x\n");
    for k in 0..20u64 {
        text += &format!(
            "{},9.81,0.5,{}\n",
            1_600_000_000_000_000_000 + k * 20_000_000,
            k as f64 * 0.01
        );
    }
    let files = vec![
        ("TotalAcceleration.csv".to_string(), text.into_bytes()),
        (
            "Accelerometer.csv".to_string(),
            b"time,z,y,x\n1600000000000000000,5,5,5\n".to_vec(),
        ),
    ];
    let log = one(import_mem(files));
    assert_eq!(log.platform, Some(Platform::Android));
    let s = imu(&log.records);
    assert_eq!(
        s.len(),
        20,
        "TotalAcceleration is used, Accelerometer ignored"
    );
    assert_eq!(s[3].accel, Vector3::new(0.03, 0.5, 9.81));
    assert!(close(s[1].t, 1_600_000_000.02, 1e-9));
}

#[test]
fn sensor_logger_without_gravity_is_an_error() {
    let files: Vec<_> = load("sensor_logger_android", "rec/")
        .into_iter()
        .filter(|(n, _)| !n.ends_with("Gravity.csv"))
        .collect();
    let r = import_mem(files);
    assert_eq!(r.len(), 1);
    let e = r.into_iter().next().unwrap().unwrap_err();
    assert!(e.file.ends_with("rec/Accelerometer.csv"), "{e}");
    assert!(e.message.contains("gravity"), "{e}");
}

#[test]
fn sensor_logger_damaged_optional_file_is_a_warning() {
    let files: Vec<_> = load("sensor_logger_android", "rec/")
        .into_iter()
        .map(|(n, b)| {
            if n.ends_with("Magnetometer.csv") {
                (n, b"\xff\xfe\x00junk\n1,2,3\n".to_vec())
            } else {
                (n, b)
            }
        })
        .collect();
    let log = one(import_mem(files));
    assert_eq!(imu(&log.records).len(), 40);
    assert!(imu(&log.records).iter().all(|s| s.mag.is_none()));
    assert!(
        has_warning(&log, "rec/Magnetometer.csv", 1, None),
        "{:#?}",
        log.warnings
    );
}

#[test]
fn sensor_logger_zip_same_as_folder() {
    let files = load("sensor_logger_android", "Recording 2023-10-31/");
    let folder = one(import_mem(files.clone()));
    let zip = zip_bytes(&files);
    // A zip as a file set…
    let mut set = ZipSet::new(Cursor::new(zip.clone()), "walk.zip").unwrap();
    let from_zip = one(import_all(&mut set));
    assert_eq!(from_zip.records, folder.records);
    assert_eq!(from_zip.source, "walk.zip/Recording 2023-10-31");
    assert!(from_zip.warnings[0].file.starts_with("walk.zip/"));
    // …and a zip inside a file set (an upload).
    let uploaded = one(import_mem(vec![("walk.zip".into(), zip)]));
    assert_eq!(uploaded.records, folder.records);
}

#[test]
fn sensor_logger_json() {
    let log = one(import_mem(load("sensor_logger.json", "")));
    assert_eq!(log.format, Format::SensorLoggerJson);
    assert_eq!(log.platform, Some(Platform::Android));
    let s = imu(&log.records);
    assert_eq!(s.len(), 20);
    assert!(close(s[0].t, 1698745673.473, 1e-6));
    let expect = Vector3::new(0.35 * 0.4f64.sin() + 0.31, 1.27, 9.72);
    assert!((s[0].accel - expect).norm() < 1e-5, "{:?}", s[0].accel);
    // The gyroscope comes 2 ms later: not carried back to the first record.
    assert!(s[0].gyro.is_none() && s[1].gyro.is_some());
    assert!(s[0].orientation.unwrap().angle() < 1e-12);
    assert_eq!(fixes(&log.records).len(), 1);
    // The `n/a` element: field `z` named, line of the element.
    let w = &log.warnings[0];
    assert_eq!(w.file, "sensor_logger.json");
    assert_eq!(w.field.as_deref(), Some("z"));
    assert_eq!(w.line, 10, "{w}");
    assert!(w.message.contains("element 10"), "{w}");
    assert_round_trip(&log);
}

#[test]
fn sensor_logger_json_cut_short_keeps_what_was_read() {
    let (name, bytes) = load("sensor_logger.json", "").remove(0);
    let cut = bytes[..bytes.len() * 2 / 3].to_vec();
    let log = one(import_mem(vec![(name, cut)]));
    assert!(imu(&log.records).len() > 5);
    assert!(log
        .warnings
        .iter()
        .any(|w| w.message.contains("JSON damaged")));
}

// ------------------------------------------------------------------------------------------
// phyphox
// ------------------------------------------------------------------------------------------

#[test]
fn phyphox_folder_and_zip() {
    let files = load("phyphox", "phyphox 2023-10-31 09-47-53/");
    let log = one(import_mem(files.clone()));
    assert_eq!(log.format, Format::Phyphox);
    let s = imu(&log.records);
    assert_eq!(s.len(), 30);
    assert!(
        close(s[0].t, 0.0048, 1e-12),
        "seconds from the start, as written"
    );
    assert!(close(s[0].accel.y, 9.62, 1e-6));
    assert!(s[0].gyro.is_some() && s[2].mag.is_some());
    assert!(close(s[5].gyro.unwrap().x, 0.05, 1e-12), "{:?}", s[5].gyro);
    assert!(close(s[2].mag.unwrap().y, -38.1, 1e-12));
    let f = fixes(&log.records);
    assert_eq!(f.len(), 2);
    assert_eq!(f[1].speed_mps, None, "NaN is a missing value");
    assert_eq!(f[0].altitude_m, Some(52.4));
    assert!(
        has_warning(&log, "Accelerometer.csv", 14, Some(3)),
        "{:#?}",
        log.warnings
    );
    assert_round_trip(&log);
    let mut zip = ZipSet::new(Cursor::new(zip_bytes(&files)), "phyphox.zip").unwrap();
    let z = one(import_all(&mut zip));
    assert_eq!(z.records, log.records);
}

#[test]
fn phyphox_semicolon_and_decimal_comma() {
    let log = one(import_mem(load("phyphox_semicolon", "")));
    let s = imu(&log.records);
    assert_eq!(s.len(), 25);
    assert!(close(s[0].t, 0.009364549, 1e-12));
    assert_eq!(s[0].accel, Vector3::new(0.05, 9.364549, 2.81));
    assert!(log.warnings.is_empty(), "{:?}", log.warnings);
}

#[test]
fn phyphox_linear_acceleration_only_is_refused() {
    let r = import_mem(load("phyphox_linear", ""));
    assert_eq!(r.len(), 1);
    let e = r.into_iter().next().unwrap().unwrap_err();
    assert_eq!(e.file, "Linear Accelerometer.csv");
    assert!(e.message.contains("linear acceleration"), "{e}");
}

// ------------------------------------------------------------------------------------------
// GnssLogger
// ------------------------------------------------------------------------------------------

#[test]
fn gnss_logger() {
    let log = one(import_mem(load("gnss_logger.txt", "")));
    assert_eq!(log.format, Format::GnssLogger);
    let s = imu(&log.records);
    assert_eq!(s.len(), 30);
    // utcTimeMillis → s.
    assert!(close(s[0].t, 1698745673.473, 1e-9));
    // Calibrated Accel preferred over UncalAccel − bias (z 9.81 vs 9.80).
    assert!(close(s[0].accel.z, 9.81, 1e-9), "{:?}", s[0].accel);
    // No calibrated Gyro: UncalGyro − drift.
    let g = s[1].gyro.unwrap();
    assert!((g - Vector3::new(0.10, -0.02, 0.0)).norm() < 1e-9, "{g:?}");
    // Calibrated Mag.
    assert_eq!(s[1].mag, Some(Vector3::new(-18.0, 30.0, -42.0)));
    // OrientationDeg yaw 90°: the top of the phone points east.
    let q = s[0].orientation.unwrap();
    assert!((q * Vector3::y() - Vector3::x()).norm() < 1e-9);
    // Fixes: GPS preferred over FLP; the one without accuracy skipped.
    let f = fixes(&log.records);
    assert_eq!(f.len(), 2);
    assert_eq!(f[0].h_accuracy_m, 4.7);
    assert!(close(f[0].t, 1698745673.573, 1e-9));
    assert!(
        has_warning(&log, "gnss_logger.txt", 84, Some(5)),
        "{:#?}",
        log.warnings
    );
    assert_round_trip(&log);
}

#[test]
fn gnss_logger_old_fix_layout() {
    let text = "# Fix,Provider,Latitude,Longitude,Altitude,Speed,Accuracy,(UTC)TimeInMs\n\
                # Accel,utcTimeMillis,elapsedRealtimeNanos,AccelXMps2,AccelYMps2,AccelZMps2\n\
                Accel,1500000000000,1,0,0,9.8\n\
                Fix,gps,45.5,9.2,120.0,0.5,8.0,1500000000500\n\
                Accel,1500000001000,2,0,0,9.8\n";
    let log = one(import_mem(vec![(
        "old.txt".into(),
        text.as_bytes().to_vec(),
    )]));
    let f = fixes(&log.records);
    assert_eq!(f.len(), 1);
    assert_eq!(
        (f[0].t, f[0].lat_deg, f[0].h_accuracy_m),
        (1_500_000_000.5, 45.5, 8.0)
    );
    assert_eq!(f[0].altitude_m, Some(120.0));
}

// ------------------------------------------------------------------------------------------
// GetSensorData
// ------------------------------------------------------------------------------------------

#[test]
fn get_sensor_data() {
    let log = one(import_mem(load("get_sensor_data.txt", "")));
    assert_eq!(log.format, Format::GetSensorData);
    let s = imu(&log.records);
    assert_eq!(s.len(), 30);
    // Spacing from SensorTimestamp (exactly 20 ms), placed on the app clock by the least delay
    // (4 ms for the first sample).
    for w in s.windows(2) {
        assert!(close(w[1].t - w[0].t, 0.02, 1e-9), "{} {}", w[0].t, w[1].t);
    }
    assert!(close(s[0].t, 0.064, 1e-9), "{}", s[0].t);
    // The gyroscope and the AHRS begin after the accelerometer: the first record has neither
    // (nothing is moved earlier than it was measured); the engine moves up to the OS attitude
    // when it comes.
    assert!(s[0].gyro.is_none() && s[0].orientation.is_none());
    assert!(s[1].gyro.is_some() && s[1].orientation.is_some());
    let run = pdr::engine::replay(pdr::engine::PipelineConfig::default(), &log.records).unwrap();
    assert_eq!(
        run.pipeline.orientation_diagnostics().map(|o| o.source),
        Some(pdr::engine::OrientationSource::Os)
    );
    // AHRS rotation vector (0, 0, sin 15°) → 30° about up.
    let q = s[1].orientation.unwrap();
    assert!(close(q.angle(), 30f64.to_radians(), 1e-4), "{}", q.angle());
    // Each GNSS fix is written twice.
    let f = fixes(&log.records);
    assert_eq!(f.len(), 2);
    assert_eq!(f[0].h_accuracy_m, 4.0);
    // POSI → waypoints in metres east/north of the first.
    let w = &log.truth.waypoints;
    assert_eq!(w.len(), 3);
    assert_eq!((w[0].t, w[0].x_m, w[0].y_m), (0.052, 0.0, 0.0));
    assert!(
        close(w[1].x_m, 0.0, 0.01) && close(w[1].y_m, 6.0, 0.1),
        "{:?}",
        w[1]
    );
    assert!(
        close(w[2].x_m, 5.94, 0.1) && close(w[2].y_m, 6.0, 0.1),
        "{:?}",
        w[2]
    );
    // The ACCE line with an empty Acc_Y.
    let bad = log.warnings.iter().find(|w| w.column == Some(5)).unwrap();
    assert_eq!(bad.field.as_deref(), Some("Acc_Y"));
    assert_eq!(bad.file, "get_sensor_data.txt");
    assert_round_trip(&log);
}

// ------------------------------------------------------------------------------------------
// The project's own format and the evaluation data sets' layouts
// ------------------------------------------------------------------------------------------

#[test]
fn pdr_log_every_record_kind() {
    let log = one(import_mem(load("walk.pdrlog", "")));
    assert_eq!(log.format, Format::PdrLog);
    assert_sane(&log);
    assert_eq!(log.skipped, 0);
    let s = imu(&log.records);
    assert_eq!(s.len(), 300);
    // Optional groups: every third sample carries gyroscope, magnetometer and attitude.
    assert!(s[0].gyro.is_some() && s[0].mag.is_some() && s[0].orientation.is_some());
    assert!(s[1].gyro.is_none() && s[1].mag.is_none() && s[1].orientation.is_none());
    assert_eq!(s[0].mag.unwrap(), Vector3::new(20.5, -3.25, -40.0));
    let f = fixes(&log.records);
    assert_eq!(f.len(), 2);
    assert_eq!((f[0].altitude_m, f[1].altitude_m), (Some(12.0), None));
    assert_eq!(
        log.records
            .iter()
            .filter(|r| matches!(r, Record::Gap(..)))
            .count(),
        1
    );
    assert_round_trip(&log);
}

#[test]
fn pdr_log_bad_lines_name_line_and_field() {
    let text = "# pdr-log 1\nimu,1,0,0,9.8,,,,,,,,,,\nimu,2,0,abc,9.8,,,,,,,,,,\nimu,3,0,0,9.8,1,2,,,,,,,,\nweird,4\nimu,5,0,0,9.8,,,,,,,,,,\n";
    let log = one(import_mem(vec![(
        "x.pdrlog".into(),
        text.as_bytes().to_vec(),
    )]));
    assert_eq!(
        imu(&log.records).len(),
        2,
        "the good lines before and after are kept"
    );
    assert_eq!(log.skipped, 3);
    assert!(has_warning(&log, "x.pdrlog", 3, Some(4)));
    assert_eq!(log.warnings[0].field.as_deref(), Some("ay"));
    assert!(has_warning(&log, "x.pdrlog", 4, Some(6)));
    assert!(has_warning(&log, "x.pdrlog", 5, Some(1)));
    // Not a pdr-log at all: the version tag is checked.
    let e = pdrlog::read(&b"# pdr-log 9\nimu,1\n"[..], "y.pdrlog").unwrap_err();
    assert_eq!((e.file.as_str(), e.line), ("y.pdrlog", 1));
    assert!(pdrlog::read(&b""[..], "empty.pdrlog").is_err());
}

#[test]
fn oxford_trace_folder() {
    let log = one(import_mem(load("oxford", "")));
    assert_eq!(log.format, Format::OxfordSteps);
    assert_eq!(log.platform, Some(Platform::Android));
    assert_eq!(log.group.as_deref(), Some("FrontPocket"));
    assert_sane(&log);
    let s = imu(&log.records);
    // Nanoseconds since boot become seconds on the same clock; gravity on +y stays.
    assert!(close(s[0].t, 263239.144953734, 1e-6), "{}", s[0].t);
    assert!(close(s[0].accel.y, 9.81, 1e-6));
    // 12 contacts, one of them a bounce of the same foot 0.4 s after its landing.
    assert_eq!(log.truth.steps, Some(12));
    assert_eq!(log.truth.step_events.len(), 12);
    assert_eq!(log.truth.steps_debounced(), Some(11));
    assert_round_trip(&log);
}

#[test]
fn ms_indoor_trace() {
    let log = one(import_mem(load("ms_indoor.txt", "")));
    assert_eq!(log.format, Format::MsIndoor);
    assert_sane(&log);
    let s = imu(&log.records);
    assert_eq!(
        s.len(),
        400,
        "uncalibrated, Wi-Fi and waypoint lines are not samples"
    );
    assert!(close(s[0].t, 1574594529.04, 1e-6));
    assert_eq!(log.truth.waypoints.len(), 3);
    assert!(close(log.truth.waypoints[2].x_m, 5.4, 1e-9));
    // The rotation vector (w implied) of a phone flat, screen up, top to the north-east.
    let q = s[10].orientation.unwrap();
    let top = q * Vector3::y();
    assert!(close(top.x, top.y, 1e-6) && top.x > 0.7, "{top:?}");
    assert!(s[10].gyro.is_some() && s[10].mag.is_some());
    assert_round_trip(&log);
}

#[test]
fn xio_foot_units() {
    let log = one(import_mem(load("xio_foot.csv", "")));
    assert_eq!(log.format, Format::XioFoot);
    assert!(log.truth.loop_closure);
    assert_sane(&log);
    let s = imu(&log.records);
    assert_eq!(s.len(), 500);
    // g become m/s², deg/s become rad/s.
    assert!(close(s[0].accel.z, 9.80665, 1e-9));
    let k = s.iter().position(|x| x.t >= 1.5).unwrap();
    let want = 90f64.to_radians() * (2.0 * std::f64::consts::PI * 0.9 * s[k].t).sin();
    assert!(close(s[k].gyro.unwrap().x, want, 1e-4));
    assert_round_trip(&log);
}
