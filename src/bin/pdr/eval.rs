//! `pdr eval`: runs the engine on every log under the paths, scores it against the logs' truth
//! and prints a table or one JSON object.
//! May import: the `pdr` library; nothing of the other subcommands.

use pdr::settings::Settings;
use std::path::PathBuf;

pub fn eval(
    paths: &[PathBuf],
    json: bool,
    settings: &Settings,
    show_config: bool,
    recipe: Option<&pdr::io::import::recipe::Recipe>,
) -> Result<(), String> {
    use pdr::eval::{evaluate, summarise, LogResult, Report};
    use pdr::io::import::{import_with, DirSet};
    let cfg = settings.config().map_err(|e| e.to_string())?;
    if show_config {
        out!(
            "{}",
            serde_json::to_string_pretty(&cfg).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    let mut logs = Vec::new();
    for path in paths {
        let label = path.display().to_string();
        let mut set = match DirSet::new(path) {
            Ok(s) => s,
            Err(e) => {
                logs.push(LogResult::failed(&label, "", e.to_string()));
                continue;
            }
        };
        let found = import_with(&mut set, recipe.map(std::slice::from_ref).unwrap_or(&[]));
        if found.is_empty() {
            let why = match recipe {
                Some(r) => format!(
                    "no recognisable log, and recipe {:?} matches no folder: {}",
                    r.name,
                    pdr::io::import::recipe::why_not(&set, r)
                ),
                None => "no recognisable log".into(),
            };
            logs.push(LogResult::failed(&label, "", why));
        }
        for r in found {
            logs.push(match r {
                Ok(log) => {
                    for c in &log.checks {
                        eprintln!("pdr: {}: check: {c}", log.source);
                    }
                    evaluate(&log, &cfg)
                }
                Err(e) => LogResult::failed(&e.file, "", e.to_string()),
            });
        }
    }
    let summary = summarise(&logs);
    let report = Report { logs, summary };
    if json {
        out!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    print_report(&report);
    Ok(())
}

/// The text report: the table of logs, each log's lines for its extra truths, the per-group
/// figures and the totals.
fn print_report(report: &pdr::eval::Report) {
    print_table(&report.logs);
    for l in &report.logs {
        print_foot(l);
    }
    for l in report.logs.iter().filter(|l| l.fused_error_m.is_some()) {
        print_fusion(l);
    }
    for l in &report.logs {
        print_floors(l);
    }
    for l in &report.logs {
        print_steps_and_turns(l);
    }
    print_summary(&report.summary);
}

/// `v` with `prec` decimals, or `-` without a value.
fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or("-".to_string(), |x| format!("{x:.prec$}"))
}

/// The last part of a log's path (its file or folder name).
fn base_name(path: &str) -> &str {
    path.rsplit('/').next().unwrap_or(path)
}

/// A path cut to its last 43 characters after an ellipsis when longer than 44.
fn shorten(path: &str) -> String {
    if path.chars().count() <= 44 {
        return path.to_string();
    }
    format!(
        "…{}",
        path.chars()
            .rev()
            .take(43)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect::<String>()
    )
}

/// The table: one row per log (its format, samples, duration, steps against the truth and the
/// waypoint and loop-closure errors), or the log's error.
fn print_table(logs: &[pdr::eval::LogResult]) {
    out!(
        "{:<44} {:<15} {:>8} {:>7} {:>6} {:>6} {:>7} {:>4} {:>7} {:>7} {:>7}",
        "log",
        "format",
        "samples",
        "dur s",
        "steps",
        "truth",
        "err %",
        "wps",
        "p75 m",
        "final m",
        "loop m"
    );
    for l in logs {
        let path = shorten(&l.path);
        if let Some(e) = &l.error {
            out!("{path:<44} {:<15} error: {e}", l.format);
            continue;
        }
        out!(
            "{path:<44} {:<15} {:>8} {:>7.1} {:>6} {:>6} {:>7} {:>4} {:>7} {:>7} {:>7}",
            l.format,
            l.samples,
            l.duration_s,
            l.steps,
            l.truth_steps.map_or("-".into(), |t| t.to_string()),
            opt(l.step_error_pct, 2),
            l.waypoints,
            opt(l.waypoint_error_m.map(|w| w.p75), 1),
            opt(l.waypoint_error_m.map(|w| w.r#final), 1),
            opt(l.loop_closure_m, 1),
        );
    }
}

/// A foot-mounted log's strides, distance and loop closure.
fn print_foot(l: &pdr::eval::LogResult) {
    let Some(strides) = l.strides else { return };
    out!(
        "foot mode {:<34} {} strides ({} steps), {:.2} m walked, loop closure {} m ({} % of the distance)",
        base_name(&l.path),
        strides,
        l.steps,
        l.distance_m,
        opt(l.loop_closure_m, 3),
        opt(
            l.loop_closure_m
                .filter(|_| l.distance_m > 0.0)
                .map(|c| 100.0 * c / l.distance_m),
            2
        )
    );
}

/// A log's GNSS, fused and smoothed errors, with the receiver's on time and the declination's
/// note.
fn print_fusion(l: &pdr::eval::LogResult) {
    let on = l
        .fusion
        .and_then(|f| Some((f.gnss_on_s?, f.gnss_span_s?)))
        .map_or(String::new(), |(on, span)| {
            format!(", receiver on {on:.0} s of {span:.0} s")
        });
    let note = l
        .declination_note
        .as_ref()
        .map_or(String::new(), |n| format!("; {n}"));
    out!(
        "fusion {:<37} GNSS p75 {} m, fused p75 {} m, smoothed p75 {} m; yardstick {} m, causal {} m{on}{note}",
        base_name(&l.path),
        opt(l.gnss_error_m.map(|e| e.p75), 2),
        opt(l.fused_error_m.map(|e| e.p75), 2),
        opt(l.smoothed_error_m.map(|e| e.p75), 2),
        opt(l.yardstick_p75_m, 2),
        opt(l.causal_yardstick_p75_m, 2)
    );
}

/// A log's floor landmarks on the right relative floor and its height error.
fn print_floors(l: &pdr::eval::LogResult) {
    let Some(f) = &l.floors else { return };
    let barometer = match l.pressure_samples {
        0 => "no barometer".to_string(),
        n => format!("barometer {n} readings"),
    };
    let height = f.height_error_m.map_or(String::new(), |h| {
        format!(", height error p75 {:.2} m (max {:.2} m)", h.p75, h.max)
    });
    out!(
        "floors {:<37} {}/{} landmarks on the right relative floor ({:.1} %){height}; {barometer}",
        base_name(&l.path),
        f.right,
        f.landmarks,
        100.0 * f.share
    );
}

/// A log's steps inside the truth's window, its trajectory's errors and its turns.
fn print_steps_and_turns(l: &pdr::eval::LogResult) {
    let name = base_name(&l.path);
    if let (Some(n), Some(t)) = (l.steps_in_window, l.truth_steps) {
        out!(
            "window {name:<37} {n} steps found inside the truth's window of {t} ({} %)",
            opt(l.step_error_pct, 2)
        );
    }
    if let Some(t) = &l.trajectory {
        out!(
            "trajectory {name:<33} heading error median {}° (p75 {}°, {} steps), distance {:.1} m of {:.1} m (ratio {}), position p75 {} m{}",
            opt(t.heading_error_deg, 1),
            opt(t.heading_error_p75_deg, 1),
            t.headings_scored,
            t.track_distance_m,
            t.truth_distance_m,
            opt(t.distance_ratio, 2),
            opt(t.position_p75_m, 2),
            if t.has_track { "" } else { "; no track" }
        );
    }
    if let Some(t) = &l.turns {
        out!(
            "turns {name:<38} {} of {} turns scored, median error {}°",
            t.scored.len(),
            t.turns,
            opt(t.median_error_deg, 1)
        );
    }
}

/// The figures per group of logs (trajectory, steps), the turns' and floors' and the totals.
fn print_summary(s: &pdr::eval::Summary) {
    if !s.trajectory_by_group.is_empty() {
        out!();
        for (g, v) in &s.trajectory_by_group {
            out!(
                "{g:<16} {:>3} logs  heading error {:>5}°  distance ratio {:>5}  position p75 {:>5} m  without a track {}",
                v.logs,
                opt(v.heading_error_deg, 1),
                opt(v.distance_ratio, 2),
                opt(v.position_p75_m, 2),
                v.without_track
            );
        }
    }
    if !s.carry_share_by_group.is_empty() {
        let shares: Vec<String> = s
            .carry_share_by_group
            .iter()
            .map(|(g, v)| format!("{g} {:.1} %", 100.0 * v))
            .collect();
        out!("carrying mode right on: {} of the steps", shares.join(", "));
    }
    if let Some(e) = s.turn_error_median_deg {
        out!("turns: median error {e:.1}° over {} turns", s.turns_scored);
    }
    if !s.step_mae_by_group.is_empty() {
        out!();
        for (g, v) in &s.step_mae_by_group {
            out!(
                "{g:<16} {:>3} logs  step MAE {:>5.2} %  (debounced truth {} %)",
                v.logs,
                v.mae_pct,
                opt(v.mae_debounced_pct, 2)
            );
        }
    }
    out!(
        "\n{} logs, {} failed; step MAE {} % (debounced truth {} %); waypoint p75 {} m ({} % of the path walked)",
        s.logs,
        s.failed,
        opt(s.step_mae_pct, 2),
        opt(s.step_mae_debounced_pct, 2),
        opt(s.waypoint_p75_m, 2),
        opt(s.waypoint_p75_pct, 1)
    );
    print_fusion_summary(s);
    if s.floor_logs > 0 {
        out!(
            "floors: {} % of {} landmarks on the right relative floor, over {} logs{}",
            opt(s.floor_share.map(|x| 100.0 * x), 1),
            s.floor_landmarks,
            s.floor_logs,
            s.height_p75_m
                .map_or(String::new(), |h| format!("; height error p75 {h:.2} m"))
        );
    }
}

/// The medians over the logs with fixes of GNSS alone, the fused and smoothed tracks and the
/// yardsticks, and how many logs come near their yardstick.
fn print_fusion_summary(s: &pdr::eval::Summary) {
    if s.gnss_p75_m.is_none() {
        return;
    }
    out!(
        "fusion: median p75 GNSS {} m, fused {} m, smoothed {} m; yardstick {} m, causal {} m",
        opt(s.gnss_p75_m, 2),
        opt(s.fused_p75_m, 2),
        opt(s.smoothed_p75_m, 2),
        opt(s.yardstick_p75_m, 2),
        opt(s.causal_yardstick_p75_m, 2)
    );
    let [sn, sl] = s.smoothed_near_yardstick;
    let [fn_, fl] = s.fused_near_causal_yardstick;
    out!(
        "fusion: smoothed within 1 m of the yardstick on {sn} of {sl} logs, fused within 1 m of the causal one on {fn_} of {fl}; fused worse than 1.1 × GNSS alone on {}",
        s.fused_worse_than_gnss
    );
}

/// `pdr eval --compare`: each path is a data set; every method on each, as one table.
pub fn compare(paths: &[PathBuf], json: bool) -> Result<(), String> {
    use pdr::compare::{compare, markdown, DataSet};
    use pdr::io::import::{import_all, DirSet};
    let mut sets = Vec::new();
    for path in paths {
        let mut dir = DirSet::new(path).map_err(|e| e.to_string())?;
        let mut logs = Vec::new();
        for r in import_all(&mut dir) {
            match r {
                Ok(log) => logs.push(log),
                Err(e) => eprintln!("pdr: left out: {e}"),
            }
        }
        if logs.is_empty() {
            return Err(format!("{}: no recognisable log", path.display()));
        }
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        eprintln!("pdr: {name}: {} logs", logs.len());
        sets.push(DataSet { name, logs });
    }
    let table = compare(&sets, |key, value| eprintln!("pdr: {key}={value}"));
    if json {
        out!(
            "{}",
            serde_json::to_string(&table).map_err(|e| e.to_string())?
        );
    } else {
        out!("{}", markdown(&table));
    }
    Ok(())
}

/// `pdr eval --energy`: every log in best performance and in energy saving, per group.
pub fn energy(
    paths: &[PathBuf],
    json: bool,
    settings: &Settings,
    recipe: Option<&pdr::io::import::recipe::Recipe>,
) -> Result<(), String> {
    use pdr::eval::energy::{energy_report, markdown};
    use pdr::io::import::{import_with, DirSet};
    let cfg = settings.config().map_err(|e| e.to_string())?;
    let mut logs = Vec::new();
    for path in paths {
        let mut set = DirSet::new(path).map_err(|e| format!("{}: {e}", path.display()))?;
        for r in import_with(&mut set, recipe.map(std::slice::from_ref).unwrap_or(&[])) {
            match r {
                Ok(log) => logs.push(log),
                Err(e) => eprintln!("pdr: left out: {e}"),
            }
        }
    }
    if logs.is_empty() {
        return Err("no recognisable log".into());
    }
    let report = energy_report(&logs, &cfg);
    if json {
        out!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        out!("{}", markdown(&report));
    }
    Ok(())
}
