//! Heading and track per carrying mode on the simulator ([`pdr::sim::scenarios::carried_walk`],
//! seeds 1–8): each step's heading against the true path heading at its time (mean
//! absolute error, degrees), the step count against the truth, and the track's p75 error and
//! end error, m.
//!
//! `cargo run --release --example carry_heading`
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Carry};

fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    (a + 0.5 * t).rem_euclid(t) - 0.5 * t
}

fn main() {
    println!("| mode | steps (truth) | heading MAE ° | p75 m | end m |");
    println!("|---|---|---|---|---|");
    for carry in Carry::ALL {
        let (mut n, mut nt, mut herr, mut nh) = (0, 0, 0.0, 0);
        let (mut p75s, mut ends) = (Vec::new(), Vec::new());
        for seed in 1..=8 {
            let sim = scenarios::carried_walk(carry, seed).generate();
            let run = replay(PipelineConfig::default(), &sim.records).unwrap();
            let tr = run.pipeline.track();
            n += tr.len();
            nt += sim.truth.observed_steps();
            let mut errs = Vec::new();
            let (mut h1, mut n1) = (0.0, 0);
            for s in tr {
                let k = sim
                    .truth
                    .steps
                    .partition_point(|x| x.t < s.t)
                    .min(sim.truth.steps.len() - 1);
                if let Some(h) = s.heading_rad {
                    let e = wrap(h - sim.truth.steps[k].heading_rad).to_degrees();
                    h1 += e;
                    n1 += 1;
                    herr += e.abs();
                    nh += 1;
                }
                let (e, nn) = sim.truth.position_at(s.t);
                errs.push(((s.east_m - e).powi(2) + (s.north_m - nn).powi(2)).sqrt());
            }
            if std::env::var("PER_SEED").is_ok() {
                eprintln!(
                    "{} seed {seed}: mean signed heading error {:.1}°",
                    carry.as_str(),
                    h1 / n1.max(1) as f64
                );
            }
            errs.sort_by(|a, b| a.total_cmp(b));
            p75s.push(errs[(errs.len() * 3) / 4]);
            let last = tr.last().unwrap();
            ends.push(
                ((last.east_m - sim.truth.end.0).powi(2)
                    + (last.north_m - sim.truth.end.1).powi(2))
                .sqrt(),
            );
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        println!(
            "| {} | {n} ({nt}) | {:.1} | {:.2} | {:.2} |",
            carry.as_str(),
            herr / nh.max(1) as f64,
            mean(&p75s),
            mean(&ends)
        );
    }
}
