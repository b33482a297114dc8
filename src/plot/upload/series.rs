//! What each diagnostics plot shows of an [`Analysis`] between two times, computed apart from
//! its drawing (`plots`): one plain data struct per plot, with its title, axes and note, in the
//! plot's time axis (s from the log's first sample). Testable without a drawing backend.
//! May import: `engine` (step records and activities), `analysis`; never `web`, `live` or
//! `eval`.

use super::decimate::{band, envelope, of, Column, GAP_S};
use super::fusion::FusionSeries;
use super::heading;
use super::height::HeightSeries;
use crate::analysis::{activity_from_code, Analysis};
use crate::engine::activity::Activity;
use crate::engine::carry::CarryMode;
use crate::engine::StepRecord;

/// The diagnostics plots, all against the same time axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plot {
    /// Vertical acceleration, PLL output, detected (and true) steps.
    Accel,
    /// σ of the vertical acceleration with the thresholds and the activity (a band, with its
    /// key).
    Sigma,
    /// Height above the start (m) and floor (Munoz Diaz 2015 §6, and the barometer).
    Height,
    /// Per-step heading: single-step, two-step average, and the device's heading.
    Heading,
    /// Step frequency and step length per step.
    Steps,
    /// GNSS accuracy and the innovations of the fixes offered to the filter.
    Gnss,
    /// The fusion's estimated step-length scale and heading correction (Basso 2021 §2.2.5's
    /// systematic errors) per step.
    Fusion,
}

impl Plot {
    /// Every plot, in the page's order.
    pub const ALL: [Plot; 7] = [
        Plot::Accel,
        Plot::Sigma,
        Plot::Height,
        Plot::Heading,
        Plot::Steps,
        Plot::Gnss,
        Plot::Fusion,
    ];

    /// From its name in the page.
    pub fn parse(name: &str) -> Option<Plot> {
        Some(match name {
            "accel" => Plot::Accel,
            "sigma" => Plot::Sigma,
            "height" => Plot::Height,
            "heading" => Plot::Heading,
            "steps" => Plot::Steps,
            "gnss" => Plot::Gnss,
            "fusion" => Plot::Fusion,
            _ => return None,
        })
    }
}

