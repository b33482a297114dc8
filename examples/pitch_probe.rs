//! The Munoz Diaz 2015 methods on the simulated pocket walks, every pose: step counts, the
//! activity of each step, the height and the floors, with the PLL and the pitch detector.
//! `cargo run --release --example pitch_probe`
use pdr::engine::{replay, Activity, PipelineConfig, StepDetectorConfig};
use pdr::sim::{scenarios, PocketPose, Scenario};

fn main() {
    type Make = fn(PocketPose) -> Scenario;
    let walks: [(&str, Make); 4] = [
        ("flat", scenarios::pocket_flat),
        ("stairs", scenarios::stairs_walk),
        ("sit/stand", scenarios::sit_stand),
        ("mixed", scenarios::pocket_mixed),
    ];
    let baro = std::env::args().any(|a| a == "--no-baro");
    for (name, make) in walks {
        for pose in PocketPose::ALL {
            let mut sc = make(pose);
            if baro {
                sc.sensors.barometer = None;
            }
            let sim = sc.generate();
            let truth = &sim.truth;
            let mut line = format!("{name:9} {:28}", pose.as_str());
            for kind in ["pll", "pitch"] {
                let mut cfg = PipelineConfig::default();
                if kind == "pitch" {
                    cfg.detector = StepDetectorConfig::Pitch(Default::default());
                }
                let r = replay(cfg, &sim.records).unwrap();
                let t = r.pipeline.track();
                // Each step against the truth's nearest footfall.
                let nearest = |t: f64| {
                    truth
                        .steps
                        .iter()
                        .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
                        .map_or(Activity::Still, |s| s.activity)
                };
                let right = t.iter().filter(|s| s.activity == nearest(s.t)).count();
                let top = t.iter().map(|s| s.up_m).fold(f64::MIN, f64::max);
                let last = t.last().map_or(0.0, |s| s.up_m);
                let floors = t.iter().map(|s| s.floor).max().unwrap_or(0);
                let wrong: Vec<String> = t
                    .iter()
                    .filter(|s| s.activity != nearest(s.t))
                    .take(3)
                    .map(|s| {
                        format!(
                            "{:.1}:{}≠{}",
                            s.t,
                            s.activity.as_str(),
                            nearest(s.t).as_str()
                        )
                    })
                    .collect();
                line += &format!(
                    " | {kind}: {}/{}, act {:.1} %, top {:.2}/{:.2} m, end {:.2}, fl {} {:?}",
                    t.len(),
                    truth.steps.len(),
                    100.0 * right as f64 / t.len().max(1) as f64,
                    top,
                    truth.steps.iter().map(|s| s.up_m).fold(f64::MIN, f64::max),
                    last,
                    floors,
                    wrong
                );
                let _ = Activity::Walking;
            }
            println!("{}", line.replace(" | pitch", "\n{:38} | pitch"));
        }
    }
}
