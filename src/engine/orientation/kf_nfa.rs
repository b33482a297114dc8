//! KF-NFA: the Kalman filter with (neuro-)fuzzy adaptation of Ibarra 2015, chapter 3, for the
//! attitude from accelerometer and gyroscope.
//! May import: the rest of `engine` (a child of [`super`], the orientation stage).
//!
//! # What the thesis writes, and what is used
//! - **State** (eqs. 3.4–3.5): x = [φ, b_φ, θ, b_θ, ψ, b_ψ]: roll, pitch, yaw and a gyroscope bias
//!   per axis. **Process** (eqs. 3.5–3.8): angle_{k+1} = angle_k + (ω − b)·dt, b_{k+1} = b_k, so
//!   A has 1 on the diagonal and −dt beside each angle, B = dt on the angle rows.
//! - **Measurement** (eqs. 3.9–3.10): z = H x with H picking φ, θ, ψ; φ and θ from the
//!   accelerometer by eqs. 3.1–3.2, φ = atan(a_y / √(a_x²+a_z²)), θ = atan(−a_x / √(a_y²+a_z²)).
//! - **Noise** (eqs. 3.11–3.12): Q = diag[σ²_ω, σ²_b, …] per axis, R = diag of the accelerometer
//!   variances (Tables 3.1–3.2: about 0.05–0.23 (°/s)² and 3.6–5.2 mg²).
//! - **Adaptation** (§3.2.1–3.2.2): innovation Inn_k = z_k − H x⁻_k (eq. 3.13), its theoretical
//!   covariance S_k = H P⁻ Hᵀ + R (eq. 3.14), its actual covariance over a moving window of M
//!   samples Ĉ_k = (1/M) Σ Inn_i Inn_iᵀ (eq. 3.15), the degree of matching DoM_k = S_k − Ĉ_k
//!   (eq. 3.16), and R_k(i,i) = R_{k−1}(i,i) + ΔR_k (eq. 3.17), with ΔR from a fuzzy system on
//!   DoM(i,i) under three rules: DoM ≅ 0 → keep R; DoM > 0 → decrease R; DoM < 0 → increase R.
//! - **Kalman equations** (eqs. 2.6–2.10).
//!
//! # Decisions where the thesis is vague or wrong
//! 1. **Euler angles as a linear state are only right for a level sensor.** Eqs. 3.6–3.8
//!    integrate the body rates ω_x, ω_y, ω_z as if they were the Euler-angle rates; this holds
//!    near level (the thesis's rotation test is one axis at a time from level) but not for a
//!    phone in a pocket or held at 40°, and Euler angles lock at ±90° pitch. We keep the
//!    thesis's linear filter exactly — the same six states in the same order, the same A (with
//!    the bias column rotated into the navigation frame), the same H, Q and R, the same
//!    equations — but as an *error-state* (indirect) filter around a quaternion: the angles are
//!    the small attitude errors about the East, North and Up axes (δφ, δθ, δψ), the nominal
//!    attitude is integrated exactly from the bias-corrected gyroscope (the B·u term of
//!    eq. 3.4), and each update's angles are folded into it and zeroed. With the device level
//!    and its axes on East-North-Up, A reduces to eq. 3.5 exactly.
//! 2. **Measurements.** φ and θ are eqs. 3.1–3.2 applied to the accelerometer cast into the
//!    navigation frame by the predicted attitude: for a true attitude (I + [δ×]) C, that vector
//!    is g·(−δθ, δφ, 1) to first order, so eqs. 3.1–3.2 give the errors δφ, δθ directly. The
//!    thesis's third row (ψ from the gyroscope through eq. 3.3) is the process's own
//!    information again, correlated with its noise against eq. 2.5, so we drop it: yaw is
//!    propagated by the gyroscope alone, as in the thesis. **Magnetometer:** the thesis uses
//!    none (it cites its refs. 49 and 50 for doing so). `magnetometer = false` (the default) follows it;
//!    `magnetometer = true` fills the third row of H (eq. 3.10) with the magnetometer's heading
//!    error and starts the yaw from it, as Madgwick does here.
//! 3. **R's units.** Eq. 3.12 puts accelerometer variances (mg²) into the R of an angle
//!    measurement; we convert: σ_angle = σ_acc / g.
//! 4. **The neuro-fuzzy weights are not published** (Figs. 3.6–3.7 show the trained Gaussian
//!    memberships but not their values). In their place a fuzzy system of our own, zero-order
//!    Sugeno like ANFIS's, on a *normalised* degree of matching x = DoM/(S + Ĉ) ∈ (−1, 1) so that
//!    one rule base fits every sensor and rate (the thesis feeds the raw DoM of its one sensor):
//!    five Gaussian memberships ([`FUZZY_SETS`], σ = [`FUZZY_SIGMA`]) and five rules, output the
//!    relative change of R per second, defuzzified by the weighted mean; ΔR = f·dt·R_{k−1}
//!    (eq. 3.17), the factor per sample kept within [1/2, 2] and R within
//!    [R₀/100, `r_max`].
//! 5. **Order of eq. 3.14 and 3.17.** S_k uses R_{k−1}; the new R_k is then used in this sample's
//!    gain. Adaptation starts once the window holds M innovations.
//! 6. **The update** is done one measurement row at a time (Joseph form): with R diagonal it is
//!    the same as eqs. 2.8–2.10 with the matrix inverse, and needs no inversion but of a
//!    positive scalar, which is guarded.
//! 7. **Divergence.** A non-finite or runaway state (|b| > [`MAX_BIAS`], a variance beyond
//!    [`MAX_VARIANCE`]) restarts the filter from the next sample, counted in the diagnostics; a
//!    sample with no usable accelerometer direction is propagated only, also counted.
//! 8. **Defaults** were measured on the real sets, not the simulator
//!    (`docs/methods/ibarra2015.md`): R₀ is the thesis's Table 3.2 (σ_acc = 0.022 m/s²), and
//!    the adaptation is what makes that usable in a walk.

