//! Hybrid heading (Strozzi 2017 §4): each stride's length from a foot-mounted IMU (foot mode,
//! [`crate::engine::foot`]), its heading from a trunk (lower back, or pocket) sensor's attitude,
//! sampled at the foot's mid-swing (method 1, §4.1 eq. 3) or where the trunk heading crosses its
//! FIR-filtered self (method 2, §4.1 and Fig. 7); propagation by eq. 4.
//! May import: the rest of `engine`.
//!
//! # What is sampled
//! The paper samples the *attitude* of the lower-back sensor (q̂(k) of eq. 3, the heading h(k)
//! of eq. 4 from it), not a per-step direction of walking computed from the acceleration, so
//! [`Hybrid::push_heading`] takes the trunk sensor's yaw for every trunk sample (in the
//! pipeline: the twist of the trunk attitude about the vertical,
//! [`crate::engine::heading::yaw_aid::device_twist`]). Basso's per-step headings are a
//! different method and are not used here.
//!
//! # Decisions where the paper is vague or wrong
//! - **Eq. 3** reads t_mid = (t_end + t_start)/2 + t_end, which is not an instant between the
//!   two (it is about 1.5 × t_end): a typo for the midpoint. With one foot sensor, the mid-swing
//!   is the middle of that foot's swing, the foot stage's [`Stride::t_mid_swing`] (the midpoint
//!   of the stance end and the next stance start, as eq. 3 means).
//! - **The median of quaternions** (eq. 3) is not defined; the median of the yaw angles of the
//!   `Win` = 10 trunk samples nearest the instant (unwrapped, so the median does not straddle
//!   ±π) is. With an even count, the mean of the two central values, as the paper says.
//! - **Frames.** The paper's two Xsens sensors share one north. Here the foot sensor has no
//!   magnetometer (its yaw is that of its first stance, [`crate::engine::foot`]) and a pocket
//!   phone sits at an unknown yaw in the pocket, so the trunk yaw is taken relative to the
//!   foot's frame: δ, the circular mean of (foot stride heading − sampled trunk yaw) over the
//!   first [`HybridConfig::align_strides`] strides (of at least 0.2 m), is added to every
//!   sample; before that many strides, the mean so far. Headings come out in the foot's frame,
//!   where foot mode's track is, so the two compare directly.
//! - **Method 2's filter.** The paper's FIR: least squares (firls) with a 0.5 Hz passband edge
//!   and a 0.6 Hz stopband edge, M = 150 taps at F_s = 100 Hz (a 0.75 s delay). The trunk yaw
//!   is resampled (linear interpolation) to a fixed 100 Hz grid so that the same taps serve any
//!   sensor rate, and the filter is designed once ([`fir_least_squares`], equal weights on both
//!   bands, DC gain normalised to 1). The raw yaw is compared with the filter output delayed by
//!   exactly (M − 1)/2 samples (the paper rounds it to M/2).
//! - **Which crossing.** The trunk yaw crosses its low-passed self twice per stride (when the
//!   pelvis faces the walking direction at each foot's mid-swing). For a stride of the one foot
//!   sensor, the crossing within that foot's swing [t_start, t_end] nearest its mid-swing is
//!   taken: the paper's aim is the same mid-swing instant (§4.1: "find the same middle swing
//!   point"), and the swing (~40 % of a cycle) excludes the other foot's crossing (half a cycle
//!   away). The heading there is the raw yaw at the crossing. A stride with no crossing in its
//!   swing (a turn, a stop) falls back to method 1 and is counted.
//! - **Latency.** Method 2 knows a crossing (M − 1)/2 samples after it; a stride is resolved
//!   once the trunk's filtered yaw has reached its end, so [`Hybrid::push_stride`] queues it and
//!   [`Hybrid::pop`] gives it when ready ([`Hybrid::flush`] at the end of a log).
//! - **No trunk yaw** near the instant (more than 0.1 s away, a gap): the foot's own heading,
//!   counted.

use super::foot::Stride;
use super::math::{wrap_2pi, wrap_pi};
use super::types::{positive, time_in_range, ConfigError};
use nalgebra::{DMatrix, DVector};
use std::collections::VecDeque;
use std::f64::consts::PI;

/// How the trunk heading is sampled for each stride.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HybridMethod {
    /// Method 1: the median trunk yaw around the foot's mid-swing (eq. 3).
    MidSwing,
    /// Method 2: the trunk yaw where it crosses its FIR-filtered self (Fig. 7).
    FirCrossing,
    /// The foot's own heading (foot mode, §3.2): the trunk is not used.
    Foot,
}

