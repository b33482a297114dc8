//! Upload mode's plots of an [`Analysis`]: the map (zoomable), the time-aligned diagnostics,
//! and the horizontal-acceleration ellipse of one stride (Basso 2016 Fig. 5).

pub use super::MapFrame;
use super::{legend, map_chart_in, north_and_scale, start_end, tick, Mark, Theme};
use crate::analysis::Analysis;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The PDR track's points in the map's frame (the fixes' frame when there are fixes).
pub fn pdr_points(a: &Analysis) -> Vec<(f64, f64)> {
    let (oe, on) = a.pdr_offset;
    std::iter::once((oe, on))
        .chain(a.steps.iter().map(|s| (s.east_m + oe, s.north_m + on)))
        .collect()
}

/// Draws the map of an analysis: the PDR track, the fixes with accuracy circles, the fused and
/// smoothed tracks, the truth, start and end, the `highlight`ed step, a legend, a north arrow
/// and a scale bar; `bounds` zooms (None fits everything). Returns where it drew.
pub fn draw_map<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    bounds: Option<(f64, f64, f64, f64)>,
    highlight: Option<usize>,
    theme: &Theme,
    scale: f64,
) -> Result<MapFrame, DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let pdr = pdr_points(a);
    let (oe, on) = a.pdr_offset;
    let truth: Vec<(f64, f64)> = a.truth_path.iter().map(|p| (p.0 + oe, p.1 + on)).collect();
    let fused: Vec<(f64, f64)> = a.fused.iter().map(|f| (f[1], f[2])).collect();
    let smoothed: Vec<(f64, f64)> = a.smoothed.iter().map(|f| (f[1], f[2])).collect();
    let pts = pdr
        .iter()
        .chain(&fused)
        .chain(&truth)
        .copied()
        .chain(a.fixes.iter().map(|f| (f[1], f[2])));
    let mut chart = map_chart_in(area, pts, bounds, theme, scale)?;
    let ring = ShapeStyle::from(&theme.gnss.mix(0.35)).stroke_width(px(1.0));
    let step = (a.fixes.len() / 300).max(1);
    let circles: Vec<Circle<(f64, f64), u32>> = a
        .fixes
        .iter()
        .step_by(step)
        .map(|f| {
            let p0 = chart.backend_coord(&(f[1], f[2]));
            let p1 = chart.backend_coord(&(f[1] + f[3], f[2]));
            Circle::new((f[1], f[2]), (p1.0 - p0.0).unsigned_abs().max(1), ring)
        })
        .collect();
    chart.draw_series(circles)?;
    chart.draw_series(
        a.fixes
            .iter()
            .map(|f| Circle::new((f[1], f[2]), px(2.0), theme.gnss.filled())),
    )?;
    if !truth.is_empty() {
        chart.draw_series(LineSeries::new(
            truth.iter().copied(),
            ShapeStyle::from(&theme.reference).stroke_width(px(2.0)),
        ))?;
        chart.draw_series(
            truth
                .iter()
                .map(|&p| Circle::new(p, px(3.0), theme.reference.filled())),
        )?;
    }
    let pdr_colour = if fused.is_empty() {
        theme.track
    } else {
        theme.pdr
    };
    chart.draw_series(LineSeries::new(
        pdr.iter().copied(),
        ShapeStyle::from(&pdr_colour).stroke_width(px(2.5)),
    ))?;
    for (path, colour) in [(&smoothed, theme.smoothed), (&fused, theme.track)] {
        chart.draw_series(LineSeries::new(
            path.iter().copied(),
            ShapeStyle::from(&colour).stroke_width(px(2.5)),
        ))?;
    }
    start_end(
        &mut chart,
        if fused.is_empty() { &pdr } else { &fused },
        theme,
        scale,
    )?;
    if let Some(p) = highlight.and_then(|i| a.step_position(i)) {
        chart.draw_series([Circle::new(
            p,
            px(8.0),
            ShapeStyle::from(&theme.foreground).stroke_width(px(2.5)),
        )])?;
    }
    let mut entries = vec![(
        if fused.is_empty() {
            "PDR track"
        } else {
            "PDR only"
        },
        Mark::Line(pdr_colour),
    )];
    if !fused.is_empty() {
        entries.push(("fused", Mark::Line(theme.track)));
        entries.push(("smoothed", Mark::Line(theme.smoothed)));
    }
    if !a.fixes.is_empty() {
        entries.push(("GNSS fixes", Mark::Dot(theme.gnss)));
    }
    if !truth.is_empty() {
        entries.push(("truth (aligned)", Mark::Line(theme.reference)));
    }
    legend(area, &chart, &entries, theme, scale)?;
    north_and_scale(area, &chart, theme, scale)?;
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    if a.has_steps_without_any_heading() {
        let font = ("sans-serif", 13.0 * scale)
            .into_font()
            .color(&theme.foreground);
        area.draw(&Text::new(
            format!(
                "No heading in this log (no gyroscope, magnetometer or orientation): its {} steps cannot be placed.",
                a.steps.len()
            ),
            (rx.start + px(12.0) as i32, (ry.start + ry.end) / 2 + px(24.0) as i32),
            font,
        ))?;
    }
    let (xr, yr) = (
        chart.plotting_area().get_x_range(),
        chart.plotting_area().get_y_range(),
    );
    Ok(MapFrame {
        px: (rx.start, rx.end, ry.start, ry.end),
        m: (xr.start, xr.end, yr.start, yr.end),
    })
}

