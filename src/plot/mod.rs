//! Drawing, generic over the plotters [`DrawingBackend`], so the same code draws on a browser
//! canvas and, in tests, into a bitmap.

pub mod upload;

use crate::engine::pipeline::StepRecord;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Colours of one scheme.
#[derive(Debug, Clone, Copy)]
pub struct Theme {
    /// Background.
    pub background: RGBColor,
    /// Text, axes and the north arrow.
    pub foreground: RGBColor,
    /// Grid lines.
    pub grid: RGBColor,
    /// The estimated track.
    pub track: RGBColor,
    /// The reference (true) path.
    pub reference: RGBColor,
    /// Start mark.
    pub start: RGBColor,
    /// End mark.
    pub end: RGBColor,
    /// GNSS fixes.
    pub gnss: RGBColor,
    /// The PDR-only track beside a fused one.
    pub pdr: RGBColor,
    /// The smoothed track.
    pub smoothed: RGBColor,
}

impl Theme {
    /// Light scheme.
    pub const LIGHT: Theme = Theme {
        background: RGBColor(0xfb, 0xfb, 0xf8),
        foreground: RGBColor(0x22, 0x26, 0x2e),
        grid: RGBColor(0xe3, 0xe4, 0xe0),
        track: RGBColor(0x1f, 0x6f, 0xd1),
        reference: RGBColor(0xa8, 0xab, 0xb2),
        start: RGBColor(0x1a, 0x9e, 0x55),
        end: RGBColor(0xd1, 0x3b, 0x2f),
        gnss: RGBColor(0xe0, 0x8a, 0x1e),
        pdr: RGBColor(0x9b, 0x59, 0xb6),
        smoothed: RGBColor(0x13, 0x9c, 0x8a),
    };
    /// Dark scheme.
    pub const DARK: Theme = Theme {
        background: RGBColor(0x15, 0x18, 0x1d),
        foreground: RGBColor(0xe6, 0xe8, 0xeb),
        grid: RGBColor(0x2a, 0x2f, 0x37),
        track: RGBColor(0x5a, 0xa9, 0xff),
        reference: RGBColor(0x5d, 0x63, 0x6d),
        start: RGBColor(0x3c, 0xc7, 0x7a),
        end: RGBColor(0xff, 0x6b, 0x5e),
        gnss: RGBColor(0xf0, 0xa4, 0x3a),
        pdr: RGBColor(0xc3, 0x8b, 0xe0),
        smoothed: RGBColor(0x3f, 0xd0, 0xbb),
    };
}

/// The bounds (min_e, max_e, min_n, max_n) of the points; infinite when there are none.
fn bounds(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64, f64, f64) {
    points.fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(x0, x1, y0, y1), (x, y)| (x0.min(x), x1.max(x), y0.min(y), y1.max(y)),
    )
}

/// An axis label with `decimals` decimals, never "-0".
pub(crate) fn tick(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(abs) if abs.bytes().all(|b| b == b'0' || b == b'.') => abs.to_string(),
        _ => s,
    }
}

/// Widens bounds on one axis, about their centre, so that one metre spans the same number of
/// pixels on both axes of a `w` × `h` area.
fn to_equal_scale((x0, x1, y0, y1): (f64, f64, f64, f64), w: f64, h: f64) -> (f64, f64, f64, f64) {
    let (sx, sy) = ((x1 - x0) / w, (y1 - y0) / h);
    if sx > sy {
        let grow = (sx * h - (y1 - y0)) / 2.0;
        (x0, x1, y0 - grow, y1 + grow)
    } else {
        let grow = (sy * w - (x1 - x0)) / 2.0;
        (x0 - grow, x1 + grow, y0, y1)
    }
}

/// Bounds (min_e, max_e, min_n, max_n) of the points with a margin, widened so that one metre
/// spans the same number of pixels on both axes.
fn equal_aspect(points: impl Iterator<Item = (f64, f64)>, w: f64, h: f64) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = bounds(points);
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (-10.0, 10.0, -10.0, 10.0);
    }
    // At least 10 m across (a walk's first step, or a log whose steps have no heading), so the
    // labels and the scale bar stay readable.
    let widen = |a: f64, b: f64| {
        let grow = (10.0 - (b - a)).max(0.0) / 2.0;
        (a - grow, b + grow)
    };
    ((x0, x1), (y0, y1)) = (widen(x0, x1), widen(y0, y1));
    let pad = 0.06 * (x1 - x0).max(y1 - y0);
    to_equal_scale((x0 - pad, x1 + pad, y0 - pad, y1 + pad), w, h)
}

