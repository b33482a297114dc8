// One-hour soak of live mode: a benchmark that prints figures, not a test (`./dev soak`).
//
// The path of the samples. The walk is `pdr simulate --scenario long` (walking, turning, pausing,
// running), its first hour of 100 Hz motion. The page runs under CDP virtual time
// (`Emulation.setVirtualTimePolicy`): its clocks (performance.now, Date.now, event timeStamps)
// and timers advance virtually, as fast as the page can keep up. A page timer,
// `setInterval(…, 10)`, fires one `deviceorientationabsolute` and one `devicemotion` per tick,
// each a real `new DeviceMotionEvent(...)` whose `timeStamp` the browser sets to the (virtual)
// time of its creation: nothing overrides it. So the page receives what a phone firing at
// 100 Hz gives it, on a clock that reads like real time, and its own timers (the 250 ms
// recording batches, IndexedDB writes, requestAnimationFrame's readouts) run as they would,
// virtually. The CDP virtual sensors are not used: Chromium samples them at 60 Hz of wall time,
// so an hour through them takes an hour. Time is granted a minute at a time; in between, with
// virtual time paused, the next minute's samples are handed to the page and the figures taken.
//
// Figures, after the first minute and then every `--every` minutes:
// - wasm memory: the engine's `WebAssembly.Memory` (the module's exported `memory`), bytes;
// - JS heap: CDP `Runtime.getHeapUsage` used size after a forced garbage collection;
// - IndexedDB: the length of the text the page has written (its count of chunks written; the
//   database cannot be read while virtual time is paused, as its callbacks wait for it), and
//   the chunks not yet written; at the end the stored recording is read back;
// - draw: one redraw of the map and the scope (`live.draw` + `draw_scope`), each followed by a
//   one-pixel read of both canvases so that the drawing is rasterised, not only recorded;
//   wall-clock ms, measured from this script around a page call of 50 redraws made while
//   virtual time is paused (the page's clock does not move then), less the same call with
//   none (the least of 5 tries each), over 50;
// - samples fed and recorded (the stored log's `imu` lines), steps, wall time.
// The pocket guard stays up during the walk, as in a pocket: the page then draws no plots.
// At the end: the stored log's sample spacing, and `pdr run` of it against the page's steps.
//
// Usage: node tests/e2e/soak.mjs [--minutes 60] [--every 10]   (PDR_E2E_URL, PDR_BIN as for the tests)
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const arg = (name, dflt) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? Number(process.argv[i + 1]) : dflt;
};
const MINUTES = arg('minutes', 60);
const EVERY = arg('every', 10);
const URL_HTTP = process.env.PDR_E2E_URL ?? 'http://127.0.0.1:8080/';
const BIN = process.env.PDR_BIN ?? path.join(path.dirname(new URL(import.meta.url).pathname), '../../target/release/pdr');
const HZ = 100;
const DRAWS = 50;
const tmp = mkdtempSync(path.join(os.tmpdir(), 'pdr-soak-'));
const wall0 = Date.now();
const wall = () => ((Date.now() - wall0) / 1000).toFixed(0);

