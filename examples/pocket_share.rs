//! Which pocket ([`pdr::engine::back_pocket`]): for each pocket walk of `tyrex-pocket`,
//! `ubicomp13-pocket` and `weallwalk`, the mean of the leg pitch's swing-axis share over the
//! walking steps in a pocket, the median step period, and the steps read as riding behind the
//! hip. The folder names say which pocket (WeAllWalk's do not: `1L` and `2R` are the left and
//! right phones).
//!
//! `cargo run --release --example pocket_share` (data in `../shared/data`).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::carry::CarryMode;
use pdr::engine::replay::replay_observed;
use pdr::engine::{Motion, Pipeline, PipelineConfig, Record};
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn main() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    println!("set              group          steps  mean share  period s  behind  walk");
    for set in ["tyrex-pocket", "ubicomp13-pocket", "weallwalk"] {
        let Ok(mut files) = DirSet::new(&data.join(set)) else {
            eprintln!("{set} skipped: not found under {}", data.display());
            continue;
        };
        for log in import_all(&mut files).into_iter().flatten() {
            let group = log.group.clone().unwrap_or_default();
            if !group.contains("Pocket") {
                continue;
            }
            let (mut seen, mut last_t) = (0, None);
            let (mut shares, mut periods, mut behind) = (Vec::new(), Vec::new(), 0);
            let mut observe = |p: &Pipeline, _: usize, r: &Record, _: bool| {
                let d = p.diagnostics();
                if d.steps == seen {
                    return;
                }
                seen = d.steps;
                if let Some(t0) = last_t.replace(r.t()) {
                    periods.push(r.t() - t0);
                }
                if d.carry != Some(CarryMode::Pocket) || d.motion != Some(Motion::Walking) {
                    return;
                }
                shares.extend(d.leg_pitch.map(|l| l.axis_share).filter(|s| *s > 0.0));
                behind += usize::from(d.back_pocket.behind);
            };
            let cfg = log.dated(&PipelineConfig::default());
            if replay_observed(cfg, &log.records, &mut observe).is_err() || shares.is_empty() {
                continue;
            }
            periods.sort_by(f64::total_cmp);
            let mean = shares.iter().sum::<f64>() / shares.len() as f64;
            let name = Path::new(&log.source)
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            println!(
                "{set:16} {group:14} {:5}  {mean:10.3}  {:8.3}  {behind:6}  {name}",
                shares.len(),
                periods.get(periods.len() / 2).copied().unwrap_or(f64::NAN),
            );
        }
    }
}
