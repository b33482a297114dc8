//! The recent samples in the navigation frame, which the heading, the step length and the
//! onset look-back read. May import: the rest of `engine`.

use crate::engine::heading::NavSample;
use std::collections::VecDeque;

/// The samples of the last `history_s` seconds, the latest last.
#[derive(Debug, Clone)]
pub(super) struct Window {
    pub buf: VecDeque<NavSample>,
    /// The motion detector's σ_z when each sample of `buf` came, m/s²: in a pocket the onset
    /// look-back never judges a sample more leniently than the live loop did.
    pub sigma_z: VecDeque<f64>,
    history_s: f64,
}

impl Window {
    /// A window reaching `history_s` back, s.
    pub(super) fn new(history_s: f64) -> Self {
        Window {
            buf: VecDeque::new(),
            sigma_z: VecDeque::new(),
            history_s,
        }
    }

    /// Adds the latest sample, with the motion detector's σ_z then (m/s²), and drops those
    /// older than the history.
    pub(super) fn push(&mut self, x: NavSample, sigma_z: f64) {
        let t = x.t;
        self.buf.push_back(x);
        self.sigma_z.push_back(sigma_z);
        while self.buf.front().is_some_and(|f| f.t < t - self.history_s) {
            self.buf.pop_front();
            self.sigma_z.pop_front();
        }
    }

    /// Forgets every sample (after a gap).
    pub(super) fn clear(&mut self) {
        self.buf.clear();
        self.sigma_z.clear();
    }

    /// The latest sample.
    pub(super) fn last(&self) -> Option<&NavSample> {
        self.buf.back()
    }
}
