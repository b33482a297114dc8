//! The yaw aid, our addition to the papers: the device's own yaw as the step heading in the
//! reading pose, and optionally a learnt offset from it elsewhere (see [`YawAid`]).
//! May import: the rest of `engine`.

use crate::engine::math::wrap_pi;

/// Yaw-aided heading: our addition to the papers.
///
/// Basso's methods find the direction of walking afresh at every step from the acceleration, for
/// a phone in a trouser pocket, where the device's own yaw says nothing about where the walker
/// goes. A phone held flat in front of the body to read the screen is different: the top of the
/// phone *is* the way forward, and the acceleration methods are poor there (the hand damps the
/// pelvis motion, and the headings flip by 180° now and then). So:
/// - **Reading pose** (screen up, tilted less than [`YawAid::reading_tilt_deg`] from level): the
///   step's heading is the device's yaw ψ, the twist of the attitude about the vertical,
///   2·atan2(q_z, q_w) (swing–twist decomposition; [`device_twist`]).
/// - **The hand, at any tilt** ([`YawAid::hand_mode`]): when the carrying mode is
///   `hand` ([`crate::engine::carry`]: screen up by up to 66°, held steady), the device's yaw
///   too, whatever its tilt: walkers hold the phone well beyond the reading pose, and a wider
///   tilt limit would take a swinging or pocketed phone's yaw too. Only while the screen faces
///   up at the step (its normal's up component ≥ [`YawAid::hand_screen_up_min`]) and gravity
///   turned in the device by at most [`YawAid::hand_steady_deg`] since the last step: the mode
///   is a vote over seconds, so a phone being put away or lifted to the ear is still `hand` for
///   a few steps, and its yaw then turns with the hand. 20°: smaller limits also refuse real
///   steps in sharp turns. A step given late (a walk's first steps) takes the yaw from
///   [`HAND_LATENCY_S`] after its end ([`YawAid::hand_late_yaw`]).
/// - **In a pocket and at the ear** ([`YawAid::pocket_offset`], [`YawAid::ear_offset`]), where
///   the phone is held still against the body, the engine walks along ψ_s + δ: ψ_s the screen's
///   yaw over a stride ([`screen_stride`]: the compass direction of the mean horizontal part of
///   the screen's normal, from the attitude alone, over the stride around the step's middle
///   with the turn lead, [`screen_at_step`], else the stride before the step). The integrated
///   yaw ψ is not that yaw: the thigh rocks about two axes at once and ψ drifts against the way
///   walked by up to a turn in two minutes (TyrEx's motion capture as much as the phone), and at
///   the ear it strays 10–16° from the truth's yaw, while the screen comes back with the thigh
///   or the head and holds the way walked within 2–9° after one offset in a pocket. δ is learnt
///   from the acceleration heading before the turn lead against the screen's yaw over the same
///   windows, so every step whose side is settled teaches, turning or not, as a circular
///   exponential mean over [`YawAid::pocket_steps`] steps with the outlier gate; it steers once
///   [`YawAid::offset_min_steps`] steps taught it. The pocket and the ear each keep their own δ
///   through a spell of another mode and restart it when gravity's mean direction in the device
///   moved by more than [`RESEAT_DEG`] (the phone sits another way). Only while the phone is
///   steady, as the hand's yaw: a phone taken from the ear turns with the arm. The heading is
///   the acceleration heading's, smoothed, not the walker's own way ([`Steered::own`]).
///   Measured in `docs/methods/pocket-heading.md` and `docs/methods/yaw-offset.md`.
/// - **In a swinging hand** ([`YawAid::swinging_offset`]) the same, with a δ of its own: the
///   arm swings the phone about the body's lateral axis, which leaves the stride's mean of the
///   screen's direction where the hand holds it (TyrEx's motion capture: within 6–19° of the
///   way walked after one offset), while the acceleration heading flips by half a turn for
///   stretches. Not steady from one step to the next (the arm is at the other end of its swing),
///   so that is not asked; a new grip restarts δ as in a pocket. Measured in
///   `docs/methods/yaw-offset.md`.
/// - **Otherwise**, by default, the papers' acceleration heading. [`YawAid::learn_offset`] walks
///   along ψ̄ + δ in every other mode: ψ integrated from the attitude increments about the
///   vertical and averaged over two steps, δ = θ̄ − ψ̄ learnt on straight steps (the yaw turned
///   by at most [`YawAid::straight_deg`] since two steps back: in and after a turn θ̄, a stride
///   average, lags the yaw) over [`YawAid::steps`] steps, restarted when taught in another mode
///   than before. It is off by default because in a pocket the
///   device yaw sampled at the step instants carries the thigh's sway, which two steps do not
///   cancel exactly, and the real pocket and swinging walks get worse.
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
    /// Outside the reading pose, learn the offset δ and walk along ψ̄ + δ in every carrying mode
    /// (off by default: in a pocket the thigh's sway spoils it, see above).
    pub learn_offset: bool,
    /// At the ear, learn the offset δ from the screen's yaw over the stride and walk along it
    /// plus δ, as in a pocket (see above).
    pub ear_offset: bool,
    /// In a pocket, learn the offset δ from the screen's yaw over the stride and walk along it
    /// plus δ (see above).
    pub pocket_offset: bool,
    /// In a swinging hand, learn the offset δ from the screen's yaw over the stride and walk
    /// along it plus δ, as in a pocket (see above).
    pub swinging_offset: bool,
    /// Time constant of the pocket's, the ear's and the swinging hand's offsets, steps (in a
    /// pocket a plateau from 20 to 160 on TyrEx).
    pub pocket_steps: f64,
    /// Straight steps that must have taught δ since it last restarted before it steers (see
    /// above).
    pub offset_min_steps: f64,
    /// In the carrying mode `hand`, the device's yaw at any tilt (see above), while the phone is
    /// steady and its screen faces up at the step ([`YawAid::hand_steady_deg`],
    /// [`YawAid::hand_screen_up_min`]).
    pub hand_mode: bool,
    /// The up component of the screen's normal the hand's yaw needs at the step (see
    /// [`YawAid::hand_mode`]).
    pub hand_screen_up_min: f64,
    /// The largest turn of gravity in the device from the last step for the hand's yaw,
    /// degrees: a phone being moved to another place is not steady.
    pub hand_steady_deg: f64,
    /// A step the detector gives later than [`HAND_LATENCY_S`] after its end (the first steps
    /// of a walk, found looking back) takes the hand's yaw from that long after its end, not
    /// the latest: the device's turn since then is taken off (see [`HAND_LATENCY_S`]).
    pub hand_late_yaw: bool,
}

