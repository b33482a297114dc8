// Upload mode: files in (picker, folder, drag & drop), the worker parses and runs the engine,
// the page draws each analysis (AnalysisView, in wasm) and lets the user zoom, pan, hover,
// compare two configurations and export. Event plumbing only: the figures come from the engine.
import { AnalysisView, compare_settings, plot_titles, upload_config } from './pkg/pdr.js';
import * as profiles from './profiles.js';
import * as recipes from './recipes.js';
import { $, dark, download, el, fit, safeName, test } from './util.js';

let worker = null;
let logs = []; // [{info, card, views: {a, b}, step, bounds}]
let lastFiles = null;
let lastRecipes = []; // recipes uploaded with lastFiles (JSON), applied again on a re-run
let pending = 0; // worker jobs not yet done

function banner(text, kind = 'error') {
  const li = document.createElement('li');
  li.className = kind;
  li.textContent = text;
  $('upload-banners').append(li);
}

/** The settings of a row (A or B) for the worker, and how they are described (`upload_config`
 * decides whether the chosen profile applies to the chosen step-length model). */
function config(tag) {
  const row = document.querySelector(`.config[data-config="${tag}"]`);
  const set = {};
  for (const sel of row.querySelectorAll('select[data-choice]')) set[sel.name] = sel.value;
  const profile = row.querySelector('[name=profile]').value;
  return upload_config(set, profile ? profiles.all()[profile] : undefined);
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
    sel.replaceChildren(new Option('built-in step length', ''), ...Object.keys(profiles.all()).sort().map((n) => new Option(`profile: ${n}`, n)));
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

function fmtBytes(n) {
  return n > 1e6 ? `${(n / 1e6).toFixed(1)} MB` : `${Math.ceil(n / 1e3)} kB`;
}

function startWorker() {
  worker?.terminate();
  worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = ({ data }) => onWorker(data);
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
      const [left, right] = cv.axis;
      const [t0, t1] = logs[k].views.a.span();
      return [r.left + left + (t - t0) / (t1 - t0) * (right - left), r.top + r.height / 2];
    },
    span: (k) => logs[k].views.a.span(),
    // Shows `[t0, t1]` on log `k`'s plots, as a zoom would.
    setSpan(k, t0, t1) { logs[k].views.a.set_span(t0, t1); drawPlots(logs[k]); },
    full: (k) => logs[k].views.a.full_span(),
    stepTime: (k, i) => logs[k].views.a.step_info(i).t,
  };
  progress(`reading ${files.length} file${files.length > 1 ? 's' : ''}…`, 0);
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
    $('upload-status').textContent = `${n} recording${n === 1 ? '' : 's'} loaded`
      + (u?.bytes ? ` from ${fmtBytes(u.bytes)}` : '') + ` in ${(ms / 1000).toFixed(1)} s`
      + (u?.errors.length ? `, ${u.errors.length} file${u.errors.length === 1 ? '' : 's'} refused` : '');
  }
  $('upload-cancel').hidden = true;
  $('rerun').disabled = !logs.length;
  document.documentElement.dataset.upload = 'done';
  if (u) u.done_ms = ms;
}

