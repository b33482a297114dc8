//! The fuzz targets' bodies and the checks they share. Each `fuzz_targets/<name>.rs` calls the
//! function of the same name here; `tests/fuzz_regressions.rs` in the main crate includes this
//! file (`#[path]`) and replays the saved crash inputs through the same functions, without the
//! fuzzer.
//!
//! The property every target checks: no panic, and no NaN or infinity in anything the engine
//! receives (every `f64` of every `Record` of every imported `Log`, and the truth), nor in what
//! the live session shows (where it says "none" it is `None`, never NaN).
//!
//! Folder formats take several files from one input: the input is split at NUL bytes (a CSV
//! holds none), and the pieces are the files named in the target's list, in order.

use pdr::engine::types::{GnssFix, ImuSample};
use pdr::engine::{PipelineConfig, Record};
use pdr::io::import::{self, Log, MemSet};
use pdr::io::ParseError;
use pdr::live::{LiveSession, MotionEvent, OrientationEvent, Platform, SensorReading};

/// Every target, by name (the names of `fuzz_targets/*.rs`).
pub const TARGETS: [&str; 17] = [
    "pdrlog",
    "sniff",
    "sensor_logger_csv",
    "sensor_logger_json",
    "phyphox",
    "gnss_logger",
    "get_sensor_data",
    "oxford",
    "ms_indoor",
    "xio",
    "profile_json",
    "live",
    "zip",
    "recipe",
    "tyrex",
    "ubicomp13",
    "weallwalk",
];

/// Runs the target `name` on `data`. Panics (the finding) when a check fails.
pub fn run(name: &str, data: &[u8]) {
    match name {
        "pdrlog" => pdrlog(data),
        "sniff" => sniff(data),
        "sensor_logger_csv" => sensor_logger_csv(data),
        "sensor_logger_json" => sensor_logger_json(data),
        "phyphox" => phyphox(data),
        "gnss_logger" => gnss_logger(data),
        "get_sensor_data" => get_sensor_data(data),
        "oxford" => oxford(data),
        "ms_indoor" => ms_indoor(data),
        "xio" => xio(data),
        "profile_json" => profile_json(data),
        "live" => live(data),
        "zip" => zip(data),
        "recipe" => recipe(data),
        "tyrex" => tyrex(data),
        "ubicomp13" => ubicomp13(data),
        "weallwalk" => weallwalk(data),
        _ => panic!("no fuzz target `{name}`"),
    }
}

// ---------------------------------------------------------------------------------------------
// Checks.

fn finite(what: &str, v: f64) {
    assert!(v.is_finite(), "{what} is not finite: {v}");
}

fn finite_opt(what: &str, v: Option<f64>) {
    if let Some(v) = v {
        finite(what, v);
    }
}

/// Every `f64` of a record is finite.
pub fn check_record(r: &Record) {
    match r {
        Record::Imu(ImuSample {
            t,
            accel,
            gyro,
            mag,
            orientation,
        })
        | Record::Foot(ImuSample {
            t,
            accel,
            gyro,
            mag,
            orientation,
        }) => {
            finite("imu.t", *t);
            accel.iter().for_each(|&v| finite("imu.accel", v));
            gyro.iter()
                .flat_map(|g| g.iter())
                .for_each(|&v| finite("imu.gyro", v));
            mag.iter()
                .flat_map(|m| m.iter())
                .for_each(|&v| finite("imu.mag", v));
            if let Some(q) = orientation {
                q.coords.iter().for_each(|&v| finite("imu.orientation", v));
            }
        }
        Record::Gnss(f) => check_fix(f),
        Record::Gap(a, b) => {
            finite("gap.t0", *a);
            finite("gap.t1", *b);
        }
        Record::Pressure(p) => {
            finite("pressure.t", p.t);
            finite("pressure.hpa", p.hpa);
        }
    }
}

fn check_fix(f: &GnssFix) {
    finite("fix.t", f.t);
    finite("fix.lat", f.lat_deg);
    finite("fix.lon", f.lon_deg);
    finite("fix.h_accuracy", f.h_accuracy_m);
    finite_opt("fix.altitude", f.altitude_m);
    finite_opt("fix.speed", f.speed_mps);
    finite_opt("fix.bearing", f.bearing_deg);
}

