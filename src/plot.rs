//! Drawing, generic over the plotters [`DrawingBackend`], so the same code draws on a browser
//! canvas and, in tests, into a bitmap.

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

/// Bounds (min_e, max_e, min_n, max_n) of the points with a margin, widened so that one metre
/// spans the same number of pixels on both axes.
fn equal_aspect(points: impl Iterator<Item = (f64, f64)>, w: f64, h: f64) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in points {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (-10.0, 10.0, -10.0, 10.0);
    }
    let pad = 0.06 * (x1 - x0).max(y1 - y0).max(10.0);
    let (mut x0, mut x1, mut y0, mut y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    let (sx, sy) = ((x1 - x0) / w, (y1 - y0) / h);
    if sx > sy {
        let grow = (sx * h - (y1 - y0)) / 2.0;
        y0 -= grow;
        y1 += grow;
    } else {
        let grow = (sy * w - (x1 - x0)) / 2.0;
        x0 -= grow;
        x1 += grow;
    }
    (x0, x1, y0, y1)
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

type MapChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Fills the area and sets up a map in metres (east right, north up, equal scale) fitting
/// `points`, with its grid and axis labels.
fn map_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    points: impl Iterator<Item = (f64, f64)>,
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
    let (x0, x1, y0, y1) = equal_aspect(points, plot_w, plot_h);
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
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    Ok(chart)
}

/// A north arrow (top right) and a scale bar (bottom left) over the map, in pixel space.
fn north_and_scale<DB: DrawingBackend>(
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
fn start_end<DB: DrawingBackend>(
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
    // Legend, top left.
    let font = ("sans-serif", 13.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    let (x, mut y) = (rx.start + px(10.0) as i32, ry.start + px(8.0) as i32);
    let mut entries = vec![
        ("fused", theme.track),
        ("smoothed", theme.smoothed),
        ("PDR only", theme.pdr),
        ("GNSS fixes", theme.gnss),
    ];
    if view.truth.is_some() {
        entries.push(("true path", theme.reference));
    }
    let row = px(18.0) as i32;
    area.draw(&Rectangle::new(
        [
            (x - px(6.0) as i32, y - px(4.0) as i32),
            (
                x + px(112.0) as i32,
                y + row * entries.len() as i32 + px(2.0) as i32,
            ),
        ],
        theme.background.mix(0.85).filled(),
    ))?;
    for (label, colour) in entries {
        let mid = y + row / 2;
        if label == "GNSS fixes" {
            area.draw(&Circle::new(
                (x + px(10.0) as i32, mid),
                px(3.0),
                colour.filled(),
            ))?;
        } else {
            area.draw(&PathElement::new(
                vec![(x, mid), (x + px(22.0) as i32, mid)],
                ShapeStyle::from(&colour).stroke_width(px(3.0)),
            ))?;
        }
        area.draw(&Text::new(
            label,
            (x + px(30.0) as i32, mid - px(7.0) as i32),
            font.clone(),
        ))?;
        y += row;
    }
    north_and_scale(area, &chart, theme, scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_bar_is_nice() {
        assert_eq!(scale_bar_length(100.0), 20.0);
        assert_eq!(scale_bar_length(9.0), 2.0);
        assert_eq!(scale_bar_length(1000.0), 200.0);
    }

    use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};

    /// An in-memory RGB raster that ignores text (no font engine natively).
    struct Raster {
        w: u32,
        h: u32,
        px: std::rc::Rc<std::cell::RefCell<Vec<(u8, u8, u8)>>>,
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
}
