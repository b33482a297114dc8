//! The magnetic guard: where the magnetometer is disturbed, the yaw follows the gyroscope.
//! May import: the rest of `engine`.
//!
//! Our addition to the papers. Every orientation source that has a heading takes its
//! yaw from the magnetometer: the OS rotation vector, Madgwick with a magnetometer. Indoors the
//! field is bent by steel and wiring: on the 24 Microsoft walks its size swings by ±6–9 µT
//! (1 sd) about ~41 µT, from 17 to 67 µT, and the attitude's yaw is pulled with it. A constant
//! offset is harmless (a learnt correction or the fusion removes it), a yaw that bends with the
//! building is not.
//!
//! # Rule
//! Each sample, the guard keeps a yaw correction δ (counter-clockwise about up, radians) and hands
//! on the attitude `R_z(δ)·q`, with the horizontal acceleration turned alike:
//! 1. **Predict** with the gyroscope: the previous guarded attitude turned by the body rate,
//!    `q̂ = q'ₖ₋₁·exp(ω·dt)`. δ becomes the twist about up of `q̂·qₖ⁻¹` (the swing is dropped:
//!    the source's tilt is kept, only its yaw is overruled).
//! 2. **Test the field** against a reference: the field's size |B| and its inclination (dip,
//!    below the horizontal, from the source's tilt). The field is *clean* when both are within
//!    [`MagneticConfig::magnitude_tol`] and [`MagneticConfig::dip_tol_deg`] of the reference and
//!    have been for [`MagneticConfig::settle_s`].
//! 3. **Correct** only while clean: δ decays towards 0 (the source's own yaw) with time constant
//!    [`MagneticConfig::tau_s`]. While disturbed δ is left as predicted: the heading follows the
//!    gyroscope, and [`MagneticDiagnostics::disturbed`] says so.
//!
//! # Reference
//! The median |B| and dip of the walk so far, from fixed histograms (0.5 µT bins, and 0.005 bins
//! of sin(dip), which needs no arcsine per sample: bounded memory, deterministic), refreshed each
//! second once [`MagneticConfig::learn_s`] of samples are in. The walk's own
//! median rather than the World Magnetic Model's value: a phone's magnetometer carries its own
//! scale and hard-iron residue (Android calibrates it on the fly; the IPIN 2023 phone reads
//! 29–39 µT and a 55–63° dip where the model gives 49.0 µT and 65.5°), and most uploads carry no
//! position to look the model up at. A walk disturbed more than half the time has a reference
//! within the disturbance; the test then still flags the swings about it.
//!
//! Without a gyroscope or a magnetometer on the sample, or with a source that has no heading,
//! the attitude passes unchanged (so in live mode, where a browser has no magnetometer event).
//!
//! The fusion is given the heading without the correction ([`Magnetic::unguarded`]): its heading
//! correction is one constant, and a yaw held on the gyroscope for minutes wanders: fed the
//! guarded heading, the fused track of the IPIN 2023 walks got worse at every setting tried.
//!
//! The tolerances (15 %, 5°) are twice the cleanest walks' median departures (IPIN route 05:
//! 5–7 %, 2°); τ = 3 s because a clean field taking the yaw at once (τ → 0) brings the last
//! bend's error with it. A gyroscope bias b leaves a steady offset b·τ while clean (0.5° on the
//! simulator's 0.17°/s); an integral term that learnt it learnt the field's bends instead, so
//! there is none. The figures are in `docs/methods/magnetic-guard.md`.

use super::math::{atan2, wrap_pi};
use super::orientation::NavAccel;
use super::types::{positive, ConfigError, ImuSample};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Settings of the magnetic guard.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct MagneticConfig {
    /// Whether the guard runs (default on).
    pub enabled: bool,
    /// Largest departure of |B| from the reference for a clean field, as a fraction of it.
    pub magnitude_tol: f64,
    /// Largest departure of the dip from the reference for a clean field, degrees.
    pub dip_tol_deg: f64,
    /// How long the field must stay clean before it corrects the yaw again, s.
    pub settle_s: f64,
    /// Time constant with which a clean field pulls the yaw back to the source's, s.
    pub tau_s: f64,
    /// Samples needed, in seconds of data, before the reference is trusted, s.
    pub learn_s: f64,
}

