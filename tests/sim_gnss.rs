//! The simulated GNSS receiver's real-phone error shapes (`sim::GnssErrors`): each
//! shape measured on the fixes it produces against the truth, over several seeds, and shown to
//! be absent when it is off; the default shapes leave the city walk bit for bit what it was.
//! These tests are about the simulator; the fusion's targets on the real-GNSS city walk
//! (`sim::scenarios::gnss_city_walk_real`) live in tests/fusion.rs, and
//! `cargo run --release --example city_real_gnss` prints the default pipeline's figures on it.

use common::fusion::run;
use common::gnss::{autocorrelation, fixed, Fixed};
use pdr::engine::types::GnssFix;
use pdr::engine::{PipelineConfig, Record};
use pdr::sim::{
    scenarios, Canyon, Gait, GnssErrors, GnssSim, Multipath, Scenario, Segment, Simulation, Walker,
};

mod common;

/// Seeds over which the statistics are taken.
const SEEDS: std::ops::RangeInclusive<u64> = 1..=8;

/// A 20-minute walk (straight legs, turns, two one-minute stands) with the receiver `g`.
fn long_walk(g: GnssSim, seed: u64) -> Simulation {
    let w = Walker::default();
    let mut segs = vec![Segment::still(3.0)];
    for k in 0..6 {
        segs.push(Segment::walk(170.0, 1.8));
        segs.push(Segment::walk(2.5, 1.8).turning(90.0));
        if k % 3 == 1 {
            segs.push(Segment::still(60.0));
        }
    }
    segs.push(Segment::walk_distance(20.0, 1.8, &w));
    segs.push(Segment::still(3.0));
    Scenario {
        seed,
        gnss: Some(g),
        clock_offset_s: 1_780_272_000.0,
        ..Scenario::new(segs)
    }
    .generate()
}

fn with(errors: GnssErrors) -> GnssSim {
    GnssSim {
        errors,
        ..GnssSim::default()
    }
}

fn multipath(white_share: f64) -> GnssErrors {
    GnssErrors {
        multipath: Some(Multipath {
            tau_s: 14.0,
            white_share,
        }),
        ..GnssErrors::default()
    }
}

/// Share of fixes whose error is within their reported accuracy.
fn within_accuracy(walks: &[Vec<Fixed>]) -> f64 {
    let all: Vec<&Fixed> = walks.iter().flatten().collect();
    let inside = all
        .iter()
        .filter(|f| libm::hypot(f.err.0, f.err.1) <= f.fix.h_accuracy_m)
        .count();
    inside as f64 / all.len() as f64
}

fn walks(g: &GnssSim) -> Vec<Vec<Fixed>> {
    SEEDS.map(|s| fixed(&long_walk(g.clone(), s))).collect()
}

/// FNV-1a over every record's time and values (the fixes' all of them, the samples' time and
/// acceleration).
fn record_digest(records: &[Record]) -> u64 {
    common::fnv1a(records.iter().flat_map(|r| match r {
        Record::Gnss(f) => vec![
            f.t,
            f.lat_deg,
            f.lon_deg,
            f.h_accuracy_m,
            f.altitude_m.unwrap_or(f64::NAN),
            f.speed_mps.unwrap_or(-1.0),
        ],
        Record::Imu(s) => vec![s.t, s.accel[0], s.accel[1], s.accel[2]],
        _ => vec![r.t()],
    }))
}

/// The city walk's records before the error shapes existed (commit b7edfd8).
const CITY_WALK_DIGEST: u64 = 0x60e6_c88f_f72d_b254;

#[test]
fn default_shapes_leave_the_city_walk_bit_identical() {
    let sim = scenarios::gnss_city_walk().generate();
    assert_eq!(sim.records.len(), 76865);
    let d = record_digest(&sim.records);
    assert_eq!(d, CITY_WALK_DIGEST, "city walk changed: {d:#x}");
    assert!(!GnssSim::default().errors.any());
}

