//! `pdr calibrate` from the command line: a simulated walk of known length makes a profile file
//! that `pdr run --profile` reads and that measures the walk; bad input is refused with a
//! message naming the file, never a panic.
//!
//! Native only: it runs the `pdr` binary.
#![cfg(not(target_arch = "wasm32"))]

mod common;

use common::pdr;
use std::path::{Path, PathBuf};

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pdr-calibrate-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A simulated calibration walk of `metres` at `cadence` by a walker whose step length is
/// 0.30·f + 0.12 m, written as a pdr-log.
fn walk(dir: &Path, name: &str, cadence: f64, metres: f64) -> String {
    let file = dir.join(name).display().to_string();
    let (ok, _, err) = pdr(&[
        "simulate",
        "--scenario",
        "calibration",
        "--cadence",
        &cadence.to_string(),
        "--metres",
        &metres.to_string(),
        "--sl-a",
        "0.3",
        "--sl-b",
        "0.12",
        "--out",
        &file,
    ]);
    assert!(ok, "{err}");
    file
}

/// The `distance` line of `pdr run`, m.
fn run_distance(args: &[&str]) -> f64 {
    let (ok, out, err) = pdr(args);
    assert!(ok, "{err}");
    let line = out.lines().find(|l| l.starts_with("distance")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

#[test]
fn two_walks_make_a_profile_that_pdr_run_reads() {
    let dir = folder("ok");
    let slow = walk(&dir, "slow.pdrlog", 1.6, 60.0);
    let fast = walk(&dir, "fast.pdrlog", 2.1, 80.0);
    let out = dir.join("me.json").display().to_string();
    let (ok, text, err) = pdr(&[
        "calibrate",
        &slow,
        "--metres",
        "60",
        &fast,
        "--metres",
        "80",
        "--out",
        &out,
        "--name",
        "tester",
    ]);
    assert!(ok, "{err}");
    assert!(
        text.contains("least-squares line through 2 walks"),
        "{text}"
    );
    assert!(
        text.contains("slow.pdrlog") && text.contains("fast.pdrlog"),
        "{text}"
    );
    assert!(
        text.contains(" m before (") && text.contains(" m after ("),
        "{text}"
    );
    let file =
        pdr::engine::calibration::ProfileFile::from_json(&std::fs::read_to_string(&out).unwrap())
            .unwrap();
    assert_eq!(file.name, "tester");
    assert_eq!(file.walking_points.len(), 2);
    let (a, b) = (file.profile.walking.a, file.profile.walking.b);
    assert!(
        (a - 0.3).abs() < 0.02 && (b - 0.12).abs() < 0.04,
        "a {a}, b {b}"
    );
    // A third walk at another pace, measured with the profile and without.
    let other = walk(&dir, "other.pdrlog", 1.85, 100.0);
    let with = run_distance(&["run", &other, "--profile", &out]);
    let without = run_distance(&["run", &other]);
    assert!((with - 100.0).abs() < 1.5, "with the profile: {with} m");
    assert!((without - 100.0).abs() > 4.0, "built-in: {without} m");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_is_refused_naming_the_file() {
    let dir = folder("bad");
    let good = walk(&dir, "walk.pdrlog", 1.8, 40.0);
    let out = dir.join("p.json").display().to_string();
    let missing = dir.join("missing.csv").display().to_string();
    // A recording with no step: the walk's opening pause only (the pdr-log's first lines).
    let text = std::fs::read_to_string(&good).unwrap();
    let still = dir.join("still.pdrlog").display().to_string();
    let head: Vec<&str> = text.lines().take(150).collect();
    std::fs::write(&still, head.join("\n") + "\n").unwrap();
    let notes = dir.join("notes.txt").display().to_string();
    std::fs::write(&notes, "shopping list\n").unwrap();
    let cases: [(Vec<&str>, &str); 8] = [
        (vec![&missing, "--metres", "40"], "missing.csv: "),
        (
            vec![&notes, "--metres", "40"],
            "notes.txt: no recognisable log",
        ),
        (
            vec![&still, "--metres", "40"],
            "still.pdrlog: only 0 steps were counted",
        ),
        (
            vec![&good, "--metres", "0"],
            "walk.pdrlog: the distance must be a positive number",
        ),
        (
            vec![&good, "--metres", "-5"],
            "walk.pdrlog: the distance must be a positive number",
        ),
        (
            vec![&good, "--metres", "nan"],
            "walk.pdrlog: the distance must be a positive number",
        ),
        (
            vec![&good],
            "walk.pdrlog: no distance: give its true length with --metres",
        ),
        (
            vec![&good, "--metres", "40", "--metres", "50"],
            "2 distances for 1 recordings",
        ),
    ];
    for (args, want) in cases {
        let mut all = vec!["calibrate"];
        all.extend(args.iter().copied());
        all.extend(["--out", &out]);
        let (ok, _, err) = pdr(&all);
        assert!(!ok, "{args:?} succeeded");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!Path::new(&out).exists(), "{args:?} wrote a profile");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
