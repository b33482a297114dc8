//! The legibility test of the diagnostics plots: every plot, drawn for a whole long walk and at
//! 10 s and 1 s windows, on a phone's and a desktop's canvas, in both themes, is not a solid
//! block of one colour (compiled for tests only).
//! May import: the plots, the raster and the analysis; never `web`, `live` or `eval`.

use super::plots::draw_plot_area;
use super::series::Plot;
use crate::analysis::Analysis;
use crate::plot::raster;
use crate::plot::Theme;
use plotters::prelude::*;

/// The largest share of the plot area's pixels any one colour other than the background, the
/// grid and the axes covers. A legible plot leaves most of its area to the background.
pub(crate) const MAX_DOMINANT_SHARE: f64 = 0.35;

/// The share of the plot area (`cols` × `rows`) covered by its most common colour that is not
/// the background, a grid line or the axes' colour, and that colour.
pub(crate) fn dominant_share(
    px: &raster::Pixels,
    w: u32,
    (cols, rows): ((i32, i32), (i32, i32)),
    theme: &Theme,
) -> (f64, (u8, u8, u8)) {
    let skip = [theme.background, theme.grid, theme.foreground].map(|c| (c.0, c.1, c.2));
    let mut counts = std::collections::HashMap::new();
    let px = px.borrow();
    for y in rows.0.max(0)..rows.1 {
        for x in cols.0.max(0)..cols.1 {
            let p = px[(y as u32 * w + x as u32) as usize];
            if !skip.contains(&p) {
                *counts.entry(p).or_insert(0usize) += 1;
            }
        }
    }
    let area = ((cols.1 - cols.0) * (rows.1 - rows.0)).max(1) as f64;
    counts
        .into_iter()
        .max_by_key(|(_, n)| *n)
        .map_or((0.0, (0, 0, 0)), |(c, n)| (n as f64 / area, c))
}

/// Each plot of `a` at full zoom, 10 s and 1 s (in the middle of the log), on a phone (a
/// 390 px page at three device pixels each) and a desktop (840 px at one), light and dark:
/// the name of each drawing and its dominant share.
pub(crate) fn shares(a: &Analysis) -> Vec<(String, f64)> {
    let (first, last) = (a.trace.t[0], *a.trace.t.last().unwrap());
    let mid = (first + last) / 2.0;
    let mut out = Vec::new();
    for plot in Plot::ALL {
        for (zoom, span) in [
            ("full", (first, last)),
            ("10s", (mid, mid + 10.0)),
            ("1s", (mid, mid + 1.0)),
        ] {
            // The page's heights: 170 CSS px, the acceleration's two lanes 230.
            let css_h = if plot == Plot::Accel { 230 } else { 170 };
            for (device, w, h, scale) in [
                ("phone", 1050, 3 * css_h, 3.0),
                ("desktop", 840, css_h, 1.0),
            ] {
                for (name, theme) in [("light", Theme::LIGHT), ("dark", Theme::DARK)] {
                    let (r, px) = raster::new(w, h);
                    let area =
                        draw_plot_area(&r.into_drawing_area(), a, plot, span, None, &theme, scale)
                            .unwrap();
                    let (share, colour) = dominant_share(&px, w, area, &theme);
                    if let Ok(dir) = std::env::var("PDR_PLOT_DUMP") {
                        dump(
                            &px,
                            w,
                            h,
                            &format!("{dir}/{plot:?}-{zoom}-{device}-{name}.ppm"),
                        );
                    }
                    out.push((
                        format!("{plot:?} {zoom} {device} {name} ({colour:?})"),
                        share,
                    ));
                }
            }
        }
    }
    out
}

