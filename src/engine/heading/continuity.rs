//! The heading carried across a change of its source (ours, none of the papers
//! changes the carrying mode mid-walk).
//! May import: the rest of `engine`.
//!
//! Each carrying mode walks along its own source ([`super::Heading`]): the device's yaw in the
//! hand, the acceleration heading elsewhere. The acceleration heading is absolute but only as
//! good as its forward sign and its axis, which a limb can turn by up to half a turn; the yaw
//! in the hand is what a walker looks along. So at a change the walker is taken to go on the way they went: the steps
//! keep the heading carried while [`Continuity::steps`] acceleration headings of the new mode are
//! gathered, and the offset from their circular mean to the heading carried, weighed by how far
//! each is trusted (below), is then added to every acceleration heading, until the next change.
//!
//! - **A change** is one of the source (the hand's yaw to the acceleration heading), or one of
//!   the mode with the phone moved in the body ([`moved`]). A vote that flickers between two
//!   modes of one source while the phone stays where it was (a pocket on stairs) changes
//!   nothing: carrying the heading there made the simulated stairs walks' ends worse.
//! - **The heading carried** is the median of the last [`RECENT`] steps' walked at least
//!   [`Continuity::lag_s`] before the change: the mode is a vote over seconds, so the phone was
//!   already moving for that long, and the steps meanwhile can walk its move (taken from the
//!   last steps, an ear's move into a swinging hand was carried half a turn off). Only a recent one: the last step at most [`Continuity::max_gap_s`] before (a
//!   walker who stood still longer may have turned). Nor from a step at or after one whose limb
//!   turned its way forward (the thigh's sign or the swinging arm's vote, [`Walked::flipped`]):
//!   that is the phone on its way too, more than 2 s before the vote turned (a swinging hand's
//!   arm vote turns over for a few steps while the phone goes to the pocket).
//! - **How much of the offset:** the heading carried and the new source's are weighed by how
//!   far each source is off over a walk ([`SourceErrors`]): from a pocket into a swinging hand
//!   or to the ear the new source keeps nearly its own heading; from the hand's yaw into a
//!   pocket the pocket takes nearly all of the offset. Headings more than 90° apart: the one
//!   trusted more wins (the new source's sign is turned only by a heading carried that is
//!   trusted more).
//! - **What teaches the offset:** steps of the settled mode only (a step the vote still calls
//!   `hand` but whose yaw the hand's gates refused is the phone on its way), and only headings
//!   that agree ([`Continuity::agreement_min`]); else the offset is 0. A mode that has not
//!   settled within 4 × [`Continuity::steps`] steps ends the carry with what was gathered.
//! - **Before the vote turns** ([`Continuity::hold_while_moved`]): a phone moving in the body
//!   ([`moved`]) in a walk under way ([`KEPT`] steps without a stop) walks the heading walked
//!   before the move, by the same rule as the heading carried.
//! - **The hand's yaw** is the walker's own: it ends a carry and is taken as it is.
//! - [`Continuity::sign_only`] keeps only the offset's sign: 180° when the mean is more than
//!   90° off (and the heading carried is trusted more), else 0 (measured worse on the
//!   simulator; docs/methods/mode-change.md).

use super::super::carry::CarryMode;
use super::super::math::{wrap_2pi, wrap_pi};
use std::collections::VecDeque;

/// How many of the last steps' headings the anchor is the median of.
pub const RECENT: usize = 3;

/// How many of the last steps' times and headings the heading stage keeps for the anchor: the
/// [`RECENT`] before the [`Continuity::lag_s`] and the steps within it (up to 9, running).
pub const KEPT: usize = 12;

/// The heading among `hs` closest to the others (the sum of absolute angles to them least):
/// a median that a turn of the phone on the last step before a change does not move.
fn circular_median(hs: impl Iterator<Item = f64> + Clone) -> Option<f64> {
    let cost = |a: f64| hs.clone().map(|b| wrap_pi(a - b).abs()).sum::<f64>();
    hs.clone().min_by(|&a, &b| cost(a).total_cmp(&cost(b)))
}

/// Settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Continuity {
    /// Acceleration headings gathered after a change before the offset is set, steps.
    pub steps: usize,
    /// Longest time from the last step before the change, s.
    pub max_gap_s: f64,
    /// Keep only the offset's sign (0 or 180°).
    pub sign_only: bool,
    /// The least mean resultant length of the gathered headings (1: all alike, about 0.44 for
    /// four random ones) for their offset to be learnt.
    pub agreement_min: f64,
    /// How far gravity must turn in the device for a change between two modes of one source to
    /// count as the phone moved, degrees ([`moved`]).
    pub moved_deg: f64,
    /// How long before a change the heading carried was walked, s: the carrying mode's vote
    /// turns [`crate::engine::carry::CarryConfig::switch_votes`] evaluations
    /// [`crate::engine::carry::CarryConfig::every_s`] apart after the phone began to move
    /// (4 × 0.5 s), and the steps meanwhile are the phone on its way.
    pub lag_s: f64,
    /// How far each source's heading is off over a walk, degrees: what weighs the heading
    /// carried against the new source's own ([`SourceErrors`]).
    pub errors: SourceErrors,
    /// While the phone moves in the body ([`moved`]) and no change is open, an acceleration
    /// heading's step walks the heading walked before the move: the mode's vote turns 2 s or
    /// more after the phone began to move, and meanwhile the acceleration heading is the
    /// move's.
    pub hold_while_moved: bool,
}

/// The typical error of each source's heading over a walk, degrees: the part a constant offset
/// carries (a bias; the step-to-step scatter averages out). At a change the heading carried and
/// the new source's are two estimates of one walking direction, weighed by the inverse of
/// their variances (a one-state Kalman update): a source trusted less than the one before takes
/// the offset to the heading carried, a source trusted more keeps its own (its sign still
/// turned when the two are more than 90° apart).
///
/// The defaults are the simulator's (`examples/carry_heading`, seeds 1–8, one mode per walk:
/// the RMS over the walks of each walk's mean signed heading error, rounded up to 0.5°; the
/// values measured are in docs/methods/mode-change.md).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct SourceErrors {
    /// The device's yaw in the hand (a real yaw's field is bent indoors, but it is still the
    /// walker's own line).
    pub yaw: f64,
    /// The acceleration heading in a pocket.
    pub pocket: f64,
    /// In a swinging hand.
    pub swinging: f64,
    /// At the ear.
    pub ear: f64,
    /// In a bag.
    pub bag: f64,
    /// In the hand or before the mode is known: the largest.
    pub other: f64,
}

impl Default for SourceErrors {
    fn default() -> Self {
        SourceErrors {
            yaw: 0.5,
            pocket: 7.0,
            swinging: 2.0,
            ear: 1.5,
            bag: 8.5,
            other: 8.5,
        }
    }
}

impl SourceErrors {
    /// The error's variance for a step of `source` in `mode`, degrees².
    fn variance(&self, source: Source, mode: Option<CarryMode>) -> f64 {
        let e = match (source, mode) {
            (Source::Yaw, _) => self.yaw,
            (_, Some(CarryMode::Pocket)) => self.pocket,
            (_, Some(CarryMode::Swinging)) => self.swinging,
            (_, Some(CarryMode::Ear)) => self.ear,
            (_, Some(CarryMode::Bag)) => self.bag,
            (_, Some(CarryMode::Hand) | None) => self.other,
        };
        e * e
    }

