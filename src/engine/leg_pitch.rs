//! The leg pitch: the opening angle of the thigh a phone in a trouser pocket rides on (Munoz
//! Diaz 2015 §4.1, Fig. 2), whatever way round the phone sits in the pocket.
//! May import: the rest of `engine`.
//!
//! # Method
//! The paper reads the pitch from its attitude filter with the sensor mounted one way. A phone
//! goes into a pocket upright or upside down, screen in or out, turned; so the angle is taken
//! about the axis the thigh swings about, found from the data:
//! - **Swing axis.** The gyroscope's second moment C = Σ e^(−Δt/τ) ω_h ω_hᵀ Δt of the rate
//!   without its vertical part, ω_h = ω − (ω·u)u (device frame, τ =
//!   [`LegPitchConfig::axis_tau_s`], u the up direction below); its principal eigenvector is the
//!   thigh's lateral axis `a`, which is horizontal. Leaving the vertical out keeps turns and the
//!   pelvis's yaw out: with them a landing's turn dropped the share below 0.6. Its share of C's trace
//!   says whether a swing dominates at all ([`LegPitchConfig::min_axis_share`]): a phone in the
//!   hand or a bag has no single axis, and gets no pitch.
//! - **Angle.** The world's up direction seen from the device, u = Rᵀ ẑ from the attitude, and
//!   a reference u_ref, both projected onto the plane normal to `a`. The phone turns with the
//!   thigh by θ about `a`, so u turns by −θ: θ = −atan2(a·(u_ref × u), u_ref·u).
//! - **Reference.** The paper's zero is the thigh vertical (standing). While walking the thigh
//!   swings about a mean a few degrees forward of vertical (hip flexion ranges about +30° to
//!   −10° over the gait cycle in published gait data), so u_ref is the mean of u over the level
//!   strides ([`LegPitch::commit_level_stride`]; over all moving samples before the first), and
//!   the angle is offset by [`LegPitchConfig::level_mean_deg`]: θ = 0 is standing, as in the
//!   paper, and a seated thigh reads 70–90°.
//! - **Sign.** The eigenvector's sign is arbitrary. A thigh swings forward fast (the swing
//!   phase, about 40 % of the gait cycle) and back slowly (the stance, about 60 %): in a stride
//!   whose raw maximum is the forward extreme, the rise from the minimum to the maximum takes
//!   less than half the stride. Each of a thigh's strides votes by how much
//!   ([`LegPitch::push_stride`]), and the sign follows the votes' decaying sum. This needs no
//!   heading, which in a pocket can be 180° off for a while (a first version voted with each
//!   step's heading and turned over mid-walk on the simulated mixed walk when the heading did;
//!   a second used the skewness of the rate about the axis, which the heel strike's jolt and
//!   the stairs' shapes made unreliable). The step count
//!   and Δθ do not depend on the sign, so the step detector is given the raw angle; the
//!   activities' θ_max and θ_min, and standing against sitting, take the sign
//!   ([`LegPitch::signed`]).

