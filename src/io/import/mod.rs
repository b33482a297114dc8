//! Import: the recordings people make, read into the engine's own records.
//! May import: `engine` and `io` (a [`pdrlog`](crate::io::pdrlog) is one of the formats it reads).
//!
//! One layer for the CLI, the upload page (in wasm) and the tests. The input is a [`FileSet`]: a
//! folder, a zip archive, or files held in memory. [`import_all`] finds every recognisable log in
//! it (a folder of per-sensor CSVs is one log; a file of mixed records is one log), detects each
//! format from file names and first lines, and returns one [`Log`] per recording.
//!
//! # One convention after import
//! - Time: seconds on one clock per log, with no offset (Unix ms and ns become s; a time in
//!   seconds stays as it is).
//! - Units: m/s², rad/s, µT, WGS84 degrees, metres.
//! - Acceleration: specific force including gravity, Android sign (face up at rest: z = +9.81),
//!   device frame x right, y top of the screen, z out of the screen. iOS sources, whose
//!   acceleration has the opposite sign, are converted by [`Platform::to_android`].
//! - Orientation: the unit quaternion taking device vectors to East-North-Up.
//! - Sensors on separate clocks and rates are merged in time order by [`Streams::into_records`]:
//!   one IMU record per accelerometer sample, carrying the latest gyroscope, magnetometer and
//!   orientation samples not older than [`HOLD_S`]. Nothing is resampled, and nothing is moved
//!   earlier than it was measured: a stream that begins late is absent from the records before
//!   its first sample (the engine's `auto` orientation moves up when it appears).
//!
//! # Errors
//! A log that cannot be read at all gives a [`ParseError`] naming the file, line and column. A bad
//! line inside a readable log is skipped and kept in [`Log::warnings`]; every good line is kept.

pub mod archive_limits;
pub(crate) mod common;
pub mod date;
pub mod fileset;
pub mod get_sensor_data;
pub mod gnss_logger;
pub mod ms_indoor;
pub mod oxford;
pub mod phyphox;
pub mod recipe;
pub mod sensor_logger;
pub mod stream_zip;
pub mod tyrex;
pub mod ubicomp13;
pub mod weallwalk;
pub mod xio;

pub use super::lines::{MAX_LINE, MAX_WARNINGS};
pub use super::{field_error, file_error};
pub use archive_limits::{ArchiveLimits, Budget, LimitHit};
pub use fileset::{DirSet, FileSet, MemSet, ZipSet};
pub use stream_zip::StreamZipSet;

use super::ParseError;
use crate::engine::types::{GnssFix, ImuSample, PressureSample};
use crate::engine::Record;
use nalgebra::{UnitQuaternion, Vector3};

/// Standard gravity, m/s² (for sources that give acceleration in g).
#[doc(inline)]
pub use crate::engine::orientation::G0;

/// Longest a gyroscope, magnetometer or orientation sample is carried forward to later
/// accelerometer samples, s. Longer than one period of the slowest stream we read (a 10 Hz
/// orientation), shorter than a step. The engine holds the OS attitude as long.
#[doc(inline)]
pub use crate::engine::orientation::HOLD_S;

/// The formats we read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// The project's own `pdr-log`.
    PdrLog,
    /// Sensor Logger (Android/iOS), a folder or zip of per-sensor CSVs.
    SensorLogger,
    /// Sensor Logger's JSON export.
    SensorLoggerJson,
    /// phyphox CSV export.
    Phyphox,
    /// Google GnssLogger `.txt`.
    GnssLogger,
    /// GetSensorData (IPIN competitions) `.txt`.
    GetSensorData,
    /// Oxford Step Counter data set trace folder.
    OxfordSteps,
    /// Microsoft Indoor Location Competition 2.0 trace.
    MsIndoor,
    /// x-io Gait-Tracking foot-mounted CSV.
    XioFoot,
    /// TyrEx recording folder (Android or iOS), with its motion-capture trajectory.
    Tyrex,
    /// UbiComp 2013 step-counting walk folder.
    Ubicomp13,
    /// WeAllWalk walk folder (iOS Core Motion CSV, heel strikes and turns).
    #[serde(rename = "weallwalk")]
    WeAllWalk,
    /// Any recorder's per-sensor files, read by a user's [`recipe`] (column mapping).
    Recipe,
}

