//! The simulated foot IMU (`sim::foot`) and Strozzi 2017 §4's hybrid heading
//! (`engine::hybrid`). Every test runs natively under `cargo test` and in headless Chromium under
//! wasm-bindgen-test.

use nalgebra::{Matrix3, Rotation3, Vector3};
use pdr::engine::foot::{Foot, FootConfig, Stride};
use pdr::engine::heading::yaw_aid::device_twist;
use pdr::engine::hybrid::{Hybrid, HybridConfig, HybridMethod, HybridStride};
use pdr::engine::math::{heading_of, wrap_pi};
use pdr::engine::{replay, PipelineConfig, Record};
use pdr::settings::Settings;
use pdr::sim::{scenarios, FootImu, FootStride, Scenario, Segment, Walker};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// Exact strapdown integration of the noise-free foot readings, started from the true state at
/// the start of each stride (at rest: true position and attitude, zero velocity), reproduces the
/// true trajectory: position error far below 1 cm over a stride. Rest samples read gravity and no
/// rate.
#[wasm_bindgen_test(unsupported = test)]
fn foot_readings_integrate_to_the_true_trajectory() {
    let sc = scenarios::square(20.0);
    let foot = FootImu::noiseless();
    let fs = sc.generate_foot(&foot);
    assert!(fs.strides.len() > 20, "{} strides", fs.strides.len());
    let imu: Vec<_> = fs
        .sim
        .records
        .iter()
        .filter_map(|r| match r {
            Record::Imu(s) => Some(*s),
            _ => None,
        })
        .collect();
    let g = Vector3::new(0.0, 0.0, 9.80665);
    let mut worst: f64 = 0.0;
    let mut worst_att: f64 = 0.0;
    for st in &fs.strides {
        let i0 = imu.partition_point(|s| s.t < st.t_start - 0.02);
        let i1 = imu.partition_point(|s| s.t <= st.t_end + 0.02);
        let p0 = fs.track.pose(imu[i0].t);
        let (mut p, mut v, mut r) = (p0.p, p0.v, p0.r);
        for k in i0..i1 - 1 {
            let (a, b) = (imu[k], imu[k + 1]);
            let dt = b.t - a.t;
            let (wa, wb) = (a.gyro.unwrap(), b.gyro.unwrap());
            // Rate: linear over the interval, with the coning correction of second order.
            let phi = (wa + wb) * (0.5 * dt) + wa.cross(&wb) * (dt * dt / 12.0);
            let r1 = r * Rotation3::new(phi).into_inner();
            let acc = |r: &Matrix3<f64>, f: Vector3<f64>| r * f - g;
            let (aa, ab) = (acc(&r, a.accel), acc(&r1, b.accel));
            let v1 = v + (aa + ab) * (0.5 * dt);
            // Position: the velocity quadratic over the interval (Simpson-like, exact for a
            // linear acceleration).
            p += v * dt + (aa * (1.0 / 3.0) + ab * (1.0 / 6.0)) * (dt * dt);
            v = v1;
            r = r1;
            let truth = fs.track.pose(b.t);
            worst = worst.max((p - truth.p).norm());
            let rel = r.transpose() * truth.r;
            worst_att = worst_att.max(Rotation3::from_matrix_unchecked(rel).angle());
        }
    }
    assert!(worst < 1e-3, "position error {worst} m");
    // Second-order integration of rates up to ~6 rad/s at 400 Hz: about 1e-4 rad.
    assert!(worst_att < 5e-4, "attitude error {worst_att} rad");
    println!("strapdown over every stride: position {worst:.2e} m, attitude {worst_att:.2e} rad");
    // At rest: gravity only, no rate.
    let rest: Vec<_> = imu
        .iter()
        .filter(|s| {
            !fs.strides
                .iter()
                .any(|st| s.t > st.t_start && s.t < st.t_end)
        })
        .collect();
    assert!(rest.len() > imu.len() / 3);
    for s in rest {
        assert!((s.accel - g).norm() < 1e-9, "{s:?}");
        assert!(s.gyro.unwrap().norm() < 1e-12, "{s:?}");
    }
}

