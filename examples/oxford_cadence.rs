//! Checks the autocorrelation cadence estimator (`engine::motion::Periodicity`) on the Oxford
//! Step Counter data set (CC BY 4.0): every second, the estimate against the true cadence over
//! the last 3 s, with σ_z and the score. Prints per trace the share of seconds estimated right
//! (±15 %), at half, at double, or not at all, and score/σ statistics.
//!
//! `cargo run --release --example oxford_cadence [trace-name-filter] [-v]`
use pdr::engine::motion::{MotionConfig, MotionDetector, Periodicity};
use pdr::engine::orientation::{Orientation, OrientationSource};
use pdr::engine::ImuSample;
use std::path::Path;

fn truth_steps(dir: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join("stepcounter.csv")).unwrap();
    let mut truth = Vec::new();
    let mut prev = (0, 0);
    for l in text.lines() {
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
    truth.sort_by(f64::total_cmp);
    truth
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let verbose = std::env::args().any(|a| a == "-v");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/oxford-steps");
    let Ok(rd) = std::fs::read_dir(&root) else {
        println!("skipped: {} not found", root.display());
        return;
    };
    let mut names: Vec<String> = rd
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(&filter))
        .collect();
    names.sort();
    for name in names {
        let dir = root.join(&name);
        let truth = truth_steps(&dir);
        let text = std::fs::read_to_string(dir.join("accelerometer.csv")).unwrap();
        let mut o = Orientation::new(OrientationSource::GRAVITY);
        let mut m = MotionDetector::new(MotionConfig::default());
        let mut p = Periodicity::new();
        let mut last_t: Option<f64> = None;
        let mut next = None;
        let (mut ok, mut half, mut dbl, mut none, mut other, mut n) = (0, 0, 0, 0, 0, 0);
        let (mut ssum, mut smin, mut sigsum) = (0.0, f64::INFINITY, 0.0);
        for l in text.lines() {
            let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
            if v.len() != 5 {
                continue;
            }
            let s = ImuSample::accel_only(v[0] * 1e-9, nalgebra::Vector3::new(v[2], v[3], v[4]));
            let dt = last_t.map_or(0.0, |l| s.t - l);
            last_t = Some(s.t);
            let up = o.push(&s, dt).unwrap().up;
            m.push(s.t, up);
            p.push(s.t, dt, up);
            let t1 = *next.get_or_insert(s.t + 4.0);
            if s.t >= t1 {
                next = Some(t1 + 1.0);
                let w: Vec<f64> = truth
                    .iter()
                    .copied()
                    .filter(|&x| x >= s.t - 3.0 && x <= s.t)
                    .collect();
                if w.len() < 4 {
                    continue;
                }
                let f_true = (w.len() - 1) as f64 / (w[w.len() - 1] - w[0]);
                let f = p.frequency();
                n += 1;
                ssum += p.score();
                smin = smin.min(p.score());
                sigsum += m.sigma();
                let r = f / f_true;
                let verdict = if f == 0.0 {
                    none += 1;
                    "none"
                } else if (r - 1.0).abs() < 0.15 {
                    ok += 1;
                    "ok"
                } else if (r - 0.5).abs() < 0.1 {
                    half += 1;
                    "half"
                } else if (r - 2.0).abs() < 0.3 {
                    dbl += 1;
                    "double"
                } else {
                    other += 1;
                    "other"
                };
                if verbose {
                    println!(
                        "  t {:6.1} true {f_true:.2} est {f:.2} score {:.2} half {:+.2} sigma {:.2} {verdict}",
                        s.t - truth[0],
                        p.score(),
                        p.half_lag_r(),
                        m.sigma()
                    );
                    if std::env::args().any(|a| a == "-r") {
                        let r = p.autocorrelation();
                        let txt: Vec<String> = r.iter().map(|x| format!("{:+.2}", x)).collect();
                        println!("    R {}", txt.join(" "));
                    }
                }
            }
        }
        println!(
            "{name:<36} n {n:>3} ok {ok:>3} half {half:>2} double {dbl:>2} other {other:>2} none {none:>2}  score mean {:.2} min {:.2}  sigma {:.2}",
            ssum / n as f64,
            smin,
            sigsum / n as f64
        );
    }
}
