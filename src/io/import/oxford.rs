//! Oxford Step Counter trace folders, one of the evaluation data sets of `../shared/data`, read
//! directly. May import: `engine` and `io`.

use super::common::{add_warnings, each_record, numbers, set_records, Warnings};
use super::{file_error, fileset, FileSet, Format, Log, Platform, Streams, TrueStep};
use crate::io::ParseError;
use nalgebra::Vector3;

/// The files of an Oxford trace folder that the reader consumes.
pub const OXFORD_FILES: [&str; 3] = ["accelerometer.csv", "stepcounter.csv", "stats.csv"];

/// An Oxford Step Counter trace folder (`dir` ends with `/` or is empty): `accelerometer.csv`
/// (time ns since boot, sensor code, ax, ay, az in m/s², Android axes) and the truth device's
/// `stepcounter.csv` (time ns, one 0/1 contact column per foot; each 0→1 change is a step).
pub fn read_oxford(set: &mut dyn FileSet, dir: &str) -> Result<Log, ParseError> {
    let source = set.label(dir.trim_end_matches('/'));
    let mut log = Log::new(source, Format::OxfordSteps);
    log.platform = Some(Platform::Android);
    // `<Phone>_<Walker>_<Surface>_<Position>_<n>`.
    log.group = fileset::base(dir.trim_end_matches('/'))
        .split('_')
        .nth(3)
        .map(str::to_string);
    let name = format!("{dir}accelerometer.csv");
    let label = set.label(&name);
    let mut streams = Streams::default();
    let reader = set
        .open(&name)
        .map_err(|e| file_error(&label, 0, e.to_string()))?;
    let mut warnings = Warnings::default();
    each_record(reader, &label, Some(','), &mut warnings, |n, f| {
        let [t] = numbers(f, 0, ["time_ns"], &label, n)?;
        let a = numbers(f, 2, ["ax", "ay", "az"], &label, n)?;
        streams
            .accel
            .push((t * 1e-9, Vector3::new(a[0], a[1], a[2])));
        Ok(())
    })?;
    if streams.accel.is_empty() {
        return Err(file_error(&label, 0, "no accelerometer samples"));
    }
    let name = format!("{dir}stepcounter.csv");
    let label = set.label(&name);
    let reader = set
        .open(&name)
        .map_err(|e| file_error(&label, 0, e.to_string()))?;
    let mut prev: Option<[f64; 2]> = None;
    let mut events = Vec::new();
    each_record(reader, &label, Some(','), &mut warnings, |n, f| {
        let [t, l, r] = numbers(f, 0, ["time_ns", "left", "right"], &label, n)?;
        let c = [l, r];
        if let Some(p) = prev {
            for foot in 0..2u8 {
                let k = usize::from(foot);
                if p[k] < 0.5 && c[k] >= 0.5 {
                    events.push(TrueStep {
                        t: t * 1e-9,
                        foot: Some(foot),
                    });
                }
            }
        }
        prev = Some(c);
        Ok(())
    })?;
    crate::engine::sort::sort_by(&mut events, |a, b| a.t.total_cmp(&b.t));
    log.truth.steps = Some(events.len() as u64);
    log.truth.step_events = events;
    set_records(&mut log, streams, &label);
    add_warnings(&mut log, warnings);
    Ok(log)
}
