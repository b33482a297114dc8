//! The walker's script: what they do ([`Gait`]), for how long, at which cadence and turning how
//! far ([`Segment`]), and the stairs they climb ([`Stair`]).
//! May import: `engine` and `io`.

use super::Walker;

/// What the walker does during a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Gait {
    /// Phone still in the pocket of a standing person.
    Still,
    /// Phone slowly handled (turned and moved by hand), below the motion threshold.
    Handled,
    /// Walking.
    Walk,
    /// Running.
    Run,
    /// Walking up a flight of stairs ([`Segment::stair`] gives riser and tread).
    StairsUp,
    /// Walking down a flight of stairs.
    StairsDown,
    /// Sitting: sits down over the first [`super::GaitThigh::transition_s`], stands up over the last.
    Sit,
    /// Standing, taking the phone out of the pocket into the texting hold (with
    /// [`super::Scenario::real_ends`] and [`super::Carry::Pocket`]; otherwise still). See
    /// [`super::ends`].
    TakeOut,
}

impl Gait {
    pub(super) fn moving(self) -> bool {
        matches!(
            self,
            Gait::Walk | Gait::Run | Gait::StairsUp | Gait::StairsDown
        )
    }
}

/// The steps of a flight of stairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stair {
    /// Height of a step, m.
    pub riser_m: f64,
    /// Depth of a step, m.
    pub tread_m: f64,
}

/// One piece of the script.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// What the walker does.
    pub gait: Gait,
    /// Duration, s.
    pub duration_s: f64,
    /// Cadence at the start and at the end of the segment (linear ramp), Hz. Ignored when still.
    pub cadence_hz: (f64, f64),
    /// Total heading change over the segment, degrees, clockwise positive.
    pub turn_deg: f64,
    /// The stairs' riser and tread (stairs segments only).
    pub stair: Option<Stair>,
}

impl Segment {
    /// Standing still for `s` seconds.
    pub fn still(s: f64) -> Self {
        Segment {
            gait: Gait::Still,
            duration_s: s,
            cadence_hz: (0.0, 0.0),
            turn_deg: 0.0,
            stair: None,
        }
    }

    /// Sitting for `s` seconds, sitting down and standing up included.
    pub fn sit(s: f64) -> Self {
        Segment {
            gait: Gait::Sit,
            ..Segment::still(s)
        }
    }

    /// Walking `n` steps (may be fractional) at cadence `f`.
    pub fn walk_steps(n: f64, f: f64) -> Self {
        Segment::walk(n / f, f)
    }

    /// `n` steps up a flight of stairs at cadence `f`: each footfall one `riser_m` up and one
    /// `tread_m` forward.
    pub fn stairs_up(n: usize, f: f64, riser_m: f64, tread_m: f64) -> Self {
        Segment {
            gait: Gait::StairsUp,
            stair: Some(Stair { riser_m, tread_m }),
            ..Segment::walk(n as f64 / f, f)
        }
    }

    /// `n` steps down a flight of stairs at cadence `f`.
    pub fn stairs_down(n: usize, f: f64, riser_m: f64, tread_m: f64) -> Self {
        Segment {
            gait: Gait::StairsDown,
            ..Segment::stairs_up(n, f, riser_m, tread_m)
        }
    }

    /// Taking the phone out of the pocket over `s` seconds, standing ([`Gait::TakeOut`]).
    pub fn take_out(s: f64) -> Self {
        Segment {
            gait: Gait::TakeOut,
            ..Segment::still(s)
        }
    }

    /// Handling the phone for `s` seconds.
    pub fn handled(s: f64) -> Self {
        Segment {
            gait: Gait::Handled,
            ..Segment::still(s)
        }
    }

    /// Walking for `s` seconds at cadence `f` Hz.
    pub fn walk(s: f64, f: f64) -> Self {
        Segment {
            gait: Gait::Walk,
            duration_s: s,
            cadence_hz: (f, f),
            turn_deg: 0.0,
            stair: None,
        }
    }

    /// Running for `s` seconds at cadence `f` Hz.
    pub fn run(s: f64, f: f64) -> Self {
        Segment {
            gait: Gait::Run,
            ..Segment::walk(s, f)
        }
    }

    /// Walking `metres` at cadence `f` with the walker's step-length law.
    pub fn walk_distance(metres: f64, f: f64, walker: &Walker) -> Self {
        Segment::walk(metres / (walker.step_length.length(f) * f), f)
    }

    /// The same segment turning by `deg` over its duration.
    pub fn turning(self, deg: f64) -> Self {
        Segment {
            turn_deg: deg,
            ..self
        }
    }

    /// The same segment with the cadence ramping to `f_end`.
    pub fn ramp_to(self, f_end: f64) -> Self {
        Segment {
            cadence_hz: (self.cadence_hz.0, f_end),
            ..self
        }
    }
}