    /// Every error, with its setting's name.
    pub fn named(&self) -> [(&'static str, f64); 6] {
        [
            ("heading.continuity.errors.yaw", self.yaw),
            ("heading.continuity.errors.pocket", self.pocket),
            ("heading.continuity.errors.swinging", self.swinging),
            ("heading.continuity.errors.ear", self.ear),
            ("heading.continuity.errors.bag", self.bag),
            ("heading.continuity.errors.other", self.other),
        ]
    }
}

impl Default for Continuity {
    fn default() -> Self {
        Continuity {
            steps: 4,
            max_gap_s: 4.0,
            sign_only: false,
            agreement_min: 0.7,
            moved_deg: 30.0,
            lag_s: 2.0,
            errors: SourceErrors::default(),
            hold_while_moved: true,
        }
    }
}

/// Where a step's heading comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The device's yaw (the hand, the reading pose, the learnt offset).
    Yaw,
    /// The acceleration heading.
    Acceleration,
}

/// How many of the last steps' device "up" vectors [`moved`] looks at.
pub const UPS: usize = 9;

/// Whether the phone moved in the body: gravity's mean direction in the device over the last 3
/// steps is more than [`Continuity::moved_deg`] from its mean over the 3 steps 6 before.
pub fn moved(ups: &VecDeque<nalgebra::Vector3<f64>>, cfg: &Continuity) -> bool {
    if ups.len() < UPS {
        return false;
    }
    let mean =
        |r: std::ops::Range<usize>| ups.range(r).fold(nalgebra::Vector3::zeros(), |a, u| a + u);
    let (old, new) = (mean(0..3), mean(UPS - 3..UPS));
    let cos = old.dot(&new) / (old.norm() * new.norm());
    !(cos >= libm::cos(cfg.moved_deg.to_radians()))
}

/// A step walked, as the heading stage keeps it for the heading carried.
#[derive(Debug, Clone, Copy)]
pub struct Walked {
    /// Its time, s.
    pub t: f64,
    /// The heading it walked, rad.
    pub heading: f64,
    /// The limb that signs the heading turned its way forward at it (the phone moving).
    pub flipped: bool,
}

/// The heading walked before the phone began to move, at a step at `t`: the median of the last
/// [`RECENT`] steps walked at least [`Continuity::lag_s`] before (walked while the phone was
/// already on its way, the vote not yet turned) and before the first step at which a limb
/// turned its way forward (the phone on its way too); `None` when the last step is more than
/// [`Continuity::max_gap_s`] old.
fn walked_before(cfg: &Continuity, t: f64, recent: &VecDeque<Walked>) -> Option<f64> {
    let before = recent
        .iter()
        .take_while(|r| !r.flipped)
        .filter(|r| r.t <= t - cfg.lag_s);
    let skip = before.clone().count().saturating_sub(RECENT);
    recent
        .back()
        .filter(|r| t - r.t <= cfg.max_gap_s)
        .and_then(|_| circular_median(before.skip(skip).map(|r| r.heading)))
}

/// Whether the [`KEPT`] steps up to `t` were walked without a stop (no gap over 1 s, longer than
/// a step of the slowest walking, 1.2 Hz): a walk
/// under way for that long, so that gravity's turn in the device is the phone's move, not a
/// walker who stood and set off again, nor a hand that began to swing (a swinging hand's first
/// steps can read half a turn off for several steps).
fn walked_on(t: f64, recent: &VecDeque<Walked>) -> bool {
    let times = recent.iter().map(|r| r.t).chain([t]);
    recent.len() == KEPT && times.clone().zip(times.skip(1)).all(|(a, b)| b - a <= 1.0)
}

/// One step as [`Carried::push`] sees it.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// Where its heading comes from.
    pub source: Source,
    /// The carrying mode, once decided.
    pub mode: Option<CarryMode>,
    /// False while the mode still names another source (the hand's, with the phone already
    /// moving): such steps keep the heading carried and teach nothing.
    pub settled: bool,
    /// The phone moved in the body lately ([`moved`]).
    pub moved: bool,
    /// Its time, s.
    pub t: f64,
    /// Its heading from that source, rad.
    pub heading: Option<f64>,
}

