//! Strapdown integration of a foot-mounted IMU with zero-velocity updates in a 9-state
//! error-state Kalman filter (Foxlin 2005, "Pedestrian tracking with shoe-mounted inertial
//! sensors", IEEE CG&A 25(6); the OpenShoe form of Nilsson, Skog, Händel, Hari 2012,
//! "Foot-mounted INS for everybody – an open-source embedded implementation", IEEE/ION PLANS).
//! May import: the rest of `engine`.
//!
//! # The filter
//! Navigation frame East-North-Up, the foot's attitude `q` taking foot-frame vectors to ENU.
//! Per sample (dt): `q ← q ⊗ exp((ω − b_ω) dt)`, `a = q f − (0, 0, g)`,
//! `p ← p + v dt + a dt²/2`, `v ← v + a dt`. The error state is δx = (δp, δv, δθ) with
//! `q_true = exp(δθ) ⊗ q` (attitude error in the navigation frame); it propagates with
//!
//! ```text
//!     | I  I·dt   0          |
//! F = | 0  I     −[q f]×·dt  |,   Q = diag(0, σ_a² dt I, σ_ω² dt I)
//!     | 0  0      I          |
//! ```
//!
//! and in a stance the pseudo-measurement "velocity is zero", `z = 0 − v`, `H = [0 I 0]`,
//! `R = σ_v² I`, is applied every sample (Joseph form). The correction is folded into the nominal
//! state and δx is reset to zero (the error-state form; with δθ small the reset Jacobian is I).
//!
//! # ESKF against a velocity reset
//! Setting v = 0 at each stance (Strozzi §3.2, and x-io's Gait-Tracking, which also removes a
//! linear drift of v over each swing) forgets where the velocity error came from. The filter
//! keeps the covariance the swing built between δv, δp and the tilt δθ (through −[q f]× of the
//! heel strike and push-off), so the zero-velocity measurement also corrects the position
//! accumulated from the velocity error and the roll and pitch that made gravity leak into the
//! horizontal acceleration; the tilt error is what drifts a reset-only track. Yaw and the
//! gyroscope bias about the vertical are unobservable from zero velocity; they drift, and the
//! gyroscope bias is taken from the first stance ([`Zupt::init`]).

use nalgebra::{Matrix3, SMatrix, UnitQuaternion, Vector3};

type M9 = SMatrix<f64, 9, 9>;

/// Noise settings of the filter (OpenShoe's defaults where they exist).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ZuptConfig {
    /// σ_a: accelerometer white noise, m/s²/√Hz-equivalent per sample. Default 0.5 (OpenShoe
    /// uses 0.5 m/s² for its MEMS IMU).
    pub sigma_a: f64,
    /// σ_ω: gyroscope white noise, rad/s. Default 0.5°/s (OpenShoe).
    pub sigma_w: f64,
    /// σ_v: the zero-velocity pseudo-measurement's noise, m/s. Default 0.01 (OpenShoe).
    pub sigma_v: f64,
    /// Initial attitude uncertainty (roll, pitch, yaw), rad (1σ). Default 1° tilt, 0.1° yaw (the
    /// yaw is the frame's, zero by definition).
    pub sigma_tilt0: f64,
}

impl Default for ZuptConfig {
    fn default() -> Self {
        ZuptConfig {
            sigma_a: 0.5,
            sigma_w: 0.5f64.to_radians(),
            sigma_v: 0.01,
            sigma_tilt0: 1f64.to_radians(),
        }
    }
}

impl ZuptConfig {
    /// Checks every value; the error names the field.
    pub fn validate(&self) -> Result<(), crate::engine::types::ConfigError> {
        use crate::engine::types::positive;
        positive("foot.zupt.sigma_a", self.sigma_a)?;
        positive("foot.zupt.sigma_w", self.sigma_w)?;
        positive("foot.zupt.sigma_v", self.sigma_v)?;
        positive("foot.zupt.sigma_tilt0", self.sigma_tilt0)
    }
}

/// The strapdown navigator and its error-state filter.
#[derive(Debug, Clone)]
pub struct Zupt {
    cfg: ZuptConfig,
    /// Foot → ENU.
    pub q: UnitQuaternion<f64>,
    /// Position, ENU, m.
    pub p: Vector3<f64>,
    /// Velocity, ENU, m/s.
    pub v: Vector3<f64>,
    /// Gyroscope bias, foot frame, rad/s.
    pub bias_w: Vector3<f64>,
    /// Gravity, m/s².
    pub g: f64,
    cov: M9,
}

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

