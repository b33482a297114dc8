//! Carrying mode: where the phone is while the person walks: in a trouser pocket, in the hand
//! with the screen up, in a swinging hand, at the ear, or in a bag or a jacket (ours; none of the
//! papers has it: Basso assumes the pocket, Munoz Diaz the thigh, Ibarra the hand, Strozzi the
//! foot).
//! May import: the rest of `engine`.
//!
//! # Features (over the last [`CarryConfig::window_s`], accelerometer in the device frame, and
//! the gyroscope where the log has one)
//! - **Up**: u, the mean specific force, normalised: where gravity sits in the device.
//! - **Tilt**: the rms angle between each 20 ms average of the specific force and u, degrees. A
//!   thigh or an arm swings the phone; a hand, a head or a trunk carries it steadily.
//! - **Step and stride correlation**: c₁ and c₂, the autocorrelation of the specific force
//!   (3 axes, mean removed) at one and at two step periods. The step period is the lag in
//!   0.28–0.85 s (a cadence of 1.2–3.6 Hz) where the vertical acceleration in the navigation
//!   frame correlates best: every mode bounces once a step. (Along u instead, the thigh's swing
//!   hid the step in real front pockets.) (The motion detector's cadence was tried
//!   first; it reads twice the cadence on some simulated walks, which turned c₁ negative.)
//!   On the trunk every step looks alike (c₁ ≈ c₂); on a leg or an arm a step and the next are
//!   mirror images, and only the stride repeats (c₁ ≪ c₂, or both low for a back pocket).
//! - **Forward axis**: |z| of the main axis of the horizontal specific force (the forward
//!   surge of each step) in the device frame: near 1 when the screen faces forward or back (a
//!   jacket, a neck pouch), near 0 when it faces sideways (the ear, an armband).
//! - **Rate**: the rms of ω about its mean over the window, rad/s.
//! - **Swing rate**: the rms of ω about the horizontal axes (its covariance projected off u),
//!   rad/s: a thigh or an arm swings the phone about a horizontal axis at the stride
//!   frequency, while the walk's turns and a head's yaw are about the vertical.
//! - **Swing axis**: |z| of the main axis of that horizontal rotation in the device frame: a
//!   hand at the side swings the phone about its screen's normal (z); a trouser pocket, screen
//!   to the thigh, about the phone's short axis (x).
//!
//! The window's sums (of the specific force, its square and its direction, of ω and ω ωᵀ, and
//! the vertical acceleration's lagged products) are kept as running sums, updated as 20 ms
//! slots enter and leave it and summed afresh every 1024 slots; the means are taken out of
//! them algebraically (Σ (x − x̄)² = Σ x² − n x̄²).
//!
//! - **Drift**: the angle between the mean specific force of the window's first half and of
//!   its second, degrees: a phone being moved to another place turns over within the window.
//!
//! # Rule (each [`CarryConfig::every_s`]; a vote of the last [`CarryConfig::votes`] decides)
//! 0. A window whose drift exceeds [`CarryConfig::drift_max_deg`] does not vote: its features
//!    mix two places. The votes start afresh ([`Ballot::reopen`]).
//! 1. The **hand**, screen up: u_z ≥ [`CarryConfig::screen_up_min`] and tilt <
//!    [`CarryConfig::hand_tilt_deg`]. First: a turn while texting turns the phone fast, and
//!    a hand-held step can look like a limb's.
//!
//! With a gyroscope:
//! 2. A **limb** swings it: swing rate ≥ [`CarryConfig::swing_rate_min`]. It is the
//!    **swinging** hand when the tilt per swing rate is low, as a pendulum's (<
//!    [`CarryConfig::pendulum_ratio_max`]), or when the phone swings about its screen's normal
//!    (swing axis ≥ [`CarryConfig::side_swing_axis_min`]) and the tilt per rate is below
//!    [`CarryConfig::side_swing_ratio_max`]; else the **pocket**.
//! 3. The **ear**: the screen faces sideways (|u_z| < [`CarryConfig::screen_side_max`]) and
//!    so does the forward surge (forward axis < [`CarryConfig::forward_z_max`]) or the steps
//!    alternate as a head's sway does (c₁ < [`CarryConfig::ear_step_corr_max`]).
//! 4. Else a **bag** or a jacket.
//!
//! From the accelerometer alone:
//! 2. A limb swings it: c₁ < [`CarryConfig::step_corr_max`] and (c₂ − c₁ ≥
//!    [`CarryConfig::stride_gain_min`] or tilt ≥ [`CarryConfig::limb_tilt_deg`]). Then the
//!    **pocket** when the long axis is near the vertical (|u_y| ≥
//!    [`CarryConfig::pocket_axis_min`], the phone along the thigh), else the **swinging** hand.
//! 3. The **ear**: |u_z| < [`CarryConfig::screen_side_max`] and forward axis <
//!    [`CarryConfig::forward_z_max`].
//! 4. Else a **bag** or a jacket.
//!
//! The accelerometer-only thresholds were set from the Oxford placements' feature medians and
//! the simulator's modes; those with a gyroscope from the real walks of TyrEx, UbiComp 2013 and
//! WeAllWalk, chosen leave-one-walker-out (`examples/carry_features.rs`).
//! `docs/methods/carrying-mode.md` has the figures.

