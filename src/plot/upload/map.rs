//! Upload mode's map of an [`Analysis`]: tracks, fixes, truth, the highlighted step.
//! May import: `analysis`, the map frame and the base map; never `web`, `live` or `eval`.

use super::palette::floor_colour;
use crate::analysis::Analysis;
use crate::plot::basemap::{credit_line, map_chart_under, Basemap};
use crate::plot::frame::{
    accuracy_rings, frame_of, legend, north_and_scale, start_end, MapChart, MapFrame, Mark,
};
use crate::plot::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The PDR track's points in the map's frame (the fixes' frame when there are fixes).
fn pdr_points(a: &Analysis) -> Vec<(f64, f64)> {
    let (oe, on) = a.pdr_offset;
    std::iter::once((oe, on))
        .chain(a.steps.iter().map(|s| (s.east_m + oe, s.north_m + on)))
        .collect()
}

/// The step nearest to pixel (x, y) on a map drawn in `frame`, within `radius` pixels.
pub fn pick_step(a: &Analysis, frame: &MapFrame, x: f64, y: f64, radius: f64) -> Option<usize> {
    let (e, n) = frame.to_metres(x, y);
    let r = radius * frame.metres_per_px();
    (0..a.steps.len())
        .filter_map(|i| {
            a.step_position(i)
                .map(|p| (i, libm::hypot(p.0 - e, p.1 - n)))
        })
        .filter(|(_, d)| *d <= r)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// Draws the map of an analysis: the PDR track, the fixes with accuracy circles, the fused and
/// smoothed tracks, the truth, start and end, the `highlight`ed step, a legend, a north arrow
/// and a scale bar, over the `basemap` when there is one; `bounds` zooms (None fits
/// everything). Returns where it drew.
pub fn draw_map<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: &Analysis,
    bounds: Option<(f64, f64, f64, f64)>,
    highlight: Option<usize>,
    mut basemap: Option<&mut Basemap<'_>>,
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
    let mut chart = map_chart_under(area, pts, bounds, basemap.as_deref_mut(), theme, scale)?;
    let ring = ShapeStyle::from(&theme.gnss.mix(0.35)).stroke_width(px(1.0));
    let every = (a.fixes.len() / 300).max(1);
    let rings = a.fixes.iter().step_by(every).map(|f| (f[1], f[2], f[3]));
    accuracy_rings(&mut chart, rings, ring)?;
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
        if !a.truth_is_trajectory {
            chart.draw_series(
                truth
                    .iter()
                    .map(|&p| Circle::new(p, px(3.0), theme.reference.filled())),
            )?;
        }
    }
    let pdr_colour = if fused.is_empty() {
        theme.track
    } else {
        theme.pdr
    };
    // More than one floor: the main track (the fused one, else the PDR track) in one colour
    // per floor, and the legend names the floors.
    let floors = a.floors();
    let by_floor = floors.len() > 1;
    let tracks = Tracks {
        pdr: &pdr,
        fused: &fused,
        smoothed: &smoothed,
        pdr_colour,
        by_floor,
    };
    draw_tracks(&mut chart, a, &tracks, theme, scale)?;
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
    let floor_names: Vec<(String, RGBColor)> = if by_floor {
        floors
            .iter()
            .map(|&f| (crate::analysis::floor_label(f), floor_colour(f, theme)))
            .collect()
    } else {
        Vec::new()
    };
    let entries = entries(a, &tracks, !truth.is_empty(), &floor_names, theme);
    legend(area, &chart, &entries, theme, scale)?;
    north_and_scale(area, &mut chart, theme, scale)?;
    no_heading_note(area, &chart, a, theme, scale)?;
    credit_line(area, &chart, basemap.as_deref(), theme, scale)?;
    Ok(frame_of(&chart))
}

