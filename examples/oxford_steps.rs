//! Step-count accuracy on the Oxford Step Counter data set (CC BY 4.0), accelerometer only.
//! Reads `../shared/data/oxford-steps`; prints per-trace and mean absolute count errors for the
//! PLL and the peak detector. A first measurement: the evaluation bench (`pdr eval`) is the
//! import issue's work.
//!
//! `cargo run --release --example oxford_steps`

use pdr::engine::ImuSample;
use pdr::engine::{replay, PipelineConfig, Record, StepDetectorConfig};
use std::path::Path;

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/oxford-steps");
    let Ok(stats) = std::fs::read_to_string(dir.join("stats.csv")) else {
        println!(
            "skipped: {} not found (the shared data set is not beside this checkout)",
            dir.display()
        );
        return;
    };
    let mut rows = Vec::new();
    for line in stats
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        let (name, position, truth) = (f[0], f[3], f[6].parse::<f64>().expect("steps"));
        let text = std::fs::read_to_string(dir.join(name).join("accelerometer.csv"))
            .expect("accelerometer.csv");
        let records: Vec<Record> = text
            .lines()
            .filter_map(|l| {
                let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
                (v.len() == 5).then(|| {
                    Record::Imu(ImuSample::accel_only(
                        v[0] * 1e-9,
                        nalgebra::Vector3::new(v[2], v[3], v[4]),
                    ))
                })
            })
            .collect();
        let pll = replay(PipelineConfig::default(), &records).unwrap();
        let peak_cfg = PipelineConfig {
            detector: StepDetectorConfig::Peak(Default::default()),
            ..Default::default()
        };
        let peak = replay(peak_cfg, &records).unwrap();
        let (np, nk) = (
            pll.pipeline.track().len() as f64,
            peak.pipeline.track().len() as f64,
        );
        println!("{name:<36} {position:<12} truth {truth:>4}  PLL {np:>4} ({:+6.1} %)  peak {nk:>4} ({:+6.1} %)  refused {}", 100.0 * (np - truth) / truth, 100.0 * (nk - truth) / truth, pll.errors.len());
        rows.push((
            position.to_string(),
            (np - truth).abs() / truth,
            (nk - truth).abs() / truth,
        ));
    }
    let mean = |v: &[f64]| 100.0 * v.iter().sum::<f64>() / v.len() as f64;
    let all_p: Vec<f64> = rows.iter().map(|r| r.1).collect();
    let all_k: Vec<f64> = rows.iter().map(|r| r.2).collect();
    println!("mean absolute count error over {} traces: PLL {:.2} %, peak {:.2} % (baseline in data/README: 2.68 %)", rows.len(), mean(&all_p), mean(&all_k));
    let mut positions: Vec<String> = rows.iter().map(|r| r.0.clone()).collect();
    positions.sort();
    positions.dedup();
    for p in positions {
        let sel: Vec<&(String, f64, f64)> = rows.iter().filter(|r| r.0 == p).collect();
        let pe: Vec<f64> = sel.iter().map(|r| r.1).collect();
        let ke: Vec<f64> = sel.iter().map(|r| r.2).collect();
        println!(
            "  {p:<12} n={}  PLL {:.2} %  peak {:.2} %",
            sel.len(),
            mean(&pe),
            mean(&ke)
        );
    }
}
