//! Simulated walks written in every import format (`pdr::sim::formats`) and read back through
//! the import the CLI and the upload page use: no warnings, one IMU record per simulated sample,
//! the simulation's values to the precision each format writes, its fixes, the truth the format
//! carries, and the engine's step count against the pdr-log of the same walk (equal where the
//! format carries the OS orientation, within 1 % where the engine falls back to Madgwick or the
//! gravity low-pass).
//!
//! `cargo test --release --test formats -- --nocapture` prints one summary line per case.

// Tolerances computed with std's `cos` and `hypot` are fine in tests (see clippy.toml).
#![allow(clippy::disallowed_methods)]

use pdr::engine::OrientationSource;
use pdr::engine::{replay, PipelineConfig, Record};
use pdr::io::import::{import_all, Format, Log, MemSet, Platform};
use pdr::sim::formats::{self, Recording};
use pdr::sim::{scenarios, Simulation};
use std::sync::OnceLock;

mod common;
use common::{fixes, imu};

fn demo() -> &'static Simulation {
    static S: OnceLock<Simulation> = OnceLock::new();
    S.get_or_init(|| scenarios::demo_walk().generate())
}

fn gnss_city() -> &'static Simulation {
    static S: OnceLock<Simulation> = OnceLock::new();
    S.get_or_init(|| scenarios::gnss_city_walk().generate())
}

/// The engine's step count (and the orientation source it picked) on a log's records.
fn steps(records: &[Record]) -> (usize, Option<OrientationSource>) {
    let r = replay(PipelineConfig::default(), records).unwrap();
    assert_eq!(r.refused, 0, "records refused: {:?}", r.errors);
    (
        r.pipeline.track().len(),
        r.pipeline.diagnostics().orientation,
    )
}

fn import_one(rec: &Recording) -> Log {
    let mut results = import_all(&mut MemSet::new(rec.files.clone()));
    assert_eq!(results.len(), 1, "expected one log: {results:#?}");
    results.pop().unwrap().unwrap()
}

/// The pdr-log's step count of a walk: the reference every format is compared with.
fn reference_steps(sim: &Simulation) -> usize {
    let rec = formats::write(sim, Format::PdrLog, Platform::Android);
    let log = import_one(&rec);
    assert!(log.warnings.is_empty());
    assert_eq!(log.records, sim.records, "pdr-log is lossless");
    steps(&log.records).0
}

fn demo_reference() -> usize {
    static N: OnceLock<usize> = OnceLock::new();
    *N.get_or_init(|| reference_steps(demo()))
}

fn gnss_city_reference() -> usize {
    static N: OnceLock<usize> = OnceLock::new();
    *N.get_or_init(|| reference_steps(gnss_city()))
}

/// Which orientation the engine should end up with.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Attitude {
    Os,
    Madgwick,
    Gravity,
}

/// Tolerances: the precision each format writes.
#[derive(Debug, Clone, Copy)]
struct Tol {
    t: f64,
    accel: f64,
    gyro: f64,
    mag: f64,
    q_rad: f64,
    /// Fix position, m; accuracy and altitude, m.
    fix_m: f64,
    fix_acc: f64,
}

struct Case {
    format: Format,
    platform: Platform,
    attitude: Attitude,
    gyro: bool,
    mag: bool,
    gnss: bool,
    tol: Tol,
}

const F32: Tol = Tol {
    t: 1e-6,
    accel: 1e-5,
    gyro: 1e-6,
    mag: 1e-5,
    q_rad: 1e-5,
    fix_m: 1e-6,
    fix_acc: 1e-5,
};

