//! Step-length calibration on simulated walks: a walker with a known line SL = a·f + b walks a
//! measured distance at several paces; the engine counts the steps and their frequencies, and
//! the fit must give a and b back. Runs natively and in headless Chromium.

use pdr::engine::calibration::{fit_band, CalibrationWalk, FitWarning};
use pdr::engine::{replay, PipelineConfig};
use pdr::sim::{scenarios, Scenario};
use wasm_bindgen_test::wasm_bindgen_test;

mod common;

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
        ..Default::default()
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
        ..Default::default()
    };
    assert!(quick
        .add(Band::Walking, "slow", &few)
        .unwrap_err()
        .to_string()
        .contains("only 5 steps"));
    let no_distance = CalibrationWalk {
        distance_m: f64::NAN,
        step_freqs_hz: vec![1.8; 50],
        ..Default::default()
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

/// A calibration walk as the page's wizard records it: the simulated walk fed as a phone's
/// motion events to a live session (the one pipeline, default settings), its distance, its
/// steps' frequencies and their unscaled fuzzy lengths (`LiveSession::fuzzy_lengths`); and the
/// session.
fn wizard_walk_session(
    f: f64,
    metres: f64,
    seed: u64,
) -> (CalibrationWalk, pdr::live::LiveSession) {
    use pdr::live::{LiveSession, Platform};
    let sim = Scenario {
        seed,
        ..scenarios::calibration_walk(f, metres, A, B)
    }
    .generate();
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    common::push_motion_only(&mut live, &sim.records, Platform::Android);
    assert_eq!(live.fuzzy_lengths().len(), live.step_freqs().len());
    let walk = CalibrationWalk {
        distance_m: sim.truth.distance_m,
        step_freqs_hz: live.step_freqs(),
        fuzzy_lengths_m: live.fuzzy_lengths().to_vec(),
    };
    (walk, live)
}

fn wizard_walk(f: f64, metres: f64, seed: u64) -> CalibrationWalk {
    wizard_walk_session(f, metres, seed).0
}

/// The distance the fuzzy model with `profile` (JSON) gives on a separate walk, and the truth.
fn fuzzy_distance(profile: Option<String>, f: f64, metres: f64, seed: u64) -> (f64, f64) {
    let sim = Scenario {
        seed,
        ..scenarios::calibration_walk(f, metres, A, B)
    }
    .generate();
    let settings = pdr::settings::Settings {
        profile,
        ..Default::default()
    }
    .with("step_length.kind", "fuzzy");
    let r = replay(settings.config().unwrap(), &sim.records).unwrap();
    (r.pipeline.diagnostics().distance_m, sim.truth.distance_m)
}

#[wasm_bindgen_test(unsupported = test)]
fn the_session_s_fuzzy_lengths_are_the_fuzzy_model_s() {
    // The lengths the live session computes per step (fuzzy model at scale 1, whatever model
    // runs) are those a pipeline running the fuzzy model gives the same steps: the session's
    // recording replayed with the fuzzy model, and the recording resumed in a new session.
    use pdr::io::pdrlog;
    let (walk, mut live) = wizard_walk_session(1.8, 60.0, 7);
    let text = live.take_log();
    let records = pdrlog::read(text.as_bytes(), "walk.pdrlog")
        .unwrap()
        .records;
    let cfg = pdr::settings::Settings::new()
        .with("step_length.kind", "fuzzy")
        .config()
        .unwrap();
    let fuzzy = replay(cfg, &records).unwrap();
    let want: Vec<f64> = fuzzy.pipeline.track().iter().map(|s| s.length_m).collect();
    assert!(want.len() > 60);
    assert_eq!(walk.fuzzy_lengths_m, want);
    let resumed = pdr::live::LiveSession::resume(
        PipelineConfig::default(),
        pdr::live::Platform::Android,
        0.0,
        &text,
    )
    .unwrap();
    assert_eq!(resumed.fuzzy_lengths(), &want[..]);
}

#[wasm_bindgen_test(unsupported = test)]
fn the_wizard_fits_the_fuzzy_scale_that_measures_another_walk_within_3_percent() {
    use pdr::engine::calibration::{Band, ProfileFile, Wizard, PROFILE_VERSION};
    let mut wiz = Wizard::default();
    for (i, f) in [1.5, 1.8, 2.1].into_iter().enumerate() {
        let w = wiz
            .add(Band::Walking, "pace", &wizard_walk(f, 60.0, 30 + i as u64))
            .unwrap();
        assert!(w.fuzzy_sum_m.is_some_and(|l| l > 0.0), "{w:?}");
    }
    let k = wiz.fuzzy_scale().unwrap();
    let (profile, notes) = wiz.profile(&Default::default());
    assert!(notes.iter().any(|n| n.contains("scale k")), "{notes:?}");
    let file = ProfileFile {
        version: PROFILE_VERSION,
        name: "fuzzy".into(),
        profile,
        walking_points: wiz.points(Band::Walking),
        running_points: vec![],
        fuzzy_scale: Some(k),
        pitch_offset_m: None,
    };
    let json = file.to_json().unwrap();
    assert_eq!(ProfileFile::from_json(&json).unwrap().fuzzy_scale, Some(k));
    let (with, truth) = fuzzy_distance(Some(json), 1.7, 120.0, 99);
    let (without, _) = fuzzy_distance(None, 1.7, 120.0, 99);
    let err = (with - truth).abs() / truth;
    println!(
        "fuzzy scale k = {k:.4}; 120 m at 1.7 Hz: {with:.1} m ({:.1} %), {without:.1} m with k = 1 (truth {truth:.1} m)",
        100.0 * err
    );
    assert!(err < 0.03, "{with} m of {truth} m with k = {k}");

    // An old profile without the field still loads (and still serves the line), and a walk
    // whose fuzzy lengths are unusable is refused with a reason, not fitted to k = ∞.
    let old = r#"{"version": 1, "name": "old", "profile": {"walking": {"a": 0.3, "b": 0.12, "f_lo": 1.5, "f_hi": 2.2},
        "running": {"a": 0.9, "b": -1.5, "f_lo": 2.7, "f_hi": 3.5}}}"#;
    let f = ProfileFile::from_json(old).unwrap();
    assert_eq!(f.fuzzy_scale, None);
    let mut zero = wizard_walk(1.8, 40.0, 3);
    zero.fuzzy_lengths_m.iter_mut().for_each(|l| *l = 0.0);
    let e = Wizard::default()
        .add(Band::Walking, "normal", &zero)
        .unwrap_err();
    assert!(e.to_string().contains("fuzzy step lengths"), "{e}");
    assert!(pdr::engine::calibration::fit_fuzzy_scale(&[]).is_err());
    assert!(pdr::engine::calibration::fit_fuzzy_scale(&[(40.0, 0.0)]).is_err());
    assert!(Wizard::default().fuzzy_scale().is_none());
}