use super::pitch_detector::PitchStride;
use super::types::{positive, ConfigError, DeviceVec};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Settings of the leg pitch.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct LegPitchConfig {
    /// Time constant of the gyroscope's second moment, s. Default 4 s: several strides.
    pub axis_tau_s: f64,
    /// Share of the second moment's trace the swing axis must hold for a pitch to be given.
    /// Default 0.6: the simulated pocket in every pose holds 0.85–0.97 while walking; a
    /// rotation spread evenly over three axes holds 1/3.
    pub min_axis_share: f64,
    /// The mean thigh angle of level walking, degrees forward of standing. Default 7°: hip
    /// flexion spans about +30° to −10° over a gait cycle (Winter's gait data), and the thigh
    /// spends longer behind the mid-point than a sinusoid would.
    pub level_mean_deg: f64,
    /// Weight of a level stride's mean up direction in the reference. Default 0.2 (about the
    /// last five level strides).
    pub reference_weight: f64,
    /// A thigh is recognised (and the activities, stairs and heights follow the pitch) when the
    /// median Δθ of the last [`Self::thigh_strides`] strides reaches this, degrees. Default
    /// 25°: a thigh swings 30–50° on the level and 27° down stairs (the paper's §6.1); a phone
    /// held in the hand sways 9–24° (10th–90th percentile of the strides found on
    /// `../shared/data/ms-indoor`, median 13.5°).
    pub thigh_min_amplitude_deg: f64,
    /// ... and the swing axis holds at least this share of the gyroscope's second moment.
    /// Default 0.8: the thigh's sagittal rate (3–4 rad/s peaks) dwarfs its roll and yaw; the
    /// hand-held Microsoft walks hold a median of 0.70.
    pub thigh_min_axis_share: f64,
    /// Strides the thigh test looks at. Default 5.
    pub thigh_strides: usize,
    /// The thigh gives the way forward ([`LegPitch::forward_axis`]) only while its swing axis
    /// lies within this of the horizontal ([`LegPitch::axis_tilt_deg`]): the phone rides the
    /// thigh now. Default 15°, the real thigh's bound of [`crate::engine::pll::PllConfig::axis_tilt_max_deg`]
    /// (a hip's ab- and adduction and the pelvis's roll, ±5° each). The axis is learnt over
    /// seconds, so a phone taken from the pocket to the ear kept the thigh's sign for 3–4 s
    /// on the simulator and walked 180° off.
    pub riding_tilt_max_deg: f64,
}

impl Default for LegPitchConfig {
    fn default() -> Self {
        LegPitchConfig {
            axis_tau_s: 4.0,
            min_axis_share: 0.6,
            level_mean_deg: 7.0,
            reference_weight: 0.2,
            thigh_min_amplitude_deg: 25.0,
            thigh_min_axis_share: 0.8,
            thigh_strides: 5,
            riding_tilt_max_deg: 15.0,
        }
    }
}

impl LegPitchConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("leg_pitch.axis_tau_s", self.axis_tau_s)?;
        if !(self.min_axis_share > 0.0 && self.min_axis_share < 1.0) {
            return Err(ConfigError::new(
                "leg_pitch.min_axis_share",
                "must lie strictly between 0 and 1",
            ));
        }
        if !(self.level_mean_deg.is_finite() && self.level_mean_deg.abs() < 45.0) {
            return Err(ConfigError::new(
                "leg_pitch.level_mean_deg",
                "must be a finite angle within ±45°",
            ));
        }
        positive(
            "leg_pitch.thigh_min_amplitude_deg",
            self.thigh_min_amplitude_deg,
        )?;
        if !(self.thigh_min_axis_share > 0.0 && self.thigh_min_axis_share < 1.0) {
            return Err(ConfigError::new(
                "leg_pitch.thigh_min_axis_share",
                "must lie strictly between 0 and 1",
            ));
        }
        positive("leg_pitch.riding_tilt_max_deg", self.riding_tilt_max_deg)?;
        if self.thigh_strides == 0 {
            return Err(ConfigError::new(
                "leg_pitch.thigh_strides",
                "must be at least 1",
            ));
        }
        if !(self.reference_weight > 0.0 && self.reference_weight <= 1.0) {
            return Err(ConfigError::new(
                "leg_pitch.reference_weight",
                "must lie in (0, 1]",
            ));
        }
        Ok(())
    }
}

/// What the leg pitch is given per sample.
#[derive(Debug, Clone, Copy)]
pub struct LegPitchInput {
    /// Time since the previous sample, s.
    pub dt: f64,
    /// Angular rate, rad/s, device frame.
    pub gyro: Option<DeviceVec>,
    /// The device → ENU attitude.
    pub attitude: Option<UnitQuaternion<f64>>,
    /// Whether the motion detector sees a gait.
    pub moving: bool,
}

/// The leg pitch's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LegPitchDiagnostics {
    /// The last pitch, degrees.
    pub pitch_deg: Option<f64>,
    /// The swing axis's share of the gyroscope's second moment.
    pub axis_share: f64,
    /// The sign's vote: the decaying sum over strides of half the stride less the rise from
    /// the minimum to the maximum, s (positive: forward is a positive rotation about the
    /// eigenvector).
    pub sign_vote: f64,
    /// Whether the phone rides on a thigh.
    pub on_thigh: bool,
}

