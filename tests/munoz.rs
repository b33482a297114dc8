//! Munoz Diaz 2015 in the pipeline: the leg pitch, the pitch step detector, its step length,
//! the activities and the height, on simulated pocket walks.

mod common;

use common::{assert_count, run};
use pdr::engine::calibration::pitch_offset;
use pdr::engine::pitch_step_length::{PitchStepLength, UNIVERSAL_SLOPE_M_PER_DEG};
use pdr::engine::{
    replay, Activity, PipelineConfig, StepDetectorConfig, StepLengthModel, StepRecord,
};
use pdr::sim::scenarios;

fn pitch_cfg() -> PipelineConfig {
    PipelineConfig {
        detector: StepDetectorConfig::Pitch(Default::default()),
        ..PipelineConfig::default()
    }
}

fn pitch_length_cfg() -> PipelineConfig {
    PipelineConfig {
        step_length: StepLengthModel::Pitch(PitchStepLength::default()),
        ..pitch_cfg()
    }
}

/// The pitch detector counts the simulated pocket walks, in pockets turned every way about the
/// vertical, within 1 %.
#[test]
fn pitch_detector_counts_pocket_walks() {
    for yaw in [0.0, 75.0, 160.0, 250.0] {
        for (name, mut sc) in [
            ("square", scenarios::square(60.0)),
            ("cadence change", common::cadence_change()),
            ("straight", scenarios::straight_walk(1.7, 90.0)),
        ] {
            sc.pocket_yaw_deg = yaw;
            let sim = sc.generate();
            let truth = sim.truth.steps.len();
            let track = run(&sim, pitch_cfg());
            assert_count(&format!("{name}, pocket yaw {yaw}°"), track.len(), truth);
        }
    }
}

/// On a log without a gyroscope the pitch detector cannot be fed: the PLL counts the steps and
/// the diagnostics say so. The same count as the PLL chosen outright.
#[test]
fn without_a_gyroscope_the_pll_counts() {
    let mut sc = scenarios::square(40.0);
    sc.sensors.gyro = false;
    sc.sensors.os_orientation = false;
    sc.sensors.mag = false;
    let sim = sc.generate();
    let r = replay(pitch_cfg(), &sim.records).unwrap();
    assert!(r.errors.is_empty());
    let d = r.pipeline.diagnostics();
    assert!(d.detector_fallback, "the fallback is reported");
    assert_eq!(d.pitch_deg, None);
    let pll = run(&sim, PipelineConfig::default());
    assert_eq!(r.pipeline.track().len(), pll.len());
    assert!(r
        .pipeline
        .track()
        .iter()
        .all(|s| s.pitch_amplitude_deg.is_none()));
    // With a gyroscope the detector is the pitch's, and nothing falls back.
    let r = replay(pitch_cfg(), &scenarios::square(40.0).generate().records).unwrap();
    assert!(!r.pipeline.diagnostics().detector_fallback);
}

/// Every step of a pocket walk carries its stride's Δθ; the simulated thigh swings ±20°, so
/// Δθ ≈ 40°, and the steps are level.
#[test]
fn steps_carry_the_stride_amplitude() {
    let sim = scenarios::square(60.0).generate();
    let track = run(&sim, PipelineConfig::default());
    let with: Vec<f64> = track.iter().filter_map(|s| s.pitch_amplitude_deg).collect();
    assert!(
        with.len() as f64 > 0.9 * track.len() as f64,
        "{} of {} steps have a pitch",
        with.len(),
        track.len()
    );
    let mut sorted = with.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    assert!((median - 40.0).abs() < 4.0, "median Δθ {median}");
    assert!(track.iter().all(|s| s.activity == Activity::Walking));
    assert!(track.iter().all(|s| s.up_m == 0.0 && s.floor == 0));
}

/// §5.1's one-walk calibration: the offset b fitted on one walk of known length makes a second
/// walk of the same walker come out right; the universal line alone is off by the walker's own
/// offset.
#[test]
fn one_walk_calibration_of_the_offset() {
    let calibration = scenarios::calibration_walk(1.8, 80.0, 0.25, 0.17).generate();
    let track = run(&calibration, pitch_length_cfg());
    let amps: Vec<f64> = track.iter().filter_map(|s| s.pitch_amplitude_deg).collect();
    let d = calibration.truth.distance_m;
    // Only the steps with a pitch: the first steps of the bout have none yet.
    let share = amps.len() as f64 / track.len() as f64;
    let b = pitch_offset(d * share, &amps, UNIVERSAL_SLOPE_M_PER_DEG).unwrap();
    let walk = scenarios::square(60.0).generate();
    let err = |cfg: PipelineConfig| {
        let t: Vec<StepRecord> = run(&walk, cfg);
        let est: f64 = t.iter().map(|s| s.length_m).sum();
        (est - walk.truth.distance_m).abs() / walk.truth.distance_m
    };
    let calibrated = err(PipelineConfig {
        step_length: StepLengthModel::Pitch(PitchStepLength {
            b,
            ..PitchStepLength::default()
        }),
        ..pitch_cfg()
    });
    let universal = err(pitch_length_cfg());
    assert!(calibrated < 0.02, "calibrated distance error {calibrated}");
    assert!(calibrated < universal, "{calibrated} against {universal}");
}
