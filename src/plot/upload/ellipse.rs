//! Upload mode's horizontal-acceleration ellipse of one stride (Basso 2016 Fig. 5).
//! May import: `analysis`, the theme and the axis labels; never `web`, `live` or `eval`.

use super::palette::draw_title;
use crate::analysis::Analysis;
use crate::plot::frame::tick;
use crate::plot::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

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
    let font = theme.text(scale);
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
