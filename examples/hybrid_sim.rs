//! Strozzi 2017 §4's hybrid against foot mode on simulated two-sensor walks, over noise seeds:
//! end error (m) of each `hybrid.method` through the pipeline. `cargo run --release --example
//! hybrid_sim`.
//!
//! Walks: once round the 400 m athletic track (`scenarios::athletic_track`, Strozzi's outdoor
//! path) with the foot gyroscope's bias drifting by 0.05°/s over the walk, the same without
//! drift, and a 4 × 25 m square (sharp 90° corners, Strozzi's indoor case) with the drift.

use pdr::engine::replay;
use pdr::settings::Settings;
use pdr::sim::{scenarios, FootImu, Scenario};

fn end_errors(sc: &Scenario, drift_deg_s: f64) -> [f64; 3] {
    let foot = FootImu {
        gyro_bias_drift: [0.0, 0.0, drift_deg_s.to_radians() / sc.duration_s()],
        ..FootImu::default()
    };
    let (sim, fs) = sc.generate_two_sensor(&foot);
    let start = fs.track.pose(0.0).p;
    let end = fs.strides.last().map_or((start.x, start.y), |s| s.to);
    let mut out = [f64::NAN; 3];
    for (k, m) in ["foot", "mid_swing", "fir_crossing"].iter().enumerate() {
        let cfg = Settings::new().with("hybrid.method", *m).config().unwrap();
        let r = replay(cfg, &sim.records).unwrap();
        if let Some(l) = r.pipeline.track().last() {
            out[k] = libm::hypot(l.east_m - (end.0 - start.x), l.north_m - (end.1 - start.y));
        }
    }
    out
}

fn main() {
    println!("walk                      seed  foot    mid_swing  fir_crossing   (end error, m)");
    for (name, drift) in [("track, drift 0.05°/s", 0.05), ("track, no drift", 0.0)] {
        for seed in 1..=5u64 {
            let mut sc = scenarios::athletic_track(1);
            sc.seed = seed;
            let e = end_errors(&sc, drift);
            println!(
                "{name:<25} {seed:>4}  {:>6.2}  {:>9.2}  {:>12.2}",
                e[0], e[1], e[2]
            );
        }
    }
    for seed in 1..=5u64 {
        let mut sc = scenarios::square(25.0);
        sc.sensors.os_yaw_error_deg = 2.0;
        sc.seed = seed;
        let e = end_errors(&sc, 0.05);
        println!(
            "{:<25} {seed:>4}  {:>6.2}  {:>9.2}  {:>12.2}",
            "square 4×25 m, drift", e[0], e[1], e[2]
        );
    }
}