impl Default for MagneticConfig {
    fn default() -> Self {
        MagneticConfig {
            enabled: true,
            magnitude_tol: 0.15,
            dip_tol_deg: 5.0,
            settle_s: 1.0,
            tau_s: 3.0,
            learn_s: 3.0,
        }
    }
}

impl MagneticConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("magnetic.magnitude_tol", self.magnitude_tol)?;
        positive("magnetic.dip_tol_deg", self.dip_tol_deg)?;
        positive("magnetic.tau_s", self.tau_s)?;
        positive("magnetic.learn_s", self.learn_s)?;
        if !(self.settle_s.is_finite() && self.settle_s >= 0.0) {
            return Err(ConfigError::new(
                "magnetic.settle_s",
                "must be a finite number of seconds, 0 or more",
            ));
        }
        Ok(())
    }
}

/// The guard's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MagneticDiagnostics {
    /// Whether the last sample's field was disturbed (the yaw follows the gyroscope).
    pub disturbed: bool,
    /// Time spent disturbed so far, s.
    pub disturbed_s: f64,
    /// Time with a field tested so far, s.
    pub tested_s: f64,
    /// The reference field size, µT, and dip, degrees, once learnt.
    pub reference: Option<(f64, f64)>,
    /// The yaw correction now, degrees (counter-clockwise about up).
    pub correction_deg: f64,
}

const MAG_BIN: f64 = 0.5;
const MAG_BINS: usize = 400; // 0–200 µT
const SIN_DIP_BIN: f64 = 0.005;
const SIN_DIP_BINS: usize = 400; // sin(dip) −1…1: about 0.3° near 0°, 1.3° near 65°

/// A median over fixed bins. The median's bin is followed as values come (`med`, with the count
/// of the values below it), so a median moves it by the bins it moved, not a scan from the
/// first bin.
#[derive(Debug, Clone)]
struct Histogram {
    counts: Vec<u32>,
    total: u64,
    lo: f64,
    bin: f64,
    med: usize,
    below: u64,
}

impl Histogram {
    fn new(lo: f64, bin: f64, bins: usize) -> Self {
        Histogram {
            counts: vec![0; bins],
            total: 0,
            lo,
            bin,
            med: 0,
            below: 0,
        }
    }

    fn add(&mut self, v: f64) {
        if let Some(i) = self.bin_of(v) {
            // A full bin stays full (and the median may then not be reached: none).
            if self.counts[i] < u32::MAX {
                self.counts[i] += 1;
                if i < self.med {
                    self.below += 1;
                }
            }
            self.total += 1;
        }
    }

    /// The bin of `v`: ⌊(v − lo)/bin⌋, the first below it and the last above it; none for a
    /// value that is not finite. For a finite x, `x.max(0.0) as u32` is
    /// `x.floor().max(0.0) as usize` (a cast truncates, and above 0 truncation is the floor),
    /// without the floor, which x86-64's baseline computes in software; at or above the last
    /// bin's index (an integer) the floor is too, so the cast is needed only below it, where a
    /// cast to `u32` costs fewer instructions than one to `usize`.
    fn bin_of(&self, v: f64) -> Option<usize> {
        let x = (v - self.lo) / self.bin;
        let last = self.counts.len() - 1;
        if !x.is_finite() {
            None
        } else if x < last as f64 {
            Some(x.max(0.0) as u32 as usize)
        } else {
            Some(last)
        }
    }

    /// The centre of the first bin at which the count so far reaches half the values.
    fn median(&mut self) -> Option<f64> {
        if self.total == 0 {
            return None;
        }
        let half = self.total.div_ceil(2);
        // The bins below the median hold fewer than half, with the median's bin at least half.
        while self.med > 0 && self.below >= half {
            self.med -= 1;
            self.below -= u64::from(self.counts[self.med]);
        }
        while self.below + u64::from(self.counts[self.med]) < half {
            if self.med + 1 == self.counts.len() {
                return None;
            }
            self.below += u64::from(self.counts[self.med]);
            self.med += 1;
        }
        Some(self.lo + (self.med as f64 + 0.5) * self.bin)
    }
}

