//! The scores of the carried-phone data sets, end to end: a simulated walk written as each set
//! writes it (TyrEx's motion capture, UbiComp 2013's counted window, WeAllWalk's heel strikes
//! and turns), read back by sniffing and scored by `pdr eval`'s bench. The simulator's truth is
//! exact, so each figure must come out near its ideal; a broken reader, frame or metric moves
//! it far. No file on disk: the tests also run in headless Chromium (wasm-bindgen-test).

use pdr::engine::PipelineConfig;
use pdr::eval::{evaluate, summarise, LogResult};
use pdr::io::import::{import_all, Format, Log, MemSet, Platform};
use pdr::sim::{formats, scenarios, Simulation};
use wasm_bindgen_test::wasm_bindgen_test;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// The simulated walk as `format` writes it, read back (one log).
fn written(sim: &Simulation, format: Format, platform: Platform) -> Log {
    let rec = formats::write(sim, format, platform);
    let mut logs = import_all(&mut MemSet::new(rec.files));
    assert_eq!(logs.len(), 1, "{format:?}");
    let log = logs.pop().unwrap().unwrap();
    assert_eq!(log.format, format);
    log
}

fn scored(sim: &Simulation, format: Format, platform: Platform) -> LogResult {
    let r = evaluate(&written(sim, format, platform), &PipelineConfig::default());
    assert!(r.error.is_none(), "{:?}", r.error);
    r
}

#[wasm_bindgen_test(unsupported = test)]
fn a_motion_capture_truth_scores_the_square_near_its_ideal_on_both_layouts() {
    let sim = scenarios::square(25.0).generate();
    for platform in [Platform::Android, Platform::Ios] {
        let r = scored(&sim, Format::Tyrex, platform);
        let t = r.trajectory.expect("a trajectory truth");
        assert!(t.has_track, "{platform:?}");
        assert!(t.headings_scored > 100, "{platform:?}: {t:?}");
        // The simulator's heading is within a degree of its truth; the truth is written in its
        // frame (no offset).
        assert!(t.heading_error_deg.unwrap() < 1.0, "{platform:?}: {t:?}");
        assert!(
            t.heading_offset_deg.unwrap().abs() < 1.5,
            "{platform:?}: {t:?}"
        );
        assert!((0.99..1.02).contains(&t.distance_ratio.unwrap()), "{t:?}");
        assert!(t.position_p75_m.unwrap() < 0.6, "{platform:?}: {t:?}");
        let s = summarise(std::slice::from_ref(&r));
        let all = s.trajectory_by_group["all"];
        assert_eq!((all.logs, all.without_track), (1, 0));
        assert_eq!(all.heading_error_deg, t.heading_error_deg);
    }
}

#[wasm_bindgen_test(unsupported = test)]
fn a_counted_window_scores_only_the_steps_inside_it() {
    let sim = scenarios::straight_walk(1.8, 40.0).generate();
    let r = scored(&sim, Format::Ubicomp13, Platform::Android);
    let inside = r.steps_in_window.expect("a window");
    let truth = r.truth_steps.unwrap();
    assert!(inside <= r.steps);
    assert!(inside.abs_diff(truth) <= 1, "{inside} of {truth}");
    assert!(r.step_error_pct.unwrap() < 2.0, "{r:?}");
}

#[wasm_bindgen_test(unsupported = test)]
fn heel_strikes_and_turns_score_the_square() {
    let sim = scenarios::square(25.0).generate();
    let r = scored(&sim, Format::WeAllWalk, Platform::Ios);
    assert!(r.step_error_pct.unwrap() < 2.0, "{r:?}");
    let turns = r.turns.clone().expect("turns");
    assert_eq!(turns.turns, 3);
    assert_eq!(turns.scored.len(), 3, "{turns:?}");
    for [truth, change, _] in &turns.scored {
        // The square is walked clockwise: right turns, −90°.
        assert!((truth + 90.0).abs() < 2.0, "{turns:?}");
        assert!((change + 90.0).abs() < 3.0, "{turns:?}");
    }
    assert!(turns.median_error_deg.unwrap() < 2.0, "{turns:?}");
    let s = summarise(&[r]);
    assert_eq!(s.turns_scored, 3);
}