// The walk: a little more than asked (the scenario adds its pauses), cut at MINUTES of samples.
console.log(`soak: ${MINUTES} min at ${HZ} Hz through ${URL_HTTP}`);
const file = path.join(tmp, 'walk.json');
execFileSync(BIN, ['simulate', '--scenario', 'long', '--minutes', String(MINUTES), '--events', file]);
const walk = JSON.parse(readFileSync(file, 'utf8'));
const N = MINUTES * 60 * HZ;
// One row per tick: motion x y z alpha beta gamma, then the orientation alpha beta gamma.
const rows = [];
let orientation = null;
for (const e of walk.events) {
  if (e.type === 'orientation') orientation = [e.alpha, e.beta, e.gamma];
  else if (rows.length < N) rows.push([e.x, e.y, e.z, e.alpha, e.beta, e.gamma, ...(orientation ?? [null, null, null])]);
}
walk.events = null;
if (rows.length < N) throw new Error(`the walk has ${rows.length} samples, fewer than ${N}`);
console.log(`walk: ${rows.length} samples (${walk.truth_steps} true steps in the whole scenario); wall ${wall()} s`);

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync'],
});
const context = await browser.newContext({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true });
const page = await context.newPage();
const errors = [];
page.on('pageerror', (e) => errors.push(String(e)));
page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
await page.goto(URL_HTTP);
await page.waitForFunction(() => document.documentElement.dataset.state === 'ready', null, { timeout: 30_000 });
await page.selectOption('#gnss-mode', 'off');
await page.click('#start');
await page.waitForFunction(() => document.documentElement.dataset.source === 'events', null, { timeout: 10_000 });
// The pocket guard stays up, as in a pocket; the plots are drawn for the figures only.
await page.evaluate(async () => {
  window.__wasm = await (await import('./www/pkg/pdr.js')).default(); // the initialised module's exports
  const soak = { queue: [], k: 0, fired: 0, starved: 0 };
  window.__soak = soak;
  setInterval(() => {
    if (soak.k >= soak.queue.length) { soak.starved++; return; }
    const e = soak.queue[soak.k++];
    if (e[6] != null) {
      window.dispatchEvent(new DeviceOrientationEvent('deviceorientationabsolute', { alpha: e[6], beta: e[7], gamma: e[8], absolute: true }));
    }
    window.dispatchEvent(new DeviceMotionEvent('devicemotion', {
      accelerationIncludingGravity: { x: e[0], y: e[1], z: e[2] },
      rotationRate: { alpha: e[3], beta: e[4], gamma: e[5] },
      interval: 10,
    }));
    soak.fired++;
  }, 10);
});
const cdp = await context.newCDPSession(page);
await cdp.send('Emulation.setVirtualTimePolicy', { policy: 'pause' });

/** Grants `ms` of virtual time and waits until it has passed. */
async function advance(ms) {
  const expired = new Promise((resolve) => cdp.once('Emulation.virtualTimeBudgetExpired', resolve));
  await cdp.send('Emulation.setVirtualTimePolicy', { policy: 'advance', budget: ms });
  await expired;
}

/** Hands the page the next rows (virtual time paused), keeping what it has not fired. */
let given = 0;
async function give(count) {
  const next = rows.slice(given, given + count);
  given += next.length;
  for (let i = 0; i < next.length; i += 3000) {
    await page.evaluate((chunk) => {
      const s = window.__soak;
      if (s.k > 0) { s.queue = s.queue.slice(s.k); s.k = 0; }
      s.queue.push(...chunk);
    }, next.slice(i, i + 3000));
  }
}


/**
 * Runs `fn` in the page and waits for its promise: IndexedDB's callbacks wait for virtual time,
 * so time is granted in small steps until it settles (call only once the walk has ended).
 */
async function settle(fn, arg) {
  await page.evaluate(([src, arg]) => {
    window.__settled = undefined;
    (0, eval)(src)(arg).then((v) => { window.__settled = { v }; }, (e) => { window.__settled = { e: String(e) }; });
  }, [fn.toString(), arg]);
  for (let i = 0; i < 2000; i++) {
    const r = await page.evaluate(() => window.__settled);
    if (r) { if (r.e) throw new Error(r.e); return r.v; }
    await advance(20);
  }
  throw new Error('the page did not settle');
}

/** The stored recording: its text length, imu lines, and (`full`) the text and the sample spacing. */
const stored = (full) => settle(async (full) => {
  const store = await import('./www/store.js');
  const [rec] = (await store.list()).filter((r) => r.state === 'recording');
  const { pieces } = await store.pieces(rec.id);
  let chars = 0;
  let imu = 0;
  const dt = { min: Infinity, max: -Infinity, off: 0 };
  let last = null;
  for (const p of pieces) {
    chars += p.text.length;
    for (const line of p.text.split('\n')) {
      if (!line.startsWith('imu,')) continue;
      imu++;
      if (!full) continue;
      const t = Number(line.slice(4, line.indexOf(',', 4)));
      if (last != null) {
        const d = (t - last) * 1000;
        dt.min = Math.min(dt.min, d);
        dt.max = Math.max(dt.max, d);
        if (Math.abs(d - 10) > 0.15) dt.off++;
      }
      last = t;
    }
  }
  return { chars, imu, dt, text: full ? pieces.map((p) => p.text).join('') : null };
}, full);

