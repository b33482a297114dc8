//! The yaw aid's tests: each place's rule on constructed steps.

use super::*;
use std::f64::consts::{FRAC_PI_2, PI};

#[test]
fn device_twist_is_the_compass_heading_of_the_top_of_a_flat_phone() {
    use nalgebra::{UnitQuaternion, Vector3};
    // Flat, face up, top (device y) turned to the east: a rotation of −90° about up.
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -std::f64::consts::FRAC_PI_2);
    let top = q * Vector3::y();
    assert!((top - Vector3::x()).norm() < 1e-12);
    let psi = device_twist(&q).unwrap();
    assert!((psi - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "{psi}");
    assert!(reading_pose(&q, &YawAid::default()));
    // Upright in a pocket: not the reading pose; upside down: no twist at all.
    let upright = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.5);
    assert!(!reading_pose(&upright, &YawAid::default()));
    let flipped = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 3.1);
    assert_eq!(device_twist(&flipped), None);
}

#[test]
fn a_late_step_in_the_hand_walks_the_way_the_phone_pointed_just_after_it() {
    use crate::engine::heading::NavSample;
    use nalgebra::{UnitQuaternion, Vector3};
    // The walker turns at 0.5 rad/s; the buffer runs to 3 s, sampled at 100 Hz.
    let buf: std::collections::VecDeque<NavSample> = (0..=300)
        .map(|i| {
            let t = 0.01 * f64::from(i);
            NavSample {
                yaw: 0.5 * t,
                ..NavSample::empty(t)
            }
        })
        .collect();
    // A step that ended at 1.0 s, given at 3.0 s: its moment is 1.3 s, and the phone has
    // turned by 0.5 · 1.7 rad since. One given within the usual latency is on time.
    let then = late_hand_moment(&buf, 1.0).unwrap();
    assert!((then.t - 1.0 - HAND_LATENCY_S).abs() < 1e-12, "{then:?}");
    let turned = buf.back().unwrap().yaw - then.yaw;
    assert!(
        (turned - 0.5 * (3.0 - 1.0 - HAND_LATENCY_S)).abs() < 1e-9,
        "{turned}"
    );
    assert_eq!(late_hand_moment(&buf, 2.8), None);
    // Flat in the hand, the top of the phone at 1.2 rad now: the late step goes 0.85 rad
    // before that.
    let attitude = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -1.2);
    let x = SteerInput {
        attitude,
        yaw: 1.5,
        up: Some(Vector3::z()),
        previous_up: Some(Vector3::z()),
        carry: Some(crate::engine::carry::CarryMode::Hand),
        continued: true,
        averaged: None,
        settled: true,
        unled: None,
        screen: None,
        screen_at_step: None,
        turned_since: turned,
        behind_hip: false,
    };
    let aid = YawAid::default();
    let late = Steer::default().push(&aid, &x).unwrap();
    assert!((late.heading - (1.2 - turned)).abs() < 1e-9, "{late:?}");
    assert!(late.own);
    let on_time = Steer::default()
        .push(
            &aid,
            &SteerInput {
                turned_since: 0.0,
                behind_hip: false,
                ..x
            },
        )
        .unwrap();
    assert!((on_time.heading - 1.2).abs() < 1e-9, "{on_time:?}");
}

#[test]
fn yaw_offset_ignores_a_flip_and_follows_a_moved_phone() {
    let aid = YawAid::default();
    let mut o = YawOffset::default();
    for i in 0..30 {
        // 0.5 rad with one 180° flip among them.
        let d = if i == 12 { 0.5 + PI } else { 0.5 };
        o.update(&aid, d);
    }
    assert!((o.get().unwrap() - 0.5).abs() < 1e-9, "{:?}", o.get());
    // The phone moves to another pocket: δ jumps by 2 rad and stays there.
    for _ in 0..25 {
        o.update(&aid, 2.5);
    }
    assert!((o.get().unwrap() - 2.5).abs() < 0.05, "{:?}", o.get());
}

