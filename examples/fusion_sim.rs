//! GNSS/PDR fusion on the simulated city walk (`sim::scenarios::gnss_city_walk`): p75 errors of
//! GNSS alone, PDR alone, the filter and the smoother against the true path; the scale and
//! heading correction found; energy saving; NEES.
//!
//! `cargo run --release --example fusion_sim [-- KEY=VALUE…]` (overrides as `pdr eval --set`).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use pdr::engine::fusion::FusedStep;
use pdr::engine::replay;
use pdr::sim::scenarios;

fn p75(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    pdr::eval::percentile(&v, 75.0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cfg = pdr::settings::Settings::new()
        .with_args(&args)
        .and_then(|s| s.config())
        .unwrap();
    let mut sc = if std::env::var("REAL").is_ok() {
        scenarios::gnss_city_walk_real()
    } else {
        scenarios::gnss_city_walk()
    };
    if let Ok(seed) = std::env::var("SEED") {
        sc.seed = seed.parse().unwrap();
    }
    // ORACLE=1: a bound. The walker's step length is the engine's own line and the OS heading
    // has no bias, and the filter is told so (scale 1 and correction 0, known to 0.01 % and
    // 0.01°, fixed): only the per-step noise and the fixes remain.
    let mut cfg = cfg;
    if std::env::var("ORACLE").is_ok() {
        sc.walker = pdr::sim::Walker::default();
        sc.sensors.os_yaw_bias_deg = 0.0;
        let f = &mut cfg.fusion;
        f.scale0_sd = 1e-4;
        f.bias0_sd_deg = 0.01;
        f.scale_rw = 1e-9;
        f.bias_rw_deg = 1e-9;
    }
    let sim = sc.generate();
    let r = replay(cfg.clone(), &sim.records).unwrap();
    let p = &r.pipeline;
    let frame = *p.frame().unwrap();
    let sim_frame = sim.truth.frame.unwrap();
    // Truth in the pipeline's frame.
    let truth_at = |t: f64| {
        let (e, n) = sim.truth.position_at(t);
        let (lat, lon, h) = sim_frame.to_geodetic([e, n, 0.0]);
        let [e, n, _] = frame.to_enu(lat, lon, h);
        (e, n)
    };
    let err = |s: &[FusedStep]| -> Vec<f64> {
        s.iter()
            .map(|x| {
                let (e, n) = truth_at(x.t);
                (x.east_m - e).hypot(x.north_m - n)
            })
            .collect()
    };
    let gnss: Vec<f64> = p
        .fixes()
        .iter()
        .map(|f| {
            let (e, n) = frame.en_of_fix(f);
            let (te, tn) = truth_at(f.t);
            (e - te).hypot(n - tn)
        })
        .collect();
    let fused = p.fused();
    let smoothed = p.smoothed();
    // PDR alone, anchored at the start like the fused track's frame (first fix ≈ start).
    let pdr: Vec<f64> = p
        .track()
        .iter()
        .map(|s| {
            let (te, tn) = sim.truth.position_at(s.t);
            (s.east_m - te).hypot(s.north_m - tn)
        })
        .collect();
    let last = fused.last().unwrap();
    // NEES of the position at every fused step.
    let nees: Vec<f64> = fused
        .iter()
        .map(|x| {
            let (e, n) = truth_at(x.t);
            let (de, dn) = (x.east_m - e, x.north_m - n);
            let [a, b, c] = x.cov;
            let det = a * c - b * b;
            (c * de * de - 2.0 * b * de * dn + a * dn * dn) / det
        })
        .collect();
    if std::env::var("V").is_ok() {
        for (x, e) in fused.iter().zip(err(fused)) {
            if x.fix.is_some() || e > 10.0 || std::env::var("ALL").is_ok() {
                println!(
                    "  t {:7.1} err {:6.1} fix {:?} nu {:?} sd {:.1} scale {:.3}±{:.3} bias {:.1}±{:.1}",
                    x.t - sim.truth.steps[0].t,
                    e,
                    x.fix,
                    x.innovation.map(|n| (n[0].hypot(n[1]) * 10.0).round() / 10.0),
                    (x.cov[0] + x.cov[2]).sqrt(),
                    x.scale,
                    x.scale_bias_sd[0],
                    x.bias_rad.to_degrees(),
                    x.scale_bias_sd[1].to_degrees()
                );
            }
        }
    }
    if std::env::var("START").is_ok() {
        for ((f, sm), (ef, es)) in fused
            .iter()
            .zip(&smoothed)
            .zip(err(fused).into_iter().zip(err(&smoothed)))
            .take(25)
        {
            println!(
                "  {:.1} fused {:.1} smoothed {:.1} fix {:?} sd {:.1}/{:.1}",
                f.t - fused[0].t,
                ef,
                es,
                f.fix,
                f.cov[0].sqrt(),
                sm.cov[0].sqrt()
            );
        }
    }
    let over = nees.iter().filter(|&&v| v > 5.991).count();
    let lo = nees.iter().filter(|&&v| v < 0.0506).count();
    let hi = nees.iter().filter(|&&v| v > 7.378).count();
    println!(
        "NEES two-sided 95 % interval [0.0506, 7.378]: {:.1} % below, {:.1} % above",
        100.0 * lo as f64 / nees.len() as f64,
        100.0 * hi as f64 / nees.len() as f64
    );
    let d = p.diagnostics();
    println!(
        "steps {} (truth {}), fixes {}; counts {:?}; declination {:?}° {:?}; GNSS on {:?}",
        p.track().len(),
        sim.truth.steps.len(),
        p.fixes().len(),
        d.fix_counts,
        d.declination_deg,
        d.declination_note,
        d.gnss_on_s
    );
    println!(
        "p75 error: GNSS {:.2} m, PDR {:.2} m, fused {:.2} m, smoothed {:.2} m; max fused {:.1} m",
        p75(gnss),
        p75(pdr),
        p75(err(fused)),
        p75(err(&smoothed)),
        err(fused).iter().cloned().fold(0.0, f64::max)
    );
    println!(
        "scale {:.4} (truth {:.4}), heading correction {:.2}° (truth -8.00°)",
        last.scale,
        1.0 / 1.1,
        last.bias_rad.to_degrees()
    );
    println!(
        "NEES mean {:.2} (2 expected), share over chi2(2, 95 %) {:.1} %",
        nees.iter().sum::<f64>() / nees.len() as f64,
        100.0 * over as f64 / nees.len() as f64
    );
}
