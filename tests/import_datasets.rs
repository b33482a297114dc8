//! The data sets' own folder layouts read by sniffing: TyrEx (Android and iOS), UbiComp 2013 and
//! WeAllWalk. Small recordings built in memory: units, signs and frames converted, the truth each
//! carries, the group, bad lines as warnings naming file, line, column and field, unreadable
//! folders as errors naming the file, look-alike folders left alone, and a user's recipe taking
//! precedence. No file on disk: the tests also run in headless Chromium (wasm-bindgen-test).
//! The real sets of `../shared/data` are `tests/import_shared_sets.rs`'s.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use pdr::io::import::recipe::Recipe;
use pdr::io::import::{import_all, import_with, Format, Log, MemSet, Platform, G0};
use pdr::io::ParseError;
use pdr::sim::{formats, scenarios};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

mod common;
use common::imu;

/// Files as (name, text).
fn files(list: &[(&str, &str)]) -> Vec<(String, Vec<u8>)> {
    list.iter()
        .map(|(n, t)| (n.to_string(), t.as_bytes().to_vec()))
        .collect()
}

/// Every log of the files.
fn read(list: &[(&str, &str)]) -> Vec<Result<Log, ParseError>> {
    import_all(&mut MemSet::new(files(list)))
}

/// The one log of the files, read without an error.
fn one(list: &[(&str, &str)]) -> Log {
    let mut logs = read(list);
    assert_eq!(logs.len(), 1, "{logs:#?}");
    logs.pop().unwrap().unwrap()
}

/// The one error of the files.
fn error(list: &[(&str, &str)]) -> ParseError {
    let mut logs = read(list);
    assert_eq!(logs.len(), 1, "{logs:#?}");
    logs.pop().unwrap().unwrap_err()
}

