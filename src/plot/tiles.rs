//! Web Mercator ("slippy map") tile maths for the opt-in base map: latitude and longitude ↔ tile
//! coordinates at a zoom, the zoom whose tiles best match a map's metres per pixel, the tiles a
//! drawn map shows with the pixel rectangle each covers, and the tile server's URL template
//! (checked, substituted, attributed).
//! May import: `engine` (the local frame's geodetic origin) and the map frame; never `web`,
//! `live` or `eval`.
//!
//! The map is drawn in metres of the engine's local East-North-Up frame; the tiles are squares
//! of the spherical Web Mercator projection (EPSG:3857) of WGS84 latitude and longitude. Over a
//! walk (a few km) the two differ by far less than a pixel once each tile edge is placed through
//! the exact geodetic conversion, so the tiles are drawn as axis-aligned rectangles whose edges
//! are computed once per column and once per row: neighbours share their edge, there is never a
//! gap or an overlap.

use super::frame::MapFrame;
use crate::engine::geo::LocalFrame;

/// The largest latitude Web Mercator shows, degrees: atan(sinh(π)), where the square world ends.
pub const MAX_LATITUDE_DEG: f64 = 85.051_128_779_806_59;
/// Ground metres per pixel of a 256-pixel tile at zoom 0 on the equator (2π · 6 378 137 / 256).
const EQUATOR_M_PER_PX_Z0: f64 = 156_543.033_928_041;
/// The deepest zoom any template may ask for (OpenStreetMap's standard tiles stop at 19).
pub const MAX_ZOOM: u8 = 19;
/// At most this many tiles on one map; a larger view takes the next coarser zoom (a 4K screen
/// at one device pixel per CSS pixel needs 16 × 10).
pub const MAX_TILES: usize = 192;
/// No base map over a view wider than this, m: the local tangent plane is meant for a walk.
pub const MAX_VIEW_M: f64 = 200_000.0;
/// The default tile server: OpenStreetMap's standard tiles.
pub const OSM_TEMPLATE: &str = "https://tile.openstreetmap.org/{z}/{x}/{y}.png";
/// The attribution OpenStreetMap's licence (ODbL) asks for, with its copyright page.
pub const OSM_ATTRIBUTION: &str = "© OpenStreetMap contributors";

/// Why there is no tile, or no template.
#[derive(Debug, Clone, PartialEq)]
pub enum TileError {
    /// A coordinate or a frame was not a finite number, or empty.
    NotFinite(&'static str),
    /// A zoom beyond [`MAX_ZOOM`].
    Zoom(u8),
    /// The view is wider than [`MAX_VIEW_M`].
    TooWide(f64),
    /// The URL template is unusable; the text says why.
    Template(String),
}

impl std::fmt::Display for TileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TileError::NotFinite(what) => write!(f, "the base map needs a finite {what}"),
            TileError::Zoom(z) => write!(f, "tile zoom {z} is beyond the deepest, {MAX_ZOOM}"),
            TileError::TooWide(m) => write!(
                f,
                "the view is {:.0} km wide; the base map shows views up to {:.0} km",
                m / 1e3,
                MAX_VIEW_M / 1e3
            ),
            TileError::Template(why) => write!(f, "tile URL template: {why}"),
        }
    }
}

impl std::error::Error for TileError {}

/// Fractional tile coordinates (x east, y south; the integer part names the tile) of a latitude
/// and longitude (degrees) at zoom `z`. Latitude is clamped to ±[`MAX_LATITUDE_DEG`]; longitude
/// is not wrapped (x beyond 0‥2^z lies in the world's repeat, see [`wrap_x`]).
pub fn tile_xy(lat_deg: f64, lon_deg: f64, z: u8) -> Result<(f64, f64), TileError> {
    if !(lat_deg.is_finite() && lon_deg.is_finite()) {
        return Err(TileError::NotFinite("latitude and longitude"));
    }
    if z > MAX_ZOOM {
        return Err(TileError::Zoom(z));
    }
    let n = f64::from(1u32 << z);
    let lat = lat_deg
        .clamp(-MAX_LATITUDE_DEG, MAX_LATITUDE_DEG)
        .to_radians();
    let x = (lon_deg + 180.0) / 360.0 * n;
    let y = (1.0 - libm::asinh(libm::tan(lat)) / std::f64::consts::PI) / 2.0 * n;
    Ok((x, y))
}

