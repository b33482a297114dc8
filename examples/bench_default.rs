//! One replay of a simulated 10-minute walk through the default pipeline, for profilers
//! (`valgrind --tool=callgrind target/release/examples/bench_default`).
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{Scenario, Segment, Walker};

fn main() {
    let w = Walker::default();
    let mut segs = Vec::new();
    for _ in 0..8 {
        segs.push(Segment::walk_distance(60.0, 1.8, &w));
        segs.push(Segment::walk(2.0, 1.8).turning(90.0));
    }
    let sim = Scenario::new(segs).generate();
    let mut r = replay(PipelineConfig::default(), &sim.records).unwrap();
    for _ in 0..std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(9)
    {
        r = replay(PipelineConfig::default(), &sim.records).unwrap();
    }
    println!(
        "{} samples, {} steps",
        sim.records.len(),
        r.pipeline.track().len()
    );
}
