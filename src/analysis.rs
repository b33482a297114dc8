//! Upload mode's analysis of one log: the engine runs once over it, and everything the page
//! shows is kept — the track, the per-sample signals of the diagnostics plots, the fixes, the
//! fused and smoothed tracks, the truth placed in the track's frame, and the evaluation bench's
//! scores. Pure Rust: the web worker makes it, the page draws it ([`crate::plot`]), the tests
//! check it natively.
//! May import: `engine`, `io`, `eval`.
//!
//! It is serialised ([`Analysis::to_bytes`], postcard) to cross from the worker to the page:
//! signals are `f32` (plenty for a plot), times `f64` (Unix seconds need it).

use crate::engine::activity::Activity;
use crate::engine::fusion::{FixCounts, GnssVerdict};
use crate::engine::motion::Motion;
use crate::engine::replay::replay_observed;
use crate::engine::types::ConfigError;
use crate::engine::types::Record;
use crate::engine::vertical::VerticalSource;
use crate::engine::{Pipeline, PipelineConfig, StepRecord};
use crate::eval::LogResult;
/// The words the page shows for activities and floors (from `io::export`, for `plot`, which
/// may not import `io`).
pub use crate::io::export::{activity_words, floor_label};

pub mod page;
mod text;
use crate::io::import::Log;
pub use text::{carry_text, fixed};

/// The per-sample signals, one entry per IMU sample the engine accepted.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Trace {
    /// Time, s.
    pub t: Vec<f64>,
    /// Vertical linear acceleration, m/s².
    pub up: Vec<f32>,
    /// PLL output cos φ (NaN with the peak detector).
    pub pll: Vec<f32>,
    /// σ of the vertical acceleration over the motion window, m/s².
    pub sigma: Vec<f32>,
    /// Motion state: 0 still, 1 walking, 2 running.
    pub motion: Vec<u8>,
    /// Compass heading of the device's top from the OS (or filter) attitude, degrees (NaN
    /// without one).
    pub device_heading_deg: Vec<f32>,
    /// Horizontal acceleration east and north, m/s² (the tip-to-tail ellipse of a stride).
    pub east: Vec<f32>,
    /// See `east`.
    pub north: Vec<f32>,
    /// The activity (Munoz Diaz 2015 §4.3): its index in `Activity::ALL`; from the motion
    /// state (still, walking, running) while the engine has no activity of its own.
    pub activity: Vec<u8>,
    /// Height above the walk's start, m (`Diagnostics::up_m`).
    pub height: Vec<f32>,
    /// Floor relative to the walk's start (`Diagnostics::floor`).
    pub floor: Vec<i16>,
}

/// The activity a sample's diagnostics show: the engine's when it has one, else the motion
/// state's (still, walking, running).
pub fn activity_of(d: &crate::engine::Diagnostics, motion: Motion) -> Activity {
    d.activity.unwrap_or(match motion {
        Motion::Still => Activity::Still,
        Motion::Walking => Activity::Walking,
        Motion::Running => Activity::Running,
    })
}

/// An activity's index in `Activity::ALL` (the trace's code), and back.
pub fn activity_code(a: Activity) -> u8 {
    Activity::ALL.iter().position(|&x| x == a).unwrap_or(0) as u8
}

/// See [`activity_code`]; `Still` for a code out of range.
pub fn activity_from_code(c: u8) -> Activity {
    Activity::ALL
        .get(usize::from(c))
        .copied()
        .unwrap_or(Activity::Still)
}

/// A GNSS fix in the local frame: time, east, north, reported accuracy.
pub type FixPoint = [f64; 4];

