//! Barometer readings and landmark floors through the import: GetSensorData `PRES` and `POSI`
//! floors, Sensor Logger `Barometer.csv` (hPa, and kPa guarded), phyphox `Pressure.csv`, and a
//! recipe's pressure file. Good readings become `Record::Pressure` on the log's clock; a bad
//! one is skipped with a warning naming file, line and field, and nothing else is lost.

use pdr::engine::{PressureSample, Record};
use pdr::io::import::recipe::Recipe;
use pdr::io::import::{import_all, import_with, Log, MemSet};
use pdr::io::ParseError;

mod common;
use common::imu;

fn one(files: Vec<(String, Vec<u8>)>) -> Log {
    let mut logs = import_all(&mut MemSet::new(files));
    assert_eq!(logs.len(), 1, "{logs:#?}");
    logs.pop().unwrap().unwrap()
}

fn pressures(log: &Log) -> Vec<PressureSample> {
    log.records
        .iter()
        .filter_map(|r| match r {
            Record::Pressure(p) => Some(*p),
            _ => None,
        })
        .collect()
}

/// The warning of `file` at `line`, when there is one.
fn warning<'a>(log: &'a Log, file: &str, line: u64) -> Option<&'a ParseError> {
    log.warnings
        .iter()
        .find(|w| w.file.ends_with(file) && w.line == line)
}

fn in_order(log: &Log) -> bool {
    log.records.windows(2).all(|w| w[0].t() <= w[1].t())
}

#[test]
fn get_sensor_data_pressure_and_floors() {
    let mut text = String::from("% LogFile created by the 'GetSensorData' App for Android.\n");
    for k in 0..50 {
        let t = 0.02 * k as f64;
        text += &format!("ACCE;{:.4};{:.4};0.1;0.2;9.8;3\n", t + 0.003, 500.0 + t);
    }
    // Line numbers: the header is line 1, the ACCE lines 2–51.
    text += "PRES;0.1030;500.1000;976.8699;3\n"; // 52
    text += "PRES;0.2050;500.2000;abc;3\n"; // 53: not a number
    text += "PRES;0.3030;500.3000;5000.0;3\n"; // 54: out of range
    text += "PRES;0.4030;500.4000;976.9000;3\n"; // 55
    text += "POSI;0.0500;1;49.4612219;11.1115901;0;100\n"; // 56
    text += "POSI;0.5000;2;49.4613229;11.1115677;-1;100\n"; // 57
    text += "POSI;0.7000;3;49.4612939;11.1115481;x;100\n"; // 58: bad floor, landmark kept
    text += "POSI;0.9000;4;49.4612939;11.1115481;-2.0;100\n"; // 59
    let log = one(vec![("route.txt".into(), text.into_bytes())]);
    let p = pressures(&log);
    assert_eq!(p.len(), 2, "{p:?}");
    // On the app clock by the least delay, as the accelerometer (3 ms).
    assert!(
        (p[0].t - 0.103).abs() < 1e-9 && p[0].hpa == 976.8699,
        "{p:?}"
    );
    assert!((p[1].t - 0.403).abs() < 1e-9 && p[1].hpa == 976.9, "{p:?}");
    let w = warning(&log, "route.txt", 53).expect("PRES not a number");
    assert_eq!((w.column, w.field.as_deref()), (Some(4), Some("Pres")));
    let w = warning(&log, "route.txt", 54).expect("PRES out of range");
    assert_eq!((w.column, w.field.as_deref()), (Some(4), Some("Pres")));
    assert!(w.message.contains("outside 100–1200 hPa"), "{w}");
    let w = warning(&log, "route.txt", 58).expect("bad floor");
    assert_eq!((w.column, w.field.as_deref()), (Some(6), Some("floorID")));
    let floors: Vec<Option<i32>> = log.truth.waypoints.iter().map(|w| w.floor).collect();
    assert_eq!(floors, [Some(0), Some(-1), None, Some(-2)]);
    assert_eq!(log.warnings.len(), 3, "{:#?}", log.warnings);
    assert_eq!(imu(&log.records).len(), 50, "nothing else lost");
    assert!(in_order(&log));
}