/// The running state.
#[derive(Debug, Clone, Default)]
pub struct Carried {
    key: Option<(Source, Option<CarryMode>)>,
    // While a change is open: the heading carried, and the acceleration headings gathered since
    // the last change of key (as the sum of unit vectors of anchor − θ) and all told.
    anchor: Option<f64>,
    sum: (f64, f64),
    n: usize,
    open_steps: usize,
    offset: f64,
    // The variance of the heading walked, degrees² (`None`: its source's own), and of the
    // heading carried while a change is open.
    var: Option<f64>,
    anchor_var: f64,
    // The heading walked while the phone moves before a change ([`Continuity::hold_while_moved`]),
    // and the steps since the last change.
    held: Option<f64>,
    since_change: usize,
}

impl Carried {
    /// One step, given the last steps walked (up to [`KEPT`], the latest last); returns the
    /// heading to walk (`None` when nothing is known).
    pub fn push(
        &mut self,
        cfg: &Continuity,
        step: &Step,
        recent: &VecDeque<Walked>,
    ) -> Option<f64> {
        let &Step {
            source,
            mode,
            settled,
            moved,
            t,
            heading: h,
        } = step;
        let key = (source, mode);
        let old = self.key.replace(key);
        // A change of source, or of mode with the phone moved in the body: the first decision
        // of the mode, and a vote that flickers between two modes of one source while the phone
        // stays put (a pocket on stairs), change nothing on the phone.
        let change = match old {
            Some(o) if o != key => o.0 != source || (o.1.is_some() && moved),
            _ => false,
        };
        self.since_change = self.since_change.saturating_add(1);
        if change {
            self.since_change = 0;
            self.held = None;
            if self.anchor.is_none() {
                // While a change is open (the mode settles over a few votes) its anchor stays.
                self.anchor = walked_before(cfg, t, recent);
                self.open_steps = 0;
                let (s0, m0) = old.unwrap_or(key);
                self.anchor_var = self.var.unwrap_or_else(|| cfg.errors.variance(s0, m0));
            }
            self.var = None;
            self.sum = (0.0, 0.0);
            self.n = 0;
            self.offset = 0.0;
        }
        if source == Source::Yaw {
            // The yaw is the walker's own heading: nothing to carry.
            self.anchor = None;
            self.held = None;
            return h;
        }
        let Some(anchor) = self.anchor else {
            // The phone moving in the body before the vote turned: its acceleration heading is
            // the move's, so the step walks the heading walked before. Not for the [`UPS`]
            // steps after a change, over which `moved` still sees the move the change was.
            if !moved || !cfg.hold_while_moved {
                self.held = None;
            } else if self.held.is_none() && self.since_change >= UPS && walked_on(t, recent) {
                self.held = walked_before(cfg, t, recent);
            }
            if self.held.is_some() {
                return self.held;
            }
            return h.map(|th| self.turn(th));
        };
        self.open_steps += 1;
        // A mode that has not settled within four times the steps ends the carry.
        let open = self.open_steps < 4 * cfg.steps;
        if !settled && open {
            return Some(anchor);
        }
        if let Some(th) = h {
            let (s, c) = libm::sincos(wrap_pi(anchor - th));
            self.sum = (self.sum.0 + c, self.sum.1 + s);
            self.n += 1;
        }
        if self.n < cfg.steps && open {
            return Some(anchor);
        }
        let agree = libm::hypot(self.sum.0, self.sum.1) >= cfg.agreement_min * self.n as f64;
        let mean = if self.n > 0 && agree {
            libm::atan2(self.sum.1, self.sum.0)
        } else {
            0.0
        };
        // Two headings more than 90° apart: one has the wrong sign, and the one trusted more
        // wins (the heading carried turns the new source's sign, with the rest weighed). Else
        // the two are weighed by their trust.
        let var = cfg.errors.variance(source, mode);
        let w = var / (var + self.anchor_var);
        let flip = mean.abs() > std::f64::consts::FRAC_PI_2;
        self.offset = match (flip, cfg.sign_only) {
            (true, _) if w < 0.5 => 0.0,
            (true, true) => std::f64::consts::PI,
            (true, false) => {
                wrap_pi(std::f64::consts::PI + w * wrap_pi(mean - std::f64::consts::PI))
            }
            (false, true) => 0.0,
            (false, false) => w * mean,
        };
        if self.n > 0 && agree && !cfg.sign_only {
            self.var = Some(w * self.anchor_var);
        }
        self.anchor = None;
        h.map(|th| self.turn(th))
    }

