//! Every input the fuzzers found a problem with (`tests/fixtures/fuzz/<target>/`), replayed
//! through the fuzz targets' own bodies and checks (`fuzz/src/lib.rs`, included here), without
//! the fuzzer: no panic, nothing non-finite reaches the engine or the live readouts, and each
//! input finishes within a time limit (a `timeout-*` input once never did).
//!
//! Native only (it reads the fixture tree). See docs/reliability.md, "Fuzzing".
#![cfg(not(target_arch = "wasm32"))]

#[path = "../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod harness;

use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

/// Longest one input may take (in a release build they take milliseconds).
const LIMIT: Duration = Duration::from_secs(60);

#[test]
fn fuzz_findings_replay_cleanly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fuzz");
    let mut replayed = 0;
    for target in harness::TARGETS {
        let dir = root.join(target);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut files: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        for path in files {
            let data = std::fs::read(&path).unwrap();
            let (tx, rx) = mpsc::channel();
            let name = path.display().to_string();
            std::thread::spawn(move || {
                let r = std::panic::catch_unwind(|| harness::run(target, &data));
                let _ = tx.send(r.is_ok());
            });
            match rx.recv_timeout(LIMIT) {
                Ok(true) => replayed += 1,
                Ok(false) => panic!("{name}: the `{target}` checks failed (see the panic above)"),
                Err(_) => panic!("{name}: the `{target}` target took longer than {LIMIT:?}"),
            }
        }
    }
    assert!(replayed > 0, "no fuzz findings under {}", root.display());
}
