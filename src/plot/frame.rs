//! The map frame every map shares: bounds at an equal scale, the chart in metres with its grid,
//! north arrow, scale bar, start and end marks and legend, and [`MapFrame`] (a drawn map's pixels
//! and metres, zoom and pan).
//! May import: the theme; never `web`, `live` or `eval`.

use super::theme::Theme;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

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
pub(super) fn map_chart<'a, DB: DrawingBackend>(
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
    map_chart_over(area, points, bounds, None, theme, scale)
}

/// What is drawn under a map's grid and track, given where the map is (the base map's tiles).
pub(crate) type Underlay<'u, DB> =
    &'u mut dyn FnMut(
        &DrawingArea<DB, Shift>,
        &MapFrame,
    ) -> Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// [`map_chart_in`] with `under` drawn after the background and before the grid.
pub(crate) fn map_chart_over<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    points: impl Iterator<Item = (f64, f64)>,
    bounds: Option<(f64, f64, f64, f64)>,
    under: Option<Underlay<'_, DB>>,
    theme: &Theme,
    scale: f64,
) -> Result<MapChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    area.fill(&theme.background)?;
    let (w, h) = area.dim_in_pixel();
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
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
    if let Some(under) = under {
        under(area, &frame_of(&chart))?;
    }
    axes(&mut chart, true, theme, scale)?;
    Ok(chart)
}

/// A map's axes and their labels, with the grid when `grid`.
fn axes<DB: DrawingBackend>(
    chart: &mut MapChart<'_, DB>,
    grid: bool,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = ("sans-serif", 13.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font)
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| tick(*v, 0))
        .y_label_formatter(&|v| tick(*v, 0));
    if !grid {
        mesh.disable_mesh();
    }
    mesh.draw()
}

/// Masks what the series drew past the plotting area and draws the axes again: plotters does
/// not clip, so a zoomed map's track, or a far fix's accuracy ring, would cover the axes and
/// their labels.
fn mask_margins<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &mut MapChart<'_, DB>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    let (ox, oy) = area.get_base_pixel();
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    let (l, r, t, b) = (rx.start - ox, rx.end - ox, ry.start - oy, ry.end - oy);
    let fill = theme.background.filled();
    for (a, c) in [
        ((0, 0), (w, t - 1)),
        ((0, b), (w, h)),
        ((0, 0), (l - 1, h)),
        ((r, 0), (w, h)),
    ] {
        if a.0 <= c.0 && a.1 <= c.1 {
            area.draw(&Rectangle::new([a, c], fill))?;
        }
    }
    axes(chart, false, theme, scale)
}

/// Where a chart draws: its plotting area in pixels and the metres it shows.
pub(crate) fn frame_of<DB: DrawingBackend>(chart: &MapChart<'_, DB>) -> MapFrame {
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    let (xr, yr) = (
        chart.plotting_area().get_x_range(),
        chart.plotting_area().get_y_range(),
    );
    MapFrame {
        px: (rx.start, rx.end, ry.start, ry.end),
        m: (xr.start, xr.end, yr.start, yr.end),
    }
}

/// Finishes a map once its series are drawn: masks what spilled past the plotting area (see
/// [`mask_margins`]), then a north arrow (top right) and a scale bar (bottom left) over the
/// map, in pixel space.
pub(crate) fn north_and_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &mut MapChart<'_, DB>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    mask_margins(area, chart, theme, scale)?;
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

/// The accuracy circles of GNSS fixes (east, north, radius, m), each as wide on the map as its
/// radius (at least a pixel), in the `ring` style.
pub(crate) fn accuracy_rings<DB: DrawingBackend>(
    chart: &mut MapChart<'_, DB>,
    fixes: impl Iterator<Item = (f64, f64, f64)>,
    ring: ShapeStyle,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let circles: Vec<Circle<(f64, f64), u32>> = fixes
        .map(|(e, n, acc)| {
            let a = chart.backend_coord(&(e, n));
            let b = chart.backend_coord(&(e + acc, n));
            Circle::new((e, n), (b.0 - a.0).unsigned_abs().max(1), ring)
        })
        .collect();
    chart.draw_series(circles)?;
    Ok(())
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

/// The zoom factor of one turn of the wheel (`delta_y` as the browser's wheel event gives it):
/// out by 1.25 when it turns down, else in by 0.8.
pub fn wheel_factor(delta_y: f64) -> f64 {
    if delta_y > 0.0 {
        1.25
    } else {
        0.8
    }
}

/// Where a map was drawn: the plotting area in pixels and the metres it shows, to turn a
/// pointer position into metres (hover, zoom, pan).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct MapFrame {
    /// Plotting area, pixels: left, right, top, bottom.
    pub px: (i32, i32, i32, i32),
    /// Metres shown: min east, max east, min north, max north.
    pub m: (f64, f64, f64, f64),
}

impl MapFrame {
    /// The point (east, north) under pixel (x, y).
    pub fn to_metres(&self, x: f64, y: f64) -> (f64, f64) {
        let (l, r, t, b) = self.px;
        let (e0, e1, n0, n1) = self.m;
        (
            e0 + (x - l as f64) / (r - l).max(1) as f64 * (e1 - e0),
            n1 - (y - t as f64) / (b - t).max(1) as f64 * (n1 - n0),
        )
    }

    /// Metres per pixel.
    pub fn metres_per_px(&self) -> f64 {
        (self.m.1 - self.m.0) / (self.px.1 - self.px.0).max(1) as f64
    }

