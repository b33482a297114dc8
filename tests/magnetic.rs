//! The magnetic guard (`engine::magnetic`) on real walks: where the field is bent, the
//! yaw follows the gyroscope. Skips with a message when `../shared/data` is absent.
#![allow(clippy::disallowed_methods)] // test scoring, not the track path

mod common;

use pdr::engine::{replay, PipelineConfig};
use pdr::eval::{evaluate, summarise, Summary};
use pdr::io::import::Log;

fn summary(logs: &[Log], guard: bool) -> Summary {
    let mut cfg = PipelineConfig::default();
    cfg.magnetic.enabled = guard;
    let results: Vec<_> = logs.iter().map(|l| evaluate(l, &l.dated(&cfg))).collect();
    summarise(&results)
}

#[test]
fn microsoft_indoor_walks_are_better_on_the_gyroscope_where_the_field_is_bent() {
    let Some(logs) = common::ipin::shared_logs("ms-indoor") else {
        return;
    };
    let (with, without) = (summary(&logs, true), summary(&logs, false));
    let (w, wo) = (
        with.waypoint_p75_m.unwrap(),
        without.waypoint_p75_m.unwrap(),
    );
    // Measured: 5.61 m against 5.87 m.
    assert!(w <= 5.7 && w < wo - 0.15, "{w:.2} m against {wo:.2} m");
    // Indoors the field is bent most of the time, and the steps say so.
    let log = &logs[0];
    let run = replay(log.dated(&PipelineConfig::default()), &log.records).unwrap();
    let held = run
        .pipeline
        .track()
        .iter()
        .filter(|s| s.gyro_heading)
        .count();
    assert!(held * 2 > run.pipeline.track().len(), "{held} steps held");
    let d = run.pipeline.magnetic_diagnostics();
    assert!(
        d.reference.is_some() && d.disturbed_s > 0.5 * d.tested_s,
        "{d:?}"
    );
}

#[test]
fn ipin_flat_routes_meet_four_metres_and_the_fusion_keeps_the_magnetometer() {
    let Some(logs) = common::ipin::ipin_logs() else {
        return;
    };
    let flat: Vec<Log> = logs
        .into_iter()
        .filter(|l| !l.source.contains("Trial51"))
        .collect();
    let (with, without) = (summary(&flat, true), summary(&flat, false));
    let (w, wo) = (
        with.waypoint_p75_m.unwrap(),
        without.waypoint_p75_m.unwrap(),
    );
    // Measured: 3.44 m against 4.37 m (the target: 4.0 m).
    assert!(w <= 3.55 && w < 0.85 * wo, "{w:.2} m against {wo:.2} m");
    // The fusion is given the heading the magnetometer's yaw gives: its figures do not move.
    for (a, b) in [
        (with.fused_p75_m, without.fused_p75_m),
        (with.smoothed_p75_m, without.smoothed_p75_m),
    ] {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!((a - b).abs() < 0.01, "{a:.3} m against {b:.3} m");
    }
}
