//! Could a walk's own signals set its step-length scale? Tried: a step length that
//! adapts from the log alone (Weinberg's amplitude blended with the frequency line). For the
//! Microsoft walks and IPIN routes 01–25 this scores, by pooled waypoint p75 (PDR only), each
//! walk's frequency line scaled by
//! `s = s̄ + g_w·(w̄/w_ref − 1) + g_f·(f̄/f_ref − 1)`:
//! w̄ the walk's mean Weinberg amplitude (a_max − a_min)^¼ between its first and last waypoint,
//! f̄ its mean cadence, and s̄, g_w, g_f least squares on the *other* walks' true scales
//! (leave-one-walk-out), then fitted on one set and scored on the other. The table in
//! docs/experiments.md ("A step length that adapts: tried, not adopted") is this output.
//!
//! `cargo run --release --example step_scale_loo`
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::{replay, PipelineConfig, StepLengthModel};
use pdr::io::import::{import_all, DirSet, Log};
use std::path::Path;

fn p75(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    pdr::eval::percentile(&v, 75.0)
}

/// One walk: mean cadence, mean Weinberg amplitude, true scale, default waypoint errors.
struct Walk {
    f: f64,
    w: f64,
    s: f64,
    errors: Vec<f64>,
}

fn walks(logs: &[Log]) -> Vec<Walk> {
    let base = PipelineConfig::default();
    let weinberg = PipelineConfig {
        step_length: StepLengthModel::Weinberg { k: 1.0 },
        ..base.clone()
    };
    logs.iter()
        .map(|log| {
            let wp = &log.truth.waypoints;
            let (t0, t1) = (wp[0].t, wp[wp.len() - 1].t);
            let inside = |t: f64| t > t0 && t <= t1;
            let truth: f64 = wp
                .windows(2)
                .map(|p| (p[1].x_m - p[0].x_m).hypot(p[1].y_m - p[0].y_m))
                .sum();
            let cfg = log.dated(&base);
            let run = replay(cfg.clone(), &log.records).unwrap();
            let steps: Vec<_> = run
                .pipeline
                .track()
                .iter()
                .filter(|s| inside(s.t))
                .collect();
            let n = steps.len().max(1) as f64;
            let est: f64 = steps.iter().map(|s| s.length_m).sum();
            let w_run = replay(log.dated(&weinberg), &log.records).unwrap();
            let w: Vec<f64> = w_run
                .pipeline
                .track()
                .iter()
                .filter(|s| inside(s.t))
                .map(|s| s.length_m)
                .collect();
            Walk {
                f: steps.iter().map(|s| s.freq_hz).sum::<f64>() / n,
                w: w.iter().sum::<f64>() / w.len().max(1) as f64,
                s: truth / est,
                errors: pdr::eval::evaluate(log, &cfg).waypoint_errors_m,
            }
        })
        .collect()
}

/// The waypoint errors of `log` with its walking line scaled by `s`.
fn scaled(log: &Log, s: f64) -> Vec<f64> {
    let mut cfg = PipelineConfig::default();
    if let StepLengthModel::Frequency(p) = &mut cfg.step_length {
        p.walking.a *= s;
        p.walking.b *= s;
    }
    pdr::eval::evaluate(log, &log.dated(&cfg)).waypoint_errors_m
}

/// The model fitted on `train`: (s̄, g_w, g_f, w_ref, f_ref), with and without the cadence.
struct Fit {
    mean: f64,
    gw: f64,
    gf: f64,
    w_ref: f64,
    f_ref: f64,
}

fn fit(train: &[&Walk], cadence: bool) -> Fit {
    let n = train.len() as f64;
    let w_ref = train.iter().map(|x| x.w).sum::<f64>() / n;
    let f_ref = train.iter().map(|x| x.f).sum::<f64>() / n;
    let mean = train.iter().map(|x| x.s).sum::<f64>() / n;
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for x in train {
        let (u, v, y) = (x.w / w_ref - 1.0, x.f / f_ref - 1.0, x.s - mean);
        a11 += u * u;
        a12 += u * v;
        a22 += v * v;
        b1 += u * y;
        b2 += v * y;
    }
    let (gw, gf) = if cadence {
        let det = a11 * a22 - a12 * a12;
        ((a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det)
    } else {
        (b1 / a11, 0.0)
    };
    Fit {
        mean,
        gw,
        gf,
        w_ref,
        f_ref,
    }
}

impl Fit {
    fn scale(&self, x: &Walk, w_ref: f64, f_ref: f64) -> f64 {
        self.mean + self.gw * (x.w / w_ref - 1.0) + self.gf * (x.f / f_ref - 1.0)
    }
}

fn load(name: &str) -> Option<Vec<Log>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(name);
    let mut set = DirSet::new(&root).ok()?;
    Some(
        import_all(&mut set)
            .into_iter()
            .flatten()
            .filter(|l| l.truth.waypoints.len() >= 2 && !l.source.contains("Trial51"))
            .collect(),
    )
}

fn main() {
    let (Some(ms), Some(ipin)) = (load("ms-indoor"), load("ipin2023")) else {
        println!("skipped: ../shared/data/ms-indoor or ipin2023 not found");
        return;
    };
    let sets = [
        ("Microsoft", walks(&ms), &ms),
        ("IPIN 01-25", walks(&ipin), &ipin),
    ];
    for (name, ws, logs) in &sets {
        let all: Vec<&Walk> = ws.iter().collect();
        let f = fit(&all, true);
        println!(
            "{name}: {} walks, in-sample g_w {:+.2} g_f {:+.2}, w_ref {:.3}, f_ref {:.2} Hz, mean true scale {:.3}",
            ws.len(),
            f.gw,
            f.gf,
            f.w_ref,
            f.f_ref,
            f.mean
        );
        let mut rows: [Vec<f64>; 5] = Default::default();
        for (i, (x, log)) in ws.iter().zip(logs.iter()).enumerate() {
            let others: Vec<&Walk> = ws
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, x)| x)
                .collect();
            let (fw, fwf) = (fit(&others, false), fit(&others, true));
            rows[0].extend(x.errors.iter().copied());
            rows[1].extend(scaled(log, x.s));
            rows[2].extend(scaled(log, fw.mean));
            rows[3].extend(scaled(log, fw.scale(x, fw.w_ref, fw.f_ref)));
            rows[4].extend(scaled(log, fwf.scale(x, fwf.w_ref, fwf.f_ref)));
        }
        let [d, o, m, w, wf] = rows.map(p75);
        println!("  pooled p75: default line {d:.2} m, perfect scale per walk {o:.2} m");
        println!("  leave-one-walk-out: constant {m:.2} m, + Weinberg {w:.2} m, + Weinberg + cadence {wf:.2} m");
    }
    for (a, b) in [(0, 1), (1, 0)] {
        let (train, (test_name, test, logs)) = (&sets[a].1, &sets[b]);
        let f = fit(&train.iter().collect::<Vec<_>>(), true);
        let n = test.len() as f64;
        let own = (
            test.iter().map(|x| x.w).sum::<f64>() / n,
            test.iter().map(|x| x.f).sum::<f64>() / n,
        );
        for (label, (w_ref, f_ref)) in [
            ("its own w_ref, f_ref", own),
            ("the fit's", (f.w_ref, f.f_ref)),
        ] {
            let e: Vec<f64> = test
                .iter()
                .zip(logs.iter())
                .flat_map(|(x, log)| scaled(log, f.scale(x, w_ref, f_ref)))
                .collect();
            println!(
                "{test_name} with the fit of {} ({label}): {:.2} m",
                sets[a].0,
                p75(e)
            );
        }
    }
}
