//! `pdr simcheck`: the accuracy of every method (step counts, heading, loop closure) on simulated
//! walks with known truth.
//! May import: the `pdr` library; nothing of the other subcommands.

use pdr::engine::heading::HeadingMethod;
use pdr::engine::OrientationSource;
use pdr::engine::{replay, PipelineConfig, StepDetectorConfig};
use pdr::sim::{scenarios, Simulation};

pub fn simcheck() {
    let methods = [
        ("tip-to-tail 2016", HeadingMethod::TipToTail2016),
        ("closed form 2021", HeadingMethod::ClosedForm2021),
        ("PCA 2 s", HeadingMethod::Pca),
    ];
    out!("Step counts (PLL vs peak detector), count error against truth:");
    let mut cases: Vec<(String, Simulation)> = Vec::new();
    for f in [1.5, 1.8, 2.2] {
        cases.push((
            format!("walk {f} Hz 70 s"),
            scenarios::straight_walk(f, 70.0).generate(),
        ));
    }
    for f in [2.7, 3.4, 4.2] {
        cases.push((
            format!("run {f} Hz 35 s"),
            scenarios::straight_run(f, 35.0).generate(),
        ));
    }
    cases.push(("demo walk".into(), scenarios::demo_walk().generate()));
    for (label, sim) in &cases {
        let pll = replay(PipelineConfig::default(), &sim.records)
            .unwrap()
            .pipeline
            .track()
            .len();
        let peak_cfg = PipelineConfig {
            detector: StepDetectorConfig::Peak(Default::default()),
            ..Default::default()
        };
        let peak = replay(peak_cfg, &sim.records)
            .unwrap()
            .pipeline
            .track()
            .len();
        let truth = sim.truth.observed_steps();
        out!(
            "  {label:<20} truth {truth:>4}  PLL {pll:>4} ({:+})  peak {peak:>4} ({:+})",
            pll as i64 - truth as i64,
            peak as i64 - truth as i64
        );
    }
    out!("Heading, mean absolute error of the used (averaged) heading, straight 1.8 Hz walks:");
    for (name, m) in methods {
        let mut row = Vec::new();
        for yaw in [0.0, 90.0, 180.0, 270.0] {
            let mut sc = scenarios::straight_walk(1.8, 40.0);
            sc.pocket_yaw_deg = yaw;
            sc.start_heading_deg = 60.0;
            let sim = sc.generate();
            let r = replay(PipelineConfig::with_heading(m), &sim.records).unwrap();
            row.push(format!(
                "yaw {yaw:>3}°: {:.2}°",
                heading_err(&sim, r.pipeline.track())
            ));
        }
        out!("  {name:<18} {}", row.join("  "));
    }
    out!("Square 4 × 25 m, loop-closure error:");
    let sim = scenarios::square(25.0).generate();
    for (name, m) in methods {
        for (oname, o) in [
            ("OS", OrientationSource::Os),
            ("Madgwick", OrientationSource::MADGWICK),
        ] {
            let cfg = PipelineConfig {
                orientation: o,
                ..PipelineConfig::with_heading(m)
            };
            let r = replay(cfg, &sim.records).unwrap();
            let last = r.pipeline.track().last().copied();
            let c = last.map_or(f64::NAN, |l| libm::hypot(l.east_m, l.north_m));
            out!(
                "  {name:<18} {oname:<9} {c:.2} m ({:.2} % of {:.0} m)",
                100.0 * c / sim.truth.distance_m,
                sim.truth.distance_m
            );
        }
    }
}

/// Heading error statistics (mean absolute, degrees) of the used heading against the truth.
fn heading_err(sim: &Simulation, track: &[pdr::engine::StepRecord]) -> f64 {
    let mut errs = Vec::new();
    for s in track.iter().skip(2) {
        let Some(h) = s.heading_rad else { continue };
        let nearest = sim
            .truth
            .steps
            .iter()
            .min_by(|a, b| (a.t - s.t).abs().total_cmp(&(b.t - s.t).abs()));
        if let Some(tr) = nearest {
            errs.push(
                pdr::engine::math::wrap_pi(h - tr.heading_rad)
                    .abs()
                    .to_degrees(),
            );
        }
    }
    errs.iter().sum::<f64>() / errs.len().max(1) as f64
}