/// The diagnostics plots, all against the same time axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plot {
    /// Vertical acceleration, PLL output, detected (and true) steps.
    Accel,
    /// σ of the vertical acceleration with the thresholds and the motion state.
    Sigma,
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
    /// From its name in the page.
    pub fn parse(name: &str) -> Option<Plot> {
        Some(match name {
            "accel" => Plot::Accel,
            "sigma" => Plot::Sigma,
            "heading" => Plot::Heading,
            "steps" => Plot::Steps,
            "gnss" => Plot::Gnss,
            "fusion" => Plot::Fusion,
            _ => return None,
        })
    }
}

/// Min and max of `v` per pixel column between `t0` and `t1`, as a zig-zag line: a long signal
/// drawn at any zoom without losing its peaks.
fn envelope(
    t: &[f64],
    v: &[f32],
    t0: f64,
    t1: f64,
    cols: usize,
    origin: f64,
) -> Vec<Vec<(f64, f64)>> {
    let i0 = t.partition_point(|&x| x < t0);
    let i1 = t.partition_point(|&x| x <= t1);
    let mut runs = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    if i1 <= i0 {
        return runs;
    }
    let n = i1 - i0;
    if n <= 2 * cols {
        let mut last = f64::NEG_INFINITY;
        for i in i0..i1 {
            if t[i] - last > 0.5 && !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
            last = t[i];
            if v[i].is_finite() {
                run.push((t[i] - origin, f64::from(v[i])));
            }
        }
    } else {
        let width = (t1 - t0) / cols as f64;
        let mut i = i0;
        let mut last = f64::NEG_INFINITY;
        for c in 0..cols {
            let end = t0 + (c + 1) as f64 * width;
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            let start = i;
            while i < i1 && t[i] <= end {
                if v[i].is_finite() {
                    lo = lo.min(v[i]);
                    hi = hi.max(v[i]);
                }
                i += 1;
            }
            if i == start || !lo.is_finite() {
                continue;
            }
            if t[start] - last > 0.5 + width && !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
            last = t[i - 1];
            let tc = t0 + (c as f64 + 0.5) * width - origin;
            run.push((tc, f64::from(lo)));
            run.push((tc, f64::from(hi)));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// Draws one diagnostics plot between `t0` and `t1` (s, the log's clock), with a cursor at a
/// time when given. The time axis is in seconds from the log's first sample. Returns the
/// pixel columns where `t0` and `t1` fall, for the page to map a pointer to a time.
pub fn draw_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    plot: Plot,
    (t0, t1): (f64, f64),
    cursor: Option<f64>,
    theme: &Theme,
    scale: f64,
) -> Result<(i32, i32), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    area.fill(&theme.background)?;
    let font = ("sans-serif", 12.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let origin = a.trace.t.first().copied().unwrap_or(0.0);
    let (x0, x1) = (t0 - origin, t1 - origin);
    let cols = (area.dim_in_pixel().0 as usize).max(10);
    let tr = &a.trace;
    let steps_in: Vec<&crate::engine::pipeline::StepRecord> =
        a.steps.iter().filter(|s| s.t >= t0 && s.t <= t1).collect();
    #[allow(clippy::type_complexity)]
    let (title, y_label, (y0, y1), right): (
        &str,
        &str,
        (f64, f64),
        Option<(&str, (f64, f64))>,
    ) = match plot {
        Plot::Accel => {
            let amp = envelope(&tr.t, &tr.up, t0, t1, cols, 0.0)
                .iter()
                .flatten()
                .fold(2.0_f64, |m, p| m.max(p.1.abs()))
                .min(40.0)
                * 1.1;
            (
                "vertical acceleration (m/s²), PLL cos φ (right), steps (red), true steps (grey)",
                "m/s²",
                (-amp, amp),
                Some(("cos φ", (-1.25, 1.25))),
            )
        }
        Plot::Sigma => {
            let top = envelope(&tr.t, &tr.sigma, t0, t1, cols, 0.0)
                .iter()
                .flatten()
                .fold(a.sigma_thresholds.1 * 1.3, |m, p| m.max(p.1))
                * 1.1;
            (
                "σ of vertical acceleration (m/s²), thresholds, motion: still / walk / run",
                "m/s²",
                (0.0, top),
                None,
            )
        }
        Plot::Heading => (
            "heading (°): single step (dots), two-step average (line), device (grey)",
            "°",
            (0.0, 360.0),
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
            // Each axis spans what the filter estimated and its neutral value (1, 0°), the
            // scale in the upper half and the correction in the lower, so they do not overlap.
            let (mut k, mut b) = ((1.0_f64, 1.0_f64), (0.0_f64, 0.0_f64));
            for f in a.fused.iter().filter(|f| f[0] >= t0 && f[0] <= t1) {
                k = (k.0.min(f[3]), k.1.max(f[3]));
                let d = f[4].to_degrees();
                b = (b.0.min(d), b.1.max(d));
            }
            let ks = (k.1 - k.0).max(0.02);
            let bs = (b.1 - b.0).max(2.0);
            (
                "fusion: step-length scale (blue, left), heading correction (°, orange, right)",
                "",
                (k.0 - 1.3 * ks, k.1 + 0.2 * ks),
                Some(("°", (b.0 - 0.2 * bs, b.1 + 1.3 * bs))),
            )
        }
    };
    let lines = draw_title(area, title, &font, scale)?;
    let body = area.margin(px(5.0 + 15.0 * lines as f64), 0, 0, 0);
    let mut builder = ChartBuilder::on(&body);
    // The same label areas on every plot, with a right axis or not, so that their time axes
    // line up on the page.
    builder
        .margin(px(6.0))
        .x_label_area_size(px(22.0))
        .y_label_area_size(px(40.0))
        .right_y_label_area_size(px(40.0));
    let (r0, r1) = right.map_or((0.0, 1.0), |r| r.1);
    let mut chart = builder
        .build_cartesian_2d(x0..x1, y0..y1)?
        .set_secondary_coord(x0..x1, r0..r1);
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(8)
        .y_labels(5)
        .x_label_formatter(&|v| {
            if x1 - x0 < 20.0 {
                format!("{v:.1} s")
            } else {
                format!("{v:.0} s")
            }
        })
        .y_label_formatter(&|v| match y_label {
            "°" => format!("{v:.0}°"),
            "" => format!("{v:.2}"),
            _ => format!("{v:.0}"),
        })
        .draw()?;
    if right.is_some() {
        chart
            .configure_secondary_axes()
            .axis_style(theme.foreground)
            .label_style(font.clone())
            .y_labels(5)
            .y_label_formatter(&|v| match right {
                Some(("°", _)) => format!("{v:.0}°"),
                _ => format!("{v:.2}"),
            })
            .draw()?;
    }
    let (columns, rows) = chart.plotting_area().get_pixel_range();
    let note = match plot {
        Plot::Gnss | Plot::Fusion if a.fixes.is_empty() => Some("no GNSS fixes in this log"),
        Plot::Heading if a.has_steps_without_any_heading() => {
            Some("no heading in this log (no gyroscope, magnetometer or orientation)")
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
    let columns = (columns.start, columns.end);
    let line = |c: RGBColor, w: f64| ShapeStyle::from(&c).stroke_width(px(w));
    let rel = |t: f64| t - origin;
    match plot {
        Plot::Accel => {
            chart.draw_series(steps_in.iter().map(|s| {
                PathElement::new(vec![(rel(s.t), y0), (rel(s.t), y1)], line(theme.end, 1.0))
            }))?;
            chart.draw_series(
                a.truth_steps
                    .iter()
                    .filter(|&&t| t >= t0 && t <= t1)
                    .map(|&t| {
                        PathElement::new(
                            vec![(rel(t), y0), (rel(t), y0 + 0.15 * (y1 - y0))],
                            line(theme.reference, 2.0),
                        )
                    }),
            )?;
            for run in envelope(&tr.t, &tr.pll, t0, t1, cols, origin) {
                chart.draw_secondary_series(LineSeries::new(run, line(theme.gnss, 1.0)))?;
            }
            for run in envelope(&tr.t, &tr.up, t0, t1, cols, origin) {
                chart.draw_series(LineSeries::new(run, line(theme.track, 1.5)))?;
            }
        }
        Plot::Sigma => {
            // Motion state as a band along the bottom.
            let band = 0.06 * (y1 - y0);
            let i0 = tr.t.partition_point(|&x| x < t0);
            let i1 = tr.t.partition_point(|&x| x <= t1);
            let every = ((i1 - i0) / cols).max(1);
            chart.draw_series((i0..i1).step_by(every).filter_map(|i| {
                let c = match tr.motion[i] {
                    1 => theme.start,
                    2 => theme.end,
                    _ => return None,
                };
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
            for run in envelope(&tr.t, &tr.sigma, t0, t1, cols, origin) {
                chart.draw_series(LineSeries::new(run, line(theme.track, 1.5)))?;
            }
        }
        Plot::Heading => {
            let wrap = |r: f64| r.to_degrees().rem_euclid(360.0);
            for run in envelope(&tr.t, &tr.device_heading_deg, t0, t1, cols, origin) {
                // Not joined across the 0°/360° wrap.
                chart.draw_series(
                    run.iter()
                        .map(|&p| Circle::new(p, px(0.8), theme.reference.filled())),
                )?;
            }
            chart.draw_series(steps_in.iter().filter_map(|s| {
                s.step_heading_rad
                    .map(|h| Circle::new((rel(s.t), wrap(h)), px(2.0), theme.gnss.filled()))
            }))?;
            let mut segment: Vec<(f64, f64)> = Vec::new();
            let mut segs = Vec::new();
            for s in &steps_in {
                let Some(h) = s.heading_rad else { continue };
                let p = (rel(s.t), wrap(h));
                if segment
                    .last()
                    .is_some_and(|l: &(f64, f64)| (l.1 - p.1).abs() > 180.0)
                {
                    segs.push(std::mem::take(&mut segment));
                }
                segment.push(p);
            }
            segs.push(segment);
            for seg in segs {
                chart.draw_series(LineSeries::new(seg, line(theme.track, 2.0)))?;
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
            let fused_in = || a.fused.iter().filter(|f| f[0] >= t0 && f[0] <= t1);
            chart.draw_series(LineSeries::new(
                [(x0, 1.0), (x1, 1.0)],
                line(theme.grid, 1.0),
            ))?;
            chart.draw_series(LineSeries::new(
                fused_in().map(|f| (rel(f[0]), f[3])),
                line(theme.track, 2.0),
            ))?;
            chart.draw_secondary_series(fused_in().map(|f| {
                Circle::new((rel(f[0]), f[4].to_degrees()), px(1.5), theme.gnss.filled())
            }))?;
        }
    }
    if let Some(c) = cursor.filter(|c| *c >= t0 && *c <= t1) {
        chart.draw_series([PathElement::new(
            vec![(rel(c), y0), (rel(c), y1)],
            line(theme.foreground, 1.0),
        )])?;
    }
    Ok(columns)
}

/// Draws a plot's title at its top left, on two lines when one is too narrow (a phone), broken
/// after a comma. Returns the number of lines.
fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    font: &TextStyle,
    scale: f64,
) -> Result<usize, DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let width = area.dim_in_pixel().0.saturating_sub(px(16.0));
    let fits = |t: &str| {
        area.estimate_text_size(t, font)
            .is_ok_and(|(w, _)| w <= width)
    };
    let breaks: Vec<usize> = title.match_indices(", ").map(|(i, _)| i).collect();
    let lines: Vec<&str> = match breaks.into_iter().rev().find(|&i| fits(&title[..=i])) {
        Some(i) if !fits(title) => vec![&title[..=i], &title[i + 2..]],
        _ => vec![title],
    };
    for (k, line) in lines.iter().enumerate() {
        area.draw(&Text::new(
            *line,
            (px(8.0) as i32, px(4.0 + 15.0 * k as f64) as i32),
            font.clone(),
        ))?;
    }
    Ok(lines.len())
}

/// The horizontal acceleration (east, north) over the stride that ends at step `k` (from the
/// step two before it), as Basso 2016 Fig. 5 draws it, with the step's heading as an arrow from
/// the centre.
pub fn draw_ellipse<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    k: usize,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    area.fill(&theme.background)?;
    let font = ("sans-serif", 12.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let Some(step) = a.steps.get(k) else {
        area.draw(&Text::new(
            "no step selected",
            (px(8.0) as i32, px(6.0) as i32),
            font,
        ))?;
        return Ok(());
    };
    let from = k.checked_sub(2).map_or(step.t - 1.2, |j| a.steps[j].t);
    let tr = &a.trace;
    let i0 = tr.t.partition_point(|&x| x < from);
    let i1 = tr.t.partition_point(|&x| x <= step.t);
    let pts: Vec<(f64, f64)> = (i0..i1)
        .map(|i| (f64::from(tr.east[i]), f64::from(tr.north[i])))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let r = pts
        .iter()
        .fold(1.0_f64, |m, p| m.max(p.0.abs()).max(p.1.abs()))
        * 1.15;
    let title = format!(
        "step {} at {:.1} s, stride's horizontal acc. (m/s²), heading {}",
        k + 1,
        step.t - tr.t.first().copied().unwrap_or(0.0),
        step.heading_rad.map_or("–".into(), |h| format!(
            "{:.0}°",
            h.to_degrees().rem_euclid(360.0)
        ))
    );
    let lines = draw_title(area, &title, &font, scale)?;
    let body = area.margin(px(5.0 + 15.0 * lines as f64), 0, 0, 0);
    let (w, h) = body.dim_in_pixel();
    let side = w.min(h);
    let square = body.margin(0, 0, (w - side) / 2, (w - side) / 2);
    let decimals = if r < 5.0 { 1 } else { 0 };
    let mut chart = ChartBuilder::on(&square)
        .margin(px(6.0))
        .x_label_area_size(px(22.0))
        .y_label_area_size(px(30.0))
        .build_cartesian_2d(-r..r, -r..r)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(5)
        .y_labels(5)
        .x_label_formatter(&|v| format!("{} E", tick(*v, decimals)))
        .y_label_formatter(&|v| format!("{} N", tick(*v, decimals)))
        .draw()?;
    chart.draw_series(LineSeries::new(
        pts.iter().copied(),
        ShapeStyle::from(&theme.track).stroke_width(px(1.5)),
    ))?;
    if pts.is_empty() || a.has_steps_without_any_heading() {
        let (columns, rows) = chart.plotting_area().get_pixel_range();
        area.draw(&Text::new(
            "no horizontal acceleration (no heading)",
            (columns.start + px(8.0) as i32, rows.start + px(8.0) as i32),
            font.clone(),
        ))?;
    }
    if let Some(hd) = step.heading_rad {
        let (s, c) = libm::sincos(hd);
        let tip = (0.9 * r * s, 0.9 * r * c);
        chart.draw_series([PathElement::new(
            vec![(0.0, 0.0), tip],
            ShapeStyle::from(&theme.end).stroke_width(px(3.0)),
        )])?;
        chart.draw_series([Circle::new(tip, px(4.0), theme.end.filled())])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster;

    #[test]
    fn draws_every_upload_plot_of_the_gnss_walk() {
        let sim = crate::sim::scenarios::gnss_city_walk().generate();
        let mut log = crate::io::import::Log::new("city.pdrlog", crate::io::import::Format::PdrLog);
        log.records = sim.records;
        let mut calls = 0;
        let a =
            crate::analysis::analyse(&log, &Default::default(), &mut |_, _| calls += 1).unwrap();
        assert!(calls >= 2);
        assert_eq!(a.trace.t.len(), a.trace.up.len());
        assert!(!a.fixes.is_empty() && !a.fused.is_empty() && !a.innovations.is_empty());
        // The trip from the worker to the page keeps everything, NaN included.
        let back = crate::analysis::Analysis::from_bytes(&a.to_bytes()).unwrap();
        assert_eq!(back.steps, a.steps);
        assert_eq!(back.trace.t, a.trace.t);
        let t = Theme::LIGHT;
        let (r, px) = raster::new(500, 400);
        let f = draw_map(&r.into_drawing_area(), &a, None, Some(10), &t, 1.0).unwrap();
        assert!(raster::count(&px, t.track) > 300 && raster::count(&px, t.gnss) > 100);
        // The frame maps pixels back to metres: the plot's corners are its bounds.
        let (e, n) = f.to_metres(f.px.0 as f64, f.px.2 as f64);
        assert!((e - f.m.0).abs() < 1e-9 && (n - f.m.3).abs() < 1e-9);
        let span = (a.trace.t[0], *a.trace.t.last().unwrap());
        let mut axes = Vec::new();
        for (plot, colour) in [
            (Plot::Accel, t.track),
            (Plot::Sigma, t.track),
            (Plot::Heading, t.track),
            (Plot::Steps, t.track),
            (Plot::Gnss, t.gnss),
            (Plot::Fusion, t.track),
        ] {
            let (r, px) = raster::new(600, 200);
            let (left, right) = draw_plot(
                &r.into_drawing_area(),
                &a,
                plot,
                span,
                Some(span.0 + 10.0),
                &t,
                1.0,
            )
            .unwrap();
            assert!(
                raster::count(&px, colour) > 100,
                "{plot:?}: {}",
                raster::count(&px, colour)
            );
            // The time axis lies between the label areas.
            assert!(
                left > 30 && right < 595 && right - left > 450,
                "{plot:?}: {left}..{right}"
            );
            axes.push((left, right));
        }
        // Stacked on the page, the plots share one time axis, pixel for pixel.
        assert!(axes.iter().all(|x| *x == axes[0]), "{axes:?}");
        // The heading correction is drawn too (dots on the fusion plot's right axis).
        let (r, px) = raster::new(600, 200);
        draw_plot(
            &r.into_drawing_area(),
            &a,
            Plot::Fusion,
            span,
            None,
            &t,
            1.0,
        )
        .unwrap();
        assert!(raster::count(&px, t.gnss) > 100);
        let (r, px) = raster::new(300, 300);
        draw_ellipse(&r.into_drawing_area(), &a, 40, &t, 1.0).unwrap();
        assert!(raster::count(&px, t.track) > 50 && raster::count(&px, t.end) > 20);
    }
}
