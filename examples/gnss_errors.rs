//! What real phone GNSS errors look like, from the IPIN 2023 logs (the phone's own fixes against
//! the surveyed landmarks): the error's size against the reported accuracy (how many σ an
//! "accuracy" is), and how long an error persists (its autocorrelation over time). The fusion's
//! GNSS error model takes its constants from these figures.
//!
//! For every landmark, the fix error is the fix position interpolated at the landmark's time
//! minus the landmark (the fixes on both sides at most 3 s away), in the tangent plane of the
//! log's first landmark. The autocorrelation pairs the errors of one log at two landmarks,
//! binned by their time apart.
//!
//! `cargo run --release --example gnss_errors [PATH]` (default `../shared/data/ipin2023`).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::geo::LocalFrame;
use pdr::io::import::{import_all, DirSet};
use std::path::PathBuf;

fn percentile(v: &[f64], q: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    pdr::eval::percentile(&s, q)
}

fn main() {
    let root = std::env::args().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ipin2023"),
        PathBuf::from,
    );
    let Ok(mut set) = DirSet::new(&root) else {
        println!("skipped: {} not found", root.display());
        return;
    };
    // Per log: (time, error east, error north, reported accuracy) at each landmark.
    type Errors = Vec<(f64, f64, f64, f64)>;
    let mut all: Vec<(String, Errors)> = Vec::new();
    for log in import_all(&mut set).into_iter().flatten() {
        let wps: Vec<_> = log.geodetic_waypoints().collect();
        let fixes: Vec<_> = log.fixes().copied().collect();
        let (Some(w0), false) = (wps.first(), fixes.is_empty()) else {
            continue;
        };
        let (lat0, lon0) = w0.geo.unwrap_or_default();
        let frame = LocalFrame::new(lat0, lon0, 0.0);
        let mut errs = Vec::new();
        for w in &wps {
            let (lat, lon) = w.geo.unwrap_or_default();
            let [te, tn, _] = frame.to_enu(lat, lon, 0.0);
            let i = fixes.partition_point(|f| f.t <= w.t);
            let (Some(a), Some(b)) = (i.checked_sub(1).map(|k| fixes[k]), fixes.get(i)) else {
                continue;
            };
            if w.t - a.t > 3.0 || b.t - w.t > 3.0 {
                continue;
            }
            let k = if b.t > a.t {
                (w.t - a.t) / (b.t - a.t)
            } else {
                0.0
            };
            let [ae, an, _] = frame.to_enu(a.lat_deg, a.lon_deg, 0.0);
            let [be, bn, _] = frame.to_enu(b.lat_deg, b.lon_deg, 0.0);
            let (fe, fn_) = (ae + k * (be - ae), an + k * (bn - an));
            let acc = a.h_accuracy_m + k * (b.h_accuracy_m - a.h_accuracy_m);
            errs.push((w.t, fe - te, fn_ - tn, acc));
        }
        let name = log
            .source
            .rsplit('/')
            .next()
            .unwrap_or(&log.source)
            .to_string();
        if let Some((lt, lg, lp)) = baselines(&log) {
            println!(
                "{name:<44} between landmarks: truth {lt:>6.1} m, fixes {:.2} ×, PDR {:.2} ×",
                lg / lt,
                lp / lt
            );
        }
        all.push((name, errs));
    }
    println!(
        "{:<44} {:>4} {:>7} {:>7} {:>9} {:>9}",
        "log", "n", "p75 m", "acc m", "|e|/acc≤1", "p68 e/acc"
    );
    let mut ratios = Vec::new();
    for (name, e) in &all {
        let mag: Vec<f64> = e.iter().map(|x| libm::hypot(x.1, x.2)).collect();
        let r: Vec<f64> = e
            .iter()
            .map(|x| libm::hypot(x.1, x.2) / x.3.max(1.0))
            .collect();
        if e.is_empty() {
            continue;
        }
        ratios.extend(&r);
        println!(
            "{name:<44} {:>4} {:>7.1} {:>7.1} {:>8.0} % {:>9.2}",
            e.len(),
            percentile(&mag, 75.0),
            percentile(&e.iter().map(|x| x.3).collect::<Vec<_>>(), 50.0),
            100.0 * r.iter().filter(|&&x| x <= 1.0).count() as f64 / r.len() as f64,
            percentile(&r, 68.0)
        );
    }
    println!(
        "\nall landmarks: {} errors; |error| within the reported accuracy for {:.0} %; the 68th \
         percentile of |error| / accuracy is {:.2} (1.00 if accuracy were the 68 % radius)",
        ratios.len(),
        100.0 * ratios.iter().filter(|&&x| x <= 1.0).count() as f64 / ratios.len().max(1) as f64,
        percentile(&ratios, 68.0)
    );
    // Autocorrelation of the error components, normalised per log, binned by the time apart.
    let bins = [0.5, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0, 120.0, 180.0];
    let mut sums = vec![(0.0, 0.0, 0usize); bins.len()];
    for (_, e) in &all {
        if e.len() < 3 {
            continue;
        }
        let n = e.len() as f64;
        let (me, mn) = (
            e.iter().map(|x| x.1).sum::<f64>() / n,
            e.iter().map(|x| x.2).sum::<f64>() / n,
        );
        // Normalised by the log's error spread about zero (a constant offset is correlated).
        let var = e.iter().map(|x| x.1 * x.1 + x.2 * x.2).sum::<f64>() / n;
        let _ = (me, mn);
        for i in 0..e.len() {
            for j in i + 1..e.len() {
                let dt = (e[j].0 - e[i].0).abs();
                let Some(b) = bins.windows(2).position(|w| dt >= w[0] && dt < w[1]) else {
                    continue;
                };
                let prod = (e[i].1 * e[j].1 + e[i].2 * e[j].2) / var;
                sums[b].0 += prod;
                sums[b].2 += 1;
            }
        }
    }
    println!("\nerror autocorrelation (errors about zero, per-log normalised), by time apart:");
    for (k, w) in bins.windows(2).enumerate() {
        let (s, _, n) = sums[k];
        if n > 0 {
            println!(
                "  {:>5.0}–{:<5.0} s: {:>5.2}  ({n} pairs)",
                w[0],
                w[1],
                s / n as f64
            );
        }
    }
}

