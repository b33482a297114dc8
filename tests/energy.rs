//! `pdr eval --energy`: every log in best performance and in energy saving, the
//! receiver's on time per log (`fusion.gnss_on_s`, `gnss_span_s`) and per group
//! (`gnss_on_share`), and the ratio of the two modes' median p75.

mod common;

use pdr::engine::fusion::GnssMode;
use pdr::engine::PipelineConfig;
use pdr::eval::energy::{energy_report, markdown};
use pdr::io::import::{import_all, Format, Log, MemSet, Platform};
use pdr::sim::{formats, scenarios};

/// The simulated city walk as GetSensorData writes it: fixes and geodetic landmarks.
fn city_log() -> Log {
    let sim = scenarios::gnss_city_walk().generate();
    let rec = formats::write(&sim, Format::GetSensorData, Platform::Android);
    import_all(&mut MemSet::new(rec.files))
        .pop()
        .unwrap()
        .unwrap()
}

#[test]
fn receiver_on_time_per_log_and_per_group() {
    let log = city_log();
    let r = energy_report(std::slice::from_ref(&log), &PipelineConfig::default());
    assert_eq!((r.period_s, r.window_s), (60.0, 10.0));
    let names: Vec<&str> = r.groups.iter().map(|g| g.group.as_str()).collect();
    assert_eq!(names, ["other", "all"]);
    let [best, saving] = &r.logs;
    let (b, s) = (best[0].fusion.unwrap(), saving[0].fusion.unwrap());
    let (b_on, b_span) = (b.gnss_on_s.unwrap(), b.gnss_span_s.unwrap());
    let (s_on, s_span) = (s.gnss_on_s.unwrap(), s.gnss_span_s.unwrap());
    assert!(b_span > 60.0, "{b_span}");
    assert!((b_on - b_span).abs() < 1e-9, "best performance: always on");
    assert!(
        s_on < 0.9 * s_span,
        "energy saving switches off: {s_on} of {s_span}"
    );
    let all = &r.groups[1];
    assert_eq!(all.logs, 1);
    assert_eq!(all.best_performance.gnss_on_share, Some(1.0));
    let share = all.energy_saving.gnss_on_share.unwrap();
    assert!((share - s_on / s_span).abs() < 1e-12);
    let ratio = all.fused_ratio.unwrap();
    let fused = |l: &pdr::eval::LogResult| l.fused_error_m.unwrap().p75;
    assert!((ratio - fused(&saving[0]) / fused(&best[0])).abs() < 1e-12);
    // One log: the median of the logs' ratios is its ratio.
    assert!((all.fused_log_ratio.unwrap() - ratio).abs() < 1e-12);
    assert!(markdown(&r).contains("| all | 1 |"));
    // The same figures in `pdr eval --json`'s rows and summary.
    let json = serde_json::to_value(&saving[0]).unwrap();
    assert_eq!(json["fusion"]["gnss_on_s"].as_f64(), Some(s_on));
    assert_eq!(json["fusion"]["gnss_span_s"].as_f64(), Some(s_span));
    let summary = pdr::eval::summarise(saving);
    assert_eq!(summary.gnss_on_share, Some(share));
}

#[test]
fn energy_saving_settings_are_kept() {
    let mut cfg = PipelineConfig::default();
    cfg.fusion.mode = GnssMode::EnergySaving {
        period_s: 30.0,
        window_s: 5.0,
    };
    let r = energy_report(&[city_log()], &cfg);
    assert_eq!((r.period_s, r.window_s), (30.0, 5.0));
}

#[test]
fn ipin_route_groups() {
    let Some(logs) = common::ipin::ipin_logs() else {
        return;
    };
    let r = energy_report(&logs, &PipelineConfig::default());
    let rows: Vec<(&str, u64)> = r
        .groups
        .iter()
        .map(|g| (g.group.as_str(), g.logs))
        .collect();
    assert_eq!(
        rows,
        [
            ("trials 0x", 12),
            ("trials 2x", 12),
            ("trials 5x", 1),
            ("all", 25)
        ]
    );
    for g in &r.groups {
        assert_eq!(g.best_performance.gnss_on_share, Some(1.0), "{}", g.group);
        let s = g.energy_saving.gnss_on_share.unwrap();
        assert!(s > 0.0 && s <= 1.0, "{}: {s}", g.group);
    }
}