#[test]
fn with_learn_offset_the_yaw_walks_with_the_offset_the_straight_strides_taught() {
    use crate::engine::carry::CarryMode;
    use nalgebra::{UnitQuaternion, Vector3};
    let aid = YawAid {
        learn_offset: true,
        ear_offset: false,
        pocket_offset: false,
        ..YawAid::default()
    };
    // Upright at the ear: not the reading pose, screen facing sideways.
    let attitude = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.5);
    let upright = attitude.inverse() * Vector3::z();
    let up = Some(upright);
    let x = |yaw: f64, carry: CarryMode, averaged: f64, previous_up| SteerInput {
        attitude,
        yaw,
        up,
        previous_up,
        carry: Some(carry),
        continued: true,
        averaged: Some(averaged),
        unled: None,
        settled: true,
        screen: None,
        screen_at_step: None,
        turned_since: 0.0,
        behind_hip: false,
    };
    let mut steer = Steer::default();
    // Walking straight, the acceleration heading 0.5 rad off the yaw, either way by 0.3.
    let mut got = Vec::new();
    for k in 0..12 {
        let scatter = if k % 2 == 0 { 0.3 } else { -0.3 };
        got.push(steer.push(&aid, &x(1.0, CarryMode::Ear, 1.5 + scatter, up)));
    }
    // Not before offset_min_steps straight strides (the first two have no stride behind them).
    assert!(got[..8].iter().all(Option::is_none), "{got:?}");
    let last = got[11].expect("steered");
    assert!(!last.own && !last.sided);
    assert!((last.heading - 1.5).abs() < 0.05, "{last:?}");
    // In a turn the yaw carries the walk at once, with the offset held.
    let turned = steer
        .push(&aid, &x(1.6, CarryMode::Ear, 0.0, up))
        .expect("steered");
    assert!((turned.heading - (1.3 + 0.5)).abs() < 0.05, "{turned:?}");
    // Taught in another mode, the offset starts again.
    assert_eq!(steer.push(&aid, &x(1.6, CarryMode::Pocket, 2.0, up)), None);
    // At the ear by default (the screen's rule), a phone being moved is not steady.
    let mut moved = Steer::default();
    let screen = Some(ScreenStride {
        yaw: 1.0,
        up: upright,
    });
    let unsteady = SteerInput {
        screen,
        screen_at_step: screen,
        turned_since: 0.0,
        behind_hip: false,
        unled: Some((1.5, false)),
        ..x(1.0, CarryMode::Ear, 1.5, Some(Vector3::z()))
    };
    for _ in 0..12 {
        assert_eq!(moved.push(&YawAid::default(), &unsteady), None);
    }
}

