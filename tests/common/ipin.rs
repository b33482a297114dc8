//! The real walks of `../shared/data`, or `None` (with a message saying the test is skipped)
//! when a clone has no `../shared` (tests/dates.rs, energy.rs, fusion_real.rs, magnetic.rs, import_shared_sets.rs).

use pdr::io::import::{import_all, DirSet, Log};
use std::path::Path;

/// Every log of the set `name` (a folder of `../shared/data`), read; `None` when the set is
/// absent.
pub fn shared_logs(name: &str) -> Option<Vec<Log>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(name);
    if !dir.is_dir() {
        eprintln!(
            "skipped: {} is absent (see ../shared/data/README.md)",
            dir.display()
        );
        return None;
    }
    let mut set = DirSet::new(&dir).expect("the folder opens");
    Some(
        import_all(&mut set)
            .into_iter()
            .map(|r| r.unwrap_or_else(|e| panic!("{name} log reads: {e}")))
            .collect(),
    )
}

/// Every IPIN 2023 log, read; `None` when the set is absent.
pub fn ipin_logs() -> Option<Vec<Log>> {
    shared_logs("ipin2023")
}
