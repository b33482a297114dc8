//! The real phone's GNSS error shapes for the simulated receiver: a multipath bias
//! correlated in time, urban-canyon stretches, an optimistic reported accuracy, a stale first
//! fix, fixes wandering while the walker stands, and a receiver that lags (a constant latency,
//! and a hold at walk start). All are off by default, and they draw their random numbers from a
//! stream of their own, so a scenario that does not ask for them is bit for bit what it was.
//! May import: `engine` and `io`.

use super::{Rng, Truth};
use std::f64::consts::TAU;

/// The multipath bias: a 2-D first-order Gauss–Markov error (per axis
/// b(t+Δt) = e^(−Δt/τ)·b(t) + √(1 − e^(−2Δt/τ))·σ_b·w), plus a white part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Multipath {
    /// Time constant τ, s (IPIN 2023's fixes: autocorrelation of the error ≈ e^(−Δt/14 s)).
    pub tau_s: f64,
    /// Share of the error's variance that is white (drawn afresh at each fix); the rest is the
    /// correlated bias. Per axis, the total σ is the reported accuracy / 1.51 (its 68 % radius),
    /// times [`GnssErrors::optimism`].
    pub white_share: f64,
}

impl Default for Multipath {
    fn default() -> Self {
        Multipath {
            tau_s: 14.0,
            white_share: 0.1,
        }
    }
}

/// An urban-canyon stretch: a large bias held for its whole length while the reported accuracy
/// stays what it was (the receiver does not know).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canyon {
    /// Start and end, s, in the times written out (as [`super::GnssSim::outages`]).
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// Size of the bias, m; its direction is drawn once per stretch.
    pub bias_m: f64,
}

/// How long an urban-canyon bias takes to build up and to go away, s.
pub const CANYON_RAMP_S: f64 = 5.0;

/// The first fix(es) of the log at a position the phone cached elsewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaleFix {
    /// How many of the first fixes are stale.
    pub count: usize,
    /// Distance from the true start, m.
    pub distance_m: f64,
    /// Direction from the true start, degrees clockwise from north.
    pub bearing_deg: f64,
    /// Their reported accuracy, m.
    pub accuracy_m: f64,
}

/// How long the walker must have stood for the receiver to hold its position when the walk
/// starts ([`GnssErrors::start_hold_s`]), s.
pub const HOLD_AFTER_STANDING_S: f64 = 2.0;

/// Time constant with which the error gathered while standing fades once the walker moves, s.
const WANDER_FADE_S: f64 = 10.0;

/// σ of the reported speed's noise, m/s.
const SPEED_NOISE_MPS: f64 = 0.1;

/// The real phone's error shapes; [`Default`] turns every one off.
#[derive(Debug, Clone, PartialEq)]
pub struct GnssErrors {
    /// The correlated multipath bias (None: the error is white, as the reported accuracy says).
    pub multipath: Option<Multipath>,
    /// How far the reported accuracy understates the real error: the error's σ is this times
    /// what the accuracy describes (1: honest; IPIN 2023's logs ranged 0.2–2.8, typically 1).
    pub optimism: f64,
    /// Urban-canyon stretches.
    pub canyons: Vec<Canyon>,
    /// A stale first fix.
    pub stale_first_fix: Option<StaleFix>,
    /// While the walker stands the error random-walks by this RMS distance in 10 s, m (0: off).
    pub stand_wander_m: f64,
    /// When the walker starts walking after standing ([`HOLD_AFTER_STANDING_S`] or more), the
    /// receiver keeps reporting the standing position, at speed 0, for this long, s, then
    /// catches up at once (0: off).
    pub start_hold_s: f64,
    /// Each fix reports where the walker was this long ago, s.
    pub latency_s: f64,
    /// Fill each fix's speed (the truth's, with a little noise; 0 while held).
    pub speed: bool,
}

impl Default for GnssErrors {
    fn default() -> Self {
        GnssErrors {
            multipath: None,
            optimism: 1.0,
            canyons: Vec::new(),
            stale_first_fix: None,
            stand_wander_m: 0.0,
            start_hold_s: 0.0,
            latency_s: 0.0,
            speed: false,
        }
    }
}

impl GnssErrors {
    /// Whether any shape is on.
    pub fn any(&self) -> bool {
        *self != GnssErrors::default()
    }

    /// σ per axis of the white part of the error, for a fix whose reported accuracy describes
    /// `sigma` (exactly `sigma` with every shape off).
    pub(super) fn white_sigma(&self, sigma: f64) -> f64 {
        match self.multipath {
            Some(m) => libm::sqrt(m.white_share) * self.optimism * sigma,
            None => self.optimism * sigma,
        }
    }
}

/// What the receiver reports at one fix, beyond the white error.
pub(super) struct Shaped {
    /// The true position the fix refers to (`latency_s` ago), m.
    pub truth: (f64, f64),
    /// The correlated error: multipath bias, canyon, wander, m.
    pub error: (f64, f64),
    /// Report this position instead (a held or stale fix), m.
    pub replace: Option<(f64, f64)>,
    /// Reported accuracy instead of the ordinary one (a stale fix), m.
    pub accuracy_m: Option<f64>,
    /// Reported speed, m/s.
    pub speed_mps: Option<f64>,
}

