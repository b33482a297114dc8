//! Heading of each step from the horizontal acceleration in the navigation frame.
//! May import: the rest of `engine`.
//!
//! - [`tip_to_tail`]: Basso 2016 Algorithm 1 (second-order Fourier over the last stride, tip and
//!   tail of the pseudo-ellipse).
//! - [`closed_form`]: Basso 2021 §2.2.3–2.2.4, eqs. 6–22 (first harmonic over the last step, the
//!   time of maximal planar acceleration in closed form).
//! - [`pca`]: principal component of the horizontal acceleration over a 2 s window, the literature
//!   baseline (Steinhoff & Schiele 2010) that Basso 2016 §I argues against.
//! - [`yaw_aid`] (ours): the device's own yaw in the hand and the reading pose.
//! - [`continuity`] (ours): the heading carried across a change of source or carrying mode.
//! - [`harmonics`]: the Fourier coefficients the methods share, and the pelvis's forward sign.
//! - [`arm`] (ours): the swinging hand's 180°, the arm's pendulum taken out of the pelvis's rule.
//! - [`turn`] (ours): the gyroscope's turn from the heading's window to the step walked.
//! - [`opening`] (ours): a bout's first steps held until a limb or the yaw gives their side.
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
//!
//! A phone on a limb adds a vertical term of its own at the step frequency, in antiphase with the
//! pelvis's (a pendulum is highest at the ends of its swing, which are the heel strikes); with
//! [`HeadingConfig::limb_sign`] the pocket takes the 180° from the thigh's swing and the swinging
//! hand from the pelvis's rule with the arm's term taken out ([`arm`]).

pub mod arm;
pub mod average;
pub mod closed_form;
pub mod continuity;
pub mod harmonics;
pub mod opening;
pub mod pca;
pub mod sign;
pub mod tip_to_tail;
pub mod turn;
pub mod yaw_aid;

pub use harmonics::{forward_sign, forwardness, fourier, fourier_of, Harmonic};
pub use yaw_aid::{device_twist, reading_pose, YawAid, YawOffset};

use super::carry::CarryMode;
use super::math::wrap_2pi;
use super::types::{positive, ConfigError};
use std::collections::VecDeque;

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
    /// The leg pitch, degrees, when known ([`crate::engine::leg_pitch`]).
    pub pitch: Option<f64>,
    /// The sine of how far the limb's swing axis is tilted from the horizontal, while the phone
    /// rides on a thigh ([`crate::engine::leg_pitch::LegPitch::axis_tilt_sin`]).
    pub axis_tilt_sin: Option<f64>,
    /// The device's turn about the vertical since the start, compass radians, unwrapped: the
    /// attitude's increments integrated ([`Heading::push_attitude`]; 0 without an attitude).
    pub yaw: f64,
    /// Up in the device frame, unit, from the attitude (zero without one): where gravity sits
    /// in the device.
    pub device_up: [f64; 3],
    /// The horizontal part (east, north) of the screen's normal, the device's z axis, in the
    /// navigation frame, from the attitude (zero without one): the pocket's yaw reference
    /// ([`yaw_aid::screen_stride`]).
    pub screen: [f64; 2],
    /// The magnetic guard's yaw correction δ when the sample came, radians counter-clockwise
    /// about up (0 without the guard; [`crate::engine::magnetic::Magnetic::correction`]): the
    /// integrated [`NavSample::yaw`] carries its changes.
    pub guard: f64,
    /// The motion detector's σ_z when the sample came, m/s² ([`crate::engine::motion`]): the
    /// onset look-back in a pocket never judges a sample more leniently than the live loop did.
    pub sigma_z: f64,
}

/// The samples `start..end` of `buf` as its contiguous runs, in order: loops over plain slices
/// rather than the buffer's iterator (which checks for the wrap at every sample).
pub(crate) fn runs(buf: &VecDeque<NavSample>, start: usize, end: usize) -> [&[NavSample]; 2] {
    let (head, tail) = buf.as_slices();
    let split = head.len();
    [
        &head[start.min(split)..end.min(split)],
        &tail[start.max(split) - split..end.max(split) - split],
    ]
}