mod window;

use super::types::{positive, ConfigError, DeviceVec};
use nalgebra::{Matrix3, SymmetricEigen};
use std::collections::VecDeque;
use std::ops::RangeInclusive;
use window::{Slot, Window};

/// Where the phone is carried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CarryMode {
    /// A front or back trouser pocket.
    Pocket,
    /// In the hand, screen up (texting, reading).
    Hand,
    /// In the hand of a swinging arm.
    Swinging,
    /// At the ear (calling); also an armband, whose screen faces sideways too.
    Ear,
    /// A bag or a jacket: on the trunk, not held.
    Bag,
}

impl CarryMode {
    /// Every mode.
    pub const ALL: [CarryMode; 5] = [
        CarryMode::Pocket,
        CarryMode::Hand,
        CarryMode::Swinging,
        CarryMode::Ear,
        CarryMode::Bag,
    ];

    /// Lower-case name, as in the CSV's `carry` column.
    pub fn as_str(self) -> &'static str {
        match self {
            CarryMode::Pocket => "pocket",
            CarryMode::Hand => "hand",
            CarryMode::Swinging => "swinging",
            CarryMode::Ear => "ear",
            CarryMode::Bag => "bag",
        }
    }

    /// Words for the page.
    pub fn words(self) -> &'static str {
        match self {
            CarryMode::Pocket => "In a pocket",
            CarryMode::Hand => "In the hand, screen up",
            CarryMode::Swinging => "Swinging in the hand",
            CarryMode::Ear => "At the ear",
            CarryMode::Bag => "In a bag or a jacket",
        }
    }
}