/// Everything upload mode shows about one log.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Analysis {
    /// Where the log came from (file, or archive/member).
    pub source: String,
    /// Its format.
    pub format: String,
    /// Lines the reader skipped, with the first reasons.
    pub warnings: Vec<String>,
    /// The evaluation bench's result for this log (the same object as `pdr eval --json`).
    pub score: LogResult,
    /// The steps.
    pub steps: Vec<StepRecord>,
    /// The per-sample signals.
    pub trace: Trace,
    /// Fixes in the local frame of the first fix.
    pub fixes: Vec<FixPoint>,
    /// Fused track: t, east, north, step-length scale, heading correction (rad).
    pub fused: Vec<[f64; 5]>,
    /// The standard deviations of each fused step's scale and heading correction (rad),
    /// parallel to `fused` (the fusion plot's ±1σ bands).
    pub fused_sd: Vec<[f64; 2]>,
    /// What the filter did with the fixes, when it ran.
    pub fix_counts: Option<FixCounts>,
    /// The filter's verdict on the GNSS at the end of the log, when it ran.
    pub verdict: Option<GnssVerdict>,
    /// Smoothed track: t, east, north.
    pub smoothed: Vec<[f64; 3]>,
    /// Innovations of the fixes offered: t, east, north, m.
    pub innovations: Vec<[f64; 3]>,
    /// Added to the PDR track to draw it in the fixes' frame (zero without fixes).
    pub pdr_offset: (f64, f64),
    /// The local frame's origin (latitude, longitude, height), when there are fixes.
    pub origin: Option<(f64, f64, f64)>,
    /// The truth's path in the PDR track's frame, aligned as the bench scores it: its waypoints,
    /// or a motion-capture trajectory every [`TRUTH_EVERY_S`].
    pub truth_path: Vec<(f64, f64)>,
    /// Whether [`Analysis::truth_path`] is a motion-capture trajectory (a line) rather than
    /// waypoints (each a dot).
    pub truth_is_trajectory: bool,
    /// True step times, when the truth has them.
    pub truth_steps: Vec<f64>,
    /// The motion detector's σ thresholds: still below, running above (m/s²).
    pub sigma_thresholds: (f64, f64),
    /// What the height comes from (None: no height, a flat walk assumed).
    pub vertical: Option<VerticalSource>,
    /// Barometer readings the engine accepted.
    pub pressure_samples: u64,
    /// Some IMU record of the log has a gyroscope, a magnetometer or an OS attitude: an input
    /// a heading can come from.
    pub heading_inputs: bool,
}

/// Spacing of the points drawn from a motion-capture truth, s: a step's worth, enough for the
/// map's line, few enough for the trip to the page.
pub const TRUTH_EVERY_S: f64 = 0.25;

/// Why an analysis cannot cross from the worker to the page.
#[derive(Debug, Clone, PartialEq)]
pub enum AnalysisError {
    /// It could not be written as bytes.
    Encode(String),
    /// The bytes are not an analysis.
    Decode(String),
}

impl std::fmt::Display for AnalysisError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AnalysisError::Encode(e) => write!(f, "the analysis cannot be written: {e}"),
            AnalysisError::Decode(e) => write!(f, "unreadable analysis: {e}"),
        }
    }
}

impl std::error::Error for AnalysisError {}

/// How often [`analyse`] reports progress, records.
pub const PROGRESS_EVERY: usize = 65_536;

