//! The step's heading in a turn (ours): the acceleration heading is the direction of
//! its window, which lies behind the step it is walked along; the gyroscope's turn over that lag
//! is added.
//! May import: the rest of `engine`.
//!
//! The track walks step k from the footfall t_{k−1} to t_k, so its direction is the path's
//! heading at the middle of the step, (t_{k−1} + t_k)/2. Each method's direction is the mean of
//! its window ([`window`]): the stride (t_{k−2}, t_k) for tip-to-tail, centred a whole step
//! earlier, at t_{k−1}; the step itself for the closed form; the last 2 s for PCA. The two-step
//! average (A-HE) takes the mean of two windows a step apart, half a step further back. In a turn
//! of r per step, tip-to-tail's averaged heading so lags the step by one step of turning: on the
//! simulator's 90° turns over 8 steps, 11°, and the track cuts every corner by about a step
//! length times the angle turned (0.7 m × π/2 ≈ 1.1 m per right angle), whatever the turn's
//! rate.
//!
//! The device's yaw ψ (the attitude's turn about the vertical, integrated sample by sample:
//! [`NavSample::yaw`]) turns with the walker wherever the phone rides. The lead is ψ at the
//! middle of the step less ψ at the centres of the windows averaged, each ψ the mean over the
//! stride around its time ([`around`]). Whole strides, because the thigh and the pelvis yaw back
//! and forth once a stride (the simulated thigh by ±6°): over a stride that cancels, over a step
//! it does not, and a step's mean would add a left–right alternation the two-step average no
//! longer cancels. The stride around the step's middle ends half a period after the step, which
//! is when the step detector judges it, so no extrapolation is needed.
//!
//! Where it adds nothing:
//! - **The first [`FIRST_LEAD_STEP`] steps of a bout**: the strides around their windows reach
//!   into the standing before the walk, whose yaw the acceleration does not weigh. Without this,
//!   the simulated walk's start (whose attitude jumps when the thigh starts to swing) made live
//!   events and the log part by 6–9 cm instead of 5 mm (`tests/live.rs`).
//! - **A phone moving in the body** turns ψ without the walker: the lead needs gravity's mean
//!   direction in the device over the strides compared within [`STEADY_DEG`].
//! - **The device's own yaw** (the hand, the reading pose) is taken at the instant the step is
//!   judged and is not led: on the real hand-held walks, taking it back to the step's middle
//!   made every figure worse (docs/methods/turns.md).
//! - A walker who turns on the spot between two bouts: the first steps take the new direction
//!   from their own windows.

use super::{HeadingConfig, HeadingMethod, NavSample, StepWindow};
use std::collections::VecDeque;

/// The window whose direction `method` gives at the step `w`, (start, end), s.
pub fn window(cfg: &HeadingConfig, w: StepWindow) -> (f64, f64) {
    match cfg.method {
        HeadingMethod::TipToTail2016 => (w.t_km2, w.t_k),
        HeadingMethod::ClosedForm2021 => (w.t_km1, w.t_k),
        HeadingMethod::Pca => (w.t_k - cfg.pca_window_s, w.t_k),
    }
}

/// The trapezoidal mean over (t0, t1) of `channel`; `None` when the buffer does not span the
/// window.
pub(super) fn mean_over<const N: usize>(
    buf: &VecDeque<NavSample>,
    t0: f64,
    t1: f64,
    channel: impl Fn(&NavSample) -> [f64; N],
) -> Option<[f64; N]> {
    if !(t1 > t0) || buf.front()?.t > t0 || buf.back()?.t < t1 {
        return None;
    }
    let start = buf.partition_point(|s| s.t <= t0);
    let end = buf.partition_point(|s| s.t < t1);
    if start == 0 || end >= buf.len() || end < start {
        return None;
    }
    let at = |a: &NavSample, b: &NavSample, t: f64| {
        let w = if b.t > a.t {
            (t - a.t) / (b.t - a.t)
        } else {
            0.0
        };
        let (x, y) = (channel(a), channel(b));
        std::array::from_fn(|i| x[i] + w * (y[i] - x[i]))
    };
    let first = (t0, at(&buf[start - 1], &buf[start], t0));
    let last = (t1, at(&buf[end - 1], &buf[end], t1));
    let mut sum = [0.0; N];
    let mut prev = first;
    for run in super::runs(buf, start, end) {
        for s in run {
            let p = (s.t, channel(s));
            add_trapezoid(&mut sum, &prev, &p);
            prev = p;
        }
    }
    add_trapezoid(&mut sum, &prev, &last);
    Some(sum.map(|v| v / (t1 - t0)))
}

/// Adds the trapezoid from the point `a` to the point `b` (time, channels) to `sum`.
#[inline]
fn add_trapezoid<const N: usize>(sum: &mut [f64; N], a: &(f64, [f64; N]), b: &(f64, [f64; N])) {
    let dt = b.0 - a.0;
    for ((s, y), x) in sum.iter_mut().zip(b.1).zip(a.1) {
        *s += 0.5 * (y + x) * dt;
    }
}

