//! Heading of each step from the horizontal acceleration in the navigation frame.
//!
//! - [`tip_to_tail`]: Basso 2016 Algorithm 1 (second-order Fourier over the last stride, tip and
//!   tail of the pseudo-ellipse).
//! - [`closed_form`]: Basso 2021 §2.2.3–2.2.4, eqs. 6–22 (first harmonic over the last step, the
//!   time of maximal planar acceleration in closed form).
//! - [`pca`]: principal component of the horizontal acceleration over a 2 s window, the literature
//!   baseline (Steinhoff & Schiele 2010) that Basso 2016 §I argues against.
//!
//! # Angles
//! Headings are compass headings in radians, clockwise from north, in [0, 2π). Averages of two
//! headings are circular means ([`crate::engine::math::circular_mean2`]), so 350° and 10° average
//! to 0°, never 180°.
//!
//! # The 180° ambiguity
//! An axis of the horizontal acceleration only gives a *line* of motion. Basso 2016 §III says the
//! tip lies "on the acceleration phase" but gives no computable rule, and the 2021 closed form
//! returns one of two opposite maxima depending on where the step window starts. We resolve the
//! direction the same way for all three methods, from gait kinematics: the pelvis moves as an
//! inverted pendulum, so its height is lowest and its forward speed highest at double support,
//! where the vertical acceleration peaks. With a_up ∝ cos ωt the forward acceleration is
//! ∝ −sin ωt, that is, proportional to +d a_up/dt. So the forward direction u is the one for which
//! ∫ (a_h · u) (d a_up/dt) dt > 0 over the window. For the Fourier methods this integral is
//! evaluated on the coefficients at the step frequency: ∫ = (T/2)·ω·(p·d − q·c) with (p, q) the
//! cos/sin coefficients of a_h·u and (c, d) those of a_up ([`forward_sign`]).

pub mod closed_form;
pub mod pca;
pub mod tip_to_tail;

use super::types::{positive, ConfigError};
use std::collections::VecDeque;
use std::f64::consts::TAU;

/// One sample in the navigation frame, as kept in the heading window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NavSample {
    /// Time, s.
    pub t: f64,
    /// East acceleration, m/s².
    pub e: f64,
    /// North acceleration, m/s².
    pub n: f64,
    /// Vertical linear acceleration, m/s², up positive.
    pub up: f64,
}

impl NavSample {
    fn lerp(a: &NavSample, b: &NavSample, t: f64) -> NavSample {
        let w = if b.t > a.t {
            (t - a.t) / (b.t - a.t)
        } else {
            0.0
        };
        NavSample {
            t,
            e: a.e + w * (b.e - a.e),
            n: a.n + w * (b.n - a.n),
            up: a.up + w * (b.up - a.up),
        }
    }
}

/// Which heading method to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadingMethod {
    /// Basso 2016 Algorithm 1.
    TipToTail2016,
    /// Basso 2021 closed form.
    ClosedForm2021,
    /// PCA over a window.
    Pca,
}

/// Settings of the heading stage.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct HeadingConfig {
    /// The method.
    pub method: HeadingMethod,
    /// Average the last two single-step directions (A-HE, Basso 2016 Algorithm 1 step e; Basso
    /// 2021 end of §2.2.3). Default on.
    pub average_two: bool,
    /// PCA window, s (2 s, "commonly used" per Basso 2016 §I).
    pub pca_window_s: f64,
    /// Steer the heading with the device's own yaw between steps (see [`YawAid`]); `None`
    /// uses the acceleration heading of each step alone, as the papers do.
    pub yaw_aid: Option<YawAid>,
}