fn case(name: &str) -> Case {
    let c = |format, platform, attitude, gyro, mag, gnss, tol| Case {
        format,
        platform,
        attitude,
        gyro,
        mag,
        gnss,
        tol,
    };
    use Attitude::*;
    let android = Platform::Android;
    match name {
        "sensor-logger" => c(Format::SensorLogger, android, Os, true, true, true, F32),
        "sensor-logger-ios" => c(
            Format::SensorLogger,
            Platform::Ios,
            Os,
            true,
            true,
            true,
            Tol {
                accel: 1e-9,
                gyro: 1e-12,
                mag: 1e-12,
                q_rad: 1e-7,
                ..F32
            },
        ),
        "sensor-logger-json" => c(Format::SensorLoggerJson, android, Os, true, true, true, F32),
        "phyphox" => c(
            Format::Phyphox,
            android,
            Madgwick,
            true,
            true,
            true,
            Tol {
                accel: 1e-6,
                gyro: 1e-8,
                mag: 1e-6,
                fix_m: 2e-3,
                fix_acc: 1e-7,
                ..F32
            },
        ),
        "gnss-logger" => c(
            Format::GnssLogger,
            android,
            Os,
            true,
            true,
            true,
            Tol {
                t: 0.5e-3 + 1e-6,
                q_rad: 1e-4,
                ..F32
            },
        ),
        "get-sensor-data" => c(
            Format::GetSensorData,
            android,
            Os,
            true,
            true,
            true,
            Tol {
                t: 0.5e-3 + 1e-6,
                accel: 5e-6 + 1e-9,
                gyro: 5e-6 + 1e-9,
                mag: 5e-6 + 1e-9,
                q_rad: 1e-3,
                fix_m: 1.2e-3,
                fix_acc: 0.05 + 1e-9,
            },
        ),
        "oxford" => c(
            Format::OxfordSteps,
            android,
            Gravity,
            false,
            false,
            false,
            Tol {
                accel: 5e-7 + 1e-9,
                ..F32
            },
        ),
        "ms-indoor" => c(
            Format::MsIndoor,
            android,
            Os,
            true,
            true,
            false,
            Tol {
                t: 0.5e-3 + 1e-6,
                q_rad: 1e-3,
                ..F32
            },
        ),
        "xio" => c(
            Format::XioFoot,
            android,
            Madgwick,
            true,
            false,
            false,
            Tol {
                accel: 5e-7 * 9.80665 + 1e-9,
                gyro: 1e-8,
                ..F32
            },
        ),
        "tyrex" => c(Format::Tyrex, android, Os, true, true, false, F32),
        "tyrex-ios" => c(
            Format::Tyrex,
            Platform::Ios,
            Os,
            true,
            true,
            false,
            // Four decimals of s, g, rad/s, µT and quaternion components, as the iPhone app.
            Tol {
                t: 0.5e-4 + 1e-9,
                accel: 0.5e-4 * 9.80665 + 1e-9,
                gyro: 0.5e-4 + 1e-9,
                mag: 0.5e-4 + 1e-9,
                q_rad: 3e-4,
                ..F32
            },
        ),
        "ubicomp13" => c(Format::Ubicomp13, android, Madgwick, true, true, false, F32),
        "weallwalk" => c(
            Format::WeAllWalk,
            Platform::Ios,
            Os,
            true,
            false,
            false,
            // Six decimals; the acceleration is the sum of two columns in g.
            Tol {
                t: 0.5e-6 + 1e-9,
                accel: 1e-6 * 9.80665 + 1e-9,
                gyro: 0.5e-6 + 1e-9,
                q_rad: 5e-6,
                ..F32
            },
        ),
        _ => panic!("no case {name}"),
    }
}

/// Checks one optional value of sample `i` of recording `name`: when the format `carried` it,
/// present in both and within `tol` (the error by `err`, the worst kept in `worst`); otherwise
/// absent from what was read back.
#[allow(clippy::too_many_arguments)]
fn check_value<T: std::fmt::Debug + Copy>(
    (name, i): (&str, usize),
    what: &str,
    carried: bool,
    got: Option<T>,
    want: Option<T>,
    err: impl Fn(T, T) -> f64,
    tol: f64,
    worst: &mut f64,
) {
    match (got, want) {
        (Some(a), Some(b)) if carried => {
            let e = err(a, b);
            *worst = worst.max(e);
            assert!(
                e <= tol,
                "{name}: sample {i} {what} {a:?} vs {b:?}, off by {e}"
            );
        }
        (None, _) if !carried => {}
        (a, b) => panic!("{name}: sample {i} {what} {a:?} vs {b:?}"),
    }
}

/// Expected ground-truth waypoints: the start of the true path, every 10 s, and its end.
fn expected_waypoints(sim: &Simulation) -> Vec<(f64, f64, f64)> {
    let path = &sim.truth.path;
    let (first, last) = (path[0], *path.last().unwrap());
    let mut out = Vec::new();
    let mut t = first.0;
    let mut k = 0.0;
    while t < last.0 - 1e-6 {
        let (e, n) = sim.truth.position_at(t);
        out.push((t, e, n));
        k += 1.0;
        t = first.0 + 10.0 * k;
    }
    out.push(last);
    out
}

