//! The simulated real-GNSS city walk (`sim::scenarios::gnss_city_walk_real`, seeds 1–4): the
//! autocorrelation of its fixes' error at the lags where IPIN 2023's phones were measured
//! (≤ 5 s 0.79, 5–10 s 0.59, 10–20 s 0.32, 20–45 s about 0.2; `--example gnss_errors`), and
//! the default pipeline on it: GNSS alone, fused and smoothed p75, the final corrections.
//!
//! `cargo run --release --example city_real_gnss`
#[path = "../tests/common/fusion.rs"]
#[allow(dead_code)]
mod fusion;
#[path = "../tests/common/gnss.rs"]
mod gnss;

use fusion::{errors, gnss_errors, p75, run};
use gnss::{autocorrelation, fixed, Fixed};
use pdr::engine::PipelineConfig;
use pdr::sim::{scenarios, Simulation};

fn city_real(seed: u64) -> Simulation {
    let mut sc = scenarios::gnss_city_walk_real();
    sc.seed = seed;
    sc.generate()
}

fn main() {
    let walks: Vec<Simulation> = (1..=4).map(city_real).collect();
    let fixes: Vec<Vec<Fixed>> = walks
        .iter()
        .map(|w| fixed(w).into_iter().skip(1).collect())
        .collect();
    for lag in [3.0, 7.0, 15.0, 30.0] {
        let rho = autocorrelation(&fixes, lag);
        println!("real-GNSS city walk: autocorrelation {rho:.2} at {lag} s");
    }
    println!("\nseed  gnss p75  fused p75  smoothed p75  scale   heading corr");
    for (seed, sim) in (1..).zip(&walks) {
        let p = run(sim, PipelineConfig::default());
        let gnss = p75(&gnss_errors(sim, &p));
        let fused = p75(&errors(sim, &p, p.fused()));
        let smoothed = p75(&errors(sim, &p, &p.smoothed()));
        let Some(last) = p.fused().last() else {
            println!("{seed:>4}  no fused step");
            continue;
        };
        println!(
            "{seed:>4}  {gnss:>8.2}  {fused:>9.2}  {smoothed:>12.2}  {:.3}  {:>+8.2}°",
            last.scale,
            last.bias_rad.to_degrees()
        );
    }
    println!(
        "(the scale to learn {:.3}, the heading correction {:+.1}°)",
        1.0 / scenarios::GNSS_CITY_LENGTH_FACTOR,
        -scenarios::GNSS_CITY_HEADING_BIAS_DEG
    );
}
