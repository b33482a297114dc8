//! The stage clock: where the time of a sample goes, stage by stage, for `pdr bench`.
//! May import: the rest of `engine`.
//!
//! Off by default: the pipeline then only tests, once per stage call, that it has none, so
//! nobody pays for the timing who does not ask for it; a WebAssembly build (the phone's) has
//! not even the tests. The engine has no clock of its own (a
//! WebAssembly build has none in `std`): the caller hands it one, a function that reads a
//! monotonic time in nanoseconds. Each stage call costs two readings when it is on. Once a
//! sample the clock also times nothing at all, in the same place and the same state of the
//! caches as the stages: [`StageClock::own_ns`], what each stage's time holds of the clock
//! itself, for the caller to subtract ([`StageClock::laps`] says how many times).

/// A stage of the pipeline's work on one IMU sample, in the order it runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// The sample's check (finite values, time order, the fields the orientation needs).
    Check,
    /// The orientation source: the attitude and the acceleration in the navigation frame.
    Orientation,
    /// The magnetic guard ([`crate::engine::magnetic`]).
    Magnetic,
    /// The attitude's histories for the heading and the trunk.
    Attitude,
    /// The motion detector (σ_z and the periodicity).
    Motion,
    /// The handling detector ([`crate::engine::handling`]).
    Handling,
    /// The carrying-mode detector ([`crate::engine::carry`]).
    Carry,
    /// The leg pitch, the pitch detector's input, the activity and the height.
    LegPitch,
    /// The heading window's sample.
    Window,
    /// The step detector (the PLL by default).
    StepDetector,
    /// Each step's emission: heading, length, position.
    Emission,
    /// The foot mode's recogniser and, on a foot, its strides.
    Foot,
}

impl Stage {
    /// Every stage, in the order a sample goes through them.
    pub const ALL: [Stage; 12] = [
        Stage::Check,
        Stage::Orientation,
        Stage::Magnetic,
        Stage::Attitude,
        Stage::Motion,
        Stage::Handling,
        Stage::Carry,
        Stage::LegPitch,
        Stage::Window,
        Stage::StepDetector,
        Stage::Emission,
        Stage::Foot,
    ];

    /// A short name for a table.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Check => "the sample's check",
            Stage::Orientation => "orientation",
            Stage::Magnetic => "magnetic guard",
            Stage::Attitude => "attitude histories",
            Stage::Motion => "motion detector",
            Stage::Handling => "handling",
            Stage::Carry => "carrying mode",
            Stage::LegPitch => "leg pitch and pocket",
            Stage::Window => "heading window",
            Stage::StepDetector => "step detector",
            Stage::Emission => "steps' emission",
            Stage::Foot => "foot mode",
        }
    }
}

/// A monotonic time, ns.
pub type Now = fn() -> u64;

/// The time spent in each stage and the number of calls timed.
#[derive(Debug, Clone)]
pub struct StageClock {
    // A WebAssembly build times nothing (see the module notes).
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    now: Now,
    // Per stage, and last the clock's own empty laps.
    ns: [u64; Stage::ALL.len() + 1],
    laps: [u64; Stage::ALL.len() + 1],
}

/// The index of the clock's own empty laps.
const OWN: usize = Stage::ALL.len();

impl StageClock {
    /// A clock reading `now`, with nothing timed yet.
    pub fn new(now: Now) -> Self {
        StageClock {
            now,
            ns: [0; Stage::ALL.len() + 1],
            laps: [0; Stage::ALL.len() + 1],
        }
    }

    /// The time now, ns.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    pub(super) fn read(&self) -> u64 {
        (self.now)()
    }

    /// Adds the time since `start` (ns, from [`Self::read`]) to `stage`.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    pub(super) fn lap(&mut self, stage: Stage, start: u64) {
        self.add(stage as usize, start);
    }

    /// Times an empty lap: the clock's own cost.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    pub(super) fn own_lap(&mut self) {
        let start = self.read();
        self.add(OWN, start);
    }

    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    fn add(&mut self, i: usize, start: u64) {
        let end = (self.now)();
        self.ns[i] += end.saturating_sub(start);
        self.laps[i] += 1;
    }

    /// Time spent in `stage` so far, ns, with the clock's own readings in it.
    pub fn ns(&self, stage: Stage) -> u64 {
        self.ns[stage as usize]
    }

    /// Calls of `stage` timed so far.
    pub fn laps(&self, stage: Stage) -> u64 {
        self.laps[stage as usize]
    }

    /// The mean time of an empty lap, ns: what each stage call's time holds of the clock.
    pub fn own_ns(&self) -> f64 {
        self.ns[OWN] as f64 / self.laps[OWN].max(1) as f64
    }
}
