// Upload mode: files in (picker, folder, drag & drop), the worker parses and runs the engine,
// the page draws each analysis (AnalysisView, in wasm) and lets the user zoom, pan, hover,
// compare two configurations and export. Event plumbing only: the figures come from the engine.
import {
  cancelled_text, compare_settings, config_label, engine_progress, loaded_text, map_box,
  profile_options, read_progress, reading_text, result_card, upload_config,
} from './pkg/pdr.js';
import * as profiles from './profiles.js';
import * as recipes from './recipes.js';
import {
  $, dark, download, el, paint, render, safeName, test, uploadExports as wasm, uploadWasm, values,
} from './util.js';

let worker = null;
let logs = []; // [{info, card, views: {a, b}, step, bounds}]
let lastFiles = null;
let lastRecipes = []; // recipes uploaded with lastFiles (JSON), applied again on a re-run
let pending = 0; // worker jobs not yet done

function banner(text, kind = 'error') {
  $('upload-banners').append(el('li', { className: kind, textContent: text }));
}

/** The settings of a row (A or B) for the worker, and how they are described (`upload_config`
 * decides whether the chosen profile applies to the chosen step-length model). */
function config(tag) {
  const row = document.querySelector(`.config[data-config="${tag}"]`);
  const profile = row.querySelector('[name=profile]').value;
  return upload_config(values(row, 'select[data-choice]'), profile ? profiles.all()[profile] : undefined);
}

function configs() {
  const c = { a: config('a') };
  if ($('compare').checked) c.b = config('b');
  return c;
}

/** The profile choices; `adopt` sets them to the profile now selected on the device. */
function fillProfiles(adopt = false) {
  for (const sel of document.querySelectorAll('.config [name=profile]')) {
    const keep = adopt === true ? profiles.selectedName() : sel.value;
    sel.replaceChildren(...profile_options(Object.keys(profiles.all())).map(render));
    // '' is the built-in step length: a choice of its own, kept like a profile's name.
    sel.value = keep === '' || keep in profiles.all() ? keep : profiles.selectedName();
  }
}

// --- loading -------------------------------------------------------------------------------
function progress(text, fraction) {
  if (test.upload) {
    test.upload.progress_seen = true;
    test.upload.progress_max = Math.max(test.upload.progress_max ?? 0, fraction);
  }
  $('upload-progress').hidden = false;
  $('upload-cancel').hidden = false;
  $('upload-status').textContent = text;
  $('upload-bar').value = fraction;
  document.documentElement.dataset.upload = 'loading';
}

function startWorker() {
  worker?.terminate();
  const w = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  worker = w;
  // The analyses' views are upload mode's module's, loaded beside the worker: a message that
  // comes first waits for it (in order), unless this worker has been replaced meanwhile.
  uploadWasm();
  w.onmessage = ({ data }) => {
    if (wasm) onWorker(data);
    else uploadWasm().then(() => { if (worker === w) onWorker(data); });
  };
  worker.onerror = (e) => { banner(`The worker failed: ${e.message}`); finish(); };
}

/**
 * Reads `files`: with the recipes saved on this device (each folder one of them matches is read
 * by it) and `extra` (recipe JSON texts: the form's mapping, not saved).
 */
function load(files, extra = []) {
  if (!files.length) return;
  lastFiles = files;
  lastRecipes = extra;
  recipes.hideForm();
  for (const l of logs) for (const v of Object.values(l.views)) v?.free();
  logs = [];
  $('upload-results').replaceChildren();
  $('upload-banners').replaceChildren();
  startWorker();
  test.upload = {
    logs: [],
    errors: [],
    started: performance.now(),
    // For the end-to-end tests: where step `i` of log `k` is on the screen (CSS pixels).
    stepPixel(k, i) {
      const cv = logs[k].card.querySelector('.mapbox[data-tag="a"] canvas');
      const p = logs[k].views.a.step_pixel(i);
      const r = cv.getBoundingClientRect();
      return p && [r.left + p[0] * r.width / cv.width, r.top + p[1] * r.height / cv.height];
    },
    // Where time `t` (the log's clock) is on plot `kind` of log `k` (CSS pixels), and the span shown.
    plotPoint(k, kind, t) {
      const cv = logs[k].card.querySelector(`canvas.plot-${kind}`);
      const r = cv.getBoundingClientRect();
      return [r.left + logs[k].views.a.axis_x_at(cv.axis, t), r.top + r.height / 2];
    },
    span: (k) => logs[k].views.a.span(),
    // Shows `[t0, t1]` on log `k`'s plots, as a zoom would.
    setSpan(k, t0, t1) { logs[k].views.a.set_span(t0, t1); drawPlots(logs[k]); },
    full: (k) => logs[k].views.a.full_span(),
    stepTime: (k, i) => logs[k].views.a.step_info(i).t,
  };
  progress(reading_text(files.length), 0);
  pending = 1;
  worker.postMessage({ type: 'load', files, configs: configs(), recipes: [...extra, ...Object.values(recipes.saved())] });
}

