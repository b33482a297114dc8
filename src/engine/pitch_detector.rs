//! The pitch step detector (Munoz Diaz 2015 §4.1–4.2): one stride per maximum of the leg pitch,
//! on level ground and on stairs.
//! May import: the rest of `engine`.
//!
//! # Method
//! The paper: "each maximum indicated as θ_Hmax corresponds to a step", and the threshold "is
//! fixed for all walking speeds". Its step is a stride: two hits on the floor of the same foot
//! (its §1, and the 0.52 m "step" on stairs of 0.26 m treads in §7.3). The engine counts every
//! footfall, as every other detector here and every truth it is scored on, so each maximum
//! gives two steps: the other foot's at the stride's mid-time, and the pocket leg's at the
//! maximum. A bout's ends are decided by the pitch too (the paper is silent on them):
//! - the first maximum gives one step, or two when the rise to it is a whole stride's
//!   (`FULL_RISE` of the last amplitude): the thigh first went back while the other foot took
//!   the first step, at the thigh's backward extreme;
//! - when no maximum follows for `STOP_PERIODS` stride periods, the walk stopped, and the
//!   other foot's closing step is given half a stride after the last maximum.
//!
//! A maximum is taken once the pitch has fallen [`PitchDetectorConfig::hysteresis_deg`] below
//! it, and the next one is looked for once the pitch has risen as far above the minimum in
//! between. The paper's Fig. 2 shows a second, smaller maximum at heel strike, a few degrees
//! below the first; the hysteresis is above that dip and below the smallest amplitude of a
//! stride (down stairs, about 27° in the paper's §6.1), so each stride gives one maximum.
//! Each stride's θ_max, θ_min (the minimum before the maximum) and Δθ = θ_max − θ_min (eq. 4)
//! are kept for the activities, the step length and the height ([`PitchStride`]).

use std::collections::VecDeque;

use super::detector::{Candidate, DetectorInput};
use super::types::{positive, ConfigError};

/// Settings of the pitch step detector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct PitchDetectorConfig {
    /// How far the pitch must fall below a maximum (and rise above a minimum) to confirm it,
    /// degrees. Default 8°: above the heel-strike dip of Fig. 2 (3–5°), a third of the
    /// smallest stride amplitude the paper reports (26.6° down stairs).
    pub hysteresis_deg: f64,
    /// Longest stride that continues a bout, s. Default 2.5 s (a 0.8 Hz step rate: slower
    /// walking is a stop and a start).
    pub max_stride_s: f64,
}

impl Default for PitchDetectorConfig {
    fn default() -> Self {
        PitchDetectorConfig {
            hysteresis_deg: 8.0,
            max_stride_s: 2.5,
        }
    }
}

impl PitchDetectorConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive("detector.hysteresis_deg", self.hysteresis_deg)?;
        positive("detector.max_stride_s", self.max_stride_s)
    }
}

/// One stride of the pocket leg: the extremes and amplitude (Munoz Diaz 2015 eq. 4) of the
/// angle the detector was given (the leg pitch's raw angle: see [`crate::engine::leg_pitch`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PitchStride {
    /// Time of the maximum, s.
    pub t_max: f64,
    /// θ_max, degrees.
    pub max_deg: f64,
    /// θ_min, the minimum before the maximum, degrees.
    pub min_deg: f64,
    /// Time of that minimum, s.
    pub t_min: f64,
    /// Δθ = θ_max − θ_min, degrees.
    pub amplitude_deg: f64,
    /// Time since the previous maximum, s, when the stride continues a bout.
    pub period_s: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Phase {
    /// Looking for a minimum (the pitch is falling).
    Falling,
    /// Looking for a maximum (the pitch is rising).
    Rising,
}

/// The pitch step detector's running state.
#[derive(Debug, Clone)]
pub struct PitchDetector {
    cfg: PitchDetectorConfig,
    phase: Option<Phase>,
    ext: (f64, f64),
    min_deg: Option<(f64, f64)>,
    last_max_t: Option<f64>,
    pending: Option<Candidate>,
    stride: Option<PitchStride>,
    /// The last [`RECENT_STRIDES`] strides, oldest first.
    recent: VecDeque<PitchStride>,
    /// The amplitude of the last stride that continued a bout, degrees.
    ref_amp: f64,
    /// The bout's last stride period, s, until its closing step is given.
    open_period: Option<f64>,
}