/// Writes `sim` as the named format, reads it back and checks everything; returns a summary
/// line.
fn check(name: &str, sim: &Simulation, reference: usize, walk: &str) -> String {
    let c = case(name);
    let rec = formats::write(sim, c.format, c.platform);
    let again = formats::write(sim, c.format, c.platform);
    assert!(rec == again, "{name}: output is deterministic");
    // Layout: one file, or a folder of files named after the recording.
    if formats::is_folder(c.format) {
        let top = rec.files[0].0.split('/').next().unwrap().to_string();
        assert!(
            rec.files
                .iter()
                .all(|(n, _)| n.starts_with(&format!("{top}/"))),
            "{name}: every file inside the recording's folder"
        );
    } else {
        assert_eq!(rec.files.len(), 1, "{name}: one file");
        assert!(!rec.files[0].0.contains('/'));
    }
    for (n, bytes) in &rec.files {
        let text = std::str::from_utf8(bytes).unwrap();
        let bad = text
            .split([',', ';', '\t', '\n', '"', ':'])
            .map(|f| f.trim().trim_start_matches(['-', '+']).to_lowercase())
            .find(|f| f == "nan" || f == "inf" || f == "infinity");
        assert!(bad.is_none(), "{name}: {n} holds {bad:?}");
    }
    let log = import_one(&rec);
    assert_eq!(log.format, c.format, "{name}");
    assert!(
        log.warnings.is_empty() && log.skipped == 0,
        "{name}: warnings {:#?}",
        log.warnings
    );
    if matches!(
        c.format,
        Format::SensorLogger | Format::SensorLoggerJson | Format::Tyrex | Format::WeAllWalk
    ) {
        assert_eq!(log.platform, Some(c.platform), "{name}");
    }
    let tol = c.tol;
    let off = rec.clock_offset_s;

    // IMU: one record per simulated sample, values to the written precision.
    let want = imu(&sim.records);
    let got = imu(&log.records);
    assert_eq!(got.len(), want.len(), "{name}: IMU samples");
    let mut worst = [0.0f64; 5];
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        let e_t = (g.t - (w.t + off)).abs();
        let e_a = (g.accel - w.accel).amax();
        worst[0] = worst[0].max(e_t);
        worst[1] = worst[1].max(e_a);
        assert!(
            e_t <= tol.t,
            "{name}: sample {i} t {} vs {}",
            g.t,
            w.t + off
        );
        assert!(
            e_a <= tol.accel,
            "{name}: sample {i} accel {:?} vs {:?}",
            g.accel,
            w.accel
        );
        let at = (name, i);
        check_value(
            at,
            "gyro",
            c.gyro,
            g.gyro,
            w.gyro,
            |a, b| (a - b).amax(),
            tol.gyro,
            &mut worst[2],
        );
        check_value(
            at,
            "mag",
            c.mag,
            g.mag,
            w.mag,
            |a, b| (a - b).amax(),
            tol.mag,
            &mut worst[3],
        );
        let os = c.attitude == Attitude::Os;
        check_value(
            at,
            "orientation",
            os,
            g.orientation,
            w.orientation,
            |a, b| a.angle_to(&b),
            tol.q_rad,
            &mut worst[4],
        );
    }

    // Fixes: every one, where the format carries them.
    let want_fixes = fixes(&sim.records);
    let got_fixes = fixes(&log.records);
    if c.gnss {
        assert_eq!(got_fixes.len(), want_fixes.len(), "{name}: fixes");
        for (g, w) in got_fixes.iter().zip(&want_fixes) {
            assert!((g.t - (w.t + off)).abs() <= tol.t, "{name}: fix t");
            let dn = (g.lat_deg - w.lat_deg) * 111_200.0;
            let de = (g.lon_deg - w.lon_deg) * 111_200.0 * w.lat_deg.to_radians().cos();
            assert!(
                dn.hypot(de) <= tol.fix_m,
                "{name}: fix off by {} m",
                dn.hypot(de)
            );
            assert!(
                (g.h_accuracy_m - w.h_accuracy_m).abs() <= tol.fix_acc,
                "{name}: accuracy"
            );
            let (ga, wa) = (g.altitude_m.unwrap(), w.altitude_m.unwrap());
            assert!(
                (ga - wa).abs() <= tol.fix_acc.max(1e-6 * wa.abs()),
                "{name}: altitude"
            );
        }
    } else {
        assert!(got_fixes.is_empty(), "{name}: no fixes");
    }

    let truth_note = check_truth(name, &c, sim, &log, off);

    // The engine on the imported log against the pdr-log of the same walk.
    let (n, source) = steps(&log.records);
    let source = source.unwrap();
    let attitude = match source {
        OrientationSource::Os => Attitude::Os,
        OrientationSource::Madgwick { .. } => Attitude::Madgwick,
        OrientationSource::GravityLowPass { .. } => Attitude::Gravity,
        OrientationSource::Auto | OrientationSource::KfNfa(_) => {
            panic!("unresolved or not Auto's: {source:?}")
        }
    };
    assert_eq!(attitude, c.attitude, "{name}: orientation source");
    let diff = n as f64 - reference as f64;
    if c.attitude == Attitude::Os {
        assert_eq!(n, reference, "{name}: steps against the pdr-log");
    } else {
        assert!(
            diff.abs() <= 0.01 * reference as f64,
            "{name}: {n} steps, pdr-log {reference}"
        );
    }
    let bytes: usize = rec.files.iter().map(|f| f.1.len()).sum();
    let line = format!(
        "{walk:<9} {name:<19} files {:>2} ({:>5.1} MB)  samples {:>6}  steps {n:>5} vs pdr-log {reference:>5} ({:+})  {attitude:?}  fixes {:>4}  truth {truth_note}  worst t {:.1e} a {:.1e} g {:.1e} m {:.1e} q {:.1e}",
        rec.files.len(),
        bytes as f64 / 1e6,
        got.len(),
        n as i64 - reference as i64,
        got_fixes.len(),
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        worst[4],
    );
    eprintln!("{line}");
    line
}

