//! How the phone is carried when it is not in a trouser pocket: in the hand with the screen up
//! (texting or reading), swinging in the hand, at the ear (calling), or in a bag.
//! May import: `engine` and `io`.
//!
//! # Model
//! Body frame as in [`super::pose`]: x forward, y left, z up. Each mode has a mount (device →
//! body) and a limb: a rotation of the mount about a pivot and the pivot's lever, both at the
//! stride's phase, on top of the pelvis's accelerations (scaled by [`Carry::bounce`]: the arm
//! damps them in the hand, the neck at the ear).
//! - **Texting**: top forward, tilted up by [`TEXT_TILT_DEG`] (the Microsoft traces hold the
//!   phone flat, the IPIN ones at 30–60°), screen up; the hand trembles by ±1.5° at the step
//!   and at the stride frequency. No lever.
//! - **Swinging**: the arm swings ±[`ARM_SWING_DEG`] about the shoulder, [`ARM_LEVER_M`] above
//!   the hand, at the stride frequency and opposite to the leg on its side; the phone is gripped
//!   top forward and down by 45°, screen out of the body (the Oxford swinging traces read
//!   gravity at (−0.8, −0.6, 0) in the device frame, this mount at (−0.71, −0.71, 0)).
//! - **Ear**: screen against the head, top up and back by [`EAR_TILT_DEG`] (the line from the
//!   ear to the mouth); the head nods by ±1°.
//! - **Bag**: a shoulder bag at the hip swings on a 0.35 m strap at the stride frequency, as the
//!   pelvis sways, ±6° forward and ±4° sideways; the phone lies in it screen forward, leaning 25°
//!   sideways and turned 35° about the vertical. (A sideways swing at the step frequency, tried
//!   first, put 3 m/s² of lateral acceleration into the step's harmonic and turned the
//!   acceleration heading by a constant 64°.)
//!
//! [`Carry::Pocket`] is the pocket model of [`super`] and its [`super::PocketPose`]s, untouched.
//!
//! # A change of mode mid-walk ([`Switch`], opt-in: [`super::Scenario::switches`])
//! Over the switch's seconds the walk goes on while the hand moves the phone: its attitude in
//! the body (limb ∘ mount) is the slerp from the old mode's to the new one's, and its place (the
//! limb's pivot, [`Carry::anchor`], plus the lever) and the pelvis's share ([`Carry::bounce`])
//! blend linearly, all by the quintic smoothstep of the time; the move's acceleration is the
//! second derivative of that place. The pocket's pivot is the hip; the texting hand's is in front
//! of the chest, the swinging arm's the shoulder, the ear's the head, the bag's its strap's hook.

use nalgebra::{Matrix3, Vector3};

/// Tilt of the texting phone's top above the horizontal, degrees.
pub const TEXT_TILT_DEG: f64 = 30.0;
/// Amplitude of the swinging arm, degrees (walking; running swings 1.4 times as far).
pub const ARM_SWING_DEG: f64 = 30.0;
/// Shoulder to hand, m.
pub const ARM_LEVER_M: f64 = 0.65;
/// Tilt of the phone at the ear from the vertical, top backwards, degrees.
pub const EAR_TILT_DEG: f64 = 40.0;

/// How the phone is carried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Carry {
    /// In a front trouser pocket ([`super::PocketPose`]).
    #[default]
    Pocket,
    /// In the hand, screen up, in front of the body.
    Texting,
    /// In the hand of a swinging arm.
    Swinging,
    /// At the ear.
    Ear,
    /// In a shoulder bag.
    Bag,
}

fn rot(axis: Vector3<f64>, a: f64) -> Matrix3<f64> {
    nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), a).into_inner()
}

impl Carry {
    /// Every mode.
    pub const ALL: [Carry; 5] = [
        Carry::Pocket,
        Carry::Texting,
        Carry::Swinging,
        Carry::Ear,
        Carry::Bag,
    ];

