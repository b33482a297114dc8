//! The opt-in base map on the page's canvases: the tile server the page chose (none by default),
//! the tile images (a bounded least-recently-used cache of `<img>` elements, fetched only for
//! tiles on screen), and the painter that draws a tile's image under a map.
//! May import: `engine` (the geodetic origin) and `plot`.
//!
//! Nothing here runs, and no image is requested, until the page calls [`set_basemap`] with a
//! template: with the setting off the page makes no request to another origin. A tile that
//! arrives fires the window event `pdr-tile`; the page redraws its maps on it (once a frame).

use super::{to_js, to_value};
use crate::engine::geo::LocalFrame;
use crate::plot::basemap_setting::BasemapSetting;
use crate::plot::tiles::{Piece, Tile, TileTemplate, OSM_ATTRIBUTION, OSM_TEMPLATE};
use crate::plot::{Basemap, TileState};
use std::cell::RefCell;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{HtmlCanvasElement, HtmlImageElement};

/// Tile images kept: more than one map's worst case ([`crate::plot::tiles::MAX_TILES`]), so
/// that redrawing a map never evicts its own tiles.
const CACHE_TILES: usize = 256;

struct Entry {
    url: String,
    img: HtmlImageElement,
    used: u64,
}

#[derive(Default)]
struct State {
    template: Option<TileTemplate>,
    images: Vec<Entry>,
    clock: u64,
    notify: Option<Closure<dyn FnMut()>>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

/// Turns the base map on with the tile URL `template` and the credit line `attribution` (empty:
/// the server's own, see [`TileTemplate::parse`]), or off when `template` is empty. A template
/// that is not usable is an error naming what is wrong, and leaves the base map off.
#[wasm_bindgen]
pub fn set_basemap(template: &str, attribution: &str) -> Result<(), JsError> {
    let parsed = if template.trim().is_empty() {
        None
    } else {
        Some(TileTemplate::parse(template, attribution))
    };
    STATE.with(|s| {
        let mut s = s.borrow_mut();
        let changed = s.template.as_ref().map(TileTemplate::as_str)
            != parsed
                .as_ref()
                .and_then(|p| p.as_ref().ok())
                .map(TileTemplate::as_str);
        if changed {
            for e in s.images.drain(..) {
                e.img.set_onload(None);
                e.img.set_onerror(None);
            }
        }
        match parsed {
            Some(Ok(t)) => {
                s.template = Some(t);
                Ok(())
            }
            Some(Err(e)) => {
                s.template = None;
                Err(to_js(e))
            }
            None => {
                s.template = None;
                Ok(())
            }
        }
    })
}

/// The default tile server and its credit: `[template, attribution]`.
#[wasm_bindgen]
pub fn basemap_default() -> Vec<String> {
    vec![OSM_TEMPLATE.to_string(), OSM_ATTRIBUTION.to_string()]
}

/// The stored setting `{on, template, attribution}` from its JSON text (`null`: nothing stored;
/// see `plot::basemap_setting`): off with OpenStreetMap's tiles by default.
#[wasm_bindgen]
pub fn basemap_stored(text: Option<String>) -> Result<JsValue, JsError> {
    to_value(&BasemapSetting::from_stored(text.as_deref()))
}

/// The setting `{on, template, attribution}` from the form's fields (trimmed; a blank template
/// is OpenStreetMap's).
#[wasm_bindgen]
pub fn basemap_form(on: bool, template: &str, attribution: &str) -> Result<JsValue, JsError> {
    to_value(&BasemapSetting::from_form(on, template, attribution))
}

/// What the page says about the base map for `key` (see `plot::basemap_setting::message`).
#[wasm_bindgen]
pub fn basemap_message(key: &str, detail: Option<String>) -> Result<String, JsError> {
    crate::plot::basemap_setting::message(key, detail.as_deref().unwrap_or(""))
        .ok_or_else(|| to_js(format!("no base map message `{key}`")))
}

/// Tells the page a tile arrived (or failed): the window event `pdr-tile`.
fn notify_closure() -> Closure<dyn FnMut()> {
    Closure::new(|| {
        if let Some(w) = web_sys::window() {
            if let Ok(ev) = web_sys::Event::new("pdr-tile") {
                let _ = w.dispatch_event(&ev);
            }
        }
    })
}

/// Paints the part `piece` of a tile from the cache, or requests the tile (the least recently
/// used image makes room).
fn paint(ctx: &web_sys::CanvasRenderingContext2d, piece: &Piece, url: &str) -> TileState {
    STATE.with(|s| {
        let mut guard = s.borrow_mut();
        let s = &mut *guard;
        s.clock += 1;
        let now = s.clock;
        if let Some(e) = s.images.iter_mut().find(|e| e.url == url) {
            e.used = now;
            if !e.img.complete() {
                return TileState::Loading;
            }
            if e.img.natural_width() == 0 {
                return TileState::Failed;
            }
            let (w, h) = (
                f64::from(e.img.natural_width()),
                f64::from(e.img.natural_height()),
            );
            let (sl, st, sr, sb) = piece.src;
            let (l, t, r, b) = piece.dst;
            return match ctx
                .draw_image_with_html_image_element_and_sw_and_sh_and_dx_and_dy_and_dw_and_dh(
                    &e.img,
                    sl * w,
                    st * h,
                    (sr - sl) * w,
                    (sb - st) * h,
                    f64::from(l),
                    f64::from(t),
                    f64::from(r - l),
                    f64::from(b - t),
                ) {
                Ok(()) => TileState::Drawn,
                Err(_) => TileState::Failed,
            };
        }
        let Ok(img) = HtmlImageElement::new() else {
            return TileState::Failed;
        };
        let notify = s.notify.get_or_insert_with(notify_closure);
        img.set_onload(Some(notify.as_ref().unchecked_ref()));
        img.set_onerror(Some(notify.as_ref().unchecked_ref()));
        // CORS, so that the canvas stays readable (PNG export); tile servers send
        // Access-Control-Allow-Origin for this.
        img.set_cross_origin(Some("anonymous"));
        img.set_src(url);
        if s.images.len() >= CACHE_TILES {
            if let Some(i) = (0..s.images.len()).min_by_key(|&i| s.images[i].used) {
                let old = s.images.swap_remove(i);
                old.img.set_onload(None);
                old.img.set_onerror(None);
            }
        }
        s.images.push(Entry {
            url: url.to_string(),
            img,
            used: now,
        });
        TileState::Loading
    })
}

/// Runs `draw` with the base map for a map at `origin` on `canvas` (none when the setting is off
/// or the map has no geodetic origin), then notes on the canvas what it showed: the attribute
/// `data-basemap` holds the credit line and `data-tiles` "drawn loading failed".
pub(super) fn with_basemap<R>(
    canvas: &HtmlCanvasElement,
    origin: Option<LocalFrame>,
    draw: impl FnOnce(Option<&mut Basemap<'_>>) -> R,
) -> R {
    let el: &web_sys::Element = canvas.unchecked_ref();
    let template = STATE.with(|s| s.borrow().template.clone());
    let ctx = canvas
        .get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<web_sys::CanvasRenderingContext2d>().ok());
    let (Some(template), Some(origin), Some(ctx)) = (template, origin, ctx) else {
        let _ = el.remove_attribute("data-basemap");
        let _ = el.remove_attribute("data-tiles");
        return draw(None);
    };
    let mut painter = |_: &Tile, piece: &Piece, url: &str| paint(&ctx, piece, url);
    let mut basemap = Basemap {
        origin,
        tiles: &template,
        paint: &mut painter,
        shown: None,
    };
    let out = draw(Some(&mut basemap));
    if let Some(s) = &basemap.shown {
        let _ = el.set_attribute("data-basemap", &s.line);
        let (d, l, f) = s.counts;
        let _ = el.set_attribute("data-tiles", &format!("{d} {l} {f}"));
    }
    out
}
