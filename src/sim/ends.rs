//! Real-shaped starts and stops (opt-in, [`super::Scenario::real_ends`]): the standing sway, a
//! first step from stillness, a deceleration step, the body settling, and the phone taken out
//! of the pocket. The steps at both ends of a short real walk were
//! off by up to 3 while the simulator, which started and stopped at full stride, counted them
//! exactly.
//! May import: `engine` and `io`.
//!
//! # Model
//! - **First and last steps.** Every swing of the gait (the pelvis's accelerations, the waist's
//!   yaw, the thigh's or the limb's swing) is scaled by the bout's envelope
//!   ([`super::body::Body::walk_envelope`]: a quintic smoothstep over the first step and over
//!   the last one), and so is the forward speed, which adds the push of getting under way
//!   (v·ė, about +0.7 m/s² at 1.8 Hz) and the braking of the deceleration step. The first and
//!   the last true steps fall where the envelope is ½: half a stride's strength.
//! - **Settling.** After the last step the body comes to rest with a damped vertical bounce,
//!   [`SETTLE_MS2`]·e^(−τ/[`SETTLE_TAU_S`])·sin(2π·[`SETTLE_HZ`]·τ), τ from the bout's end.
//! - **Standing sway** (still segments): the quiet stance's sway, horizontal accelerations of
//!   0.05 m/s² at 0.3 Hz and 0.04 m/s² at 0.7 Hz, vertical 0.03 m/s² at 1.1 Hz, and a tilt of
//!   ±0.4° at 0.3 Hz (Winter 1995 gives the centre of pressure 5–10 mm at 0.1–1 Hz; these
//!   are a few times that, for the fidgeting of a person waiting).
//! - **Taking the phone out** ([`super::Gait::TakeOut`], pocket only): over the segment the
//!   phone turns from its pocket mount to the texting hold (slerp by the smoothstep), rises by
//!   [`LIFT_M`] (forward by [`LIFT_FORWARD_M`]) on the same smoothstep, and is jerked along the
//!   thigh at 3 Hz (±[`PULL_MS2`]) while it comes free. Afterwards it stays in the hand.

use super::body::{s5, s5dd, Body};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::f64::consts::{PI, TAU};

/// Peak of the settling bounce, m/s².
pub const SETTLE_MS2: f64 = 1.0;
/// Its frequency, Hz.
pub const SETTLE_HZ: f64 = 2.0;
/// Its decay, s.
pub const SETTLE_TAU_S: f64 = 0.3;
/// The hand lifts the phone this far from the pocket, m.
pub const LIFT_M: f64 = 0.5;
/// And this far forward, m.
pub const LIFT_FORWARD_M: f64 = 0.25;
/// The pull that frees the phone from the pocket, m/s².
pub const PULL_MS2: f64 = 1.5;

/// The envelope's rate at `t`, 1/s (central difference of the smooth envelope).
pub fn envelope_rate(body: &Body, t: f64) -> f64 {
    let h = 1e-4;
    (body.walk_envelope(t + h) - body.walk_envelope(t - h)) / (2.0 * h)
}

/// The settling bounce's vertical acceleration at `t`, m/s² (0 during a bout and before the
/// first one ends).
pub fn settle(body: &Body, t: f64) -> f64 {
    let i = body.bouts.partition_point(|b| b.1 <= t);
    let Some(&(_, t1, _)) = i.checked_sub(1).map(|k| &body.bouts[k]) else {
        return 0.0;
    };
    if body.bouts.get(i).is_some_and(|b| b.0 <= t) {
        return 0.0;
    }
    let tau = t - t1;
    if tau > 10.0 * SETTLE_TAU_S {
        return 0.0;
    }
    SETTLE_MS2 * libm::exp(-tau / SETTLE_TAU_S) * libm::sin(TAU * SETTLE_HZ * tau)
}

/// The standing sway at `t`: the tilt (body frame) and the acceleration (body frame, m/s²).
pub fn sway(t: f64) -> (Matrix3<f64>, Vector3<f64>) {
    let s = |f: f64, p: f64| libm::sin(TAU * f * t + p);
    let tilt = Rotation3::from_euler_angles(
        0.4f64.to_radians() * s(0.3, 0.5),
        0.3f64.to_radians() * s(0.23, 1.7),
        0.0,
    )
    .into_inner();
    let a = Vector3::new(
        0.05 * s(0.3, 0.0) + 0.04 * s(0.7, 2.1),
        0.04 * s(0.37, 1.0),
        0.03 * s(1.1, 0.3),
    );
    (tilt, a)
}

/// How far the phone is out of the pocket at `t`: 0 in it, 1 in the hand, the smoothstep in
/// between; `None` before the first take-out.
pub fn taken_out(body: &Body, t: f64) -> Option<f64> {
    let &(t0, t1) = body.take_outs.iter().take_while(|k| k.0 <= t).last()?;
    Some(s5((t - t0) / (t1 - t0)))
}

/// The acceleration of taking the phone out at `t`, body frame, m/s²: the lift's second
/// derivative and the pull.
pub fn take_out_accel(body: &Body, t: f64) -> Vector3<f64> {
    let Some(&(t0, t1)) = body.take_outs.iter().find(|k| k.0 <= t && t < k.1) else {
        return Vector3::zeros();
    };
    let d = t1 - t0;
    let x = (t - t0) / d;
    let lift = s5dd(x) / (d * d);
    let pull = PULL_MS2 * libm::sin(TAU * 3.0 * (t - t0)) * libm::sin(PI * x.min(0.5) * 2.0);
    Vector3::new(LIFT_FORWARD_M * lift, 0.0, LIFT_M * lift + pull)
}

/// The mount part-way out of the pocket: `w` of the way from `pocket` to `hand`.
pub fn mount_between(pocket: &Matrix3<f64>, hand: &Matrix3<f64>, w: f64) -> Matrix3<f64> {
    let q = |m: &Matrix3<f64>| UnitQuaternion::from_matrix(m);
    q(pocket)
        .slerp(&q(hand), w)
        .to_rotation_matrix()
        .into_inner()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Segment;

    #[test]
    fn the_settling_follows_each_bout_and_the_take_out_ends_in_the_hand() {
        let body = Body::new(
            &[
                Segment::still(1.0),
                Segment::walk(2.0, 2.0),
                Segment::still(1.0),
                Segment {
                    gait: crate::sim::Gait::TakeOut,
                    ..Segment::still(1.5)
                },
                Segment::still(1.0),
            ],
            1.0,
            0.0,
        );
        assert_eq!(settle(&body, 0.5), 0.0);
        assert_eq!(settle(&body, 2.0), 0.0, "walking");
        assert!(settle(&body, 3.1) > 0.5, "{}", settle(&body, 3.1));
        assert_eq!(taken_out(&body, 3.5), None);
        assert!((taken_out(&body, 4.75).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(taken_out(&body, 6.0), Some(1.0));
        // The lift's acceleration integrates to no speed at the end.
        let (mut v, dt) = (0.0, 1e-3);
        let mut t = 4.0;
        while t < 5.5 {
            v += take_out_accel(&body, t + 0.5 * dt).x * dt;
            t += dt;
        }
        assert!(v.abs() < 1e-3, "{v}");
        let p = Matrix3::identity();
        let h = crate::sim::Carry::Texting.mount().unwrap();
        assert!((mount_between(&p, &h, 1.0) - h).norm() < 1e-9);
    }
}
