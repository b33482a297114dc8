//! Recipes (docs/recipes.md): the JSON schema and its errors, every
//! separator and unit, headed and header-less files, errors naming file, line and field, the
//! sanity warnings firing and staying quiet, and matching by file name. Whole walks and the
//! command line: `tests/recipe_walks.rs`.

use pdr::io::import::recipe::{self, Recipe};
use pdr::io::import::{import_with, Format, Log, MemSet, Platform};
use pdr::sim::formats;
use pdr::sim::scenarios;
use std::f64::consts::PI;

mod common;
use common::imu;
use common::recipe::read;

/// A recipe of one accelerometer file, header-less, columns 1–4, and a gyroscope file.
fn recipe_json(delimiter: &str, time_unit: &str, acc_unit: &str, gyr_unit: &str) -> String {
    format!(
        r#"{{"recipe": 1, "name": "test", "files": [
          {{"match": "acc*.csv", "sensor": "accelerometer", "delimiter": "{delimiter}",
            "columns": {{"t": 1, "x": 2, "y": 3, "z": 4}}, "time_unit": "{time_unit}", "unit": "{acc_unit}"}},
          {{"match": "gyr.csv", "sensor": "gyroscope", "delimiter": "{delimiter}",
            "columns": {{"t": 1, "x": 2, "y": 3, "z": 4}}, "time_unit": "{time_unit}", "unit": "{gyr_unit}"}}
        ]}}"#
    )
}

/// 10 s at 100 Hz of a phone upright in a pocket: gravity on y, a 2 Hz bounce on y and z, a
/// 1 rad/s sway about x. Values in SI units.
fn signal() -> Vec<(f64, [f64; 3], [f64; 3])> {
    (0..1000)
        .map(|i| {
            let t = 1_700_000_000.0 + i as f64 * 0.01;
            let ph = 2.0 * PI * 2.0 * i as f64 * 0.01;
            (
                t,
                [
                    0.2 * libm::cos(ph),
                    9.81 + 1.5 * libm::sin(ph),
                    0.8 * libm::cos(ph),
                ],
                [1.0 * libm::sin(ph), 0.1, -0.2 * libm::cos(ph)],
            )
        })
        .collect()
}

/// Writes the signal as text: `sep` between fields, time scaled to `time_exp` (10^exp per s)
/// and written as an integer when exp > 0, values divided by the units' factors.
fn write(
    sep: &str,
    time_exp: i32,
    acc_div: f64,
    gyr_div: f64,
    header: Option<&str>,
) -> Vec<(String, Vec<u8>)> {
    let mut acc = String::new();
    let mut gyr = String::new();
    if let Some(h) = header {
        acc += &format!("{h}\n");
        gyr += &format!("{h}\n");
    }
    for (t, a, g) in signal() {
        let ts = if time_exp == 0 {
            format!("{t:.3}")
        } else {
            format!(
                "{}",
                (t * [1.0, 1e3, 1e6, 1e9][time_exp as usize / 3]).round() as i64
            )
        };
        acc += &format!(
            "{ts}{sep}{:.6}{sep}{:.6}{sep}{:.6}\n",
            a[0] / acc_div,
            a[1] / acc_div,
            a[2] / acc_div
        );
        gyr += &format!(
            "{ts}{sep}{:.6}{sep}{:.6}{sep}{:.6}\n",
            g[0] / gyr_div,
            g[1] / gyr_div,
            g[2] / gyr_div
        );
    }
    vec![
        ("rec/acc.csv".into(), acc.into_bytes()),
        ("rec/gyr.csv".into(), gyr.into_bytes()),
    ]
}

/// Checks that the log holds the signal to within the text's precision.
fn same_as_signal(log: &Log) {
    let s = imu(&log.records);
    let want = signal();
    assert_eq!(s.len(), want.len());
    for (got, (t, a, g)) in s.iter().zip(&want) {
        assert!((got.t - t).abs() < 1e-6, "t {} vs {t}", got.t);
        for k in 0..3 {
            assert!(
                (got.accel[k] - a[k]).abs() < 1e-4,
                "accel {:?} vs {a:?}",
                got.accel
            );
            let gy = got.gyro.expect("gyro merged");
            assert!((gy[k] - g[k]).abs() < 1e-4, "gyro {gy:?} vs {g:?}");
        }
    }
}

