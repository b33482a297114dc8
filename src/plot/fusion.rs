//! The fusion demo's map: GNSS fixes, the PDR-only, fused and smoothed tracks and the truth.
//! May import: the map frame, the base map and the theme; never `web`, `live` or `eval`.

use super::basemap::{credit_line, map_chart_under, Basemap};
use super::frame::{accuracy_rings, legend, north_and_scale, start_end, Mark};
use super::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

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
/// smoothed tracks and the true path, with a legend, a north arrow and a scale bar, over the
/// `basemap` when there is one.
pub fn draw_fusion<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    view: &FusionView<'_>,
    mut basemap: Option<&mut Basemap<'_>>,
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
    let mut chart = map_chart_under(area, pts, None, basemap.as_deref_mut(), theme, scale)?;
    let gnss = ShapeStyle::from(&theme.gnss.mix(0.35)).stroke_width(px(1.0));
    accuracy_rings(&mut chart, view.fixes.iter().step_by(5).copied(), gnss)?;
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
    north_and_scale(area, &mut chart, theme, scale)?;
    credit_line(area, &chart, basemap.as_deref(), theme, scale)
}

/// The fusion demo's walk as [`draw_fusion`] draws it (the tests' and the pixel check's).
#[cfg(test)]
pub(crate) fn view_of(demo: &crate::demo::FusionDemoSummary) -> FusionView<'_> {
    FusionView {
        truth: Some(&demo.truth),
        fixes: &demo.fix_points,
        pdr: &demo.pdr,
        fused: &demo.fused,
        smoothed: &demo.smoothed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster::Raster;

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
        let view = view_of(&demo);
        draw_fusion(&area, &view, None, &Theme::LIGHT, 1.0).unwrap();
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
}
