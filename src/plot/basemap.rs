//! The opt-in base map under a map's track: the tiles of the visible area painted first (by
//! whoever holds the images: the page's canvas), a veil of the background colour so the track
//! stays legible over them, and the tile server's credit line on the map.
//! May import: `engine` (the geodetic origin), the map frame, the theme and the tile maths;
//! never `web`, `live` or `eval`.

use super::frame::{map_chart_over, MapChart, MapFrame};
use super::theme::Theme;
use super::tiles::{visible_tiles, Piece, Tile, TileTemplate};
use crate::engine::geo::LocalFrame;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// What became of one tile when it was to be painted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TileState {
    /// Painted.
    Drawn,
    /// Requested, not here yet (the map is drawn again when it arrives).
    Loading,
    /// The server refused it or it could not be read.
    Failed,
}

/// A base map for one drawing: where the map is on Earth, which tile server, and the painter
/// that puts a tile's image over a pixel rectangle of the canvas.
pub struct Basemap<'a> {
    /// The local frame the map's metres are in.
    pub origin: LocalFrame,
    /// The tile server.
    pub tiles: &'a TileTemplate,
    /// Paints the part `Piece` of the tile (its URL given), or says why it cannot yet.
    pub paint: &'a mut dyn FnMut(&Tile, &Piece, &str) -> TileState,
    /// What the last drawing showed (set by the map that drew it).
    pub shown: Option<Shown>,
}

/// What the base map showed: the line drawn in the map's corner.
#[derive(Debug, Clone, PartialEq)]
pub struct Shown {
    /// The credit line, with what is missing when some tiles are not there.
    pub line: String,
    /// Tiles on the map, painted, still loading, failed.
    pub counts: (usize, usize, usize),
}

/// How much of the background colour covers the tiles: light enough in the light scheme to read
/// the streets, more in the dark one so that bright tiles do not outshine the track.
pub fn veil_alpha(theme: &Theme) -> f64 {
    let b = theme.background;
    if u32::from(b.0) + u32::from(b.1) + u32::from(b.2) < 3 * 128 {
        0.6
    } else {
        0.3
    }
}

/// Paints the tiles under a map drawn in `frame` (before its grid and track), then the veil over
/// the plotting area, and keeps what it showed in `basemap.shown`. A view the base map cannot
/// show (wider than [`super::tiles::MAX_VIEW_M`]) draws no tile and says so in the credit line.
pub fn draw_under<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    frame: &MapFrame,
    basemap: &mut Basemap<'_>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    basemap.shown = Some(under(area, frame, basemap, theme, scale)?);
    Ok(())
}

fn under<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    frame: &MapFrame,
    basemap: &mut Basemap<'_>,
    theme: &Theme,
    scale: f64,
) -> Result<Shown, DrawingAreaErrorKind<DB::ErrorType>> {
    let tiles = match visible_tiles(frame, &basemap.origin, scale, super::tiles::MAX_ZOOM) {
        Ok(t) => t,
        Err(e) => {
            return Ok(Shown {
                line: format!("No base map: {e}"),
                counts: (0, 0, 0),
            })
        }
    };
    let (mut drawn, mut loading, mut failed) = (0, 0, 0);
    for (t, piece) in tiles.iter().filter_map(|t| Some((t, t.clipped(frame.px)?))) {
        match (basemap.paint)(t, &piece, &basemap.tiles.url(t)) {
            TileState::Drawn => drawn += 1,
            TileState::Loading => loading += 1,
            TileState::Failed => failed += 1,
        }
    }
    let (l, r, t, b) = frame.px;
    area.draw(&Rectangle::new(
        [(l, t), (r, b)],
        theme.background.mix(veil_alpha(theme)).filled(),
    ))?;
    let credit = basemap.tiles.attribution();
    let line = if failed > 0 {
        format!(
            "{credit} · {failed} of {} tiles failed to load from {}",
            tiles.len(),
            basemap.tiles.host()
        )
    } else if loading > 0 {
        format!("{credit} · loading {loading} tiles")
    } else {
        credit.to_string()
    };
    Ok(Shown {
        line,
        counts: (drawn, loading, failed),
    })
}

/// The map chart of [`super::frame::map_chart_in`] over the base map, when there is one.
pub(crate) fn map_chart_under<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    points: impl Iterator<Item = (f64, f64)>,
    bounds: Option<(f64, f64, f64, f64)>,
    basemap: Option<&mut Basemap<'_>>,
    theme: &Theme,
    scale: f64,
) -> Result<MapChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    match basemap {
        Some(b) => map_chart_over(
            area,
            points,
            bounds,
            Some(&mut |area: &DrawingArea<DB, Shift>, frame: &MapFrame| {
                draw_under(area, frame, b, theme, scale)
            }),
            theme,
            scale,
        ),
        None => map_chart_over(area, points, bounds, None, theme, scale),
    }
}

