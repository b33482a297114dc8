//! The carrying-mode detector's features on the real logs whose mode is known, and its rule
//! scored leave-one-walker-out ([`pdr::engine::carry`]).
//!
//! Truth: TyrEx's folder names and the pocket sets' placement ([`pdr::io::import::Truth::carry`]),
//! the Oxford placements (the armband has no mode), the hand for the Microsoft and IPIN walks,
//! the simulator's five modes (seeds 1–8) and its demo walk (the pocket, upright, screen out of
//! the thigh). Each evaluation of the detector inside the
//! truth's step window counts once, with the mode the vote decided (a step-weighted figure is
//! `pdr eval`'s `carry_share_by_group`). WeAllWalk's left phone (`1L`), which does not move as
//! a thigh does, is shown but the thresholds are not chosen for it.
//!
//! Leave-one-walker-out: for each walker of TyrEx (the first name), UbiComp 2013 (pN) and
//! WeAllWalk (IDn), the thresholds of the rule with a gyroscope are chosen on a grid without
//! that walker's logs (the largest smallest share over the groups, then the largest mean), and
//! that walker is scored with them.
//!
//! `cargo run --release --example carry_features` (the tables), `… -- --csv` (one row per
//! evaluation, for plotting).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::carry::{Ballot, CarryConfig, CarryFeatures, CarryMode};
use pdr::engine::replay::replay_observed;
use pdr::engine::{Pipeline, PipelineConfig, Record};
use pdr::io::import::{import_all, DirSet};
use pdr::sim::{scenarios, Carry};
use std::collections::BTreeMap;
use std::path::Path;

/// One evaluation of the detector.
struct Row {
    /// Data set and group (`tyrex:Swinging`), the figures' row.
    group: String,
    /// Data set and walker (`tyrex:Jakob`).
    walker: String,
    truth: Option<CarryMode>,
    /// Inside the truth's step window, with a mode.
    inside: bool,
    /// Inside, and a mode the thresholds are chosen for.
    scored: bool,
    t: f64,
    f: CarryFeatures,
}

fn main() {
    let logs = collect();
    if std::env::args().any(|a| a == "--csv") {
        print_csv(&logs);
        return;
    }
    let grid = grid();
    let right: Vec<Vec<bool>> = grid.iter().map(|c| decide(&logs, c)).collect();
    let rows: Vec<&Row> = logs.iter().flatten().collect();
    let defaults = decide(&logs, &CarryConfig::default());
    let mut walkers: Vec<&str> = rows
        .iter()
        .filter(|r| {
            r.scored
                && ["tyrex", "ubicomp", "weallwalk"]
                    .iter()
                    .any(|s| r.walker.starts_with(s))
        })
        .map(|r| r.walker.as_str())
        .collect();
    walkers.sort_unstable();
    walkers.dedup();
    let mut lowo = vec![None; rows.len()];
    println!("thresholds chosen without each walker (swing rate, pendulum, side axis, side ratio, ear c1):");
    for w in &walkers {
        let best = best_config(&rows, &right, |r| r.walker != *w);
        let c = &grid[best];
        println!(
            "  {w}: {} {} {} {} {}",
            c.swing_rate_min,
            c.pendulum_ratio_max,
            c.side_swing_axis_min,
            c.side_swing_ratio_max,
            c.ear_step_corr_max
        );
        for (i, r) in rows.iter().enumerate() {
            if r.walker == *w {
                lowo[i] = Some(right[best][i]);
            }
        }
    }
    let in_sample = best_config(&rows, &right, |_| true);
    println!(
        "\n| group | evaluations | defaults | best on the grid, in-sample | leave-one-walker-out |"
    );
    println!("|---|---|---|---|---|");
    for (g, idx) in groups(&rows, |r| r.inside) {
        let share = |ok: &dyn Fn(usize) -> Option<bool>| {
            let v: Vec<bool> = idx.iter().filter_map(|&i| ok(i)).collect();
            (!v.is_empty())
                .then(|| 100.0 * v.iter().filter(|&&b| b).count() as f64 / v.len() as f64)
        };
        let pct = |x: Option<f64>| x.map_or("—".to_string(), |v| format!("{v:.1} %"));
        println!(
            "| {g} | {} | {} | {} | {} |",
            idx.len(),
            pct(share(&|i| Some(defaults[i]))),
            pct(share(&|i| Some(right[in_sample][i]))),
            pct(share(&|i| lowo[i])),
        );
    }
}

