//! `pdr bench`: the full pipeline's throughput on a long simulated walk, per configuration, and
//! the default pipeline's cost per stage, and the import's throughput on a large pdr-log.
//! May import: the `pdr` library; nothing of the other subcommands.

use pdr::engine::heading::HeadingMethod;
use pdr::engine::OrientationSource;
use pdr::engine::{
    replay, Pipeline, PipelineConfig, Record, Stage, StageClock, StepDetectorConfig,
};
use pdr::io::pdrlog;
use pdr::sim::scenarios;
use std::hint::black_box;
use std::sync::OnceLock;
use std::time::Instant;

pub fn bench(minutes: f64, repeats: usize) {
    let t = Instant::now();
    let sim = scenarios::long_walk(minutes).generate();
    let n = sim.records.len();
    out!(
        "simulated {n} IMU samples ({minutes} min at 100 Hz) in {:.2} s",
        t.elapsed().as_secs_f64()
    );
    let configs = [
        (
            "default: OS orientation, PLL, tip-to-tail 2016",
            PipelineConfig::default(),
        ),
        (
            "OS, PLL, closed form 2021",
            PipelineConfig::with_heading(HeadingMethod::ClosedForm2021),
        ),
        (
            "OS, PLL, PCA",
            PipelineConfig::with_heading(HeadingMethod::Pca),
        ),
        (
            "Madgwick (MARG), PLL, tip-to-tail",
            PipelineConfig {
                orientation: OrientationSource::MADGWICK,
                ..Default::default()
            },
        ),
        (
            "gravity low-pass, PLL (no heading)",
            PipelineConfig {
                orientation: OrientationSource::GRAVITY,
                ..Default::default()
            },
        ),
        (
            "OS, peak detector, tip-to-tail",
            PipelineConfig {
                detector: StepDetectorConfig::Peak(Default::default()),
                ..Default::default()
            },
        ),
    ];
    let imu: Vec<Record> = sim.records;
    for (name, cfg) in configs {
        let mut best = f64::INFINITY;
        let mut steps = 0;
        for _ in 0..repeats.max(1) {
            let t = Instant::now();
            let r = replay(cfg.clone(), &imu).unwrap();
            best = best.min(t.elapsed().as_secs_f64());
            steps = r.pipeline.track().len();
        }
        out!(
            "{:>7.2} M samples/s  {name}  ({steps} steps)",
            n as f64 / best / 1e6
        );
    }
    print_stages(&stage_costs(&imu, repeats));
    bench_parse(&imu, repeats);
}

/// The default pipeline's cost per sample, stage by stage.
#[derive(Debug, Clone, PartialEq)]
struct StageCosts {
    /// Each stage's time per sample, ns, the clock's own readings subtracted.
    stages: Vec<(Stage, f64)>,
    /// The whole replay's time per sample without the clock, ns.
    total_ns: f64,
    /// Samples per second without the clock and with it.
    rate: (f64, f64),
    /// The clock's own cost per stage call, ns, subtracted from each (the least of the runs).
    lap_ns: f64,
}

impl StageCosts {
    /// What no stage accounts for: the pipeline's routing between them, the replay loop, the
    /// bouts and the onset look-back, ns per sample.
    fn rest_ns(&self) -> f64 {
        self.total_ns - self.stages.iter().map(|s| s.1).sum::<f64>()
    }
}

/// A monotonic time, ns, for the stage clock.
fn now_ns() -> u64 {
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_nanos() as u64
}

/// Replays `imu` through the default pipeline `repeats` times with the stage clock and
/// without it, alternately (a shared machine's load then falls on both alike), and keeps the
/// fastest run of each, and each stage's least time, less the clock's own cost measured in
/// the same runs ([`StageClock::own_ns`]).
fn stage_costs(imu: &[Record], repeats: usize) -> StageCosts {
    let n = imu.len().max(1) as f64;
    let mut best_off = f64::INFINITY;
    let mut best_on = f64::INFINITY;
    // Per stage, the least time of the runs, ns per sample; and the clock's own cost then.
    let mut stages: Vec<(Stage, f64)> = Stage::ALL.iter().map(|&s| (s, f64::INFINITY)).collect();
    let mut lap_ns = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        black_box(replay(PipelineConfig::default(), imu).unwrap());
        best_off = best_off.min(t.elapsed().as_secs_f64());
        let mut p = Pipeline::new(PipelineConfig::default()).unwrap();
        p.set_stage_clock(Some(StageClock::new(now_ns)));
        let t = Instant::now();
        for r in imu {
            // A refused record is counted by the pipeline; the bench's walk has none.
            let _ = p.push(r);
        }
        p.finish();
        best_on = best_on.min(t.elapsed().as_secs_f64());
        let Some(clock) = p.stage_clock() else {
            continue;
        };
        let own = clock.own_ns();
        lap_ns = lap_ns.min(own);
        for (st, best) in &mut stages {
            let ns = clock.ns(*st) as f64 - own * clock.laps(*st) as f64;
            *best = best.min(ns.max(0.0) / n);
        }
    }
    StageCosts {
        stages,
        total_ns: best_off * 1e9 / n,
        rate: (n / best_off, n / best_on),
        lap_ns,
    }
}

