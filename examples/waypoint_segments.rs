//! Where a hand-held walk's waypoint error lies. Each walk is rebuilt from its
//! segments between waypoints, with one part of the truth put in at a time, and scored as
//! `pdr eval` scores the track: pooled waypoint p75, PDR only, the same rotation alignment
//! (`eval::waypoint_errors`). Then the bearings of the long segments are checked for drift.
//! docs/methods/carrying-mode.md quotes this output.
//!
//! The rows that put truth in are bounds, not methods: no estimator has the truth. A row can
//! also be lower than any estimator could reach, because the truth's own scatter (a waypoint
//! clicked a metre off, a walker who weaves between two waypoints) is copied into it.
//!
//! `cargo run --release --example waypoint_segments -- [SET] [KEY=VALUE ...]`: SET is a folder
//! of `../shared/data` (default `ms-indoor`; `ipin2023` scores routes 01–25, without route 51's
//! stairs), and the settings are `pdr eval --set`'s.
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::pipeline::position_at;
use pdr::engine::{replay, StepRecord};
use pdr::eval::{percentile, waypoint_errors};
use pdr::io::import::Waypoint;
use pdr::settings::Settings;

/// The tests' reader of `../shared/data`, which says when a clone has none.
#[path = "../tests/common/ipin.rs"]
#[allow(dead_code)]
mod shared;

/// Segments of 6 m or more: a waypoint a metre off turns them by under 10°.
const LONG_M: f64 = 6.0;
/// Spans for the drift check: consecutive waypoints at least this far apart.
const SPAN_M: f64 = 20.0;

type Xy = (f64, f64);

fn p75(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    percentile(&v, 75.0)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    percentile(&v, 50.0)
}