/// The rotation by the angle-axis vector `v` (rad): `UnitQuaternion::from_scaled_axis(v)`,
/// the same operations in the same order (nalgebra's `Quaternion::exp` of v/2, whose real part
/// is 0 so its e⁰ = 1 drops out) with one `sincos` of the half angle for its `sin` and `cos`.
fn rotation_of(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let half = v / 2.0;
    let nn = half.norm_squared();
    if nn <= f64::EPSILON * f64::EPSILON {
        return UnitQuaternion::identity();
    }
    let n = nn.sqrt();
    let (s, c) = libm::sincos(n);
    UnitQuaternion::new_unchecked(Quaternion::from_parts(c, half * (s / n)))
}

/// The real part and the `k` part of `p·q⁻¹` for unit quaternions: the two of the product's
/// four components that the twist about up needs, each as nalgebra's product computes it.
fn real_and_k_of_product_with_inverse(
    p: &UnitQuaternion<f64>,
    q: &UnitQuaternion<f64>,
) -> (f64, f64) {
    let (p0, p1, p2, p3) = (p.i, p.j, p.k, p.w);
    let (r0, r1, r2, r3) = (-q.i, -q.j, -q.k, q.w);
    let w = p3 * r3 - p0 * r0 - p1 * r1 - p2 * r2;
    let k = p3 * r2 + p0 * r1 - p1 * r0 + p2 * r3;
    (w, k)
}

/// The up (z) component of `q·b`, the vector `b` rotated by `q`, as nalgebra's rotation of a
/// vector computes it (t = 2 v×b, then t·w + v×t + b), without its other two components.
fn up_of_rotated(q: &UnitQuaternion<f64>, b: &Vector3<f64>) -> f64 {
    let (vx, vy, vz, w) = (q.i, q.j, q.k, q.w);
    let tx = (vy * b.z - vz * b.y) * 2.0;
    let ty = (vz * b.x - vx * b.z) * 2.0;
    let tz = (vx * b.y - vy * b.x) * 2.0;
    tz * w + (vx * ty - vy * tx) + b.z
}

/// [`wrap_pi`] of an angle within ±2π: there `remainder(a, 2π)` is `a` itself or `a ∓ 2π`,
/// both exact (Sterbenz), so the same value without the `remainder` call. −2π (whose remainder
/// is −0) and anything else go to [`wrap_pi`].
fn wrap_half_turns(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if a > -PI && a <= PI {
        a
    } else if a > PI && a <= TAU {
        a - TAU
    } else if a <= -PI && a > -TAU {
        a + TAU
    } else {
        wrap_pi(a)
    }
}

/// The magnetic guard stage.
#[derive(Debug, Clone)]
pub struct Magnetic {
    cfg: MagneticConfig,
    magnitude: Histogram,
    // sin(dip): the median is the same (asin is monotonic) and a sample needs no asin.
    sin_dip: Histogram,
    // The clean band of sin(dip) about the reference.
    sin_dip_band: (f64, f64),
    // The last dt and its decay exp(−dt/τ): sample intervals repeat.
    decay: (f64, f64),
    learnt_s: f64,
    reference: Option<(f64, f64)>,
    since_refresh_s: f64,
    clean_for_s: f64,
    delta: f64,
    last: Option<UnitQuaternion<f64>>,
    diag: MagneticDiagnostics,
}

impl Magnetic {
    /// A stage with validated settings.
    pub fn new(cfg: MagneticConfig) -> Self {
        Magnetic {
            cfg,
            magnitude: Histogram::new(0.0, MAG_BIN, MAG_BINS),
            sin_dip: Histogram::new(-1.0, SIN_DIP_BIN, SIN_DIP_BINS),
            sin_dip_band: (-1.0, 1.0),
            decay: (0.0, 1.0),
            learnt_s: 0.0,
            reference: None,
            since_refresh_s: 0.0,
            clean_for_s: 0.0,
            delta: 0.0,
            last: None,
            diag: MagneticDiagnostics {
                disturbed: false,
                disturbed_s: 0.0,
                tested_s: 0.0,
                reference: None,
                correction_deg: 0.0,
            },
        }
    }

    /// After a gap: the yaw is the source's again (the gyroscope cannot bridge it).
    pub fn reset(&mut self) {
        self.delta = 0.0;
        self.last = None;
        self.clean_for_s = 0.0;
    }