/// Writes the raster as a binary PPM (set `PDR_PLOT_DUMP` to a folder to look at the drawings;
/// the raster draws no text).
fn dump(px: &raster::Pixels, w: u32, h: u32, path: &str) {
    let mut out = format!("P6 {w} {h} 255\n").into_bytes();
    out.extend(px.borrow().iter().flat_map(|p| [p.0, p.1, p.2]));
    std::fs::write(path, out).unwrap();
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(a: &Analysis) {
        let mut worst = (String::new(), 0.0);
        let mut bad = Vec::new();
        for (name, share) in shares(a) {
            println!("{name}: {:.1} %", 100.0 * share);
            if share > worst.1 {
                worst = (name.clone(), share);
            }
            if share > MAX_DOMINANT_SHARE {
                bad.push(format!("{name}: {:.1} %", 100.0 * share));
            }
        }
        println!("worst: {} {:.1} %", worst.0, 100.0 * worst.1);
        assert!(
            bad.is_empty(),
            "plots covered by one colour beyond {} %:\n{}",
            100.0 * MAX_DOMINANT_SHARE,
            bad.join("\n")
        );
    }

    #[test]
    fn no_plot_of_the_simulated_city_walk_is_a_block_of_one_colour() {
        let sim = crate::sim::scenarios::gnss_city_walk().generate();
        let mut log = crate::io::import::Log::new("city.pdrlog", crate::io::import::Format::PdrLog);
        log.records = sim.records;
        let a = crate::analysis::analyse(&log, &Default::default(), &mut |_, _| {}).unwrap();
        check(&a);
    }

    #[test]
    fn the_heading_plot_bands_each_steps_carrying_mode_and_the_gyroscope() {
        use super::super::palette::carry_colour;
        use crate::engine::carry::CarryMode;
        let mut a = crate::analysis::three_floor_analysis();
        assert!(a.steps.len() > 20);
        let (t0, t1) = (a.trace.t[0], *a.trace.t.last().unwrap());
        // The first half of the time in a pocket, the second in the hand; every third step held
        // on the gyroscope.
        for (i, s) in a.steps.iter_mut().enumerate() {
            s.carry = Some(if s.t < 0.5 * (t0 + t1) {
                CarryMode::Pocket
            } else {
                CarryMode::Hand
            });
            s.gyro_heading = i % 3 == 0;
        }
        let theme = Theme::LIGHT;
        let (w, h) = (840, 170);
        let (r, px) = raster::new(w, h);
        let ((c0, c1), (_, r1)) = draw_plot_area(
            &r.into_drawing_area(),
            &a,
            Plot::Heading,
            (t0, t1),
            None,
            &theme,
            1.0,
        )
        .unwrap();
        // Which colours the band rows (the bottom 10 % of the plot) hold, left half and right.
        let px = px.borrow();
        let count = |c: plotters::style::RGBColor, left: bool| {
            let (x0, x1) = if left {
                (c0, (c0 + c1) / 2)
            } else {
                ((c0 + c1) / 2, c1)
            };
            (r1 - 14..r1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| px[(y as u32 * w + x as u32) as usize] == (c.0, c.1, c.2))
                .count()
        };
        let (pocket, hand) = (
            carry_colour(CarryMode::Pocket, &theme),
            carry_colour(CarryMode::Hand, &theme),
        );
        // (One step may straddle the middle: a few pixels.)
        let (pl, pr, hl, hr) = (
            count(pocket, true),
            count(pocket, false),
            count(hand, true),
            count(hand, false),
        );
        assert!(
            pl > 1000 && pr < 50 && hr > 1000 && hl < 50,
            "{pl} {pr} {hl} {hr}"
        );
        assert!(count(theme.reference, true) > 30 && count(theme.reference, false) > 30);
    }

    #[test]
    fn no_plot_of_a_three_floor_walk_is_a_block_of_one_colour() {
        check(&crate::analysis::three_floor_analysis());
    }

    #[test]
    fn no_plot_of_a_real_ipin_walk_is_a_block_of_one_colour() {
        use crate::io::import::{fileset::DirSet, import_all};
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/ipin2023");
        let file = "IPIN2023_T3_TrainingTrial01_repetition01.txt";
        if !dir.join(file).exists() {
            println!(
                "skipped: {} not found (the shared data set is not beside this checkout)",
                dir.display()
            );
            return;
        }
        let mut set = DirSet::new(&dir.join(file)).unwrap();
        let log = import_all(&mut set).remove(0).unwrap();
        let a = crate::analysis::analyse(&log, &Default::default(), &mut |_, _| {}).unwrap();
        check(&a);
    }
}
