//! The pocket simulator (Munoz Diaz 2015): the realistic thigh's pitch has the
//! paper's shape on level ground and stairs, its amplitude follows the walker's true pitch law,
//! heights, floors and activities in the truth are right, the barometer follows the height, every
//! pocket pose swings about the thigh's lateral axis, and the scenarios are deterministic.

mod common;

use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion, Vector3};
use pdr::engine::{Activity, Record};
use pdr::sim::scenarios::{
    pitch_calibration_walk, pocket_flat, pocket_mixed, sit_stand, stairs_walk, POCKET_RISER_M,
    POCKET_STEPS_PER_FLOOR, POCKET_TREAD_M,
};
use pdr::sim::{pose::flexion_axis_device, PocketPose, Scenario, Simulation};

/// The thigh's pitch from the OS attitude of each sample: the angle of the device-frame image
/// of the body's vertical (the thigh's axis, through the mount) to the world's vertical, signed
/// positive when it leans back (knee forward) against the path's heading.
fn pitch_from_attitude(sc: &Scenario, sim: &Simulation) -> Vec<(f64, f64)> {
    let m = sc.mount().transpose();
    let (up_device, left_device) = (m * Vector3::z(), m * Vector3::y());
    sim.records
        .iter()
        .filter_map(|r| match r {
            Record::Imu(s) => s.orientation.map(|q| (s.t, q)),
            _ => None,
        })
        .map(|(t, q): (f64, UnitQuaternion<f64>)| {
            let u = q * up_device;
            // The thigh swings about the body's lateral axis, which stays horizontal: forward
            // is left × up.
            let fwd = (q * left_device).cross(&Vector3::z());
            let angle = libm::acos(u.z.clamp(-1.0, 1.0)).to_degrees();
            (t, if u.dot(&fwd) > 0.0 { -angle } else { angle })
        })
        .collect()
}

/// (θ_min, θ_max) of each stride window of the truth's pitch that lies inside steps of
/// `activity` (two consecutive steps, the one before and the one after also of `activity`).
fn stride_extremes(sim: &Simulation, activity: Activity) -> Vec<(f64, f64)> {
    let st = &sim.truth.steps;
    let mut out = Vec::new();
    for k in 1..st.len().saturating_sub(3) {
        if st[k - 1..k + 4].iter().all(|s| s.activity == activity) {
            let (a, b) = (st[k].t, st[k + 2].t);
            let w = sim
                .truth
                .thigh_pitch_deg
                .iter()
                .filter(|p| p.0 >= a && p.0 < b)
                .map(|p| p.1);
            let (lo, hi) = w.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v), h.max(v))
            });
            out.push((lo, hi));
        }
    }
    out
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    assert!(n > 0, "nothing to average");
    s / n as f64
}

#[test]
fn attitude_follows_the_exposed_thigh_pitch() {
    for sc in [
        stairs_walk(PocketPose::UpsideDownInTurned),
        sit_stand(PocketPose::UprightIn),
    ] {
        let sim = sc.generate();
        let mut worst: f64 = 0.0;
        for (t, p) in pitch_from_attitude(&sc, &sim) {
            worst = worst.max((p - sim.truth.pitch_at(t)).abs());
        }
        // The truth is sampled at 100 Hz and interpolated; the waist yaw tilts the attitude's
        // vertical plane a little off the path heading the sign uses.
        assert!(worst < 0.6, "attitude pitch vs truth: {worst:.2}°");
        // The gyroscope is the attitude's rate: the rotation between consecutive attitudes is
        // the mean rate of the two samples (less the bias) over the interval.
        let bias = Vector3::from(sc.sensors.gyro_bias);
        let imu = common::imu(&sim.records);
        let mut worst: f64 = 0.0;
        for w in imu.windows(2) {
            let (q0, q1) = (w[0].orientation.unwrap(), w[1].orientation.unwrap());
            let dt = w[1].t - w[0].t;
            let from_attitude = (q0.inverse() * q1).scaled_axis() / dt;
            let gyro = 0.5 * (w[0].gyro.unwrap() + w[1].gyro.unwrap()) - bias;
            worst = worst.max((from_attitude - gyro).norm());
        }
        assert!(worst < 0.06, "gyro vs attitude: {worst:.3} rad/s");
    }
}