impl NavSample {
    /// A sample at `t` with nothing in it: no acceleration, pitch, turn or attitude (tests
    /// set what they need over it).
    #[cfg(test)]
    pub(crate) fn empty(t: f64) -> Self {
        NavSample {
            t,
            e: 0.0,
            n: 0.0,
            up: 0.0,
            pitch: None,
            axis_tilt_sin: None,
            yaw: 0.0,
            device_up: [0.0; 3],
            screen: [0.0; 2],
            guard: 0.0,
            sigma_z: 0.0,
        }
    }

    /// The sample at `t`, linear between the two around it; `None` outside the buffer.
    pub(crate) fn at(buf: &VecDeque<NavSample>, t: f64) -> Option<NavSample> {
        let i = buf.partition_point(|s| s.t <= t);
        (i > 0 && i < buf.len()).then(|| NavSample::lerp(&buf[i - 1], &buf[i], t))
    }

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
            pitch: a.pitch,
            axis_tilt_sin: a.axis_tilt_sin,
            yaw: a.yaw + w * (b.yaw - a.yaw),
            device_up: a.device_up,
            screen: a.screen,
            guard: a.guard,
            sigma_z: a.sigma_z,
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
    /// Carry the heading across a change of its source or of the carrying mode
    /// ([`continuity`]); `None` lets each source stand alone.
    pub continuity: Option<continuity::Continuity>,
    /// Take the acceleration heading's 180° from the limb the phone rides, not from the
    /// pelvis's vertical phase alone: in a pocket the thigh's forward swing
    /// ([`StepInput::limb_forward`]), in a swinging hand the pelvis's rule with the arm's
    /// pendulum taken out ([`arm`]). Default on.
    pub limb_sign: bool,
    /// Add to the acceleration heading the device's turn from the middle of the windows it was
    /// found over to the middle of the step ([`turn`]). Default on; off, as the papers.
    pub turn_lead: bool,
    /// With [`Self::limb_sign`], hold at most this many of a bout's first steps whose side only
    /// the pelvis gives, until a limb or the device's yaw gives it ([`opening`]); 0 holds none.
    pub opening_steps: usize,
    /// The held steps go as the pelvis voted once [`opening::TRUNK_STEPS`] steps in a row after
    /// the bout's first tilt the phone by less than this, degrees ([`opening::step_tilt_deg`]):
    /// no limb carries it, and none will sign the side. Default 12.5°, half the least stride of
    /// a thigh the leg pitch recognises
    /// ([`crate::engine::leg_pitch::LegPitchConfig::thigh_min_amplitude_deg`], 25°): a step
    /// swings a thigh from one end of its stride to the other, so a phone that tilts less about
    /// its mean is one the thigh's sign will not come for. 0 waits for the limb or the cap.
    pub opening_limb_tilt_deg: f64,
}

impl Default for HeadingConfig {
    fn default() -> Self {
        HeadingConfig {
            method: HeadingMethod::TipToTail2016,
            average_two: true,
            pca_window_s: 2.0,
            yaw_aid: Some(YawAid::default()),
            continuity: Some(continuity::Continuity::default()),
            limb_sign: true,
            turn_lead: true,
            opening_steps: 12,
            opening_limb_tilt_deg: crate::engine::leg_pitch::LegPitchConfig::default()
                .thigh_min_amplitude_deg
                / 2.0,
        }
    }
}

