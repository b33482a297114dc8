//! The simulator's noise: a seeded SplitMix64 generator with Box–Muller normals over `libm`, so
//! a scenario gives bit-identical samples natively and in WebAssembly.

use nalgebra::Vector3;
use std::f64::consts::TAU;

/// SplitMix64 with Box–Muller normals.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub(super) fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(super) fn normal(&mut self) -> f64 {
        let u1 = self.uniform().max(1e-300);
        let u2 = self.uniform();
        libm::sqrt(-2.0 * libm::log(u1)) * libm::cos(TAU * u2)
    }
    pub(super) fn vec3(&mut self, s: f64) -> Vector3<f64> {
        Vector3::new(self.normal() * s, self.normal() * s, self.normal() * s)
    }
}
