//! Small numeric helpers shared by the stages.
//! May import: nothing of the crate (libm and nalgebra only).
//!
//! Every transcendental function goes through `libm`, a pure-Rust implementation, so that a
//! replay gives bit-identical results natively and in WebAssembly.

use std::f64::consts::{PI, TAU};

/// The six distinct entries of the outer product v·vᵀ: xx, yy, zz, xy, xz, yz.
pub fn outer_entries(v: &nalgebra::Vector3<f64>) -> [f64; 6] {
    [
        v.x * v.x,
        v.y * v.y,
        v.z * v.z,
        v.x * v.y,
        v.x * v.z,
        v.y * v.z,
    ]
}

/// The symmetric matrix whose six distinct entries are `e`, in [`outer_entries`]'s order (xx,
/// yy, zz, xy, xz, yz).
pub fn from_outer_entries(e: &[f64; 6]) -> nalgebra::Matrix3<f64> {
    let [xx, yy, zz, xy, xz, yz] = *e;
    nalgebra::Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// Wraps an angle to (−π, π].
pub fn wrap_pi(a: f64) -> f64 {
    let mut x = libm::remainder(a, TAU);
    if x <= -PI {
        x += TAU;
    }
    x
}

/// Wraps an angle to [0, 2π).
pub fn wrap_2pi(a: f64) -> f64 {
    let x = a.rem_euclid(TAU);
    if x >= TAU {
        0.0
    } else {
        x
    }
}

/// Circular mean of two angles: the direction of the sum of their unit vectors. When the two are
/// exactly opposite the mean is undefined and the newer angle `b` is returned.
pub fn circular_mean2(a: f64, b: f64) -> f64 {
    let (sa, ca) = libm::sincos(a);
    let (sb, cb) = libm::sincos(b);
    let (s, c) = (sa + sb, ca + cb);
    if s * s + c * c < 1e-18 {
        b
    } else {
        libm::atan2(s, c)
    }
}

/// `libm::atan2(y, x)` bit for bit, rad, cheaper in its usual case: with |y| < x (x > 0, within
/// 45° of +x) libm's atan2 is `atan(|y/x|)` with y's sign, and libm's `atan` takes the absolute
/// value and puts the sign back itself, so `atan(y/x)` is the same number without atan2's case
/// analysis. Anything else (x ≤ |y|, infinities, NaN) goes to `libm::atan2`.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    if y.abs() < x {
        libm::atan(y / x)
    } else {
        libm::atan2(y, x)
    }
}

/// Compass heading (radians clockwise from north) of the horizontal vector (east, north).
pub fn heading_of(east: f64, north: f64) -> f64 {
    wrap_2pi(libm::atan2(east, north))
}

/// sin and cos of a phase increment `x`, rad: the per-sample rotation of the PLL's oscillator and
/// of the Fourier integrals' phasor (ω·Δt ≈ 0.06–0.11 rad at 100 Hz).
///
/// Up to 0.4 rad (15 Hz sampling of a 1 s stride) by the Taylor series to x⁷/x⁸; the error per
/// call is below |x|⁹/9! ≤ 1.9e-9·|x|, so a phasor rotated through a whole cycle (Σ|x| = 2π) drifts
/// by less than 1.2e-8 rad (4e-13 rad at 100 Hz). Both users re-anchor the phasor every cycle, and the trapezoidal rule of
/// the Fourier integrals is itself only accurate to about (ωΔt)²/12 ≈ 3e-4. Larger increments go
/// to `libm`. Pure arithmetic, so identical natively and in wasm.
#[inline]
pub fn sincos_increment(x: f64) -> (f64, f64) {
    if !(x.abs() <= 0.4) {
        return libm::sincos(x);
    }
    let x2 = x * x;
    if x.abs() <= 0.12 {
        // The usual case (ω·dt ≈ 0.06–0.11 rad at 100 Hz): to x⁵/x⁶, error below
        // |x|⁷/7! ≤ 6e-10·|x|, inside the bound above.
        let s = x * (1.0 - x2 * (1.0 / 6.0) * (1.0 - x2 * (1.0 / 20.0)));
        let c = 1.0 - x2 * 0.5 * (1.0 - x2 * (1.0 / 12.0) * (1.0 - x2 * (1.0 / 30.0)));
        return (s, c);
    }
    let s = x * (1.0 - x2 * (1.0 / 6.0) * (1.0 - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0))));
    let c = 1.0
        - x2 * 0.5
            * (1.0 - x2 * (1.0 / 12.0) * (1.0 - x2 * (1.0 / 30.0) * (1.0 - x2 * (1.0 / 56.0))));
    (s, c)
}

