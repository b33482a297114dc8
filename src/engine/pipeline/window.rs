//! The recent samples in the navigation frame, which the heading, the step length and the
//! onset look-back read. May import: the rest of `engine`.

use crate::engine::heading::NavSample;
use std::collections::VecDeque;

/// The samples of the last `history_s` seconds, the latest last.
#[derive(Debug, Clone)]
pub(super) struct Window {
    pub buf: VecDeque<NavSample>,
    history_s: f64,
}

impl Window {
    /// A window reaching `history_s` back, s.
    pub(super) fn new(history_s: f64) -> Self {
        Window {
            buf: VecDeque::new(),
            history_s,
        }
    }

    /// Adds the latest sample and drops those older than the history.
    pub(super) fn push(&mut self, x: NavSample) {
        let t = x.t;
        self.buf.push_back(x);
        while self.buf.front().is_some_and(|f| f.t < t - self.history_s) {
            self.buf.pop_front();
        }
    }

    /// Forgets every sample (after a gap).
    pub(super) fn clear(&mut self) {
        self.buf.clear();
    }

    /// The latest sample.
    pub(super) fn last(&self) -> Option<&NavSample> {
        self.buf.back()
    }
}