impl HeadingConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("heading.pca_window_s", self.pca_window_s)?;
        if !(self.opening_limb_tilt_deg >= 0.0 && self.opening_limb_tilt_deg <= 90.0) {
            return Err(ConfigError::new(
                "heading.opening_limb_tilt_deg",
                "must be in [0, 90]",
            ));
        }
        if self.opening_steps > opening::MAX_STEPS {
            return Err(ConfigError::new(
                "heading.opening_steps",
                format!("must be at most {}", opening::MAX_STEPS),
            ));
        }
        if let Some(a) = &self.yaw_aid {
            positive("heading.yaw_aid.steps", a.steps)?;
            positive("heading.yaw_aid.pocket_steps", a.pocket_steps)?;
            positive("heading.yaw_aid.gate_deg", a.gate_deg)?;
            positive("heading.yaw_aid.straight_deg", a.straight_deg)?;
            positive("heading.yaw_aid.hand_steady_deg", a.hand_steady_deg)?;
            if !(a.offset_min_steps >= 0.0 && a.offset_min_steps.is_finite()) {
                return Err(ConfigError::new(
                    "heading.yaw_aid.offset_min_steps",
                    "must be a finite number of steps, 0 or more",
                ));
            }
            if !(-1.0..=1.0).contains(&a.hand_screen_up_min) {
                return Err(ConfigError::new(
                    "heading.yaw_aid.hand_screen_up_min",
                    "must be within −1 … 1",
                ));
            }
        }
        if let Some(c) = &self.continuity {
            if c.steps == 0 {
                return Err(ConfigError::new(
                    "heading.continuity.steps",
                    "must be at least 1",
                ));
            }
            positive("heading.continuity.max_gap_s", c.max_gap_s)?;
            positive("heading.continuity.moved_deg", c.moved_deg)?;
            if !(c.lag_s >= 0.0 && c.lag_s <= c.max_gap_s) {
                return Err(ConfigError::new(
                    "heading.continuity.lag_s",
                    "must be in 0 ..= heading.continuity.max_gap_s",
                ));
            }
            for (name, e) in c.errors.named() {
                positive(name, e)?;
            }
            if !(0.0..=1.0).contains(&c.agreement_min) {
                return Err(ConfigError::new(
                    "heading.continuity.agreement_min",
                    "must be within 0 … 1",
                ));
            }
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

/// What the heading stage is given at each step.
#[derive(Debug, Clone, Copy)]
pub struct StepInput<'a> {
    /// The recent samples in the navigation frame.
    pub buf: &'a VecDeque<NavSample>,
    /// The step's boundaries.
    pub window: StepWindow,
    /// The step continues the previous one (no cycle skipped, no stop between them).
    pub continued: bool,
    /// The orientation source gives horizontal axes referenced to a heading.
    pub has_heading: bool,
    /// Where the phone is carried, once decided ([`crate::engine::carry`]).
    pub carry: Option<crate::engine::carry::CarryMode>,
    /// The way forward (east, north) a swinging thigh shows, when the phone rides on one
    /// ([`crate::engine::leg_pitch::LegPitch::forward_axis`]); see [`HeadingConfig::limb_sign`].
    pub limb_forward: Option<(f64, f64)>,
    /// For a step the step detector decided a cycle late, the stage's [`Pose`] when it was
    /// judged: the step's heading takes it, not the latest sample's.
    pub judged_at: Option<Pose>,
    /// The phone rides behind the hip, in a back pocket ([`crate::engine::back_pocket`]): its
    /// path lags the turns, and the pocket's heading is not led to the step's middle.
    pub behind_hip: bool,
}

/// The heading stage's view of the device at one sample ([`Heading::pose`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// The device → ENU attitude, when the orientation source has one.
    pub attitude: Option<nalgebra::UnitQuaternion<f64>>,
    /// The device's yaw integrated from the attitude's increments, compass radians, unwrapped.
    pub yaw: f64,
}

/// One step's heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepHeading {
    /// The heading the step is walked along, rad from north: the yaw aid's, else the (averaged)
    /// acceleration heading, else the last heading known.
    pub used: Option<f64>,
    /// The single-step direction θ_k before averaging, rad from north.
    pub single: Option<f64>,
    /// The step's side is not known yet: it waits, with the steps held before it, for the
    /// next step's [`Self::release`] ([`opening`]).
    pub held: bool,
    /// The steps held before this one are released, turned by 180° when `true`.
    pub release: Option<bool>,
    /// The magnetic guard's correction ([`NavSample::guard`]) at the moment whose yaw the
    /// heading took, when that is not the latest (a late step in the hand,
    /// [`yaw_aid::late_hand_moment`]): the heading without the guard adds it, not the current
    /// one.
    pub guard_then: Option<f64>,
}

/// The heading stage's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HeadingDiagnostics {
    /// The heading of the last step, rad from north.
    pub last_rad: Option<f64>,
    /// The learnt offset δ from the device's yaw to the direction of walking, rad.
    pub yaw_offset_rad: Option<f64>,
    /// The offset added to the acceleration heading since the last change of source or mode
    /// ([`continuity`]), rad.
    pub continuity_offset_rad: f64,
}