function onWorker(m) {
  if (m.type === 'progress') {
    if (m.phase === 'read') progress(`parsed ${fmtBytes(m.done)} of ${fmtBytes(m.total)}`, 0.35 * m.done / Math.max(m.total, 1));
    else {
      const l = logs[m.index];
      const samples = l ? Math.round(l.info.samples * m.done / Math.max(m.total, 1)) : 0;
      progress(`${l?.info.source ?? ''}: ${samples.toLocaleString('en')} of ${(l?.info.samples ?? 0).toLocaleString('en')} samples through the engine`,
        0.35 + 0.65 * ((m.index + m.done / Math.max(m.total, 1)) / Math.max(logs.length, 1)));
    }
  } else if (m.type === 'parsed') {
    Object.assign(test.upload, { parse_ms: m.parse_ms, bytes: m.bytes });
    for (const e of m.parsed.errors) {
      banner(e.text);
      test.upload.errors.push(e);
    }
    if (!m.parsed.logs.length && !m.parsed.errors.length) banner('No recording recognised in these files: describe them below, or choose other files.', 'warn');
    for (const e of m.parsed.recipe_errors ?? []) banner(`A saved recipe was left out: ${e}`, 'warn');
    for (const info of m.parsed.logs) logs[info.index] = { info, views: {}, card: card(info) };
    for (const info of m.parsed.logs) for (const c of info.checks ?? []) banner(`${info.source}, read with the recipe "${info.recipe}": ${c}`, 'warn');
  } else if (m.type === 'analysis') {
    const l = logs[m.index];
    l.views[m.tag]?.free();
    l.views[m.tag] = AnalysisView.from_bytes(new Uint8Array(m.bytes));
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
  const c = el('article', { className: 'log-result' });
  c.dataset.index = info.index;
  c.append(el('h3', { textContent: info.source }),
    el('p', { className: 'hint', textContent: info.hint }));
  c.append(el('div', { className: 'maps' }));
  c.append(el('div', { className: 'stepinfo', textContent: 'Hover or tap a step on the track, or click a plot, to see its values.' }));
  const plots = el('div', { className: 'plots' });
  for (const [kind, label] of plot_titles()) {
    const cv = el('canvas', { className: `plot plot-${kind}` });
    cv.dataset.kind = kind;
    cv.setAttribute('role', 'img');
    cv.setAttribute('aria-label', label);
    plots.append(cv);
  }
  const ell = el('canvas', { className: 'ellipse' });
  ell.setAttribute('role', 'img');
  ell.setAttribute('aria-label', 'Horizontal acceleration over the selected stride, with its heading');
  plots.append(el('p', { className: 'hint', textContent: 'Wheel or pinch to zoom the time axis, drag to pan, double-click to reset; click to pick a step.' }), ell);
  c.append(plots);
  const ex = el('div', { className: 'controls exports' });
  for (const [what, label] of [['gpx', 'GPX'], ['geojson', 'GeoJSON'], ['csv', 'Steps CSV'], ['pdrlog', 'pdr-log'], ['png', 'PNG of the plots']]) {
    const b = el('button', { type: 'button', className: 'small', textContent: label });
    b.dataset.export = what;
    ex.append(b);
  }
  c.append(ex);
  $('upload-results').append(c);
  return c;
}

/** The figures under a map, as the engine words them. */
function figures(view) {
  const dl = el('dl', { className: 'summary' });
  for (const [k, v] of view.figures()) dl.append(el('dt', { textContent: k }), el('dd', { textContent: v }));
  return dl;
}

function show(l, tag, label) {
  const v = l.views[tag];
  const s = v.summary();
  l.summaries = { ...(l.summaries ?? {}), [tag]: s };
  test.upload.logs[l.info.index] = { ...(test.upload.logs[l.info.index] ?? {}), [tag]: s };
  const maps = l.card.querySelector('.maps');
  let box = maps.querySelector(`[data-tag="${tag}"]`);
  if (!box) {
    box = el('div', { className: 'mapbox' });
    box.dataset.tag = tag;
    const cv = el('canvas', { className: 'map' });
    cv.setAttribute('role', 'img');
    cv.setAttribute('aria-label', 'Track in metres, east right, north up');
    box.append(el('h4', { className: 'config-label' }), cv, el('dl'));
    maps.append(box);
    [...maps.children].sort((a, b) => a.dataset.tag.localeCompare(b.dataset.tag)).forEach((c) => maps.append(c));
    wireMap(l, tag, cv);
  }
  box.querySelector('dl').replaceWith(figures(v));
  // The configuration each map was run with, named once there are two.
  box.dataset.label = label;
  const two = Object.keys(l.views).length > 1;
  maps.classList.toggle('two', two);
  for (const b of maps.children) {
    const h = b.querySelector('.config-label');
    h.hidden = !two;
    h.textContent = `${b.dataset.tag.toUpperCase()}: ${b.dataset.label}`;
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
    const dpr = fit(cv);
    if (dpr) v.draw_map(cv, dark.matches, dpr, l.bounds ?? [], l.step ?? undefined);
  }
}

function drawPlots(l) {
  const v = l.views.a;
  if (!v) return;
  const cursor = l.step != null ? v.step_info(l.step).t : undefined;
  for (const cv of l.card.querySelectorAll('canvas.plot')) {
    const dpr = fit(cv);
    if (!dpr) continue;
    // [left, right, top, bottom] of the plot area in canvas pixels (for the legibility test).
    cv.area = v.draw_plot(cv, dark.matches, dpr, cv.dataset.kind, cursor);
    // Where the time axis lies, canvas pixels → CSS pixels, for pointer → time.
    cv.axis = cv.area.slice(0, 2).map((x) => x / dpr);
  }
  const ell = l.card.querySelector('canvas.ellipse');
  const dpr = fit(ell);
  if (dpr) v.draw_ellipse(ell, dark.matches, dpr, l.step ?? Math.floor(v.summary().steps / 2));
}

function select(l, i, view) {
  if (i == null) return;
  l.step = i;
  const info = l.card.querySelector('.stepinfo');
  info.textContent = view.step_text(i);
  info.dataset.step = String(i);
  drawAll(l);
}

/** Hover or tap picks a step; wheel and pinch zoom; drag pans; double-click resets. */
function wireMap(l, tag, cv) {
  const pointers = new Map();
  let drag = null;
  const pos = (e) => {
    const r = cv.getBoundingClientRect();
    const dpr = cv.width / r.width;
    return [(e.clientX - r.left) * dpr, (e.clientY - r.top) * dpr, dpr];
  };
  // New bounds from the engine (none when a pinch has nothing to zoom by), then redraw.
  const setBounds = (bounds) => {
    if (!bounds) return;
    l.bounds = bounds;
    drawAll(l);
  };
  cv.addEventListener('wheel', (e) => { e.preventDefault(); const [x, y] = pos(e); setBounds(l.views[tag].map_wheel(x, y, e.deltaY)); }, { passive: false });
  cv.addEventListener('dblclick', () => { l.bounds = null; drawAll(l); });
  cv.addEventListener('pointerdown', (e) => {
    cv.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, pos(e));
    drag = { moved: false };
  });
  cv.addEventListener('pointermove', (e) => {
    const p = pos(e);
    const v = l.views[tag];
    if (!pointers.has(e.pointerId)) {
      if (e.pointerType === 'mouse') {
        const i = v.pick(p[0], p[1], 12 * p[2]);
        if (i != null && i !== l.step) select(l, i, v);
      }
      return;
    }
    const prev = pointers.get(e.pointerId);
    pointers.set(e.pointerId, p);
    if (pointers.size === 2) {
      const [a, b] = [...pointers.values()];
      const other = a === p ? b : a;
      setBounds(v.map_pinch(prev[0], prev[1], p[0], p[1], other[0], other[1]));
    } else if (pointers.size === 1 && Math.hypot(p[0] - prev[0], p[1] - prev[1]) > 0.5) {
      drag.moved = true;
      setBounds(v.map_pan(p[0] - prev[0], p[1] - prev[1]));
    }
  });
  const up = (e) => {
    const p = pointers.get(e.pointerId);
    pointers.delete(e.pointerId);
    if (p && drag && !drag.moved) {
      const v = l.views[tag];
      select(l, v.pick(p[0], p[1], 24 * p[2]), v);
    }
  };
  cv.addEventListener('pointerup', up);
  cv.addEventListener('pointercancel', (e) => pointers.delete(e.pointerId));
}