/** The end of a load or a re-run: the bar stays, full, with what was done (or why not). */
function finish(cancelled = false) {
  const u = test.upload;
  const ms = u ? performance.now() - u.started : 0;
  const n = logs.filter(Boolean).length;
  if (cancelled) $('upload-status').textContent = 'Cancelled.';
  else {
    if (u) u.progress_max = 1;
    $('upload-bar').value = 1;
    $('upload-status').textContent = loaded_text(n, u?.bytes ?? 0, ms / 1000, u?.errors.length ?? 0);
  }
  $('upload-cancel').hidden = true;
  $('rerun').disabled = cancelled ? !lastFiles : !logs.length;
  document.documentElement.dataset.upload = 'done';
  if (u) u.done_ms = ms;
}

function onWorker(m) {
  if (m.type === 'progress') {
    const info = logs[m.index]?.info;
    if (m.phase === 'read') progress(...read_progress(m.done, m.total));
    else progress(...engine_progress(info?.source ?? '', info?.samples ?? 0, m.done, m.total, m.index, logs.length));
  } else if (m.type === 'parsed') {
    Object.assign(test.upload, { parse_ms: m.parse_ms, bytes: m.bytes });
    test.upload.errors.push(...m.parsed.errors);
    for (const [kind, text] of m.parsed.banners) banner(text, kind);
    for (const info of m.parsed.logs) logs[info.index] = { info, views: {}, card: card(info) };
  } else if (m.type === 'analysis') {
    const l = logs[m.index];
    l.views[m.tag]?.free();
    l.views[m.tag] = wasm.AnalysisView.from_bytes(new Uint8Array(m.bytes));
    show(l, m.tag, m.label);
    Object.assign(test.upload.logs[m.index], { engine_ms: m.engine_ms, analyse_ms: m.analyse_ms, memory_mb: m.memory_mb });
  } else if (m.type === 'describe') {
    recipes.showForm(m.description, {
      preview: (json) => worker?.postMessage({ type: 'preview', recipe: json }),
      run: (json) => load(lastFiles, [json]),
    });
  } else if (m.type === 'preview') {
    recipes.showPreview(m.result);
  } else if (m.type === 'pdrlog') {
    download(m.text, `${safeName(logs[m.index].info.source)}.pdrlog`);
  } else if (m.type === 'done') {
    pending -= 1;
    if (pending <= 0) finish();
  } else if (m.type === 'failed') {
    banner(m.message);
    finish();
  }
}

/** Loads uploaded files, a recipe among them applied to the others (recipes.splitUploaded). */
async function loadUploaded(files) {
  if (!recipes.mayHoldRecipes(files)) { load(files); return; }
  // The page is busy from the pick on (the tests and the user see it), while the recipes are read.
  document.documentElement.dataset.upload = 'loading';
  const split = await recipes.splitUploaded(files);
  load(split.files.length ? split.files : files, split.recipes);
}

/** Files from a drop, folders walked (their paths kept, so that folder formats are found). */
async function dropped(dt) {
  const entries = [...dt.items].map((i) => i.webkitGetAsEntry?.()).filter(Boolean);
  if (!entries.length) return [...dt.files].map((file) => ({ name: file.name, file }));
  const out = [];
  const walk = async (entry, path) => {
    if (entry.isFile) {
      out.push({ name: path + entry.name, file: await new Promise((res, rej) => entry.file(res, rej)) });
    } else if (entry.isDirectory) {
      const reader = entry.createReader();
      for (;;) {
        const batch = await new Promise((res, rej) => reader.readEntries(res, rej));
        if (!batch.length) break;
        for (const e of batch) await walk(e, `${path}${entry.name}/`);
      }
    }
  };
  for (const e of entries) await walk(e, '');
  return out;
}

// --- results -------------------------------------------------------------------------------
function card(info) {
  const c = render(result_card(info.index, info.source, info.hint));
  $('upload-results').append(c);
  return c;
}

