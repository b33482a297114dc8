//! The carrying-mode detector's confusion matrices ([`pdr::engine::carry`]): on the
//! simulator's five modes ([`pdr::sim::scenarios::carried_walk`], seeds 1–8) and on the real
//! logs whose mode is known: the Oxford placements (accelerometer only), the Microsoft traces
//! (hand, screen up) and the IPIN 2023 walks (hand). Each step counts once, with the mode the
//! engine gave it (`none` before the detector decided).
//!
//! `cargo run --release --example carry_modes`
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::carry::CarryMode;
use pdr::engine::{replay, PipelineConfig, Record};
use pdr::io::import::{import_all, DirSet};
use pdr::sim::{scenarios, Carry};
use std::collections::BTreeMap;
use std::path::Path;

const COLS: [&str; 6] = ["pocket", "hand", "swinging", "ear", "bag", "none"];

#[derive(Default)]
struct Matrix(BTreeMap<String, [u64; 6]>);

impl Matrix {
    fn add(&mut self, truth: &str, track: &[pdr::engine::StepRecord]) {
        let row = self.0.entry(truth.to_string()).or_default();
        for s in track {
            let k = match s.carry {
                Some(m) => CarryMode::ALL.iter().position(|&x| x == m).unwrap(),
                None => 5,
            };
            row[k] += 1;
        }
    }
    fn print(&self, title: &str, expected: impl Fn(&str) -> Option<&'static str>) {
        println!("\n{title}\n| truth | {} | right |", COLS.join(" | "));
        println!("|---|{}---|", "---|".repeat(COLS.len()));
        let (mut right, mut all) = (0, 0);
        for (truth, row) in &self.0 {
            let n: u64 = row.iter().sum();
            let ok = expected(truth).map(|e| row[COLS.iter().position(|&c| c == e).unwrap()]);
            if let Some(k) = ok {
                right += k;
                all += n;
            }
            let share = ok.map_or("—".to_string(), |k| {
                format!("{:.1} %", 100.0 * k as f64 / n.max(1) as f64)
            });
            let cells: Vec<String> = row.iter().map(|v| v.to_string()).collect();
            println!("| {truth} | {} | {share} |", cells.join(" | "));
        }
        println!(
            "share of steps right: {:.1} % ({right} of {all})",
            100.0 * right as f64 / all.max(1) as f64
        );
    }
}

fn main() {
    let mut sim = Matrix::default();
    for carry in Carry::ALL {
        for seed in 1..=8 {
            let s = scenarios::carried_walk(carry, seed).generate();
            let run = replay(PipelineConfig::default(), &s.records).unwrap();
            sim.add(carry.as_str(), run.pipeline.track());
        }
    }
    sim.print("simulator (seeds 1–8)", |t| {
        Some(match t {
            "texting" => "hand",
            "pocket" => "pocket",
            "swinging" => "swinging",
            "ear" => "ear",
            _ => "bag",
        })
    });
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    if !data.exists() {
        println!("\nreal logs skipped: {} not found", data.display());
        return;
    }
    let mut real = Matrix::default();
    for (set, label) in [
        ("oxford-steps", None),
        ("ms-indoor", Some("ms-indoor (hand)")),
        ("ipin2023", Some("ipin2023 (hand)")),
    ] {
        let Ok(mut files) = DirSet::new(&data.join(set)) else {
            continue;
        };
        for log in import_all(&mut files).into_iter().flatten() {
            let run = replay(log.dated(&PipelineConfig::default()), &log.records).unwrap();
            let truth = label
                .map(str::to_string)
                .or(log.group.clone())
                .unwrap_or_default();
            real.add(&truth, run.pipeline.track());
            let _ = Record::Gap(0.0, 0.0);
        }
    }
    real.print("real logs", |t| match t {
        "FrontPocket" | "BackPocket" => Some("pocket"),
        "InHand" | "ms-indoor (hand)" | "ipin2023 (hand)" => Some("hand"),
        "SwingingArm" => Some("swinging"),
        "Purse" | "NeckPouch" => Some("bag"),
        _ => None,
    });
}