/// Runs the engine over a log, keeping what the page shows. `progress(done, total)` is called
/// every [`PROGRESS_EVERY`] records.
pub fn analyse(
    log: &Log,
    cfg: &PipelineConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Analysis, ConfigError> {
    let total = log.records.len();
    let mut tr = Trace::with_capacity(log.imu_samples());
    progress(0, total);
    let mut observe = |pipeline: &Pipeline, i: usize, r: &Record, accepted: bool| {
        if let (Record::Imu(s), true) = (r, accepted) {
            tr.push(pipeline, s.t);
        }
        if (i + 1) % PROGRESS_EVERY == 0 && i + 1 < total {
            progress(i + 1, total);
        }
    };
    let run = replay_observed(log.dated(cfg), &log.records, &mut observe)?;
    progress(total, total);
    let score = crate::eval::score(log, &run);
    let p = &run.pipeline;
    let d = p.diagnostics();
    let frame = p.frame();
    let fixes: Vec<FixPoint> = frame.map_or_else(Vec::new, |fr| {
        p.fixes()
            .iter()
            .map(|f| {
                let (e, n) = fr.en_of_fix(f);
                [f.t, e, n, f.h_accuracy_m]
            })
            .collect()
    });
    let fused = p.fused();
    let pdr_offset = p.pdr_offset();
    Ok(Analysis {
        source: log.source.clone(),
        format: log.format.as_str().to_string(),
        warnings: warnings(log, &run.errors),
        score,
        steps: p.track().to_vec(),
        trace: tr,
        fixes,
        fused: fused
            .iter()
            .map(|f| [f.t, f.east_m, f.north_m, f.scale, f.bias_rad])
            .collect(),
        fused_sd: fused.iter().map(|f| f.scale_bias_sd).collect(),
        fix_counts: p.fusion().map(|f| f.diagnostics().counts),
        verdict: p.fusion().map(|f| f.verdict()),
        smoothed: p
            .smoothed()
            .iter()
            .map(|f| [f.t, f.east_m, f.north_m])
            .collect(),
        innovations: fused
            .iter()
            .filter_map(|f| f.innovation.map(|i| [f.t, i[0], i[1]]))
            .collect(),
        pdr_offset,
        origin: frame.map(|f| (f.lat0_deg, f.lon0_deg, f.h0_m)),
        truth_is_trajectory: log.truth.waypoints.is_empty() && !log.truth.trajectory.is_empty(),
        truth_path: truth_path(log, p.track()),
        truth_steps: log.truth.step_events.iter().map(|s| s.t).collect(),
        sigma_thresholds: (cfg.motion.still_max, cfg.motion.run_sigma_min),
        vertical: d.vertical,
        pressure_samples: d.pressure_samples,
        heading_inputs: log.records.iter().any(|r| {
            matches!(r, Record::Imu(s) if s.gyro.is_some() || s.mag.is_some() || s.orientation.is_some())
        }),
    })
}

impl Trace {
    /// An empty trace with room for `n` samples. Every signal at its final size at once:
    /// growing by doubling would copy each and, in wasm, raise the memory's high-water mark by
    /// up to their size again.
    fn with_capacity(n: usize) -> Self {
        let mut tr = Trace::default();
        for v in [
            &mut tr.up,
            &mut tr.pll,
            &mut tr.sigma,
            &mut tr.device_heading_deg,
            &mut tr.east,
            &mut tr.north,
        ] {
            v.reserve_exact(n);
        }
        tr.t.reserve_exact(n);
        tr.motion.reserve_exact(n);
        tr.activity.reserve_exact(n);
        tr.height.reserve_exact(n);
        tr.floor.reserve_exact(n);
        tr
    }

    /// Keeps the signals of the IMU sample at `t` (s) the pipeline has just taken.
    fn push(&mut self, pipeline: &Pipeline, t: f64) {
        let deg = 180.0 / std::f64::consts::PI;
        let (up, e, north) = pipeline.last_nav().unwrap_or((f64::NAN, 0.0, 0.0));
        self.t.push(t);
        self.up.push(up as f32);
        self.pll
            .push(pipeline.pll_output().map_or(f32::NAN, |p| p as f32));
        self.sigma.push(pipeline.vertical_stats().1 as f32);
        let motion = pipeline.motion_state();
        self.motion.push(motion as u8);
        let d = pipeline.diagnostics();
        self.activity.push(activity_code(activity_of(&d, motion)));
        self.height.push(d.up_m as f32);
        self.floor
            .push(d.floor.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16);
        self.device_heading_deg
            .push(pipeline.attitude().map_or(f32::NAN, |q| {
                let top = q * nalgebra::Vector3::y();
                (libm::atan2(top.x, top.y) * deg).rem_euclid(360.0) as f32
            }));
        self.east.push(e as f32);
        self.north.push(north as f32);
    }
}

/// The reader's warnings, the count of the lines it skipped when it gave fewer, and the first
/// ten records the engine refused.
fn warnings<E: std::fmt::Display>(log: &Log, refused: &[(usize, E)]) -> Vec<String> {
    let mut warnings: Vec<String> = log.warnings.iter().map(|e| e.to_string()).collect();
    if log.skipped > warnings.len() as u64 {
        warnings.push(format!("{} lines skipped in all", log.skipped));
    }
    for (i, e) in refused.iter().take(10) {
        warnings.push(format!("record {}: {e} (refused by the engine)", i + 1));
    }
    warnings
}

/// The truth's path in the track's frame: its waypoints, else its motion-capture trajectory
/// every [`TRUTH_EVERY_S`].
fn truth_path(log: &Log, track: &[StepRecord]) -> Vec<(f64, f64)> {
    if log.truth.waypoints.is_empty() {
        crate::eval::trajectory::trajectory_in_track_frame(
            track,
            &log.truth.trajectory,
            TRUTH_EVERY_S,
        )
    } else {
        crate::eval::waypoints_in_track_frame(track, &log.truth.waypoints)
    }
}

impl Analysis {
    /// The analysis as bytes (postcard: compact, integers as varints, floats bit for bit so NaN
    /// survives), for the trip from the worker to the page.
    pub fn to_bytes(&self) -> Result<Vec<u8>, AnalysisError> {
        postcard::to_stdvec(self).map_err(|e| AnalysisError::Encode(e.to_string()))
    }

    /// Reads [`Analysis::to_bytes`]; bytes left over after the analysis are an error.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, AnalysisError> {
        match postcard::take_from_bytes(bytes) {
            Ok((a, [])) => Ok(a),
            Ok((_, rest)) => Err(AnalysisError::Decode(format!(
                "{} bytes after the end",
                rest.len()
            ))),
            Err(e) => Err(AnalysisError::Decode(e.to_string())),
        }
    }

    /// The local frame of the fixes, for geodetic exports.
    pub fn frame(&self) -> Option<crate::engine::geo::LocalFrame> {
        self.origin
            .map(|(lat, lon, h)| crate::engine::geo::LocalFrame::new(lat, lon, h))
    }

    /// The log has steps and not one of them has a heading (an accelerometer only): there is
    /// no track to draw.
    pub fn has_steps_without_any_heading(&self) -> bool {
        !self.steps.is_empty() && self.steps.iter().all(|s| s.heading_rad.is_none())
    }

    /// Why no step has a heading, when none has: the log has no input a heading comes from,
    /// or (it has one) the engine gave none.
    pub fn no_heading_why(&self) -> Option<&'static str> {
        if !self.has_steps_without_any_heading() {
            None
        } else if self.heading_inputs {
            Some("the engine gave no step a heading, although the log has a gyroscope, magnetometer or orientation")
        } else {
            Some("the log has no gyroscope, magnetometer or orientation")
        }
    }

    /// Where step `i` is drawn on the map: its fused position when the fusion has the step,
    /// else the PDR track's (shifted into the fixes' frame).
    pub fn step_position(&self, i: usize) -> Option<(f64, f64)> {
        let s = self.steps.get(i)?;
        let k = self.fused.partition_point(|f| f[0] < s.t);
        match self.fused.get(k) {
            Some(f) if (f[0] - s.t).abs() < 1e-6 => Some((f[1], f[2])),
            _ => Some((s.east_m + self.pdr_offset.0, s.north_m + self.pdr_offset.1)),
        }
    }

    /// Whether the log has a height: the engine said where it came from, or a step or sample
    /// left the start's level.
    pub fn has_height(&self) -> bool {
        self.vertical.is_some()
            || self.steps.iter().any(|s| s.up_m != 0.0 || s.floor != 0)
            || self.trace.floor.iter().any(|&f| f != 0)
    }

    /// The floors the walk visited (steps and samples), lowest first; `[0]` without a height.
    pub fn floors(&self) -> Vec<i32> {
        let mut f: Vec<i32> = std::iter::once(0)
            .chain(self.steps.iter().map(|s| s.floor))
            .chain(self.trace.floor.iter().map(|&f| i32::from(f)))
            .collect();
        f.sort_unstable();
        f.dedup();
        f
    }

    /// Where the height comes from, for the height plot's title: "leg pitch", "barometer",
    /// "leg pitch + barometer"; "no height: flat walk assumed" without one.
    pub fn height_source(&self) -> &'static str {
        match self.vertical {
            Some(v) => v.as_str(),
            None if self.has_height() => "height from the steps",
            None => "no height: flat walk assumed",
        }
    }

    /// The activities the walk's samples and steps show, in `Activity::ALL`'s order.
    pub fn activities(&self) -> Vec<Activity> {
        let mut seen = [false; Activity::ALL.len()];
        for &c in &self.trace.activity {
            if let Some(x) = seen.get_mut(usize::from(c)) {
                *x = true;
            }
        }
        for s in &self.steps {
            seen[usize::from(activity_code(s.activity))] = true;
        }
        Activity::ALL
            .iter()
            .zip(seen)
            .filter_map(|(&a, s)| s.then_some(a))
            .collect()
    }

    /// The index of the step nearest to a time, s.
    pub fn step_near_time(&self, t: f64) -> Option<usize> {
        let i = self.steps.partition_point(|s| s.t < t);
        [i.checked_sub(1), Some(i)]
            .into_iter()
            .flatten()
            .filter(|&k| k < self.steps.len())
            .min_by(|&a, &b| {
                (self.steps[a].t - t)
                    .abs()
                    .total_cmp(&(self.steps[b].t - t).abs())
            })
    }
}

