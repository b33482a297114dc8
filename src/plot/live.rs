//! Live mode's map: the walk so far, the current position and heading, fixes, gaps.
//! May import: the map frame, the base map and the theme; never `web`, `live` or `eval` (only the test below
//! feeds a simulated walk through `crate::live`, to have a live map to draw).

use super::basemap::{credit_line, map_chart_under, Basemap};
use super::frame::{accuracy_rings, legend, north_and_scale, Mark};
use super::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

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
/// scale bar, over the `basemap` when there is one.
pub fn draw_live<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    view: &LiveView<'_>,
    mut basemap: Option<&mut Basemap<'_>>,
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
    let mut chart = map_chart_under(area, pts, None, basemap.as_deref_mut(), theme, scale)?;
    let ring = ShapeStyle::from(&theme.gnss.mix(0.45)).stroke_width(px(1.0));
    // The newest fixes' circles (a long walk has thousands).
    accuracy_rings(&mut chart, view.fixes.iter().rev().take(300).copied(), ring)?;
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
        draw_position(area, at, view.heading_rad, theme, scale)?;
    }
    let entries = entries(view, theme);
    if !entries.is_empty() {
        legend(area, &chart, &entries, theme, scale)?;
    }
    north_and_scale(area, &mut chart, theme, scale)?;
    credit_line(area, &chart, basemap.as_deref(), theme, scale)
}

/// The current position at pixel `at`: a dot ringed in the background colour, with an arrow
/// along the heading (rad from north) when there is one.
fn draw_position<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    at: (i32, i32),
    heading_rad: Option<f64>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    if let Some(h) = heading_rad {
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
    Ok(())
}

/// The legend's entries: the tracks when there is a fused one, the fixes and the gaps.
fn entries(view: &LiveView<'_>, theme: &Theme) -> Vec<(&'static str, Mark)> {
    let mut entries = Vec::new();
    if !view.fused.is_empty() {
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
    entries
}

/// The live map's view of a session's map data (the tests' and the pixel check's).
#[cfg(test)]
pub(crate) fn view_of(d: &crate::live::MapData) -> LiveView<'_> {
    LiveView {
        pdr: &d.pdr,
        fused: &d.fused,
        smoothed: &d.smoothed,
        fixes: &d.fixes,
        gaps: &d.gaps,
        heading_rad: d.heading_rad,
    }
}

/// A live session fed a simulated straight walk's browser events, with 4 s without motion
/// events (a gap) in it: the live map and scope to draw, here and in the pixel check.
#[cfg(test)]
pub(crate) fn simulated_session() -> crate::live::LiveSession {
    use crate::live::{
        browser_events, BrowserEvent, LiveSession, MotionEvent, OrientationEvent, Platform,
    };
    let sim = crate::sim::scenarios::straight_walk(1.8, 30.0).generate();
    let imu = |r: &crate::engine::Record| matches!(r, crate::engine::Record::Imu(_));
    assert!(sim.records.iter().any(imu));
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
            } => live.push_orientation(&OrientationEvent::absolute(t, alpha, beta, gamma)),
            BrowserEvent::Motion { t, x, y, z, .. } if !(12e3..16e3).contains(&t) => {
                live.push_motion(&MotionEvent {
                    time_stamp_ms: t,
                    accel: Some([x, y, z]),
                    rotation_rate_deg_s: None,
                })
                .unwrap();
            }
            _ => {}
        }
    }
    live
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::draw_scope;
    use crate::plot::raster;

    #[test]
    fn draws_the_live_map_and_scope() {
        let mut live = super::simulated_session();
        let d = live.map_data();
        assert_eq!(d.gaps.len(), 1, "the 4 s without events is a gap");
        let (r, px) = raster::new(400, 400);
        let view = super::view_of(&d);
        draw_live(&r.into_drawing_area(), &view, None, &Theme::LIGHT, 1.0).unwrap();
        let t = Theme::LIGHT;
        let count = |c: RGBColor| raster::count(&px, c);
        assert!(count(t.track) > 200, "track {}", count(t.track));
        assert!(count(t.start) > 20 && count(t.end) > 40);
        let crate::live::ScopeData {
            samples,
            steps,
            now,
        } = live.scope_data();
        assert!(steps.len() >= 10 && steps.iter().all(|&s| s > now - 10.0));
        let (r, shared) = raster::new(600, 200);
        draw_scope(&r.into_drawing_area(), &samples, &steps, now, 10.0, &t, 1.0).unwrap();
        let n = |c: RGBColor| raster::count(&shared, c);
        assert!(
            n(t.track) > 500 && n(t.gnss) > 300 && n(t.end) > 10 * 100,
            "{} {} {}",
            n(t.track),
            n(t.gnss),
            n(t.end)
        );
        // Legible, as upload mode's plots (src/plot/upload/legibility.rs): in the plot area
        // (left of the labels' 34 + 8 pixels, below the key, above the time labels) no colour
        // but the background, grid and axes covers 35 % or more, in either theme.
        use crate::plot::upload::legibility::{dominant_share, MAX_DOMINANT_SHARE};
        for theme in [Theme::LIGHT, Theme::DARK] {
            let (r, px) = crate::plot::raster::new(600, 200);
            draw_scope(
                &r.into_drawing_area(),
                &samples,
                &steps,
                now,
                10.0,
                &theme,
                1.0,
            )
            .unwrap();
            let (share, colour) = dominant_share(&px, 600, ((42, 592), (22, 168)), &theme);
            assert!(share < MAX_DOMINANT_SHARE, "{colour:?}: {share}");
            println!("scope: {colour:?} covers {:.1} %", 100.0 * share);
        }
    }
}
