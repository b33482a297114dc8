//! What live mode tells the user when the browser, the sensors or the storage get in the way:
//! the page's messages by key, the offer to recover an unfinished recording with its sentence
//! about a damaged one, and what the page says about its stored lists that cannot be read.
//! May import: nothing.

/// The message shown for `key` (the page adds a detail after some, e.g. the error's words);
/// `guardTitle` is the pocket guard's title while a recording runs.
pub fn message(key: &str) -> Option<&'static str> {
    Some(match key {
        "guardTitle" => "Recording — screen locked for the pocket",
        "insecure" => "Motion and location need a secure page. Open it as https:// (./dev run serves one on port 8443 with a self-signed certificate; accept the warning once) or as http://localhost.",
        "motionDenied" => "Motion access was refused, so steps cannot be counted. On an iPhone, tap Start again and choose Allow; if no prompt appears, close the tab and open the page again (Safari › Settings › Motion & Orientation Access must be on). On Android, allow “Motion sensors” in the site settings (the icon left of the address).",
        "noSensor" => "No motion data has arrived. This device or browser may have no accelerometer, or may withhold it (desktop browsers usually do). Use a phone with Chrome, Samsung Internet, Firefox or Safari.",
        "noCompass" => "No compass heading: the track’s shape is right, but it is turned by an unknown angle. Allow motion and orientation access, or use a browser that reports an absolute orientation.",
        "locationDenied" => "Location was refused: the track uses the motion sensors alone, without GNSS corrections. To use GNSS, allow location for this site and tap Start again.",
        "locationUnavailable" => "No GNSS fix yet (indoors, or the receiver is starting). The track goes on without; fixes are used when they come.",
        "noGeolocation" => "This browser has no geolocation: the track uses the motion sensors alone.",
        "noWakeLock" => "This browser cannot keep the screen on. Set a long screen timeout: when the screen goes off, the browser stops the sensors and the walk has a gap.",
        "engine" => "Some sensor events were refused: ",
        "cannotStart" => "Live mode could not start: ",
        "unreadable" => "An unfinished recording is stored on this device but cannot be read: ",
        "storage" => "The recording cannot be saved on this device (storage full, or refused in private mode). The walk goes on and what was not saved is kept in memory: tap Stop, then “Download recording”, to keep the whole walk; closing the page now would lose it. ",
        _ => return None,
    })
}

/// The messages a new start (a recording, a resumed one, a calibration walk) clears once motion
/// access is granted: that it was refused, and those about the previous session's sensors,
/// engine, storage and location.
pub const CLEARED_AT_START: [&str; 8] = [
    "motionDenied",
    "noSensor",
    "noCompass",
    "engine",
    "cannotStart",
    "storage",
    "locationDenied",
    "locationUnavailable",
];

/// The sentence the recovery offer adds about a damaged recording (lines skipped, pieces
/// missing, the first problem's `notes`), or "" for a whole one.
pub fn damage(skipped_lines: u64, missing_pieces: u64, notes: &[String]) -> String {
    if skipped_lines == 0 && missing_pieces == 0 && notes.is_empty() {
        return String::new();
    }
    let mut parts = Vec::new();
    if skipped_lines > 0 {
        let was = if skipped_lines > 1 {
            "lines were"
        } else {
            "line was"
        };
        parts.push(format!("{skipped_lines} damaged {was} skipped"));
    }
    if missing_pieces > 0 {
        let are = if missing_pieces > 1 {
            "pieces are"
        } else {
            "piece is"
        };
        parts.push(format!(
            "{missing_pieces} {are} missing (a gap in the walk)"
        ));
    }
    let what = if parts.is_empty() {
        "it was repaired".to_string()
    } else {
        parts.join(", ")
    };
    format!(
        " Part of it is damaged: {what}; everything else is kept. First problem: {}.",
        notes.first().map_or("–", String::as_str)
    )
}

/// The recovery offer: a recording started at `started` (a date in the user's words) with
/// `samples` and, when known, `steps` was not stopped; `damage` is [`damage`]'s sentence.
pub fn recovery_offer(started: &str, samples: usize, steps: Option<usize>, damage: &str) -> String {
    let steps = steps.map_or(String::new(), |n| format!(", {n} steps"));
    format!(
        "An unfinished recording from {started} ({samples} samples{steps}) was not stopped: the \
         page was closed or reloaded. Resume it, or download it.{damage}"
    )
}

/// The page's list of `what` (its words: "step-length profiles") cannot be read, and cannot be
/// moved aside either (storage full).
pub fn stored_unreadable(what: &str) -> String {
    format!(
        "The {what} stored on this device cannot be read, and there is no room to keep them \
         aside: nothing is saved over them. Free some storage and reload the page."
    )
}

/// A change to the page's list of `what` is refused: the list cannot be read, nor moved aside.
pub fn not_saved(what: &str) -> String {
    format!("The stored {what} cannot be read and cannot be kept aside: nothing was saved.")
}

/// The page's list of `what` could not be read: its text is kept under the storage keys
/// `kept`. The page adds a download and a delete button after it.
pub fn kept_aside(what: &str, kept: &[String]) -> String {
    format!(
        "The {what} stored on this device could not be read (damaged JSON), so they are not \
         shown. Their text is kept unchanged under “{}” in this browser's storage and nothing \
         is saved over it: download it to repair it by hand. ",
        kept.join("”, “")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damage_is_worded_for_people() {
        assert_eq!(damage(0, 0, &[]), "");
        assert_eq!(
            damage(1, 2, &["line 3: bad".into()]),
            " Part of it is damaged: 1 damaged line was skipped, 2 pieces are missing (a gap in the walk); everything else is kept. First problem: line 3: bad."
        );
        assert!(message("storage").is_some() && message("nothing").is_none());
    }

    #[test]
    fn the_messages_a_start_clears_exist() {
        for key in CLEARED_AT_START {
            assert!(message(key).is_some(), "{key}");
        }
    }

    #[test]
    fn recovery_and_storage_sentences() {
        assert_eq!(
            recovery_offer("28/11/2026, 18:29:01", 120, Some(7), ""),
            "An unfinished recording from 28/11/2026, 18:29:01 (120 samples, 7 steps) was not stopped: the page was closed or reloaded. Resume it, or download it."
        );
        assert_eq!(
            recovery_offer("then", 0, None, " Part of it is damaged."),
            "An unfinished recording from then (0 samples) was not stopped: the page was closed or reloaded. Resume it, or download it. Part of it is damaged."
        );
        assert_eq!(
            stored_unreadable("recipes"),
            "The recipes stored on this device cannot be read, and there is no room to keep them aside: nothing is saved over them. Free some storage and reload the page."
        );
        assert_eq!(
            not_saved("recipes"),
            "The stored recipes cannot be read and cannot be kept aside: nothing was saved."
        );
        assert_eq!(
            kept_aside("step-length profiles", &["a-unreadable-1".into(), "a-unreadable-2".into()]),
            "The step-length profiles stored on this device could not be read (damaged JSON), so they are not shown. Their text is kept unchanged under “a-unreadable-1”, “a-unreadable-2” in this browser's storage and nothing is saved over it: download it to repair it by hand. "
        );
    }
}