/// A hand-made walk on three floors, for the tests of what shows heights, floors and
/// activities while the engine cannot make one: the simulated demo walk analysed, then its
/// samples and steps given a climb of two floors (3 m each) between 30 % and 50 % of the walk,
/// a descent of one between 70 % and 80 %, standing before the first step and sitting after
/// the last, and a height from the leg pitch and the barometer.
#[cfg(test)]
pub(crate) fn three_floor_analysis() -> Analysis {
    let mut log = crate::io::import::Log::new("stairs.pdrlog", crate::io::import::Format::PdrLog);
    log.records = crate::sim::scenarios::demo_walk().generate().records;
    let mut a = analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap();
    let (t0, t1) = (a.trace.t[0], *a.trace.t.last().unwrap());
    let (first, last) = (a.steps[0].t, a.steps.last().unwrap().t);
    let height = |t: f64| {
        let f = (t - t0) / (t1 - t0);
        let ramp = |a: f64, b: f64| ((f - a) / (b - a)).clamp(0.0, 1.0);
        6.0 * ramp(0.3, 0.5) - 3.0 * ramp(0.7, 0.8)
    };
    let activity = |t: f64, stepping: bool| {
        let f = (t - t0) / (t1 - t0);
        match () {
            _ if t < first => Activity::Standing,
            _ if t > last => Activity::Sitting,
            _ if !stepping => Activity::Still,
            _ if (0.3..0.5).contains(&f) => Activity::Upstairs,
            _ if (0.7..0.8).contains(&f) => Activity::Downstairs,
            _ => Activity::Walking,
        }
    };
    let floor = |h: f64| (h / 3.0 + 0.5).floor() as i32;
    for i in 0..a.trace.t.len() {
        let t = a.trace.t[i];
        let h = height(t);
        a.trace.height[i] = h as f32;
        a.trace.floor[i] = floor(h) as i16;
        a.trace.activity[i] = activity_code(activity(t, a.trace.motion[i] != 0));
    }
    for s in &mut a.steps {
        s.up_m = height(s.t);
        s.floor = floor(s.up_m);
        s.activity = activity(s.t, true);
        s.pitch_amplitude_deg = Some(40.0);
    }
    a.vertical = Some(VerticalSource::PitchAndBarometer);
    a
}