#[test]
fn every_separator_reads_the_same() {
    for (sep, name) in [
        (",", "comma"),
        ("\t", "tab"),
        (";", "semicolon"),
        ("   ", "whitespace"),
        (",", "auto"),
        ("\t", "auto"),
        (";", "auto"),
        (" ", "auto"),
    ] {
        let r = Recipe::from_json(&recipe_json(name, "s", "m/s2", "rad/s")).unwrap();
        let (log, report) = read(write(sep, 0, 1.0, 1.0, None), &r);
        same_as_signal(&log);
        assert_eq!(log.format, Format::Recipe);
        assert_eq!(log.recipe.as_deref(), Some("test"));
        assert!(
            log.warnings.is_empty(),
            "{sep:?} {name}: {:?}",
            log.warnings
        );
        assert!(report.warnings.is_empty(), "{name}: {:?}", report.warnings);
    }
}

#[test]
fn every_time_unit_reads_the_same() {
    for (exp, unit) in [(0, "s"), (3, "ms"), (6, "us"), (6, "µs"), (9, "ns")] {
        let r = Recipe::from_json(&recipe_json("comma", unit, "m/s2", "rad/s")).unwrap();
        let (log, report) = read(write(",", exp, 1.0, 1.0, None), &r);
        same_as_signal(&log);
        assert!(report.warnings.is_empty(), "{unit}: {:?}", report.warnings);
        let hz = report.files[0].rate_hz.unwrap();
        assert!((hz - 100.0).abs() < 0.5, "{unit}: {hz} Hz");
    }
}

#[test]
fn every_value_unit_converts() {
    for (acc, acc_div) in [("m/s2", 1.0), ("m/s²", 1.0), ("g", 9.80665)] {
        for (gyr, gyr_div) in [("rad/s", 1.0), ("deg/s", PI / 180.0), ("°/s", PI / 180.0)] {
            let r = Recipe::from_json(&recipe_json("comma", "ms", acc, gyr)).unwrap();
            let (log, report) = read(write(",", 3, acc_div, gyr_div, None), &r);
            same_as_signal(&log);
            assert!(
                report.warnings.is_empty(),
                "{acc} {gyr}: {:?}",
                report.warnings
            );
        }
    }
    // Field in µT, nT and gauss; pressure in hPa and Pa.
    for (unit, div) in [("uT", 1.0), ("µT", 1.0), ("nT", 1e-3), ("G", 100.0)] {
        for (punit, pdiv) in [("hPa", 1.0), ("Pa", 0.01)] {
            let mut files = write(",", 3, 1.0, 1.0, None);
            let mut mag = String::new();
            let mut bar = String::new();
            for (t, _, _) in signal().iter().step_by(5) {
                let ms = (t * 1e3).round() as i64;
                mag += &format!("{ms},{},{},{}\n", 20.0 / div, -5.0 / div, -40.0 / div);
                bar += &format!("{ms},{}\n", 1013.25 / pdiv);
            }
            files.push(("rec/mag.csv".into(), mag.into_bytes()));
            files.push(("rec/bar.csv".into(), bar.into_bytes()));
            let json = recipe_json("comma", "ms", "m/s2", "rad/s").replace(
                "]}",
                &format!(
                    r#", {{"match": "mag.csv", "sensor": "magnetometer", "columns": {{"t": 1, "x": 2, "y": 3, "z": 4}},
                          "time_unit": "ms", "unit": "{unit}"}},
                        {{"match": "bar.csv", "sensor": "pressure", "columns": {{"t": 1, "value": 2}},
                          "time_unit": "ms", "unit": "{punit}"}}]}}"#
                ),
            );
            let r = Recipe::from_json(&json).unwrap();
            let (log, report) = read(files, &r);
            let m = imu(&log.records)[10].mag.expect("mag merged");
            assert!(
                (m - nalgebra::Vector3::new(20.0, -5.0, -40.0)).norm() < 1e-6,
                "{unit}: {m}"
            );
            let p = report.files[3].median.unwrap();
            assert!((p - 1013.25).abs() < 1e-6, "{punit}: {p}");
            assert!(
                report.warnings.is_empty(),
                "{unit} {punit}: {:?}",
                report.warnings
            );
            assert!(
                report
                    .notes
                    .iter()
                    .any(|n| n.contains("pressure samples read and checked; the engine uses them")),
                "{:?}",
                report.notes
            );
        }
    }
}