fn print_stages(c: &StageCosts) {
    out!(
        "default pipeline per stage, ns per sample (least of the runs; the clock's own {:.0} ns per call subtracted):",
        c.lap_ns
    );
    let share = |ns: f64| 100.0 * ns / c.total_ns;
    for &(st, ns) in &c.stages {
        if ns > 0.0 {
            out!("{:>9.1} ns  {:>5.1} %  {}", ns, share(ns), st.name());
        } else {
            // Less than the clock's own cost varies by: callgrind resolves these.
            out!(
                "{:>12}  {:>7}  {} (within the clock's noise)",
                "-",
                "-",
                st.name()
            );
        }
    }
    let rest = c.rest_ns();
    if rest >= 0.0 {
        out!(
            "{rest:>9.1} ns  {:>5.1} %  routing and the rest",
            share(rest)
        );
    } else {
        // Timed, the stages run slower than untimed (the clock's readings disturb the caches and
        // the pipelining): their sum then exceeds the untimed total, and the rest cannot be told.
        out!(
            "{:>12}  {:>7}  routing and the rest (the timed stages sum to {:.1} ns more than the untimed total)",
            "-",
            "-",
            -rest
        );
    }
    out!(
        "{:>9.1} ns  100.0 %  total: {:.2} M samples/s without the clock, {:.2} M with it",
        c.total_ns,
        c.rate.0 / 1e6,
        c.rate.1 / 1e6
    );
}

/// Import throughput: a pdr-log of at least 60 MB, built from the simulated walk, read through
/// the import layer (format detection, streaming parse, records) from memory.
fn bench_parse(records: &[Record], repeats: usize) {
    let mut text = pdrlog::preamble();
    let lines: Vec<String> = records.iter().map(pdrlog::line).collect();
    let span = match (records.first(), records.last()) {
        (Some(Record::Imu(a)), Some(Record::Imu(b))) => b.t - a.t + 0.01,
        _ => 0.0,
    };
    let mut copy = 0;
    'fill: loop {
        // Later copies continue the clock, so the log stays in time order.
        for (r, l) in records.iter().zip(&lines) {
            if text.len() >= 60_000_000 {
                break 'fill;
            }
            match r {
                Record::Imu(s) if copy > 0 => {
                    let mut s = *s;
                    s.t += span * copy as f64;
                    text.push_str(&pdrlog::line(&Record::Imu(s)));
                }
                _ => text.push_str(l),
            }
        }
        copy += 1;
    }
    let bytes = text.into_bytes();
    let mb = bytes.len() as f64 / 1e6;
    let mut set = pdr::io::import::MemSet::new(vec![("bench.pdrlog".into(), bytes)]);
    let mut best = f64::INFINITY;
    let mut n = 0;
    for _ in 0..repeats.clamp(1, 3) {
        let t = Instant::now();
        let logs = pdr::io::import::import_all(&mut set);
        best = best.min(t.elapsed().as_secs_f64());
        n = logs.iter().flatten().map(|l| l.records.len()).sum();
    }
    out!(
        "{:>7.2} s  to import a {mb:.1} MB pdr-log ({n} records, {:.0} MB/s)",
        best,
        mb / best
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stage_table_has_every_stage_timed() {
        let imu = scenarios::long_walk(0.5).generate().records;
        let c = stage_costs(&imu, 1);
        let names: Vec<Stage> = c.stages.iter().map(|s| s.0).collect();
        assert_eq!(names, Stage::ALL.to_vec());
        assert!(c.stages.iter().all(|s| s.1.is_finite() && s.1 >= 0.0));
        // Timed stages were called: every sample goes through the check and the carry.
        let clocked = |st: Stage| c.stages.iter().find(|s| s.0 == st).unwrap().1;
        assert!(clocked(Stage::Check) > 0.0 || clocked(Stage::Carry) > 0.0);
        assert!(c.total_ns > 0.0 && c.rate.0 > 0.0 && c.rate.1 > 0.0);
    }
}