    /// Feeds one sample, `dt` seconds after the previous (0 after a gap), with the orientation
    /// source's output for it; returns that output with the guarded attitude.
    pub fn push(&mut self, s: &ImuSample, dt: f64, nav: NavAccel) -> NavAccel {
        let (Some(q), Some(gyro), Some(b), true) = (nav.attitude, s.gyro, s.mag, self.cfg.enabled)
        else {
            self.reset();
            return nav;
        };
        // 1. Predict: the guarded attitude turned by the body rate; keep only its yaw.
        if let Some(prev) = self.last.filter(|_| dt > 0.0) {
            let predicted = prev * rotation_of(&(gyro * dt));
            let (w, k) = real_and_k_of_product_with_inverse(&predicted, &q);
            self.delta = wrap_half_turns(2.0 * atan2(k, w));
        }
        // 2. Test the field.
        let clean = self.clean(&q, &b, dt);
        // 3. Correct while clean.
        if clean {
            if self.decay.0 != dt {
                self.decay = (dt, libm::exp(-dt / self.cfg.tau_s));
            }
            self.delta *= self.decay.1;
        }
        // R_z(δ) from the half angle; the horizontal acceleration turns by δ alike.
        let (s2, c2) = libm::sincos(0.5 * self.delta);
        let turn = UnitQuaternion::new_unchecked(Quaternion::new(c2, 0.0, 0.0, s2));
        let (sn, cs) = (2.0 * s2 * c2, c2 * c2 - s2 * s2);
        let guarded = turn * q;
        self.last = Some(guarded);
        self.diag.disturbed = !clean;
        self.diag.correction_deg = self.delta.to_degrees();
        NavAccel {
            up: nav.up,
            horizontal: nav
                .horizontal
                .map(|(e, n)| (cs * e - sn * n, sn * e + cs * n)),
            attitude: Some(guarded),
        }
    }

    /// Whether the field `b` (device frame, µT) is clean, seen through the source's tilt `q`;
    /// learns the reference from it.
    fn clean(&mut self, q: &UnitQuaternion<f64>, b: &Vector3<f64>, dt: f64) -> bool {
        let size = b.norm();
        if !(size.is_finite() && size > 1e-6) {
            return true;
        }
        let sin_dip = (-up_of_rotated(q, b) / size).clamp(-1.0, 1.0);
        self.magnitude.add(size);
        self.sin_dip.add(sin_dip);
        self.learnt_s += dt;
        self.since_refresh_s += dt;
        if self.learnt_s >= self.cfg.learn_s
            && (self.reference.is_none() || self.since_refresh_s >= 1.0)
        {
            self.since_refresh_s = 0.0;
            self.reference = self
                .magnitude
                .median()
                .zip(self.sin_dip.median().map(|x| libm::asin(x).to_degrees()));
            if let Some((_, dip)) = self.reference {
                let sin_deg = |d: f64| libm::sin(d.clamp(-90.0, 90.0).to_radians());
                self.sin_dip_band = (
                    sin_deg(dip - self.cfg.dip_tol_deg),
                    sin_deg(dip + self.cfg.dip_tol_deg),
                );
            }
            self.diag.reference = self.reference;
        }
        let Some((size_ref, _)) = self.reference else {
            // Before a reference, the source's yaw is all there is.
            self.clean_for_s += dt;
            return true;
        };
        self.diag.tested_s += dt;
        let ok = (size - size_ref).abs() <= self.cfg.magnitude_tol * size_ref
            && (self.sin_dip_band.0..=self.sin_dip_band.1).contains(&sin_dip);
        self.clean_for_s = if ok { self.clean_for_s + dt } else { 0.0 };
        let clean = ok && self.clean_for_s >= self.cfg.settle_s;
        if !clean {
            self.diag.disturbed_s += dt;
        }
        clean
    }

    /// A compass heading (radians, clockwise from north) taken in the guarded attitude, turned
    /// back into the source's: what the heading would have been without the guard. `then`: the
    /// correction of the moment the heading was taken, when that is not now (a late step in the
    /// hand, [`crate::engine::heading::StepHeading::guard_then`]).
    pub fn unguarded(&self, heading_rad: f64, then: Option<f64>) -> f64 {
        super::math::wrap_2pi(heading_rad + then.unwrap_or(self.delta))
    }

    /// The yaw correction δ handed on now, radians counter-clockwise about up.
    pub fn correction(&self) -> f64 {
        self.delta
    }

