//! The same path, the same length? WeAllWalk's walkers walk the same six paths, each with two
//! phones at once (`1L`, `2R`), so a path's track length should agree across the walkers and the
//! phones (docs/methods/step-length-pocket.md, "Why it is off by default").
//!
//! For each path and phone: every walker's track length with the default engine and with the
//! thigh's step length on (`thigh_step_length.on`), and their spread, (max − min) / mean.
//!
//! `cargo run --release --example weallwalk_paths [-- DATA_DIR]` (default
//! `../shared/data/weallwalk`).
use pdr::engine::{replay, PipelineConfig};
use pdr::io::import::{import_all, DirSet};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// (path, phone) → (walker, default m, thigh on m) of each walk.
type Paths = BTreeMap<(String, String), Vec<(String, f64, f64)>>;

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("../shared/data/weallwalk"), PathBuf::from);
    let Ok(mut files) = DirSet::new(&dir) else {
        eprintln!("not found: {}", dir.display());
        return;
    };
    let mut on = PipelineConfig::default();
    on.thigh_step_length.on = true;
    let mut paths = Paths::new();
    for log in import_all(&mut files).into_iter().flatten() {
        let name = Path::new(&log.source)
            .file_name()
            .map_or(log.source.clone(), |n| n.to_string_lossy().into_owned());
        // T<path>_ID<walker>_<phone>
        let parts: Vec<&str> = name.split('_').collect();
        let [path, walker, phone] = parts[..] else {
            eprintln!("{name}: not a WeAllWalk walk folder");
            continue;
        };
        let length = |cfg: PipelineConfig| {
            replay(cfg, &log.records).map_or(0.0, |r| {
                r.pipeline.track().iter().map(|s| s.length_m).sum::<f64>()
            })
        };
        let (l0, l1) = (length(PipelineConfig::default()), length(on.clone()));
        paths
            .entry((path.to_string(), phone.to_string()))
            .or_default()
            .push((walker.to_string(), l0, l1));
    }
    println!("path | phone | walkers | default, m | thigh on, m | spread: default → thigh on");
    for ((path, phone), walks) in &paths {
        let list = |k: usize| {
            walks
                .iter()
                .map(|w| format!("{:.0}", if k == 0 { w.1 } else { w.2 }))
                .collect::<Vec<_>>()
                .join(" / ")
        };
        let spread = |v: Vec<f64>| {
            let (lo, hi) = v
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
            100.0 * (hi - lo) / (v.iter().sum::<f64>() / v.len() as f64)
        };
        let names: Vec<&str> = walks.iter().map(|w| w.0.as_str()).collect();
        println!(
            "{path} | {phone} | {} | {} | {} | {:.1} → {:.1} %",
            names.join(" / "),
            list(0),
            list(1),
            spread(walks.iter().map(|w| w.1).collect()),
            spread(walks.iter().map(|w| w.2).collect()),
        );
    }
}
