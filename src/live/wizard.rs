//! The step-length calibration wizard as the page shows it: its words (the paces, a walk's
//! guard title and progress, its messages, the GNSS check's state, an imported profile's name)
//! and the fits box (a chart per band with its warnings, an outlier's with the button that
//! drops it, and the notes). `www/wizard.js` keeps the events, the walks through live mode,
//! the storage and the drawing.
//! May import: `engine`, `view`.

use crate::engine::calibration::{fit_band, Band, FitWarning, ProfileFile, Wizard, WizardWalk};
use crate::view::El;
use std::collections::BTreeMap;

/// The paces the wizard asks for, as in the page's rows (`data-pace`), and their names.
pub const PACES: [(&str, &str); 5] = [
    ("slow", "slow walk"),
    ("normal", "normal walk"),
    ("fast", "fast walk"),
    ("jog", "jog"),
    ("run", "run"),
];

/// The bands, as the page names them (`cal-chart-walking`).
pub const BANDS: [(Band, &str); 2] = [(Band::Walking, "walking"), (Band::Running, "running")];

/// The pace's name ("normal walk"), or an error naming an unknown pace.
pub fn pace_name(pace: &str) -> Result<&'static str, String> {
    PACES
        .iter()
        .find(|(p, _)| *p == pace)
        .map(|(_, name)| *name)
        .ok_or_else(|| format!("unknown pace `{pace}`"))
}

/// The title of a calibration walk's screen: a walk of `target_m` metres, measured by GNSS (the
/// wizard stops it) or typed (the walker stops it); `None` without a distance (not a positive
/// number of metres: the walk may not start).
pub fn walk_title(pace: &str, target_m: f64, gnss: bool) -> Result<Option<String>, String> {
    let name = pace_name(pace)?;
    if !(target_m > 0.0 && target_m.is_finite()) {
        return Ok(None);
    }
    Ok(Some(if gnss {
        format!("Calibration, {name}: walk; the wizard stops you at {target_m} m")
    } else {
        format!("Calibration, {name}: walk the {target_m} m, then unlock and tap Stop")
    }))
}

/// A walk's progress in its row: the steps, and with GNSS the path the fixes measured so far,
/// m ("52 steps · 31 of 150 m by GNSS").
pub fn walk_progress(steps: usize, gnss_path_m: Option<f64>, target_m: f64) -> String {
    match gnss_path_m {
        Some(p) => format!("{steps} steps · {} of {target_m} m by GNSS", p.round()),
        None => format!("{steps} steps"),
    }
}

/// Where a calibration walk toward its target stands.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WalkProgress {
    /// Its progress in words ([`walk_progress`]).
    pub text: String,
    /// The walk's distance, m: the path the fixes measured with GNSS, else the typed target.
    pub distance_m: f64,
    /// A GNSS walk has reached its target: the wizard stops it.
    pub done: bool,
}

/// A walk toward `target_m` with `steps` counted and, measured by GNSS, the path of its good
/// fixes so far, m.
pub fn walk_state(steps: usize, gnss_path_m: Option<f64>, target_m: f64) -> WalkProgress {
    WalkProgress {
        text: walk_progress(steps, gnss_path_m, target_m),
        distance_m: gnss_path_m.unwrap_or(target_m),
        done: gnss_path_m.is_some_and(|p| p >= target_m),
    }
}

/// A walk's figures as its row shows them once it is added: its steps, distance, mean
/// frequency (eq. 1) and step length (eq. 2), the point it gives `band_name`'s line, and the
/// sum of its fuzzy lengths when measured.
pub fn walk_text(w: &WizardWalk, band_name: &str) -> String {
    let fuzzy = w
        .fuzzy_sum_m
        .map_or(String::new(), |f| format!(" · fuzzy Σ = {f:.1} m at k = 1"));
    format!(
        "N = {} steps over {:.1} m · f̄ = {:.2} Hz (eq. 1) · SL̄ = D/N = {:.3} m (eq. 2) → one point of your \
         {band_name} line{fuzzy}",
        w.steps, w.distance_m, w.f_mean_hz, w.sl_mean_m
    )
}