/// The truth the format carries, read back against the simulation's (`off`: the reader's clock
/// at simulation time 0); a note for the summary line.
fn check_truth(name: &str, c: &Case, sim: &Simulation, log: &Log, off: f64) -> String {
    let truth = &log.truth;
    let tol = c.tol;
    match c.format {
        Format::OxfordSteps => {
            let steps = &sim.truth.steps;
            assert_eq!(truth.steps, Some(steps.len() as u64), "{name}: true steps");
            assert_eq!(truth.steps_debounced(), truth.steps, "{name}: no bounces");
            for (k, (e, s)) in truth.step_events.iter().zip(steps).enumerate() {
                let d = e.t - (s.t + off);
                assert!(
                    (-1e-6..=0.0101).contains(&d),
                    "{name}: contact {k} {d} s after the true step"
                );
                assert_eq!(e.foot, Some((k % 2) as u8), "{name}: feet alternate");
            }
            format!("{} contacts", steps.len())
        }
        Format::MsIndoor | Format::GetSensorData => {
            let want = expected_waypoints(sim);
            assert_eq!(truth.waypoints.len(), want.len(), "{name}: waypoints");
            let (t_tol, xy_tol) = if c.format == Format::MsIndoor {
                (tol.t, 1e-4)
            } else {
                (tol.t, 0.015)
            };
            for (g, w) in truth.waypoints.iter().zip(&want) {
                assert!((g.t - (w.0 + off)).abs() <= t_tol, "{name}: waypoint t");
                let d = (g.x_m - w.1).hypot(g.y_m - w.2);
                assert!(d <= xy_tol, "{name}: waypoint off by {d} m");
                assert_eq!(g.geo.is_some(), c.format == Format::GetSensorData);
            }
            format!("{} waypoints", want.len())
        }
        Format::Tyrex => {
            let path = &sim.truth.path;
            let (t0, t1) = (path[0].0, path.last().unwrap().0);
            let rows = ((t1 - t0) * formats::TRUTH_RATE_HZ + 1e-6).floor() as usize + 1;
            assert_eq!(truth.trajectory.len(), rows, "{name}: 60 Hz over the path");
            for (k, p) in truth.trajectory.iter().enumerate() {
                let t = t0 + k as f64 / formats::TRUTH_RATE_HZ;
                assert!((p.t - (t + off)).abs() <= 0.5e-4 + 1e-9, "{name}: truth t");
                let (e, n) = sim.truth.position_at(t);
                let d = (p.x_m - e).hypot(p.y_m - n);
                assert!(d <= 1e-5, "{name}: truth off by {d} m at {t}");
                assert!((p.z_m - formats::POCKET_HEIGHT_M).abs() <= 1e-5);
            }
            assert_eq!(log.group.as_deref(), Some("FrontPocket"));
            format!("{rows} positions")
        }
        Format::Ubicomp13 => {
            let steps = &sim.truth.steps;
            assert_eq!(truth.steps, Some(steps.len() as u64), "{name}: true steps");
            let (a, b) = truth.step_window.expect("a walk window");
            assert!(
                steps.iter().all(|s| (a..=b).contains(&(s.t + off))),
                "{name}: the window covers every true step"
            );
            assert_eq!(log.group.as_deref(), Some("FrontPocket"));
            format!("{} steps in {:.1} s", steps.len(), b - a)
        }
        Format::WeAllWalk => {
            let steps = &sim.truth.steps;
            assert_eq!(truth.steps, Some(steps.len() as u64), "{name}: true steps");
            assert_eq!(truth.step_events.len(), steps.len());
            for (k, (e, s)) in truth.step_events.iter().zip(steps).enumerate() {
                assert!(
                    (e.t - (s.t + off)).abs() <= 0.5e-4 + 1e-9,
                    "{name}: step {k}"
                );
                assert_eq!(e.foot, Some((k % 2) as u8), "{name}: feet alternate");
            }
            let want: Vec<_> = formats::path_segments(sim)
                .into_iter()
                .filter(|s| s.turn_deg.is_some())
                .collect();
            assert!(!want.is_empty(), "{name}: the walk turns");
            assert_eq!(truth.turns.len(), want.len(), "{name}: turns");
            for (g, w) in truth.turns.iter().zip(&want) {
                assert!((g.t_start - (w.start + off)).abs() <= 0.5e-4 + 1e-9);
                assert!((g.t_end - (w.end + off)).abs() <= 0.5e-4 + 1e-9);
                assert!((g.angle_deg - w.turn_deg.unwrap()).abs() <= 0.5 + 1e-9);
            }
            assert_eq!(log.group.as_deref(), Some("LeftPocket"));
            format!("{} heel strikes, {} turns", steps.len(), want.len())
        }
        Format::XioFoot => {
            assert!(truth.loop_closure);
            assert!(truth.waypoints.is_empty() && truth.steps.is_none());
            "loop closure (claimed)".into()
        }
        _ => {
            assert_eq!(*truth, Default::default(), "{name}: no truth");
            "-".to_string()
        }
    }
}

