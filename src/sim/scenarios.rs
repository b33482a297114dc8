//! Named scenarios used by the tests, the benchmark and the demo page; the pocket scenarios of
//! Munoz Diaz 2015 (realistic thigh, stairs, sitting, a pose, a barometer).
//! May import: `engine` and `io`.

use super::{
    BaroSim, Canyon, GnssErrors, GnssSim, Multipath, PocketPose, Scenario, Segment, StaleFix,
    Walker,
};

/// A straight walk of `seconds` at cadence `f` Hz, preceded and followed by 3 s still.
pub fn straight_walk(f: f64, seconds: f64) -> Scenario {
    Scenario::new(vec![
        Segment::still(3.0),
        Segment::walk(seconds, f),
        Segment::still(3.0),
    ])
}

/// A straight run.
pub fn straight_run(f: f64, seconds: f64) -> Scenario {
    Scenario::new(vec![
        Segment::still(3.0),
        Segment::run(seconds, f),
        Segment::still(3.0),
    ])
}

/// A closed square of `side_m` metres, walked clockwise at 1.8 Hz with 90° turns taken over
/// about three steps at each corner.
pub fn square(side_m: f64) -> Scenario {
    let walker = Walker::default();
    let f = 1.8;
    let turn_s = 1.7;
    let turn_len = walker.step_length.length(f) * f * turn_s;
    let mut segs = vec![Segment::still(3.0)];
    for i in 0..4 {
        // Each corner's turn is split between the end of one side and the start of the next.
        let straight = side_m - turn_len;
        if i == 0 {
            segs.push(Segment::walk_distance(
                straight + turn_len / 2.0,
                f,
                &walker,
            ));
        } else {
            segs.push(Segment::walk_distance(straight, f, &walker));
        }
        if i < 3 {
            segs.push(Segment::walk(turn_s, f).turning(90.0));
        } else {
            segs.push(Segment::walk_distance(turn_len / 2.0, f, &walker));
        }
    }
    segs.push(Segment::still(3.0));
    Scenario {
        walker,
        ..Scenario::new(segs)
    }
}

/// The demo walk of the web page: about three minutes around a block, with a stop, a stretch at
/// a faster pace, a short run, and the phone handled while standing.
pub fn demo_walk() -> Scenario {
    let w = Walker::default();
    let segs = vec![
        Segment::still(2.0),
        Segment::walk_distance(40.0, 1.8, &w),
        Segment::walk(2.0, 1.8).turning(90.0),
        Segment::walk_distance(30.0, 1.8, &w).ramp_to(2.0),
        Segment::walk(3.0, 2.0).turning(-120.0),
        Segment::walk_distance(25.0, 1.7, &w),
        Segment::still(4.0),
        Segment::handled(5.0),
        Segment::walk_distance(20.0, 1.75, &w),
        Segment::run(12.0, 2.9).turning(60.0),
        Segment::walk(3.0, 1.9).turning(75.0),
        Segment::walk_distance(45.0, 1.85, &w).turning(20.0),
        Segment::walk(2.5, 1.8).turning(90.0),
        Segment::walk_distance(30.0, 1.8, &w),
        Segment::still(3.0),
    ];
    Scenario {
        seed: 2016,
        start_heading_deg: 20.0,
        ..Scenario::new(segs)
    }
}

/// How much longer the engine's default step length is than the walker's on
/// [`gnss_city_walk`]: the fusion should learn a scale of 1 / this.
pub const GNSS_CITY_LENGTH_FACTOR: f64 = 1.1;

/// How far east of the truth the OS heading reads on [`gnss_city_walk`], degrees: the fusion
/// should learn a heading correction of minus this.
pub const GNSS_CITY_HEADING_BIAS_DEG: f64 = 8.0;

