//! Which of live mode's buttons the page shows in each of its states.
//! May import: nothing.

/// The buttons of live mode in `state` (`idle`, `recording` or `stopped`), each with whether it
/// is hidden: Start unless recording; Stop and the pocket lock while recording; the download
/// once a recording has stopped.
pub fn controls(state: &str) -> [(&'static str, bool); 4] {
    let recording = state == "recording";
    [
        ("start", recording),
        ("stop", !recording),
        ("lock", !recording),
        ("download", state != "stopped"),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_state_shows_its_buttons() {
        let shown = |state| {
            controls(state)
                .iter()
                .filter(|(_, hidden)| !hidden)
                .map(|(id, _)| *id)
                .collect::<Vec<_>>()
        };
        assert_eq!(shown("idle"), ["start"]);
        assert_eq!(shown("recording"), ["stop", "lock"]);
        assert_eq!(shown("stopped"), ["start", "download"]);
    }
}