#[cfg(test)]
mod tests {
    use super::fixed;
    use super::*;

    #[test]
    fn the_trace_has_an_activity_a_height_and_a_floor_per_sample() {
        let mut log = crate::io::import::Log::new("demo.pdrlog", crate::io::import::Format::PdrLog);
        log.records = crate::sim::scenarios::demo_walk().generate().records;
        let a = analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap();
        let n = a.trace.t.len();
        assert_eq!(
            (
                a.trace.activity.len(),
                a.trace.height.len(),
                a.trace.floor.len()
            ),
            (n, n, n)
        );
        // Without the engine's own activity, the motion state's: walking while walking.
        for (m, c) in a.trace.motion.iter().zip(&a.trace.activity) {
            let want = [Activity::Still, Activity::Walking, Activity::Running][usize::from(*m)];
            assert!(
                activity_from_code(*c) == want || a.vertical.is_some(),
                "{m} {c}"
            );
        }
        assert!(a.activities().contains(&Activity::Walking));
        assert_eq!(
            activity_from_code(activity_code(Activity::Downstairs)),
            Activity::Downstairs
        );
        assert_eq!(activity_from_code(200), Activity::Still);
        let back = Analysis::from_bytes(&a.to_bytes().unwrap()).unwrap();
        assert_eq!(back, a);
    }