    /// The pixel (x, y) of the point (east, north).
    pub fn to_pixel(&self, e: f64, n: f64) -> (f64, f64) {
        let (l, r, t, b) = self.px;
        let (e0, e1, n0, n1) = self.m;
        (
            l as f64 + (e - e0) / (e1 - e0) * (r - l) as f64,
            t as f64 + (n1 - n) / (n1 - n0) * (b - t) as f64,
        )
    }

    /// The bounds (min_e, max_e, min_n, max_n) zoomed by `factor` (above 1 out, below 1 in)
    /// about the point under pixel (x, y), which stays under it.
    pub fn zoomed(&self, x: f64, y: f64, factor: f64) -> (f64, f64, f64, f64) {
        let (e0, e1, n0, n1) = self.m;
        let (e, n) = self.to_metres(x, y);
        (
            e - (e - e0) * factor,
            e + (e1 - e) * factor,
            n - (n - n0) * factor,
            n + (n1 - n) * factor,
        )
    }

    /// A pinch: one pointer moved from pixel `prev` to `now` while the other stays at `other`.
    /// The bounds zoomed about the pointers' middle by the ratio of their distances, or None
    /// when two of the points coincide.
    pub fn pinched(
        &self,
        prev: (f64, f64),
        now: (f64, f64),
        other: (f64, f64),
    ) -> Option<(f64, f64, f64, f64)> {
        let d0 = libm::hypot(prev.0 - other.0, prev.1 - other.1);
        let d1 = libm::hypot(now.0 - other.0, now.1 - other.1);
        (d0 > 0.0 && d1 > 0.0)
            .then(|| self.zoomed((now.0 + other.0) / 2.0, (now.1 + other.1) / 2.0, d0 / d1))
    }

    /// The bounds after a drag of (dx, dy) pixels: the map follows the pointer.
    pub fn panned(&self, dx: f64, dy: f64) -> (f64, f64, f64, f64) {
        let (e0, e1, n0, n1) = self.m;
        let mpp = self.metres_per_px();
        let de = dx * mpp;
        let dn = dy * mpp;
        (e0 - de, e1 - de, n0 + dn, n1 + dn)
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

    /// A 400 × 300 pixel plotting area at (40, 10) showing 200 m × 150 m.
    const FRAME: MapFrame = MapFrame {
        px: (40, 440, 10, 310),
        m: (-100.0, 100.0, -50.0, 100.0),
    };

    #[test]
    fn pixels_and_metres_are_inverse() {
        assert_eq!(FRAME.to_metres(40.0, 10.0), (-100.0, 100.0));
        assert_eq!(FRAME.to_metres(440.0, 310.0), (100.0, -50.0));
        assert_eq!(FRAME.to_pixel(0.0, 0.0), (240.0, 210.0));
        assert_eq!(FRAME.metres_per_px(), 0.5);
        for (x, y) in [(0.0, 0.0), (123.25, 77.5), (440.0, 310.0), (-20.0, 500.0)] {
            let (e, n) = FRAME.to_metres(x, y);
            let (x1, y1) = FRAME.to_pixel(e, n);
            assert!(
                (x1 - x).abs() < 1e-9 && (y1 - y).abs() < 1e-9,
                "{x} {y}: {x1} {y1}"
            );
        }
    }

    // The expected bounds are what the page's own JavaScript computed for the same gestures.
    #[test]
    fn wheel_zooms_about_the_pointer() {
        assert_eq!(wheel_factor(100.0), 1.25);
        assert_eq!(wheel_factor(-100.0), 0.8);
        assert_eq!(
            FRAME.zoomed(140.0, 60.0, 1.25),
            (-112.5, 137.5, -81.25, 106.25)
        );
        assert_eq!(FRAME.zoomed(140.0, 60.0, 0.8), (-90.0, 70.0, -25.0, 95.0));
        assert_eq!(
            FRAME.zoomed(373.5, 222.25, 0.8),
            (-66.65, 93.35, -41.225, 78.775)
        );
        // The point under the pointer stays under it.
        let (x0, x1, y0, y1) = FRAME.zoomed(373.5, 222.25, 0.8);
        let zoomed = MapFrame {
            m: (x0, x1, y0, y1),
            ..FRAME
        };
        let (a, b) = (
            FRAME.to_metres(373.5, 222.25),
            zoomed.to_metres(373.5, 222.25),
        );
        assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9);
    }

    #[test]
    fn pinch_zooms_about_the_middle() {
        let apart = FRAME.pinched((100.0, 100.0), (80.0, 90.0), (300.0, 200.0));
        let js = (
            -93.18181818181817,
            88.63636363636363,
            -42.5,
            93.86363636363636,
        );
        let (a, b) = (apart.unwrap(), js);
        for (x, y) in [(a.0, b.0), (a.1, b.1), (a.2, b.2), (a.3, b.3)] {
            assert!((x - y).abs() < 1e-12, "{a:?} {b:?}");
        }
        assert_eq!(
            FRAME.pinched((100.0, 120.0), (160.0, 200.0), (400.0, 520.0)),
            Some((-130.0, 120.0, -43.75, 143.75))
        );
        assert_eq!(
            FRAME.pinched((300.0, 200.0), (80.0, 90.0), (300.0, 200.0)),
            None
        );
    }

    #[test]
    fn drag_pans_with_the_pointer() {
        assert_eq!(FRAME.panned(30.0, -10.0), (-115.0, 85.0, -55.0, 95.0));
        assert_eq!(FRAME.panned(-0.75, 1.5), (-99.625, 100.375, -49.25, 100.75));
    }

    #[test]
    fn scale_bar_is_nice() {
        assert_eq!(scale_bar_length(100.0), 20.0);
        assert_eq!(scale_bar_length(9.0), 2.0);
        assert_eq!(scale_bar_length(1000.0), 200.0);
    }
}