#[test]
fn headed_files_by_column_name_in_any_order() {
    // Columns in another order, named; semicolons; a two-line preamble.
    let mut acc = String::from("# logger v2\n# device: test\nz;x;timestamp;y\n");
    let mut gyr = String::from("# logger v2\n# device: test\nwz;wx;timestamp;wy\n");
    for (t, a, g) in signal() {
        acc += &format!("{};{};{t:.3};{}\n", a[2], a[0], a[1]);
        gyr += &format!("{};{};{t:.3};{}\n", g[2], g[0], g[1]);
    }
    let json = r#"{"recipe": 1, "name": "named", "files": [
      {"match": "ACC.CSV", "sensor": "accelerometer", "delimiter": "semicolon", "header": true,
       "skip_lines": 2, "columns": {"t": "Timestamp", "x": "x", "y": "y", "z": "z"}, "time_unit": "s"},
      {"match": "gyr.csv", "sensor": "gyroscope", "header": true, "skip_lines": 2,
       "columns": {"t": "timestamp", "x": "wx", "y": "wy", "z": "wz"}, "time_unit": "s"}]}"#;
    let r = Recipe::from_json(json).unwrap();
    let (acc_text, gyr_text) = (acc.clone(), gyr.clone());
    let (log, _) = read(
        vec![
            ("rec/acc.csv".into(), acc.into_bytes()),
            ("rec/gyr.csv".into(), gyr.into_bytes()),
        ],
        &r,
    );
    same_as_signal(&log);
    // A name that is not in the header: the file, the header line, and the columns there are.
    let bad = json.replace("\"wx\"", "\"gx\"");
    let r = Recipe::from_json(&bad).unwrap();
    let mut set = MemSet::new(vec![
        ("rec/acc.csv".into(), acc_text.into_bytes()),
        ("rec/gyr.csv".into(), gyr_text.into_bytes()),
    ]);
    let e = recipe::read_set(&mut set, &r).pop().unwrap().unwrap_err();
    assert!(e.file.ends_with("gyr.csv") && e.line == 3, "{e}");
    assert!(e.message.contains("no column named \"gx\""), "{e}");
    assert!(e.message.contains("wz, wx, timestamp, wy"), "{e}");
}

#[test]
fn bad_lines_name_file_line_column_and_field() {
    let mut files = write(",", 3, 1.0, 1.0, None);
    let mut text = String::from_utf8(files[0].1.clone()).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut l11: Vec<String> = lines[11].split(',').map(String::from).collect();
    l11[2] = "abc".into();
    let fixed: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| {
            if i == 11 {
                l11.join(",")
            } else {
                l.to_string()
            }
        })
        .collect();
    text = fixed.join("\n") + "\n";
    files[0].1 = text.into_bytes();
    let r = Recipe::from_json(&recipe_json("comma", "ms", "m/s2", "rad/s")).unwrap();
    let (log, report) = read(files, &r);
    assert_eq!(log.skipped, 1);
    let e = &log.warnings[0];
    assert_eq!(
        e.to_string(),
        "rec/acc.csv:12:3 field `y`: not a number: \"abc\"",
        "the file, line 12, column 3 and the field"
    );
    assert_eq!(report.files[0].skipped, 1);
    assert_eq!(report.files[0].errors[0], *e);
    // A file without one good line is an error (its first bad line's).
    let files = vec![
        ("rec/acc.csv".into(), b"t,x,y,z\nfoo,1,2,3\n".to_vec()),
        ("rec/gyr.csv".into(), b"1,0,0,0\n".to_vec()),
    ];
    let mut set = MemSet::new(files);
    let e = recipe::read_set(&mut set, &r).pop().unwrap().unwrap_err();
    assert_eq!(e.file, "rec/acc.csv");
    assert_eq!(e.line, 1);
    assert_eq!(e.field.as_deref(), Some("t"));
}

