//! The first and last steps on real walks: the Oxford Step Counter traces (CC BY 4.0)
//! carry every true foot contact, so each walk's count splits into its start, its middle and
//! its end ([`pdr::eval::ends`], the first and the last 4 s; the truth debounced as
//! `Truth::steps_debounced` does). Prints each trace's split and the totals per placement;
//! `--list` adds the true and the counted step times at both ends.
//!
//! `cargo run --release --example oxford_ends [-- --list]`
use pdr::engine::{replay, PipelineConfig};
use pdr::eval::ends::end_errors;
use pdr::io::import::{import_all, DirSet};
use std::collections::BTreeMap;
use std::path::Path;

const WINDOW_S: f64 = 4.0;

/// A walk's (start, end, whole count) errors, steps.
type Split = (i64, i64, i64);

fn main() {
    let list = std::env::args().any(|a| a == "--list");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/oxford-steps");
    let Ok(mut set) = DirSet::new(&dir) else {
        println!(
            "skipped: {} not found (the shared data set is not beside this checkout)",
            dir.display()
        );
        return;
    };
    let mut per: BTreeMap<String, Vec<Split>> = BTreeMap::new();
    for log in import_all(&mut set).into_iter().flatten() {
        let Some(truth) = log.truth.step_times_debounced() else {
            continue;
        };
        let run = match replay(log.dated(&PipelineConfig::default()), &log.records) {
            Ok(run) => run,
            Err(e) => {
                println!("{}: {e}", log.source);
                continue;
            }
        };
        let found: Vec<f64> = run.pipeline.track().iter().map(|s| s.t).collect();
        let Some(e) = end_errors(&found, &truth, WINDOW_S) else {
            continue;
        };
        let name = log.source.rsplit('/').next().unwrap_or(&log.source);
        println!(
            "{name:<36} lag {:+.2} s  start {:+}  middle {:+}  end {:+}",
            e.lag_s, e.start, e.middle, e.end
        );
        if list {
            let (t0, t1) = (truth[0], truth[truth.len() - 1]);
            let times = |v: &[f64], shift: f64, a: f64, b: f64| {
                v.iter()
                    .map(|t| t - shift)
                    .filter(|&t| t >= a && t < b)
                    .map(|t| format!("{:.2}", t - t0))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let (s, f) = (t0 - 10.0, t0 + 6.0);
            println!("   start  true {}", times(&truth, 0.0, s, f));
            println!("        counted {}", times(&found, e.lag_s, s, f));
            let (s, f) = (t1 - 6.0, t1 + 10.0);
            println!("   end    true {}", times(&truth, 0.0, s, f));
            println!("        counted {}", times(&found, e.lag_s, s, f));
        }
        per.entry(log.group.clone().unwrap_or_default())
            .or_default()
            .push((e.start, e.end, e.start + e.middle + e.end));
    }
    println!("\nplacement  traces  starts exact  ends exact  Σ|start|  Σ|end|  Σ|total| (steps)");
    let mut rows: Vec<(String, Vec<Split>)> = per.into_iter().collect();
    let all: Vec<Split> = rows.iter().flat_map(|r| r.1.clone()).collect();
    rows.push(("all".into(), all));
    for (g, v) in &rows {
        let exact = |f: fn(&Split) -> i64| v.iter().filter(|x| f(x) == 0).count();
        let sum = |f: fn(&Split) -> i64| v.iter().map(|x| f(x).abs()).sum::<i64>();
        println!(
            "{g:<12} {:>4}  {:>12}  {:>10}  {:>8}  {:>6}  {:>8}",
            v.len(),
            exact(|x| x.0),
            exact(|x| x.1),
            sum(|x| x.0),
            sum(|x| x.1),
            sum(|x| x.2)
        );
    }
}