/// Yaw-aided heading: our addition to the papers, measured on the Microsoft indoor traces.
///
/// Basso's methods find the direction of walking afresh at every step from the acceleration, for
/// a phone in a trouser pocket, where the device's own yaw says nothing about where the walker
/// goes. A phone held flat in front of the body to read the screen is different: the top of the
/// phone *is* the way forward, and the acceleration methods are poor there (the hand damps the
/// pelvis motion; on the 24 hand-held Microsoft walks tip-to-tail headings are off by 20–40° per
/// segment with occasional 180° flips). So:
/// - **Reading pose** (screen up, tilted less than [`YawAid::reading_tilt_deg`] from level): the
///   step's heading is the device's yaw ψ, the twist of the attitude about the vertical,
///   2·atan2(q_z, q_w) (swing–twist decomposition; [`device_twist`]). Measured: waypoint p75
///   5.9 m against 8.7 m for tip-to-tail alone.
/// - **Otherwise**, by default, the papers' acceleration heading. With
///   [`YawAid::learn_offset`] the engine instead walks along ψ̄ + δ: ψ integrated from the
///   attitude increments about the vertical and averaged over two steps, δ = θ̄ − ψ̄ learnt on
///   straight steps ([`YawAid::straight_deg`]) as a circular exponential mean over
///   [`YawAid::steps`] steps with an outlier gate ([`YawOffset`]). It is off by default because on
///   simulated pockets it made straight walks worse (tip-to-tail 0.5° → 7° mean error): the
///   device yaw sampled at the step instants carries the thigh's sway, which two steps do not
///   cancel exactly.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct YawAid {
    /// Time constant of the offset estimate, steps.
    pub steps: f64,
    /// Outlier gate, degrees.
    pub gate_deg: f64,
    /// Largest yaw change from the previous step for the step to update the offset, degrees.
    pub straight_deg: f64,
    /// Largest tilt of the screen from facing up for the reading pose, degrees; `0` disables it.
    pub reading_tilt_deg: f64,
    /// Outside the reading pose, learn the offset δ and walk along ψ̄ + δ (off by default: on
    /// simulated pockets it made straight walks worse, see the module notes).
    pub learn_offset: bool,
}

impl Default for YawAid {
    fn default() -> Self {
        YawAid {
            steps: 10.0,
            gate_deg: 60.0,
            straight_deg: 10.0,
            reading_tilt_deg: 35.0,
            learn_offset: false,
        }
    }
}

impl Default for HeadingConfig {
    fn default() -> Self {
        HeadingConfig {
            method: HeadingMethod::TipToTail2016,
            average_two: true,
            pca_window_s: 2.0,
            yaw_aid: Some(YawAid::default()),
        }
    }
}

impl HeadingConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("heading.pca_window_s", self.pca_window_s)?;
        if let Some(a) = &self.yaw_aid {
            positive("heading.yaw_aid.steps", a.steps)?;
            positive("heading.yaw_aid.gate_deg", a.gate_deg)?;
            positive("heading.yaw_aid.straight_deg", a.straight_deg)?;
        }
        Ok(())
    }

    /// How far back the window buffer must reach, s, given a step period.
    pub fn history_s(&self) -> f64 {
        // Two strides of the slowest walking (2 × 2 × 1/1.2 Hz) or the PCA window, plus the
        // motion detector's look-back.
        (4.0f64).max(self.pca_window_s) + 2.0
    }
}

/// The device's yaw: the twist of the device → ENU attitude about the vertical, compass radians
/// (clockwise from north, like every heading here), or `None` when ill-conditioned (see
/// [`YawAid`]).
pub fn device_twist(q: &nalgebra::UnitQuaternion<f64>) -> Option<f64> {
    let (w, z) = (q.w, q.k);
    if w * w + z * z < 0.1 {
        return None;
    }
    // 2·atan2(z, w) is counter-clockwise about up; a compass heading turns the other way.
    Some(crate::engine::math::wrap_2pi(-2.0 * libm::atan2(z, w)))
}

