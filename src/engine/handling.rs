//! Handling: the phone turned over in the hand (a compass calibration's figure of eight, taking it
//! out, looking at it from every side) is not a gait, whatever rhythm its acceleration has (ours;
//! none of the papers has it).
//! May import: the rest of `engine`.
//!
//! Every IPIN 2023 log opens with 30–40 s of such handling: σ_z of 2–7 m/s² at a rhythm the
//! motion detector (Basso 2016 §II.B) takes for walking, so the PLL counted tens of steps
//! before each walk began, and the GNSS fusion learnt its corrections from them.
//!
//! The rule, over a window of [`HandlingConfig::window_s`]: the phone turns fast, mean |ω| ≥
//! [`HandlingConfig::rate_min`], about no single axis, the largest eigenvalue of Σ ω ωᵀ is less
//! than [`HandlingConfig::axis_share_max`] of its trace; about an axis that wanders in the
//! device, the main axes of the window and of the window before it apart by more than
//! acos [`HandlingConfig::axis_steady_min`]; and it is not running. A gait turns the phone
//! slowly, or about one axis, or about an axis that stays put in the device (a limb's swing:
//! the hand that holds it keeps its grip, the pocket its place on the thigh):
//! - IPIN 2023, hand-held walks: mean |ω| 0.1–0.5 rad/s walking, ≤ 1.1 rad/s in turns (about
//!   the vertical, share ≥ 0.85); handling 2–7.5 rad/s, shares 0.46–0.88;
//! - the simulator's thigh in 8 pocket poses (walking, stairs, sitting down): ≤ 2.4 rad/s;
//!   running in the pocket: ≤ 3.0 rad/s, share ≥ 0.69 (p10 1.0).
//!
//! - a thigh in a trouser pocket at a brisk pace (UbiComp 2013, 23 walks) passes the rate and
//!   share tests in 2 s windows (the near leg's rotation about the hip and about the femur),
//!   but its main axis stays put: |cos| between consecutive 2 s windows ≥ 0.97 on 95 % of
//!   those windows; a hand swinging at the side (TyrEx) has a median of 0.98; IPIN's handling
//!   a median of 0.66 and a 90th percentile of 0.96. The windows are whole blocks, the last
//!   two windows and the two one block earlier: a single window that a gait's wobble takes
//!   below the threshold does not make handling.
//!
//! Until a whole window of complete blocks lies before the last one (the input's first 4 s,
//! and after a gap), the steadiness is not known and the share alone decides.
//!
//! Handling lasts [`HandlingConfig::hold_s`] beyond the last window that shows it, so that the
//! slower turns between two fast ones do not count as steps. Without a gyroscope the rule never
//! fires.

use super::math::{from_outer_entries, outer_entries};
use super::motion::Motion;
use super::types::{positive, ConfigError, DeviceVec};
use nalgebra::SymmetricEigen;
use std::collections::VecDeque;

/// Settings of the handling detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct HandlingConfig {
    /// Window, s.
    pub window_s: f64,
    /// Smallest mean |ω| over the window, rad/s. 3: above the simulated thigh's 2.4 walking
    /// and 3.0 running, below the 4–7 rad/s of most IPIN handling windows.
    pub rate_min: f64,
    /// Largest share of the rotation about its main axis, below 1. 0.85: a turn while walking
    /// (IPIN) and a running thigh (simulator) are above it, most handling is below.
    pub axis_share_max: f64,
    /// Smallest |cos| between the main rotation axes (in the device) of the last 2 s window of
    /// complete blocks and of the window before it at which the rotation is a limb's swing,
    /// not handling; at most 1 (1 turns the test off: only an axis that does not move at all
    /// would pass). 0.98 (the axis within 11°): above nine in ten of IPIN's handling windows,
    /// below nineteen in twenty of a pocketed thigh's fast ones.
    pub axis_steady_min: f64,
    /// How long handling lasts after the last window that shows it, s.
    pub hold_s: f64,
}

impl Default for HandlingConfig {
    fn default() -> Self {
        HandlingConfig {
            window_s: 2.0,
            rate_min: 3.0,
            axis_share_max: 0.85,
            axis_steady_min: 0.98,
            hold_s: 2.0,
        }
    }
}

