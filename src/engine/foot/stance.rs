//! Stance detection for a foot-mounted IMU (Strozzi 2017 §3.2, eqs. 1–2 and the minimum
//! stance duration T_min).
//! May import: the rest of `engine`.
//!
//! Strozzi's indicator (eq. 2) is γ(i) = 1 when a_Σ(i) < th_a and |ω(i)| < th_ω, with
//! |ω| the norm of the angular rate and a_Σ (eq. 1) the absolute value of the *sum* of the three
//! components of the linear (gravity-free) acceleration in the world frame, which the Xsens
//! sensor computes itself. A stance (a run of γ = 1) shorter than T_min is discarded (set to 0).
//!
//! # Decisions (the paper is vague or wrong here; measured on `../shared/data/xio-foot`)
//! - **a_Σ.** The sum of the components is not rotation-invariant and needs an attitude before
//!   the stance is known (the filter that gives it needs the stance). The detector uses the
//!   orientation-free form `a_Σ = | |f| − g |`, the deviation of the specific force's norm from
//!   gravity, which is zero whenever the foot is still whatever its attitude (the first test of
//!   the standard "GLRT"/magnitude detectors of the field).
//! - **th_ω.** The printed th_ω = 50 rad/s (2 865 °/s) is above the whole range of the x-io
//!   NGIMU's gyroscope (2 000 °/s): with it, γ is decided by the acceleration alone and every
//!   moment of mid-swing where |f| crosses g (several per stride) would be a "stance". It is
//!   surely 50 °/s (0.87 rad/s), a value of the field. On the x-io walks |ω| is under 0.3 rad/s
//!   for most of each stance and 3–10 rad/s in swing; the default here is 0.6 rad/s (34 °/s):
//!   see [`StanceConfig::th_w_rad_s`].
//! - **th_a.** The printed th_a = 9 m/s² concerns a_Σ of the linear acceleration; with the
//!   norm's deviation, a foot flat on the ground is within 0.5 m/s² of g and the heel strike and
//!   push-off reach 10–30 m/s². The default is 2.5 m/s² (see [`StanceConfig::th_a_m_s2`]).
//! - **T_min.** 0.3 s as printed would drop the short stances of a brisk walk (0.15–0.3 s on the
//!   long x-io walk); the default is 0.1 s, which still removes the single-sample crossings of
//!   mid-swing.
//!
//! Streaming: whether a sample belongs to a stance of at least T_min is known T_min after it,
//! so [`Stance`] is a delay line that releases each sample with its final label T_min late.

use crate::engine::types::{positive, ConfigError, ImuSample};
use std::collections::VecDeque;

/// Settings of the stance detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StanceConfig {
    /// th_a: largest | |f| − g | of a still foot, m/s². Default 2.5 (x-io walks: a foot flat
    /// stays within 0.5 m/s² of g; the swing is far above).
    pub th_a_m_s2: f64,
    /// th_ω: largest |ω| of a still foot, rad/s. Default 0.6 (34 °/s); Strozzi prints 50 rad/s,
    /// surely meaning 50 °/s (see the module documentation).
    pub th_w_rad_s: f64,
    /// T_min: shortest stance, s. Default 0.1 (Strozzi: 0.3, too long for brisk walking).
    pub t_min_s: f64,
    /// Gravity used in | |f| − g |, m/s². Default [`crate::engine::orientation::G0`].
    pub g_m_s2: f64,
}

impl Default for StanceConfig {
    fn default() -> Self {
        StanceConfig {
            th_a_m_s2: 2.5,
            th_w_rad_s: 0.6,
            t_min_s: 0.1,
            g_m_s2: crate::engine::orientation::G0,
        }
    }
}

impl StanceConfig {
    /// Checks every value; the error names the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("foot.stance.th_a_m_s2", self.th_a_m_s2)?;
        positive("foot.stance.th_w_rad_s", self.th_w_rad_s)?;
        positive("foot.stance.t_min_s", self.t_min_s)?;
        positive("foot.stance.g_m_s2", self.g_m_s2)?;
        if self.t_min_s > 5.0 {
            return Err(ConfigError::new(
                "foot.stance.t_min_s",
                format!(
                    "must be at most 5 s (a delay line that long), got {}",
                    self.t_min_s
                ),
            ));
        }
        Ok(())
    }

    /// Strozzi eq. 2: γ(i) for one sample (before the duration test). Needs the gyroscope.
    pub fn gamma(&self, accel_norm: f64, gyro_norm: f64) -> bool {
        (accel_norm - self.g_m_s2).abs() < self.th_a_m_s2 && gyro_norm < self.th_w_rad_s
    }
}

/// The most samples the delay line holds, whatever the clock does (T_min at 8 kHz): a stuck
/// clock must not grow memory without bound.
pub const MAX_HELD: usize = 4096;

/// A sample released by the delay line with its final label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Labelled {
    /// The sample.
    pub sample: ImuSample,
    /// Its dt, s.
    pub dt: f64,
    /// Whether it belongs to a stance of at least T_min.
    pub stance: bool,
}

/// Counters of the stance detector.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct StanceDiagnostics {
    /// Stances of at least T_min (each counted when its first sample is released).
    pub stances: u64,
    /// Runs of γ = 1 shorter than T_min, discarded.
    pub discarded: u64,
}