/// Says, over the middle of the map, why a walk without a heading has no track.
fn no_heading_note<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &MapChart<'_, DB>,
    a: &Analysis,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    if let Some(why) = a.no_heading_why() {
        let (rx, ry) = chart.plotting_area().get_pixel_range();
        let font = ("sans-serif", 13.0 * scale)
            .into_font()
            .color(&theme.foreground);
        area.draw(&Text::new(
            format!(
                "No heading ({why}): its {} steps cannot be placed.",
                a.steps.len()
            ),
            (
                rx.start + px(12.0) as i32,
                (ry.start + ry.end) / 2 + px(24.0) as i32,
            ),
            font,
        ))?;
    }
    Ok(())
}

/// The map's tracks, in the fixes' frame: the PDR track, the fused and smoothed ones (empty
/// without fixes), the PDR track's colour, and whether the main track is coloured by floor.
struct Tracks<'a> {
    pdr: &'a [(f64, f64)],
    fused: &'a [(f64, f64)],
    smoothed: &'a [(f64, f64)],
    pdr_colour: RGBColor,
    by_floor: bool,
}

/// Draws the PDR, smoothed and fused tracks, the main one (the fused one, else the PDR track)
/// in runs of one floor's colour when the walk visits more than one.
fn draw_tracks<DB: DrawingBackend>(
    chart: &mut MapChart<'_, DB>,
    a: &Analysis,
    t: &Tracks<'_>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let (fused, by_floor) = (t.fused, t.by_floor);
    let main = if fused.is_empty() { t.pdr } else { fused };
    let main_floors: Vec<i32> = if fused.is_empty() {
        std::iter::once(0)
            .chain(a.steps.iter().map(|s| s.floor))
            .collect()
    } else {
        a.fused.iter().map(|f| floor_at(a, f[0])).collect()
    };
    let draw_line = |chart: &mut _, path: &[(f64, f64)], colour: RGBColor| {
        draw_path(chart, path, ShapeStyle::from(&colour).stroke_width(px(2.5)))
    };
    if !(by_floor && fused.is_empty()) {
        draw_line(chart, t.pdr, t.pdr_colour)?;
    }
    draw_line(chart, t.smoothed, theme.smoothed)?;
    if !by_floor || fused.is_empty() {
        draw_line(chart, fused, theme.track)?;
    }
    if by_floor {
        // Runs of one floor, each joined to the next run's first point so that the line stays
        // whole.
        let mut from = 0;
        for k in 1..=main.len() {
            if k < main.len() && main_floors[k] == main_floors[from] {
                continue;
            }
            let end = (k + 1).min(main.len());
            draw_line(
                chart,
                &main[from..end],
                floor_colour(main_floors[from], theme),
            )?;
            from = k;
        }
    }
    Ok(())
}

/// The legend's entries: the tracks drawn, the floors' colours, the fixes and the truth.
fn entries<'a>(
    a: &Analysis,
    t: &Tracks<'_>,
    truth: bool,
    floor_names: &'a [(String, RGBColor)],
    theme: &Theme,
) -> Vec<(&'a str, Mark)> {
    let (fused, by_floor) = (!t.fused.is_empty(), t.by_floor);
    let mut entries = Vec::new();
    if !by_floor || fused {
        entries.push((
            if fused { "PDR only" } else { "PDR track" },
            Mark::Line(t.pdr_colour),
        ));
    }
    if fused {
        if !by_floor {
            entries.push(("fused", Mark::Line(theme.track)));
        }
        entries.push(("smoothed", Mark::Line(theme.smoothed)));
    }
    for (name, c) in floor_names {
        entries.push((name.as_str(), Mark::Line(*c)));
    }
    if !a.fixes.is_empty() {
        entries.push(("GNSS fixes", Mark::Dot(theme.gnss)));
    }
    if truth {
        entries.push(("truth (aligned)", Mark::Line(theme.reference)));
    }
    entries
}

/// The floor of the step nearest to time `t` (0 without steps).
fn floor_at(a: &Analysis, t: f64) -> i32 {
    a.step_near_time(t).map_or(0, |i| a.steps[i].floor)
}