/// Settings of the carrying-mode detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct CarryConfig {
    /// Window, s: two and a half strides at 0.8 Hz.
    pub window_s: f64,
    /// Time between two evaluations, s.
    pub every_s: f64,
    /// Evaluations that vote.
    pub votes: usize,
    /// Votes a new mode needs to replace the current one.
    pub switch_votes: usize,
    /// Smallest rms of the specific force about its mean for a gait, m/s².
    pub accel_rms_min: f64,
    /// Smallest autocorrelation of the vertical specific force at the step period for a gait.
    pub periodicity_min: f64,
    /// Largest step correlation c₁ of a limb. Oxford: pockets and the swinging arm −0.06 …
    /// 0.14, hand, bag and neck 0.15 … 0.67.
    pub step_corr_max: f64,
    /// Smallest c₂ − c₁ of a swinging limb. Oxford: front pocket and swinging arm ≥ 0.23.
    pub stride_gain_min: f64,
    /// Smallest tilt of a limb without a stride gain (a back pocket), degrees. Oxford: back
    /// pockets ≥ 17.7°, hand ≤ 12.7°.
    pub limb_tilt_deg: f64,
    /// Smallest |u_y| of a pocket. Oxford pockets ≥ 0.87, the swinging arm ≤ 0.68.
    pub pocket_axis_min: f64,
    /// Smallest u_z of the hand, screen up. Microsoft 1.0, IPIN 0.47–0.61, Oxford 0.84–0.99.
    pub screen_up_min: f64,
    /// Largest tilt of the hand, degrees. Oxford hand ≤ 12.7°, bags ≥ 16.8°.
    pub hand_tilt_deg: f64,
    /// Largest |u_z| of the ear (screen sideways).
    pub screen_side_max: f64,
    /// Largest forward axis of the ear. Oxford armbands ≤ 0.51, neck pouches ≥ 0.88.
    pub forward_z_max: f64,
    /// Largest drift of a window that votes, degrees: past it the phone turned over within
    /// the window (it is being moved to another place), and its features mix two modes. Real
    /// walks: 0–2.3 % of the windows above 20° (Oxford's purse and swinging arm, TyrEx's
    /// swinging hand); the simulated moves between modes 17–130°.
    pub drift_max_deg: f64,
    /// With a gyroscope: the smallest swing rate of a limb, rad/s. TyrEx (p5 … p95): at the ear
    /// 0.15 … 0.39, pockets ≥ 0.63, the swinging hand ≥ 0.88; the simulated bag ≤ 0.56.
    pub swing_rate_min: f64,
    /// With a gyroscope: the largest tilt per swing rate of a swinging hand, degrees per rad/s.
    /// A phone turned by an angle A at the stride frequency f, the specific force staying put
    /// in the world, tilts by A in the device at a rate 2πf·A: 57.3°/(2πf) ≈ 10°/(rad/s) at
    /// 0.9 Hz. A thigh comes near that (real pockets ≥ 10.6 at p5, the simulator's 7.7–10.7);
    /// a hand swung as a pendulum keeps the force along the arm and tilts less (TyrEx
    /// swinging: median 6.1, p75 7.7).
    pub pendulum_ratio_max: f64,
    /// With a gyroscope: the smallest swing axis |z| of a hand swung about the screen's
    /// normal, whose tilt per rate may then reach [`CarryConfig::side_swing_ratio_max`].
    /// TyrEx swinging: 0.90 at p25; real pockets ≤ 0.88 at p95 (the running pocket ≤ 0.96,
    /// at ratios ≥ 16).
    pub side_swing_axis_min: f64,
    /// With a gyroscope: the largest tilt per swing rate of a hand swung about the screen's
    /// normal, degrees per rad/s. No real pocket window with such an axis came below it.
    pub side_swing_ratio_max: f64,
    /// With a gyroscope: the largest step correlation c₁ of the ear when the forward surge is
    /// along the screen's normal. The head sways to the side of each foot in turn (TyrEx at the
    /// ear: c₁ ≤ 0.33 at p95); the trunk repeats each step (simulated bag ≥ 0.58, Oxford neck
    /// pouches ≥ 0.48 at p5).
    pub ear_step_corr_max: f64,
}

impl Default for CarryConfig {
    fn default() -> Self {
        CarryConfig {
            window_s: 3.0,
            every_s: 0.5,
            votes: 6,
            switch_votes: 4,
            accel_rms_min: 0.5,
            periodicity_min: 0.3,
            step_corr_max: 0.15,
            stride_gain_min: 0.15,
            limb_tilt_deg: 17.0,
            pocket_axis_min: 0.8,
            screen_up_min: 0.4,
            hand_tilt_deg: 14.0,
            screen_side_max: 0.5,
            forward_z_max: 0.7,
            drift_max_deg: 20.0,
            swing_rate_min: 0.6,
            pendulum_ratio_max: 7.5,
            side_swing_axis_min: 0.9,
            side_swing_ratio_max: 12.5,
            ear_step_corr_max: 0.35,
        }
    }
}

impl CarryConfig {
    /// The mode one evaluation's features say (the rule in the module's documentation).
    pub fn classify(&self, f: &CarryFeatures) -> CarryMode {
        if f.up[2] >= self.screen_up_min && f.tilt_deg < self.hand_tilt_deg {
            return CarryMode::Hand;
        }
        match (f.swing_rate, f.swing_axis_z) {
            (Some(swing), Some(axis_z)) => self.classify_with_rate(f, swing, axis_z),
            _ => self.classify_without_rate(f),
        }
    }