/// Whether the phone is in the reading pose: screen up, tilted less than
/// [`YawAid::reading_tilt_deg`] from level.
pub fn reading_pose(q: &nalgebra::UnitQuaternion<f64>, aid: &YawAid) -> bool {
    let up = (q * nalgebra::Vector3::z()).z;
    up > libm::cos(aid.reading_tilt_deg.to_radians())
}

/// The running estimate of δ, the angle from the device's yaw to the direction of walking.
#[derive(Debug, Clone, Default)]
pub struct YawOffset {
    sum: (f64, f64),
    n: f64,
    rejected: f64,
}

impl YawOffset {
    /// The estimate, radians, once a step has been seen.
    pub fn get(&self) -> Option<f64> {
        (self.n > 0.0 && (self.sum.0 != 0.0 || self.sum.1 != 0.0))
            .then(|| libm::atan2(self.sum.1, self.sum.0))
    }

    /// Feeds one step's δ = θ̄ − ψ̄.
    pub fn update(&mut self, cfg: &YawAid, delta: f64) {
        if let Some(cur) = self.get() {
            let off = crate::engine::math::wrap_pi(delta - cur).abs();
            if self.n >= cfg.steps && off > cfg.gate_deg.to_radians() {
                self.rejected += 1.0;
                if self.rejected >= cfg.steps {
                    *self = YawOffset::default();
                } else {
                    return;
                }
            }
        }
        self.rejected = 0.0;
        self.n += 1.0;
        let k = 1.0 / self.n.min(cfg.steps);
        let (s, c) = libm::sincos(delta);
        self.sum = (
            self.sum.0 + k * (c - self.sum.0),
            self.sum.1 + k * (s - self.sum.1),
        );
    }
}

/// Fourier coefficients of the three navigation-frame channels at one harmonic.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Harmonic {
    /// cos coefficients (east, north, up).
    pub alpha: [f64; 3],
    /// sin coefficients (east, north, up).
    pub beta: [f64; 3],
}

