//! The walker's slow motions over the script: walking bouts fading in and out, flights of stairs
//! (height, vertical acceleration, tread-paced speed), sitting down and standing up, and the
//! true activity over time.
//! May import: `engine` and `io`.
//!
//! # Model
//! Every blend uses the quintic smoothstep S(x) = 6x⁵ − 15x⁴ + 10x³ (x clamped to [0, 1]), so
//! positions are C², and accelerations continuous.
//! - **Bouts** (a run of moving segments): the realistic thigh's swing fades in over the first
//!   step and out over the last one, envelope S((t − t₀)/T)·S((t₁ − t)/T), T = one step.
//! - **Flights** (a stairs segment from t₀ to t₁ at cadence f, riser r, tread d): the weight
//!   W(t) = S((t − t₀)/T + ½) − S((t − t₁)/T + ½), T = 1/f, rises over the step centred on t₀
//!   and falls over the one centred on t₁, so ∫W dt = t₁ − t₀ exactly. The body climbs at
//!   ±r·f·W(t) (so by r per footfall; the height is the closed-form integral), the forward speed
//!   is (1 − W)·v_level + W·d·f (one tread per footfall), and the thigh's shape is blended with
//!   the same weight. A flight should lie between walking segments (landings).
//! - **Sitting** (a sit segment from t₀ to t₁, transitions of T): the sitting weight
//!   S((t − t₀)/T) − S((t − t₁)/T + 1) rises over the first T seconds and falls over the last
//!   T seconds; the thigh goes 0 → θ_sit → 0 and the hip drops and rises with it.

use super::{Gait, Segment};
use crate::engine::Activity;

/// Quintic smoothstep and its first two derivatives, and its integral from 0.
pub(super) fn s5(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (10.0 + x * (6.0 * x - 15.0))
}
pub(super) fn s5d(x: f64) -> f64 {
    if !(0.0..=1.0).contains(&x) {
        return 0.0;
    }
    30.0 * x * x * (1.0 - x) * (1.0 - x)
}
pub(super) fn s5dd(x: f64) -> f64 {
    if !(0.0..=1.0).contains(&x) {
        return 0.0;
    }
    60.0 * x * (1.0 - x) * (1.0 - 2.0 * x)
}
fn s5i(x: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x >= 1.0 {
        x - 0.5
    } else {
        x * x * x * x * (2.5 + x * (x - 3.0))
    }
}

/// One flight of stairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// Start and end of the segment, s (simulation time, without the clock offset).
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// Cadence, Hz.
    pub f: f64,
    /// Riser, m (positive).
    pub riser_m: f64,
    /// Tread, m.
    pub tread_m: f64,
    /// Whether it goes up.
    pub up: bool,
}

impl Flight {
    fn ramp(&self) -> f64 {
        1.0 / self.f
    }
    fn xs(&self, t: f64) -> (f64, f64) {
        let r = self.ramp();
        ((t - self.t0) / r + 0.5, (t - self.t1) / r + 0.5)
    }
    /// The flight's weight W(t) and its rate.
    pub fn weight(&self, t: f64) -> (f64, f64) {
        let (a, b) = self.xs(t);
        (s5(a) - s5(b), (s5d(a) - s5d(b)) / self.ramp())
    }
    fn climb_rate(&self) -> f64 {
        let v = self.riser_m * self.f;
        if self.up {
            v
        } else {
            -v
        }
    }
}

/// The script's slow motions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Body {
    /// (start, end, fade) of each walking bout, s.
    pub bouts: Vec<(f64, f64, f64)>,
    /// The flights of stairs.
    pub flights: Vec<Flight>,
    /// (start, end) of each sitting segment, s.
    pub sits: Vec<(f64, f64)>,
    /// (start, end) of each segment taking the phone out of the pocket, s.
    pub take_outs: Vec<(f64, f64)>,
    /// Duration of sitting down and of standing up, s.
    pub transition_s: f64,
    /// Hip drop when seated, m.
    pub sit_drop_m: f64,
    /// (start, end, activity) over the whole script, s.
    pub activities: Vec<(f64, f64, Activity)>,
}

impl Body {
    /// From the segments as walked.
    pub fn new(segments: &[Segment], transition_s: f64, sit_drop_m: f64) -> Self {
        let mut b = Body {
            transition_s,
            sit_drop_m,
            ..Body::default()
        };
        let mut t = 0.0;
        let mut bout: Option<(f64, f64)> = None;
        for s in segments {
            let (t0, t1) = (t, t + s.duration_s);
            let f = 0.5 * (s.cadence_hz.0 + s.cadence_hz.1);
            if s.gait.moving() {
                if bout.is_none() {
                    bout = Some((t0, if f > 0.0 { 1.0 / f } else { 0.5 }));
                }
                if let (Gait::StairsUp | Gait::StairsDown, Some(st)) = (s.gait, s.stair) {
                    b.flights.push(Flight {
                        t0,
                        t1,
                        f,
                        riser_m: st.riser_m,
                        tread_m: st.tread_m,
                        up: s.gait == Gait::StairsUp,
                    });
                }
            } else if let Some((a, fa)) = bout.take() {
                b.bouts.push((a, t0, fa));
            }
            let act = match s.gait {
                Gait::Still => Activity::Standing,
                Gait::Handled => Activity::Still,
                Gait::TakeOut => {
                    b.take_outs.push((t0, t1));
                    Activity::Still
                }
                Gait::Walk => Activity::Walking,
                Gait::Run => Activity::Running,
                Gait::StairsUp => Activity::Upstairs,
                Gait::StairsDown => Activity::Downstairs,
                Gait::Sit => {
                    // Seated from the middle of sitting down to the middle of standing up
                    // (where the thigh passes 45°).
                    let h = (0.5 * transition_s).min(0.25 * s.duration_s);
                    b.sits.push((t0, t1));
                    b.activities.push((t0, t0 + h, Activity::Standing));
                    b.activities.push((t0 + h, t1 - h, Activity::Sitting));
                    b.activities.push((t1 - h, t1, Activity::Standing));
                    t = t1;
                    continue;
                }
            };
            b.activities.push((t0, t1, act));
            t = t1;
        }
        if let Some((a, fa)) = bout {
            b.bouts.push((a, t, fa));
        }
        b
    }

