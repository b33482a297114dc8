//! The comparison table: every step detector, heading method, orientation source, step-length
//! model and placement (foot mode) the engine offers, each run on every data set where it can run, beside the
//! paper's own claim. `pdr eval --compare` prints it; docs/evaluation.md carries it.
//! May import: `engine`, `io`, `eval`, `settings`.
//!
//! Each row changes one choice from the defaults (one option of one of [`COMPARED`]), so a row
//! measures that method with everything else as shipped. Each data set is scored by the truth it
//! carries ([`Metric::for_logs`]): step counts (the mean absolute count error), a trajectory
//! (the median of the walks' median heading errors), waypoints (the
//! pooled aligned waypoint p75) or loop closure (the mean distance between the end and the start,
//! as a share of the distance walked). A method that cannot run on a set (every sample refused
//! for a field it needs: a gyroscope, an OS orientation; or no step found in any log, as foot mode
//! on a phone) says so instead of a figure. The hybrid heading needs a second, foot-mounted sensor,
//! which no shared data set has: it is measured on the simulator (`examples/hybrid_sim.rs`).

use crate::engine::foot::placement::Placement;
use crate::engine::{replay, InputError};
use crate::eval::{score, summarise, LogResult};
use crate::io::import::Log;
use crate::settings::{choice, Settings};
use serde::Serialize;

/// The choices compared, in the table's order: their keys in [`crate::settings::CHOICES`].
pub const COMPARED: &[&str] = &[
    "detector.kind",
    "heading.method",
    "orientation.kind",
    "step_length.kind",
    "placement",
];

/// What a data set's figure measures: the truth it carries decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Mean absolute step-count error, %.
    StepMaePct,
    /// Median over the walks of each walk's median per-step heading error against a trajectory
    /// truth, after its one offset, degrees ([`crate::eval::trajectory`]).
    HeadingErrorDeg,
    /// Pooled aligned waypoint error, 75th percentile, m.
    WaypointP75M,
    /// Mean loop-closure error, % of the distance walked.
    LoopClosurePct,
}

impl Metric {
    /// The metric of a data set: step counts when its logs have them, else waypoints, else loop
    /// closure; `None` for logs without truth.
    pub fn for_logs(logs: &[Log]) -> Option<Metric> {
        if logs.iter().any(|l| l.truth.steps.is_some()) {
            Some(Metric::StepMaePct)
        } else if logs.iter().any(|l| !l.truth.trajectory.is_empty()) {
            Some(Metric::HeadingErrorDeg)
        } else if logs.iter().any(|l| !l.truth.waypoints.is_empty()) {
            Some(Metric::WaypointP75M)
        } else if logs.iter().any(|l| l.truth.loop_closure) {
            Some(Metric::LoopClosurePct)
        } else {
            None
        }
    }

    /// The column heading's unit.
    pub fn label(self) -> &'static str {
        match self {
            Metric::StepMaePct => "step MAE %",
            Metric::HeadingErrorDeg => "heading error °",
            Metric::WaypointP75M => "waypoint p75 m",
            Metric::LoopClosurePct => "loop closure % of distance",
        }
    }

    /// The figure over a set's results; `None` when no result carries it.
    fn of(self, results: &[LogResult]) -> Option<f64> {
        match self {
            Metric::StepMaePct => summarise(results).step_mae_pct,
            Metric::HeadingErrorDeg => summarise(results)
                .trajectory_by_group
                .get("all")
                .and_then(|g| g.heading_error_deg),
            Metric::WaypointP75M => summarise(results).waypoint_p75_m,
            Metric::LoopClosurePct => {
                let v: Vec<f64> = results
                    .iter()
                    .filter_map(|r| {
                        let lc = r.loop_closure_m?;
                        (r.distance_m > 0.0).then(|| 100.0 * lc / r.distance_m)
                    })
                    .collect();
                (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
            }
        }
    }
}

/// A data set: a name and its logs.
pub struct DataSet {
    /// Its name (the folder's).
    pub name: String,
    /// Its logs.
    pub logs: Vec<Log>,
}

/// One cell: a method on a data set.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Cell {
    /// The figure, over the logs where the method ran.
    Figure {
        /// The value, in the set's metric.
        value: f64,
        /// Logs it ran on.
        logs: usize,
        /// Logs of the set it could not run on.
        skipped: usize,
        /// Logs on which foot mode ran (recognised, or chosen): the row's body method did not.
        foot: usize,
        /// Logs without a gyroscope on which the pitch detector was chosen and the PLL counted.
        pll: usize,
    },
    /// It ran nowhere in the set; why (the first refusal).
    CannotRun {
        /// The reason.
        why: String,
    },
    /// The set has no truth for its metric.
    NoTruth,
}