/// The row indices of each group, of the rows `keep` keeps.
fn groups(rows: &[&Row], keep: impl Fn(&Row) -> bool) -> BTreeMap<String, Vec<usize>> {
    let mut out = BTreeMap::<String, Vec<usize>>::new();
    for (i, r) in rows.iter().enumerate() {
        if keep(r) {
            out.entry(r.group.clone()).or_default().push(i);
        }
    }
    out
}

/// The index of the grid's configuration with the largest smallest share over the groups (then
/// the largest mean share), on the rows `train` keeps.
fn best_config(rows: &[&Row], right: &[Vec<bool>], train: impl Fn(&Row) -> bool) -> usize {
    let groups: Vec<Vec<usize>> = groups(rows, |r| r.scored)
        .into_values()
        .map(|idx| {
            idx.into_iter()
                .filter(|&i| train(rows[i]))
                .collect::<Vec<_>>()
        })
        .filter(|idx| !idx.is_empty())
        .collect();
    let score = |ok: &Vec<bool>| {
        let shares: Vec<f64> = groups
            .iter()
            .map(|idx| idx.iter().filter(|&&i| ok[i]).count() as f64 / idx.len() as f64)
            .collect();
        let min = shares.iter().copied().fold(f64::INFINITY, f64::min);
        min + 0.01 * shares.iter().sum::<f64>() / shares.len() as f64
    };
    let mut best = (0, f64::NEG_INFINITY);
    for (k, ok) in right.iter().enumerate() {
        let s = score(ok);
        if s > best.1 {
            best = (k, s);
        }
    }
    best.0
}

/// The thresholds tried for the rule with a gyroscope, the others at their defaults.
fn grid() -> Vec<CarryConfig> {
    let mut out = Vec::new();
    for swing in [0.5, 0.55, 0.6, 0.65, 0.7] {
        for pendulum in [7.0, 7.5, 8.0, 8.5, 9.0] {
            for axis in [0.8, 0.85, 0.9, 0.93] {
                for side in [10.5, 11.0, 11.5, 12.0, 12.5] {
                    for ear in [0.25, 0.35, 0.45] {
                        out.push(CarryConfig {
                            swing_rate_min: swing,
                            pendulum_ratio_max: pendulum,
                            side_swing_axis_min: axis,
                            side_swing_ratio_max: side,
                            ear_step_corr_max: ear,
                            ..CarryConfig::default()
                        });
                    }
                }
            }
        }
    }
    out
}

/// For each row (in the order of the logs), whether the mode `cfg`'s rule and vote decide
/// there is the truth's.
fn decide(logs: &[Vec<Row>], cfg: &CarryConfig) -> Vec<bool> {
    let mut out = Vec::new();
    for log in logs {
        let mut ballot = Ballot::default();
        for r in log {
            let mode = ballot.cast(cfg.classify(&r.f), cfg);
            out.push(r.truth.is_some() && mode == r.truth);
        }
    }
    out
}

