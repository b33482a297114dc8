//! The log's own date for the declination: every format that carries a date gives it
//! to [`Log::date_unix_s`], `pdr run`, `pdr eval` and the upload page's analysis hand it to the
//! World Magnetic Model ([`Log::dated`]), and the IPIN 2023 logs (GetSensorData, whose clock is
//! time since the app started) no longer say "without a known date".

mod common;

use pdr::engine::fusion::{wmm_declination_deg, DeclinationNote};
use pdr::engine::{replay, PipelineConfig};
use pdr::io::import::{import_with, Format, Log, MemSet, Platform};
use pdr::sim::formats::{self, DEFAULT_UNIX_START_S, PLAIN_CSV_RECIPE};
use pdr::sim::{scenarios, Simulation};
use std::sync::OnceLock;

fn city() -> &'static Simulation {
    static S: OnceLock<Simulation> = OnceLock::new();
    S.get_or_init(|| scenarios::gnss_city_walk().generate())
}

fn import(files: Vec<(String, Vec<u8>)>) -> Log {
    let recipe =
        pdr::io::import::recipe::Recipe::from_json(PLAIN_CSV_RECIPE).expect("the plain CSV recipe");
    let mut logs = import_with(&mut MemSet::new(files), std::slice::from_ref(&recipe));
    assert_eq!(logs.len(), 1, "one log expected");
    logs.pop().unwrap().expect("the log reads")
}

/// The simulated walk's start as the formats write it, Unix s.
fn sim_start(sim: &Simulation) -> f64 {
    let first = sim.records.first().map_or(0.0, |r| r.t());
    let start = first.min(sim.truth.path.first().map_or(first, |p| p.0));
    if start >= 1e9 {
        start // the simulation's clock is Unix time already
    } else {
        DEFAULT_UNIX_START_S as f64 + start
    }
}

fn demo() -> &'static Simulation {
    static S: OnceLock<Simulation> = OnceLock::new();
    S.get_or_init(|| scenarios::demo_walk().generate())
}

#[test]
fn every_format_with_a_date_gives_it() {
    let sim = city();
    let start = sim_start(sim);
    let dated = [
        (Format::SensorLogger, Platform::Android),
        (Format::SensorLogger, Platform::Ios),
        (Format::SensorLoggerJson, Platform::Android),
        (Format::Phyphox, Platform::Android),
        (Format::GnssLogger, Platform::Android),
        (Format::GetSensorData, Platform::Android),
        (Format::MsIndoor, Platform::Android),
        (Format::Recipe, Platform::Android),
    ];
    for (format, platform) in dated {
        let log = import(formats::write(sim, format, platform).files);
        let d = log
            .date_unix_s
            .unwrap_or_else(|| panic!("{format:?} {platform:?}: no date"));
        // Each format's start within a second (its clock's precision and first record).
        assert!(
            (d - start).abs() < 1.0,
            "{format:?} {platform:?}: date {d}, the walk started at {start}"
        );
    }
    // Formats without a date, and a pdr-log on the simulation's own clock: none is invented.
    for format in [Format::OxfordSteps, Format::XioFoot] {
        let log = import(formats::write(sim, format, Platform::Android).files);
        assert_eq!(log.date_unix_s, None, "{format:?}");
    }
    assert!(
        demo().records[0].t() < 1e9,
        "the demo walk's clock is not Unix time"
    );
    let log = import(formats::write(demo(), Format::PdrLog, Platform::Android).files);
    assert_eq!(log.date_unix_s, None);
    // A pdr-log on Unix time (a live recording) is dated by its clock.
    let log = import(formats::write(sim, Format::PdrLog, Platform::Android).files);
    assert_eq!(log.date_unix_s, Some(sim.records[0].t()));
}

