//! Ibarra 2015's zero-crossing detector and fuzzy step length on simulated walks: step counts
//! against the truth (beside the PLL and the peak counter) and the mean step-length error of the
//! fuzzy system, the population line and Weinberg.
//! `cargo run --release --example ibarra_sim`

use pdr::engine::fuzzy_step_length::FuzzyConfig;
use pdr::engine::{replay, PipelineConfig, StepDetectorConfig, StepLengthModel, StepRecord};
use pdr::sim::{scenarios, Simulation};

fn run(sim: &Simulation, cfg: PipelineConfig) -> Vec<StepRecord> {
    replay(cfg, &sim.records)
        .expect("valid config")
        .pipeline
        .track()
        .to_vec()
}

fn length_error_pct(sim: &Simulation, track: &[StepRecord]) -> f64 {
    let errs: Vec<f64> = track
        .iter()
        .skip(2)
        .filter_map(|s| {
            let t = sim
                .truth
                .steps
                .iter()
                .min_by(|a, b| (a.t - s.t).abs().total_cmp(&(b.t - s.t).abs()))?;
            Some(100.0 * (s.length_m - t.length_m).abs() / t.length_m)
        })
        .collect();
    errs.iter().sum::<f64>() / errs.len().max(1) as f64
}

fn main() {
    let detectors = [
        ("pll", StepDetectorConfig::default()),
        ("peak", StepDetectorConfig::Peak(Default::default())),
        (
            "zero_crossing",
            StepDetectorConfig::ZeroCrossing(Default::default()),
        ),
    ];
    let models = [
        ("frequency", StepLengthModel::default()),
        ("weinberg", StepLengthModel::Weinberg { k: 0.47 }),
        ("fuzzy", StepLengthModel::Fuzzy(FuzzyConfig::default())),
    ];
    println!("walk        truth  pll  peak  zc   | SL error %: frequency weinberg fuzzy");
    let mut walks: Vec<(String, Simulation)> = [1.5, 1.8, 2.0, 2.2]
        .iter()
        .map(|&f| {
            (
                format!("walk {f} Hz"),
                scenarios::straight_walk(f, 60.0).generate(),
            )
        })
        .collect();
    walks.extend([2.7, 3.1, 3.4, 4.2].iter().map(|&f| {
        (
            format!("run {f} Hz"),
            scenarios::straight_run(f, 35.0).generate(),
        )
    }));
    walks.push(("demo".into(), scenarios::demo_walk().generate()));
    for (name, sim) in &walks {
        let counts: Vec<usize> = detectors
            .iter()
            .map(|(_, d)| {
                run(
                    sim,
                    PipelineConfig {
                        detector: *d,
                        ..Default::default()
                    },
                )
                .len()
            })
            .collect();
        let errs: Vec<f64> = models
            .iter()
            .map(|(_, m)| {
                let cfg = PipelineConfig {
                    step_length: m.clone(),
                    ..Default::default()
                };
                length_error_pct(sim, &run(sim, cfg))
            })
            .collect();
        println!(
            "{name:<11} {:>5} {:>4} {:>5} {:>4} | {:>5.1} {:>5.1} {:>5.1}",
            sim.truth.steps.len(),
            counts[0],
            counts[1],
            counts[2],
            errs[0],
            errs[1],
            errs[2]
        );
    }
    // The scale: a 60 m calibration walk at 1.8 Hz by a walker with SL = 0.30·f + 0.20 m, then
    // a 120 m walk at 1.7 Hz by the same walker.
    let fuzzy = |k: f64| PipelineConfig {
        step_length: StepLengthModel::Fuzzy(FuzzyConfig { scale: k }),
        ..Default::default()
    };
    let cal = scenarios::calibration_walk(1.8, 60.0, 0.30, 0.20).generate();
    let lengths: Vec<f64> = run(&cal, fuzzy(1.0)).iter().map(|s| s.length_m).collect();
    let k = pdr::engine::calibration::fuzzy_scale(cal.truth.distance_m, &lengths, 1.0)
        .expect("a good walk");
    let test = scenarios::calibration_walk(1.7, 120.0, 0.30, 0.20).generate();
    let d = |k: f64| run(&test, fuzzy(k)).iter().map(|s| s.length_m).sum::<f64>();
    println!(
        "scale k = {k:.3}; 120 m walk ({:.1} m true): {:.1} m calibrated, {:.1} m with k = 1",
        test.truth.distance_m,
        d(k),
        d(1.0)
    );
}