    /// The rule with a gyroscope, after the hand: `swing` the swing rate (rad/s), `axis_z`
    /// the swing axis's |z|.
    fn classify_with_rate(&self, f: &CarryFeatures, swing: f64, axis_z: f64) -> CarryMode {
        if swing >= self.swing_rate_min {
            let ratio = f.tilt_deg / swing;
            let pendulum = ratio < self.pendulum_ratio_max;
            let side = axis_z >= self.side_swing_axis_min && ratio < self.side_swing_ratio_max;
            // A pocket holds the screen near the vertical: screen up, it is a hand moving.
            let screen_up = f.up[2] >= self.screen_up_min;
            return if pendulum || side || screen_up {
                CarryMode::Swinging
            } else {
                CarryMode::Pocket
            };
        }
        let sideways = libm::fabs(f.up[2]) < self.screen_side_max;
        if sideways && (f.forward_z < self.forward_z_max || f.step_corr < self.ear_step_corr_max) {
            CarryMode::Ear
        } else {
            CarryMode::Bag
        }
    }

    /// The rule from the accelerometer alone, after the hand.
    fn classify_without_rate(&self, f: &CarryFeatures) -> CarryMode {
        let limb = f.step_corr < self.step_corr_max
            && (f.stride_corr - f.step_corr >= self.stride_gain_min
                || f.tilt_deg >= self.limb_tilt_deg);
        if limb {
            if libm::fabs(f.up[1]) >= self.pocket_axis_min {
                CarryMode::Pocket
            } else {
                CarryMode::Swinging
            }
        } else if libm::fabs(f.up[2]) < self.screen_side_max && f.forward_z < self.forward_z_max {
            CarryMode::Ear
        } else {
            CarryMode::Bag
        }
    }

    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("carry.window_s", self.window_s)?;
        positive("carry.every_s", self.every_s)?;
        positive("carry.limb_tilt_deg", self.limb_tilt_deg)?;
        positive("carry.hand_tilt_deg", self.hand_tilt_deg)?;
        positive("carry.drift_max_deg", self.drift_max_deg)?;
        positive("carry.swing_rate_min", self.swing_rate_min)?;
        positive("carry.pendulum_ratio_max", self.pendulum_ratio_max)?;
        positive("carry.side_swing_ratio_max", self.side_swing_ratio_max)?;
        if self.votes == 0 {
            return Err(ConfigError::new("carry.votes", "must be at least 1"));
        }
        if self.switch_votes == 0 || self.switch_votes > self.votes {
            return Err(ConfigError::new(
                "carry.switch_votes",
                "must be in 1 ..= carry.votes",
            ));
        }
        Ok(())
    }
}

/// The features of the last evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct CarryFeatures {
    /// Where gravity sits in the device (u), unit.
    pub up: [f64; 3],
    /// Rms swing of the specific force's direction, degrees.
    pub tilt_deg: f64,
    /// Autocorrelation at one step, c₁.
    pub step_corr: f64,
    /// Autocorrelation at two steps, c₂.
    pub stride_corr: f64,
    /// |z| of the forward surge's axis in the device frame.
    pub forward_z: f64,
    /// Rms rate about the mean, rad/s, with a gyroscope.
    pub rate: Option<f64>,
    /// Rms rate about the horizontal axes, rad/s (the rate's covariance without its part
    /// about u): a limb's swing without the walk's turns, with a gyroscope.
    pub swing_rate: Option<f64>,
    /// |z| of the main axis of that horizontal rotation in the device frame: near 1 when the
    /// phone swings about its screen's normal, as a hand at the side swings it.
    pub swing_axis_z: Option<f64>,
    /// The step period found, s.
    pub step_s: f64,
    /// The angle between the mean specific force of the window's first half and of its
    /// second, degrees: how far the phone turned over within the window.
    pub drift_deg: f64,
}

/// The detector's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct CarryDiagnostics {
    /// The mode decided, once one was.
    pub mode: Option<CarryMode>,
    /// The last evaluation's own answer.
    pub raw: Option<CarryMode>,
    /// Its features.
    pub features: Option<CarryFeatures>,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Mode changes so far (the first decision is not one).
    pub switches: u64,
}

/// Samples are averaged over slots of this length before they enter the window: the features
/// live below 5 Hz, and a 400 Hz phone then costs what a 50 Hz one does. (40 ms slots cost
/// half as much, but blur a back pocket's steps.)
const SLOT_S: f64 = 0.02;

