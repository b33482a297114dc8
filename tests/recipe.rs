//! Recipes (README, "Logs from any recorder (recipes)"): the JSON schema and its errors, every
//! separator and unit, headed and header-less files, errors naming file, line and field, the
//! sanity warnings firing and staying quiet, matching by file name, a simulated walk written as
//! a header-less folder and read back, and `pdr run --recipe` / `pdr eval --recipe`.

use pdr::engine::{replay, PipelineConfig, Record};
use pdr::io::import::recipe::{self, Recipe, Report};
use pdr::io::import::{import_all, import_with, Format, Log, MemSet, Platform};
use pdr::sim::formats;
use pdr::sim::scenarios;
use std::f64::consts::PI;

mod common;
use common::imu;

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

fn read(files: Vec<(String, Vec<u8>)>, recipe: &Recipe) -> (Log, Report) {
    let mut set = MemSet::new(files);
    let mut r = recipe::read_set(&mut set, recipe);
    assert_eq!(r.len(), 1, "one log");
    r.pop().unwrap().expect("reads")
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
    let e = |text: &str| Recipe::from_json(text).unwrap_err();
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
    // The example recipe of the README (the one the simulator writes) reads and round-trips.
    let r = Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap();
    assert_eq!(Recipe::from_json(&r.to_json()).unwrap(), r);
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
        .unwrap_err();
    assert_eq!(e, "no file matches \"gyr.csv\"");
    let e = r
        .match_dir(
            &names(&["rec/acc.csv", "rec/acc_old.csv", "rec/gyr.csv"]),
            "rec/",
        )
        .unwrap_err();
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

/// The engine's step count and final position on records.
fn run(records: &[Record]) -> (usize, f64, f64) {
    let r = replay(PipelineConfig::default(), records).unwrap();
    assert_eq!(r.refused, 0);
    let track = r.pipeline.track();
    let last = track.last().unwrap();
    (track.len(), last.east_m, last.north_m)
}

#[test]
fn simulated_walk_round_trips_through_a_header_less_folder() {
    let sim = scenarios::demo_walk().generate();
    let plain = formats::write(&sim, Format::Recipe, Platform::Android);
    let mut names: Vec<&str> = plain.files.iter().map(|f| f.0.as_str()).collect();
    names.sort();
    assert!(names[0].ends_with("/acc.csv") && names[1].ends_with("/bar.csv"));
    assert!(names[2].ends_with("/gyr.csv") && names[3].ends_with("/mag.csv"));
    // Not recognised without the recipe.
    assert!(import_all(&mut MemSet::new(plain.files.clone())).is_empty());
    let r = Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap();
    let mut logs = import_with(
        &mut MemSet::new(plain.files.clone()),
        std::slice::from_ref(&r),
    );
    let log = logs.pop().unwrap().unwrap();
    assert!(log.warnings.is_empty(), "{:?}", log.warnings);
    let (_, report) = read(plain.files.clone(), &r);
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    // The same walk from phyphox (the same sensors: accelerometer, gyroscope, magnetometer, no
    // OS orientation): the same steps, and the same track to within the ms time rounding.
    let ph = formats::write(&sim, Format::Phyphox, Platform::Android);
    let native = import_all(&mut MemSet::new(ph.files))
        .pop()
        .unwrap()
        .unwrap();
    let (n_plain, e_plain, n_n) = run(&log.records);
    let (n_native, e_native, n_native_n) = run(&native.records);
    assert_eq!(n_plain, n_native, "steps");
    let d = libm::hypot(e_plain - e_native, n_n - n_native_n);
    assert!(d < 1.0, "final positions {d:.2} m apart");
    // And against the truth: within 2 % of the simulated steps.
    let truth = sim.truth.steps.len() as f64;
    assert!(
        ((n_plain as f64 - truth) / truth).abs() < 0.02,
        "{n_plain} vs {truth}"
    );
}

#[test]
fn describe_guesses_a_recipe_for_the_form() {
    let sim = scenarios::straight_walk(1.8, 30.0).generate();
    let plain = formats::write(&sim, Format::Recipe, Platform::Android);
    let d = recipe::describe(&mut MemSet::new(plain.files.clone()));
    assert_eq!(d.files.len(), 4);
    assert!(d.files.iter().all(|f| !f.header && f.columns[0] == "1"));
    let draft = d.draft.unwrap();
    let sensors: Vec<&str> = draft.files.iter().map(|f| f.sensor.as_str()).collect();
    assert_eq!(
        sensors,
        ["accelerometer", "pressure", "gyroscope", "magnetometer"]
    );
    assert!(draft.files.iter().all(|f| f.time_unit.as_str() == "ms"));
    // The draft reads the folder as the hand-written recipe does.
    draft.check().unwrap();
    let (a, _) = read(plain.files.clone(), &draft);
    let (b, _) = read(
        plain.files,
        &Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap(),
    );
    assert_eq!(a.records, b.records);
}

// --- the command line -----------------------------------------------------------------------

fn pdr(args: &[&str]) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pdr"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn pdr_run_and_eval_take_a_recipe() {
    let dir = std::env::temp_dir().join(format!("pdr-recipe-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let (ok, out, err) = pdr(&[
        "simulate",
        "--scenario",
        "straight",
        "--format",
        "plain-csv",
        "--out",
        d,
    ]);
    assert!(ok, "{out}{err}");
    let recipe_file = dir.join("recipe.json");
    let r = recipe_file.to_str().unwrap();
    // Without the recipe: refused, with a pointer to recipes.
    let (ok, _, err) = pdr(&["run", d]);
    assert!(
        !ok && err.contains("no recognisable log") && err.contains("--recipe"),
        "{err}"
    );
    // With it.
    let (ok, out, err) = pdr(&["run", d, "--recipe", r]);
    assert!(ok, "{err}");
    assert!(
        out.contains("format        recipe (\"plain CSV, ms\")"),
        "{out}"
    );
    assert!(
        err.contains("note: bar.csv")
            && err.contains("the engine uses them for the height and floor changes"),
        "{err}"
    );
    let steps: usize = out
        .lines()
        .find_map(|l| l.strip_prefix("steps"))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    assert!(steps > 100, "{out}");
    let (ok, out, err) = pdr(&["eval", d, "--recipe", r, "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["logs"][0]["format"], "recipe");
    assert_eq!(v["logs"][0]["steps"].as_u64(), Some(steps as u64), "{out}");
    // A recipe that does not match says why; a broken recipe names its file and field.
    let wrong = dir.join("wrong.json");
    std::fs::write(
        &wrong,
        formats::PLAIN_CSV_RECIPE.replace("\"acc.csv\"", "\"accel.csv\""),
    )
    .unwrap();
    let (ok, _, err) = pdr(&["run", d, "--recipe", wrong.to_str().unwrap()]);
    assert!(
        !ok && err.contains("matches no folder") && err.contains("no file matches \"accel.csv\""),
        "{err}"
    );
    std::fs::write(
        &wrong,
        formats::PLAIN_CSV_RECIPE.replace("\"unit\": \"rad/s\"", "\"unit\": \"g\""),
    )
    .unwrap();
    let (ok, _, err) = pdr(&["run", d, "--recipe", wrong.to_str().unwrap()]);
    assert!(
        !ok && err.contains("wrong.json") && err.contains("does not fit a gyroscope"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn recipes_apply_inside_zip_archives() {
    use std::io::Write as _;
    let sim = scenarios::straight_walk(1.8, 30.0).generate();
    let plain = formats::write(&sim, Format::Recipe, Platform::Android);
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in &plain.files {
        w.start_file(name.as_str(), opts).unwrap();
        w.write_all(bytes).unwrap();
    }
    let zip = w.finish().unwrap().into_inner();
    let r = Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap();
    let direct = import_with(&mut MemSet::new(plain.files), std::slice::from_ref(&r))
        .pop()
        .unwrap()
        .unwrap();
    let mut zipped = import_with(
        &mut MemSet::new(vec![("walk.zip".into(), zip)]),
        std::slice::from_ref(&r),
    );
    assert_eq!(zipped.len(), 1);
    let zipped = zipped.pop().unwrap().unwrap();
    assert_eq!(zipped.format, Format::Recipe);
    assert_eq!(zipped.records, direct.records);
    assert!(zipped.source.starts_with("walk.zip/"), "{}", zipped.source);
}

#[test]
fn one_file_of_several_sensors_reads_as_its_own_reader_does() {
    // The x-io Gait-Tracking CSV (a real recording's first lines, tests/fixtures/import): time,
    // gyroscope in deg/s and accelerometer in g in one headed file. Read by a recipe with an
    // entry per sensor, it gives the records of the dedicated reader.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/import/xio_foot.csv"
    );
    let bytes = std::fs::read(path).unwrap();
    let json = r#"{"recipe": 1, "name": "x-io", "files": [
      {"match": "*.csv", "sensor": "accelerometer", "header": true, "time_unit": "s", "unit": "g",
       "columns": {"t": "Time (s)", "x": "Accelerometer X (g)", "y": "Accelerometer Y (g)", "z": "Accelerometer Z (g)"}},
      {"match": "*.csv", "sensor": "gyroscope", "header": true, "time_unit": "s", "unit": "deg/s",
       "columns": {"t": "Time (s)", "x": "Gyroscope X (deg/s)", "y": "Gyroscope Y (deg/s)", "z": "Gyroscope Z (deg/s)"}}]}"#;
    let r = Recipe::from_json(json).unwrap();
    let files = vec![("xio/walk.csv".to_string(), bytes.clone())];
    let (by_recipe, report) = read(files, &r);
    let native = pdr::io::import::xio::read_xio(&bytes[..], "walk.csv").unwrap();
    assert_eq!(by_recipe.records.len(), native.records.len());
    for (a, b) in imu(&by_recipe.records).iter().zip(imu(&native.records)) {
        assert_eq!(a.t, b.t);
        assert!(
            (a.accel - b.accel).norm() < 1e-9,
            "{} vs {}",
            a.accel,
            b.accel
        );
        assert!((a.gyro.unwrap() - b.gyro.unwrap()).norm() < 1e-9);
    }
    // (A foot at rest and swinging: no unit warning for gravity or rates.)
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    // Two entries reading one file as the same sensor are refused.
    let twice = json
        .replace("\"sensor\": \"gyroscope\"", "\"sensor\": \"accelerometer\"")
        .replace("\"unit\": \"deg/s\"", "\"unit\": \"g\"");
    let e = Recipe::from_json(&twice)
        .unwrap()
        .match_dir(&["xio/walk.csv".to_string()], "xio/")
        .unwrap_err();
    assert!(e.contains("both read walk.csv as accelerometer"), "{e}");
}

#[test]
fn shared_xio_walks_read_by_a_recipe_as_by_their_reader() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/xio-foot");
    if !dir.exists() {
        eprintln!(
            "skipped: {} is absent (see /work/shared/data/README.md)",
            dir.display()
        );
        return;
    }
    let json = r#"{"recipe": 1, "name": "x-io", "files": [
      {"match": "*_walk.csv", "sensor": "accelerometer", "header": true, "time_unit": "s", "unit": "g",
       "columns": {"t": "Time (s)", "x": "Accelerometer X (g)", "y": "Accelerometer Y (g)", "z": "Accelerometer Z (g)"}},
      {"match": "*_walk.csv", "sensor": "gyroscope", "header": true, "time_unit": "s", "unit": "deg/s",
       "columns": {"t": "Time (s)", "x": "Gyroscope X (deg/s)", "y": "Gyroscope Y (deg/s)", "z": "Gyroscope Z (deg/s)"}}]}"#;
    let r = Recipe::from_json(json).unwrap();
    for name in ["short_walk.csv", "long_walk.csv"] {
        let bytes = std::fs::read(dir.join(name)).unwrap();
        let native = pdr::io::import::xio::read_xio(&bytes[..], name).unwrap();
        let (log, report) = read(vec![(format!("x/{name}"), bytes)], &r);
        assert_eq!(log.records, native.records, "{name}");
        assert!(report.warnings.is_empty(), "{name}: {:?}", report.warnings);
    }
}

