//! Step-length calibration on simulated walks: a walker with a known line SL = a·f + b walks a
//! measured distance at several paces; the engine counts the steps and their frequencies, and
//! the fit must give a and b back. Runs natively and in headless Chromium.

use pdr::engine::calibration::{fit_band, CalibrationWalk, FitWarning};
use pdr::engine::pipeline::{replay, PipelineConfig};
use pdr::sim::{Scenario, Segment, Walker};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// The walker's true line.
const A: f64 = 0.30;
const B: f64 = 0.12;

/// One calibration walk of `metres` at cadence `f`: the engine's steps, the true distance.
fn walk(f: f64, metres: f64, seed: u64) -> CalibrationWalk {
    let mut w = Walker::default();
    w.step_length.walking.a = A;
    w.step_length.walking.b = B;
    let sc = Scenario {
        seed,
        ..Scenario::new(vec![
            Segment::still(3.0),
            Segment::walk_distance(metres, f, &w),
            Segment::still(3.0),
        ])
    };
    let sc = Scenario { walker: w, ..sc };
    let sim = sc.generate();
    let r = replay(PipelineConfig::default(), &sim.records).unwrap();
    CalibrationWalk {
        distance_m: sim.truth.distance_m,
        step_freqs_hz: r.pipeline.track().iter().map(|s| s.freq_hz).collect(),
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn fit_recovers_the_walkers_line_within_2_percent() {
    for paces in [&[1.5, 1.8, 2.1][..], &[1.5, 1.7, 1.9, 2.1, 2.2][..]] {
        let points: Vec<(f64, f64)> = paces
            .iter()
            .enumerate()
            .map(|(i, &f)| walk(f, 150.0, 10 + i as u64).point().unwrap())
            .collect();
        let band = fit_band(&points);
        let fit = band.fit.unwrap();
        assert!(
            (fit.a - A).abs() <= 0.02 * A && (fit.b - B).abs() <= 0.02 * B,
            "{paces:?}: a {:.4} b {:.4} (true {A} {B})",
            fit.a,
            fit.b
        );
        assert!(band.warnings.is_empty(), "{:?}", band.warnings);
        assert!(fit.r2 > 0.99);
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_mistyped_distance_is_flagged() {
    // Five paces; the third walk's distance typed 12 % too long.
    let mut points: Vec<(f64, f64)> = [1.5, 1.7, 1.9, 2.1, 2.2]
        .iter()
        .enumerate()
        .map(|(i, &f)| walk(f, 100.0, 20 + i as u64).point().unwrap())
        .collect();
    points[2].1 *= 1.12;
    let band = fit_band(&points);
    assert!(
        band.warnings
            .iter()
            .any(|w| matches!(w, FitWarning::Outlier { index: 2, .. })),
        "{:?}",
        band.warnings
    );
}