/// One row: one option of one choice.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The setting's key (`detector.kind`).
    pub key: &'static str,
    /// The option's value (`pll`).
    pub value: &'static str,
    /// The option's words (`PLL (Basso 2016)`).
    pub title: &'static str,
    /// Whether this option is the default.
    pub default: bool,
    /// One cell per data set, in order.
    pub cells: Vec<Cell>,
}

/// The table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    /// The data sets' names and metrics, in column order.
    pub sets: Vec<(String, Option<Metric>)>,
    /// The rows.
    pub rows: Vec<Row>,
}

/// Runs every option of every [`COMPARED`] choice on every set. `progress` is told each row as
/// it starts.
pub fn compare(sets: &[DataSet], mut progress: impl FnMut(&str, &str)) -> Table {
    let defaults = Settings::new()
        .config()
        .expect("the defaults are a valid configuration");
    let metrics: Vec<Option<Metric>> = sets.iter().map(|s| Metric::for_logs(&s.logs)).collect();
    let mut rows = Vec::new();
    for key in COMPARED {
        let Some(c) = choice(key) else { continue };
        for &(value, title) in c.options {
            progress(key, value);
            let cfg = match Settings::new().with(key, value).config() {
                Ok(cfg) => cfg,
                Err(e) => {
                    let why = e.to_string();
                    let cells = sets
                        .iter()
                        .map(|_| Cell::CannotRun { why: why.clone() })
                        .collect();
                    rows.push(row(key, value, title, false, cells));
                    continue;
                }
            };
            let cells = sets
                .iter()
                .zip(&metrics)
                .map(|(set, m)| cell(set, *m, &cfg))
                .collect();
            rows.push(row(key, value, title, cfg == defaults, cells));
        }
    }
    Table {
        sets: sets.iter().map(|s| s.name.clone()).zip(metrics).collect(),
        rows,
    }
}

fn row(
    key: &'static str,
    value: &'static str,
    title: &'static str,
    default: bool,
    cells: Vec<Cell>,
) -> Row {
    Row {
        key,
        value,
        title,
        default,
        cells,
    }
}

fn cell(set: &DataSet, metric: Option<Metric>, cfg: &crate::engine::PipelineConfig) -> Cell {
    let Some(metric) = metric else {
        return Cell::NoTruth;
    };
    let mut ran = Vec::new();
    let mut why = None;
    for log in &set.logs {
        match replay(log.dated(cfg), &log.records) {
            Ok(run) if run.pipeline.diagnostics().samples > 0 => ran.push(score(log, &run)),
            Ok(run) => {
                why.get_or_insert_with(|| match run.errors.first() {
                    Some((_, InputError::MissingField { field, .. })) => {
                        format!("the logs have no `{field}`")
                    }
                    Some((_, e)) => e.to_string(),
                    None => "no IMU sample".to_string(),
                });
            }
            Err(e) => {
                why.get_or_insert_with(|| e.to_string());
            }
        }
    }
    if !ran.is_empty() && ran.iter().all(|r| r.steps == 0) {
        return Cell::CannotRun {
            why: "no step found in any log".into(),
        };
    }
    match metric.of(&ran) {
        Some(value) => Cell::Figure {
            value,
            logs: ran.len(),
            skipped: set.logs.len() - ran.len(),
            foot: ran
                .iter()
                .filter(|r| r.placement == Placement::Foot)
                .count(),
            pll: ran.iter().filter(|r| r.detector_fallback).count(),
        },
        None => Cell::CannotRun {
            why: why.unwrap_or_else(|| match ran.iter().all(|r| r.distance_m == 0.0) {
                true => "no heading, so no track".into(),
                false => "no figure".into(),
            }),
        },
    }
}

