//! How well can the PDR track's shape be placed on real walks? For each IPIN 2023 log, the PDR
//! track is moved by a rigid transform (rotation and translation, optionally a scale) fitted
//! (a) to the truth landmarks — the bound no fusion can beat with this shape — and (b) to the
//! fixes alone, by iteratively reweighted least squares (Cauchy weights), as an offline fit
//! would. Printed: the median of the per-log p75 errors at the landmarks.
//!
//! `cargo run --release --example fit_bound`; with `WALKING=1` only the fixes taken while the
//! PDR steps count, `LAG=s` compares each fix with the PDR position that many seconds earlier
//! (a receiver that reports late), `C=m` sets the robust loss's scale in metres (default: twice
//! each fix's σ).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::geo::LocalFrame;
use pdr::engine::pipeline::position_at;
use pdr::engine::{replay, PipelineConfig};
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn percentile(v: &[f64], q: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    pdr::eval::percentile(&s, q)
}

/// Weighted similarity (or rigid) fit of points `a` onto `b`: (scale, cos, sin, tx, ty).
fn fit(a: &[(f64, f64)], b: &[(f64, f64)], w: &[f64], scaled: bool) -> (f64, f64, f64, f64, f64) {
    let sw: f64 = w.iter().sum();
    let ca = a
        .iter()
        .zip(w)
        .fold((0.0, 0.0), |s, (p, w)| (s.0 + w * p.0, s.1 + w * p.1));
    let cb = b
        .iter()
        .zip(w)
        .fold((0.0, 0.0), |s, (p, w)| (s.0 + w * p.0, s.1 + w * p.1));
    let (ca, cb) = ((ca.0 / sw, ca.1 / sw), (cb.0 / sw, cb.1 / sw));
    let (mut dot, mut cross, mut aa) = (0.0, 0.0, 0.0);
    for ((p, q), w) in a.iter().zip(b).zip(w) {
        let (px, py) = (p.0 - ca.0, p.1 - ca.1);
        let (qx, qy) = (q.0 - cb.0, q.1 - cb.1);
        dot += w * (px * qx + py * qy);
        cross += w * (px * qy - py * qx);
        aa += w * (px * px + py * py);
    }
    let th = cross.atan2(dot);
    let (s, c) = th.sin_cos();
    let k = if scaled && aa > 0.0 {
        let k = (dot * c + cross * s) / aa;
        if std::env::var("UNCLAMPED").is_ok() {
            k
        } else {
            k.clamp(0.8, 1.25)
        }
    } else {
        1.0
    };
    let tx = cb.0 - k * (c * ca.0 - s * ca.1);
    let ty = cb.1 - k * (s * ca.0 + c * ca.1);
    (k, c, s, tx, ty)
}

fn apply(t: (f64, f64, f64, f64, f64), p: (f64, f64)) -> (f64, f64) {
    let (k, c, s, tx, ty) = t;
    (k * (c * p.0 - s * p.1) + tx, k * (s * p.0 + c * p.1) + ty)
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ipin2023");
    let Ok(mut set) = DirSet::new(&root) else {
        println!("skipped: {} not found", root.display());
        return;
    };
    let mut rows: Vec<[f64; 4]> = Vec::new();
    for log in import_all(&mut set).into_iter().flatten() {
        let wps: Vec<_> = log.geodetic_waypoints().collect();
        let fixes: Vec<_> = log
            .fixes()
            .filter(|f| f.h_accuracy_m <= 50.0)
            .copied()
            .collect();
        let Some(w0) = wps.first() else { continue };
        let (lat0, lon0) = w0.geo.unwrap_or_default();
        let frame = LocalFrame::new(lat0, lon0, 0.0);
        let run = replay(PipelineConfig::default(), &log.records).unwrap();
        let track = run.pipeline.track();
        if track.is_empty() || fixes.len() < 5 {
            continue;
        }
        let truth: Vec<(f64, f64)> = wps
            .iter()
            .map(|w| {
                let (la, lo) = w.geo.unwrap_or_default();
                let [e, n, _] = frame.to_enu(la, lo, 0.0);
                (e, n)
            })
            .collect();
        let pdr_at_wps: Vec<(f64, f64)> = wps.iter().map(|w| position_at(track, w.t)).collect();
        let errors = |t: (f64, f64, f64, f64, f64)| -> f64 {
            let e: Vec<f64> = pdr_at_wps
                .iter()
                .zip(&truth)
                .map(|(p, q)| {
                    let a = apply(t, *p);
                    (a.0 - q.0).hypot(a.1 - q.1)
                })
                .collect();
            percentile(&e, 75.0)
        };
        let ones = vec![1.0; truth.len()];
        let oracle_rigid = errors(fit(&pdr_at_wps, &truth, &ones, false));
        let oracle_fit = fit(&pdr_at_wps, &truth, &ones, true);
        let oracle_scaled = errors(oracle_fit);
        // Fit to the fixes (from the first step on), robustly.
        let t_first = track[0].t;
        // (PDR position, fix position, fix σ) of each fix.
        type Pair = ((f64, f64), (f64, f64), f64);
        let pts: Vec<Pair> = fixes
            .iter()
            .filter(|f| f.t >= t_first - 2.0)
            .map(|f| {
                let [e, n, _] = frame.to_enu(f.lat_deg, f.lon_deg, 0.0);
                let sigma = f.h_accuracy_m / 1.51;
                (position_at(track, f.t), (e, n), sigma)
            })
            .collect();
        let a: Vec<_> = pts.iter().map(|p| p.0).collect();
        let b: Vec<_> = pts.iter().map(|p| p.1).collect();
        let mut fitted = [(1.0, 1.0, 0.0, 0.0, 0.0); 2];
        for (k, scaled) in [false, true].into_iter().enumerate() {
            let mut w: Vec<f64> = pts.iter().map(|p| 1.0 / (p.2 * p.2)).collect();
            let mut t = fit(&a, &b, &w, scaled);
            for _ in 0..20 {
                for (i, p) in pts.iter().enumerate() {
                    let q = apply(t, p.0);
                    let r = (q.0 - p.1 .0).hypot(q.1 - p.1 .1) / p.2;
                    w[i] = 1.0 / (p.2 * p.2) / (1.0 + (r / 2.0).powi(2));
                }
                t = fit(&a, &b, &w, scaled);
            }
            fitted[k] = t;
        }
        let name = log
            .source
            .rsplit('/')
            .next()
            .unwrap_or(&log.source)
            .to_string();
        let row = [
            oracle_rigid,
            oracle_scaled,
            errors(fitted[0]),
            errors(fitted[1]),
        ];
        println!(
            "{name:<44} truth fit: rigid {:>5.1} scaled {:>5.1} | fix fit: rigid {:>5.1} scaled {:>5.1} (scale {:.2}) truth: scale {:.2} rotation {:+.1}°",
            row[0], row[1], row[2], row[3], fitted[1].0, oracle_fit.0, oracle_fit.2.atan2(oracle_fit.1).to_degrees()
        );
        rows.push(row);
    }
    let med = |k: usize| percentile(&rows.iter().map(|r| r[k]).collect::<Vec<_>>(), 50.0);
    println!(
        "\nmedian of per-log p75: truth fit rigid {:.2} m, scaled {:.2} m; fix fit rigid {:.2} m, scaled {:.2} m",
        med(0),
        med(1),
        med(2),
        med(3)
    );
}
