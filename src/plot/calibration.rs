//! The calibration wizard's chart of one band: the walks' points, the line and the residuals.
//! May import: `engine` (the band fit and the line); never `web`, `live` or `eval`.

use super::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

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
    let font = theme.text(scale);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster::Raster;

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
