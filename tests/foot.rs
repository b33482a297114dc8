//! Foot mode (Strozzi 2017 §3.2; zero-velocity updates in an error-state Kalman filter):
//! through the one pipeline on synthetic foot strides (natively and in headless Chromium), and
//! on the real x-io foot walks and the real phone logs of `../shared/data` (native; skipped with
//! a message when the data set is not beside this checkout).

use nalgebra::Vector3;
use pdr::engine::foot::placement::Placement;
use pdr::engine::orientation::G0;
use pdr::engine::{replay, ImuSample, PipelineConfig, Record};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// A foot IMU at 400 Hz: still 2 s, then `n` strides (a 0.5 s swing pushing along the foot's x
/// axis, +a for 0.25 s then −a, with the swing's rotation to and fro about the foot's y axis at
/// 6 rad/s, no net rotation; a 0.6 s stance), then still 1 s. Each stride is a·0.0625 m.
fn foot_walk(n: usize, a: f64) -> Vec<Record> {
    let dt = 0.0025;
    let mut out = Vec::new();
    let mut t = 0.0;
    let mut push = |f: Vector3<f64>, w: Vector3<f64>| {
        out.push(Record::Imu(ImuSample {
            t,
            accel: f,
            gyro: Some(w),
            mag: None,
            orientation: None,
        }));
        t += dt;
    };
    let still = Vector3::new(0.0, 0.0, G0);
    for _ in 0..800 {
        push(still, Vector3::zeros());
    }
    for _ in 0..n {
        for i in 0..200 {
            let ax = if i < 100 { a } else { -a };
            let wy = if i % 2 == 0 { 6.0 } else { -6.0 };
            push(Vector3::new(ax, 0.0, G0), Vector3::new(0.0, wy, 0.0));
        }
        for _ in 0..240 {
            push(still, Vector3::zeros());
        }
    }
    for _ in 0..400 {
        push(still, Vector3::zeros());
    }
    out
}

#[wasm_bindgen_test(unsupported = test)]
fn a_foot_is_recognised_and_its_strides_counted_twice() {
    // 8 strides of 1.25 m (a = 20 m/s²).
    let recs = foot_walk(8, 20.0);
    let r = replay(PipelineConfig::default(), &recs).unwrap();
    let d = r.pipeline.diagnostics();
    assert_eq!(d.placement, Placement::Foot);
    assert_eq!(d.strides, 8);
    assert_eq!(d.steps, 16, "a stride is two steps");
    let track = r.pipeline.track();
    assert_eq!(track.len(), 8, "one record per stride");
    for (k, s) in track.iter().enumerate() {
        assert!((s.length_m - 1.25).abs() < 0.02, "stride {k}: {s:?}");
        assert!((s.north_m - 1.25 * (k + 1) as f64).abs() < 0.1, "{s:?}");
    }
    assert!((d.distance_m - 10.0).abs() < 0.1, "{}", d.distance_m);
}

#[wasm_bindgen_test(unsupported = test)]
fn placement_body_and_foot_are_obeyed() {
    let recs = foot_walk(8, 20.0);
    let body = PipelineConfig {
        placement: Placement::Body,
        ..PipelineConfig::default()
    };
    let r = replay(body, &recs).unwrap();
    assert_eq!(r.pipeline.diagnostics().placement, Placement::Body);
    assert_eq!(r.pipeline.diagnostics().strides, 0);
    assert!(r.pipeline.diagnostics().foot.is_none());
    // Foot mode from the first sample: even 2 strides (too few to recognise) are strides.
    let foot = PipelineConfig {
        placement: Placement::Foot,
        ..PipelineConfig::default()
    };
    let recs = foot_walk(2, 20.0);
    let r = replay(foot.clone(), &recs).unwrap();
    assert_eq!(r.pipeline.diagnostics().strides, 2);
    let r = replay(PipelineConfig::default(), &recs).unwrap();
    assert_eq!(
        r.pipeline.diagnostics().placement,
        Placement::Auto,
        "undecided"
    );
    assert_eq!(r.pipeline.diagnostics().strides, 0);
    // `--set placement=foot` reaches the configuration.
    let cfg = pdr::settings::Settings::new()
        .with("placement", "foot")
        .config()
        .unwrap();
    assert_eq!(cfg, foot);
}