impl Format {
    /// The name used in reports (`pdr eval`), stable.
    pub fn as_str(self) -> &'static str {
        match self {
            Format::PdrLog => "pdr-log",
            Format::SensorLogger => "sensor-logger",
            Format::SensorLoggerJson => "sensor-logger-json",
            Format::Phyphox => "phyphox",
            Format::GnssLogger => "gnss-logger",
            Format::GetSensorData => "get-sensor-data",
            Format::OxfordSteps => "oxford-steps",
            Format::MsIndoor => "ms-indoor",
            Format::XioFoot => "xio-foot",
            Format::Tyrex => "tyrex",
            Format::Ubicomp13 => "ubicomp13",
            Format::WeAllWalk => "weallwalk",
            Format::Recipe => "recipe",
        }
    }
}

/// The phone platform a recording came from, when it matters for axis signs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Platform {
    /// Android: specific force, face up at rest z = +9.81.
    Android,
    /// iOS (Core Motion): acceleration in the opposite sign, face up at rest z = −1 g.
    Ios,
}

impl Platform {
    /// Converts an acceleration (or gravity) vector of this platform to the Android sign.
    pub fn to_android(self, v: Vector3<f64>) -> Vector3<f64> {
        match self {
            Platform::Android => v,
            Platform::Ios => -v,
        }
    }

    /// Guesses the platform from the mean acceleration including gravity, when nothing better
    /// is known (see `sensor_logger::decide_platform` for the full order of rules, and
    /// docs/formats.md): the axis with the largest mean magnitude reads +9.81 on Android when the
    /// phone lies face up (z) or stands upright (y), and −1 g on iOS. Phones are carried face up
    /// or upright far more often than face down or upside down, so a positive mean is Android.
    /// `None` when the mean is zero or not finite.
    pub fn guess(mean_accel: Vector3<f64>) -> Option<Platform> {
        let (i, _) = mean_accel.iamax_full();
        let v = mean_accel[i];
        if !v.is_finite() || v == 0.0 {
            return None;
        }
        Some(if v > 0.0 {
            Platform::Android
        } else {
            Platform::Ios
        })
    }
}

/// A ground-truth waypoint: where the walker was at a time, in a local metric frame (metres,
/// x to the right of y, as east is to north; the frame need not point north).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Waypoint {
    /// Time, s, on the log's clock.
    pub t: f64,
    /// x, m.
    pub x_m: f64,
    /// y, m.
    pub y_m: f64,
    /// Latitude and longitude, WGS84 degrees, when the truth is geodetic (then `x_m`, `y_m`
    /// are east and north of the first waypoint).
    pub geo: Option<(f64, f64)>,
    /// The floor the landmark is on, when the truth says (GetSensorData `POSI` floor ID: 0 the
    /// ground floor, −1 the one below, …). `pdr eval` scores the track's floor against it.
    pub floor: Option<i32>,
    /// The true height, m (any fixed origin), when the truth has one; `pdr eval` scores the
    /// track's height change against it. No imported format carries one today.
    pub height_m: Option<f64>,
}

/// One step reported by a truth device.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TrueStep {
    /// Time of the foot contact, s, on the log's clock.
    pub t: f64,
    /// Which foot (0 or 1), when the device tells.
    pub foot: Option<u8>,
}

/// One sample of a dense trajectory truth (motion capture): where the device was at a time, in a
/// local metric frame (metres; z up; x and y need not point east and north).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TruePosition {
    /// Time, s, on the log's clock.
    pub t: f64,
    /// x, m.
    pub x_m: f64,
    /// y, m.
    pub y_m: f64,
    /// z (up), m.
    pub z_m: f64,
}

