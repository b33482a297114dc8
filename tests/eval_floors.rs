//! `pdr eval`'s floor scoring and barometer count on simulated walks written as the apps write
//! them: a GetSensorData log (landmarks with floors, a barometer) gets a `floors` object and
//! its `pressure_samples`; a Microsoft Indoor log (waypoints without floors, no barometer) gets
//! `floors: null` and 0 readings.

use pdr::engine::{PipelineConfig, PressureSample, Record};
use pdr::eval::{evaluate, summarise};
use pdr::io::import::{import_all, Format, Log, MemSet, Platform};
use pdr::sim::formats;
use pdr::sim::{scenarios, Simulation};

/// A straight walk with a still barometer at 4 Hz.
fn walk() -> Simulation {
    let mut sim = scenarios::straight_walk(1.8, 40.0).generate();
    let (t0, t1) = (sim.records[0].t(), sim.records.last().unwrap().t());
    let mut t = t0 + 0.11;
    while t < t1 {
        sim.records
            .push(Record::Pressure(PressureSample { t, hpa: 977.5 }));
        t += 0.25;
    }
    sim.records.sort_by(|a, b| a.t().total_cmp(&b.t()));
    sim
}

fn import(sim: &Simulation, format: Format) -> Log {
    let rec = formats::write(sim, format, Platform::Android);
    let mut logs = import_all(&mut MemSet::new(rec.files));
    assert_eq!(logs.len(), 1);
    logs.pop().unwrap().unwrap()
}

#[test]
fn landmarks_with_floors_are_scored_and_others_are_not() {
    let sim = walk();
    let readings = sim
        .records
        .iter()
        .filter(|r| matches!(r, Record::Pressure(_)))
        .count() as u64;
    let cfg = PipelineConfig::default();
    let gsd = evaluate(&import(&sim, Format::GetSensorData), &cfg);
    let f = gsd
        .floors
        .clone()
        .expect("GetSensorData landmarks have floors");
    assert_eq!(
        f.landmarks,
        gsd.waypoints - 1,
        "every landmark but the reference"
    );
    assert!(f.landmarks >= 4);
    // A flat walk: the track stays on its floor, as the truth does.
    assert_eq!(f.right, f.landmarks);
    assert_eq!(f.share, 1.0);
    assert_eq!(f.height_error_m, None, "POSI has no height");
    assert_eq!(gsd.pressure_samples, readings);
    let json = serde_json::to_value(&gsd).unwrap();
    assert_eq!(json["floors"]["landmarks"], f.landmarks);
    assert!(json["floors"]["height_error_m"].is_null());

    let ms = evaluate(&import(&sim, Format::MsIndoor), &cfg);
    assert!(ms.waypoints > 2);
    assert_eq!(ms.floors, None);
    assert_eq!(ms.pressure_samples, 0);
    let json = serde_json::to_value(&ms).unwrap();
    assert!(json["floors"].is_null(), "{json}");
    assert_eq!(json["pressure_samples"], 0);

    let s = summarise(&[gsd.clone(), ms, gsd]);
    assert_eq!(s.floor_logs, 2);
    assert_eq!(s.floor_landmarks, 2 * f.landmarks);
    assert_eq!(s.floor_share, Some(1.0));
    assert_eq!(s.height_p75_m, None);
}