#[test]
fn sensor_logger_barometer_csv() {
    let mut files = common::import::load("sensor_logger_android", "rec/");
    let bar = "time,seconds_elapsed,relativeAltitude,pressure\n\
               1698745673480000000,0.038,0,976.5\n\
               1698745673500000000,0.058,0.1,n/a\n\
               1698745673520000000,0.078,0.2,97.64\n\
               1698745673540000000,0.098,0.3,5.0\n\
               1698745673560000000,0.118,0.4,976.3\n";
    files.push(("rec/Barometer.csv".into(), bar.as_bytes().to_vec()));
    let before = one(common::import::load("sensor_logger_android", "rec/"));
    let log = one(files);
    let p = pressures(&log);
    let hpa: Vec<f64> = p.iter().map(|p| p.hpa).collect();
    // 97.64 is in kPa: ×10.
    assert_eq!(hpa.len(), 3, "{hpa:?}");
    assert!(
        hpa[0] == 976.5 && (hpa[1] - 976.4).abs() < 1e-9 && hpa[2] == 976.3,
        "{hpa:?}"
    );
    assert!((p[0].t - 1698745673.48).abs() < 1e-6);
    let w = warning(&log, "Barometer.csv", 3).expect("n/a");
    assert_eq!((w.column, w.field.as_deref()), (Some(4), Some("pressure")));
    let w = warning(&log, "Barometer.csv", 5).expect("5 kPa = 50 hPa: out of range");
    assert!(w.message.contains("outside"), "{w}");
    // Nothing else lost: the same records as without the barometer, plus the readings.
    let others: Vec<&Record> = log
        .records
        .iter()
        .filter(|r| !matches!(r, Record::Pressure(_)))
        .collect();
    assert_eq!(others, before.records.iter().collect::<Vec<_>>());
    assert_eq!(log.warnings.len(), before.warnings.len() + 2);
    assert!(in_order(&log));
}

#[test]
fn sensor_logger_json_barometer() {
    let path = common::import::fixtures().join("sensor_logger.json");
    let log = one(vec![(
        "sensor_logger.json".into(),
        std::fs::read(path).unwrap(),
    )]);
    let p = pressures(&log);
    assert_eq!(p.len(), 1);
    assert!(
        (p[0].t - 1698745673.573).abs() < 1e-6 && p[0].hpa == 1013.2,
        "{p:?}"
    );
}

#[test]
fn phyphox_pressure_csv() {
    let dir = "phyphox 2023-10-31 09-47-53/";
    let mut files = common::import::load("phyphox", dir);
    let pres = "\"Time (s)\",\"Pressure (hPa)\"\n\
                1.000000000E-2,9.765000000E2\n\
                5.000000000E-2,NaN\n\
                9.000000000E-2,9.764000000E2\n";
    files.push((format!("{dir}Pressure.csv"), pres.as_bytes().to_vec()));
    let before = one(common::import::load("phyphox", dir));
    let log = one(files);
    let p = pressures(&log);
    assert_eq!(p.len(), 2, "{p:?}");
    assert!((p[0].t - 0.01).abs() < 1e-12 && (p[0].hpa - 976.5).abs() < 1e-9);
    assert!((p[1].t - 0.09).abs() < 1e-12 && (p[1].hpa - 976.4).abs() < 1e-9);
    let w = warning(&log, "Pressure.csv", 3).expect("NaN pressure");
    assert_eq!(
        (w.column, w.field.as_deref()),
        (Some(2), Some("Pressure (hPa)"))
    );
    assert_eq!(imu(&log.records), imu(&before.records));
    assert_eq!(log.warnings.len(), before.warnings.len() + 1);
    assert!(in_order(&log));
}

#[test]
fn recipe_pressure_in_pa_becomes_hpa_and_out_of_range_is_counted() {
    let mut acc = String::new();
    let mut bar = String::new();
    for k in 0..200 {
        let ms = 1000 + 10 * k;
        acc += &format!("{ms},0.1,0.2,9.8\n");
        if k % 10 == 0 {
            // Pa; two readings of 5 Pa (0.05 hPa) are out of range.
            let pa = if k == 50 || k == 60 { 5.0 } else { 97_650.0 };
            bar += &format!("{ms},{pa}\n");
        }
    }
    let files = vec![
        ("r/acc.csv".to_string(), acc.into_bytes()),
        ("r/bar.csv".to_string(), bar.into_bytes()),
    ];
    let r = Recipe::from_json(
        r#"{"recipe": 1, "name": "t", "files": [
            {"match": "acc.csv", "sensor": "accelerometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
             "time_unit": "ms", "unit": "m/s2"},
            {"match": "bar.csv", "sensor": "pressure", "columns": {"t": 1, "value": 2},
             "time_unit": "ms", "unit": "Pa"}]}"#,
    )
    .unwrap();
    let mut logs = import_with(&mut MemSet::new(files), std::slice::from_ref(&r));
    let log = logs.pop().unwrap().unwrap();
    let p = pressures(&log);
    assert_eq!(p.len(), 18);
    assert!(p.iter().all(|p| (p.hpa - 976.5).abs() < 1e-9));
    assert!((p[0].t - 1.0).abs() < 1e-12);
    assert_eq!(log.skipped, 2);
    let w = &log.warnings[0];
    assert!(
        w.file.ends_with("bar.csv") && w.message.contains("2 sample(s) outside"),
        "{w}"
    );
    assert_eq!(imu(&log.records).len(), 200);
    assert!(in_order(&log));
}