/// The error shapes' state along one walk.
pub(super) struct ErrorState<'a> {
    cfg: &'a GnssErrors,
    truth: &'a Truth,
    rng: Rng,
    /// Gauss–Markov state per axis, unit variance.
    gm: (f64, f64),
    /// Error gathered while standing, m.
    wander: (f64, f64),
    /// Time of the previous fix, s.
    last_t: Option<f64>,
    /// Fixes produced so far.
    count: usize,
    /// The last position reported that was neither stale nor held, m.
    last_reported: Option<(f64, f64)>,
    /// Unit direction of each canyon's bias.
    canyon_dirs: Vec<(f64, f64)>,
    /// Start of each walk that follows a stand, s.
    walk_starts: Vec<f64>,
}

impl<'a> ErrorState<'a> {
    pub(super) fn new(cfg: &'a GnssErrors, truth: &'a Truth, seed: u64) -> Self {
        let mut rng = Rng(seed ^ 0x6E55_E440_5EA1_F1E5);
        let gm = (rng.normal(), rng.normal());
        let canyon_dirs = cfg
            .canyons
            .iter()
            .map(|_| libm::sincos(TAU * rng.uniform()))
            .collect();
        let mut walk_starts = Vec::new();
        let mut stood = 0.0;
        for &(a, b, gait) in &truth.segments {
            if gait.moving() {
                if stood >= HOLD_AFTER_STANDING_S {
                    walk_starts.push(a);
                }
                stood = 0.0;
            } else {
                stood += b - a;
            }
        }
        ErrorState {
            cfg,
            truth,
            rng,
            gm,
            wander: (0.0, 0.0),
            last_t: None,
            count: 0,
            last_reported: None,
            canyon_dirs,
            walk_starts,
        }
    }

    /// Whether the walker stands at `t` (any segment that is not walking, running or stairs).
    fn standing(&self, t: f64) -> bool {
        self.truth
            .segments
            .iter()
            .find(|s| t >= s.0 && t < s.1)
            .is_some_and(|s| !s.2.moving())
    }

    /// The true speed at `t`, m/s (over ±0.5 s of the path).
    fn true_speed(&self, t: f64) -> f64 {
        let (e0, n0) = self.truth.position_at(t - 0.5);
        let (e1, n1) = self.truth.position_at(t + 0.5);
        libm::hypot(e1 - e0, n1 - n0)
    }

    /// Notes the position a fix reported when it was neither stale nor held (the position a
    /// hold keeps), m.
    pub(super) fn reported(&mut self, at: (f64, f64)) {
        self.last_reported = Some(at);
    }

    /// The shapes at the fix of time `t` (times written out), whose reported accuracy
    /// describes σ = `sigma` per axis.
    pub(super) fn at(&mut self, t: f64, sigma: f64) -> Shaped {
        let cfg = self.cfg;
        let dt = self.last_t.map_or(0.0, |l| t - l);
        self.last_t = Some(t);
        let index = self.count;
        self.count += 1;
        let mut err = (0.0, 0.0);
        if let Some(m) = cfg.multipath {
            let phi = libm::exp(-dt / m.tau_s);
            let q = libm::sqrt((1.0 - phi * phi).max(0.0));
            self.gm = (
                phi * self.gm.0 + q * self.rng.normal(),
                phi * self.gm.1 + q * self.rng.normal(),
            );
            let sb = libm::sqrt(1.0 - m.white_share) * cfg.optimism * sigma;
            err = (sb * self.gm.0, sb * self.gm.1);
        }
        for (c, &(s, co)) in cfg.canyons.iter().zip(&self.canyon_dirs) {
            let w = ((t - c.start_s).min(c.end_s - t) / CANYON_RAMP_S).clamp(0.0, 1.0);
            err.0 += w * c.bias_m * s;
            err.1 += w * c.bias_m * co;
        }
        let standing = self.standing(t);
        if cfg.stand_wander_m > 0.0 {
            if standing {
                let step = cfg.stand_wander_m * libm::sqrt(dt / 20.0);
                self.wander.0 += step * self.rng.normal();
                self.wander.1 += step * self.rng.normal();
            } else {
                let fade = libm::exp(-dt / WANDER_FADE_S);
                self.wander = (fade * self.wander.0, fade * self.wander.1);
            }
            err.0 += self.wander.0;
            err.1 += self.wander.1;
        }
        let t_true = t - cfg.latency_s;
        let truth = self.truth.position_at(t_true);
        let mut speed = cfg
            .speed
            .then(|| (self.true_speed(t_true) + SPEED_NOISE_MPS * self.rng.normal()).max(0.0));
        let held = cfg.start_hold_s > 0.0
            && self
                .walk_starts
                .iter()
                .any(|&s| t >= s && t < s + cfg.start_hold_s);
        let mut replace = None;
        let mut accuracy_m = None;
        match cfg.stale_first_fix {
            Some(st) if index < st.count => {
                let (s, c) = libm::sincos(st.bearing_deg.to_radians());
                let (e0, n0) = self.truth.position_at(t_true);
                replace = Some((e0 + st.distance_m * s, n0 + st.distance_m * c));
                accuracy_m = Some(st.accuracy_m);
                speed = speed.map(|_| 0.0);
            }
            _ if held && self.last_reported.is_some() => {
                replace = self.last_reported;
                speed = speed.map(|_| 0.0);
            }
            _ => {}
        }
        Shaped {
            truth,
            error: err,
            replace,
            accuracy_m,
            speed_mps: speed,
        }
    }
}