/** The plots share one time axis (its span kept by the engine): wheel or pinch zooms it about
 * the pointer, drag pans, click picks, double-click resets. */
function wirePlots(l) {
  for (const cv of l.card.querySelectorAll('canvas.plot')) {
    if (cv.dataset.wired) continue;
    cv.dataset.wired = '1';
    const pointers = new Map(); // pointerId → clientX
    let drag = null;
    const v = () => l.views.a;
    // A client x in CSS pixels from the canvas's left edge, and where the engine drew the axis.
    const at = (x) => x - cv.getBoundingClientRect().left;
    const axis = () => cv.axis ?? [0, cv.getBoundingClientRect().width];
    const grab = (x) => { v().axis_grab(); return { x, moved: true }; };
    cv.addEventListener('wheel', (e) => {
      e.preventDefault();
      v().axis_wheel(axis(), at(e.clientX), e.deltaY);
      drawPlots(l);
    }, { passive: false });
    cv.addEventListener('dblclick', () => { v().reset_span(); drawPlots(l); });
    cv.addEventListener('pointerdown', (e) => {
      cv.setPointerCapture(e.pointerId);
      pointers.set(e.pointerId, e.clientX);
      drag = { ...grab(e.clientX), moved: pointers.size > 1 };
    });
    cv.addEventListener('pointermove', (e) => {
      if (!pointers.has(e.pointerId)) return;
      const prev = pointers.get(e.pointerId);
      pointers.set(e.pointerId, e.clientX);
      if (pointers.size === 2) {
        // Pinch (see TimeAxis::pinched).
        const other = [...pointers.entries()].find(([id]) => id !== e.pointerId)[1];
        if (v().axis_pinch(axis(), at(prev), at(e.clientX), at(other))) drawPlots(l);
        return;
      }
      if (!drag) return;
      if (Math.abs(e.clientX - drag.x) > 3) drag.moved = true;
      if (!drag.moved) return;
      v().axis_pan(axis(), at(drag.x), at(e.clientX));
      drawPlots(l);
    });
    cv.addEventListener('pointerup', (e) => {
      pointers.delete(e.pointerId);
      if (drag && !drag.moved && !pointers.size) select(l, v().step_near_time(v().axis_time_at(axis(), at(e.clientX))), v());
      // A finger left after a pinch does not start a pan from where it was.
      drag = pointers.size ? grab([...pointers.values()][0]) : null;
    });
    // The browser took the gesture (a vertical scroll): nothing to pick.
    cv.addEventListener('pointercancel', (e) => { pointers.delete(e.pointerId); drag = null; });
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
  const v = l.views.a;
  const base = safeName(l.info.source.split('/').pop());
  if (what === 'gpx') download(v.gpx(), `${base}.gpx`, 'application/gpx+xml');
  else if (what === 'geojson') download(v.geojson(), `${base}.geojson`, 'application/geo+json');
  else if (what === 'csv') download(v.steps_csv(), `${base}.steps.csv`, 'text/csv');
  else if (what === 'pdrlog') worker.postMessage({ type: 'pdrlog', index: l.info.index });
  else if (what === 'png') download(await pngOf(l), `${base}.png`, 'image/png');
}

export function setupUpload() {
  recipes.saved(); // damaged stored recipes are told at once, not at the first upload
  fillProfiles(true);
  window.addEventListener('storage', () => fillProfiles());
  window.addEventListener('pdr-profiles-changed', () => fillProfiles(true));
  for (const sel of document.querySelectorAll('.config [name=profile]')) sel.addEventListener('focus', () => fillProfiles());
  $('upload-files').addEventListener('change', (e) => {
    loadUploaded([...e.target.files].map((file) => ({ name: file.name, file })));
    e.target.value = '';
  });
  $('upload-folder').addEventListener('change', (e) => {
    loadUploaded([...e.target.files].map((file) => ({ name: file.webkitRelativePath || file.name, file })));
    e.target.value = '';
  });
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
    banner('Cancelled: nothing more will be read or run. Choose the files again, or Re-run, to start over.', 'warn');
    finish(true);
    $('rerun').disabled = !lastFiles;
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
    for (const l of logs) {
      for (const [tag, config] of Object.entries(c)) {
        pending += 1;
        worker.postMessage({ type: 'rerun', index: l.info.index, config, tag });
      }
    }
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
