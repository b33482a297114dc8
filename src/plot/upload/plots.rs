//! Upload mode's diagnostics plots of an [`Analysis`] on one time axis (its zoom and pan:
//! `time_axis`): the drawing of the series `series` computes.
//! May import: `engine` (step records), `analysis` and the theme; never `web`, `live` or `eval`.

use super::decimate::COARSE_COLUMN_S;
use super::fusion::FusionSeries;
use super::heading;
use super::height::{floor_tick, HeightSeries};
use super::palette::{
    activity_colour, activity_key, carry_colour, carry_key, draw_key, draw_title,
};
use super::series::{
    AccelLines, GnssLines, HeadingLines, Lines, PllLane, Plot, PlotSeries, SigmaLines,
};
use crate::analysis::Analysis;
use crate::engine::StepRecord;
use crate::plot::theme::Theme;
use plotters::chart::DualCoordChartContext;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Draws one diagnostics plot between `t0` and `t1` (s, the log's clock), with a cursor at a
/// time when given. The time axis is in seconds from the log's first sample. Returns the plot
/// area's pixel columns (where `t0` and `t1` fall, for the page to map a pointer to a time) and
/// rows (from the top of the first lane to the bottom of the last: where the legibility tests
/// look). The series are computed first (`PlotSeries`), then drawn.
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
    area.fill(&theme.background)?;
    let origin = a.trace.t.first().copied().unwrap_or(0.0);
    let cols = (area.dim_in_pixel().0 as usize).max(10);
    let series = PlotSeries::new(a, plot, (t0, t1), cols);
    let pen = Pen {
        theme,
        scale,
        font: theme.text(scale),
        x: (t0 - origin, t1 - origin),
        y: series.y,
        // Envelopes drawn as two lines (coarse) thinner than a signal, so they do not merge.
        signal_w: if (t1 - t0) / cols as f64 > COARSE_COLUMN_S {
            1.0
        } else {
            1.5
        },
    };
    let key = key(a, plot, (t0, t1), theme);
    let lines = draw_title(area, &series.title, &pen.font, scale)?;
    let lines = lines + draw_key(area, &key, lines, &pen.font, scale)?;
    let body = area.margin(pen.px(5.0 + 15.0 * lines as f64), 0, 0, 0);
    // The acceleration plot's PLL output has a lane of its own under the acceleration: drawn
    // over it (as it was) its ±1 wave covers the signal and the steps over a whole walk.
    let (main, lane) = if plot == Plot::Accel {
        let h = body.dim_in_pixel().1 as i32;
        let (main, lane) = body.split_vertically(h * 68 / 100);
        (main, Some(lane))
    } else {
        (body, None)
    };
    let mut chart = plot_chart(&main, &series, plot, lane.is_some(), &pen)?;
    let (columns, rows) = chart.plotting_area().get_pixel_range();
    if let Some(note) = &series.note {
        let at = (
            columns.start + pen.px(12.0) as i32,
            rows.start + pen.px(12.0) as i32,
        );
        area.draw(&Text::new(note.as_str(), at, pen.font.clone()))?;
    }
    let (columns, mut rows) = ((columns.start, columns.end), (rows.start, rows.end));
    // Steps marked by a line across the plot only while they are at least 6 pixels apart;
    // closer, the lines would fill the plot, and the ticks along its top show them.
    let step_lines = series.steps.len() as i32 * 6 * pen.px(1.0) as i32 <= columns.1 - columns.0;
    draw_lines(area, &mut chart, &series, step_lines, &pen)?;
    let cursor = cursor.filter(|c| *c >= t0 && *c <= t1).map(|c| c - origin);
    if let Some(c) = cursor {
        let (y0, y1) = pen.y;
        chart.draw_series([PathElement::new(
            vec![(c, y0), (c, y1)],
            pen.line(theme.foreground, 1.0),
        )])?;
    }
    if let (Some(lane), Lines::Accel(l)) = (lane, &series.lines) {
        rows.1 = draw_pll_lane(&lane, &l.pll, &series.steps, step_lines, cursor, &pen)?;
    }
    Ok((columns, rows))
}

/// The coordinates of a diagnostics plot: time (s from the log's start) and its left axis, and
/// the same time with its right axis.
type PlotChart<'a, DB> = DualCoordChartContext<
    'a,
    DB,
    Cartesian2d<RangedCoordf64, RangedCoordf64>,
    Cartesian2d<RangedCoordf64, RangedCoordf64>,
>;

/// What every part of one plot draws with: the theme, the scale (device pixels per CSS pixel),
/// the font, the axes' ranges and the width of a signal's line.
struct Pen<'a> {
    theme: &'a Theme,
    scale: f64,
    font: TextStyle<'a>,
    /// The time axis, s from the log's start.
    x: (f64, f64),
    /// The left axis.
    y: (f64, f64),
    /// A signal's line width, CSS pixels.
    signal_w: f64,
}

