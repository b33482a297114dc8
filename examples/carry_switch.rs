//! The heading across a change of carrying mode mid-walk, on the simulator
//! ([`pdr::sim::scenarios::switched_walk`], seeds 1–8, every ordered pair of the five modes):
//! each step's heading against
//! the true path heading (mean absolute error, degrees) before the change, over the 5 s from its
//! start, and after; the count against the truth; and the end error, m. Each pair is run with the
//! heading carried across the change (the default) and with each source alone.
//!
//! `cargo run --release --example carry_switch [FIRST_SEED]` (8 seeds from it; 1 unless given:
//! 9 runs walks no constant was chosen with)
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path

use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Carry};

fn main() {
    let first: u64 = std::env::args()
        .nth(1)
        .map_or(1, |a| a.parse().expect("FIRST_SEED: a whole number"));
    let pairs: Vec<(Carry, Carry)> = Carry::ALL
        .into_iter()
        .flat_map(|a| Carry::ALL.into_iter().map(move |b| (a, b)))
        .filter(|(a, b)| a != b)
        .collect();
    let mut alone = PipelineConfig::default();
    alone.heading.continuity = None;
    println!("| change | steps (truth) | heading MAE ° before / 5 s / after | end m | each source alone: ° after, end m |");
    println!("|---|---|---|---|---|");
    for (from, to) in pairs {
        let run = |cfg: &PipelineConfig| {
            let (mut n, mut nt, mut end) = (0, 0, 0.0);
            let mut e = [(0.0, 0usize); 3];
            for seed in first..first + 8 {
                let sc = scenarios::switched_walk(from, to, seed);
                let t_switch = sc.switches[0].t_s;
                let sim = sc.generate();
                let r = replay(cfg.clone(), &sim.records).unwrap();
                let track = r.pipeline.track();
                n += track.len();
                nt += sim.truth.observed_steps();
                for s in track {
                    if let Some(err) = sim.truth.heading_error(s) {
                        let part = if s.t < t_switch {
                            0
                        } else if s.t < t_switch + 5.0 {
                            1
                        } else {
                            2
                        };
                        e[part].0 += err.abs().to_degrees();
                        e[part].1 += 1;
                    }
                }
                let last = track.last().unwrap();
                end += (last.east_m - sim.truth.end.0).hypot(last.north_m - sim.truth.end.1);
            }
            let mae = e.map(|(s, k)| s / k.max(1) as f64);
            (n, nt, mae, end / 8.0)
        };
        let (n, nt, mae, end) = run(&PipelineConfig::default());
        let (_, _, mae0, end0) = run(&alone);
        println!(
            "| {} → {} | {n} ({nt}) | {:.1} / {:.1} / {:.1} | {end:.2} | {:.1}, {end0:.2} |",
            from.as_str(),
            to.as_str(),
            mae[0],
            mae[1],
            mae[2],
            mae0[2],
        );
    }
}