/// The foot's strides follow the walker: twice the step length at constant cadence, along the
/// path on straight legs, the swing's clearance and rest share as configured.
#[wasm_bindgen_test(unsupported = test)]
fn foot_strides_follow_the_walker() {
    let f = 1.8;
    let sc = scenarios::straight_walk(f, 40.0);
    let foot = FootImu::default();
    let fs = sc.generate_foot(&foot);
    let sl = Walker::default().step_length.length(f);
    let n_steps = fs.sim.truth.steps.len();
    assert!(
        fs.strides.len() * 2 >= n_steps - 2 && fs.strides.len() * 2 <= n_steps + 1,
        "{} strides for {n_steps} steps",
        fs.strides.len()
    );
    let inner = &fs.strides[..fs.strides.len() - 1];
    for s in inner {
        assert!((s.length_m - 2.0 * sl).abs() < 1e-3, "{s:?} vs {sl}");
        assert!(wrap_pi(s.heading_rad).abs() < 1e-9, "{s:?}");
        let motion_share = (s.t_end - s.t_start) * f / 2.0;
        assert!((motion_share - 0.4).abs() < 1e-3, "{motion_share}");
    }
    let top = (0..100)
        .map(|i| {
            fs.track
                .pose(inner[3].t_start + (inner[3].t_end - inner[3].t_start) * f64::from(i) / 100.0)
                .p
                .z
        })
        .fold(0.0, f64::max);
    assert!((top - foot.clearance_m).abs() < 1e-3, "clearance {top}");
    // The distance walked by the foot is the walker's.
    let total: f64 = fs.strides.iter().map(|s| s.length_m).sum();
    assert!(
        (total - fs.sim.truth.distance_m).abs() < 0.3,
        "{total} vs {}",
        fs.sim.truth.distance_m
    );
    // The last footprint is where the walker stopped (plus the foot's lateral offset).
    let last = fs.strides.last().unwrap().to;
    let end = fs.sim.truth.end;
    assert!(
        (libm::hypot(last.0 - end.0, last.1 - end.1) - foot.lateral_m).abs() < 1e-3,
        "{last:?} {end:?}"
    );
    // Turns: the stride headings follow the path.
    let sq = scenarios::square(30.0).generate_foot(&foot);
    for s in &sq.strides {
        let chord = heading_of(s.to.0 - s.from.0, s.to.1 - s.from.1);
        assert!(wrap_pi(chord - s.path_heading_rad).abs() < 0.35, "{s:?}");
    }
}

/// The same scenario gives the same foot samples (and the phone's samples are unchanged by the
/// foot IMU's existence: it has its own noise stream).
#[wasm_bindgen_test(unsupported = test)]
fn foot_simulation_is_deterministic() {
    let sc = Scenario::new(vec![
        Segment::still(1.0),
        Segment::walk(8.0, 1.9).turning(45.0),
        Segment::run(4.0, 2.8),
        Segment::still(1.0),
    ]);
    let a = sc.generate_foot(&FootImu::default());
    let b = sc.generate_foot(&FootImu::default());
    assert_eq!(a.sim.records, b.sim.records);
    let sum: f64 = a
        .sim
        .records
        .iter()
        .map(|r| match r {
            Record::Imu(s) => s.accel.x + s.gyro.map_or(0.0, |g| g.z),
            _ => 0.0,
        })
        .sum();
    assert!(sum.is_finite());
    assert!(a.strides.len() >= 8, "{}", a.strides.len());
}

/// Foot mode's strides on a foot-only walk.
fn foot_strides(records: &[Record]) -> Vec<Stride> {
    let mut foot = Foot::new(FootConfig::default()).unwrap();
    let mut out = Vec::new();
    let mut last = None;
    for r in records {
        if let Record::Imu(s) | Record::Foot(s) = r {
            let dt = last.map_or(0.0, |l| s.t - l);
            last = Some(s.t);
            out.extend(foot.push(s, dt));
        }
    }
    out
}