/// One turn of the true path.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TrueTurn {
    /// When the walker leaves the straight before the turn, s, on the log's clock.
    pub t_start: f64,
    /// When the walker is on the straight after it, s.
    pub t_end: f64,
    /// The turn's angle, degrees, counter-clockwise (to the left) positive.
    pub angle_deg: f64,
}

/// Ground truth a recording carries.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Truth {
    /// The true number of steps (inside [`Truth::step_window`] when there is one).
    pub steps: Option<u64>,
    /// The span the true step count covers, s (start, end) on the log's clock, when the truth
    /// counts only part of the recording (the phone is handled outside it): only the steps
    /// found inside it are scored.
    pub step_window: Option<(f64, f64)>,
    /// The true steps one by one, when the truth device reports them (Oxford: each foot
    /// contact), in time order.
    pub step_events: Vec<TrueStep>,
    /// Waypoints (or landmarks) in time order.
    pub waypoints: Vec<Waypoint>,
    /// The walk ends where it started.
    pub loop_closure: bool,
    /// A dense trajectory (motion capture), in time order; it may have holes where the
    /// cameras lost the device.
    pub trajectory: Vec<TruePosition>,
    /// The turns of the path, in time order.
    pub turns: Vec<TrueTurn>,
    /// How the phone was carried through the whole recording, when the data set says
    /// (TyrEx's folder names; the pocket sets'); `pdr eval` scores the carrying mode of every
    /// step against it.
    pub carry: Option<crate::engine::carry::CarryMode>,
}

impl Truth {
    /// The true step count without the truth device's contact bounces, when it reports feet.
    ///
    /// The Oxford contact sensors sometimes report one foot landing twice in a row, the second
    /// time 0.18–0.41 s after the first, with the other foot's next contact then arriving a
    /// normal step after the first one: a bounce of the sensor (heel, then toe), not a step.
    /// 20 of the 284 contacts of Pixel_Jamie_Hard_SwingingArm_1 are such repeats, 14 of 280 of
    /// Pixel_Jamie_Hard_Armband_1. A contact is dropped when the previous kept contact was the
    /// same foot less than [`BOUNCE_STRIDE_SHARE`] of the median stride (same-foot interval)
    /// before it. The published count (`steps`) stays the headline figure; this one is reported
    /// beside it.
    pub fn steps_debounced(&self) -> Option<u64> {
        self.step_times_debounced().map(|t| t.len() as u64)
    }

    /// The times of the true steps without the contact bounces ([`Truth::steps_debounced`]),
    /// s, when the truth device reports feet.
    pub fn step_times_debounced(&self) -> Option<Vec<f64>> {
        let ev = &self.step_events;
        if ev.is_empty() || ev.iter().any(|e| e.foot.is_none()) {
            return None;
        }
        let mut strides: Vec<f64> = (0..2u8)
            .flat_map(|f| {
                let t: Vec<f64> = ev
                    .iter()
                    .filter(|e| e.foot == Some(f))
                    .map(|e| e.t)
                    .collect();
                t.windows(2).map(|w| w[1] - w[0]).collect::<Vec<_>>()
            })
            .collect();
        crate::engine::sort::sort_by(&mut strides, f64::total_cmp);
        let Some(&median) = strides.get(strides.len() / 2) else {
            return Some(ev.iter().map(|e| e.t).collect());
        };
        let mut kept: Vec<TrueStep> = Vec::with_capacity(ev.len());
        for e in ev {
            match kept.last() {
                Some(p) if p.foot == e.foot && e.t - p.t < BOUNCE_STRIDE_SHARE * median => {}
                _ => kept.push(*e),
            }
        }
        Some(kept.iter().map(|e| e.t).collect())
    }
}

/// See [`Truth::steps_debounced`]: a same-foot repeat closer than this share of the median
/// stride is a bounce. 0.6: bounces come at 0.2–0.4 of a stride, a missed contact of the other
/// foot makes a repeat of about one stride.
pub const BOUNCE_STRIDE_SHARE: f64 = 0.6;

