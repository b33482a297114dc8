//! The live readouts in words: what the page writes into each readout (and the pocket guard's),
//! from the session's [`Readouts`].
//! May import: [`super::session`].

use super::session::Readouts;

/// The readouts' texts, each with the id of the page element it goes into (`r-steps`, …, and
/// the pocket guard's `g-steps`, …), and the tooltips (`title`) of those that have one.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ReadoutTexts {
    /// `(element id, text)`, in the page's order.
    pub texts: Vec<(&'static str, String)>,
    /// `(element id, tooltip)`; an empty tooltip clears it.
    pub titles: Vec<(&'static str, String)>,
}

/// A duration as the page shows it: `m:ss`, or `h:mm:ss` from an hour.
pub fn clock(s: f64) -> String {
    let m = (s / 60.0).floor();
    let h = (m / 60.0).floor();
    let ss = (s % 60.0).floor();
    if h > 0.0 {
        format!("{h}:{:02}:{ss:02}", m % 60.0)
    } else {
        format!("{m}:{ss:02}")
    }
}

/// The nearest of the eight compass points to a heading, degrees from north.
pub fn compass_point(deg: f64) -> &'static str {
    const POINTS: [&str; 8] = ["N", "NE", "E", "SE", "S", "SW", "W", "NW"];
    POINTS[((deg.rem_euclid(360.0) / 45.0).round() as usize) % 8]
}

/// `n` and the noun, plural from two: "1 gap", "3 gaps".
fn count(n: impl Into<u64>, one: &str, many: &str) -> String {
    let n = n.into();
    format!("{n} {}", if n > 1 { many } else { one })
}

/// The parts that are given, joined by " · ".
fn joined(parts: &[Option<&str>]) -> String {
    let parts: Vec<&str> = parts
        .iter()
        .flatten()
        .copied()
        .filter(|p| !p.is_empty())
        .collect();
    parts.join(" · ")
}

/// What the fixes readout adds in energy-saving mode: whether the receiver is off now and its
/// share of the time since the first fix, with the times as its tooltip.
fn receiver(r: &Readouts, gnss_mode: &str) -> (String, String) {
    match r.gnss_on_s {
        Some((on, span)) if gnss_mode == "energy_saving" && span > 0.0 => (
            format!(
                "{} · on {} %",
                if r.gnss_wanted { "" } else { " · off" },
                (100.0 * on / span).round()
            ),
            format!(
                "The receiver has been on {} of the {} since the first fix.",
                clock(on),
                clock(span)
            ),
        ),
        _ => (String::new(), String::new()),
    }
}

/// The height above the start with what it comes from ("+3.1 m · leg pitch"), once known.
fn height(r: &Readouts) -> String {
    match r.up_m {
        Some(up) => format!(
            "{}{:.1} m{}",
            if up >= 0.0 { "+" } else { "−" },
            up.abs(),
            r.height_source.map_or(String::new(), |s| format!(" · {s}"))
        ),
        None if r.samples > 0 => "no height yet".into(),
        None => "–".into(),
    }
}

/// The heading with its compass point ("87° E"), and what it is measured from (or how many of
/// a walk's first steps wait for a forward direction).
fn heading(r: &Readouts) -> (Option<String>, String) {
    let heading = r.heading_deg.map(|d| {
        let h = d.rem_euclid(360.0);
        format!("{}° {}", h.round(), compass_point(h))
    });
    let reference = if r.held_steps > 0 {
        format!("{} waiting", count(r.held_steps as u64, "step", "steps"))
    } else if r.absolute_heading {
        "from north".into()
    } else if r.samples > 0 {
        "relative to start".into()
    } else {
        "–".into()
    };
    (heading, reference)
}

