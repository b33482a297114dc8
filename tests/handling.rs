//! Handling is not walking (`engine/handling.rs`): the IPIN 2023 walks open with the phone turned
//! over in the hand, which counted as 22–65 steps each before the walk began; no simulated gait
//! (walking, stairs, sitting down, running, in any of the 8 pocket poses) is taken for handling.
//! The IPIN part is skipped when `../shared` is absent.

mod common;

use pdr::engine::pipeline::Diagnostics;
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::pose::PocketPose;
use pdr::sim::scenarios;

fn diagnostics(
    records: &[pdr::engine::types::Record],
    cfg: PipelineConfig,
) -> (Diagnostics, Vec<f64>) {
    let r = replay(cfg, records).expect("valid config");
    let steps = r.pipeline.track().iter().map(|s| s.t).collect();
    (r.pipeline.diagnostics(), steps)
}

#[test]
fn no_simulated_gait_is_handling() {
    let mut walks = vec![
        ("demo", scenarios::demo_walk()),
        (
            "long (walking, turns, pauses, running)",
            scenarios::long_walk(10.0),
        ),
        ("straight run", scenarios::straight_run(2.8, 60.0)),
    ];
    for pose in PocketPose::ALL {
        walks.push(("stairs", scenarios::stairs_walk(pose)));
        walks.push(("pocket, mixed", scenarios::pocket_mixed(pose)));
    }
    for (name, sc) in walks {
        let sim = sc.generate();
        let (d, _) = diagnostics(&sim.records, PipelineConfig::default());
        assert_eq!(d.handling_s, 0.0, "{name}: {} s of handling", d.handling_s);
    }
}

#[test]
fn the_ipin_walks_start_after_their_handling() {
    let Some(logs) = common::ipin::ipin_logs() else {
        return;
    };
    let mut before = 0;
    for log in &logs {
        let first = log
            .truth
            .waypoints
            .first()
            .expect("IPIN logs have landmarks")
            .t;
        let (d, steps) = diagnostics(&log.records, log.dated(&PipelineConfig::default()));
        // Every log opens with 30–40 s of handling; the rule finds at least 10 s of it.
        assert!(
            d.handling_s >= 10.0,
            "{}: {} s of handling",
            log.source,
            d.handling_s
        );
        let n = steps.iter().filter(|&&t| t < first - 1.0).count();
        // The walker stands at the first landmark; 22–65 steps were counted before it.
        assert!(n <= 30, "{}: {n} steps before the walk", log.source);
        before += n;
    }
    // The timeline says so: the first log's opening shows the activity "handling".
    let mut p = pdr::engine::Pipeline::new(logs[0].dated(&PipelineConfig::default())).unwrap();
    let mut handled = 0;
    for r in &logs[0].records {
        if p.push(r).is_ok()
            && matches!(r, pdr::engine::types::Record::Imu(_))
            && p.diagnostics().activity == Some(pdr::engine::Activity::Handling)
        {
            handled += 1;
        }
    }
    assert!(handled > 500, "{handled} samples shown as handling");
    println!("steps counted before the first landmark: {before} over {} logs (925 before the handling detector)", logs.len());
    assert!(before <= 200, "{before} steps before the walks");
}

/// Seconds of handling inside the logs' counted windows.
fn handled_inside(logs: &[pdr::io::import::Log], cfg: &PipelineConfig) -> f64 {
    let mut inside = 0.0;
    for log in logs {
        let (a, b) = log.truth.step_window.expect("a counted window");
        let mut p = pdr::engine::Pipeline::new(log.dated(cfg)).unwrap();
        let mut last = None;
        for r in &log.records {
            let pdr::engine::types::Record::Imu(s) = r else {
                continue;
            };
            if p.push(r).is_ok() {
                let handled = p.diagnostics().activity == Some(pdr::engine::Activity::Handling);
                if handled && s.t > a && s.t < b {
                    inside += s.t - last.unwrap_or(s.t);
                }
                last = Some(s.t);
            }
        }
    }
    inside
}

/// A thigh in a trouser pocket at a brisk pace turns the phone fast and about more than one
/// axis, as handling does, but about an axis that stays put in the device: the real walks of
/// UbiComp 2013 are walks (skipped when `../shared` is absent).
#[test]
fn a_brisk_pocket_is_a_walk() {
    let Some(pockets) = common::ipin::shared_logs("ubicomp13-pocket") else {
        return;
    };
    let cfg = PipelineConfig::default();
    let mut without = cfg.clone();
    without.handling.axis_steady_min = 1.0;
    let (now, before) = (
        handled_inside(&pockets, &cfg),
        handled_inside(&pockets, &without),
    );
    println!(
        "UbiComp 2013: {now:.1} s of handling inside the counted walks ({before:.1} s without \
         the steadiness test)"
    );
    assert!(now < 0.25 * before, "{now} s against {before} s");
}
