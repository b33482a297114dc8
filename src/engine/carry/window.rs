//! The carrying-mode detector's window: its slots, and the sums its features are made of, kept
//! as running sums. May import: the rest of `engine`.
//!
//! A slot adds its terms as it enters the window and takes them out as it leaves, so an
//! evaluation reads the sums instead of going over the window again. The lagged products of
//! the vertical acceleration, S(k) = Σ up\[i\]·up\[i + k\] over the window's pairs, cost two
//! multiply-adds per lag per slot this way; summed afresh at each evaluation they cost a
//! window's length per lag. Every [`RESUM_SLOTS`] slots that left, the sums are summed afresh
//! so that rounding in them cannot accumulate.

use crate::engine::math::{from_outer_entries, outer_entries};
use nalgebra::{Matrix3, Vector3};
use std::ops::RangeInclusive;

/// The running sums are summed afresh after this many slots have left the window (20 s of
/// 20 ms slots).
const RESUM_SLOTS: u32 = 1024;

/// Slots that have left are dropped from the front of the buffers once there are this many
/// (and at least as many as are still in the window): a move of the window's slots, rarely.
const DROP_AT: usize = 256;

/// A slot being filled: sums of its samples.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Slot {
    pub t0: f64,
    pub n: f64,
    pub up: f64,
    pub a: Vector3<f64>,
    pub w: Vector3<f64>,
    pub nw: f64,
}

/// A complete slot in the window: its means, taken once when it closes.
#[derive(Debug, Clone, Copy)]
pub(super) struct Closed {
    pub t0: f64,
    /// Mean specific force, m/s².
    pub a: Vector3<f64>,
}

impl Closed {
    /// The slot's means, its terms of the window's sums, and its mean vertical acceleration in
    /// the navigation frame, m/s².
    fn of(s: &Slot) -> (Self, Sums, f64) {
        let a = s.a / s.n;
        let dir = a / a.norm().max(1e-9);
        let mut t = [0.0; TERMS];
        t[..3].copy_from_slice(a.as_slice());
        t[3..9].copy_from_slice(&outer_entries(&a));
        t[9..12].copy_from_slice(dir.as_slice());
        if s.nw > 0.0 {
            let w = s.w / s.nw;
            t[12] = 1.0;
            t[13..16].copy_from_slice(w.as_slice());
            t[16..22].copy_from_slice(&outer_entries(&w));
        }
        (Closed { t0: s.t0, a }, Sums(t), s.up / s.n)
    }
}

/// How many sums [`Sums`] holds.
const TERMS: usize = 22;

/// Sums over the window's slots: Σ a (m/s²), Σ a aᵀ (m²/s⁴), Σ a/|a|, and over the slots with
/// a rate their number, Σ ω (rad/s) and Σ ω ωᵀ (rad²/s²), side by side.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Sums([f64; TERMS]);

impl Sums {
    /// Σ a, m/s².
    pub fn a(&self) -> Vector3<f64> {
        Vector3::new(self.0[0], self.0[1], self.0[2])
    }

    /// Σ a aᵀ, m²/s⁴.
    pub fn aa(&self) -> Matrix3<f64> {
        from_outer_entries(&std::array::from_fn(|i| self.0[3 + i]))
    }

    /// Σ |a|², m²/s⁴.
    pub fn aa_trace(&self) -> f64 {
        self.0[3] + self.0[4] + self.0[5]
    }

    /// Σ a/|a|.
    pub fn dir(&self) -> Vector3<f64> {
        Vector3::new(self.0[9], self.0[10], self.0[11])
    }

    /// The slots with a rate: how many, Σ ω (rad/s) and Σ |ω|² (rad²/s²).
    pub fn rate(&self) -> (f64, Vector3<f64>, f64) {
        let s = &self.0;
        (
            s[12],
            Vector3::new(s[13], s[14], s[15]),
            s[16] + s[17] + s[18],
        )
    }

    /// Σ ω ωᵀ over the slots with a rate, rad²/s².
    pub fn ww(&self) -> Matrix3<f64> {
        from_outer_entries(&std::array::from_fn(|i| self.0[16 + i]))
    }

    /// Adds a slot's terms.
    fn add(&mut self, x: &Sums) {
        for i in 0..TERMS {
            self.0[i] += x.0[i];
        }
    }

    /// Takes a slot's terms out.
    fn sub(&mut self, x: &Sums) {
        for i in 0..TERMS {
            self.0[i] -= x.0[i];
        }
    }
}