/// Whether the log has a warning on `line`, `column` and `field` of the file ending so.
fn warned(log: &Log, file_ends: &str, line: u64, column: usize, field: &str) -> bool {
    log.warnings.iter().any(|w| {
        w.file.ends_with(file_ends)
            && w.line == line
            && w.column == Some(column)
            && w.field.as_deref() == Some(field)
    })
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ------------------------------------------------------------------------------------------
// TyrEx
// ------------------------------------------------------------------------------------------

const PROPERTIES: &str = "[Device]\nManufacturer = LGE\nModel = Nexus 5\nOSVersion = 23\n\n\
                          [Time]\nStartTime = 1464871900";

/// An Android TyrEx folder: the phone upright (top up), 100 Hz accelerometer from 0.5 s, the
/// gyroscope from 0.55 s, the rotation vector of the top pointing up and the screen facing
/// south (x east), a truth with one hole.
fn tyrex_android(dir: &str) -> Vec<(String, String)> {
    let acc: String = (0..20)
        .map(|i| format!("{:.9} 0.1 9.8 0.2\n", 0.5 + 0.01 * i as f64))
        .collect();
    let gyr: String = (0..15)
        .map(|i| format!("{:.9} 0.01 -0.02 0.03\n", 0.55 + 0.01 * i as f64))
        .collect();
    let mag: String = (0..4)
        .map(|i| format!("{:.9} 0.0 -40.0 -20.0\n", 0.5 + 0.05 * i as f64))
        .collect();
    // Device → ENU: +90° about x takes the top (y) to up (z).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let rv: String = (0..10)
        .map(|i| format!("{:.9} {h} 0.0 0.0 {h} 0.17453292\n", 0.52 + 0.02 * i as f64))
        .collect();
    let truth = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n\
                 0.5000,1.00000,2.00000,0.95000,1,0,0,0\n\
                 0.5167,,,,,,,\n\
                 0.5333,1.01000,2.00500,0.95000,1,0,0,0\n";
    [
        ("accelerometer.txt", acc),
        ("gyroscope-calibrated.txt", gyr),
        ("magnetometer-calibrated.txt", mag),
        ("rotation-vector.txt", rv),
        ("record.properties", PROPERTIES.to_string()),
        ("timeAlignment.txt", "  -3.1500000e+00\n".to_string()),
        ("truth.csv", truth.to_string()),
    ]
    .into_iter()
    .map(|(n, t)| (format!("{dir}{n}"), t))
    .collect()
}

fn as_refs(v: &[(String, String)]) -> Vec<(&str, &str)> {
    v.iter().map(|(n, t)| (n.as_str(), t.as_str())).collect()
}

#[wasm_bindgen_test(unsupported = test)]
fn tyrex_android_folder() {
    let f = tyrex_android("Guillaume_Nexus5_NoDist_Texting/");
    let log = one(&as_refs(&f));
    assert_eq!(log.format, Format::Tyrex);
    assert_eq!(log.format.as_str(), "tyrex");
    assert_eq!(log.platform, Some(Platform::Android));
    assert_eq!(log.group.as_deref(), Some("Texting"));
    assert_eq!(log.source, "Guillaume_Nexus5_NoDist_Texting");
    assert_eq!(log.date_unix_s, Some(1_464_871_900.0));
    assert!(
        log.warnings.is_empty() && log.skipped == 0,
        "{:#?}",
        log.warnings
    );
    let s = imu(&log.records);
    assert_eq!(s.len(), 20, "one record per accelerometer sample");
    // The phone's own clock, no offset; m/s² as written.
    assert!(close(s[0].t, 0.5, 1e-12), "{}", s[0].t);
    assert_eq!(s[0].accel, Vector3::new(0.1, 9.8, 0.2));
    // The gyroscope starts 50 ms after the accelerometer: the records before it have none
    // (nothing is moved earlier than it was measured), the later ones carry it; the rotation
    // vector is the orientation, device → ENU: gravity up.
    assert_eq!(s[0].gyro, None);
    assert!(s[5..].iter().all(|x| x.gyro.is_some()));
    let q = s[5].orientation.unwrap();
    assert!(close((q * s[5].accel).z, 9.8, 1e-9), "{:?}", q * s[5].accel);
    assert!(s[0].mag.is_some());
    // The truth: two positions, the hole skipped without a warning.
    let tr = &log.truth.trajectory;
    assert_eq!(tr.len(), 2, "{tr:?}");
    assert_eq!(
        (tr[0].t, tr[0].x_m, tr[0].y_m, tr[0].z_m),
        (0.5, 1.0, 2.0, 0.95)
    );
    assert_eq!(tr[1].t, 0.5333);
    assert!(log.truth.steps.is_none() && log.truth.turns.is_empty());
}

#[wasm_bindgen_test(unsupported = test)]
fn tyrex_android_raw_files_when_no_calibrated_ones() {
    let f: Vec<(String, String)> = tyrex_android("rec/")
        .into_iter()
        .map(|(n, t)| (n.replace("-calibrated", ""), t))
        .filter(|(n, _)| !n.ends_with("truth.csv"))
        .collect();
    let log = one(&as_refs(&f));
    assert_eq!(log.format, Format::Tyrex);
    assert_eq!(log.group, None, "not a TyrEx walk name");
    let s = imu(&log.records);
    assert!(s[5].gyro.is_some() && s[5].mag.is_some());
    assert!(
        log.truth.trajectory.is_empty(),
        "a user's recording has no truth"
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn tyrex_ios_folder() {
    // Face up, top north: Core Motion reads −1 g on z; its attitude (device → x north, y west,
    // z up) is −90° about z, which is the identity in ENU.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let acc: String = (0..10)
        .map(|i| format!("{:.4} 0.0100 -0.0200 -1.0000\n", 60217.0 + 0.01 * i as f64))
        .collect();
    let gyr: String = (0..10)
        .map(|i| format!("{:.4} 0.1079 0.0022 0.0145\n", 60217.0 + 0.01 * i as f64))
        .collect();
    let mag: String = (0..10)
        .map(|i| {
            format!(
                "{:.4} -7.2650 -39.1329 7.9500 2\n",
                60217.0 + 0.01 * i as f64
            )
        })
        .collect();
    let att: String = (0..10)
        .map(|i| format!("{:.4} {h} 0.0 0.0 {}\n", 60217.0 + 0.01 * i as f64, -h))
        .collect();
    let d = "Guillaume_iPhone5_Dist_BackPocket/";
    let list = [
        (format!("{d}accelerometer.txt"), acc),
        (format!("{d}gyroscope.txt"), gyr),
        (format!("{d}magnetometer-calibrated.txt"), mag),
        (format!("{d}attitude.txt"), att),
        (
            format!("{d}description.txt"),
            "[Time]\nBootTime = 60217.4626".to_string(),
        ),
    ];
    let log = one(&as_refs(&list));
    assert_eq!(log.format, Format::Tyrex);
    assert_eq!(log.platform, Some(Platform::Ios));
    assert_eq!(log.group.as_deref(), Some("BackPocket"));
    assert_eq!(
        log.date_unix_s, None,
        "a boot clock says nothing of the date"
    );
    assert!(log.warnings.is_empty(), "{:#?}", log.warnings);
    let s = imu(&log.records);
    assert_eq!(s.len(), 10);
    assert!(close(s[0].t, 60217.0, 1e-9));
    // g and Core Motion's sign → m/s², Android sign.
    assert!((s[0].accel - Vector3::new(-0.01 * G0, 0.02 * G0, G0)).norm() < 1e-9);
    assert_eq!(s[0].gyro, Some(Vector3::new(0.1079, 0.0022, 0.0145)));
    assert_eq!(s[0].mag, Some(Vector3::new(-7.265, -39.1329, 7.95)));
    let q = s[0].orientation.unwrap();
    assert!(q.angle() < 1e-9, "device frame = ENU: {q:?}");
    assert!(close((q * s[0].accel).z, G0, 1e-9));
}

#[wasm_bindgen_test(unsupported = test)]
fn tyrex_bad_lines_are_warnings_naming_file_line_column_and_field() {
    let mut f = tyrex_android("w_p_Dist_Swinging/");
    f[0].1 = f[0].1.replacen("0.1 9.8 0.2\n", "0.1 abc 0.2\n", 1); // line 1
                                                                   // rotation-vector.txt line 3: a vector of norm 2.2, no rotation.
    let rv = &mut f
        .iter_mut()
        .find(|x| x.0.ends_with("rotation-vector.txt"))
        .unwrap()
        .1;
    let mut lines: Vec<&str> = rv.lines().collect();
    lines.insert(2, "0.6 2.0 0.0 0.0 1.0 0.1");
    *rv = lines.join("\n") + "\n";
    let truth = &mut f.iter_mut().find(|x| x.0.ends_with("truth.csv")).unwrap().1;
    truth.push_str("0.55,1.0,2.0,oops,1,0,0,0\n");
    let log = one(&as_refs(&f));
    assert!(
        warned(&log, "w_p_Dist_Swinging/accelerometer.txt", 1, 3, "ay"),
        "{:#?}",
        log.warnings
    );
    assert!(
        warned(&log, "rotation-vector.txt", 3, 2, "x"),
        "{:#?}",
        log.warnings
    );
    assert!(
        warned(&log, "truth.csv", 5, 4, "z_m"),
        "{:#?}",
        log.warnings
    );
    assert_eq!(log.skipped, 3, "{:#?}", log.warnings);
    assert_eq!(imu(&log.records).len(), 19);
    assert_eq!(log.truth.trajectory.len(), 2);
}

#[wasm_bindgen_test(unsupported = test)]
fn tyrex_without_accelerometer_is_an_error_naming_it() {
    let f: Vec<(String, String)> = tyrex_android("walk/")
        .into_iter()
        .filter(|(n, _)| !n.ends_with("accelerometer.txt"))
        .collect();
    let e = error(&as_refs(&f));
    assert_eq!(e.file, "walk/accelerometer.txt", "{e}");
    // An accelerometer file without a sample: an error naming it.
    let mut f = tyrex_android("walk/");
    f[0].1 = "\n\n".to_string();
    let e = error(&as_refs(&f));
    assert_eq!(e.file, "walk/accelerometer.txt", "{e}");
}

#[wasm_bindgen_test(unsupported = test)]
fn look_alike_folders_are_not_tyrex() {
    // An accelerometer.txt without a TyrEx marker file, or of comma-separated lines, or a marker
    // without any sensor file: not claimed.
    let acc = "0.5 0.1 9.8 0.2\n0.51 0.1 9.8 0.2\n";
    for list in [
        vec![("a/accelerometer.txt", acc)],
        vec![
            ("a/accelerometer.txt", acc),
            ("a/record.properties", "name = value\n"),
        ],
        vec![
            ("a/accelerometer.txt", "t,x,y,z\n0.5,0.1,9.8,0.2\n"),
            ("a/record.properties", PROPERTIES),
        ],
        vec![
            ("a/record.properties", PROPERTIES),
            ("a/notes.txt", "hello"),
        ],
        vec![
            ("a/accelerometer.txt", acc),
            ("a/description.txt", "a walk in the park"),
        ],
    ] {
        let logs = read(&list);
        assert!(
            logs.iter()
                .all(|l| l.as_ref().map_or(true, |l| l.format != Format::Tyrex)),
            "{list:?}: {logs:#?}"
        );
    }
}

// ------------------------------------------------------------------------------------------
// UbiComp 2013
// ------------------------------------------------------------------------------------------

const UBI_TRUTH: &str = r#"{
 "steps": 70,
 "walk_start_s": 16155.1,
 "walk_end_s": 16155.15,
 "walk_start_sample": 3,
 "walk_end_sample": 8,
 "placement": "back pocket",
 "person": "p1",
 "units": {"acc": "m/s^2"}
}
"#;

fn ubicomp13(dir: &str, truth: &str) -> Vec<(String, String)> {
    let t = |i: usize| format!("{}.{:09}", 16155, 73_486_322 + 10_000_000 * i);
    let acc: String = (0..10)
        .map(|i| format!("{},-1.78,5.88,8.81\n", t(i)))
        .collect();
    let gyr: String = (0..10)
        .map(|i| format!("{},-2.72,-0.49,1.32\n", t(i)))
        .collect();
    let mag: String = (0..10)
        .map(|i| format!("{},7.29,-21.67,-15.78\n", t(i)))
        .collect();
    [
        ("acc.csv", acc),
        ("gyr.csv", gyr),
        ("mag.csv", mag),
        ("truth.json", truth.to_string()),
    ]
    .into_iter()
    .map(|(n, t)| (format!("{dir}{n}"), t))
    .collect()
}

#[wasm_bindgen_test(unsupported = test)]
fn ubicomp13_folder() {
    let f = ubicomp13(
        "p1.1_Female_20-29_170-179cm_Trousers_back_pocket/",
        UBI_TRUTH,
    );
    let log = one(&as_refs(&f));
    assert_eq!(log.format, Format::Ubicomp13);
    assert_eq!(log.format.as_str(), "ubicomp13");
    assert_eq!(log.platform, Some(Platform::Android));
    assert_eq!(log.group.as_deref(), Some("BackPocket"));
    assert!(log.warnings.is_empty(), "{:#?}", log.warnings);
    assert_eq!(log.truth.steps, Some(70));
    assert_eq!(log.truth.step_window, Some((16155.1, 16155.15)));
    let s = imu(&log.records);
    assert_eq!(s.len(), 10);
    assert!(close(s[0].t, 16155.073486322, 1e-9), "{}", s[0].t);
    assert_eq!(s[0].accel, Vector3::new(-1.78, 5.88, 8.81));
    assert_eq!(s[0].gyro, Some(Vector3::new(-2.72, -0.49, 1.32)));
    assert_eq!(s[0].mag, Some(Vector3::new(7.29, -21.67, -15.78)));
    assert!(s.iter().all(|x| x.orientation.is_none()));
    // gyr.csv and mag.csv are optional.
    let f: Vec<_> = f
        .into_iter()
        .filter(|(n, _)| n.ends_with("acc.csv") || n.ends_with("truth.json"))
        .collect();
    let log = one(&as_refs(&f));
    assert!(imu(&log.records).iter().all(|x| x.gyro.is_none()));
}

#[wasm_bindgen_test(unsupported = test)]
fn ubicomp13_errors_and_warnings() {
    let mut f = ubicomp13("w/", UBI_TRUTH);
    f[0].1 = f[0].1.replacen(",5.88,", ",,", 1); // acc.csv line 1
    f[1].1 = f[1].1.replacen("-0.49", "x", 2); // gyr.csv line 1 (the second is line 2)
    let log = one(&as_refs(&f));
    assert!(warned(&log, "w/acc.csv", 1, 3, "y"), "{:#?}", log.warnings);
    assert!(warned(&log, "w/gyr.csv", 2, 3, "y"), "{:#?}", log.warnings);
    assert_eq!(log.skipped, 3);
    // No acc.csv: an error naming it.
    let g: Vec<_> = ubicomp13("w/", UBI_TRUTH)
        .into_iter()
        .filter(|(n, _)| !n.ends_with("acc.csv"))
        .collect();
    assert_eq!(error(&as_refs(&g)).file, "w/acc.csv");
    // A truth.json that is no JSON, or whose window ends before it starts: an error naming it.
    for truth in [
        "{\"walk_start_s\": 1.0, ",
        "{\"walk_start_s\": 2.0, \"walk_end_s\": 1.0}",
        "{\"walk_start_s\": \"soon\", \"walk_end_s\": 1.0}",
    ] {
        let e = error(&as_refs(&ubicomp13("w/", truth)));
        assert_eq!(e.file, "w/truth.json", "{truth}: {e}");
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_csv_folder_without_the_truth_is_not_ubicomp13() {
    // The same three files without truth.json, or with a truth.json of another kind: any
    // logger's header-less CSVs, which only a recipe reads.
    let f: Vec<_> = ubicomp13("w/", UBI_TRUTH)
        .into_iter()
        .filter(|(n, _)| !n.ends_with("truth.json"))
        .collect();
    assert!(read(&as_refs(&f)).is_empty());
    let f = ubicomp13("w/", "{\"steps\": 70}");
    assert!(read(&as_refs(&f)).is_empty());
}

#[wasm_bindgen_test(unsupported = test)]
fn a_recipe_matching_a_ubicomp13_folder_reads_it() {
    let recipe = Recipe::from_json(
        r#"{"recipe": 1, "name": "mine", "files": [
          {"match": "acc.csv", "sensor": "accelerometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
           "time_unit": "s", "unit": "m/s2"},
          {"match": "gyr.csv", "sensor": "gyroscope", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
           "time_unit": "s", "unit": "rad/s"}
        ]}"#,
    )
    .unwrap();
    let f = ubicomp13("p1.1_x_back_pocket/", UBI_TRUTH);
    let mut logs = import_with(&mut MemSet::new(files(&as_refs(&f))), &[recipe]);
    assert_eq!(logs.len(), 1, "{logs:#?}");
    let log = logs.pop().unwrap().unwrap();
    assert_eq!(log.format, Format::Recipe, "the user's recipe first");
    assert_eq!(log.recipe.as_deref(), Some("mine"));
    assert_eq!(imu(&log.records).len(), 10);
    assert_eq!(log.truth.steps, None, "a recipe reads no truth");
}

// ------------------------------------------------------------------------------------------
// WeAllWalk
// ------------------------------------------------------------------------------------------

/// One `sensors.csv` row at `t`: the phone upright in the pocket (top up, screen facing north),
/// Core Motion's gravity (0, −1, 0) g, a user acceleration, a rotation rate, and raw columns
/// that must not be read.
fn weallwalk_row(t: f64, user: [f64; 3], q_ref: &UnitQuaternion<f64>) -> String {
    let q = q_ref.quaternion();
    let g = q_ref.inverse() * Vector3::new(0.0, 0.0, -1.0);
    let mut f: Vec<String> = vec![format!("{t:.6}")];
    f.extend(["0.1", "0.2", "0.3"].map(String::from)); // roll, pitch, yaw
    f.extend((0..9).map(|_| "0.5".to_string())); // matrix (not read)
    f.extend([q.i, q.j, q.k, q.w].map(|v| format!("{v:.6}")));
    f.extend(["0.010000", "-0.020000", "0.030000"].map(String::from));
    f.extend(user.map(|v| format!("{v:.6}")));
    f.extend([g.x, g.y, g.z].map(|v| format!("{v:.6}")));
    f.extend(["0.000000", "0.000000", "0.000000", "-1"].map(String::from));
    f.extend(["9.0", "9.0", "9.0"].map(String::from)); // raw accelerometer (not read)
    f.extend(["0.1", "0.1", "0.1"].map(String::from)); // raw gyroscope
    f.extend(["60.8", "162.4", "-510.1"].map(String::from)); // raw magnetometer
    f.extend(["0", "0"].map(String::from));
    assert_eq!(f.len(), 41);
    f.join(",")
}

/// Device → Core Motion reference (x north, y west, z up) of a phone standing upright, its top
/// up, its screen facing south, its x axis east.
fn upright() -> UnitQuaternion<f64> {
    // Device → ENU: +90° about x (top up, screen south); ENU → Core Motion: −90° about z.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let to_enu = UnitQuaternion::new_unchecked(Quaternion::new(h, h, 0.0, 0.0));
    let enu_to_ref = UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, -h));
    enu_to_ref * to_enu
}

