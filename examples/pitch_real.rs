//! Probe: what the leg pitch sees on the real sets (axis share, stride amplitude, activities).
use pdr::engine::{Pipeline, PipelineConfig};
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn main() {
    for set in ["ms-indoor", "ipin2023", "oxford-steps"] {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/data")
            .join(set);
        let Ok(mut files) = DirSet::new(&root) else {
            println!("skipped: {} not found", root.display());
            continue;
        };
        let mut shares = Vec::new();
        let mut amps = Vec::new();
        let mut acts = std::collections::BTreeMap::<&str, usize>::new();
        for log in import_all(&mut files).into_iter().flatten() {
            let mut p = Pipeline::new(PipelineConfig::default()).unwrap();
            for r in &log.records {
                let n = p.push(r).map(|s| s.len()).unwrap_or(0);
                if n > 0 {
                    let d = p.diagnostics();
                    if let Some(l) = d.leg_pitch {
                        shares.push(l.axis_share);
                    }
                    for s in &p.track()[p.track().len() - n..] {
                        if s.pitch_amplitude_deg.is_some() {
                            println!(
                                "   {} t {:.1} amp {:?} {}",
                                log.source,
                                s.t,
                                s.pitch_amplitude_deg,
                                s.activity.as_str()
                            );
                        }
                        amps.extend(s.pitch_amplitude_deg);
                        *acts.entry(s.activity.as_str()).or_default() += 1;
                    }
                }
            }
        }
        let q = |v: &mut Vec<f64>, p: f64| {
            v.sort_by(f64::total_cmp);
            v.get(((v.len() as f64 - 1.0) * p) as usize)
                .copied()
                .unwrap_or(f64::NAN)
        };
        println!(
            "{set}: share p10 {:.2} p50 {:.2} p90 {:.2}; amp n {} p10 {:.1} p50 {:.1} p90 {:.1}; {:?}",
            q(&mut shares, 0.1),
            q(&mut shares, 0.5),
            q(&mut shares, 0.9),
            amps.len(),
            q(&mut amps, 0.1),
            q(&mut amps, 0.5),
            q(&mut amps, 0.9),
            acts
        );
    }
}
