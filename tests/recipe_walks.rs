//! Recipes on whole walks and from the command line (docs/recipes.md): a simulated walk
//! written as a header-less folder and read back, the form's guessed recipe, `pdr run --recipe` / `pdr eval --recipe`, recipes inside zips, one file of
//! several sensors, and the shared x-io walks read by a recipe as by their own reader.

use pdr::engine::{replay, PipelineConfig, Record};
use pdr::io::import::recipe::{self, Recipe};
use pdr::io::import::{import_all, import_with, Format, MemSet, Platform};
use pdr::sim::formats;
use pdr::sim::scenarios;

mod common;
use common::imu;
use common::pdr;
use common::recipe::read;

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
    // The error of `pdr run` with the recipe whose `from` is replaced by `to`.
    let refused = |from: &str, to: &str| {
        std::fs::write(&wrong, formats::PLAIN_CSV_RECIPE.replace(from, to)).unwrap();
        let (ok, _, err) = pdr(&["run", d, "--recipe", wrong.to_str().unwrap()]);
        assert!(!ok, "a broken recipe was taken");
        err
    };
    let err = refused("\"acc.csv\"", "\"accel.csv\"");
    assert!(
        err.contains("matches no folder") && err.contains("no file matches \"accel.csv\""),
        "{err}"
    );
    let err = refused("\"unit\": \"rad/s\"", "\"unit\": \"g\"");
    assert!(
        err.contains("wrong.json") && err.contains("does not fit a gyroscope"),
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

/// A recipe for x-io Gait-Tracking CSVs (time, gyroscope in deg/s, accelerometer in g in one
/// headed file) named by `pattern`: an entry per sensor.
fn xio_recipe(pattern: &str) -> String {
    r#"{"recipe": 1, "name": "x-io", "files": [
      {"match": "PATTERN", "sensor": "accelerometer", "header": true, "time_unit": "s", "unit": "g",
       "columns": {"t": "Time (s)", "x": "Accelerometer X (g)", "y": "Accelerometer Y (g)", "z": "Accelerometer Z (g)"}},
      {"match": "PATTERN", "sensor": "gyroscope", "header": true, "time_unit": "s", "unit": "deg/s",
       "columns": {"t": "Time (s)", "x": "Gyroscope X (deg/s)", "y": "Gyroscope Y (deg/s)", "z": "Gyroscope Z (deg/s)"}}]}"#
        .replace("PATTERN", pattern)
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
    let json = xio_recipe("*.csv");
    let r = Recipe::from_json(&json).unwrap();
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
        .unwrap_err()
        .to_string();
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
    let r = Recipe::from_json(&xio_recipe("*_walk.csv")).unwrap();
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