/// The true stride whose landing is nearest.
fn true_stride(truth: &[FootStride], t_end: f64) -> &FootStride {
    truth
        .iter()
        .min_by(|a, b| (a.t_end - t_end).abs().total_cmp(&(b.t_end - t_end).abs()))
        .unwrap()
}

/// Foot mode (the `foot` stage) on the simulated foot: stride length within 2 %, heading within
/// 2° on straight legs (Strozzi 2017 §3.2), walking at three cadences and running.
#[wasm_bindgen_test(unsupported = test)]
fn foot_mode_on_the_simulated_foot() {
    let walks = [
        scenarios::straight_walk(1.6, 30.0),
        scenarios::straight_walk(1.9, 30.0),
        scenarios::straight_walk(2.2, 30.0),
        scenarios::straight_run(2.8, 20.0),
    ];
    for sc in walks {
        let fs = sc.generate_foot(&FootImu::default());
        let got = foot_strides(&fs.sim.records);
        assert!(
            got.len() + 1 >= fs.strides.len() && got.len() <= fs.strides.len(),
            "{} strides found of {}",
            got.len(),
            fs.strides.len()
        );
        let (mut worst_len, mut worst_head): (f64, f64) = (0.0, 0.0);
        for s in &got {
            let t = true_stride(&fs.strides, s.t_end);
            assert!((t.t_end - s.t_end).abs() < 0.2, "{s:?} vs {t:?}");
            if t.length_m < 0.5 {
                continue; // the last half stride (feet together)
            }
            worst_len = worst_len.max((s.length_m / t.length_m - 1.0).abs());
            worst_head = worst_head.max(wrap_pi(s.heading_rad - t.heading_rad).abs().to_degrees());
        }
        println!(
            "foot mode, {:?}: {} strides, worst length error {:.2} %, worst heading error {:.2}°",
            sc.segments[1].gait,
            got.len(),
            100.0 * worst_len,
            worst_head
        );
        assert!(worst_len < 0.02, "length error {worst_len}");
        assert!(worst_head < 2.0, "heading error {worst_head}°");
    }
}

/// A long outdoor-like walk, an athletic track as Strozzi's (two straights, two smooth 180°
/// bends), `laps` times round ([`scenarios::athletic_track`]).
fn track_walk(laps: usize) -> Scenario {
    scenarios::athletic_track(laps)
}

/// The foot's gyroscope bias drifts (warming up) by 0.05°/s over the walk about its vertical
/// axis.
fn track_foot(duration_s: f64) -> FootImu {
    FootImu {
        gyro_bias_drift: [0.0, 0.0, 0.05f64.to_radians() / duration_s],
        ..FootImu::default()
    }
}

struct HybridRun {
    strides: Vec<HybridStride>,
    diag: pdr::engine::hybrid::HybridDiagnostics,
}

/// The trunk yaw (the twist of the phone's attitude) and the foot's strides through the hybrid
/// stage, in time order, as a pipeline would feed them.
fn run_hybrid(records: &[Record], method: HybridMethod) -> HybridRun {
    let mut h = Hybrid::new(HybridConfig {
        method,
        ..HybridConfig::default()
    })
    .unwrap();
    let mut foot = Foot::new(FootConfig::default()).unwrap();
    let mut last = None;
    let mut out = Vec::new();
    for r in records {
        match r {
            Record::Imu(s) => {
                if let Some(y) = s.orientation.as_ref().and_then(device_twist) {
                    h.push_heading(s.t, y);
                }
            }
            Record::Foot(s) => {
                let dt = last.map_or(0.0, |l| s.t - l);
                last = Some(s.t);
                if let Some(st) = foot.push(s, dt) {
                    h.push_stride(&st);
                }
            }
            _ => {}
        }
        while let Some(x) = h.pop() {
            out.push(x);
        }
    }
    out.extend(h.flush());
    HybridRun {
        strides: out,
        diag: h.diagnostics(),
    }
}