/// The closed slots of the last window, oldest first, with their running sums.
#[derive(Debug, Clone)]
pub(super) struct Window {
    // The window is `slots[first..]`, `terms[first..]` (each slot's terms of the sums) and
    // `up[first..]` (each slot's mean vertical acceleration, m/s²): a slot leaves by a step of
    // `first`, so the window is always one slice.
    slots: Vec<Closed>,
    terms: Vec<Sums>,
    up: Vec<f64>,
    first: usize,
    sums: Sums,
    // S(k) for k = 0 ..= the largest lag; those below the smallest lag but 0 are not kept
    // (they stay 0).
    lags: Vec<f64>,
    min_lag: usize,
    // The last `lags.len()` values of `up`, newest first, as a mirrored ring: each is written
    // at `pos` and `pos + lags.len()`, so `recent[pos..pos + lags.len()]` is the newest first.
    recent: Vec<f64>,
    pos: usize,
    left: u32,
    // Prefix sums of `up` over the window, made by [`Window::centre`].
    prefix: Vec<f64>,
}

impl Window {
    /// An empty window whose lagged products are kept for lag 0 and the lags in `lags`, slots.
    pub fn new(lags: RangeInclusive<usize>) -> Self {
        let len = lags.end() + 1;
        Window {
            slots: Vec::new(),
            terms: Vec::new(),
            up: Vec::new(),
            first: 0,
            sums: Sums::default(),
            lags: vec![0.0; len],
            min_lag: (*lags.start()).clamp(1, len),
            recent: vec![0.0; 2 * len],
            pos: 0,
            left: 0,
            prefix: Vec::new(),
        }
    }

    /// The slots in the window, oldest first.
    pub fn slots(&self) -> &[Closed] {
        &self.slots[self.first..]
    }

    /// The running sums.
    pub fn sums(&self) -> &Sums {
        &self.sums
    }

    /// Closes slot `s` into the window, and lets out the slots that start before `t_min`, s.
    pub fn push(&mut self, s: &Slot, t_min: f64) {
        let (c, terms, x) = Closed::of(s);
        self.slots.push(c);
        self.terms.push(terms);
        self.up.push(x);
        self.sums.add(&terms);
        let len = self.lags.len();
        self.pos = if self.pos == 0 { len - 1 } else { self.pos - 1 };
        self.recent[self.pos] = x;
        self.recent[self.pos + len] = x;
        // The newest first, as many as the window has: lag 0 is the slot itself.
        let n = (self.up.len() - self.first).min(len);
        let recent = &self.recent[self.pos..self.pos + n];
        let lo = self.min_lag.min(n);
        let leaves = |i: usize| self.slots.get(i).is_some_and(|f| f.t0 < t_min);
        if n > 1 && leaves(self.first) && !leaves(self.first + 1) {
            // One slot in, one out (the usual case): both in one pass over the lags.
            let up = &self.up[self.first..self.first + n];
            let x0 = up[0];
            self.lags[0] += x * x - x0 * x0;
            for ((s, &o), &u) in self.lags[lo..n]
                .iter_mut()
                .zip(&recent[lo..])
                .zip(&up[lo..])
            {
                *s += x * o - x0 * u;
            }
            self.sums.sub(&self.terms[self.first]);
            self.first += 1;
            self.left += 1;
        } else {
            self.lags[0] += x * x;
            for (s, &o) in self.lags[lo..n].iter_mut().zip(&recent[lo..]) {
                *s += x * o;
            }
        }
        while self.slots.get(self.first).is_some_and(|f| f.t0 < t_min) {
            let up = &self.up[self.first..];
            let (x, n) = (up[0], up.len().min(len));
            self.lags[0] -= x * x;
            let lo = self.min_lag.min(n);
            for (s, &o) in self.lags[lo..n].iter_mut().zip(&up[lo..n]) {
                *s -= x * o;
            }
            self.sums.sub(&self.terms[self.first]);
            self.first += 1;
            self.left += 1;
        }
        if self.first >= DROP_AT && 2 * self.first >= self.slots.len() {
            self.slots.drain(..self.first);
            self.terms.drain(..self.first);
            self.up.drain(..self.first);
            self.first = 0;
        }
        if self.left >= RESUM_SLOTS {
            self.resum();
        }
    }

    /// Sums every running sum afresh from the slots in the window.
    fn resum(&mut self) {
        self.left = 0;
        let mut sums = Sums::default();
        for x in &self.terms[self.first..] {
            sums.add(x);
        }
        self.sums = sums;
        let up = &self.up[self.first..];
        self.lags[0] = lag_sum(up, 0);
        for k in self.min_lag..self.lags.len() {
            self.lags[k] = lag_sum(up, k);
        }
    }

    /// Forgets every slot.
    pub fn clear(&mut self) {
        *self = Window::new(self.min_lag..=self.lags.len() - 1);
    }