fn check_error(e: &ParseError) {
    assert!(!e.message.is_empty(), "an error without a message: {e:?}");
}

/// An imported log: its records and truth are finite, its warnings bounded.
pub fn check_log(log: &Log) {
    log.records.iter().for_each(check_record);
    for w in &log.truth.waypoints {
        finite("waypoint.t", w.t);
        finite("waypoint.x", w.x_m);
        finite("waypoint.y", w.y_m);
        if let Some((lat, lon)) = w.geo {
            finite("waypoint.lat", lat);
            finite("waypoint.lon", lon);
        }
    }
    for s in &log.truth.step_events {
        finite("step_event.t", s.t);
    }
    if let Some((a, b)) = log.truth.step_window {
        finite("step_window.start", a);
        finite("step_window.end", b);
    }
    for p in &log.truth.trajectory {
        finite("trajectory.t", p.t);
        finite("trajectory.x", p.x_m);
        finite("trajectory.y", p.y_m);
        finite("trajectory.z", p.z_m);
    }
    for t in &log.truth.turns {
        finite("turn.t_start", t.t_start);
        finite("turn.t_end", t.t_end);
        finite("turn.angle", t.angle_deg);
    }
    let _ = log.truth.steps_debounced();
    assert!(log.warnings.len() <= import::MAX_WARNINGS);
    assert!(log.skipped >= log.warnings.len() as u64);
    log.warnings.iter().for_each(check_error);
    let _ = log.time_span();
}

fn check_result(r: &Result<Log, ParseError>) {
    match r {
        Ok(log) => check_log(log),
        Err(e) => check_error(e),
    }
}

/// Reads a set of files as `import_all` does, and checks every log.
fn import_files(files: Vec<(String, Vec<u8>)>) {
    let mut set = MemSet::new(files);
    for r in import::import_all(&mut set) {
        check_result(&r);
    }
}

/// The input split at NUL bytes into the files `names`, in order; an empty piece is a file
/// that is absent.
fn split_files(dir: &str, names: &[&str], data: &[u8]) -> Vec<(String, Vec<u8>)> {
    names
        .iter()
        .zip(data.split(|&b| b == 0))
        .filter(|(_, d)| !d.is_empty())
        .map(|(n, d)| (format!("{dir}{n}"), d.to_vec()))
        .collect()
}

/// Whether the input is (or starts like) a zip archive: archives are not fuzzed here (their
/// handling is being rewritten with limits).
fn is_zip(data: &[u8]) -> bool {
    data.starts_with(b"PK")
}

// ---------------------------------------------------------------------------------------------
// Targets.

/// The pdr-log reader, then the records through a live session resumed from the text (the
/// engine, as after a reload).
pub fn pdrlog(data: &[u8]) {
    match pdr::io::pdrlog::read(data, "fuzz.pdrlog") {
        Ok(p) => {
            p.records.iter().for_each(check_record);
            // One more: the notice that records were put back in time order.
            assert!(p.errors.len() <= import::MAX_WARNINGS + 1);
            p.errors.iter().for_each(check_error);
        }
        Err(e) => check_error(&e),
    }
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(mut s) =
            LiveSession::resume(PipelineConfig::default(), Platform::Android, 0.0, text)
        {
            check_session(&mut s);
        }
    }
}

/// The names the sniffing target gives its one file (chosen by the input's first byte).
const SNIFF_NAMES: [&str; 8] = [
    "log.txt",
    "walk.pdrlog",
    "export.json",
    "trace.csv",
    "Accelerometer.csv",
    "Raw Data.csv",
    "accelerometer.csv",
    "dir/gnss_log.txt",
];

/// Format sniffing, and `import_all` over a set of one file.
pub fn sniff(data: &[u8]) {
    let Some((&k, body)) = data.split_first() else {
        return;
    };
    if is_zip(body) {
        return;
    }
    let name = SNIFF_NAMES[k as usize % SNIFF_NAMES.len()];
    let head = String::from_utf8_lossy(&body[..body.len().min(import::fileset::HEAD_BYTES)]);
    let _ = import::sniff(&head);
    import_files(vec![(name.to_string(), body.to_vec())]);
}

