//! The real walks of `../shared/data` read by the data sets' own readers (TyrEx, UbiComp 2013,
//! WeAllWalk): every folder one log of the right format and group, without a warning, with a
//! gyroscope, an orientation that turns gravity up where the set has one, and its truth. Skipped
//! with a message when `../shared/data` is absent (a user's clone). The readers on small
//! recordings made in memory: `tests/import_datasets.rs`.

mod common;
use common::imu;
use common::ipin::shared_logs;
use pdr::io::import::{Format, Log, Platform};

/// The folder name of a log.
fn name(log: &Log) -> &str {
    log.source.trim_end_matches('/').rsplit('/').next().unwrap()
}

/// Checks what every log of the three sets has: the format, no warning, a gyroscope on the
/// records (once the gyroscope has started), and, when `up` is set, an orientation that turns
/// the acceleration of the first second up (mean vertical component over 8.5 m/s²).
fn check_common(log: &Log, format: Format, up: bool) {
    let n = name(log);
    assert_eq!(log.format, format, "{n}");
    assert!(
        log.warnings.is_empty() && log.skipped == 0,
        "{n}: {:#?}",
        log.warnings
    );
    let s = imu(&log.records);
    assert!(s.len() > 1000, "{n}: {} samples", s.len());
    let with_gyro = s.iter().filter(|x| x.gyro.is_some()).count();
    assert!(
        with_gyro as f64 > 0.98 * s.len() as f64,
        "{n}: gyroscope on {with_gyro}"
    );
    if up {
        let t0 = s[0].t;
        let first: Vec<f64> = s
            .iter()
            .filter(|x| x.t < t0 + 1.0)
            .filter_map(|x| x.orientation.map(|q| (q * x.accel).z))
            .collect();
        assert!(!first.is_empty(), "{n}: an orientation in the first second");
        let mean = first.iter().sum::<f64>() / first.len() as f64;
        assert!(
            mean > 8.5,
            "{n}: gravity turned into ENU reads {mean:.2} m/s² up"
        );
    }
}

#[test]
fn tyrex_pocket_reads_with_its_trajectories() {
    let Some(logs) = shared_logs("tyrex-pocket") else {
        return;
    };
    assert_eq!(logs.len(), 33);
    let mut ios = 0;
    for log in &logs {
        let n = name(log);
        check_common(log, Format::Tyrex, true);
        let mode = n.rsplit('_').next().unwrap();
        assert_eq!(log.group.as_deref(), Some(mode), "{n}");
        let platform = if n.contains("_iPhone5_") {
            ios += 1;
            Platform::Ios
        } else {
            Platform::Android
        };
        assert_eq!(log.platform, Some(platform), "{n}");
        let tr = &log.truth.trajectory;
        assert!(tr.len() > 5000, "{n}: {} positions", tr.len());
        assert!(
            tr.windows(2).all(|w| w[0].t < w[1].t),
            "{n}: truth in time order"
        );
        // The truth is on the phone's clock: over the recording (on five walks the cameras
        // start up to 1.1 s before the phone's first sample).
        let (a, b) = log.time_span().unwrap();
        assert!(tr[0].t >= a - 2.0 && tr.last().unwrap().t <= b, "{n}");
        // In the room: a few metres.
        assert!(
            tr.iter().all(|p| p.x_m.abs() < 10.0 && p.y_m.abs() < 10.0),
            "{n}"
        );
        assert_eq!(
            log.date_unix_s.is_some(),
            platform == Platform::Android,
            "{n}"
        );
    }
    assert_eq!(ios, 11);
}

#[test]
fn ubicomp13_pocket_reads_with_its_step_counts() {
    let Some(logs) = shared_logs("ubicomp13-pocket") else {
        return;
    };
    assert_eq!(logs.len(), 23);
    for log in &logs {
        let n = name(log);
        check_common(log, Format::Ubicomp13, false);
        assert_eq!(log.platform, Some(Platform::Android));
        let group = if n.ends_with("_front_pocket") {
            "FrontPocket"
        } else {
            "BackPocket"
        };
        assert_eq!(log.group.as_deref(), Some(group), "{n}");
        let steps = log.truth.steps.expect("a step count");
        assert!((50..=120).contains(&steps), "{n}: {steps}");
        let (a, b) = log.truth.step_window.expect("a walk window");
        let (t0, t1) = log.time_span().unwrap();
        assert!(
            t0 < a && a < b && b < t1,
            "{n}: window {a}–{b} in {t0}–{t1}"
        );
    }
}

#[test]
fn weallwalk_reads_with_its_heel_strikes_and_turns() {
    let Some(logs) = shared_logs("weallwalk") else {
        return;
    };
    assert_eq!(logs.len(), 36);
    for log in &logs {
        let n = name(log);
        check_common(log, Format::WeAllWalk, true);
        assert_eq!(log.platform, Some(Platform::Ios));
        let group = if n.ends_with("_1L") {
            "LeftPocket"
        } else {
            "RightPocket"
        };
        assert_eq!(log.group.as_deref(), Some(group), "{n}");
        let t = &log.truth;
        assert_eq!(t.steps, Some(t.step_events.len() as u64), "{n}");
        assert!(t.step_events.len() > 50, "{n}");
        assert!(t.step_events.iter().all(|e| e.foot.is_some()), "{n}");
        assert!(!t.turns.is_empty(), "{n}: turns");
        assert!(
            t.turns
                .iter()
                .all(|x| x.angle_deg.abs() >= 45.0 && x.t_start < x.t_end),
            "{n}: {:?}",
            t.turns
        );
        assert!(
            imu(&log.records).iter().all(|x| x.mag.is_none()),
            "{n}: no magnetometer"
        );
    }
}
