//! Which pocket (ours): a phone in a back pocket rides behind the hip, and its path lags the
//! walker's turns. May import: the rest of `engine`.
//!
//! **Why it matters.** In a turn at rate φ̇ and speed v, a point d behind the point the walker
//! turns about moves like a trailer: its path's direction is the body's less d·φ̇/v. From
//! TyrEx's motion capture, a phone in a back pocket sits 0.15–0.18 m behind that point and its
//! path lags the screen's yaw by 0.16–0.26 s, about what the turn lead adds
//! ([`crate::engine::heading::turn`]); a front pocket's sits on it (−0.05 … +0.05 m). So the
//! pocket's heading takes the screen's yaw over the stride before the step in a back pocket,
//! and at the step's middle elsewhere ([`crate::engine::heading::yaw_aid`]).
//!
//! **How the pocket is told.** On the thigh the phone swings about one horizontal axis; on the
//! buttock the hip's swing mixes with the pelvis's tilt and roll. The leg pitch's swing axis
//! ([`crate::engine::leg_pitch::LegPitch::swing_share`]) therefore holds a smaller share of the
//! gyroscope's horizontal rotation in a back pocket. Each walking step in a pocket adds the
//! share to a mean: of the steps so far, then exponential over [`BackPocketConfig::steps`]
//! steps. Below [`BackPocketConfig::max_share`] the phone rides behind the hip.
//!
//! **The threshold** was chosen on the walks of `ubicomp13-pocket` alone, whose placement is
//! labelled: 23 walks by 12 people, the walks' means 0.83–0.91 in a front pocket and 0.68–0.84
//! in a back one. 0.838 errs on one walk (a front pocket at 0.828); chosen leaving each person
//! out, it errs on 3 of the 23. On `tyrex-pocket`, not used to choose it, it tells all twelve
//! walking pocket walks apart (front 0.86–0.92, back 0.75–0.83), and the back pocket's heading
//! goes 9.6° → 6.0° (docs/methods/pocket-heading.md).
//!
//! Running steps neither teach the mean nor ride behind: running swings the thigh another way
//! (TyrEx's running walks in a pocket read 0.59–0.86), and their headings need the whole lead.
//! Another carrying mode starts the mean again: the phone may come back to the other pocket.

use super::types::ConfigError;

/// Settings of the pocket's side.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct BackPocketConfig {
    /// Whether a back pocket is told from a front one (default on); off, every pocket is led
    /// as a front pocket.
    pub on: bool,
    /// A pocket whose walking steps' mean swing-axis share is below this is a back pocket.
    pub max_share: f64,
    /// The mean's memory, steps.
    pub steps: f64,
}

impl Default for BackPocketConfig {
    fn default() -> Self {
        BackPocketConfig {
            on: true,
            max_share: 0.838,
            steps: 20.0,
        }
    }
}

impl BackPocketConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(self.max_share > 0.0 && self.max_share <= 1.0) {
            return Err(ConfigError::new(
                "back_pocket.max_share",
                "must be in (0, 1]",
            ));
        }
        if !(self.steps >= 1.0 && self.steps.is_finite()) {
            return Err(ConfigError::new(
                "back_pocket.steps",
                "must be a finite number of steps, 1 or more",
            ));
        }
        Ok(())
    }
}

/// One step as the pocket's side sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackPocketInput {
    /// The leg pitch's swing-axis share now, once it has one.
    pub share: Option<f64>,
    /// The carrying mode reads a pocket.
    pub pocket: bool,
    /// The step is walked, not run.
    pub walking: bool,
}

/// What the stage holds.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct BackPocketDiagnostics {
    /// The mean swing-axis share of the pocket's walking steps so far.
    pub mean_share: Option<f64>,
    /// The last step rode behind the hip.
    pub behind: bool,
}

/// The pocket's side, step by step.
#[derive(Debug, Clone)]
pub struct BackPocket {
    cfg: BackPocketConfig,
    diag: BackPocketDiagnostics,
    // Steps in the mean since it started.
    taught: f64,
}