/// Strozzi 2017 §5.1, Table 1: on long outdoor paths the hybrid (foot lengths, trunk heading,
/// either method) ends closer to the truth than the foot alone, whose heading drifts.
#[wasm_bindgen_test(unsupported = test)]
fn hybrid_beats_foot_mode_on_a_long_two_sensor_walk() {
    let sc = track_walk(1);
    let foot_imu = track_foot(sc.duration_s());
    let (sim, fs) = sc.generate_two_sensor(&foot_imu);
    let start = fs.track.pose(0.0).p;
    let end = fs.strides.last().unwrap().to;
    let truth = (end.0 - start.x, end.1 - start.y);
    let distance: f64 = fs.strides.iter().map(|s| s.length_m).sum();
    let foot_only = foot_strides(&fs.sim.records);
    let f_end = foot_only.last().unwrap();
    let err = |e: f64, n: f64| libm::hypot(e - truth.0, n - truth.1);
    let foot_err = err(f_end.east_m, f_end.north_m);
    println!(
        "track walk: {distance:.1} m, {} true strides, {} found; foot mode ends {foot_err:.2} m ({:.2} %) from the truth",
        fs.strides.len(),
        foot_only.len(),
        100.0 * foot_err / distance
    );
    for method in [HybridMethod::MidSwing, HybridMethod::FirCrossing] {
        let run = run_hybrid(&sim.records, method);
        assert_eq!(run.strides.len(), foot_only.len(), "{method:?}");
        let last = run.strides.last().unwrap();
        let e = err(last.east_m, last.north_m);
        println!(
            "hybrid {method:?}: ends {e:.2} m ({:.2} %) from the truth; {:?}",
            100.0 * e / distance,
            run.diag
        );
        assert!(e < foot_err, "{method:?}: {e} m vs foot mode {foot_err} m");
        // Method 2 finds the mid-swing instant from the trunk alone (§4.1: "the same middle
        // swing point"); method 1 samples there by construction.
        let lag: f64 = run
            .strides
            .iter()
            .map(|s| (s.t_sample - s.stride.t_mid_swing).abs())
            .sum::<f64>()
            / run.strides.len() as f64;
        println!("  mean |sampling instant − mid-swing| {:.1} ms", 1e3 * lag);
        assert!(lag < 0.05, "{method:?}: {lag} s");
        assert!(run.diag.no_trunk == 0, "{:?}", run.diag);
    }
}

/// A two-sensor walk round-trips through the pdr-log (`foot` records), and its x-io CSV holds
/// the foot IMU (as the x-io sensor is on a foot), which foot mode reads to the same strides.
#[wasm_bindgen_test(unsupported = test)]
fn two_sensor_walks_are_written_and_read_back() {
    let sc = scenarios::straight_walk(1.8, 12.0);
    let (sim, fs) = sc.generate_two_sensor(&FootImu::default());
    let feet = sim
        .records
        .iter()
        .filter(|r| matches!(r, Record::Foot(_)))
        .count();
    assert_eq!(feet, fs.sim.records.len());
    assert!(sim.records.len() > feet + 1000);
    let text = pdr::io::pdrlog::to_string(&sim.records);
    let back = pdr::io::pdrlog::read(text.as_bytes(), "two.pdrlog").unwrap();
    assert!(back.errors.is_empty(), "{:?}", back.errors.first());
    assert_eq!(back.records, sim.records);
    let rec = pdr::sim::formats::write(
        &sim,
        pdr::io::import::Format::XioFoot,
        pdr::io::import::Platform::Android,
    );
    let (_, csv) = &rec.files[0];
    let log = pdr::io::import::xio::read_xio(&csv[..], "sensor_data.csv").unwrap();
    assert_eq!(log.records.len(), feet);
    let strides = foot_strides(&log.records);
    assert_eq!(strides.len(), foot_strides(&fs.sim.records).len());
    assert!(strides.len() >= 9, "{}", strides.len());
}