/// The fixes received, with the receiver's share in energy-saving mode, and its tooltip.
fn fixes(r: &Readouts, gnss_mode: &str) -> (String, String) {
    let (saving, title) = receiver(r, gnss_mode);
    let text = if r.fixes > 0 {
        format!("{}{saving}", count(r.fixes as u64, "fix", "fixes"))
    } else if gnss_mode == "off" {
        "off".into()
    } else {
        "no fix".into()
    };
    (text, title)
}

/// The readouts in words. `source` names the motion source ("devicemotion events", "Generic
/// Sensor API"); `gnss_mode` is the fusion mode the walk runs (`off`, `energy_saving`, …).
pub fn readout_texts(r: &Readouts, source: &str, gnss_mode: &str) -> ReadoutTexts {
    let started = r.samples > 0;
    let or_dash = |v: Option<String>, before: &str| v.unwrap_or_else(|| before.to_string());
    let dash = if started { None } else { Some("–") };
    let height = height(r);
    let time = clock(r.duration_s);
    let gaps = if r.gaps > 0 {
        format!(" · {}", count(r.gaps, "gap", "gaps"))
    } else {
        String::new()
    };
    let (heading, heading_ref) = heading(r);
    let (fixes, saving_title) = fixes(r, gnss_mode);
    let texts = vec![
        ("r-steps", r.steps.to_string()),
        (
            "r-motion",
            match r.activity {
                Some(a) if !a.is_empty() => joined(&[Some(a), r.carry]),
                _ => "waiting for motion".into(),
            },
        ),
        (
            "r-floor",
            or_dash(r.floor_change.clone(), dash.unwrap_or("start floor")),
        ),
        ("r-height", height),
        ("r-distance", format!("{:.1}", r.distance_m)),
        ("r-time", format!("{time}{gaps}")),
        (
            "r-cadence",
            or_dash(r.cadence_hz.map(|c| format!("{c:.2}")), "–"),
        ),
        (
            "r-spm",
            match r.cadence_hz {
                Some(c) => format!("{} steps/min", (c * 60.0).round()),
                None => "– steps/min".into(),
            },
        ),
        ("r-heading", or_dash(heading, "–")),
        ("r-heading-ref", heading_ref),
        (
            "r-gnss",
            or_dash(r.gnss_accuracy_m.map(|a| format!("±{} m", a.round())), "–"),
        ),
        ("r-fixes", fixes),
        ("r-scale", or_dash(r.scale_text.clone(), "–")),
        (
            "r-correction",
            format!("heading {}", r.correction_text.as_deref().unwrap_or("–")),
        ),
        ("gnss-notice", r.gnss_notice.unwrap_or_default().to_string()),
        (
            "r-rate",
            if r.sample_rate_hz != 0.0 && !r.sample_rate_hz.is_nan() {
                format!("{:.0}", r.sample_rate_hz)
            } else {
                "–".into()
            },
        ),
        (
            "r-source",
            format!(
                "{source}{}",
                r.orientation.map_or(String::new(), |o| format!(" · {o}"))
            ),
        ),
        ("g-steps", r.steps.to_string()),
        ("g-distance", format!("{:.0}", r.distance_m)),
        ("g-time", time),
        (
            "g-note",
            if started {
                joined(&[r.activity, r.floor_change.as_deref()])
            } else {
                "waiting for the sensors…".into()
            },
        ),
    ];
    let held = if r.held_steps > 0 {
        "A walk’s first steps wait off the track until the phone’s swing says which way is forward."
    } else {
        ""
    };
    ReadoutTexts {
        texts,
        titles: vec![("r-heading-ref", held.into()), ("r-fixes", saving_title)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clocks_and_compass_points() {
        assert_eq!(clock(0.0), "0:00");
        assert_eq!(clock(75.9), "1:15");
        assert_eq!(clock(3725.0), "1:02:05");
        assert_eq!(compass_point(0.0), "N");
        assert_eq!(compass_point(359.0), "N");
        assert_eq!(compass_point(-90.0), "W");
        assert_eq!(compass_point(130.0), "SE");
    }
}