/// The streaming stance detector: γ (eq. 2), then the T_min test, T_min late.
pub struct Stance {
    cfg: StanceConfig,
    buf: VecDeque<(Labelled, bool)>,
    /// Time of the first sample of the current run of γ = 1 among released samples.
    run_start: Option<f64>,
    prev_released: bool,
    diag: StanceDiagnostics,
}

impl Stance {
    /// A detector with validated settings.
    pub fn new(cfg: StanceConfig) -> Result<Self, ConfigError> {
        cfg.validate()?;
        Ok(Stance {
            cfg,
            buf: VecDeque::new(),
            run_start: None,
            prev_released: false,
            diag: StanceDiagnostics::default(),
        })
    }

    /// Feeds a sample (it must hold a gyroscope reading; without one γ = 0). Returns the samples
    /// whose label became final, oldest first (usually one, none while the line fills).
    pub fn push(&mut self, s: &ImuSample, dt: f64) -> Option<Labelled> {
        let gamma = s
            .gyro
            .is_some_and(|g| self.cfg.gamma(s.accel.norm(), g.norm()));
        self.buf.push_back((
            Labelled {
                sample: *s,
                dt,
                stance: false,
            },
            gamma,
        ));
        let oldest = self.buf.front()?.0.sample.t;
        if s.t - oldest < self.cfg.t_min_s && self.buf.len() <= MAX_HELD {
            return None;
        }
        let (mut out, gamma) = self.buf.pop_front()?;
        out.stance = gamma && self.confirmed(out.sample.t);
        if gamma && !out.stance && self.run_start.is_none() {
            self.diag.discarded += 1;
        }
        self.run_start = if gamma {
            Some(self.run_start.unwrap_or(out.sample.t))
        } else {
            None
        };
        if out.stance && !self.prev_released {
            self.diag.stances += 1;
        }
        self.prev_released = out.stance;
        Some(out)
    }

    /// Whether the run of γ = 1 holding the sample at `t` (just released) lasts at least T_min:
    /// from the run's first released sample to the last consecutive γ = 1 still in the line.
    fn confirmed(&self, t: f64) -> bool {
        let start = self.run_start.unwrap_or(t);
        let mut end = t;
        for (x, g) in &self.buf {
            if !*g {
                break;
            }
            end = x.sample.t;
        }
        end - start >= self.cfg.t_min_s
    }

    /// Counters.
    pub fn diagnostics(&self) -> StanceDiagnostics {
        self.diag
    }

    /// Forgets the samples in the line (after a gap).
    pub fn clear(&mut self) {
        self.buf.clear();
        self.run_start = None;
        self.prev_released = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn sample(t: f64, still: bool) -> ImuSample {
        let g = crate::engine::orientation::G0;
        ImuSample {
            t,
            accel: if still {
                Vector3::new(0.0, 0.0, g)
            } else {
                Vector3::new(5.0, 0.0, g + 8.0)
            },
            gyro: Some(if still {
                Vector3::zeros()
            } else {
                Vector3::new(0.0, 5.0, 0.0)
            }),
            mag: None,
            orientation: None,
        }
    }

    /// Labels of a pattern of still (true) and moving samples at 100 Hz.
    fn run(pattern: &[(bool, usize)]) -> (Vec<bool>, StanceDiagnostics) {
        let mut st = Stance::new(StanceConfig::default()).unwrap();
        let mut out = Vec::new();
        let mut i = 0;
        for &(still, n) in pattern {
            for _ in 0..n {
                if let Some(l) = st.push(&sample(i as f64 * 0.01, still), 0.01) {
                    out.push(l.stance);
                }
                i += 1;
            }
        }
        (out, st.diagnostics())
    }

    #[test]
    fn a_long_stance_is_kept_a_short_one_discarded() {
        // 30 still, 50 moving, 5 still (under T_min = 0.1 s), 50 moving, 30 still, 20 moving.
        let (labels, d) = run(&[
            (true, 30),
            (false, 50),
            (true, 5),
            (false, 50),
            (true, 30),
            (false, 20),
        ]);
        // Released T_min (10 or 11 samples, as the clock's rounding falls) late.
        assert!((174..=175).contains(&labels.len()), "{}", labels.len());
        assert!(labels[..30].iter().all(|&x| x));
        assert!(
            labels[30..135].iter().all(|&x| !x),
            "the short run is discarded"
        );
        assert!(labels[135..165].iter().all(|&x| x));
        assert!(labels[165..].iter().all(|&x| !x));
        assert_eq!(d.stances, 2);
        assert_eq!(d.discarded, 1);
    }

    #[test]
    fn gamma_needs_both_thresholds() {
        let c = StanceConfig::default();
        assert!(c.gamma(c.g_m_s2 + 0.2, 0.1));
        assert!(!c.gamma(c.g_m_s2 + 3.0, 0.1), "acceleration above th_a");
        assert!(!c.gamma(c.g_m_s2, 2.0), "rate above th_ω");
        let mut bad = c;
        bad.t_min_s = f64::NAN;
        assert_eq!(bad.validate().unwrap_err().field, "foot.stance.t_min_s");
    }
}
