//! Live input: a simulated walk fed as the browser's `devicemotion` and `deviceorientation`
//! events, Android-style and iOS-style, through `LiveSession`, against the same walk replayed as
//! a log; and the session's recording replayed. Runs natively and in headless Chromium.

use pdr::engine::{replay, PipelineConfig, Record};
use pdr::io::pdrlog;
use pdr::live::{
    browser_events, orientation_angles, BrowserEvent, LiveSession, MotionEvent, OrientationEvent,
    Platform, SensorReading,
};
use pdr::sim::scenarios;
use wasm_bindgen_test::wasm_bindgen_test;

mod common;

wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

/// Feeds the events a phone of `platform` would fire for `records` to a session.
fn feed_into(live: &mut LiveSession, records: &[Record], platform: Platform) {
    for ev in browser_events(records, platform) {
        match ev {
            BrowserEvent::Orientation {
                t,
                alpha,
                beta,
                gamma,
            } => live.push_orientation(&OrientationEvent::absolute(t, alpha, beta, gamma)),
            BrowserEvent::Motion {
                t,
                x,
                y,
                z,
                alpha,
                beta,
                gamma,
                ..
            } => {
                live.push_motion(&MotionEvent {
                    time_stamp_ms: t,
                    accel: Some([x, y, z]),
                    rotation_rate_deg_s: alpha.zip(beta).zip(gamma).map(|((a, b), g)| [a, b, g]),
                })
                .unwrap();
            }
        }
    }
}

/// A session fed with `records` as `platform`'s events.
fn feed(records: &[Record], platform: Platform) -> LiveSession {
    let mut live = LiveSession::new(PipelineConfig::default(), platform, 0.0).unwrap();
    feed_into(&mut live, records, platform);
    live
}