impl HandlingConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("handling.window_s", self.window_s)?;
        positive("handling.rate_min", self.rate_min)?;
        positive("handling.hold_s", self.hold_s)?;
        if !(self.axis_share_max > 0.0 && self.axis_share_max <= 1.0) {
            return Err(ConfigError::new(
                "handling.axis_share_max",
                "must be in (0, 1]",
            ));
        }
        if !(self.axis_steady_min > 0.0 && self.axis_steady_min <= 1.0) {
            return Err(ConfigError::new(
                "handling.axis_steady_min",
                "must be in (0, 1]",
            ));
        }
        Ok(())
    }
}

/// The detector's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct HandlingDiagnostics {
    /// The phone is being handled.
    pub handling: bool,
    /// Mean |ω| over the window, rad/s.
    pub rate: f64,
    /// Share of the rotation about its main axis (0 when the phone is at rest).
    pub axis_share: f64,
    /// |cos| between the main axes of the window and of the window before it (0 when either
    /// is at rest).
    pub axis_steady: f64,
    /// Time spent handling so far, s.
    pub total_s: f64,
}

/// The window is kept as blocks of this many seconds: a sample costs a few additions, a new block
/// a sum over the window's nine (cheaper than a deque of samples).
const BLOCK_S: f64 = 0.25;

/// Sums over some samples: their number, Σ |ω|, and Σ ω ωᵀ's six distinct entries (xx, yy, zz,
/// xy, xz, yz).
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    n: f64,
    rate: f64,
    moment: [f64; 6],
}

impl Sums {
    fn add(&mut self, o: &Sums) {
        self.n += o.n;
        self.rate += o.rate;
        for (m, x) in self.moment.iter_mut().zip(o.moment) {
            *m += x;
        }
    }

    fn of(w: &DeviceVec) -> Sums {
        Sums {
            n: 1.0,
            rate: libm::sqrt(w.x * w.x + w.y * w.y + w.z * w.z),
            moment: outer_entries(w),
        }
    }
}

/// The running detector.
#[derive(Debug, Clone)]
pub struct Handling {
    cfg: HandlingConfig,
    // The blocks of the last two windows (start time, sums), the newest filling; the window's
    // total (its blocks and the samples of the filling one).
    blocks: VecDeque<(f64, Sums)>,
    total: Sums,
    // The steadiness of the main axis over the complete blocks, judged once per block when
    // needed: the last window of complete blocks and the one before it; and the same one
    // block earlier.
    steady: Steady,
    steady_before: Steady,
    until: Option<f64>,
    last_t: Option<f64>,
    diag: HandlingDiagnostics,
}

/// The two windows of complete blocks whose main axes the steadiness compares, and the
/// steadiness once computed.
#[derive(Debug, Clone, Copy, Default)]
struct Steady {
    now: Sums,
    before: Sums,
    known: bool,
    value: Option<f64>,
}

impl Steady {
    fn value(&mut self) -> f64 {
        let (now, before) = (self.now, self.before);
        *self
            .value
            .get_or_insert_with(|| steadiness(&main_axis(&now), &main_axis(&before)))
    }
}

impl Handling {
    /// A detector that has seen nothing.
    pub fn new(cfg: HandlingConfig) -> Self {
        Handling {
            cfg,
            blocks: VecDeque::new(),
            total: Sums::default(),
            steady: Steady::default(),
            steady_before: Steady::default(),
            until: None,
            last_t: None,
            diag: HandlingDiagnostics::default(),
        }
    }