/// The files of a Sensor Logger CSV folder, in the order the input gives them.
pub const SENSOR_LOGGER_FILES: [&str; 8] = [
    "Accelerometer.csv",
    "Gyroscope.csv",
    "Magnetometer.csv",
    "Orientation.csv",
    "Gravity.csv",
    "Location.csv",
    "Metadata.csv",
    "TotalAcceleration.csv",
];

/// Sensor Logger's CSV folder.
pub fn sensor_logger_csv(data: &[u8]) {
    import_files(split_files("rec/", &SENSOR_LOGGER_FILES, data));
}

/// Sensor Logger's JSON export.
pub fn sensor_logger_json(data: &[u8]) {
    check_result(&import::sensor_logger::read_json(data, "fuzz.json"));
}

/// The files of a phyphox export, in the order the input gives them.
pub const PHYPHOX_FILES: [&str; 7] = [
    "Accelerometer.csv",
    "Gyroscope.csv",
    "Magnetometer.csv",
    "Location.csv",
    "meta/device.csv",
    "meta/time.csv",
    "Raw Data.csv",
];

/// phyphox's CSV export.
pub fn phyphox(data: &[u8]) {
    import_files(split_files("exp/", &PHYPHOX_FILES, data));
}

/// Google GnssLogger `.txt`.
pub fn gnss_logger(data: &[u8]) {
    check_result(&import::gnss_logger::read(data, "gnss_log.txt"));
}

/// GetSensorData `.txt`.
pub fn get_sensor_data(data: &[u8]) {
    check_result(&import::get_sensor_data::read(data, "gsd.txt"));
}

/// The files of an Oxford trace folder, in the order the input gives them.
pub const OXFORD_FILES: [&str; 3] = ["accelerometer.csv", "stepcounter.csv", "stats.csv"];

/// An Oxford Step Counter trace folder.
pub fn oxford(data: &[u8]) {
    import_files(split_files(
        "Pixel_Fuzz_Hard_FrontPocket_1/",
        &OXFORD_FILES,
        data,
    ));
}

/// The files of a TyrEx recording folder, in the order of the input's pieces: both layouts'.
pub const TYREX_FILES: [&str; 10] = [
    "accelerometer.txt",
    "gyroscope-calibrated.txt",
    "gyroscope.txt",
    "magnetometer-calibrated.txt",
    "magnetometer.txt",
    "rotation-vector.txt",
    "attitude.txt",
    "record.properties",
    "description.txt",
    "truth.csv",
];

/// A TyrEx recording folder (Android or iOS, as the marker file among the pieces says).
pub fn tyrex(data: &[u8]) {
    import_files(split_files(
        "Fuzz_Nexus5_NoDist_FrontPocket/",
        &TYREX_FILES,
        data,
    ));
}

/// The files of a UbiComp 2013 walk folder, in the order of the input's pieces.
pub const UBICOMP13_FILES: [&str; 4] = ["acc.csv", "gyr.csv", "mag.csv", "truth.json"];

/// A UbiComp 2013 walk folder.
pub fn ubicomp13(data: &[u8]) {
    import_files(split_files(
        "p0.1_Fuzz_20-29_170-179cm_Trousers_front_pocket/",
        &UBICOMP13_FILES,
        data,
    ));
}

/// The files of a WeAllWalk walk folder, in the order of the input's pieces.
pub const WEALLWALK_FILES: [&str; 3] = ["sensors.csv", "steps.csv", "segments.csv"];

/// A WeAllWalk walk folder.
pub fn weallwalk(data: &[u8]) {
    import_files(split_files("T1_ID0_1L/", &WEALLWALK_FILES, data));
}

/// Microsoft Indoor Location 2.0 trace.
pub fn ms_indoor(data: &[u8]) {
    check_result(&import::ms_indoor::read_ms_indoor(data, "trace.txt"));
}

/// x-io Gait-Tracking CSV.
pub fn xio(data: &[u8]) {
    check_result(&import::xio::read_xio(data, "xio.csv"));
}

