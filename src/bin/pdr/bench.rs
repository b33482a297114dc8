//! `pdr bench`: the full pipeline's throughput on a long simulated walk, per configuration, and
//! the import's throughput on a large pdr-log.
//! May import: the `pdr` library; nothing of the other subcommands.

use pdr::engine::heading::HeadingMethod;
use pdr::engine::OrientationSource;
use pdr::engine::{replay, PipelineConfig, Record, StepDetectorConfig};
use pdr::io::pdrlog;
use pdr::sim::scenarios;
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
    bench_parse(&imu, repeats);
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
