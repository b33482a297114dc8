//! The short walks ([`scenarios::short_walk`]): 20 steps between 3 s of standing, in each
//! carrying mode the simulator has, seeds 1–20 (cadence 1.6–2.0 Hz, the eight pocket poses,
//! either pocket), with the simulator's historic ends (a bout starts and stops at full stride)
//! and with real-shaped ones ([`pdr::sim::ends`]: the standing sway, the first and the last
//! steps at half strength, the body settling, the pocket's phone taken out after the walk).
//! Each walk's count is split into its first and last 4 s ([`pdr::eval::ends`]), so a step lost
//! at the start and a phantom at the end do not cancel. Prints, per mode, how many walks are
//! exact at the start, at the end, in all three parts and in the whole count, and for the first
//! walk of a mode that misses, its first and last steps against the true footfalls.
//!
//! Swinging: the PLL counts the swinging hand's steps half a step after the footfalls, so which
//! footfall a step belongs to at a boundary is a coin's toss, and only the whole count is
//! meaningful there.
//!
//! `cargo run --release --example short_walks`
use pdr::engine::{replay, PipelineConfig};
use pdr::eval::ends::end_errors;
use pdr::sim::{scenarios, Carry};

fn main() {
    for real in [false, true] {
        println!(
            "{}",
            if real {
                "real-shaped ends:"
            } else {
                "historic ends:"
            }
        );
        for carry in Carry::ALL {
            let (mut starts, mut ends, mut all, mut whole, mut shown) = (0, 0, 0, 0, false);
            for seed in 1..=20u64 {
                let sim = scenarios::short_walk(carry, seed, real).generate();
                let run = replay(PipelineConfig::default(), &sim.records).unwrap();
                let found: Vec<f64> = run.pipeline.track().iter().map(|s| s.t).collect();
                let truth: Vec<f64> = sim.truth.steps.iter().map(|s| s.t).collect();
                let e = end_errors(&found, &truth, 4.0).unwrap();
                starts += usize::from(e.start == 0);
                ends += usize::from(e.end == 0);
                all += usize::from(e.start == 0 && e.end == 0 && e.middle == 0);
                whole += usize::from(found.len() == truth.len());
                if (e.start, e.middle, e.end) != (0, 0, 0) && !shown {
                    shown = true;
                    let span = |t: &[f64]| {
                        format!(
                            "first {:.2} s, last {:.2} s",
                            t.first().copied().unwrap_or(f64::NAN),
                            t.last().copied().unwrap_or(f64::NAN)
                        )
                    };
                    println!(
                        "  {carry:?} seed {seed}: start {:+}, middle {:+}, end {:+}; steps {} ({}) against footfalls {} ({})",
                        e.start,
                        e.middle,
                        e.end,
                        found.len(),
                        span(&found),
                        truth.len(),
                        span(&truth)
                    );
                }
            }
            println!(
                "{:<9} exact of 20 walks: start {starts:>2}, end {ends:>2}, all three parts {all:>2}, whole count {whole:>2}",
                carry.as_str()
            );
        }
    }
}
