//! Foot mode: a shoe-mounted IMU (Strozzi 2017 §3.2, the "EPDR" of a foot sensor): stance
//! detection ([`stance`]), strapdown integration with zero-velocity updates in an error-state
//! Kalman filter ([`zupt`]), and a stride at each stance from the integrated track.
//! May import: the rest of `engine`.
//!
//! The stage [`Foot`] takes every IMU sample and gives a [`Stride`] at the first (confirmed)
//! sample of each stance that follows a swing. Its length and heading are those of the foot's
//! horizontal displacement between the two stances, in the filter's frame: East-North-Up with
//! north the foot's x axis at the first stance (the yaw of a foot IMU without magnetometer is
//! unobservable; [`zupt`]).

pub mod placement;
pub mod stance;
pub mod zupt;

use crate::engine::math::heading_of;
use crate::engine::types::{ConfigError, ImuSample};
use nalgebra::Vector3;
use stance::{Stance, StanceConfig};
use zupt::{Zupt, ZuptConfig};

/// The shortest swing that makes a stride, s. A foot's swing lasts 0.3–0.5 s; on the x-io walks
/// the stance test also drops out for a few tens of milliseconds within a stance (the foot
/// rolling), which would otherwise count as strides of a few centimetres.
pub const MIN_SWING_S: f64 = 0.15;

/// Settings of foot mode.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FootConfig {
    /// The stance detector.
    pub stance: StanceConfig,
    /// The filter's noises.
    pub zupt: ZuptConfig,
}

impl FootConfig {
    /// Checks every value; the error names the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.stance.validate()?;
        self.zupt.validate()
    }
}

/// One stride of the foot: from toe-off to foot flat, and where it took the foot.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stride {
    /// Toe-off: the first sample of the swing, s.
    pub t_start: f64,
    /// Foot flat: the first sample of the stance that ends the stride, s.
    pub t_end: f64,
    /// Mid-swing, (t_start + t_end)/2, s (Strozzi §4 samples the trunk's heading there).
    pub t_mid_swing: f64,
    /// Horizontal displacement of the foot from the previous stance to this one, m.
    pub length_m: f64,
    /// Direction of that displacement, rad clockwise from the filter's north, in [0, 2π).
    pub heading_rad: f64,
    /// Foot position at foot flat, east, m.
    pub east_m: f64,
    /// Foot position at foot flat, north, m.
    pub north_m: f64,
    /// Foot position at foot flat, up, m.
    pub up_m: f64,
    /// Largest |ω| in the swing, rad/s (a foot turns at several rad/s; [`placement`]).
    pub peak_rate_rad_s: f64,
}

/// Counters and current values of foot mode; read-only.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct FootDiagnostics {
    /// Samples that went through the filter.
    pub samples: u64,
    /// Samples before the first stance (the filter starts at rest there).
    pub before_start: u64,
    /// Samples without a gyroscope reading (skipped).
    pub no_gyro: u64,
    /// Stances (of at least T_min).
    pub stances: u64,
    /// Runs of stillness shorter than T_min, discarded.
    pub discarded: u64,
    /// Strides emitted.
    pub strides: u64,
    /// "Swings" shorter than [`MIN_SWING_S`] between two stances: not strides.
    pub short_swings: u64,
    /// Horizontal distance of the strides, m.
    pub distance_m: f64,
    /// Zero-velocity updates refused (singular or non-finite), and filter restarts after a
    /// non-finite state.
    pub refused_updates: u64,
    /// Whether the foot is in a stance now (as released by the delay line).
    pub in_stance: bool,
    /// Position uncertainty, m (1σ, all axes).
    pub position_sigma_m: f64,
}

