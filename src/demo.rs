//! The embedded demo walks, run through the default pipeline; the web page and `pdr demo` show
//! the same figures.
//! May import: `engine`, `sim`, `eval`, `analysis` (numbers as the page writes them).
//!
//! - [`run_demo`]: the simulator's [`crate::sim::scenarios::demo_walk`], PDR only;
//! - [`run_fusion_demo`]: [`crate::sim::scenarios::gnss_city_walk`], with GNSS, through the
//!   fusion filter and the smoother.

use crate::analysis::fixed;
use crate::engine::fusion::FusedStep;
use crate::engine::{replay, PipelineConfig, StepRecord};
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

/// Figures and series of the GNSS demo walk. Positions are east and north, m, in the local
/// frame of the first usable fix.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FusionDemoSummary {
    /// Steps counted.
    pub steps: usize,
    /// Fixes received, used in the filter, refused by the gate.
    pub fixes: usize,
    /// See `fixes`.
    pub fixes_used: u64,
    /// See `fixes`.
    pub fixes_gated: u64,
    /// 75th percentile of the error of the fixes themselves, m.
    pub gnss_p75_m: f64,
    /// Of the PDR-only track (anchored at the smoothed start), m.
    pub pdr_p75_m: f64,
    /// Of the fused track, m.
    pub fused_p75_m: f64,
    /// Of the smoothed track, m.
    pub smoothed_p75_m: f64,
    /// Step-length scale found.
    pub scale: f64,
    /// The true scale ([`scenarios::GNSS_CITY_LENGTH_FACTOR`]).
    pub true_scale: f64,
    /// Heading correction found, degrees.
    pub heading_correction_deg: f64,
    /// The true correction, degrees ([`scenarios::GNSS_CITY_HEADING_BIAS_DEG`]).
    pub true_heading_correction_deg: f64,
    /// Magnetic declination applied, degrees.
    pub declination_deg: f64,
    /// The local frame's geodetic origin (latitude°, longitude°, height m): the first usable
    /// fix, where the base map is placed.
    #[serde(skip)]
    pub origin: (f64, f64, f64),
    /// The true path.
    #[serde(skip)]
    pub truth: Vec<(f64, f64)>,
    /// The fixes: east, north, reported accuracy (m).
    #[serde(skip)]
    pub fix_points: Vec<(f64, f64, f64)>,
    /// PDR alone.
    #[serde(skip)]
    pub pdr: Vec<(f64, f64)>,
    /// Fused.
    #[serde(skip)]
    pub fused: Vec<(f64, f64)>,
    /// Smoothed.
    #[serde(skip)]
    pub smoothed: Vec<(f64, f64)>,
}

fn p75(mut v: Vec<f64>) -> f64 {
    crate::engine::sort::sort_by(&mut v, f64::total_cmp);
    crate::eval::percentile(&v, 75.0)
}

/// Generates and processes the GNSS demo walk.
pub fn run_fusion_demo() -> FusionDemoSummary {
    let sim = scenarios::gnss_city_walk().generate();
    let r = replay(PipelineConfig::default(), &sim.records)
        .expect("the default configuration is valid");
    let p = &r.pipeline;
    let frame = *p.frame().expect("the demo walk has fixes");
    let sim_frame = sim.truth.frame.expect("the demo walk has a geodetic frame");
    let to_frame = |e: f64, n: f64| {
        let (lat, lon, h) = sim_frame.to_geodetic([e, n, 0.0]);
        let [e, n, _] = frame.to_enu(lat, lon, h);
        (e, n)
    };
    let truth_at = |t: f64| {
        let (e, n) = sim.truth.position_at(t);
        to_frame(e, n)
    };
    let error = |t: f64, e: f64, n: f64| {
        let (te, tn) = truth_at(t);
        libm::hypot(e - te, n - tn)
    };
    let fused = p.fused();
    let smoothed = p.smoothed();
    // The PDR track starts at the walk's start, which the engine only knows through the fixes:
    // it is drawn from the smoothed estimate of that point.
    let start = crate::engine::pipeline::offset_onto(p.track(), smoothed.first());
    let pdr: Vec<(f64, f64, f64)> = p
        .track()
        .iter()
        .map(|s| (s.t, s.east_m + start.0, s.north_m + start.1))
        .collect();
    let fix_points: Vec<(f64, f64, f64, f64)> = p
        .fixes()
        .iter()
        .map(|f| {
            let (e, n) = frame.en_of_fix(f);
            (f.t, e, n, f.h_accuracy_m)
        })
        .collect();
    let errors = |s: &[FusedStep]| p75(s.iter().map(|x| error(x.t, x.east_m, x.north_m)).collect());
    let counts = p.diagnostics().fix_counts.unwrap_or_default();
    let last = fused.last().copied();
    FusionDemoSummary {
        steps: p.track().len(),
        fixes: fix_points.len(),
        fixes_used: counts.used,
        fixes_gated: counts.gated,
        gnss_p75_m: p75(fix_points.iter().map(|f| error(f.0, f.1, f.2)).collect()),
        pdr_p75_m: p75(pdr.iter().map(|x| error(x.0, x.1, x.2)).collect()),
        fused_p75_m: errors(fused),
        smoothed_p75_m: errors(&smoothed),
        scale: last.map_or(1.0, |l| l.scale),
        true_scale: 1.0 / scenarios::GNSS_CITY_LENGTH_FACTOR,
        heading_correction_deg: last.map_or(0.0, |l| l.bias_rad.to_degrees()),
        true_heading_correction_deg: -scenarios::GNSS_CITY_HEADING_BIAS_DEG,
        declination_deg: p.diagnostics().declination_deg.unwrap_or(0.0),
        origin: (frame.lat0_deg, frame.lon0_deg, frame.h0_m),
        truth: sim
            .truth
            .path
            .iter()
            .map(|&(_, e, n)| to_frame(e, n))
            .collect(),
        fix_points: fix_points.iter().map(|f| (f.1, f.2, f.3)).collect(),
        pdr: pdr.iter().map(|x| (x.1, x.2)).collect(),
        fused: fused.iter().map(|x| (x.east_m, x.north_m)).collect(),
        smoothed: smoothed.iter().map(|x| (x.east_m, x.north_m)).collect(),
    }
}

