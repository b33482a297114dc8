//! Live mode's scrolling scope: vertical acceleration, the PLL output and the detected steps.
//! May import: the theme; never `web`, `live` or `eval`.

use super::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A sample of the scrolling view: time (s), vertical acceleration (m/s²), PLL output.
pub type ScopePoint = (f64, f64, Option<f64>);

/// The scrolling view of the last `span_s` seconds up to `now`: vertical acceleration (m/s²)
/// with the detected steps (vertical marks), and the PLL output cos φ in a lane under it.
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
    let font = theme.text(scale);
    let amp = samples
        .iter()
        .map(|s| s.1.abs())
        .fold(2.0_f64, f64::max)
        .min(40.0)
        * 1.1;
    // The PLL output has a lane of its own under the acceleration, as in upload mode's plot:
    // drawn over it, its ±1 wave covers the signal.
    let body = area.margin(px(22.0), 0, 0, 0);
    let h = body.dim_in_pixel().1 as i32;
    let (main, lane) = body.split_vertically(h * 60 / 100);
    let mut chart = ChartBuilder::on(&main)
        .margin(px(8.0))
        .margin_top(0)
        .margin_bottom(px(2.0))
        .x_label_area_size(0)
        .y_label_area_size(px(34.0))
        .build_cartesian_2d(-span_s..0.0, -amp..amp)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(6)
        .y_labels(5)
        .x_label_formatter(&|_| String::new())
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    let mut pll = ChartBuilder::on(&lane)
        .margin(px(8.0))
        .margin_top(px(2.0))
        .x_label_area_size(px(24.0))
        .y_label_area_size(px(34.0))
        .build_cartesian_2d(-span_s..0.0, -1.6..1.6)?;
    pll.configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(theme.grid)
        .axis_style(theme.foreground)
        .label_style(font.clone())
        .x_labels(6)
        .y_labels(3)
        .x_label_formatter(&|v| format!("{v:.0} s"))
        .y_label_formatter(&pll_lane_label)
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
    pll.draw_series(
        steps
            .iter()
            .filter(|&&t| visible(t))
            .map(|&t| PathElement::new(vec![(rel(t), -1.6), (rel(t), 1.6)], step_style)),
    )?;
    let pll_style = ShapeStyle::from(&theme.gnss).stroke_width(px(1.5));
    let acc_style = ShapeStyle::from(&theme.track).stroke_width(px(2.0));
    for run in runs(samples) {
        let wave: Vec<(f64, f64)> = run
            .iter()
            .filter(|s| visible(s.0))
            .filter_map(|s| s.2.map(|p| (rel(s.0), p)))
            .collect();
        pll.draw_series(LineSeries::new(wave, pll_style))?;
        chart.draw_series(LineSeries::new(
            run.iter().filter(|s| visible(s.0)).map(|s| (rel(s.0), s.1)),
            acc_style,
        ))?;
    }
    draw_key(area, theme, &font, scale)
}

/// Runs of samples without a gap (samples further apart than 0.5 s).
fn runs(samples: &[ScopePoint]) -> Vec<&[ScopePoint]> {
    let mut runs: Vec<&[ScopePoint]> = Vec::new();
    let mut from = 0;
    for i in 1..=samples.len() {
        if i == samples.len() || samples[i].0 - samples[i - 1].0 > 0.5 {
            runs.push(&samples[from..i]);
            from = i;
        }
    }
    runs
}

/// The key, above the plot: each series' colour and name.
fn draw_key<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    theme: &Theme,
    font: &TextStyle,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let (x0, y0) = (px(40.0) as i32, px(4.0) as i32);
    let mut x = x0;
    for (label, colour) in [
        ("vertical acc., m/s²", theme.track),
        ("PLL cos φ, below", theme.gnss),
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
        let (w, _) = area.estimate_text_size(label, font)?;
        x += px(32.0) as i32 + w as i32;
    }
    Ok(())
}

/// The label of a PLL lane's axis (live scope and upload plot): ±1 only, the lane being a few
/// labels high.
pub(crate) fn pll_lane_label(v: &f64) -> String {
    if v.abs() > 0.5 {
        format!("{v:.0}")
    } else {
        String::new()
    }
}