    /// The current values.
    pub fn diagnostics(&self) -> MagneticDiagnostics {
        self.diag
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;
    use crate::engine::orientation::G0;

    /// A flat phone turning about up at `rate` rad/s (counter-clockwise), sampled at 100 Hz for
    /// `secs`; the source's yaw is off by `bend(t)` rad and the field's size is scaled by
    /// `scale(t)`. Returns the guard's yaw error (guarded yaw minus true yaw), rad, and whether
    /// each sample was flagged.
    fn run(
        secs: f64,
        rate: f64,
        bend: impl Fn(f64) -> f64,
        scale: impl Fn(f64) -> f64,
        gyro: bool,
    ) -> Vec<(f64, f64, bool)> {
        let mut g = Magnetic::new(MagneticConfig::default());
        // Earth's field in ENU: 20 µT north, 40 µT down (dip 63.4°).
        let field = Vector3::new(0.0, 20.0, -40.0);
        let dt = 0.01;
        let mut out = Vec::new();
        for i in 0..(secs / dt) as usize {
            let t = i as f64 * dt;
            let truth = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rate * t);
            let source = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rate * t + bend(t));
            let s = ImuSample {
                t,
                accel: Vector3::new(0.0, 0.0, G0),
                gyro: gyro.then(|| Vector3::new(0.0, 0.0, rate)),
                mag: Some(truth.inverse() * field * scale(t)),
                orientation: Some(source),
            };
            let nav = NavAccel {
                up: 0.0,
                horizontal: Some((0.0, 0.0)),
                attitude: Some(source),
            };
            let q = g
                .push(&s, if i == 0 { 0.0 } else { dt }, nav)
                .attitude
                .unwrap();
            let err = wrap_pi(2.0 * libm::atan2((q * truth.inverse()).k, (q * truth.inverse()).w));
            out.push((t, err, g.diagnostics().disturbed));
        }
        out
    }

    #[test]
    fn a_clean_field_leaves_the_source_yaw_alone() {
        let r = run(20.0, 0.4, |_| 0.0, |_| 1.0, true);
        assert!(r.iter().all(|&(_, e, d)| e.abs() < 1e-6 && !d));
    }

    #[test]
    fn a_bent_field_is_flagged_and_the_gyroscope_holds_the_yaw() {
        // From 10 to 20 s a steel beam: the field is 40 % stronger and the source's yaw is
        // pulled 30° off.
        let inside = |t: f64| (10.0..20.0).contains(&t);
        let r = run(
            40.0,
            0.2,
            |t| if inside(t) { 0.5 } else { 0.0 },
            |t| if inside(t) { 1.4 } else { 1.0 },
            true,
        );
        for &(t, e, d) in &r {
            if inside(t) {
                assert!(d, "flagged at {t}");
                assert!(e.abs() < 1e-6, "held at {t}: {e}");
            }
            // Clean again: back on the source's (right) yaw within the settling time.
            if t > 21.5 {
                assert!(!d && e.abs() < 1e-6, "{t}: {e}");
            }
        }
    }

    #[test]
    fn a_field_bent_at_the_start_is_judged_against_the_walk() {
        // The first 2 s are bent, before any reference: the source's yaw is taken, then the
        // reference (learnt from the whole walk so far) settles on the true field and the
        // yaw returns to the source's, right again.
        let r = run(
            30.0,
            0.0,
            |t| if t < 2.0 { 0.3 } else { 0.0 },
            |t| if t < 2.0 { 1.5 } else { 1.0 },
            true,
        );
        assert!(r.iter().filter(|x| x.0 > 10.0).all(|&(_, _, d)| !d));
        assert!(r
            .iter()
            .filter(|x| x.0 > 25.0)
            .all(|&(_, e, _)| e.abs() < 1e-3));
    }

    #[test]
    fn without_a_gyroscope_the_attitude_passes_unchanged() {
        let r = run(
            20.0,
            0.2,
            |t| if t > 5.0 { 0.5 } else { 0.0 },
            |t| if t > 5.0 { 1.4 } else { 1.0 },
            false,
        );
        assert!(r
            .iter()
            .filter(|x| x.0 > 5.0)
            .all(|&(_, e, _)| (e - 0.5).abs() < 1e-9));
    }

    #[test]
    fn a_value_takes_the_bin_of_its_floor() {
        let h = Histogram::new(-1.0, 0.005, 400);
        for v in [
            -5.0, -1.0, -0.9999, -0.0, 0.0, 0.0049, 0.005, 0.3, 0.99, 0.995, 1.0, 7.0, 1e300,
        ] {
            let x = (v - h.lo) / h.bin;
            let floor = (x.floor().max(0.0) as usize).min(h.counts.len() - 1);
            assert_eq!(h.bin_of(v), Some(floor), "{v}");
        }
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(h.bin_of(v), None);
        }
    }

    #[test]
    fn every_value_takes_the_bin_of_its_floor() {
        for h in [
            Histogram::new(-1.0, 0.005, 400),
            Histogram::new(0.0, 0.5, 400),
        ] {
            for i in -2000..=300_000 {
                let v = h.lo + i as f64 * h.bin * 0.0013 + 1e-9 * (i % 7) as f64;
                let x = (v - h.lo) / h.bin;
                let floor = (x.floor().max(0.0) as usize).min(h.counts.len() - 1);
                assert_eq!(h.bin_of(v), Some(floor), "{v}");
            }
        }
    }

    #[test]
    fn the_reference_is_a_median_of_bins() {
        let mut h = Histogram::new(0.0, 0.5, 400);
        for v in [30.0, 30.2, 30.4, 55.0, 31.0] {
            h.add(v);
        }
        h.add(f64::NAN);
        h.add(1e9);
        assert_eq!(h.total, 6);
        assert_eq!(h.median(), Some(30.25));
        assert_eq!(Histogram::new(0.0, 0.5, 4).median(), None);
    }

    #[test]
    fn the_followed_median_is_the_scanned_one() {
        let scanned = |h: &Histogram| {
            let half = h.total.div_ceil(2);
            let mut acc = 0u64;
            for (i, &c) in h.counts.iter().enumerate() {
                acc += u64::from(c);
                if acc >= half && h.total > 0 {
                    return Some(h.lo + (i as f64 + 0.5) * h.bin);
                }
            }
            None
        };
        let mut h = Histogram::new(0.0, 0.5, 400);
        let mut x = 0.77f64;
        for k in 0..5000 {
            x = (x * 9301.0 + 49297.0) % 233280.0;
            // Drifting up, then down, with outliers: the median walks both ways.
            let centre = if k < 2500 {
                20.0 + k as f64 * 0.02
            } else {
                120.0 - k as f64 * 0.03
            };
            let v = centre + (x / 233280.0 - 0.5) * 30.0 + if k % 97 == 0 { 150.0 } else { 0.0 };
            h.add(v);
            if k % 7 == 0 {
                let want = scanned(&h);
                assert_eq!(h.median(), want, "{k}");
            }
        }
    }

    #[test]
    fn the_shortcuts_match_nalgebra_and_remainder_bit_for_bit() {
        use std::f64::consts::{PI, TAU};
        let mut x = 0.1234f64;
        let mut next = || {
            x = (x * 9301.0 + 49297.0) % 233280.0;
            x / 233280.0 * 2.0 - 1.0
        };
        for i in 0..2000 {
            let scale = [1e-9, 1e-3, 0.05, 1.0, 4.0][i % 5];
            let v = Vector3::new(next(), next(), next()) * scale;
            let p = UnitQuaternion::from_scaled_axis(Vector3::new(next(), next(), next()) * 3.0);
            let q = UnitQuaternion::from_scaled_axis(Vector3::new(next(), next(), next()) * 3.0);
            let b = Vector3::new(next(), next(), next()) * 50.0;
            let r = rotation_of(&v);
            let want = UnitQuaternion::from_scaled_axis(v);
            assert_eq!(r.coords, want.coords, "{v:?}");
            let d = p * q.inverse();
            assert_eq!(real_and_k_of_product_with_inverse(&p, &q), (d.w, d.k));
            assert_eq!(up_of_rotated(&q, &b).to_bits(), (q * b).z.to_bits());
            let a = next() * 2.0 * TAU;
            assert_eq!(wrap_half_turns(a).to_bits(), wrap_pi(a).to_bits(), "{a}");
        }
        for a in [0.0, -0.0, PI, -PI, TAU, -TAU, 2.0 * TAU, f64::NAN, 1e300] {
            let (got, want) = (wrap_half_turns(a), wrap_pi(a));
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{a}"
            );
        }
        let tiny = Vector3::new(1e-17, 0.0, 0.0);
        assert_eq!(rotation_of(&tiny), UnitQuaternion::from_scaled_axis(tiny));
    }
}
