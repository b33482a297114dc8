// The opt-in base map's setting: off by default, kept in localStorage, handed to the engine
// (set_basemap, src/web/basemap.rs), which checks the template, fetches only the tiles on
// screen and draws them under the maps. Maps redraw on the window event `pdr-basemap`: when the
// setting changes, and once a frame while tiles arrive (the engine fires `pdr-tile` for each).
import { basemap_default, basemap_form, basemap_message, basemap_stored, set_basemap } from './pkg/pdr.js';
import { $, note, onUploadWasm, uploadExports } from './util.js';

const KEY = 'pdr-basemap';
/** The service worker's tile cache (see sw.js). */
export const TILE_CACHE = 'pdr-tiles-v1';

/** The stored setting `{on, template, attribution}`; off with OpenStreetMap's tiles by default. */
export const load = () => basemap_stored(localStorage.getItem(KEY));

function save(s) {
  localStorage.setItem(KEY, JSON.stringify(s));
}

const redraw = () => window.dispatchEvent(new Event('pdr-basemap'));

/** The template and attribution the engine has; upload mode's module (its maps) gets them too. */
let handed = ['', ''];
function hand(template, attribution) {
  set_basemap(template, attribution);
  handed = [template, attribution];
  uploadExports?.set_basemap(template, attribution);
}

/** Hands the setting to the engine; a template it refuses leaves the map off, with the reason. */
function apply(s) {
  try {
    hand(s.on ? s.template : '', s.attribution);
    note('basemap-messages', 'template', null);
  } catch (err) {
    hand('', '');
    note('basemap-messages', 'template', basemap_message('off', String(err.message ?? err)), 'error');
  }
  $('basemap').dataset.on = s.on ? 'yes' : 'no';
  redraw();
}

/** Wires the setting's controls; call once the engine is loaded, before the maps draw. */
export function setupBasemap() {
  const s = load();
  $('basemap-on').checked = s.on;
  $('basemap-template').value = s.template;
  $('basemap-attribution').value = s.attribution;
  apply(s);
  onUploadWasm((m) => m.set_basemap(...handed));
  const fromForm = () => basemap_form($('basemap-on').checked, $('basemap-template').value,
    $('basemap-attribution').value);
  const changed = () => { const n = fromForm(); save(n); apply(n); };
  $('basemap-on').addEventListener('change', changed);
  $('basemap-apply').addEventListener('click', changed);
  $('basemap-template').addEventListener('keydown', (e) => { if (e.key === 'Enter') changed(); });
  $('basemap-reset').addEventListener('click', () => {
    $('basemap-template').value = basemap_default()[0];
    $('basemap-attribution').value = '';
    changed();
  });
  $('basemap-forget').addEventListener('click', async () => {
    const gone = 'caches' in window && await caches.delete(TILE_CACHE);
    note('basemap-messages', 'forget', basemap_message(gone ? 'forgotten' : 'none_cached'), 'ok');
  });
  // Tiles arrive one by one: one redraw a frame.
  let pending = false;
  window.addEventListener('pdr-tile', () => {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; redraw(); });
  });
}