/// The heading stage: the configured method at each step, then a chain of stages, each with
/// what it remembers from step to step: the limb's sign ([`sign`]), a bout's opening
/// ([`opening`]), the two-step average (A-HE, [`average`]), the turn lead ([`turn`]), the yaw
/// aid ([`YawAid`]) and the continuity across a change of source or mode ([`continuity`]).
#[derive(Debug, Clone)]
pub struct Heading {
    cfg: HeadingConfig,
    sign: sign::LimbSign,
    opening: opening::Opening,
    average: average::Average,
    turn: turn::TurnLead,
    steer: yaw_aid::Steer,
    carried: continuity::Carried,
    last_used: Option<f64>,
    attitude: Option<nalgebra::UnitQuaternion<f64>>,
    // Device yaw integrated from the attitude increments about the vertical, compass radians,
    // unwrapped.
    yaw: f64,
    // The last steps walked, the latest last.
    recent: VecDeque<continuity::Walked>,
    // Where gravity sat in the device at the last steps, the latest last.
    ups: VecDeque<nalgebra::Vector3<f64>>,
}

/// A step's direction as the opening left it ([`Heading::open`]).
#[derive(Debug, Clone, Copy)]
struct Opened {
    /// The single-step direction, rad from north.
    theta: Option<f64>,
    /// The limb gave its sign, and the step is not held for it.
    by_limb: bool,
    /// The step's side waits for a limb or the yaw.
    waiting: bool,
    /// The steps held were turned by the limb's side.
    turned: bool,
    /// The steps held before are released, turned by 180° when `true`.
    release: Option<bool>,
}

impl Heading {
    /// A stage with validated settings.
    pub fn new(cfg: HeadingConfig) -> Self {
        Heading {
            cfg,
            sign: sign::LimbSign::default(),
            opening: opening::Opening::default(),
            average: average::Average::default(),
            turn: turn::TurnLead::default(),
            steer: yaw_aid::Steer::default(),
            carried: continuity::Carried::default(),
            last_used: None,
            attitude: None,
            yaw: 0.0,
            recent: VecDeque::with_capacity(continuity::KEPT),
            ups: VecDeque::with_capacity(continuity::UPS),
        }
    }

    /// The latest sample's attitude and integrated yaw.
    pub fn pose(&self) -> Pose {
        Pose {
            attitude: self.attitude,
            yaw: self.yaw,
        }
    }

    /// Each sample's device → ENU attitude, when the orientation source has one; the device's
    /// yaw is integrated from its increments.
    #[inline]
    pub fn push_attitude(&mut self, q: Option<nalgebra::UnitQuaternion<f64>>) {
        if let (Some(q), Some(p)) = (&q, &self.attitude) {
            // World-frame increment q·p⁻¹; for a small rotation its vertical component is
            // half the yaw change (counter-clockwise, so subtracted for a compass angle).
            let d = q * p.inverse();
            self.yaw -= 2.0 * d.k * d.w.signum();
        }
        self.attitude = q;
    }

    /// The heading of one step: the method's direction, then the chain sign → opening →
    /// average → turn lead → yaw aid → continuity, and the opening's verdict on the steps held.
    pub fn push(&mut self, step: &StepInput) -> StepHeading {
        let pose = step.judged_at.unwrap_or_else(|| self.pose());
        let up = pose.attitude.map(|q| q.inverse() * nalgebra::Vector3::z());
        let previous_up = self.ups.back().copied();
        if let Some(u) = up {
            if self.ups.len() == continuity::UPS {
                self.ups.pop_front();
            }
            self.ups.push_back(u);
        }
        let theta = if step.has_heading {
            single_step(&self.cfg, step.buf, step.window)
        } else {
            None
        };
        let keep = self.last_used.filter(|_| self.carried.carrying());
        let signed = self.sign.push(self.cfg.limb_sign, step, theta, keep);
        let opened = self.open(step, signed, pose.yaw);
        // A mode whose sign comes from its limb has not settled until the limb gave it.
        let limb_mode = self.cfg.limb_sign
            && matches!(step.carry, Some(CarryMode::Pocket | CarryMode::Swinging));
        let (averaged, two) = self.average.push(
            self.cfg.average_two,
            opened.theta,
            step.continued,
            (limb_mode, opened.by_limb, self.sign.flipped()),
        );
        let unled = averaged.map(|a| (a, two));
        let averaged = self.lead(step, averaged, two);
        // A late step in the hand takes the yaw of its own moment; a step the detector held
        // for a cycle has its own pose already.
        let late = self
            .cfg
            .yaw_aid
            .filter(|a| a.hand_late_yaw && step.judged_at.is_none())
            .and_then(|_| {
                Some((
                    yaw_aid::late_hand_moment(step.buf, step.window.t_k)?,
                    step.buf.back()?.yaw,
                ))
            });
        let steered = match &self.cfg.yaw_aid {
            Some(aid) if step.has_heading => pose.attitude.and_then(|attitude| {
                let x = yaw_aid::SteerInput {
                    attitude,
                    yaw: pose.yaw,
                    up,
                    previous_up,
                    carry: step.carry,
                    continued: step.continued,
                    averaged,
                    unled,
                    settled: !opened.waiting,
                    screen: yaw_aid::screen_stride(step.buf, step.window.t_km2, step.window.t_k),
                    screen_at_step: if self.cfg.turn_lead {
                        yaw_aid::screen_at_step(step.buf, step.window)
                    } else {
                        None
                    },
                    turned_since: late.map_or(0.0, |(then, now)| now - then.yaw),
                    behind_hip: step.behind_hip,
                };
                self.steer.push(aid, &x)
            }),
            _ => None,
        };
        // The hand's yaw is the walker's own way; the yaw with a learnt offset is the
        // acceleration heading's, smoothed, and is carried and opened as that.
        let own = steered.filter(|s| s.own).map(|s| s.heading);
        let h = steered.map(|s| s.heading).or(averaged);
        let walked = self.carry_on(step, own, h, opened.by_limb, limb_mode);
        let sided = steered.filter(|s| s.sided).map(|s| s.heading);
        StepHeading {
            guard_then: late.filter(|_| own.is_some()).map(|(then, _)| then.guard),
            ..self.close(step, opened, sided, walked)
        }
    }