impl Pen<'_> {
    /// `v` CSS pixels in device pixels, at least one.
    fn px(&self, v: f64) -> u32 {
        (v * self.scale).round().max(1.0) as u32
    }

    /// A line of colour `c`, `w` CSS pixels wide.
    fn line(&self, c: RGBColor, w: f64) -> ShapeStyle {
        ShapeStyle::from(&c).stroke_width(self.px(w))
    }
}

/// The key of a plot's band: the σ plot's activities in the span, the heading plot's carrying
/// modes and where the gyroscope held the heading.
fn key(a: &Analysis, plot: Plot, (t0, t1): (f64, f64), theme: &Theme) -> Vec<(String, RGBColor)> {
    match plot {
        Plot::Sigma => activity_key(a, t0, t1, theme),
        Plot::Heading => {
            let steps: Vec<&StepRecord> =
                a.steps.iter().filter(|s| s.t >= t0 && s.t <= t1).collect();
            carry_key(&steps, theme)
        }
        _ => Vec::new(),
    }
}

/// A time axis's labels: tenths of a second over a short span.
fn time_label(span_s: f64) -> impl Fn(&f64) -> String {
    move |v: &f64| {
        if span_s < 20.0 {
            format!("{v:.1} s")
        } else {
            format!("{v:.0} s")
        }
    }
}

/// The plot's chart in `main` with its grid, axes and labels (the same label areas on every
/// plot and lane, with a right axis or not, so that their time axes line up on the page); its
/// time labels left to the lane under it when there is one.
fn plot_chart<'a, DB: DrawingBackend>(
    main: &'a DrawingArea<DB, Shift>,
    s: &PlotSeries,
    plot: Plot,
    laned: bool,
    pen: &Pen<'_>,
) -> Result<PlotChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), (y0, y1)) = (pen.x, pen.y);
    let mut builder = ChartBuilder::on(main);
    builder
        .margin(pen.px(6.0))
        .x_label_area_size(pen.px(22.0))
        .y_label_area_size(pen.px(40.0))
        .right_y_label_area_size(pen.px(40.0));
    if laned {
        builder.margin_bottom(pen.px(2.0)).x_label_area_size(0);
    }
    let (r0, r1) = s.right.map_or((0.0, 1.0), |r| r.1);
    let mut chart = builder
        .build_cartesian_2d(x0..x1, y0..y1)?
        .set_secondary_coord(x0..x1, r0..r1);
    let time_label = time_label(x1 - x0);
    let no_label = |_: &f64| String::new();
    let y_format = |v: &f64| match s.unit {
        "°" => format!("{v:.0}°"),
        "" => format!("{v:.2}"),
        // Heights: a decimal while the axis spans a few metres.
        "m" if plot == Plot::Height && y1 - y0 < 8.0 => format!("{v:.1}"),
        _ => format!("{v:.0}"),
    };
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(TRANSPARENT)
        .bold_line_style(pen.theme.grid)
        .axis_style(pen.theme.foreground)
        .label_style(pen.font.clone())
        .x_labels(8)
        .y_labels(5)
        .x_label_formatter(if laned { &no_label } else { &time_label })
        .y_label_formatter(&y_format);
    if plot == Plot::Heading {
        // Its own grid and labels: whole compass points of the unwrapped heading.
        mesh.disable_y_mesh().y_labels(0);
    }
    mesh.draw()?;
    if let Some((unit, _)) = s.right {
        chart
            .configure_secondary_axes()
            .axis_style(pen.theme.foreground)
            .label_style(pen.font.clone())
            .y_labels(5)
            .y_label_formatter(&|v| match unit {
                "°" => format!("{v:.0}°"),
                "floor" => floor_tick(v),
                _ => format!("{v:.2}"),
            })
            .draw()?;
    }
    Ok(chart)
}

/// Draws a plot's own series on its chart.
fn draw_lines<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &mut PlotChart<'_, DB>,
    s: &PlotSeries,
    step_lines: bool,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    match &s.lines {
        Lines::Accel(l) => draw_accel(chart, l, &s.steps, step_lines, pen),
        Lines::Sigma(l) => draw_sigma(chart, l, pen),
        Lines::Height(h, at) => draw_height(chart, h, at, step_lines, pen),
        Lines::Heading(l) => draw_heading(area, chart, l, pen),
        Lines::Steps(v) => draw_steps(chart, v, pen),
        Lines::Gnss(l) => draw_gnss(chart, l, pen),
        Lines::Fusion(f) => draw_fusion(chart, f, pen),
    }
}