// Munoz Diaz 2015 §5.1's one-walk calibration of the pitch step length's offset.
#[test]
fn the_pitch_offset_of_one_walk_is_recovered_exactly() {
    // 30 strides (60 steps) with amplitudes from 30° to 44.5°, slope 0.0314 m/°, offset
    // 0.17 m: each step is half its stride.
    let (a, b) = (0.0314, 0.17);
    let strides: Vec<f64> = (0..30).map(|k| 30.0 + 0.5 * k as f64).collect();
    let steps: Vec<f64> = strides.iter().flat_map(|&d| [d, d]).collect();
    let distance: f64 = strides.iter().map(|&d| a * d + b).sum();
    let got = pdr::engine::calibration::pitch_offset(distance, &steps, a).unwrap();
    assert!((got - b).abs() < 1e-12, "{got}");
    // Steps without a leg pitch are left out (here: the same walk with 5 more steps that
    // had none, and their distance is not in D either).
    let mut gaps = steps.clone();
    gaps.extend([f64::NAN, 0.0, -3.0, f64::INFINITY, f64::NAN]);
    assert!(
        (pdr::engine::calibration::pitch_offset(distance, &gaps, a).unwrap() - b).abs() < 1e-12
    );
    // A negative offset is possible (a short-legged walker): no clamping.
    let d2: f64 = strides.iter().map(|&d| a * d - 0.1).sum();
    assert!((pdr::engine::calibration::pitch_offset(d2, &steps, a).unwrap() + 0.1).abs() < 1e-12);
}