/// The rows of every log, one list per log.
fn collect() -> Vec<Vec<Row>> {
    let mut logs = Vec::new();
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    for set in [
        "tyrex-pocket",
        "ubicomp13-pocket",
        "weallwalk",
        "oxford-steps",
        "ms-indoor",
        "ipin2023",
    ] {
        let Ok(mut files) = DirSet::new(&data.join(set)) else {
            eprintln!("{set} skipped: not found under {}", data.display());
            continue;
        };
        for log in import_all(&mut files).into_iter().flatten() {
            let short = set.split(['-', '1']).next().unwrap_or(set);
            let group = log.group.clone().unwrap_or_else(|| "hand".into());
            let truth = log.truth.carry.or(match group.as_str() {
                "FrontPocket" | "BackPocket" => Some(CarryMode::Pocket),
                "InHand" | "hand" => Some(CarryMode::Hand),
                "SwingingArm" => Some(CarryMode::Swinging),
                "Purse" | "NeckPouch" => Some(CarryMode::Bag),
                _ => None,
            });
            let meta = Row {
                group: format!("{short}:{group}"),
                walker: format!("{short}:{}", walker(set, &log.source)),
                truth,
                inside: truth.is_some(),
                scored: truth.is_some() && group != "LeftPocket",
                t: 0.0,
                f: CarryFeatures::default(),
            };
            logs.push(rows(
                &meta,
                log.dated(&PipelineConfig::default()),
                log.truth.step_window,
                &log.records,
            ));
        }
    }
    let demo = Row {
        group: "sim:demo walk (pocket)".into(),
        walker: "sim:demo".into(),
        truth: Some(CarryMode::Pocket),
        inside: true,
        scored: true,
        t: 0.0,
        f: CarryFeatures::default(),
    };
    let sim = scenarios::demo_walk().generate();
    logs.push(rows(&demo, PipelineConfig::default(), None, &sim.records));
    for carry in Carry::ALL {
        for seed in 1..=8 {
            let sim = scenarios::carried_walk(carry, seed).generate();
            let truth = match carry {
                Carry::Pocket => CarryMode::Pocket,
                Carry::Texting => CarryMode::Hand,
                Carry::Swinging => CarryMode::Swinging,
                Carry::Ear => CarryMode::Ear,
                Carry::Bag => CarryMode::Bag,
            };
            let meta = Row {
                group: format!("sim:{}", carry.as_str()),
                walker: format!("sim:{seed}"),
                truth: Some(truth),
                inside: true,
                scored: true,
                t: 0.0,
                f: CarryFeatures::default(),
            };
            logs.push(rows(&meta, PipelineConfig::default(), None, &sim.records));
        }
    }
    logs
}

/// The walker of a log: TyrEx's first name, UbiComp's pN, WeAllWalk's IDn, Oxford's name.
fn walker(set: &str, source: &str) -> String {
    let folder = Path::new(source)
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .find(|c| c.contains('_'))
        .unwrap_or_default();
    let parts: Vec<&str> = folder.split('_').collect();
    let part = |i: usize| parts.get(i).copied().unwrap_or("?").to_string();
    match set {
        "tyrex-pocket" => part(0),
        "ubicomp13-pocket" => part(0).split('.').next().unwrap_or("?").to_string(),
        "weallwalk" | "oxford-steps" => part(1),
        _ => folder,
    }
}

/// The detector's evaluations over a replay of `records`, each a copy of `meta` with its time,
/// features and whether it falls inside `window`.
fn rows(
    meta: &Row,
    cfg: PipelineConfig,
    window: Option<(f64, f64)>,
    records: &[Record],
) -> Vec<Row> {
    let (mut seen, mut out) = (0, Vec::new());
    let mut observe = |p: &Pipeline, _: usize, r: &Record, _: bool| {
        let d = p.carry_diagnostics();
        if d.evaluations == seen {
            return;
        }
        seen = d.evaluations;
        let Some(f) = d.features else { return };
        let t = r.t();
        let inside = window.map_or(true, |(a, b)| t >= a && t <= b);
        out.push(Row {
            group: meta.group.clone(),
            walker: meta.walker.clone(),
            truth: meta.truth,
            inside: meta.inside && inside,
            scored: meta.scored && inside,
            t,
            f,
        });
    };
    if replay_observed(cfg, records, &mut observe).is_err() {
        return Vec::new();
    }
    out
}

fn print_csv(logs: &[Vec<Row>]) {
    println!("group,walker,truth,scored,t,mode,ux,uy,uz,tilt_deg,c1,c2,forward_z,rate,swing_rate,swing_axis_z,drift_deg");
    let cfg = CarryConfig::default();
    for log in logs {
        let mut ballot = Ballot::default();
        for r in log {
            let mode = ballot.cast(cfg.classify(&r.f), &cfg);
            let o = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:.4}"));
            let f = &r.f;
            println!(
                "{},{},{},{},{:.2},{},{:.4},{:.4},{:.4},{:.3},{:.4},{:.4},{:.4},{},{},{},{:.2}",
                r.group,
                r.walker,
                r.truth.map_or("", |m| m.as_str()),
                u8::from(r.scored),
                r.t,
                mode.map_or("", |m| m.as_str()),
                f.up[0],
                f.up[1],
                f.up[2],
                f.tilt_deg,
                f.step_corr,
                f.stride_corr,
                f.forward_z,
                o(f.rate),
                o(f.swing_rate),
                o(f.swing_axis_z),
                f.drift_deg,
            );
        }
    }
}
