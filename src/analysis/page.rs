//! Upload mode's page in words and pieces: the progress and status sentences, the banners about
//! what was read, and the result card's structure as view trees (`render` in `www/util.js`
//! builds them), so that native tests read what the page shows.

use super::text::fixed;
use crate::view::{thousands, El};

/// A file size for people: megabytes with one decimal past 1 MB, else kilobytes rounded up.
pub fn bytes_text(bytes: f64) -> String {
    if bytes > 1e6 {
        format!("{} MB", fixed(bytes / 1e6, 1))
    } else {
        format!("{} kB", (bytes / 1e3).ceil())
    }
}

/// `n` and the noun, plural unless `n` is 1 ("1 file", "3 files").
fn count(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// Share of the progress bar the reading of the files takes; the engine runs take the rest.
const READ_SHARE: f64 = 0.35;
/// Share of the progress bar the engine runs take.
const ENGINE_SHARE: f64 = 0.65;

/// The status as the files are being opened.
pub fn reading_text(files: usize) -> String {
    format!("reading {}…", count(files, "file"))
}

/// The status while `done` of `total` bytes are parsed, and the bar's fraction.
pub fn read_progress(done: f64, total: f64) -> (String, f64) {
    let text = format!("parsed {} of {}", bytes_text(done), bytes_text(total));
    (text, READ_SHARE * done / total.max(1.0))
}

/// The status while log `index` of `logs` (named `source`, `samples` long) goes through the
/// engine, `done` of `total` of its work finished, and the bar's fraction.
pub fn engine_progress(
    source: &str,
    samples: usize,
    (done, total): (f64, f64),
    index: usize,
    logs: usize,
) -> (String, f64) {
    let through = (samples as f64 * done / total.max(1.0)).round().max(0.0) as u64;
    let text = format!(
        "{source}: {} of {} samples through the engine",
        thousands(through),
        thousands(samples as u64)
    );
    let whole = (index as f64 + done / total.max(1.0)) / (logs.max(1) as f64);
    (text, READ_SHARE + ENGINE_SHARE * whole)
}

/// The status once done: `logs` read from `bytes` (none: not said) in `seconds`, `refused`
/// files refused.
pub fn loaded_text(logs: usize, bytes: f64, seconds: f64, refused: usize) -> String {
    let mut s = count(logs, "recording") + " loaded";
    if bytes > 0.0 {
        s += &format!(" from {}", bytes_text(bytes));
    }
    s += &format!(" in {} s", fixed(seconds, 1));
    if refused > 0 {
        s += &format!(", {} refused", count(refused, "file"));
    }
    s
}

/// The banner when the user stops a load.
pub const CANCELLED: &str =
    "Cancelled: nothing more will be read or run. Choose the files again, or Re-run, to start over.";

/// What reading the files found, as the worker hands it to the page: each log read, each file
/// refused, each saved recipe left out, and the banners they make ([`banners`]).
#[derive(Debug, Default, serde::Serialize)]
pub struct Parsed {
    /// The logs read.
    pub logs: Vec<ParsedLog>,
    /// The files refused.
    pub errors: Vec<ParsedError>,
    /// Why saved recipes were left out.
    pub recipe_errors: Vec<String>,
    /// The banners the page shows, `(kind, text)`, once [`banners`] made them.
    pub banners: Vec<(&'static str, String)>,
}

/// One log read.
#[derive(Debug, Default, serde::Serialize)]
pub struct ParsedLog {
    /// Its place among the logs read (the analyses name it).
    pub index: usize,
    /// Its name (the file, or the folder).
    pub source: String,
    /// Its format's name.
    pub format: &'static str,
    /// Its motion samples.
    pub samples: usize,
    /// From its first to its last record, s.
    pub duration_s: f64,
    /// Lines skipped as unreadable.
    pub warnings: usize,
    /// The recipe that read it, if one did.
    pub recipe: Option<String>,
    /// What the recipe's checks said.
    pub checks: Vec<String>,
    /// What it is, for people.
    pub hint: String,
}

/// A file refused: where and why, and the same in words.
#[derive(Debug, Default, serde::Serialize)]
pub struct ParsedError {
    /// The file.
    pub file: String,
    /// The line (1-based; 0: the file as a whole).
    pub line: u64,
    /// The column, when known.
    pub column: Option<usize>,
    /// The field, when known.
    pub field: Option<String>,
    /// Why.
    pub message: String,
    /// The refusal in words.
    pub text: String,
}

/// The banners after reading, in order, `(kind, text)` with kind `error` or `warn`.
pub fn banners(p: &Parsed) -> Vec<(&'static str, String)> {
    let mut out: Vec<(&str, String)> = p.errors.iter().map(|e| ("error", e.text.clone())).collect();
    if p.logs.is_empty() && p.errors.is_empty() {
        let none =
            "No recording recognised in these files: describe them below, or choose other files.";
        out.push(("warn", none.into()));
    }
    for e in &p.recipe_errors {
        out.push(("warn", format!("A saved recipe was left out: {e}")));
    }
    for log in &p.logs {
        let recipe = log.recipe.as_deref().unwrap_or("");
        for c in &log.checks {
            out.push((
                "warn",
                format!("{}, read with the recipe \"{recipe}\": {c}", log.source),
            ));
        }
    }
    out
}

/// The export buttons under a result, `(data-export, label)`.
const EXPORTS: [(&str, &str); 5] = [
    ("gpx", "GPX"),
    ("geojson", "GeoJSON"),
    ("csv", "Steps CSV"),
    ("pdrlog", "pdr-log"),
    ("png", "PNG of the plots"),
];

/// The card of log `index` (named `source`, `hint` about it): its maps' box (filled as the runs
/// arrive, [`map_box`]), the selected step's line, one canvas per plot `(kind, title)`, the
/// stride ellipse and the exports.
pub fn result_card(index: usize, source: &str, hint: &str, plots: &[(&str, &str)]) -> El {
    let canvases = plots.iter().map(|(kind, title)| {
        El::new("canvas")
            .attr("class", format!("plot plot-{kind}"))
            .attr("data-kind", *kind)
            .attr("role", "img")
            .attr("aria-label", *title)
    });
    let ellipse = El::new("canvas").class("ellipse").attr("role", "img").attr(
        "aria-label",
        "Horizontal acceleration over the selected stride, with its heading",
    );
    let zoom = "Wheel or pinch to zoom the time axis, drag to pan, double-click to reset; click to pick a step.";
    let buttons = EXPORTS.iter().map(|(what, label)| {
        El::new("button")
            .attr("type", "button")
            .class("small")
            .attr("data-export", *what)
            .text(*label)
    });
    El::new("article")
        .class("log-result")
        .attr("data-index", index.to_string())
        .child(El::new("h3").text(source))
        .child(El::new("p").class("hint").text(hint))
        .child(El::new("div").class("maps"))
        .child(
            El::new("div")
                .class("stepinfo")
                .text("Hover or tap a step on the track, or click a plot, to see its values."),
        )
        .child(
            El::new("div")
                .class("plots")
                .children(canvases)
                .child(El::new("p").class("hint").text(zoom))
                .child(ellipse),
        )
        .child(El::new("div").class("controls exports").children(buttons))
}

/// The box of one run's map (`tag` `a` or `b`): the configuration's name (shown once there are
/// two), the map's canvas, and its figures ([`figures`], an empty list until they come).
pub fn map_box(tag: &str) -> El {
    El::new("div")
        .class("mapbox")
        .attr("data-tag", tag)
        .child(El::new("h4").class("config-label"))
        .child(
            El::new("canvas")
                .class("map")
                .attr("role", "img")
                .attr("aria-label", "Track in metres, east right, north up"),
        )
        .child(El::new("dl"))
}

/// The heading of run `tag`'s map: the configuration it ran with (`label`), shown only when
/// there are `two` maps.
pub fn config_label(tag: &str, label: &str, two: bool) -> El {
    let h = El::new("h4").class("config-label");
    let h = if two { h } else { h.attr("hidden", "") };
    h.text(format!("{}: {label}", tag.to_uppercase()))
}

/// The choices of a row's profile: the built-in step length (value `''`), then each saved
/// profile by name, sorted.
pub fn profile_options(names: &[String]) -> Vec<El> {
    let mut names: Vec<&String> = names.iter().collect();
    crate::engine::sort::sort(&mut names);
    let builtin = El::new("option")
        .attr("value", "")
        .text("built-in step length");
    let profiles = names.into_iter().map(|n| {
        El::new("option")
            .attr("value", n.as_str())
            .text(format!("profile: {n}"))
    });
    std::iter::once(builtin).chain(profiles).collect()
}

/// The figures under a map, `(label, text)` rows, as a definition list.
pub fn figures(rows: &[(String, String)]) -> El {
    let mut dl = El::new("dl").class("summary");
    for (k, v) in rows {
        dl = dl
            .child(El::new("dt").text(k.clone()))
            .child(El::new("dd").text(v.clone()));
    }
    dl
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_counts_and_progress_read_as_before() {
        assert_eq!(bytes_text(1_234.0), "2 kB");
        assert_eq!(bytes_text(2_450_000.0), "2.5 MB");
        assert_eq!(reading_text(1), "reading 1 file…");
        assert_eq!(reading_text(3), "reading 3 files…");
        let (t, f) = read_progress(500_000.0, 2_000_000.0);
        assert_eq!(t, "parsed 500 kB of 2.0 MB");
        assert!((f - 0.0875).abs() < 1e-12);
        let (t, f) = engine_progress("walk.csv", 12_000, (1.0, 2.0), 1, 2);
        assert_eq!(t, "walk.csv: 6,000 of 12,000 samples through the engine");
        assert!((f - (0.35 + 0.65 * 0.75)).abs() < 1e-12);
        // Nothing to read yet: no division by zero.
        assert_eq!(read_progress(0.0, 0.0).1, 0.0);
        assert_eq!(engine_progress("", 0, (0.0, 0.0), 0, 0).1, 0.35);
    }

    #[test]
    fn the_final_status_names_what_was_done() {
        assert_eq!(
            loaded_text(2, 3_100_000.0, 1.26, 1),
            "2 recordings loaded from 3.1 MB in 1.3 s, 1 file refused"
        );
        assert_eq!(loaded_text(1, 0.0, 0.04, 0), "1 recording loaded in 0.0 s");
        assert_eq!(
            loaded_text(0, 900.0, 2.0, 3),
            "0 recordings loaded from 1 kB in 2.0 s, 3 files refused"
        );
    }

    #[test]
    fn banners_come_in_order() {
        let none = banners(&Parsed::default());
        assert_eq!(none.len(), 1);
        assert!(none[0]
            .1
            .starts_with("No recording recognised in these files"));
        let p = Parsed {
            logs: vec![ParsedLog {
                source: "a/b".into(),
                recipe: Some("mine".into()),
                checks: vec!["the clock goes back".into()],
                ..Default::default()
            }],
            errors: vec![ParsedError {
                text: "x.csv: bad".into(),
                ..Default::default()
            }],
            recipe_errors: vec!["old: unreadable".into()],
            ..Default::default()
        };
        assert_eq!(
            banners(&p),
            vec![
                ("error", "x.csv: bad".to_string()),
                (
                    "warn",
                    "A saved recipe was left out: old: unreadable".to_string()
                ),
                (
                    "warn",
                    "a/b, read with the recipe \"mine\": the clock goes back".to_string()
                ),
            ]
        );
    }

    #[test]
    fn the_card_holds_the_plots_the_exports_and_the_words() {
        let c = result_card(4, "walk.csv", "60 s", &[("accel", "Acceleration")]);
        assert_eq!(c.get("data-index"), Some("4"));
        let all = c.descendants();
        let plot = all
            .iter()
            .find(|e| e.get("data-kind") == Some("accel"))
            .unwrap();
        assert_eq!(plot.get("class"), Some("plot plot-accel"));
        assert_eq!(plot.get("aria-label"), Some("Acceleration"));
        let exports: Vec<_> = all.iter().filter_map(|e| e.get("data-export")).collect();
        assert_eq!(exports, ["gpx", "geojson", "csv", "pdrlog", "png"]);
        assert!(c
            .text_content()
            .starts_with("walk.csv60 sHover or tap a step"));
        let b = map_box("b");
        assert_eq!(b.get("data-tag"), Some("b"));
        assert_eq!(b.descendants().len(), 4);
        let h = config_label("b", "peak detector", true);
        assert_eq!(h.text_content(), "B: peak detector");
        assert_eq!(h.get("hidden"), None);
        assert_eq!(config_label("a", "x", false).get("hidden"), Some(""));
        let o = profile_options(&["walk".into(), "run".into()]);
        let shown: Vec<_> = o
            .iter()
            .map(|e| (e.get("value").unwrap(), e.text_content()))
            .collect();
        assert_eq!(
            shown,
            [
                ("", "built-in step length".to_string()),
                ("run", "profile: run".to_string()),
                ("walk", "profile: walk".to_string())
            ]
        );
        let f = figures(&[("Steps".into(), "12".into())]);
        assert_eq!(
            serde_json::to_string(&f).unwrap(),
            r#"["dl",{"class":"summary"},[["dt",{},["Steps"]],["dd",{},["12"]]]]"#
        );
    }
}