/// Displacement between consecutive landmarks, summed over a log: truth, fixes (interpolated at
/// the landmarks' times) and the PDR track (its position at those times): how far each says
/// the walker went between the landmarks.
pub fn baselines(log: &pdr::io::import::Log) -> Option<(f64, f64, f64)> {
    let wps: Vec<_> = log.geodetic_waypoints().collect();
    let fixes: Vec<_> = log.fixes().copied().collect();
    let (lat0, lon0) = wps.first()?.geo?;
    let frame = LocalFrame::new(lat0, lon0, 0.0);
    let run = pdr::engine::replay(pdr::engine::PipelineConfig::default(), &log.records).ok()?;
    let track = run.pipeline.track();
    let fix_at = |t: f64| -> Option<(f64, f64)> {
        let i = fixes.partition_point(|f| f.t <= t);
        let (a, b) = (fixes.get(i.checked_sub(1)?)?, fixes.get(i)?);
        if t - a.t > 3.0 || b.t - t > 3.0 {
            return None;
        }
        let k = if b.t > a.t {
            (t - a.t) / (b.t - a.t)
        } else {
            0.0
        };
        let [ae, an, _] = frame.to_enu(a.lat_deg, a.lon_deg, 0.0);
        let [be, bn, _] = frame.to_enu(b.lat_deg, b.lon_deg, 0.0);
        Some((ae + k * (be - ae), an + k * (bn - an)))
    };
    let (mut lt, mut lg, mut lp) = (0.0, 0.0, 0.0);
    for w in wps.windows(2) {
        let (Some(g0), Some(g1)) = (fix_at(w[0].t), fix_at(w[1].t)) else {
            continue;
        };
        let [t0e, t0n, _] = frame.to_enu(w[0].geo?.0, w[0].geo?.1, 0.0);
        let [t1e, t1n, _] = frame.to_enu(w[1].geo?.0, w[1].geo?.1, 0.0);
        let p0 = pdr::engine::pipeline::position_at(track, w[0].t);
        let p1 = pdr::engine::pipeline::position_at(track, w[1].t);
        lt += libm::hypot(t1e - t0e, t1n - t0n);
        lg += libm::hypot(g1.0 - g0.0, g1.1 - g0.1);
        lp += libm::hypot(p1.0 - p0.0, p1.1 - p0.1);
    }
    Some((lt, lg, lp))
}
