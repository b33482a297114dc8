//! The evaluation bench: a log with ground truth through the engine, scored.
//! May import: `engine`, `io`.
//!
//! Used by `pdr eval`, the tests and (for uploaded logs that carry truth) the page.
//!
//! # Metrics
//! - **Steps**: `step_error_pct` = 100·|steps − truth| / truth.
//! - **Waypoints**, as inertial-odometry papers report an aligned trajectory error: the estimated
//!   position at the first waypoint's time is pinned on the first waypoint; the estimated track
//!   is rotated about that point by the least-squares rotation onto all the waypoints (rotation
//!   only, no scale); then the distance to each later waypoint at its time is the error. The
//!   percentage divides it by the true path length walked so far (the polyline through the
//!   waypoints) and counts only waypoints at least [`MIN_PATH_FOR_PCT_M`] along.
//! - **Loop closure**: the distance between the last and the first position of the track.
//! - **Steps in a window**: where the truth counts only part of the recording
//!   ([`crate::io::import::Truth::step_window`]), the steps found inside it are scored.
//! - **Trajectory** (motion capture): each step's heading, the distance and the position against
//!   the smoothed truth, free of the truth frame's direction ([`trajectory`]).
//! - **Turns**: the track's heading change across each true turn against its angle
//!   ([`turn_angles`]).
//! - **Carrying mode**: where the truth says how the phone was carried, the share of steps
//!   whose carrying mode is that one ([`carry`]).
//! - **Floors**: where the truth's landmarks have floors (GetSensorData `POSI`), the share of
//!   landmarks at which the track's floor relative to the first landmark is the truth's
//!   ([`floors`]); the height error where the truth has heights.
//! - **Fusion yardsticks**: for a log with geodetic landmarks and fixes, how close the true
//!   walk shape gets when only the fixes place it, offline and causally ([`yardstick`]).
//! - Percentiles interpolate linearly between order statistics (the common "linear" definition,
//!   as numpy's default).
//!
//! The estimated position between two steps is interpolated linearly in time; before the first
//! step it is the origin, after the last step the last position.

use crate::engine::pipeline::{position_at, PipelineConfig, StepRecord};
use crate::engine::replay;
use crate::io::import::{Log, Waypoint};
use serde::{Deserialize, Serialize};

pub mod absolute;
pub mod carry;
pub mod ends;
pub mod energy;
pub mod floors;
pub mod trajectory;
pub mod turn_angles;
pub mod turns;
pub mod yardstick;

pub use floors::FloorResult;
pub use trajectory::{TrajectoryGroup, TrajectoryResult};
pub use turn_angles::TurnResult;

/// Waypoints nearer the start than this along the true path are left out of the percentages, m.
pub const MIN_PATH_FOR_PCT_M: f64 = 20.0;

/// Summary of waypoint errors in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MetresSummary {
    /// Mean, m.
    pub mean: f64,
    /// 75th percentile, m.
    pub p75: f64,
    /// Largest, m.
    pub max: f64,
    /// At the last waypoint, m.
    pub r#final: f64,
}

/// Summary of waypoint errors as a percentage of the path walked so far.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PctSummary {
    /// Mean, %.
    pub mean: f64,
    /// 75th percentile, %.
    pub p75: f64,
    /// At the last counted waypoint, %.
    pub r#final: f64,
}

/// Summary of absolute errors in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorSummary {
    /// Mean, m.
    pub mean: f64,
    /// 75th percentile, m.
    pub p75: f64,
    /// Largest, m.
    pub max: f64,
}

impl ErrorSummary {
    fn of(v: &[f64]) -> Option<Self> {
        (!v.is_empty()).then(|| ErrorSummary {
            mean: mean(v),
            p75: percentile(v, 75.0),
            max: v.iter().copied().fold(0.0, f64::max),
        })
    }
}