/// The lags searched for the step period, slots: 0.28–0.85 s.
fn step_lags() -> RangeInclusive<usize> {
    libm::round(0.28 / SLOT_S) as usize..=libm::round(0.85 / SLOT_S) as usize
}

/// The angle between the mean specific force of the first half of `slots` and of the second,
/// degrees (0 for fewer than two slots).
fn drift_deg(slots: &[window::Closed]) -> f64 {
    let half = slots.len() / 2;
    if half == 0 {
        return 0.0;
    }
    let first: nalgebra::Vector3<f64> = slots[..half].iter().map(|c| c.a).sum();
    let second: nalgebra::Vector3<f64> = slots[half..].iter().map(|c| c.a).sum();
    let (n1, n2) = (first.norm(), second.norm());
    if !(n1 > 0.0 && n2 > 0.0) {
        return 0.0;
    }
    libm::acos((first.dot(&second) / (n1 * n2)).clamp(-1.0, 1.0)).to_degrees()
}

/// The vote over the last evaluations' modes, and the mode it decided.
#[derive(Debug, Clone, Default)]
pub struct Ballot {
    votes: VecDeque<CarryMode>,
    mode: Option<CarryMode>,
    /// The phone was moved since the last vote ([`Ballot::reopen`]).
    reopened: bool,
}

impl Ballot {
    /// Adds an evaluation's mode and returns the mode decided: the first decision takes the
    /// plurality of the first two votes (a second); a new mode then needs
    /// [`CarryConfig::switch_votes`] of the last [`CarryConfig::votes`].
    pub fn cast(&mut self, raw: CarryMode, cfg: &CarryConfig) -> Option<CarryMode> {
        self.votes.push_back(raw);
        while self.votes.len() > cfg.votes {
            self.votes.pop_front();
        }
        let count = |m: CarryMode| self.votes.iter().filter(|&&v| v == m).count();
        match self.mode {
            None if self.votes.len() >= 2 => {
                self.mode = CarryMode::ALL.into_iter().max_by_key(|&m| count(m));
            }
            Some(_) if self.reopened && self.votes.len() >= 2 && count(raw) >= 2 => {
                self.mode = Some(raw);
                self.reopened = false;
            }
            Some(m) if m != raw && count(raw) >= cfg.switch_votes => self.mode = Some(raw),
            _ => {}
        }
        self.mode
    }

    /// Forgets the votes; the mode decided is kept.
    pub fn clear(&mut self) {
        self.votes.clear();
    }

    /// The mode decided, or before any is (or since the phone was moved), the latest vote cast.
    pub fn provisional(&self) -> Option<CarryMode> {
        self.mode.or(self.votes.back().copied())
    }

    /// Forgets the votes after the phone was moved. From a hand (screen up, swinging, at the
    /// ear), which also moves it, the mode is kept until two votes agree on one, which then
    /// replaces it (instead of [`CarryConfig::switch_votes`] of them). From a pocket or a bag
    /// the phone is taken out, and that mode's heading (the thigh's sign, the acceleration's)
    /// does not hold while it moves: the mode is not known until two votes decide it.
    pub fn reopen(&mut self) {
        self.votes.clear();
        self.reopened = true;
        if matches!(self.mode, Some(CarryMode::Pocket | CarryMode::Bag)) {
            self.mode = None;
        }
    }
}

/// The running detector.
#[derive(Debug, Clone)]
pub struct Carry {
    cfg: CarryConfig,
    window: Window,
    filling: Option<Slot>,
    next_eval_t: f64,
    ballot: Ballot,
    diag: CarryDiagnostics,
}

impl Carry {
    /// A detector that has seen nothing.
    pub fn new(cfg: CarryConfig) -> Self {
        Carry {
            cfg,
            // From the shortest step period searched's neighbour to the stride of the longest's.
            window: Window::new(step_lags().start() - 1..=2 * (step_lags().end() + 1)),
            filling: None,
            next_eval_t: f64::NEG_INFINITY,
            ballot: Ballot::default(),
            diag: CarryDiagnostics::default(),
        }
    }