fn weallwalk(dir: &str) -> Vec<(String, String)> {
    let q = upright();
    let sensors: String = (0..25)
        .map(|i| weallwalk_row(0.04 * i as f64, [0.01, 0.02, -0.03], &q) + "\n")
        .collect();
    let steps = "t_s,foot\n0.2000,L\n0.5000,R\n0.8000,L\n";
    let segments = "segment,spatial_segment,start_s,end_s,direction,turn_time_s,turn_deg,steps\n\
                    1,1,0.1000,0.4000,E,,,1\n\
                    2,1-5,0.4000,0.6000,TurnEtoS,0.5000,-90,1\n\
                    3,5,0.6000,0.9000,S,,,1\n";
    [
        ("sensors.csv", sensors),
        ("steps.csv", steps.to_string()),
        ("segments.csv", segments.to_string()),
        ("T1_ID11_NA.xml", "<walk/>".to_string()),
    ]
    .into_iter()
    .map(|(n, t)| (format!("{dir}{n}"), t))
    .collect()
}

#[wasm_bindgen_test(unsupported = test)]
fn weallwalk_folder() {
    let f = weallwalk("T1_ID11_2R/");
    let log = one(&as_refs(&f));
    assert_eq!(log.format, Format::WeAllWalk);
    assert_eq!(log.format.as_str(), "weallwalk");
    assert_eq!(log.platform, Some(Platform::Ios));
    assert_eq!(log.group.as_deref(), Some("RightPocket"));
    assert!(log.warnings.is_empty(), "{:#?}", log.warnings);
    let s = imu(&log.records);
    assert_eq!(s.len(), 25);
    assert!(close(s[1].t, 0.04, 1e-12));
    // (user + gravity) × −G0, not the raw columns: gravity (0, −1, 0) g → +G0 on y.
    let want = Vector3::new(-0.01, 1.0 - 0.02, 0.03) * G0;
    assert!((s[0].accel - want).norm() < 1e-5, "{:?}", s[0].accel);
    assert_eq!(s[0].gyro, Some(Vector3::new(0.01, -0.02, 0.03)));
    assert!(s.iter().all(|x| x.mag.is_none()), "no magnetometer");
    // The orientation in ENU: the top (y) up, gravity up.
    let q = s[0].orientation.unwrap();
    assert!(
        (q * Vector3::y() - Vector3::z()).norm() < 1e-5,
        "{:?}",
        q * Vector3::y()
    );
    assert!(close((q * s[0].accel).z, 0.98 * G0, 1e-4));
    // Truth: the heel strikes and the one turn (clockwise: −90).
    let t = &log.truth;
    assert_eq!(t.steps, Some(3));
    let feet: Vec<_> = t.step_events.iter().map(|e| (e.t, e.foot)).collect();
    assert_eq!(feet, [(0.2, Some(0)), (0.5, Some(1)), (0.8, Some(0))]);
    assert_eq!(t.turns.len(), 1);
    assert_eq!(
        (t.turns[0].t_start, t.turns[0].t_end, t.turns[0].angle_deg),
        (0.4, 0.6, -90.0)
    );
    let left = one(&as_refs(&weallwalk("T1_ID11_1L/")));
    assert_eq!(left.group.as_deref(), Some("LeftPocket"));
    assert_eq!(one(&as_refs(&weallwalk("walk/"))).group, None);
}