    /// Adds a sample's angular rate (device frame, rad/s; `None` without a gyroscope) with the
    /// motion detector's state, and says whether the phone is being handled.
    pub fn push(&mut self, t: f64, gyro: Option<&DeviceVec>, motion: Motion) -> bool {
        let dt = self.last_t.map_or(0.0, |l| (t - l).max(0.0));
        self.last_t = Some(t);
        if let Some(w) = gyro {
            let x = Sums::of(w);
            match self.blocks.back_mut() {
                Some((t0, b)) if t < *t0 + BLOCK_S => {
                    b.add(&x);
                    self.total.add(&x);
                }
                _ => self.new_block(t, x),
            }
        }
        // The span of the blocks in the window: the blocks are in time order, so the first in
        // it is found by bisection, and only when the rate asks.
        let span = || {
            let w = self.cfg.window_s;
            let first = self.blocks.partition_point(|(t0, _)| *t0 + BLOCK_S < t - w);
            self.blocks.get(first).map_or(0.0, |(t0, _)| t - t0)
        };
        self.diag.rate = if self.total.n > 0.0 {
            self.total.rate / self.total.n
        } else {
            0.0
        };
        // The eigenvalues only when the rate calls for them: they cost more than the rest.
        if self.diag.rate >= self.cfg.rate_min
            && span() >= 0.5 * self.cfg.window_s
            && motion != Motion::Running
            && main_axis(&self.total).share < self.cfg.axis_share_max
            // Until a whole window lies before the last one (the input's first seconds), the
            // axis before is not known: the share alone decides.
            && !self.steady_axis()
        {
            self.until = Some(t + self.cfg.hold_s);
        }
        let handling = self.until.is_some_and(|u| t <= u);
        if handling && self.diag.handling {
            self.diag.total_s += dt;
        }
        self.diag.handling = handling;
        handling
    }

    /// Starts a block at `t` with its first sample. Blocks older than two windows leave; the
    /// window's total is summed afresh from its blocks (no rounding accumulates), and the
    /// complete blocks are split into the last window and the one before it for the
    /// steadiness.
    fn new_block(&mut self, t: f64, x: Sums) {
        let w = self.cfg.window_s;
        self.blocks.push_back((t, x));
        while self
            .blocks
            .front()
            .is_some_and(|(t0, _)| *t0 + BLOCK_S < t - 2.0 * w)
        {
            self.blocks.pop_front();
        }
        self.total = Sums::default();
        for (_, b) in self.blocks.iter().filter(|(t0, _)| *t0 + BLOCK_S >= t - w) {
            self.total.add(b);
        }
        let n = ((w / BLOCK_S).round() as usize).max(1);
        let complete = self.blocks.len() - 1;
        self.steady_before = self.steady;
        self.steady = Steady {
            known: complete >= 2 * n,
            ..Steady::default()
        };
        for (i, (_, b)) in self.blocks.iter().take(complete).enumerate() {
            if i + n >= complete {
                self.steady.now.add(b);
            } else if i + 2 * n >= complete {
                self.steady.before.add(b);
            }
        }
    }

    /// Whether the main axis stayed put: over the last windows of complete blocks, or over
    /// those one block earlier (a single window that a gait's own wobble takes below the
    /// threshold is not handling; handling moves the axis window after window). Not known in
    /// the input's first seconds.
    fn steady_axis(&mut self) -> bool {
        let min = self.cfg.axis_steady_min;
        self.steady.known
            && (self.steady.value() >= min
                || (self.steady_before.known && self.steady_before.value() >= min))
    }

    /// Forgets the window (after a gap in the input).
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.total = Sums::default();
        self.steady = Steady::default();
        self.steady_before = Steady::default();
        self.until = None;
        self.last_t = None;
        self.diag.handling = false;
    }

    /// Whether the phone is being handled now.
    pub fn active(&self) -> bool {
        self.diag.handling
    }

    /// Time spent handling so far, s.
    pub fn total_s(&self) -> f64 {
        self.diag.total_s
    }

    /// The current values.
    pub fn diagnostics(&self) -> HandlingDiagnostics {
        HandlingDiagnostics {
            axis_share: main_axis(&self.total).share,
            axis_steady: if self.steady.known {
                self.steady.clone().value()
            } else {
                0.0
            },
            ..self.diag
        }
    }
}

/// The main axis of a rotation: the unit eigenvector of Σ ω ωᵀ's largest eigenvalue, and that
/// eigenvalue's share of the trace (0, with no axis, at rest).
struct Axis {
    axis: Option<DeviceVec>,
    share: f64,
}

fn main_axis(s: &Sums) -> Axis {
    let trace = s.moment[0] + s.moment[1] + s.moment[2];
    if !(trace > 0.0) {
        return Axis {
            axis: None,
            share: 0.0,
        };
    }
    let e = SymmetricEigen::new(from_outer_entries(&s.moment));
    let k = e.eigenvalues.imax();
    Axis {
        axis: Some(e.eigenvectors.column(k).into_owned()),
        share: e.eigenvalues[k] / trace,
    }
}