/// The device over the stride around a time: its yaw, and where gravity sits in it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stride {
    /// The mean yaw, compass radians ([`NavSample::yaw`]).
    pub yaw: f64,
    /// The mean of up in the device frame ([`NavSample::device_up`]).
    pub up: nalgebra::Vector3<f64>,
}

impl Stride {
    /// Whether the phone sat the same way in the body over both strides: gravity's mean
    /// direction in the device within [`STEADY_DEG`].
    fn steady_with(&self, other: &Stride) -> bool {
        let n = self.up.norm() * other.up.norm();
        n > 0.0 && self.up.dot(&other.up) >= n * libm::cos(STEADY_DEG.to_radians())
    }
}

/// The largest turn of gravity in the device between the strides a lead compares, degrees: a
/// phone being moved in the body turns about the vertical without the walker. Moves between
/// carrying modes turn it by tens of degrees over the strides a lead compares, steady walking
/// (even a loose hold in the hand) by a few; a tighter limit costs the hand-held walks much of
/// the lead's gain.
pub const STEADY_DEG: f64 = 10.0;

/// The device over the stride around `c`, (c − T, c + T) for the step period T: the thigh's and
/// the pelvis's back and forth cancel over a stride. `None` when the buffer does not span it.
pub fn around(buf: &VecDeque<NavSample>, c: f64, period: f64) -> Option<Stride> {
    stride(buf, c - period, c + period)
}

fn stride(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> Option<Stride> {
    mean_over(buf, t0, t1, |s| {
        let u = s.device_up;
        [s.yaw, u[0], u[1], u[2]]
    })
    .map(|[yaw, x, y, z]| Stride {
        yaw,
        up: nalgebra::Vector3::new(x, y, z),
    })
}

/// The device at the middle of the step `w` ([`around`]). The step is judged about half a
/// period after its end, so the buffer nearly reaches the stride around its middle; when it
/// falls short, the last stride the buffer holds stands in, if it is centred within a quarter
/// period of the middle.
pub fn at_step(buf: &VecDeque<NavSample>, w: StepWindow) -> Option<Stride> {
    let period = w.t_k - w.t_km1;
    let mid = 0.5 * (w.t_km1 + w.t_k);
    around(buf, mid, period).or_else(|| {
        let end = buf.back()?.t;
        if end >= mid + 0.75 * period {
            stride(buf, end - 2.0 * period, end)
        } else {
            None
        }
    })
}

/// Steps of a bout before its first lead: the strides around the last two windows' centres
/// then lie after the bout's first step began, not over the standing before it, whose yaw the
/// windows' acceleration does not weigh (a phone still has none).
pub const FIRST_LEAD_STEP: u32 = 3;

/// The lead of the step's heading over its windows' (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TurnLead {
    // The device around the centre of the last step's heading window.
    last: Option<Stride>,
    // Steps since the bout's first.
    run: u32,
}

impl TurnLead {
    /// The turn, rad (compass: clockwise positive), to add to the step `w`'s heading, whose
    /// window is `win` and which was averaged with the last step's (`averaged`): the yaw at the
    /// middle of the step less the yaw around the windows' centres. 0 for the first
    /// [`FIRST_LEAD_STEP`] steps of a bout (a step that does not continue the last begins one),
    /// where the yaw is not known over the strides, and where gravity turned in the device
    /// between them by more than [`STEADY_DEG`].
    pub fn push(
        &mut self,
        buf: &VecDeque<NavSample>,
        w: StepWindow,
        win: (f64, f64),
        continued: bool,
        averaged: bool,
    ) -> f64 {
        self.run = if continued {
            self.run.saturating_add(1)
        } else {
            0
        };
        let here = around(buf, 0.5 * (win.0 + win.1), w.t_k - w.t_km1);
        let last = std::mem::replace(&mut self.last, here);
        if self.run < FIRST_LEAD_STEP {
            return 0.0;
        }
        let (Some(at), Some(here)) = (at_step(buf, w), here) else {
            return 0.0;
        };
        let from = match (averaged, last) {
            (false, _) => [here, here],
            (true, Some(last)) => [here, last],
            (true, None) => return 0.0,
        };
        if !from.iter().all(|f| at.steady_with(f)) {
            return 0.0;
        }
        let lead = at.yaw - 0.5 * (from[0].yaw + from[1].yaw);
        // Never a NaN into the heading: without a finite yaw there is no lead.
        if lead.is_finite() {
            lead
        } else {
            0.0
        }
    }

