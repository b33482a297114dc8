//! Helpers shared by the integration tests (natively, and in Chromium for the wasm-bindgen
//! tests). Each test crate uses some of them.
#![allow(dead_code)]

pub mod fusion;
#[cfg(not(target_arch = "wasm32"))]
pub mod import;
pub mod ipin;
#[cfg(not(target_arch = "wasm32"))]
pub mod recipe;

use pdr::engine::types::{GnssFix, ImuSample};
use pdr::engine::{replay, PipelineConfig, Record, StepRecord};
use pdr::live::{browser_events, BrowserEvent, LiveSession, MotionEvent, Platform};
use pdr::sim::{Scenario, Segment, Simulation};

/// Peak resident memory of this process, bytes (Linux only; `None` elsewhere).
pub fn peak_rss() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb: u64 = s
        .lines()
        .find(|l| l.starts_with("VmHWM:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()?;
    Some(kb * 1024)
}

/// Fails when the peak resident memory grew by `limit` bytes or more since `before` (a
/// [`peak_rss`]; nothing is checked where the platform has none).
pub fn assert_peak_grew_less(before: Option<u64>, limit: u64) {
    if let (Some(a), Some(b)) = (before, peak_rss()) {
        assert!(
            b.saturating_sub(a) < limit,
            "peak memory grew by {} MB",
            (b - a) >> 20
        );
    }
}

/// FNV-1a over the bits of a sequence of numbers: the digests that the bit-identical replay
/// tests check natively and in Chromium against one constant.
pub fn fnv1a(values: impl IntoIterator<Item = f64>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for v in values {
        for b in v.to_bits().to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// The track of a simulated walk replayed with `cfg`, which must refuse none of its records.
pub fn run(sim: &Simulation, cfg: PipelineConfig) -> Vec<StepRecord> {
    let r = replay(cfg, &sim.records).expect("valid config");
    assert!(
        r.errors.is_empty(),
        "clean input refused: {:?}",
        r.errors.first()
    );
    r.pipeline.track().to_vec()
}

/// Allowed count error: ±1 step per 100 (at least 1).
pub fn tolerance(truth: usize) -> usize {
    (truth / 100).max(1)
}

/// A step count within [`tolerance`] of the truth.
pub fn assert_count(label: &str, counted: usize, truth: usize) {
    let err = counted.abs_diff(truth);
    assert!(
        err <= tolerance(truth),
        "{label}: counted {counted} steps, truth {truth}"
    );
}

/// A walk whose cadence changes: 1.6 Hz, ramp to 2.1 Hz, ramp to a 2.9 Hz run, with stills at
/// both ends.
pub fn cadence_change() -> Scenario {
    Scenario::new(vec![
        Segment::still(3.0),
        Segment::walk(25.0, 1.6),
        Segment::walk(10.0, 1.6).ramp_to(2.1),
        Segment::walk(25.0, 2.1),
        Segment::walk(4.0, 2.1).ramp_to(2.9),
        Segment::run(20.0, 2.9),
        Segment::still(3.0),
    ])
}

/// The IMU samples of a list of records.
pub fn imu(records: &[Record]) -> Vec<ImuSample> {
    records
        .iter()
        .filter_map(|r| match r {
            Record::Imu(s) => Some(*s),
            _ => None,
        })
        .collect()
}

/// The fixes of a list of records.
pub fn fixes(records: &[Record]) -> Vec<GnssFix> {
    records
        .iter()
        .filter_map(|r| match r {
            Record::Gnss(f) => Some(*f),
            _ => None,
        })
        .collect()
}

/// Feeds the records to a live session as a browser's motion events alone (acceleration and
/// rotation rate, no attitude event).
pub fn push_motion_only(live: &mut LiveSession, records: &[Record], platform: Platform) {
    for ev in browser_events(records, platform) {
        if let BrowserEvent::Motion {
            t,
            x,
            y,
            z,
            alpha,
            beta,
            gamma,
            ..
        } = ev
        {
            live.push_motion(&MotionEvent {
                time_stamp_ms: t,
                accel: Some([x, y, z]),
                rotation_rate_deg_s: alpha.zip(beta).zip(gamma).map(|((a, b), g)| [a, b, g]),
            })
            .unwrap();
        }
    }
}
