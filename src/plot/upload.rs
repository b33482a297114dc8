//! Upload mode's plots of an [`Analysis`](crate::analysis::Analysis): the map (zoomable), the
//! time-aligned diagnostics, and the horizontal-acceleration ellipse of one stride (Basso 2016
//! Fig. 5).
//!
//! One file each: the map (`map`), the diagnostics plots (`plots`), the decimation of their
//! signals to pixel columns (`decimate`), the unwrapping of their headings (`heading`), the
//! height and floor plot's series (`height`), the fusion plot's series and ±1σ bands
//! (`fusion`), every plot's series computed apart from their drawing (`series`), the colours of the activities, carrying modes and floors, with the titles and keys
//! (`palette`), the time axis's gestures (`time_axis`), the plots' legibility test
//! (`legibility`) and the ellipse (`ellipse`).
//! May import: `engine`, `analysis` and the rest of `plot`; never `web`, `live` or `eval`.

mod decimate;
mod ellipse;
mod fusion;
mod heading;
mod height;
mod map;
mod palette;
mod plots;
mod series;
mod time_axis;

#[cfg(test)]
pub(crate) mod legibility;

pub use crate::plot::MapFrame;
pub use ellipse::draw_ellipse;
pub use map::{draw_map, pick_step};
pub use palette::{activity_colour, floor_colour};
pub use plots::draw_plot_area;
pub use series::Plot;
pub use time_axis::TimeAxis;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster;
    use crate::plot::Theme;
    use plotters::prelude::*;

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
        let back = crate::analysis::Analysis::from_bytes(&a.to_bytes().unwrap()).unwrap();
        assert_eq!(back.steps, a.steps);
        assert_eq!(back.trace.t, a.trace.t);
        let t = Theme::LIGHT;
        let (r, px) = raster::new(500, 400);
        let f = draw_map(&r.into_drawing_area(), &a, None, Some(10), None, &t, 1.0).unwrap();
        assert!(raster::count(&px, t.track) > 300 && raster::count(&px, t.gnss) > 100);
        // The frame maps pixels back to metres: the plot's corners are its bounds.
        let (e, n) = f.to_metres(f.px.0 as f64, f.px.2 as f64);
        assert!((e - f.m.0).abs() < 1e-9 && (n - f.m.3).abs() < 1e-9);
        let span = (a.trace.t[0], *a.trace.t.last().unwrap());
        let mut axes = Vec::new();
        for (plot, colour) in [
            (Plot::Accel, t.track),
            (Plot::Sigma, t.track),
            (Plot::Height, t.gnss),
            (Plot::Heading, t.track),
            (Plot::Steps, t.track),
            (Plot::Gnss, t.gnss),
            (Plot::Fusion, t.track),
        ] {
            let (r, px) = raster::new(600, 200);
            let ((left, right), _) = draw_plot_area(
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
        draw_plot_area(
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

    /// A hand-made walk on three floors (the engine cannot make one yet): the map colours the
    /// track by floor, the timeline shows the stairs, the height plot the climb, and every plot
    /// keeps the one time axis.
    #[test]
    fn draws_the_floors_heights_and_activities_of_a_three_floor_walk() {
        let a = crate::analysis::three_floor_analysis();
        let t = Theme::LIGHT;
        let (r, px) = raster::new(500, 400);
        draw_map(&r.into_drawing_area(), &a, None, None, None, &t, 1.0).unwrap();
        for f in [0, 1, 2] {
            let n = raster::count(&px, floor_colour(f, &t));
            assert!(n > 100, "floor {f}: {n} px");
        }
        // The flat walk: the track in its one colour, no floor's.
        let mut flat = a.clone();
        flat.vertical = None;
        flat.trace.floor.iter_mut().for_each(|f| *f = 0);
        flat.steps.iter_mut().for_each(|s| s.floor = 0);
        let (r, px) = raster::new(500, 400);
        draw_map(&r.into_drawing_area(), &flat, None, None, None, &t, 1.0).unwrap();
        assert!(raster::count(&px, t.track) > 300);
        // (Floor +1's colour is the GNSS fixes', which the demo walk has none of.)
        assert_eq!(raster::count(&px, floor_colour(1, &t)), 0);
        let span = (a.trace.t[0], *a.trace.t.last().unwrap());
        let mut axes = Vec::new();
        for plot in Plot::ALL {
            let (r, px) = raster::new(600, 200);
            let (cols, rows) =
                draw_plot_area(&r.into_drawing_area(), &a, plot, span, None, &t, 1.0).unwrap();
            axes.push(cols);
            match plot {
                Plot::Sigma => {
                    // The band: walking, upstairs, downstairs, standing and sitting.
                    for act in [
                        crate::engine::Activity::Walking,
                        crate::engine::Activity::Upstairs,
                        crate::engine::Activity::Downstairs,
                    ] {
                        let c = activity_colour(act, &t).unwrap();
                        let n = raster::count(&px, c);
                        assert!(n > 40, "{act:?}: {n} px");
                    }
                }
                Plot::Height => {
                    // The height line climbs to 6 m: blue pixels in the plot's upper half.
                    let p = px.borrow();
                    let blue = (t.track.0, t.track.1, t.track.2);
                    let mid = (rows.0 + rows.1) / 2;
                    let high = (rows.0..mid)
                        .flat_map(|y| (cols.0..cols.1).map(move |x| (x, y)))
                        .filter(|&(x, y)| p[(y * 600 + x) as usize] == blue)
                        .count();
                    assert!(high > 50, "height line above the middle: {high} px");
                    assert!(raster::count(&px, t.gnss) > 200, "floor staircase");
                }
                _ => {}
            }
        }
        assert!(axes.iter().all(|x| *x == axes[0]), "{axes:?}");
    }
}