/// The steps (lines across the plot, or ticks along its top), the true steps (ticks along its
/// bottom) and the vertical acceleration.
fn draw_accel<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    l: &AccelLines,
    steps: &[f64],
    step_lines: bool,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (y0, y1) = pen.y;
    let tick = 0.1 * (y1 - y0);
    let from = if step_lines { y0 } else { y1 - tick };
    chart.draw_series(
        steps
            .iter()
            .map(|&t| PathElement::new(vec![(t, from), (t, y1)], pen.line(pen.theme.end, 1.0))),
    )?;
    chart.draw_series(l.truth.iter().map(|&t| {
        PathElement::new(
            vec![(t, y0), (t, y0 + tick)],
            pen.line(pen.theme.reference, 2.0),
        )
    }))?;
    draw_signal(chart, &l.signal, pen)?;
    Ok(())
}

/// A signal's runs (a gap breaks the line) in the track's colour at the signal's width.
fn draw_signal<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    runs: &[Vec<(f64, f64)>],
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    for run in runs {
        chart.draw_series(LineSeries::new(
            run.clone(),
            pen.line(pen.theme.track, pen.signal_w),
        ))?;
    }
    Ok(())
}

/// The activity as a band along the bottom (none while still), the thresholds and σ.
fn draw_sigma<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    l: &SigmaLines,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), (y0, y1)) = (pen.x, pen.y);
    let band = 0.08 * (y1 - y0);
    chart.draw_series(l.activity.iter().filter_map(|&(t, w, act)| {
        let c = activity_colour(act, pen.theme)?;
        Some(Rectangle::new([(t, y0), (t + w, y0 + band)], c.filled()))
    }))?;
    for (v, c) in [
        (l.thresholds.0, pen.theme.start),
        (l.thresholds.1, pen.theme.end),
    ] {
        chart.draw_series(LineSeries::new([(x0, v), (x1, v)], pen.line(c, 1.0)))?;
    }
    draw_signal(chart, &l.signal, pen)?;
    Ok(())
}

/// The heading's own grid of compass points, the device's heading (dots: it jumps where a line
/// would draw a bar), the single steps, the two-step average, and the band of each step's
/// carrying mode with a grey strip above it where its heading followed the gyroscope.
fn draw_heading<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &mut PlotChart<'_, DB>,
    l: &HeadingLines,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), (y0, y1)) = (pen.x, pen.y);
    let (h, theme) = (&l.headings, pen.theme);
    let base = area.get_base_pixel();
    for g in heading::grid(y0, y1) {
        chart.draw_series(LineSeries::new(
            [(x0, g), (x1, g)],
            pen.line(theme.grid, 1.0),
        ))?;
        let (x, y) = chart.backend_coord(&(x0, g));
        area.draw(&Text::new(
            heading::grid_label(g, y0, y1),
            (x - base.0 - pen.px(4.0) as i32, y - base.1),
            pen.font.pos(Pos::new(HPos::Right, VPos::Center)),
        ))?;
    }
    chart.draw_series(
        h.device
            .iter()
            .flatten()
            .filter(|p| p.1 >= y0 && p.1 <= y1)
            .map(|&p| Circle::new(p, pen.px(0.8), theme.reference.filled())),
    )?;
    chart.draw_series(
        h.single
            .iter()
            .map(|&p| Circle::new(p, pen.px(2.0), theme.gnss.filled())),
    )?;
    for run in &h.line {
        chart.draw_series(LineSeries::new(run.clone(), pen.line(theme.track, 2.0)))?;
    }
    let band = 0.06 * (y1 - y0);
    chart.draw_series(l.periods.iter().filter_map(|&((a, b), carry, _)| {
        let c = carry_colour(carry?, theme);
        Some(Rectangle::new([(a, y0), (b, y0 + band)], c.filled()))
    }))?;
    chart.draw_series(l.periods.iter().filter(|p| p.2).map(|&((a, b), _, _)| {
        Rectangle::new(
            [(a, y0 + 1.2 * band), (b, y0 + 2.0 * band)],
            theme.reference.filled(),
        )
    }))?;
    Ok(())
}

/// The zero line, the floors' staircase (right axis), the height and each step's height where
/// the steps are far enough apart to be told apart.
fn draw_height<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    h: &HeightSeries,
    at_steps: &[(f64, f64)],
    step_lines: bool,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x0, x1) = pen.x;
    let theme = pen.theme;
    chart.draw_series(LineSeries::new(
        [(x0, 0.0), (x1, 0.0)],
        pen.line(theme.grid, 1.0),
    ))?;
    chart.draw_secondary_series(LineSeries::new(
        h.floor.iter().copied(),
        pen.line(theme.gnss, 2.0),
    ))?;
    draw_signal(chart, &h.height, pen)?;
    if step_lines {
        chart.draw_series(
            at_steps
                .iter()
                .map(|&p| Circle::new(p, pen.px(1.5), theme.track.filled())),
        )?;
    }
    Ok(())
}

