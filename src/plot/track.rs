//! The demo's track: the PDR track in metres with the reference path.
//! May import: `engine` (step records) and the map frame; never `web`, `live` or `eval`.

use super::frame::{map_chart, north_and_scale, start_end};
use super::theme::Theme;
use crate::engine::StepRecord;
use plotters::coord::Shift;
use plotters::prelude::*;

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
    north_and_scale(area, &mut chart, theme, scale)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster::Raster;

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
