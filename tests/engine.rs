//! Engine behaviour on simulated walks with known truth. Every test runs natively under
//! `cargo test` and in headless Chromium under wasm-bindgen-test.

use pdr::engine::heading::HeadingMethod;
use pdr::engine::math::wrap_pi;
use pdr::engine::{replay, PipelineConfig, Record};
use pdr::engine::{ImuSample, InputError, Motion, Pipeline, StepRecord};
use pdr::sim::{scenarios, Scenario, Segment, Simulation};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

mod common;
use common::{assert_count, digest, run, StepFields};

/// Mean absolute heading error in degrees over the steps of the walking bout, skipping the first
/// two steps (the two-step average needs a previous step).
fn heading_error_deg(track: &[StepRecord], truth_heading_deg: f64) -> f64 {
    let errs: Vec<f64> = track
        .iter()
        .skip(2)
        .filter_map(|s| s.heading_rad)
        .map(|h| {
            wrap_pi(h - truth_heading_deg.to_radians())
                .abs()
                .to_degrees()
        })
        .collect();
    assert!(!errs.is_empty());
    errs.iter().sum::<f64>() / errs.len() as f64
}

#[wasm_bindgen_test(unsupported = test)]
fn pll_counts_walking_and_running_cadences() {
    for f in [1.5, 1.8, 2.2] {
        let sim = scenarios::straight_walk(f, 70.0).generate();
        let n = run(&sim, PipelineConfig::default()).len();
        assert_count(&format!("walk {f} Hz"), n, sim.truth.steps.len());
    }
    for f in [2.7, 3.4, 4.2] {
        let sim = scenarios::straight_run(f, 35.0).generate();
        let n = run(&sim, PipelineConfig::default()).len();
        assert_count(&format!("run {f} Hz"), n, sim.truth.steps.len());
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn pll_follows_cadence_changes() {
    let sc = common::cadence_change();
    let sim = sc.generate();
    let track = run(&sim, PipelineConfig::default());
    assert_count("cadence change", track.len(), sim.truth.steps.len());
    // The frequency estimate follows: the last walking steps near 2.1 Hz, running near 2.9 Hz.
    let near = |t: f64| {
        track
            .iter()
            .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
            .unwrap()
    };
    assert!((near(60.0).freq_hz - 2.1).abs() < 0.1, "{:?}", near(60.0));
    assert!((near(80.0).freq_hz - 2.9).abs() < 0.15, "{:?}", near(80.0));
}

#[wasm_bindgen_test(unsupported = test)]
fn no_steps_while_still_or_slowly_handled() {
    let sim = Scenario::new(vec![
        Segment::still(30.0),
        Segment::handled(40.0),
        Segment::still(10.0),
    ])
    .generate();
    assert_eq!(run(&sim, PipelineConfig::default()).len(), 0);
    let peak = PipelineConfig {
        detector: pdr::engine::StepDetectorConfig::Peak(Default::default()),
        ..Default::default()
    };
    assert_eq!(run(&sim, peak).len(), 0);
}

#[wasm_bindgen_test(unsupported = test)]
fn both_heading_methods_within_3_degrees_for_any_pocket_yaw() {
    for method in [HeadingMethod::TipToTail2016, HeadingMethod::ClosedForm2021] {
        for yaw in [0.0, 90.0, 180.0, 270.0] {
            let mut sc = scenarios::straight_walk(1.8, 40.0);
            sc.pocket_yaw_deg = yaw;
            sc.start_heading_deg = 60.0;
            let sim = sc.generate();
            let track = run(&sim, PipelineConfig::with_heading(method));
            let err = heading_error_deg(&track, 60.0);
            assert!(
                err < 3.0,
                "{method:?} pocket yaw {yaw}°: mean error {err:.2}°"
            );
        }
    }
}

fn closure(track: &[StepRecord]) -> f64 {
    let last = track.last().unwrap();
    libm::hypot(last.east_m, last.north_m)
}

#[wasm_bindgen_test(unsupported = test)]
fn square_of_4x25m_closes_within_3_percent() {
    let sim = scenarios::square(25.0).generate();
    for method in [HeadingMethod::TipToTail2016, HeadingMethod::ClosedForm2021] {
        let track = run(&sim, PipelineConfig::with_heading(method));
        let c = closure(&track);
        assert!(
            c < 0.03 * 100.0,
            "{method:?}: closure error {c:.2} m over 100 m"
        );
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn sigma_thresholds_switch_states_at_the_right_times() {
    let sc = Scenario::new(vec![
        Segment::still(6.0),
        Segment::walk(10.0, 1.8),
        Segment::run(10.0, 3.0),
        Segment::walk(10.0, 1.8),
        Segment::still(6.0),
    ]);
    let sim = sc.generate();
    let mut p = Pipeline::new(PipelineConfig::default()).unwrap();
    let mut at = Vec::new();
    for r in &sim.records {
        if let Record::Imu(s) = r {
            p.push(r).unwrap();
            at.push((s.t, p.diagnostics().motion.unwrap()));
        }
    }
    let state_at = |t: f64| at.iter().find(|(ts, _)| *ts >= t).unwrap().1;
    // Each state holds from 2.5 s (the 2 s window plus margin) after a change to the next change.
    for (t0, t1, want) in [
        (2.0, 6.0, Motion::Still),
        (8.5, 16.0, Motion::Walking),
        (18.5, 26.0, Motion::Running),
        (28.5, 36.0, Motion::Walking),
        (38.5, 42.0, Motion::Still),
    ] {
        let mut t = t0;
        while t < t1 {
            assert_eq!(state_at(t), want, "at t={t:.1}");
            t += 0.25;
        }
    }
}

fn with_timing(mut sc: Scenario, rate: f64, jitter: f64, gaps: Vec<(f64, f64)>) -> Simulation {
    sc.sensors.rate_hz = rate;
    sc.sensors.jitter = jitter;
    sc.sensors.gaps = gaps;
    sc.generate()
}

#[wasm_bindgen_test(unsupported = test)]
fn irregular_timing_keeps_counts_and_headings() {
    let base = || {
        let mut sc = scenarios::straight_walk(1.8, 70.0);
        sc.start_heading_deg = 200.0;
        sc
    };
    let cases = [
        (
            "60 Hz with ±40 % jitter",
            with_timing(base(), 60.0, 0.4, vec![]),
        ),
        ("fixed 16 ms", with_timing(base(), 62.5, 0.0, vec![])),
        ("15 Hz", with_timing(base(), 15.0, 0.1, vec![])),
        (
            "3 s gap",
            with_timing(base(), 100.0, 0.0, vec![(30.0, 33.0)]),
        ),
    ];
    for (label, sim) in cases {
        for method in [HeadingMethod::TipToTail2016, HeadingMethod::ClosedForm2021] {
            let track = run(&sim, PipelineConfig::with_heading(method));
            assert_count(label, track.len(), sim.truth.observed_steps());
            let err = heading_error_deg(&track, 200.0);
            assert!(err < 3.0, "{label} {method:?}: heading error {err:.2}°");
        }
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn gap_is_not_bridged_with_phantom_steps() {
    let sim = with_timing(
        scenarios::straight_walk(1.8, 60.0),
        100.0,
        0.0,
        vec![(25.0, 31.0)],
    );
    let track = run(&sim, PipelineConfig::default());
    assert!(
        !track.iter().any(|s| s.t > 25.0 && s.t < 31.0),
        "a step was placed inside the gap"
    );
    let r = replay(PipelineConfig::default(), &sim.records).unwrap();
    assert_eq!(r.pipeline.diagnostics().gaps, 1);
}

#[wasm_bindgen_test(unsupported = test)]
fn bad_input_is_refused_and_changes_nothing() {
    let sim = scenarios::straight_walk(1.8, 30.0).generate();
    let clean = run(&sim, PipelineConfig::default());
    let mut dirty: Vec<Record> = Vec::new();
    for (i, r) in sim.records.iter().enumerate() {
        dirty.push(*r);
        if let Record::Imu(s) = r {
            if i % 250 == 7 {
                let mut bad = *s;
                bad.accel.y = f64::NAN;
                dirty.push(Record::Imu(bad));
                dirty.push(Record::Imu(ImuSample { t: s.t - 0.5, ..*s }));
                dirty.push(Record::Imu(ImuSample {
                    gyro: Some(nalgebra::Vector3::new(f64::INFINITY, 0.0, 0.0)),
                    ..*s
                }));
            }
        }
    }
    let r = replay(PipelineConfig::default(), &dirty).unwrap();
    let d = r.pipeline.diagnostics();
    assert!(d.rejected_non_finite > 0 && d.rejected_backwards > 0);
    assert_eq!(r.refused, d.rejected_non_finite + d.rejected_backwards);
    assert_eq!(r.errors.len() as u64, r.refused.min(100));
    assert!(r
        .errors
        .iter()
        .any(|(_, e)| matches!(e, InputError::NonFinite { field: "accel", .. })));
    assert!(r
        .errors
        .iter()
        .any(|(_, e)| matches!(e, InputError::NonFinite { field: "gyro", .. })));
    assert!(r
        .errors
        .iter()
        .any(|(_, e)| matches!(e, InputError::TimeWentBackwards { .. })));
    assert_eq!(
        r.pipeline.track(),
        &clean[..],
        "refused records changed the track"
    );
}

/// The OS attitude often arrives on its own, slower stream: samples without one use the last
/// attitude up to `HOLD_S` old. Older than that, `auto` carries on with the gyroscope from the
/// last attitude, and the explicit `os` source refuses them.
#[wasm_bindgen_test(unsupported = test)]
fn os_attitude_on_a_slower_stream_is_held() {
    let mut sim = scenarios::straight_walk(1.8, 30.0).generate();
    let full = run(&sim, PipelineConfig::default());
    // Every third sample keeps its attitude (≈ 33 Hz beside 100 Hz motion).
    let mut k = 0;
    for r in &mut sim.records {
        if let Record::Imu(s) = r {
            if k % 3 != 0 {
                s.orientation = None;
            }
            k += 1;
        }
    }
    let sparse = run(&sim, PipelineConfig::default());
    assert_count("attitude at 33 Hz", sparse.len(), full.len());
    assert!(heading_error_deg(&sparse, 0.0) < 3.0);
    // A long stretch without any attitude.
    for r in &mut sim.records {
        if let Record::Imu(s) = r {
            if (10.0..20.0).contains(&s.t) {
                s.orientation = None;
            }
        }
    }
    let stretch = run(&sim, PipelineConfig::default());
    assert_count("attitude missing for 10 s", stretch.len(), full.len());
    assert!(heading_error_deg(&stretch, 0.0) < 3.0);
    assert!(stretch.iter().all(|s| s.heading_rad.is_some()));
    let r = replay(PipelineConfig::default(), &sim.records).unwrap();
    assert_eq!(r.pipeline.orientation_diagnostics().unwrap().switches, 2);
    let os = PipelineConfig {
        orientation: pdr::engine::OrientationSource::Os,
        ..PipelineConfig::default()
    };
    let r = replay(os, &sim.records).unwrap();
    let d = r.pipeline.diagnostics();
    assert!(d.rejected_missing_field > 900, "{d:?}");
    assert!(r.errors.iter().all(
        |(_, e)| matches!(e, InputError::MissingField { field: "orientation", t } if *t > 10.15)
    ));
}

/// Phones start the gyroscope (and the OS attitude) after the accelerometer, by 0.2–0.7 s and
/// sometimes more: the heading comes as soon as they do, for every step after.
#[wasm_bindgen_test(unsupported = test)]
fn a_late_gyroscope_or_attitude_gives_a_heading_from_when_it_begins() {
    // Walking from the first second, so that a stream 3 s late misses steps.
    let sim = Scenario::new(vec![
        Segment::still(1.0),
        Segment::walk(60.0, 1.8),
        Segment::still(2.0),
    ])
    .generate();
    let t0 = sim.records.first().map(Record::t).unwrap();
    for late_s in [0.3, 0.7, 3.0] {
        for keep_attitude in [false, true] {
            let records: Vec<Record> = sim
                .records
                .iter()
                .map(|r| match r {
                    Record::Imu(s) => {
                        let begun = s.t >= t0 + late_s;
                        Record::Imu(ImuSample {
                            gyro: s.gyro.filter(|_| begun),
                            orientation: s.orientation.filter(|_| begun && keep_attitude),
                            ..*s
                        })
                    }
                    other => *other,
                })
                .collect();
            let r = replay(PipelineConfig::default(), &records).unwrap();
            assert!(r.errors.is_empty());
            let track = r.pipeline.track();
            let with = track.iter().filter(|s| s.heading_rad.is_some()).count();
            let label = format!("{late_s} s late, attitude {keep_attitude}");
            assert_count(&label, track.len(), sim.truth.steps.len());
            assert!(
                with * 100 >= 95 * track.len(),
                "{label}: {with} of {}",
                track.len()
            );
            assert!(heading_error_deg(track, 0.0) < 3.0, "{label}");
            // The leg pitch's detector, which needs the gyroscope, takes over when it begins.
            let pitch = PipelineConfig {
                detector: pdr::engine::StepDetectorConfig::Pitch(Default::default()),
                ..PipelineConfig::default()
            };
            let r = replay(pitch, &records).unwrap();
            assert!(!r.pipeline.diagnostics().detector_fallback, "{label}");
            let (n, truth) = (r.pipeline.track().len(), sim.truth.steps.len());
            if late_s < 1.0 {
                assert_count(&label, n, truth);
            } else {
                // Walking 2 s before it began: the PLL counted those steps, and the pitch
                // detector starting afresh misses the first of its own.
                assert!(n + 6 >= truth && n <= truth + 1, "{label}: {n} of {truth}");
            }
        }
    }
}

/// The demo walk's track, bit for bit. The same constant is checked natively and in Chromium, so
/// this fails if the two builds ever disagree. When an intended engine change alters the track,
/// update the constant from the native failure message (and check the wasm run agrees).
#[wasm_bindgen_test(unsupported = test)]
fn replay_is_bit_identical_natively_and_in_wasm() {
    let demo = pdr::demo::run_demo();
    let again = pdr::demo::run_demo();
    assert_eq!(
        digest(&demo.track, StepFields::TrackAndFrequency),
        digest(&again.track, StepFields::TrackAndFrequency),
        "two replays differ"
    );
    assert_eq!(
        digest(&demo.track, StepFields::TrackAndFrequency),
        DEMO_DIGEST,
        "demo track digest changed: {:#x}",
        digest(&demo.track, StepFields::TrackAndFrequency)
    );
}

const DEMO_DIGEST: u64 = 0x727d_251e_3b93_8bf7;
