//! Step-length calibration on simulated walks: a walker with a known line SL = a·f + b walks a
//! measured distance at several paces; the engine counts the steps and their frequencies, and
//! the fit must give a and b back. Runs natively and in headless Chromium.

use pdr::engine::calibration::{fit_band, CalibrationWalk, FitWarning};
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Scenario};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// The walker's true line.
const A: f64 = 0.30;
const B: f64 = 0.12;

/// One calibration walk of `metres` at cadence `f`: the engine's steps, the true distance.
fn walk(f: f64, metres: f64, seed: u64) -> CalibrationWalk {
    let sc = Scenario {
        seed,
        ..scenarios::calibration_walk(f, metres, A, B)
    };
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

#[wasm_bindgen_test(unsupported = test)]
fn the_wizard_makes_the_profile_from_three_paces_or_one() {
    use pdr::engine::calibration::{Band, Wizard, UNIVERSAL_SLOPE};
    use pdr::engine::step_length::StepLengthProfile;
    let base = StepLengthProfile::default();
    let mut wiz = Wizard::default();
    for (i, f) in [1.5, 1.8, 2.1].into_iter().enumerate() {
        let w = wiz
            .add(Band::Walking, "pace", &walk(f, 150.0, 10 + i as u64))
            .unwrap();
        assert!(w.steps > 150 && (w.f_mean_hz - f).abs() < 0.05, "{w:?}");
    }
    let (p, notes) = wiz.profile(&base);
    assert!((p.walking.a - A).abs() < 0.02 * A && (p.walking.b - B).abs() < 0.02 * B);
    assert_eq!(p.running, base.running, "a band without walks stays");
    assert!(notes[0].contains("least-squares") && notes[1].contains("no walks"));
    p.validate().unwrap();

    // Quick mode: one normal walk keeps the population slope and fits the offset through it.
    let mut quick = Wizard::default();
    let w = quick
        .add(Band::Walking, "normal", &walk(1.8, 40.0, 3))
        .unwrap()
        .clone();
    let (p, notes) = quick.profile(&base);
    assert_eq!(p.walking.a, UNIVERSAL_SLOPE);
    assert!((p.walking.eval(w.f_mean_hz) - w.sl_mean_m).abs() < 1e-12);
    assert!(notes[0].contains("quick mode"));

    // Bad walks are refused with a reason.
    let few = CalibrationWalk {
        distance_m: 10.0,
        step_freqs_hz: vec![1.8; 5],
    };
    assert!(quick
        .add(Band::Walking, "slow", &few)
        .unwrap_err()
        .to_string()
        .contains("only 5 steps"));
    let no_distance = CalibrationWalk {
        distance_m: f64::NAN,
        step_freqs_hz: vec![1.8; 50],
    };
    assert!(quick.add(Band::Walking, "slow", &no_distance).is_err());
    // A slope that cannot be right falls back to quick mode on the mean point.
    let mut wrong = Wizard::default();
    for (f, d) in [(1.5, 40.0), (2.1, 25.0)] {
        let mut w = walk(f, 40.0, 5);
        w.distance_m = d;
        wrong.add(Band::Walking, "pace", &w).unwrap();
    }
    let (p, notes) = wrong.profile(&base);
    assert_eq!(p.walking.a, base.walking.a);
    assert!(notes[0].contains("quick mode"), "{notes:?}");
}