fn sd(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len().max(1) as f64;
    (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

fn len(v: Xy) -> f64 {
    v.0.hypot(v.1)
}

/// `v` with the length of `l`'s and its own direction.
fn with_length(v: Xy, l: f64) -> Xy {
    let k = l / len(v).max(1e-9);
    (v.0 * k, v.1 * k)
}

/// The waypoint errors of the chain of segment displacements `d` starting at the first
/// waypoint, scored by `eval::waypoint_errors` on a track with a point at each waypoint.
fn chain_errors(template: &StepRecord, wps: &[Waypoint], d: &[Xy]) -> Vec<f64> {
    let mut p = (0.0, 0.0);
    let mut track = vec![StepRecord {
        t: wps[0].t,
        east_m: 0.0,
        north_m: 0.0,
        ..*template
    }];
    for (w, x) in wps[1..].iter().zip(d) {
        p = (p.0 + x.0, p.1 + x.1);
        track.push(StepRecord {
            t: w.t,
            east_m: p.0,
            north_m: p.1,
            ..*template
        });
    }
    waypoint_errors(&track, wps)
        .map(|e| e.into_iter().map(|(m, _)| m).collect())
        .unwrap_or_default()
}

/// Compass bearing of `v` (east, north) in degrees.
fn bearing(v: Xy) -> f64 {
    v.0.atan2(v.1).to_degrees()
}

/// The difference `a − b` of two bearings in degrees, in (−180, 180].
fn diff_deg(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 {
        d - 360.0
    } else {
        d
    }
}

fn main() {
    let mut args = std::env::args().skip(1).peekable();
    let name = match args.peek() {
        Some(a) if !a.contains('=') => args.next().unwrap_or_default(),
        _ => "ms-indoor".to_string(),
    };
    let settings: Vec<String> = args.collect();
    let cfg = match Settings::new()
        .with_args(&settings)
        .and_then(|s| s.config())
    {
        Ok(c) => c,
        Err(e) => {
            eprintln!("waypoint_segments: {e}");
            std::process::exit(2);
        }
    };
    let Some(logs) = shared::shared_logs(&name) else {
        return;
    };
    let logs: Vec<_> = logs
        .into_iter()
        .filter(|l| l.truth.waypoints.len() >= 2 && !l.source.contains("Trial51"))
        .collect();
    let rows = [
        "as estimated (= pdr eval)",
        "each walk's perfect scale (truth)",
        "true bearing, estimated length",
        "true bearing + perfect scale",
        "true bearing on segments >= 6 m + perfect scale",
        "true length, estimated bearing",
    ];
    let mut pooled: Vec<Vec<f64>> = vec![Vec::new(); rows.len()];
    let (mut long_err, mut long_diff, mut span_err) = (Vec::new(), Vec::new(), Vec::new());
    let mut walks = 0;
    let mut scales = Vec::new();
    for log in &logs {
        let run = match replay(log.dated(&cfg), &log.records) {
            Ok(r) => r,
            Err(e) => {
                println!("{}: {e}", log.source);
                continue;
            }
        };
        let track = run.pipeline.track();
        let Some(template) = track.first() else {
            println!("{}: no step", log.source);
            continue;
        };
        walks += 1;
        let wps = &log.truth.waypoints;
        let pos: Vec<Xy> = wps.iter().map(|w| position_at(track, w.t)).collect();
        // The waypoints' plan coordinates, x then y, as the alignment reads them.
        let truth: Vec<Xy> = wps
            .windows(2)
            .map(|p| (p[1].x_m - p[0].x_m, p[1].y_m - p[0].y_m))
            .collect();
        // The estimate's segments turned into the plan frame by the rotation that scores the
        // walk, so that estimated and true segments can be mixed in one chain.
        let est: Vec<Xy> = pos
            .windows(2)
            .map(|p| (p[1].0 - p[0].0, p[1].1 - p[0].1))
            .collect();
        let (s, c) = alignment(&est, &truth).sin_cos();
        let d: Vec<Xy> = est
            .iter()
            .map(|x| (c * x.0 - s * x.1, s * x.0 + c * x.1))
            .collect();
        let k = truth.iter().map(|&t| len(t)).sum::<f64>()
            / d.iter().map(|&x| len(x)).sum::<f64>().max(1e-9);
        scales.push(k);
        let scaled = |x: Xy| (x.0 * k, x.1 * k);
        let true_bearing: Vec<Xy> = d
            .iter()
            .zip(&truth)
            .map(|(&e, &t)| with_length(t, len(e)))
            .collect();
        let chains: [Vec<Xy>; 6] = [
            d.clone(),
            d.iter().map(|&x| scaled(x)).collect(),
            true_bearing.clone(),
            true_bearing.iter().map(|&x| scaled(x)).collect(),
            d.iter()
                .zip(&truth)
                .map(|(&e, &t)| {
                    scaled(if len(t) >= LONG_M {
                        with_length(t, len(e))
                    } else {
                        e
                    })
                })
                .collect(),
            d.iter()
                .zip(&truth)
                .map(|(&e, &t)| with_length(e, len(t)))
                .collect(),
        ];
        for (row, chain) in pooled.iter_mut().zip(&chains) {
            row.extend(chain_errors(template, wps, chain));
        }
        let mut prev: Option<f64> = None;
        for (e, t) in d.iter().zip(&truth) {
            if len(*t) < LONG_M {
                continue;
            }
            let err = diff_deg(bearing(*e), bearing(*t));
            long_err.push(err);
            if let Some(p) = prev {
                long_diff.push(err - p);
            }
            prev = Some(err);
        }
        let mut i = 0;
        while let Some(j) = (i + 1..wps.len())
            .find(|&j| len((wps[j].x_m - wps[i].x_m, wps[j].y_m - wps[i].y_m)) >= SPAN_M)
        {
            let e = d[i..j]
                .iter()
                .fold((0.0, 0.0), |a, x| (a.0 + x.0, a.1 + x.1));
            let t = (wps[j].x_m - wps[i].x_m, wps[j].y_m - wps[i].y_m);
            span_err.push(diff_deg(bearing(e), bearing(t)).abs());
            i = j;
        }
    }
    println!(
        "{name}: {walks} walks, {} waypoints scored; settings {settings:?}",
        pooled[0].len()
    );
    println!("pooled waypoint p75 with each segment rebuilt from:");
    for (row, e) in rows.iter().zip(pooled) {
        println!("  {row:<50} {:5.2} m", p75(e));
    }
    scales.sort_by(f64::total_cmp);
    println!(
        "the walks' perfect scales (true path / estimated): {:.2}..{:.2}, median {:.2}, sd {:.3}",
        scales.first().copied().unwrap_or(f64::NAN),
        scales.last().copied().unwrap_or(f64::NAN),
        median(scales.clone()),
        sd(&scales)
    );
    let abs: Vec<f64> = long_err.iter().map(|e| e.abs()).collect();
    println!(
        "segments >= {LONG_M} m ({}): |bearing error| mean {:.1}°, p75 {:.1}°; sd {:.1}°, of two consecutive ones' difference {:.1}° (sqrt 2 x sd = {:.1}° if each were its own)",
        abs.len(),
        abs.iter().sum::<f64>() / abs.len().max(1) as f64,
        p75(abs.clone()),
        sd(&long_err),
        sd(&long_diff),
        std::f64::consts::SQRT_2 * sd(&long_err),
    );
    println!(
        "spans >= {SPAN_M} m ({}): |bearing error| median {:.1}°, p75 {:.1}°",
        span_err.len(),
        median(span_err.clone()),
        p75(span_err)
    );
}

/// The least-squares rotation (radians, counter-clockwise in the plan's x–y) of the estimate's
/// cumulative positions onto the truth's: `eval::waypoint_errors`'s alignment.
fn alignment(d: &[Xy], truth: &[Xy]) -> f64 {
    let (mut e, mut r) = ((0.0, 0.0), (0.0, 0.0));
    let (mut dot, mut cross) = (0.0, 0.0);
    for (x, t) in d.iter().zip(truth) {
        e = (e.0 + x.0, e.1 + x.1);
        r = (r.0 + t.0, r.1 + t.1);
        dot += e.0 * r.0 + e.1 * r.1;
        cross += e.0 * r.1 - e.1 * r.0;
    }
    cross.atan2(dot)
}