/// First-order low-pass filter for irregular sampling.
///
/// Backward-Euler discretisation of `τ ẏ = x − y`: `y += dt/(τ+dt) · (x − y)`. It is stable for any
/// `dt` and needs no `exp` per sample; for `dt ≪ τ` it matches the exact exponential response.
/// Biquads (e.g. the `biquad` crate) assume a fixed sample rate, which our inputs do not have.
#[derive(Debug, Clone, Copy)]
pub struct OnePole {
    tau: f64,
    y: Option<f64>,
}

impl OnePole {
    /// A filter with time constant `tau` seconds (cut-off `1/(2πτ)` Hz).
    pub fn new(tau: f64) -> Self {
        OnePole { tau, y: None }
    }

    /// A filter with the given −3 dB cut-off frequency in Hz.
    pub fn with_cutoff_hz(fc: f64) -> Self {
        Self::new(1.0 / (TAU * fc))
    }

    /// Feeds `x` after `dt` seconds; the first call initialises the output to `x`.
    pub fn update(&mut self, x: f64, dt: f64) -> f64 {
        self.update_with_gain(x, self.gain(dt))
    }

    /// The gain dt/(τ+dt) of a step of `dt` seconds, for filters sharing one τ.
    #[inline]
    pub fn gain(&self, dt: f64) -> f64 {
        dt / (self.tau + dt)
    }

    /// [`OnePole::update`] with the gain already computed by [`OnePole::gain`].
    #[inline]
    pub fn update_with_gain(&mut self, x: f64, k: f64) -> f64 {
        let y = match self.y {
            None => x,
            Some(y) => y + k * (x - y),
        };
        self.y = Some(y);
        y
    }

    /// The time constant, s.
    pub fn tau(&self) -> f64 {
        self.tau
    }

    /// The current output, if any input was seen.
    pub fn value(&self) -> Option<f64> {
        self.y
    }

    /// Forgets the state.
    pub fn reset(&mut self) {
        self.y = None;
    }
}

/// The symmetric part (P + Pᵀ)/2 of a covariance: keeps rounding from making it asymmetric.
pub fn symmetric<const D: usize>(p: nalgebra::SMatrix<f64, D, D>) -> nalgebra::SMatrix<f64, D, D> {
    (p + p.transpose()) * 0.5
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn the_outer_entries_rebuild_the_outer_product() {
        let v = nalgebra::Vector3::new(0.3, -1.7, 2.9);
        assert_eq!(from_outer_entries(&outer_entries(&v)), v * v.transpose());
    }

    #[test]
    fn atan2_is_libms_bit_for_bit() {
        let mut r = 0.4321f64;
        let mut next = || {
            r = (r * 9301.0 + 49297.0) % 233280.0;
            r / 233280.0 * 2.0 - 1.0
        };
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            1e-300,
            -1e-300,
            5e-324,
            1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let same = |y: f64, x: f64| {
            let (got, want) = (atan2(y, x), libm::atan2(y, x));
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "atan2({y:e}, {x:e}): {got:e} against {want:e}"
            );
        };
        for &y in &special {
            for &x in &special {
                same(y, x);
            }
        }
        for i in 0..200_000 {
            let scale = [1e-12, 1e-3, 1.0, 7.0, 1e9][i % 5];
            let (y, x) = (
                next() * scale,
                next() * [1e-12, 1e-3, 1.0, 7.0, 1e9][(i / 5) % 5],
            );
            same(y, x);
            same(x, y);
            same(y, y.abs());
            same(-y.abs(), y.abs());
        }
    }

    #[test]
    fn wrap_and_mean() {
        assert!((wrap_pi(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_2pi(-0.5) - (TAU - 0.5)).abs() < 1e-12);
        // Across the wrap: 350° and 10° average to 0°, not 180°.
        let m = circular_mean2(350f64.to_radians(), 10f64.to_radians());
        assert!(wrap_pi(m).abs() < 1e-9);
        assert!((heading_of(1.0, 0.0) - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn sincos_increment_within_its_bound() {
        for i in -2000..=2000 {
            let x = i as f64 / 1000.0;
            let (s, c) = sincos_increment(x);
            let err = (s - x.sin()).abs().max((c - x.cos()).abs());
            let bound = if x.abs() <= 0.4 {
                1.9e-9 * x.abs() + 2e-16
            } else {
                1e-15
            };
            assert!(err <= bound, "x {x}: error {err}");
        }
    }

    #[test]
    fn one_pole_step_response_independent_of_rate() {
        // Reaching ~63 % after one time constant, at 15 Hz and at 200 Hz alike.
        for rate in [15.0, 200.0] {
            let mut f = OnePole::new(1.0);
            f.update(0.0, 0.0);
            let mut y = 0.0;
            let n = (rate * 1.0) as usize;
            for _ in 0..n {
                y = f.update(1.0, 1.0 / rate);
            }
            assert!((y - 0.632).abs() < 0.05, "rate {rate}: {y}");
        }
    }
}