use super::{attitude_from_vectors, G0};
use crate::engine::types::{positive, ConfigError, DeviceVec};
use nalgebra::{Matrix3, SMatrix, SVector, UnitQuaternion, Vector3};

type Mat6 = SMatrix<f64, 6, 6>;
type Vec6 = SVector<f64, 6>;

/// Index of each angle (φ, θ, ψ) and of each bias in the state, in the thesis's order (eq. 3.5).
const ANGLE: [usize; 3] = [0, 2, 4];
const BIAS: [usize; 3] = [1, 3, 5];

/// The fuzzy sets on the normalised degree of matching x = DoM/(S + Ĉ), and each rule's output,
/// the relative change of R per second: (centre, consequent).
/// - NL (S far below Ĉ: the innovations are much larger than the filter expects) → raise R fast;
/// - NS → raise R slowly; Z (S ≅ Ĉ) → keep R (rule 1 of §3.2.2);
/// - PS → lower R slowly; PL (S far above Ĉ) → lower R fast.
pub const FUZZY_SETS: [(f64, f64); 5] = [
    (-0.8, 30.0),
    (-0.35, 5.0),
    (0.0, 0.0),
    (0.35, -5.0),
    (0.8, -30.0),
];
/// Width (σ) of the Gaussian memberships.
pub const FUZZY_SIGMA: f64 = 0.2;
/// A gyroscope bias estimate beyond this, rad/s, is divergence (phone gyroscopes: < 0.05).
pub const MAX_BIAS: f64 = 0.5;
/// A state variance beyond this is divergence.
pub const MAX_VARIANCE: f64 = 1e4;
/// Most innovations kept for eq. 3.15.
pub const MAX_WINDOW: usize = 10_000;

