//! Probe: the leg pitch and the pitch detector on a simulated pocket walk (exploration).
use pdr::engine::{replay, PipelineConfig, StepDetectorConfig};
use pdr::sim::scenarios;

fn main() {
    let sim = scenarios::square(60.0).generate();
    for kind in ["pll", "pitch"] {
        let mut cfg = PipelineConfig::default();
        if kind == "pitch" {
            cfg.detector = StepDetectorConfig::Pitch(Default::default());
        }
        let r = replay(cfg, &sim.records).unwrap();
        let t = r.pipeline.track();
        let acts: std::collections::BTreeMap<&str, usize> =
            t.iter().fold(Default::default(), |mut m, s| {
                *m.entry(s.activity.as_str()).or_default() += 1;
                m
            });
        let d = r.pipeline.diagnostics();
        println!(
            "{kind}: {} steps (truth {}), dist {:.1} (truth {:.1}) acts {:?} amp {:?} pitch_now {:?}",
            t.len(),
            sim.truth.steps.len(),
            d.distance_m,
            sim.truth.distance_m,
            acts,
            t.get(40).and_then(|s| s.pitch_amplitude_deg),
            d.pitch_deg
        );
        println!("  leg {:?}", d.leg_pitch);
        if kind == "pitch" {
            let mut j = 0;
            for ts in &sim.truth.steps {
                while j < t.len() && t[j].t < ts.t - 0.2 {
                    println!("  extra step at {:.2}", t[j].t);
                    j += 1;
                }
                if j < t.len() && (t[j].t - ts.t).abs() <= 0.2 {
                    j += 1;
                } else {
                    println!("  missed truth step at {:.2}", ts.t);
                }
            }
            println!(
                "  first steps {:?}",
                t.iter()
                    .take(8)
                    .map(|s| (s.t * 100.0).round() / 100.0)
                    .collect::<Vec<_>>()
            );
            println!(
                "  truth first {:?}",
                sim.truth
                    .steps
                    .iter()
                    .take(4)
                    .map(|s| s.t)
                    .collect::<Vec<_>>()
            );
        }
    }
}

#[allow(dead_code)]
fn unused() {}
