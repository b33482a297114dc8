//! The heading stage's tests, on constructed steps.

use super::*;
use crate::engine::math::wrap_pi;

#[test]
fn a_limb_that_turns_its_way_forward_is_not_averaged_across_the_turn() {
    // Steps of 0.5 s (the inverted pendulum: up cos ωt, forward −sin ωt) turning right by
    // 10° a step from north; the thigh says forward, then back.
    let w = std::f64::consts::TAU / 0.5;
    let buf: VecDeque<NavSample> = (0..300)
        .map(|i| {
            let t = 0.01 * i as f64;
            let phi = 20f64.to_radians() * t;
            NavSample {
                e: -(w * t).sin() * phi.sin(),
                n: -(w * t).sin() * phi.cos(),
                up: (w * t).cos(),
                ..NavSample::empty(t)
            }
        })
        .collect();
    let mut h = Heading::new(HeadingConfig::default());
    let mut step = |k: f64, forward: (f64, f64)| {
        h.push(&StepInput {
            buf: &buf,
            window: StepWindow {
                t_km2: 0.5 * (k - 2.0),
                t_km1: 0.5 * (k - 1.0),
                t_k: 0.5 * k,
            },
            continued: true,
            has_heading: true,
            carry: Some(CarryMode::Pocket),
            limb_forward: Some(forward),
            judged_at: None,
            behind_hip: false,
        })
        .used
        .unwrap()
    };
    // Step k's middle faces 10k − 5°.
    let off = |a: f64, want: f64| wrap_pi(a - want.to_radians()).to_degrees().abs();
    assert!(off(step(3.0, (0.0, 1.0)), 25.0) < 10.0);
    assert!(off(step(4.0, (0.0, 1.0)), 35.0) < 10.0);
    // Averaged with the step before, the turned step would walk 90° off (−52°).
    let turned = step(5.0, (0.0, -1.0));
    assert!(off(turned, 225.0) < 10.0, "{}", turned.to_degrees());
}
