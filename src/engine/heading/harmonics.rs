//! The step frequency's harmonics of the navigation-frame acceleration (Basso 2016 §III; Basso
//! 2021 eqs. 8 and 13), and the pelvis's rule for the way forward along a line (see the module
//! documentation of [`super`], "The 180° ambiguity").
//! May import: the rest of `engine`.

use super::NavSample;
use std::collections::VecDeque;
use std::f64::consts::TAU;

/// Fourier coefficients of the three navigation-frame channels at one harmonic.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Harmonic {
    /// cos coefficients (east, north, up).
    pub alpha: [f64; 3],
    /// sin coefficients (east, north, up).
    pub beta: [f64; 3],
}

/// Computes, over the window [t0, t1] of period T = t1 − t0, the coefficients
/// α_n = (2/T)∫ a(τ) cos(nωτ) dτ and β_n = (2/T)∫ a(τ) sin(nωτ) dτ (τ = t − t0, ω = 2π/T) for
/// n = 1 and 2 (Basso 2016 §III; Basso 2021 eqs. 8 and 13), by the trapezoidal rule on the
/// irregular samples, with the end values interpolated at t0 and t1.
/// Returns `None` when the buffer does not cover the window or has fewer than 4 samples in it.
pub fn fourier(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> Option<[Harmonic; 2]> {
    fourier_of(buf, t0, t1, |p| [p.e, p.n, p.up])
}

/// [`fourier`] of three channels taken from each sample by `channels` (the east, north and up
/// slots of the [`Harmonic`]s), the end values taken from the samples interpolated at t0 and t1.
pub fn fourier_of(
    buf: &VecDeque<NavSample>,
    t0: f64,
    t1: f64,
    channels: impl Fn(&NavSample) -> [f64; 3],
) -> Option<[Harmonic; 2]> {
    let period = t1 - t0;
    let first = buf.front()?;
    let last = buf.back()?;
    if !(period > 0.0) || first.t > t0 || last.t < t1 {
        return None;
    }
    let start = buf.partition_point(|s| s.t <= t0);
    let end = buf.partition_point(|s| s.t < t1);
    if end < start + 2 || start == 0 || end >= buf.len() {
        return None;
    }
    let w = TAU / period;
    // Trapezoidal rule written as a weighted sum: ∫ f ≈ Σ wᵢ fᵢ with wᵢ = (τᵢ₊₁ − τᵢ₋₁)/2 (half
    // intervals at the ends), over the interpolated end points and the samples between them. The
    // phasor (cos ωτ, sin ωτ) is rotated from point to point by the small angle ω·Δτ.
    let p0 = NavSample::lerp(&buf[start - 1], &buf[start], t0);
    let p1 = NavSample::lerp(&buf[end - 1], &buf[end], t1);
    let mut acc = [[0.0f64; 4]; 3];
    let mut add = |p: &NavSample, weight: f64, (c1, s1): (f64, f64)| {
        let trig = [c1, s1, c1 * c1 - s1 * s1, 2.0 * s1 * c1];
        for (a, v) in acc.iter_mut().zip(channels(p)) {
            let vw = v * weight;
            for j in 0..4 {
                a[j] += vw * trig[j];
            }
        }
    };
    let mut phasor = (1.0f64, 0.0f64);
    let rotate = |(c, s): (f64, f64), dt: f64| {
        let (ds, dc) = crate::engine::math::sincos_increment(w * dt);
        (c * dc - s * ds, s * dc + c * ds)
    };
    let (mut prev_t, mut cur) = (t0, p0);
    let [head, tail] = super::runs(buf, start, end);
    for run in [head, tail, std::slice::from_ref(&p1)] {
        for n in run {
            add(&cur, 0.5 * (n.t - prev_t), phasor);
            phasor = rotate(phasor, n.t - cur.t);
            prev_t = cur.t;
            cur = *n;
        }
    }
    add(&cur, 0.5 * (cur.t - prev_t), phasor);
    let scale = 2.0 / period;
    let coef = |j: usize| acc.map(|a| a[j] * scale);
    Some([
        Harmonic {
            alpha: coef(0),
            beta: coef(1),
        },
        Harmonic {
            alpha: coef(2),
            beta: coef(3),
        },
    ])
}

/// Returns +1 or −1: the sign that makes the horizontal unit vector `u` = (east, north) point
/// forward, from the harmonic `h` at the step frequency (see the module documentation).
pub fn forward_sign(h: &Harmonic, u: (f64, f64)) -> f64 {
    if forwardness(h, u) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The integral [`forward_sign`] takes the sign of, (T/2ω)⁻¹·∫ (a_h·u)(d a_up/dt) dt = p·d − q·c:
/// positive when `u` points forward, m²/s⁴.
pub fn forwardness(h: &Harmonic, u: (f64, f64)) -> f64 {
    let p = h.alpha[0] * u.0 + h.alpha[1] * u.1;
    let q = h.beta[0] * u.0 + h.beta[1] * u.1;
    let (c, d) = (h.alpha[2], h.beta[2]);
    p * d - q * c
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn fourier_recovers_coefficients_on_irregular_samples() {
        let (t0, t1) = (10.0, 10.6);
        let w = TAU / (t1 - t0);
        let mut buf = VecDeque::new();
        let mut t = 9.9;
        let mut i = 0u32;
        while t < 10.7 {
            let tau = t - t0;
            buf.push_back(NavSample {
                e: 1.5 * (w * tau).cos() - 0.5 * (2.0 * w * tau).sin(),
                n: 0.7 * (w * tau).sin() + 0.2,
                up: 2.0 * (2.0 * w * tau).cos(),
                ..NavSample::empty(t)
            });
            i += 1;
            t += 0.004 + 0.002 * ((i * 7919) % 13) as f64 / 13.0;
        }
        let h = fourier(&buf, t0, t1).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() < 0.01;
        assert!(
            close(h[0].alpha[0], 1.5) && close(h[1].beta[0], -0.5),
            "{h:?}"
        );
        assert!(
            close(h[0].beta[1], 0.7) && close(h[0].alpha[1], 0.0),
            "{h:?}"
        );
        assert!(close(h[1].alpha[2], 2.0), "{h:?}");
    }

    #[test]
    fn forward_sign_follows_inverted_pendulum() {
        // a_up = cos ωt, forward (north) a = −sin ωt.
        let h = Harmonic {
            alpha: [0.0, 0.0, 1.0],
            beta: [0.0, -1.0, 0.0],
        };
        assert_eq!(forward_sign(&h, (0.0, 1.0)), 1.0);
        assert_eq!(forward_sign(&h, (0.0, -1.0)), -1.0);
    }
}
