//! The embedded demo walk: the simulator's [`crate::sim::scenarios::demo_walk`] run through the
//! default pipeline. The web page and `pdr demo` show the same figures.

use crate::engine::pipeline::{replay, PipelineConfig, StepRecord};
use crate::sim::scenarios;

/// Figures and series of the demo walk.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DemoSummary {
    /// Steps counted by the engine.
    pub steps: usize,
    /// True steps.
    pub truth_steps: usize,
    /// Distance walked per the engine, m.
    pub distance_m: f64,
    /// True distance, m.
    pub truth_distance_m: f64,
    /// Distance between the estimated and the true end point, m.
    pub end_error_m: f64,
    /// Duration, s.
    pub duration_s: f64,
    /// IMU samples processed.
    pub samples: u64,
    /// The estimated track.
    #[serde(skip)]
    pub track: Vec<StepRecord>,
    /// The true path at each true step, (east, north) m.
    #[serde(skip)]
    pub truth_path: Vec<(f64, f64)>,
}

/// Generates and processes the demo walk.
pub fn run_demo() -> DemoSummary {
    let sim = scenarios::demo_walk().generate();
    let r = replay(PipelineConfig::default(), &sim.records)
        .expect("the default configuration is valid");
    let d = r.pipeline.diagnostics();
    let track = r.pipeline.track().to_vec();
    let end = track.last().map_or((0.0, 0.0), |s| (s.east_m, s.north_m));
    DemoSummary {
        steps: track.len(),
        truth_steps: sim.truth.steps.len(),
        distance_m: d.distance_m,
        truth_distance_m: sim.truth.distance_m,
        end_error_m: libm::hypot(end.0 - sim.truth.end.0, end.1 - sim.truth.end.1),
        duration_s: d.time_span.map_or(0.0, |(a, b)| b - a),
        samples: d.samples,
        track,
        truth_path: std::iter::once((0.0, 0.0))
            .chain(sim.truth.steps.iter().map(|s| (s.east_m, s.north_m)))
            .collect(),
    }
}
