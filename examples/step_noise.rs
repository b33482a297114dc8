//! The simulated city walk's per-step errors as the fusion filter sees them: each detected
//! step's length against the true one (after the walk's known 10 % scale) and its heading against
//! the true path heading; mean, standard deviation, the 95th percentile of the deviation, and the
//! autocorrelation at lags 1, 2, 5 and 20 steps. For choosing the filter's process noise.
//!
//! `SEED=n cargo run --release --example step_noise`
#![allow(clippy::disallowed_methods)]
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::scenarios;
fn stats(name: &str, v: &[f64]) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / n;
    let ac = |k: usize| {
        v.windows(k + 1)
            .map(|w| (w[0] - m) * (w[k] - m))
            .sum::<f64>()
            / (n - k as f64)
            / var
    };
    let mut a: Vec<f64> = v.iter().map(|x| (x - m).abs()).collect();
    a.sort_by(f64::total_cmp);
    println!(
        "{name}: mean {m:.4} sd {:.4} p95|dev| {:.4} ac1 {:.2} ac2 {:.2} ac5 {:.2} ac20 {:.2}",
        var.sqrt(),
        a[(a.len() * 95) / 100],
        ac(1),
        ac(2),
        ac(5),
        ac(20)
    );
}
fn main() {
    let mut sc = scenarios::gnss_city_walk();
    if let Ok(seed) = std::env::var("SEED") {
        sc.seed = seed.parse().unwrap();
    }
    let sim = sc.generate();
    let r = replay(PipelineConfig::default(), &sim.records).unwrap();
    let tr = r.pipeline.track();
    let truth = &sim.truth.steps;
    println!("steps {} truth {}", tr.len(), truth.len());
    let mut le = vec![];
    let mut he = vec![];
    for s in tr {
        let Some(h) = s.heading_rad else { continue };
        let i = truth.partition_point(|x| x.t < s.t);
        let j = if i > 0 && (i == truth.len() || (s.t - truth[i - 1].t) < (truth[i].t - s.t)) {
            i - 1
        } else {
            i
        };
        let t = &truth[j];
        le.push(s.length_m / 1.1 / t.length_m - 1.0);
        let mut d = h - t.heading_rad;
        while d > std::f64::consts::PI {
            d -= 2.0 * std::f64::consts::PI;
        }
        while d < -std::f64::consts::PI {
            d += 2.0 * std::f64::consts::PI;
        }
        he.push(d.to_degrees());
    }
    stats("length rel", &le);
    stats("heading deg", &he);
}
