//! The phone's attitude, angular velocity and acceleration at one instant of the walk.
//! May import: `engine` and `io`.
//!
//! [`Scenario::kinematics`] builds a [`PhoneMotion`], the attitude and the pocket's place as
//! functions of a small time offset around the instant, and differentiates them: the angular
//! velocity from the attitude's derivative, the lever arm's acceleration from the place's second
//! derivative. The gait's own accelerations (the pelvis, the path) and those of the opt-in
//! models (real-shaped ends, the phone handled) are added to it.

use super::carry::{self, Carry};
use super::{amplitudes, body, ends, rx, ry, rz, Gait, Scenario, State, ThighModel, Timeline};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use std::f64::consts::{FRAC_PI_2, TAU};

impl Scenario {
    /// World attitude, world angular velocity and world acceleration of the phone. `ext` (the
    /// timeline, the body's slow motions and the time) turns on the opt-in models: the realistic
    /// thigh, stairs, sitting and real-shaped ends; without it the historic model runs untouched.
    pub(super) fn kinematics(
        &self,
        st: &State,
        mount: &Matrix3<f64>,
        ext: Option<(&Timeline, &body::Body, f64)>,
    ) -> (Matrix3<f64>, Vector3<f64>, Vector3<f64>) {
        let m = PhoneMotion::new(self, st, mount, ext);
        let r = m.attitude(0.0);
        // Angular velocity from the attitude's derivative: [ω]× = Ṙ Rᵀ (central difference of an
        // analytic function of time; error O(h²)).
        let h = 1e-4;
        let rdot = (m.attitude(h) - m.attitude(-h)) / (2.0 * h);
        let skew = rdot * r.transpose();
        let w_world = Vector3::new(
            0.5 * (skew[(2, 1)] - skew[(1, 2)]),
            0.5 * (skew[(0, 2)] - skew[(2, 0)]),
            0.5 * (skew[(1, 0)] - skew[(0, 1)]),
        );
        let mut a = Vector3::zeros();
        if st.gait.moving() {
            m.add_gait_accel(&mut a);
        }
        m.add_lever_accel(&mut a);
        m.add_ends_accel(&mut a);
        if m.handled {
            let tt = st.tau;
            a += Vector3::new(
                0.3 * libm::sin(TAU * 0.9 * tt),
                0.25 * libm::sin(TAU * 0.6 * tt + 2.0),
                0.35 * libm::sin(TAU * 1.3 * tt + 0.7),
            );
        }
        (r, w_world, a)
    }
}

/// The phone's motion around one instant of the walk: its angles, attitude and place as
/// functions of a time offset `dt` from the instant (s), for the derivatives of
/// [`Scenario::kinematics`].
struct PhoneMotion<'a> {
    sc: &'a Scenario,
    st: &'a State,
    /// The phone's resting mount (see [`Scenario::mount`]).
    mount: &'a Matrix3<f64>,
    /// The opt-in models' timeline, slow motions and time (see [`Scenario::kinematics`]).
    ext: Option<(&'a Timeline, &'a body::Body, f64)>,
    /// Real-shaped ends ([`ends`]), when the scenario asks for them: the body and the time.
    ends: Option<(&'a body::Body, f64)>,
    /// The time, when the scenario changes carrying mode mid-walk ([`carry::Switch`]).
    switching: Option<f64>,
    /// Step rate, rad/s.
    omega: f64,
    /// Half the step phase, rad: the stride's phase, to which the angles are tied (pelvis yaw
    /// and thigh flexion both peak at the heel strike of the pocket leg).
    half: f64,
    /// Amplitudes of the pelvis's yaw and the sinusoidal thigh's pitch, rad.
    yaw_amp: f64,
    pitch_amp: f64,
    /// Whether the realistic thigh ([`ThighModel::Gait`]) gives the pitch.
    real: bool,
    /// Whether the phone is handled (turned over in the hand).
    handled: bool,
    /// Whether the walker stands swaying (real-shaped ends, standing still).
    swaying: bool,
    /// Scale of the carrying mode's limb swing: 0 standing, 1 walking, 1.4 running.
    k_limb: f64,
}

impl<'a> PhoneMotion<'a> {
    fn new(
        sc: &'a Scenario,
        st: &'a State,
        mount: &'a Matrix3<f64>,
        ext: Option<(&'a Timeline, &'a body::Body, f64)>,
    ) -> Self {
        let w = &sc.walker;
        let (yaw_amp, pitch_amp) = if st.gait.moving() {
            let k = if st.gait == Gait::Run { 1.4 } else { 1.0 };
            (
                w.waist_yaw_deg.to_radians(),
                k * w.thigh_pitch_deg.to_radians(),
            )
        } else {
            (0.0, 0.0)
        };
        let ends = ext.filter(|_| sc.real_ends).map(|(_, body, t)| (body, t));
        let k_limb = if !st.gait.moving() {
            0.0
        } else if st.gait == Gait::Run {
            1.4
        } else {
            1.0
        };
        PhoneMotion {
            sc,
            st,
            mount,
            ext,
            ends,
            switching: ext.filter(|_| !sc.switches.is_empty()).map(|(_, _, t)| t),
            omega: TAU * st.f,
            half: 0.5 * st.phi,
            yaw_amp,
            pitch_amp,
            real: matches!(w.thigh, ThighModel::Gait(_)),
            handled: st.gait == Gait::Handled,
            swaying: ends.is_some() && st.gait == Gait::Still,
            k_limb,
        }
    }