    /// Prepares [`Window::centred_lag_sum`] and returns μ, the mean vertical acceleration over
    /// the window, m/s² (NaN when it is empty).
    pub fn centre(&mut self) -> f64 {
        self.prefix.clear();
        self.prefix.push(0.0);
        let mut total = 0.0;
        for &x in &self.up[self.first..] {
            total += x;
            self.prefix.push(total);
        }
        total / (self.up.len() - self.first) as f64
    }

    /// Σ v\[i\]·v\[i + k\] over the window's pairs, v = up − μ; for `k` 0 or one of the lags kept,
    /// S(k) − μ·(Σ up\[i\] over the first n − k + Σ up\[i\] over the last n − k) + (n − k)·μ².
    /// 0 without a pair. [`Window::centre`] gave μ, since the last slot came.
    pub fn centred_lag_sum(&self, k: usize, mu: f64) -> f64 {
        let n = self.up.len() - self.first;
        let Some(pairs) = n.checked_sub(k).filter(|&p| p > 0) else {
            return 0.0;
        };
        if k != 0 && !(self.min_lag..self.lags.len()).contains(&k) {
            // A lag not kept: summed over the window.
            let up = &self.up[self.first..];
            return (0..pairs).map(|i| (up[i] - mu) * (up[i + k] - mu)).sum();
        }
        let p = &self.prefix;
        let sides = p[pairs] + (p[n] - p[k]);
        self.lags[k] - mu * sides + pairs as f64 * mu * mu
    }
}

/// Σ v\[i\]·v\[i + k\] over the pairs the window has, summed in order of i (0 without a pair).
pub(super) fn lag_sum(v: &[f64], k: usize) -> f64 {
    (0..v.len().saturating_sub(k))
        .map(|i| v[i] * v[i + k])
        .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slot(i: usize) -> Slot {
        let t = i as f64 * 0.02;
        let x = libm::sin(t * 11.0) * 1.7 + libm::cos(t * 3.1) * 0.4 + 0.3;
        Slot {
            t0: t,
            n: 2.0,
            up: 2.0 * x,
            a: Vector3::new(x, 0.5 * x, 9.81 + x) * 2.0,
            w: Vector3::new(0.1, x, -x),
            nw: if i % 3 == 0 { 0.0 } else { 2.0 },
        }
    }

    #[test]
    fn the_running_sums_are_the_sums_over_the_window() {
        let mut w = Window::new(13..=88);
        for i in 0..3000 {
            let s = slot(i);
            w.push(&s, s.t0 - 3.0);
            if i % 97 != 0 && i != 2999 {
                continue;
            }
            let up: Vec<f64> = (0..=i)
                .map(slot)
                .filter(|x| x.t0 >= s.t0 - 3.0)
                .map(|x| x.up / x.n)
                .collect();
            assert_eq!(up.len(), w.slots().len(), "slot {i}");
            let mu = w.centre();
            let direct_mu = up.iter().sum::<f64>() / up.len() as f64;
            assert!((mu - direct_mu).abs() < 1e-12, "slot {i}");
            let v: Vec<f64> = up.iter().map(|x| x - mu).collect();
            for k in [0, 13, 14, 43, 86, 88] {
                let (run, direct) = (w.centred_lag_sum(k, mu), lag_sum(&v, k));
                assert!(
                    (run - direct).abs() < 1e-9 * (1.0 + direct.abs()),
                    "slot {i} lag {k}"
                );
            }
            let direct: Vector3<f64> = w.slots().iter().map(|c| c.a.normalize()).sum();
            assert!((w.sums().dir() - direct).norm() < 1e-9, "slot {i}");
            let direct: f64 = w.slots().iter().map(|c| c.a.norm_squared()).sum();
            assert!(
                (w.sums().aa_trace() - direct).abs() < 1e-9 * direct,
                "slot {i}"
            );
        }
    }

    #[test]
    fn a_lag_past_the_window_sums_nothing() {
        let mut w = Window::new(13..=88);
        for i in 0..10 {
            w.push(&slot(i), f64::NEG_INFINITY);
        }
        let mu = w.centre();
        assert_eq!(w.centred_lag_sum(10, mu), 0.0);
        assert_eq!(w.centred_lag_sum(88, mu), 0.0);
        let v: Vec<f64> = (0..10).map(|i| slot(i).up / 2.0 - mu).collect();
        for k in [1, 5, 9] {
            assert!(
                (w.centred_lag_sum(k, mu) - lag_sum(&v, k)).abs() < 1e-12,
                "lag {k}"
            );
        }
        w.clear();
        assert!(w.slots().is_empty() && w.centre().is_nan());
    }
}