    /// Lower-case name.
    pub fn as_str(self) -> &'static str {
        match self {
            Carry::Pocket => "pocket",
            Carry::Texting => "texting",
            Carry::Swinging => "swinging",
            Carry::Ear => "ear",
            Carry::Bag => "bag",
        }
    }

    /// The mount (device → body), for the modes other than the pocket.
    pub fn mount(self) -> Option<Matrix3<f64>> {
        let from = |x: Vector3<f64>, y: Vector3<f64>| {
            let (x, y) = (x.normalize(), y.normalize());
            Matrix3::from_columns(&[x, y, x.cross(&y)])
        };
        let deg = |d: f64| libm::sincos(d.to_radians());
        match self {
            Carry::Pocket => None,
            Carry::Texting => {
                let (s, c) = deg(TEXT_TILT_DEG);
                Some(from(Vector3::new(0.0, -1.0, 0.0), Vector3::new(c, 0.0, s)))
            }
            Carry::Swinging => {
                let (s, c) = deg(45.0);
                Some(from(Vector3::new(-s, 0.0, -c), Vector3::new(c, 0.0, -s)))
            }
            Carry::Ear => {
                let (s, c) = deg(EAR_TILT_DEG);
                Some(from(Vector3::new(-c, 0.0, -s), Vector3::new(-s, 0.0, c)))
            }
            Carry::Bag => {
                let base = from(Vector3::new(0.0, 1.0, 0.0), Vector3::new(0.0, 0.0, 1.0));
                Some(
                    rot(Vector3::z(), 35f64.to_radians())
                        * rot(Vector3::x(), 25f64.to_radians())
                        * base,
                )
            }
        }
    }

    /// The pelvis's accelerations as the phone feels them.
    pub fn bounce(self) -> f64 {
        match self {
            Carry::Pocket | Carry::Swinging | Carry::Bag => 1.0,
            Carry::Texting => 0.8,
            Carry::Ear => 0.75,
        }
    }

    /// The limb's rotation (body frame) at step phase `phi` (rad, 2π per step) of a gait whose
    /// swings are `k` times a walk's (0 when still). Every swing is at rest where a bout starts
    /// and ends (φ ≡ π mod 2π), so the attitude is continuous across them.
    pub fn limb(self, phi: f64, k: f64) -> Matrix3<f64> {
        let half = 0.5 * phi;
        let d = |a: f64| k * a.to_radians();
        match self {
            Carry::Pocket => Matrix3::identity(),
            Carry::Texting => {
                rot(Vector3::y(), d(1.5) * libm::sin(phi))
                    * rot(Vector3::x(), d(1.5) * libm::cos(half))
            }
            // Opposite to the right leg: forward (a negative rotation about y) at the left
            // leg's heel strike.
            Carry::Swinging => rot(Vector3::y(), d(ARM_SWING_DEG) * libm::cos(half)),
            Carry::Ear => rot(Vector3::y(), d(1.0) * libm::sin(phi)),
            Carry::Bag => {
                rot(Vector3::y(), d(6.0) * libm::cos(half))
                    * rot(Vector3::x(), d(4.0) * libm::cos(half))
            }
        }
    }

    /// The limb's pivot in the body frame (x forward, y left, z up), m from the middle of the
    /// pelvis: the hip of the pocket's side (`left_pocket`), in front of the chest, the right
    /// shoulder, the right ear, the strap's hook.
    pub fn anchor(self, left_pocket: bool) -> Vector3<f64> {
        match self {
            Carry::Pocket => Vector3::new(0.0, if left_pocket { 0.1 } else { -0.1 }, 0.0),
            Carry::Texting => Vector3::new(0.3, 0.0, 0.5),
            Carry::Swinging => Vector3::new(0.0, -0.2, 0.55),
            Carry::Ear => Vector3::new(0.0, -0.08, 0.75),
            Carry::Bag => Vector3::new(0.0, -0.15, 0.35),
        }
    }

    /// The limb's lever below its pivot, m (the shoulder, the strap's hook; 0 for a hand or a
    /// head that carries the phone with the trunk).
    pub fn lever_m(self) -> f64 {
        match self {
            Carry::Swinging => ARM_LEVER_M,
            Carry::Bag => 0.35,
            Carry::Pocket | Carry::Texting | Carry::Ear => 0.0,
        }
    }
}