/// Computes, over the window [t0, t1] of period T = t1 − t0, the coefficients
/// α_n = (2/T)∫ a(τ) cos(nωτ) dτ and β_n = (2/T)∫ a(τ) sin(nωτ) dτ (τ = t − t0, ω = 2π/T) for
/// n = 1 and 2 (Basso 2016 §III; Basso 2021 eqs. 8 and 13), by the trapezoidal rule on the
/// irregular samples, with the end values interpolated at t0 and t1.
/// Returns `None` when the buffer does not cover the window or has fewer than 4 samples in it.
pub fn fourier(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> Option<[Harmonic; 2]> {
    let period = t1 - t0;
    let first = buf.front()?;
    let last = buf.back()?;
    if !(period > 0.0) || first.t > t0 || last.t < t1 {
        return None;
    }
    let start = buf.partition_point(|s| s.t <= t0);
    let end = buf.partition_point(|s| s.t < t1);
    if end < start + 2 || start == 0 || end >= buf.len() {
        return None;
    }
    let w = TAU / period;
    // Trapezoidal rule written as a weighted sum: ∫ f ≈ Σ wᵢ fᵢ with wᵢ = (τᵢ₊₁ − τᵢ₋₁)/2 (half
    // intervals at the ends), over the interpolated end points and the samples between them. The
    // phasor (cos ωτ, sin ωτ) is rotated from point to point by the small angle ω·Δτ.
    let p0 = NavSample::lerp(&buf[start - 1], &buf[start], t0);
    let p1 = NavSample::lerp(&buf[end - 1], &buf[end], t1);
    let mut acc = [[0.0f64; 4]; 3];
    let mut add = |p: &NavSample, weight: f64, (c1, s1): (f64, f64)| {
        let trig = [c1, s1, c1 * c1 - s1 * s1, 2.0 * s1 * c1];
        for (a, v) in acc.iter_mut().zip([p.e, p.n, p.up]) {
            let vw = v * weight;
            for j in 0..4 {
                a[j] += vw * trig[j];
            }
        }
    };
    let mut phasor = (1.0f64, 0.0f64);
    let rotate = |(c, s): (f64, f64), dt: f64| {
        let (ds, dc) = crate::engine::math::sincos_increment(w * dt);
        (c * dc - s * ds, s * dc + c * ds)
    };
    let (mut prev_t, mut cur) = (t0, p0);
    for n in buf.range(start..end).chain(std::iter::once(&p1)) {
        add(&cur, 0.5 * (n.t - prev_t), phasor);
        phasor = rotate(phasor, n.t - cur.t);
        prev_t = cur.t;
        cur = *n;
    }
    add(&cur, 0.5 * (cur.t - prev_t), phasor);
    let scale = 2.0 / period;
    let coef = |j: usize| acc.map(|a| a[j] * scale);
    Some([
        Harmonic {
            alpha: coef(0),
            beta: coef(1),
        },
        Harmonic {
            alpha: coef(2),
            beta: coef(3),
        },
    ])
}

/// Returns +1 or −1: the sign that makes the horizontal unit vector `u` = (east, north) point
/// forward, from the harmonic `h` at the step frequency (see the module documentation).
pub fn forward_sign(h: &Harmonic, u: (f64, f64)) -> f64 {
    let p = h.alpha[0] * u.0 + h.alpha[1] * u.1;
    let q = h.beta[0] * u.0 + h.beta[1] * u.1;
    let (c, d) = (h.alpha[2], h.beta[2]);
    if p * d - q * c >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Step boundaries handed to a heading method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepWindow {
    /// End of the step before the previous one, t_{k−2}.
    pub t_km2: f64,
    /// End of the previous step, t_{k−1}.
    pub t_km1: f64,
    /// End of this step, t_k.
    pub t_k: f64,
}

/// Single-step heading (before any averaging) by the configured method, radians from north.
pub fn single_step(cfg: &HeadingConfig, buf: &VecDeque<NavSample>, w: StepWindow) -> Option<f64> {
    match cfg.method {
        HeadingMethod::TipToTail2016 => tip_to_tail::heading(buf, w),
        HeadingMethod::ClosedForm2021 => closed_form::heading(buf, w),
        HeadingMethod::Pca => pca::heading(buf, w.t_k - cfg.pca_window_s, w.t_k),
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn fourier_recovers_coefficients_on_irregular_samples() {
        let (t0, t1) = (10.0, 10.6);
        let w = TAU / (t1 - t0);
        let mut buf = VecDeque::new();
        let mut t = 9.9;
        let mut i = 0u32;
        while t < 10.7 {
            let tau = t - t0;
            buf.push_back(NavSample {
                t,
                e: 1.5 * (w * tau).cos() - 0.5 * (2.0 * w * tau).sin(),
                n: 0.7 * (w * tau).sin() + 0.2,
                up: 2.0 * (2.0 * w * tau).cos(),
            });
            i += 1;
            t += 0.004 + 0.002 * ((i * 7919) % 13) as f64 / 13.0;
        }
        let h = fourier(&buf, t0, t1).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() < 0.01;
        assert!(
            close(h[0].alpha[0], 1.5) && close(h[1].beta[0], -0.5),
            "{h:?}"
        );
        assert!(
            close(h[0].beta[1], 0.7) && close(h[0].alpha[1], 0.0),
            "{h:?}"
        );
        assert!(close(h[1].alpha[2], 2.0), "{h:?}");
    }

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
    fn forward_sign_follows_inverted_pendulum() {
        // a_up = cos ωt, forward (north) a = −sin ωt.
        let h = Harmonic {
            alpha: [0.0, 0.0, 1.0],
            beta: [0.0, -1.0, 0.0],
        };
        assert_eq!(forward_sign(&h, (0.0, 1.0)), 1.0);
        assert_eq!(forward_sign(&h, (0.0, -1.0)), -1.0);
    }
}