/// The leg pitch stage.
#[derive(Debug, Clone)]
pub struct LegPitch {
    cfg: LegPitchConfig,
    moment: Matrix3<f64>,
    axis: Option<Vector3<f64>>,
    share: f64,
    since_axis: u32,
    reference: Option<Vector3<f64>>,
    level_refs: u32,
    stride_sum: Vector3<f64>,
    vote: f64,
    vote_periods: f64,
    /// The swing axis the votes refer to (the axis when they began).
    vote_axis: Option<Vector3<f64>>,
    /// The swing axis at the end of the last stride.
    stride_axis: Option<Vector3<f64>>,
    /// Whether the axis held still over the last stride.
    stride_steady: bool,
    up: Option<Vector3<f64>>,
    last: Option<f64>,
    amplitudes: std::collections::VecDeque<f64>,
    thigh: bool,
    thigh_like: bool,
}

/// Samples between two power iterations of the swing axis (about 0.1 s).
const AXIS_EVERY: u32 = 8;

/// Power iterations more, at most, when the axis's share is below
/// [`LegPitchConfig::min_axis_share`] ([`LegPitch::update_axis`]).
const CATCH_UP_ITERATIONS: usize = 8;

/// The largest Δθ of a thigh's stride, degrees: a hip flexes to about 120° and extends to
/// about −20°, and no gait uses all of it (stairs up: about 55–70°).
const THIGH_MAX_AMPLITUDE_DEG: f64 = 100.0;

/// The shortest stride of a thigh, s: two steps at 2.5 Hz, beyond brisk walking (1.6–2.2 Hz).
const THIGH_MIN_STRIDE_S: f64 = 0.8;

/// Strides that must look like a thigh's before its swing gives the heading's sign.
const EARLY_STRIDES: usize = 2;

/// The votes' net share of the strides they span that makes the sign clear enough for the
/// heading.
const SIGN_CLEAR: f64 = 0.1;

/// Weight kept by the sign's vote per stride (about the last 30 strides count).
const SIGN_KEEP: f64 = 0.97;

/// The votes start again when the swing axis has turned in the device by more than this from
/// the axis they began on (cos 45°): the phone was moved in the body.
const REMOUNT_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A stride votes only if the swing axis turned in the device by less than this since the
/// last stride (cos 15°): a phone being moved swings about no axis of its own.
const STEADY_AXIS_COS: f64 = 0.966;

/// `m ← m·decay + w wᵀ·dt` for the symmetric second moment `m`: each entry as
/// `m * decay + w * w.transpose() * dt` computes it, `m_ij·decay + (w_i w_j)·dt`, the six
/// distinct ones once and mirrored (w_i w_j and w_j w_i are the same product).
fn add_outer(m: &mut Matrix3<f64>, decay: f64, w: &Vector3<f64>, dt: f64) {
    let (x, y, z) = (w.x, w.y, w.z);
    let e = |v: f64, p: f64| v * decay + p * dt;
    let (xx, yy, zz) = (e(m.m11, x * x), e(m.m22, y * y), e(m.m33, z * z));
    let (xy, xz, yz) = (e(m.m12, x * y), e(m.m13, x * z), e(m.m23, y * z));
    *m = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
}

impl LegPitch {
    /// A stage with validated settings.
    pub fn new(cfg: LegPitchConfig) -> Self {
        LegPitch {
            cfg,
            moment: Matrix3::zeros(),
            axis: None,
            share: 0.0,
            since_axis: 0,
            reference: None,
            level_refs: 0,
            stride_sum: Vector3::zeros(),
            vote: 0.0,
            vote_periods: 0.0,
            vote_axis: None,
            stride_axis: None,
            stride_steady: true,
            up: None,
            last: None,
            amplitudes: std::collections::VecDeque::new(),
            thigh: false,
            thigh_like: false,
        }
    }