/// Latitude and longitude (degrees) of fractional tile coordinates at zoom `z` (the inverse of
/// [`tile_xy`]; the tile (x, y)'s north-west corner for integer coordinates).
pub fn tile_lat_lon(x: f64, y: f64, z: u8) -> (f64, f64) {
    let n = f64::from(1u32 << z.min(MAX_ZOOM));
    let lon = x / n * 360.0 - 180.0;
    let lat = libm::atan(libm::sinh(std::f64::consts::PI * (1.0 - 2.0 * y / n))).to_degrees();
    (lat, lon)
}

/// A tile column in the world's repeat 0‥2^z (across the antimeridian x = −1 is 2^z − 1).
pub fn wrap_x(x: i64, z: u8) -> u32 {
    x.rem_euclid(1i64 << z.min(MAX_ZOOM)) as u32
}

/// Ground metres per tile pixel at latitude `lat_deg` and zoom `z` (256-pixel tiles).
pub fn metres_per_tile_px(lat_deg: f64, z: u8) -> f64 {
    let lat = lat_deg
        .clamp(-MAX_LATITUDE_DEG, MAX_LATITUDE_DEG)
        .to_radians();
    EQUATOR_M_PER_PX_Z0 * libm::cos(lat) / f64::from(1u32 << z.min(MAX_ZOOM))
}

/// The zoom (0‥`max_zoom`) whose tile pixels are nearest, on a log scale, to `metres_per_px`
/// at latitude `lat_deg`: a tile is then drawn at 0.71 to 1.41 times its own size.
pub fn zoom_for(metres_per_px: f64, lat_deg: f64, max_zoom: u8) -> Result<u8, TileError> {
    if !(metres_per_px.is_finite() && metres_per_px > 0.0 && lat_deg.is_finite()) {
        return Err(TileError::NotFinite("scale"));
    }
    let z0 = metres_per_tile_px(lat_deg, 0);
    let z = libm::log2(z0 / metres_per_px).round();
    Ok(z.clamp(0.0, f64::from(max_zoom.min(MAX_ZOOM))) as u8)
}

/// One tile on a drawn map: its zoom and (wrapped) column and row, and the pixel rectangle it
/// covers on the canvas (left, top, right, bottom; may reach beyond the plotting area).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tile {
    /// Zoom.
    pub z: u8,
    /// Column, 0‥2^z.
    pub x: u32,
    /// Row, 0‥2^z.
    pub y: u32,
    /// Canvas pixels: left, top, right, bottom.
    pub rect: (i32, i32, i32, i32),
}

/// The part of a tile inside a clip rectangle: which part of its image, to which pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Of the tile's image, as fractions of its width and height: left, top, right, bottom.
    pub src: (f64, f64, f64, f64),
    /// Canvas pixels: left, top, right, bottom.
    pub dst: (i32, i32, i32, i32),
}

impl Tile {
    /// The part of the tile inside `clip` (left, right, top, bottom, as [`MapFrame::px`]), or
    /// None when none of it is: a map's tiles are drawn within its plotting area only.
    pub fn clipped(&self, clip: (i32, i32, i32, i32)) -> Option<Piece> {
        let (l, t, r, b) = self.rect;
        let (cl, cr, ct, cb) = clip;
        let dst = (l.max(cl), t.max(ct), r.min(cr), b.min(cb));
        if dst.0 >= dst.2 || dst.1 >= dst.3 || r <= l || b <= t {
            return None;
        }
        let fx = |x: i32| f64::from(x - l) / f64::from(r - l);
        let fy = |y: i32| f64::from(y - t) / f64::from(b - t);
        Some(Piece {
            src: (fx(dst.0), fy(dst.1), fx(dst.2), fy(dst.3)),
            dst,
        })
    }
}