    /// The bout's envelope: every swing fades in and out with the bout under real-shaped ends.
    fn env(&self, dt: f64) -> f64 {
        self.ends
            .map_or(1.0, |(body, t)| body.walk_envelope(t + dt))
    }

    /// The pelvis's yaw, rad.
    fn waist(&self, dt: f64) -> f64 {
        match self.ext {
            // With the realistic thigh the pelvis's rotation fades in and out with the bout too.
            Some((_, body, t)) if self.real || self.sc.real_ends => {
                self.yaw_amp
                    * body.walk_envelope(t + dt)
                    * libm::cos(self.half + 0.5 * self.omega * dt)
            }
            _ => self.yaw_amp * libm::cos(self.half + 0.5 * self.omega * dt),
        }
    }

    /// The path's heading (compass), rad, to second order in `dt`.
    fn path(&self, dt: f64) -> f64 {
        let st = self.st;
        st.psi + st.psi_dot * dt + 0.5 * st.psi_ddot * dt * dt
    }

    /// The thigh's pitch, rad: the body frame's y is the walker's left, so flexion is a
    /// negative rotation about it.
    fn pitch(&self, dt: f64) -> f64 {
        match self.ext {
            Some((tl, body, t)) if self.real => -self.sc.thigh_deg(tl, body, t + dt).to_radians(),
            _ => self.pitch_amp * self.env(dt) * libm::cos(self.half + 0.5 * self.omega * dt),
        }
    }

    /// The mount, part-way out of the pocket while it is taken out.
    fn mount_at(&self, dt: f64) -> Matrix3<f64> {
        match self.ends {
            Some((body, t)) if self.sc.carry == Carry::Pocket => ends::taken_out(body, t + dt)
                .map_or(*self.mount, |w| {
                    let hand = Carry::Texting.mount().unwrap_or(*self.mount);
                    ends::mount_between(self.mount, &hand, w)
                }),
            _ => *self.mount,
        }
    }

    /// The limb's rotation in carrying mode `c`: out of the pocket the thigh's pitch is replaced
    /// by the carrying mode's limb.
    fn limb_of(&self, c: Carry, dt: f64) -> Matrix3<f64> {
        if c == Carry::Pocket {
            ry(self.pitch(dt))
        } else {
            c.limb(self.st.phi + self.omega * dt, self.k_limb * self.env(dt))
        }
    }

    /// The limb's length from its pivot to the phone in carrying mode `c`, m.
    fn lever_of(&self, c: Carry) -> f64 {
        if c == Carry::Pocket {
            self.sc.walker.lever_m
        } else {
            c.lever_m()
        }
    }

    /// A change of mode mid-walk ([`carry::Switch`]): the modes moved from and to, and how far
    /// the move has gone (0 to 1).
    fn phase(&self, dt: f64) -> (Carry, Carry, f64) {
        let sc = self.sc;
        self.switching.map_or((sc.carry, sc.carry, 0.0), |t| {
            carry::phase(sc.carry, &sc.switches, t + dt)
        })
    }

    /// The resting mount of carrying mode `c`.
    fn mount_of(&self, c: Carry) -> Matrix3<f64> {
        c.mount().unwrap_or_else(|| self.sc.pocket_mount())
    }

    /// The phone's attitude in the world (ENU).
    fn attitude(&self, dt: f64) -> Matrix3<f64> {
        let st = self.st;
        let heading = self.path(dt) + self.waist(dt);
        if self.switching.is_some() {
            return rz(FRAC_PI_2 - heading) * self.switching_attitude(dt);
        }
        let mut r = rz(FRAC_PI_2 - heading) * self.limb_of(self.sc.carry, dt);
        if self.handled {
            let tt = st.tau + dt;
            r *= rx(0.25 * libm::sin(TAU * 0.31 * tt)) * ry(0.2 * libm::sin(TAU * 0.17 * tt + 1.0));
        }
        if let (true, Some((_, t))) = (self.swaying, self.ends) {
            r *= ends::sway(t + dt).0;
        }
        r * self.mount_at(dt)
    }