    /// The walking bouts' envelope at `t` (0 outside bouts).
    pub fn walk_envelope(&self, t: f64) -> f64 {
        let i = self.bouts.partition_point(|b| b.0 <= t);
        match i.checked_sub(1).map(|k| self.bouts[k]) {
            Some((t0, t1, fade)) if t < t1 => s5((t - t0) / fade) * s5((t1 - t) / fade),
            _ => 0.0,
        }
    }

    /// The flights whose weight is not zero at `t`, with their weights.
    pub fn flights_at(&self, t: f64) -> impl Iterator<Item = (f64, &Flight)> + '_ {
        self.flights.iter().filter_map(move |fl| {
            let (w, _) = fl.weight(t);
            (w > 0.0).then_some((w, fl))
        })
    }

    /// Height of the ground under the walker relative to the start, m.
    pub fn height(&self, t: f64) -> f64 {
        self.flights
            .iter()
            .map(|fl| {
                let (a, b) = fl.xs(t);
                fl.climb_rate() * fl.ramp() * (s5i(a) - s5i(b))
            })
            .sum()
    }

    /// Height of the stair the walker stands on at `t`, m: one riser per footfall completed on
    /// each flight (footfalls at t₀ + k/f). The smooth [`Body::height`] meets it at every
    /// footfall but the first and the last of a flight, where its blend is 0.078 riser short.
    pub fn stair_height(&self, t: f64) -> f64 {
        self.flights
            .iter()
            .map(|fl| {
                let n = libm::round((fl.t1 - fl.t0) * fl.f);
                let k = libm::round((t - fl.t0) * fl.f).clamp(0.0, n);
                if fl.up {
                    k * fl.riser_m
                } else {
                    -k * fl.riser_m
                }
            })
            .sum()
    }

    /// Vertical acceleration of the body from the stairs, m/s².
    pub fn stairs_accel(&self, t: f64) -> f64 {
        self.flights
            .iter()
            .map(|fl| fl.climb_rate() * fl.weight(t).1)
            .sum()
    }

    /// Forward speed and its rate, from the level speed and its rate: on a flight one tread per
    /// footfall.
    pub fn speed(&self, t: f64, v_level: f64, dv_level: f64) -> (f64, f64) {
        let (mut v, mut dv) = (v_level, dv_level);
        for fl in &self.flights {
            let (w, wd) = fl.weight(t);
            if w > 0.0 || wd != 0.0 {
                let vs = fl.tread_m * fl.f;
                v += w * (vs - v_level);
                dv += -w * dv_level + wd * (vs - v_level);
            }
        }
        (v, dv)
    }

    /// The sitting weight (0 standing, 1 seated), its rate and its second derivative.
    pub fn sit(&self, t: f64) -> (f64, f64, f64) {
        let tr = self.transition_s;
        let mut out = (0.0, 0.0, 0.0);
        for &(t0, t1) in &self.sits {
            let tr = tr.min(0.5 * (t1 - t0));
            let (a, b) = ((t - t0) / tr, (t - t1) / tr + 1.0);
            out.0 += s5(a) - s5(b);
            out.1 += (s5d(a) - s5d(b)) / tr;
            out.2 += (s5dd(a) - s5dd(b)) / (tr * tr);
        }
        out
    }

    /// The phone's height above its standing height at the start, m: the ground's height less
    /// the hip's drop when seated.
    pub fn phone_height(&self, t: f64) -> f64 {
        self.height(t) - self.sit_drop_m * self.sit(t).0
    }

    /// The true activity at `t` (simulation time).
    pub fn activity_at(&self, t: f64) -> Activity {
        let i = self.activities.partition_point(|a| a.0 <= t);
        i.checked_sub(1)
            .map_or(Activity::Standing, |k| self.activities[k].2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothstep_integral_and_derivatives_agree() {
        let h = 1e-5;
        for i in 1..100 {
            let x = i as f64 / 100.0;
            assert!(((s5i(x + h) - s5i(x - h)) / (2.0 * h) - s5(x)).abs() < 1e-8);
            assert!(((s5(x + h) - s5(x - h)) / (2.0 * h) - s5d(x)).abs() < 1e-6);
            assert!(((s5d(x + h) - s5d(x - h)) / (2.0 * h) - s5dd(x)).abs() < 1e-5);
        }
        assert_eq!(s5i(1.0), 0.5);
    }
}