#[wasm_bindgen_test(unsupported = test)]
fn weallwalk_errors_and_warnings() {
    let mut f = weallwalk("w/");
    // sensors.csv line 3: user acceleration x (column 21) is not a number; line 5 too short.
    let mut lines: Vec<String> = f[0].1.lines().map(String::from).collect();
    let mut cells: Vec<String> = lines[2].split(',').map(String::from).collect();
    cells[20] = "n/a".into();
    lines[2] = cells.join(",");
    lines[4] = lines[4].split(',').take(20).collect::<Vec<_>>().join(",");
    f[0].1 = lines.join("\n") + "\n";
    f[1].1.push_str("1.1000,Q\n");
    f[2].1.push_str("4,5-8,1.0,1.5,TurnStoE,1.2,ninety,1\n");
    let log = one(&as_refs(&f));
    assert!(
        warned(&log, "w/sensors.csv", 3, 21, "user_accel_x"),
        "{:#?}",
        log.warnings
    );
    assert!(
        warned(&log, "w/sensors.csv", 5, 21, "user_accel_x"),
        "{:#?}",
        log.warnings
    );
    assert!(
        warned(&log, "w/steps.csv", 5, 2, "foot"),
        "{:#?}",
        log.warnings
    );
    assert!(
        warned(&log, "w/segments.csv", 5, 7, "turn_deg"),
        "{:#?}",
        log.warnings
    );
    assert_eq!(log.skipped, 4);
    assert_eq!(imu(&log.records).len(), 23);
    assert_eq!(log.truth.steps, Some(3));
    // No sensors.csv beside the truth: an error naming it.
    let g: Vec<_> = weallwalk("w/")
        .into_iter()
        .filter(|(n, _)| !n.ends_with("sensors.csv"))
        .collect();
    assert_eq!(error(&as_refs(&g)).file, "w/sensors.csv");
    // A sensors.csv of another width is not this set's.
    let h = vec![("x/sensors.csv", "0.0,1,2,3\n0.04,1,2,3\n")];
    assert!(read(&h).is_empty());
}

