//! Where the phone rides against the point the walker turns about: TyrEx's motion capture
//! (`truth.csv`: the phone's position and attitude) says, walk by walk, how far behind that
//! point the phone is (docs/methods/pocket-heading.md, "The back pocket rides behind the turn").
//!
//! A point d behind the one the walker turns about moves like a trailer: at speed v and a turn
//! rate φ̇, its path's direction is the body's φ less d·φ̇/v. The screen's yaw over a stride
//! is the body's φ (plus one constant, the phone's place); the truth's path is the phone's.
//! Both from the motion capture alone, smoothed over a stride: d is the least-squares slope of
//! (path − screen's yaw − constant) against −φ̇/v, and the shift is the time by which the
//! screen's yaw best leads the phone's path (median absolute difference).
//!
//! `cargo run --release --example tyrex_lever_arm [-- DATA_DIR]` (default
//! `../shared/data/tyrex-pocket`).
use pdr::engine::math::wrap_pi;
use std::path::{Path, PathBuf};

/// Resampling step, s.
const DT: f64 = 0.02;
/// The stride the truth is smoothed over, s.
const STRIDE_S: f64 = 1.2;
/// The least speed whose direction counts, m/s.
const MIN_SPEED: f64 = 0.5;

/// (t, x, y, screen's normal x, y) of each complete row of `truth.csv`.
fn read(path: &Path) -> Option<Vec<[f64; 5]>> {
    let mut reader = csv::Reader::from_path(path).ok()?;
    // Rows with an empty field (the cameras lost the phone) are left out.
    let rows = reader.deserialize::<[f64; 8]>().filter_map(|r| {
        let [t, x, y, _, w, qx, qy, qz] = r.ok()?;
        // The device's z axis in the room: the rotation's third column.
        Some([t, x, y, 2.0 * (qx * qz + w * qy), 2.0 * (qy * qz - w * qx)])
    });
    Some(rows.collect())
}

/// The rows linearly resampled every [`DT`], then each channel's centred mean over a stride.
fn smoothed(rows: &[[f64; 5]]) -> Vec<[f64; 5]> {
    let (t0, t1) = (rows[0][0], rows[rows.len() - 1][0]);
    let mut out: Vec<[f64; 5]> = Vec::new();
    let mut j = 0;
    let mut t = t0;
    while t <= t1 {
        while rows[j + 1][0] < t {
            j += 1;
        }
        let (a, b) = (rows[j], rows[j + 1]);
        let w = (t - a[0]) / (b[0] - a[0]).max(1e-9);
        out.push(std::array::from_fn(|i| a[i] + w * (b[i] - a[i])));
        t += DT;
    }
    let h = (0.5 * STRIDE_S / DT) as usize;
    (h..out.len().saturating_sub(h))
        .map(|i| {
            let s = &out[i - h..=i + h];
            std::array::from_fn(|c| s.iter().map(|r| r[c]).sum::<f64>() / s.len() as f64)
        })
        .collect()
}

fn main() {
    let dir = std::env::args().nth(1).map_or_else(
        || PathBuf::from("../shared/data/tyrex-pocket"),
        PathBuf::from,
    );
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("not found: {}", dir.display());
        return;
    };
    let mut walks: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    walks.sort();
    println!("walk | speed, m/s | d behind the turn, m | the phone's path lags the screen by, s");
    for walk in walks {
        let Some(rows) = read(&walk.join("truth.csv")).filter(|r| r.len() > 500) else {
            continue;
        };
        let s = smoothed(&rows);
        let name = walk
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        // A screen within about 60° of vertical has no yaw to speak of (the engine's rule).
        let level = s.iter().filter(|r| libm::hypot(r[3], r[4]) >= 0.5).count();
        if 2 * level < s.len() {
            println!("{name} | | | (the screen faces up)");
            continue;
        }
        // (path direction, screen's yaw unwrapped, turn rate, speed) at each inner sample.
        let mut at = Vec::new();
        let mut phi_prev: Option<f64> = None;
        for i in 1..s.len() - 1 {
            let (vx, vy) = (
                (s[i + 1][1] - s[i - 1][1]) / (2.0 * DT),
                (s[i + 1][2] - s[i - 1][2]) / (2.0 * DT),
            );
            let yaw = |r: &[f64; 5]| libm::atan2(r[3], r[4]);
            let phi = match phi_prev {
                Some(p) => p + wrap_pi(yaw(&s[i]) - p),
                None => yaw(&s[i]),
            };
            phi_prev = Some(phi);
            let rate = wrap_pi(yaw(&s[i + 1]) - yaw(&s[i - 1])) / (2.0 * DT);
            at.push((libm::atan2(vx, vy), phi, rate, libm::hypot(vx, vy)));
        }
        let moving: Vec<&(f64, f64, f64, f64)> = at.iter().filter(|a| a.3 >= MIN_SPEED).collect();
        let (sn, cs) = moving.iter().fold((0.0, 0.0), |(sn, cs), a| {
            let (si, co) = libm::sincos(a.0 - a.1);
            (sn + si, cs + co)
        });
        let c = libm::atan2(sn, cs);
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for a in &moving {
            let (x, y) = (a.2 / a.3, wrap_pi(a.0 - a.1 - c));
            if y.abs() < 0.8 {
                sxy += x * y;
                sxx += x * x;
            }
        }
        let lag = (-40..=40)
            .map(|l: i64| {
                let mut e: Vec<f64> = (0..at.len())
                    .filter_map(|i| {
                        let j = usize::try_from(i as i64 - l)
                            .ok()
                            .filter(|&j| j < at.len())?;
                        (at[i].3 >= MIN_SPEED).then(|| wrap_pi(at[i].0 - at[j].1 - c).abs())
                    })
                    .collect();
                e.sort_by(f64::total_cmp);
                (e.get(e.len() / 2).copied().unwrap_or(f64::INFINITY), l)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or(0.0, |(_, l)| l as f64 * DT);
        let mut speeds: Vec<f64> = moving.iter().map(|a| a.3).collect();
        speeds.sort_by(f64::total_cmp);
        let name = walk
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        println!(
            "{name} | {:.2} | {:.2} | {:.2}",
            speeds.get(speeds.len() / 2).copied().unwrap_or(0.0),
            -sxy / sxx,
            lag
        );
    }
}