/// Settings of the KF-NFA.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct KfNfaConfig {
    /// Gyroscope white noise σ_ω, rad/s (eq. 3.11; Table 3.1's largest variance, 0.227 (°/s)²,
    /// is 0.0083 rad/s).
    pub gyro_noise: f64,
    /// Gyroscope bias random walk σ_b, rad/s per √s (eq. 3.11; the thesis gives no value).
    pub bias_walk: f64,
    /// Initial uncertainty (1σ) of the gyroscope bias, rad/s. Tight by default: a phone's
    /// gyroscope is already calibrated by the OS, and with a loose prior the tilt innovations of a
    /// walk (linear acceleration, not tilt) steer the bias states and with them the yaw.
    /// Suggested 1e-4 rad/s; the figures of looser priors are in `docs/methods/ibarra2015.md`.
    pub bias_init: f64,
    /// Accelerometer noise σ_acc, m/s², giving R₀ = (σ_acc/g)² (eq. 3.12; Table 3.2's
    /// 5.2 mg² is σ = 0.022 m/s²).
    pub accel_noise: f64,
    /// Magnetometer heading noise, rad (R₀ of the yaw row when `magnetometer` is on). With the
    /// defaults R₀ = (0.1 rad)² is `r_max`, so the yaw row only adapts downwards. A higher cap
    /// for the yaw row, or a smaller `mag_noise`, gave mixed results (`docs/methods/ibarra2015.md`).
    pub mag_noise: f64,
    /// Window M of eq. 3.15, samples.
    pub window: usize,
    /// Largest R, rad² (0.01: σ = 0.1 rad). The innovations cannot tell a tilt error from
    /// measurement noise, so an unbounded R feeds on the filter's own error (R up, accelerometer
    /// ignored, tilt drifts, innovations up); a cap of 0.25 let the tilt drift by tens of degrees
    /// on the IPIN walks.
    pub r_max: f64,
    /// Adapt R (eqs. 3.13–3.17); `false` is the thesis's "T-KF" with R fixed at R₀.
    pub adapt: bool,
    /// Use the magnetometer for yaw (the thesis does not).
    pub magnetometer: bool,
}

impl Default for KfNfaConfig {
    fn default() -> Self {
        KfNfaConfig {
            gyro_noise: 0.0083,
            bias_walk: 1e-6,
            bias_init: 1e-4,
            accel_noise: 0.022,
            mag_noise: 0.1,
            window: 50,
            r_max: 0.01,
            adapt: true,
            magnetometer: false,
        }
    }
}

impl KfNfaConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("orientation.gyro_noise", self.gyro_noise)?;
        positive("orientation.bias_walk", self.bias_walk)?;
        positive("orientation.bias_init", self.bias_init)?;
        positive("orientation.accel_noise", self.accel_noise)?;
        positive("orientation.mag_noise", self.mag_noise)?;
        positive("orientation.r_max", self.r_max)?;
        if !(1..=MAX_WINDOW).contains(&self.window) {
            return Err(ConfigError::new(
                "orientation.window",
                format!("must be 1 to {MAX_WINDOW} samples, got {}", self.window),
            ));
        }
        let r0 = sq(self.accel_noise / G0);
        if self.r_max < r0 {
            return Err(ConfigError::new(
                "orientation.r_max",
                format!("must be at least R₀ = (accel_noise/g)² = {r0:e}"),
            ));
        }
        Ok(())
    }
}

/// The filter's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct KfNfaDiagnostics {
    /// R(i,i) / R₀(i,i) for roll, pitch and yaw (yaw stays 1 without the magnetometer).
    pub r_scale: [f64; 3],
    /// The last normalised degree of matching DoM/(S + Ĉ) per axis (0 before the window fills).
    pub mismatch: [f64; 3],
    /// The gyroscope bias estimate, rad/s, device axes.
    pub bias: [f64; 3],
    /// Samples with no usable accelerometer direction (propagated only).
    pub skipped: u64,
    /// Restarts after divergence.
    pub resets: u64,
}