#[test]
fn level_pitch_has_the_papers_shape_and_follows_the_true_law() {
    let sim = pitch_calibration_walk(60.0).generate();
    let ex = stride_extremes(&sim, Activity::Walking);
    assert!(ex.len() > 30, "{} strides", ex.len());
    let f = sim.truth.steps[10].freq_hz;
    let l = pdr::engine::step_length::StepLengthProfile::default().length(f);
    let want = (2.0 * l - 0.06) / 0.030;
    for &(lo, hi) in &ex {
        assert!(hi > lo.abs(), "θmax {hi:.1} ≤ |θmin| {lo:.1}");
        assert!(
            ((hi - lo) - want).abs() < 0.3,
            "Δθ {:.2} vs {want:.2}",
            hi - lo
        );
        assert!((hi / (hi - lo) - 0.68).abs() < 0.01);
    }
    // Double maximum: two local maxima of the pitch per stride while walking, the second (at
    // heel strike) 3–6° above the dip between them.
    let p: Vec<f64> = sim
        .truth
        .thigh_pitch_deg
        .iter()
        .filter(|q| q.0 > 10.0 && q.0 < 30.0)
        .map(|q| q.1)
        .collect();
    let maxima: Vec<usize> = (1..p.len() - 1)
        .filter(|&i| p[i] > p[i - 1] && p[i] >= p[i + 1])
        .collect();
    let strides = 20.0 * f / 2.0;
    let ratio = maxima.len() as f64 / strides;
    assert!(
        (ratio - 2.0).abs() < 0.15,
        "{} maxima in {strides:.1} strides",
        maxima.len()
    );
}

#[test]
fn stair_pitch_matches_section_6_1() {
    let sim = stairs_walk(PocketPose::UprightOut).generate();
    let level = stride_extremes(&sim, Activity::Walking);
    let up = stride_extremes(&sim, Activity::Upstairs);
    let down = stride_extremes(&sim, Activity::Downstairs);
    assert!(
        up.len() >= 20 && down.len() >= 20,
        "{} {}",
        up.len(),
        down.len()
    );
    let d_up = mean(up.iter().map(|e| e.1 - e.0));
    let d_down = mean(down.iter().map(|e| e.1 - e.0));
    assert!((d_up - 53.07).abs() < 2.0, "Δθ_U {d_up:.2}");
    assert!((d_down - 26.62).abs() < 2.0, "Δθ_D {d_down:.2}");
    let h_max = mean(level.iter().map(|e| e.1));
    let h_min = mean(level.iter().map(|e| e.0));
    let u_max = mean(up.iter().map(|e| e.1));
    let u_min = mean(up.iter().map(|e| e.0));
    assert!(
        (1.7..2.3).contains(&(u_max / h_max)),
        "θUmax {u_max:.1} θHmax {h_max:.1}"
    );
    assert!(
        u_min.abs() < 3.0 && u_min.abs() < h_min.abs(),
        "θUmin {u_min:.1}"
    );
    for &(lo, hi) in &down {
        assert!(lo > 0.0, "θDmin {lo:.2} ≤ 0");
        assert!(
            hi > h_max && hi < 1.25 * h_max,
            "θDmax {hi:.1} θHmax {h_max:.1}"
        );
    }
}

#[test]
fn heights_floors_and_activities_in_the_truth() {
    let sc = stairs_walk(PocketPose::UprightOut);
    let sim = sc.generate();
    let tr = &sim.truth;
    let floor = POCKET_STEPS_PER_FLOOR as f64 * POCKET_RISER_M;
    assert!((tr.floor_height_m - floor).abs() < 1e-12);
    let top = tr
        .up_path
        .iter()
        .map(|p| p.1)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!((top - 3.0 * floor).abs() < 1e-6, "top {top:.3} m");
    assert!(tr.up_path.last().unwrap().1.abs() < 1e-6);
    assert_eq!(tr.steps.iter().map(|s| s.floor).max(), Some(3));
    assert_eq!(tr.steps.last().unwrap().floor, 0);
    let count = |a: Activity| tr.steps.iter().filter(|s| s.activity == a).count();
    assert_eq!(count(Activity::Upstairs), 3 * POCKET_STEPS_PER_FLOOR);
    assert_eq!(count(Activity::Downstairs), 3 * POCKET_STEPS_PER_FLOOR);
    assert_eq!(
        count(Activity::Walking),
        tr.steps.len() - 6 * POCKET_STEPS_PER_FLOOR
    );
    // Inside a flight each footfall is one riser up or down and one tread forward.
    for w in tr.steps.windows(3) {
        if w.iter().all(|s| s.activity == w[0].activity) && w[0].activity != Activity::Walking {
            let rise = w[2].up_m - w[1].up_m;
            assert!((rise.abs() - POCKET_RISER_M).abs() < 1e-9, "rise {rise:.3}");
            assert_eq!(rise > 0.0, w[0].activity == Activity::Upstairs);
            assert!(
                (w[1].length_m - POCKET_TREAD_M).abs() < 0.001,
                "{}",
                w[1].length_m
            );
        }
    }
    assert_eq!(tr.activity_at(1.0), Activity::Standing);

    let sim = sit_stand(PocketPose::UprightOut).generate();
    let sits: Vec<_> = sim
        .truth
        .activities
        .iter()
        .filter(|a| a.2 == Activity::Sitting)
        .collect();
    assert_eq!(sits.len(), 1);
    let (a, b, _) = *sits[0];
    assert!((b - a - 21.5).abs() < 1e-9, "seated {:.2} s", b - a);
    assert!(sim.truth.steps.iter().all(|s| s.t < a || s.t > b));
    assert!((sim.truth.pitch_at(0.5 * (a + b)) - 85.0).abs() < 1.5);
    assert!(sim.truth.pitch_at(a - 2.0).abs() < 1e-9);
    assert!(sim
        .truth
        .steps
        .iter()
        .all(|s| s.up_m == 0.0 && s.floor == 0));
}