/// One recording, read.
#[derive(Debug, Clone)]
pub struct Log {
    /// Where it came from (path, or path inside a zip), for reports.
    pub source: String,
    /// Its format.
    pub format: Format,
    /// The platform, when known or detected.
    pub platform: Option<Platform>,
    /// The engine's records, in time order.
    pub records: Vec<Record>,
    /// Ground truth carried by the file.
    pub truth: Truth,
    /// Lines skipped, at most [`MAX_WARNINGS`] of them (see `skipped`).
    pub warnings: Vec<ParseError>,
    /// Number of lines skipped in total.
    pub skipped: u64,
    /// The condition the recording belongs to within its data set, for per-group figures
    /// (Oxford: where the phone was carried, e.g. `FrontPocket`).
    pub group: Option<String>,
    /// The name of the [`recipe`] the log was read with, if any.
    pub recipe: Option<String>,
    /// The recipe's sanity warnings about the files (a likely wrong unit or column, see
    /// [`recipe::check`]), each naming its file; empty for the other formats.
    pub checks: Vec<String>,
    /// When the recording was made, Unix seconds: the time its format gives for the start
    /// (GetSensorData's `Date of creation`, phyphox's `meta/time.csv`, a pdr-log's `# date`
    /// line), else its first time when the log's clock is Unix time (Sensor Logger, GnssLogger,
    /// Microsoft Indoor, live recordings). `None` when nothing says. The World Magnetic Model
    /// needs it for the declination ([`Log::dated`]); a day's accuracy is plenty.
    pub date_unix_s: Option<f64>,
}

impl Log {
    /// An empty log of a format.
    pub fn new(source: impl Into<String>, format: Format) -> Self {
        Log {
            source: source.into(),
            format,
            platform: None,
            records: Vec::new(),
            truth: Truth::default(),
            warnings: Vec::new(),
            skipped: 0,
            group: None,
            recipe: None,
            checks: Vec::new(),
            date_unix_s: None,
        }
    }

    /// `cfg` with the log's date for the declination ([`Log::date_unix_s`]), unless `cfg`
    /// already sets one (`fusion.date_unix_s`). Every path that runs an imported log through the
    /// engine (`pdr run`, `pdr eval`, the upload page) builds its pipeline with this.
    pub fn dated(&self, cfg: &crate::engine::PipelineConfig) -> crate::engine::PipelineConfig {
        let mut cfg = cfg.clone();
        if cfg.fusion.date_unix_s.is_none() {
            cfg.fusion.date_unix_s = self.date_unix_s;
        }
        cfg
    }

    /// Records a skipped line.
    pub fn warn(&mut self, e: ParseError) {
        self.skipped += 1;
        if self.warnings.len() < MAX_WARNINGS {
            self.warnings.push(e);
        }
    }

    /// Number of IMU samples.
    pub fn imu_samples(&self) -> usize {
        self.records
            .iter()
            .filter(|r| matches!(r, Record::Imu(_)))
            .count()
    }

    /// The GNSS fixes, in time order.
    pub fn fixes(&self) -> impl Iterator<Item = &GnssFix> {
        self.records.iter().filter_map(|r| match r {
            Record::Gnss(f) => Some(f),
            _ => None,
        })
    }

    /// The truth waypoints that are geodetic (latitude and longitude).
    pub fn geodetic_waypoints(&self) -> impl Iterator<Item = &Waypoint> {
        self.truth.waypoints.iter().filter(|w| w.geo.is_some())
    }

    /// First and last record time, s.
    pub fn time_span(&self) -> Option<(f64, f64)> {
        Some((self.records.first()?.t(), self.records.last()?.t()))
    }
}

