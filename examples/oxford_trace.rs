//! Diagnostic trace of one Oxford recording: per 5 s window, true steps vs counted, σ, PLL frequency.
use pdr::engine::PipelineConfig;
use pdr::engine::{ImuSample, Pipeline, Record};
use std::path::Path;

fn main() {
    let name = std::env::args()
        .nth(1)
        .unwrap_or("Pixel_Jamie_Hard_FrontPocket_1".into());
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data/oxford-steps")
        .join(&name);
    let Ok(text) = std::fs::read_to_string(dir.join("accelerometer.csv")) else {
        println!("skipped: {} not found", dir.display());
        return;
    };
    let truth_text = std::fs::read_to_string(dir.join("stepcounter.csv")).unwrap();
    let mut truth = Vec::new();
    let mut prev = (0, 0);
    for l in truth_text.lines() {
        let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
        if v.len() < 3 {
            continue;
        }
        let cur = (v[1] as i32, v[2] as i32);
        if cur.0 == 1 && prev.0 == 0 {
            truth.push(v[0] * 1e-9);
        }
        if cur.1 == 1 && prev.1 == 0 {
            truth.push(v[0] * 1e-9);
        }
        prev = cur;
    }
    let mut p = Pipeline::new(PipelineConfig::default()).unwrap();
    let mut next = None;
    for l in text.lines() {
        let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
        if v.len() != 5 {
            continue;
        }
        let s = ImuSample::accel_only(v[0] * 1e-9, nalgebra::Vector3::new(v[2], v[3], v[4]));
        let _ = p.push(&Record::Imu(s));
        let t0 = *next.get_or_insert(s.t);
        if s.t >= t0 + 5.0 {
            let d = p.diagnostics();
            let tr = truth.iter().filter(|&&t| t >= t0 && t < s.t).count();
            let est = p.track().iter().filter(|x| x.t >= t0 && x.t < s.t).count();
            println!(
                "t={:7.1} truth {tr:>3} est {est:>3} sigma {:.2} f {:.2} lock {:?} {:?}",
                s.t - truth.first().copied().unwrap_or(0.0),
                d.sigma_z,
                d.pll_freq_hz.unwrap_or(0.0),
                d.pll_locked,
                d.motion
            );
            next = Some(s.t);
        }
    }
}
