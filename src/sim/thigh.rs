//! The thigh's pitch: today's pure sinusoid, or a realistic gait-cycle shape on level ground,
//! up and down stairs and sitting (Munoz Diaz 2015 §4.1, §4.2, §6.1).
//! May import: `engine` and `io`.
//!
//! # Convention
//! θ is the thigh's angle to the vertical in the sagittal plane, degrees: 0 standing, positive
//! with the knee forward (hip flexion). One stride (one cycle of the pocket leg, two of the
//! simulator's steps) is the stride phase s ∈ [0, 1); the pocket leg's heel strikes at s = 0
//! (the simulator's step phase φ ≡ 0 mod 4π, where the historic sinusoid peaks).
//!
//! # Level walking (paper Fig. 2)
//! The thigh swings forward to its largest angle θ_Hmax while the foot is in the air
//! (s ≈ 0.86), dips by about 12 % of the amplitude (4–5° at Δθ_H ≈ 38°), and comes back to a
//! second, lower peak at heel strike (s ≈ 0.99); then it extends through stance to θ_Hmin, the
//! knee bent behind (s ≈ 0.53). The amplitude follows the walker's TRUE pitch law
//! stride = a_true·Δθ_H + b_true (Δθ in degrees, stride = 2 × the step length at the cadence):
//! Δθ_H = (2·L(f) − b_true)/a_true, split θ_Hmax = 0.68 Δθ_H, θ_Hmin = −0.32 Δθ_H (the paper's
//! θ_Hmax ≫ |θ_Hmin|). Defaults a_true = 0.030 m/°, b_true = 0.06 m: close to, but not, the
//! engine's universal slope 0.0314 and zero offset, so a calibration has something to find.
//! The default walker at 1.8 Hz (L = 0.62 m) swings Δθ_H = 39.3°, at 1.7 Hz 37.7°.
//!
//! # Stairs (paper §4.2, §6.1)
//! Up: the thigh rises almost twice as far (θ_Umax ≈ 2 θ_Hmax) and comes back to about 0
//! (θ_Umin = −0.03 Δθ_U: slightly negative); one maximum (s ≈ 0.93), a double minimum
//! (s ≈ 0.45 and 0.62). Down: θ_Dmax = 1.1 θ_Hmax (slightly above level), θ_Dmin positive,
//! one maximum (s ≈ 0.90), a double minimum. The amplitudes depend on the riser r (m) AND on the
//! walker's own level amplitude at the stair cadence:
//!
//!   Δθ_U = Δθ_H + k_u·r,  Δθ_D = Δθ_H − k_d·r,
//!
//! with k_u = (53.07 − 38)/0.17 = 88.65 °/m and k_d = (38 − 26.62)/0.17 = 66.94 °/m, so a walker
//! with Δθ_H = 38° gives the paper's 53.07° and 26.62° on its 17 cm stairs (§6.1). This is
//! deliberately not the engine's proportional model V = e·Δθ: a test of it against this is not
//! circular. (Δθ_D never falls below 0.2 Δθ_H.)
//!
//! # Shapes
//! Each shape is a sum of von Mises bumps exp(κ(cos 2π(s − c) − 1)) (smooth and periodic, so
//! the rate and the lever-arm acceleration are continuous), scaled so that its minimum and
//! maximum over the stride are exactly θ_min and θ_max.
//!
//! # Sitting
//! θ_sit = 85° (thigh almost horizontal) with a slow wobble of under 1°.

use std::f64::consts::TAU;
use std::sync::OnceLock;

/// How the thigh pitches.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ThighModel {
    /// The historic model: ±`Walker::thigh_pitch_deg` (× 1.4 running) as a cosine of half the
    /// step phase, symmetric; nothing while still or sitting.
    #[default]
    Sinusoid,
    /// The realistic gait-cycle shape ([`GaitThigh`]).
    Gait(GaitThigh),
}

/// The realistic thigh: its true pitch law and its stair and sitting angles.
#[derive(Debug, Clone, PartialEq)]
pub struct GaitThigh {
    /// Slope of the true pitch law stride = a·Δθ_H + b, m per degree.
    pub a_true: f64,
    /// Offset of the true pitch law, m.
    pub b_true: f64,
    /// θ_Hmax as a share of Δθ_H (the rest is θ_Hmin below zero).
    pub max_share: f64,
    /// k_u: how much larger Δθ_U is than Δθ_H per metre of riser, degrees per metre.
    pub up_deg_per_m: f64,
    /// k_d: how much smaller Δθ_D is than Δθ_H per metre of riser, degrees per metre.
    pub down_deg_per_m: f64,
    /// θ_Umin as a share of Δθ_U (about zero, slightly negative).
    pub up_min_share: f64,
    /// θ_Dmax as a multiple of θ_Hmax.
    pub down_max_gain: f64,
    /// Thigh angle sitting, degrees.
    pub sit_deg: f64,
    /// Duration of sitting down and of standing up, s.
    pub transition_s: f64,
    /// Largest Δθ running, degrees (the law extrapolated to running strides would exceed it).
    pub run_max_deg: f64,
    /// How far the hip drops on sitting down, m (the phone's height, so the barometer, follows).
    pub sit_drop_m: f64,
}

impl Default for GaitThigh {
    fn default() -> Self {
        GaitThigh {
            a_true: 0.030,
            b_true: 0.06,
            max_share: 0.68,
            up_deg_per_m: (53.07 - 38.0) / 0.17,
            down_deg_per_m: (38.0 - 26.62) / 0.17,
            up_min_share: -0.03,
            down_max_gain: 1.1,
            sit_deg: 85.0,
            transition_s: 1.5,
            run_max_deg: 60.0,
            sit_drop_m: 0.45,
        }
    }
}