/// Settings of the hybrid heading.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HybridConfig {
    /// Method 1 or 2.
    pub method: HybridMethod,
    /// `Win`: trunk samples in the median of eq. 3 (the paper: 10).
    pub median_samples: usize,
    /// FIR taps M (the paper: 150).
    pub fir_taps: usize,
    /// Rate of the grid the FIR runs on, Hz (the paper's F_s: 100).
    pub fir_rate_hz: f64,
    /// FIR passband edge, Hz (the paper: 0.5).
    pub pass_hz: f64,
    /// FIR stopband edge, Hz (the paper: 0.6).
    pub stop_hz: f64,
    /// Strides over which the trunk-to-foot yaw offset δ is learnt (ours; see the module notes).
    pub align_strides: usize,
}

impl Default for HybridConfig {
    fn default() -> Self {
        HybridConfig {
            method: HybridMethod::MidSwing,
            median_samples: 10,
            fir_taps: 150,
            fir_rate_hz: 100.0,
            pass_hz: 0.5,
            stop_hz: 0.6,
            align_strides: 10,
        }
    }
}

impl HybridConfig {
    /// Checks every value; the error names the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("hybrid.fir_rate_hz", self.fir_rate_hz)?;
        positive("hybrid.pass_hz", self.pass_hz)?;
        positive("hybrid.stop_hz", self.stop_hz)?;
        if self.stop_hz <= self.pass_hz || self.stop_hz >= 0.5 * self.fir_rate_hz {
            return Err(ConfigError::new(
                "hybrid.stop_hz",
                "must lie between the passband edge and half the FIR rate",
            ));
        }
        if !(2..=1000).contains(&self.fir_taps) {
            return Err(ConfigError::new("hybrid.fir_taps", "must be 2 to 1000"));
        }
        if !(1..=1000).contains(&self.median_samples) {
            return Err(ConfigError::new(
                "hybrid.median_samples",
                "must be 1 to 1000",
            ));
        }
        if self.align_strides == 0 {
            return Err(ConfigError::new(
                "hybrid.align_strides",
                "must be at least 1",
            ));
        }
        Ok(())
    }
}

/// A stride with its hybrid heading and the position it takes the walker to (eq. 4).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HybridStride {
    /// The foot's stride.
    pub stride: Stride,
    /// The instant the trunk heading was sampled, s.
    pub t_sample: f64,
    /// The heading, rad clockwise from the foot frame's north, [0, 2π).
    pub heading_rad: f64,
    /// Position after the stride, east, m (foot frame).
    pub east_m: f64,
    /// Position after the stride, north, m (foot frame).
    pub north_m: f64,
}

/// Counters of the hybrid stage; read-only.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct HybridDiagnostics {
    /// Strides resolved.
    pub strides: u64,
    /// Method 2: crossings found.
    pub crossings: u64,
    /// Method 2: strides with no crossing in their swing (method 1 used).
    pub no_crossing: u64,
    /// Strides with no trunk yaw near their instant (the foot's heading used).
    pub no_trunk: u64,
    /// Trunk samples and strides refused (non-finite, time going backwards).
    pub refused: u64,
    /// Strides waiting for the filter.
    pub pending: usize,
    /// The trunk-to-foot yaw offset δ, rad.
    pub offset_rad: Option<f64>,
}

/// Least-squares linear-phase FIR low-pass (firls): `taps` coefficients minimising the squared
/// error of the amplitude response against 1 on [0, pass] and 0 on [stop, ½] (cycles/sample),
/// equal weights, DC gain normalised to 1. `None` when the normal equations are singular.
pub fn fir_least_squares(taps: usize, pass: f64, stop: f64) -> Option<Vec<f64>> {
    let k = taps.div_ceil(2);
    let half = if taps % 2 == 0 { 0.5 } else { 0.0 };
    let a: Vec<f64> = (0..k).map(|j| j as f64 + half).collect();
    let (wp, ws) = (2.0 * PI * pass, 2.0 * PI * stop);
    // ∫ cos(cω) dω from 0 to w.
    let prim = |c: f64, w: f64| if c == 0.0 { w } else { libm::sin(c * w) / c };
    let band = |c: f64| prim(c, wp) + prim(c, PI) - prim(c, ws);
    let q = DMatrix::from_fn(k, k, |i, j| 0.5 * (band(a[i] - a[j]) + band(a[i] + a[j])));
    let p = DVector::from_fn(k, |i, _| prim(a[i], wp));
    let b = q.lu().solve(&p)?;
    let mut h = vec![0.0; taps];
    let c = (taps as f64 - 1.0) / 2.0;
    for (i, hi) in h.iter_mut().enumerate() {
        let d = (i as f64 - c).abs();
        let j = (d - half).round() as usize;
        *hi = if a[j] == 0.0 { b[j] } else { 0.5 * b[j] };
    }
    let dc: f64 = h.iter().sum();
    if !(dc.is_finite() && dc.abs() > 1e-9) {
        return None;
    }
    h.iter_mut().for_each(|v| *v /= dc);
    Some(h)
}