#[test]
fn recipe_json_errors_name_the_entry_and_field() {
    let ok = recipe_json("comma", "ms", "m/s2", "rad/s");
    assert!(Recipe::from_json(&ok).is_ok());
    let e = |text: &str| Recipe::from_json(text).unwrap_err().to_string();
    let err = e(&ok.replace("\"time_unit\"", "\"timeunit\""));
    assert!(err.contains("unknown field `timeunit`"), "{err}");
    let err = e(&ok.replace("\"recipe\": 1", "\"recipe\": 2"));
    assert!(err.contains("version 2 is not supported"), "{err}");
    let err = e(&ok.replace("\"unit\": \"rad/s\"", "\"unit\": \"g\""));
    assert!(
        err.contains("files[1]") && err.contains("does not fit a gyroscope"),
        "{err}"
    );
    let err = e(&ok.replace("\"x\": 2,", "\"x\": \"ax\","));
    assert!(err.contains("no header"), "{err}");
    let err = e(&ok.replace("\"x\": 2,", "\"x\": 0,"));
    assert!(
        err.contains("a 1-based number or a header name, not 0"),
        "{err}"
    );
    let err = e(&ok.replace("\"x\": 2,", "\"x\": -1,"));
    assert!(
        err.contains("a column is a 1-based number or a header name, not -1"),
        "{err}"
    );
    let err = e(&ok.replace("\"x\": 2,", "\"x\": [2],"));
    assert!(err.contains("not [2]"), "{err}");
    let err = e(&ok.replace("\"y\": 3, ", ""));
    assert!(err.contains("needs `columns.y`"), "{err}");
    let err = e(&ok.replace("\"sensor\": \"accelerometer\"", "\"sensor\": \"barometer\""));
    assert!(err.contains("unknown variant `barometer`"), "{err}");
    let err = e(&ok
        .replace(
            "\"sensor\": \"accelerometer\"",
            "\"sensor\": \"magnetometer\"",
        )
        .replace("\"unit\": \"m/s2\"", "\"unit\": \"uT\""));
    assert!(err.contains("no accelerometer file"), "{err}");
    let err = e(&ok.replace(
        "\"sensor\": \"accelerometer\"",
        "\"sensor\": \"linear-accelerometer\"",
    ));
    assert!(
        err.contains("needs a gravity or an orientation file"),
        "{err}"
    );
    let err = e(&ok.replace(
        "\"unit\": \"m/s2\"",
        "\"unit\": \"m/s2\", \"axes\": [\"x\", \"x\", \"z\"]",
    ));
    assert!(err.contains("twice"), "{err}");
    let err = e("{\"recipe\": 1, \"name\": \"x\", \"files\": []}");
    assert!(err.contains("1 to 32 entries"), "{err}");
    // The example recipe of docs/recipes.md (the one the simulator writes) reads and round-trips.
    let r = Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap();
    assert_eq!(Recipe::from_json(&r.to_json().unwrap()).unwrap(), r);
}

#[test]
fn axes_remap_and_flip() {
    // The logger's axes: its x is our y, its y is our −x.
    let sig = signal();
    let mut acc = String::new();
    for (t, a, _) in &sig {
        acc += &format!("{t:.3},{},{},{}\n", a[1], -a[0], a[2]);
    }
    let json = r#"{"recipe": 1, "name": "axes", "files": [
      {"match": "acc.csv", "sensor": "accelerometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4},
       "time_unit": "s", "axes": ["-y", "x", "z"]}]}"#;
    let r = Recipe::from_json(json).unwrap();
    let (log, _) = read(vec![("rec/acc.csv".into(), acc.into_bytes())], &r);
    for (s, (_, a, _)) in imu(&log.records).iter().zip(&sig) {
        assert!((s.accel - nalgebra::Vector3::from(*a)).norm() < 1e-6);
    }
}