/// A change of carrying mode while the walk goes on: from `t_s` (simulation time, s) over
/// `seconds` the phone moves to `to` (see the module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    /// When the hand starts to move the phone, s.
    pub t_s: f64,
    /// How long the move takes, s.
    pub seconds: f64,
    /// The new mode.
    pub to: Carry,
}

/// The modes at `t` and how far the move between them has gone: (from, to, w), w the quintic
/// smoothstep from 0 to 1 over the switch; before the first switch (`first`, `first`, 0).
/// `switches` are in time order.
pub fn phase(first: Carry, switches: &[Switch], t: f64) -> (Carry, Carry, f64) {
    let k = switches.partition_point(|s| s.t_s <= t);
    match k.checked_sub(1) {
        None => (first, first, 0.0),
        Some(i) => {
            let s = &switches[i];
            let from = i.checked_sub(1).map_or(first, |j| switches[j].to);
            (from, s.to, super::body::s5((t - s.t_s) / s.seconds))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mounts_are_rotations_and_gravity_sits_where_the_real_phones_read_it() {
        for c in Carry::ALL.into_iter().skip(1) {
            let m = c.mount().unwrap();
            assert!((m.transpose() * m - Matrix3::identity()).norm() < 1e-12);
            assert!((m.determinant() - 1.0).abs() < 1e-12, "{}", c.as_str());
        }
        // The accelerometer at rest reads +up: Mᵀ ẑ in device coordinates.
        let up = |c: Carry| c.mount().unwrap().transpose() * Vector3::z();
        assert!(up(Carry::Texting).z > 0.8, "screen up");
        let s = up(Carry::Swinging);
        assert!(s.x < -0.6 && s.y < -0.6 && s.z.abs() < 1e-12, "{s}");
        let e = up(Carry::Ear);
        assert!(
            e.y > 0.7 && e.z.abs() < 1e-12,
            "top up, screen sideways: {e}"
        );
    }

    #[test]
    fn a_switch_moves_the_phone_from_one_mount_to_the_other() {
        let sw = [Switch {
            t_s: 10.0,
            seconds: 2.0,
            to: Carry::Ear,
        }];
        assert_eq!(
            phase(Carry::Texting, &sw, 5.0),
            (Carry::Texting, Carry::Texting, 0.0)
        );
        assert_eq!(
            phase(Carry::Texting, &sw, 11.0),
            (Carry::Texting, Carry::Ear, 0.5)
        );
        assert_eq!(
            phase(Carry::Texting, &sw, 20.0),
            (Carry::Texting, Carry::Ear, 1.0)
        );
        // Gravity in the device, standing before the walk and after it, is each mode's.
        let sc = crate::sim::scenarios::switched_walk(Carry::Texting, Carry::Ear, 1);
        let sim = sc.generate();
        let mean_up = |t0: f64, t1: f64| {
            let v: Vector3<f64> = sim
                .records
                .iter()
                .filter_map(|r| match r {
                    crate::engine::Record::Imu(s) if s.t >= t0 && s.t < t1 => Some(s.accel),
                    _ => None,
                })
                .sum();
            v.normalize()
        };
        let up = |c: Carry| c.mount().unwrap().transpose() * Vector3::z();
        let end = sc.duration_s();
        assert!((mean_up(0.5, 2.5) - up(Carry::Texting)).norm() < 0.02);
        assert!((mean_up(end - 2.5, end - 0.5) - up(Carry::Ear)).norm() < 0.02);
    }
}