/// Draws a path as one line.
fn draw_path<DB: DrawingBackend>(
    chart: &mut MapChart<'_, DB>,
    path: &[(f64, f64)],
    style: ShapeStyle,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart.draw_series(LineSeries::new(path.iter().copied(), style))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Zoomed into the middle of a walk, the tracks and the fixes' rings run far past the
    /// plotting area: nothing of them may be left over the axes, labels or margins (plotters
    /// does not clip; `north_and_scale` masks the margins and draws the axes again).
    #[test]
    fn a_zoomed_map_draws_nothing_past_its_plotting_area() {
        use crate::plot::raster;
        let s = crate::sim::scenarios::gnss_city_walk();
        let mut log = crate::io::import::Log::new("demo.pdrlog", crate::io::import::Format::PdrLog);
        log.records = s.generate().records;
        let a = crate::analysis::analyse(&log, &Default::default(), &mut |_, _| {}).unwrap();
        let t = crate::plot::theme::Theme::LIGHT;
        let (w, h) = (500usize, 400usize);
        let (r, px) = raster::new(w as u32, h as u32);
        let (e, n) = a.step_position(a.steps.len() / 2).unwrap();
        let bounds = (e - 10.0, e + 10.0, n - 8.0, n + 8.0);
        let f = draw_map(
            &r.into_drawing_area(),
            &a,
            Some(bounds),
            None,
            None,
            &t,
            1.0,
        )
        .unwrap();
        let (l, rt, tp, b) = f.px;
        let series = [t.track, t.pdr, t.smoothed, t.gnss, t.reference];
        let mut inside = 0;
        let mut outside = Vec::new();
        for (i, p) in px.borrow().iter().enumerate() {
            let (x, y) = ((i % w) as i32, (i / w) as i32);
            if !series.iter().any(|c| *p == (c.0, c.1, c.2)) {
                continue;
            }
            if x >= l && x < rt && y >= tp && y < b {
                inside += 1;
            } else {
                outside.push((x, y));
            }
        }
        assert!(inside > 200, "the zoomed map shows the walk: {inside} px");
        assert!(
            outside.is_empty(),
            "{} series pixels past the plotting area {:?}, e.g. {:?}",
            outside.len(),
            f.px,
            &outside[..outside.len().min(5)]
        );
    }

    #[test]
    fn picks_the_step_under_the_pointer() {
        let mut log = crate::io::import::Log::new("demo.pdrlog", crate::io::import::Format::PdrLog);
        log.records = crate::sim::scenarios::demo_walk().generate().records;
        let a = crate::analysis::analyse(&log, &Default::default(), &mut |_, _| {}).unwrap();
        // 1 m per pixel about the walk.
        let frame = MapFrame {
            px: (0, 400, 0, 300),
            m: (-200.0, 200.0, -150.0, 150.0),
        };
        let mpp = frame.metres_per_px();
        for i in [0, a.steps.len() / 2, a.steps.len() - 1] {
            let (e, n) = a.step_position(i).unwrap();
            let (x, y) = frame.to_pixel(e, n);
            let picked = pick_step(&a, &frame, x, y, 12.0).unwrap();
            let p = a.step_position(picked).unwrap();
            assert!(
                libm::hypot(p.0 - e, p.1 - n) < 1e-9,
                "step {i}: picked {picked}"
            );
            // Off by 5 pixels, the pick is the nearest step, within the radius.
            let picked = pick_step(&a, &frame, x + 5.0, y, 12.0).unwrap();
            let (pe, pn) = a.step_position(picked).unwrap();
            let d = libm::hypot(pe - (e + 5.0 * mpp), pn - n);
            assert!(
                d <= 5.0 * mpp + 1e-9 && d <= 12.0 * mpp,
                "step {i}: {picked} at {d} m"
            );
        }
        // Nothing within 12 pixels of a corner far from the walk.
        assert_eq!(pick_step(&a, &frame, 0.0, 0.0, 12.0), None);
    }
}