/// The hybrid heading stage.
pub struct Hybrid {
    cfg: HybridConfig,
    taps: Vec<f64>,
    /// Recent trunk yaw samples (t, unwrapped yaw).
    trunk: VecDeque<(f64, f64)>,
    /// The last trunk yaw (unwrapped).
    last: Option<(f64, f64)>,
    /// Method 2: the grid's next time, its recent values and the last difference raw − filtered.
    grid_next: Option<f64>,
    grid: VecDeque<f64>,
    last_diff: Option<(f64, f64, f64)>,
    /// Latest time the filter output covers.
    filtered_until: f64,
    /// Crossings (t, unwrapped yaw).
    crossings: VecDeque<(f64, f64)>,
    queue: VecDeque<Stride>,
    ready: VecDeque<HybridStride>,
    /// δ: sums of sin and cos and count.
    align: (f64, f64, usize),
    pos: (f64, f64),
    diag: HybridDiagnostics,
}

/// How long trunk samples and crossings are kept, s: more than a stride's latency (its swing,
/// the foot stage's stance confirmation and the FIR's delay).
const HISTORY_S: f64 = 6.0;
/// A pause in the trunk samples longer than this restarts the filter, s.
const GAP_S: f64 = 0.5;
/// Strides held at most; an older one is resolved with what is known.
const MAX_QUEUE: usize = 64;

impl Hybrid {
    /// The stage with validated settings.
    pub fn new(cfg: HybridConfig) -> Result<Self, ConfigError> {
        cfg.validate()?;
        let taps = fir_least_squares(
            cfg.fir_taps,
            cfg.pass_hz / cfg.fir_rate_hz,
            cfg.stop_hz / cfg.fir_rate_hz,
        )
        .ok_or_else(|| ConfigError::new("hybrid.fir_taps", "the FIR design is singular"))?;
        Ok(Hybrid {
            cfg,
            taps,
            trunk: VecDeque::new(),
            last: None,
            grid_next: None,
            grid: VecDeque::new(),
            last_diff: None,
            filtered_until: f64::NEG_INFINITY,
            crossings: VecDeque::new(),
            queue: VecDeque::new(),
            ready: VecDeque::new(),
            align: (0.0, 0.0, 0),
            pos: (0.0, 0.0),
            diag: HybridDiagnostics::default(),
        })
    }

    /// The FIR's taps.
    pub fn taps(&self) -> &[f64] {
        &self.taps
    }

    /// Feeds the trunk sensor's yaw at time `t` (compass radians), for every trunk sample in
    /// time order. A non-finite value, a time beyond
    /// ±[`MAX_TIME_S`](super::types::MAX_TIME_S) or going backwards is
    /// refused and counted. A pause longer than 0.5 s restarts the filter (nothing is
    /// interpolated across it).
    pub fn push_heading(&mut self, t: f64, yaw_rad: f64) {
        if !(time_in_range(t) && yaw_rad.is_finite()) || self.last.is_some_and(|(lt, _)| t < lt) {
            self.diag.refused += 1;
            return;
        }
        let (x, bridged) = match self.last {
            Some((lt, lx)) if t - lt <= GAP_S => (lx + wrap_pi(yaw_rad - lx), true),
            Some((_, lx)) => {
                self.restart_filter();
                (lx + wrap_pi(yaw_rad - lx), false)
            }
            None => (wrap_pi(yaw_rad), false),
        };
        if self.cfg.method == HybridMethod::FirCrossing {
            // Within GAP_S of the previous sample: at most GAP_S × rate grid points.
            let from = self.last.filter(|_| bridged).unwrap_or((t, x));
            self.grid_to(from, (t, x));
        }
        self.last = Some((t, x));
        self.trunk.push_back((t, x));
        while self.trunk.front().is_some_and(|f| f.0 < t - HISTORY_S) {
            self.trunk.pop_front();
        }
        while self.crossings.front().is_some_and(|f| f.0 < t - HISTORY_S) {
            self.crossings.pop_front();
        }
    }

