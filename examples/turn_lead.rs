//! The heading in a turn on the simulator ([`pdr::sim::scenarios::carried_walk`], seeds 1–8, two
//! right-angle turns a walk), with and without `heading.turn_lead`
//! (`engine/heading/turn.rs`): per carrying mode, the mean of how far each turn shifts the track
//! sideways ([`pdr::eval::turns`]), and each step's heading against the direction of the true
//! step it ends (mean absolute error).
//!
//! `cargo run --release --example turn_lead`

use pdr::engine::{replay, PipelineConfig};
use pdr::eval::turns::{turn_shifts, Found};
use pdr::sim::{scenarios, Carry};

fn main() {
    println!(
        "| mode | sideways shift per turn, m: without / with | heading MAE °: without / with |"
    );
    println!("|---|---|---|");
    for carry in Carry::ALL {
        let mut cells = Vec::new();
        for lead in [false, true] {
            let mut cfg = PipelineConfig::default();
            cfg.heading.turn_lead = lead;
            let (mut shifts, mut errors) = (Vec::new(), Vec::new());
            for seed in 1..=8 {
                let sim = scenarios::carried_walk(carry, seed).generate();
                let run = replay(cfg.clone(), &sim.records).unwrap();
                let found = Found::from_track(run.pipeline.track());
                let (s, e) = turn_shifts(&found, &sim.truth.step_points(), 0.1);
                shifts.extend(s.iter().map(|x| x.abs()));
                errors.extend(e.iter().map(|x| x.abs().to_degrees()));
            }
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
            cells.push((mean(&shifts), mean(&errors)));
        }
        println!(
            "| {} | {:.2} / {:.2} | {:.1} / {:.1} |",
            carry.as_str(),
            cells[0].0,
            cells[1].0,
            cells[0].1,
            cells[1].1
        );
    }
}
