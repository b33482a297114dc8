//! The pixel check of every drawing (compiled for tests only): each plot drawn onto the native
//! [`Raster`](super::raster::Raster) at a phone's and a desktop's size, in both themes, and its
//! pixels hashed. The hashes were recorded from the drawings as they are; a change that moves a
//! single pixel of any plot, or a character of the figures under the map, changes one of them.
//! A deliberate change of a drawing records them again (the failing test prints the new table).
//! May import: the raster and the theme; its tests the whole of `plot`, `analysis` and, to
//! have walks to draw, `sim`, `io`, `demo` and `live`.

use super::raster;
use super::tiles::{Piece, Tile};
use super::{Theme, TileState};

/// The sizes drawn at: a phone (narrow, device pixel ratio 2) and a desktop (wide, ratio 1),
/// for the diagnostics plots (w, h, scale) and for the maps.
const PLOT_SIZES: [(&str, u32, u32, f64); 2] =
    [("phone", 720, 420, 2.0), ("desktop", 1100, 240, 1.0)];
const MAP_SIZES: [(&str, u32, u32, f64); 2] =
    [("phone", 720, 760, 2.0), ("desktop", 900, 560, 1.0)];
const THEMES: [(&str, Theme); 2] = [("light", Theme::LIGHT), ("dark", Theme::DARK)];

/// FNV-1a, 64 bits: a hash that is the same on every machine and every run.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn pixels(&mut self, px: &raster::Pixels) {
        for p in px.borrow().iter() {
            self.bytes(&[p.0, p.1, p.2]);
        }
    }
    fn text(&mut self, s: &str) {
        self.bytes(s.as_bytes());
        self.bytes(&[0]);
    }
    fn int(&mut self, v: i64) {
        self.bytes(&v.to_le_bytes());
    }
}

/// The hash of a drawing's pixels.
fn pixel_hash(px: &raster::Pixels) -> u64 {
    let mut f = Fnv::new();
    f.pixels(px);
    f.0
}

/// Compares the hashes with the recorded ones, printing the whole table when any differs.
fn check(got: &[(String, u64)], want: &[(&str, u64)]) {
    let differ: Vec<&str> = got
        .iter()
        .filter(|(k, h)| !want.iter().any(|(wk, wh)| wk == k && wh == h))
        .map(|(k, _)| k.as_str())
        .collect();
    if !differ.is_empty() || got.len() != want.len() {
        for (k, h) in got {
            println!("    (\"{k}\", 0x{h:016x}),");
        }
        panic!(
            "{} of {} drawings changed (recorded {}), the first: {:?}",
            differ.len(),
            got.len(),
            want.len(),
            &differ[..differ.len().min(5)]
        );
    }
}