impl Default for YawAid {
    fn default() -> Self {
        YawAid {
            steps: 10.0,
            gate_deg: 60.0,
            straight_deg: 10.0,
            reading_tilt_deg: 35.0,
            learn_offset: false,
            ear_offset: true,
            pocket_offset: true,
            swinging_offset: true,
            pocket_steps: 40.0,
            offset_min_steps: 7.0,
            hand_mode: true,
            hand_screen_up_min: 0.2,
            hand_steady_deg: 20.0,
            hand_late_yaw: true,
        }
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

/// How long after a step's end the step detector usually gives it, s: the PLL judges a step
/// about a third of a period after it (median 0.29–0.47 s on TyrEx's front-pocket and texting
/// walks). An on-time step's heading is the yaw of that moment. A step given later, up to 3 s
/// on those walks (the first steps of a walk or of a bout, which the motion detector's onset
/// finds looking back), takes the hand's yaw from this long after its end
/// ([`YawAid::hand_late_yaw`]): in the hand the walker turns with the phone, and a turn since
/// then is not the step's. Measured in `docs/methods/hand-yaw.md`.
pub const HAND_LATENCY_S: f64 = 0.3;

/// The buffer's sample [`HAND_LATENCY_S`] after the end `t_k` of a step, when the buffer runs
/// past it: the moment whose yaw a late step in the hand takes. `None` for a step given within
/// that time, or when the buffer does not reach back.
pub fn late_hand_moment(
    buf: &std::collections::VecDeque<crate::engine::heading::NavSample>,
    t_k: f64,
) -> Option<crate::engine::heading::NavSample> {
    crate::engine::heading::NavSample::at(buf, t_k + HAND_LATENCY_S)
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

    /// Steps taught since the estimate last restarted.
    pub fn steps(&self) -> f64 {
        self.n
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

/// The yaw aid's stage: the device's yaw at the last two steps and the learnt offset.
#[derive(Debug, Clone, Default)]
pub struct Steer {
    // The device's yaw at the previous step of the bout and the one before, compass radians,
    // unwrapped.
    last_yaw: Option<f64>,
    before_last_yaw: Option<f64>,
    offset: YawOffset,
    // The carrying mode the offset was learnt in.
    offset_mode: Option<crate::engine::carry::CarryMode>,
    // The offsets from the screen's yaw in a pocket, at the ear and in a swinging hand: each
    // kept through a spell of another mode.
    held: [HeldOffset; 3],
    // The screen's yaw over the stride of the last step, compass radians, unwrapped.
    last_screen: Option<f64>,
}

/// The offset of a phone held still against the body, from its screen's yaw
/// ([`Steer::held`]).
#[derive(Debug, Clone, Default)]
struct HeldOffset {
    offset: YawOffset,
    // Gravity's mean direction in the device when the offset restarted.
    up: Option<nalgebra::Vector3<f64>>,
}

impl HeldOffset {
    /// The pocket's place in [`Steer::held`].
    const POCKET: usize = 0;
    /// The ear's place in [`Steer::held`].
    const EAR: usize = 1;
    /// The swinging hand's place in [`Steer::held`].
    const SWINGING: usize = 2;
}

/// The yaw aid's heading of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steered {
    /// Rad from north.
    pub heading: f64,
    /// The device's yaw as it is (the hand, the reading pose): the way the walker looks, not an
    /// offset learnt from the acceleration heading.
    pub own: bool,
    /// The heading's side is known: the opening of a bout does not hold the step for it (the
    /// pocket's screen yaw with an offset the limb-signed steps taught).
    pub sided: bool,
}

/// What the yaw aid is given at a step.
#[derive(Debug, Clone, Copy)]
pub struct SteerInput {
    /// The device → ENU attitude at the step.
    pub attitude: nalgebra::UnitQuaternion<f64>,
    /// The device's integrated yaw at the step, compass radians, unwrapped.
    pub yaw: f64,
    /// Up in the device frame at this step, when known.
    pub up: Option<nalgebra::Vector3<f64>>,
    /// Up in the device frame at the last step, when known.
    pub previous_up: Option<nalgebra::Vector3<f64>>,
    /// Where the phone is carried, once decided.
    pub carry: Option<crate::engine::carry::CarryMode>,
    /// The step continues the previous one.
    pub continued: bool,
    /// The acceleration heading of the step (averaged, turn-led), rad from north.
    pub averaged: Option<f64>,
    /// The step's side is settled: it is not held at a bout's opening
    /// ([`crate::engine::heading::opening`]).
    pub settled: bool,
    /// The acceleration heading before the turn lead, rad from north, and whether it is the
    /// mean of this step's window and the last step's (A-HE).
    pub unled: Option<(f64, bool)>,
    /// The screen over the stride before the step ([`screen_stride`]).
    pub screen: Option<ScreenStride>,
    /// The screen over the stride around the middle of the step ([`screen_at_step`]), with the
    /// turn lead ([`crate::engine::heading::HeadingConfig::turn_lead`]).
    pub screen_at_step: Option<ScreenStride>,
    /// How far the device turned about the vertical since the moment whose yaw a late step in
    /// the hand takes ([`late_hand_moment`]), compass radians; 0 when
    /// [`YawAid::hand_late_yaw`] is off or the step is on time.
    pub turned_since: f64,
    /// The phone rides behind the hip ([`crate::engine::back_pocket`]): in a pocket, the
    /// screen's yaw over the stride before the step, not led to its middle.
    pub behind_hip: bool,
}

/// The screen over a stride ([`screen_stride`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenStride {
    /// The compass direction of the mean horizontal part of the screen's normal, radians.
    pub yaw: f64,
    /// The mean of up in the device frame, unit.
    pub up: nalgebra::Vector3<f64>,
}

/// The largest move of gravity's mean direction in the device (over a stride) from where the
/// pocket's offset was taught, degrees; beyond it the phone sits another way in the pocket and
/// the offset restarts. A phone turned in the pocket to face the other way moves it by about
/// 44° (TyrEx's pockets); the mean pitch of a running thigh moved it past 30° on one running
/// walk.
pub const RESEAT_DEG: f64 = 35.0;

/// The least mean horizontal part of the screen's normal over a stride for its yaw: the screen
/// within about 60° of vertical on average (a phone in a pocket: 70–80°, TyrEx's walks).
pub const SCREEN_MIN_HORIZONTAL: f64 = 0.5;

/// The screen over (t0, t1): the compass direction of the mean horizontal part of the
/// screen's normal ([`crate::engine::heading::NavSample::screen`]) and the mean of up in the
/// device; `None` when the buffer does not span the window, when the mean horizontal part is
/// shorter than [`SCREEN_MIN_HORIZONTAL`] or when no sample had an attitude.
pub fn screen_stride(
    buf: &std::collections::VecDeque<crate::engine::heading::NavSample>,
    t0: f64,
    t1: f64,
) -> Option<ScreenStride> {
    let [e, n, x, y, z] = super::turn::mean_over(buf, t0, t1, |s| {
        let u = s.device_up;
        [s.screen[0], s.screen[1], u[0], u[1], u[2]]
    })?;
    let up = nalgebra::Vector3::new(x, y, z).try_normalize(1e-9)?;
    (libm::hypot(e, n) >= SCREEN_MIN_HORIZONTAL).then(|| ScreenStride {
        yaw: crate::engine::math::wrap_2pi(libm::atan2(e, n)),
        up,
    })
}

/// The screen over the stride around the middle of the step `w`, where the turn lead takes the
/// acceleration heading ([`crate::engine::heading::turn`]): the stride is the last two steps'
/// span S = t_k − t_{k−2}, not twice the last step's, which the step detector's uneven steps
/// (0.4 s and 0.6 s in turn on some of TyrEx's back pockets) would leave short of a stride.
/// The span (mid − S/2, mid + S/2), or the last span S the buffer holds when it is centred
/// within S/8 of the middle.
pub fn screen_at_step(
    buf: &std::collections::VecDeque<crate::engine::heading::NavSample>,
    w: crate::engine::heading::StepWindow,
) -> Option<ScreenStride> {
    let stride = w.t_k - w.t_km2;
    let mid = 0.5 * (w.t_km1 + w.t_k);
    screen_stride(buf, mid - 0.5 * stride, mid + 0.5 * stride).or_else(|| {
        let end = buf.back()?.t;
        if end >= mid + 0.375 * stride {
            screen_stride(buf, end - stride, end)
        } else {
            None
        }
    })
}

impl Steer {
    /// The step's heading from the device's yaw, rad from north: in the hand, screen up, at any
    /// tilt the carrying mode allows, or (else, and before the mode is known) held nearly flat,
    /// the top of the phone; at the ear ([`YawAid::ear_offset`]) or elsewhere with
    /// [`YawAid::learn_offset`], the yaw plus the offset learnt on straight steps; else none.
    pub fn push(&mut self, aid: &YawAid, x: &SteerInput) -> Option<Steered> {
        let SteerInput {
            attitude,
            yaw,
            up,
            previous_up,
            carry,
            continued,
            averaged,
            unled,
            screen,
            screen_at_step,
            settled,
            turned_since,
            behind_hip,
        } = *x;
        let before_last = self.before_last_yaw.take().filter(|_| continued);
        let prev = self.last_yaw.replace(yaw).filter(|_| continued);
        self.before_last_yaw = prev;
        use crate::engine::carry::CarryMode;
        let held = match carry {
            Some(CarryMode::Pocket) if aid.pocket_offset => Some(HeldOffset::POCKET),
            Some(CarryMode::Ear) if aid.ear_offset => Some(HeldOffset::EAR),
            Some(CarryMode::Swinging) if aid.swinging_offset => Some(HeldOffset::SWINGING),
            _ => None,
        };
        let last_screen = self.screen(screen.filter(|_| held.is_some()), continued);
        let steady = match (up, previous_up) {
            (Some(u), Some(p)) => u.dot(&p) >= libm::cos(aid.hand_steady_deg.to_radians()),
            _ => true,
        };
        let reading = (aid.hand_mode
            && carry == Some(crate::engine::carry::CarryMode::Hand)
            && steady
            && up.is_some_and(|u| u.z >= aid.hand_screen_up_min))
            || reading_pose(&attitude, aid);
        if reading {
            // Held in front, screen up: the top of the phone is the way forward, as it pointed
            // just after the step (a late step's turn since then taken off).
            return device_twist(&attitude).map(|twist| Steered {
                heading: crate::engine::math::wrap_2pi(twist - turned_since),
                own: true,
                sided: true,
            });
        }
        if let Some(place) = held {
            // The screen's yaw over the stride: read from the attitude, not integrated, so the
            // thigh's swing or the head's sway leaves no drift in it. A phone being moved in the
            // body, or from the ear, is not steady: its screen turns without the walker. A
            // swinging arm is at the other end of its swing at each step.
            let now = screen.filter(|_| steady || place == HeldOffset::SWINGING)?;
            let now = ScreenStride {
                yaw: self.last_screen?,
                ..now
            };
            // Walked along the screen's yaw at the middle of the step, as the turn lead takes
            // the acceleration heading there (`turn.rs`), when it is given. Behind the hip the
            // phone's own path lags the walker's by about as much: the stride before the step.
            let led = screen_at_step
                .filter(|_| !behind_hip)
                .map_or(now.yaw, |s| now.yaw + wrap_pi(s.yaw - now.yaw));
            return self.held(
                aid,
                place,
                &now,
                led,
                last_screen,
                unled.filter(|_| settled),
            );
        }
        if !aid.learn_offset {
            return None;
        }
        // Two-step mean, as A-HE, so the sway of a pocket cancels.
        let psi = prev.map_or(yaw, |p| 0.5 * (p + yaw));
        let straight = Self::straight(aid, yaw, prev, before_last);
        self.restart_in(carry);
        if let (Some(th), true) = (averaged, straight) {
            self.offset
                .update(aid, crate::engine::math::wrap_pi(th - psi));
        }
        self.steered(aid, psi, None)
    }

    /// In a pocket, at the ear or in a swinging hand (`place`: [`HeldOffset::POCKET`],
    /// [`HeldOffset::EAR`], [`HeldOffset::SWINGING`]): the step walks along the screen's yaw over
    /// its stride plus that place's δ. δ is taught by every step whose side is settled: the acceleration heading before the turn lead
    /// against the screen's yaw over the same windows (this stride's, and the last step's when
    /// the heading is the mean of two), so a turn teaches it no lag. It restarts when gravity's
    /// mean direction in the device moved by more than [`RESEAT_DEG`] from where it was
    /// taught: the phone sits another way in the pocket.
    fn held(
        &mut self,
        aid: &YawAid,
        place: usize,
        now: &ScreenStride,
        led: f64,
        prev: Option<f64>,
        unled: Option<(f64, bool)>,
    ) -> Option<Steered> {
        let held = &mut self.held[place];
        let reseated = held
            .up
            .is_some_and(|u| u.dot(&now.up) < libm::cos(RESEAT_DEG.to_radians()));
        if reseated || held.up.is_none() {
            *held = HeldOffset {
                offset: YawOffset::default(),
                up: Some(now.up),
            };
        }
        let psi = now.yaw;
        let taught = match unled {
            Some((th, true)) => prev.map(|p| (th, 0.5 * (p + psi))),
            Some((th, false)) => Some((th, psi)),
            None => None,
        };
        if let Some((th, over)) = taught {
            let cfg = YawAid {
                steps: aid.pocket_steps,
                ..*aid
            };
            held.offset
                .update(&cfg, crate::engine::math::wrap_pi(th - over));
        }
        self.steered(aid, led, Some(place))
    }

    /// A restarted offset when it is taught in another carrying mode than before.
    fn restart_in(&mut self, carry: Option<crate::engine::carry::CarryMode>) {
        if self.offset_mode != carry {
            // Taught in another place on the body: another offset.
            self.offset = YawOffset::default();
            self.offset_mode = carry;
        }
    }

    /// The heading `psi` + δ once δ has been taught by enough steps: the δ of the place the
    /// phone is held in (`held`: a pocket, the ear or a swinging hand), whose side the settled
    /// steps gave (the step is sided), or the other modes' δ.
    fn steered(&self, aid: &YawAid, psi: f64, held: Option<usize>) -> Option<Steered> {
        let offset = held.map_or(&self.offset, |place| &self.held[place].offset);
        offset
            .get()
            .filter(|_| offset.steps() >= aid.offset_min_steps)
            .map(|d| Steered {
                heading: crate::engine::math::wrap_2pi(psi + d),
                own: false,
                sided: held.is_some(),
            })
    }

    /// Only straight strides teach the offset: in and just after a turn θ̄ (a stride average
    /// of the acceleration) lags the yaw. Straight: the yaw `now` within
    /// [`YawAid::straight_deg`] of the last two steps'.
    fn straight(aid: &YawAid, now: f64, prev: Option<f64>, before_last: Option<f64>) -> bool {
        let limit = aid.straight_deg.to_radians();
        [prev, before_last]
            .iter()
            .all(|p| p.is_some_and(|p| (now - p).abs() <= limit))
    }

    /// Keeps the screen's yaw of this step, unwrapped against the last step's, and returns the
    /// last step's (a step that does not continue the last, or has no screen's yaw, forgets
    /// it).
    fn screen(&mut self, screen: Option<ScreenStride>, continued: bool) -> Option<f64> {
        let prev = self.last_screen.take().filter(|_| continued);
        self.last_screen = screen.map(|s| prev.map_or(s.yaw, |p| p + wrap_pi(s.yaw - p)));
        prev
    }

    /// The learnt offset δ from the device's yaw to the direction of walking, rad.
    pub fn offset(&self) -> Option<f64> {
        self.offset.get()
    }

    /// The end of a bout: the next step's yaw is not compared with the last.
    pub fn end_bout(&mut self) {
        self.last_yaw = None;
        self.before_last_yaw = None;
        self.last_screen = None;
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests;