/// The running filter.
#[derive(Debug, Clone)]
pub struct KfNfa {
    cfg: KfNfaConfig,
    /// Nominal device → ENU attitude; `None` until a sample gives one.
    q: Option<UnitQuaternion<f64>>,
    bias: Vector3<f64>,
    p: Mat6,
    r: [f64; 3],
    r0: [f64; 3],
    /// Squared innovations of the last M samples per axis (eq. 3.15), a ring.
    inn2: Vec<[f64; 3]>,
    next: usize,
    diag: KfNfaDiagnostics,
}

/// The Sugeno output of the rule base for a normalised degree of matching `x`: relative change
/// of R per second.
pub fn fuzzy_rate(x: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (c, out) in FUZZY_SETS {
        let d = (x - c) / FUZZY_SIGMA;
        let w = libm::exp(-0.5 * d * d);
        num += w * out;
        den += w;
    }
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

fn sq(x: f64) -> f64 {
    x * x
}

/// The rotation by the rotation vector `v` (axis × angle), with `libm`.
fn exp_rot(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let th = v.norm();
    let (s, c) = libm::sincos(0.5 * th);
    let k = if th > 1e-12 { s / th } else { 0.5 };
    UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(c, k * v.x, k * v.y, k * v.z))
}

fn renormalize(q: &UnitQuaternion<f64>) -> Option<UnitQuaternion<f64>> {
    let n = q.as_ref().norm();
    (n.is_finite() && n > 0.5).then(|| UnitQuaternion::new_unchecked(q.as_ref() / n))
}

impl KfNfa {
    /// A new filter (validate the settings first).
    pub fn new(cfg: KfNfaConfig) -> Self {
        let ra = sq(cfg.accel_noise / G0);
        let r0 = [ra, ra, cfg.mag_noise * cfg.mag_noise];
        KfNfa {
            cfg,
            q: None,
            bias: Vector3::zeros(),
            p: Mat6::zeros(),
            r: r0,
            r0,
            inn2: Vec::with_capacity(cfg.window.clamp(1, MAX_WINDOW)),
            next: 0,
            diag: KfNfaDiagnostics {
                r_scale: [1.0; 3],
                ..Default::default()
            },
        }
    }

    /// The configuration.
    pub fn config(&self) -> KfNfaConfig {
        self.cfg
    }

    /// The current values.
    pub fn diagnostics(&self) -> KfNfaDiagnostics {
        self.diag
    }

    /// The current device → ENU attitude, once started.
    pub fn attitude(&self) -> Option<UnitQuaternion<f64>> {
        self.q
    }

    /// Forgets the state; the next sample starts the filter again.
    pub fn reset(&mut self) {
        let d = self.diag;
        *self = KfNfa::new(self.cfg);
        self.diag.skipped = d.skipped;
        self.diag.resets = d.resets;
    }

    fn start(&mut self, accel: &DeviceVec, mag: Option<&DeviceVec>) {
        let finite = |v: &DeviceVec| v.iter().all(|x| x.is_finite());
        if !finite(accel) {
            return;
        }
        let mag = mag.filter(|m| self.cfg.magnetometer && finite(m));
        self.q = attitude_from_vectors(accel, mag).and_then(|q| renormalize(&q));
        if self.q.is_some() {
            let mut p = Mat6::zeros();
            for i in 0..3 {
                p[(ANGLE[i], ANGLE[i])] = 0.01;
                p[(BIAS[i], BIAS[i])] = self.cfg.bias_init * self.cfg.bias_init;
            }
            self.p = p;
        }
    }

    /// Feeds one sample taken `dt` seconds after the previous one and returns the attitude
    /// after it (`None` until a sample with a usable accelerometer starts the filter).
    pub fn push(
        &mut self,
        gyro: &DeviceVec,
        accel: &DeviceVec,
        mag: Option<&DeviceVec>,
        dt: f64,
    ) -> Option<UnitQuaternion<f64>> {
        if self.q.is_none() {
            self.start(accel, mag);
            return self.q;
        }
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        if dt > 0.0 {
            self.predict(gyro, dt);
        }
        self.correct(accel, mag, dt);
        if !self.healthy() {
            self.diag.resets += 1;
            self.reset();
        }
        self.q
    }