#[wasm_bindgen_test(unsupported = test)]
fn foot_mode_never_panics_nor_emits_nan_on_wild_input() {
    let foot = PipelineConfig {
        placement: Placement::Foot,
        ..PipelineConfig::default()
    };
    let mut recs = foot_walk(3, 20.0);
    // Saturated swings, a stuck clock, huge rates.
    let mut t = 20.0;
    for i in 0..20_000 {
        let x = (i % 7) as f64 * 1e3 - 3e3;
        recs.push(Record::Imu(ImuSample {
            t,
            accel: Vector3::new(x, -x, 9.0),
            gyro: Some(Vector3::new(900.0, -x / 10.0, 0.0)),
            mag: None,
            orientation: None,
        }));
        if i % 3 == 0 {
            t += 0.0025;
        }
    }
    recs.extend(foot_walk(3, 20.0).into_iter().map(|r| match r {
        Record::Imu(mut s) => {
            s.t += 100.0;
            Record::Imu(s)
        }
        r => r,
    }));
    let r = replay(foot, &recs).unwrap();
    for s in r.pipeline.track() {
        assert!(s.east_m.is_finite() && s.north_m.is_finite() && s.length_m.is_finite());
    }
    assert!(r.pipeline.diagnostics().distance_m.is_finite());
}

/// The real logs of one data set, or `None` (with a message) when it is absent.
#[cfg(not(target_arch = "wasm32"))]
fn real_logs(set: &str) -> Option<Vec<pdr::io::import::Log>> {
    use pdr::io::import::{fileset::DirSet, import_all};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(set);
    let Ok(mut files) = DirSet::new(&dir) else {
        println!(
            "skipped: {} not found (the shared data set is not beside this checkout)",
            dir.display()
        );
        return None;
    };
    Some(
        import_all(&mut files)
            .into_iter()
            .map(|r| r.expect("readable"))
            .collect(),
    )
}

#[cfg(not(target_arch = "wasm32"))]
#[test]
fn xio_foot_loops_close_within_one_percent_of_the_distance() {
    let Some(logs) = real_logs("xio-foot") else {
        return;
    };
    assert_eq!(logs.len(), 2);
    for log in &logs {
        let res = pdr::eval::evaluate(log, &PipelineConfig::default());
        let closure = res.loop_closure_m.unwrap();
        let strides = res.strides.expect("foot mode ran");
        println!(
            "{}: {strides} strides, {:.2} m, loop closure {closure:.3} m ({:.2} %)",
            log.source,
            res.distance_m,
            100.0 * closure / res.distance_m
        );
        assert_eq!(res.placement, Placement::Foot);
        assert_eq!(res.steps, 2 * strides);
        // ~25 m and ~60 m loops (x-io); strides of 1.2–1.8 m.
        let (lo, hi) = if log.source.contains("short") {
            (20.0, 30.0)
        } else {
            (50.0, 70.0)
        };
        assert!((lo..hi).contains(&res.distance_m), "{}", res.distance_m);
        let mean = res.distance_m / strides as f64;
        assert!((1.2..1.8).contains(&mean), "mean stride {mean} m");
        assert!(closure <= 0.01 * res.distance_m, "closure {closure} m");
    }
}

#[cfg(not(target_arch = "wasm32"))]
#[test]
fn phone_logs_are_never_taken_for_a_foot() {
    for set in ["oxford-steps", "ms-indoor", "ipin2023"] {
        let Some(logs) = real_logs(set) else {
            return;
        };
        assert!(!logs.is_empty());
        for log in &logs {
            let r = replay(PipelineConfig::default(), &log.records).unwrap();
            let d = r.pipeline.diagnostics();
            assert_ne!(d.placement, Placement::Foot, "{}", log.source);
            assert_eq!(d.strides, 0, "{}", log.source);
        }
    }
}