impl DemoSummary {
    /// The figures in words for the page's elements: `(element id, text)`.
    pub fn texts(&self) -> Vec<(&'static str, String)> {
        vec![
            ("steps", self.steps.to_string()),
            ("steps-truth", format!("true: {}", self.truth_steps)),
            ("distance", fixed(self.distance_m, 1)),
            (
                "distance-truth",
                format!("true: {} m", fixed(self.truth_distance_m, 1)),
            ),
            ("end-error", fixed(self.end_error_m, 1)),
        ]
    }
}

impl FusionDemoSummary {
    /// The figures and the caption in words for the page's elements: `(element id, text)`.
    pub fn texts(&self) -> Vec<(&'static str, String)> {
        let caption = format!(
            "{} fixes, {} refused as outliers. Learnt: step length × {} (true {}), heading {}° \
             (true {}°), declination {}° from the World Magnetic Model. Grey: the true path.",
            self.fixes,
            self.fixes_gated,
            fixed(self.scale, 3),
            fixed(self.true_scale, 3),
            fixed(self.heading_correction_deg, 1),
            fixed(self.true_heading_correction_deg, 0).replacen('-', "−", 1),
            fixed(self.declination_deg, 1),
        );
        vec![
            ("gnss-p75", fixed(self.gnss_p75_m, 1)),
            ("fused-p75", fixed(self.fused_p75_m, 1)),
            ("smoothed-p75", fixed(self.smoothed_p75_m, 1)),
            (
                "fused-note",
                format!("PDR only: {} m", fixed(self.pdr_p75_m, 1)),
            ),
            ("fusion-caption", caption),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_in_words() {
        let d = DemoSummary {
            steps: 41,
            truth_steps: 40,
            distance_m: 30.25,
            truth_distance_m: 30.0,
            end_error_m: 1.04,
            duration_s: 30.0,
            samples: 3000,
            track: Vec::new(),
            truth_path: Vec::new(),
        };
        let t = d.texts();
        assert_eq!(t[0], ("steps", "41".to_string()));
        assert_eq!(t[1].1, "true: 40");
        assert_eq!(t[2].1, "30.3", "a tie rounds up as toFixed does");
        assert_eq!(t[3].1, "true: 30.0 m");
        assert_eq!(t[4], ("end-error", "1.0".to_string()));
    }

    #[test]
    fn fusion_caption_in_words() {
        let f = FusionDemoSummary {
            scale: 0.93456,
            true_scale: 1.0 / 1.07,
            heading_correction_deg: -4.04,
            true_heading_correction_deg: -4.0,
            declination_deg: 2.5,
            fixes: 60,
            fixes_gated: 3,
            pdr_p75_m: 12.34,
            ..run_fusion_demo()
        };
        let t = f.texts();
        assert_eq!(t[3], ("fused-note", "PDR only: 12.3 m".to_string()));
        assert_eq!(
            t[4].1,
            "60 fixes, 3 refused as outliers. Learnt: step length × 0.935 (true 0.935), heading -4.0° \
             (true −4°), declination 2.5° from the World Magnetic Model. Grey: the true path."
        );
    }
}