/// The amplitude expected of a first stride before any was seen, degrees (a level stride of
/// the paper's Fig. 2 and of gait data: 35–40°).
const FIRST_AMPLITUDE_DEG: f64 = 35.0;

/// A bout's first rise from a minimum this share of a stride's amplitude or more began behind
/// the standing position: the other leg stepped first.
const FULL_RISE: f64 = 0.85;

/// How many of the last strides are kept ([`PitchDetector::strides_after`]): the steps an
/// onset's look-back gives at once span the look-back's 3–3.5 s, 2–3 strides at a walk's
/// cadence, 4 at a run's.
const RECENT_STRIDES: usize = 8;

/// No maximum for this many stride periods after the last: the walk stopped.
const STOP_PERIODS: f64 = 1.25;

impl PitchDetector {
    /// A detector with validated settings.
    pub fn new(cfg: PitchDetectorConfig) -> Self {
        PitchDetector {
            cfg,
            phase: None,
            ext: (0.0, 0.0),
            min_deg: None,
            last_max_t: None,
            pending: None,
            stride: None,
            recent: VecDeque::new(),
            ref_amp: FIRST_AMPLITUDE_DEG,
            open_period: None,
        }
    }

    /// Feeds one sample; returns a step when one is found (the second step of a stride comes
    /// with the next sample).
    pub fn push(&mut self, x: &DetectorInput) -> Option<Candidate> {
        let out = self.pending.take();
        let Some(p) = x.pitch_deg else {
            return out;
        };
        let h = self.cfg.hysteresis_deg;
        match self.phase {
            None => {
                // A bout starts by looking for a minimum: from a standing thigh (0°) the first
                // forward swing is then a maximum with the start as its minimum, whichever leg
                // moves first.
                self.phase = Some(Phase::Falling);
                self.ext = (x.t, p);
            }
            Some(Phase::Rising) => {
                if p > self.ext.1 {
                    self.ext = (x.t, p);
                } else if p < self.ext.1 - h {
                    let found = self.maximum(x.cadence_hz);
                    self.phase = Some(Phase::Falling);
                    self.ext = (x.t, p);
                    return out.or(found);
                }
            }
            Some(Phase::Falling) => {
                if let (Some(period), Some(last)) = (self.open_period, self.last_max_t) {
                    if x.t - last > STOP_PERIODS * period {
                        // The walk stopped after the pocket leg's footfall: the other foot
                        // closed half a stride later (or made the footfall whose maximum never
                        // came). The next maximum starts a new bout.
                        self.open_period = None;
                        self.last_max_t = None;
                        return out.or(Some(Candidate {
                            t: last + 0.5 * period,
                            period_s: 0.5 * period,
                            coherence: 1.0,
                        }));
                    }
                }
                if p < self.ext.1 {
                    self.ext = (x.t, p);
                } else if p > self.ext.1 + h {
                    self.min_deg = Some((self.ext.0, self.ext.1));
                    self.phase = Some(Phase::Rising);
                    self.ext = (x.t, p);
                }
            }
        }
        out
    }