/// The three stride shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// Level ground: double maximum.
    Level,
    /// Up stairs: one maximum, double minimum.
    Up,
    /// Down stairs: one maximum, double minimum.
    Down,
}

/// (weight, centre, κ) of each bump.
fn bumps(shape: Shape) -> &'static [(f64, f64, f64)] {
    match shape {
        Shape::Level => &[(1.0, 0.86, 6.0), (0.8, 1.0, 14.0), (-0.9, 0.53, 2.5)],
        Shape::Up => &[(1.0, 0.93, 3.5), (-0.25, 0.45, 12.0), (-0.25, 0.62, 12.0)],
        Shape::Down => &[(1.0, 0.90, 3.0), (-0.25, 0.42, 12.0), (-0.25, 0.62, 12.0)],
    }
}

fn raw(shape: Shape, s: f64) -> f64 {
    bumps(shape)
        .iter()
        .map(|&(w, c, k)| w * libm::exp(k * (libm::cos(TAU * (s - c)) - 1.0)))
        .sum()
}

/// (minimum, maximum) of each raw shape over a stride, sampled finely once.
fn range(shape: Shape) -> (f64, f64) {
    static RANGES: OnceLock<[(f64, f64); 3]> = OnceLock::new();
    let r = RANGES.get_or_init(|| {
        [Shape::Level, Shape::Up, Shape::Down].map(|sh| {
            let n = 20_000;
            (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
                let v = raw(sh, i as f64 / n as f64);
                (lo.min(v), hi.max(v))
            })
        })
    });
    r[shape as usize]
}

/// The shape at stride phase `s`, scaled to [0, 1].
pub fn unit_shape(shape: Shape, s: f64) -> f64 {
    let (lo, hi) = range(shape);
    (raw(shape, s) - lo) / (hi - lo)
}

impl GaitThigh {
    /// Δθ_H of a stride of `stride_m` metres by the true law, degrees (≥ 0).
    pub fn level_amplitude_deg(&self, stride_m: f64) -> f64 {
        ((stride_m - self.b_true) / self.a_true).max(0.0)
    }

    /// (θ_min, θ_max) of a stride of this shape for a level amplitude `dh` and a riser, degrees.
    pub fn extremes(&self, shape: Shape, dh: f64, riser_m: f64) -> (f64, f64) {
        let hmax = self.max_share * dh;
        match shape {
            Shape::Level => (hmax - dh, hmax),
            Shape::Up => {
                let du = dh + self.up_deg_per_m * riser_m;
                let lo = self.up_min_share * du;
                (lo, lo + du)
            }
            Shape::Down => {
                let dd = (dh - self.down_deg_per_m * riser_m).max(0.2 * dh);
                let hi = self.down_max_gain * hmax;
                (hi - dd, hi)
            }
        }
    }

    /// θ at stride phase `s`, degrees.
    pub fn pitch_deg(&self, shape: Shape, s: f64, dh: f64, riser_m: f64) -> f64 {
        let (lo, hi) = self.extremes(shape, dh, riser_m);
        lo + (hi - lo) * unit_shape(shape, s)
    }

    /// θ sitting at time `t`, degrees (with its slow wobble).
    pub fn sit_deg_at(&self, t: f64) -> f64 {
        self.sit_deg + 0.6 * libm::sin(TAU * 0.11 * t + 0.3) + 0.3 * libm::sin(TAU * 0.37 * t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Local extrema of a shape over a stride: (phase, value, is_max).
    fn extrema(shape: Shape) -> Vec<(f64, f64, bool)> {
        let n = 4000;
        let v: Vec<f64> = (0..n)
            .map(|i| unit_shape(shape, i as f64 / n as f64))
            .collect();
        (0..n)
            .filter_map(|i| {
                let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
                let is_max = b > a && b >= c;
                (is_max || (b < a && b <= c)).then_some((i as f64 / n as f64, b, is_max))
            })
            .collect()
    }

    #[test]
    fn shapes_have_the_papers_peaks() {
        let lvl = extrema(Shape::Level);
        assert_eq!(lvl.iter().filter(|e| e.2).count(), 2, "{lvl:?}");
        let dip = lvl.iter().find(|e| !e.2 && e.0 > 0.8).unwrap();
        // The dip between the two maxima: 3–5° at Δθ_H = 38°.
        assert!((3.0..=5.0).contains(&((1.0 - dip.1) * 38.0)), "{dip:?}");
        for sh in [Shape::Up, Shape::Down] {
            let e = extrema(sh);
            assert_eq!(e.iter().filter(|e| e.2).count(), 2, "{e:?}");
            assert_eq!(e.iter().filter(|e| !e.2).count(), 2, "{e:?}");
            // One maximum of the stride; the other is the small bump between the two minima.
            let big = e.iter().filter(|e| e.2 && e.1 > 0.5).count();
            assert_eq!(big, 1, "{e:?}");
        }
    }

    #[test]
    fn stair_amplitudes_match_section_6_1_at_38_degrees() {
        let g = GaitThigh::default();
        let (lo, hi) = g.extremes(Shape::Up, 38.0, 0.17);
        assert!((hi - lo - 53.07).abs() < 1e-9);
        let (lo, hi) = g.extremes(Shape::Down, 38.0, 0.17);
        assert!((hi - lo - 26.62).abs() < 1e-9 && lo > 0.0);
    }
}