/// The wizard's message `key` (the key of its item in the page's list): `distance` (no
/// distance typed), `busy` (a live recording runs), `saved` and `import` (the profile `name`).
pub fn message(key: &str, name: &str) -> Result<String, String> {
    Ok(match key {
        "distance" => "Type the distance in metres first.".into(),
        "busy" => "A live recording is running: stop it first.".into(),
        "saved" => format!("Saved “{name}” and selected it: live mode now uses it."),
        "import" => format!("Imported “{name}”."),
        other => return Err(format!("no wizard message `{other}`")),
    })
}

/// The pace a walk from a recording is filed under among the wizard's walks (a walking walk;
/// its leg pitch calibrates the pitch step length as the normal walk's does).
pub const RECORDING_PACE: &str = "recording";

/// The one log of a recording the wizard was given (`file_name`, its logs as the import read
/// them), or what is wrong with it, naming the file: not a recording the app reads, or one that
/// holds several logs.
pub fn recording_log(
    file_name: &str,
    mut logs: Vec<Result<crate::io::import::Log, crate::io::ParseError>>,
) -> Result<crate::io::import::Log, String> {
    match logs.len() {
        0 => Err(format!(
            "{file_name}: no recording the app reads (live mode's pdr-log, Sensor Logger, phyphox, …; \
             see Open a recording)"
        )),
        // The import's error names the file, its line and column.
        1 => logs.pop().expect("one log").map_err(|e| e.to_string()),
        n => Err(format!(
            "{file_name} holds {n} recordings: give the one of the walk"
        )),
    }
}

/// A walk from a recording as its line shows it once added: the file and the walk's figures
/// ([`walk_text`]), and the distance the engine measured over it before calibration.
pub fn recording_text(file_name: &str, w: &WizardWalk, engine_distance_m: f64) -> String {
    format!(
        "{file_name}: {} · the engine measured {engine_distance_m:.1} m before calibration",
        walk_text(w, "walking")
    )
}

/// What the GNSS check says, and whether GNSS may measure a walk: `state` is `missing` (no
/// geolocation), `waiting`, `fix` (with its `accuracy_m`, good at `limit_m` or better),
/// `refused` (permission denied) or `failed`.
pub fn gnss_state(state: &str, accuracy_m: f64, limit_m: f64) -> Result<(String, bool), String> {
    Ok(match state {
        "missing" => ("this browser has no geolocation".into(), false),
        "waiting" => ("waiting for a fix…".into(), false),
        "refused" => ("location refused".into(), false),
        "failed" => ("no fix".into(), false),
        "fix" if accuracy_m.is_finite() => {
            let good = accuracy_m <= limit_m;
            let verdict = if good {
                "good enough"
            } else {
                "not good enough (go into the open)"
            };
            (format!("±{} m now: {verdict}", accuracy_m.round()), good)
        }
        "fix" => {
            return Err(format!(
                "a fix's accuracy is not a number of metres ({accuracy_m})"
            ))
        }
        other => return Err(format!("no GNSS state `{other}`")),
    })
}

/// What the normal walk gave the leg-pitch step length (Munoz Diaz 2015 §5.1, S = a·Δθ + b
/// with the universal slope a): the offset b, or why it gave none.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PitchCalibration {
    /// Whether the walk gave an offset.
    pub ok: bool,
    /// The offset b, m per stride.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset_m: Option<f64>,
    /// The universal slope a used, m/°.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slope_m_per_deg: Option<f64>,
    /// The walk's steps.
    pub steps: usize,
    /// Those with a leg pitch.
    pub with_pitch: usize,
    /// Why there is no offset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<String>,
    /// The outcome for people.
    pub text: String,
}