/// A walk through city streets with the GNSS receiver on (the fusion tests of issue "GNSS/PDR
/// fusion"): about eleven minutes on a closed loop of blocks at 1.7–1.95 Hz, with a stop. The
/// fixes (1 Hz, reported accuracy 3–12 m) include 20 % outliers of 30–80 m and a two-minute
/// outage. The engine's default step length is 10 % too long for this walker, and the OS heading
/// reads 8° east of the truth; the attitude refers to magnetic north, as phones' does. Dated
/// 2026-06-01 (for the declination).
pub fn gnss_city_walk() -> Scenario {
    let mut w = Walker::default();
    for line in [&mut w.step_length.walking, &mut w.step_length.running] {
        line.a /= GNSS_CITY_LENGTH_FACTOR;
        line.b /= GNSS_CITY_LENGTH_FACTOR;
    }
    let mut segs = vec![Segment::still(3.0)];
    let legs = [
        (120.0, 1.8, 90.0),
        (80.0, 1.9, 90.0),
        (150.0, 1.75, -90.0),
        (60.0, 1.85, 90.0),
        (100.0, 1.8, 90.0),
        (90.0, 1.95, -45.0),
        (70.0, 1.7, 135.0),
    ];
    for (i, &(metres, f, turn)) in legs.iter().enumerate() {
        segs.push(Segment::walk_distance(metres, f, &w));
        segs.push(Segment::walk(2.5, f).turning(turn));
        if i == 3 {
            segs.push(Segment::still(6.0));
        }
    }
    segs.push(Segment::walk_distance(80.0, 1.8, &w));
    segs.push(Segment::still(3.0));
    let start = 1_780_272_000.0; // 2026-06-01 00:00 UTC
    Scenario {
        seed: 2021,
        walker: w,
        sensors: super::Sensors {
            os_yaw_bias_deg: GNSS_CITY_HEADING_BIAS_DEG,
            ..super::Sensors::default()
        },
        gnss: Some(GnssSim {
            outlier_share: 0.2,
            outages: vec![(start + 240.0, start + 360.0)],
            ..GnssSim::default()
        }),
        clock_offset_s: start,
        ..Scenario::new(segs)
    }
}

/// Time constant of [`gnss_city_walk_real`]'s multipath bias, s (IPIN 2023's fixes).
pub const GNSS_REAL_TAU_S: f64 = 14.0;

/// How far [`gnss_city_walk_real`]'s reported accuracy understates its real error.
pub const GNSS_REAL_OPTIMISM: f64 = 1.3;

/// [`gnss_city_walk_real`]'s urban-canyon stretch: (start, end) s after the start of the walk,
/// and the bias, m.
pub const GNSS_REAL_CANYON: (f64, f64, f64) = (430.0, 520.0, 25.0);

/// How far from the true start [`gnss_city_walk_real`]'s stale first fix lies, m.
pub const GNSS_REAL_STALE_M: f64 = 3000.0;

/// How long [`gnss_city_walk_real`]'s receiver holds the standing position when the walk starts,
/// s.
pub const GNSS_REAL_HOLD_S: f64 = 6.0;

/// [`gnss_city_walk`] with a real phone's GNSS: the same route, walker, step length
/// 10 % off, 8° heading bias, outage and date, but fixes whose errors have the shapes measured
/// on IPIN 2023's walks instead of white noise and outliers. Reported accuracy 4–15 m,
/// understating the real error by [`GNSS_REAL_OPTIMISM`]; a multipath bias with
/// τ = [`GNSS_REAL_TAU_S`] (10 % of the variance white); one urban-canyon stretch of 90 s with
/// a 25 m bias ([`GNSS_REAL_CANYON`]); a stale first fix 3 km away reporting 20 m; fixes
/// wandering by 3 m per 10 s while the walker stands; the receiver holding the standing position
/// for 6 s whenever the walk starts; speeds reported. No outliers.
pub fn gnss_city_walk_real() -> Scenario {
    let sc = gnss_city_walk();
    let start = sc.clock_offset_s;
    let (a, b, bias_m) = GNSS_REAL_CANYON;
    Scenario {
        gnss: Some(GnssSim {
            accuracy_m: (4.0, 15.0),
            outages: vec![(start + 240.0, start + 360.0)],
            errors: GnssErrors {
                multipath: Some(Multipath {
                    tau_s: GNSS_REAL_TAU_S,
                    white_share: 0.1,
                }),
                optimism: GNSS_REAL_OPTIMISM,
                canyons: vec![Canyon {
                    start_s: start + a,
                    end_s: start + b,
                    bias_m,
                }],
                stale_first_fix: Some(StaleFix {
                    count: 1,
                    distance_m: GNSS_REAL_STALE_M,
                    bearing_deg: 230.0,
                    accuracy_m: 20.0,
                }),
                stand_wander_m: 3.0,
                start_hold_s: GNSS_REAL_HOLD_S,
                latency_s: 0.0,
                speed: true,
            },
            ..GnssSim::default()
        }),
        ..sc
    }
}