impl Zupt {
    /// Starts at rest at the origin from the mean specific force `f` and mean angular rate `w`
    /// of a still foot: roll and pitch put `f` on the up axis, the yaw is zero (the foot's x axis
    /// points north), gravity is |f| (absorbing the accelerometer's scale error),
    /// the gyroscope bias is `w`.
    pub fn init(cfg: ZuptConfig, f: Vector3<f64>, w: Vector3<f64>) -> Option<Self> {
        let g = f.norm();
        if !(g > 1.0 && g.is_finite() && w.iter().all(|x| x.is_finite())) {
            return None;
        }
        // Tilt: the rotation taking f/|f| onto up.
        let tilt = UnitQuaternion::rotation_between(&f, &Vector3::z()).unwrap_or_else(|| {
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        });
        // The frame's yaw is arbitrary: take the foot's x axis, projected on the horizontal,
        // as north (heading zero).
        let x = tilt * Vector3::x();
        let azimuth = libm::atan2(x.y, x.x);
        let q = UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            std::f64::consts::FRAC_PI_2 - azimuth,
        ) * tilt;
        let mut cov = M9::zeros();
        let s0 = cfg.sigma_tilt0 * cfg.sigma_tilt0;
        cov[(6, 6)] = s0;
        cov[(7, 7)] = s0;
        cov[(8, 8)] = 0.1f64.to_radians() * 0.1f64.to_radians();
        Some(Zupt {
            cfg,
            q,
            p: Vector3::zeros(),
            v: Vector3::zeros(),
            bias_w: w,
            g,
            cov,
        })
    }

    /// Strapdown and covariance propagation over `dt` with specific force `f` and rate `w`
    /// (foot frame). `dt` ≤ 0 leaves the state as it is.
    pub fn propagate(&mut self, f: &Vector3<f64>, w: &Vector3<f64>, dt: f64) {
        if !(dt > 0.0) {
            return;
        }
        let w = w - self.bias_w;
        // Attitude: midpoint of the rate over the step is the sample's (zero-order hold).
        self.q *= UnitQuaternion::from_scaled_axis(w * dt);
        let fn_ = self.q * f;
        let a = fn_ - Vector3::new(0.0, 0.0, self.g);
        self.p += self.v * dt + a * (0.5 * dt * dt);
        self.v += a * dt;
        let mut fm = M9::identity();
        fm.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(Matrix3::identity() * dt));
        fm.fixed_view_mut::<3, 3>(3, 6)
            .copy_from(&(-skew(&fn_) * dt));
        let mut qd = M9::zeros();
        let qa = self.cfg.sigma_a * self.cfg.sigma_a * dt;
        let qw = self.cfg.sigma_w * self.cfg.sigma_w * dt;
        for i in 0..3 {
            qd[(3 + i, 3 + i)] = qa;
            qd[(6 + i, 6 + i)] = qw;
        }
        self.cov = fm * self.cov * fm.transpose() + qd;
        self.cov = (self.cov + self.cov.transpose()) * 0.5;
    }

    /// The zero-velocity update. Returns false (state untouched) if the innovation covariance
    /// cannot be inverted.
    pub fn zero_velocity(&mut self) -> bool {
        let r = self.cfg.sigma_v * self.cfg.sigma_v;
        let pvv = self.cov.fixed_view::<3, 3>(3, 3).into_owned();
        let s = pvv + Matrix3::identity() * r;
        let Some(si) = s.try_inverse() else {
            return false;
        };
        // K = P Hᵀ S⁻¹, P Hᵀ = the velocity columns of P.
        let pht = self.cov.fixed_view::<9, 3>(0, 3).into_owned();
        let k = pht * si;
        let z = -self.v;
        let dx = k * z;
        if !dx.iter().all(|x| x.is_finite()) {
            return false;
        }
        self.p += dx.fixed_rows::<3>(0);
        self.v += dx.fixed_rows::<3>(3);
        let dth = Vector3::new(dx[6], dx[7], dx[8]);
        self.q = UnitQuaternion::from_scaled_axis(dth) * self.q;
        // Joseph form: (I − KH) P (I − KH)ᵀ + K R Kᵀ.
        let mut ikh = M9::identity();
        let kh = {
            let mut m = M9::zeros();
            m.fixed_view_mut::<9, 3>(0, 3).copy_from(&k);
            m
        };
        ikh -= kh;
        self.cov = ikh * self.cov * ikh.transpose() + k * k.transpose() * r;
        self.cov = (self.cov + self.cov.transpose()) * 0.5;
        true
    }

    /// Position σ, m (trace-based, for diagnostics).
    pub fn position_sigma(&self) -> f64 {
        (self.cov[(0, 0)] + self.cov[(1, 1)] + self.cov[(2, 2)])
            .max(0.0)
            .sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.80665;

    #[test]
    fn a_still_imu_with_a_gyro_bias_stays_put() {
        // Tilted foot, gyro bias 0.01 rad/s on each axis, 400 Hz for 20 s, ZUPT every sample.
        let att = UnitQuaternion::from_euler_angles(0.2, -0.3, 1.0);
        let f = att.inverse() * Vector3::new(0.0, 0.0, G);
        let b = Vector3::new(0.01, -0.01, 0.01);
        let mut z = Zupt::init(ZuptConfig::default(), f, b).unwrap();
        let up = z.q * f;
        assert!(
            (up - Vector3::new(0.0, 0.0, G)).norm() < 1e-9,
            "tilt from gravity"
        );
        for _ in 0..8000 {
            z.propagate(&f, &b, 0.0025);
            assert!(z.zero_velocity());
        }
        assert!(z.p.norm() < 1e-3, "drifted {} m", z.p.norm());
        assert!(z.v.norm() < 1e-3);
    }

    #[test]
    fn a_slide_between_stances_has_its_length() {
        // Level foot: accelerate 1 m/s² for 0.5 s, decelerate 0.5 s: 0.25 m.
        let f0 = Vector3::new(0.0, 0.0, G);
        let w0 = Vector3::zeros();
        let mut z = Zupt::init(ZuptConfig::default(), f0, w0).unwrap();
        let dt = 0.0025;
        for _ in 0..200 {
            z.propagate(&f0, &w0, dt);
            z.zero_velocity();
        }
        // The init yaw makes the foot's x axis north-of-frame zero: push along foot x.
        for i in 0..400 {
            let a = if i < 200 { 1.0 } else { -1.0 };
            z.propagate(&Vector3::new(a, 0.0, G), &w0, dt);
        }
        for _ in 0..200 {
            z.propagate(&f0, &w0, dt);
            z.zero_velocity();
        }
        let h = (z.p.x * z.p.x + z.p.y * z.p.y).sqrt();
        assert!((h - 0.25).abs() < 0.001, "length {h}");
        assert!(z.v.norm() < 1e-3);
    }
}