fn check_demo(name: &str) {
    check(name, demo(), demo_reference(), "demo");
}

fn check_gnss_city(name: &str) {
    check(name, gnss_city(), gnss_city_reference(), "gnss-city");
}

#[test]
fn sensor_logger_android() {
    check_demo("sensor-logger");
    check_gnss_city("sensor-logger");
}

#[test]
fn sensor_logger_ios() {
    check_demo("sensor-logger-ios");
    check_gnss_city("sensor-logger-ios");
}

#[test]
fn sensor_logger_json() {
    check_demo("sensor-logger-json");
    check_gnss_city("sensor-logger-json");
}

#[test]
fn sensor_logger_json_ios() {
    let sim = demo();
    let rec = formats::write(sim, Format::SensorLoggerJson, Platform::Ios);
    let log = import_one(&rec);
    assert!(log.warnings.is_empty(), "{:#?}", log.warnings);
    assert_eq!(log.platform, Some(Platform::Ios));
    let (got, want) = (imu(&log.records), imu(&sim.records));
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert!((g.accel - w.accel).amax() < 1e-9);
        assert!(g.orientation.unwrap().angle_to(&w.orientation.unwrap()) < 1e-7);
    }
    assert_eq!(steps(&log.records).0, demo_reference());
}

#[test]
fn phyphox() {
    check_demo("phyphox");
    check_gnss_city("phyphox");
}

#[test]
fn gnss_logger() {
    check_demo("gnss-logger");
    check_gnss_city("gnss-logger");
}

#[test]
fn get_sensor_data() {
    check_demo("get-sensor-data");
    check_gnss_city("get-sensor-data");
}

#[test]
fn oxford() {
    check_demo("oxford");
}

#[test]
fn ms_indoor() {
    check_demo("ms-indoor");
}

#[test]
fn xio() {
    check_demo("xio");
}

