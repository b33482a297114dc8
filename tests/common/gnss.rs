//! A simulated walk's GNSS fixes against its truth, and the autocorrelation of their error
//! (tests/sim_gnss.rs, examples/city_real_gnss.rs).

use pdr::engine::types::GnssFix;
use pdr::engine::Record;
use pdr::sim::Simulation;

/// A fix and its error against the truth at its time (east, north), m.
pub struct Fixed {
    pub fix: GnssFix,
    pub err: (f64, f64),
}

/// Every fix of a simulated walk with its error against the truth.
pub fn fixed(sim: &Simulation) -> Vec<Fixed> {
    let frame = sim.truth.frame.expect("a walk with GNSS has a frame");
    sim.records
        .iter()
        .filter_map(|r| match r {
            Record::Gnss(f) => Some(*f),
            _ => None,
        })
        .map(|fix| {
            let (e, n) = frame.en_of_fix(&fix);
            let (te, tn) = sim.truth.position_at(fix.t);
            Fixed {
                fix,
                err: (e - te, n - tn),
            }
        })
        .collect()
}

/// Autocorrelation of the error per axis, normalised by the reported accuracy (which sets the
/// error's σ), at `lag` s, pooled over the walks.
pub fn autocorrelation(walks: &[Vec<Fixed>], lag: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for w in walks {
        let z: Vec<(f64, f64, f64)> = w
            .iter()
            .map(|f| {
                let a = f.fix.h_accuracy_m;
                (f.fix.t, f.err.0 / a, f.err.1 / a)
            })
            .collect();
        for (i, a) in z.iter().enumerate() {
            den += a.1 * a.1 + a.2 * a.2;
            if let Some(b) = z[i..].iter().find(|b| (b.0 - a.0 - lag).abs() < 1e-6) {
                num += a.1 * b.1 + a.2 * b.2;
            }
        }
    }
    // Each pair was counted once; the denominator counts every fix.
    num / den
}