    /// Adds a sample (specific force and rate in the device frame, m/s² and rad/s; the vertical
    /// acceleration in the navigation frame, m/s²) with whether the phone is being handled
    /// ([`crate::engine::handling`]), and returns the mode.
    pub fn push(
        &mut self,
        t: f64,
        accel: &DeviceVec,
        up: f64,
        gyro: Option<&DeviceVec>,
        handling: bool,
    ) -> Option<CarryMode> {
        let s = self.filling.get_or_insert(Slot {
            t0: t,
            ..Slot::default()
        });
        if t >= s.t0 + SLOT_S {
            let done = *s;
            *s = Slot {
                t0: t,
                ..Slot::default()
            };
            self.window.push(&done, t - self.cfg.window_s);
        }
        s.n += 1.0;
        s.up += up;
        s.a += accel;
        if let Some(w) = gyro {
            s.nw += 1.0;
            s.w += w;
        }
        if t >= self.next_eval_t {
            self.next_eval_t = t + self.cfg.every_s;
            if !handling {
                self.evaluate(t);
            }
        }
        self.diag.mode
    }

    /// Forgets the window and the votes (after a gap); the mode decided is kept.
    pub fn clear(&mut self) {
        self.window.clear();
        self.filling = None;
        self.ballot.clear();
    }

    /// The mode decided, once one was.
    pub fn mode(&self) -> Option<CarryMode> {
        self.diag.mode
    }

    /// The mode decided, or while none is (the first second of evaluations, or after the phone
    /// was moved), the latest evaluation's since then: the best word there is now, for a
    /// decision that cannot wait for the vote (the onset look-back).
    pub fn provisional(&self) -> Option<CarryMode> {
        self.ballot.provisional()
    }

    /// The current values.
    pub fn diagnostics(&self) -> CarryDiagnostics {
        self.diag
    }

    fn evaluate(&mut self, t: f64) {
        let span = self.window.slots().first().map_or(0.0, |f| t - f.t0);
        if span < 0.8 * self.cfg.window_s {
            return;
        }
        let Some(f) = self.features() else {
            return;
        };
        if f.drift_deg > self.cfg.drift_max_deg {
            self.ballot.reopen();
            return;
        }
        let raw = self.cfg.classify(&f);
        self.diag.features = Some(f);
        self.diag.raw = Some(raw);
        self.diag.evaluations += 1;
        let before = self.diag.mode;
        self.diag.mode = self.ballot.cast(raw, &self.cfg);
        if before.is_some() && self.diag.mode != before {
            self.diag.switches += 1;
        }
    }