    /// A change is open: the heading is carried while the new source's offset is learnt.
    pub fn carrying(&self) -> bool {
        self.anchor.is_some()
    }

    /// The offset added to the acceleration heading now, rad.
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// `th` turned by the offset; untouched, bit for bit, when there is none.
    fn turn(&self, th: f64) -> f64 {
        if self.offset == 0.0 {
            th
        } else {
            wrap_2pi(th + self.offset)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn step(source: Source, mode: CarryMode, t: f64, deg: f64) -> Step {
        Step {
            source,
            mode: Some(mode),
            settled: true,
            moved: true,
            t,
            heading: Some(deg.to_radians()),
        }
    }

    fn walked(t: f64, heading: f64, flipped: bool) -> Walked {
        Walked {
            t,
            heading,
            flipped,
        }
    }

    /// Feeds `steps` and returns the headings walked, degrees. Every step of [`step`] says the
    /// phone moved, so the hold is off here (it has its own test).
    fn walk(c: &mut Carried, steps: &[Step]) -> Vec<f64> {
        let cfg = Continuity {
            hold_while_moved: false,
            ..Continuity::default()
        };
        walk_with(&cfg, c, steps)
    }

    fn walk_with(cfg: &Continuity, c: &mut Carried, steps: &[Step]) -> Vec<f64> {
        let mut recent = VecDeque::new();
        steps
            .iter()
            .map(|s| {
                let h = c.push(cfg, s, &recent).unwrap();
                if recent.len() == KEPT {
                    recent.pop_front();
                }
                recent.push_back(walked(s.t, h, false));
                wrap_2pi(h).to_degrees()
            })
            .collect()
    }

    #[test]
    fn a_change_keeps_the_heading_then_learns_the_offset() {
        let mut c = Carried::default();
        let mut steps: Vec<Step> = (0..5)
            .map(|i| step(Source::Yaw, CarryMode::Hand, 0.5 * i as f64, 10.0))
            .collect();
        // The last yaw step already turns with the phone: the median of three ignores it.
        steps[4].heading = Some(40f64.to_radians());
        // In the pocket the acceleration heading reads 150° off, then the walker turns by 30°.
        for i in 5..15 {
            let turn = if i >= 11 { 30.0 } else { 0.0 };
            steps.push(step(
                Source::Acceleration,
                CarryMode::Pocket,
                0.5 * i as f64,
                160.0 + turn,
            ));
        }
        let h = walk(&mut c, &steps);
        for (i, &d) in h.iter().enumerate().skip(5).take(3) {
            assert!((d - 10.0).abs() < 1e-9, "step {i} keeps 10°: {d}");
        }
        // Its sign turned, and the rest weighed: the yaw (0.5°) against the pocket (7°) leaves
        // 0.25 / 49.25 of the pocket's own 30°.
        let left = 30.0 * 0.25 / 49.25;
        assert!(
            (h[8] - 10.0 + left).abs() < 1e-9 && (h[14] - 40.0 + left).abs() < 1e-9,
            "{h:?}"
        );
        assert!((wrap_pi(c.offset()).to_degrees() + 150.0 + left).abs() < 1e-9);
    }

    /// Walks 8 steps in `from` reading 0°, then 8 in `to` reading `deg`; returns the last
    /// heading walked, degrees within ±180.
    fn changed(from: CarryMode, to: CarryMode, deg: f64) -> f64 {
        let steps: Vec<Step> = (0..16)
            .map(|i| {
                let (mode, d) = if i < 8 { (from, 0.0) } else { (to, deg) };
                step(Source::Acceleration, mode, 0.5 * i as f64, d)
            })
            .collect();
        let h = walk(&mut Carried::default(), &steps);
        wrap_pi(h[15].to_radians()).to_degrees()
    }

    #[test]
    fn a_phone_moving_in_the_body_walks_the_heading_walked_before() {
        // 14 steps north in the pocket, then the phone moves (gravity turns in it) and its
        // acceleration heading reads 150° for 4 steps before the vote turns; then it stays put.
        let steps: Vec<Step> = (0..22)
            .map(|i| {
                let moving = (14..18).contains(&i);
                let mut s = step(
                    Source::Acceleration,
                    CarryMode::Pocket,
                    0.5 * i as f64,
                    if moving { 150.0 } else { 5.0 },
                );
                s.moved = moving;
                s
            })
            .collect();
        let h = walk_with(&Continuity::default(), &mut Carried::default(), &steps);
        assert!(h[14..18].iter().all(|&d| (d - 5.0).abs() < 1e-9), "{h:?}");
        assert!((h[18] - 5.0).abs() < 1e-9, "{h:?}");
        // Not within a walk's first steps (a hand that begins to swing moves too), nor with it
        // off.
        let h = walk_with(&Continuity::default(), &mut Carried::default(), &steps[4..]);
        assert!((h[10] - 150.0).abs() < 1e-9, "{h:?}");
        let off = Continuity {
            hold_while_moved: false,
            ..Continuity::default()
        };
        let h = walk_with(&off, &mut Carried::default(), &steps);
        assert!((h[14] - 150.0).abs() < 1e-9, "{h:?}");
    }

    #[test]
    fn the_source_trusted_more_weighs_more() {
        // From the pocket (7°) to the ear (1.5°): the ear's own heading, 4 % of the way to the
        // pocket's; and back: 96 % of the way to the ear's.
        let to_ear = changed(CarryMode::Pocket, CarryMode::Ear, 10.0);
        assert!((to_ear - 9.56).abs() < 0.01, "{to_ear}");
        let to_pocket = changed(CarryMode::Ear, CarryMode::Pocket, 10.0);
        assert!((to_pocket - 0.44).abs() < 0.01, "{to_pocket}");
    }

    #[test]
    fn only_a_heading_trusted_more_turns_the_new_sign() {
        // The ear's heading turns a pocket that reads 185°: its sign, and most of the rest.
        let h = changed(CarryMode::Ear, CarryMode::Pocket, 185.0);
        assert!((h - 0.22).abs() < 0.01, "{h}");
        // The pocket's does not turn a swinging hand's.
        let h = changed(CarryMode::Pocket, CarryMode::Swinging, 185.0);
        assert!((h + 175.0).abs() < 1e-9, "{h}");
    }

    #[test]
    fn the_heading_carried_is_from_before_the_limb_turned() {
        // A swinging hand walks north; 3 s before the change its limb turns the way forward
        // (the phone moving) and the steps walk south.
        let recent: VecDeque<Walked> = (0..10)
            .map(|i| {
                let t = 0.5 * i as f64;
                walked(t, if t < 2.5 { 0.0 } else { PI }, t == 2.5)
            })
            .collect();
        let cfg = Continuity::default();
        let mut c = Carried::default();
        c.push(
            &cfg,
            &step(Source::Acceleration, CarryMode::Swinging, 5.0, 180.0),
            &recent,
        );
        let h = c
            .push(
                &cfg,
                &step(Source::Acceleration, CarryMode::Pocket, 5.5, 90.0),
                &recent,
            )
            .unwrap();
        assert!(c.carrying() && h.abs() < 1e-9, "{}", h.to_degrees());
    }

    #[test]
    fn the_steps_of_the_phone_on_its_way_are_not_carried() {
        // At the ear the walk goes north; the phone is moved to a swinging hand, and for 2 s the
        // vote still says the ear while its acceleration heading reads 180° (the move). Then
        // the swinging hand reads north again.
        let mut steps: Vec<Step> = (0..8)
            .map(|i| step(Source::Acceleration, CarryMode::Ear, 0.5 * i as f64, 0.0))
            .collect();
        for i in 8..12 {
            steps.push(step(
                Source::Acceleration,
                CarryMode::Ear,
                0.5 * i as f64,
                180.0,
            ));
        }
        for i in 12..20 {
            steps.push(step(
                Source::Acceleration,
                CarryMode::Swinging,
                0.5 * i as f64,
                1.0,
            ));
        }
        let mut c = Carried::default();
        let h = walk(&mut c, &steps);
        for (i, &d) in h.iter().enumerate().skip(12) {
            assert!(
                wrap_pi(d.to_radians()).abs() < 2f64.to_radians(),
                "step {i}: {d}"
            );
        }
        assert!(wrap_pi(c.offset()).to_degrees().abs() < 2.0);
    }

    #[test]
    fn headings_that_disagree_teach_no_offset_and_the_yaw_ends_the_carry() {
        let cfg = Continuity::default();
        let mut c = Carried::default();
        let recent: VecDeque<Walked> = [0.0, 0.5, 1.0].map(|t| walked(t, 0.0, false)).into();
        c.push(&cfg, &step(Source::Yaw, CarryMode::Hand, 1.0, 0.0), &recent);
        for (i, d) in [90.0, 270.0, 0.0, 180.0].into_iter().enumerate() {
            let s = step(Source::Acceleration, CarryMode::Swinging, 1.5 + i as f64, d);
            c.push(&cfg, &s, &recent);
        }
        assert_eq!(c.offset(), 0.0);
        // Back in the hand: the yaw as it is.
        let s = step(Source::Yaw, CarryMode::Hand, 6.0, 77.0);
        let h = c.push(&cfg, &s, &recent).unwrap();
        assert!((h.to_degrees() - 77.0).abs() < 1e-9);
    }

    #[test]
    fn a_flickering_vote_or_an_old_heading_carries_nothing() {
        let cfg = Continuity::default();
        let recent: VecDeque<Walked> = [0.0, 0.5, 1.0].map(|t| walked(t, 1.0, false)).into();
        let mut c = Carried::default();
        c.push(
            &cfg,
            &step(Source::Acceleration, CarryMode::Pocket, 1.0, 100.0),
            &recent,
        );
        // Pocket → bag with the phone where it was (a pocket on stairs): nothing carried.
        let mut s = step(Source::Acceleration, CarryMode::Bag, 1.5, 100.0);
        s.moved = false;
        let h = c.push(&cfg, &s, &recent).unwrap();
        assert!((h.to_degrees() - 100.0).abs() < 1e-9);
        // A change 10 s after the last step: too old to carry.
        let s = step(Source::Acceleration, CarryMode::Ear, 11.0, 200.0);
        let h = c.push(&cfg, &s, &recent).unwrap();
        assert!((h.to_degrees() - 200.0).abs() < 1e-9);
    }

    #[test]
    fn the_phone_moved_when_gravity_turned_in_it() {
        let cfg = Continuity::default();
        let still: VecDeque<_> = (0..UPS).map(|_| nalgebra::Vector3::y()).collect();
        assert!(!moved(&still, &cfg));
        let turned: VecDeque<_> = (0..UPS)
            .map(|i| {
                if i < 3 {
                    nalgebra::Vector3::y()
                } else {
                    nalgebra::Vector3::z()
                }
            })
            .collect();
        assert!(moved(&turned, &cfg));
        assert!(
            !moved(&turned.range(1..).copied().collect(), &cfg),
            "too few steps"
        );
    }
}