    /// The opening's first part: a new bout releases the last one's held steps; a step whose
    /// side only the pelvis gives waits, chained to the step before; a limb's side turns the
    /// steps held to it.
    fn open(&mut self, step: &StepInput, signed: sign::Signed, yaw: f64) -> Opened {
        let (buf, window) = (step.buf, step.window);
        // A new bout: the last one's held steps go as the pelvis voted.
        let mut release = None;
        if !step.continued {
            release = self.release_held();
            self.opening = opening::Opening::default();
        }
        // A swinging arm's first vote is one stride's, which can point back: it settles a
        // bout's opening from its second.
        let young_arm =
            signed.by_limb && step.carry == Some(CarryMode::Swinging) && self.sign.arm_steps() < 2;
        let waiting = self.cfg.limb_sign
            && self.cfg.opening_steps > 0
            && step.has_heading
            && (!signed.by_limb || young_arm)
            && !self.opening.settled();
        // Held, it is chained as the pelvis's steps are, and not averaged as a limb's.
        let by_limb = signed.by_limb && !waiting;
        let theta = match signed.theta {
            Some(th) if waiting => {
                // The yaw at the step's own time: the onset look-back's steps come together.
                let at = buf.partition_point(|x| x.t < window.t_k);
                let yaw_k = buf.get(at).map_or(yaw, |x| x.yaw);
                self.opening.tilt(
                    opening::step_tilt_deg(buf, window.t_km1, window.t_k),
                    self.cfg.opening_limb_tilt_deg,
                );
                Some(self.opening.chain(th, self.average.last, yaw_k))
            }
            th => th,
        };
        // A limb's side settles the bout: the steps held turn to it before it is averaged.
        let mut turned = false;
        if let (Some(th), Some(l), true) = (theta, self.average.last, by_limb) {
            if self.opening.held() > 0 && libm::cos(th - l) < 0.0 {
                self.turn_held(self.opening.held(), true);
                turned = true;
            }
        }
        Opened {
            theta,
            by_limb,
            waiting,
            turned,
            release,
        }
    }

    /// The averaged heading with the device's turn from the middle of its windows to the middle
    /// of the step ([`turn`]), when configured.
    fn lead(&mut self, step: &StepInput, averaged: Option<f64>, two: bool) -> Option<f64> {
        match averaged {
            Some(a) if self.cfg.turn_lead => {
                let w = step.window;
                let lead =
                    self.turn
                        .push(step.buf, w, turn::window(&self.cfg, w), step.continued, two);
                Some(wrap_2pi(a + lead))
            }
            a => {
                // A step without a direction of its own breaks the run the lead compares.
                self.turn.clear();
                a
            }
        }
    }