    fn restart_filter(&mut self) {
        self.grid_next = None;
        self.grid.clear();
        self.last_diff = None;
    }

    /// Resamples the segment from `a` to `b` onto the FIR grid and filters it.
    fn grid_to(&mut self, a: (f64, f64), b: (f64, f64)) {
        let step = 1.0 / self.cfg.fir_rate_hz;
        let mut g = self
            .grid_next
            .unwrap_or_else(|| libm::ceil(a.0 * self.cfg.fir_rate_hz) * step);
        let m = self.taps.len();
        let delay = (m as f64 - 1.0) / 2.0;
        while g <= b.0 {
            let w = if b.0 > a.0 {
                ((g - a.0) / (b.0 - a.0)).clamp(0.0, 1.0)
            } else {
                1.0
            };
            self.grid.push_back(a.1 + w * (b.1 - a.1));
            if self.grid.len() > m {
                self.grid.pop_front();
            }
            if self.grid.len() == m {
                // grid[m − 1 − i] is x[n − i].
                let y: f64 = self
                    .taps
                    .iter()
                    .enumerate()
                    .map(|(i, h)| h * self.grid[m - 1 - i])
                    .sum();
                // The raw value (M − 1)/2 samples back (between two grid points for even M).
                let lo = (m - 1) / 2;
                let hi = m / 2;
                let raw = 0.5 * (self.grid[m - 1 - lo] + self.grid[m - 1 - hi]);
                let tc = g - delay * step;
                let d = raw - y;
                if let Some((t0, d0, r0)) = self.last_diff {
                    if (d0 < 0.0 && d >= 0.0) || (d0 > 0.0 && d <= 0.0) {
                        let f = d0 / (d0 - d);
                        self.crossings
                            .push_back((t0 + f * (tc - t0), r0 + f * (raw - r0)));
                        self.diag.crossings += 1;
                    }
                }
                self.last_diff = Some((tc, d, raw));
                self.filtered_until = tc;
            }
            g += step;
        }
        self.grid_next = Some(g);
    }

    /// Queues a stride of the foot (in time order); see [`Hybrid::pop`]. A stride with a
    /// non-finite field or ending before the previous one is refused and counted.
    pub fn push_stride(&mut self, s: &Stride) {
        let finite = [s.t_start, s.t_end, s.t_mid_swing, s.length_m, s.heading_rad]
            .iter()
            .all(|v| v.is_finite());
        if !finite || self.queue.back().is_some_and(|b| s.t_end < b.t_end) {
            self.diag.refused += 1;
            return;
        }
        if self.queue.len() >= MAX_QUEUE {
            if let Some(old) = self.queue.pop_front() {
                let out = self.resolve(&old);
                self.ready.push_back(out);
            }
        }
        self.queue.push_back(*s);
        self.diag.pending = self.queue.len();
    }

    /// The next stride whose heading is known, in order.
    pub fn pop(&mut self) -> Option<HybridStride> {
        if let Some(r) = self.ready.pop_front() {
            return Some(r);
        }
        let s = *self.queue.front()?;
        let known = match self.cfg.method {
            HybridMethod::Foot => true,
            HybridMethod::MidSwing => self.last.is_some_and(|(t, _)| t >= s.t_end),
            HybridMethod::FirCrossing => self.filtered_until >= s.t_end,
        };
        if !known {
            return None;
        }
        self.queue.pop_front();
        self.diag.pending = self.queue.len();
        Some(self.resolve(&s))
    }

    /// Resolves every queued stride with what is known (the end of a log).
    pub fn flush(&mut self) -> Vec<HybridStride> {
        let mut out: Vec<HybridStride> = self.ready.drain(..).collect();
        while let Some(s) = self.queue.pop_front() {
            out.push(self.resolve(&s));
        }
        self.diag.pending = 0;
        out
    }