/// The longitude `lon` moved by whole turns to within 180° of `near`.
fn unwrap_lon(lon: f64, near: f64) -> f64 {
    near + (lon - near + 180.0).rem_euclid(360.0) - 180.0
}

/// The tiles under a map drawn in `frame` with the local frame `origin`, at the zoom that
/// matches the map's scale in CSS pixels (`scale` device pixels each, so that a tile's labels
/// read at their designed size), at most [`MAX_TILES`] of them and no deeper than `max_zoom`.
/// Rows beyond ±85.05° have no tile; columns across the antimeridian wrap.
pub fn visible_tiles(
    frame: &MapFrame,
    origin: &LocalFrame,
    scale: f64,
    max_zoom: u8,
) -> Result<Vec<Tile>, TileError> {
    let (e0, e1, n0, n1) = frame.m;
    let (l, r, t, b) = frame.px;
    if !([e0, e1, n0, n1, scale].iter().all(|v| v.is_finite()) && e1 > e0 && n1 > n0)
        || r <= l
        || b <= t
        || !(scale > 0.0)
    {
        return Err(TileError::NotFinite("map frame"));
    }
    let wide = (e1 - e0).max(n1 - n0);
    if wide > MAX_VIEW_M {
        return Err(TileError::TooWide(wide));
    }
    let geo = |e: f64, n: f64| {
        let (lat, lon, _) = origin.to_geodetic([e, n, 0.0]);
        (lat, unwrap_lon(lon, origin.lon0_deg))
    };
    let (ec, nc) = ((e0 + e1) / 2.0, (n0 + n1) / 2.0);
    let (lat_c, _) = geo(ec, nc);
    let mut z = zoom_for(frame.metres_per_px() * scale, lat_c, max_zoom)?;
    loop {
        let at = |e: f64, n: f64| {
            let (lat, lon) = geo(e, n);
            tile_xy(lat, lon, z)
        };
        let (xl, _) = at(e0, nc)?;
        let (xr, _) = at(e1, nc)?;
        let (xc, _) = at(ec, nc)?;
        let (_, yt) = at(ec, n1)?;
        let (_, yb) = at(ec, n0)?;
        let (_, yc) = at(ec, nc)?;
        let n = i64::from(1u32 << z);
        let cols = xl.floor() as i64..=xr.floor() as i64;
        let rows = (yt.floor() as i64).max(0)..=(yb.floor() as i64).min(n - 1);
        let count = (cols.end() - cols.start() + 1).max(0) * (rows.end() - rows.start() + 1).max(0);
        if count as usize > MAX_TILES && z > 0 {
            z -= 1;
            continue;
        }
        // Each column edge and each row edge once, through the exact conversion, rounded:
        // neighbouring tiles share them.
        let edge_x = |i: i64| {
            let (lat, lon) = tile_lat_lon(i as f64, yc, z);
            let [e, n, _] = origin.to_enu(lat, lon, origin.h0_m);
            frame.to_pixel(e, n).0.round() as i32
        };
        let edge_y = |j: i64| {
            let (lat, lon) = tile_lat_lon(xc, j as f64, z);
            let [e, n, _] = origin.to_enu(lat, lon, origin.h0_m);
            frame.to_pixel(e, n).1.round() as i32
        };
        let xs: Vec<(i64, i32)> = (*cols.start()..=*cols.end() + 1)
            .map(|i| (i, edge_x(i)))
            .collect();
        let ys: Vec<(i64, i32)> = (*rows.start()..=*rows.end() + 1)
            .map(|j| (j, edge_y(j)))
            .collect();
        let mut out = Vec::with_capacity(count.max(0) as usize);
        for wy in ys.windows(2) {
            for wx in xs.windows(2) {
                out.push(Tile {
                    z,
                    x: wrap_x(wx[0].0, z),
                    y: wy[0].0 as u32,
                    rect: (wx[0].1, wy[0].1, wx[1].1, wy[1].1),
                });
            }
        }
        return Ok(out);
    }
}