/// What the fusion filter learnt from a log's fixes, at its last step, and what it did with
/// them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FusionResult {
    /// Step-length scale (true length = scale × PDR length).
    pub scale: f64,
    /// Its standard deviation.
    pub scale_sd: f64,
    /// Heading correction (true heading = PDR heading + declination + this), degrees.
    pub heading_correction_deg: f64,
    /// Its standard deviation, degrees.
    pub heading_correction_sd_deg: f64,
    /// Fixes that updated the filter.
    pub fixes_used: u64,
    /// Fixes the gate refused.
    pub fixes_gated: u64,
    /// Position resets after repeated gating.
    pub resets: u64,
    /// How long the receiver was on from the first fix to the end of the log, s (energy
    /// saving switches it off between windows; best performance keeps it on).
    #[serde(default)]
    pub gnss_on_s: Option<f64>,
    /// That span, from the first fix to the end of the log, s.
    #[serde(default)]
    pub gnss_span_s: Option<f64>,
    /// Baselines between fixes that taught the scale and the heading correction.
    #[serde(default)]
    pub baselines: u64,
    /// The share of the fixes' error new at every fix, as the filter measured it.
    #[serde(default)]
    pub white_share: Option<f64>,
}

/// One log's result. The field names are stable: other tools read them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogResult {
    /// Where the log came from.
    pub path: String,
    /// Its format name.
    pub format: String,
    /// IMU samples read.
    pub samples: u64,
    /// Duration, s.
    pub duration_s: f64,
    /// Steps counted.
    pub steps: u64,
    /// Distance walked, m.
    pub distance_m: f64,
    /// True steps, when known.
    pub truth_steps: Option<u64>,
    /// Steps found inside the truth's window, when the truth counts only part of the log
    /// ([`crate::io::import::Truth::step_window`]); the step error is then theirs.
    #[serde(default)]
    pub steps_in_window: Option<u64>,
    /// Step-count error, %.
    pub step_error_pct: Option<f64>,
    /// True steps without the truth device's contact bounces, when it reports feet
    /// ([`crate::io::import::Truth::steps_debounced`]).
    pub truth_steps_debounced: Option<u64>,
    /// Step-count error against [`LogResult::truth_steps_debounced`], %.
    pub step_error_debounced_pct: Option<f64>,
    /// Number of truth waypoints.
    pub waypoints: u64,
    /// Aligned waypoint errors, m.
    pub waypoint_error_m: Option<MetresSummary>,
    /// Aligned waypoint errors, % of the path so far.
    pub waypoint_error_pct: Option<PctSummary>,
    /// Loop-closure error, m, for walks that end where they started.
    pub loop_closure_m: Option<f64>,
    /// The mode that ran: `body` or `foot` (`auto` when the log was too short to decide).
    pub placement: crate::engine::foot::placement::Placement,
    /// Strides, when foot mode ran (each counts as two steps in `steps`).
    pub strides: Option<u64>,
    /// The log's group within its data set (Oxford: the phone's placement).
    pub group: Option<String>,
    /// Absolute error of the GNSS fixes alone at the geodetic truth's times (fixes interpolated
    /// in time), m.
    pub gnss_error_m: Option<ErrorSummary>,
    /// Absolute error of the fused track at those times, m.
    pub fused_error_m: Option<ErrorSummary>,
    /// Absolute error of the smoothed track at those times, m.
    pub smoothed_error_m: Option<ErrorSummary>,
    /// The offline fusion yardstick's p75, m: the true walk shape placed by the fixes alone
    /// ([`yardstick`]); `null` without landmarks and usable fixes.
    #[serde(default)]
    pub yardstick_p75_m: Option<f64>,
    /// The causal yardstick's p75, m: each landmark placed with the fixes up to its time.
    #[serde(default)]
    pub causal_yardstick_p75_m: Option<f64>,
    /// What the fusion filter learnt and how sure it is, for a log with fixes.
    pub fusion: Option<FusionResult>,
    /// The magnetic declination applied to the headings, degrees (positive east), once a fix
    /// set the origin with fusion on.
    #[serde(default)]
    pub declination_deg: Option<f64>,
    /// Why that declination may be off (no date for the World Magnetic Model, none at all);
    /// `null` when it is the model's for the log's date.
    #[serde(default)]
    pub declination_note: Option<String>,
    /// Lines skipped while reading.
    pub skipped_lines: u64,
    /// Records the engine refused.
    pub refused_records: u64,
    /// Barometer readings the engine took (0: the log has no barometer).
    #[serde(default)]
    pub pressure_samples: u64,
    /// Floors (and heights) against the truth's landmarks, for a log whose landmarks have
    /// floors ([`floors::score_floors`]); `null` otherwise. (Always written: the analysis
    /// crosses to the page as postcard, which cannot skip fields.)
    #[serde(default)]
    pub floors: Option<FloorResult>,
    /// Heading, distance and position against a trajectory truth (motion capture).
    #[serde(default)]
    pub trajectory: Option<TrajectoryResult>,
    /// The heading change across each true turn.
    #[serde(default)]
    pub turns: Option<TurnResult>,
    /// Steps whose carrying mode is the truth's, and steps scored (those inside the truth's
    /// step window when it has one), for a log whose truth says how the phone was carried.
    #[serde(default)]
    pub carry_steps: Option<[u64; 2]>,
    /// The pitch detector was chosen and the log has no gyroscope: the PLL counted the steps.
    pub detector_fallback: bool,
    /// Share of the steps whose leg pitch showed a thigh's swing (a phone in a trouser
    /// pocket, with a gyroscope; Munoz Diaz 2015): they have the pitch's activity, height and
    /// stairs.
    pub thigh_share: f64,
    /// Why the log could not be evaluated.
    pub error: Option<String>,
    /// Every waypoint error, m (for pooling; not serialised).
    #[serde(skip)]
    pub waypoint_errors_m: Vec<f64>,
    /// Every counted waypoint error, % (for pooling; not serialised).
    #[serde(skip)]
    pub waypoint_errors_pct: Vec<f64>,
    /// Every absolute error of GNSS alone, fused and smoothed, m (for pooling; not serialised).
    #[serde(skip)]
    pub absolute_errors_m: [Vec<f64>; 3],
}