#[wasm_bindgen_test(unsupported = test)]
fn live_events_count_like_the_log_and_both_platforms_agree() {
    let sim = scenarios::demo_walk().generate();
    // A browser has no magnetometer event: the log is replayed with the same sensors (with
    // one, the magnetic guard would hold the yaw on the gyroscope, `engine::magnetic`).
    let no_mag: Vec<Record> = sim
        .records
        .iter()
        .map(|r| match r {
            Record::Imu(s) => Record::Imu(pdr::engine::ImuSample { mag: None, ..*s }),
            r => *r,
        })
        .collect();
    let log = replay(PipelineConfig::default(), &no_mag).unwrap();
    let android = feed(&sim.records, Platform::Android);
    let ios = feed(&sim.records, Platform::Ios);
    let (a, i) = (android.pipeline().track(), ios.pipeline().track());
    assert_eq!(a, i, "iOS-style and Android-style events differ");
    assert_eq!(a.len(), log.pipeline.track().len());
    let (end, end_log) = (a.last().unwrap(), log.pipeline.track().last().unwrap());
    assert!(
        libm::hypot(end.east_m - end_log.east_m, end.north_m - end_log.north_m) < 0.05,
        "live and log tracks part"
    );
    let r = android.readouts();
    assert_eq!(r.steps, a.len());
    // The track's current position, as `pdr run --track`'s last row.
    assert_eq!(r.end_m, Some([end.east_m, end.north_m]));
    assert!(
        (r.sample_rate_hz - 100.0).abs() < 2.0,
        "{}",
        r.sample_rate_hz
    );
    assert_eq!(r.refused, 0);
    // The activity in words, the engine's (or its motion state's while it has none), and the
    // floor change and height from its diagnostics.
    let d = android.pipeline().diagnostics();
    let act = d.activity.unwrap_or(match d.motion.unwrap() {
        pdr::engine::Motion::Still => pdr::engine::Activity::Still,
        pdr::engine::Motion::Walking => pdr::engine::Activity::Walking,
        pdr::engine::Motion::Running => pdr::engine::Activity::Running,
    });
    assert_eq!(r.activity, Some(pdr::io::export::activity_words(act)));
    assert_eq!(r.activity_key, Some(act.as_str()));
    assert_eq!(r.floor, d.floor);
    assert_eq!(r.floor_change, pdr::io::export::floor_change(d.floor));
    assert_eq!(
        r.up_m.is_some(),
        d.vertical.is_some() || d.floor != 0 || d.up_m != 0.0
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn the_steps_held_at_a_walks_opening_are_counted_and_shown_as_held() {
    // A pocket walk cut 2 s after its first step: the thigh has not said yet which way is
    // forward, so its steps are counted but not on the track.
    let sim = scenarios::short_walk(pdr::sim::Carry::Pocket, 1, true).generate();
    let end = sim.truth.steps[0].t + 2.0;
    let cut: Vec<Record> = sim
        .records
        .iter()
        .filter(|r| !matches!(r, Record::Imu(s) if s.t > end))
        .copied()
        .collect();
    let mut live = feed(&cut, Platform::Android);
    let r = live.readouts();
    assert!(
        r.held_steps >= 3
            && r.steps == r.held_steps
            && r.heading_deg.is_none()
            && r.end_m.is_none(),
        "{r:?}"
    );
    // Stop: they are placed.
    assert_eq!(live.finish(), r.held_steps);
    let r = live.readouts();
    assert_eq!(r.held_steps, 0);
    assert_eq!(live.pipeline().track().len(), r.steps);
    assert!(r.heading_deg.is_some());
    let last = live.pipeline().track().last().unwrap();
    assert_eq!(r.end_m, Some([last.east_m, last.north_m]));
}

#[wasm_bindgen_test(unsupported = test)]
fn the_recording_replays_to_the_same_track() {
    let sim = scenarios::demo_walk().generate();
    let mut live = feed(&sim.records, Platform::Ios);
    // The page takes the recording in batches.
    let mut text = String::new();
    for _ in 0..3 {
        text.push_str(&live.take_log());
    }
    let parsed = pdrlog::read(text.as_bytes(), "live.pdrlog").unwrap();
    assert_eq!(parsed.skipped, 0);
    let again = replay(PipelineConfig::default(), &parsed.records).unwrap();
    assert_eq!(again.pipeline.track(), live.pipeline().track());
}

#[wasm_bindgen_test(unsupported = test)]
fn a_hidden_page_is_a_gap_not_steps() {
    let sim = scenarios::straight_walk(1.8, 40.0).generate();
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    let mut hidden = false;
    for r in &sim.records {
        let Record::Imu(s) = r else { continue };
        // The page is hidden from 15 s to 25 s: no events, then the page says so.
        if (15.0..25.0).contains(&s.t) {
            hidden = true;
            continue;
        }
        if hidden {
            live.mark_gap(15_000.0, s.t * 1e3);
            hidden = false;
        }
        let deg = 180.0 / std::f64::consts::PI;
        if let Some(q) = s.orientation {
            let (a, b, g) = orientation_angles(&q);
            live.push_orientation(&OrientationEvent::absolute(s.t * 1e3, a, b, g));
        }
        live.push_motion(&MotionEvent {
            time_stamp_ms: s.t * 1e3,
            accel: Some([s.accel.x, s.accel.y, s.accel.z]),
            rotation_rate_deg_s: s.gyro.map(|g| [g.x * deg, g.y * deg, g.z * deg]),
        })
        .unwrap();
    }
    let r = live.readouts();
    assert_eq!(r.gaps, 1);
    let marks = live.gap_marks();
    assert_eq!(marks.len(), 1);
    assert_eq!((marks[0].t0, marks[0].t1), (15.0, marks[0].t1));
    assert!(marks[0].t1 >= 25.0 && marks[0].east_m.abs() + marks[0].north_m.abs() > 5.0);
    let in_gap = live
        .pipeline()
        .track()
        .iter()
        .filter(|s| (15.0..25.0).contains(&s.t))
        .count();
    assert_eq!(in_gap, 0, "steps inside the hidden time");
    // 40 s of walking at 1.8 Hz less the 10 s hidden: about 54 steps lost.
    let truth = sim
        .truth
        .steps
        .iter()
        .filter(|s| !(15.0..25.0).contains(&s.t))
        .count();
    assert!(r.steps.abs_diff(truth) <= 3, "{} against {truth}", r.steps);
}

#[wasm_bindgen_test(unsupported = test)]
fn a_recording_resumed_after_a_reload_continues_the_same_track() {
    let sim = scenarios::demo_walk().generate();
    let whole = feed(&sim.records, Platform::Android);
    let cut = sim.records.len() / 2;
    // The first page: events on its clock, origin 0.
    let mut first = feed(&sim.records[..cut], Platform::Android);
    let recorded = first.take_log();
    // The reloaded page has a later time origin: its timeStamps are 40 s smaller.
    let origin = 40_000.0;
    let mut second = LiveSession::resume(
        PipelineConfig::default(),
        Platform::Android,
        origin,
        &recorded,
    )
    .unwrap();
    assert_eq!(second.pipeline().track(), first.pipeline().track());
    let shifted: Vec<Record> = sim.records[cut..]
        .iter()
        .map(|r| match r {
            Record::Imu(s) => Record::Imu(pdr::engine::ImuSample {
                t: s.t - origin * 1e-3,
                ..*s
            }),
            other => *other,
        })
        .collect();
    feed_into(&mut second, &shifted, Platform::Android);
    // The same walk, but for the last bits of the times (ms since another origin).
    let (a, b) = (second.pipeline().track(), whole.pipeline().track());
    assert_eq!(a.len(), b.len());
    let (ea, eb) = (a.last().unwrap(), b.last().unwrap());
    assert!(libm::hypot(ea.east_m - eb.east_m, ea.north_m - eb.north_m) < 1e-3);
    // Only the new records are taken, and both parts replay as one log.
    let rest = second.take_log();
    assert!(!rest.starts_with("#"), "the version tag came twice");
    let parsed = pdrlog::read(format!("{recorded}{rest}").as_bytes(), "resumed.pdrlog").unwrap();
    let again = replay(PipelineConfig::default(), &parsed.records).unwrap();
    assert_eq!(again.pipeline.track(), second.pipeline().track());
}

#[wasm_bindgen_test(unsupported = test)]
fn a_damaged_recording_resumes_with_every_good_line_and_says_what_was_skipped() {
    let sim = scenarios::straight_walk(1.8, 20.0).generate();
    let mut first = feed(&sim.records, Platform::Android);
    let good = first.take_log();
    let lines: Vec<&str> = good.split_inclusive('\n').collect();
    let n = lines.len();
    // The version tag lost, garbage, a field that is not a number, absurd but finite values,
    // a time going backwards, and the last line cut short.
    let mut bad = lines[1..n / 2].concat();
    bad.push_str("\u{0}\u{1}garbage,,,\nimu,12.5,0,nan,9.8,,,,,,,,,,\n");
    bad.push_str("imu,12.51,1e300,-1e300,1e300,1e300,0,0,,,,,,,\nimu,0.5,0,0,9.8,,,,,,,,,,\n");
    bad.push_str(&lines[n / 2..n - 1].concat());
    bad.push_str(&lines[n - 1][..20]);
    let s = LiveSession::resume(PipelineConfig::default(), Platform::Android, 0.0, &bad).unwrap();
    let r = s.readouts();
    assert_eq!(r.skipped_lines, 3, "{:?}", r.last_error);
    let why = r.last_error.clone().unwrap();
    assert!(
        why.contains("field `accel` is not a finite, in-range number"),
        "{why}"
    );
    assert!(r.distance_m.is_finite(), "distance {}", r.distance_m);
    assert!(r.heading_deg.is_none_or(f64::is_finite));
    assert!(r.cadence_hz.is_none_or(f64::is_finite));
    assert!(s
        .pipeline()
        .track()
        .iter()
        .all(|st| st.east_m.is_finite() && st.north_m.is_finite()));
    // Every good sample went through: all but the cut one, with the early one; the absurd one
    // was refused by the engine, naming its field.
    assert_eq!(r.samples, first.readouts().samples);
    assert_eq!(r.refused, 1);
    assert!(
        r.steps.abs_diff(first.readouts().steps) <= 2,
        "{} against {}",
        r.steps,
        first.readouts().steps
    );
}

#[wasm_bindgen_test(unsupported = test)]
fn motion_is_used_before_the_attitude_comes_and_the_scope_keeps_ten_seconds() {
    let sim = scenarios::straight_walk(1.8, 20.0).generate();
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    // Orientation starts 0.5 s after motion: every motion event is used and recorded, the
    // engine starting on the gyroscope and moving up to the attitude when it comes.
    let events = browser_events(&sim.records, Platform::Android);
    for ev in events {
        match ev {
            BrowserEvent::Orientation {
                t,
                alpha,
                beta,
                gamma,
            } if t >= 500.0 => {
                live.push_orientation(&OrientationEvent::absolute(t, alpha, beta, gamma))
            }
            BrowserEvent::Motion {
                t, x, y, z, alpha, ..
            } => {
                live.push_motion(&MotionEvent {
                    time_stamp_ms: t,
                    accel: Some([x, y, z]),
                    rotation_rate_deg_s: alpha.map(|a| [a, 0.0, 0.0]),
                })
                .unwrap();
            }
            _ => {}
        }
    }
    let r = live.readouts();
    assert_eq!(r.orientation, Some("os"));
    assert!(r.absolute_heading);
    let motion_events = sim
        .records
        .iter()
        .filter(|r| matches!(r, Record::Imu(_)))
        .count();
    assert_eq!(r.samples as usize, motion_events);
    let o = live.pipeline().orientation_diagnostics().unwrap();
    assert_eq!(o.switches, 1, "madgwick, then the attitude");
    let first = live.take_log();
    let first_imu = first.lines().find(|l| l.starts_with("imu,")).unwrap();
    assert!(first_imu.starts_with("imu,0,"), "{first_imu}");
    let scope = live.scope();
    let span = scope.back().unwrap().t - scope.front().unwrap().t;
    assert!((9.9..=10.0).contains(&span), "{span}");
    assert!(scope.iter().all(|s| s.pll.is_some() && s.up.is_finite()));

    // No attitude at all: the engine goes on with the gyroscope (Madgwick).
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    common::push_motion_only(&mut live, &sim.records, Platform::Android);
    let r = live.readouts();
    assert_eq!(r.orientation, Some("madgwick"));
    assert!(!r.absolute_heading);
    assert!(r.steps > 30, "{}", r.steps);
}

#[wasm_bindgen_test(unsupported = test)]
fn a_rotation_rate_that_comes_late_gives_the_steps_their_heading_from_then_on() {
    // Some browsers fire their first devicemotion events without a rotation rate. Here it is
    // missing for the first 6 s: 3 s standing and 3 s of walking.
    const LATE_MS: f64 = 6000.0;
    let sim = scenarios::straight_walk(1.8, 60.0).generate();
    let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    for ev in browser_events(&sim.records, Platform::Android) {
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
            let rate = alpha.zip(beta).zip(gamma).map(|((a, b), g)| [a, b, g]);
            live.push_motion(&MotionEvent {
                time_stamp_ms: t,
                accel: Some([x, y, z]),
                rotation_rate_deg_s: rate.filter(|_| t >= LATE_MS),
            })
            .unwrap();
        }
    }
    let r = live.readouts();
    assert_eq!(r.orientation, Some("madgwick"));
    let track = live.pipeline().track();
    let with = track.iter().filter(|s| s.heading_rad.is_some()).count();
    assert!(track.len() > 100, "{} steps", track.len());
    assert!(
        with * 100 >= 95 * track.len(),
        "{with} of {} steps have a heading",
        track.len()
    );
    assert!(track
        .iter()
        .filter(|s| s.t > LATE_MS * 1e-3 + 1.5)
        .all(|s| s.heading_rad.is_some()));
}

#[wasm_bindgen_test(unsupported = test)]
fn generic_sensor_readings_and_motion_events_agree() {
    let sim = scenarios::straight_walk(1.8, 15.0).generate();
    let events = feed(&sim.records, Platform::Android);
    let mut sensors = LiveSession::new(PipelineConfig::default(), Platform::Ios, 0.0).unwrap();
    for r in &sim.records {
        let Record::Imu(s) = r else { continue };
        if let Some(q) = s.orientation {
            let q = q.into_inner();
            sensors.push_quaternion(s.t * 1e3, [q.i, q.j, q.k, q.w]);
        }
        // The Generic Sensor API has the specification's sign on every platform.
        sensors
            .push_sensor(&SensorReading {
                timestamp_ms: s.t * 1e3,
                accel: s.accel.into(),
                gyro_rad_s: s.gyro.map(Into::into),
            })
            .unwrap();
    }
    assert_eq!(sensors.readouts().steps, events.readouts().steps);
    let (a, b) = (
        sensors.pipeline().track().last().unwrap(),
        events.pipeline().track().last().unwrap(),
    );
    assert!(libm::hypot(a.east_m - b.east_m, a.north_m - b.north_m) < 0.05);
    assert!(sensors
        .push_sensor(&SensorReading {
            timestamp_ms: 2e4,
            accel: [f64::NAN, 0.0, 9.8],
            gyro_rad_s: None,
        })
        .is_err());
    assert_eq!(sensors.readouts().refused, 1);

    // A still phone: the orientation sensor reports once (it fires on change only), the
    // accelerometer goes on; the attitude holds.
    let mut still = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
    still.push_quaternion(0.0, [0.0, 0.0, 0.382_683_4, 0.923_879_5]);
    for i in 0..500 {
        still
            .push_sensor(&SensorReading {
                timestamp_ms: f64::from(i) * 10.0,
                accel: [0.0, 0.0, 9.81],
                gyro_rad_s: Some([0.0; 3]),
            })
            .unwrap();
    }
    let r = still.readouts();
    assert_eq!((r.samples, r.refused, r.orientation), (500, 0, Some("os")));
}

#[wasm_bindgen_test(unsupported = test)]
fn the_ios_compass_heading_gives_the_absolute_alpha() {
    use pdr::live::{ios_compass_alpha, orientation_quaternion};
    // Flat, top to the east: compass 90°.
    let alpha = ios_compass_alpha(90.0, 0.0);
    assert!((alpha - 270.0).abs() < 1e-9);
    let top = orientation_quaternion(alpha, 0.0, 0.0) * nalgebra::Vector3::y();
    assert!((top - nalgebra::Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-9);
    // Interface turned a quarter: the interface's top (the device's left side) points to 0°,
    // so the device's top points east.
    assert!((ios_compass_alpha(0.0, 90.0) - 270.0).abs() < 1e-9);
    assert!((ios_compass_alpha(350.0, 90.0) - 280.0).abs() < 1e-9);
}

/// The live map's smoothed track, kept between fixes, is at every moment the smoother's whole
/// backward pass over the walk so far (energy-saving mode, the city walk's fixes).
#[wasm_bindgen_test(unsupported = test)]
fn live_smoothed_track_equals_the_smoother_at_any_time() {
    use pdr::engine::fusion::GnssMode;
    let sim = scenarios::gnss_city_walk().generate();
    let mut cfg = PipelineConfig::default();
    cfg.fusion.mode = GnssMode::ENERGY_SAVING;
    let mut live = LiveSession::new(cfg, Platform::Android, 0.0).unwrap();
    let mut checks = 0;
    for (i, r) in sim.records.iter().enumerate() {
        match r {
            Record::Gnss(f) => live.push_fix(f).unwrap(),
            Record::Imu(_) => feed_into(&mut live, std::slice::from_ref(r), Platform::Android),
            Record::Gap(..) | Record::Foot(_) | Record::Pressure(_) => {}
        }
        if i % 3000 == 0 || i + 1 == sim.records.len() {
            let shown = live.map_data().smoothed;
            let full: Vec<(f64, f64)> = live
                .pipeline()
                .smoothed()
                .iter()
                .map(|f| (f.east_m, f.north_m))
                .collect();
            assert_eq!(shown, full, "after record {i}");
            checks += usize::from(!full.is_empty());
        }
    }
    assert!(checks > 20, "{checks} checks with a fused track");
}

/// A small deterministic generator (SplitMix64) for the hostile streams.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d4_9bb1_3311_13eb);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
    /// A value that is not a number, or not a finite one.
    fn junk(&mut self) -> f64 {
        [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -f64::NAN][(self.next() % 4) as usize]
    }
}

/// Checks everything the page shows for numbers that are not finite.
fn assert_shows_finite(live: &mut LiveSession, what: &str) {
    let r = live.readouts();
    let ok = |v: f64| v.is_finite();
    assert!(
        ok(r.distance_m) && ok(r.sample_rate_hz) && ok(r.duration_s),
        "{what}: {r:?}"
    );
    for v in [r.cadence_hz, r.heading_deg, r.gnss_accuracy_m]
        .into_iter()
        .flatten()
    {
        assert!(ok(v), "{what}: {r:?}");
    }
    if let Some((a, b)) = r.fusion_scale {
        assert!(ok(a) && ok(b), "{what}: {r:?}");
    }
    for s in live.pipeline().track() {
        assert!(
            ok(s.t) && ok(s.east_m) && ok(s.north_m) && ok(s.length_m),
            "{what}: {s:?}"
        );
        assert!(s.heading_rad.map_or(true, ok), "{what}: {s:?}");
    }
    let m = live.map_data();
    for &(e, n) in m
        .pdr
        .iter()
        .chain(&m.fused)
        .chain(&m.smoothed)
        .chain(&m.gaps)
    {
        assert!(ok(e) && ok(n), "{what}: map {m:?}");
    }
    assert!(
        m.fixes.iter().all(|&(e, n, a)| ok(e) && ok(n) && ok(a)),
        "{what}"
    );
    let s = live.scope_data();
    assert!(ok(s.now) && s.steps.iter().all(|&t| ok(t)), "{what}");
    for &(t, up, pll) in &s.samples {
        assert!(ok(t) && ok(up) && pll.map_or(true, ok), "{what}: scope");
    }
}

/// Hostile event streams into the live session: values that are NaN, infinite or missing,
/// time going backwards, duplicate timestamps, bursts at 1 kHz, throttling to 5 Hz (a
/// background tab), a sensor that stops mid-walk, garbage attitudes, fixes and gaps. The
/// session never panics and never shows a number that is not finite; the steps only grow; and
/// the recording replays to the same track and the same number of samples.
#[wasm_bindgen_test(unsupported = test)]
fn hostile_event_streams_keep_the_session_consistent() {
    let sim = scenarios::gnss_city_walk().generate();
    let t0 = sim.records.iter().find_map(|r| match r {
        Record::Imu(s) => Some(s.t),
        _ => None,
    });
    let records: Vec<Record> = sim
        .records
        .iter()
        .take_while(|r| !matches!(r, Record::Imu(s) if Some(s.t - 150.0) > t0))
        .cloned()
        .collect();
    let seeds: u64 = if cfg!(target_arch = "wasm32") { 2 } else { 6 };
    for seed in 0..seeds {
        let mut rng = Rng(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) + 1);
        let mut live = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
        let (mut burst, mut throttle, mut stopped) = (0u32, 0u32, 0u32);
        let (mut steps, mut pushed, mut refused, mut n) = (0usize, 0u64, 0u64, 0u64);
        let mut log = String::new();
        for r in &records {
            let evs: Vec<BrowserEvent> = match r {
                Record::Gnss(f) => {
                    let mut f = *f;
                    if rng.chance(0.1) {
                        match rng.next() % 4 {
                            0 => f.lat_deg = rng.junk(),
                            1 => {
                                f.h_accuracy_m = [0.0, -5.0, rng.junk()][(rng.next() % 3) as usize]
                            }
                            2 => f.t -= 30.0 * rng.unit(),
                            _ => f.t = rng.junk(),
                        }
                    }
                    refused += u64::from(live.push_fix(&f).is_err());
                    continue;
                }
                Record::Gap(a, b) => {
                    live.mark_gap(a * 1e3, b * 1e3);
                    continue;
                }
                Record::Imu(_) => browser_events(std::slice::from_ref(r), Platform::Android),
                Record::Foot(_) | Record::Pressure(_) => continue,
            };
            if rng.chance(0.0005) {
                burst = 30;
            }
            if rng.chance(0.0003) {
                throttle = 500;
            }
            if rng.chance(0.0002) {
                stopped = 1500;
            }
            for ev in evs {
                match ev {
                    BrowserEvent::Orientation {
                        t,
                        alpha,
                        beta,
                        gamma,
                    } => {
                        let mut o = OrientationEvent::absolute(t, alpha, beta, gamma);
                        if rng.chance(0.02) {
                            match rng.next() % 4 {
                                0 => o.alpha = None,
                                1 => o.beta = Some(rng.junk()),
                                2 => o.gamma = Some(720.0),
                                _ => o.time_stamp_ms = rng.junk(),
                            }
                        }
                        live.push_orientation(&o);
                        if rng.chance(0.002) {
                            let q = [[f64::NAN, 0.0, 0.0, 1.0], [0.0; 4], [3.0, 0.0, 0.0, 4.0]];
                            live.push_quaternion(t, q[(rng.next() % 3) as usize]);
                        }
                    }
                    BrowserEvent::Motion {
                        t,
                        x,
                        y,
                        z,
                        alpha,
                        beta,
                        gamma,
                        ..
                    } => {
                        n += 1;
                        if stopped > 0 {
                            stopped -= 1;
                            if stopped == 0 && rng.chance(0.5) {
                                live.mark_gap(t - 15_000.0, t);
                            }
                            continue;
                        }
                        if throttle > 0 {
                            throttle -= 1;
                            if n % 20 != 0 {
                                continue;
                            }
                        }
                        let mut m = MotionEvent {
                            time_stamp_ms: t,
                            accel: Some([x, y, z]),
                            rotation_rate_deg_s: alpha
                                .zip(beta)
                                .zip(gamma)
                                .map(|((a, b), g)| [a, b, g]),
                        };
                        if rng.chance(0.03) {
                            match rng.next() % 6 {
                                0 => m.accel = Some([x, rng.junk(), z]),
                                1 => m.accel = None,
                                2 => m.rotation_rate_deg_s = None,
                                3 => m.rotation_rate_deg_s = Some([rng.junk(), 0.0, 0.0]),
                                4 => m.time_stamp_ms -= 2000.0 * rng.unit(),
                                _ => m.time_stamp_ms = rng.junk(),
                            }
                        }
                        let copies = if burst > 0 {
                            burst -= 1;
                            10
                        } else if rng.chance(0.02) {
                            2 // a duplicate timestamp
                        } else {
                            1
                        };
                        for k in 0..copies {
                            let mut c = m;
                            if burst > 0 {
                                c.time_stamp_ms += f64::from(k); // 1 kHz
                            }
                            pushed += 1;
                            refused += u64::from(live.push_motion(&c).is_err());
                        }
                    }
                }
            }
            let now = live.readouts().steps;
            assert!(
                now >= steps,
                "seed {seed}: steps went from {steps} to {now}"
            );
            steps = now;
            if n % 1000 == 0 {
                assert_shows_finite(&mut live, &format!("seed {seed}, event {n}"));
                log.push_str(&live.take_log());
            }
        }
        assert_shows_finite(&mut live, &format!("seed {seed}, end"));
        log.push_str(&live.take_log());
        let r = live.readouts();
        assert!(
            refused > 0 && r.steps > 20,
            "seed {seed}: {refused} refused, {} steps",
            r.steps
        );
        // Refused orientation events are counted too.
        assert!(
            r.refused >= refused,
            "seed {seed}: {} < {refused}",
            r.refused
        );
        let parsed = pdrlog::read(log.as_bytes(), "hostile.pdrlog").unwrap();
        assert_eq!(parsed.skipped, 0, "seed {seed}: {:?}", parsed.errors);
        let samples = parsed
            .records
            .iter()
            .filter(|r| matches!(r, Record::Imu(_)))
            .count();
        assert_eq!(samples as u64, r.samples, "seed {seed}: samples recorded");
        assert!(r.samples <= pushed, "seed {seed}");
        // Stopped, as the page stops it: the steps still held at an opening are placed.
        live.finish();
        let again = replay(PipelineConfig::default(), &parsed.records).unwrap();
        assert_eq!(
            again.pipeline.track(),
            live.pipeline().track(),
            "seed {seed}: replay"
        );
        eprintln!(
            "seed {seed}: {pushed} motion events pushed, {} refused in all, {} samples, {} steps",
            r.refused, r.samples, r.steps
        );
    }
}