/// A calibration walk: `metres` straight at cadence `f` by a walker whose walking step length is
/// `a`·f + `b`, between two 3 s pauses (the calibration wizard's tests).
pub fn calibration_walk(f: f64, metres: f64, a: f64, b: f64) -> Scenario {
    let mut w = Walker::default();
    w.step_length.walking.a = a;
    w.step_length.walking.b = b;
    Scenario {
        walker: w.clone(),
        ..Scenario::new(vec![
            Segment::still(3.0),
            Segment::walk_distance(metres, f, &w),
            Segment::still(3.0),
        ])
    }
}

/// A long mixed walk of about `minutes`: 60 m walks with 90° turns, 5 s pauses and 20 s runs, in
/// a loop (the throughput benchmarks' walk).
pub fn long_walk(minutes: f64) -> Scenario {
    let mut segs: Vec<Segment> = Vec::new();
    let w = Walker::default();
    while segs.iter().map(|s| s.duration_s).sum::<f64>() < minutes * 60.0 {
        segs.push(Segment::walk_distance(60.0, 1.8, &w));
        segs.push(Segment::walk(2.0, 1.8).turning(90.0));
        segs.push(Segment::still(5.0));
        segs.push(Segment::run(20.0, 3.0));
    }
    Scenario::new(segs)
}

/// `laps` times round a 400 m athletic track like Strozzi 2017 §5.1's outdoor path (84.4 m
/// straights, smooth 180° bends of 115.6 m) at 1.8 Hz, between 3 s pauses; the phone's OS yaw
/// wanders by 2° (1σ), as a real attitude's does. The two-sensor walk of `tests/hybrid.rs` (with
/// [`super::FootImu`]).
pub fn athletic_track(laps: usize) -> Scenario {
    let w = Walker::default();
    let f = 1.8;
    let mut segs = vec![Segment::still(3.0)];
    for _ in 0..laps {
        for _ in 0..2 {
            segs.push(Segment::walk_distance(84.4, f, &w));
            segs.push(Segment::walk_distance(115.6, f, &w).turning(180.0));
        }
    }
    segs.push(Segment::still(3.0));
    let mut sc = Scenario::new(segs);
    sc.sensors.os_yaw_error_deg = 2.0;
    sc.seed = 2017;
    sc
}

/// Riser of the pocket scenarios' stairs, m (the paper's office stairs, §6.1).
pub const POCKET_RISER_M: f64 = 0.17;
/// Tread of the pocket scenarios' stairs, m.
pub const POCKET_TREAD_M: f64 = 0.28;
/// Steps per floor of the pocket scenarios (two flights of nine): a floor is 3.06 m.
pub const POCKET_STEPS_PER_FLOOR: usize = 18;
/// Cadence on the pocket scenarios' stairs, Hz (the default walker's level amplitude there is
/// 37.7°, near the 38° at which its stair amplitudes are the paper's 53.07° and 26.62°).
pub const POCKET_STAIRS_HZ: f64 = 1.7;

/// `n` steps walked while the cadence ramps from `f0` to `f1` (a whole number of steps keeps the
/// next segment starting at a footfall).
fn steps(n: f64, f0: f64, f1: f64) -> Segment {
    Segment::walk(n / (0.5 * (f0 + f1)), f0).ramp_to(f1)
}

/// Pelvic rotation of the pocket scenarios' walker, degrees each way (Perry & Burnfield, *Gait
/// Analysis*: about 4° at a comfortable speed; the historic walker's 6° is kept elsewhere).
/// It peaks with the thigh's flexion, so the gyroscope's principal axis leans from the thigh's
/// lateral axis towards the vertical: by 6.2° at 4°, 9.4° at 6° (pocket_flat).
pub const POCKET_WAIST_YAW_DEG: f64 = 4.0;