impl LogResult {
    /// The row of a log that could not be read or run.
    pub fn failed(path: &str, format: &str, error: String) -> Self {
        LogResult {
            path: path.to_string(),
            format: format.to_string(),
            samples: 0,
            duration_s: 0.0,
            steps: 0,
            distance_m: 0.0,
            truth_steps: None,
            steps_in_window: None,
            step_error_pct: None,
            truth_steps_debounced: None,
            step_error_debounced_pct: None,
            waypoints: 0,
            waypoint_error_m: None,
            waypoint_error_pct: None,
            loop_closure_m: None,
            placement: crate::engine::foot::placement::Placement::Auto,
            strides: None,
            group: None,
            gnss_error_m: None,
            fused_error_m: None,
            smoothed_error_m: None,
            yardstick_p75_m: None,
            causal_yardstick_p75_m: None,
            fusion: None,
            declination_deg: None,
            declination_note: None,
            skipped_lines: 0,
            refused_records: 0,
            pressure_samples: 0,
            floors: None,
            trajectory: None,
            turns: None,
            carry_steps: None,
            detector_fallback: false,
            thigh_share: 0.0,
            error: Some(error),
            waypoint_errors_m: Vec::new(),
            waypoint_errors_pct: Vec::new(),
            absolute_errors_m: Default::default(),
        }
    }
}

