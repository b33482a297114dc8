//! Count or length: why TyrEx's distance ratios are off, walk by walk
//! (docs/methods/step-length-pocket.md).
//!
//! For each TyrEx walk: the engine's steps and track length (default, and with the thigh's eq. 5
//! on, `thigh_step_length.on`), against the motion capture's own count of steps and its path.
//! - The true count of a pocket walk: twice the thigh's swings, the principal component of the
//!   phone's up direction in its own axes (from the truth's attitude), 2 s mean removed, each
//!   cycle counted once it crosses ±¼ of its σ.
//! - The true count of a hand-held walk (texting, at the ear): the phone's vertical bobs (height,
//!   1 s mean removed, crossings of ±0.3 σ), one per footfall. A swinging hand's own swing hides
//!   them: no count for `Swinging`.
//! - The path: the truth's positions at 60 Hz, smoothed over 1 s, over the whole walk (`pdr
//!   eval` takes it between the first and the last step, so its ratios differ by a few %).
//!
//! `cargo run --release --example pocket_step_length [-- DATA_DIR]` (default
//! `../shared/data/tyrex-pocket`).
use pdr::engine::{replay, PipelineConfig};
use pdr::io::import::{import_all, DirSet};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Truth rows resampled at [`FS`]: time, position (x, y, z) and attitude (w, x, y, z).
const FS: f64 = 60.0;

fn main() {
    let dir = std::env::args().nth(1).map_or_else(
        || PathBuf::from("../shared/data/tyrex-pocket"),
        PathBuf::from,
    );
    let Ok(mut files) = DirSet::new(&dir) else {
        eprintln!("not found: {}", dir.display());
        return;
    };
    let mut on = PipelineConfig::default();
    on.thigh_step_length.on = true;
    let mut by_mode: BTreeMap<String, Vec<[f64; 4]>> = BTreeMap::new();
    println!(
        "walk | steps | true steps | count | m per step: engine / true | ratio | ratio, thigh on"
    );
    for log in import_all(&mut files).into_iter().flatten() {
        let name = Path::new(&log.source)
            .file_name()
            .map_or(log.source.clone(), |n| n.to_string_lossy().into_owned());
        let Some(truth) = read_truth(&Path::new(&log.source).join("truth.csv")) else {
            eprintln!("{name}: no truth.csv");
            continue;
        };
        let length = |cfg: PipelineConfig| {
            replay(cfg, &log.records).map_or((0, 0.0), |r| {
                let t = r.pipeline.track();
                (t.len(), t.iter().map(|s| s.length_m).sum::<f64>())
            })
        };
        let (n, l0) = length(PipelineConfig::default());
        let (_, l1) = length(on.clone());
        let mode = name.rsplit('_').next().unwrap_or("").to_string();
        let pocket = mode.contains("Pocket");
        let true_steps = if pocket {
            2 * thigh_swings(&truth)
        } else if mode == "Swinging" {
            0
        } else {
            bobs(&truth)
        };
        let d = path_m(&truth);
        let (r0, r1) = (l0 / d, l1 / d);
        let count = if true_steps > 0 {
            n as f64 / true_steps as f64
        } else {
            f64::NAN
        };
        println!(
            "{name} | {n} | {} | {} | {:.2} / {} | {r0:.2} | {r1:.2}",
            if true_steps > 0 {
                true_steps.to_string()
            } else {
                "—".into()
            },
            two(count),
            l0 / n.max(1) as f64,
            two(d / true_steps as f64)
        );
        by_mode
            .entry(mode)
            .or_default()
            .push([r0, r1, count, l0 / n.max(1) as f64]);
    }
    println!("\nmode | median ratio | thigh on | count / true | engine m per step");
    for (mode, v) in by_mode {
        let med = |k: usize| median(v.iter().map(|x| x[k]).collect());
        println!(
            "{mode} | {} | {} | {} | {}",
            two(med(0)),
            two(med(1)),
            two(med(2)),
            two(med(3))
        );
    }
}

/// `x` with two decimals, a dash when it is not a number (no true count).
fn two(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "—".into()
    }
}

