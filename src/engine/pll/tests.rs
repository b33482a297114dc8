//! The PLL's tests: locking, and the cycle gate's rules on synthetic walks. May import: the PLL.

use super::*;

fn count(f_in: f64, seconds: f64, rate: f64) -> (usize, f64) {
    let mut p = Pll::new(PllConfig::default());
    let mut n = 0;
    let steps = (seconds * rate) as usize;
    for i in 1..steps {
        let t = i as f64 / rate;
        let a = 3.0 * (TAU * f_in * t).cos();
        let x = DetectorInput {
            t,
            dt: 1.0 / rate,
            up: a,
            mean: 0.0,
            sigma: 3.0 / 2f64.sqrt(),
            motion: Motion::Walking,
            cadence_hz: None,
            pitch_deg: None,
            axis_tilt_sin: None,
            pocket: false,
        };
        if p.push(&x).is_some() {
            n += 1;
        }
    }
    (n, p.frequency())
}

#[test]
fn locks_to_walking_cadences() {
    for f in [1.3, 1.5, 1.8, 2.2, 2.5] {
        let (n, fr) = count(f, 60.0, 100.0);
        let expect = f * 60.0;
        assert!(
            (n as f64 - expect).abs() <= 3.0,
            "f={f}: counted {n}, expected {expect}"
        );
        assert!((fr - f).abs() < 0.05, "f={f}: tracked {fr}");
    }
}

/// A walk at 1.8 Hz sampled at 100 Hz for `seconds`: the vertical acceleration's amplitude,
/// the leg pitch (degrees) and the axis tilt at each time. Returns the steps [`Pll::push`]
/// gave, and those [`Pll::take_late_step`] gave after a push.
fn walk_with(
    cfg: PllConfig,
    seconds: f64,
    amplitude: impl Fn(f64) -> f64,
    pitch: impl Fn(f64) -> Option<f64>,
    tilt: impl Fn(f64) -> Option<f64>,
) -> (Vec<f64>, Vec<f64>) {
    let f = 1.8;
    let mut p = Pll::new(cfg);
    let (mut steps, mut late) = (Vec::new(), Vec::new());
    for i in 1..(seconds * 100.0) as usize {
        let t = i as f64 / 100.0;
        let c = p.push(&DetectorInput {
            t,
            dt: 0.01,
            up: amplitude(t) * (TAU * f * t).cos(),
            mean: 0.0,
            sigma: 3.0 / 2f64.sqrt(),
            motion: Motion::Walking,
            cadence_hz: Some(f),
            pitch_deg: pitch(t),
            axis_tilt_sin: tilt(t).map(|d: f64| libm::sin(d.to_radians())),
            pocket: false,
        });
        steps.extend(c.map(|c| c.t));
        late.extend(p.take_late_step().map(|c| c.t));
    }
    (steps, late)
}

/// [`walk_with`] the default settings.
fn walk(
    seconds: f64,
    amplitude: impl Fn(f64) -> f64,
    pitch: impl Fn(f64) -> Option<f64>,
    tilt: impl Fn(f64) -> Option<f64>,
) -> (Vec<f64>, Vec<f64>) {
    walk_with(PllConfig::default(), seconds, amplitude, pitch, tilt)
}

#[test]
fn a_lone_cycle_of_motion_on_a_limb_between_a_standing_and_a_stepless_one_is_no_step() {
    let f = 1.8;
    let trough = |k: f64| (k - 0.5) / f;
    // Standing over the cycles of the 15th and 16th peaks, motion over the 17th's, and over
    // the 18th's either standing again or motion without a step's peak (a phone being taken
    // out); walking again from the 19th.
    let amplitude = |t: f64| {
        if (trough(15.0)..trough(17.0)).contains(&t) {
            0.0
        } else if (trough(17.0)..trough(18.0)).contains(&t) {
            // Rising from nothing at its troughs.
            3.0 * libm::cos(PI * (f * t - 17.0)).powi(2)
        } else {
            3.0
        }
    };
    let shape = |stepless: bool| {
        move |t: f64| {
            let c = (TAU * f * t).cos();
            if (trough(18.0)..trough(19.0)).contains(&t) {
                // Its peak falls where the oscillator's trough is.
                if stepless {
                    -c
                } else {
                    0.0
                }
            } else {
                c
            }
        }
    };
    let run = |cfg: PllConfig, stepless: bool, limb: bool| {
        let s = shape(stepless);
        let (steps, late) = walk_with(
            cfg,
            20.0,
            |t| amplitude(t) * s(t),
            |_| None,
            |_| limb.then_some(0.0),
        );
        let mut all = steps;
        all.extend(late);
        all.sort_by(f64::total_cmp);
        all
    };
    let on = PllConfig::default();
    let off = PllConfig {
        lone_step_confirm: false,
        ..on
    };
    let has = |v: &[f64], k: f64| v.iter().any(|&t| (t - k / f).abs() < 0.1);
    // On a limb, followed by motion without a step: no step; followed by standing, or off
    // a limb, or with the rule off, the step counts (as the paper).
    assert!(!has(&run(on, true, true), 17.0));
    assert!(has(&run(on, false, true), 17.0));
    assert!(has(&run(on, true, false), 17.0));
    assert!(has(&run(off, true, true), 17.0));
    // The step held and given back comes a cycle late, and every later step counts.
    let level = run(off, false, true);
    assert_eq!(run(on, false, true), level);
    assert!(has(&level, 19.0) && has(&run(on, true, true), 19.0));
}