/// Bounds of exactly the given corner points, widened on one axis to an equal scale.
fn equal_aspect_exact(
    points: impl Iterator<Item = (f64, f64)>,
    w: f64,
    h: f64,
) -> (f64, f64, f64, f64) {
    let (x0, x1, y0, y1) = bounds(points);
    if !(x1 > x0 && y1 > y0) {
        return equal_aspect([(x0, y0), (x1, y1)].into_iter(), w, h);
    }
    to_equal_scale((x0, x1, y0, y1), w, h)
}

/// A "nice" scale-bar length (1, 2 or 5 × 10^k m) close to a quarter of `span` metres.
pub fn scale_bar_length(span: f64) -> f64 {
    let target = span / 4.0;
    let k = libm::pow(10.0, libm::log10(target).floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * k)
        .find(|&l| l <= target)
        .unwrap_or(k)
}

pub(crate) type MapChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Fills the area and sets up a map in metres (east right, north up, equal scale) fitting
/// `points`, with its grid and axis labels.
fn map_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    points: impl Iterator<Item = (f64, f64)>,
    theme: &Theme,
    scale: f64,
) -> Result<MapChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    map_chart_in(area, points, None, theme, scale)
}

/// [`map_chart`] showing `bounds` (min_e, max_e, min_n, max_n; widened to an equal scale)
/// instead of fitting the points, when given: a zoomed or panned view.
pub(crate) fn map_chart_in<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    points: impl Iterator<Item = (f64, f64)>,
    bounds: Option<(f64, f64, f64, f64)>,
    theme: &Theme,
    scale: f64,
) -> Result<MapChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    area.fill(&theme.background)?;
    let (w, h) = area.dim_in_pixel();
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let font = ("sans-serif", 13.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let label_area = px(34.0);
    let plot_w = (w as f64 - label_area as f64 - px(12.0) as f64).max(10.0);
    let plot_h = (h as f64 - label_area as f64 - px(12.0) as f64).max(10.0);
    let (x0, x1, y0, y1) = match bounds {
        Some((a, b, c, d)) => equal_aspect_exact([(a, c), (b, d)].into_iter(), plot_w, plot_h),
        None => equal_aspect(points, plot_w, plot_h),
    };
    let mut chart = ChartBuilder::on(area)
        .margin(px(12.0))
        .x_label_area_size(label_area)
        .y_label_area_size(label_area)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font)
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| tick(*v, 0))
        .y_label_formatter(&|v| tick(*v, 0))
        .draw()?;
    Ok(chart)
}

/// A north arrow (top right) and a scale bar (bottom left) over the map, in pixel space.
pub(crate) fn north_and_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &MapChart<'_, DB>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let font = ("sans-serif", 13.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let plot_area = chart.plotting_area();
    let (px_range_x, px_range_y) = plot_area.get_pixel_range();
    let right = px_range_x.end - px(26.0) as i32;
    let top = px_range_y.start + px(14.0) as i32;
    let len = px(28.0) as i32;
    let fg = ShapeStyle::from(&theme.foreground).stroke_width(px(2.0));
    area.draw(&PathElement::new(
        vec![(right, top + len), (right, top)],
        fg,
    ))?;
    area.draw(&Polygon::new(
        vec![
            (right, top - px(4.0) as i32),
            (right - px(6.0) as i32, top + px(8.0) as i32),
            (right + px(6.0) as i32, top + px(8.0) as i32),
        ],
        theme.foreground.filled(),
    ))?;
    area.draw(&Text::new(
        "N",
        (right - px(5.0) as i32, top + len + px(4.0) as i32),
        font.clone(),
    ))?;
    let x = plot_area.get_x_range();
    let span = x.end - x.start;
    let bar_m = scale_bar_length(span);
    let bar_px = (bar_m / span * (px_range_x.end - px_range_x.start) as f64).round() as i32;
    let bx = px_range_x.start + px(12.0) as i32;
    let by = px_range_y.end - px(16.0) as i32;
    area.draw(&PathElement::new(
        vec![
            (bx, by - px(5.0) as i32),
            (bx, by),
            (bx + bar_px, by),
            (bx + bar_px, by - px(5.0) as i32),
        ],
        fg,
    ))?;
    area.draw(&Text::new(
        format!("{bar_m:.0} m"),
        (bx, by - px(22.0) as i32),
        font,
    ))?;
    Ok(())
}