/// The step-length profile's JSON import: a profile that is accepted gives finite lengths
/// within its bounds, writes back to JSON that reads the same, and refines to a valid profile.
pub fn profile_json(data: &[u8]) {
    use pdr::engine::calibration::ProfileFile;
    use pdr::engine::fusion::GnssVerdict;
    use pdr::engine::refinement::{refine, WalkEvidence};
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(p) = ProfileFile::from_json(text) else {
        return;
    };
    let prof = &p.profile;
    for f in [0.0, 0.3, 1.0, 1.8, 2.45, 3.0, 5.0, 1e6] {
        let l = prof.length(f);
        finite("profile.length", l);
    }
    let _ = p.describe();
    let json = p.to_json().expect("an accepted profile writes to JSON");
    let back = ProfileFile::from_json(&json).expect("a written profile reads back");
    assert_eq!(back, p, "the profile changed through JSON");
    let walk = WalkEvidence {
        fixes: 40,
        fixes_used: 40,
        verdict: Some(GnssVerdict::Calibrated),
        scale: Some((1.1, 0.01)),
        step_freqs_hz: vec![1.8; 60],
    };
    if let Ok(r) = refine(&p, &walk) {
        r.file
            .profile
            .validate()
            .expect("a refined profile is valid");
        finite("refined.offset", r.offset_m.1);
    }
    let cfg = PipelineConfig {
        step_length: pdr::engine::step_length::StepLengthModel::Frequency(p.profile.clone()),
        ..PipelineConfig::default()
    };
    cfg.validate()
        .expect("an accepted profile is a valid configuration");
}

// ---------------------------------------------------------------------------------------------
// The live session.

/// A byte decoder for the live target's events.
struct Bytes<'a> {
    d: &'a [u8],
    /// The last time read, ms (times may be given relative to it).
    t_ms: f64,
}

/// Values a tag byte 1..=15 stands for.
const SPECIAL: [f64; 15] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    1e300,
    -1e300,
    5e-324,
    1e-300,
    9.81,
    -9.81,
    1.0,
];

impl Bytes<'_> {
    fn u8(&mut self) -> Option<u8> {
        let (&b, rest) = self.d.split_first()?;
        self.d = rest;
        Some(b)
    }

    fn raw(&mut self) -> Option<f64> {
        let (b, rest) = self.d.split_first_chunk::<8>()?;
        self.d = rest;
        Some(f64::from_le_bytes(*b))
    }

    /// A value: tag 0 then 8 bytes (little-endian f64), 1..=15 a special value, else a small
    /// number (tag − 136) / 8.
    fn f64(&mut self) -> Option<f64> {
        match self.u8()? {
            0 => self.raw(),
            t @ 1..=15 => Some(SPECIAL[t as usize - 1]),
            t => Some((f64::from(t) - 136.0) / 8.0),
        }
    }

    /// A time, ms: tag 0 then an absolute f64, 1..=15 a special value, 16..=127 the last time
    /// plus 0..=111 ms (0: a duplicate), 128..=191 minus 0..=63 ms (backwards), 192..=255 plus
    /// 2^0..2^63 s (gaps).
    fn time(&mut self) -> Option<f64> {
        let t = match self.u8()? {
            0 => self.raw()?,
            t @ 1..=15 => SPECIAL[t as usize - 1],
            t @ 16..=127 => self.t_ms + f64::from(t - 16),
            t @ 128..=191 => self.t_ms - f64::from(t - 128),
            t => self.t_ms + 1000.0 * (1u64 << (t - 192)) as f64,
        };
        self.t_ms = t;
        Some(t)
    }

    fn vec3(&mut self) -> Option<[f64; 3]> {
        Some([self.f64()?, self.f64()?, self.f64()?])
    }

    fn opt(&mut self, present: bool) -> Option<Option<f64>> {
        Some(if present { Some(self.f64()?) } else { None })
    }
}