    /// Forgets the last step (a stop or a gap).
    pub fn clear(&mut self) {
        *self = TurnLead::default();
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    /// A walker turning at `rate` rad/s from t = 0, sampled at 100 Hz, yaw only.
    fn turning(rate: f64, sway: f64, stride_s: f64) -> VecDeque<NavSample> {
        (0..1000)
            .map(|i| {
                let t = i as f64 * 0.01;
                NavSample {
                    yaw: rate * t + sway * (std::f64::consts::TAU * t / stride_s).sin(),
                    device_up: [0.0, 0.0, 1.0],
                    ..NavSample::empty(t)
                }
            })
            .collect()
    }

    #[test]
    fn the_yaw_around_a_time_in_a_steady_turn_is_its_value_then() {
        let buf = turning(0.3, 0.0, 1.0);
        let (c, period) = (2.669, 0.664);
        let m = around(&buf, c, period).unwrap();
        assert!((m.yaw - 0.3 * c).abs() < 1e-9, "{m:?}");
        assert_eq!(m.up, nalgebra::Vector3::z());
        assert_eq!(around(&buf, 0.5, 1.0), None);
        assert_eq!(around(&buf, 9.5, 1.0), None);
    }

    #[test]
    fn tip_to_tail_averaged_leads_one_step_of_turning_and_a_sway_adds_nothing() {
        let step = 0.6;
        let cfg = HeadingConfig::default();
        for sway in [0.0, 0.1] {
            let buf = turning(0.2, sway, 2.0 * step);
            let mut lead = TurnLead::default();
            let mut got = Vec::new();
            for k in 2..12 {
                let t_k = k as f64 * step;
                let w = StepWindow {
                    t_km2: t_k - 2.0 * step,
                    t_km1: t_k - step,
                    t_k,
                };
                got.push(lead.push(&buf, w, window(&cfg, w), k > 2, true));
            }
            // The bout's first steps lead nothing; from the fourth on, one step of turning.
            assert!(got[..3].iter().all(|g| *g == 0.0), "{got:?}");
            for g in &got[3..] {
                assert!((g - 0.2 * step).abs() < 1e-9, "sway {sway}: {got:?}");
            }
        }
    }

    #[test]
    fn a_bout_leads_from_its_fourth_step_and_a_break_or_a_stop_starts_a_bout() {
        let buf = turning(0.2, 0.0, 1.2);
        let cfg = HeadingConfig::default();
        let mut lead = TurnLead::default();
        let at = |lead: &mut TurnLead, t_k: f64, continued: bool| {
            let w = StepWindow {
                t_km2: t_k - 1.2,
                t_km1: t_k - 0.6,
                t_k,
            };
            lead.push(&buf, w, window(&cfg, w), continued, true) != 0.0
        };
        let leads: Vec<bool> = [
            (2.4, false),
            (3.0, true),
            (3.6, true),
            (4.2, true),
            (4.8, false),
        ]
        .iter()
        .chain(&[(5.4, true), (6.0, true), (6.6, true)])
        .map(|&(t, c)| at(&mut lead, t, c))
        .collect();
        assert_eq!(
            leads,
            [false, false, false, true, false, false, false, true]
        );
        lead.clear();
        assert!(!at(&mut lead, 7.2, true));
    }

    #[test]
    fn a_wrapped_buffer_gives_the_same_bits_as_a_contiguous_one() {
        let sample = |i: usize| {
            let t = i as f64 * 0.0101 + 1e-4 * libm::sin(i as f64);
            NavSample {
                e: libm::sin(7.0 * t),
                n: libm::cos(5.0 * t) + 0.1,
                up: libm::sin(11.0 * t + 0.3),
                yaw: 0.2 * t,
                device_up: [libm::sin(t), 0.3, libm::cos(t)],
                ..NavSample::empty(t)
            }
        };
        // A ring buffer whose samples wrap around its end, and the same samples in one run.
        let mut wrapped = VecDeque::with_capacity(256);
        for i in 0..200 {
            wrapped.push_back(sample(i));
        }
        for i in 200..300 {
            wrapped.pop_front();
            wrapped.push_back(sample(i));
        }
        assert!(!wrapped.as_slices().1.is_empty());
        let mut flat = wrapped.clone();
        flat.make_contiguous();
        assert!(flat.as_slices().1.is_empty());
        for (t0, t1) in [(1.2, 2.3), (1.05, 1.9), (2.2, 2.9), (1.7, 2.05)] {
            let f = super::super::fourier(&wrapped, t0, t1).unwrap();
            assert_eq!(f, super::super::fourier(&flat, t0, t1).unwrap());
            let (a, b) = (
                stride(&wrapped, t0, t1).unwrap(),
                stride(&flat, t0, t1).unwrap(),
            );
            assert_eq!((a.yaw.to_bits(), a.up), (b.yaw.to_bits(), b.up));
            let (start, end) = (40, 120);
            let runs: Vec<NavSample> = super::super::runs(&wrapped, start, end).concat();
            assert_eq!(runs, wrapped.range(start..end).copied().collect::<Vec<_>>());
        }
    }
}