/// The foot-mode stage.
pub struct Foot {
    cfg: FootConfig,
    stance: Stance,
    zupt: Option<Zupt>,
    /// Sums of the first stance's specific force and rate, and their count.
    init: (Vector3<f64>, Vector3<f64>, u32),
    prev_stance: bool,
    swing_start: f64,
    swing_peak_rate: f64,
    /// Foot position at the end of the last stance.
    last_stance_p: Vector3<f64>,
    /// Where the foot was when the filter last restarted (it restarts from there).
    origin: Vector3<f64>,
    diag: FootDiagnostics,
}

impl Foot {
    /// The stage with validated settings.
    pub fn new(cfg: FootConfig) -> Result<Self, ConfigError> {
        cfg.validate()?;
        Ok(Foot {
            stance: Stance::new(cfg.stance)?,
            cfg,
            zupt: None,
            init: (Vector3::zeros(), Vector3::zeros(), 0),
            prev_stance: false,
            swing_start: 0.0,
            swing_peak_rate: 0.0,
            last_stance_p: Vector3::zeros(),
            origin: Vector3::zeros(),
            diag: FootDiagnostics::default(),
        })
    }

    /// Feeds one sample (checked by the caller: finite, in range) and its interval from the
    /// previous one. Returns the stride this sample's delayed label completed, if any.
    pub fn push(&mut self, s: &ImuSample, dt: f64) -> Option<Stride> {
        if s.gyro.is_none() {
            self.diag.no_gyro += 1;
            return None;
        }
        let l = self.stance.push(s, dt)?;
        let st = self.stance.diagnostics();
        self.diag.stances = st.stances;
        self.diag.discarded = st.discarded;
        self.diag.in_stance = l.stance;
        let w = l.sample.gyro.unwrap_or_default();
        let f = l.sample.accel;
        let t = l.sample.t;
        if self.zupt.is_none() {
            self.diag.before_start += 1;
            if l.stance {
                self.init.0 += f;
                self.init.1 += w;
                self.init.2 += 1;
            } else if self.init.2 > 0 {
                // The first stance is over: start from its mean, at the origin.
                let n = f64::from(self.init.2);
                self.zupt = Zupt::init(self.cfg.zupt, self.init.0 / n, self.init.1 / n);
                self.init = (Vector3::zeros(), Vector3::zeros(), 0);
                if let Some(z) = &mut self.zupt {
                    z.p = self.origin;
                    self.last_stance_p = z.p;
                }
                self.prev_stance = true;
                return self.push_labelled(f, w, t, l.dt, false);
            }
            return None;
        }
        self.push_labelled(f, w, t, l.dt, l.stance)
    }

    fn push_labelled(
        &mut self,
        f: Vector3<f64>,
        w: Vector3<f64>,
        t: f64,
        dt: f64,
        stance: bool,
    ) -> Option<Stride> {
        let z = self.zupt.as_mut()?;
        self.diag.samples += 1;
        z.propagate(&f, &w, dt);
        if stance && !z.zero_velocity() {
            self.diag.refused_updates += 1;
        }
        if !(z.p.iter().chain(z.v.iter()).all(|x| x.is_finite())
            && z.q.coords.iter().all(|x| x.is_finite()))
        {
            // Never reached on any log seen; restart at the next stance from the last good
            // position rather than emit NaN.
            self.diag.refused_updates += 1;
            self.origin = self.last_stance_p;
            self.zupt = None;
            self.prev_stance = false;
            return None;
        }
        self.diag.position_sigma_m = z.position_sigma();
        let p = z.p;
        let out = match (self.prev_stance, stance) {
            (true, false) => {
                self.swing_start = t;
                self.swing_peak_rate = w.norm();
                self.last_stance_p = p;
                None
            }
            (false, true) if t - self.swing_start < MIN_SWING_S => {
                // A flicker of the stance test, not a stride: the stance goes on.
                self.diag.short_swings += 1;
                self.last_stance_p = p;
                None
            }
            (false, true) => {
                let d = p - self.last_stance_p;
                let length = (d.x * d.x + d.y * d.y).sqrt();
                self.diag.strides += 1;
                self.diag.distance_m += length;
                Some(Stride {
                    t_start: self.swing_start,
                    t_end: t,
                    t_mid_swing: 0.5 * (self.swing_start + t),
                    length_m: length,
                    heading_rad: heading_of(d.x, d.y),
                    east_m: p.x,
                    north_m: p.y,
                    up_m: p.z,
                    peak_rate_rad_s: self.swing_peak_rate,
                })
            }
            (true, true) => {
                self.last_stance_p = p;
                None
            }
            (false, false) => {
                self.swing_peak_rate = self.swing_peak_rate.max(w.norm());
                None
            }
        };
        self.prev_stance = stance;
        out
    }