function show(l, tag, label) {
  const v = l.views[tag];
  const s = v.summary();
  test.upload.logs[l.info.index] = { ...(test.upload.logs[l.info.index] ?? {}), [tag]: s };
  const maps = l.card.querySelector('.maps');
  let box = maps.querySelector(`[data-tag="${tag}"]`);
  if (!box) {
    box = render(map_box(tag));
    // A's map first.
    if (tag === 'a') maps.prepend(box);
    else maps.append(box);
    wireMap(l, tag, box.querySelector('canvas'));
  }
  box.querySelector('dl').replaceWith(render(v.figures()));
  // The configuration each map was run with, named once there are two.
  box.dataset.label = label;
  const two = Object.keys(l.views).length > 1;
  maps.classList.toggle('two', two);
  for (const b of maps.children) {
    b.querySelector('.config-label').replaceWith(render(config_label(b.dataset.tag, b.dataset.label, two)));
  }
  if (tag === 'a') {
    l.step = null;
    wirePlots(l);
  }
  drawAll(l);
  l.card.dataset.ready = 'yes';
}

function drawAll(l) {
  drawMaps(l);
  drawPlots(l);
}

/** The log's maps (A, and B when comparing); alone when base map tiles arrive. */
function drawMaps(l) {
  for (const [tag, v] of Object.entries(l.views)) {
    const cv = l.card.querySelector(`.mapbox[data-tag="${tag}"] canvas`);
    paint(cv, (...a) => v.draw_map(...a, l.bounds ?? [], l.step ?? undefined));
  }
}

function drawPlots(l) {
  const v = l.views.a;
  if (!v) return;
  const cursor = l.step != null ? v.step_info(l.step).t : undefined;
  for (const cv of l.card.querySelectorAll('canvas.plot')) {
    paint(cv, (c, dk, dpr) => {
      // [left, right, top, bottom] of the plot area in canvas pixels (for the legibility test).
      cv.area = v.draw_plot(c, dk, dpr, cv.dataset.kind, cursor);
      // Where the time axis lies, canvas pixels → CSS pixels, for pointer → time.
      cv.axis = cv.area.slice(0, 2).map((x) => x / dpr);
    });
  }
  const ell = l.card.querySelector('canvas.ellipse');
  paint(ell, (...a) => v.draw_ellipse(...a, l.step ?? Math.floor(v.summary().steps / 2)));
}

function select(l, i, view) {
  if (i == null) return;
  l.step = i;
  const info = l.card.querySelector('.stepinfo');
  info.textContent = view.step_text(i);
  info.dataset.step = String(i);
  drawAll(l);
}

/** Sends a canvas's pointer, wheel and double-click events to `handle` as the numbers the
 * engine's gesture rules read: (x, y) from the canvas's corner in CSS pixels × `scale(rect)`. */
function forward(cv, scale, handle) {
  const send = (e) => {
    const r = cv.getBoundingClientRect();
    const k = scale(r);
    const pointer = { kind: e.type, id: e.pointerId ?? 0, mouse: e.pointerType === 'mouse', delta_y: e.deltaY ?? 0 };
    handle({ ...pointer, x: (e.clientX - r.left) * k, y: (e.clientY - r.top) * k, scale: k });
  };
  cv.addEventListener('wheel', (e) => { e.preventDefault(); send(e); }, { passive: false });
  cv.addEventListener('pointerdown', (e) => { cv.setPointerCapture(e.pointerId); send(e); });
  for (const kind of ['dblclick', 'pointermove', 'pointerup', 'pointercancel']) cv.addEventListener(kind, send);
}

/** What the engine answered a gesture on `view`: a step to select, new map bounds, or the plots
 * to redraw. */
function answered(l, view, { step, bounds, redraw }) {
  if (bounds) l.bounds = bounds;
  if (step != null) select(l, step, view);
  else if (bounds) drawAll(l);
  else if (redraw) drawPlots(l);
}

/** Hover or tap picks a step; wheel and pinch zoom; drag pans; double-click resets (the map's
 * bounds are the log's, shared by its maps). In canvas pixels. */
function wireMap(l, tag, cv) {
  const g = new wasm.Gesture('map');
  forward(cv, (r) => cv.width / r.width, (ev) => {
    const v = l.views[tag];
    answered(l, v, v.map_gesture(g, ev, l.step ?? undefined));
  });
}

/** The plots share one time axis (its span kept by the engine): wheel or pinch zooms it about
 * the pointer, drag pans, click picks, double-click resets. In CSS pixels. */