/// Per-sensor streams of one recording on the log's clock, before merging.
#[derive(Debug, Clone, Default)]
pub struct Streams {
    /// Acceleration including gravity, Android sign, m/s².
    pub accel: Vec<(f64, Vector3<f64>)>,
    /// Angular rate, rad/s.
    pub gyro: Vec<(f64, Vector3<f64>)>,
    /// Magnetic field, µT.
    pub mag: Vec<(f64, Vector3<f64>)>,
    /// Device → ENU orientation.
    pub orientation: Vec<(f64, UnitQuaternion<f64>)>,
    /// GNSS fixes.
    pub fixes: Vec<GnssFix>,
    /// Barometer readings, hPa (each checked by [`PressureSample::check`] by its reader).
    pub pressure: Vec<PressureSample>,
}

/// Carries the latest sample of a stream forward to later times.
struct Hold<'a, T: Copy> {
    items: &'a [(f64, T)],
    next: usize,
}

impl<'a, T: Copy> Hold<'a, T> {
    fn at(&mut self, t: f64) -> Option<T> {
        while self.next < self.items.len() && self.items[self.next].0 <= t {
            self.next += 1;
        }
        let k = self.next.checked_sub(1)?;
        let (ti, v) = self.items[k];
        (t - ti <= HOLD_S).then_some(v)
    }
}

impl Streams {
    /// Merges the streams into records in time order: one IMU record per accelerometer sample,
    /// with the latest gyroscope, magnetometer and orientation samples at most [`HOLD_S`] old, and
    /// the fixes and barometer readings in between (a fix or reading at the time of an IMU sample
    /// comes before it; fixes before readings of the same time). Each stream is sorted by time first (stable), since some recorders
    /// write a few samples out of order.
    pub fn into_records(mut self) -> Vec<Record> {
        let by_t = |a: &(f64, Vector3<f64>), b: &(f64, Vector3<f64>)| a.0.total_cmp(&b.0);
        crate::engine::sort::sort_by(&mut self.accel, by_t);
        crate::engine::sort::sort_by(&mut self.gyro, by_t);
        crate::engine::sort::sort_by(&mut self.mag, by_t);
        crate::engine::sort::sort_by(&mut self.orientation, |a, b| a.0.total_cmp(&b.0));
        crate::engine::sort::sort_by(&mut self.fixes, |a, b| a.t.total_cmp(&b.t));
        crate::engine::sort::sort_by(&mut self.pressure, |a, b| a.t.total_cmp(&b.t));
        let mut gyro = Hold {
            items: &self.gyro,
            next: 0,
        };
        let mut mag = Hold {
            items: &self.mag,
            next: 0,
        };
        let mut orientation = Hold {
            items: &self.orientation,
            next: 0,
        };
        let mut out = Vec::with_capacity(self.accel.len() + self.fixes.len() + self.pressure.len());
        let mut fixes = self.fixes.iter().peekable();
        let mut pressure = self.pressure.iter().peekable();
        for &(t, a) in &self.accel {
            // The fixes and readings up to this sample, the earlier first (a fix first at a tie).
            loop {
                let tf = fixes.peek().map(|f| f.t).filter(|&x| x <= t);
                let tp = pressure.peek().map(|p| p.t).filter(|&x| x <= t);
                match (tf, tp) {
                    (Some(a), Some(b)) if b < a => {
                        out.extend(pressure.next().copied().map(Record::Pressure))
                    }
                    (Some(_), _) => out.extend(fixes.next().copied().map(Record::Gnss)),
                    (None, Some(_)) => out.extend(pressure.next().copied().map(Record::Pressure)),
                    (None, None) => break,
                }
            }
            out.push(Record::Imu(ImuSample {
                t,
                accel: a,
                gyro: gyro.at(t),
                mag: mag.at(t),
                orientation: orientation.at(t),
            }));
        }
        // After the last IMU sample: the rest of both, in time order.
        let mut rest: Vec<Record> = fixes
            .map(|f| Record::Gnss(*f))
            .chain(pressure.map(|p| Record::Pressure(*p)))
            .collect();
        crate::engine::sort::sort_by(&mut rest, |a, b| a.t().total_cmp(&b.t()));
        out.extend(rest);
        out
    }
}

