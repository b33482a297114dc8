//! The walker's height: Munoz Diaz 2015 §6's vertical displacement from the leg pitch on stairs,
//! fused with the barometer where the log has one, and the floor changes.
//! May import: the rest of `engine`.

/// Where the height comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VerticalSource {
    /// The leg pitch alone (Munoz Diaz 2015 eqs. 6–7): no barometer.
    Pitch,
    /// The barometer alone: no leg pitch (not in a pocket, or no gyroscope).
    Barometer,
    /// Both, fused.
    PitchAndBarometer,
}

impl VerticalSource {
    /// Lower-case words, as shown.
    pub fn as_str(self) -> &'static str {
        match self {
            VerticalSource::Pitch => "leg pitch",
            VerticalSource::Barometer => "barometer",
            VerticalSource::PitchAndBarometer => "leg pitch + barometer",
        }
    }
}