#[test]
fn the_cycle_in_which_the_phone_leaves_the_thigh_is_no_step() {
    // The thigh's pitch swings ±15° at the stride frequency, 30° over each step's cycle.
    let swing = |t: f64| Some(15.0 * (std::f64::consts::PI * 1.8 * t).sin());
    // Every step, the late ones (a step after a refused cycle comes a cycle late) with them.
    let all = |(mut steps, late): (Vec<f64>, Vec<f64>)| {
        steps.extend(late);
        steps.sort_by(f64::total_cmp);
        steps
    };
    let level = all(walk(20.0, |_| 3.0, swing, |_| Some(0.0)));
    // From 10 s on the axis tilts by `tilt` and stays tilted: the first cycle over which it
    // exceeds 15° is refused, and no other (the phone is elsewhere now).
    for (tilt, lost) in [(10.0, 0), (20.0, 1)] {
        let steps = all(walk(
            20.0,
            |_| 3.0,
            swing,
            |t| Some(if t < 10.0 { 0.0 } else { tilt }),
        ));
        assert_eq!(steps.len() + lost, level.len(), "tilt {tilt}°: {steps:?}");
    }
    // Tilted for a second at 6 s and at 12 s, level between: each departure costs a step.
    let tilt = |t: f64| {
        Some(if (6.0..7.0).contains(&t) || (12.0..13.0).contains(&t) {
            30.0
        } else {
            0.0
        })
    };
    let steps = all(walk(20.0, |_| 3.0, swing, tilt));
    assert_eq!(steps.len() + 2, level.len(), "{steps:?}");
    let counted_in = |a: f64, b: f64| steps.iter().any(|&t| t > a && t < b);
    assert!(counted_in(7.5, 11.5) && counted_in(13.5, 20.0), "{steps:?}");
}

#[test]
fn a_cycle_tilted_alone_between_level_ones_is_a_step_on_the_thigh() {
    let f = 1.8;
    let trough = |k: f64| (k - 0.5) / f;
    let swing = |t: f64| Some(15.0 * (PI * f * t).sin());
    let all = |(mut steps, late): (Vec<f64>, Vec<f64>)| {
        steps.extend(late);
        steps.sort_by(f64::total_cmp);
        steps
    };
    let level = all(walk(20.0, |_| 3.0, swing, |_| Some(0.0)));
    // The 11th step's cycle tilts the axis by 20° (a brisk step's hip), the next is level
    // again: the step counts, a cycle late.
    let once = |after: f64| {
        move |t: f64| {
            // Inside the cycle: the sample at its trough ends the cycle before.
            Some(if (trough(11.0) + 0.02..trough(12.0)).contains(&t) {
                20.0
            } else if t >= trough(12.0) {
                after
            } else {
                0.0
            })
        }
    };
    let steps = all(walk(20.0, |_| 3.0, swing, once(0.0)));
    assert_eq!(steps.len(), level.len(), "{steps:?}");
    assert!(
        steps.iter().any(|&t| (t - 11.0 / f).abs() < 0.05),
        "{steps:?}"
    );
    // Staying at 12°, under the 15° that refuses a cycle but over the level's 10°: the phone
    // has left the thigh, and the tilted cycle's step is lost.
    let steps = all(walk(20.0, |_| 3.0, swing, once(12.0)));
    assert_eq!(steps.len() + 1, level.len(), "{steps:?}");
}

