//! Upload mode's diagnostics plots of an [`Analysis`], all against one time axis.
//! Imports: `engine` (step records), `analysis` and the theme; never `web`, `live` or `eval`.

use crate::analysis::Analysis;
use crate::plot::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

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
pub(super) fn draw_title<DB: DrawingBackend>(
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