impl BackPocket {
    /// A stage with validated settings.
    pub fn new(cfg: BackPocketConfig) -> Self {
        BackPocket {
            cfg,
            diag: BackPocketDiagnostics::default(),
            taught: 0.0,
        }
    }

    /// Feeds one step; whether it rides behind the hip.
    pub fn push(&mut self, x: &BackPocketInput) -> bool {
        let d = &mut self.diag;
        if !x.pocket {
            d.mean_share = None;
        }
        if x.pocket && x.walking {
            if let Some(s) = x.share.filter(|s| *s > 0.0 && *s <= 1.0) {
                // The mean of the steps so far, then an exponential one: the first steps
                // weigh no more than the others.
                self.taught = if d.mean_share.is_some() {
                    self.taught + 1.0
                } else {
                    1.0
                };
                let m = d.mean_share.get_or_insert(s);
                *m += (s - *m) / self.taught.min(self.cfg.steps);
            }
        }
        d.behind = self.cfg.on
            && x.pocket
            && x.walking
            && d.mean_share.is_some_and(|m| m < self.cfg.max_share);
        d.behind
    }

    /// What the stage holds.
    pub fn diagnostics(&self) -> BackPocketDiagnostics {
        self.diag
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(share: f64, pocket: bool, walking: bool) -> BackPocketInput {
        BackPocketInput {
            share: Some(share),
            pocket,
            walking,
        }
    }

    #[test]
    fn a_buttock_rides_behind_the_hip_and_a_thigh_does_not() {
        let mut b = BackPocket::new(BackPocketConfig::default());
        assert!((0..30).all(|_| b.push(&step(0.76, true, true))));
        let mut f = BackPocket::new(BackPocketConfig::default());
        assert!((0..30).all(|_| !f.push(&step(0.89, true, true))));
    }

    #[test]
    fn running_neither_teaches_nor_rides_behind() {
        let mut b = BackPocket::new(BackPocketConfig::default());
        assert!(!b.push(&step(0.6, true, false)));
        assert_eq!(b.diagnostics().mean_share, None);
        for _ in 0..30 {
            b.push(&step(0.76, true, true));
        }
        assert!(!b.push(&step(0.76, true, false)), "a running step is led");
        assert!(b.push(&step(0.76, true, true)));
    }

    #[test]
    fn the_mean_follows_a_change_of_pocket_and_starts_again_out_of_it() {
        let mut b = BackPocket::new(BackPocketConfig::default());
        for _ in 0..40 {
            b.push(&step(0.76, true, true));
        }
        // The same pocket, the share drifting up: the mean follows within its memory.
        let n = (0..200)
            .take_while(|_| b.push(&step(0.9, true, true)))
            .count();
        assert!((3..20).contains(&n), "{n} steps to follow");
        // Out of the pocket: nothing rides behind, and the mean starts again.
        assert!(!b.push(&step(0.7, false, true)));
        assert_eq!(b.diagnostics().mean_share, None);
        assert!(!b.push(&step(0.9, true, true)));
    }

    #[test]
    fn bad_settings_are_refused_by_name() {
        for (cfg, name) in [
            (
                BackPocketConfig {
                    max_share: 0.0,
                    ..Default::default()
                },
                "back_pocket.max_share",
            ),
            (
                BackPocketConfig {
                    steps: f64::NAN,
                    ..Default::default()
                },
                "back_pocket.steps",
            ),
        ] {
            let e = cfg.validate().unwrap_err();
            assert!(e.to_string().contains(name), "{e}");
        }
        assert!(BackPocketConfig::default().validate().is_ok());
    }

    #[test]
    fn no_share_yet_is_the_front_pocket() {
        let mut b = BackPocket::new(BackPocketConfig::default());
        let x = BackPocketInput {
            share: None,
            pocket: true,
            walking: true,
        };
        assert!(!b.push(&x));
    }
}