// ------------------------------------------------------------------------------------------
// Simulated walks
// ------------------------------------------------------------------------------------------

#[wasm_bindgen_test(unsupported = test)]
fn simulated_walks_read_back_as_their_format() {
    let sim = scenarios::straight_walk(1.8, 20.0).generate();
    let n = imu(&sim.records).len();
    for (format, platform) in [
        (Format::Tyrex, Platform::Android),
        (Format::Tyrex, Platform::Ios),
        (Format::Ubicomp13, Platform::Android),
        (Format::WeAllWalk, Platform::Ios),
    ] {
        let rec = formats::write(&sim, format, platform);
        let mut logs = import_all(&mut MemSet::new(rec.files));
        assert_eq!(logs.len(), 1, "{format:?}");
        let log = logs.pop().unwrap().unwrap();
        assert_eq!((log.format, log.platform), (format, Some(platform)));
        assert!(log.warnings.is_empty(), "{format:?}: {:#?}", log.warnings);
        assert_eq!(imu(&log.records).len(), n, "{format:?}");
        assert!(imu(&log.records).iter().all(|s| s.gyro.is_some()));
        let truth = &log.truth;
        match format {
            Format::Tyrex => assert!(truth.trajectory.len() >= 19 * 60),
            Format::Ubicomp13 => {
                assert_eq!(truth.steps, Some(sim.truth.steps.len() as u64));
                assert!(truth.step_window.is_some());
            }
            _ => {
                assert_eq!(truth.step_events.len(), sim.truth.steps.len());
                assert!(truth.turns.is_empty(), "a straight walk");
            }
        }
    }
}