/// |cos| between two main axes (an axis has no sign); 0 when either is missing.
fn steadiness(a: &Axis, b: &Axis) -> f64 {
    match (a.axis, b.axis) {
        (Some(a), Some(b)) => a.dot(&b).abs(),
        _ => 0.0,
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // test signals, not the track path
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn run(rate: impl Fn(f64) -> Vector3<f64>, motion: Motion) -> f64 {
        let mut h = Handling::new(HandlingConfig::default());
        let mut handled = 0.0;
        for i in 0..2000 {
            let t = i as f64 * 0.01;
            if h.push(t, Some(&rate(t)), motion) {
                handled += 0.01;
            }
        }
        handled
    }

    #[test]
    fn a_phone_turned_every_way_is_handled() {
        // 4 rad/s about an axis that wanders round the sphere every 1.3 s.
        let handled = run(
            |t| {
                let (a, b) = (t * 4.8, t * 2.9);
                Vector3::new(a.cos() * b.cos(), a.sin() * b.cos(), b.sin()) * 4.0
            },
            Motion::Walking,
        );
        assert!(handled > 18.0, "{handled}");
    }

    #[test]
    fn a_thigh_swinging_about_one_axis_is_not() {
        // ±6 rad/s about one axis at 1 Hz (faster than any walk), a little about the others.
        let handled = run(
            |t| {
                let s = (std::f64::consts::TAU * t).sin();
                Vector3::new(6.0 * s, 0.8 * (3.0 * t).cos(), 0.5 * s)
            },
            Motion::Walking,
        );
        assert_eq!(handled, 0.0);
    }

    #[test]
    fn a_hand_swinging_with_a_twisting_wrist_is_not() {
        // The arm's swing, ±5 rad/s at 0.9 Hz about the device's x, and the wrist's twist,
        // ±3.5 rad/s at twice that about an axis of its own: fast, and about no single axis
        // (share 0.67), but about axes that stay put in the device.
        let twist = Vector3::new(0.2, 0.4, 0.9).normalize();
        let swing = |t: f64| {
            let p = std::f64::consts::TAU * 0.9 * t;
            Vector3::x() * 5.0 * p.sin() + twist * 3.5 * (2.0 * p).cos()
        };
        // (In the first 4 s, until a window lies before the current one, the share alone
        // decides, and what it finds is held 2 s more.)
        let mut h = Handling::new(HandlingConfig::default());
        let mut seen = (0.0f64, 1.0f64);
        for i in 0..2000 {
            let t = i as f64 * 0.01;
            let handled = h.push(t, Some(&swing(t)), Motion::Walking);
            assert!(t < 6.5 || !handled, "handled at {t} s");
            let d = h.diagnostics();
            if t > 4.0 {
                seen = (seen.0.max(d.rate), seen.1.min(d.axis_share));
            }
        }
        assert!(seen.0 > 3.0 && seen.1 < 0.85, "{seen:?}");
        // The same signal with the twist's axis wandering through the device every 3 s.
        let mut h = Handling::new(HandlingConfig::default());
        let handled = (0..2000)
            .filter(|&i| {
                let t = i as f64 * 0.01;
                let (s, c) = (2.1 * t).sin_cos();
                let axis = Vector3::new(c, s * 0.6, s * 0.8);
                let p = std::f64::consts::TAU * 0.9 * t;
                let w = axis * 5.0 * p.sin() + twist * 3.5 * (2.0 * p).cos();
                h.push(t, Some(&w), Motion::Walking)
            })
            .count();
        assert!(handled > 1000, "{handled}");
    }

    #[test]
    fn running_is_not_handling_nor_is_a_missing_gyroscope() {
        let every_way = |t: f64| {
            let (a, b) = (t * 4.8, t * 2.9);
            Vector3::new(a.cos() * b.cos(), a.sin() * b.cos(), b.sin()) * 4.0
        };
        assert_eq!(run(every_way, Motion::Running), 0.0);
        let mut h = Handling::new(HandlingConfig::default());
        assert!((0..500).all(|i| !h.push(i as f64 * 0.01, None, Motion::Walking)));
    }
}
