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
        }
    }

    /// Every activity, in the order above.
    pub const ALL: [Activity; 7] = [
        Activity::Still,
        Activity::Standing,
        Activity::Sitting,
        Activity::Walking,
        Activity::Upstairs,
        Activity::Downstairs,
        Activity::Running,
    ];

    /// Whether the walker takes steps.
    pub fn is_stepping(self) -> bool {
        matches!(
            self,
            Activity::Walking | Activity::Upstairs | Activity::Downstairs | Activity::Running
        )
    }
}
