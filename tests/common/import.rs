//! Helpers of the import tests (`tests/import.rs`, `tests/import_robustness.rs`): the fixtures
//! under `tests/fixtures/import/`, file sets in memory and in zips, and the checks every
//! imported log passes.

use pdr::engine::Record;
use pdr::io::import::{import_all, Log, MemSet};
use pdr::io::pdrlog;
use pdr::io::ParseError;
use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

/// The import fixtures' folder.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/import")
}

/// The files of a fixture (a file or a folder), named `prefix` + path relative to it.
pub fn load(fixture: &str, prefix: &str) -> Vec<(String, Vec<u8>)> {
    let root = fixtures().join(fixture);
    if root.is_file() {
        return vec![(format!("{prefix}{fixture}"), std::fs::read(&root).unwrap())];
    }
    let mut out = Vec::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p
                    .strip_prefix(&root)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/");
                out.push((format!("{prefix}{rel}"), std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// A zip of `files`, stored.
pub fn zip_bytes(files: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let opts =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, bytes) in files {
        w.start_file(name.as_str(), opts).unwrap();
        w.write_all(bytes).unwrap();
    }
    w.finish().unwrap().into_inner()
}

/// Every log in `files`, read from memory.
pub fn import_mem(files: Vec<(String, Vec<u8>)>) -> Vec<Result<Log, ParseError>> {
    import_all(&mut MemSet::new(files))
}

/// The one log a set gives, checked for sanity.
pub fn one(results: Vec<Result<Log, ParseError>>) -> Log {
    assert_eq!(results.len(), 1, "expected one log: {results:#?}");
    let log = results.into_iter().next().unwrap().unwrap();
    assert_sane(&log);
    log
}

/// Finite values everywhere, records in time order, warnings naming a file.
pub fn assert_sane(log: &Log) {
    let mut last = f64::NEG_INFINITY;
    for r in &log.records {
        let t = match r {
            Record::Imu(s) | Record::Foot(s) => {
                s.check_finite().unwrap();
                if let Some(q) = s.orientation {
                    assert!((q.norm() - 1.0).abs() < 1e-9);
                }
                s.t
            }
            Record::Gnss(f) => {
                f.check().unwrap();
                f.t
            }
            Record::Gap(a, b) => {
                assert!(a.is_finite() && b.is_finite());
                *a
            }
            Record::Pressure(p) => {
                p.check().unwrap();
                p.t
            }
        };
        assert!(t >= last, "records out of order: {t} after {last}");
        last = t;
    }
    for w in &log.truth.waypoints {
        assert!(w.t.is_finite() && w.x_m.is_finite() && w.y_m.is_finite());
    }
    for w in &log.warnings {
        assert!(!w.file.is_empty(), "warning without a file: {w}");
    }
}

/// import → pdr-log text → read gives the same records.
pub fn assert_round_trip(log: &Log) {
    let text = pdrlog::to_string(&log.records);
    let back = pdrlog::read(text.as_bytes(), "round-trip").unwrap();
    assert!(back.errors.is_empty(), "{:?}", back.errors);
    assert_eq!(back.records, log.records);
}

/// Whether `log` has a warning on `line` (and `column`) of the file whose name ends so.
pub fn has_warning(log: &Log, file_ends: &str, line: u64, column: Option<usize>) -> bool {
    log.warnings
        .iter()
        .any(|w| w.file.ends_with(file_ends) && w.line == line && w.column == column)
}

/// |a − b| ≤ tol.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}