#[test]
fn multipath_error_is_correlated_with_its_time_constant() {
    let walks = walks(&with(multipath(0.0)));
    for (lag, tol) in [(5.0, 0.08), (10.0, 0.08), (20.0, 0.08), (40.0, 0.08)] {
        let rho = autocorrelation(&walks, lag);
        let want = libm::exp(-lag / 14.0);
        println!("lag {lag:>4} s: autocorrelation {rho:.3}, e^(-lag/14 s) {want:.3}");
        assert!(
            (rho - want).abs() <= tol,
            "autocorrelation {rho:.3} at {lag} s, want {want:.3}"
        );
    }
    // A white share lowers it in proportion.
    let rho = autocorrelation(&self::walks(&with(multipath(0.3))), 10.0);
    let want = 0.7 * libm::exp(-10.0 / 14.0);
    assert!((rho - want).abs() <= 0.08, "{rho:.3} against {want:.3}");
    // Off, the error is white.
    let rho = autocorrelation(&self::walks(&GnssSim::default()), 10.0);
    assert!(rho.abs() <= 0.06, "white error's autocorrelation {rho:.3}");
}

#[test]
fn optimistic_accuracy_understates_the_error() {
    // Honest: 68 % of the errors within the reported accuracy (its definition).
    let honest = within_accuracy(&walks(&with(multipath(0.1))));
    assert!((honest - 0.68).abs() <= 0.06, "honest: {honest:.3}");
    // Optimistic by 1.3: 1 − e^(−(1.51/1.3)²/2) = 49 %.
    let optimistic = within_accuracy(&walks(&with(GnssErrors {
        optimism: 1.3,
        ..multipath(0.1)
    })));
    let want = 1.0 - libm::exp(-0.5 * (1.51 / 1.3) * (1.51 / 1.3));
    println!("within accuracy: honest {honest:.3}, optimistic {optimistic:.3} (want {want:.3})");
    assert!(
        (optimistic - want).abs() <= 0.06,
        "optimistic: {optimistic:.3} against {want:.3}"
    );
    // The real-GNSS city walk too.
    let city: Vec<Vec<Fixed>> = (1..=4)
        .map(|s| {
            let mut sc = scenarios::gnss_city_walk_real();
            sc.seed = s;
            fixed(&sc.generate())
        })
        .collect();
    let share = within_accuracy(&city);
    println!("real-GNSS city walk: {share:.3} within the reported accuracy");
    assert!(share < 0.6, "real-GNSS city walk: {share:.3}");
}

fn city_real(seed: u64) -> Simulation {
    let mut sc = scenarios::gnss_city_walk_real();
    sc.seed = seed;
    sc.generate()
}

#[test]
fn the_first_fix_is_stale() {
    for seed in 1..=4 {
        let f = fixed(&city_real(seed));
        let d0 = libm::hypot(f[0].err.0, f[0].err.1);
        let d1 = libm::hypot(f[1].err.0, f[1].err.1);
        assert!(
            (2000.0..=5000.0).contains(&d0),
            "seed {seed}: first fix {d0:.0} m away"
        );
        assert!(f[0].fix.h_accuracy_m <= 30.0, "a modest reported accuracy");
        assert!(d1 < 100.0, "seed {seed}: second fix {d1:.0} m away");
    }
    let f = fixed(&scenarios::gnss_city_walk().generate());
    assert!(libm::hypot(f[0].err.0, f[0].err.1) < 100.0);
}

/// Fixes whose white error is 0.3 m (1σ) per axis, with `errors`.
fn precise(errors: GnssErrors) -> GnssSim {
    GnssSim {
        accuracy_m: (0.45, 0.45),
        errors,
        ..GnssSim::default()
    }
}

/// RMS distance a fix moves in 10 s while the walker stands (the two one-minute stands of
/// [`long_walk`], their first and last 2 s left out), m.
fn stand_wander(g: &GnssSim) -> f64 {
    let (mut sum, mut n) = (0.0, 0);
    for seed in SEEDS {
        let sim = long_walk(g.clone(), seed);
        let fixes = common::fixes(&sim.records);
        for &(a, b, _) in sim
            .truth
            .segments
            .iter()
            .filter(|s| s.2 == Gait::Still && s.1 - s.0 > 30.0)
        {
            let inside: Vec<&GnssFix> = fixes
                .iter()
                .filter(|f| f.t >= a + 2.0 && f.t <= b - 2.0)
                .collect();
            let frame = sim.truth.frame.unwrap();
            for (i, f) in inside.iter().enumerate() {
                if let Some(g) = inside.get(i + 10) {
                    let (e0, n0) = frame.en_of_fix(f);
                    let (e1, n1) = frame.en_of_fix(g);
                    sum += (e1 - e0) * (e1 - e0) + (n1 - n0) * (n1 - n0);
                    n += 1;
                }
            }
        }
    }
    assert!(n > 500, "{n} pairs");
    libm::sqrt(sum / n as f64)
}

