#![allow(clippy::disallowed_methods, missing_docs)]
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Carry};
fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    (a + 0.5 * t).rem_euclid(t) - 0.5 * t
}
fn main() {
    for real in [true, false] {
        for carry in Carry::ALL {
            for kind in ["short", "carried"] {
                if kind == "carried" && !real {
                    continue;
                }
                let mut line = String::new();
                let mut ends = Vec::new();
                let mut off = [0usize; 8];
                let mut nwalk = 0;
                let seeds: Vec<u64> = if kind == "short" {
                    (1..=20).collect()
                } else {
                    (1..=8).collect()
                };
                for seed in seeds {
                    let sim = if kind == "short" {
                        scenarios::short_walk(carry, seed, real)
                    } else {
                        scenarios::carried_walk(carry, seed)
                    }
                    .generate();
                    let run = replay(PipelineConfig::default(), &sim.records).unwrap();
                    let tr = run.pipeline.track();
                    nwalk += 1;
                    let mut bad = Vec::new();
                    for (i, s) in tr.iter().enumerate().take(8) {
                        let k = sim
                            .truth
                            .steps
                            .partition_point(|x| x.t < s.t)
                            .min(sim.truth.steps.len() - 1);
                        if let Some(h) = s.heading_rad {
                            let e = wrap(h - sim.truth.steps[k].heading_rad).to_degrees();
                            if e.abs() > 90.0 {
                                off[i] += 1;
                                bad.push(i + 1);
                            }
                        }
                    }
                    if !bad.is_empty() {
                        line += &format!(" s{seed}:{bad:?}");
                    }
                    let last = tr.last().unwrap();
                    ends.push(
                        ((last.east_m - sim.truth.end.0).powi(2)
                            + (last.north_m - sim.truth.end.1).powi(2))
                        .sqrt(),
                    );
                }
                ends.sort_by(|a, b| a.total_cmp(b));
                println!("{} {carry:?} {kind} ({nwalk}): off>90 by step idx {off:?} = {}; end median {:.2} max {:.2};{line}", if real {"real"} else {"hist"}, off.iter().sum::<usize>(), ends[ends.len()/2], ends[ends.len()-1]);
            }
        }
    }
}