#[test]
fn get_sensor_data_falls_back_on_the_fixes_unix_time() {
    let rec = formats::write(city(), Format::GetSensorData, Platform::Android);
    let (name, bytes) = rec.files[0].clone();
    let text = String::from_utf8(bytes).unwrap();
    let without: String = text
        .lines()
        .filter(|l| !l.contains("Date of creation"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(without.len(), text.len(), "the header had a date");
    let log = import(vec![(name, without.into_bytes())]);
    let d = log.date_unix_s.expect("the fixes' Unix time");
    // The fix's SensorTimeStamp minus its AppTimestamp: the start, to the ms the app writes.
    assert!((d - sim_start(city())).abs() < 0.01, "{d}");
}

#[test]
fn pdr_log_date_round_trips() {
    let sim = demo();
    let date = 1_686_729_658.5;
    let text = pdr::io::pdrlog::to_string_dated(&sim.records, Some(date));
    let log = import(vec![("walk.pdrlog".into(), text.clone().into_bytes())]);
    assert_eq!(log.date_unix_s, Some(date));
    assert_eq!(log.records, sim.records, "still lossless");
    assert!(log.warnings.is_empty());
    // A bad date is a warning naming its line and field; the records are all kept.
    let bad = text.replace("# date_unix_s 1686729658.5", "# date_unix_s June");
    let log = import(vec![("walk.pdrlog".into(), bad.into_bytes())]);
    assert_eq!(log.date_unix_s, None);
    assert_eq!(log.records.len(), sim.records.len());
    let w = &log.warnings[0];
    assert_eq!(
        (w.line, w.field.as_deref()),
        (7, Some("date_unix_s")),
        "{w}"
    );
}

#[test]
fn the_log_date_reaches_the_world_magnetic_model() {
    // GetSensorData's clock counts from the app's start: only the header dates the walk.
    let rec = formats::write(city(), Format::GetSensorData, Platform::Android);
    let log = import(rec.files);
    let undated = replay(PipelineConfig::default(), &log.records).unwrap();
    assert!(
        matches!(
            undated.pipeline.diagnostics().declination_note,
            Some(DeclinationNote::NoDate { .. })
        ),
        "without the log's date the model has none"
    );
    let dated = replay(log.dated(&PipelineConfig::default()), &log.records).unwrap();
    let d = dated.pipeline.diagnostics();
    assert_eq!(d.declination_note, None);
    assert!(d.declination_deg.is_some_and(f64::is_finite));
    // A date the configuration sets wins over the log's.
    let mut cfg = PipelineConfig::default();
    cfg.fusion.date_unix_s = Some(1.6e9);
    assert_eq!(log.dated(&cfg).fusion.date_unix_s, Some(1.6e9));
}

#[test]
fn ipin_logs_have_their_date() {
    let Some(logs) = common::ipin::ipin_logs() else {
        return;
    };
    assert_eq!(logs.len(), 25);
    // Route 01, first repetition: "Wed Jun 14 10:00:58 GMT+02:00 2023".
    let first = logs
        .iter()
        .find(|l| l.source.contains("TrainingTrial01_repetition01"))
        .unwrap();
    assert_eq!(first.date_unix_s, Some(1_686_729_658.0));
    for log in &logs {
        // June 2023.
        let d = log.date_unix_s.expect("every IPIN log is dated");
        assert!((1_685_577_600.0..1_688_169_600.0).contains(&d), "{d}");
        let r = pdr::eval::evaluate(log, &PipelineConfig::default());
        assert_eq!(r.declination_note, None, "{}", log.source);
        // The origin, and with it the declination, needs three fixes that agree: route 21's
        // second repetition has one fix, written twice.
        if log.fixes().count() < 3 {
            assert_eq!(r.declination_deg, None, "{}", log.source);
            continue;
        }
        // Nuremberg in June 2023 (WMM2020), not the model's value for 2025 (WMM2025, 0.1° more).
        let dec = r.declination_deg.expect("a declination");
        let f = log.fixes().next().unwrap();
        let at = |date| {
            wmm_declination_deg(f.lat_deg, f.lon_deg, 0.0, date)
                .unwrap()
                .0
        };
        assert!((dec - at(Some(d))).abs() < 0.01, "{}: {dec}", log.source);
        assert!((at(Some(d)) - at(None)).abs() > 0.05, "the date matters");
    }
}

#[test]
fn live_sessions_are_dated_by_the_page_time_origin() {
    use pdr::live::LiveSession;
    // performance.timeOrigin: Unix ms.
    let s = LiveSession::new(PipelineConfig::default(), Platform::Android, 1.7e12).unwrap();
    assert_eq!(s.pipeline().config().fusion.date_unix_s, Some(1.7e9));
    // A page clock without an origin (0) dates nothing; a configured date stays.
    let s = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    assert_eq!(s.pipeline().config().fusion.date_unix_s, None);
    let mut cfg = PipelineConfig::default();
    cfg.fusion.date_unix_s = Some(1.6e9);
    let s = LiveSession::new(cfg, Platform::Android, 1.7e12).unwrap();
    assert_eq!(s.pipeline().config().fusion.date_unix_s, Some(1.6e9));
}
