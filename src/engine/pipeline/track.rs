//! The track: the steps placed so far, the position they reached and their counts.
//! May import: the rest of `engine`.

use super::StepRecord;
use crate::engine::activity::Activity;
use crate::engine::foot::Stride;
use crate::engine::motion::Motion;

/// The share of a gait cycle spent in swing (about 40 %, Perry's gait analysis), giving the
/// stride frequency of the first stride of a walk from its swing alone.
const SWING_SHARE: f64 = 0.4;

/// What the track has counted.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct TrackCounts {
    /// Steps counted, with those a bout's opening still holds off the track (a stride counts
    /// two).
    pub steps: u64,
    /// Steps recovered by the onset look-back.
    pub onset_steps: u64,
    /// Steps placed without a heading (no displacement applied).
    pub steps_without_heading: u64,
    /// Distance walked, m.
    pub distance_m: f64,
    /// Strides placed.
    pub strides: u64,
}

/// The step records placed, in order, and the dead-reckoned position after the last.
#[derive(Debug, Clone, Default)]
pub(super) struct Track {
    pos: (f64, f64),
    steps: Vec<StepRecord>,
    counts: TrackCounts,
}

impl Track {
    /// Every step placed.
    pub(super) fn steps(&self) -> &[StepRecord] {
        &self.steps
    }

    /// How many steps are placed.
    pub(super) fn len(&self) -> usize {
        self.steps.len()
    }

    /// The counts.
    pub(super) fn counts(&self) -> TrackCounts {
        self.counts
    }

    /// A step counted, held or placed (the live count does not wait for a bout's opening).
    pub(super) fn count_step(&mut self) {
        self.counts.steps += 1;
    }

    /// A step the onset look-back recovered.
    pub(super) fn count_onset(&mut self) {
        self.counts.onset_steps += 1;
    }

    /// Places a step after the last, advanced along its heading by its length (Basso 2021
    /// eq. 24 with x north and y east); a step without a heading stays where the last ended.
    pub(super) fn place(&mut self, mut step: StepRecord) {
        match step.heading_rad {
            Some(h) => {
                let (sh, ch) = libm::sincos(h);
                self.pos.0 += step.length_m * sh;
                self.pos.1 += step.length_m * ch;
                self.counts.distance_m += step.length_m;
            }
            None => self.counts.steps_without_heading += 1,
        }
        (step.east_m, step.north_m) = self.pos;
        self.steps.push(step);
    }

    /// Places a stride's record where the foot's track put it; it counts as two steps.
    pub(super) fn place_stride(&mut self, step: StepRecord) {
        self.pos = (step.east_m, step.north_m);
        self.counts.steps += 2;
        self.counts.strides += 1;
        self.counts.distance_m += step.length_m;
        self.steps.push(step);
    }

    /// The steps so far, their counts and the position they reached, forgotten: strides (foot
    /// mode, or a second, foot-mounted sensor) take their place. The strides placed stay
    /// counted.
    pub(super) fn forget_steps(&mut self) {
        self.steps.clear();
        self.counts = TrackCounts {
            strides: self.counts.strides,
            ..TrackCounts::default()
        };
        self.pos = (0.0, 0.0);
    }
}

/// The step record of a stride that ends at foot flat, placed at `(east_m, north_m)` with
/// `heading_rad` (foot mode's own, or the hybrid's); `prev_t` is the previous stride's foot
/// flat.
pub(super) fn stride_record(
    st: &Stride,
    prev_t: Option<f64>,
    (east_m, north_m): (f64, f64),
    heading_rad: f64,
) -> StepRecord {
    let period = prev_t
        .map(|l| st.t_end - l)
        .filter(|&p| p > 0.0 && p <= 3.0)
        .unwrap_or((st.t_end - st.t_start) / SWING_SHARE);
    StepRecord {
        t: st.t_end,
        east_m,
        north_m,
        heading_rad: Some(heading_rad),
        step_heading_rad: Some(st.heading_rad),
        length_m: st.length_m,
        freq_hz: if period > 0.0 { 1.0 / period } else { 0.0 },
        motion: Motion::Walking,
        activity: Activity::Walking,
        up_m: 0.0,
        floor: 0,
        pitch_amplitude_deg: None,
        carry: None,
        gyro_heading: false,
    }
}
