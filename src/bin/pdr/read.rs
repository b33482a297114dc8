//! Reading the one log a file, folder or archive holds, as `pdr run` and `pdr calibrate` do.
//! May import: the `pdr` library.

use pdr::io::import::recipe::Recipe;
use pdr::io::import::Log;
use std::path::Path;

/// The one log that `file` holds, read as usual or, with `recipe`, by the recipe (whose checks'
/// warnings and notes go to standard error). An error when it holds none or several.
pub fn read_one(file: &Path, name: &str, recipe: Option<&Recipe>) -> Result<Log, String> {
    let mut set = pdr::io::import::DirSet::new(file).map_err(|e| format!("{name}: {e}"))?;
    let mut logs = match recipe {
        Some(r) => {
            let read = pdr::io::import::recipe::read_set(&mut set, r);
            if read.is_empty() {
                return Err(format!(
                    "{name}: recipe {:?} matches no folder: {}",
                    r.name,
                    pdr::io::import::recipe::why_not(&set, r)
                ));
            }
            read.into_iter()
                .map(|r| {
                    r.map(|(log, report)| {
                        for w in &report.warnings {
                            eprintln!("check: {w}");
                        }
                        for n in &report.notes {
                            eprintln!("note: {n}");
                        }
                        log
                    })
                })
                .collect()
        }
        None => pdr::io::import::import_all(&mut set),
    };
    match logs.len() {
        0 => Err(format!(
            "{name}: no recognisable log (see README, Import; for another recorder's files, \
             describe them with `--recipe FILE`, see docs/recipes.md)"
        )),
        1 => logs.pop().expect("one log").map_err(|e| e.to_string()),
        n => Err(format!(
            "{name} holds {n} logs; give one of them, or use `pdr eval`"
        )),
    }
}