/// One diagnostics plot's series between two times, with what frames them.
pub struct PlotSeries {
    /// The title (it wraps over as many lines as the width asks).
    pub title: String,
    /// The left axis's unit: "m/s²", "m", "°", "Hz" or "" (a plain number).
    pub unit: &'static str,
    /// The left axis's range.
    pub y: (f64, f64),
    /// The right axis's unit and range, when the plot has one.
    pub right: Option<(&'static str, (f64, f64))>,
    /// The times of the steps in the span.
    pub steps: Vec<f64>,
    /// What the plot says instead of (or beside) its series when the log lacks them.
    pub note: Option<String>,
    /// The plot's own series.
    pub lines: Lines,
}

/// The series particular to each plot.
pub enum Lines {
    /// See [`AccelLines`].
    Accel(AccelLines),
    /// See [`SigmaLines`].
    Sigma(SigmaLines),
    /// The height's runs and the floors' staircase, and each step's height (t, m).
    Height(HeightSeries, Vec<(f64, f64)>),
    /// See [`HeadingLines`].
    Heading(HeadingLines),
    /// Each step's time, frequency (Hz) and length (m).
    Steps(Vec<(f64, f64, f64)>),
    /// See [`GnssLines`].
    Gnss(GnssLines),
    /// The fusion's scale and correction with their bands.
    Fusion(FusionSeries),
}

/// The acceleration plot's series.
pub struct AccelLines {
    /// The vertical acceleration's runs ([`envelope`]), m/s².
    pub signal: Vec<Vec<(f64, f64)>>,
    /// The true steps' times.
    pub truth: Vec<f64>,
    /// The PLL's output in its lane.
    pub pll: PllLane,
}

/// The PLL's output cos φ: a faint band of its range per column over a long span (column
/// width, columns), else its runs.
pub enum PllLane {
    /// See [`band`].
    Band(f64, Vec<Column>),
    /// See [`envelope`].
    Runs(Vec<Vec<(f64, f64)>>),
}

/// The σ plot's series.
pub struct SigmaLines {
    /// σ's runs ([`envelope`]), m/s².
    pub signal: Vec<Vec<(f64, f64)>>,
    /// The activity band: each piece's start, width (s) and activity.
    pub activity: Vec<(f64, f64, Activity)>,
    /// The motion detector's thresholds, m/s².
    pub thresholds: (f64, f64),
}

/// The heading plot's series.
pub struct HeadingLines {
    /// The unwrapped headings.
    pub headings: Headings,
    /// Each step's period (from, to), its carrying mode and whether its heading followed the
    /// gyroscope: the band along the bottom.
    pub periods: Vec<((f64, f64), Option<CarryMode>, bool)>,
}

/// The GNSS plot's series.
pub struct GnssLines {
    /// Each fix's time and reported accuracy, m.
    pub fixes: Vec<(f64, f64)>,
    /// Each innovation's time and length, m.
    pub innovations: Vec<(f64, f64)>,
}

impl PlotSeries {
    /// `plot`'s series of `a` between `t0` and `t1` (s, the log's clock), decimated to `cols`
    /// pixel columns.
    pub fn new(a: &Analysis, plot: Plot, (t0, t1): (f64, f64), cols: usize) -> Self {
        let origin = a.trace.t.first().copied().unwrap_or(0.0);
        let steps_in: Vec<&StepRecord> =
            a.steps.iter().filter(|s| s.t >= t0 && s.t <= t1).collect();
        let span = Span {
            t0,
            t1,
            cols,
            origin,
        };
        let mut s = match plot {
            Plot::Accel => accel(a, &span),
            Plot::Sigma => sigma(a, &span),
            Plot::Height => height(a, &span, &steps_in),
            Plot::Heading => headings(a, &span, &steps_in),
            Plot::Steps => steps(&span, &steps_in),
            Plot::Gnss => gnss(a, &span),
            Plot::Fusion => fusion(a, &span),
        };
        s.steps = steps_in.iter().map(|s| s.t - origin).collect();
        s.note = note(a, plot);
        s
    }
}

/// The span of a plot: its times (the log's clock), columns, and the time axis's origin.
struct Span {
    t0: f64,
    t1: f64,
    cols: usize,
    origin: f64,
}

/// A series with its frame; the steps and the note are filled in by [`PlotSeries::new`].
fn framed(
    title: String,
    unit: &'static str,
    y: (f64, f64),
    right: Option<(&'static str, (f64, f64))>,
    lines: Lines,
) -> PlotSeries {
    PlotSeries {
        title,
        unit,
        y,
        right,
        steps: Vec::new(),
        note: None,
        lines,
    }
}

fn accel(a: &Analysis, s: &Span) -> PlotSeries {
    let tr = &a.trace;
    let (t0, t1, cols, origin) = (s.t0, s.t1, s.cols, s.origin);
    let amp = envelope(&tr.t, of(&tr.up), t0, t1, cols, 0.0)
        .iter()
        .flatten()
        .fold(2.0_f64, |m, p| m.max(p.1.abs()))
        .min(40.0)
        * 1.1;
    let pll = match band(&tr.t, of(&tr.pll), t0, t1, cols, origin) {
        Some((w, columns)) => PllLane::Band(w, columns),
        None => PllLane::Runs(envelope(&tr.t, of(&tr.pll), t0, t1, cols, origin)),
    };
    // Room above the signal for the step ticks.
    framed(
        "vertical acceleration (m/s²), steps (red), true steps (grey), PLL cos φ (lower lane)"
            .to_string(),
        "m/s²",
        (-amp, 1.3 * amp),
        None,
        Lines::Accel(AccelLines {
            signal: envelope(&tr.t, of(&tr.up), t0, t1, cols, origin),
            truth: a
                .truth_steps
                .iter()
                .filter(|&&t| t >= t0 && t <= t1)
                .map(|&t| t - origin)
                .collect(),
            pll,
        }),
    )
}

fn sigma(a: &Analysis, s: &Span) -> PlotSeries {
    let tr = &a.trace;
    let (t0, t1, cols, origin) = (s.t0, s.t1, s.cols, s.origin);
    let top = envelope(&tr.t, of(&tr.sigma), t0, t1, cols, 0.0)
        .iter()
        .flatten()
        .fold(a.sigma_thresholds.1 * 1.3, |m, p| m.max(p.1))
        * 1.1;
    let i0 = tr.t.partition_point(|&x| x < t0);
    let i1 = tr.t.partition_point(|&x| x <= t1).min(tr.activity.len());
    let every = (i1.saturating_sub(i0) / cols).max(1);
    let activity = (i0..i1)
        .step_by(every)
        .map(|i| {
            let w = (tr.t[(i + every).min(i1 - 1)] - tr.t[i]).max(0.01);
            (tr.t[i] - origin, w, activity_from_code(tr.activity[i]))
        })
        .collect();
    framed(
        "σ of vertical acceleration (m/s²), thresholds, activity (band along the bottom)"
            .to_string(),
        "m/s²",
        (0.0, top),
        None,
        Lines::Sigma(SigmaLines {
            signal: envelope(&tr.t, of(&tr.sigma), t0, t1, cols, origin),
            activity,
            thresholds: a.sigma_thresholds,
        }),
    )
}

fn height(a: &Analysis, s: &Span, steps_in: &[&StepRecord]) -> PlotSeries {
    let h = HeightSeries::new(a, s.t0, s.t1, s.cols, s.origin);
    let title = format!(
        "height above the start (m, blue), floor (orange, right, 3 m each), {}",
        match a.vertical {
            Some(v) => format!("from {}", v.as_str()),
            None => a.height_source().to_string(),
        }
    );
    let (metres, floors) = (h.metres, h.floors);
    let at = steps_in
        .iter()
        .map(|st| (st.t - s.origin, st.up_m))
        .collect();
    framed(
        title,
        "m",
        metres,
        Some(("floor", floors)),
        Lines::Height(h, at),
    )
}

fn headings(a: &Analysis, s: &Span, steps_in: &[&StepRecord]) -> PlotSeries {
    let h = Headings::new(a, s.t0, s.t1, s.cols, s.origin);
    // Room under the headings for the band.
    let (lo, hi) = h.range();
    let periods = steps_in
        .iter()
        .map(|st| {
            let p = 1.0 / st.freq_hz.max(0.3);
            let period = ((st.t - p).max(s.t0) - s.origin, st.t - s.origin);
            (period, st.carry, st.gyro_heading)
        })
        .collect();
    framed(
        "heading (°, unwrapped): single step (dots), two-step average (line), device (grey), carrying mode (band along the bottom)".to_string(),
        "°",
        (lo - 0.16 * (hi - lo), hi),
        None,
        Lines::Heading(HeadingLines {
            headings: h,
            periods,
        }),
    )
}

fn steps(s: &Span, steps_in: &[&StepRecord]) -> PlotSeries {
    let top = steps_in.iter().fold(3.0_f64, |m, s| m.max(s.freq_hz)) * 1.1;
    let len = steps_in.iter().fold(1.0_f64, |m, s| m.max(s.length_m)) * 1.1;
    framed(
        "step frequency (Hz, blue), step length (m, orange, right)".to_string(),
        "Hz",
        (0.0, top),
        Some(("m", (0.0, len))),
        Lines::Steps(
            steps_in
                .iter()
                .map(|st| (st.t - s.origin, st.freq_hz, st.length_m))
                .collect(),
        ),
    )
}

fn gnss(a: &Analysis, s: &Span) -> PlotSeries {
    let inside = |t: f64| t >= s.t0 && t <= s.t1;
    let top = a
        .fixes
        .iter()
        .filter(|f| inside(f[0]))
        .fold(10.0_f64, |m, f| m.max(f[3]).max(0.0))
        .min(200.0)
        * 1.1;
    framed(
        "GNSS accuracy (m, dots), innovation (m, rings)".to_string(),
        "m",
        (0.0, top),
        None,
        Lines::Gnss(GnssLines {
            fixes: a
                .fixes
                .iter()
                .filter(|f| inside(f[0]))
                .map(|f| (f[0] - s.origin, f[3]))
                .collect(),
            innovations: a
                .innovations
                .iter()
                .filter(|i| inside(i[0]))
                .map(|i| (i[0] - s.origin, libm::hypot(i[1], i[2])))
                .collect(),
        }),
    )
}

fn fusion(a: &Analysis, s: &Span) -> PlotSeries {
    let f = FusionSeries::new(a, s.t0, s.t1, s.origin);
    framed(
        "fusion: step-length scale (blue, left), heading correction (°, orange, right), shaded ±1σ (cut at ±0.05 and ±5°)".to_string(),
        "",
        f.scale_axis,
        Some(("°", f.correction_axis)),
        Lines::Fusion(f),
    )
}

/// What a plot says when the log lacks what it shows.
fn note(a: &Analysis, plot: Plot) -> Option<String> {
    match plot {
        Plot::Gnss | Plot::Fusion if a.fixes.is_empty() => {
            Some("no GNSS fixes in this log".to_string())
        }
        Plot::Heading => a.no_heading_why().map(|why| format!("no heading: {why}")),
        Plot::Height if !a.has_height() => Some(
            "no height in this log (no leg pitch, no barometer): a flat walk is assumed"
                .to_string(),
        ),
        _ => None,
    }
}

/// The heading plot's series between two times, unwrapped onto one set of turns: the two-step
/// average's line (unwrapped over the whole log, so that zoom and pan do not move it by a
/// turn), each step's single-step heading on the turn nearest the line, and the device's
/// heading on the turn nearest the line.
pub struct Headings {
    /// The two-step average's runs within the span (time from the log's start, °).
    pub line: Vec<Vec<(f64, f64)>>,
    /// The single-step headings.
    pub single: Vec<(f64, f64)>,
    /// The device heading's runs ([`envelope`]).
    pub device: Vec<Vec<(f64, f64)>>,
}

impl Headings {
    fn new(a: &Analysis, t0: f64, t1: f64, cols: usize, origin: f64) -> Self {
        let all = heading::unwrap_runs(
            a.steps
                .iter()
                .map(|s| (s.t, s.heading_rad.map_or(f64::NAN, f64::to_degrees))),
            heading::BOUT_GAP_S,
        );
        let inside = |p: &&(f64, f64)| p.0 >= t0 && p.0 <= t1;
        let line = all
            .iter()
            .map(|r| {
                r.iter()
                    .filter(inside)
                    .map(|p| (p.0 - origin, p.1))
                    .collect()
            })
            .filter(|r: &Vec<_>| !r.is_empty())
            .collect();
        let single = a
            .steps
            .iter()
            .filter(|s| s.t >= t0 && s.t <= t1)
            .filter_map(|s| {
                let h = s.step_heading_rad?.to_degrees();
                let near = heading::line_at(&all, s.t).unwrap_or(h.rem_euclid(360.0));
                Some((s.t - origin, heading::nearest_turn(h, near)))
            })
            .collect();
        let tr = &a.trace;
        let mut last: Option<(f64, f64)> = None;
        let mut cursor = heading::LineCursor::new(&all);
        let device = envelope(
            &tr.t,
            |i| {
                let (t, h) = (tr.t[i], f64::from(tr.device_heading_deg[i]));
                if !h.is_finite() {
                    return f64::NAN;
                }
                // On the turn nearest the walking line (so that the axis spans the walk, and a
                // device turned by half a turn, as a phone in a pocket with its top near
                // vertical flips, lies half a turn off it); without one, sample by sample.
                let near = match (cursor.at(t), last) {
                    (Some(l), _) => l,
                    (None, Some((lt, lh))) if t - lt <= GAP_S => lh,
                    _ => h.rem_euclid(360.0),
                };
                let v = heading::nearest_turn(h, near);
                last = Some((t, v));
                v
            },
            t0,
            t1,
            cols,
            origin,
        );
        Headings {
            line,
            single,
            device,
        }
    }

    /// The heading axis: the walking heading (the line and the single steps; the device's
    /// without them), and at least 60°. The device's heading may lie half a turn off the
    /// walking one (a phone in a pocket): it is drawn where it falls within.
    fn range(&self) -> (f64, f64) {
        let walking = !self.line.is_empty() || !self.single.is_empty();
        let (lo, hi) = self
            .line
            .iter()
            .chain(if walking { &[][..] } else { &self.device[..] })
            .flatten()
            .chain(&self.single)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            });
        if !lo.is_finite() {
            return (0.0, 360.0);
        }
        let pad = ((hi - lo).max(60.0) - (hi - lo)) / 2.0 + 0.08 * (hi - lo).max(60.0);
        (lo - pad, hi + pad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The series are plain data: the σ plot's activity band covers the span, the step plot
    /// has every step, and a walk without fixes says so on the GNSS plot.
    #[test]
    fn each_plot_has_its_series_without_a_backend() {
        let a = crate::analysis::three_floor_analysis();
        let span = (a.trace.t[0], *a.trace.t.last().unwrap());
        let s = PlotSeries::new(&a, Plot::Steps, span, 600);
        assert_eq!(s.steps.len(), a.steps.len());
        assert!(matches!(&s.lines, Lines::Steps(v) if v.len() == a.steps.len()));
        let s = PlotSeries::new(&a, Plot::Sigma, span, 600);
        let Lines::Sigma(l) = &s.lines else {
            panic!("the σ plot's series")
        };
        assert!(l.activity.iter().any(|p| p.2 == Activity::Upstairs));
        assert!(s.y.1 > l.thresholds.1);
        let s = PlotSeries::new(&a, Plot::Gnss, span, 600);
        assert_eq!(s.note.as_deref(), Some("no GNSS fixes in this log"));
        let s = PlotSeries::new(&a, Plot::Height, span, 600);
        assert!(s.y.1 > 6.0 && s.right.is_some() && s.note.is_none());
    }
}