#[test]
fn a_pitch_walk_is_refused_without_a_distance_or_enough_steps_with_a_pitch() {
    let steps = vec![40.0; 40];
    assert_eq!(
        pdr::engine::calibration::pitch_offset(0.0, &steps, 0.0314),
        Err(pdr::engine::calibration::WalkError::Distance(0.0))
    );
    assert!(matches!(
        pdr::engine::calibration::pitch_offset(f64::NAN, &steps, 0.0314),
        Err(pdr::engine::calibration::WalkError::Distance(_))
    ));
    let few = vec![40.0; pdr::engine::calibration::MIN_STEPS - 1];
    assert_eq!(
        pdr::engine::calibration::pitch_offset(30.0, &few, 0.0314),
        Err(pdr::engine::calibration::WalkError::TooFewSteps(
            pdr::engine::calibration::MIN_STEPS - 1
        ))
    );
    let none = vec![f64::NAN; 60];
    assert_eq!(
        pdr::engine::calibration::pitch_offset(30.0, &none, 0.0314),
        Err(pdr::engine::calibration::WalkError::TooFewSteps(0))
    );
    assert!(pdr::engine::calibration::pitch_offset(30.0, &steps, f64::NAN).is_err());
}

/// A recorded walk (`pdr calibrate`, the wizard's "Open a recording") calibrates the walker's
/// step length: one 100 m walk at 1.8 Hz gives the quick-mode line through its point, whose
/// length at that cadence is the walker's true one, A·1.8 + B = 0.66 m, within 1 %. Why 1 %:
/// SL̄ = D/N is exact for the steps counted, so the error is the count's, and the engine counts
/// the simulated walk's ~150 steps within ±1 (0.7 %). Another walk at that pace, run with the
/// profile, then measures its distance within 1.5 % (the built-in line, 0.62 m at 1.8 Hz, is
/// 6 % short).
#[wasm_bindgen_test(unsupported = test)]
fn a_recorded_walk_calibrates_to_the_walker_s_step_length() {
    use pdr::engine::calibration::{Band, Wizard};
    use pdr::engine::recorded_walk::recorded_walk;
    let sim = Scenario {
        seed: 31,
        ..scenarios::calibration_walk(1.8, 100.0, A, B)
    }
    .generate();
    let r = recorded_walk(
        PipelineConfig::default(),
        &sim.records,
        sim.truth.distance_m,
    )
    .unwrap();
    let n = r.walk.step_freqs_hz.len();
    assert!(
        n.abs_diff(sim.truth.steps.len()) <= 1,
        "{n} steps of {}",
        sim.truth.steps.len()
    );
    assert_eq!(r.walk.fuzzy_lengths_m.len(), n);
    assert_eq!(r.pitch_amplitudes_deg.len(), n);
    let mut wiz = Wizard::default();
    wiz.add(Band::Walking, "recording", &r.walk).unwrap();
    let file = wiz.profile_file("me", None);
    let truth = A * 1.8 + B;
    let sl = file.profile.walking.eval(1.8);
    assert!(
        (sl - truth).abs() < 0.01 * truth,
        "SL(1.8 Hz) {sl:.4} m, true {truth:.4} m"
    );
    assert_eq!(file.walking_points.len(), 1);
    assert!(file.fuzzy_scale.is_some());

    let other = Scenario {
        seed: 32,
        ..scenarios::calibration_walk(1.8, 150.0, A, B)
    }
    .generate();
    let distance = |profile: Option<String>| {
        let cfg = pdr::settings::Settings {
            profile,
            ..Default::default()
        }
        .config()
        .unwrap();
        let r = replay(cfg, &other.records).unwrap();
        r.pipeline.diagnostics().distance_m / other.truth.distance_m
    };
    let calibrated = distance(Some(file.to_json().unwrap()));
    let built_in = distance(None);
    assert!(
        (calibrated - 1.0).abs() < 0.015,
        "calibrated ratio {calibrated:.4}"
    );
    assert!(
        (built_in - 1.0).abs() > 0.04,
        "built-in ratio {built_in:.4}"
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn a_recorded_walk_is_the_live_walk_it_was_recorded_from() {
    // The live session's recording, replayed as a recording, gives the wizard the same steps'
    // frequencies and fuzzy lengths the live walk gave (the steps a bout's opening still held
    // when the live walk was read come after them).
    use pdr::engine::recorded_walk::recorded_walk;
    let (walk, mut live) = wizard_walk_session(1.8, 60.0, 9);
    let records = pdr::io::pdrlog::read(live.take_log().as_bytes(), "walk.pdrlog")
        .unwrap()
        .records;
    let r = recorded_walk(PipelineConfig::default(), &records, walk.distance_m).unwrap();
    let n = walk.step_freqs_hz.len();
    assert!(n > 60 && r.walk.step_freqs_hz.len() >= n);
    assert_eq!(r.walk.step_freqs_hz[..n], walk.step_freqs_hz[..]);
    assert_eq!(r.walk.fuzzy_lengths_m[..n], walk.fuzzy_lengths_m[..]);
}
