//! The KF-NFA (Ibarra 2015 ch. 3) and Madgwick against the phone's own attitude (the OS
//! quaternion, itself an estimate but a steady reference) on the real logs that carry one:
//! tilt error (angle between the two verticals) and relative yaw drift (the change of the yaw
//! difference since the first second), per set, pooled over samples.
//!
//! `cargo run --release --example kf_nfa_vs_os [orientation.KEY=VALUE…] [SET…]` (default sets:
//! ms-indoor ipin2023, read from `../shared/data`; the settings change the KF-NFA's defaults).
#![allow(clippy::disallowed_methods)] // diagnostics, not the track path
use nalgebra::{UnitQuaternion, Vector3};
use pdr::engine::math::wrap_pi;
use pdr::engine::orientation::kf_nfa::KfNfaConfig;
use pdr::engine::orientation::{Orientation, OrientationSource};
use pdr::engine::Record;
use pdr::io::import::{import_all, DirSet};
use std::path::Path;

fn tilt_deg(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    let (u, v) = (a.inverse() * Vector3::z(), b.inverse() * Vector3::z());
    libm::atan2(u.cross(&v).norm(), u.dot(&v)).to_degrees()
}

/// Yaw of the attitude: the heading of whichever device axis is most horizontal.
fn yaw(q: &UnitQuaternion<f64>, axis: &Vector3<f64>) -> f64 {
    let v = q * axis;
    libm::atan2(v.x, v.y)
}

fn pct(v: &mut [f64], p: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * p) as usize]
}

fn main() {
    let (set_args, mut sets): (Vec<String>, Vec<String>) =
        std::env::args().skip(1).partition(|a| a.contains('='));
    if sets.is_empty() {
        sets = vec!["ms-indoor".into(), "ipin2023".into()];
    }
    let base = pdr::settings::Settings::new()
        .with("orientation.kind", "kf_nfa")
        .with_args(&set_args)
        .and_then(|s| s.config())
        .unwrap();
    let OrientationSource::KfNfa(base) = base.orientation else {
        unreachable!()
    };
    let kf = |f: fn(&mut KfNfaConfig)| {
        let mut c = base;
        f(&mut c);
        OrientationSource::KfNfa(c)
    };
    let sources = [
        ("madgwick", OrientationSource::MADGWICK),
        ("kf_nfa", kf(|_| {})),
        ("kf_nfa R fixed", kf(|c| c.adapt = false)),
        ("kf_nfa +mag", kf(|c| c.magnetometer = true)),
        (
            "kf_nfa +mag R fixed",
            kf(|c| {
                c.magnetometer = true;
                c.adapt = false
            }),
        ),
    ];
    for set in sets {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/data")
            .join(&set);
        let Ok(mut dir) = DirSet::new(&root) else {
            println!("skipped: {} not found", root.display());
            continue;
        };
        let logs: Vec<_> = import_all(&mut dir).into_iter().flatten().collect();
        for (name, src) in sources {
            let (mut tilts, mut drifts, mut resets, mut rscale) = (vec![], vec![], 0, vec![]);
            for log in &logs {
                let mut o = Orientation::new(src);
                let (mut last, mut held, mut yaw0) = (None, None, None);
                let mut axis = None;
                for r in &log.records {
                    let Record::Imu(s) = r else { continue };
                    if s.gyro.is_none() {
                        continue;
                    }
                    let dt = last.map_or(0.0, |l| s.t - l);
                    last = Some(s.t);
                    held = s.orientation.or(held);
                    let Ok(nav) = o.push(s, dt) else { continue };
                    let (Some(q), Some(t)) = (nav.attitude, held) else {
                        continue;
                    };
                    tilts.push(tilt_deg(&q, &t));
                    // The device axis most horizontal in the reference at the start.
                    let axis = *axis.get_or_insert_with(|| {
                        [Vector3::x(), Vector3::y(), Vector3::z()]
                            .into_iter()
                            .min_by(|a, b| (t * a).z.abs().total_cmp(&(t * b).z.abs()))
                            .unwrap()
                    });
                    let d = wrap_pi(yaw(&q, &axis) - yaw(&t, &axis));
                    match yaw0 {
                        None => yaw0 = Some(d),
                        Some(y0) => drifts.push(wrap_pi(d - y0).abs().to_degrees()),
                    }
                }
                if let Some(k) = o.diagnostics().kf_nfa {
                    resets += k.resets;
                    rscale.push(k.r_scale[0]);
                }
            }
            println!(
                "{set:10} {name:20} tilt p50 {:5.2}° p95 {:5.2}°  yaw drift p50 {:6.2}° p95 {:6.2}°  resets {resets}  final R scale p50 {:.0}",
                pct(&mut tilts.clone(), 0.5),
                pct(&mut tilts, 0.95),
                pct(&mut drifts.clone(), 0.5),
                pct(&mut drifts, 0.95),
                pct(&mut rscale, 0.5),
            );
        }
    }
}