    /// Feeds one sample; returns the raw angle about the swing axis from the reference, degrees,
    /// once a swing axis is known and dominant and the sample has an attitude. Its sign is the
    /// eigenvector's: the step detector counts on it as it is (a stride has one maximum either
    /// way, and a sign learnt later must not turn a stride's signal over mid-walk);
    /// [`Self::signed`] gives the pitch.
    pub fn push(&mut self, x: &LegPitchInput) -> Option<f64> {
        self.up = x
            .attitude
            .map(|q| q.inverse_transform_vector(&Vector3::z()));
        // Every sample counts, moving or not: a still phone adds nothing, and the axis is
        // known a second into a walk, before the motion detector confirms it, so the onset
        // look-back finds the first strides. The rate about the vertical is left out: turns
        // and the pelvis's yaw are not the thigh's swing, whose axis is horizontal.
        if let Some(w) = x.gyro {
            if x.dt > 0.0 {
                let w = match self.up {
                    Some(u) => w - u * u.dot(&w),
                    None => w,
                };
                // e^(−Δt/τ) to first order: Δt/τ is about 0.003.
                let decay = (1.0 - x.dt / self.cfg.axis_tau_s).max(0.0);
                add_outer(&mut self.moment, decay, &w, x.dt);
                self.since_axis += 1;
                if self.axis.is_none() || self.since_axis >= AXIS_EVERY {
                    self.since_axis = 0;
                    self.update_axis();
                }
            }
        }
        self.last = self.angle(x.moving);
        self.last
    }

    /// One power iteration a ← C·a / |C·a| from the last axis (the largest column of C to
    /// start): the principal eigenvector, followed as C changes. The swing's eigenvalue is
    /// several times the others', so one iteration every [`AXIS_EVERY`] samples keeps up with a
    /// moment whose time constant is seconds. C a stays on a's side (C is positive
    /// semi-definite), so the axis keeps its sign and the sign's vote refers to it.
    ///
    /// When the share is then below [`LegPitchConfig::min_axis_share`], up to
    /// [`CATCH_UP_ITERATIONS`] more while it rises. When the dominant rotation moves to another
    /// axis (standing's sway giving way to the first stride), one iteration a block lags it, and
    /// the pitch could be lost for a block, and a walk's first step with it.
    fn update_axis(&mut self) {
        let c = &self.moment;
        let trace = c.trace();
        if !(trace > 0.0) || !c.iter().all(|v| v.is_finite()) {
            return;
        }
        let start = self.axis.unwrap_or_else(|| {
            let i = (0..3)
                .max_by(|&i, &j| c.column(i).norm().total_cmp(&c.column(j).norm()))
                .unwrap_or(0);
            c.column(i).into_owned()
        });
        // C·a of the axis so far: each iteration's product gives its share and the next step.
        let (mut a, mut ca) = (start, c * start);
        for i in 0..=CATCH_UP_ITERATIONS {
            let n = ca.norm();
            if !(n > 0.0) {
                if i == 0 {
                    return;
                }
                break;
            }
            let next = ca / n;
            let c_next = c * next;
            let share = next.dot(&c_next) / trace;
            if i > 0 && !(share > self.share) {
                break;
            }
            (a, ca) = (next, c_next);
            self.share = share;
            if share >= self.cfg.min_axis_share {
                break;
            }
        }
        self.axis = Some(a);
    }

    /// θ = −atan2(a·(r × u), r⊥·u⊥) for the up direction u and the reference r, where the
    /// triple product needs no projection (the parts along `a` drop out) and r⊥·u⊥ = r·u −
    /// (a·r)(a·u): no square root per sample.
    fn angle(&mut self, moving: bool) -> Option<f64> {
        let (a, u) = (self.axis?, self.up?);
        let au = a.dot(&u);
        if !(u.norm_squared() - au * au > 1e-12) {
            // The up direction lies along the swing axis: no angle about it.
            return None;
        }
        if moving {
            self.stride_sum += u;
        }
        let swing = self.share >= self.cfg.min_axis_share;
        if self.level_refs == 0 && swing {
            // Before the first level stride: the running mean while a swing dominates.
            let r = self.reference.unwrap_or(u);
            self.reference = Some(r * 0.995 + u * 0.005);
        }
        if !swing {
            return None;
        }
        let r = self.reference?;
        let (ar, cross) = (a.dot(&r), a.dot(&r.cross(&u)));
        let dot = r.dot(&u) - ar * au;
        if !(cross.abs() + dot.abs() > 1e-12) {
            return None;
        }
        Some(-super::math::atan2(cross, dot).to_degrees())
    }