    /// The heading `h` carried across a change of its source or of the carrying mode
    /// ([`continuity`]), when configured.
    fn carry_on(
        &mut self,
        step: &StepInput,
        aided: Option<f64>,
        h: Option<f64>,
        by_limb: bool,
        limb_mode: bool,
    ) -> Option<f64> {
        let c = match &self.cfg.continuity {
            Some(c) if step.has_heading => c,
            _ => return h,
        };
        let source = if aided.is_some() {
            continuity::Source::Yaw
        } else {
            continuity::Source::Acceleration
        };
        let settled = source == continuity::Source::Yaw
            || ((step.carry != Some(CarryMode::Hand)
                || !self.cfg.yaw_aid.is_some_and(|a| a.hand_mode))
                && (by_limb || !limb_mode));
        let moved = continuity::moved(&self.ups, c);
        self.carried.push(
            c,
            &continuity::Step {
                source,
                mode: step.carry,
                settled,
                moved,
                t: step.window.t_k,
                heading: h,
            },
            &self.recent,
        )
    }

    /// The opening's second part: a step still waiting is held, or released with those before
    /// as the pelvis voted once held long enough; the first step whose side is known settles
    /// the bout. Then the step is remembered.
    fn close(
        &mut self,
        step: &StepInput,
        opened: Opened,
        aided: Option<f64>,
        walked: Option<f64>,
    ) -> StepHeading {
        let Opened {
            mut theta,
            by_limb,
            waiting,
            turned,
            mut release,
        } = opened;
        let back = |h: Option<f64>| h.map(|h| wrap_2pi(h + std::f64::consts::PI));
        let mut used = walked.or(self.last_used);
        let mut held = false;
        if waiting && aided.is_none() {
            if self.opening.held() + 1 >= self.cfg.opening_steps || self.opening.no_limb() {
                // Held long enough, or no limb carries the phone: this step and those before go
                // as the pelvis voted.
                let n = self.opening.held();
                let turn = self.opening.release_by_vote();
                if n > 0 {
                    self.turn_held(n, turn);
                    release = Some(turn);
                }
                if turn {
                    used = back(used);
                    theta = back(theta);
                }
            } else {
                self.opening.hold();
                held = true;
            }
        } else if !self.opening.settled() {
            // The first step whose side is known: the steps held turn to it (a limb's turned
            // them already).
            if self.opening.held() > 0 {
                let turn = match (used, self.last_used) {
                    (Some(u), Some(l)) => libm::cos(u - l) < 0.0,
                    _ => false,
                };
                self.turn_held(self.opening.held(), turn);
                if turn && waiting {
                    // This step's own direction was chained to theirs.
                    theta = back(theta);
                }
                release = Some(turn != turned);
            }
            self.opening.settle();
        }
        self.average.remember(theta, by_limb);
        if let Some(u) = used {
            self.last_used = used;
            if self.recent.len() == continuity::KEPT {
                self.recent.pop_front();
            }
            self.recent.push_back(continuity::Walked {
                t: step.window.t_k,
                heading: u,
                flipped: self.sign.flipped(),
            });
        }
        StepHeading {
            used,
            single: theta,
            held,
            release,
            guard_then: None,
        }
    }

    /// Releases the steps held at the bout's opening as the pelvis voted ([`opening`]), the
    /// bout then settled; returns whether they turn by 180° (`None`: none were held). The
    /// pipeline calls it when the bout ends without a step that says (a stop, a gap, the end
    /// of the input).
    pub fn release_held(&mut self) -> Option<bool> {
        let n = self.opening.held();
        if n == 0 {
            return None;
        }
        let turn = self.opening.release_by_vote();
        self.turn_held(n, turn);
        Some(turn)
    }

    // The last `n` steps walked (those held) turned by 180°, when `turn`.
    fn turn_held(&mut self, n: usize, turn: bool) {
        if !turn {
            return;
        }
        let back = |h: f64| wrap_2pi(h + std::f64::consts::PI);
        let k = self.recent.len();
        for w in self.recent.range_mut(k.saturating_sub(n)..) {
            w.heading = back(w.heading);
        }
        self.last_used = self.last_used.map(back);
        self.average.last = self.average.last.map(back);
    }

    /// The end of a bout (a stop or a gap): the next step is not averaged with the last one.
    pub fn end_bout(&mut self) {
        self.average.last = None;
        self.steer.end_bout();
        self.turn.clear();
    }

    /// The current values.
    pub fn diagnostics(&self) -> HeadingDiagnostics {
        HeadingDiagnostics {
            last_rad: self.last_used,
            yaw_offset_rad: self.steer.offset(),
            continuity_offset_rad: self.carried.offset(),
        }
    }
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
mod tests;