/// The credit line of the base map drawn by [`draw_under`], if any, in the bottom-right corner
/// of the plotting area on a box of the background colour (the tile licences ask for it to be
/// visible on the map). Drawn last, over the track.
pub fn credit_line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &MapChart<'_, DB>,
    basemap: Option<&Basemap<'_>>,
    theme: &Theme,
    scale: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let Some(line) = basemap
        .and_then(|b| b.shown.as_ref())
        .map(|s| s.line.as_str())
    else {
        return Ok(());
    };
    let px = |v: f64| (v * scale).round().max(1.0) as i32;
    let font = ("sans-serif", 11.0 * scale)
        .into_font()
        .color(&theme.foreground);
    let (rx, ry) = chart.plotting_area().get_pixel_range();
    let (w, h) = area.estimate_text_size(line, &font)?;
    let (x, y) = (rx.end - px(4.0), ry.end - px(3.0));
    area.draw(&Rectangle::new(
        [
            (x - w as i32 - px(4.0), y - h as i32 - px(1.0)),
            (rx.end, ry.end),
        ],
        theme.background.mix(0.85).filled(),
    ))?;
    area.draw(&Text::new(
        line.to_string(),
        (x, y),
        font.pos(Pos::new(HPos::Right, VPos::Bottom)),
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::raster;

    #[test]
    fn the_veil_is_lighter_in_the_light_scheme() {
        assert_eq!(veil_alpha(&Theme::LIGHT), 0.3);
        assert_eq!(veil_alpha(&Theme::DARK), 0.6);
    }

    /// A tile URL of the test server: a tile of zoom 14 to 17 within three tiles of the
    /// place (around 43.77° N, 11.26° E: Florence, where the demo walks).
    fn assert_near_florence(url: &str, lat: f64, lon: f64) {
        let parts: Vec<u32> = url
            .trim_start_matches("https://tiles.test/")
            .trim_end_matches(".png")
            .split('/')
            .map(|s| s.parse().unwrap())
            .collect();
        let (z, x, y) = (parts[0] as u8, parts[1], parts[2]);
        let (tx, ty) = crate::plot::tiles::tile_xy(lat, lon, z).unwrap();
        assert!((14..=17).contains(&z), "{url}");
        assert!(
            x.abs_diff(tx as u32) <= 3 && y.abs_diff(ty as u32) <= 3,
            "{url}"
        );
    }

    /// The fusion demo drawn over a base map whose painter fills each tile with a checker
    /// colour: the tiles show under the whole plotting area (veiled), the track over them, and
    /// the painter was asked for the tiles of Florence, where the demo walks.
    #[test]
    fn tiles_are_painted_under_the_track() {
        let demo = crate::demo::run_fusion_demo();
        let (lat, lon, h) = demo.origin;
        let (w, h_px) = (500u32, 400u32);
        let (r, pixels) = raster::new(w, h_px);
        let area = r.into_drawing_area();
        let template = TileTemplate::parse("https://tiles.test/{z}/{x}/{y}.png", "").unwrap();
        let (a, b) = (RGBColor(0x40, 0xa0, 0x40), RGBColor(0x40, 0x40, 0xa0));
        let mut urls = Vec::new();
        let shared = pixels.clone();
        let mut plot_area = None;
        let mut paint = |t: &Tile, piece: &Piece, url: &str| {
            urls.push(url.to_string());
            let c = if (t.x + t.y) % 2 == 0 { a } else { b };
            let mut p = shared.borrow_mut();
            let (l, top, r, bottom) = piece.dst;
            plot_area = Some(plot_area.map_or(
                piece.dst,
                |(l0, t0, r0, b0): (i32, i32, i32, i32)| {
                    (l0.min(l), t0.min(top), r0.max(r), b0.max(bottom))
                },
            ));
            for y in top.max(0)..bottom.min(h_px as i32) {
                for x in l.max(0)..r.min(w as i32) {
                    p[(y as u32 * w + x as u32) as usize] = (c.0, c.1, c.2);
                }
            }
            TileState::Drawn
        };
        let mut basemap = Basemap {
            origin: LocalFrame::new(lat, lon, h),
            tiles: &template,
            paint: &mut paint,
            shown: None,
        };
        let view = crate::plot::fusion::view_of(&demo);
        crate::plot::draw_fusion(&area, &view, Some(&mut basemap), &Theme::LIGHT, 1.0).unwrap();
        let shown = basemap.shown.expect("a base map was drawn");
        // Within the plotting area only: the axis labels' margin keeps the background.
        let (l, t0, r, b0) = plot_area.expect("tiles were painted");
        assert!(
            l > 20 && t0 > 0 && r < w as i32 && b0 < h_px as i32 - 20,
            "{l} {t0} {r} {b0}"
        );
        assert_eq!(shown.line, "Map tiles: tiles.test");
        assert!(shown.counts.0 >= 1 && shown.counts.1 == 0 && shown.counts.2 == 0);
        // Florence at the zoom of a walk.
        assert!(!urls.is_empty());
        for u in &urls {
            assert_near_florence(u, lat, lon);
        }
        // The checker colours, under the veil (the background at 0.3, blended as the canvas
        // does), fill most of the map; the track is drawn over them.
        let t = Theme::LIGHT;
        let veiled = |c: RGBColor| {
            let v = veil_alpha(&t);
            let mix =
                |new: u8, old: u8| (v * f64::from(new) + (1.0 - v) * f64::from(old)).round() as u8;
            let g = t.background;
            (mix(g.0, c.0), mix(g.1, c.1), mix(g.2, c.2))
        };
        let p = pixels.borrow();
        let tile_px = p
            .iter()
            .filter(|px| **px == veiled(a) || **px == veiled(b))
            .count();
        assert!(
            tile_px > (w * h_px) as usize / 2,
            "{tile_px} of {} pixels show a tile",
            w * h_px
        );
        drop(p);
        let track = raster::count(&pixels, t.track);
        assert!(track > 100, "track {track}");
    }
}