/// Each step's frequency (left axis) and length (right axis), as dots.
fn draw_steps<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    steps: &[(f64, f64, f64)],
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart.draw_series(
        steps
            .iter()
            .map(|s| Circle::new((s.0, s.1), pen.px(2.0), pen.theme.track.filled())),
    )?;
    chart.draw_secondary_series(
        steps
            .iter()
            .map(|s| Circle::new((s.0, s.2), pen.px(2.0), pen.theme.gnss.filled())),
    )?;
    Ok(())
}

/// The fixes' accuracy (dots) and the innovations' lengths (rings), cut at the top.
fn draw_gnss<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    l: &GnssLines,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let y1 = pen.y.1;
    chart.draw_series(
        l.fixes
            .iter()
            .map(|&(t, m)| Circle::new((t, m.min(y1)), pen.px(2.0), pen.theme.gnss.filled())),
    )?;
    chart.draw_series(
        l.innovations
            .iter()
            .map(|&(t, m)| Circle::new((t, m.min(y1)), pen.px(3.0), pen.line(pen.theme.pdr, 1.0))),
    )?;
    Ok(())
}

/// The ±1σ bands under the values (faint, each in its value's colour, edged so that a narrow
/// one still shows beside its line), the neutral scale, the scale and the corrections.
fn draw_fusion<DB: DrawingBackend>(
    chart: &mut PlotChart<'_, DB>,
    f: &FusionSeries,
    pen: &Pen<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), theme) = (pen.x, pen.theme);
    let edge = |c: RGBColor| ShapeStyle::from(&c.mix(0.6)).stroke_width(pen.px(1.0));
    chart.draw_series([Polygon::new(f.scale_band(), theme.track.mix(0.25).filled())])?;
    let [up, down] = f.scale_edges();
    chart.draw_series([up, down].map(|e| PathElement::new(e, edge(theme.track))))?;
    chart.draw_secondary_series([Polygon::new(
        f.correction_band(),
        theme.gnss.mix(0.3).filled(),
    )])?;
    let [up, down] = f.correction_edges();
    chart.draw_secondary_series([up, down].map(|e| PathElement::new(e, edge(theme.gnss))))?;
    chart.draw_series(LineSeries::new(
        [(x0, 1.0), (x1, 1.0)],
        pen.line(theme.grid, 1.0),
    ))?;
    chart.draw_series(LineSeries::new(
        f.scale.iter().map(|p| (p.0, p.1)),
        pen.line(theme.track, 1.5),
    ))?;
    chart.draw_secondary_series(
        f.correction
            .iter()
            .map(|p| Circle::new((p.0, p.1), pen.px(1.5), theme.gnss.filled())),
    )?;
    Ok(())
}

/// The PLL's lane under the acceleration: its own ±1 scale, the step lines when they are far
/// enough apart (a step is where cos φ crosses from − to +), the wave or its band, the cursor,
/// and the time axis of the whole plot. Returns the lane's bottom row.
fn draw_pll_lane<DB: DrawingBackend>(
    lane: &DrawingArea<DB, Shift>,
    wave: &PllLane,
    steps: &[f64],
    step_lines: bool,
    cursor: Option<f64>,
    pen: &Pen<'_>,
) -> Result<i32, DrawingAreaErrorKind<DB::ErrorType>> {
    let ((x0, x1), theme) = (pen.x, pen.theme);
    let mut pll = ChartBuilder::on(lane)
        .margin(pen.px(6.0))
        .margin_top(pen.px(2.0))
        .x_label_area_size(pen.px(22.0))
        .y_label_area_size(pen.px(40.0))
        .right_y_label_area_size(pen.px(40.0))
        .build_cartesian_2d(x0..x1, -1.6..1.6)?;
    pll.configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(pen.font.clone())
        .x_labels(8)
        .y_labels(3)
        .x_label_formatter(&time_label(x1 - x0))
        .y_label_formatter(&crate::plot::scope::pll_lane_label)
        .draw()?;
    if step_lines {
        pll.draw_series(
            steps
                .iter()
                .map(|&t| PathElement::new(vec![(t, -1.6), (t, 1.6)], pen.line(theme.end, 1.0))),
        )?;
    }
    match wave {
        // Over a long span the wave cannot be followed: a faint band shows where the PLL ran
        // and how far it swung, and lets the step lines show through.
        PllLane::Band(w, columns) => {
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
        PllLane::Runs(runs) => {
            for run in runs {
                pll.draw_series(LineSeries::new(run.clone(), pen.line(theme.gnss, 1.0)))?;
            }
        }
    }
    if let Some(c) = cursor {
        pll.draw_series([PathElement::new(
            vec![(c, -1.6), (c, 1.6)],
            pen.line(theme.foreground, 1.0),
        )])?;
    }
    Ok(pll.plotting_area().get_pixel_range().1.end)
}