#[test]
fn sanity_warnings_fire_on_wrong_units_and_stay_quiet_otherwise() {
    let warns = |json: String, files| read(files, &Recipe::from_json(&json).unwrap()).1.warnings;
    // Right units: quiet (checked in every_value_unit_converts too).
    assert!(warns(
        recipe_json("comma", "ms", "m/s2", "rad/s"),
        write(",", 3, 1.0, 1.0, None)
    )
    .is_empty());
    // m/s² data read as g.
    let w = warns(
        recipe_json("comma", "ms", "g", "rad/s"),
        write(",", 3, 1.0, 1.0, None),
    );
    assert!(
        w.len() == 1 && w[0].contains("acc.csv") && w[0].contains("not near 9.81"),
        "{w:?}"
    );
    assert!(w[0].contains("m/s² read as g"), "{w:?}");
    // g data read as m/s².
    let w = warns(
        recipe_json("comma", "ms", "m/s2", "rad/s"),
        write(",", 3, 9.80665, 1.0, None),
    );
    assert!(w.len() == 1 && w[0].contains("g read as m/s²"), "{w:?}");
    // °/s data read as rad/s.
    let w = warns(
        recipe_json("comma", "ms", "m/s2", "rad/s"),
        write(",", 3, 1.0, PI / 180.0, None),
    );
    assert!(
        w.len() == 1 && w[0].contains("gyr.csv") && w[0].contains("°/s read as rad/s"),
        "{w:?}"
    );
    // ms read as s: 0.1 samples per second; s read as ms: 100000.
    let w = warns(
        recipe_json("comma", "s", "m/s2", "rad/s"),
        write(",", 3, 1.0, 1.0, None),
    );
    assert!(
        w.len() == 2 && w[0].contains("0.100 samples per second"),
        "{w:?}"
    );
    let w = warns(
        recipe_json("comma", "ms", "m/s2", "rad/s"),
        write(",", 0, 1.0, 1.0, None),
    );
    let hz: f64 = w[0]
        .strip_prefix("acc.csv: ")
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(w.len() == 2 && (hz - 1e5).abs() < 2.0, "{w:?}");
    assert!(w[0].contains("samples per second is implausible: is the time unit (ms) right?"));
    // Time going backwards.
    let mut files = write(",", 3, 1.0, 1.0, None);
    let text = String::from_utf8(files[1].1.clone()).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines.swap(40, 41);
    files[1].1 = (lines.join("\n") + "\n").into_bytes();
    let w = warns(recipe_json("comma", "ms", "m/s2", "rad/s"), files);
    assert!(
        w.len() == 1 && w[0].contains("gyr.csv: time goes backwards 1 time(s), first at line 42"),
        "{w:?}"
    );
    // A field far from the Earth's: nT read as µT.
    let mut files = write(",", 3, 1.0, 1.0, None);
    files.push((
        "rec/mag.csv".into(),
        b"1700000000000,20000,-5000,-40000\n1700000000010,20000,-5000,-40000\n".to_vec(),
    ));
    let json = recipe_json("comma", "ms", "m/s2", "rad/s").replace(
        "]}",
        r#", {"match": "mag.csv", "sensor": "magnetometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4}, "time_unit": "ms"}]}"#,
    );
    let w = warns(json, files);
    assert!(
        w.len() == 1 && w[0].contains("mag.csv: the median field is 45000 µT"),
        "{w:?}"
    );
}