#[test]
fn a_quiet_first_step_counts_when_the_limb_swung_over_it() {
    let f = 1.8;
    // The first judged cycle, around the peak at 1/f, at 0.3 of the walk's amplitude: its
    // RMS is 0.3 σ, below the σ-relative gate's 0.5.
    let amplitude = |t: f64| if t < 1.5 / f { 0.9 } else { 3.0 };
    let thigh = |a: f64| move |t: f64| Some(a * (std::f64::consts::PI * f * t).sin());
    let (steps, first) = walk(6.0, amplitude, thigh(15.0), |_| Some(0.0));
    assert!(
        first.len() == 1 && (first[0] - 1.0 / f).abs() < 0.02,
        "{first:?}"
    );
    assert!((steps[0] - 2.0 / f).abs() < 0.02, "{steps:?}");
    // Without a leg pitch, or with a limb that barely swings (10° over a step, a hand's
    // rocking), the quiet cycle stays out.
    assert!(walk(6.0, amplitude, |_| None, |_| None).1.is_empty());
    assert!(walk(6.0, amplitude, thigh(5.0), |_| Some(0.0)).1.is_empty());
    // The quiet cycle runs from 0.5/f to 1.5/f. Its swing as a share of the next cycle's: a
    // trailing thigh's, which only extends, 0.45, counts; 0.3 does not.
    let first_share = |k: f64| {
        move |t: f64| {
            let k = if t < 1.5 / f { k } else { 1.0 };
            Some(15.0 * k * (std::f64::consts::PI * f * t).sin())
        }
    };
    assert_eq!(
        walk(6.0, amplitude, first_share(0.45), |_| Some(0.0))
            .1
            .len(),
        1
    );
    assert!(walk(6.0, amplitude, first_share(0.3), |_| Some(0.0))
        .1
        .is_empty());
    // The pitch known over the quiet cycle's last half only: not weighed, though the swing
    // there is half of the next cycle's (a phone handled in the hand, its rotation's axis
    // dominant by turns, looked so on a hand-held IPIN 2023 walk).
    let known_from = |t0: f64| move |t: f64| (t >= t0 / f).then(|| thigh(15.0)(t)).flatten();
    assert!(walk(6.0, amplitude, known_from(1.0), |_| Some(0.0))
        .1
        .is_empty());
}

#[test]
fn a_far_legs_quiet_step_counts_between_two_counted_steps_on_a_thigh() {
    let f = 1.8;
    // The near leg's cycles (even peaks) at 3 m/s², the far leg's (odd) at 1.2 m/s²: RMS
    // 0.85 m/s², 0.4 σ_z, under the σ-relative gate. The walk stops after the 19th peak, a far
    // leg's, and the phone rests.
    let run = |thigh: bool| {
        let mut p = Pll::new(PllConfig::default());
        let mut all = Vec::new();
        for i in 1..1500 {
            let t = i as f64 / 100.0;
            let k = (t * f).round() as i64;
            let a = match k {
                k if k > 19 => 0.0,
                k if k % 2 == 0 => 3.0,
                _ => 1.2,
            };
            let c = p.push(&DetectorInput {
                t,
                dt: 0.01,
                up: a * (TAU * f * t).cos(),
                mean: 0.0,
                sigma: 3.0 / 2f64.sqrt(),
                motion: Motion::Walking,
                cadence_hz: Some(f),
                pitch_deg: None,
                axis_tilt_sin: thigh.then_some(0.0),
                pocket: false,
            });
            all.extend(c.map(|c| c.t));
            all.extend(p.take_late_step().map(|c| c.t));
        }
        all.sort_by(f64::total_cmp);
        all
    };
    let has = |v: &[f64], k: i64| v.iter().any(|&t| (t - k as f64 / f).abs() < 0.1);
    let (thigh, hand) = (run(true), run(false));
    // On a thigh every step from the 4th to the 18th counts; off a limb only the near leg's.
    for k in 4..=18 {
        assert!(has(&thigh, k), "peak {k}: {thigh:?}");
        assert_eq!(has(&hand, k), k % 2 == 0, "peak {k}: {hand:?}");
    }
    // The last step, a far leg's, counts by the same leg's share now that the one before it
    // counted; the resting cycles after it do not.
    assert!(has(&thigh, 19) && !has(&hand, 19), "{thigh:?}");
    assert!(thigh.iter().all(|&t| t < 19.5 / f), "{thigh:?}");
}
