//! Helpers shared by the integration tests (natively, and in Chromium for the wasm-bindgen
//! tests). Each test crate uses some of them.
#![allow(dead_code)]

pub mod fusion;
pub mod gnss;
#[cfg(not(target_arch = "wasm32"))]
pub mod import;
pub mod ipin;
#[cfg(not(target_arch = "wasm32"))]
pub mod recipe;

use pdr::engine::fusion::FusedStep;
use pdr::engine::types::{GnssFix, ImuSample};
use pdr::engine::{replay, Activity, PipelineConfig, Record, StepRecord};
use pdr::live::{browser_events, BrowserEvent, LiveSession, MotionEvent, Platform};
use pdr::sim::{Scenario, Segment, Simulation};

/// Runs the `pdr` binary with `args`: (success, stdout, stderr). Native only.
#[cfg(not(target_arch = "wasm32"))]
pub fn pdr(args: &[&str]) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pdr"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

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

/// FNV-1a over a sequence of bytes.
pub fn fnv1a_bytes(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// FNV-1a over the bits of a sequence of numbers: the digests that the bit-identical replay
/// tests check natively and in Chromium against one constant.
pub fn fnv1a(values: impl IntoIterator<Item = f64>) -> u64 {
    fnv1a_bytes(values.into_iter().flat_map(|v| v.to_bits().to_le_bytes()))
}

/// Which fields of each step a track's [`digest`] covers.
#[derive(Clone, Copy, Debug)]
pub enum StepFields {
    /// Time, east, north, heading (−1 when none) and length.
    Track,
    /// [`StepFields::Track`] and the step frequency.
    TrackAndFrequency,
    /// Time, east, north, length, up, floor, the activity's index in [`Activity::ALL`] and the
    /// leg pitch's amplitude (−1 when none).
    Stairs,
}

/// FNV-1a over the bits of `fields` of every step of a track.
pub fn digest(track: &[StepRecord], fields: StepFields) -> u64 {
    fnv1a(track.iter().flat_map(|s| {
        let heading = s.heading_rad.unwrap_or(-1.0);
        match fields {
            StepFields::Track => vec![s.t, s.east_m, s.north_m, heading, s.length_m],
            StepFields::TrackAndFrequency => {
                vec![s.t, s.east_m, s.north_m, heading, s.length_m, s.freq_hz]
            }
            StepFields::Stairs => vec![
                s.t,
                s.east_m,
                s.north_m,
                s.length_m,
                s.up_m,
                f64::from(s.floor),
                Activity::ALL
                    .iter()
                    .position(|a| *a == s.activity)
                    .unwrap_or(99) as f64,
                s.pitch_amplitude_deg.unwrap_or(-1.0),
            ],
        }
    }))
}

/// FNV-1a over the bits of the fused and smoothed positions and corrections.
pub fn fused_digest(tracks: [&[FusedStep]; 2]) -> u64 {
    fnv1a(
        tracks
            .into_iter()
            .flatten()
            .flat_map(|s| [s.t, s.east_m, s.north_m, s.scale, s.bias_rad, s.cov[0]]),
    )
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
