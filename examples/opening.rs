//! A walk's opening ([`pdr::engine::heading::opening`]): per carrying mode, how many of
//! each walk's first 8 steps walk more than 90° off the true direction, on how many walks, and
//! the walks' median and worst end error, with the opening held (the default) and without
//! (`heading.opening_steps = 0`). The short walks ([`scenarios::short_walk`], seeds 1–20) with
//! real-shaped ends and with the historic ones, and [`scenarios::carried_walk`] (seeds 1–8).
//!
//! `cargo run --release --example opening`
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::heading::HeadingConfig;
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Carry, Scenario};

/// Steps backwards among the first 8, walks with one, median and worst end error (m).
fn measure(walks: &[Scenario], cfg: &PipelineConfig) -> (usize, usize, f64, f64) {
    let (mut steps, mut bad) = (0, 0);
    let mut ends = Vec::new();
    for w in walks {
        let sim = w.generate();
        let run = replay(cfg.clone(), &sim.records).unwrap();
        let track = run.pipeline.track();
        let off = track
            .iter()
            .take(8)
            .filter(|s| {
                sim.truth
                    .heading_error(s)
                    .is_some_and(|e| e.abs() > std::f64::consts::FRAC_PI_2)
            })
            .count();
        steps += off;
        bad += usize::from(off > 0);
        if let Some(last) = track.last() {
            ends.push(
                ((last.east_m - sim.truth.end.0).powi(2)
                    + (last.north_m - sim.truth.end.1).powi(2))
                .sqrt(),
            );
        }
    }
    ends.sort_by(f64::total_cmp);
    let median = ends.get(ends.len() / 2).copied().unwrap_or(f64::NAN);
    (steps, bad, median, ends.last().copied().unwrap_or(f64::NAN))
}

fn main() {
    let without = PipelineConfig {
        heading: HeadingConfig {
            opening_steps: 0,
            ..HeadingConfig::default()
        },
        ..PipelineConfig::default()
    };
    println!("| walks | mode | without: steps backwards (walks), end median / worst m | held |");
    println!("|---|---|---|---|");
    for (name, make) in [
        (
            "short, real-shaped ends",
            (|c, s| scenarios::short_walk(c, s, true)) as fn(Carry, u64) -> Scenario,
        ),
        ("short, historic ends", |c, s| {
            scenarios::short_walk(c, s, false)
        }),
        ("carried_walk", scenarios::carried_walk),
    ] {
        let seeds = if name == "carried_walk" { 8 } else { 20 };
        for carry in Carry::ALL {
            let walks: Vec<Scenario> = (1..=seeds).map(|s| make(carry, s)).collect();
            let show =
                |(s, w, m, x): (usize, usize, f64, f64)| format!("{s} ({w}), {m:.2} / {x:.2}");
            println!(
                "| {name} | {} | {} | {} |",
                carry.as_str(),
                show(measure(&walks, &without)),
                show(measure(&walks, &PipelineConfig::default()))
            );
        }
    }
}