/// The table as Markdown: a row per option, a column per data set, the paper's claim last.
pub fn markdown(t: &Table) -> String {
    let mut s = String::from("| method |");
    for (name, m) in &t.sets {
        s += &format!(" {name} ({}) |", m.map_or("no truth", Metric::label));
    }
    s += " the paper's claim |\n|---|";
    s += &"---:|".repeat(t.sets.len());
    s += "---|\n";
    for r in &t.rows {
        let star = if r.default { " **(default)**" } else { "" };
        s += &format!("| `{}={}` {}{star} |", r.key, r.value, r.title);
        for c in &r.cells {
            s += &match c {
                Cell::Figure {
                    value,
                    logs,
                    skipped,
                    foot,
                    pll,
                } => {
                    let mut v = format!(" {value:.2}");
                    if *skipped > 0 {
                        v += &format!(" ({logs} of {} logs)", logs + skipped);
                    }
                    if *foot > 0 && r.key != "placement" {
                        v += if foot == logs {
                            " (foot mode ran)"
                        } else {
                            " (foot mode ran on some)"
                        };
                    }
                    if *pll > 0 {
                        v += if pll == logs {
                            " (the PLL ran: no gyroscope)"
                        } else {
                            " (the PLL ran on some: no gyroscope)"
                        };
                    }
                    v + " |"
                }
                Cell::CannotRun { why } => format!(" cannot run: {} |", why.replace('|', "/")),
                Cell::NoTruth => " – |".to_string(),
            };
        }
        s += &format!(" {} |\n", claim(r.key, r.value));
    }
    s
}

/// The paper's own claim for a method, as it states it, where it makes one.
pub fn claim(key: &str, value: &str) -> &'static str {
    CLAIMS
        .iter()
        .find(|c| c.0 == key && c.1 == value)
        .map_or("–", |c| c.2)
}

/// The papers' claims, by setting and option, as each paper states it (section, table, the data
/// it was measured on). None of them reports a waypoint percentile or a loop closure as such.
const CLAIMS: &[(&str, &str, &str)] = &[
    (
        "detector.kind",
        "pll",
        "no count figure (Basso 2016 §IV, 2021 §4: \"extremely accurate\" step frequency)",
    ),
    (
        "detector.kind",
        "peak",
        "peaks of the acceleration norm, pocket, 1 walker: 0.4 % undetected / 5 % false on a \
         level rectangle, 63 % / 12 % with speed changes (Munoz Diaz 2015 Table 1)",
    ),
    (
        "detector.kind",
        "zero_crossing",
        "1.26 % count error, waist, 14 walkers × 5 repetitions, 48–299 m (Ibarra 2015 Table \
         5.18; one step short on every trial)",
    ),
    (
        "detector.kind",
        "pitch",
        "0 % undetected and 0 % false on a level rectangle, with speed changes, and four floors \
         up and down, front pocket, 1 walker (Munoz Diaz 2015 Table 1)",
    ),
    (
        "heading.method",
        "tip_to_tail2016",
        "within 5–6° of an Xsens MTi-G over ~1 500 steps (Basso 2016 Fig. 10); the position \
         figures of its Table I are not in the text",
    ),
    (
        "heading.method",
        "closed_form2021",
        "no figure (Basso 2021 Figs. 9, 11–13: plots of an urban walk without truth)",
    ),
    (
        "heading.method",
        "pca",
        "no figure (Basso 2016 §I, §III argue against it)",
    ),
    (
        "orientation.kind",
        "madgwick",
        "no figure (Basso 2021 §2.2.1)",
    ),
    (
        "orientation.kind",
        "kf_nfa",
        "yaw error 16.53 (% MSE) against 29.95 for a fixed-R Kalman filter; roll 8.39, pitch \
         7.80 (Ibarra 2015 Table 5.1; a hand-rotated IMU, not a walk)",
    ),
    (
        "step_length.kind",
        "frequency",
        "no error figure (Basso 2016 Fig. 4: the line holds for 1.5–2.2 Hz walking); \
         personalised, 1 walker: 0.19–9.63 % of the length (Munoz Diaz 2015 Table 2)",
    ),
    (
        "step_length.kind",
        "weinberg",
        "lower back, athletic track: 0.67 % at 400 m, 1.4–3.5 % at the other checkpoints \
         (Strozzi 2017 Table 1)",
    ),
    (
        "step_length.kind",
        "fuzzy",
        "5.12 % distance error, waist, 14 walkers (Ibarra 2015 Table 5.19)",
    ),
    (
        "step_length.kind",
        "pitch",
        "personalised, 1 walker, front pocket: 0.18 % of the length at a constant pace, 3.24 % \
         with speed changes, 1.15 % slow with stops (Munoz Diaz 2015 Table 2)",
    ),
    (
        "placement",
        "foot",
        "3.23 % of the distance at 400 m outdoors, 2.5 % at 105 m indoors (Strozzi 2017 Tables \
         1–2, foot ZUPT)",
    ),
];
