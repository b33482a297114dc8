//! Live input: a simulated walk fed as the browser's `devicemotion` and `deviceorientation`
//! events, Android-style and iOS-style, through `LiveSession`, against the same walk replayed as
//! a log; and the session's recording replayed. Runs natively and in headless Chromium.

use pdr::engine::pipeline::{replay, PipelineConfig, Record};
use pdr::io::pdrlog;
use pdr::live::{orientation_angles, LiveSession, MotionEvent, Platform};
use pdr::sim::scenarios;
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// Feeds a simulation's samples as browser events of `platform`'s conventions.
fn feed(records: &[Record], platform: Platform) -> LiveSession {
    let mut live = LiveSession::new(PipelineConfig::default(), platform).unwrap();
    let flip = if platform == Platform::Ios { -1.0 } else { 1.0 };
    for r in records {
        let Record::Imu(s) = r else { continue };
        let ms = s.t * 1e3;
        if let Some(q) = s.orientation {
            let (a, b, g) = orientation_angles(&q);
            live.push_orientation(ms, a, b, g, true);
        }
        let deg = 180.0 / std::f64::consts::PI;
        live.push_motion(&MotionEvent {
            time_stamp_ms: ms,
            accel: Some([flip * s.accel.x, flip * s.accel.y, flip * s.accel.z]),
            rotation_rate_deg_s: s.gyro.map(|g| [g.x * deg, g.y * deg, g.z * deg]),
            interval: Some(if platform == Platform::Ios {
                0.01
            } else {
                10.0
            }),
        })
        .unwrap();
    }
    live
}

#[wasm_bindgen_test(unsupported = test)]
fn live_events_count_like_the_log_and_both_platforms_agree() {
    let sim = scenarios::demo_walk().generate();
    let log = replay(PipelineConfig::default(), &sim.records).unwrap();
    let android = feed(&sim.records, Platform::Android);
    let ios = feed(&sim.records, Platform::Ios);
    let (a, i) = (android.pipeline().track(), ios.pipeline().track());
    assert_eq!(a, i, "iOS-style and Android-style events differ");
    assert_eq!(a.len(), log.pipeline.track().len());
    let (end, end_log) = (a.last().unwrap(), log.pipeline.track().last().unwrap());
    assert!(
        libm::hypot(end.east_m - end_log.east_m, end.north_m - end_log.north_m) < 0.05,
        "live and log tracks part"
    );
    let r = android.readouts();
    assert_eq!(r.steps, a.len());
    assert!(
        (r.sample_rate_hz - 100.0).abs() < 2.0,
        "{}",
        r.sample_rate_hz
    );
    assert_eq!(r.refused, 0);
}

#[wasm_bindgen_test(unsupported = test)]
fn the_recording_replays_to_the_same_track() {
    let sim = scenarios::demo_walk().generate();
    let mut live = feed(&sim.records, Platform::Ios);
    // The page takes the recording in batches.
    let mut text = String::new();
    for _ in 0..3 {
        text.push_str(&live.take_log());
    }
    let parsed = pdrlog::read(text.as_bytes(), "live.pdrlog").unwrap();
    assert_eq!(parsed.skipped, 0);
    let again = replay(PipelineConfig::default(), &parsed.records).unwrap();
    assert_eq!(again.pipeline.track(), live.pipeline().track());
}

#[wasm_bindgen_test(unsupported = test)]
fn a_hidden_page_is_a_gap_not_steps() {
    let sim = scenarios::straight_walk(1.8, 40.0).generate();
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android).unwrap();
    let mut hidden = false;
    for r in &sim.records {
        let Record::Imu(s) = r else { continue };
        // The page is hidden from 15 s to 25 s: no events, then the page says so.
        if (15.0..25.0).contains(&s.t) {
            hidden = true;
            continue;
        }
        if hidden {
            live.mark_gap(15_000.0, s.t * 1e3);
            hidden = false;
        }
        let deg = 180.0 / std::f64::consts::PI;
        if let Some(q) = s.orientation {
            let (a, b, g) = orientation_angles(&q);
            live.push_orientation(s.t * 1e3, a, b, g, true);
        }
        live.push_motion(&MotionEvent {
            time_stamp_ms: s.t * 1e3,
            accel: Some([s.accel.x, s.accel.y, s.accel.z]),
            rotation_rate_deg_s: s.gyro.map(|g| [g.x * deg, g.y * deg, g.z * deg]),
            interval: None,
        })
        .unwrap();
    }
    let r = live.readouts();
    assert_eq!(r.gaps, 1);
    let in_gap = live
        .pipeline()
        .track()
        .iter()
        .filter(|s| (15.0..25.0).contains(&s.t))
        .count();
    assert_eq!(in_gap, 0, "steps inside the hidden time");
    // 40 s of walking at 1.8 Hz less the 10 s hidden: about 54 steps lost.
    let truth = sim
        .truth
        .steps
        .iter()
        .filter(|s| !(15.0..25.0).contains(&s.t))
        .count();
    assert!(r.steps.abs_diff(truth) <= 3, "{} against {truth}", r.steps);
}