#[test]
fn pressure_falls_with_height() {
    let sim = stairs_walk(PocketPose::UprightOut).generate();
    let p: Vec<(f64, f64)> = sim
        .records
        .iter()
        .filter_map(|r| match r {
            Record::Pressure(p) => Some((p.t, p.hpa)),
            _ => None,
        })
        .collect();
    let dur = sim.truth.path.last().unwrap().0;
    assert!(
        (p.len() as f64 - 10.0 * dur).abs() < 2.0,
        "{} samples",
        p.len()
    );
    assert!(sim.records.windows(2).all(|w| w[0].t() <= w[1].t()));
    // Least-squares slope of pressure against the true height.
    let pts: Vec<(f64, f64)> = p
        .iter()
        .map(|&(t, hpa)| (sim.truth.height_at(t), hpa))
        .collect();
    let mh = mean(pts.iter().map(|q| q.0));
    let mp = mean(pts.iter().map(|q| q.1));
    let sxy: f64 = pts.iter().map(|q| (q.0 - mh) * (q.1 - mp)).sum();
    let sxx: f64 = pts.iter().map(|q| (q.0 - mh) * (q.0 - mh)).sum();
    let slope = sxy / sxx;
    assert!((slope + 0.120).abs() < 0.01, "{slope:.4} hPa/m");
    let start = mean(p.iter().filter(|q| q.0 < 3.0).map(|q| q.1));
    assert!((start - 1013.25).abs() < 0.1, "{start:.3} hPa");
}

#[test]
fn every_pose_swings_about_the_thighs_lateral_axis() {
    for pose in PocketPose::ALL {
        for left in [false, true] {
            let mut sc = pocket_flat(pose);
            sc.left_pocket = left;
            let sim = sc.generate();
            let walking = |t: f64| sim.truth.activity_at(t) == Activity::Walking;
            let g: Vec<Vector3<f64>> = sim
                .records
                .iter()
                .filter_map(|r| match r {
                    Record::Imu(s) if walking(s.t) => s.gyro,
                    _ => None,
                })
                .collect();
            let m = g.iter().sum::<Vector3<f64>>() / g.len() as f64;
            let cov = g
                .iter()
                .map(|v| (v - m) * (v - m).transpose())
                .sum::<Matrix3<f64>>();
            let eig = SymmetricEigen::new(cov);
            let i = eig.eigenvalues.imax();
            let axis = eig.eigenvectors.column(i).into_owned();
            let want = flexion_axis_device(&sc.mount());
            let angle = libm::acos(axis.dot(&want).abs().min(1.0)).to_degrees();
            assert!(angle < 10.0, "{} left={left}: {angle:.1}°", pose.as_str());
        }
    }
}

#[test]
fn same_seed_same_records() {
    let digest = |sim: &Simulation| {
        common::fnv1a_bytes(
            sim.records
                .iter()
                .flat_map(|r| format!("{r:?}").into_bytes()),
        )
    };
    let a = pocket_mixed(PocketPose::UpsideDownOutTurned).generate();
    let b = pocket_mixed(PocketPose::UpsideDownOutTurned).generate();
    assert_eq!(digest(&a), digest(&b));
    assert!(a.records == b.records && a.truth == b.truth);
    let mut other = pocket_mixed(PocketPose::UpsideDownOutTurned);
    other.seed += 1;
    assert_ne!(digest(&other.generate()), digest(&a));
    // Every activity of the paper shows up in the mixed walk's truth.
    for act in [
        Activity::Standing,
        Activity::Sitting,
        Activity::Walking,
        Activity::Upstairs,
        Activity::Downstairs,
    ] {
        assert!(a.truth.activities.iter().any(|x| x.2 == act), "{act:?}");
    }
    assert_eq!(a.truth.steps.iter().map(|s| s.floor).max(), Some(2));
}
