//! Activities from the leg pitch (Munoz Diaz 2015 §4.3): standing, sitting, walking, walking up
//! stairs and walking down stairs; running from the motion detector.
//! May import: the rest of `engine`.

/// What the walker is doing. Without a leg pitch (no gyroscope, or the phone not in a pocket)
/// only `still`, `walking` and `running` are told apart, from the motion detector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activity {
    /// No step, and no leg pitch to tell standing from sitting.
    #[default]
    Still,
    /// No step, the thigh near vertical (pitch near 0°).
    Standing,
    /// No step, the thigh near horizontal (pitch 45–90°).
    Sitting,
    /// Steps on level ground.
    Walking,
    /// Steps up a staircase.
    Upstairs,
    /// Steps down a staircase.
    Downstairs,
    /// Running (the motion detector's σ above its running threshold).
    Running,
    /// No step: the phone is being turned over in the hand ([`crate::engine::handling`]).
    Handling,
}

impl Activity {
    /// Lower-case name, as written in track files.
    pub fn as_str(self) -> &'static str {
        match self {
            Activity::Still => "still",
            Activity::Standing => "standing",
            Activity::Sitting => "sitting",
            Activity::Walking => "walking",
            Activity::Upstairs => "upstairs",
            Activity::Downstairs => "downstairs",
            Activity::Running => "running",
            Activity::Handling => "handling",
        }
    }

    /// Every activity, in the order above.
    pub const ALL: [Activity; 8] = [
        Activity::Still,
        Activity::Standing,
        Activity::Sitting,
        Activity::Walking,
        Activity::Upstairs,
        Activity::Downstairs,
        Activity::Running,
        Activity::Handling,
    ];
}

/// Settings of the activity classifier. The paper's rule (§4.3) compares each stride with the
/// mean of the recent level strides, strictly; it says the thresholds "can be universal or
/// personalized" and prints none. A strict comparison calls half of all level strides stairs
/// (any stride above the mean), so each test has a margin, chosen from the paper's own figures
/// (level Δθ_H ≈ 38°, up Δθ_U ≈ 53° with θ_Umax ≈ 2 θ_Hmax, down Δθ_D ≈ 27° with θ_Dmin > 0):
/// a stair stride passes them by twice the margin, a level stride at a cadence 20 % off the
/// mean does not reach them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ActivityConfig {
    /// Level strides averaged for the reference θ̄_Hmax, θ̄_Hmin, Δθ̄_H. Default 8.
    pub level_strides: usize,
    /// Strides at the start of a walk taken as level (the paper: "under the assumption that the
    /// pedestrian starts walking on a horizontal surface"). Default 2.
    pub warmup_strides: usize,
    /// Up stairs: Δθ > this × Δθ̄_H. Default 1.15.
    pub up_amplitude_ratio: f64,
    /// Up stairs: θ_max > θ̄_Hmax + this, degrees. Default 8°.
    pub up_max_margin_deg: f64,
    /// Down stairs: Δθ < this × Δθ̄_H. Default 0.85.
    pub down_amplitude_ratio: f64,
    /// Down stairs: θ_min > θ̄_Hmin + this, degrees. Default 8°.
    pub down_min_margin_deg: f64,
    /// Without steps, sitting when the pitch exceeds this, degrees; standing below. Default 35°:
    /// the paper has standing "around zero" and sitting "around 45–90 degrees".
    pub sitting_deg: f64,
}

impl Default for ActivityConfig {
    fn default() -> Self {
        ActivityConfig {
            level_strides: 8,
            warmup_strides: 2,
            up_amplitude_ratio: 1.15,
            up_max_margin_deg: 8.0,
            down_amplitude_ratio: 0.85,
            down_min_margin_deg: 8.0,
            sitting_deg: 35.0,
        }
    }
}

impl ActivityConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), super::types::ConfigError> {
        use super::types::{positive, ConfigError};
        if self.level_strides == 0 {
            return Err(ConfigError::new(
                "activity.level_strides",
                "must be at least 1",
            ));
        }
        positive("activity.up_amplitude_ratio", self.up_amplitude_ratio)?;
        positive("activity.down_amplitude_ratio", self.down_amplitude_ratio)?;
        for (v, f) in [
            (self.up_max_margin_deg, "activity.up_max_margin_deg"),
            (self.down_min_margin_deg, "activity.down_min_margin_deg"),
            (self.sitting_deg, "activity.sitting_deg"),
        ] {
            if !v.is_finite() {
                return Err(ConfigError::new(f, "must be finite"));
            }
        }
        Ok(())
    }
}

/// The classifier's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ActivityDiagnostics {
    /// The activity now.
    pub activity: Activity,
    /// The level reference (θ̄_Hmax, θ̄_Hmin, Δθ̄_H), degrees, once there is one.
    pub level: Option<(f64, f64, f64)>,
}