    fn features(&mut self) -> Option<CarryFeatures> {
        let mu = self.window.centre();
        let w = &self.window;
        let (a, s) = (w.slots(), w.sums());
        let n = a.len() as f64;
        let m = s.a() / n;
        let g = m.norm();
        // Σ |a − m|² = Σ |a|² − n |m|².
        let var = (s.aa_trace() / n - m.norm_squared()).max(0.0);
        let rms = libm::sqrt(var);
        if !(g > 1.0) || rms < self.cfg.accel_rms_min {
            return None;
        }
        let u = m / g;
        // Σ 2(1 − cos θ) = 2(n − u·Σ a/|a|), where 2(1 − cos θ) = (2 sin(θ/2))², θ² within
        // 0.7 % up to 30°, without an acos.
        let tilt = libm::sqrt((2.0 * (n - u.dot(&s.dir()))).max(0.0) / n).to_degrees();
        // Autocorrelations at a lag in slots (the slots are SLOT_S apart within a few percent),
        // each over the pairs it has: a stride's lag has half the window's.
        let corr = |k: usize| {
            if k == 0 || k >= a.len() {
                return 0.0;
            }
            let c: f64 = (0..a.len() - k)
                .map(|i| (a[i].a - m).dot(&(a[i + k].a - m)))
                .sum();
            c / (a.len() - k) as f64 / var.max(1e-12)
        };
        let var_v = w.centred_lag_sum(0, mu) / n;
        let corr_v = |k: usize| -> f64 {
            let m = a.len().saturating_sub(k).max(1);
            w.centred_lag_sum(k, mu) / m as f64 / var_v.max(1e-12)
        };
        // Every other lag, then the best one's neighbours.
        let best = |b: (usize, f64), x: (usize, f64)| if x.1 > b.1 { x } else { b };
        let score = |k: usize| (k, 0.5 * (corr_v(k) + corr_v(2 * k)));
        let coarse = step_lags()
            .step_by(2)
            .map(score)
            .fold((0, f64::NEG_INFINITY), best);
        let (step, periodicity) = [coarse.0.saturating_sub(1), coarse.0 + 1]
            .into_iter()
            .map(score)
            .fold(coarse, best);
        if periodicity < self.cfg.periodicity_min {
            return None;
        }
        // The horizontal part of Σ (a − m)(a − m)ᵀ = Σ a aᵀ − m (Σ a)ᵀ.
        let p = Matrix3::identity() - u * u.transpose();
        let h = p * (s.aa() - m * s.a().transpose()) * p;
        let e = SymmetricEigen::new(h);
        let forward_z = libm::fabs(e.eigenvectors.column(e.eigenvalues.imax())[2]);
        // Σ |ω − ω̄|² = Σ |ω|² − k |ω̄|² over the k slots with a rate.
        let (nw, sw, sww) = s.rate();
        let rate = (nw * 2.0 >= n).then(|| {
            let mw = sw / nw;
            libm::sqrt((sww / nw - mw.norm_squared()).max(0.0))
        });
        // The rate's covariance about the horizontal axes: P C P, P = I − u uᵀ.
        let swing = rate.map(|_| p * (s.ww() / nw - (sw / nw) * (sw / nw).transpose()) * p);
        Some(CarryFeatures {
            up: [u.x, u.y, u.z],
            tilt_deg: tilt,
            step_corr: corr(step),
            stride_corr: corr(2 * step),
            forward_z,
            rate,
            swing_rate: swing.map(|c| libm::sqrt(c.trace().max(0.0))),
            step_s: step as f64 * SLOT_S,
            drift_deg: drift_deg(a),
            swing_axis_z: swing.map(|c| {
                let e = SymmetricEigen::new(c);
                libm::fabs(e.eigenvectors.column(e.eigenvalues.imax())[2])
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn a_phone_at_rest_or_a_tiny_window_decides_nothing_and_never_panics() {
        for window_s in [3.0, 0.1] {
            let mut c = Carry::new(CarryConfig {
                window_s,
                ..CarryConfig::default()
            });
            let g = Vector3::new(0.0, 0.0, 9.81);
            for i in 0..2000 {
                let t = f64::from(i) * 0.01;
                // At rest, then a bounce too fast and too small for a gait.
                let a = if i < 1000 {
                    g
                } else {
                    g * (1.0 + 0.01 * libm::sin(t * 60.0))
                };
                assert_eq!(c.push(t, &a, 0.0, Some(&Vector3::zeros()), false), None);
            }
            assert_eq!(c.diagnostics().evaluations, 0);
        }
    }

    /// Features with a gyroscope: u, tilt (°), c₁, forward axis, swing rate (rad/s), swing
    /// axis |z|.
    fn with_rate(
        up: [f64; 3],
        tilt: f64,
        c1: f64,
        fz: f64,
        swing: f64,
        axis_z: f64,
    ) -> CarryFeatures {
        CarryFeatures {
            up,
            tilt_deg: tilt,
            step_corr: c1,
            stride_corr: 0.6,
            forward_z: fz,
            rate: Some(swing),
            swing_rate: Some(swing),
            swing_axis_z: Some(axis_z),
            ..CarryFeatures::default()
        }
    }

    #[test]
    fn with_a_gyroscope_the_swing_tells_the_pocket_the_swinging_hand_and_the_ear_apart() {
        let c = CarryConfig::default();
        let down = [0.1, 0.95, 0.1];
        // TyrEx's medians: a front pocket, a hand swung as a pendulum, one swung about the
        // screen's normal at a thigh's tilt per rate, the ear, texting.
        let cases = [
            (
                with_rate(down, 13.0, -0.1, 0.96, 0.92, 0.2),
                CarryMode::Pocket,
            ),
            (
                with_rate(down, 8.8, 0.2, 0.67, 1.55, 0.5),
                CarryMode::Swinging,
            ),
            (
                with_rate(down, 11.0, 0.0, 0.8, 1.0, 0.95),
                CarryMode::Swinging,
            ),
            (
                with_rate([0.5, 0.77, -0.32], 5.7, -0.04, 0.88, 0.25, 0.9),
                CarryMode::Ear,
            ),
            (
                with_rate([0.05, 0.08, 0.99], 4.3, 0.2, 0.07, 0.26, 0.06),
                CarryMode::Hand,
            ),
            // The simulated bag: a trunk repeats each step, its surge along the screen's normal.
            (
                with_rate([0.4, 0.9, 0.0], 7.6, 0.92, 0.81, 0.49, 0.93),
                CarryMode::Bag,
            ),
            // Screen up and swinging, not steady: a hand moving the phone, not a pocket.
            (
                with_rate([0.0, 0.6, 0.8], 26.0, 0.1, 0.2, 1.3, 0.3),
                CarryMode::Swinging,
            ),
        ];
        for (f, want) in cases {
            assert_eq!(c.classify(&f), want, "{f:?}");
        }
        // Without a gyroscope the accelerometer's rule decides: the Oxford front pocket.
        let f = CarryFeatures {
            up: [0.05, 1.0, 0.06],
            tilt_deg: 18.7,
            step_corr: -0.04,
            stride_corr: 0.8,
            forward_z: 0.81,
            ..CarryFeatures::default()
        };
        assert_eq!(c.classify(&f), CarryMode::Pocket);
    }

    #[test]
    fn the_ballot_decides_switches_and_starts_afresh_after_a_move() {
        use CarryMode::{Bag, Ear, Hand, Pocket, Swinging};
        let c = CarryConfig::default();
        let mut b = Ballot::default();
        assert_eq!(b.cast(Hand, &c), None);
        assert_eq!(b.cast(Hand, &c), Some(Hand));
        for _ in 0..3 {
            assert_eq!(b.cast(Pocket, &c), Some(Hand));
        }
        assert_eq!(b.cast(Pocket, &c), Some(Pocket), "4 of the last 6");
        // Out of a pocket the mode is not known until two votes decide.
        b.reopen();
        assert_eq!(b.mode, None);
        assert_eq!(b.cast(Swinging, &c), None);
        assert_eq!(b.cast(Swinging, &c), Some(Swinging));
        // Moved by the hand holding it: kept until two votes agree on another.
        b.reopen();
        assert_eq!(b.cast(Ear, &c), Some(Swinging));
        assert_eq!(b.cast(Bag, &c), Some(Swinging));
        assert_eq!(b.cast(Bag, &c), Some(Bag));
        // Then the usual rule again.
        assert_eq!(b.cast(Ear, &c), Some(Bag));
        assert_eq!(b.cast(Ear, &c), Some(Bag));
    }

    #[test]
    fn before_the_ballot_decides_its_latest_vote_stands_in() {
        use CarryMode::{Bag, Hand, Pocket};
        let c = CarryConfig::default();
        let mut b = Ballot::default();
        assert_eq!(b.provisional(), None);
        b.cast(Pocket, &c);
        assert_eq!((b.mode, b.provisional()), (None, Some(Pocket)));
        b.cast(Pocket, &c);
        assert_eq!(b.provisional(), Some(Pocket));
        // Decided, the mode stands whatever the latest vote.
        b.cast(Bag, &c);
        assert_eq!((b.mode, b.provisional()), (Some(Pocket), Some(Pocket)));
        // Out of a pocket the mode is undecided, and so is the word until a vote is cast.
        b.reopen();
        assert_eq!(b.provisional(), None);
        b.cast(Hand, &c);
        assert_eq!((b.mode, b.provisional()), (None, Some(Hand)));
    }

    #[test]
    fn the_drift_is_how_far_the_phone_turned_over_within_the_window() {
        let slot = |i: usize, a: Vector3<f64>| window::Closed {
            t0: i as f64 * SLOT_S,
            a,
        };
        let g = Vector3::new(0.0, 9.81, 0.0);
        let steady: Vec<window::Closed> = (0..100)
            .map(|i| slot(i, g * (1.0 + 0.1 * libm::sin(i as f64))))
            .collect();
        assert!(drift_deg(&steady) < 1.0);
        let turned: Vec<window::Closed> = (0..100)
            .map(|i| {
                slot(
                    i,
                    if i < 50 {
                        g
                    } else {
                        Vector3::new(0.0, 0.0, 9.81)
                    },
                )
            })
            .collect();
        assert!((drift_deg(&turned) - 90.0).abs() < 1e-9);
        assert_eq!(drift_deg(&turned[..1]), 0.0);
    }
}