/// The live session's event input: the input decoded into a sequence of events (see
/// [`Bytes`]), each pushed into a session, with the session's outputs checked now and then and
/// at the end. First byte: the platform (bit 0) and whether a time origin follows (bit 1).
pub fn live(data: &[u8]) {
    let mut b = Bytes { d: data, t_ms: 0.0 };
    let Some(head) = b.u8() else { return };
    let platform = if head & 1 == 0 {
        Platform::Android
    } else {
        Platform::Ios
    };
    let origin = if head & 2 != 0 {
        b.f64().unwrap_or(0.0)
    } else {
        0.0
    };
    let mut s = LiveSession::new(PipelineConfig::default(), platform, origin)
        .expect("the default configuration is valid");
    let mut log = String::new();
    while let Some(op) = b.u8() {
        let done = match op % 9 {
            0 => (|| {
                let t = b.time()?;
                let flags = b.u8()?;
                let accel = if flags & 1 != 0 {
                    Some(b.vec3()?)
                } else {
                    None
                };
                let rot = if flags & 2 != 0 {
                    Some(b.vec3()?)
                } else {
                    None
                };
                let _ = s.push_motion(&MotionEvent {
                    time_stamp_ms: t,
                    accel,
                    rotation_rate_deg_s: rot,
                });
                Some(())
            })(),
            1 => (|| {
                let t = b.time()?;
                let accel = b.vec3()?;
                let flags = b.u8()?;
                let gyro = if flags & 1 != 0 {
                    Some(b.vec3()?)
                } else {
                    None
                };
                let _ = s.push_sensor(&SensorReading {
                    timestamp_ms: t,
                    accel,
                    gyro_rad_s: gyro,
                });
                Some(())
            })(),
            2 => (|| {
                let t = b.time()?;
                let flags = b.u8()?;
                let ev = OrientationEvent {
                    time_stamp_ms: t,
                    alpha: b.opt(flags & 1 != 0)?,
                    beta: b.opt(flags & 2 != 0)?,
                    gamma: b.opt(flags & 4 != 0)?,
                    absolute: flags & 8 != 0,
                    compass_heading_deg: b.opt(flags & 16 != 0)?,
                    screen_angle_deg: if flags & 32 != 0 { b.f64()? } else { 0.0 },
                };
                s.push_orientation(&ev);
                Some(())
            })(),
            3 => (|| {
                let t = b.time()?;
                let q = [b.f64()?, b.f64()?, b.f64()?, b.f64()?];
                s.push_quaternion(t, q);
                Some(())
            })(),
            4 => (|| {
                // Geolocation times are in seconds on the page's clock.
                let t = b.time()? * 1e-3;
                let (lat, lon, acc) = (b.f64()?, b.f64()?, b.f64()?);
                let flags = b.u8()?;
                let f = GnssFix {
                    t,
                    lat_deg: lat,
                    lon_deg: lon,
                    h_accuracy_m: acc,
                    altitude_m: b.opt(flags & 1 != 0)?,
                    speed_mps: b.opt(flags & 2 != 0)?,
                    bearing_deg: b.opt(flags & 4 != 0)?,
                };
                let _ = s.push_fix(&f);
                Some(())
            })(),
            5 => (|| {
                let t0 = b.time()?;
                let t1 = b.time()?;
                s.mark_gap(t0, t1);
                Some(())
            })(),
            6 => {
                check_readouts(&s);
                Some(())
            }
            7 => {
                log.push_str(&s.take_log());
                Some(())
            }
            _ => {
                check_views(&mut s);
                Some(())
            }
        };
        if done.is_none() {
            break;
        }
    }
    check_session(&mut s);
    log.push_str(&s.take_log());
    // The recording reads back, every record of it finite.
    let p = pdr::io::pdrlog::read(log.as_bytes(), "live recording")
        .expect("the live recording is a readable pdr-log");
    p.records.iter().for_each(check_record);
    assert_eq!(
        p.skipped, 0,
        "the live recording has bad lines: {:?}",
        p.errors
    );
}

fn check_readouts(s: &LiveSession) {
    let r = s.readouts();
    finite("readouts.distance_m", r.distance_m);
    finite_opt("readouts.cadence_hz", r.cadence_hz);
    finite_opt("readouts.heading_deg", r.heading_deg);
    finite_opt("readouts.gnss_accuracy_m", r.gnss_accuracy_m);
    finite("readouts.sample_rate_hz", r.sample_rate_hz);
    finite("readouts.duration_s", r.duration_s);
    if let Some((a, b)) = r.gnss_on_s {
        finite("readouts.gnss_on_s", a);
        finite("readouts.gnss_on_s", b);
    }
    if let Some((a, b)) = r.fusion_scale {
        finite("readouts.fusion_scale", a);
        finite("readouts.fusion_scale", b);
    }
}

