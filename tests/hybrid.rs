//! The simulated foot IMU (`sim::foot`) and Strozzi 2017 §4's hybrid heading
//! (`engine::hybrid`). Every test runs natively under `cargo test` and in headless Chromium under
//! wasm-bindgen-test.

use nalgebra::{Matrix3, Rotation3, Vector3};
use pdr::engine::math::{heading_of, wrap_pi};
use pdr::engine::Record;
use pdr::sim::{scenarios, FootImu, Scenario, Segment, Walker};
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