#[test]
fn linear_acceleration_gets_gravity_back() {
    let sig = signal();
    let (mut lin, mut grav, mut ori) = (String::new(), String::new(), String::new());
    // Gravity along +y (upright phone): the orientation taking device to ENU is +90° about x.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (t, a, _) in &sig {
        lin += &format!("{t:.3},{},{},{}\n", a[0], a[1] - 9.80665, a[2]);
        grav += &format!("{t:.3},0,9.80665,0\n");
        ori += &format!("{t:.3},{h},{h},0,0\n");
    }
    let base = r#"{"recipe": 1, "name": "lin", "files": [
      {"match": "lin.csv", "sensor": "linear-accelerometer", "columns": {"t": 1, "x": 2, "y": 3, "z": 4}, "time_unit": "s"},
      SECOND]}"#;
    for (second, name, text) in [
        (
            r#"{"match": "grav.csv", "sensor": "gravity", "columns": {"t": 1, "x": 2, "y": 3, "z": 4}, "time_unit": "s"}"#,
            "grav.csv",
            grav,
        ),
        (
            r#"{"match": "ori.csv", "sensor": "orientation", "columns": {"t": 1, "w": 2, "x": 3, "y": 4, "z": 5}, "time_unit": "s"}"#,
            "ori.csv",
            ori,
        ),
    ] {
        let r = Recipe::from_json(&base.replace("SECOND", second)).unwrap();
        let (log, report) = read(
            vec![
                ("rec/lin.csv".into(), lin.clone().into_bytes()),
                (format!("rec/{name}"), text.into_bytes()),
            ],
            &r,
        );
        for (s, (_, a, _)) in imu(&log.records).iter().zip(&sig) {
            assert!(
                (s.accel - nalgebra::Vector3::from(*a)).norm() < 1e-6,
                "{name}: {}",
                s.accel
            );
        }
        assert!(
            report.notes.iter().any(|n| n.contains("gravity restored")),
            "{:?}",
            report.notes
        );
    }
}

#[test]
fn gnss_and_quaternion_files() {
    let mut files = write(",", 3, 1.0, 1.0, None);
    files.push((
        "rec/gps.csv".into(),
        b"time_ms;lat;lon;acc;alt\n1700000001000;48.1;11.5;4.5;520\n1700000002000;48.10001;11.5;4.0;\n"
            .to_vec(),
    ));
    let json = recipe_json("comma", "ms", "m/s2", "rad/s").replace(
        "]}",
        r#", {"match": "gps.csv", "sensor": "gnss", "header": true, "columns": {"t": "time_ms", "lat": "lat", "lon": "lon", "accuracy": "acc", "altitude": "alt"}, "time_unit": "ms"}]}"#,
    );
    let (log, report) = read(files, &Recipe::from_json(&json).unwrap());
    let fixes: Vec<_> = log.fixes().collect();
    assert_eq!(fixes.len(), 2);
    assert_eq!(fixes[0].altitude_m, Some(520.0));
    assert_eq!(fixes[1].altitude_m, None);
    assert!((fixes[0].t - 1_700_000_001.0).abs() < 1e-9 && fixes[0].h_accuracy_m == 4.5);
    assert_eq!(
        report.files[2].rows[0],
        vec![1_700_000_001.0, 48.1, 11.5, 4.5]
    );
}

#[test]
fn a_recipe_matches_files_by_name_and_refuses_others() {
    let r = Recipe::from_json(&recipe_json("comma", "ms", "m/s2", "rad/s")).unwrap();
    let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    // acc*.csv matches acc_2024.csv; gyr.csv only itself; extra files are left alone.
    let n = names(&["rec/README.txt", "rec/acc_2024.csv", "rec/gyr.csv"]);
    assert_eq!(r.match_dir(&n, "rec/").unwrap(), vec![Some(1), Some(2)]);
    // Another folder, or a missing gyroscope file: no match, and why.
    assert!(r.match_dir(&n, "").is_err());
    let e = r
        .match_dir(&names(&["rec/acc.csv", "rec/gyro.csv"]), "rec/")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "no file matches \"gyr.csv\"");
    let e = r
        .match_dir(
            &names(&["rec/acc.csv", "rec/acc_old.csv", "rec/gyr.csv"]),
            "rec/",
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("matches several files"), "{e}");
    // A Sensor Logger folder is not read by this recipe, and import_with reads it as usual.
    let sim = scenarios::straight_walk(1.8, 30.0).generate();
    let sl = formats::write(&sim, Format::SensorLogger, Platform::Android);
    let mut set = MemSet::new(sl.files.clone());
    assert!(recipe::read_set(&mut set, &r).is_empty());
    // (Its Accelerometer.csv matches acc*.csv, case-insensitive; there is no gyr.csv.)
    let why = recipe::why_not(&set, &r);
    assert!(why.contains("/: no file matches \"gyr.csv\""), "{why}");
    let logs = import_with(&mut MemSet::new(sl.files), std::slice::from_ref(&r));
    assert_eq!(logs.len(), 1);
    assert_eq!(logs[0].as_ref().unwrap().format, Format::SensorLogger);
}