fn check_views(s: &mut LiveSession) {
    let m = s.map_data();
    for &(e, n) in m
        .pdr
        .iter()
        .chain(&m.fused)
        .chain(&m.smoothed)
        .chain(&m.gaps)
    {
        finite("map.east", e);
        finite("map.north", n);
    }
    for &(e, n, a) in &m.fixes {
        finite("map.fix.east", e);
        finite("map.fix.north", n);
        finite("map.fix.accuracy", a);
    }
    finite_opt("map.heading_rad", m.heading_rad);
    let sc = s.scope_data();
    finite("scope.now", sc.now);
    for &(t, up, pll) in &sc.samples {
        finite("scope.t", t);
        finite("scope.up", up);
        finite_opt("scope.pll", pll);
    }
    sc.steps.iter().for_each(|&t| finite("scope.step", t));
}

/// A session's readouts, track, fused track and views are finite.
fn check_session(s: &mut LiveSession) {
    check_readouts(s);
    check_views(s);
    let p = s.pipeline();
    for st in p.track() {
        finite("step.t", st.t);
        finite("step.east", st.east_m);
        finite("step.north", st.north_m);
        finite_opt("step.heading", st.heading_rad);
        finite_opt("step.step_heading", st.step_heading_rad);
        finite("step.length", st.length_m);
        finite("step.freq", st.freq_hz);
    }
    for f in p.fused() {
        finite("fused.east", f.east_m);
        finite("fused.north", f.north_m);
        finite("fused.scale", f.scale);
    }
    p.fixes().iter().for_each(check_fix);
    let _ = s.walk_evidence();
    finite("fix_path_m", s.fix_path_m(20.0));
}

/// A zip archive as an upload (read in place by the zip crate, within the archive limits), and
/// the same bytes as a zip inside a stored zip (read as a stream from its local headers,
/// `io::import::stream_zip`).
pub fn zip(data: &[u8]) {
    use std::io::Write;
    import_files(vec![("upload.zip".to_string(), data.to_vec())]);
    let mut w = ::zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = ::zip::write::SimpleFileOptions::default()
        .compression_method(::zip::CompressionMethod::Stored);
    w.start_file("inner.zip", opts).expect("a stored entry");
    w.write_all(data).expect("in memory");
    let outer = w.finish().expect("in memory").into_inner();
    import_files(vec![("outer.zip".to_string(), outer)]);
}

/// The files of a recipe input after the recipe itself, in order.
pub const RECIPE_FILES: [&str; 4] = ["acc.csv", "gyr.csv", "mag.csv", "bar.csv"];

/// A recipe and the files it reads: the input split at NUL bytes into the recipe's JSON (when it
/// is not an accepted recipe, the simulator's plain-CSV recipe is used, so that the CSV reading
/// is fuzzed too) and [`RECIPE_FILES`]. An accepted recipe writes to JSON and reads back the
/// same; the logs read by it pass the import checks; the report's figures are finite; the
/// form's description of the files does not panic.
pub fn recipe(data: &[u8]) {
    use pdr::io::import::recipe::{self, Recipe};
    let mut pieces = data.splitn(2, |&b| b == 0);
    let json = pieces.next().unwrap_or_default();
    let rest = pieces.next().unwrap_or_default();
    let parsed = std::str::from_utf8(json)
        .ok()
        .and_then(|t| Recipe::from_json(t).ok());
    if let Some(r) = &parsed {
        let json = r.to_json().expect("an accepted recipe writes to JSON");
        let back = Recipe::from_json(&json).expect("a written recipe reads back");
        assert_eq!(&back, r, "the recipe changed through JSON");
    }
    let r = parsed.unwrap_or_else(|| {
        Recipe::from_json(pdr::sim::formats::PLAIN_CSV_RECIPE).expect("the built-in recipe")
    });
    let files = split_files("rec/", &RECIPE_FILES, rest);
    let mut set = MemSet::new(files);
    for res in recipe::read_set(&mut set, &r) {
        match res {
            Ok((log, report)) => {
                check_log(&log);
                for f in &report.files {
                    finite_opt("report.rate_hz", f.rate_hz);
                    finite_opt("report.median", f.median);
                    f.rows
                        .iter()
                        .flatten()
                        .for_each(|v| finite("report.row", *v));
                }
            }
            Err(e) => check_error(&e),
        }
    }
    let d = recipe::describe(&mut set);
    if let Some(draft) = d.draft {
        if !draft.files.is_empty() {
            let _ = draft.check();
        }
    }
}