/// The one-walk calibration of the pitch step length: a walk of `distance_m` whose steps had
/// the leg pitch amplitudes `amplitudes_deg` (NaN or 0 without one). Refused when most steps
/// had no leg pitch (the phone not in a trouser pocket, or no gyroscope), or when the engine
/// finds no offset (too few steps, no distance).
pub fn pitch_calibration(distance_m: f64, amplitudes_deg: &[f64]) -> PitchCalibration {
    let steps = amplitudes_deg.len();
    let with_pitch = amplitudes_deg
        .iter()
        .filter(|d| d.is_finite() && **d > 0.0)
        .count();
    let refused = |why: String| PitchCalibration {
        ok: false,
        offset_m: None,
        slope_m_per_deg: None,
        steps,
        with_pitch,
        text: format!("Leg-pitch step length not calibrated: {why}."),
        why: Some(why),
    };
    if 2 * with_pitch < steps || with_pitch == 0 {
        return refused(format!(
            "only {with_pitch} of the walk's {steps} steps had a leg pitch: the pitch step length needs the phone \
             in a front trouser pocket and a gyroscope (the browser's rotation rate)"
        ));
    }
    let a = PITCH_SLOPE_M_PER_DEG;
    match crate::engine::calibration::pitch_offset(distance_m, amplitudes_deg, a) {
        Err(e) => refused(e.to_string()),
        Ok(b) => PitchCalibration {
            ok: true,
            offset_m: Some(b),
            slope_m_per_deg: Some(a),
            steps,
            with_pitch,
            why: None,
            text: format!(
                "Leg-pitch step length (Munoz Diaz 2015 §5.1): with the universal slope a = {a} m/°, your offset is \
                 b = {b:.3} m per stride ({with_pitch} steps with a leg pitch). It is saved with the profile."
            ),
        },
    }
}

/// The pitch step length's universal slope, m/°.
pub use crate::engine::pitch_step_length::UNIVERSAL_SLOPE_M_PER_DEG as PITCH_SLOPE_M_PER_DEG;

/// The name a profile the wizard made is saved under: the name field's, else "me".
pub fn profile_name(field: &str) -> String {
    match field.trim() {
        "" => "me".into(),
        name => name.into(),
    }
}

/// A profile file imported: the name it is saved under ([`import_name`]) and what the page says
/// of it, or the error of a file that is not a profile, naming the file.
pub fn import_profile(
    file_name: &str,
    text: &str,
    existing: &BTreeMap<String, String>,
) -> Result<(String, String), String> {
    let p = ProfileFile::from_json(text).map_err(|e| format!("{file_name}: {e}"))?;
    let name = import_name(&p.name, file_name, text, existing);
    let said = message("import", &name)?;
    Ok((name, said))
}

/// The profile choices: the built-in lines, then the saved profiles by name, `selected` (a
/// saved name, or `""` for the built-in) selected.
pub fn profile_options<'a>(names: impl IntoIterator<Item = &'a str>, selected: &str) -> Vec<El> {
    let mut names: Vec<&str> = names.into_iter().collect();
    names.sort_unstable();
    std::iter::once(("", "built-in (no calibration)"))
        .chain(names.into_iter().map(|n| (n, n)))
        .map(|(value, label)| {
            let o = El::new("option").attr("value", value);
            let o = if value == selected {
                o.attr("selected", "")
            } else {
                o
            };
            o.text(label)
        })
        .collect()
}

/// The profile in use as the page names it: the selected one's name, or "built-in".
pub fn profile_in_use(selected: &str) -> &str {
    if selected.is_empty() {
        "built-in"
    } else {
        selected
    }
}

/// The name an imported profile is saved under: its own (`profile_name`), else the file's name
/// without `.json`; when another profile (`existing`: name → JSON) has that name with other
/// text, the first free "name (2)", "name (3)", …. The same text under the same name is the
/// same profile, imported again.
pub fn import_name(
    profile_name: &str,
    file_name: &str,
    text: &str,
    existing: &BTreeMap<String, String>,
) -> String {
    let base = if profile_name.is_empty() {
        file_name.strip_suffix(".json").unwrap_or(file_name)
    } else {
        profile_name
    };
    let taken = |n: &str| existing.get(n).is_some_and(|t| t != text);
    let mut name = base.to_string();
    let mut k = 2;
    while taken(&name) {
        name = format!("{base} ({k})");
        k += 1;
    }
    name
}