#[test]
fn fixes_wander_while_the_walker_stands() {
    let on = stand_wander(&precise(GnssErrors {
        stand_wander_m: 3.0,
        ..GnssErrors::default()
    }));
    let off = stand_wander(&precise(GnssErrors::default()));
    println!("while standing, fixes move {on:.2} m per 10 s (off: {off:.2} m)");
    assert!((2.3..=3.7).contains(&on), "wander {on:.2} m per 10 s");
    assert!(off < 0.8, "without the shape {off:.2} m per 10 s");
    // On the real-GNSS city walk the fixes move during the 6 s stop too.
    for seed in 1..=4 {
        let sim = city_real(seed);
        let stop = sim.truth.segments[9];
        assert_eq!(stop.1 - stop.0, 6.0, "the stop");
        let f: Vec<GnssFix> = common::fixes(&sim.records)
            .into_iter()
            .filter(|f| f.t > stop.0 && f.t < stop.1)
            .collect();
        assert!(f.windows(2).all(|w| w[0].lat_deg != w[1].lat_deg));
    }
}

/// The fixes in the first `hold_s` of each walk that follows a stand of at least 2 s.
fn walk_starts(sim: &Simulation) -> Vec<f64> {
    let s = &sim.truth.segments;
    (1..s.len())
        .filter(|&i| s[i].2 != s[i - 1].2 && s[i - 1].1 - s[i - 1].0 >= 2.0)
        .filter(|&i| matches!(s[i - 1].2, Gait::Still))
        .map(|i| s[i].0)
        .collect()
}

#[test]
fn the_receiver_holds_at_walk_start_then_jumps() {
    let hold = |start_hold_s| {
        precise(GnssErrors {
            start_hold_s,
            speed: true,
            ..GnssErrors::default()
        })
    };
    for seed in 1..=4 {
        let sim = long_walk(hold(6.0), seed);
        let f = fixed(&sim);
        let starts = walk_starts(&sim);
        assert_eq!(starts.len(), 3, "three walk starts");
        for s in starts {
            let before = f.iter().rposition(|x| x.fix.t < s).unwrap();
            let held: Vec<&Fixed> = f
                .iter()
                .filter(|x| x.fix.t >= s && x.fix.t < s + 6.0)
                .collect();
            assert_eq!(held.len(), 6);
            for x in &held {
                assert_eq!(
                    (x.fix.lat_deg, x.fix.lon_deg),
                    (f[before].fix.lat_deg, f[before].fix.lon_deg),
                    "held at the standing position"
                );
                assert_eq!(x.fix.speed_mps, Some(0.0));
            }
            // The walker has gone on; the fix then catches up at once.
            let last = held.last().unwrap();
            assert!(
                libm::hypot(last.err.0, last.err.1) > 4.0,
                "lag at the end of the hold"
            );
            let next = &f[before + 7];
            assert!(next.fix.t >= s + 6.0);
            assert!(libm::hypot(next.err.0, next.err.1) < 1.5, "caught up");
            assert!(next.fix.speed_mps.unwrap() > 0.8, "walking speed reported");
        }
        // Without the hold the fixes follow the walker from the start.
        let sim = long_walk(hold(0.0), seed);
        let f = fixed(&sim);
        for s in walk_starts(&sim) {
            let x = f.iter().find(|x| x.fix.t >= s + 5.0).unwrap();
            assert!(libm::hypot(x.err.0, x.err.1) < 1.5);
        }
    }
    // The real-GNSS city walk holds at its start (after 3 s standing) for 6 s.
    let f = common::fixes(&city_real(1).records);
    let t0 = f[0].t - 0.5;
    let held: Vec<&GnssFix> = f
        .iter()
        .filter(|x| x.t >= t0 + 3.0 && x.t < t0 + 9.0)
        .collect();
    assert_eq!(held.len(), 6);
    assert!(held
        .iter()
        .all(|x| x.lat_deg == held[0].lat_deg && x.speed_mps == Some(0.0)));
}