/// A pocket scenario: the realistic thigh, the phone in `pose` in the right front pocket, a
/// barometer, floors of [`POCKET_STEPS_PER_FLOOR`] risers.
fn pocket(segments: Vec<Segment>, pose: PocketPose, seed: u64) -> Scenario {
    Scenario {
        walker: Walker {
            waist_yaw_deg: POCKET_WAIST_YAW_DEG,
            ..Walker::default()
        },
        pose,
        seed,
        floor_height_m: Some(POCKET_STEPS_PER_FLOOR as f64 * POCKET_RISER_M),
        sensors: super::Sensors {
            barometer: Some(BaroSim::default()),
            ..super::Sensors::default()
        },
        ..Scenario::new(segments)
    }
    .with_gait_thigh()
}

/// `floors` floors up (or down): per floor two flights of nine steps with a four-step landing
/// turning 180° between them and after them (the last landing is left to the caller).
fn floors(segs: &mut Vec<Segment>, floors: usize, up: bool) {
    let f = POCKET_STAIRS_HZ;
    let n = POCKET_STEPS_PER_FLOOR / 2;
    for k in 0..2 * floors {
        segs.push(if up {
            Segment::stairs_up(n, f, POCKET_RISER_M, POCKET_TREAD_M)
        } else {
            Segment::stairs_down(n, f, POCKET_RISER_M, POCKET_TREAD_M)
        });
        if k + 1 < 2 * floors {
            segs.push(steps(4.0, f, f).turning(180.0));
        }
    }
}

/// Level walk, three floors up, a level stretch there and back, three floors down, and the
/// level walk back; 3 s standing at both ends (about 2 min 20 s).
pub fn stairs_walk(pose: PocketPose) -> Scenario {
    let (f, fs) = (1.8, POCKET_STAIRS_HZ);
    let mut segs = vec![Segment::still(3.0), steps(16.5, f, f), steps(4.0, f, fs)];
    floors(&mut segs, 3, true);
    segs.push(steps(4.0, fs, f).turning(90.0));
    segs.push(steps(24.0, f, f));
    segs.push(steps(5.0, f, f).turning(180.0));
    segs.push(steps(24.0, f, f));
    segs.push(steps(4.0, f, fs).turning(90.0));
    floors(&mut segs, 3, false);
    segs.push(steps(4.0, fs, f).turning(180.0));
    segs.push(steps(20.0, f, f));
    segs.push(Segment::still(3.0));
    pocket(segs, pose, 1815)
}

/// Standing, a walk, sitting for 20 s (sitting down and standing up 1.5 s each), standing, a
/// walk back and standing.
pub fn sit_stand(pose: PocketPose) -> Scenario {
    let f = 1.8;
    let segs = vec![
        Segment::still(4.0),
        steps(20.5, f, f),
        steps(4.0, f, f).turning(90.0),
        Segment::still(3.0),
        Segment::sit(23.0),
        Segment::still(3.0),
        steps(4.5, f, f).turning(180.0),
        steps(24.0, f, f),
        Segment::still(4.0),
    ];
    pocket(segs, pose, 1816)
}

/// About 2.5 minutes of level walking with cadence changes (1.6–2.0 Hz, as ramps) and turns.
pub fn pocket_flat(pose: PocketPose) -> Scenario {
    let segs = vec![
        Segment::still(3.0),
        steps(40.5, 1.8, 1.8),
        steps(4.0, 1.8, 1.8).turning(90.0),
        steps(40.0, 1.8, 2.0),
        steps(5.0, 2.0, 2.0).turning(-120.0),
        steps(40.0, 2.0, 1.6),
        steps(30.0, 1.6, 1.6).turning(45.0),
        steps(4.0, 1.6, 1.7).turning(90.0),
        steps(50.0, 1.7, 1.9),
        steps(5.0, 1.9, 1.9).turning(-90.0),
        steps(40.0, 1.9, 1.8),
        Segment::still(3.0),
    ];
    pocket(segs, pose, 1817)
}

