//! The barometer through the import formats: a simulated walk with pressure readings written in
//! every format that holds them and read back (times and pressures to each format's precision),
//! the formats without one saying so, and GetSensorData landmarks carrying their floors.
#![allow(clippy::disallowed_methods)] // the test's own standard atmosphere, not the track path

use pdr::engine::{replay, PipelineConfig, PressureSample, Record};
use pdr::io::import::recipe::Recipe;
use pdr::io::import::{import_with, Format, Log, MemSet, Platform};
use pdr::sim::formats::{self, Recording};
use pdr::sim::{scenarios, Simulation};
use std::sync::OnceLock;

mod common;

fn import_one(rec: &Recording) -> Log {
    let mut results = common::import::import_mem(rec.files.clone());
    assert_eq!(results.len(), 1, "expected one log: {results:#?}");
    results.pop().unwrap().unwrap()
}

/// Pressure at a height in the standard atmosphere, hPa.
fn standard_pressure(h_m: f64) -> f64 {
    1013.25 * (1.0 - h_m / 44_330.77).powf(5.255_88)
}

/// A straight walk with a barometer: readings at 8 Hz, between the IMU samples, from a made-up
/// height profile (300 m above sea level, up 3.3 m between 10 and 20 s, down again between 40
/// and 50 s), merged into the records in time order.
fn with_barometer() -> &'static Simulation {
    static S: OnceLock<Simulation> = OnceLock::new();
    S.get_or_init(|| {
        let mut sim = scenarios::straight_walk(1.8, 60.0).generate();
        let (t0, t1) = (sim.records[0].t(), sim.records.last().unwrap().t());
        let height = |t: f64| {
            let ramp = |a: f64| ((t - t0 - a) / 10.0).clamp(0.0, 1.0);
            300.0 + 3.3 * (ramp(10.0) - ramp(40.0))
        };
        let mut t = t0 + 0.0613;
        while t < t1 {
            sim.records.push(Record::Pressure(PressureSample {
                t,
                hpa: standard_pressure(height(t)),
            }));
            t += 0.125;
        }
        sim.records.sort_by(|a, b| a.t().total_cmp(&b.t()));
        sim
    })
}

fn pressures(records: &[Record]) -> Vec<PressureSample> {
    records
        .iter()
        .filter_map(|r| match r {
            Record::Pressure(p) => Some(*p),
            _ => None,
        })
        .collect()
}

#[test]
fn barometer_round_trips_through_every_format_that_holds_it() {
    let sim = with_barometer();
    let truth = pressures(&sim.records);
    assert!(truth.len() > 400, "{}", truth.len());
    let recipe = Recipe::from_json(formats::PLAIN_CSV_RECIPE).unwrap();
    // (format, platform, time tolerance s, pressure tolerance hPa): the precision each writes.
    let cases = [
        (Format::PdrLog, Platform::Android, 0.0, 0.0),
        // ns clock; Android: a 32-bit float (ulp 6.1e-5 near 1000 hPa); iOS: a double.
        (Format::SensorLogger, Platform::Android, 1e-6, 3.1e-5),
        (Format::SensorLogger, Platform::Ios, 1e-6, 1e-9),
        (Format::SensorLoggerJson, Platform::Android, 1e-6, 3.1e-5),
        (Format::SensorLoggerJson, Platform::Ios, 1e-6, 1e-9),
        // Ten significant digits of time and pressure.
        (Format::Phyphox, Platform::Android, 1e-7, 1e-6),
        // Milliseconds, four decimals (mbar).
        (Format::GetSensorData, Platform::Android, 1.001e-3, 5.001e-5),
        (Format::Recipe, Platform::Android, 1.001e-3, 5.001e-5),
    ];
    for (format, platform, dt, dp) in cases {
        assert!(formats::holds_pressure(format), "{format:?}");
        let rec = formats::write(sim, format, platform);
        let mut logs = import_with(
            &mut MemSet::new(rec.files.clone()),
            std::slice::from_ref(&recipe),
        );
        assert_eq!(logs.len(), 1, "{format:?}");
        let log = logs.pop().unwrap().unwrap();
        assert!(log.warnings.is_empty(), "{format:?}: {:?}", log.warnings);
        let back = pressures(&log.records);
        assert_eq!(back.len(), truth.len(), "{format:?} {platform:?}");
        for (b, p) in back.iter().zip(&truth) {
            let t = p.t + rec.clock_offset_s;
            assert!(
                (b.t - t).abs() <= dt + 1e-9 * t.abs(),
                "{format:?} {platform:?}: t {} vs {t}",
                b.t
            );
            assert!(
                (b.hpa - p.hpa).abs() <= dp,
                "{format:?} {platform:?}: {} hPa vs {}",
                b.hpa,
                p.hpa
            );
        }
        // In time order among the other records, and the engine takes every reading.
        assert!(log.records.windows(2).all(|w| w[0].t() <= w[1].t()));
        let r = replay(PipelineConfig::default(), &log.records).unwrap();
        assert_eq!(r.refused, 0, "{format:?}: {:?}", r.errors);
        assert_eq!(
            r.pipeline.diagnostics().pressure_samples,
            truth.len() as u64
        );
    }
}

#[test]
fn formats_without_a_barometer_say_so_and_write_none() {
    let sim = with_barometer();
    for format in [
        Format::GnssLogger,
        Format::OxfordSteps,
        Format::MsIndoor,
        Format::XioFoot,
        Format::Tyrex,
        Format::Ubicomp13,
        Format::WeAllWalk,
    ] {
        assert!(!formats::holds_pressure(format), "{format:?}");
        let log = import_one(&formats::write(sim, format, Platform::Android));
        assert!(pressures(&log.records).is_empty(), "{format:?}");
    }
}

#[test]
fn get_sensor_data_landmarks_carry_their_floor() {
    let log = import_one(&formats::write(
        with_barometer(),
        Format::GetSensorData,
        Platform::Android,
    ));
    let wps = &log.truth.waypoints;
    assert!(wps.len() > 5);
    // The simulator's walks are on one floor today (see `landmark_floor` in the writer).
    assert!(wps.iter().all(|w| w.floor == Some(0)), "{wps:?}");
}
