//! What the filter reports: the fused estimate at each step ([`FusedStep`]) and what happened
//! to each fix ([`FixOutcome`], counted in [`FixCounts`]).
//! May import: nothing of `engine`.

/// What happened to a fix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FixOutcome {
    /// It updated the filter.
    Used,
    /// It started the filter (the first usable fix).
    Started,
    /// Its reported accuracy was worse than the limit.
    TooInaccurate,
    /// It was older than the limit when the next step came.
    Stale,
    /// The Mahalanobis gate refused it.
    Gated,
    /// It reset the position after repeated gating.
    Reset,
    /// The receiver was off (energy saving).
    ReceiverOff,
    /// Held for a consensus of fixes (the prior was too wide to gate one fix alone).
    Held,
}

impl FixOutcome {
    /// The outcome's name as the files write it (the fused CSV's `fix` column, the JSON).
    pub fn as_str(self) -> &'static str {
        match self {
            FixOutcome::Used => "used",
            FixOutcome::Started => "started",
            FixOutcome::TooInaccurate => "too_inaccurate",
            FixOutcome::Stale => "stale",
            FixOutcome::Gated => "gated",
            FixOutcome::Reset => "reset",
            FixOutcome::ReceiverOff => "receiver_off",
            FixOutcome::Held => "held",
        }
    }
}

/// Counters of the fixes by outcome.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FixCounts {
    /// Used in an update.
    pub used: u64,
    /// Refused for their accuracy.
    pub too_inaccurate: u64,
    /// Refused as stale.
    pub stale: u64,
    /// Refused by the gate.
    pub gated: u64,
    /// Position resets after repeated gating.
    pub resets: u64,
    /// Ignored while the receiver was off.
    pub receiver_off: u64,
    /// Replaced by a newer fix before a step came.
    pub superseded: u64,
    /// Baselines between fixes that taught the scale and the heading correction.
    pub baselines: u64,
    /// Baselines refused by the gate.
    pub baselines_gated: u64,
}

/// The filter's result at one step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FusedStep {
    /// Time of the step, s.
    pub t: f64,
    /// Fused position, east and north, m (local tangent plane of the first fix).
    pub east_m: f64,
    /// See `east_m`.
    pub north_m: f64,
    /// Position covariance (ee, en, nn), m².
    pub cov: [f64; 3],
    /// Step-length scale.
    pub scale: f64,
    /// Heading correction, rad.
    pub bias_rad: f64,
    /// Standard deviations of the scale and the heading correction (rad).
    pub scale_bias_sd: [f64; 2],
    /// Innovation of the fix used or refused at this step (east, north), m.
    pub innovation: Option<[f64; 2]>,
    /// What happened to the fix offered at this step, if any.
    pub fix: Option<FixOutcome>,
}

/// What the filter makes of the GNSS at the moment, for the user.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GnssVerdict {
    /// No usable fix yet.
    Waiting,
    /// Fixes correct the position; the walk has not yet made the step-length scale and the
    /// heading correction known.
    Learning,
    /// The scale and the heading correction are known (within
    /// `FusionConfig::calibrated_scale_sd` and `calibrated_bias_sd_deg`).
    Calibrated,
    /// Most recent fixes disagree with the steps beyond their error: the track follows the
    /// steps.
    Distrusted,
}

impl GnssVerdict {
    /// The notice shown to the user.
    pub fn text(self) -> &'static str {
        match self {
            GnssVerdict::Waiting => "Waiting for GNSS",
            GnssVerdict::Learning => "GNSS: learning your step length and heading",
            GnssVerdict::Calibrated => "GNSS: step length and heading known",
            GnssVerdict::Distrusted => "GNSS disagrees with your steps: using steps",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::FixOutcome;

    #[test]
    fn outcome_names_are_the_json_names() {
        use FixOutcome::*;
        for o in [
            Used,
            Started,
            TooInaccurate,
            Stale,
            Gated,
            Reset,
            ReceiverOff,
            Held,
        ] {
            assert_eq!(serde_json::to_value(o).unwrap(), o.as_str());
        }
    }
}