/// Start and end marks of a path.
pub(crate) fn start_end<DB: DrawingBackend>(
    chart: &mut MapChart<'_, DB>,
    path: &[(f64, f64)],
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let r = (6.0 * scale).round() as u32;
    if let (Some(&a), Some(&b)) = (path.first(), path.last()) {
        chart.draw_series([
            Circle::new(a, r, theme.start.filled()),
            Circle::new(b, r, theme.end.filled()),
        ])?;
    }
    Ok(())
}

/// Draws the track in metres (east right, north up, equal scale) with start and end marks, the
/// optional reference path, a north arrow and a scale bar. `scale` is the device pixel ratio:
/// line widths and fonts are multiplied by it so the drawing is sharp and readable on any screen.
pub fn draw_track<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    track: &[StepRecord],
    reference: Option<&[(f64, f64)]>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let path: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain(track.iter().map(|s| (s.east_m, s.north_m)))
        .collect();
    let pts = path
        .iter()
        .copied()
        .chain(reference.unwrap_or(&[]).iter().copied());
    let mut chart = map_chart(area, pts, theme, scale)?;
    if let Some(r) = reference {
        chart.draw_series(LineSeries::new(
            r.iter().copied(),
            ShapeStyle::from(&theme.reference).stroke_width(px(2.0)),
        ))?;
    }
    chart.draw_series(LineSeries::new(
        path.iter().copied(),
        ShapeStyle::from(&theme.track).stroke_width(px(3.0)),
    ))?;
    start_end(&mut chart, &path, theme, scale)?;
    north_and_scale(area, &chart, theme, scale)
}

/// What [`draw_fusion`] draws: positions in metres in one local frame.
pub struct FusionView<'a> {
    /// The true path, when known.
    pub truth: Option<&'a [(f64, f64)]>,
    /// GNSS fixes: east, north, reported accuracy (68 % radius), m.
    pub fixes: &'a [(f64, f64, f64)],
    /// The PDR-only track.
    pub pdr: &'a [(f64, f64)],
    /// The fused track.
    pub fused: &'a [(f64, f64)],
    /// The smoothed track.
    pub smoothed: &'a [(f64, f64)],
}

/// Draws GNSS fixes (dots, with the accuracy circle of every fifth), the PDR-only, fused and
/// smoothed tracks and the true path, with a legend, a north arrow and a scale bar.
pub fn draw_fusion<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    view: &FusionView<'_>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    // Fit the tracks and the truth; far outliers among the fixes may fall outside.
    let pts = view
        .fused
        .iter()
        .chain(view.smoothed)
        .chain(view.pdr)
        .chain(view.truth.unwrap_or(&[]))
        .copied();
    let mut chart = map_chart(area, pts, theme, scale)?;
    let to_px = |chart: &MapChart<'_, DB>, p: (f64, f64)| chart.backend_coord(&p);
    let gnss = ShapeStyle::from(&theme.gnss.mix(0.35)).stroke_width(px(1.0));
    let circles: Vec<Circle<(f64, f64), u32>> = view
        .fixes
        .iter()
        .step_by(5)
        .map(|&(e, n, acc)| {
            let a = to_px(&chart, (e, n));
            let b = to_px(&chart, (e + acc, n));
            Circle::new((e, n), (b.0 - a.0).unsigned_abs().max(1), gnss)
        })
        .collect();
    chart.draw_series(circles)?;
    chart.draw_series(
        view.fixes
            .iter()
            .map(|&(e, n, _)| Circle::new((e, n), px(2.0), theme.gnss.filled())),
    )?;
    for (path, colour, width) in [
        (view.pdr, theme.pdr, 2.0),
        (view.smoothed, theme.smoothed, 2.5),
        (view.fused, theme.track, 2.5),
    ] {
        chart.draw_series(LineSeries::new(
            path.iter().copied(),
            ShapeStyle::from(&colour).stroke_width(px(width)),
        ))?;
    }
    // The truth last and thin, so that the tracks' agreement with it shows.
    if let Some(t) = view.truth {
        chart.draw_series(LineSeries::new(
            t.iter().copied(),
            ShapeStyle::from(&theme.reference).stroke_width(px(1.0)),
        ))?;
    }
    start_end(&mut chart, view.fused, theme, scale)?;
    let mut entries = vec![
        ("fused", Mark::Line(theme.track)),
        ("smoothed", Mark::Line(theme.smoothed)),
        ("PDR only", Mark::Line(theme.pdr)),
        ("GNSS fixes", Mark::Dot(theme.gnss)),
    ];
    if view.truth.is_some() {
        entries.push(("true path", Mark::Line(theme.reference)));
    }
    legend(area, &chart, &entries, theme, scale)?;
    north_and_scale(area, &chart, theme, scale)
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Mark {
    Line(RGBColor),
    Dot(RGBColor),
    Ring(RGBColor),
}