    /// Time update, eqs. 2.6–2.7 with A, B of eq. 3.5 and Q of eq. 3.11.
    fn predict(&mut self, gyro: &DeviceVec, dt: f64) {
        let Some(q) = self.q else { return };
        // B·u: the nominal attitude turns by the bias-corrected rate (eqs. 3.6–3.8).
        let w = gyro - self.bias;
        self.q = renormalize(&(q * exp_rot(&(w * dt))));
        // A: angle errors (ENU axes) gain −dt · C · b, C the device → ENU rotation; C = I gives
        // eq. 3.5's −dt exactly.
        let c: Matrix3<f64> = *q.to_rotation_matrix().matrix();
        let mut a = Mat6::identity();
        for i in 0..3 {
            for j in 0..3 {
                a[(ANGLE[i], BIAS[j])] = -dt * c[(i, j)];
            }
        }
        let mut p = a * self.p * a.transpose();
        let (qa, qb) = (sq(self.cfg.gyro_noise * dt), sq(self.cfg.bias_walk) * dt);
        for i in 0..3 {
            p[(ANGLE[i], ANGLE[i])] += qa;
            p[(BIAS[i], BIAS[i])] += qb;
        }
        self.p = p;
    }

    /// Measurement update, eqs. 2.8–2.10 and 3.13–3.17.
    fn correct(&mut self, accel: &DeviceVec, mag: Option<&DeviceVec>, dt: f64) {
        let Some(q) = self.q else { return };
        let a = q * accel;
        let n = a.norm();
        if !(n.is_finite() && n > 1e-6) {
            self.diag.skipped += 1;
            return;
        }
        let u = a / n;
        // Eqs. 3.1–3.2 on the accelerometer in the predicted navigation frame: the errors
        // about East (φ) and North (θ).
        let mut z = [
            Some(libm::atan2(u.y, libm::sqrt(u.x * u.x + u.z * u.z))),
            Some(libm::atan2(-u.x, libm::sqrt(u.y * u.y + u.z * u.z))),
            None,
        ];
        if self.cfg.magnetometer {
            if let Some(m) = mag.map(|m| q * m) {
                // Horizontal field ≈ |h|·(δψ, 1) for a field towards (magnetic) north.
                if libm::hypot(m.x, m.y) > 1e-6 && m.iter().all(|v| v.is_finite()) {
                    z[2] = Some(libm::atan2(m.x, m.y));
                }
            }
        }
        // Eq. 3.15: the window of squared innovations (the error state is zero before the
        // update, so Inn = z, eq. 3.13).
        let inn2 = [0, 1, 2].map(|i| z[i].map_or(0.0, |v| v * v));
        // Validation keeps the window in 1..=MAX_WINDOW; clamped again so that an unvalidated
        // setting can neither divide by zero nor grow the ring.
        let m = self.cfg.window.clamp(1, MAX_WINDOW);
        if self.inn2.len() < m {
            self.inn2.push(inn2);
        } else {
            self.inn2[self.next] = inn2;
        }
        self.next = (self.next + 1) % m;
        let full = self.inn2.len() == m;
        let mut x = Vec6::zeros();
        for i in 0..3 {
            let Some(zi) = z[i] else { continue };
            let k = ANGLE[i];
            if self.cfg.adapt && full && dt > 0.0 {
                // Eqs. 3.14, 3.15, 3.16; S with R_{k−1}.
                let s = self.p[(k, k)] + self.r[i];
                let c = self.inn2.iter().map(|v| v[i]).sum::<f64>() / m as f64;
                let dom = s - c;
                let xn = if s + c > 0.0 { dom / (s + c) } else { 0.0 };
                self.diag.mismatch[i] = xn;
                // Eq. 3.17 with ΔR = f·dt·R_{k−1}, the factor kept within [1/2, 2].
                let factor = (1.0 + fuzzy_rate(xn) * dt).clamp(0.5, 2.0);
                let rmin = self.r0[i] * 0.01;
                self.r[i] = (self.r[i] * factor).clamp(rmin, self.cfg.r_max.max(self.r0[i]));
                self.diag.r_scale[i] = self.r[i] / self.r0[i];
            }
            // Eqs. 2.8–2.10 for row i of H (eq. 3.10), Joseph form.
            let inn = zi - x[k];
            let s = self.p[(k, k)] + self.r[i];
            if !(s.is_finite() && s > 0.0) {
                continue;
            }
            let gain: Vec6 = self.p.column(k) / s;
            x += gain * inn;
            let mut ikh = Mat6::identity();
            for r in 0..6 {
                ikh[(r, k)] -= gain[r];
            }
            self.p = ikh * self.p * ikh.transpose() + gain * gain.transpose() * self.r[i];
        }
        self.p = (self.p + self.p.transpose()) * 0.5;
        // Fold the angle errors into the nominal attitude, C ← (I + [δ×]) C, and zero them.
        let delta = Vector3::new(x[ANGLE[0]], x[ANGLE[1]], x[ANGLE[2]]);
        self.q = renormalize(&(exp_rot(&delta) * q));
        self.bias += Vector3::new(x[BIAS[0]], x[BIAS[1]], x[BIAS[2]]);
        self.diag.bias = [self.bias.x, self.bias.y, self.bias.z];
    }

