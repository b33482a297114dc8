//! `pdr eval --calibrate-loo`: what calibration buys on real walks, leave one walk out. For each
//! walker, each walking walk in turn is the one calibration walk (its true distance the truth's
//! smoothed path length, as `pdr eval` measures it), the wizard's fit makes a profile of it
//! (`pdr calibrate`'s), and the walker's other walking walks are run with that profile and
//! scored; their distance ratios (track length over the truth's) are set beside the
//! uncalibrated ones, per carrying mode and overall.
//!
//! Logs are grouped by walker from their folder's name, `<Walker>_<…>_<Mode>` (TyrEx's
//! `Guillaume_Nexus5_Dist_FrontPocket`); the mode is the log's group. Running walks (a mode
//! containing `Running`) and logs without a trajectory truth are left out.
//! May import: the `pdr` library; nothing of the other subcommands.

use pdr::engine::calibration::{Band, Wizard};
use pdr::engine::recorded_walk::recorded_walk;
use pdr::engine::PipelineConfig;
use pdr::eval::{evaluate, percentile};
use pdr::io::import::recipe::Recipe;
use pdr::io::import::{import_with, DirSet, Log};
use pdr::settings::Settings;
use std::path::PathBuf;

/// One walking walk: its log, walker, mode, uncalibrated ratio and true distance, m.
struct Walk {
    log: Log,
    walker: String,
    mode: String,
    ratio: f64,
    truth_m: f64,
}

/// One walk run with the profile another walk of its walker made.
#[derive(serde::Serialize)]
struct Applied {
    /// The walk the profile was fitted on.
    fitted: String,
    /// The walk it was applied to, and its walker.
    applied: String,
    walker: String,
    /// Their modes.
    fitted_mode: String,
    applied_mode: String,
    /// The applied walk's distance ratio, uncalibrated and calibrated.
    before: f64,
    after: f64,
}

/// A group's figures (a mode, a walker, or all): its walks and their median distance ratio
/// uncalibrated; its applied pairs and their median ratio calibrated, with its quartiles; and
/// the median over the pairs whose two walks share a mode, when there are such pairs.
#[derive(serde::Serialize)]
struct Row {
    group: String,
    walks: usize,
    before: f64,
    pairs: usize,
    after: f64,
    after_p25: f64,
    after_p75: f64,
    same_mode_pairs: usize,
    after_same_mode: Option<f64>,
}

