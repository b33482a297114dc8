//! The fusion tests' measures on simulated walks: the pipeline's run, the truth in its local
//! frame, the errors of the fused track and of the fixes alone, and their 75th percentile
//! (tests/fusion.rs, tests/sim_gnss.rs).

use pdr::engine::fusion::FusedStep;
use pdr::engine::{replay, Pipeline, PipelineConfig};
use pdr::sim::Simulation;

/// The pipeline after replaying a simulated walk with `cfg`; it must refuse none of its records.
pub fn run(sim: &Simulation, cfg: PipelineConfig) -> Pipeline {
    let r = replay(cfg, &sim.records).expect("valid config");
    assert_eq!(r.refused, 0, "clean input refused: {:?}", r.errors.first());
    r.pipeline
}

/// The true position at time `t` in the pipeline's local frame (its origin is the first
/// usable fix, not the start of the walk).
pub fn truth_at(sim: &Simulation, p: &Pipeline, t: f64) -> (f64, f64) {
    let (e, n) = sim.truth.position_at(t);
    let (lat, lon, h) = sim.truth.frame.unwrap().to_geodetic([e, n, 0.0]);
    let [e, n, _] = p.frame().unwrap().to_enu(lat, lon, h);
    (e, n)
}

/// Distance of each step of `track` from the truth, m.
pub fn errors(sim: &Simulation, p: &Pipeline, track: &[FusedStep]) -> Vec<f64> {
    track
        .iter()
        .map(|s| {
            let (e, n) = truth_at(sim, p, s.t);
            libm::hypot(s.east_m - e, s.north_m - n)
        })
        .collect()
}

/// Distance of each fix the pipeline took from the truth at its time, m (GNSS alone).
pub fn gnss_errors(sim: &Simulation, p: &Pipeline) -> Vec<f64> {
    let frame = p.frame().unwrap();
    p.fixes()
        .iter()
        .map(|f| {
            let (e, n) = frame.en_of_fix(f);
            let (te, tn) = truth_at(sim, p, f.t);
            libm::hypot(e - te, n - tn)
        })
        .collect()
}

/// The 75th percentile.
pub fn p75(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    pdr::eval::percentile(&v, 75.0)
}

/// Fails unless every step of `track` has a valid position covariance (finite, non-negative
/// variances, |correlation| ≤ 1) and finite standard deviations of the scale and the heading
/// correction: what the page draws as ellipses and ±1σ bands.
pub fn assert_valid_covariances(track: &[FusedStep], what: &str) {
    for s in track {
        let [ee, en, nn] = s.cov;
        assert!(
            ee >= 0.0 && nn >= 0.0 && en * en <= ee * nn * (1.0 + 1e-9) + 1e-12,
            "{what}: t {:.1} s: position covariance {:?} is no covariance",
            s.t,
            s.cov
        );
        assert!(
            s.scale_bias_sd.iter().all(|v| v.is_finite() && *v >= 0.0),
            "{what}: t {:.1} s: σ of scale and correction {:?}",
            s.t,
            s.scale_bias_sd
        );
    }
}