/// The summary over all logs. Field names are stable.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Logs evaluated (including failed ones).
    pub logs: u64,
    /// Logs that failed.
    pub failed: u64,
    /// Mean step-count error over the logs with step truth, %.
    pub step_mae_pct: Option<f64>,
    /// Mean of [`LogResult::step_error_debounced_pct`], %.
    pub step_mae_debounced_pct: Option<f64>,
    /// Mean step-count error per group (Oxford: per placement), %; and against the debounced
    /// truth.
    pub step_mae_by_group: std::collections::BTreeMap<String, GroupSteps>,
    /// 75th percentile of all waypoint errors of all logs, pooled, m.
    pub waypoint_p75_m: Option<f64>,
    /// 75th percentile of all counted waypoint errors of all logs, pooled, %.
    pub waypoint_p75_pct: Option<f64>,
    /// Median over the logs of each log's 75th percentile of the absolute error of GNSS alone,
    /// m (every log counts once, whatever its length).
    pub gnss_p75_m: Option<f64>,
    /// The same for the fused track, m.
    pub fused_p75_m: Option<f64>,
    /// The same for the smoothed track, m.
    pub smoothed_p75_m: Option<f64>,
    /// Median over the logs of [`LogResult::yardstick_p75_m`], m.
    pub yardstick_p75_m: Option<f64>,
    /// Median over the logs of [`LogResult::causal_yardstick_p75_m`], m.
    pub causal_yardstick_p75_m: Option<f64>,
    /// Logs whose smoothed p75 is within 1 m of their yardstick, of the logs with both.
    pub smoothed_near_yardstick: [u64; 2],
    /// Logs whose fused p75 is within 1 m of their causal yardstick, of the logs with both.
    pub fused_near_causal_yardstick: [u64; 2],
    /// 75th percentile of all absolute errors of GNSS alone of all logs, pooled, m.
    pub gnss_pooled_p75_m: Option<f64>,
    /// The same for the fused track, m.
    pub fused_pooled_p75_m: Option<f64>,
    /// The same for the smoothed track, m.
    pub smoothed_pooled_p75_m: Option<f64>,
    /// Logs whose fused p75 is more than 1.1 × their GNSS-alone p75.
    pub fused_worse_than_gnss: u64,
    /// The receiver's on time over its span, summed over the logs with fusion
    /// ([`FusionResult::gnss_on_s`] / [`FusionResult::gnss_span_s`]): 1 in best performance,
    /// about window / period in energy saving.
    pub gnss_on_share: Option<f64>,
    /// Logs scored on floors (their landmarks have floors).
    pub floor_logs: u64,
    /// Landmarks scored on floors, over all those logs.
    pub floor_landmarks: u64,
    /// Share of those landmarks with the right relative floor, pooled.
    pub floor_share: Option<f64>,
    /// 75th percentile of all height errors, pooled, m (only where the truth has heights).
    pub height_p75_m: Option<f64>,
    /// The logs with a trajectory truth, per group (the carrying mode), and `all` of them.
    pub trajectory_by_group: std::collections::BTreeMap<String, TrajectoryGroup>,
    /// Per group (the carrying mode, the pocket) and `all`: the share of the scored steps whose
    /// carrying mode is the truth's ([`LogResult::carry_steps`], pooled).
    pub carry_share_by_group: std::collections::BTreeMap<String, f64>,
    /// True turns scored, over all logs.
    pub turns_scored: u64,
    /// Median absolute turn error over every scored turn of every log, pooled, degrees.
    pub turn_error_median_deg: Option<f64>,
}

/// Step-count figures of one group of logs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GroupSteps {
    /// Logs in the group with step truth.
    pub logs: u64,
    /// Mean step-count error, %.
    pub mae_pct: f64,
    /// Mean step-count error against the debounced truth, %, when every log has it.
    pub mae_debounced_pct: Option<f64>,
}

/// The whole report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// One row per log.
    pub logs: Vec<LogResult>,
    /// Summary.
    pub summary: Summary,
}

/// Runs one log through a pipeline with `cfg` and scores it.
pub fn evaluate(log: &Log, cfg: &PipelineConfig) -> LogResult {
    match replay(log.dated(cfg), &log.records) {
        Ok(run) => score(log, &run),
        Err(e) => LogResult::failed(&log.source, log.format.as_str(), e.to_string()),
    }
}