    /// Median of the `Win` trunk yaws nearest `t` (unwrapped), or `None` without a trunk sample
    /// within 0.1 s.
    fn median_at(&self, t: f64) -> Option<f64> {
        let i = self.trunk.partition_point(|s| s.0 < t);
        let near = [i.checked_sub(1), Some(i)]
            .into_iter()
            .flatten()
            .filter_map(|k| self.trunk.get(k))
            .any(|s| (s.0 - t).abs() <= 0.1);
        if !near {
            return None;
        }
        let n = self.cfg.median_samples;
        let lo = i.saturating_sub(n / 2);
        let hi = (lo + n).min(self.trunk.len());
        let lo = hi.saturating_sub(n);
        let mut v: Vec<f64> = self.trunk.range(lo..hi).map(|s| s.1).collect();
        crate::engine::sort::sort_by(&mut v, f64::total_cmp);
        let m = v.len();
        match m {
            0 => None,
            _ if m % 2 == 1 => Some(v[m / 2]),
            _ => Some(0.5 * (v[m / 2 - 1] + v[m / 2])),
        }
    }

    fn resolve(&mut self, s: &Stride) -> HybridStride {
        let mut t_sample = s.t_mid_swing;
        let mut yaw = None;
        if self.cfg.method == HybridMethod::FirCrossing {
            let best = self
                .crossings
                .iter()
                .filter(|c| c.0 >= s.t_start && c.0 <= s.t_end)
                .min_by(|a, b| {
                    (a.0 - s.t_mid_swing)
                        .abs()
                        .total_cmp(&(b.0 - s.t_mid_swing).abs())
                });
            match best {
                Some(&(t, x)) => {
                    t_sample = t;
                    yaw = Some(x);
                }
                None => self.diag.no_crossing += 1,
            }
        }
        if self.cfg.method == HybridMethod::Foot {
            self.diag.strides += 1;
            return self.propagate(s, s.t_end, s.heading_rad);
        }
        let yaw = yaw.or_else(|| self.median_at(t_sample));
        let heading = match yaw {
            Some(y) => {
                if self.align.2 < self.cfg.align_strides && s.length_m >= 0.2 {
                    let (sn, cs) = libm::sincos(s.heading_rad - y);
                    self.align = (self.align.0 + sn, self.align.1 + cs, self.align.2 + 1);
                    self.diag.offset_rad = Some(libm::atan2(self.align.0, self.align.1));
                }
                match self.diag.offset_rad {
                    Some(d) => wrap_2pi(y + d),
                    None => s.heading_rad,
                }
            }
            None => {
                self.diag.no_trunk += 1;
                s.heading_rad
            }
        };
        self.diag.strides += 1;
        self.propagate(s, t_sample, heading)
    }

    /// Eq. 4 with compass headings (clockwise from north): east += SL sin h, north += SL cos h.
    fn propagate(&mut self, s: &Stride, t_sample: f64, heading: f64) -> HybridStride {
        let (sh, ch) = libm::sincos(heading);
        self.pos.0 += s.length_m * sh;
        self.pos.1 += s.length_m * ch;
        HybridStride {
            stride: *s,
            t_sample,
            heading_rad: heading,
            east_m: self.pos.0,
            north_m: self.pos.1,
        }
    }

    /// Counters.
    pub fn diagnostics(&self) -> HybridDiagnostics {
        self.diag
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fir_is_a_low_pass() {
        let h = fir_least_squares(150, 0.005, 0.006).unwrap();
        assert_eq!(h.len(), 150);
        assert!((h[0] - h[149]).abs() < 1e-12 && (h[40] - h[109]).abs() < 1e-12);
        let gain = |f: f64| {
            let (mut re, mut im) = (0.0, 0.0);
            for (i, v) in h.iter().enumerate() {
                re += v * libm::cos(2.0 * PI * f * i as f64);
                im += v * libm::sin(2.0 * PI * f * i as f64);
            }
            libm::hypot(re, im)
        };
        assert!((gain(0.0) - 1.0).abs() < 1e-12);
        // A stride's pelvis yaw (0.8–1.5 Hz at 100 Hz) is damped; slow turns pass.
        for f in [0.008, 0.01, 0.012, 0.015] {
            assert!(gain(f) < 0.1, "{f}: {}", gain(f));
        }
        assert!(gain(0.001) > 0.9, "{}", gain(0.001));
    }

    #[test]
    fn settings_are_checked() {
        let bad = HybridConfig {
            stop_hz: 0.4,
            ..HybridConfig::default()
        };
        assert_eq!(bad.validate().unwrap_err().field, "hybrid.stop_hz");
        let bad = HybridConfig {
            fir_taps: 1,
            ..HybridConfig::default()
        };
        assert_eq!(bad.validate().unwrap_err().field, "hybrid.fir_taps");
        assert!(Hybrid::new(HybridConfig::default()).is_ok());
    }
}