/// Runs the leave-one-walk-out comparison on the logs under `paths` with `settings`, and prints
/// its table (Markdown) or, with `json`, `{rows, applied}` (every pair's ratios).
pub fn calibrate_loo(
    paths: &[PathBuf],
    json: bool,
    settings: &Settings,
    recipe: Option<&Recipe>,
) -> Result<(), String> {
    let cfg = settings.config().map_err(|e| e.to_string())?;
    let walks = load(paths, &cfg, recipe)?;
    let mut applied = Vec::new();
    for fit in &walks {
        let profiled = profile_settings(fit, &cfg, settings)?;
        for w in walks
            .iter()
            .filter(|w| w.walker == fit.walker && w.log.source != fit.log.source)
        {
            let r = evaluate(&w.log, &profiled);
            let Some(after) = r.trajectory.and_then(|t| t.distance_ratio) else {
                continue;
            };
            applied.push(Applied {
                fitted: fit.log.source.clone(),
                applied: w.log.source.clone(),
                walker: w.walker.clone(),
                fitted_mode: fit.mode.clone(),
                applied_mode: w.mode.clone(),
                before: w.ratio,
                after,
            });
        }
    }
    let rows = rows(&walks, &applied);
    if json {
        let doc = serde_json::json!({ "rows": rows, "applied": applied });
        out!(
            "{}",
            serde_json::to_string(&doc).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    out!(
        "| group | walks | uncalibrated | pairs | calibrated on another walk (p25–p75) | \
         same-mode pairs | calibrated on a walk of the same mode |"
    );
    out!("|---|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        out!(
            "| {} | {} | {:.3} | {} | {:.3} ({:.3}–{:.3}) | {} | {} |",
            r.group,
            r.walks,
            r.before,
            r.pairs,
            r.after,
            r.after_p25,
            r.after_p75,
            r.same_mode_pairs,
            r.after_same_mode
                .map_or("-".to_string(), |x| format!("{x:.3}"))
        );
    }
    Ok(())
}

/// The settings with the profile the wizard fits to `fit` alone (quick mode: the population
/// slope through its point), as a configuration.
fn profile_settings(
    fit: &Walk,
    cfg: &PipelineConfig,
    settings: &Settings,
) -> Result<PipelineConfig, String> {
    let name = &fit.log.source;
    let rw = recorded_walk(fit.log.dated(cfg), &fit.log.records, fit.truth_m)
        .map_err(|e| format!("{name}: {e}"))?;
    let mut wizard = Wizard::default();
    wizard
        .add(Band::Walking, "recording", &rw.walk)
        .map_err(|e| format!("{name}: {e}"))?;
    let pitch = pdr::live::wizard::pitch_calibration(fit.truth_m, &rw.pitch_amplitudes_deg);
    let json = wizard
        .profile_file("loo", pitch.offset_m)
        .to_json()
        .map_err(|e| e.to_string())?;
    Settings {
        profile: Some(json),
        ..settings.clone()
    }
    .config()
    .map_err(|e| e.to_string())
}

/// The walking walks under `paths` with a trajectory truth, each with its uncalibrated figures.
fn load(
    paths: &[PathBuf],
    cfg: &PipelineConfig,
    recipe: Option<&Recipe>,
) -> Result<Vec<Walk>, String> {
    let mut walks = Vec::new();
    for path in paths {
        let mut set = DirSet::new(path).map_err(|e| format!("{}: {e}", path.display()))?;
        for log in import_with(&mut set, recipe.map(std::slice::from_ref).unwrap_or(&[])) {
            let log = log.map_err(|e| e.to_string())?;
            let folder = log.source.rsplit('/').next().unwrap_or(&log.source);
            let walker = folder.split('_').next().unwrap_or(folder).to_string();
            let mode = log.group.clone().unwrap_or_default();
            if mode.contains("Running") {
                continue;
            }
            let r = evaluate(&log, cfg);
            let Some(t) = r.trajectory.filter(|t| t.distance_ratio.is_some()) else {
                continue;
            };
            walks.push(Walk {
                walker,
                mode,
                ratio: t.distance_ratio.unwrap_or(f64::NAN),
                truth_m: t.truth_distance_m,
                log,
            });
        }
    }
    if walks.len() < 2 {
        return Err(
            "--calibrate-loo needs at least two walking walks with a trajectory truth".into(),
        );
    }
    Ok(walks)
}

/// The medians per mode of the applied walks, then per walker, then over all.
fn rows(walks: &[Walk], applied: &[Applied]) -> Vec<Row> {
    let median = |v: &[f64], q: f64| {
        if v.is_empty() {
            f64::NAN
        } else {
            percentile(v, q)
        }
    };
    let row = |group: &str, keep: &dyn Fn(&str, &str) -> bool| {
        let before: Vec<f64> = walks
            .iter()
            .filter(|w| keep(&w.mode, &w.walker))
            .map(|w| w.ratio)
            .collect();
        let pairs: Vec<&Applied> = applied
            .iter()
            .filter(|a| keep(&a.applied_mode, &a.walker))
            .collect();
        let after: Vec<f64> = pairs.iter().map(|a| a.after).collect();
        let same: Vec<f64> = pairs
            .iter()
            .filter(|a| a.fitted_mode == a.applied_mode)
            .map(|a| a.after)
            .collect();
        Row {
            group: group.to_string(),
            walks: before.len(),
            before: median(&before, 50.0),
            pairs: pairs.len(),
            after: median(&after, 50.0),
            after_p25: median(&after, 25.0),
            after_p75: median(&after, 75.0),
            same_mode_pairs: same.len(),
            after_same_mode: (!same.is_empty()).then(|| median(&same, 50.0)),
        }
    };
    let mut modes: Vec<&str> = walks.iter().map(|w| w.mode.as_str()).collect();
    let mut walkers: Vec<&str> = walks.iter().map(|w| w.walker.as_str()).collect();
    for v in [&mut modes, &mut walkers] {
        v.sort_unstable();
        v.dedup();
    }
    let mut out: Vec<Row> = modes.iter().map(|m| row(m, &|x, _| x == *m)).collect();
    out.extend(walkers.iter().map(|p| row(p, &|_, x| x == *p)));
    out.push(row("all", &|_, _| true));
    out
}