/// The middle finite value (the mean of the two middle ones for an even count); NaN when none.
fn median(v: Vec<f64>) -> f64 {
    let mut v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// The truth's rows (t, x, y, z, qw, qx, qy, qz) resampled at [`FS`] by linear interpolation;
/// rows with an empty field (the cameras lost the phone) are left out first.
fn read_truth(path: &Path) -> Option<Vec<[f64; 8]>> {
    let text = std::fs::read_to_string(path).ok()?;
    let rows: Vec<[f64; 8]> = text
        .lines()
        .skip(1)
        .filter_map(|line| {
            let v: Vec<f64> = line.split(',').filter_map(|f| f.parse().ok()).collect();
            <[f64; 8]>::try_from(v).ok()
        })
        .collect();
    let (first, last) = (rows.first()?[0], rows.last()?[0]);
    let mut out = Vec::new();
    let mut j = 0;
    let mut t = first;
    while t <= last {
        while j + 2 < rows.len() && rows[j + 1][0] <= t {
            j += 1;
        }
        let (a, b) = (rows[j], rows[(j + 1).min(rows.len() - 1)]);
        let w = if b[0] > a[0] {
            (t - a[0]) / (b[0] - a[0])
        } else {
            0.0
        };
        let mut r = [0.0; 8];
        for k in 0..8 {
            r[k] = a[k] + w * (b[k] - a[k]);
        }
        out.push(r);
        t += 1.0 / FS;
    }
    Some(out)
}

/// The centred moving average of `x` over `n` samples, the ends held.
fn moving_mean(x: &[f64], n: usize) -> Vec<f64> {
    let n = n.max(1);
    let len = x.len() as isize;
    (0..len)
        .map(|i| {
            let (a, b) = (i - (n as isize) / 2, i - (n as isize) / 2 + n as isize);
            (a..b).map(|j| x[j.clamp(0, len - 1) as usize]).sum::<f64>() / n as f64
        })
        .collect()
}

/// The length of the truth's horizontal path smoothed over 1 s, m.
fn path_m(truth: &[[f64; 8]]) -> f64 {
    let col = |k: usize| moving_mean(&truth.iter().map(|r| r[k]).collect::<Vec<_>>(), FS as usize);
    let (x, y) = (col(1), col(2));
    x.windows(2)
        .zip(y.windows(2))
        .map(|(a, b)| libm::hypot(a[1] - a[0], b[1] - b[0]))
        .sum()
}

/// Full cycles of `x` (mean about 0): each rise through +h after a fall through −h.
fn cycles(x: &[f64], h: f64) -> usize {
    let (mut state, mut n) = (0i8, 0);
    for &v in x {
        if state <= 0 && v > h {
            state = 1;
            n += 1;
        } else if state >= 0 && v < -h {
            state = -1;
        }
    }
    n
}

/// The standard deviation of `x` (mean about 0).
fn sigma(x: &[f64]) -> f64 {
    libm::sqrt(x.iter().map(|v| v * v).sum::<f64>() / x.len().max(1) as f64)
}

/// The thigh's swings: cycles of the phone's up direction (in the phone's axes) along its
/// principal component, the 2 s mean removed and 0.15 s smoothing.
fn thigh_swings(truth: &[[f64; 8]]) -> usize {
    // The room's up in the phone's axes: the third row of the attitude's rotation matrix.
    let up: Vec<[f64; 3]> = truth
        .iter()
        .map(|r| {
            let (w, x, y, z) = (r[4], r[5], r[6], r[7]);
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ]
        })
        .collect();
    let comp: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            let c: Vec<f64> = up.iter().map(|u| u[k]).collect();
            let slow = moving_mean(&c, 2 * FS as usize);
            let hp: Vec<f64> = c.iter().zip(&slow).map(|(a, b)| a - b).collect();
            moving_mean(&hp, (0.15 * FS) as usize)
        })
        .collect();
    let pts: Vec<[f64; 3]> = comp[0]
        .iter()
        .zip(&comp[1])
        .zip(&comp[2])
        .map(|((a, b), c)| [*a, *b, *c])
        .collect();
    let mut cov = [[0.0; 3]; 3];
    for &p in &pts {
        for (row, pa) in cov.iter_mut().zip(p) {
            for (c, pb) in row.iter_mut().zip(p) {
                *c += pa * pb;
            }
        }
    }
    // The principal axis by power iteration.
    let mut v = [1.0, 1.0, 1.0];
    for _ in 0..100 {
        let n = cov.map(|row| row.iter().zip(&v).map(|(c, x)| c * x).sum::<f64>());
        let norm = libm::sqrt(n.iter().map(|x| x * x).sum::<f64>()).max(1e-300);
        v = n.map(|x| x / norm);
    }
    let pc: Vec<f64> = pts
        .iter()
        .map(|p| p.iter().zip(&v).map(|(a, b)| a * b).sum())
        .collect();
    cycles(&pc, 0.25 * sigma(&pc))
}

/// The phone's vertical bobs: its height, the 1 s mean removed and 0.12 s smoothing.
fn bobs(truth: &[[f64; 8]]) -> usize {
    let z: Vec<f64> = truth.iter().map(|r| r[3]).collect();
    let slow = moving_mean(&z, FS as usize);
    let hp: Vec<f64> = z.iter().zip(&slow).map(|(a, b)| a - b).collect();
    let s = moving_mean(&hp, (0.12 * FS) as usize);
    cycles(&s, 0.3 * sigma(&s))
}