/// Everything: standing, a walk, sitting, two floors up, a walk with a cadence change, two
/// floors down, a walk with turns, a stop, a walk, standing.
pub fn pocket_mixed(pose: PocketPose) -> Scenario {
    let (f, fs) = (1.8, POCKET_STAIRS_HZ);
    let mut segs = vec![
        Segment::still(3.0),
        steps(12.5, f, f),
        Segment::still(2.0),
        Segment::sit(15.0),
        Segment::still(2.0),
        steps(10.5, f, f),
        steps(4.0, f, fs).turning(-90.0),
    ];
    floors(&mut segs, 2, true);
    segs.push(steps(4.0, fs, f).turning(90.0));
    segs.push(steps(20.0, f, 2.0));
    segs.push(steps(5.0, 2.0, 2.0).turning(180.0));
    segs.push(steps(20.0, 2.0, f));
    segs.push(steps(4.0, f, fs).turning(90.0));
    floors(&mut segs, 2, false);
    segs.push(steps(4.0, fs, f).turning(180.0));
    segs.push(steps(16.0, f, 1.65).turning(60.0));
    segs.push(Segment::still(4.0));
    segs.push(steps(12.5, 1.65, 1.65));
    segs.push(Segment::still(3.0));
    pocket(segs, pose, 1818)
}

/// The pitch calibration walk of Munoz Diaz 2015 §5.1: `metres` straight at a comfortable 1.75
/// Hz with the realistic thigh (upright, screen out), between 3 s of standing.
pub fn pitch_calibration_walk(metres: f64) -> Scenario {
    let w = Walker::default();
    let segs = vec![
        Segment::still(3.0),
        Segment::walk_distance(metres, 1.75, &w),
        Segment::still(3.0),
    ];
    pocket(segs, PocketPose::UprightOut, 1819)
}

/// A walk with the phone carried in `carry` (the carrying-mode detector and heading per mode): 3 s
/// standing, 40 steps, a 90° turn over 8, 30 steps, 4 s standing, 30 steps turning back by 90°,
/// 20 steps and 3 s standing. The seed sets the cadence (1.6–2.0 Hz) and, in the pocket, the
/// pose ([`PocketPose::ALL`]) and the side.
pub fn carried_walk(carry: super::Carry, seed: u64) -> Scenario {
    let f = 1.6 + 0.1 * (seed % 5) as f64;
    let segs = vec![
        Segment::still(3.0),
        steps(40.0, f, f),
        steps(8.0, f, f).turning(90.0),
        steps(30.0, f, f),
        Segment::still(4.0),
        steps(30.0, f, f).turning(-90.0),
        steps(20.0, f, f),
        Segment::still(3.0),
    ];
    let pose = PocketPose::ALL[(seed % 8) as usize];
    Scenario {
        carry,
        left_pocket: seed % 2 == 1,
        ..pocket(segs, pose, seed)
    }
}

/// A short walk: 20 steps between 3 s of standing, carried as [`carried_walk`] carries
/// it (the seed sets the cadence, the pose and the side). With `real_ends`
/// ([`Scenario::real_ends`]) the steps at both ends are real-shaped, and a phone in the pocket is
/// taken out half a second after the last step (over 1.5 s, then 2 s standing).
pub fn short_walk(carry: super::Carry, seed: u64, real_ends: bool) -> Scenario {
    let f = 1.6 + 0.1 * (seed % 5) as f64;
    let mut segments = vec![
        Segment::still(3.0),
        Segment::walk_steps(20.0, f),
        Segment::still(3.0),
    ];
    if real_ends && carry == super::Carry::Pocket {
        segments[2] = Segment::still(0.5);
        segments.extend([Segment::take_out(1.5), Segment::still(2.0)]);
    }
    Scenario {
        segments,
        real_ends,
        ..carried_walk(carry, seed)
    }
}

/// A change of carrying mode mid-walk (the heading carried across it): 3 s standing,
/// 30 steps, the phone moved from `from` to `to` over 2 s while 16 more steps go on straight,
/// a 90° turn over 8 steps, 30 steps and 3 s standing. The seed sets the cadence, the pocket's
/// pose and side, as [`carried_walk`] does. The switch starts 3 s + 32 steps in.
pub fn switched_walk(from: super::Carry, to: super::Carry, seed: u64) -> Scenario {
    let f = 1.6 + 0.1 * (seed % 5) as f64;
    let segments = vec![
        Segment::still(3.0),
        steps(30.0, f, f),
        steps(16.0, f, f),
        steps(8.0, f, f).turning(90.0),
        steps(30.0, f, f),
        Segment::still(3.0),
    ];
    Scenario {
        segments,
        switches: vec![super::carry::Switch {
            t_s: 3.0 + 32.0 / f,
            seconds: 2.0,
            to,
        }],
        ..carried_walk(from, seed)
    }
}