    fn healthy(&self) -> bool {
        self.q.is_some()
            && self
                .bias
                .iter()
                .all(|b| b.is_finite() && b.abs() <= MAX_BIAS)
            && self.p.iter().all(|v| v.is_finite())
            && (0..6).all(|i| self.p[(i, i)] >= 0.0 && self.p[(i, i)] <= MAX_VARIANCE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_base_follows_the_three_rules() {
        assert!(fuzzy_rate(0.0).abs() < 1e-9);
        assert!(fuzzy_rate(0.5) < 0.0 && fuzzy_rate(-0.5) > 0.0);
        assert!(fuzzy_rate(-0.99) > fuzzy_rate(-0.3));
        assert!(fuzzy_rate(0.99) < fuzzy_rate(0.3));
        // Odd symmetry: lowering and raising R are mirror images.
        for x in [0.1, 0.4, 0.9] {
            assert!((fuzzy_rate(x) + fuzzy_rate(-x)).abs() < 1e-9);
        }
    }

    #[test]
    fn window_and_noise_are_checked() {
        let e = KfNfaConfig {
            window: 0,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.to_string().contains("window"), "{e}");
        let e = KfNfaConfig {
            gyro_noise: f64::NAN,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.to_string().contains("gyro_noise"), "{e}");
        KfNfaConfig::default().validate().unwrap();
    }

    #[test]
    fn garbage_never_gives_nan() {
        let mut f = KfNfa::new(KfNfaConfig::default());
        let g = Vector3::new(0.0, 0.0, G0);
        for (i, (w, a)) in [
            (Vector3::zeros(), Vector3::zeros()),
            (Vector3::new(1e300, 0.0, 0.0), g),
            (Vector3::new(f64::NAN, 0.0, 0.0), g),
            (Vector3::zeros(), Vector3::new(f64::INFINITY, 0.0, 0.0)),
            (Vector3::new(50.0, -50.0, 3.0), g),
        ]
        .iter()
        .cycle()
        .take(500)
        .enumerate()
        {
            if let Some(q) = f.push(w, a, None, if i % 7 == 0 { 0.0 } else { 0.01 }) {
                assert!(q.as_ref().coords.iter().all(|v| v.is_finite()));
            }
        }
        assert!(f.diagnostics().resets > 0);
        // An unvalidated window of 0 neither panics nor adapts by nonsense.
        let mut f = KfNfa::new(KfNfaConfig {
            window: 0,
            ..Default::default()
        });
        for _ in 0..10 {
            assert!(f.push(&Vector3::zeros(), &g, None, 0.01).is_some());
        }
    }
}