/// A legend in the top-left corner of the chart's plotting area.
pub(crate) fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &MapChart<'_, DB>,
    entries: &[(&str, Mark)],
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as i32;
    let font = ("sans-serif", 13.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    let (x, mut y) = (rx.start + px(10.0), ry.start + px(8.0));
    let row = px(18.0);
    area.draw(&Rectangle::new(
        [
            (x - px(6.0), y - px(4.0)),
            (x + px(112.0), y + row * entries.len() as i32 + px(2.0)),
        ],
        theme.background.mix(0.85).filled(),
    ))?;
    for &(label, mark) in entries {
        let mid = y + row / 2;
        let at = (x + px(10.0), mid);
        match mark {
            Mark::Dot(c) => area.draw(&Circle::new(at, px(3.0) as u32, c.filled()))?,
            Mark::Ring(c) => area.draw(&Circle::new(
                at,
                px(5.0) as u32,
                ShapeStyle::from(&c).stroke_width(px(2.0) as u32),
            ))?,
            Mark::Line(c) => area.draw(&PathElement::new(
                vec![(x, mid), (x + px(22.0), mid)],
                ShapeStyle::from(&c).stroke_width(px(3.0) as u32),
            ))?,
        }
        area.draw(&Text::new(
            label,
            (x + px(30.0), mid - px(7.0)),
            font.clone(),
        ))?;
        y += row;
    }
    Ok(())
}

/// What [`draw_live`] draws: positions in metres in one local frame (the first fix's when
/// there are fixes, else the walk's start).
pub struct LiveView<'a> {
    /// The PDR track, from the start.
    pub pdr: &'a [(f64, f64)],
    /// The fused track (empty without fixes).
    pub fused: &'a [(f64, f64)],
    /// The smoothed track: the walk so far, each fix's correction carried back.
    pub smoothed: &'a [(f64, f64)],
    /// GNSS fixes as received: east, north, reported accuracy, m.
    pub fixes: &'a [(f64, f64, f64)],
    /// Where the input stopped (page hidden, sensors paused).
    pub gaps: &'a [(f64, f64)],
    /// The current heading, rad from north, drawn as an arrow at the current position.
    pub heading_rad: Option<f64>,
}

/// The live map: the track so far with its start, the current position and heading, every fix
/// with its accuracy circle, the fused and smoothed tracks, gaps, a legend, a north arrow and a
/// scale bar.
pub fn draw_live<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    view: &LiveView<'_>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let fused = !view.fused.is_empty();
    // The main line: the fused track when there is one.
    let main = if fused { view.fused } else { view.pdr };
    let pts = view
        .pdr
        .iter()
        .chain(view.fused)
        .chain(view.smoothed)
        .copied()
        .chain(view.fixes.iter().map(|&(e, n, _)| (e, n)));
    let mut chart = map_chart(area, pts, theme, scale)?;
    let ring = ShapeStyle::from(&theme.gnss.mix(0.45)).stroke_width(px(1.0));
    // The newest fixes' circles (a long walk has thousands).
    let circles: Vec<Circle<(f64, f64), u32>> = view
        .fixes
        .iter()
        .rev()
        .take(300)
        .map(|&(e, n, acc)| {
            let a = chart.backend_coord(&(e, n));
            let b = chart.backend_coord(&(e + acc, n));
            Circle::new((e, n), (b.0 - a.0).unsigned_abs().max(1), ring)
        })
        .collect();
    chart.draw_series(circles)?;
    chart.draw_series(
        view.fixes
            .iter()
            .map(|&(e, n, _)| Circle::new((e, n), px(2.5), theme.gnss.filled())),
    )?;
    if fused {
        chart.draw_series(LineSeries::new(
            view.pdr.iter().copied(),
            ShapeStyle::from(&theme.pdr).stroke_width(px(2.0)),
        ))?;
    }
    if !view.smoothed.is_empty() {
        chart.draw_series(LineSeries::new(
            view.smoothed.iter().copied(),
            ShapeStyle::from(&theme.smoothed).stroke_width(px(2.5)),
        ))?;
    }
    chart.draw_series(LineSeries::new(
        main.iter().copied(),
        ShapeStyle::from(&theme.track).stroke_width(px(3.0)),
    ))?;
    let gap_style = ShapeStyle::from(&theme.end).stroke_width(px(2.0));
    chart.draw_series(
        view.gaps
            .iter()
            .map(|&p| Circle::new(p, px(7.0), gap_style)),
    )?;
    if let Some(&a) = main.first() {
        chart.draw_series([Circle::new(a, px(6.0), theme.start.filled())])?;
    }
    if let Some(&b) = main.last() {
        let at = chart.backend_coord(&b);
        if let Some(h) = view.heading_rad {
            let len = f64::from(px(22.0));
            let tip = (
                at.0 + (len * libm::sin(h)).round() as i32,
                at.1 - (len * libm::cos(h)).round() as i32,
            );
            area.draw(&PathElement::new(
                vec![at, tip],
                ShapeStyle::from(&theme.end).stroke_width(px(3.0)),
            ))?;
        }
        area.draw(&Circle::new(at, px(7.0), theme.end.filled()))?;
        area.draw(&Circle::new(
            at,
            px(7.0),
            ShapeStyle::from(&theme.background).stroke_width(px(2.0)),
        ))?;
    }
    let mut entries = Vec::new();
    if fused {
        entries.push(("fused", Mark::Line(theme.track)));
        if !view.smoothed.is_empty() {
            entries.push(("smoothed", Mark::Line(theme.smoothed)));
        }
        entries.push(("PDR only", Mark::Line(theme.pdr)));
    }
    if !view.fixes.is_empty() {
        entries.push(("GNSS fixes", Mark::Dot(theme.gnss)));
    }
    if !view.gaps.is_empty() {
        entries.push(("gap in input", Mark::Ring(theme.end)));
    }
    if !entries.is_empty() {
        legend(area, &chart, &entries, theme, scale)?;
    }
    north_and_scale(area, &chart, theme, scale)
}