/// Parses a number, accepting a decimal comma (`9,81`) and surrounding quotes or spaces.
pub fn number(s: &str) -> Option<f64> {
    let s = s.trim().trim_matches('"').trim();
    if let Ok(v) = s.parse::<f64>() {
        return v.is_finite().then_some(v);
    }
    if s.contains(',') && !s.contains('.') {
        return number(&s.replace(',', "."));
    }
    None
}

/// Reads every recognisable log in a file set. Unrecognised files are ignored; the result is
/// empty when nothing was recognised. A log that fails to read is an `Err` in the list, and
/// never stops the others.
pub fn import_all(set: &mut dyn FileSet) -> Vec<Result<Log, ParseError>> {
    import_with(set, &[])
}

/// [`import_all`] with the user's recipes: a folder that a recipe matches
/// ([`recipe::Recipe::match_dir`]) is read by the first one that does, before any format is
/// sniffed, so a recipe also overrides a format we would otherwise recognise. The report's
/// sanity warnings are kept in [`Log::checks`]; [`recipe::read_dir`] gives the whole report.
pub fn import_with(
    set: &mut dyn FileSet,
    recipes: &[recipe::Recipe],
) -> Vec<Result<Log, ParseError>> {
    let mut out = Vec::new();
    let names: Vec<String> = set.names().to_vec();
    let mut used = vec![false; names.len()];
    // Folder formats first: each folder holding their files is one log.
    let mut dirs: Vec<&str> = names.iter().map(|n| fileset::parent(n)).collect();
    dirs.sort_unstable();
    dirs.dedup();
    for dir in dirs {
        if let Some((files, read)) = read_folder(set, &names, dir, recipes) {
            for (i, n) in names.iter().enumerate() {
                used[i] |= files.contains(n);
            }
            out.push(read);
        }
    }
    // Then every remaining file on its own.
    for (i, name) in names.iter().enumerate() {
        if !used[i] {
            read_file(set, name, recipes, &mut out);
        }
    }
    for log in out.iter_mut().flatten() {
        if log.date_unix_s.is_none() {
            log.date_unix_s = date::from_clock(log.records.first().map(Record::t));
        }
    }
    out
}

/// Reads folder `dir` of `names` as one log when a recipe or a folder format recognises it:
/// the files it consumed and the log. `None` when none does.
fn read_folder(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
    recipes: &[recipe::Recipe],
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    for r in recipes {
        if let Some((files, read)) = recipe::read_dir(set, names, dir, r, None) {
            let read = read.map(|(mut log, report)| {
                log.checks = report.warnings;
                log
            });
            return Some((files, read));
        }
    }
    let in_dir = |f: &str| names.iter().any(|n| n.as_str() == format!("{dir}{f}"));
    if in_dir("accelerometer.csv") && in_dir("stepcounter.csv") {
        let read = oxford::read_oxford(set, dir);
        let files = names
            .iter()
            .filter(|n| {
                fileset::parent(n) == dir && oxford::OXFORD_FILES.contains(&fileset::base(n))
            })
            .cloned()
            .collect();
        return Some((files, read));
    }
    // The data sets' folders, Sensor Logger and phyphox: each reader names the files it
    // consumed.
    tyrex::read_dir(set, names, dir)
        .or_else(|| ubicomp13::read_dir(set, names, dir))
        .or_else(|| weallwalk::read_dir(set, names, dir))
        .or_else(|| sensor_logger::read_dir(set, names, dir))
        .or_else(|| phyphox::read_dir(set, names, dir))
}

