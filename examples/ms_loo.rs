//! Leave-one-out check of the default walking step-length offset on the Microsoft indoor traces.
//! The default line's offset b was chosen on these same 24 walks, so the `pdr eval` waypoint
//! p75 is in-sample. Here each trace is scored with the offset that minimises the pooled
//! waypoint p75 of the other 23 (a grid of 0.01 m), and the held-out errors are pooled.
//!
//! `cargo run --release --example ms_loo`
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::PipelineConfig;
use pdr::engine::StepLengthModel;
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn p75(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    pdr::eval::percentile(&v, 75.0)
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ms-indoor");
    let Ok(mut set) = DirSet::new(&root) else {
        println!("skipped: {} not found", root.display());
        return;
    };
    let logs: Vec<_> = import_all(&mut set)
        .into_iter()
        .flatten()
        .filter(|l| l.truth.waypoints.len() >= 2)
        .collect();
    let grid: Vec<f64> = (8..=26).map(|i| i as f64 * 0.01).collect();
    // errors[g][i]: waypoint errors of trace i with offset grid[g].
    let errors: Vec<Vec<Vec<f64>>> = grid
        .iter()
        .map(|&b| {
            let mut cfg = PipelineConfig::default();
            if let StepLengthModel::Frequency(p) = &mut cfg.step_length {
                p.walking.b = b;
            }
            logs.iter()
                .map(|l| pdr::eval::evaluate(l, &cfg).waypoint_errors_m)
                .collect()
        })
        .collect();
    let pooled = |g: usize, skip: Option<usize>| {
        p75(errors[g]
            .iter()
            .enumerate()
            .filter(|(i, _)| Some(*i) != skip)
            .flat_map(|(_, e)| e.iter().copied())
            .collect())
    };
    let best_all = (0..grid.len())
        .min_by(|&a, &b| pooled(a, None).total_cmp(&pooled(b, None)))
        .unwrap();
    let mut held_out = Vec::new();
    let mut chosen = Vec::new();
    for i in 0..logs.len() {
        let g = (0..grid.len())
            .min_by(|&a, &b| pooled(a, Some(i)).total_cmp(&pooled(b, Some(i))))
            .unwrap();
        chosen.push(grid[g]);
        held_out.extend(errors[g].get(i).into_iter().flatten().copied());
    }
    let default_b = match PipelineConfig::default().step_length {
        StepLengthModel::Frequency(p) => p.walking.b,
        StepLengthModel::Weinberg { .. }
        | StepLengthModel::Fuzzy(_)
        | StepLengthModel::Pitch(_) => f64::NAN,
    };
    let g_def = grid
        .iter()
        .position(|&b| (b - default_b).abs() < 1e-9)
        .unwrap();
    println!(
        "{} traces, offsets {:.2}..{:.2} m",
        logs.len(),
        grid[0],
        grid[grid.len() - 1]
    );
    println!(
        "default b {default_b:.2}: pooled p75 {:.2} m (in-sample)",
        pooled(g_def, None)
    );
    println!(
        "best b on all 24: {:.2} (p75 {:.2} m)",
        grid[best_all],
        pooled(best_all, None)
    );
    chosen.sort_by(f64::total_cmp);
    println!(
        "leave-one-out: pooled held-out p75 {:.2} m; offsets chosen {:.2}..{:.2} m",
        p75(held_out),
        chosen[0],
        chosen[chosen.len() - 1]
    );
    for (g, b) in grid.iter().enumerate() {
        println!("  b {b:.2}: pooled p75 {:.2} m", pooled(g, None));
    }
}