/// A sample of the scrolling view: time (s), vertical acceleration (m/s²), PLL output.
pub type ScopePoint = (f64, f64, Option<f64>);

/// The scrolling view of the last `span_s` seconds up to `now`: vertical acceleration (left
/// axis, m/s²), the PLL output cos φ (right axis) and the detected steps (vertical marks).
/// Samples further apart than 0.5 s (a gap) are not joined.
pub fn draw_scope<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    samples: &[ScopePoint],
    steps: &[f64],
    now: f64,
    span_s: f64,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    area.fill(&theme.background)?;
    let font = ("sans-serif", 12.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let amp = samples
        .iter()
        .map(|s| s.1.abs())
        .fold(2.0_f64, f64::max)
        .min(40.0)
        * 1.1;
    let mut chart = ChartBuilder::on(area)
        .margin(px(8.0))
        .margin_top(px(22.0))
        .x_label_area_size(px(24.0))
        .y_label_area_size(px(34.0))
        .right_y_label_area_size(px(30.0))
        .build_cartesian_2d(-span_s..0.0, -amp..amp)?
        .set_secondary_coord(-span_s..0.0, -1.25..1.25);
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(6)
        .y_labels(5)
        .x_label_formatter(&|v| format!("{v:.0} s"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    chart
        .configure_secondary_axes()
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .y_labels(3)
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    let rel = |t: f64| t - now;
    let visible = |t: f64| rel(t) >= -span_s && rel(t) <= 0.0;
    let step_style = ShapeStyle::from(&theme.end).stroke_width(px(1.5));
    chart.draw_series(
        steps
            .iter()
            .filter(|&&t| visible(t))
            .map(|&t| PathElement::new(vec![(rel(t), -amp), (rel(t), amp)], step_style)),
    )?;
    // Runs of samples without a gap.
    let mut runs: Vec<&[ScopePoint]> = Vec::new();
    let mut from = 0;
    for i in 1..=samples.len() {
        if i == samples.len() || samples[i].0 - samples[i - 1].0 > 0.5 {
            runs.push(&samples[from..i]);
            from = i;
        }
    }
    let pll_style = ShapeStyle::from(&theme.gnss).stroke_width(px(1.5));
    let acc_style = ShapeStyle::from(&theme.track).stroke_width(px(2.0));
    for run in runs {
        let pll: Vec<(f64, f64)> = run
            .iter()
            .filter(|s| visible(s.0))
            .filter_map(|s| s.2.map(|p| (rel(s.0), p)))
            .collect();
        chart.draw_secondary_series(LineSeries::new(pll, pll_style))?;
        chart.draw_series(LineSeries::new(
            run.iter().filter(|s| visible(s.0)).map(|s| (rel(s.0), s.1)),
            acc_style,
        ))?;
    }
    // Key, above the plot.
    let (x0, y0) = (px(40.0) as i32, px(4.0) as i32);
    let mut x = x0;
    for (label, colour) in [
        ("vertical acc., m/s²", theme.track),
        ("PLL cos φ, right", theme.gnss),
        ("steps", theme.end),
    ] {
        area.draw(&PathElement::new(
            vec![
                (x, y0 + px(8.0) as i32),
                (x + px(16.0) as i32, y0 + px(8.0) as i32),
            ],
            ShapeStyle::from(&colour).stroke_width(px(3.0)),
        ))?;
        area.draw(&Text::new(label, (x + px(20.0) as i32, y0), font.clone()))?;
        let (w, _) = area.estimate_text_size(label, &font)?;
        x += px(32.0) as i32 + w as i32;
    }
    Ok(())
}

/// The calibration chart of one band: the walks' points (f̄, SL̄), the line (the fitted one, or
/// the profile's `line` when there is no fit) and, below, each point's residual in cm, with a
/// title giving the line, R² and the standard errors.
pub fn draw_calibration<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    fit: &crate::engine::calibration::BandFit,
    line: &crate::engine::step_length::Line,
    title: &str,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    area.fill(&theme.background)?;
    let font = ("sans-serif", 12.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let (a, b) = fit.fit.as_ref().map_or((line.a, line.b), |f| (f.a, f.b));
    let heading = match (&fit.fit, fit.se) {
        (Some(f), Some((sa, sb))) => format!(
            "{title}: SL = {a:.3}(±{sa:.3})·f {b:+.3}(±{sb:.3}) m, R² {:.3}",
            f.r2
        ),
        (Some(f), None) => format!("{title}: SL = {a:.3}·f {b:+.3} m, R² {:.3}", f.r2),
        _ => format!("{title}: SL = {a:.3}·f {b:+.3} m (slope kept)"),
    };
    area.draw(&Text::new(
        heading,
        (px(8.0) as i32, px(6.0) as i32),
        font.clone(),
    ))?;
    let (top, bottom) = area
        .margin(px(24.0), 0, 0, 0)
        .split_vertically((area.dim_in_pixel().1 as f64 * 0.62) as u32);
    let (f_lo, f_hi) = fit
        .points
        .iter()
        .fold((line.f_lo, line.f_hi), |(lo, hi), p| {
            (lo.min(p.0 - 0.1), hi.max(p.0 + 0.1))
        });
    let sl = |f: f64| a * f + b;
    let (mut y_lo, mut y_hi) = fit.points.iter().fold(
        (sl(f_lo).min(sl(f_hi)), sl(f_lo).max(sl(f_hi))),
        |(lo, hi), p| (lo.min(p.1), hi.max(p.1)),
    );
    let pad = 0.1 * (y_hi - y_lo).max(0.1);
    (y_lo, y_hi) = (y_lo - pad, y_hi + pad);
    let mut chart = ChartBuilder::on(&top)
        .margin(px(8.0))
        .margin_right(px(24.0))
        .x_label_area_size(px(22.0))
        .y_label_area_size(px(44.0))
        .build_cartesian_2d(f_lo..f_hi, y_lo..y_hi)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(6)
        .y_labels(5)
        .x_label_formatter(&|v| format!("{v:.1} Hz"))
        .y_label_formatter(&|v| format!("{v:.2} m"))
        .draw()?;
    chart.draw_series(LineSeries::new(
        [(f_lo, sl(f_lo)), (f_hi, sl(f_hi))],
        ShapeStyle::from(&theme.track).stroke_width(px(2.5)),
    ))?;
    chart.draw_series(
        fit.points
            .iter()
            .map(|&p| Circle::new(p, px(5.0), theme.gnss.filled())),
    )?;
    // Residuals, cm.
    let res: Vec<f64> = fit.points.iter().map(|p| (p.1 - sl(p.0)) * 100.0).collect();
    let r_max = res.iter().fold(2.0_f64, |m, r| m.max(r.abs())) * 1.2;
    let mut rc = ChartBuilder::on(&bottom)
        .margin(px(8.0))
        .margin_right(px(24.0))
        .x_label_area_size(px(8.0))
        .y_label_area_size(px(44.0))
        .build_cartesian_2d(f_lo..f_hi, -r_max..r_max)?;
    rc.configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font)
        .x_labels(0)
        .y_labels(3)
        .y_label_formatter(&|v| format!("{v:.0} cm"))
        .draw()?;
    let bar = ShapeStyle::from(&theme.end).stroke_width(px(4.0));
    rc.draw_series(
        fit.points
            .iter()
            .zip(&res)
            .map(|(p, r)| PathElement::new(vec![(p.0, 0.0), (p.0, *r)], bar)),
    )?;
    rc.draw_series(LineSeries::new(
        [(f_lo, 0.0), (f_hi, 0.0)],
        ShapeStyle::from(&theme.foreground).stroke_width(px(1.0)),
    ))?;
    Ok(())
}

/// An in-memory raster for the drawing tests.
#[cfg(test)]
pub(crate) mod raster {
    use plotters::prelude::*;

    /// The raster's pixels, shared with the test that reads them.
    pub(crate) type Pixels = std::rc::Rc<std::cell::RefCell<Vec<(u8, u8, u8)>>>;
    use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};

    /// An in-memory RGB raster that ignores text (no font engine natively).
    pub(crate) struct Raster {
        pub(crate) w: u32,
        pub(crate) h: u32,
        pub(crate) px: Pixels,
    }

    impl DrawingBackend for Raster {
        type ErrorType = std::io::Error;
        fn get_size(&self) -> (u32, u32) {
            (self.w, self.h)
        }
        fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
            Ok(())
        }
        fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
            Ok(())
        }
        fn draw_pixel(
            &mut self,
            p: BackendCoord,
            c: BackendColor,
        ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
            if p.0 >= 0
                && p.1 >= 0
                && (p.0 as u32) < self.w
                && (p.1 as u32) < self.h
                && c.alpha > 0.5
            {
                self.px.borrow_mut()[(p.1 as u32 * self.w + p.0 as u32) as usize] = c.rgb;
            }
            Ok(())
        }
        fn draw_text<S: BackendTextStyle>(
            &mut self,
            _: &str,
            _: &S,
            _: BackendCoord,
        ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
            Ok(())
        }
        fn estimate_text_size<S: BackendTextStyle>(
            &self,
            text: &str,
            _: &S,
        ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
            Ok((7 * text.len() as u32, 13))
        }
    }

    /// A raster of `w` × `h` and its shared pixels.
    #[allow(clippy::type_complexity)]
    pub(crate) fn new(w: u32, h: u32) -> (Raster, Pixels) {
        let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
        (
            Raster {
                w,
                h,
                px: px.clone(),
            },
            px,
        )
    }

    /// Pixels of exactly colour `c`.
    pub(crate) fn count(px: &Pixels, c: RGBColor) -> usize {
        px.borrow()
            .iter()
            .filter(|p| **p == (c.0, c.1, c.2))
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_never_read_minus_zero() {
        assert_eq!(tick(-0.3, 0), "0");
        assert_eq!(tick(-0.04, 1), "0.0");
        assert_eq!(tick(-0.6, 0), "-1");
        assert_eq!(tick(2.25, 1), "2.2");
    }

    #[test]
    fn a_map_of_one_point_spans_ten_metres() {
        let (x0, x1, y0, y1) = equal_aspect([(3.0, 4.0)].into_iter(), 400.0, 300.0);
        assert!(x1 - x0 >= 10.0 && y1 - y0 >= 10.0, "{x0} {x1} {y0} {y1}");
        assert!(((x0 + x1) / 2.0 - 3.0).abs() < 1e-9 && ((y0 + y1) / 2.0 - 4.0).abs() < 1e-9);
    }

    #[test]
    fn scale_bar_is_nice() {
        assert_eq!(scale_bar_length(100.0), 20.0);
        assert_eq!(scale_bar_length(9.0), 2.0);
        assert_eq!(scale_bar_length(1000.0), 200.0);
    }

    use raster::Raster;

    #[test]
    fn draws_the_fusion_demo_with_every_series() {
        let demo = crate::demo::run_fusion_demo();
        let (w, h) = (500u32, 400u32);
        let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
        let area = Raster {
            w,
            h,
            px: px.clone(),
        }
        .into_drawing_area();
        let view = FusionView {
            truth: Some(&demo.truth),
            fixes: &demo.fix_points,
            pdr: &demo.pdr,
            fused: &demo.fused,
            smoothed: &demo.smoothed,
        };
        draw_fusion(&area, &view, &Theme::LIGHT, 1.0).unwrap();
        let px = px.borrow();
        let count = |c: RGBColor| px.iter().filter(|p| **p == (c.0, c.1, c.2)).count();
        let t = Theme::LIGHT;
        for (name, c) in [
            ("fused", t.track),
            ("smoothed", t.smoothed),
            ("pdr", t.pdr),
            ("gnss", t.gnss),
        ] {
            assert!(count(c) > 100, "{name}: {}", count(c));
        }
    }

    #[test]
    fn draws_the_demo_track_with_marks() {
        let demo = crate::demo::run_demo();
        let (w, h) = (400u32, 300u32);
        let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
        let area = Raster {
            w,
            h,
            px: px.clone(),
        }
        .into_drawing_area();
        draw_track(
            &area,
            &demo.track,
            Some(&demo.truth_path),
            &Theme::LIGHT,
            1.0,
        )
        .unwrap();
        let px = px.borrow();
        let count = |c: RGBColor| px.iter().filter(|p| **p == (c.0, c.1, c.2)).count();
        assert!(
            count(Theme::LIGHT.track) > 300,
            "track: {}",
            count(Theme::LIGHT.track)
        );
        assert!(count(Theme::LIGHT.start) > 20 && count(Theme::LIGHT.end) > 20);
        assert!(count(Theme::LIGHT.reference) > 100);
    }

    #[test]
    fn draws_the_live_map_and_scope() {
        use crate::engine::pipeline::Record;
        use crate::live::{browser_events, BrowserEvent, LiveSession, MotionEvent, Platform};
        let sim = crate::sim::scenarios::straight_walk(1.8, 30.0).generate();
        let mut live = LiveSession::new(
            crate::engine::PipelineConfig::default(),
            Platform::Android,
            0.0,
        )
        .unwrap();
        for ev in browser_events(&sim.records, Platform::Android) {
            match ev {
                BrowserEvent::Orientation {
                    t,
                    alpha,
                    beta,
                    gamma,
                } => live.push_orientation(t, alpha, beta, gamma, true),
                BrowserEvent::Motion { t, x, y, z, .. } if !(12e3..16e3).contains(&t) => {
                    live.push_motion(&MotionEvent {
                        time_stamp_ms: t,
                        accel: Some([x, y, z]),
                        rotation_rate_deg_s: None,
                        interval: None,
                    })
                    .unwrap();
                }
                _ => {}
            }
        }
        assert!(sim.records.iter().any(|r| matches!(r, Record::Imu(_))));
        let d = live.map_data();
        assert_eq!(d.gaps.len(), 1, "the 4 s without events is a gap");
        let (w, h) = (400u32, 400u32);
        let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
        let area = Raster {
            w,
            h,
            px: px.clone(),
        }
        .into_drawing_area();
        let view = LiveView {
            pdr: &d.pdr,
            fused: &d.fused,
            smoothed: &d.smoothed,
            fixes: &d.fixes,
            gaps: &d.gaps,
            heading_rad: d.heading_rad,
        };
        draw_live(&area, &view, &Theme::LIGHT, 1.0).unwrap();
        let t = Theme::LIGHT;
        let count = |c: RGBColor| {
            px.borrow()
                .iter()
                .filter(|p| **p == (c.0, c.1, c.2))
                .count()
        };
        assert!(count(t.track) > 200, "track {}", count(t.track));
        assert!(count(t.start) > 20 && count(t.end) > 40);
        let (samples, steps, now) = live.scope_data();
        assert!(steps.len() >= 10 && steps.iter().all(|&s| s > now - 10.0));
        let area = Raster {
            w: 600,
            h: 200,
            px: std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); 600 * 200])),
        };
        let shared = area.px.clone();
        draw_scope(
            &area.into_drawing_area(),
            &samples,
            &steps,
            now,
            10.0,
            &t,
            1.0,
        )
        .unwrap();
        let n = |c: RGBColor| {
            shared
                .borrow()
                .iter()
                .filter(|p| **p == (c.0, c.1, c.2))
                .count()
        };
        assert!(
            n(t.track) > 500 && n(t.gnss) > 300 && n(t.end) > 10 * 100,
            "{} {} {}",
            n(t.track),
            n(t.gnss),
            n(t.end)
        );
    }

    #[test]
    fn draws_the_calibration_chart() {
        use crate::engine::calibration::fit_band;
        let fit = fit_band(&[(1.5, 0.65), (1.8, 0.74), (2.1, 0.83), (2.0, 0.86)]);
        let line = crate::engine::step_length::StepLengthProfile::default().walking;
        let (w, h) = (400u32, 300u32);
        let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
        let area = Raster {
            w,
            h,
            px: px.clone(),
        }
        .into_drawing_area();
        draw_calibration(&area, &fit, &line, "walking", &Theme::LIGHT, 1.0).unwrap();
        let t = Theme::LIGHT;
        let n = |c: RGBColor| {
            px.borrow()
                .iter()
                .filter(|p| **p == (c.0, c.1, c.2))
                .count()
        };
        assert!(n(t.track) > 300, "line {}", n(t.track));
        assert!(n(t.gnss) > 4 * 40, "points {}", n(t.gnss));
        assert!(n(t.end) > 20, "residual bars {}", n(t.end));
    }
}
