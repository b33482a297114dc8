//! Times `analysis::analyse` (what upload mode runs in its worker) natively on one log, to set
//! beside the wasm figure the upload benchmark prints: `cargo run --release --example
//! analyse_bench -- LOG`.
use std::time::Instant;
fn main() {
    let path = std::env::args().nth(1).expect("usage: analyse_bench LOG");
    let mut set = pdr::io::import::DirSet::new(std::path::Path::new(&path)).expect("open");
    let log = pdr::io::import::import_all(&mut set)
        .remove(0)
        .expect("import");
    let log = &log;
    let cfg = pdr::engine::PipelineConfig::default();
    for _ in 0..3 {
        let t0 = Instant::now();
        let a = pdr::analysis::analyse(log, &cfg, &mut |_, _| {}).unwrap();
        let t1 = Instant::now();
        let _ = a.to_bytes();
        let t2 = Instant::now();
        println!(
            "{} samples: analyse {:.3} s ({:.2} M/s), to_bytes {:.3} s",
            a.trace.t.len(),
            (t1 - t0).as_secs_f64(),
            a.trace.t.len() as f64 / (t1 - t0).as_secs_f64() / 1e6,
            (t2 - t1).as_secs_f64()
        );
    }
}