#[test]
fn describe_reads_headers_and_separators() {
    let files = vec![
        (
            "r/Accel.txt".to_string(),
            b"timestamp_us;ax;ay;az\n1000000;0,1;9,8;0,2\n1010000;0,1;9,8;0,2\n1020000;0,1;9,8;0,2\n"
                .to_vec(),
        ),
        (
            "r/gyro.tsv".to_string(),
            b"1.00\t0.1\t0.2\t0.3\n1.01\t0.1\t0.2\t0.3\n1.02\t0.1\t0.2\t0.3\n".to_vec(),
        ),
        ("r/notes.md".to_string(), b"# my walk\n".to_vec()),
    ];
    let d = recipe::describe(&mut MemSet::new(files.clone()));
    let acc = d.files.iter().find(|f| f.name == "r/Accel.txt").unwrap();
    assert!(acc.header);
    assert_eq!(acc.columns, ["timestamp_us", "ax", "ay", "az"]);
    assert_eq!(acc.first[0], ["1000000", "0,1", "9,8", "0,2"]);
    let gyr = d.files.iter().find(|f| f.name == "r/gyro.tsv").unwrap();
    assert!(!gyr.header);
    assert_eq!(gyr.columns, ["1", "2", "3", "4"]);
    // One column only: not offered.
    assert!(d.files.iter().all(|f| f.name != "r/notes.md"));
    let draft = d.draft.unwrap();
    let units: Vec<&str> = draft.files.iter().map(|f| f.time_unit.as_str()).collect();
    assert_eq!(units, ["us", "s"]);
    // The draft reads them: names for the headed file, numbers for the other; decimal commas.
    let (log, report) = read(files, &draft);
    assert_eq!(imu(&log.records).len(), 3);
    assert!((imu(&log.records)[0].accel.y - 9.8).abs() < 1e-12);
    assert_eq!(report.files[0].rows[0], vec![1.0, 0.1, 9.8, 0.2]);
}