    #[test]
    fn a_three_floor_walk_is_described_with_its_heights_floors_and_activities() {
        let a = three_floor_analysis();
        // Set PDR_ANALYSIS_DUMP to a file to look at it in the page (AnalysisView.from_bytes).
        if let Ok(path) = std::env::var("PDR_ANALYSIS_DUMP") {
            std::fs::write(path, a.to_bytes().unwrap()).unwrap();
        }
        assert!(a.has_height());
        assert_eq!(a.floors(), vec![0, 1, 2]);
        assert_eq!(a.height_source(), "leg pitch + barometer");
        for act in [
            Activity::Standing,
            Activity::Walking,
            Activity::Upstairs,
            Activity::Downstairs,
        ] {
            assert!(a.activities().contains(&act), "{act:?}");
        }
        let up = a
            .steps
            .iter()
            .position(|s| s.activity == Activity::Upstairs)
            .unwrap();
        let text = a.step_text(up).unwrap();
        assert!(text.contains(" · walking upstairs · height "), "{text}");
        let last = a.step_text(a.steps.len() - 1).unwrap();
        assert!(
            last.ends_with(" · walking · height 3.00 m, floor +1"),
            "{last}"
        );
        let rows = a.figures();
        let c = rows
            .iter()
            .find(|r| r.0 == "Carried")
            .expect("a Carried row");
        assert!(c.1.starts_with("in a pocket "), "{}", c.1);
        // A clean simulated field: no step held on the gyroscope, no row; two held, said.
        assert!(!rows.iter().any(|r| r.0 == "Gyroscope heading"));
        let mut held = a.clone();
        held.steps[3].gyro_heading = true;
        held.steps[4].gyro_heading = true;
        let rows_held = held.figures();
        let g = rows_held
            .iter()
            .find(|r| r.0 == "Gyroscope heading")
            .expect("a Gyroscope heading row");
        assert_eq!(
            g.1,
            format!(
                "2 of {} steps: the magnetometer was bent there",
                a.steps.len()
            )
        );
        let h = rows.iter().find(|r| r.0 == "Height").expect("a Height row");
        assert_eq!(
            h.1,
            "3.0 m at the end (floor +1), 3 floors visited (0, +1, +2); from leg pitch + barometer"
        );
        let back = Analysis::from_bytes(&a.to_bytes().unwrap()).unwrap();
        assert_eq!(back.trace.floor, a.trace.floor);
        assert_eq!(back.vertical, a.vertical);
        // A flat walk says so.
        let mut flat = a.clone();
        flat.vertical = None;
        flat.trace.floor.iter_mut().for_each(|f| *f = 0);
        flat.steps.iter_mut().for_each(|s| {
            s.up_m = 0.0;
            s.floor = 0;
        });
        assert!(!flat.has_height());
        assert_eq!(flat.height_source(), "no height: flat walk assumed");
        assert!(flat.figures().iter().all(|r| r.0 != "Height"));
        assert!(!flat.step_text(0).unwrap().contains("height"));
    }