/// The pipeline with a two-sensor log: the track is the foot's strides with the hybrid heading
/// (each `hybrid.method`), one record per stride counting two steps; `foot` is foot mode's own
/// track. The hybrid methods end closer to the truth than the foot's heading.
#[wasm_bindgen_test(unsupported = test)]
fn the_pipeline_builds_the_track_from_strides_with_a_foot_sensor() {
    let sc = track_walk(1);
    let (sim, fs) = sc.generate_two_sensor(&track_foot(sc.duration_s()));
    let start = fs.track.pose(0.0).p;
    let end = fs.strides.last().unwrap().to;
    let mut errs = Vec::new();
    for method in ["foot", "mid_swing", "fir_crossing"] {
        let cfg = Settings::new()
            .with("hybrid.method", method)
            .config()
            .unwrap();
        let r = replay(cfg, &sim.records).unwrap();
        assert!(r.errors.is_empty(), "{:?}", r.errors.first());
        let track = r.pipeline.track();
        let d = r.pipeline.diagnostics();
        assert_eq!(track.len(), fs.strides.len(), "{method}");
        assert_eq!(d.steps, 2 * track.len() as u64);
        let last = track.last().unwrap();
        let e = libm::hypot(
            last.east_m - (end.0 - start.x),
            last.north_m - (end.1 - start.y),
        );
        println!(
            "pipeline, hybrid.method = {method}: ends {e:.2} m from the truth; {:?}",
            d.hybrid
        );
        errs.push(e);
    }
    assert!(errs[1] < errs[0] && errs[2] < errs[0], "{errs:?}");
    // A body-only log never makes the hybrid stage.
    let body = replay(
        PipelineConfig::default(),
        &scenarios::straight_walk(1.8, 10.0).generate().records,
    )
    .unwrap();
    assert!(body.pipeline.diagnostics().hybrid.is_none());
    assert!(!body.pipeline.track().is_empty());
}

/// Bad input to the hybrid stage is refused and counted, never a NaN: non-finite trunk yaws,
/// times going backwards, a stride with NaN, no trunk at all (the foot's heading is used).
#[wasm_bindgen_test(unsupported = test)]
fn the_hybrid_stage_refuses_bad_input() {
    let stride = |t: f64, len: f64| Stride {
        t_start: t - 0.4,
        t_end: t,
        t_mid_swing: t - 0.2,
        length_m: len,
        heading_rad: 0.3,
        east_m: 0.0,
        north_m: 0.0,
        up_m: 0.0,
        peak_rate_rad_s: 5.0,
    };
    for method in [HybridMethod::MidSwing, HybridMethod::FirCrossing] {
        let mut h = Hybrid::new(HybridConfig {
            method,
            ..HybridConfig::default()
        })
        .unwrap();
        h.push_heading(0.0, f64::NAN);
        h.push_heading(f64::INFINITY, 0.0);
        h.push_heading(-1e300, 0.0); // finite, but beyond any clock
        for i in 0..300 {
            h.push_heading(
                f64::from(i) * 0.01,
                1.0 + 0.1 * libm::sin(f64::from(i) * 0.07),
            );
        }
        h.push_heading(1.0, 0.0); // backwards
        h.push_stride(&stride(2.0, f64::NAN));
        h.push_stride(&stride(2.5, 1.4));
        h.push_stride(&stride(2.4, 1.4)); // backwards
        let mut out: Vec<_> = std::iter::from_fn(|| h.pop()).collect();
        out.extend(h.flush());
        assert_eq!(out.len(), 1, "{method:?}");
        assert!(out[0].heading_rad.is_finite() && out[0].east_m.is_finite());
        assert_eq!(
            h.diagnostics().refused,
            6,
            "{method:?}: {:?}",
            h.diagnostics()
        );
        // A pause: nothing is interpolated across it, however long.
        h.push_heading(1e11, 0.5);
        h.push_heading(1e11 + 0.01, 0.5);
        // A stride long after the trunk stopped: the foot's heading, counted.
        h.push_stride(&stride(60.0, 1.0));
        let late = h.flush();
        assert_eq!(late.len(), 1);
        assert!((late[0].heading_rad - 0.3).abs() < 1e-12);
        assert_eq!(h.diagnostics().no_trunk, 1);
    }
}