    /// After a gap in the input: the samples held for the stance test are dropped and the
    /// velocity is set to zero (nothing is integrated across a gap); the next swing starts from
    /// the last stance.
    pub fn gap(&mut self) {
        self.stance.clear();
        if let Some(z) = &mut self.zupt {
            z.v = Vector3::zeros();
            z.p = self.last_stance_p;
        }
        self.prev_stance = true;
    }

    /// The filter's state, once started: position, velocity (ENU), attitude (foot → ENU).
    pub fn state(&self) -> Option<&Zupt> {
        self.zupt.as_ref()
    }

    /// Counters and current values.
    pub fn diagnostics(&self) -> FootDiagnostics {
        self.diag
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = crate::engine::orientation::G0;

    fn s(t: f64, f: Vector3<f64>, w: Vector3<f64>) -> ImuSample {
        ImuSample {
            t,
            accel: f,
            gyro: Some(w),
            mag: None,
            orientation: None,
        }
    }

    /// Still 1 s, then `n` strides at 400 Hz: a 0.5 s swing pushing along the foot's x axis (+a
    /// for 0.25 s then −a: a·0.0625 m) while turning to and fro about the vertical at 3 rad/s
    /// (no net rotation), a 0.5 s stance.
    fn strides(n: usize, a: f64) -> Vec<Stride> {
        let mut foot = Foot::new(FootConfig::default()).unwrap();
        let dt = 0.0025;
        let mut t = 0.0;
        let mut out = Vec::new();
        let still = Vector3::new(0.0, 0.0, G);
        let w0 = Vector3::zeros();
        let mut feed = |foot: &mut Foot, t: &mut f64, f: Vector3<f64>, w: Vector3<f64>| {
            out.extend(foot.push(&s(*t, f, w), dt));
            *t += dt;
        };
        for _ in 0..400 {
            feed(&mut foot, &mut t, still, w0);
        }
        for _ in 0..n {
            for i in 0..200 {
                let ax = if i < 100 { a } else { -a };
                // A rate above th_ω with no net rotation: +ω then −ω about the vertical.
                let wz = if i % 2 == 0 { 3.0 } else { -3.0 };
                feed(
                    &mut foot,
                    &mut t,
                    Vector3::new(ax, 0.0, G),
                    Vector3::new(0.0, 0.0, wz),
                );
            }
            for _ in 0..200 {
                feed(&mut foot, &mut t, still, w0);
            }
        }
        for _ in 0..100 {
            feed(&mut foot, &mut t, still, w0);
        }
        out
    }

    #[test]
    fn strides_have_their_length_and_heading() {
        let out = strides(5, 4.0);
        assert_eq!(out.len(), 5);
        for (k, st) in out.iter().enumerate() {
            assert!((st.length_m - 0.25).abs() < 0.01, "stride {k}: {st:?}");
            let h = crate::engine::math::wrap_pi(st.heading_rad);
            assert!(h.abs() < 0.05, "stride {k} heading {h}");
            assert!(st.t_start < st.t_mid_swing && st.t_mid_swing < st.t_end);
            assert!((st.north_m - 0.25 * (k + 1) as f64).abs() < 0.05);
        }
    }
}