/// Munoz Diaz 2015 §4.3's activity classifier: stride by stride from the leg pitch, and from the
/// pitch alone when no step comes.
#[derive(Debug, Clone)]
pub struct ActivityClassifier {
    cfg: ActivityConfig,
    level: std::collections::VecDeque<(f64, f64, f64)>,
    strides: usize,
    now: Activity,
}

impl ActivityClassifier {
    /// A classifier with validated settings.
    pub fn new(cfg: ActivityConfig) -> Self {
        ActivityClassifier {
            cfg,
            level: std::collections::VecDeque::with_capacity(cfg.level_strides),
            strides: 0,
            now: Activity::Still,
        }
    }

    fn reference(&self) -> Option<(f64, f64, f64)> {
        let n = self.level.len();
        (n > 0).then(|| {
            let s = self
                .level
                .iter()
                .fold((0.0, 0.0, 0.0), |a, l| (a.0 + l.0, a.1 + l.1, a.2 + l.2));
            let n = n as f64;
            (s.0 / n, s.1 / n, s.2 / n)
        })
    }

    /// One stride's θ_max, θ_min and Δθ (degrees): the paper's rule.
    ///
    /// ```text
    /// if Δθ > Δθ̄_H && θ_max > θ̄_Hmax      → up stairs
    /// else if Δθ < Δθ̄_H && θ_min > θ̄_Hmin → down stairs
    /// else                                  → level (joins the reference)
    /// ```
    /// with the margins of [`ActivityConfig`].
    pub fn push_stride(&mut self, max_deg: f64, min_deg: f64, amplitude_deg: f64) -> Activity {
        let c = &self.cfg;
        self.strides += 1;
        let a = match self.reference() {
            Some((h_max, h_min, h_amp)) if self.strides > c.warmup_strides => {
                if amplitude_deg > c.up_amplitude_ratio * h_amp
                    && max_deg > h_max + c.up_max_margin_deg
                {
                    Activity::Upstairs
                } else if amplitude_deg < c.down_amplitude_ratio * h_amp
                    && min_deg > h_min + c.down_min_margin_deg
                {
                    Activity::Downstairs
                } else {
                    Activity::Walking
                }
            }
            _ => Activity::Walking,
        };
        if a == Activity::Walking {
            if self.level.len() == c.level_strides {
                self.level.pop_front();
            }
            self.level.push_back((max_deg, min_deg, amplitude_deg));
        }
        self.now = a;
        a
    }

    /// Forgets the level reference and starts the warm-up again (the leg pitch's sign turned
    /// over: the reference's extremes are the other way round).
    pub fn reset(&mut self) {
        self.level.clear();
        self.strides = 0;
    }

    /// A step without a stride of its own (running, or no leg pitch): the motion state's word.
    pub fn push_step(&mut self, running: bool) -> Activity {
        self.now = if running {
            Activity::Running
        } else {
            Activity::Walking
        };
        self.now
    }

    /// No step is coming: standing or sitting from the pitch (degrees), still without one.
    pub fn push_still(&mut self, pitch_deg: Option<f64>) -> Activity {
        self.now = match pitch_deg {
            Some(p) if p > self.cfg.sitting_deg => Activity::Sitting,
            Some(_) => Activity::Standing,
            None => Activity::Still,
        };
        self.now
    }

    /// The current values.
    pub fn diagnostics(&self) -> ActivityDiagnostics {
        ActivityDiagnostics {
            activity: self.now,
            level: self.reference(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's figures: level (26, −12, 38), up (51, −2, 53), down (29, 2.4, 26.6).
    #[test]
    fn the_papers_strides() {
        let mut c = ActivityClassifier::new(ActivityConfig::default());
        for _ in 0..4 {
            assert_eq!(c.push_stride(26.0, -12.0, 38.0), Activity::Walking);
        }
        // A faster level stride is not a stair.
        assert_eq!(c.push_stride(30.0, -14.0, 44.0), Activity::Walking);
        assert_eq!(c.push_stride(51.0, -2.0, 53.0), Activity::Upstairs);
        assert_eq!(c.push_stride(29.0, 2.4, 26.6), Activity::Downstairs);
        // A slower level stride is not one either.
        assert_eq!(c.push_stride(22.0, -10.0, 32.0), Activity::Walking);
        assert_eq!(c.push_still(Some(80.0)), Activity::Sitting);
        assert_eq!(c.push_still(Some(2.0)), Activity::Standing);
        assert_eq!(c.push_still(None), Activity::Still);
    }

    #[test]
    fn the_first_strides_are_level() {
        let mut c = ActivityClassifier::new(ActivityConfig::default());
        assert_eq!(c.push_stride(51.0, -2.0, 53.0), Activity::Walking);
        assert_eq!(c.push_stride(51.0, -2.0, 53.0), Activity::Walking);
    }
}