/// Scores a run of the engine over a log against the truth the log carries.
pub fn score(log: &Log, run: &crate::engine::Replay) -> LogResult {
    let mut res = LogResult::failed(&log.source, log.format.as_str(), String::new());
    res.error = None;
    res.skipped_lines = log.skipped;
    res.group = log.group.clone();
    let p = &run.pipeline;
    let d = p.diagnostics();
    let track = p.track();
    res.samples = d.samples;
    res.duration_s = d.time_span.map_or(0.0, |(a, b)| b - a);
    res.steps = d.steps;
    res.placement = d.placement;
    res.strides =
        (d.placement == crate::engine::foot::placement::Placement::Foot).then_some(d.strides);
    res.distance_m = d.distance_m;
    res.refused_records = run.refused;
    res.pressure_samples = d.pressure_samples;
    res.detector_fallback = d.detector_fallback;
    if !track.is_empty() {
        res.thigh_share = track
            .iter()
            .filter(|s| s.pitch_amplitude_deg.is_some())
            .count() as f64
            / track.len() as f64;
    }
    if d.samples == 0 {
        res.error = Some("no IMU sample accepted".into());
        return res;
    }
    res.steps_in_window = log.truth.step_window.map(|(a, b)| {
        let all = track.iter().chain(p.held_steps());
        all.filter(|s| s.t >= a && s.t <= b).count() as u64
    });
    let counted = res.steps_in_window.unwrap_or(res.steps);
    let error_pct = |truth: u64| {
        (truth > 0).then(|| 100.0 * (counted as f64 - truth as f64).abs() / truth as f64)
    };
    res.truth_steps = log.truth.steps;
    res.step_error_pct = log.truth.steps.and_then(error_pct);
    res.truth_steps_debounced = log.truth.steps_debounced();
    res.step_error_debounced_pct = res.truth_steps_debounced.and_then(error_pct);
    let wps = &log.truth.waypoints;
    res.waypoints = wps.len() as u64;
    if let Some(errors) = waypoint_errors(track, wps) {
        let m: Vec<f64> = errors.iter().map(|e| e.0).collect();
        let pct: Vec<f64> = errors.iter().filter_map(|e| e.1).collect();
        res.waypoint_error_m = Some(MetresSummary {
            mean: mean(&m),
            p75: percentile(&m, 75.0),
            max: m.iter().copied().fold(0.0, f64::max),
            r#final: *m.last().unwrap_or(&0.0),
        });
        if !pct.is_empty() {
            res.waypoint_error_pct = Some(PctSummary {
                mean: mean(&pct),
                p75: percentile(&pct, 75.0),
                r#final: *pct.last().unwrap_or(&0.0),
            });
        }
        res.waypoint_errors_m = m;
        res.waypoint_errors_pct = pct;
    }
    absolute::absolute_errors(p, &log.truth.waypoints, &mut res);
    res.floors = floors::score_floors(track, wps);
    res.trajectory = trajectory::score_trajectory(track, &log.truth.trajectory);
    res.turns = turn_angles::score_turns(track, &log.truth.turns);
    res.carry_steps = carry::score_carry(track, &log.truth);
    res.fusion = p.fusion().and_then(|f| {
        let d = f.diagnostics();
        let last = d.last?;
        Some(FusionResult {
            scale: last.scale,
            scale_sd: last.scale_bias_sd[0],
            heading_correction_deg: last.bias_rad.to_degrees(),
            heading_correction_sd_deg: last.scale_bias_sd[1].to_degrees(),
            fixes_used: d.counts.used,
            fixes_gated: d.counts.gated,
            resets: d.counts.resets,
            gnss_on_s: d.gnss_on_s.map(|(on, _)| on),
            gnss_span_s: d.gnss_on_s.map(|(_, span)| span),
            baselines: d.counts.baselines,
            white_share: Some(d.white_share),
        })
    });
    res.declination_deg = d.declination_deg;
    res.declination_note = d.declination_note.map(|n| n.to_string());
    if log.truth.loop_closure {
        let (e, n) = track.last().map_or((0.0, 0.0), |s| (s.east_m, s.north_m));
        res.loop_closure_m = Some(libm::hypot(e, n));
    }
    res
}

