//! The analysis's trip from the worker to the page as bytes ([`Analysis::to_bytes`]): a round
//! trip gives the same analysis back, NaN included, and garbage is a clear error. The figures of
//! the encoding (size, encode and decode time on a real walk) come from the ignored test
//! `encoding_figures` (docs/development.md, "The analysis's bytes").

use pdr::analysis::{analyse, Analysis};
use pdr::engine::PipelineConfig;
use pdr::io::import::{import_all, Format, Log, MemSet};
use std::path::Path;
use std::time::Instant;

fn demo() -> Analysis {
    let mut log = Log::new("demo.pdrlog", Format::PdrLog);
    log.records = pdr::sim::scenarios::demo_walk().generate().records;
    analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap()
}

#[test]
fn a_round_trip_gives_the_same_analysis() {
    let a = demo();
    assert!(!a.steps.is_empty() && !a.trace.t.is_empty());
    let bytes = a.to_bytes().unwrap();
    let back = Analysis::from_bytes(&bytes).unwrap();
    assert_eq!(back, a);
    assert_eq!(back.to_bytes().unwrap(), bytes);
}

#[test]
fn nan_survives_the_trip() {
    let mut a = demo();
    a.trace.height[0] = f32::NAN;
    a.fused.push([f64::NAN, 1.0, f64::NEG_INFINITY, 0.5, -0.0]);
    a.sigma_thresholds.1 = f64::NAN;
    let back = Analysis::from_bytes(&a.to_bytes().unwrap()).unwrap();
    assert!(back.trace.height[0].is_nan());
    let last = back.fused.last().unwrap();
    assert!(last[0].is_nan() && last[2] == f64::NEG_INFINITY);
    assert!(last[4] == 0.0 && last[4].is_sign_negative());
    assert!(back.sigma_thresholds.1.is_nan());
    assert_eq!(back.steps, a.steps);
}

#[test]
fn garbage_and_cut_bytes_are_errors_not_panics() {
    let bytes = demo().to_bytes().unwrap();
    for cut in [0, 1, 7, bytes.len() / 2, bytes.len() - 1] {
        let e = Analysis::from_bytes(&bytes[..cut]).unwrap_err();
        assert!(e.to_string().starts_with("unreadable analysis"), "{e}");
    }
    assert!(Analysis::from_bytes(&[0xff; 64]).is_err());
}

/// The real walk the figures are measured on (IPIN 2023, track 3, about 3.7 MB of text).
const FIGURES_LOG: &str = "../shared/data/ipin2023/IPIN2023_T3_TrainingTrial01_repetition01.txt";

/// Prints the encoded size and the median encode and decode times of the analysis of
/// [`FIGURES_LOG`]; skipped with a message when the log is absent. Run with
/// `cargo test --release --test analysis_bytes -- --ignored --nocapture`.
#[test]
#[ignore = "figures, not a check: run with --ignored --nocapture"]
fn encoding_figures() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(FIGURES_LOG);
    let Ok(text) = std::fs::read(&path) else {
        eprintln!("skipped: {} is absent", path.display());
        return;
    };
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let mut set = MemSet::new(vec![(name.clone(), text)]);
    let log = import_all(&mut set).remove(0).unwrap();
    let a = analyse(&log, &PipelineConfig::default(), &mut |_, _| {}).unwrap();
    let bytes = a.to_bytes().unwrap();
    let median = |f: &mut dyn FnMut()| {
        let mut ms: Vec<f64> = (0..51)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        ms.sort_by(f64::total_cmp);
        ms[ms.len() / 2]
    };
    let enc = median(&mut || {
        std::hint::black_box(a.to_bytes().unwrap());
    });
    let dec = median(&mut || {
        std::hint::black_box(Analysis::from_bytes(&bytes).unwrap());
    });
    println!(
        "{name}: {} samples, {} steps; encoded {} bytes; encode {enc:.2} ms, decode {dec:.2} ms (median of 51)",
        a.trace.t.len(),
        a.steps.len(),
        bytes.len()
    );
}
