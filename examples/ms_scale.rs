//! Per Microsoft indoor trace: walked distance between the first and last waypoint, estimated
//! against the waypoint polyline (scale), steps and mean step length, waypoint p75 error.
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::replay;
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cfg = pdr::settings::Settings::new()
        .with_args(&args)
        .and_then(|s| s.config())
        .unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ms-indoor");
    let Ok(mut set) = DirSet::new(&root) else {
        println!("skipped: {} not found", root.display());
        return;
    };
    for log in import_all(&mut set).into_iter().flatten() {
        let w = &log.truth.waypoints;
        if w.len() < 2 {
            continue;
        }
        let (t0, t1) = (w[0].t, w[w.len() - 1].t);
        let truth: f64 = w
            .windows(2)
            .map(|p| (p[1].x_m - p[0].x_m).hypot(p[1].y_m - p[0].y_m))
            .sum();
        let r = replay(cfg.clone(), &log.records).unwrap();
        let steps: Vec<_> = r
            .pipeline
            .track()
            .iter()
            .filter(|s| s.t > t0 && s.t <= t1)
            .collect();
        let est: f64 = steps.iter().map(|s| s.length_m).sum();
        let f: f64 = steps.iter().map(|s| s.freq_hz).sum::<f64>() / steps.len().max(1) as f64;
        let res = pdr::eval::evaluate(&log, &cfg);
        println!(
            "{:<40} truth {:6.1} m est {:6.1} m scale {:5.2}  steps {:4} mean SL {:.2} f {:.2} Hz  true SL if count right {:.2}  p75 {:5.1}",
            log.source.rsplit('/').take(2).collect::<Vec<_>>().join("<"),
            truth,
            est,
            est / truth,
            steps.len(),
            est / steps.len().max(1) as f64,
            f,
            truth / steps.len().max(1) as f64,
            res.waypoint_error_m.map_or(0.0, |m| m.p75)
        );
    }
}