/// A band's fit warning as the wizard lists it: its kind, its explanation and, for an outlier,
/// the index of its walk among all the wizard's walks (the one "Drop walk N" removes).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Warning {
    /// `too_few_points`, `narrow_span`, `negative_slope` or `outlier`.
    pub kind: &'static str,
    /// For people ([`FitWarning::message`]).
    pub message: String,
    /// The outlier's walk, 0-based among all walks.
    pub walk: Option<usize>,
}

/// The warnings of `band`'s fit.
pub fn warnings(wizard: &Wizard, band: Band) -> Vec<Warning> {
    // Indices of this band's walks among all walks, to name an outlier's walk.
    let idx: Vec<usize> = (0..wizard.walks.len())
        .filter(|&i| wizard.walks[i].band == band)
        .collect();
    fit_band(&wizard.points(band))
        .warnings
        .iter()
        .map(|w| Warning {
            kind: match w {
                FitWarning::TooFewPoints { .. } => "too_few_points",
                FitWarning::NarrowSpan { .. } => "narrow_span",
                FitWarning::NegativeSlope { .. } => "negative_slope",
                FitWarning::Outlier { .. } => "outlier",
            },
            message: w.message(),
            walk: match w {
                FitWarning::Outlier { index, .. } => idx.get(*index).copied(),
                _ => None,
            },
        })
        .collect()
}

/// The fits box: for each band with walks, its chart (a canvas the page draws on,
/// `cal-chart-<band>`) and its warnings, an outlier's with a button (`data-walk`: the walk's
/// index) that drops its walk.
pub fn fits_view(wizard: &Wizard) -> Vec<El> {
    BANDS
        .iter()
        .filter(|(b, _)| !wizard.points(*b).is_empty())
        .map(|&(b, name)| {
            let canvas = El::new("canvas")
                .attr("id", format!("cal-chart-{name}"))
                .attr("role", "img")
                .attr(
                    "aria-label",
                    format!("Calibration points, line and residuals, {name}"),
                );
            let items: Vec<El> = warnings(wizard, b).into_iter().map(warning_item).collect();
            let fit = El::new("div").class("fit").child(canvas);
            if items.is_empty() {
                fit
            } else {
                fit.child(El::new("ul").children(items))
            }
        })
        .collect()
}

fn warning_item(w: Warning) -> El {
    let li = El::new("li").attr("data-kind", w.kind).text(w.message);
    match w.walk {
        None => li,
        Some(walk) => li.text(" ").child(
            El::new("button")
                .attr("type", "button")
                .class("small")
                .attr("data-walk", walk.to_string())
                .text(format!("Drop walk {}", walk + 1)),
        ),
    }
}