/// A checker painter for the base map: each tile one of two colours.
fn checker(px: raster::Pixels, w: u32, h: u32) -> impl FnMut(&Tile, &Piece, &str) -> TileState {
    move |t: &Tile, piece: &Piece, _: &str| {
        let c = if (t.x + t.y) % 2 == 0 {
            (0x40, 0xa0, 0x40)
        } else {
            (0x40, 0x40, 0xa0)
        };
        let (l, top, r, bottom) = piece.dst;
        let mut p = px.borrow_mut();
        for y in top.max(0)..bottom.min(h as i32) {
            for x in l.max(0)..r.min(w as i32) {
                p[(y as u32 * w + x as u32) as usize] = c;
            }
        }
        TileState::Drawn
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{analyse, Analysis};
    use crate::engine::geo::LocalFrame;
    use crate::engine::Record;
    use crate::plot::tiles::TileTemplate;
    use crate::plot::upload::{draw_ellipse, draw_map, draw_plot_area, Plot};
    use crate::plot::Basemap;
    use plotters::prelude::*;
    use std::sync::OnceLock;

    /// An analysis of simulated records, as upload mode makes it.
    fn analysed(name: &str, records: Vec<Record>) -> Analysis {
        let mut log = crate::io::import::Log::new(name, crate::io::import::Format::PdrLog);
        log.records = records;
        analyse(&log, &Default::default(), &mut |_, _| {}).unwrap()
    }

    /// The analyses drawn: a simulated walk, one with GNSS fixes, a foot-mounted one, one without a
    /// gyroscope and the hand-made three-floor walk.
    fn analyses() -> &'static [(&'static str, Analysis)] {
        static A: OnceLock<Vec<(&'static str, Analysis)>> = OnceLock::new();
        A.get_or_init(|| {
            use crate::sim::scenarios;
            let walk = scenarios::demo_walk().generate().records;
            let no_gyro = walk
                .iter()
                .cloned()
                .map(|r| match r {
                    Record::Imu(mut s) => {
                        s.gyro = None;
                        Record::Imu(s)
                    }
                    r => r,
                })
                .collect();
            let foot = scenarios::straight_walk(1.8, 20.0)
                .generate_foot(&crate::sim::FootImu::default())
                .sim
                .records;
            vec![
                ("walk", analysed("walk.pdrlog", walk)),
                (
                    "gnss",
                    analysed(
                        "city.pdrlog",
                        scenarios::gnss_city_walk().generate().records,
                    ),
                ),
                ("foot", analysed("foot.pdrlog", foot)),
                ("no-gyro", analysed("nogyro.pdrlog", no_gyro)),
                ("floors", crate::analysis::three_floor_analysis()),
            ]
        })
    }

    /// Upload mode's diagnostics plots: every plot of every analysis, over the whole log (with a
    /// cursor) and over ten seconds in its middle.
    fn upload_plots() -> Vec<(String, u64)> {
        let mut out = Vec::new();
        for (name, a) in analyses() {
            let (t0, t1) = (a.trace.t[0], *a.trace.t.last().unwrap());
            let mid = (t0 + t1) / 2.0;
            for (span_name, span, cursor) in [
                ("all", (t0, t1), Some(mid)),
                ("10s", (mid - 5.0, mid + 5.0), None),
            ] {
                for plot in Plot::ALL {
                    for (size, w, h, scale) in PLOT_SIZES {
                        for (theme_name, theme) in THEMES {
                            let (r, px) = raster::new(w, h);
                            let (cols, rows) = draw_plot_area(
                                &r.into_drawing_area(),
                                a,
                                plot,
                                span,
                                cursor,
                                &theme,
                                scale,
                            )
                            .unwrap();
                            let mut f = Fnv::new();
                            f.pixels(&px);
                            for v in [cols.0, cols.1, rows.0, rows.1] {
                                f.int(i64::from(v));
                            }
                            out.push((
                                format!("plot {name} {plot:?} {span_name} {size} {theme_name}"),
                                f.0,
                            ));
                        }
                    }
                }
            }
        }
        out
    }

    /// Upload mode's map of every analysis (whole, with a highlighted step; and zoomed over a
    /// base map), its ellipse, and the figures under it.
    fn upload_maps() -> Vec<(String, u64)> {
        let mut out = Vec::new();
        let template = TileTemplate::parse("https://tiles.test/{z}/{x}/{y}.png", "").unwrap();
        for (name, a) in analyses() {
            let mut f = Fnv::new();
            for (k, v) in a.figures() {
                f.text(&k);
                f.text(&v);
            }
            for i in [0, a.steps.len() / 2] {
                f.text(&a.step_text(i).unwrap_or_default());
            }
            f.text(&a.corrections_text().unwrap_or_default());
            out.push((format!("figures {name}"), f.0));
            for (size, w, h, scale) in MAP_SIZES {
                for (theme_name, theme) in THEMES {
                    let (r, px) = raster::new(w, h);
                    let frame = draw_map(
                        &r.into_drawing_area(),
                        a,
                        None,
                        Some(a.steps.len() / 3),
                        None,
                        &theme,
                        scale,
                    )
                    .unwrap();
                    let mut f = Fnv::new();
                    f.pixels(&px);
                    f.text(&format!("{frame:?}"));
                    out.push((format!("map {name} {size} {theme_name}"), f.0));
                    // Zoomed about the middle step, over a base map where there is an origin.
                    let (r, px) = raster::new(w, h);
                    let (e, n) = a.step_position(a.steps.len() / 2).unwrap_or((0.0, 0.0));
                    let bounds = (e - 15.0, e + 15.0, n - 10.0, n + 10.0);
                    let mut paint = checker(px.clone(), w, h);
                    let mut basemap = a.origin.map(|(lat, lon, height)| Basemap {
                        origin: LocalFrame::new(lat, lon, height),
                        tiles: &template,
                        paint: &mut paint,
                        shown: None,
                    });
                    let frame = draw_map(
                        &r.into_drawing_area(),
                        a,
                        Some(bounds),
                        None,
                        basemap.as_mut(),
                        &theme,
                        scale,
                    )
                    .unwrap();
                    let mut f = Fnv::new();
                    f.pixels(&px);
                    f.text(&format!("{frame:?}"));
                    f.text(&format!("{:?}", basemap.and_then(|b| b.shown)));
                    out.push((format!("map zoomed {name} {size} {theme_name}"), f.0));
                    let (r, px) = raster::new(h.min(w), h.min(w));
                    draw_ellipse(&r.into_drawing_area(), a, 40, &theme, scale).unwrap();
                    out.push((
                        format!("ellipse {name} {size} {theme_name}"),
                        pixel_hash(&px),
                    ));
                }
            }
        }
        out
    }

    /// The live map and scope of a simulated walk with a gap in its input.
    fn live() -> Vec<(String, u64)> {
        let mut live = crate::plot::live::simulated_session();
        let d = live.map_data();
        let view = crate::plot::live::view_of(&d);
        let scope = live.scope_data();
        let mut out = Vec::new();
        for (theme_name, theme) in THEMES {
            for (size, w, h, scale) in MAP_SIZES {
                let (r, px) = raster::new(w, h);
                crate::plot::draw_live(&r.into_drawing_area(), &view, None, &theme, scale).unwrap();
                out.push((format!("live map {size} {theme_name}"), pixel_hash(&px)));
            }
            for (size, w, h, scale) in PLOT_SIZES {
                let (r, px) = raster::new(w, h);
                crate::plot::draw_scope(
                    &r.into_drawing_area(),
                    &scope.samples,
                    &scope.steps,
                    scope.now,
                    10.0,
                    &theme,
                    scale,
                )
                .unwrap();
                out.push((format!("scope {size} {theme_name}"), pixel_hash(&px)));
            }
        }
        out
    }

    /// The fusion demo's map (with and without a base map), the demo's track and the calibration
    /// chart (with a fit, and with a kept slope).
    fn demos() -> Vec<(String, u64)> {
        let demo = crate::demo::run_fusion_demo();
        let track = crate::demo::run_demo();
        let template = TileTemplate::parse("https://tiles.test/{z}/{x}/{y}.png", "").unwrap();
        let view = crate::plot::fusion::view_of(&demo);
        let fits = [
            crate::engine::calibration::fit_band(&[
                (1.5, 0.65),
                (1.8, 0.74),
                (2.1, 0.83),
                (2.0, 0.86),
            ]),
            crate::engine::calibration::fit_band(&[(1.8, 0.74)]),
        ];
        let line = crate::engine::step_length::StepLengthProfile::default().walking;
        let mut out = Vec::new();
        for (theme_name, theme) in THEMES {
            for (size, w, h, scale) in MAP_SIZES {
                for tiles in [false, true] {
                    let (r, px) = raster::new(w, h);
                    let (lat, lon, height) = demo.origin;
                    let mut paint = checker(px.clone(), w, h);
                    let mut basemap = tiles.then(|| Basemap {
                        origin: LocalFrame::new(lat, lon, height),
                        tiles: &template,
                        paint: &mut paint,
                        shown: None,
                    });
                    crate::plot::draw_fusion(
                        &r.into_drawing_area(),
                        &view,
                        basemap.as_mut(),
                        &theme,
                        scale,
                    )
                    .unwrap();
                    let mut f = Fnv::new();
                    f.pixels(&px);
                    f.text(&format!("{:?}", basemap.and_then(|b| b.shown)));
                    let which = if tiles { "basemap" } else { "fusion" };
                    out.push((format!("{which} {size} {theme_name}"), f.0));
                }
                let (r, px) = raster::new(w, h);
                crate::plot::draw_track(
                    &r.into_drawing_area(),
                    &track.track,
                    Some(&track.truth_path),
                    &theme,
                    scale,
                )
                .unwrap();
                out.push((format!("track {size} {theme_name}"), pixel_hash(&px)));
                for (k, fit) in fits.iter().enumerate() {
                    let (r, px) = raster::new(w, h);
                    crate::plot::draw_calibration(
                        &r.into_drawing_area(),
                        fit,
                        &line,
                        "walking",
                        &theme,
                        scale,
                    )
                    .unwrap();
                    out.push((
                        format!("calibration {k} {size} {theme_name}"),
                        pixel_hash(&px),
                    ));
                }
            }
        }
        out
    }

    #[test]
    fn upload_plots_are_pixel_for_pixel_as_recorded() {
        check(&upload_plots(), UPLOAD_PLOTS);
    }

    #[test]
    fn upload_maps_and_figures_are_as_recorded() {
        check(&upload_maps(), UPLOAD_MAPS);
    }

    #[test]
    fn the_live_map_and_scope_are_pixel_for_pixel_as_recorded() {
        check(&live(), LIVE);
    }

    #[test]
    fn the_fusion_track_calibration_and_base_maps_are_pixel_for_pixel_as_recorded() {
        check(&demos(), DEMOS);
    }

    /// The hashes recorded from the drawings (`name`: FNV-1a of the pixels and of what the
    /// drawing returned).
    const UPLOAD_PLOTS: &[(&str, u64)] = &[
        ("plot walk Accel all phone light", 0x85e94fde313566cc),
        ("plot walk Accel all phone dark", 0xa0e5ddcda36bd147),
        ("plot walk Accel all desktop light", 0xae88c247b77ce7b0),
        ("plot walk Accel all desktop dark", 0xaacc714ea060dcb7),
        ("plot walk Sigma all phone light", 0xecac825d89b9b90e),
        ("plot walk Sigma all phone dark", 0x5647a4045f772a63),
        ("plot walk Sigma all desktop light", 0xc3bcacf7fc3d32d2),
        ("plot walk Sigma all desktop dark", 0x6e32b2ffed2d5deb),
        ("plot walk Height all phone light", 0x7a760bcc1b45ee00),
        ("plot walk Height all phone dark", 0xb42c7eeac313180b),
        ("plot walk Height all desktop light", 0x81f3c40bee09489c),
        ("plot walk Height all desktop dark", 0x262661f44b0be9af),
        ("plot walk Heading all phone light", 0xb1db729aa8bf427d),
        ("plot walk Heading all phone dark", 0xb438bf8a0dc68898),
        ("plot walk Heading all desktop light", 0x9d9a134593558e1a),
        ("plot walk Heading all desktop dark", 0x786d12db839ccb71),
        ("plot walk Steps all phone light", 0xaf07bdbc30a85666),
        ("plot walk Steps all phone dark", 0x16c119e9d29b80c6),
        ("plot walk Steps all desktop light", 0x6a78bd366db16b12),
        ("plot walk Steps all desktop dark", 0xa784d7ba6a0b8a65),
        ("plot walk Gnss all phone light", 0x2fddb38c3743e8c1),
        ("plot walk Gnss all phone dark", 0x672e15f24a9e09cb),
        ("plot walk Gnss all desktop light", 0x039e10e600cbf25d),
        ("plot walk Gnss all desktop dark", 0x674b86f187dd7e4b),
        ("plot walk Fusion all phone light", 0x5d43f2c3b6cd3956),
        ("plot walk Fusion all phone dark", 0xa64262d71b8342b9),
        ("plot walk Fusion all desktop light", 0xf72a24adbe78e8db),
        ("plot walk Fusion all desktop dark", 0xef45030cf7e57ca3),
        ("plot walk Accel 10s phone light", 0xb6b9c3fecdf16655),
        ("plot walk Accel 10s phone dark", 0x29de11bb164920b2),
        ("plot walk Accel 10s desktop light", 0x270c3c3bbe89465e),
        ("plot walk Accel 10s desktop dark", 0x7b8999beed226c72),
        ("plot walk Sigma 10s phone light", 0x8b59f2a544f2d803),
        ("plot walk Sigma 10s phone dark", 0xbcf02f40874caf2d),
        ("plot walk Sigma 10s desktop light", 0xf1960232e9fd0de9),
        ("plot walk Sigma 10s desktop dark", 0x95a97e8db6b77d61),
        ("plot walk Height 10s phone light", 0xa8db1144fc14967d),
        ("plot walk Height 10s phone dark", 0x48a9d7b634f7e916),
        ("plot walk Height 10s desktop light", 0x0d784b72b6efda39),
        ("plot walk Height 10s desktop dark", 0xbdac0c81473e0a4b),
        ("plot walk Heading 10s phone light", 0xa15ee536cee49cfc),
        ("plot walk Heading 10s phone dark", 0xe1529fc5731f0e97),
        ("plot walk Heading 10s desktop light", 0x9b5a4d6d1a0cc0e0),
        ("plot walk Heading 10s desktop dark", 0x69886e4ac2cae8d9),
        ("plot walk Steps 10s phone light", 0x5ec4cf2d0c50b3bf),
        ("plot walk Steps 10s phone dark", 0xe06f32b7ebfa754b),
        ("plot walk Steps 10s desktop light", 0xef245bfcbdf3fb30),
        ("plot walk Steps 10s desktop dark", 0xf02e8e34a9a33c54),
        ("plot walk Gnss 10s phone light", 0x9c46bc8742ca0e3b),
        ("plot walk Gnss 10s phone dark", 0x7880a4695a9c3a22),
        ("plot walk Gnss 10s desktop light", 0x5adf0e7b64e0a82a),
        ("plot walk Gnss 10s desktop dark", 0x59abf726e0a8f33f),
        ("plot walk Fusion 10s phone light", 0x344e664572bb86ba),
        ("plot walk Fusion 10s phone dark", 0x780ea4ed80896bf0),
        ("plot walk Fusion 10s desktop light", 0x77e256b29ffe0c7b),
        ("plot walk Fusion 10s desktop dark", 0x7e588e7fca881523),
        ("plot gnss Accel all phone light", 0xbef2226009a99041),
        ("plot gnss Accel all phone dark", 0x10b9ab2ed2512ab1),
        ("plot gnss Accel all desktop light", 0x5ed2dccb6bd9bc82),
        ("plot gnss Accel all desktop dark", 0xede1644c736689f8),
        ("plot gnss Sigma all phone light", 0xb094aa93255228a4),
        ("plot gnss Sigma all phone dark", 0x2e4643a915e39923),
        ("plot gnss Sigma all desktop light", 0xf707c1e988bbe351),
        ("plot gnss Sigma all desktop dark", 0x6fab3dfee9df837b),
        ("plot gnss Height all phone light", 0x931496f69480e279),
        ("plot gnss Height all phone dark", 0x7213f97b76857fea),
        ("plot gnss Height all desktop light", 0x733c79e921d95005),
        ("plot gnss Height all desktop dark", 0xea48e53de6815fea),
        ("plot gnss Heading all phone light", 0x636d820cfe3e7745),
        ("plot gnss Heading all phone dark", 0xbf8dfa1fe6afa753),
        ("plot gnss Heading all desktop light", 0x2e6cfffa75003a72),
        ("plot gnss Heading all desktop dark", 0x81aae7d56ae6852c),
        ("plot gnss Steps all phone light", 0x8ac02696453abd96),
        ("plot gnss Steps all phone dark", 0xe26ab46fa1965c93),
        ("plot gnss Steps all desktop light", 0x51901d7888d33de0),
        ("plot gnss Steps all desktop dark", 0x06f0018167c4c1b0),
        ("plot gnss Gnss all phone light", 0xc2236649a774a451),
        ("plot gnss Gnss all phone dark", 0xb069d97cc78b7ab4),
        ("plot gnss Gnss all desktop light", 0x3ef0a636a9e037da),
        ("plot gnss Gnss all desktop dark", 0x9d8e75802b29bc7e),
        ("plot gnss Fusion all phone light", 0xb0d7ec193a80fc5d),
        ("plot gnss Fusion all phone dark", 0x7f1be9b081a04492),
        ("plot gnss Fusion all desktop light", 0x6d802c72f1d46190),
        ("plot gnss Fusion all desktop dark", 0xd119e4f3399f6d56),
        ("plot gnss Accel 10s phone light", 0xd801e2d9e7115fe7),
        ("plot gnss Accel 10s phone dark", 0xfb41c912127724b5),
        ("plot gnss Accel 10s desktop light", 0xcd13c847b0a06ca9),
        ("plot gnss Accel 10s desktop dark", 0x88a11cfcc34247c4),
        ("plot gnss Sigma 10s phone light", 0x5d81c1aa32c7fea6),
        ("plot gnss Sigma 10s phone dark", 0xd46e5e18fa40f0f2),
        ("plot gnss Sigma 10s desktop light", 0x374454fc509d524e),
        ("plot gnss Sigma 10s desktop dark", 0x43b24d05d0077a01),
        ("plot gnss Height 10s phone light", 0x1fa098b422cd9eac),
        ("plot gnss Height 10s phone dark", 0x6de9d620ed876770),
        ("plot gnss Height 10s desktop light", 0x15a0e1f1e38ee695),
        ("plot gnss Height 10s desktop dark", 0x72323c56bfac6199),
        ("plot gnss Heading 10s phone light", 0xf2853e3aa6be621b),
        ("plot gnss Heading 10s phone dark", 0xf001483c30a3843c),
        ("plot gnss Heading 10s desktop light", 0xb935fdd100dfc0ab),
        ("plot gnss Heading 10s desktop dark", 0xf41f7d49dacf527d),
        ("plot gnss Steps 10s phone light", 0x296be82738bd5a72),
        ("plot gnss Steps 10s phone dark", 0x3f1429e19757af92),
        ("plot gnss Steps 10s desktop light", 0xb24c9c6f6fa8baa8),
        ("plot gnss Steps 10s desktop dark", 0x62519d8f4c664851),
        ("plot gnss Gnss 10s phone light", 0x5baecbc321880bf2),
        ("plot gnss Gnss 10s phone dark", 0xa8342ae0dca6e5a6),
        ("plot gnss Gnss 10s desktop light", 0x6fa94e587e6e4434),
        ("plot gnss Gnss 10s desktop dark", 0xeae9983c07cdd7f5),
        ("plot gnss Fusion 10s phone light", 0xe7d56e4698085cf9),
        ("plot gnss Fusion 10s phone dark", 0x69f881ef1764882f),
        ("plot gnss Fusion 10s desktop light", 0xf5cf1d04b9205e63),
        ("plot gnss Fusion 10s desktop dark", 0x7019a3a706e4fd56),
        ("plot foot Accel all phone light", 0xe4595ba0efb95a0f),
        ("plot foot Accel all phone dark", 0x537ce3640ebb3ccc),
        ("plot foot Accel all desktop light", 0xe22f645cf64436d7),
        ("plot foot Accel all desktop dark", 0x876cf1b5d68a2efd),
        ("plot foot Sigma all phone light", 0xcaa56bb334b19c96),
        ("plot foot Sigma all phone dark", 0xe642177fc1d75a17),
        ("plot foot Sigma all desktop light", 0x834219392ebc2503),
        ("plot foot Sigma all desktop dark", 0x57fac88b3a578ba8),
        ("plot foot Height all phone light", 0x37bd462dd9555818),
        ("plot foot Height all phone dark", 0xbece4b889e8800ea),
        ("plot foot Height all desktop light", 0x99511fafb2691d1a),
        ("plot foot Height all desktop dark", 0x8e2dae4d7dbe619e),
        ("plot foot Heading all phone light", 0x164d420283abcdbb),
        ("plot foot Heading all phone dark", 0xd6ab3e40dc682326),
        ("plot foot Heading all desktop light", 0x1b5225dc44abb74b),
        ("plot foot Heading all desktop dark", 0x137a3fa58a78e4f0),
        ("plot foot Steps all phone light", 0xf5be3e29eb6ec8d9),
        ("plot foot Steps all phone dark", 0xc08d163ca4cd0dc5),
        ("plot foot Steps all desktop light", 0xb2bca30f9af514d7),
        ("plot foot Steps all desktop dark", 0x9e30c8da62a5b6a5),
        ("plot foot Gnss all phone light", 0xa641f1f5bf2b764c),
        ("plot foot Gnss all phone dark", 0xf78ec7824c31aac2),
        ("plot foot Gnss all desktop light", 0x8545b8d447a15998),
        ("plot foot Gnss all desktop dark", 0x5b21f6bbceb4fec2),
        ("plot foot Fusion all phone light", 0x0bf57bc0ebc7516a),
        ("plot foot Fusion all phone dark", 0x0fe2caf89492a8e4),
        ("plot foot Fusion all desktop light", 0x204660d099fd838b),
        ("plot foot Fusion all desktop dark", 0x5c3b12889ffc620a),
        ("plot foot Accel 10s phone light", 0xb379bbbf2c1f9ab9),
        ("plot foot Accel 10s phone dark", 0xe169fea1a1df69b7),
        ("plot foot Accel 10s desktop light", 0x4453028b263c0d42),
        ("plot foot Accel 10s desktop dark", 0x720e7b427d003e4a),
        ("plot foot Sigma 10s phone light", 0xbdeabbf2727e6514),
        ("plot foot Sigma 10s phone dark", 0xe26f8fcc93fa750f),
        ("plot foot Sigma 10s desktop light", 0xf1c68c76b0a282f9),
        ("plot foot Sigma 10s desktop dark", 0x63fd6e32c5db9b90),
        ("plot foot Height 10s phone light", 0xc0eec44cbc95301f),
        ("plot foot Height 10s phone dark", 0xfc44c52a9650bb5d),
        ("plot foot Height 10s desktop light", 0x48dccea9f9f94ec3),
        ("plot foot Height 10s desktop dark", 0x8b704e695ef2b336),
        ("plot foot Heading 10s phone light", 0x62efda23f7bb4d46),
        ("plot foot Heading 10s phone dark", 0x26a68a43859caf85),
        ("plot foot Heading 10s desktop light", 0x94f235c899db5a31),
        ("plot foot Heading 10s desktop dark", 0x5446149a711d8445),
        ("plot foot Steps 10s phone light", 0x78b81545fb372b51),
        ("plot foot Steps 10s phone dark", 0x47f9777f75ef7d70),
        ("plot foot Steps 10s desktop light", 0x65c7adeefcb2226a),
        ("plot foot Steps 10s desktop dark", 0xc5d2ed280466662b),
        ("plot foot Gnss 10s phone light", 0x31402bce934b1d86),
        ("plot foot Gnss 10s phone dark", 0xd78db8d56c135acb),
        ("plot foot Gnss 10s desktop light", 0xc318116c4c02fc3d),
        ("plot foot Gnss 10s desktop dark", 0xef0bffb3b12790a8),
        ("plot foot Fusion 10s phone light", 0xd5e0234f0769a016),
        ("plot foot Fusion 10s phone dark", 0x576f7c11a92295b1),
        ("plot foot Fusion 10s desktop light", 0xdd1e8ab1626a1e33),
        ("plot foot Fusion 10s desktop dark", 0xf5790fbfc37d15fc),
        ("plot no-gyro Accel all phone light", 0x85e94fde313566cc),
        ("plot no-gyro Accel all phone dark", 0xa0e5ddcda36bd147),
        ("plot no-gyro Accel all desktop light", 0xae88c247b77ce7b0),
        ("plot no-gyro Accel all desktop dark", 0xaacc714ea060dcb7),
        ("plot no-gyro Sigma all phone light", 0x5a9c20c2ef53ca43),
        ("plot no-gyro Sigma all phone dark", 0x6c63400c41a03b8d),
        ("plot no-gyro Sigma all desktop light", 0xc1444cfd015bcc9d),
        ("plot no-gyro Sigma all desktop dark", 0xa8658b362d02bfca),
        ("plot no-gyro Height all phone light", 0x7a760bcc1b45ee00),
        ("plot no-gyro Height all phone dark", 0xb42c7eeac313180b),
        ("plot no-gyro Height all desktop light", 0x81f3c40bee09489c),
        ("plot no-gyro Height all desktop dark", 0x262661f44b0be9af),
        ("plot no-gyro Heading all phone light", 0xef80563573448cbf),
        ("plot no-gyro Heading all phone dark", 0x8e2fa3d8600ed07f),
        ("plot no-gyro Heading all desktop light", 0x2bfb38b2b8667e70),
        ("plot no-gyro Heading all desktop dark", 0xa8d961a6ef7281d9),
        ("plot no-gyro Steps all phone light", 0xaf07bdbc30a85666),
        ("plot no-gyro Steps all phone dark", 0x16c119e9d29b80c6),
        ("plot no-gyro Steps all desktop light", 0x6a78bd366db16b12),
        ("plot no-gyro Steps all desktop dark", 0xa784d7ba6a0b8a65),
        ("plot no-gyro Gnss all phone light", 0x2fddb38c3743e8c1),
        ("plot no-gyro Gnss all phone dark", 0x672e15f24a9e09cb),
        ("plot no-gyro Gnss all desktop light", 0x039e10e600cbf25d),
        ("plot no-gyro Gnss all desktop dark", 0x674b86f187dd7e4b),
        ("plot no-gyro Fusion all phone light", 0x5d43f2c3b6cd3956),
        ("plot no-gyro Fusion all phone dark", 0xa64262d71b8342b9),
        ("plot no-gyro Fusion all desktop light", 0xf72a24adbe78e8db),
        ("plot no-gyro Fusion all desktop dark", 0xef45030cf7e57ca3),
        ("plot no-gyro Accel 10s phone light", 0xb6b9c3fecdf16655),
        ("plot no-gyro Accel 10s phone dark", 0x29de11bb164920b2),
        ("plot no-gyro Accel 10s desktop light", 0x270c3c3bbe89465e),
        ("plot no-gyro Accel 10s desktop dark", 0x7b8999beed226c72),
        ("plot no-gyro Sigma 10s phone light", 0x6701a237122d0591),
        ("plot no-gyro Sigma 10s phone dark", 0x29ef2dabd3a674ad),
        ("plot no-gyro Sigma 10s desktop light", 0x669b30094626ee5f),
        ("plot no-gyro Sigma 10s desktop dark", 0xd0a897819f32cd3f),
        ("plot no-gyro Height 10s phone light", 0xa8db1144fc14967d),
        ("plot no-gyro Height 10s phone dark", 0x48a9d7b634f7e916),
        ("plot no-gyro Height 10s desktop light", 0x0d784b72b6efda39),
        ("plot no-gyro Height 10s desktop dark", 0xbdac0c81473e0a4b),
        ("plot no-gyro Heading 10s phone light", 0xc2b829b7cd201c88),
        ("plot no-gyro Heading 10s phone dark", 0x06eea7a36fdcbd84),
        ("plot no-gyro Heading 10s desktop light", 0x2acd48a5479f3104),
        ("plot no-gyro Heading 10s desktop dark", 0xa49fd13aaed22268),
        ("plot no-gyro Steps 10s phone light", 0x5ec4cf2d0c50b3bf),
        ("plot no-gyro Steps 10s phone dark", 0xe06f32b7ebfa754b),
        ("plot no-gyro Steps 10s desktop light", 0xef245bfcbdf3fb30),
        ("plot no-gyro Steps 10s desktop dark", 0xf02e8e34a9a33c54),
        ("plot no-gyro Gnss 10s phone light", 0x9c46bc8742ca0e3b),
        ("plot no-gyro Gnss 10s phone dark", 0x7880a4695a9c3a22),
        ("plot no-gyro Gnss 10s desktop light", 0x5adf0e7b64e0a82a),
        ("plot no-gyro Gnss 10s desktop dark", 0x59abf726e0a8f33f),
        ("plot no-gyro Fusion 10s phone light", 0x344e664572bb86ba),
        ("plot no-gyro Fusion 10s phone dark", 0x780ea4ed80896bf0),
        ("plot no-gyro Fusion 10s desktop light", 0x77e256b29ffe0c7b),
        ("plot no-gyro Fusion 10s desktop dark", 0x7e588e7fca881523),
        ("plot floors Accel all phone light", 0x85e94fde313566cc),
        ("plot floors Accel all phone dark", 0xa0e5ddcda36bd147),
        ("plot floors Accel all desktop light", 0xae88c247b77ce7b0),
        ("plot floors Accel all desktop dark", 0xaacc714ea060dcb7),
        ("plot floors Sigma all phone light", 0x47c5986b4019a480),
        ("plot floors Sigma all phone dark", 0xb4939fa0230d4dc2),
        ("plot floors Sigma all desktop light", 0x6b1d687ba148fb53),
        ("plot floors Sigma all desktop dark", 0x58631828202e3ff2),
        ("plot floors Height all phone light", 0xe36c6ab5c679445f),
        ("plot floors Height all phone dark", 0x8e629beb9c9ad7f0),
        ("plot floors Height all desktop light", 0xd14ac6fb74cd05fe),
        ("plot floors Height all desktop dark", 0x1c890c95dc5f2c6e),
        ("plot floors Heading all phone light", 0xb1db729aa8bf427d),
        ("plot floors Heading all phone dark", 0xb438bf8a0dc68898),
        ("plot floors Heading all desktop light", 0x9d9a134593558e1a),
        ("plot floors Heading all desktop dark", 0x786d12db839ccb71),
        ("plot floors Steps all phone light", 0xaf07bdbc30a85666),
        ("plot floors Steps all phone dark", 0x16c119e9d29b80c6),
        ("plot floors Steps all desktop light", 0x6a78bd366db16b12),
        ("plot floors Steps all desktop dark", 0xa784d7ba6a0b8a65),
        ("plot floors Gnss all phone light", 0x2fddb38c3743e8c1),
        ("plot floors Gnss all phone dark", 0x672e15f24a9e09cb),
        ("plot floors Gnss all desktop light", 0x039e10e600cbf25d),
        ("plot floors Gnss all desktop dark", 0x674b86f187dd7e4b),
        ("plot floors Fusion all phone light", 0x5d43f2c3b6cd3956),
        ("plot floors Fusion all phone dark", 0xa64262d71b8342b9),
        ("plot floors Fusion all desktop light", 0xf72a24adbe78e8db),
        ("plot floors Fusion all desktop dark", 0xef45030cf7e57ca3),
        ("plot floors Accel 10s phone light", 0xb6b9c3fecdf16655),
        ("plot floors Accel 10s phone dark", 0x29de11bb164920b2),
        ("plot floors Accel 10s desktop light", 0x270c3c3bbe89465e),
        ("plot floors Accel 10s desktop dark", 0x7b8999beed226c72),
        ("plot floors Sigma 10s phone light", 0xc27da3fb4a371ed6),
        ("plot floors Sigma 10s phone dark", 0x4dca3df8bf374296),
        ("plot floors Sigma 10s desktop light", 0x4df0f89b23bcd04d),
        ("plot floors Sigma 10s desktop dark", 0xf67c899d2fae0351),
        ("plot floors Height 10s phone light", 0x8c2411e4b3b3854f),
        ("plot floors Height 10s phone dark", 0x1ddaebc0286c0ae5),
        ("plot floors Height 10s desktop light", 0x919b0fada59916ec),
        ("plot floors Height 10s desktop dark", 0x2f6d05fe2d3ddae0),
        ("plot floors Heading 10s phone light", 0xa15ee536cee49cfc),
        ("plot floors Heading 10s phone dark", 0xe1529fc5731f0e97),
        ("plot floors Heading 10s desktop light", 0x9b5a4d6d1a0cc0e0),
        ("plot floors Heading 10s desktop dark", 0x69886e4ac2cae8d9),
        ("plot floors Steps 10s phone light", 0x5ec4cf2d0c50b3bf),
        ("plot floors Steps 10s phone dark", 0xe06f32b7ebfa754b),
        ("plot floors Steps 10s desktop light", 0xef245bfcbdf3fb30),
        ("plot floors Steps 10s desktop dark", 0xf02e8e34a9a33c54),
        ("plot floors Gnss 10s phone light", 0x9c46bc8742ca0e3b),
        ("plot floors Gnss 10s phone dark", 0x7880a4695a9c3a22),
        ("plot floors Gnss 10s desktop light", 0x5adf0e7b64e0a82a),
        ("plot floors Gnss 10s desktop dark", 0x59abf726e0a8f33f),
        ("plot floors Fusion 10s phone light", 0x344e664572bb86ba),
        ("plot floors Fusion 10s phone dark", 0x780ea4ed80896bf0),
        ("plot floors Fusion 10s desktop light", 0x77e256b29ffe0c7b),
        ("plot floors Fusion 10s desktop dark", 0x7e588e7fca881523),
    ];
    const UPLOAD_MAPS: &[(&str, u64)] = &[
        ("figures walk", 0xb5acce5b5108ab28),
        ("map walk phone light", 0xaa87bcffec0b7de4),
        ("map zoomed walk phone light", 0x66aa386d1f97d2fd),
        ("ellipse walk phone light", 0x58589dfc33026321),
        ("map walk phone dark", 0x390428dc9de5f80f),
        ("map zoomed walk phone dark", 0x3140c5ecb8cbb4dd),
        ("ellipse walk phone dark", 0x21abf93ce8f2aba3),
        ("map walk desktop light", 0x44d7afe4fba51017),
        ("map zoomed walk desktop light", 0xfc1a5cb3f4e1d10e),
        ("ellipse walk desktop light", 0x1399418994b535c2),
        ("map walk desktop dark", 0x12d3b83dd88c884f),
        ("map zoomed walk desktop dark", 0xc37026b4bf7ae119),
        ("ellipse walk desktop dark", 0xe601503294d94f29),
        ("figures gnss", 0x9f4d0fa1f92c187f),
        ("map gnss phone light", 0x962a3b28b1bccf3f),
        ("map zoomed gnss phone light", 0x754816a1a76a300a),
        ("ellipse gnss phone light", 0x36509b690114f9f7),
        ("map gnss phone dark", 0x0f9518db55cb745e),
        ("map zoomed gnss phone dark", 0xd0713c758b5646b0),
        ("ellipse gnss phone dark", 0x9b450bfb1ac4a041),
        ("map gnss desktop light", 0x871703ffbcfb7e45),
        ("map zoomed gnss desktop light", 0x4e9467c0840d0bd9),
        ("ellipse gnss desktop light", 0xa92e88728c49f370),
        ("map gnss desktop dark", 0xa4995dbab5e3a7f9),
        ("map zoomed gnss desktop dark", 0xbaf3080562480e01),
        ("ellipse gnss desktop dark", 0x561eabae61ce2d2c),
        ("figures foot", 0x2521ad8c0a96e76b),
        ("map foot phone light", 0xefb4a8f69f386630),
        ("map zoomed foot phone light", 0x5196ba2529e79e63),
        ("ellipse foot phone light", 0x3666cda086f12325),
        ("map foot phone dark", 0xcecc3923fc1ab1e8),
        ("map zoomed foot phone dark", 0x2e4d5a1bf396765f),
        ("ellipse foot phone dark", 0x8bddb6748df52f25),
        ("map foot desktop light", 0xee2080832c902888),
        ("map zoomed foot desktop light", 0xdf596e392b23f350),
        ("ellipse foot desktop light", 0x5f026bea23112325),
        ("map foot desktop dark", 0x604ffa2e9d9cdd1c),
        ("map zoomed foot desktop dark", 0x6a64934381ebbaba),
        ("ellipse foot desktop dark", 0xcedc5471038baf25),
        ("figures no-gyro", 0x0c9216f1b918518f),
        ("map no-gyro phone light", 0x456533285998b75f),
        ("map zoomed no-gyro phone light", 0x0a5c46e091dc5d8a),
        ("ellipse no-gyro phone light", 0xa7ab0dbb0c4d208a),
        ("map no-gyro phone dark", 0x8b54f61e3e28673d),
        ("map zoomed no-gyro phone dark", 0x757c8adfdeb261d1),
        ("ellipse no-gyro phone dark", 0xb32ce2c5a38ea29c),
        ("map no-gyro desktop light", 0xca339921de7ae970),
        ("map zoomed no-gyro desktop light", 0x8cfe07955365b32c),
        ("ellipse no-gyro desktop light", 0xfc520633205fc453),
        ("map no-gyro desktop dark", 0x7757957a752728c6),
        ("map zoomed no-gyro desktop dark", 0xf0ae71271320046f),
        ("ellipse no-gyro desktop dark", 0xc644752fe9923fdc),
        ("figures floors", 0xc4f0aa156efbf3c6),
        ("map floors phone light", 0xb3bb4bedf0b23a3e),
        ("map zoomed floors phone light", 0x745045c791993a9d),
        ("ellipse floors phone light", 0x58589dfc33026321),
        ("map floors phone dark", 0x3affddf3491a295a),
        ("map zoomed floors phone dark", 0x260657128cd68f6c),
        ("ellipse floors phone dark", 0x21abf93ce8f2aba3),
        ("map floors desktop light", 0x4bf225f6eebdf345),
        ("map zoomed floors desktop light", 0x2c9132a9395f7209),
        ("ellipse floors desktop light", 0x1399418994b535c2),
        ("map floors desktop dark", 0x8d5d4ba69d4f1638),
        ("map zoomed floors desktop dark", 0xa67447abbb49a8d7),
        ("ellipse floors desktop dark", 0xe601503294d94f29),
    ];
    const LIVE: &[(&str, u64)] = &[
        ("live map phone light", 0x42eb19bb955ea5e7),
        ("live map desktop light", 0x69b11727d0277c3b),
        ("scope phone light", 0x2c4aa2f9938c14cb),
        ("scope desktop light", 0xe65b46a87444b98e),
        ("live map phone dark", 0x1d94c75123f220ad),
        ("live map desktop dark", 0x97bb8d4cee6c624d),
        ("scope phone dark", 0xdbabb7cc6cfca502),
        ("scope desktop dark", 0x7aa069d3ed715da6),
    ];
    const DEMOS: &[(&str, u64)] = &[
        ("fusion phone light", 0xe7866061705e8eae),
        ("basemap phone light", 0x65789d0cf0319d1c),
        ("track phone light", 0x9bdc170fccc8ea9e),
        ("calibration 0 phone light", 0xac294fd6deca147f),
        ("calibration 1 phone light", 0xf0001373dc6e0568),
        ("fusion desktop light", 0x784472300d10022a),
        ("basemap desktop light", 0xfba111434d98ac14),
        ("track desktop light", 0x621f3536f8d2b5f8),
        ("calibration 0 desktop light", 0xdacecc1835892d95),
        ("calibration 1 desktop light", 0x7586a3e8087cdae2),
        ("fusion phone dark", 0xce1633c8394e3d09),
        ("basemap phone dark", 0x4aef16daf1423f90),
        ("track phone dark", 0xff9f76a04e8cc469),
        ("calibration 0 phone dark", 0x01c3fe691e6dbda6),
        ("calibration 1 phone dark", 0xd7e8aff212c1c4ae),
        ("fusion desktop dark", 0x888fe298d3e0909f),
        ("basemap desktop dark", 0xb9b21c0b5837f04d),
        ("track desktop dark", 0xd1423f322ef5c7ac),
        ("calibration 0 desktop dark", 0x38a8e233ba46a9c8),
        ("calibration 1 desktop dark", 0x8a1e25a10cb36ba9),
    ];
}