#[test]
fn tyrex() {
    check_demo("tyrex");
}

#[test]
fn tyrex_ios() {
    check_demo("tyrex-ios");
}

#[test]
fn ubicomp13() {
    check_demo("ubicomp13");
}

#[test]
fn weallwalk() {
    check_demo("weallwalk");
}

#[test]
fn walks_are_not_trivial() {
    // The point of these recordings: hundreds of steps, not a 3-second snippet.
    assert!(demo_reference() > 300, "{}", demo_reference());
    assert!(gnss_city_reference() > 1000, "{}", gnss_city_reference());
}

#[test]
fn folder_names_follow_the_apps() {
    let sim = demo();
    let names = |f, p| -> Vec<String> {
        formats::write(sim, f, p)
            .files
            .into_iter()
            .map(|(n, _)| n)
            .collect()
    };
    let sl = names(Format::SensorLogger, Platform::Android);
    assert!(
        sl.contains(&"2026-01-01_00-00-00/TotalAcceleration.csv".to_string()),
        "{sl:?}"
    );
    let ios = names(Format::SensorLogger, Platform::Ios);
    assert!(
        !ios.iter().any(|n| n.ends_with("TotalAcceleration.csv")),
        "{ios:?}"
    );
    let ox = names(Format::OxfordSteps, Platform::Android);
    assert_eq!(
        ox,
        [
            "Pixel_Sim_Hard_FrontPocket_1/accelerometer.csv",
            "Pixel_Sim_Hard_FrontPocket_1/stepcounter.csv"
        ]
    );
    let rec = formats::write(sim, Format::OxfordSteps, Platform::Android);
    assert_eq!(import_one(&rec).group.as_deref(), Some("FrontPocket"));
    let tyrex = names(Format::Tyrex, Platform::Android);
    assert!(
        tyrex.contains(&"Sim_Nexus5_NoDist_FrontPocket/rotation-vector.txt".to_string()),
        "{tyrex:?}"
    );
    let tyrex_ios = names(Format::Tyrex, Platform::Ios);
    assert!(
        tyrex_ios.contains(&"Sim_iPhone5_NoDist_FrontPocket/attitude.txt".to_string()),
        "{tyrex_ios:?}"
    );
    assert_eq!(
        names(Format::Ubicomp13, Platform::Android),
        [
            "p0.1_Female_20-29_170-179cm_Trousers_front_pocket/acc.csv",
            "p0.1_Female_20-29_170-179cm_Trousers_front_pocket/gyr.csv",
            "p0.1_Female_20-29_170-179cm_Trousers_front_pocket/mag.csv",
            "p0.1_Female_20-29_170-179cm_Trousers_front_pocket/truth.json"
        ]
    );
    assert_eq!(
        names(Format::WeAllWalk, Platform::Ios),
        [
            "T1_ID0_1L/segments.csv",
            "T1_ID0_1L/sensors.csv",
            "T1_ID0_1L/steps.csv"
        ]
    );
    let ph = names(Format::Phyphox, Platform::Android);
    assert!(
        ph.contains(&"Walk 2026-01-01 00-00-00/meta/time.csv".to_string()),
        "{ph:?}"
    );
    assert_eq!(
        names(Format::GnssLogger, Platform::Android),
        ["gnss_log_2026_01_01_00_00_00.txt"]
    );
    // A walk on a Unix clock keeps its date.
    let city = formats::write(gnss_city(), Format::SensorLogger, Platform::Android);
    assert!(city.files[0].0.starts_with("2026-06-01_00-00-00/"));
    assert_eq!(city.clock_offset_s, 0.0);
}

#[test]
fn empty_simulation_gives_headers_only() {
    let sim = Simulation {
        records: Vec::new(),
        truth: Default::default(),
    };
    for f in [
        Format::SensorLogger,
        Format::SensorLoggerJson,
        Format::Phyphox,
        Format::GnssLogger,
        Format::GetSensorData,
        Format::OxfordSteps,
        Format::MsIndoor,
        Format::XioFoot,
        Format::Recipe,
        Format::PdrLog,
        Format::Tyrex,
        Format::Ubicomp13,
        Format::WeAllWalk,
    ] {
        for p in [Platform::Android, Platform::Ios] {
            let rec = formats::write(&sim, f, p);
            assert!(!rec.files.is_empty(), "{f:?}");
        }
    }
}
