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
//!
//! The window's sums (of the specific force, its square and its direction, of ω and |ω|², and
//! the vertical acceleration's lagged products) are kept as running sums, updated as 20 ms
//! slots enter and leave it and summed afresh every 1024 slots; the means are taken out of
//! them algebraically (Σ (x − x̄)² = Σ x² − n x̄²).
//!
//! # Rule (each [`CarryConfig::every_s`]; a vote of the last [`CarryConfig::votes`] decides)
//! 1. The **hand**, screen up: u_z ≥ [`CarryConfig::screen_up_min`] and tilt <
//!    [`CarryConfig::hand_tilt_deg`]. First: a turn while texting turns the phone fast, and
//!    a hand-held step can look like a limb's (checked second, it took some of the real
//!    hand-held steps).
//! 2. A limb swings it: (c₁ < [`CarryConfig::step_corr_max`] and (c₂ − c₁ ≥
//!    [`CarryConfig::stride_gain_min`] or tilt ≥ [`CarryConfig::limb_tilt_deg`])), or rate ≥
//!    [`CarryConfig::limb_rate_min`]. Then the **pocket** when the long axis is near the
//!    vertical (|u_y| ≥ [`CarryConfig::pocket_axis_min`], the phone along the thigh), else the
//!    **swinging** hand.
//! 3. The **ear**: the screen faces sideways (|u_z| < [`CarryConfig::screen_side_max`]) and so
//!    does the forward surge (forward axis < [`CarryConfig::forward_z_max`]).
//! 4. Else a **bag** or a jacket.
//!
//! The thresholds were set from the Oxford placements' feature medians (accelerometer only,
//! `examples/carry_features.rs`) and the simulator's modes; `docs/methods/carrying-mode.md` has
//! the confusion matrices.

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
    /// Smallest rate of a limb, rad/s. Hand-held walks: ≤ 0.87 (Microsoft), ≤ 0.45 (IPIN);
    /// the simulated thigh ≥ 1.3.
    pub limb_rate_min: f64,
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
            limb_rate_min: 1.2,
            pocket_axis_min: 0.8,
            screen_up_min: 0.4,
            hand_tilt_deg: 14.0,
            screen_side_max: 0.5,
            forward_z_max: 0.7,
        }
    }
}

impl CarryConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("carry.window_s", self.window_s)?;
        positive("carry.every_s", self.every_s)?;
        positive("carry.limb_tilt_deg", self.limb_tilt_deg)?;
        positive("carry.hand_tilt_deg", self.hand_tilt_deg)?;
        positive("carry.limb_rate_min", self.limb_rate_min)?;
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

/// The running detector.
#[derive(Debug, Clone)]
pub struct Carry {
    cfg: CarryConfig,
    window: Window,
    filling: Option<Slot>,
    next_eval_t: f64,
    votes: VecDeque<CarryMode>,
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
            votes: VecDeque::new(),
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
        self.votes.clear();
    }

    /// The mode decided, once one was.
    pub fn mode(&self) -> Option<CarryMode> {
        self.diag.mode
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
        let raw = self.classify(&f);
        self.diag.features = Some(f);
        self.diag.raw = Some(raw);
        self.diag.evaluations += 1;
        self.votes.push_back(raw);
        while self.votes.len() > self.cfg.votes {
            self.votes.pop_front();
        }
        let count = |m: CarryMode| self.votes.iter().filter(|&&v| v == m).count();
        match self.diag.mode {
            // The first decision takes the plurality of the first two votes (a second).
            None if self.votes.len() >= 2 => {
                self.diag.mode = CarryMode::ALL.into_iter().max_by_key(|&m| count(m));
            }
            Some(m) if m != raw && count(raw) >= self.cfg.switch_votes => {
                self.diag.mode = Some(raw);
                self.diag.switches += 1;
            }
            _ => {}
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
        Some(CarryFeatures {
            up: [u.x, u.y, u.z],
            tilt_deg: tilt,
            step_corr: corr(step),
            stride_corr: corr(2 * step),
            forward_z,
            rate,
        })
    }

    fn classify(&self, f: &CarryFeatures) -> CarryMode {
        let c = &self.cfg;
        let limb = (f.step_corr < c.step_corr_max
            && (f.stride_corr - f.step_corr >= c.stride_gain_min || f.tilt_deg >= c.limb_tilt_deg))
            || f.rate.is_some_and(|r| r >= c.limb_rate_min);
        if f.up[2] >= c.screen_up_min && f.tilt_deg < c.hand_tilt_deg {
            CarryMode::Hand
        } else if limb {
            if libm::fabs(f.up[1]) >= c.pocket_axis_min {
                CarryMode::Pocket
            } else {
                CarryMode::Swinging
            }
        } else if libm::fabs(f.up[2]) < c.screen_side_max && f.forward_z < c.forward_z_max {
            CarryMode::Ear
        } else {
            CarryMode::Bag
        }
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
}