    /// The sign the votes give now: +1 when forward is a positive raw angle.
    pub fn sign(&self) -> f64 {
        if self.vote >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The pitch (degrees, thigh forward positive, 0 standing) of a raw angle [`Self::push`]
    /// gave, with the sign as voted so far.
    pub fn signed(&self, raw_deg: f64) -> f64 {
        self.sign() * raw_deg + self.cfg.level_mean_deg
    }

    /// A stride's (θ_max, θ_min), degrees, from the raw angle's extremes: with a negative sign
    /// the raw minimum is the thigh's forward extreme.
    pub fn signed_extremes(&self, raw_max_deg: f64, raw_min_deg: f64) -> (f64, f64) {
        let (a, b) = (self.signed(raw_max_deg), self.signed(raw_min_deg));
        (a.max(b), a.min(b))
    }

    /// The stride that just ended was level: its mean up direction joins the reference.
    /// Another kind of stride only starts the next one afresh ([`Self::skip_stride`]).
    pub fn commit_level_stride(&mut self) {
        let n = self.stride_sum.norm();
        if n > 1e-9 && self.stride_steady {
            let m = self.stride_sum / n;
            let w = if self.level_refs == 0 {
                1.0
            } else {
                self.cfg.reference_weight
            };
            let r = self.reference.map_or(m, |r| r * (1.0 - w) + m * w);
            let rn = r.norm();
            if rn > 1e-9 {
                self.reference = Some(r / rn);
                self.level_refs += 1;
            }
        }
        self.stride_sum = Vector3::zeros();
    }

    /// The stride that just ended is not level (stairs): it does not move the reference.
    pub fn skip_stride(&mut self) {
        self.stride_sum = Vector3::zeros();
    }

    /// A stride ended (its Δθ, period, and the times of its extremes): its vote on the sign
    /// (when `votes`: the caller's word that the stride may be a thigh's, for the carrying mode
    /// may say a swinging hand), and whether the phone rides on a thigh, by the last
    /// [`LegPitchConfig::thigh_strides`] strides.
    ///
    /// A thigh's strides are regular, last two steps, and swing a leg's angle. Three tests say
    /// no: a stride beyond `THIGH_MAX_AMPLITUDE_DEG` (no thigh swings that far: the angle is
    /// about another axis, a turning hand), a stride shorter than `THIGH_MIN_STRIDE_S` (a hand
    /// rocks once per step, a thigh once per two), and amplitudes that spread by more than
    /// their median (the hand-held IPIN walks' strides range 8–70° within five).
    pub fn push_stride(&mut self, stride: &PitchStride, votes: bool) -> bool {
        let (amplitude_deg, period_s) = (stride.amplitude_deg, stride.period_s);
        // A stride over which the swing axis itself turned in the device is the phone being
        // moved, not a swing: it neither votes on the sign nor joins the reference.
        let previous = std::mem::replace(&mut self.stride_axis, self.axis);
        let steady = match (self.axis, previous) {
            (Some(a), Some(prev)) => a.dot(&prev) >= STEADY_AXIS_COS,
            _ => true,
        };
        self.stride_steady = steady;
        // The first steady stride after a move: a phone moved in the body (from a bag into the
        // pocket) swings about another axis of the device, which the power iteration reached
        // from the old one with either sign, so the votes so far would give it a coin's sign
        // for the next 30 strides. Only the votes start again: the reference follows the new
        // mount stride by stride (started afresh from the first stride it turned a swinging
        // hand's sign over after a move from a bag), and the thigh's tests look at the last
        // strides anyway. The figures are in `docs/methods/mode-change.md`.
        if steady && self.moved() {
            self.forget_votes();
        }
        if let Some(p) = period_s.filter(|_| steady && votes) {
            let rise = stride.t_max - stride.t_min;
            if rise > 0.0 && rise < p {
                if self.vote_axis.is_none() {
                    self.vote_axis = self.axis;
                }
                self.vote = self.vote * SIGN_KEEP + (0.5 * p - rise);
                self.vote_periods = self.vote_periods * SIGN_KEEP + p;
            }
        }
        if amplitude_deg > THIGH_MAX_AMPLITUDE_DEG
            || period_s.is_some_and(|p| p < THIGH_MIN_STRIDE_S)
        {
            self.amplitudes.clear();
            self.thigh = false;
            self.thigh_like = false;
            return false;
        }
        if self.amplitudes.len() == self.cfg.thigh_strides {
            self.amplitudes.pop_front();
        }
        self.amplitudes.push_back(amplitude_deg);
        let mut a: Vec<f64> = self.amplitudes.iter().copied().collect();
        crate::engine::sort::sort_by(&mut a, f64::total_cmp);
        let median = a[a.len() / 2];
        let spread = a[a.len() - 1] - a[0];
        self.thigh_like = a.len() >= EARLY_STRIDES
            && median >= self.cfg.thigh_min_amplitude_deg
            && spread <= median
            && self.share >= self.cfg.thigh_min_axis_share;
        self.thigh = self.thigh_like && a.len() == self.cfg.thigh_strides;
        self.thigh
    }

    /// Whether the phone sits in the body otherwise than when the votes began: the swing axis
    /// turned in the device by more than 45° from the one they began on. (The stride's mean up
    /// direction more than 45° from the reference was tried as a sign too: it fired on a phone
    /// moved from the hand into a swinging hand, `docs/methods/mode-change.md`.)
    fn moved(&self) -> bool {
        matches!((self.axis, self.vote_axis), (Some(a), Some(v)) if a.dot(&v) < REMOUNT_COS)
    }

    /// Forgets the sign's votes: the strides they came from were not this thigh's.
    fn forget_votes(&mut self) {
        self.vote = 0.0;
        self.vote_periods = 0.0;
        self.vote_axis = None;
    }

    /// The up direction in the device frame of the last sample, q⁻¹·ẑ, when it had an
    /// attitude.
    pub fn device_up(&self) -> Option<Vector3<f64>> {
        self.up
    }

    /// How far the swing axis is tilted from the horizontal now, degrees, while the phone rides
    /// on a thigh ([`Self::on_thigh`]): asin |a·u| for the axis a and the up direction u in
    /// the device, both unit vectors. The axis is learnt from the horizontal rotation of the last seconds
    /// ([`LegPitchConfig::axis_tau_s`]), so it stays near 0 while the phone rides the thigh
    /// (the simulator's thighs: 0.0–0.4°; a real hip's ab- and adduction and the pelvis's
    /// roll are about ±5° each), and grows when the phone turns in a way the thigh does not:
    /// taken out of the pocket (the simulator: 14–39° within the cycle after the walk).
    pub fn axis_tilt_deg(&self) -> Option<f64> {
        self.axis_tilt_sin().map(|s| libm::asin(s).to_degrees())
    }

    /// The sine of [`Self::axis_tilt_deg`]: |a·u|, at most 1, without the arcsine.
    pub fn axis_tilt_sin(&self) -> Option<f64> {
        let (a, u) = (self.axis?, self.up?);
        self.thigh.then(|| a.dot(&u).abs().min(1.0))
    }

    /// Whether the phone rides on a thigh ([`Self::push_stride`]).
    pub fn on_thigh(&self) -> bool {
        self.thigh
    }

    /// The axis, in the device frame, about which the thigh swings *forward* (the swing axis
    /// turned by the voted sign), while the phone rides on a thigh whose swing dominates, the
    /// strides have voted, and the axis is level ([`LegPitchConfig::riding_tilt_max_deg`]). A point below the hip on a thigh turning by +θ̇ about the
    /// world axis L moves along θ̇·(ẑ × L): with L this axis in the world frame, ẑ × L is the
    /// way the walker goes ([`crate::engine::heading::HeadingConfig::limb_sign`]).
    pub fn forward_axis(&self) -> Option<Vector3<f64>> {
        if !(self.thigh_like
            && self.share >= self.cfg.thigh_min_axis_share
            && self.vote_periods > 0.0
            && self.vote.abs() >= SIGN_CLEAR * self.vote_periods
            && self
                .axis_tilt_deg()
                .map_or(true, |t| t <= self.cfg.riding_tilt_max_deg))
        {
            return None;
        }
        self.axis.map(|a| a * self.sign())
    }

    /// The swing axis's share of the gyroscope's horizontal second moment, once an axis is
    /// known ([`crate::engine::back_pocket`] tells the pocket by it).
    pub fn swing_share(&self) -> Option<f64> {
        self.axis.map(|_| self.share)
    }

    /// The current values.
    pub fn diagnostics(&self) -> LegPitchDiagnostics {
        LegPitchDiagnostics {
            pitch_deg: self.last,
            axis_share: self.share,
            sign_vote: self.vote,
            on_thigh: self.thigh,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stride of period 1.1 s whose raw angle rises from its minimum to its maximum in
    /// `rise_share` of it (a thigh's swing phase: about 0.33).
    fn stride(t_max: f64, rise_share: f64) -> PitchStride {
        PitchStride {
            t_max,
            max_deg: 25.0,
            min_deg: -15.0,
            t_min: t_max - rise_share * 1.1,
            amplitude_deg: 40.0,
            period_s: Some(1.1),
        }
    }

    /// A leg pitch whose gyroscope turns about the device's x axis only, the phone upright.
    fn swinging_about_x() -> LegPitch {
        let mut leg = LegPitch::new(LegPitchConfig::default());
        swing(&mut leg, Vector3::x(), 4.0);
        leg
    }

    /// `seconds` of a swing about the device axis `axis`, the phone upright.
    fn swing(leg: &mut LegPitch, axis: Vector3<f64>, seconds: f64) {
        for i in 0..(seconds * 100.0) as u32 {
            let w = 3.0 * libm::sin(f64::from(i) * 0.05);
            leg.push(&LegPitchInput {
                dt: 0.01,
                gyro: Some(axis * w),
                attitude: Some(UnitQuaternion::identity()),
                moving: true,
            });
        }
    }

    #[test]
    fn the_axis_catches_up_when_the_swing_moves_to_another() {
        // Standing's sway about two axes, then a swing about a third that grows over a
        // second (a first stride): while the dominant rotation moves to the new axis the pitch
        // is still given, not lost for a block of samples until the next power iteration.
        let mut leg = LegPitch::new(LegPitchConfig::default());
        let mut missing = Vec::new();
        for i in 0..600u32 {
            let t = f64::from(i) * 0.01;
            let ramp = ((t - 4.0) / 1.0).clamp(0.0, 1.0);
            let w = Vector3::y() * 0.3 * libm::sin(t * 7.0)
                + Vector3::z() * 0.15 * libm::sin(t * 5.0)
                + Vector3::x() * 3.0 * ramp * ramp * libm::sin((t - 4.0) * 11.0);
            let p = leg.push(&LegPitchInput {
                dt: 0.01,
                gyro: Some(w),
                attitude: Some(UnitQuaternion::identity()),
                moving: true,
            });
            if t >= 4.0 && p.is_none() {
                missing.push(i);
            }
        }
        // One iteration a block left samples 473–480 without one.
        assert!(missing.is_empty(), "no pitch at samples {missing:?}");
    }

    #[test]
    fn the_votes_are_the_thighs_and_start_again_when_the_phone_is_moved() {
        let strides = |leg: &mut LegPitch, t0: f64, rise: f64, votes: bool| {
            for k in 0..4 {
                leg.push_stride(&stride(t0 + 1.1 * f64::from(k), rise), votes);
            }
        };
        // Strides the caller says are no thigh's (a swinging hand's) vote nothing.
        let mut leg = swinging_about_x();
        strides(&mut leg, 1.0, 0.33, false);
        assert_eq!(leg.forward_axis(), None);
        // A thigh swinging forward about +x, then the phone moved to swing about y the other
        // way round: the strides while the axis turned vote nothing, and the first steady one
        // about the new axis starts the votes again, whose sign the old ones would have
        // outweighed for 30 strides.
        let mut leg = swinging_about_x();
        strides(&mut leg, 1.0, 0.33, true);
        assert!((leg.forward_axis().unwrap() - Vector3::x()).norm() < 1e-6);
        swing(&mut leg, Vector3::new(0.1, 1.0, 0.0).normalize(), 8.0);
        strides(&mut leg, 10.0, 0.67, true);
        let a = leg.axis.unwrap();
        assert!(a.y.abs() > 0.99, "{a}");
        assert!((leg.forward_axis().unwrap() + a).norm() < 1e-12);
        assert!(leg.vote < 0.0 && leg.vote_periods < 4.0 * 1.1);
    }

    #[test]
    fn the_forward_axis_needs_thigh_strides_and_a_clear_vote() {
        let mut leg = swinging_about_x();
        assert_eq!(leg.forward_axis(), None, "no stride yet");
        leg.push_stride(&stride(1.0, 0.33), true);
        assert_eq!(leg.forward_axis(), None, "one stride");
        leg.push_stride(&stride(2.1, 0.33), true);
        // Forward is a positive raw angle: the axis as found, turned by the sign.
        let a = leg
            .forward_axis()
            .expect("two thigh strides with a clear vote");
        let found = leg.axis.unwrap();
        assert!(
            (a - found * leg.sign()).norm() < 1e-12 && a.x.abs() > 0.99,
            "{a:?}"
        );
        // The rise taking the longer part turns it over.
        let mut back = swinging_about_x();
        back.push_stride(&stride(1.0, 0.67), true);
        back.push_stride(&stride(2.1, 0.67), true);
        assert!((back.forward_axis().unwrap() + a).norm() < 1e-12);
        // A symmetric swing (a sinusoid) votes nothing clear.
        let mut even = swinging_about_x();
        for k in 0..6 {
            even.push_stride(
                &stride(1.0 + 1.1 * k as f64, 0.5 + 0.02 * (k % 2) as f64),
                true,
            );
        }
        assert_eq!(even.forward_axis(), None);
    }

    #[test]
    fn the_forward_axis_needs_the_phone_on_the_thigh_now() {
        let mut leg = swinging_about_x();
        for k in 0..5 {
            leg.push_stride(&stride(1.0 + 1.1 * f64::from(k), 0.33), true);
        }
        assert!(leg.on_thigh());
        // The phone turned about its y axis: the x axis, learnt over seconds, tilts with it.
        let mut turned = |deg: f64| {
            leg.push(&LegPitchInput {
                dt: 0.01,
                gyro: Some(Vector3::zeros()),
                attitude: Some(UnitQuaternion::from_axis_angle(
                    &Vector3::y_axis(),
                    deg.to_radians(),
                )),
                moving: true,
            });
            (leg.axis_tilt_deg().unwrap(), leg.forward_axis())
        };
        let (tilt, a) = turned(10.0);
        assert!((tilt - 10.0).abs() < 0.5 && a.is_some(), "{tilt}");
        let (tilt, a) = turned(30.0);
        assert!((tilt - 30.0).abs() < 0.5 && a.is_none(), "{tilt}");
    }

    #[test]
    fn the_moment_update_matches_the_matrix_form() {
        let mut m = Matrix3::zeros();
        let mut want = Matrix3::zeros();
        for k in 0..50 {
            let f = k as f64;
            let w = Vector3::new(libm::sin(0.7 * f) * 3.0, libm::cos(1.3 * f), -0.2 * f + 1.0);
            let (decay, dt) = (1.0 - 0.01 / 4.0, 0.01 + 1e-4 * libm::sin(f * 0.37));
            add_outer(&mut m, decay, &w, dt);
            want = want * decay + w * w.transpose() * dt;
            assert_eq!(m, want);
        }
    }
}