    /// A maximum at `self.ext` is confirmed: the stride, and its steps.
    fn maximum(&mut self, cadence_hz: Option<f64>) -> Option<Candidate> {
        let (t_max, max_deg) = self.ext;
        let (t_min, min_deg) = self.min_deg?;
        let prev = self.last_max_t.replace(t_max);
        let period_s = prev
            .map(|l| t_max - l)
            .filter(|&p| p > 0.0 && p <= self.cfg.max_stride_s);
        let stride = PitchStride {
            t_max,
            max_deg,
            min_deg,
            t_min,
            amplitude_deg: max_deg - min_deg,
            period_s,
        };
        self.stride = Some(stride);
        if self.recent.len() == RECENT_STRIDES {
            self.recent.pop_front();
        }
        self.recent.push_back(stride);
        let step = |t: f64, period_s: f64| Candidate {
            t,
            period_s,
            coherence: 1.0,
        };
        let amplitude = max_deg - min_deg;
        match period_s {
            Some(p) => {
                self.ref_amp = amplitude;
                self.open_period = Some(p);
                let half = 0.5 * p;
                self.pending = Some(step(t_max, half));
                Some(step(t_max - half, half))
            }
            None => {
                let period = 1.0 / cadence_hz.unwrap_or(1.8);
                if amplitude >= FULL_RISE * self.ref_amp && t_max - t_min < 2.0 * period {
                    // A full stride's rise from standing: the thigh went back first, while the
                    // other foot took the walk's first step (at the thigh's extreme).
                    self.pending = Some(step(t_max, t_max - t_min));
                    Some(step(t_min, period))
                } else {
                    Some(step(t_max, period))
                }
            }
        }
    }

    /// The stride of the last maximum.
    pub fn last_stride(&self) -> Option<PitchStride> {
        self.stride
    }

    /// The strides whose maximum came after `t_max` (every one kept, `RECENT_STRIDES`, for
    /// `None`), oldest first.
    pub fn strides_after(&self, t_max: Option<f64>) -> impl Iterator<Item = &PitchStride> {
        self.recent
            .iter()
            .filter(move |s| t_max.map_or(true, |t| s.t_max > t))
    }

    /// Starts afresh (the onset look-back replays the samples since the gait began).
    pub fn restart(&mut self) {
        let ref_amp = self.ref_amp;
        *self = PitchDetector::new(self.cfg);
        self.ref_amp = ref_amp;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::motion::Motion;
    use std::f64::consts::TAU;

    fn input(t: f64, pitch: f64) -> DetectorInput {
        DetectorInput {
            t,
            dt: 0.01,
            up: 0.0,
            mean: 0.0,
            sigma: 1.0,
            motion: Motion::Walking,
            cadence_hz: Some(1.8),
            pitch_deg: Some(pitch),
            axis_tilt_sin: None,
            pocket: false,
        }
    }

    /// Fig. 2's shape: a maximum, a dip of 4° and a second peak at heel strike, then the
    /// minimum: one stride per cycle, two steps each but the first.
    #[test]
    fn one_stride_per_cycle_despite_the_heel_strike_peak() {
        let f = 0.9; // strides per second
        let mut d = PitchDetector::new(PitchDetectorConfig::default());
        let mut steps = Vec::new();
        let mut strides = 0;
        let mut last = None;
        for i in 0..1000 {
            let t = i as f64 * 0.01;
            let ph = TAU * f * t;
            let pitch = 7.0 + 18.0 * libm::cos(ph) + 4.0 * libm::cos(2.0 * ph - 0.6).max(0.0);
            if let Some(c) = d.push(&input(t, pitch)) {
                steps.push(c);
            }
            if d.last_stride() != last {
                last = d.last_stride();
                strides += 1;
            }
        }
        // 9 cycles over 10 s; the first maximum (t = 0) is not confirmed without a minimum
        // before it. The second rises a whole stride from its minimum: two steps, as every
        // later one.
        assert_eq!(strides, 8);
        assert_eq!(steps.len(), 2 * strides);
        let s = d.last_stride().unwrap();
        assert!(s.amplitude_deg > 30.0 && s.max_deg > 20.0 && s.min_deg < -5.0);
        // After the first stride (its first step is at the minimum), half a stride apart.
        for w in steps[1..].windows(2) {
            let dt = w[1].t - w[0].t;
            assert!((dt - 0.5 / f).abs() < 0.03, "steps {dt} s apart");
        }
    }

    #[test]
    fn without_pitch_no_steps() {
        let mut d = PitchDetector::new(PitchDetectorConfig::default());
        let mut x = input(0.0, 0.0);
        x.pitch_deg = None;
        for i in 0..500 {
            x.t = i as f64 * 0.01;
            assert!(d.push(&x).is_none());
        }
    }
}
