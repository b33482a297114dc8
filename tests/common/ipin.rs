//! The IPIN 2023 logs from `../shared/data/ipin2023`, or `None` (with a message saying the test
//! is skipped) when a clone has no `../shared` (tests/dates.rs, energy.rs, fusion_real.rs).

use pdr::io::import::{import_all, DirSet, Log};
use std::path::Path;

/// Every IPIN 2023 log, read; `None` when the set is absent.
pub fn ipin_logs() -> Option<Vec<Log>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ipin2023");
    if !dir.is_dir() {
        eprintln!(
            "skipped: {} is absent (the IPIN 2023 logs, see ../shared/data/README.md)",
            dir.display()
        );
        return None;
    }
    let mut set = DirSet::new(&dir).expect("the IPIN folder opens");
    Some(
        import_all(&mut set)
            .into_iter()
            .map(|r| r.expect("IPIN log reads"))
            .collect(),
    )
}