/// The wizard's notes (the profile's, ending with the fitted fuzzy scale when the walks
/// measured one), an item each.
pub fn notes_view(wizard: &Wizard) -> Vec<El> {
    let (_, notes) = wizard.profile(&Default::default());
    notes.into_iter().map(|n| El::new("li").text(n)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::calibration::CalibrationWalk;

    #[test]
    fn the_words_of_a_walk() {
        assert_eq!(
            walk_title("normal", 40.0, false).unwrap().unwrap(),
            "Calibration, normal walk: walk the 40 m, then unlock and tap Stop"
        );
        assert_eq!(
            walk_title("jog", 150.5, true).unwrap().unwrap(),
            "Calibration, jog: walk; the wizard stops you at 150.5 m"
        );
        for no_distance in [0.0, -3.0, f64::NAN, f64::INFINITY] {
            assert_eq!(walk_title("slow", no_distance, false), Ok(None));
        }
        assert!(walk_title("crawl", 40.0, false).is_err());
        assert_eq!(
            walk_progress(52, Some(30.5), 150.0),
            "52 steps · 31 of 150 m by GNSS"
        );
        assert_eq!(walk_progress(52, None, 40.0), "52 steps");
        let typed = walk_state(52, None, 40.0);
        assert_eq!(
            (typed.distance_m, typed.done),
            (40.0, false),
            "the walker stops it"
        );
        let short = walk_state(52, Some(149.9), 150.0);
        assert_eq!((short.distance_m, short.done), (149.9, false));
        let there = walk_state(60, Some(150.2), 150.0);
        assert_eq!(
            (there.distance_m, there.done),
            (150.2, true),
            "the wizard stops it"
        );
        assert_eq!(there.text, "60 steps · 150 of 150 m by GNSS");
        assert_eq!(
            message("saved", "me").unwrap(),
            "Saved “me” and selected it: live mode now uses it."
        );
        assert_eq!(message("import", "me (2)").unwrap(), "Imported “me (2)”.");
        assert!(message("hello", "").is_err());
    }

    #[test]
    fn the_pitch_calibration_needs_a_leg_pitch_in_most_steps() {
        let none = pitch_calibration(40.0, &[f64::NAN; 60]);
        assert!(!none.ok);
        assert_eq!(none.with_pitch, 0);
        assert!(none
            .text
            .starts_with("Leg-pitch step length not calibrated: only 0 of the walk's 60 steps"));
        assert!(none.text.contains("front trouser pocket") && none.text.ends_with(")."));
        // Strides of 30–44.5°, each seen by two steps, over the distance S = a·Δθ + 0.17 gives.
        let strides: Vec<f64> = (0..30).map(|k| 30.0 + 0.5 * k as f64).collect();
        let distance: f64 = strides
            .iter()
            .map(|d| PITCH_SLOPE_M_PER_DEG * d + 0.17)
            .sum();
        let steps: Vec<f64> = strides.iter().flat_map(|d| [*d, *d]).collect();
        let p = pitch_calibration(distance, &steps);
        assert!(p.ok && (p.offset_m.unwrap() - 0.17).abs() < 1e-9, "{p:?}");
        assert!(p
            .text
            .contains("b = 0.170 m per stride (60 steps with a leg pitch)"));
        let json = serde_json::to_value(&p).unwrap();
        assert!(json.get("why").is_none() && json["slope_m_per_deg"] == PITCH_SLOPE_M_PER_DEG);
    }

    #[test]
    fn a_recording_is_one_log_and_its_line_names_the_file() {
        use crate::io::import::{import_all, MemSet};
        let read = |name: &str, text: &str| {
            let mut set = MemSet::new(vec![(name.to_string(), text.as_bytes().to_vec())]);
            recording_log(name, import_all(&mut set))
        };
        let none = read("notes.txt", "shopping list\n").unwrap_err();
        assert!(
            none.starts_with("notes.txt: no recording the app reads"),
            "{none}"
        );
        let log = read("walk.pdrlog", "# pdr-log 1\nimu,0,0,9.8,0,0,0,0,,,,,,,\n").unwrap();
        assert_eq!(log.records.len(), 1);
        let mut w = Wizard::default();
        walk(&mut w, RECORDING_PACE, 40.0, 1.8, 60);
        let text = recording_text("walk.pdrlog", &w.walks[0], 37.26);
        assert!(
            text.starts_with("walk.pdrlog: N = 60 steps over 40.0 m"),
            "{text}"
        );
        assert!(text.ends_with("the engine measured 37.3 m before calibration"));
    }

    #[test]
    fn the_gnss_check_says_when_a_fix_is_good_enough() {
        assert_eq!(
            gnss_state("fix", 7.6, 10.0).unwrap(),
            ("±8 m now: good enough".into(), true)
        );
        let bad = gnss_state("fix", 25.0, 10.0).unwrap();
        assert_eq!(
            bad,
            (
                "±25 m now: not good enough (go into the open)".into(),
                false
            )
        );
        assert_eq!(
            gnss_state("waiting", f64::NAN, 10.0).unwrap().0,
            "waiting for a fix…"
        );
        assert_eq!(
            gnss_state("refused", f64::NAN, 10.0).unwrap().0,
            "location refused"
        );
        assert!(gnss_state("fix", f64::NAN, 10.0).is_err());
    }

    #[test]
    fn an_imported_profile_takes_a_free_name() {
        let mut existing = BTreeMap::new();
        assert_eq!(import_name("", "walker.json", "{}", &existing), "walker");
        existing.insert("me".to_string(), "{a}".to_string());
        existing.insert("me (2)".to_string(), "{b}".to_string());
        assert_eq!(
            import_name("me", "x.json", "{a}", &existing),
            "me",
            "the same profile again"
        );
        assert_eq!(import_name("me", "x.json", "{c}", &existing), "me (3)");
        existing.insert("x".to_string(), "{a}".to_string());
        assert_eq!(import_name("", "x.json", "{c}", &existing), "x (2)");
        let bad = import_profile("notes.json", "{\"hello\": 1}", &existing).unwrap_err();
        assert!(bad.starts_with("notes.json: "), "{bad}");
        assert_eq!(profile_name("  "), "me");
        assert_eq!(profile_name(" tester "), "tester");
    }

    #[test]
    fn the_profile_choices_start_with_the_built_in_lines() {
        let options = profile_options(["me", "bob"], "me");
        let labels: Vec<String> = options.iter().map(|o| o.text_content()).collect();
        assert_eq!(labels, ["built-in (no calibration)", "bob", "me"]);
        assert_eq!(options[2].get("selected"), Some(""));
        assert_eq!(options[0].get("value"), Some(""));
        assert_eq!(profile_options([], "")[0].get("selected"), Some(""));
        assert_eq!(profile_in_use(""), "built-in");
        assert_eq!(profile_in_use("me"), "me");
    }

    fn walk(w: &mut Wizard, pace: &str, metres: f64, hz: f64, steps: usize) {
        let walk = CalibrationWalk {
            distance_m: metres,
            step_freqs_hz: vec![hz; steps],
            fuzzy_lengths_m: Vec::new(),
        };
        w.add(Band::Walking, pace, &walk).unwrap();
    }

    #[test]
    fn the_fits_box_offers_to_drop_an_outlier() {
        let mut w = Wizard::default();
        assert!(fits_view(&w).is_empty(), "no walks, no chart");
        walk(&mut w, "slow", 40.0, 1.5, 52);
        let one = fits_view(&w);
        assert_eq!(one.len(), 1);
        let canvas = &one[0].descendants()[1];
        assert_eq!(canvas.get("id"), Some("cal-chart-walking"));
        assert_eq!(
            canvas.get("aria-label"),
            Some("Calibration points, line and residuals, walking")
        );
        assert_eq!(
            one[0].descendants()[3].get("data-kind"),
            Some("too_few_points")
        );
        // SL = 0.3 f + 0.2 for four paces, and a fifth walk whose distance was wrong.
        for (pace, hz) in [
            ("normal", 1.8),
            ("fast", 2.1),
            ("slow", 1.65),
            ("fast", 1.95),
        ] {
            walk(&mut w, pace, 40.0, hz, (40.0 / (0.3 * hz + 0.2)) as usize);
        }
        let outlier = fits_view(&w)[0]
            .descendants()
            .into_iter()
            .find(|e| e.get("data-walk").is_some())
            .cloned()
            .expect("a button that drops the first walk");
        assert_eq!(outlier.get("data-walk"), Some("0"));
        assert_eq!(outlier.text_content(), "Drop walk 1");
        assert_eq!(outlier.get("class"), Some("small"));
        let first = walk_text(&w.walks[0], "walking");
        assert!(first.starts_with(
            "N = 52 steps over 40.0 m · f̄ = 1.50 Hz (eq. 1) · SL̄ = D/N = 0.769 m (eq. 2)"
        ));
        assert!(first.ends_with("→ one point of your walking line"));
        assert!(warnings(&w, Band::Running)
            .iter()
            .any(|x| x.kind == "too_few_points"));
        assert!(!notes_view(&w).is_empty());
    }
}
