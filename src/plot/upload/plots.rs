//! Upload mode's diagnostics plots of an [`Analysis`] on one time axis (its zoom and pan:
//! `time_axis`).
//! May import: `engine` (step records), `analysis` and the theme; never `web`, `live` or `eval`.

use super::decimate::{band, envelope, of, COARSE_COLUMN_S, GAP_S};
use super::fusion::FusionSeries;
use super::heading;
use super::height::{floor_tick, HeightSeries};
use super::palette::{
    activity_colour, activity_key, carry_colour, carry_key, draw_key, draw_title,
};
use crate::analysis::activity_from_code;
use crate::analysis::Analysis;
use crate::plot::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

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

/// Draws one diagnostics plot between `t0` and `t1` (s, the log's clock), with a cursor at a
/// time when given. The time axis is in seconds from the log's first sample. Returns the
/// pixel columns where `t0` and `t1` fall, for the page to map a pointer to a time.
pub fn draw_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    plot: Plot,
    span: (f64, f64),
    cursor: Option<f64>,
    theme: &Theme,
    scale: f64,
) -> Result<(i32, i32), DrawingAreaErrorKind<DB::ErrorType>> {
    draw_plot_area(area, a, plot, span, cursor, theme, scale).map(|(columns, _)| columns)
}

/// [`draw_plot`], returning the plot area's pixel columns and rows (the rows from the top of
/// the first lane to the bottom of the last): where the legibility tests look.
#[allow(clippy::type_complexity)]
pub fn draw_plot_area<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    plot: Plot,
    (t0, t1): (f64, f64),
    cursor: Option<f64>,
    theme: &Theme,
    scale: f64,
) -> Result<((i32, i32), (i32, i32)), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    area.fill(&theme.background)?;
    let font = ("sans-serif", 12.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let origin = a.trace.t.first().copied().unwrap_or(0.0);
    let (x0, x1) = (t0 - origin, t1 - origin);
    let cols = (area.dim_in_pixel().0 as usize).max(10);
    let tr = &a.trace;
    let steps_in: Vec<&crate::engine::StepRecord> =
        a.steps.iter().filter(|s| s.t >= t0 && s.t <= t1).collect();
    let headings = (plot == Plot::Heading).then(|| Headings::new(a, t0, t1, cols, origin));
    let heights = (plot == Plot::Height).then(|| HeightSeries::new(a, t0, t1, cols, origin));
    let fusion = (plot == Plot::Fusion).then(|| FusionSeries::new(a, t0, t1, origin));
    let height_title = format!(
        "height above the start (m, blue), floor (orange, right, 3 m each), {}",
        match a.vertical {
            Some(v) => format!("from {}", v.as_str()),
            None => a.height_source().to_string(),
        }
    );
    // The key of a plot's band: the σ plot's activities in the span, the heading plot's
    // carrying modes and where the gyroscope held the heading.
    let key = match plot {
        Plot::Sigma => activity_key(a, t0, t1, theme),
        Plot::Heading => carry_key(&steps_in, theme),
        _ => Vec::new(),
    };
    #[allow(clippy::type_complexity)]
    let (title, y_label, (y0, y1), right): (
        &str,
        &str,
        (f64, f64),
        Option<(&str, (f64, f64))>,
    ) = match plot {
        Plot::Accel => {
            let amp = envelope(&tr.t, of(&tr.up), t0, t1, cols, 0.0)
                .iter()
                .flatten()
                .fold(2.0_f64, |m, p| m.max(p.1.abs()))
                .min(40.0)
                * 1.1;
            // Room above the signal for the step ticks.
            (
                "vertical acceleration (m/s²), steps (red), true steps (grey), PLL cos φ (lower lane)",
                "m/s²",
                (-amp, 1.3 * amp),
                None,
            )
        }
        Plot::Sigma => {
            let top = envelope(&tr.t, of(&tr.sigma), t0, t1, cols, 0.0)
                .iter()
                .flatten()
                .fold(a.sigma_thresholds.1 * 1.3, |m, p| m.max(p.1))
                * 1.1;
            (
                "σ of vertical acceleration (m/s²), thresholds, activity (band along the bottom)",
                "m/s²",
                (0.0, top),
                None,
            )
        }
        Plot::Height => {
            let h = heights.as_ref().expect("made for the height plot");
            (
                height_title.as_str(),
                "m",
                h.metres,
                Some(("floor", h.floors)),
            )
        }
        Plot::Heading => (
            "heading (°, unwrapped): single step (dots), two-step average (line), device (grey), carrying mode (band along the bottom)",
            "°",
            {
                // Room under the headings for the band.
                let (lo, hi) = headings.as_ref().map_or((0.0, 360.0), Headings::range);
                (lo - 0.16 * (hi - lo), hi)
            },
            None,
        ),
        Plot::Steps => {
            let top = steps_in.iter().fold(3.0_f64, |m, s| m.max(s.freq_hz)) * 1.1;
            let len = steps_in.iter().fold(1.0_f64, |m, s| m.max(s.length_m)) * 1.1;
            (
                "step frequency (Hz, blue), step length (m, orange, right)",
                "Hz",
                (0.0, top),
                Some(("m", (0.0, len))),
            )
        }
        Plot::Gnss => {
            let top = a
                .fixes
                .iter()
                .filter(|f| f[0] >= t0 && f[0] <= t1)
                .fold(10.0_f64, |m, f| m.max(f[3]).max(0.0))
                .min(200.0)
                * 1.1;
            (
                "GNSS accuracy (m, dots), innovation (m, rings)",
                "m",
                (0.0, top),
                None,
            )
        }
        Plot::Fusion => {
            let f = fusion.as_ref().expect("made for the fusion plot");
            (
                "fusion: step-length scale (blue, left), heading correction (°, orange, right), shaded ±1σ (cut at ±0.05 and ±5°)",
                "",
                f.scale_axis,
                Some(("°", f.correction_axis)),
            )
        }
    };
    let lines = draw_title(area, title, &font, scale)?;
    let lines = lines + draw_key(area, &key, lines, &font, scale)?;
    let body = area.margin(px(5.0 + 15.0 * lines as f64), 0, 0, 0);
    // The acceleration plot's PLL output has a lane of its own under the acceleration: drawn
    // over it (as it was) its ±1 wave covers the signal and the steps over a whole walk.
    let (main, lane) = if plot == Plot::Accel {
        let h = body.dim_in_pixel().1 as i32;
        let (main, lane) = body.split_vertically(h * 68 / 100);
        (main, Some(lane))
    } else {
        (body, None)
    };
    let mut builder = ChartBuilder::on(&main);
    // The same label areas on every plot and lane, with a right axis or not, so that their
    // time axes line up on the page.
    builder
        .margin(px(6.0))
        .x_label_area_size(px(22.0))
        .y_label_area_size(px(40.0))
        .right_y_label_area_size(px(40.0));
    if lane.is_some() {
        builder.margin_bottom(px(2.0)).x_label_area_size(0);
    }
    let (r0, r1) = right.map_or((0.0, 1.0), |r| r.1);
    let mut chart = builder
        .build_cartesian_2d(x0..x1, y0..y1)?
        .set_secondary_coord(x0..x1, r0..r1);
    let time_label = |v: &f64| {
        if x1 - x0 < 20.0 {
            format!("{v:.1} s")
        } else {
            format!("{v:.0} s")
        }
    };
    let no_label = |_: &f64| String::new();
    let y_format = |v: &f64| match y_label {
        "°" => format!("{v:.0}°"),
        "" => format!("{v:.2}"),
        // Heights: a decimal while the axis spans a few metres.
        "m" if plot == Plot::Height && y1 - y0 < 8.0 => format!("{v:.1}"),
        _ => format!("{v:.0}"),
    };
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(8)
        .y_labels(5)
        .x_label_formatter(if lane.is_some() {
            &no_label
        } else {
            &time_label
        })
        .y_label_formatter(&y_format);
    if plot == Plot::Heading {
        // Its own grid and labels: whole compass points of the unwrapped heading.
        mesh.disable_y_mesh().y_labels(0);
    }
    mesh.draw()?;
    if right.is_some() {
        chart
            .configure_secondary_axes()
            .axis_style(theme.foreground)
            .label_style(font.clone())
            .y_labels(5)
            .y_label_formatter(&|v| match right {
                Some(("°", _)) => format!("{v:.0}°"),
                Some(("floor", _)) => floor_tick(v),
                _ => format!("{v:.2}"),
            })
            .draw()?;
    }
    let (columns, rows) = chart.plotting_area().get_pixel_range();
    let no_heading = a.no_heading_why().map(|why| format!("no heading: {why}"));
    let note = match plot {
        Plot::Gnss | Plot::Fusion if a.fixes.is_empty() => Some("no GNSS fixes in this log"),
        Plot::Heading if no_heading.is_some() => no_heading.as_deref(),
        Plot::Height if !a.has_height() => {
            Some("no height in this log (no leg pitch, no barometer): a flat walk is assumed")
        }
        _ => None,
    };
    if let Some(note) = note {
        area.draw(&Text::new(
            note,
            (
                columns.start + px(12.0) as i32,
                rows.start + px(12.0) as i32,
            ),
            font.clone(),
        ))?;
    }
    let (columns, mut rows) = ((columns.start, columns.end), (rows.start, rows.end));
    let line = |c: RGBColor, w: f64| ShapeStyle::from(&c).stroke_width(px(w));
    let rel = |t: f64| t - origin;
    // Envelopes drawn as two lines (coarse) thinner than a signal, so they do not merge.
    let signal_w = if (t1 - t0) / cols as f64 > COARSE_COLUMN_S {
        1.0
    } else {
        1.5
    };
    // Steps marked by a line across the plot only while they are at least 6 pixels apart;
    // closer, the lines would fill the plot, and the ticks along its top show them.
    let step_lines = steps_in.len() as i32 * 6 * px(1.0) as i32 <= columns.1 - columns.0;
    match plot {
        Plot::Accel => {
            let tick = 0.1 * (y1 - y0);
            chart.draw_series(steps_in.iter().map(|s| {
                let from = if step_lines { y0 } else { y1 - tick };
                PathElement::new(vec![(rel(s.t), from), (rel(s.t), y1)], line(theme.end, 1.0))
            }))?;
            chart.draw_series(
                a.truth_steps
                    .iter()
                    .filter(|&&t| t >= t0 && t <= t1)
                    .map(|&t| {
                        PathElement::new(
                            vec![(rel(t), y0), (rel(t), y0 + tick)],
                            line(theme.reference, 2.0),
                        )
                    }),
            )?;
            for run in envelope(&tr.t, of(&tr.up), t0, t1, cols, origin) {
                chart.draw_series(LineSeries::new(run, line(theme.track, signal_w)))?;
            }
        }
        Plot::Sigma => {
            // The activity as a band along the bottom (none while still).
            let band = 0.08 * (y1 - y0);
            let i0 = tr.t.partition_point(|&x| x < t0);
            let i1 = tr.t.partition_point(|&x| x <= t1).min(tr.activity.len());
            let every = (i1.saturating_sub(i0) / cols).max(1);
            chart.draw_series((i0..i1).step_by(every).filter_map(|i| {
                let c = activity_colour(activity_from_code(tr.activity[i]), theme)?;
                let t = rel(tr.t[i]);
                let w = (tr.t[(i + every).min(i1 - 1)] - tr.t[i]).max(0.01);
                Some(Rectangle::new([(t, y0), (t + w, y0 + band)], c.filled()))
            }))?;
            for (v, c) in [
                (a.sigma_thresholds.0, theme.start),
                (a.sigma_thresholds.1, theme.end),
            ] {
                chart.draw_series(LineSeries::new([(x0, v), (x1, v)], line(c, 1.0)))?;
            }
            for run in envelope(&tr.t, of(&tr.sigma), t0, t1, cols, origin) {
                chart.draw_series(LineSeries::new(run, line(theme.track, signal_w)))?;
            }
        }
        Plot::Heading => {
            let h = headings.as_ref().expect("made for the heading plot");
            let base = area.get_base_pixel();
            for g in heading::grid(y0, y1) {
                chart.draw_series(LineSeries::new([(x0, g), (x1, g)], line(theme.grid, 1.0)))?;
                let (x, y) = chart.backend_coord(&(x0, g));
                area.draw(&Text::new(
                    heading::grid_label(g, y0, y1),
                    (x - base.0 - px(4.0) as i32, y - base.1),
                    font.pos(Pos::new(HPos::Right, VPos::Center)),
                ))?;
            }
            // Dots, not a line: the device's heading jumps where a line would draw a bar.
            chart.draw_series(
                h.device
                    .iter()
                    .flatten()
                    .filter(|p| p.1 >= y0 && p.1 <= y1)
                    .map(|&p| Circle::new(p, px(0.8), theme.reference.filled())),
            )?;
            chart.draw_series(
                h.single
                    .iter()
                    .map(|&p| Circle::new(p, px(2.0), theme.gnss.filled())),
            )?;
            for run in &h.line {
                chart.draw_series(LineSeries::new(run.clone(), line(theme.track, 2.0)))?;
            }
            // Each step's carrying mode over its own period, and a grey strip above it where
            // its heading followed the gyroscope.
            let band = 0.06 * (y1 - y0);
            let period = |s: &crate::engine::StepRecord| {
                let p = 1.0 / s.freq_hz.max(0.3);
                (rel((s.t - p).max(t0)), rel(s.t))
            };
            chart.draw_series(steps_in.iter().filter_map(|s| {
                let (a, b) = period(s);
                let c = carry_colour(s.carry?, theme);
                Some(Rectangle::new([(a, y0), (b, y0 + band)], c.filled()))
            }))?;
            chart.draw_series(steps_in.iter().filter(|s| s.gyro_heading).map(|s| {
                let (a, b) = period(s);
                Rectangle::new(
                    [(a, y0 + 1.2 * band), (b, y0 + 2.0 * band)],
                    theme.reference.filled(),
                )
            }))?;
        }
        Plot::Height => {
            let h = heights.as_ref().expect("made for the height plot");
            chart.draw_series(LineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                line(theme.grid, 1.0),
            ))?;
            chart.draw_secondary_series(LineSeries::new(
                h.floor.iter().copied(),
                line(theme.gnss, 2.0),
            ))?;
            for run in &h.height {
                chart.draw_series(LineSeries::new(run.clone(), line(theme.track, signal_w)))?;
            }
            // Each step's height, where the steps are far enough apart to be told apart.
            if step_lines {
                chart.draw_series(
                    steps_in
                        .iter()
                        .map(|s| Circle::new((rel(s.t), s.up_m), px(1.5), theme.track.filled())),
                )?;
            }
        }
        Plot::Steps => {
            chart.draw_series(
                steps_in
                    .iter()
                    .map(|s| Circle::new((rel(s.t), s.freq_hz), px(2.0), theme.track.filled())),
            )?;
            chart.draw_secondary_series(
                steps_in
                    .iter()
                    .map(|s| Circle::new((rel(s.t), s.length_m), px(2.0), theme.gnss.filled())),
            )?;
        }
        Plot::Gnss => {
            chart.draw_series(
                a.fixes
                    .iter()
                    .filter(|f| f[0] >= t0 && f[0] <= t1)
                    .map(|f| Circle::new((rel(f[0]), f[3].min(y1)), px(2.0), theme.gnss.filled())),
            )?;
            chart.draw_series(
                a.innovations
                    .iter()
                    .filter(|i| i[0] >= t0 && i[0] <= t1)
                    .map(|i| {
                        Circle::new(
                            (rel(i[0]), libm::hypot(i[1], i[2]).min(y1)),
                            px(3.0),
                            line(theme.pdr, 1.0),
                        )
                    }),
            )?;
        }
        Plot::Fusion => {
            // The ±1σ bands under the values: faint, each in its value's colour, edged so
            // that a narrow one still shows beside its line.
            let f = fusion.as_ref().expect("made for the fusion plot");
            let edge = |c: RGBColor| ShapeStyle::from(&c.mix(0.6)).stroke_width(px(1.0));
            chart.draw_series([Polygon::new(f.scale_band(), theme.track.mix(0.25).filled())])?;
            let [up, down] = f.scale_edges();
            chart.draw_series([up, down].map(|e| PathElement::new(e, edge(theme.track))))?;
            chart.draw_secondary_series([Polygon::new(
                f.correction_band(),
                theme.gnss.mix(0.3).filled(),
            )])?;
            let [up, down] = f.correction_edges();
            chart
                .draw_secondary_series([up, down].map(|e| PathElement::new(e, edge(theme.gnss))))?;
            chart.draw_series(LineSeries::new(
                [(x0, 1.0), (x1, 1.0)],
                line(theme.grid, 1.0),
            ))?;
            chart.draw_series(LineSeries::new(
                f.scale.iter().map(|p| (p.0, p.1)),
                line(theme.track, 1.5),
            ))?;
            chart.draw_secondary_series(
                f.correction
                    .iter()
                    .map(|p| Circle::new((p.0, p.1), px(1.5), theme.gnss.filled())),
            )?;
        }
    }
    let cursor = cursor.filter(|c| *c >= t0 && *c <= t1).map(rel);
    if let Some(c) = cursor {
        chart.draw_series([PathElement::new(
            vec![(c, y0), (c, y1)],
            line(theme.foreground, 1.0),
        )])?;
    }
    if let Some(lane) = lane {
        // The PLL's lane: its own ±1 scale, the step lines when they are far enough apart
        // (a step is where cos φ crosses from − to +), and the time axis of the whole plot.
        let mut pll = ChartBuilder::on(&lane)
            .margin(px(6.0))
            .margin_top(px(2.0))
            .x_label_area_size(px(22.0))
            .y_label_area_size(px(40.0))
            .right_y_label_area_size(px(40.0))
            .build_cartesian_2d(x0..x1, -1.6..1.6)?;
        pll.configure_mesh()
            .light_line_style(TRANSPARENT)
            .bold_line_style(theme.grid)
            .axis_style(theme.foreground)
            .label_style(font.clone())
            .x_labels(8)
            .y_labels(3)
            .x_label_formatter(&time_label)
            .y_label_formatter(&crate::plot::scope::pll_lane_label)
            .draw()?;
        if step_lines {
            pll.draw_series(steps_in.iter().map(|s| {
                PathElement::new(
                    vec![(rel(s.t), -1.6), (rel(s.t), 1.6)],
                    line(theme.end, 1.0),
                )
            }))?;
        }
        // Over a long span the wave cannot be followed: a faint band shows where the PLL
        // ran and how far it swung, and lets the step lines show through.
        match band(&tr.t, of(&tr.pll), t0, t1, cols, origin) {
            Some((w, columns)) => {
                // One polygon per run of columns: rectangles side by side would leave seams.
                let faint = theme.gnss.mix(0.35).filled();
                let mut from = 0;
                for k in 1..=columns.len() {
                    if k < columns.len() && !columns[k].3 {
                        continue;
                    }
                    let run = &columns[from..k];
                    let upper = run
                        .iter()
                        .flat_map(|c| [(c.0 - w / 2.0, c.2), (c.0 + w / 2.0, c.2)]);
                    let lower = run
                        .iter()
                        .rev()
                        .flat_map(|c| [(c.0 + w / 2.0, c.1), (c.0 - w / 2.0, c.1)]);
                    pll.draw_series([Polygon::new(upper.chain(lower).collect::<Vec<_>>(), faint)])?;
                    from = k;
                }
            }
            None => {
                for run in envelope(&tr.t, of(&tr.pll), t0, t1, cols, origin) {
                    pll.draw_series(LineSeries::new(run, line(theme.gnss, 1.0)))?;
                }
            }
        }
        if let Some(c) = cursor {
            pll.draw_series([PathElement::new(
                vec![(c, -1.6), (c, 1.6)],
                line(theme.foreground, 1.0),
            )])?;
        }
        rows.1 = pll.plotting_area().get_pixel_range().1.end;
    }
    Ok((columns, rows))
}

/// The heading plot's series between two times, unwrapped onto one set of turns: the two-step
/// average's line (unwrapped over the whole log, so that zoom and pan do not move it by a
/// turn), each step's single-step heading on the turn nearest the line, and the device's
/// heading on the turn nearest the line.
struct Headings {
    /// The two-step average's runs within the span (time from the log's start, °).
    line: Vec<Vec<(f64, f64)>>,
    /// The single-step headings.
    single: Vec<(f64, f64)>,
    /// The device heading's runs ([`envelope`]).
    device: Vec<Vec<(f64, f64)>>,
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