    #[test]
    fn the_gnss_walk_shows_its_corrections_with_their_uncertainty_and_the_fixes_fate() {
        let mut log = crate::io::import::Log::new("city.pdrlog", crate::io::import::Format::PdrLog);
        log.records = crate::sim::scenarios::gnss_city_walk().generate().records;
        let a = analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap();
        assert_eq!(a.fused_sd.len(), a.fused.len());
        assert!(a
            .fused_sd
            .iter()
            .flatten()
            .all(|s| s.is_finite() && *s >= 0.0));
        let rows = a.figures();
        let get = |k: &str| {
            rows.iter()
                .find(|r| r.0 == k)
                .unwrap_or_else(|| panic!("no {k} row in {rows:?}"))
                .1
                .clone()
        };
        // The last fused step's numbers, in words.
        let (f, sd) = (a.fused.last().unwrap(), a.fused_sd.last().unwrap());
        let corrections = get("Corrections");
        assert_eq!(
            corrections,
            crate::io::fusion_words::corrections_text(f[3], sd[0], f[4], sd[1])
        );
        assert!(
            corrections.starts_with(&format!("step-length scale {:.2} ± {:.2} · ", f[3], sd[0])),
            "{corrections}"
        );
        let c = a.fix_counts.unwrap();
        assert!(c.used > 0);
        let gnss = get("GNSS");
        assert!(
            gnss.starts_with(&format!("{} fixes: {} used", a.fixes.len(), c.used)),
            "{gnss}"
        );
        assert_eq!(gnss.contains("refused by the gate"), c.gated > 0, "{gnss}");
        assert_eq!(get("Fusion"), a.verdict.unwrap().text());
        // They cross to the page.
        let back = Analysis::from_bytes(&a.to_bytes().unwrap()).unwrap();
        assert_eq!(
            (back.fused_sd, back.fix_counts, back.verdict),
            (a.fused_sd.clone(), a.fix_counts, a.verdict)
        );
        // A walk without fixes has none of them.
        let mut log = crate::io::import::Log::new("demo.pdrlog", crate::io::import::Format::PdrLog);
        log.records = crate::sim::scenarios::demo_walk().generate().records;
        let a = analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap();
        assert!(a
            .figures()
            .iter()
            .all(|r| r.0 != "Corrections" && r.0 != "Fusion"));
        assert_eq!(
            (a.fix_counts, a.verdict, a.corrections_text()),
            (None, None, None)
        );
    }

    #[test]
    fn fixed_rounds_as_javascript_does() {
        // `(x).toFixed(d)` in Node for each.
        for (x, d, js) in [
            (1.25, 1, "1.3"),
            (0.35, 1, "0.3"),
            (-1.25, 1, "-1.3"),
            (2.5, 0, "3"),
            (236.75, 1, "236.8"),
            (1.005, 2, "1.00"),
            (0.05, 1, "0.1"),
            (359.5, 0, "360"),
            (-0.04, 1, "-0.0"),
        ] {
            assert_eq!(fixed(x, d), js, "{x} to {d}");
        }
    }
}