/// Reads file `name` on its own into `out`: the logs of a zip archive, the log of a
/// single-file format, an error when it cannot be read, nothing when it is not recognised.
fn read_file(
    set: &mut dyn FileSet,
    name: &str,
    recipes: &[recipe::Recipe],
    out: &mut Vec<Result<Log, ParseError>>,
) {
    let head = match set.head(name) {
        Ok(h) => h,
        Err(e) => {
            out.push(Err(file_error(&set.label(name), 0, e.to_string())));
            return;
        }
    };
    if fileset::is_zip(head.as_bytes()) {
        out.extend(import_zip(set, name, recipes));
        return;
    }
    let Some(format) = sniff(&head) else {
        return;
    };
    let label = set.label(name);
    let records = match (format, set.size(name)) {
        (Format::PdrLog, Some(size)) => crate::io::lines::estimate_records(&head, size),
        _ => 0,
    };
    let r = match set.open(name) {
        Err(e) => Err(file_error(&label, 0, e.to_string())),
        Ok(reader) => match format {
            Format::PdrLog => {
                crate::io::pdrlog::read_sized(reader, &label, records).map(|p| pdr_log(p, &label))
            }
            Format::MsIndoor => ms_indoor::read_ms_indoor(reader, &label),
            Format::XioFoot => xio::read_xio(reader, &label),
            Format::SensorLoggerJson => sensor_logger::read_json(reader, &label),
            Format::GnssLogger => gnss_logger::read(reader, &label),
            Format::GetSensorData => get_sensor_data::read(reader, &label),
            _ => Err(file_error(&label, 0, "format not supported yet")),
        },
    };
    out.push(r);
}

/// A pdr-log read by [`crate::io::pdrlog`] as a log named `label`.
fn pdr_log(p: crate::io::pdrlog::Parsed, label: &str) -> Log {
    let mut log = Log::new(label, Format::PdrLog);
    log.records = p.records;
    log.date_unix_s = p.date_unix_s;
    let extra = p.skipped.saturating_sub(p.errors.len() as u64);
    for e in p.errors {
        log.warn(e);
    }
    log.skipped += extra;
    log
}

/// Reads the logs of a zip archive found inside a file set, within the [`ArchiveLimits`]. An
/// archive on disk or in memory (an upload) is read in place; one inside another archive as a
/// stream ([`StreamZipSet`]). Its members are decompressed as they are read. A limit hit by
/// the archive as a whole is one error naming it; one hit by a member is that member's error.
/// The recipes apply inside the archive as outside.
fn import_zip(
    set: &mut dyn FileSet,
    name: &str,
    recipes: &[recipe::Recipe],
) -> Vec<Result<Log, ParseError>> {
    let label = set.label(name);
    let depth = set.depth() + 1;
    let budget = set
        .budget()
        .unwrap_or_else(|| Budget::new(ArchiveLimits::default()));
    let refused = |e: std::io::Error| {
        let message = match LimitHit::of(&e) {
            Some(hit) => format!("refused: {hit}"),
            None => format!("unreadable zip archive: {e}"),
        };
        vec![Err(file_error(&label, 0, message))]
    };
    if let Some(r) = set.open_seekable(name) {
        return match r.and_then(|r| ZipSet::within(r, &label, depth, budget.clone())) {
            Ok(mut zip) => import_with(&mut zip, recipes),
            Err(e) => refused(e),
        };
    }
    match StreamZipSet::new(set, name, depth, budget) {
        Ok(mut zip) => import_with(&mut zip, recipes),
        Err(e) => refused(e),
    }
}

/// Recognises a single-file format from its first bytes.
pub fn sniff(head: &str) -> Option<Format> {
    let first = head
        .lines()
        .next()
        .unwrap_or("")
        .trim_start_matches('\u{feff}');
    if first.starts_with(crate::io::pdrlog::HEADER) {
        return Some(Format::PdrLog);
    }
    if head.contains("\tTYPE_") || (first.starts_with("#\t") && head.contains("SiteID:")) {
        return Some(Format::MsIndoor);
    }
    if first.starts_with("Time (s),Gyroscope X (deg/s)") {
        return Some(Format::XioFoot);
    }
    if sensor_logger::looks_like_json(head) {
        return Some(Format::SensorLoggerJson);
    }
    if gnss_logger::looks_like(head) {
        return Some(Format::GnssLogger);
    }
    if get_sensor_data::looks_like(head) {
        return Some(Format::GetSensorData);
    }
    None
}