/// A tile server's URL template, checked: `https://` (the page's Content-Security-Policy lets
/// images come from https: origins only), a host, and `{z}`, `{x}` and `{y}`; `{s}` picks one
/// of the subdomains a, b, c. Nothing else in braces, no spaces or quotes.
#[derive(Debug, Clone, PartialEq)]
pub struct TileTemplate {
    template: String,
    host: String,
    attribution: String,
}

impl TileTemplate {
    /// Checks `template` and keeps `attribution` (the tile server's credit line; empty: the
    /// OpenStreetMap credit for OpenStreetMap's servers, else "Map tiles: HOST").
    pub fn parse(template: &str, attribution: &str) -> Result<TileTemplate, TileError> {
        let bad = |why: String| Err(TileError::Template(why));
        let t = template.trim();
        if t.is_empty() {
            return bad("it is empty".into());
        }
        if t.len() > 2048 {
            return bad(format!("it is {} characters long (at most 2048)", t.len()));
        }
        let Some(rest) = t.strip_prefix("https://") else {
            return bad(format!(
                "\"{t}\" must start with https:// (the page loads map images over https only)"
            ));
        };
        if let Some(c) = t
            .chars()
            .find(|c| c.is_whitespace() || c.is_control() || "\"'<>\\`^|".contains(*c))
        {
            return bad(format!("\"{t}\" contains {c:?}"));
        }
        let host = rest.split(['/', '?', '#']).next().unwrap_or("");
        let host_name = host.rsplit_once('@').map_or(host, |(_, h)| h);
        if host_name.is_empty() || host.contains('@') {
            return bad(format!("\"{t}\" names no host (or has a user name)"));
        }
        // Every brace pair is one of the known placeholders.
        let mut s = t;
        while let Some(open) = s.find('{') {
            let Some(close) = s[open..].find('}') else {
                return bad(format!("\"{t}\" has a '{{' without '}}'"));
            };
            let name = &s[open + 1..open + close];
            if !matches!(name, "z" | "x" | "y" | "s") {
                return bad(format!(
                    "\"{t}\" has {{{name}}}; the placeholders are {{z}}, {{x}}, {{y}} and {{s}}"
                ));
            }
            s = &s[open + close + 1..];
        }
        if s.contains('}') || t.matches('}').count() != t.matches('{').count() {
            return bad(format!("\"{t}\" has a '}}' without '{{'"));
        }
        for p in ["{z}", "{x}", "{y}"] {
            if !t.contains(p) {
                return bad(format!("\"{t}\" lacks {p}"));
            }
        }
        if host_name.contains('{') && !host_name.starts_with("{s}.") {
            return bad(format!(
                "\"{t}\": only {{s}}. may start the host name, no other placeholder is allowed in it"
            ));
        }
        let attribution = attribution.trim();
        if attribution.chars().count() > 120 {
            return bad("the attribution is longer than 120 characters".into());
        }
        let attribution = if !attribution.is_empty() {
            attribution.to_string()
        } else if host_name == "tile.openstreetmap.org"
            || host_name.ends_with(".tile.openstreetmap.org")
        {
            OSM_ATTRIBUTION.to_string()
        } else {
            format!("Map tiles: {host_name}")
        };
        Ok(TileTemplate {
            template: t.to_string(),
            host: host_name.to_string(),
            attribution,
        })
    }

    /// OpenStreetMap's standard tiles.
    pub fn osm() -> TileTemplate {
        Self::parse(OSM_TEMPLATE, "").expect("the default template is valid")
    }

