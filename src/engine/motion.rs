//! Motion detection by the standard deviation of vertical acceleration (Basso 2016 §II.B).
//!
//! σ_z(t) = sqrt( (1/n₂) Σ_{t_k ∈ Φ₂(t)} (a_z(t_k) − μ_z(t))² ), Φ₂(t) = { t_k : t_k ≥ t − 2 },
//! kept up to date incrementally with a time-regulated buffer: the sums Σa and Σa² are updated with
//! the samples pushed in and pulled out. Thresholds: 1.5 m/s² between still and moving, 5 m/s²
//! between walking and running. Basso 2021 §2.2.2 uses the variance over 4 s with a threshold of
//! 1.5 m²/s⁴ instead; we follow the 2016 paper, which the issue names.

use super::types::{positive, ConfigError};
use std::collections::VecDeque;

/// Motion state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// σ below the still threshold: step detection disabled.
    Still,
    /// σ between the two thresholds.
    Walking,
    /// σ above the running threshold.
    Running,
}

impl Motion {
    /// Lower-case name, as written in track files.
    pub fn as_str(self) -> &'static str {
        match self {
            Motion::Still => "still",
            Motion::Walking => "walking",
            Motion::Running => "running",
        }
    }

    /// Whether steps are detected in this state.
    pub fn is_moving(self) -> bool {
        self != Motion::Still
    }
}

/// Settings of the motion detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct MotionConfig {
    /// Window length, seconds (Basso 2016: 2 s).
    pub window_s: f64,
    /// σ threshold between still and moving, m/s² (Basso 2016: 1.5).
    pub still_max: f64,
    /// σ threshold between walking and running, m/s² (Basso 2016: 5).
    pub walk_max: f64,
    /// Data span the window must cover before σ is trusted, seconds. Before that (start of a log,
    /// or after a gap) the previous state is kept. Our choice: half a second, about one step.
    pub min_span_s: f64,
}

impl Default for MotionConfig {
    fn default() -> Self {
        MotionConfig {
            window_s: 2.0,
            still_max: 1.5,
            walk_max: 5.0,
            min_span_s: 0.5,
        }
    }
}

impl MotionConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("motion.window_s", self.window_s)?;
        positive("motion.still_max", self.still_max)?;
        positive("motion.min_span_s", self.min_span_s)?;
        if !(self.walk_max > self.still_max) {
            return Err(ConfigError::new(
                "motion.walk_max",
                "must exceed motion.still_max",
            ));
        }
        if self.min_span_s > self.window_s {
            return Err(ConfigError::new(
                "motion.min_span_s",
                "must not exceed motion.window_s",
            ));
        }
        Ok(())
    }
}

/// The running detector.
#[derive(Debug, Clone)]
pub struct MotionDetector {
    cfg: MotionConfig,
    buf: VecDeque<(f64, f64)>,
    sum: f64,
    sum_sq: f64,
    pops: u32,
    state: Motion,
    sigma: f64,
    mean: f64,
}

impl MotionDetector {
    /// A detector in the still state.
    pub fn new(cfg: MotionConfig) -> Self {
        MotionDetector {
            cfg,
            buf: VecDeque::new(),
            sum: 0.0,
            sum_sq: 0.0,
            pops: 0,
            state: Motion::Still,
            sigma: 0.0,
            mean: 0.0,
        }
    }

    /// Adds a vertical-acceleration sample (m/s², gravity removed) and returns the state.
    pub fn push(&mut self, t: f64, a: f64) -> Motion {
        self.buf.push_back((t, a));
        self.sum += a;
        self.sum_sq += a * a;
        while let Some(&(t0, a0)) = self.buf.front() {
            if t0 >= t - self.cfg.window_s {
                break;
            }
            self.buf.pop_front();
            self.sum -= a0;
            self.sum_sq -= a0 * a0;
            self.pops += 1;
        }
        // Re-sum now and then so rounding in the running sums cannot accumulate.
        if self.pops >= 4096 {
            self.pops = 0;
            self.sum = self.buf.iter().map(|p| p.1).sum();
            self.sum_sq = self.buf.iter().map(|p| p.1 * p.1).sum();
        }
        let n = self.buf.len() as f64;
        self.mean = self.sum / n;
        self.sigma = (self.sum_sq / n - self.mean * self.mean).max(0.0).sqrt();
        let span = t - self.buf.front().map_or(t, |p| p.0);
        if span >= self.cfg.min_span_s {
            self.state = if self.sigma < self.cfg.still_max {
                Motion::Still
            } else if self.sigma < self.cfg.walk_max {
                Motion::Walking
            } else {
                Motion::Running
            };
        }
        self.state
    }

    /// Drops the window (after a gap). The state is kept until the window refills.
    pub fn clear_window(&mut self) {
        self.buf.clear();
        self.sum = 0.0;
        self.sum_sq = 0.0;
    }

    /// σ_z over the window, m/s².
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// μ_z over the window, m/s².
    pub fn mean(&self) -> f64 {
        self.mean
    }

    /// Current state.
    pub fn state(&self) -> Motion {
        self.state
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn sigma_matches_direct_computation() {
        let mut d = MotionDetector::new(MotionConfig::default());
        let mut all = Vec::new();
        for i in 0..1000 {
            let t = i as f64 * 0.013;
            let a = (t * 7.0).sin() * 3.0 + 0.5;
            d.push(t, a);
            all.push((t, a));
        }
        let t_end = all.last().unwrap().0;
        let w: Vec<f64> = all
            .iter()
            .filter(|p| p.0 >= t_end - 2.0)
            .map(|p| p.1)
            .collect();
        let m = w.iter().sum::<f64>() / w.len() as f64;
        let s = (w.iter().map(|a| (a - m) * (a - m)).sum::<f64>() / w.len() as f64).sqrt();
        assert!((d.sigma() - s).abs() < 1e-9 && (d.mean() - m).abs() < 1e-12);
    }
}