/// For each waypoint after the first: the aligned error in metres, and the error as a
/// percentage of the path so far when that path is at least [`MIN_PATH_FOR_PCT_M`]. `None` with
/// fewer than two waypoints.
pub fn waypoint_errors(track: &[StepRecord], wps: &[Waypoint]) -> Option<Vec<(f64, Option<f64>)>> {
    let (w0, rest) = wps.split_first()?;
    let (pairs, s, c) = alignment(track, wps)?;
    let mut path = 0.0;
    let mut last = (w0.x_m, w0.y_m);
    let mut out = Vec::with_capacity(pairs.len());
    for (((ex, ey), (rx, ry)), w) in pairs.iter().zip(rest) {
        path += libm::hypot(w.x_m - last.0, w.y_m - last.1);
        last = (w.x_m, w.y_m);
        let (ax, ay) = (c * ex - s * ey, s * ex + c * ey);
        let err = libm::hypot(ax - rx, ay - ry);
        let pct = (path >= MIN_PATH_FOR_PCT_M).then(|| 100.0 * err / path);
        out.push((err, pct));
    }
    Some(out)
}

/// The estimate's positions at the waypoints after the first, relative to its position at the
/// first, paired with the waypoints relative to the first; and the least-squares rotation
/// (sin, cos) of the estimate onto the truth (2-D Procrustes without scale). `None` with fewer
/// than two waypoints.
#[allow(clippy::type_complexity)]
fn alignment(
    track: &[StepRecord],
    wps: &[Waypoint],
) -> Option<(Vec<((f64, f64), (f64, f64))>, f64, f64)> {
    let (w0, rest) = wps.split_first()?;
    if rest.is_empty() {
        return None;
    }
    let p0 = position_at(track, w0.t);
    let pairs: Vec<((f64, f64), (f64, f64))> = rest
        .iter()
        .map(|w| {
            let p = position_at(track, w.t);
            ((p.0 - p0.0, p.1 - p0.1), (w.x_m - w0.x_m, w.y_m - w0.y_m))
        })
        .collect();
    let (mut dot, mut cross) = (0.0, 0.0);
    for ((ex, ey), (rx, ry)) in &pairs {
        dot += ex * rx + ey * ry;
        cross += ex * ry - ey * rx;
    }
    let (s, c) = if dot == 0.0 && cross == 0.0 {
        (0.0, 1.0)
    } else {
        libm::sincos(libm::atan2(cross, dot))
    };
    Some((pairs, s, c))
}

/// The waypoints drawn in the track's frame, placed as [`waypoint_errors`] compares them (the
/// alignment's rotation undone about the track's position at the first waypoint).
pub fn waypoints_in_track_frame(track: &[StepRecord], wps: &[Waypoint]) -> Vec<(f64, f64)> {
    let Some((_, s, c)) = alignment(track, wps) else {
        return Vec::new();
    };
    let w0 = wps[0];
    let p0 = position_at(track, w0.t);
    wps.iter()
        .map(|w| {
            let (rx, ry) = (w.x_m - w0.x_m, w.y_m - w0.y_m);
            (p0.0 + c * rx + s * ry, p0.1 - s * rx + c * ry)
        })
        .collect()
}

/// Mean of a non-empty slice (0 when empty).
fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

/// Percentile `q` (0–100) by linear interpolation between order statistics; NaN-free input.
pub fn percentile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mut s = v.to_vec();
    crate::engine::sort::sort_by(&mut s, f64::total_cmp);
    let pos = q / 100.0 * (s.len() - 1) as f64;
    let i = pos.floor() as usize;
    let frac = pos - i as f64;
    match s.get(i + 1) {
        Some(&next) => s[i] + frac * (next - s[i]),
        None => s[i],
    }
}