    /// The URL of one tile.
    pub fn url(&self, tile: &Tile) -> String {
        let sub = ["a", "b", "c"][((tile.x + tile.y) % 3) as usize];
        self.template
            .replace("{z}", &tile.z.to_string())
            .replace("{x}", &tile.x.to_string())
            .replace("{y}", &tile.y.to_string())
            .replace("{s}", sub)
    }

    /// The host the tiles come from (with `{s}.` as written).
    pub fn host(&self) -> &str {
        &self.host
    }

    /// The credit line drawn on the map.
    pub fn attribution(&self) -> &str {
        &self.attribution
    }

    /// The template as checked (trimmed).
    pub fn as_str(&self) -> &str {
        &self.template
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn the_tile_under_a_known_place() {
        // By hand, from the slippy-map formulas x = (lon + 180)/360 · 2^z and
        // y = (1 − asinh(tan φ)/π)/2 · 2^z:
        // London (51.5074° N, 0.1278° W) at zoom 10: x = 179.8722/360 · 1024 = 511.636,
        // tan φ = 1.25779, asinh = 1.04716, y = (1 − 0.333326)/2 · 1024 = 340.506 → tile 511/340.
        let (x, y) = tile_xy(51.5074, -0.1278, 10).unwrap();
        assert_eq!((x.floor(), y.floor()), (511.0, 340.0));
        assert!(
            close(x, 511.636_48, 1e-5) && close(y, 340.506_14, 1e-4),
            "{x} {y}"
        );
        // Florence's Duomo square (43.7696° N, 11.2558° E), the GNSS demo's start, at zoom 16:
        // x = 191.2558/360 · 65536 = 34817.056, y = 23888.377 → tile 16/34817/23888.
        let (x, y) = tile_xy(43.7696, 11.2558, 16).unwrap();
        assert_eq!((x as u32, y as u32), (34817, 23888));
        // Sydney (33.8568° S, 151.2153° E) at zoom 15 is south of the equator: y > 2^14.
        let (x, y) = tile_xy(-33.8568, 151.2153, 15).unwrap();
        assert_eq!((x as u32, y as u32), (30147, 19662));
        // Zoom 0 is one tile; zoom 1's four quadrants.
        assert_eq!(tile_xy(0.0, 0.0, 0).unwrap(), (0.5, 0.5));
        let q = |lat: f64, lon: f64| {
            let (x, y) = tile_xy(lat, lon, 1).unwrap();
            (x as u32, y as u32)
        };
        assert_eq!(
            [
                q(10.0, -10.0),
                q(10.0, 10.0),
                q(-10.0, -10.0),
                q(-10.0, 10.0)
            ],
            [(0, 0), (1, 0), (0, 1), (1, 1)]
        );
    }

    #[test]
    fn tile_coordinates_round_trip() {
        for &(lat, lon) in &[
            (43.7696, 11.2558),
            (-33.8568, 151.2153),
            (0.0, -179.9),
            (70.0, 0.0),
        ] {
            for z in [0, 5, 12, 19] {
                let (x, y) = tile_xy(lat, lon, z).unwrap();
                let (la, lo) = tile_lat_lon(x, y, z);
                assert!(
                    close(la, lat, 1e-9) && close(lo, lon, 1e-9),
                    "{lat} {lon} z{z}"
                );
            }
        }
    }

    #[test]
    fn poles_clamp_and_the_antimeridian_wraps() {
        // The square world's edges: ±85.0511° are rows 0 and 2^z at every zoom.
        let (_, y) = tile_xy(MAX_LATITUDE_DEG, 0.0, 3).unwrap();
        assert!(close(y, 0.0, 1e-9), "{y}");
        let (_, y) = tile_xy(90.0, 0.0, 3).unwrap();
        assert!(close(y, 0.0, 1e-9), "the pole clamps to the top row: {y}");
        let (_, y) = tile_xy(-89.0, 0.0, 3).unwrap();
        assert!(close(y, 8.0, 1e-9), "{y}");
        assert!(close(tile_lat_lon(0.0, 0.0, 7).0, MAX_LATITUDE_DEG, 1e-9));
        // Across the antimeridian the column wraps.
        assert_eq!(wrap_x(-1, 4), 15);
        assert_eq!(wrap_x(16, 4), 0);
        assert_eq!(wrap_x(5, 4), 5);
        assert_eq!(unwrap_lon(-179.5, 179.8), 180.5);
        assert_eq!(unwrap_lon(10.0, 0.0), 10.0);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        assert_eq!(
            tile_xy(f64::NAN, 0.0, 3),
            Err(TileError::NotFinite("latitude and longitude"))
        );
        assert_eq!(
            tile_xy(0.0, f64::INFINITY, 3).unwrap_err().to_string(),
            "the base map needs a finite latitude and longitude"
        );
        assert_eq!(tile_xy(0.0, 0.0, 20), Err(TileError::Zoom(20)));
        assert!(zoom_for(0.0, 45.0, 19).is_err() && zoom_for(f64::NAN, 45.0, 19).is_err());
        let origin = LocalFrame::new(43.7696, 11.2558, 50.0);
        let frame = MapFrame {
            px: (0, 100, 0, 100),
            m: (0.0, f64::NAN, 0.0, 10.0),
        };
        assert!(visible_tiles(&frame, &origin, 1.0, 19).is_err());
        let empty = MapFrame {
            px: (10, 10, 0, 100),
            m: (0.0, 10.0, 0.0, 10.0),
        };
        assert!(visible_tiles(&empty, &origin, 1.0, 19).is_err());
        let huge = MapFrame {
            px: (0, 500, 0, 500),
            m: (-3e5, 3e5, -3e5, 3e5),
        };
        assert_eq!(
            visible_tiles(&huge, &origin, 1.0, 19)
                .unwrap_err()
                .to_string(),
            "the view is 600 km wide; the base map shows views up to 200 km"
        );
        // A local frame at the pole: tiles where the square world has rows, no panic.
        let pole = LocalFrame::new(89.99, 0.0, 0.0);
        let frame = MapFrame {
            px: (0, 400, 0, 400),
            m: (-500.0, 500.0, -500.0, 500.0),
        };
        let tiles = visible_tiles(&frame, &pole, 1.0, 19).unwrap();
        assert!(tiles.len() <= MAX_TILES);
    }

    #[test]
    fn the_zoom_matches_the_scale() {
        // At 43.77° a zoom-16 tile pixel is 156543.03 · cos φ / 65536 = 1.725 m.
        assert!(close(metres_per_tile_px(43.7696, 16), 1.7249, 1e-3));
        assert_eq!(zoom_for(1.7249, 43.7696, 19).unwrap(), 16);
        // Within a factor √2 either way the same zoom; beyond, the next.
        assert_eq!(zoom_for(1.7249 * 1.4, 43.7696, 19).unwrap(), 16);
        assert_eq!(zoom_for(1.7249 * 1.42, 43.7696, 19).unwrap(), 15);
        assert_eq!(zoom_for(1.7249 / 1.42, 43.7696, 19).unwrap(), 17);
        // Clamped to the template's deepest zoom and to the world.
        assert_eq!(zoom_for(0.001, 43.7696, 19).unwrap(), 19);
        assert_eq!(zoom_for(0.001, 43.7696, 17).unwrap(), 17);
        assert_eq!(zoom_for(1e7, 0.0, 19).unwrap(), 0);
    }

    /// A 600 × 400 map about Florence, 1 m per pixel, plotting area at (40, 12).
    fn florence() -> (MapFrame, LocalFrame) {
        (
            MapFrame {
                px: (40, 640, 12, 412),
                m: (-250.0, 350.0, -150.0, 250.0),
            },
            LocalFrame::new(43.7696, 11.2558, 50.0),
        )
    }

    #[test]
    fn the_tiles_cover_the_map_without_gaps() {
        let (frame, origin) = florence();
        let tiles = visible_tiles(&frame, &origin, 1.0, 19).unwrap();
        // 1 m per pixel at 43.77° is zoom 17 (0.86 m per tile pixel).
        assert!(tiles.iter().all(|t| t.z == 17));
        // Every pixel of the plotting area is in exactly one tile.
        let (l, r, t, b) = frame.px;
        for y in (t..b).step_by(7) {
            for x in (l..r).step_by(7) {
                let n = tiles
                    .iter()
                    .filter(|k| {
                        (k.rect.0..k.rect.2).contains(&x) && (k.rect.1..k.rect.3).contains(&y)
                    })
                    .count();
                assert_eq!(n, 1, "pixel ({x}, {y}) in {n} tiles");
            }
        }
        // Each tile spans 256 tile pixels of 0.862 m: 221 map pixels of 1 m.
        for k in &tiles {
            let w = k.rect.2 - k.rect.0;
            let h = k.rect.3 - k.rect.1;
            assert!(
                (219..=223).contains(&w) && (219..=223).contains(&h),
                "{k:?}"
            );
        }
        assert!(tiles.len() <= 12, "{}", tiles.len());
    }

    #[test]
    fn a_place_is_drawn_where_its_tile_says() {
        let (frame, origin) = florence();
        let tiles = visible_tiles(&frame, &origin, 1.0, 19).unwrap();
        // A point 120 m east, 80 m north of the origin: its pixel by the map frame and by the
        // tile it falls in (the fraction within the tile) agree within a pixel.
        let (lat, lon, _) = origin.to_geodetic([120.0, 80.0, 0.0]);
        let (tx, ty) = tile_xy(lat, lon, 17).unwrap();
        let tile = tiles
            .iter()
            .find(|k| k.x == tx as u32 && k.y == ty as u32)
            .expect("the point's tile is on the map");
        let x = tile.rect.0 as f64 + tx.fract() * (tile.rect.2 - tile.rect.0) as f64;
        let y = tile.rect.1 as f64 + ty.fract() * (tile.rect.3 - tile.rect.1) as f64;
        let (px, py) = frame.to_pixel(120.0, 80.0);
        assert!(
            close(x, px, 1.5) && close(y, py, 1.5),
            "{x} {y} vs {px} {py}"
        );
    }

    #[test]
    fn zoomed_out_views_stay_bounded() {
        let origin = LocalFrame::new(43.7696, 11.2558, 50.0);
        // 190 km across 4000 × 4000 device pixels at one device pixel per CSS pixel.
        let frame = MapFrame {
            px: (0, 4000, 0, 4000),
            m: (-95e3, 95e3, -95e3, 95e3),
        };
        let tiles = visible_tiles(&frame, &origin, 1.0, 19).unwrap();
        assert!(
            !tiles.is_empty() && tiles.len() <= MAX_TILES,
            "{}",
            tiles.len()
        );
        // A phone: three device pixels per CSS pixel takes a zoom 1.58 coarser.
        let phone = MapFrame {
            px: (0, 1170, 0, 1170),
            m: (-585.0, 585.0, -585.0, 585.0),
        };
        let z1 = visible_tiles(&phone, &origin, 1.0, 19).unwrap()[0].z;
        let z3 = visible_tiles(&phone, &origin, 3.0, 19).unwrap()[0].z;
        assert_eq!(z1 - z3, 2, "{z1} {z3}");
    }

    #[test]
    fn across_the_antimeridian_columns_wrap() {
        let origin = LocalFrame::new(-16.5, 179.999, 0.0); // Fiji
        let frame = MapFrame {
            px: (0, 400, 0, 400),
            m: (-400.0, 400.0, -400.0, 400.0),
        };
        let tiles = visible_tiles(&frame, &origin, 1.0, 19).unwrap();
        let n = 1u32 << tiles[0].z;
        assert!(tiles.iter().any(|t| t.x == 0) && tiles.iter().any(|t| t.x == n - 1));
        // Still one strip without gaps: the columns' rectangles follow each other.
        let mut lefts: Vec<i32> = tiles.iter().map(|t| t.rect.0).collect();
        lefts.sort();
        lefts.dedup();
        assert!(lefts.len() >= 2);
    }

    #[test]
    fn tiles_are_clipped_to_the_plotting_area() {
        let t = Tile {
            z: 17,
            x: 1,
            y: 2,
            rect: (-50, 100, 150, 300),
        };
        // Clip: left 0, right 500, top 0, bottom 250 → the right three quarters, the top quarter.
        let p = t.clipped((0, 500, 0, 250)).unwrap();
        assert_eq!(p.dst, (0, 100, 150, 250));
        assert_eq!(p.src, (0.25, 0.0, 1.0, 0.75));
        assert_eq!(
            t.clipped((-100, 500, 0, 400)).unwrap().src,
            (0.0, 0.0, 1.0, 1.0)
        );
        assert_eq!(t.clipped((150, 500, 0, 400)), None);
        assert_eq!(t.clipped((0, 500, 300, 400)), None);
    }

    #[test]
    fn templates_are_checked_and_filled() {
        let osm = TileTemplate::osm();
        let tile = Tile {
            z: 16,
            x: 34817,
            y: 23888,
            rect: (0, 0, 1, 1),
        };
        assert_eq!(
            osm.url(&tile),
            "https://tile.openstreetmap.org/16/34817/23888.png"
        );
        assert_eq!(osm.attribution(), "© OpenStreetMap contributors");
        assert_eq!(osm.host(), "tile.openstreetmap.org");
        let t = TileTemplate::parse("https://{s}.tiles.example.org/x/{z}/{y}/{x}@2x.png?k=1", "")
            .unwrap();
        // (34817 + 23888) % 3 = 58705 % 3 = 1 → b.
        assert_eq!(
            t.url(&tile),
            "https://b.tiles.example.org/x/16/23888/34817@2x.png?k=1"
        );
        assert_eq!(t.attribution(), "Map tiles: {s}.tiles.example.org");
        let t =
            TileTemplate::parse(" https://127.0.0.1:9999/{z}/{x}/{y}.png ", "Test tiles").unwrap();
        assert_eq!(t.attribution(), "Test tiles");
        assert_eq!(t.as_str(), "https://127.0.0.1:9999/{z}/{x}/{y}.png");
        for (bad, why) in [
            ("", "empty"),
            (
                "http://tile.openstreetmap.org/{z}/{x}/{y}.png",
                "must start with https://",
            ),
            ("https://a.org/{z}/{x}.png", "lacks {y}"),
            ("https://a.org/{z}/{x}/{y}/{r}.png", "has {r}"),
            ("https://a.org/{z}/{x}/{y}.png}", "'}' without '{'"),
            ("https://a.org/{z}/{x}/{y.png", "'{' without '}'"),
            ("https://a.org/{z}/{x}/{y} .png", "contains ' '"),
            ("https:///{z}/{x}/{y}.png", "names no host"),
            ("https://me@a.org/{z}/{x}/{y}.png", "user name"),
            ("https://{z}.a.org/{x}/{y}.png", "only {s}."),
            ("javascript:alert(1)//{z}{x}{y}", "must start with https://"),
        ] {
            let e = TileTemplate::parse(bad, "").unwrap_err().to_string();
            assert!(
                e.starts_with("tile URL template: ") && e.contains(why),
                "{bad}: {e}"
            );
        }
        assert!(TileTemplate::parse(OSM_TEMPLATE, &"x".repeat(121)).is_err());
    }
}