#[test]
fn in_a_pocket_the_screen_walks_with_the_offset_every_settled_step_taught() {
    use crate::engine::carry::CarryMode;
    use nalgebra::{UnitQuaternion, Vector3};
    let aid = YawAid::default();
    // Upright in a pocket, screen facing forward.
    let attitude = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.4);
    let up = attitude.inverse() * Vector3::z();
    let stride = |yaw: f64, up: Vector3<f64>| Some(ScreenStride { yaw, up });
    let x =
        |screen: f64, unled: f64, up: Vector3<f64>, carry: CarryMode, settled: bool| SteerInput {
            attitude,
            yaw: 0.0,
            up: Some(up),
            previous_up: Some(up),
            carry: Some(carry),
            continued: true,
            averaged: Some(unled),
            unled: Some((unled, false)),
            settled,
            screen: stride(screen, up),
            screen_at_step: stride(screen + 0.1, up),
            turned_since: 0.0,
            behind_hip: false,
        };
    let mut steer = Steer::default();
    // Turning all the while, the acceleration heading 0.5 rad off the screen, either way by
    // 0.2: every step teaches.
    let mut got = Vec::new();
    for k in 0..10 {
        let screen = 0.2 * f64::from(k);
        let scatter = if k % 2 == 0 { 0.2 } else { -0.2 };
        got.push(steer.push(
            &aid,
            &x(screen, screen + 0.5 + scatter, up, CarryMode::Pocket, true),
        ));
    }
    assert!(got[..6].iter().all(Option::is_none), "{got:?}");
    let last = got[9].expect("steered");
    assert!(last.sided && !last.own, "{last:?}");
    // Walked along the screen's yaw at the step's middle (1.8 + 0.1) plus δ.
    assert!((last.heading - 2.4).abs() < 0.05, "{last:?}");
    // Behind the hip, in a back pocket, along the stride before the step: 1.8 + δ.
    let next = x(1.8, 2.3, up, CarryMode::Pocket, true);
    let (mut front, mut back) = (steer.clone(), steer.clone());
    let led = front.push(&aid, &next).expect("steered");
    let behind = SteerInput {
        behind_hip: true,
        ..next
    };
    let unled = back.push(&aid, &behind).expect("steered");
    assert!((led.heading - 2.4).abs() < 0.05, "{led:?}");
    assert!((unled.heading - 2.3).abs() < 0.05, "{unled:?}");
    // A step held at a bout's opening teaches nothing, even half a turn off.
    for _ in 0..10 {
        let held = steer.push(&aid, &x(2.0, 2.0 + 0.5 + PI, up, CarryMode::Pocket, false));
        assert!(
            (held.expect("steered").heading - 2.6).abs() < 0.05,
            "{held:?}"
        );
    }
    // A spell at the ear leaves the pocket's δ as it was.
    assert!(!steer
        .push(&aid, &x(2.0, 0.0, up, CarryMode::Ear, true))
        .is_some_and(|s| s.sided));
    let back = steer
        .push(&aid, &x(2.0, 2.5, up, CarryMode::Pocket, true))
        .expect("kept");
    assert!((back.heading - 2.6).abs() < 0.05, "{back:?}");
    // The phone sits another way in the pocket: δ restarts.
    let turned = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.0) * up;
    let mut reseated = x(2.0, 1.0, turned, CarryMode::Pocket, true);
    reseated.previous_up = Some(turned);
    assert_eq!(steer.push(&aid, &reseated), None);
}

#[test]
fn a_swinging_hand_walks_along_its_screen_though_the_arm_swings_between_steps() {
    use crate::engine::carry::CarryMode;
    use nalgebra::{UnitQuaternion, Vector3};
    // Held down at the side, top up, screen towards the thigh; at each step the arm is at
    // one end of its swing, 35° forward or back about the screen's normal, while the
    // stride's mean stays where the hand holds it.
    let attitude = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2);
    let mean_up = attitude.inverse() * Vector3::z();
    let swung = |k: i32| {
        let a = if k % 2 == 0 { 0.6 } else { -0.6 };
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), a) * mean_up
    };
    let x = |k: i32, screen: f64, unled: f64, carry: CarryMode| SteerInput {
        attitude,
        yaw: 0.0,
        up: Some(swung(k)),
        previous_up: Some(swung(k - 1)),
        carry: Some(carry),
        continued: true,
        averaged: Some(unled),
        unled: Some((unled, false)),
        settled: true,
        screen: Some(ScreenStride {
            yaw: screen,
            up: mean_up,
        }),
        screen_at_step: None,
        turned_since: 0.0,
        behind_hip: false,
    };
    let aid = YawAid::default();
    let mut steer = Steer::default();
    let mut got = Vec::new();
    // Turning; the acceleration heading a quarter turn off the screen, give or take 0.2.
    for k in 0..12 {
        let screen = 0.1 * f64::from(k);
        let scatter = if k % 3 == 0 { 0.2 } else { -0.1 };
        got.push(steer.push(
            &aid,
            &x(k, screen, screen + FRAC_PI_2 + scatter, CarryMode::Swinging),
        ));
    }
    let last = got[11].expect("steered");
    assert!(last.sided && !last.own, "{last:?}");
    assert!((last.heading - (1.1 + FRAC_PI_2)).abs() < 0.1, "{last:?}");
    // Off, the swinging hand keeps the acceleration heading.
    let off = YawAid {
        swinging_offset: false,
        ..aid
    };
    assert_eq!(
        Steer::default().push(&off, &x(0, 0.0, 1.0, CarryMode::Swinging)),
        None
    );
    // The same swing in a pocket is a phone being moved: no heading from the screen.
    let mut pocket = Steer::default();
    assert!((0..12).all(|k| pocket
        .push(&aid, &x(k, 0.0, FRAC_PI_2, CarryMode::Pocket))
        .is_none()));
}
