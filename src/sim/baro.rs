//! The simulated barometer: static pressure of the phone's true height through the standard
//! atmosphere, with white noise and a slow weather drift.
//! May import: `engine` and `io`.
//!
//! p = p₀·(1 − H/44330 m)^5.255 with H the altitude (the start's plus the phone's height above
//! it), so about −0.120 hPa per metre near sea level. The noise is white (σ = 0.03 hPa, about
//! 0.25 m: a phone's BMP-class sensor after its own filtering) plus a random walk of weather
//! (RMS 0.5 hPa after an hour, so about 0.04 hPa over a five-minute walk). Default rate 10 Hz:
//! phones report 1–25 Hz (iOS's altimeter about 1 Hz, the IPIN 2023 logs' `PRES` about 6 Hz,
//! Android's fastest delay about 25 Hz); 10 Hz is in the middle of that range, above what a
//! floor detector needs and light in the logs. Seeded on a stream of its own, so turning the
//! barometer on leaves the IMU samples bit-identical.

use super::Rng;
use crate::engine::types::PressureSample;
use crate::engine::Record;

/// The barometer.
#[derive(Debug, Clone, PartialEq)]
pub struct BaroSim {
    /// Samples per second.
    pub rate_hz: f64,
    /// Sea-level pressure of the standard atmosphere, hPa.
    pub p0_hpa: f64,
    /// Altitude of the start above sea level, m.
    pub altitude_m: f64,
    /// White noise, hPa (1σ).
    pub noise_hpa: f64,
    /// Weather drift: the RMS of its random walk after one hour, hPa.
    pub drift_hpa_per_h: f64,
}

impl Default for BaroSim {
    fn default() -> Self {
        BaroSim {
            rate_hz: 10.0,
            p0_hpa: 1013.25,
            altitude_m: 0.0,
            noise_hpa: 0.03,
            drift_hpa_per_h: 0.5,
        }
    }
}

/// Pressure of the standard atmosphere at altitude `h_m` for sea-level pressure `p0_hpa`, hPa.
pub fn standard_pressure_hpa(p0_hpa: f64, h_m: f64) -> f64 {
    p0_hpa * libm::pow(1.0 - h_m / 44_330.0, 5.255)
}

impl BaroSim {
    /// Samples from 0 to `duration_s` (skipping `gaps`), the phone's height above the start given
    /// by `height`; times shifted by `offset_s`.
    pub(super) fn samples(
        &self,
        seed: u64,
        duration_s: f64,
        offset_s: f64,
        gaps: &[(f64, f64)],
        height: impl Fn(f64) -> f64,
    ) -> Vec<Record> {
        let mut rng = Rng(seed ^ 0xBA20_5EED);
        let dt = 1.0 / self.rate_hz;
        // RMS after an hour = σ_step·√(3600 s/dt).
        let step = self.drift_hpa_per_h / 60.0 * libm::sqrt(dt);
        let mut drift = 0.0;
        let mut out = Vec::new();
        let mut k = 0u64;
        loop {
            let t = k as f64 * dt;
            if t > duration_s {
                break;
            }
            k += 1;
            drift += step * rng.normal();
            let noise = self.noise_hpa * rng.normal();
            if gaps.iter().any(|&(a, b)| t > a && t < b) {
                continue;
            }
            let p = standard_pressure_hpa(self.p0_hpa, self.altitude_m + height(t));
            out.push(Record::Pressure(PressureSample {
                t: t + offset_s,
                hpa: p + drift + noise,
            }));
        }
        out
    }
}