#[test]
fn latency_reports_where_the_walker_was() {
    for (seed, latency_s) in (1..=4).flat_map(|s| [(s, 2.0), (s, 0.0)]) {
        let sim = long_walk(
            precise(GnssErrors {
                latency_s,
                ..GnssErrors::default()
            }),
            seed,
        );
        let frame = sim.truth.frame.unwrap();
        let walking = |t: f64| {
            sim.truth
                .segments
                .iter()
                .any(|s| t > s.0 + 3.0 && t < s.1 && s.2 == Gait::Walk)
        };
        let (mut then, mut now, mut n) = (0.0, 0.0, 0.0);
        for f in common::fixes(&sim.records).iter().filter(|f| walking(f.t)) {
            let (e, no) = frame.en_of_fix(f);
            let (e0, n0) = sim.truth.position_at(f.t - latency_s);
            let (e1, n1) = sim.truth.position_at(f.t);
            then += libm::hypot(e - e0, no - n0);
            now += libm::hypot(e - e1, no - n1);
            n += 1.0;
        }
        let (then, now) = (then / n, now / n);
        assert!(
            then < 0.6,
            "{then:.2} m from where the walker was {latency_s} s ago"
        );
        if latency_s > 0.0 {
            assert!(now > 2.0, "{now:.2} m behind the walker");
        } else {
            assert!(now < 0.6, "{now:.2} m behind the walker without latency");
        }
    }
}

#[test]
fn an_urban_canyon_holds_a_large_bias_under_an_optimistic_accuracy() {
    let start = 1_780_272_000.0;
    let canyon = |bias_m| {
        precise(GnssErrors {
            canyons: vec![Canyon {
                start_s: start + 100.0,
                end_s: start + 190.0,
                bias_m,
            }],
            ..GnssErrors::default()
        })
    };
    for seed in 1..=4 {
        let on = fixed(&long_walk(canyon(25.0), seed));
        let off = fixed(&long_walk(canyon(0.0), seed));
        for (a, b) in on.iter().zip(&off) {
            let d = libm::hypot(a.err.0, a.err.1);
            let t = a.fix.t - start;
            assert_eq!(a.fix.h_accuracy_m, b.fix.h_accuracy_m, "accuracy unchanged");
            if (105.0..185.0).contains(&t) {
                assert!((d - 25.0).abs() < 1.5, "at {t} s: {d:.1} m");
            } else if !(95.0..195.0).contains(&t) {
                assert!(d < 1.5, "outside the canyon at {t} s: {d:.1} m");
            }
        }
    }
    // On the real-GNSS city walk: the canyon's errors, against the reported accuracy.
    let (a, b, bias) = scenarios::GNSS_REAL_CANYON;
    for seed in 1..=4 {
        let f = fixed(&city_real(seed));
        let t0 = f[0].fix.t - 0.5;
        let inside: Vec<&Fixed> = f
            .iter()
            .filter(|x| x.fix.t - t0 > a + 5.0 && x.fix.t - t0 < b - 5.0)
            .collect();
        let over = inside
            .iter()
            .filter(|x| libm::hypot(x.err.0, x.err.1) > 0.5 * bias)
            .count();
        assert!(
            over as f64 >= 0.8 * inside.len() as f64,
            "seed {seed}: {over} of {} fixes in the canyon off by more than {} m",
            inside.len(),
            0.5 * bias
        );
        assert!(inside.iter().all(|x| x.fix.h_accuracy_m <= 15.0));
    }
}

/// The default pipeline on the real-GNSS city walk, seeds 1–4: one fused step per step from
/// the first fused one on, each at its step's time, and as many smoothed steps. The fusion's
/// targets on this walk live in tests/fusion.rs; `cargo run --release --example
/// city_real_gnss` prints its figures.
#[test]
fn fused_steps_sit_on_the_steps_of_the_city_real_gnss_walk() {
    for seed in 1..=4 {
        let p = run(&city_real(seed), PipelineConfig::default());
        let (track, fused) = (p.track(), p.fused());
        assert!(!fused.is_empty() && fused.len() <= track.len());
        let skip = track.len() - fused.len();
        for (s, f) in track[skip..].iter().zip(fused) {
            assert_eq!(s.t, f.t, "fused step at a step's time");
        }
        assert_eq!(p.smoothed().len(), fused.len());
    }
}