/// The summary of a set of results.
pub fn summarise(logs: &[LogResult]) -> Summary {
    let steps: Vec<f64> = logs.iter().filter_map(|l| l.step_error_pct).collect();
    let debounced: Vec<f64> = logs
        .iter()
        .filter_map(|l| l.step_error_debounced_pct)
        .collect();
    let mut groups = std::collections::BTreeMap::<String, Vec<&LogResult>>::new();
    for l in logs.iter().filter(|l| l.step_error_pct.is_some()) {
        if let Some(g) = &l.group {
            groups.entry(g.clone()).or_default().push(l);
        }
    }
    let median_p75 = |get: fn(&LogResult) -> Option<ErrorSummary>| {
        let v: Vec<f64> = logs.iter().filter_map(|l| get(l).map(|e| e.p75)).collect();
        (!v.is_empty()).then(|| percentile(&v, 50.0))
    };
    let median_of = |get: fn(&LogResult) -> Option<f64>| {
        let v: Vec<f64> = logs.iter().filter_map(get).collect();
        (!v.is_empty()).then(|| percentile(&v, 50.0))
    };
    // (logs within 1 m of their yardstick, logs with both figures)
    let near = |get: fn(&LogResult) -> Option<(f64, f64)>| {
        let pairs: Vec<(f64, f64)> = logs.iter().filter_map(get).collect();
        let within = pairs.iter().filter(|(p75, y)| *p75 <= y + 1.0).count();
        [within as u64, pairs.len() as u64]
    };
    let pooled = |k: usize| {
        let v: Vec<f64> = logs
            .iter()
            .flat_map(|l| l.absolute_errors_m[k].iter().copied())
            .collect();
        (!v.is_empty()).then(|| percentile(&v, 75.0))
    };
    let step_mae_by_group = groups
        .into_iter()
        .map(|(g, ls)| {
            let e: Vec<f64> = ls.iter().filter_map(|l| l.step_error_pct).collect();
            let d: Option<Vec<f64>> = ls.iter().map(|l| l.step_error_debounced_pct).collect();
            let s = GroupSteps {
                logs: ls.len() as u64,
                mae_pct: mean(&e),
                mae_debounced_pct: d.map(|d| mean(&d)),
            };
            (g, s)
        })
        .collect();
    let m: Vec<f64> = logs
        .iter()
        .flat_map(|l| l.waypoint_errors_m.iter().copied())
        .collect();
    let pct: Vec<f64> = logs
        .iter()
        .flat_map(|l| l.waypoint_errors_pct.iter().copied())
        .collect();
    let with_floors: Vec<&FloorResult> = logs.iter().filter_map(|l| l.floors.as_ref()).collect();
    let (floor_logs, floor_landmarks, _, floor_share, height_p75_m) = floors::pool(&with_floors);
    let (on, span) = logs
        .iter()
        .filter_map(|l| Some((l.fusion?.gnss_on_s?, l.fusion?.gnss_span_s?)))
        .fold((0.0, 0.0), |(a, b), (on, span)| (a + on, b + span));
    let mut trajectories = std::collections::BTreeMap::<String, Vec<&TrajectoryResult>>::new();
    for l in logs {
        if let Some(t) = &l.trajectory {
            let group = l.group.clone().unwrap_or_else(|| "other".into());
            trajectories.entry(group).or_default().push(t);
            trajectories.entry("all".into()).or_default().push(t);
        }
    }
    let turn_errors: Vec<f64> = logs
        .iter()
        .filter_map(|l| l.turns.as_ref())
        .flat_map(|t| t.scored.iter().map(|s| s[2].abs()))
        .collect();
    Summary {
        carry_share_by_group: carry::pool(logs),
        trajectory_by_group: trajectories
            .iter()
            .map(|(g, v)| (g.clone(), TrajectoryGroup::of(v)))
            .collect(),
        turns_scored: turn_errors.len() as u64,
        turn_error_median_deg: (!turn_errors.is_empty()).then(|| percentile(&turn_errors, 50.0)),
        gnss_on_share: (span > 0.0).then(|| on / span),
        logs: logs.len() as u64,
        failed: logs.iter().filter(|l| l.error.is_some()).count() as u64,
        step_mae_pct: (!steps.is_empty()).then(|| mean(&steps)),
        step_mae_debounced_pct: (!debounced.is_empty()).then(|| mean(&debounced)),
        step_mae_by_group,
        waypoint_p75_m: (!m.is_empty()).then(|| percentile(&m, 75.0)),
        waypoint_p75_pct: (!pct.is_empty()).then(|| percentile(&pct, 75.0)),
        gnss_p75_m: median_p75(|l| l.gnss_error_m),
        fused_p75_m: median_p75(|l| l.fused_error_m),
        smoothed_p75_m: median_p75(|l| l.smoothed_error_m),
        yardstick_p75_m: median_of(|l| l.yardstick_p75_m),
        causal_yardstick_p75_m: median_of(|l| l.causal_yardstick_p75_m),
        smoothed_near_yardstick: near(|l| Some((l.smoothed_error_m?.p75, l.yardstick_p75_m?))),
        fused_near_causal_yardstick: near(|l| {
            Some((l.fused_error_m?.p75, l.causal_yardstick_p75_m?))
        }),
        gnss_pooled_p75_m: pooled(0),
        fused_pooled_p75_m: pooled(1),
        smoothed_pooled_p75_m: pooled(2),
        fused_worse_than_gnss: logs
            .iter()
            .filter(|l| match (l.gnss_error_m, l.fused_error_m) {
                (Some(g), Some(f)) => f.p75 > 1.1 * g.p75,
                _ => false,
            })
            .count() as u64,
        floor_logs,
        floor_landmarks,
        floor_share,
        height_p75_m,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::engine::motion::Motion;

    pub(crate) fn step(t: f64, e: f64, n: f64) -> StepRecord {
        StepRecord {
            t,
            east_m: e,
            north_m: n,
            heading_rad: None,
            step_heading_rad: None,
            length_m: 0.7,
            freq_hz: 1.8,
            motion: Motion::Walking,
            activity: crate::engine::Activity::Walking,
            up_m: 0.0,
            floor: 0,
            pitch_amplitude_deg: None,
            carry: None,
            gyro_heading: false,
        }
    }

    #[test]
    fn rotated_track_scores_zero_and_scale_does_not() {
        // Truth: 30 m east then 30 m north. The estimate is the same path rotated by 40°.
        let wps = [
            Waypoint {
                t: 0.0,
                x_m: 5.0,
                y_m: 5.0,
                geo: None,
                floor: None,
                height_m: None,
            },
            Waypoint {
                t: 30.0,
                x_m: 35.0,
                y_m: 5.0,
                geo: None,
                floor: None,
                height_m: None,
            },
            Waypoint {
                t: 60.0,
                x_m: 35.0,
                y_m: 35.0,
                geo: None,
                floor: None,
                height_m: None,
            },
        ];
        let (s, c) = libm::sincos(0.7);
        let rot = |x: f64, y: f64| (c * x - s * y, s * x + c * y);
        let mut track = Vec::new();
        for i in 0..=60 {
            let (x, y) = if i <= 30 {
                (i as f64, 0.0)
            } else {
                (30.0, (i - 30) as f64)
            };
            let (e, n) = rot(x, y);
            track.push(step(i as f64, e, n));
        }
        let err = waypoint_errors(&track, &wps).unwrap();
        assert!(err.iter().all(|e| e.0 < 1e-9), "{err:?}");
        assert_eq!(err[0].1.map(|p| p < 1e-9), Some(true));
        // 10 % too long: the error grows with the distance.
        let long: Vec<StepRecord> = track
            .iter()
            .map(|s| step(s.t, 1.1 * s.east_m, 1.1 * s.north_m))
            .collect();
        let err = waypoint_errors(&long, &wps).unwrap();
        assert!(err[1].0 > 3.0 && err[1].0 < 5.0, "{err:?}");
    }

    #[test]
    fn percentile_interpolates() {
        assert_eq!(percentile(&[1.0, 2.0, 3.0, 4.0, 5.0], 75.0), 4.0);
        assert_eq!(percentile(&[0.0, 10.0], 75.0), 7.5);
        assert_eq!(percentile(&[3.0], 75.0), 3.0);
    }
}
