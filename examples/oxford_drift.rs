//! Where the step count of one Oxford recording goes wrong (Oxford Step Counter DataSet,
//! CC BY 4.0): the counted steps are matched one to one with the truth device's foot contacts
//! (after removing their median time offset), and every unmatched contact (missed step) and
//! unmatched count (extra step) is printed with the engine's state at that time.
//!
//! `cargo run --release --example oxford_drift -- TRACE [--set KEY=VALUE…]`
use pdr::engine::{Pipeline, Record};
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args
        .first()
        .cloned()
        .unwrap_or("Pixel_Jamie_Hard_FrontPocket_1".into());
    let sets: Vec<String> = args
        .windows(2)
        .filter(|w| w[0] == "--set")
        .map(|w| w[1].clone())
        .collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data/oxford-steps")
        .join(&name);
    let Ok(mut set) = DirSet::new(&dir) else {
        println!("skipped: {} not found", dir.display());
        return;
    };
    let log = import_all(&mut set).into_iter().next().unwrap().unwrap();
    let cfg = pdr::settings::Settings::new()
        .with_args(&sets)
        .and_then(|s| s.config())
        .unwrap();
    let mut p = Pipeline::new(cfg).unwrap();
    let mut states = Vec::new();
    let mut next = 0.0;
    for r in &log.records {
        if let Record::Imu(s) = r {
            let _ = p.push(r);
            if s.t >= next {
                next = s.t + 0.1;
                states.push((s.t, p.diagnostics()));
            }
        }
    }
    let est: Vec<f64> = p.track().iter().map(|s| s.t).collect();
    let truth: Vec<f64> = log.truth.step_events.iter().map(|s| s.t).collect();
    // Median offset estimate − truth over nearest pairs.
    let mut offs: Vec<f64> = est
        .iter()
        .filter_map(|&e| {
            truth
                .iter()
                .map(|&t| e - t)
                .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        })
        .collect();
    offs.sort_by(f64::total_cmp);
    let off = offs.get(offs.len() / 2).copied().unwrap_or(0.0);
    let mut used = vec![false; est.len()];
    let mut missed = Vec::new();
    for (i, &t) in truth.iter().enumerate() {
        let period = if i + 1 < truth.len() {
            truth[i + 1] - t
        } else {
            0.5
        }
        .clamp(0.25, 1.0);
        let best = est
            .iter()
            .enumerate()
            .filter(|(j, &e)| !used[*j] && (e - off - t).abs() < 0.5 * period)
            .min_by(|a, b| (a.1 - off - t).abs().total_cmp(&(b.1 - off - t).abs()));
        match best {
            Some((j, _)) => used[j] = true,
            None => missed.push(t),
        }
    }
    let extra: Vec<f64> = est
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|(e, _)| *e)
        .collect();
    let t0 = truth.first().copied().unwrap_or(0.0);
    let state = |t: f64| {
        let i = states.partition_point(|s| s.0 <= t).saturating_sub(1);
        let d = &states[i].1;
        format!(
            "{:?} σ {:.2} cad {} pll {:.2} lock {}",
            d.motion.unwrap(),
            d.sigma_z,
            d.cadence_hz.map_or("-".into(), |c| format!("{c:.2}")),
            d.pll_freq_hz.unwrap_or(0.0),
            d.pll_locked.unwrap_or(false)
        )
    };
    let mut ev: Vec<(f64, &str)> = missed
        .iter()
        .map(|&t| (t, "MISS "))
        .chain(extra.iter().map(|&t| (t - off, "EXTRA")))
        .collect();
    ev.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (t, k) in &ev {
        println!("{:7.2} {k} {}", t - t0, state(*t + off));
    }
    println!(
        "{name}: truth {} counted {} offset {:+.3} s; missed {} extra {}",
        truth.len(),
        est.len(),
        off,
        missed.len(),
        extra.len()
    );
}