    /// The limb and mount's rotation across a change of carrying mode, before the heading.
    ///
    /// Each mode's attitude is a quaternion whose sign is its resting mount's, and the two signs
    /// are chosen by the resting mounts alone: the slerp then follows one path all through the
    /// move. (The shortest path, nalgebra's, flipped from sample to sample between the ear and
    /// the swinging hand, whose mounts are about 180° apart, and the attitude's derivative gave
    /// rates of thousands of rad/s.)
    fn switching_attitude(&self, dt: f64) -> Matrix3<f64> {
        let (from, to, k) = self.phase(dt);
        let q = |c: Carry| {
            let rest = UnitQuaternion::from_matrix(&self.mount_of(c))
                .into_inner()
                .coords;
            let q = UnitQuaternion::from_matrix(&(self.limb_of(c, dt) * self.mount_of(c)));
            let q = q.into_inner().coords;
            (if q.dot(&rest) < 0.0 { -q } else { q }, rest)
        };
        let ((a, rest_a), (b, rest_b)) = (q(from), q(to));
        let b = if rest_a.dot(&rest_b) < 0.0 { -b } else { b };
        let v = nalgebra::Unit::new_unchecked(a).slerp(&nalgebra::Unit::new_unchecked(b), k);
        let r = UnitQuaternion::new_unchecked(nalgebra::Quaternion::from(v.into_inner()));
        r.to_rotation_matrix().into_inner()
    }

    /// The phone's place relative to the hip (the pocket's offset along the thigh, or the
    /// carrying mode's anchor and lever), in the world (ENU), m.
    fn offset(&self, dt: f64) -> Vector3<f64> {
        let heading = self.path(dt) + self.waist(dt);
        if self.switching.is_some() {
            let (from, to, k) = self.phase(dt);
            let place = |c: Carry| {
                c.anchor(self.sc.left_pocket)
                    + self.limb_of(c, dt) * Vector3::new(0.0, 0.0, -self.lever_of(c))
            };
            return rz(FRAC_PI_2 - heading) * ((1.0 - k) * place(from) + k * place(to));
        }
        let lever_m = self.lever_of(self.sc.carry);
        rz(FRAC_PI_2 - heading) * self.limb_of(self.sc.carry, dt) * Vector3::new(0.0, 0.0, -lever_m)
    }

    /// Adds the walking or running gait's acceleration: the pelvis (vertical bounce, forward
    /// surge, lateral sway) and the path (dv/dt along, v dψ/dt across).
    fn add_gait_accel(&self, a: &mut Vector3<f64>) {
        let (st, w) = (self.st, &self.sc.walker);
        let (av, af, al) = amplitudes(st.gait, st.f, w.sway);
        let (from, to, k) = self.phase(0.0);
        let b = ((1.0 - k) * from.bounce() + k * to.bounce()) * self.env(0.0);
        let (av, af, al) = (b * av, b * af, b * al);
        let body_heading = st.psi + self.waist(0.0);
        let fwd = Vector3::new(libm::sin(body_heading), libm::cos(body_heading), 0.0);
        let path_fwd = Vector3::new(libm::sin(st.psi), libm::cos(st.psi), 0.0);
        let right = Vector3::new(libm::cos(st.psi), -libm::sin(st.psi), 0.0);
        let (sp, cp) = libm::sincos(st.phi);
        *a += Vector3::z() * (av * cp + 0.3 * av * libm::cos(2.0 * st.phi + 0.5));
        *a += fwd * (-af * sp);
        *a += right * (al * libm::sin(self.half));
        let sl = &w.step_length;
        let v = sl.length(st.f) * st.f;
        let dv = (sl.length(st.f + 1e-4) * (st.f + 1e-4) - v) / 1e-4 * st.fdot;
        let (v, dv) = match self.ext {
            Some((_, body, t)) => body.speed(t, v, dv),
            None => (v, dv),
        };
        // Getting under way and braking: the speed follows the envelope.
        let (v, dv) = match self.ends {
            Some((body, t)) => (
                v * self.env(0.0),
                dv * self.env(0.0) + v * ends::envelope_rate(body, t),
            ),
            None => (v, dv),
        };
        *a += path_fwd * dv + right * (v * st.psi_dot);
    }

    /// Adds the lever's acceleration, the second derivative of the phone's place by central
    /// differences, and with the opt-in models the climb and the hip's drop sitting down.
    fn add_lever_accel(&self, a: &mut Vector3<f64>) {
        let hh = 1e-3;
        if let Some((_, body, t)) = self.ext {
            // The lever at all times (the thigh moves sitting down), the climb, the hip's drop.
            *a += (self.offset(hh) - 2.0 * self.offset(0.0) + self.offset(-hh)) / (hh * hh);
            *a += Vector3::z() * (body.stairs_accel(t) - body.sit_drop_m * body.sit(t).2);
        } else if self.st.gait.moving() {
            *a += (self.offset(hh) - 2.0 * self.offset(0.0) + self.offset(-hh)) / (hh * hh);
        }
    }

    /// Adds the real-shaped ends' accelerations: the body settling, the standing sway and the
    /// phone taken out of the pocket.
    fn add_ends_accel(&self, a: &mut Vector3<f64>) {
        let Some((body, t)) = self.ends else { return };
        let turn = rz(FRAC_PI_2 - self.st.psi);
        *a += Vector3::z() * ends::settle(body, t);
        if self.swaying {
            *a += turn * ends::sway(t).1;
        }
        if self.sc.carry == Carry::Pocket {
            *a += turn * ends::take_out_accel(body, t);
        }
    }
}
