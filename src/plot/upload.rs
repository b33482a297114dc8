//! Upload mode's plots of an [`Analysis`](crate::analysis::Analysis): the map (zoomable), the
//! time-aligned diagnostics, and the horizontal-acceleration ellipse of one stride (Basso 2016
//! Fig. 5).
//!
//! One file each: the map (`map`), the diagnostics plots (`plots`), the decimation of their
//! signals to pixel columns (`decimate`), the unwrapping of their headings (`heading`), their
//! legibility test (`legibility`) and the ellipse (`ellipse`).
//! May import: `engine`, `analysis` and the rest of `plot`; never `web`, `live` or `eval`.

mod decimate;
mod ellipse;
mod heading;
mod map;
mod plots;

#[cfg(test)]
pub(crate) mod legibility;

pub use crate::plot::MapFrame;
pub use ellipse::draw_ellipse;
pub use map::{draw_map, pdr_points, pick_step};
pub use plots::{draw_plot, draw_plot_area, Plot, TimeAxis};

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