/** The figures now (virtual time paused); `end`: the walk is over, the stored log is read. */
async function figures(minute, end = false) {
  await cdp.send('HeapProfiler.collectGarbage');
  const heap = await cdp.send('Runtime.getHeapUsage');
  const r = await page.evaluate(() => ({ ...window.__pdrTest.live.readouts, fired: window.__soak.fired, starved: window.__soak.starved,
    wasm: window.__wasm.memory.buffer.byteLength, saved: window.__pdrTest.live.saved, unsaved: window.__pdrTest.live.unsaved }));
  // The draw, in wall time: DRAWS redraws in one page call, less the same call with none (the
  // least of 5 tries each), over DRAWS.
  const timed = async (n) => {
    const t = performance.now();
    await page.evaluate((n) => {
      const canvases = ['live-map', 'live-scope'].map((id) => document.getElementById(id).getContext('2d'));
      for (let i = 0; i < n; i++) {
        window.__pdrTest.live.draw();
        for (const c of canvases) c.getImageData(0, 0, 1, 1); // the pixels made, not only the commands recorded
      }
    }, n);
    return performance.now() - t;
  };
  let zero = Infinity;
  let many = Infinity;
  for (let i = 0; i < 5; i++) zero = Math.min(zero, await timed(0));
  for (let i = 0; i < 5; i++) many = Math.min(many, await timed(DRAWS));
  const s = end ? await stored(true) : null;
  return {
    minute, wall_s: Number(wall()), fed: r.fired, recorded: s?.imu ?? '', steps: r.steps,
    wasm_MB: +(r.wasm / 2 ** 20).toFixed(2), js_heap_MB: +(heap.usedSize / 2 ** 20).toFixed(2),
    idb_MB: +(r.saved.chars / 2 ** 20).toFixed(2), unsaved_chunks: r.unsaved, draw_ms: +((many - zero) / DRAWS).toFixed(2),
    starved: r.starved, s,
  };
}

const table = [];
// A second of samples ahead of the timer, so that a minute of virtual time that holds one tick
// more than 6000 (the timer's phase) never finds the queue empty.
await give(HZ);
for (let minute = 1; minute <= MINUTES; minute++) {
  await give(60 * HZ);
  await advance(60_000);
  if (minute === MINUTES) {
    await advance(1000); // the last batch is taken (no samples left: the timer idles)
  }
  if (minute === 1 || minute % EVERY === 0 || minute === MINUTES) {
    const f = await figures(minute, minute === MINUTES);
    table.push(f);
    const { s, ...row } = f;
    console.log(JSON.stringify(row));
  }
}

const first = table[0];
const end = table.at(-1);
console.table(table.map(({ s, ...row }) => row));
const text = end.s.text;
const log = path.join(tmp, 'soak.pdrlog');
writeFileSync(log, text);
const run = execFileSync(BIN, ['run', log], { encoding: 'utf8' });
const replayed = Number(run.match(/^steps\s+(\d+)/m)[1]);
const d = end.s.dt;
console.log(`samples: fed ${end.fed}, recorded ${end.recorded}; `
  + `spacing of the stored samples ${d.min.toFixed(3)}…${d.max.toFixed(3)} ms, ${d.off} outside 10 ± 0.15 ms; timer ticks without a sample ${end.starved}`);
console.log(`steps: page ${end.steps}, pdr run of the stored log ${replayed}; IndexedDB read back: ${(end.s.chars / 2 ** 20).toFixed(2)} MB of text`);
console.log(`wasm memory ${first.wasm_MB} → ${end.wasm_MB} MB; JS heap ${first.js_heap_MB} → ${end.js_heap_MB} MB; `
  + `IndexedDB ${first.idb_MB} → ${end.idb_MB} MB; draw ${first.draw_ms} → ${end.draw_ms} ms (${(end.draw_ms / first.draw_ms).toFixed(2)}×); wall ${end.wall_s} s`);
console.log(`page errors: ${errors.length ? errors.join(' | ') : 'none'}`);
await browser.close();