function wirePlots(l) {
  for (const cv of l.card.querySelectorAll('canvas.plot')) {
    if (cv.dataset.wired) continue;
    cv.dataset.wired = '1';
    const g = new wasm.Gesture('plot');
    // Where the engine drew the time axis (CSS pixels from the canvas's left edge).
    const axis = () => cv.axis ?? [0, cv.getBoundingClientRect().width];
    forward(cv, () => 1, (ev) => answered(l, l.views.a, l.views.a.plot_gesture(g, ev, axis())));
  }
}

/** One PNG of the card's plots stacked (the map, then the diagnostics and the ellipse). */
function pngOf(l) {
  const canvases = [...l.card.querySelectorAll('canvas')];
  const w = Math.max(...canvases.map((c) => c.width));
  const h = canvases.reduce((s, c) => s + c.height, 0);
  const out = el('canvas', { width: w, height: h });
  const ctx = out.getContext('2d');
  let y = 0;
  for (const c of canvases) { ctx.drawImage(c, 0, y); y += c.height; }
  return new Promise((res) => out.toBlob(res, 'image/png'));
}

async function exportClicked(l, what) {
  const base = safeName(l.info.source.split('/').pop());
  if (what === 'pdrlog') worker.postMessage({ type: 'pdrlog', index: l.info.index });
  else if (what === 'png') download(await pngOf(l), `${base}.png`, 'image/png');
  else download(...l.views.a.export_file(what, base));
}

export function setupUpload() {
  recipes.saved(); // damaged stored recipes are told at once, not at the first upload
  fillProfiles(true);
  window.addEventListener('storage', () => fillProfiles());
  window.addEventListener('pdr-profiles-changed', () => fillProfiles(true));
  for (const sel of document.querySelectorAll('.config [name=profile]')) sel.addEventListener('focus', () => fillProfiles());
  // Files picked, or a folder (its files named with their paths in it).
  for (const id of ['upload-files', 'upload-folder']) {
    $(id).addEventListener('change', (e) => {
      loadUploaded([...e.target.files].map((file) => ({ name: file.webkitRelativePath || file.name, file })));
      e.target.value = '';
    });
  }
  const drop = $('drop');
  drop.addEventListener('dragover', (e) => { e.preventDefault(); drop.classList.add('over'); });
  drop.addEventListener('dragleave', () => drop.classList.remove('over'));
  drop.addEventListener('drop', async (e) => {
    e.preventDefault();
    drop.classList.remove('over');
    loadUploaded(await dropped(e.dataTransfer));
  });
  $('upload-cancel').addEventListener('click', () => {
    worker?.terminate();
    worker = null;
    banner(cancelled_text(), 'warn');
    finish(true);
  });
  for (const [key, value] of Object.entries(compare_settings().set)) {
    document.querySelector(`.config[data-config="b"] [name="${key}"]`).value = value;
  }
  for (const sel of document.querySelectorAll('.config [name="step_length.kind"]')) {
    const profile = sel.closest('.config').querySelector('[name=profile]');
    sel.addEventListener('change', () => { profile.disabled = sel.value !== 'frequency' && sel.value !== 'fuzzy'; });
  }
  $('compare').addEventListener('change', (e) => {
    document.querySelector('.config[data-config="b"]').hidden = !e.target.checked;
  });
  $('rerun').addEventListener('click', () => {
    fillProfiles();
    if (!worker || !logs.length) { if (lastFiles) load(lastFiles, lastRecipes); return; }
    const c = configs();
    for (const l of logs) {
      if (!c.b && l.views.b) {
        l.views.b.free();
        delete l.views.b;
        l.card.querySelector('.mapbox[data-tag="b"]')?.remove();
      }
    }
    test.upload.started = performance.now();
    test.upload.progress_max = 0;
    progress('running the engine again…', 0.35);
    pending += 1;
    worker.postMessage({ type: 'rerun', indices: logs.map((l) => l.info.index), configs: c });
  });
  $('upload-results').addEventListener('click', (e) => {
    const what = e.target.dataset?.export;
    if (!what) return;
    const l = logs[Number(e.target.closest('.log-result').dataset.index)];
    exportClicked(l, what);
  });
  const redraw = () => { for (const l of logs) if (l?.views.a) drawAll(l); };
  dark.addEventListener('change', redraw);
  window.addEventListener('resize', redraw);
  window.addEventListener('pdr-basemap', () => { for (const l of logs) if (l?.views.a) drawMaps(l); });
}
