// End-to-end tests of upload mode in headless Chromium: files of every format through the web
// worker, the plots, hovering, a corrupt file beside a good one, exports, the shared data sets
// against `pdr eval`, and a one-hour log's load time (printed).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, readdirSync, writeFileSync, statSync } from 'node:fs';
import { constants as zlibConstants, deflateRawSync } from 'node:zlib';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { ARTIFACTS, BIN, URL_HTTP, openPage, useBrowser, tempDir } from './util.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const FIXTURES = path.join(here, '../fixtures/import');
const SHARED = path.join(here, '../../../shared/data');
const tmp = tempDir('upload');

const browser = useBrowser();

function open(viewport = { width: 1100, height: 900 }, device = {}) {
  return openPage(browser(), URL_HTTP, { options: { viewport, acceptDownloads: true, ...device } });
}

/** Uploads files (or a folder) and waits until every analysis is in. */
async function upload(page, paths, { folder = false, timeout = 60_000 } = {}) {
  await page.setInputFiles(folder ? '#upload-folder' : '#upload-files', paths);
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done', null, { timeout });
  return page.evaluate(() => ({ logs: window.__pdrTest.upload.logs, errors: window.__pdrTest.upload.errors, progress: window.__pdrTest.upload.progress_seen, ms: window.__pdrTest.upload.done_ms }));
}

/** `pdr run`'s step count and distance for a file or folder, with extra options. */
function native(p, ...args) {
  const out = execFileSync(BIN, ['run', p, ...args], { encoding: 'utf8' });
  return { steps: Number(out.match(/^steps\s+(\d+)/m)[1]), distance: Number(out.match(/^distance\s+([\d.]+) m/m)[1]) };
}
const nativeSteps = (p) => native(p).steps;

/** The files under `dir`, as [relative path, bytes]. */
function filesUnder(dir, prefix = '') {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) => (e.isDirectory()
    ? filesUnder(path.join(dir, e.name), `${prefix}${e.name}/`)
    : [[`${prefix}${e.name}`, readFileSync(path.join(dir, e.name))]]));
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

/**
 * A zip archive (deflated, as phones write them) of [name, bytes] entries. An entry may instead
 * be [name, { deflated, size, crc }]: data already deflated, with the size and CRC its headers
 * state.
 */
function zip(entries) {
  const parts = [];
  const central = [];
  let offset = 0;
  const dosDate = ((2026 - 1980) << 9) | (11 << 5) | 23;
  for (const [name, entry] of entries) {
    const n = Buffer.from(name);
    const raw = entry.deflated ? entry : null;
    const data = raw ? { length: raw.size } : entry;
    const z = raw ? raw.deflated : deflateRawSync(data);
    const crc = raw ? raw.crc : crc32(data);
    const head = Buffer.alloc(30);
    head.writeUInt32LE(0x04034b50, 0);
    [20, 0, 8, 0, dosDate].forEach((v, i) => head.writeUInt16LE(v, 4 + 2 * i));
    head.writeUInt32LE(crc, 14);
    head.writeUInt32LE(z.length, 18);
    head.writeUInt32LE(data.length, 22);
    head.writeUInt16LE(n.length, 26);
    const c = Buffer.alloc(46);
    c.writeUInt32LE(0x02014b50, 0);
    [20, 20, 0, 8, 0, dosDate].forEach((v, i) => c.writeUInt16LE(v, 4 + 2 * i));
    c.writeUInt32LE(crc, 16);
    c.writeUInt32LE(z.length, 20);
    c.writeUInt32LE(data.length, 24);
    c.writeUInt16LE(n.length, 28);
    c.writeUInt32LE(offset, 42);
    parts.push(head, n, z);
    central.push(c, n);
    offset += head.length + n.length + z.length;
  }
  const cd = Buffer.concat(central);
  const end = Buffer.alloc(22);
  end.writeUInt32LE(0x06054b50, 0);
  end.writeUInt16LE(Math.min(entries.length, 0xffff), 8);
  end.writeUInt16LE(Math.min(entries.length, 0xffff), 10);
  end.writeUInt32LE(cd.length, 12);
  end.writeUInt32LE(offset, 16);
  if (entries.length < 0xffff) return Buffer.concat([...parts, cd, end]);
  // More entries than 16 bits count: the zip64 end record and its locator (APPNOTE 4.3.14-15).
  const end64 = Buffer.alloc(56 + 20);
  end64.writeUInt32LE(0x06064b50, 0);
  end64.writeBigUInt64LE(44n, 4);
  end64.writeUInt16LE(45, 12);
  end64.writeUInt16LE(45, 14);
  end64.writeBigUInt64LE(BigInt(entries.length), 24);
  end64.writeBigUInt64LE(BigInt(entries.length), 32);
  end64.writeBigUInt64LE(BigInt(cd.length), 40);
  end64.writeBigUInt64LE(BigInt(offset), 48);
  end64.writeUInt32LE(0x07064b50, 56);
  end64.writeBigUInt64LE(BigInt(offset + cd.length), 64);
  end64.writeUInt32LE(1, 72);
  return Buffer.concat([...parts, cd, end64, end]);
}

/** The one-hour 100 Hz walk (pdr-log), written once for the tests that need a long load. */
let hourLog = null;
function hour() {
  if (!hourLog) {
    hourLog = path.join(tmp, 'hour.pdrlog');
    execFileSync(BIN, ['simulate', '--scenario', 'long', '--minutes', '60', '--out', hourLog]);
  }
  return hourLog;
}

/** Non-background pixels of every canvas of result `k`. */
async function canvases(page, k) {
  return page.evaluate((k) => [...document.querySelectorAll(`.log-result[data-index="${k}"] canvas`)].map((c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 30) n++;
    return { what: c.getAttribute('aria-label'), n, total: d.length / 4 };
  }), k);
}

/** Writes the demo walk (or `scenario`) in `format` (`pdr simulate --format`) under `tmp`. */
function simulated(format, scenario = 'demo') {
  const out = path.join(tmp, `${scenario}-${format}${['sensor-logger', 'sensor-logger-ios', 'phyphox', 'oxford'].includes(format) ? '' : '.log'}`);
  if (!existsSync(out)) execFileSync(BIN, ['simulate', '--scenario', scenario, '--format', format, '--out', out]);
  return out;
}

/** Hovers step `i` of result `k` on its map; returns the step line and the step picked. */
async function hover(page, k, i) {
  await page.locator(`.log-result[data-index="${k}"] canvas.map`).scrollIntoViewIfNeeded();
  const [x, y] = await page.evaluate(([k, i]) => window.__pdrTest.upload.stepPixel(k, i), [k, i]);
  await page.mouse.move(x, y);
  await page.waitForFunction((k) => document.querySelector(`.log-result[data-index="${k}"] .stepinfo`).dataset.step, k);
  const picked = Number(await page.getAttribute(`.log-result[data-index="${k}"] .stepinfo`, 'data-step'));
  // Where the walk crosses itself another step may lie under the pointer: it must be that close.
  const [px, py] = await page.evaluate(([k, i]) => window.__pdrTest.upload.stepPixel(k, i), [k, picked]);
  assert.ok(Math.hypot(px - x, py - y) <= 12, `hovered step ${i} at (${x}, ${y}), picked ${picked} at (${px}, ${py})`);
  return { info: await page.textContent(`.log-result[data-index="${k}"] .stepinfo`), picked };
}

/** Every plot of result `k` is drawn, and hovering its middle step shows that step's values. */
async function checkResult(page, k, steps, { heading = true } = {}) {
  for (const c of await canvases(page, k)) assert.ok(c.n > 0.01 * c.total, `log ${k}: ${c.what} looks blank: ${c.n} of ${c.total}`);
  const { info } = await hover(page, k, Math.floor(steps / 2));
  // A log with an accelerometer only (Oxford) has steps and lengths but no heading.
  const h = heading ? '\\d+°' : '–';
  assert.match(info, new RegExp(`^Step \\d+: t = [\\d.]+ s · length \\d\\.\\d\\d m · frequency \\d\\.\\d\\d Hz · heading ${h} \\(single step ${h}\\) · (walking|running|still|standing|sitting|walking upstairs|walking downstairs)( · height -?\\d+\\.\\d\\d m, floor (0|\\+\\d+|\u2212\\d+))?$`));
}

test('a generated log and a walk in every single-file format: progress, the native step count, non-blank plots, hover', async () => {
  const city = path.join(tmp, 'city.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--out', city]);
  // The demo walk (3.5 min, 362 steps) as each app writes it, plus the fixtures' damaged lines.
  const files = [city, ...['pdr-log', 'sensor-logger-json', 'gnss-logger', 'get-sensor-data', 'ms-indoor', 'xio'].map((f) => simulated(f)),
    ...['get_sensor_data.txt', 'gnss_logger.txt', 'sensor_logger.json'].map((f) => path.join(FIXTURES, f))];
  const { context, page, errors } = await open();
  const r = await upload(page, files);
  assert.ok(r.progress, 'no progress was shown');
  assert.equal(await page.evaluate(() => window.__pdrTest.upload.progress_max), 1, 'the progress bar did not complete');
  assert.match(await page.textContent('#upload-status'), new RegExp(`^${files.length} recordings loaded from [\\d.]+ MB in [\\d.]+ s$`));
  assert.deepEqual(r.errors, []);
  assert.equal(r.logs.length, files.length);
  console.log(`uploaded ${files.length} files: ${r.logs.map((l) => `${l.a.source} ${l.a.format} ${l.a.steps} steps`).join('; ')}`);
  const formats = new Set();
  for (const [k, l] of r.logs.entries()) {
    const file = files.find((f) => path.basename(f) === l.a.source);
    assert.equal(l.a.steps, nativeSteps(file), `${l.a.source}: steps differ from pdr run`);
    if (!file.startsWith(FIXTURES)) {
      assert.ok(l.a.steps > 300, `${l.a.source}: only ${l.a.steps} steps`);
      formats.add(l.a.format);
      await checkResult(page, k, l.a.steps);
    }
  }
  assert.deepEqual([...formats].sort(), ['get-sensor-data', 'gnss-logger', 'ms-indoor', 'pdr-log', 'sensor-logger-json', 'xio-foot']);
  // The truth the formats carry is scored beside the track.
  const summary = (name) => page.textContent(`.log-result:has(h3:text-is("${name}")) .summary`);
  assert.match(await summary('demo-ms-indoor.log'), /Waypointserror p75 [\d.]+ m, max [\d.]+ m over 22 waypoints/);
  assert.match(await summary('demo-get-sensor-data.log'), /Waypointserror p75 [\d.]+ m, max [\d.]+ m over 22 waypoints/);
  const k = r.logs.findIndex((l) => l.a.source === 'city.pdrlog');
  const { picked } = await hover(page, k, 500);
  assert.ok(Math.abs(picked - 500) <= 3, `hovered step ${picked}, expected about 500`);
  assert.deepEqual(errors, []);
  await page.locator(`.log-result[data-index="${k}"]`).screenshot({ path: path.join(ARTIFACTS, 'upload-desktop.png') });
  await context.close();
});

test('stairs in a pocket (Munoz Diaz 2015): the height plot, the floors on the map and in the figures, the native step count and landmark floors', async () => {
  // The simulated pocket walk up and down three floors, with a barometer, as GetSensorData
  // writes it (PRES readings, POSI landmarks with their floors).
  const file = simulated('get-sensor-data', 'stairs');
  const { context, page, errors } = await open();
  const r = await upload(page, [file]);
  assert.deepEqual(r.errors, []);
  const l = r.logs[0];
  assert.equal(l.a.steps, nativeSteps(file), 'steps differ from pdr run');
  for (const c of await canvases(page, 0)) assert.ok(c.n > 0.01 * c.total, `${c.what} looks blank`);
  const figures = await page.textContent('.log-result[data-index="0"] .summary');
  // Four floors visited (0 to +3), the height from the leg pitch and the barometer, the
  // landmarks' floors scored.
  assert.match(figures, /Height[^]*4 floors visited \(0, \+1, \+2, \+3\); from leg pitch \+ barometer/);
  assert.match(figures, /Barometer\s*\d+ readings/);
  assert.match(figures, /Carried\s*in a pocket \d+ %/, 'where the phone was carried');
  const [, right, of] = figures.match(/Floors\s*(\d+) of (\d+) landmarks on the right relative floor/);
  // `pdr eval` gives 14 of 16: the simulator drops a landmark every 10 s, and two fall on the
  // landings half-way between floors, where the floor is a matter of definition (the truth
  // counts a floor once it is reached, the engine once 60 % of the way to the next).
  assert.ok(Number(of) >= 15 && Number(right) >= Number(of) - 2, `${right} of ${of} landmarks on the right floor`);
  // The height plot is there, and a step on the stairs says so.
  assert.ok(await page.locator('.log-result[data-index="0"] canvas[aria-label^="Height above the start"]').count() >= 1);
  const mid = Math.floor(l.a.steps * 0.14);
  const { info } = await hover(page, 0, mid);
  assert.match(info, / · (walking|walking upstairs|walking downstairs) · height -?\d+\.\d\d m, floor (0|\+\d)$/);
  assert.deepEqual(errors, []);
  await page.locator('.log-result[data-index="0"]').screenshot({ path: path.join(ARTIFACTS, 'upload-stairs.png') });
  await context.close();
});

test('phone: tapping a plot picks the step at that time, a pinch zooms the time axis, the fusion plots', async () => {
  const walk = path.join(tmp, 'city-phone.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--out', walk]);
  const { context, page, errors } = await open({ width: 390, height: 844 }, { hasTouch: true, isMobile: true, deviceScaleFactor: 3 });
  await upload(page, [walk]);
  for (const c of await canvases(page, 0)) assert.ok(c.n > 0.01 * c.total, `${c.what} looks blank: ${c.n} of ${c.total}`);
  // The plots are stacked on one time axis: it spans the same pixels on each.
  const axes = await page.evaluate(() => [...document.querySelectorAll('canvas.plot')].map((c) => c.axis.map((x) => x.toFixed(1)).join('..')));
  assert.equal(new Set(axes).size, 1, `time axes differ: ${axes}`);
  // A tap on the time of step 200 picks step 200.
  await page.locator('canvas.plot-accel').scrollIntoViewIfNeeded();
  const [x, y] = await page.evaluate(() => window.__pdrTest.upload.plotPoint(0, 'accel', window.__pdrTest.upload.stepTime(0, 200)));
  await page.touchscreen.tap(x, y);
  await page.waitForFunction(() => document.querySelector('.log-result .stepinfo').dataset.step);
  const picked = Number(await page.getAttribute('.log-result .stepinfo', 'data-step'));
  assert.ok(Math.abs(picked - 200) <= 1, `tapped step ${picked}, expected 200`);
  // Two fingers moving apart on the step plot: the span shrinks by about their distance ratio.
  await page.locator('canvas.plot-steps').scrollIntoViewIfNeeded();
  const box = await page.locator('canvas.plot-steps').boundingBox();
  const before = await page.evaluate(() => window.__pdrTest.upload.span(0));
  const cdp = await context.newCDPSession(page);
  const cy = box.y + box.height / 2;
  const cx = box.x + box.width / 2;
  const touch = (type, d) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: type === 'touchEnd' ? [] : [{ x: cx - d, y: cy, id: 1 }, { x: cx + d, y: cy, id: 2 }],
  });
  await touch('touchStart', 40);
  for (let d = 45; d <= 120; d += 5) await touch('touchMove', d);
  await touch('touchEnd', 0);
  const after = await page.evaluate(() => window.__pdrTest.upload.span(0));
  const ratio = (after[1] - after[0]) / (before[1] - before[0]);
  console.log(`pinch 80 → 240 px: time span ${(before[1] - before[0]).toFixed(0)} s → ${(after[1] - after[0]).toFixed(0)} s`);
  assert.ok(ratio > 0.2 && ratio < 0.5, `span ratio ${ratio}`);
  assert.deepEqual(errors, []);
  await page.locator('canvas.plot-gnss').scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(ARTIFACTS, 'upload-plots-phone.png') });
  await context.close();
});

test('the fusion: corrections ± 1σ, what the fixes did and the verdict in the figures, its plot with bands, at 390 and 1100 px', async () => {
  const walk = path.join(tmp, 'city-fusion.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--out', walk]);
  for (const [width, name] of [[390, 'phone'], [1100, 'desktop']]) {
    const { context, page, errors } = await open({ width, height: 900 }, width < 500 ? { hasTouch: true, isMobile: true, deviceScaleFactor: 3 } : {});
    await upload(page, [walk]);
    const figures = await page.textContent('.log-result[data-index="0"] .summary');
    // The filter's numbers change with its tuning: the words and their format, not the values.
    assert.match(figures, /Correctionsstep-length scale \d\.\d\d ± \d\.\d\d · heading correction −?\d+\.\d° ± \d+\.\d°/);
    assert.match(figures, /GNSS\d+ fixes: \d+ used(, \d+ [a-z ]+)*/);
    assert.match(figures, /Fusion(GNSS: step length and heading known|GNSS: learning your step length and heading|GNSS disagrees with your steps: using steps|Waiting for GNSS)/);
    // Each figure fits its card: nothing wider than the page.
    const overflow = await page.evaluate(() => [...document.querySelectorAll('.log-result .summary *')]
      .filter((e) => e.getBoundingClientRect().right > document.documentElement.clientWidth + 1).map((e) => e.textContent));
    assert.deepEqual(overflow, [], `wider than the page at ${width} px`);
    assert.deepEqual(errors, []);
    await page.locator('.log-result[data-index="0"] .summary').screenshot({ path: path.join(ARTIFACTS, `upload-fusion-figures-${name}.png`) });
    await page.locator('.log-result[data-index="0"] canvas.plot-fusion').scrollIntoViewIfNeeded();
    await page.locator('.log-result[data-index="0"] canvas.plot-fusion').screenshot({ path: path.join(ARTIFACTS, `upload-fusion-plot-${name}.png`) });
    await context.close();
  }
});

test('folders: the demo walk as Sensor Logger (Android and iOS), phyphox and Oxford folders, and the fixtures', async () => {
  const { context, page, errors } = await open();
  for (const format of ['sensor-logger', 'sensor-logger-ios', 'phyphox', 'oxford']) {
    const dir = simulated(format);
    const r = await upload(page, dir, { folder: true });
    assert.deepEqual(r.errors, [], format);
    assert.equal(r.logs.length, 1, `${format}: ${r.logs.length} logs`);
    assert.equal(r.logs[0].a.steps, nativeSteps(dir), format);
    assert.ok(r.logs[0].a.steps > 300, `${format}: only ${r.logs[0].a.steps} steps`);
    await checkResult(page, 0, r.logs[0].a.steps, { heading: format !== 'oxford' });
    console.log(`${format} folder: ${r.logs[0].a.source} ${r.logs[0].a.format} ${r.logs[0].a.steps} steps`);
    if (format === 'oxford') {
      // The true steps (foot contacts) are scored: the same error as pdr eval.
      const e = JSON.parse(execFileSync(BIN, ['eval', '--json', dir], { encoding: 'utf8' })).logs[0];
      assert.equal(r.logs[0].a.score.truth_steps, e.truth_steps);
      assert.match(await page.textContent('.log-result .summary'), new RegExp(`\\(true ${e.truth_steps}, error ${e.step_error_pct.toFixed(1)} %`));
      // An accelerometer only: no heading, said on the map, the heading plot and the figures.
      assert.match(await page.textContent('.log-result .summary'), /No heading\d+ of \d+ steps \([\d.]+ m of steps in all\): the log has no gyroscope/);
      await page.locator('.log-result').screenshot({ path: path.join(ARTIFACTS, 'upload-oxford-desktop.png') });
    }
  }
  for (const dir of ['sensor_logger_android', 'sensor_logger_ios', 'phyphox', 'phyphox_semicolon', 'oxford/Pixel_Test_Hard_FrontPocket_1']) {
    const r = await upload(page, path.join(FIXTURES, dir), { folder: true });
    assert.deepEqual(r.errors, [], dir);
    assert.equal(r.logs.length, 1, `${dir}: ${r.logs.length} logs`);
    assert.equal(r.logs[0].a.steps, nativeSteps(path.join(FIXTURES, dir)), dir);
  }
  assert.deepEqual(errors, []);
  await context.close();
});

test('a corrupt file beside a good one: the banner names the file and line, the good one loads', async () => {
  const bad = path.join(tmp, 'broken.json');
  const json = readFileSync(path.join(FIXTURES, 'sensor_logger.json'), 'utf8');
  // Damaged inside its first record: nothing can be read from it (a file damaged later keeps
  // what comes before the damage, with a warning).
  writeFileSync(bad, `${json.slice(0, json.indexOf('"sensor"') + 9)}@@@${json.slice(json.indexOf('"sensor"') + 9)}`);
  const { context, page } = await open();
  const r = await upload(page, [bad, path.join(FIXTURES, 'ms_indoor.txt')]);
  assert.equal(r.logs.length, 1);
  assert.equal(r.logs[0].a.source, 'ms_indoor.txt');
  const banner = await page.textContent('#upload-banners li.error');
  console.log(`banner: ${banner}`);
  assert.match(banner, /^broken\.json:[1-9]\d*:\d+: /);
  await context.close();
});

test('hostile archives through the worker: a deep nest, 2 GiB of zeros (honest and lying headers), 100 000 entries; each refused by name, the good file loads', async () => {
  const walk = readFileSync(path.join(FIXTURES, 'walk.pdrlog'));
  let nest = zip([['walk.pdrlog', walk]]);
  for (let level = 9; level >= 1; level--) nest = zip([[`level${level}.zip`, nest]]);
  // 2 GiB of zeros behind a pdr-log header, deflated fast: a MiB with a full flush, repeated.
  const head = deflateRawSync(Buffer.from('# pdr-log 1\n'), { finishFlush: zlibConstants.Z_FULL_FLUSH });
  const mib = deflateRawSync(Buffer.alloc(1 << 20), { finishFlush: zlibConstants.Z_FULL_FLUSH });
  const zeros = Buffer.concat([head, ...Array(2048).fill(mib), Buffer.from([0x03, 0x00])]);
  // The CRC is never reached: the limits stop the reading first.
  const honest = zip([['x.pdrlog', { deflated: zeros, size: 2 ** 31, crc: 0 }]]);
  const liar = zip([['x.pdrlog', { deflated: zeros, size: 10 << 20, crc: 0 }]]);
  const many = zip(Array.from({ length: 100_000 }, (_, i) => [`e${i}`, Buffer.alloc(0)]));
  const files = { 'nest.zip': nest, 'honest.zip': honest, 'liar.zip': liar, 'many.zip': many };
  for (const [name, bytes] of Object.entries(files)) writeFileSync(path.join(tmp, name), bytes);
  const { context, page, errors } = await open();
  const r = await upload(page, [...Object.keys(files).map((f) => path.join(tmp, f)), path.join(FIXTURES, 'walk.pdrlog')]);
  assert.deepEqual(r.logs.map((l) => l.a.source), ['walk.pdrlog']);
  const byFile = Object.fromEntries(r.errors.map((e) => [e.file, e.message]));
  console.log(r.errors.map((e) => `${e.file}: ${e.message}`).join('\n'));
  assert.match(byFile['nest.zip/level1.zip/level2.zip'], /archive limit `depth`/);
  assert.match(byFile['honest.zip/x.pdrlog'], /archive limit `ratio`/);
  assert.match(byFile['liar.zip/x.pdrlog'], /archive limit `declared size`/);
  assert.match(byFile['many.zip'], /archive limit `entries`/);
  assert.equal(r.errors.length, 4);
  // The worker's wasm memory never shrinks: its size after the analysis bounds the parse's peak.
  console.log(`worker wasm memory after the hostile archives: ${r.logs[0].memory_mb.toFixed(1)} MB`);
  assert.ok(r.logs[0].memory_mb < 128, `${r.logs[0].memory_mb} MB`);
  const banners = await page.textContent('#upload-banners');
  for (const f of ['nest.zip/level1.zip/level2.zip', 'honest.zip/x.pdrlog', 'liar.zip/x.pdrlog', 'many.zip']) assert.ok(banners.includes(f), `${f} in the banners`);
  assert.deepEqual(errors, []);
  await context.close();
});

test('drag and drop: files and a zip dropped together load like the picker', async () => {
  const walk = path.join(tmp, 'dropped.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'demo', '--out', walk]);
  const folder = simulated('sensor-logger');
  const archive = path.join(tmp, 'Recording.zip');
  writeFileSync(archive, zip(filesUnder(folder)));
  const { context, page, errors } = await open();
  const files = [walk, archive].map((f) => ({ name: path.basename(f), b64: readFileSync(f).toString('base64') }));
  const dt = await page.evaluateHandle((files) => {
    const dt = new DataTransfer();
    for (const f of files) dt.items.add(new File([Uint8Array.from(atob(f.b64), (c) => c.charCodeAt(0))], f.name));
    return dt;
  }, files);
  await page.dispatchEvent('#drop', 'dragover', { dataTransfer: dt });
  assert.ok(await page.$eval('#drop', (d) => d.classList.contains('over')), 'the drop zone does not show the drag');
  await page.dispatchEvent('#drop', 'drop', { dataTransfer: dt });
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done' && window.__pdrTest?.upload?.logs.length === 2);
  const logs = await page.evaluate(() => window.__pdrTest.upload.logs.map((l) => ({ source: l.a.source, format: l.a.format, steps: l.a.steps })));
  logs.sort((x, y) => (x.source < y.source ? 1 : -1));
  console.log(`dropped: ${logs.map((l) => `${l.source} (${l.format}) ${l.steps} steps`).join('; ')}`);
  assert.deepEqual(logs.map((l) => l.source), ['dropped.pdrlog', 'Recording.zip/2026-01-01_00-00-00']);
  assert.ok(logs[1].steps > 300, `the zip gave ${logs[1].steps} steps`);
  assert.equal(logs[0].steps, nativeSteps(walk));
  assert.equal(logs[1].steps, nativeSteps(archive));
  assert.equal(logs[1].steps, nativeSteps(folder), 'the zip reads differently from its folder');
  assert.deepEqual(errors, []);
  await context.close();
});

test('cancel: a one-hour log stops loading at once, and the next upload works', async () => {
  const { context, page, errors } = await open();
  await page.setInputFiles('#upload-files', [hour()]);
  await page.waitForFunction(() => /^parsed /.test(document.getElementById('upload-status').textContent));
  await page.click('#upload-cancel');
  assert.equal(await page.evaluate(() => document.documentElement.dataset.upload), 'done');
  assert.equal(await page.textContent('#upload-status'), 'Cancelled.');
  assert.match(await page.textContent('#upload-banners li.warn'), /^Cancelled/);
  assert.ok(await page.isHidden('#upload-cancel'));
  // Nothing arrives from the stopped worker.
  await page.waitForTimeout(2500);
  assert.equal(await page.evaluate(() => window.__pdrTest.upload.logs.filter(Boolean).length), 0);
  assert.equal(await page.locator('.log-result[data-ready]').count(), 0);
  const r = await upload(page, [path.join(FIXTURES, 'ms_indoor.txt')]);
  assert.equal(r.logs.length, 1);
  assert.equal(r.logs[0].a.steps, nativeSteps(path.join(FIXTURES, 'ms_indoor.txt')));
  assert.match(await page.textContent('#upload-status'), /^1 recording loaded from 114 kB in \d+\.\d s$/);
  assert.equal(await page.evaluate(() => document.getElementById('upload-bar').value), 1);
  assert.deepEqual(errors, []);
  await context.close();
});

test('exports: GPX and GeoJSON parse back with a point per step; CSV, pdr-log and PNG download', async () => {
  const walk = path.join(tmp, 'demo.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'demo', '--out', walk]);
  const { context, page } = await open();
  const r = await upload(page, [walk]);
  const steps = r.logs[0].a.steps;
  const get = async (what) => {
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click(`.log-result[data-index="0"] [data-export="${what}"]`)]);
    const file = path.join(tmp, dl.suggestedFilename());
    await dl.saveAs(file);
    return file;
  };
  const geo = JSON.parse(readFileSync(await get('geojson'), 'utf8'));
  assert.equal(geo.features[0].geometry.coordinates.length, steps);
  assert.equal(geo.features[0].properties.coordinates, 'local_enu_metres');
  const gpx = readFileSync(await get('gpx'), 'utf8');
  assert.equal((gpx.match(/<trkpt /g) ?? []).length, steps);
  assert.match(gpx, /<gpx version="1.1"/);
  const csv = readFileSync(await get('csv'), 'utf8').trim().split('\n');
  assert.equal(csv.length, steps + 1);
  const log = await get('pdrlog');
  assert.equal(nativeSteps(log), steps, 'the exported pdr-log replays to another count');
  const png = readFileSync(await get('png'));
  assert.deepEqual([...png.subarray(1, 4)].map((c) => String.fromCharCode(c)).join(''), 'PNG');
  // A log with fixes: the same exports in WGS84, about the first fix (Florence, 43.77° N 11.26° E).
  const city = path.join(tmp, 'exports-city.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--out', city]);
  const [lat0, lon0] = readFileSync(city, 'utf8').match(/^gnss,[^,]+,([^,]+),([^,]+)/m).slice(1).map(Number);
  const rc = await upload(page, [city]);
  const n = rc.logs[0].a.steps;
  const near = ([lon, lat]) => Math.abs(lat - lat0) < 0.01 && Math.abs(lon - lon0) < 0.01;
  const geoCity = JSON.parse(readFileSync(await get('geojson'), 'utf8'));
  assert.equal(geoCity.features[0].properties.coordinates, 'wgs84');
  assert.equal(geoCity.features[0].geometry.coordinates.length, n);
  assert.ok(geoCity.features[0].geometry.coordinates.every(near), 'GeoJSON points are not about the first fix');
  const pts = [...readFileSync(await get('gpx'), 'utf8').matchAll(/<trkpt lat="([-\d.]+)" lon="([-\d.]+)"/g)].map((m) => [Number(m[2]), Number(m[1])]);
  assert.equal(pts.length, n);
  assert.ok(pts.every(near), 'GPX points are not about the first fix');
  await context.close();
});

test('compare two configurations side by side, and re-run', async () => {
  const walk = path.join(tmp, 'demo2.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'demo', '--out', walk]);
  const { context, page, errors } = await open({ width: 390, height: 844 });
  await page.check('#compare');
  // B: the peak counter, the closed form and Weinberg's step length, whose K no profile sets.
  await page.selectOption('.config[data-config="b"] [name="step_length.kind"]', 'weinberg');
  assert.ok(await page.isDisabled('.config[data-config="b"] [name=profile]'), 'a profile offered to Weinberg');
  const r = await upload(page, [walk]);
  const { a, b } = r.logs[0];
  assert.ok(a && b, 'both configurations ran');
  const nb = native(walk, '--detector', 'peak', '--heading', 'closed_form2021', '--step-length', 'weinberg');
  assert.equal(b.steps, nb.steps, 'configuration B (peak, closed form, Weinberg) differs from pdr run');
  assert.equal(Number(b.score.distance_m.toFixed(1)), nb.distance, 'B distance differs from pdr run');
  assert.notEqual(Number(a.score.distance_m.toFixed(1)), nb.distance, 'A has B\'s distance');
  assert.equal(await page.locator('.log-result .mapbox').count(), 2);
  // Each map is named with the configuration it ran with, its figures under it.
  const labels = await page.locator('.log-result .mapbox .config-label').allTextContents();
  assert.deepEqual(labels, [
    'A: PLL (Basso 2016), tip-to-tail (2016), built-in step-length line, GNSS: every fix',
    'B: peak counter, closed form (2021), Weinberg step length (K = 0.47), GNSS: every fix',
  ]);
  const figures = await page.locator('.log-result .mapbox .summary').allTextContents();
  assert.match(figures[1], new RegExp(`Steps${nb.steps}Distance${nb.distance.toFixed(1)} m`));
  await page.locator('.log-result').screenshot({ path: path.join(ARTIFACTS, 'upload-compare-phone.png') });
  // Re-run A with the peak detector: its count becomes B's.
  await page.selectOption('.config[data-config="a"] [name="detector.kind"]', 'peak');
  await page.selectOption('.config[data-config="a"] [name="heading.method"]', 'closed_form2021');
  await page.click('#rerun');
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done' && window.__pdrTest.upload.logs[0].a.steps !== undefined);
  const peak = native(walk, '--detector', 'peak', '--heading', 'closed_form2021').steps;
  await page.waitForFunction((n) => window.__pdrTest.upload.logs[0].a.steps === n, peak, { timeout: 20_000 });
  assert.match(await page.locator('.log-result .mapbox .config-label').first().textContent(), /^A: peak counter, closed form \(2021\), /);
  assert.deepEqual(errors, []);
  await context.close();
});

test('shared data sets: an Oxford, a Microsoft, an x-io foot, a TyrEx and a UbiComp trace show the errors `pdr eval` gives', { skip: !existsSync(SHARED) && `${SHARED} is absent` }, async () => {
  const oxRoot = path.join(SHARED, 'oxford-steps');
  const msRoot = path.join(SHARED, 'ms-indoor');
  const findDir = (root, test) => {
    for (const e of readdirSync(root, { recursive: true })) {
      const p = path.join(root, e);
      if (test(p)) return p;
    }
    return null;
  };
  const ox = findDir(oxRoot, (p) => statSync(p).isDirectory() && existsSync(path.join(p, 'stepcounter.csv')));
  const ms = findDir(msRoot, (p) => p.endsWith('.txt') && statSync(p).isFile() && statSync(p).size > 100_000);
  assert.ok(ox && ms, 'no Oxford or Microsoft trace found');
  const evalOf = (p) => JSON.parse(execFileSync(BIN, ['eval', '--json', p], { encoding: 'utf8', maxBuffer: 1 << 26 })).logs[0];
  const { context, page } = await open();
  const r1 = await upload(page, ox, { folder: true });
  const e1 = evalOf(ox);
  const s1 = r1.logs[0].a.score;
  console.log(`Oxford ${path.basename(ox)}: ${s1.steps} steps, error ${s1.step_error_pct?.toFixed(2)} % (pdr eval ${e1.step_error_pct?.toFixed(2)} %)`);
  assert.equal(s1.steps, e1.steps);
  assert.equal(s1.step_error_pct, e1.step_error_pct);
  assert.match(await page.textContent('.log-result .summary'), new RegExp(`error ${e1.step_error_pct.toFixed(1)} %`));
  const r2 = await upload(page, [ms]);
  const e2 = evalOf(ms);
  const s2 = r2.logs[0].a.score;
  console.log(`Microsoft ${path.basename(ms)}: waypoint p75 ${s2.waypoint_error_m?.p75.toFixed(2)} m (pdr eval ${e2.waypoint_error_m?.p75.toFixed(2)} m)`);
  assert.equal(s2.waypoint_error_m.p75, e2.waypoint_error_m.p75);
  assert.match(await page.textContent('.log-result .summary'), new RegExp(`error p75 ${e2.waypoint_error_m.p75.toFixed(1)} m`));
  await page.locator('.log-result').screenshot({ path: path.join(ARTIFACTS, 'upload-ms-desktop.png') });
  // A shoe-mounted x-io walk: recognised as a foot, its strides and loop closure as `pdr eval`.
  const xio = path.join(SHARED, 'xio-foot', 'long_walk.csv');
  const r3 = await upload(page, [xio]);
  const e3 = evalOf(xio);
  const s3 = r3.logs[0].a.score;
  console.log(`x-io ${path.basename(xio)}: ${s3.strides} strides, loop closure ${s3.loop_closure_m?.toFixed(3)} m (pdr eval ${e3.strides} strides, ${e3.loop_closure_m?.toFixed(3)} m)`);
  assert.equal(e3.placement, 'foot');
  assert.equal(s3.strides, e3.strides);
  assert.equal(s3.loop_closure_m, e3.loop_closure_m);
  assert.match(await page.textContent('.log-result .summary'), /Strides/);
  await page.locator('.log-result').screenshot({ path: path.join(ARTIFACTS, 'upload-xio-foot-desktop.png') });
  // A TyrEx walk, phone in a front pocket, its gyroscope late: a track, scored against the
  // motion capture as `pdr eval` scores it, the truth drawn on the map.
  const tyrex = path.join(SHARED, 'tyrex-pocket', 'Guillaume_iPhone5_NoDist_BackPocket');
  if (existsSync(tyrex)) {
    const r4 = await upload(page, tyrex, { folder: true });
    const e4 = evalOf(tyrex);
    const s4 = r4.logs[0].a.score;
    console.log(`TyrEx ${path.basename(tyrex)}: heading error ${s4.trajectory?.heading_error_deg?.toFixed(1)}° (pdr eval ${e4.trajectory?.heading_error_deg?.toFixed(1)}°), distance ratio ${s4.trajectory?.distance_ratio?.toFixed(2)}`);
    assert.ok(s4.trajectory.has_track);
    assert.deepEqual(s4.trajectory, e4.trajectory);
    assert.ok(r4.logs[0].a.truth_waypoints > 100, 'the truth is drawn');
    await page.locator('.log-result').screenshot({ path: path.join(ARTIFACTS, 'upload-tyrex-desktop.png') });
  }
  // A UbiComp 2013 walk: the steps inside its counted window, as `pdr eval` counts them.
  const ubiRoot = path.join(SHARED, 'ubicomp13-pocket');
  const ubi = existsSync(ubiRoot) && findDir(ubiRoot, (p) => existsSync(path.join(p, 'truth.json')));
  if (ubi) {
    const r5 = await upload(page, ubi, { folder: true });
    const e5 = evalOf(ubi);
    const s5 = r5.logs[0].a.score;
    assert.equal(s5.steps_in_window, e5.steps_in_window);
    assert.equal(s5.step_error_pct, e5.step_error_pct);
  }
  await context.close();
});

/** Resident memory (now) and its peak (VmHWM) of every Chromium process, MB, from /proc. */
async function processMemory() {
  const cdp = await browser().newBrowserCDPSession();
  const { processInfo } = await cdp.send('SystemInfo.getProcessInfo');
  await cdp.detach();
  const out = [];
  for (const p of processInfo) {
    if (!existsSync(`/proc/${p.id}/status`)) continue;
    const st = readFileSync(`/proc/${p.id}/status`, 'utf8');
    const kb = (k) => Number(st.match(new RegExp(`^${k}:\\s+(\\d+) kB`, 'm'))?.[1] ?? 0);
    out.push({ pid: p.id, type: p.type, rss: kb('VmRSS') / 1e3, peak: kb('VmHWM') / 1e3 });
  }
  return out;
}

/** How much an upload added at its peak: per process, the peak after less the resident
 * memory before, for the page's renderer (which runs the worker too) and for all processes. */
function memoryGrowth(before, after) {
  const grow = after.map((a) => ({ ...a, grow: a.peak - (before.find((b) => b.pid === a.pid)?.rss ?? 0) }));
  return {
    renderer: Math.max(...grow.filter((g) => g.type === 'renderer').map((g) => g.grow)),
    all: grow.reduce((s, g) => s + Math.max(0, g.grow), 0),
  };
}

test('benchmark: a one-hour 100 Hz pdr-log, parse + engine + first draw (printed, not asserted)', async () => {
  const hourFile = hour();
  const mb = statSync(hourFile).size / 1e6;
  const { context, page } = await open();
  const cdp = await context.newCDPSession(page);
  await cdp.send('Performance.enable');
  // The page's main thread while the worker reads and runs: its long tasks (> 50 ms).
  await page.evaluate(() => {
    window.__longTasks = [];
    new PerformanceObserver((l) => window.__longTasks.push(...l.getEntries().map((e) => e.duration))).observe({ type: 'longtask' });
  });
  const before = await processMemory();
  const r = await upload(page, [hourFile], { timeout: 120_000 });
  const long = await page.evaluate(() => window.__longTasks);
  console.log(`one hour, main thread during the load: ${long.length} long tasks, the longest ${Math.max(0, ...long).toFixed(0)} ms `
    + `(the analysis decoded and every plot drawn), ${long.reduce((a, b) => a + b, 0).toFixed(0)} ms in all`);
  const grown = memoryGrowth(before, await processMemory());
  console.log(`one hour, ${mb.toFixed(0)} MB pdr-log: peak memory added, the page's renderer (page and worker) ${grown.renderer.toFixed(0)} MB `
    + `(${(grown.renderer / mb).toFixed(2)} × the file), all Chromium processes ${grown.all.toFixed(0)} MB (${(grown.all / mb).toFixed(2)} ×)`);
  const m = await cdp.send('Performance.getMetrics');
  const heap = m.metrics.find((x) => x.name === 'JSHeapUsedSize').value / 1e6;
  const l = r.logs[0];
  const parse = await page.evaluate(() => window.__pdrTest.upload.parse_ms);
  console.log(`one hour, ${mb.toFixed(0)} MB pdr-log, ${l.a.samples} samples: parse + engine + first draw ${(r.ms / 1000).toFixed(2)} s `
    + `(parse ${(parse / 1000).toFixed(2)} s; engine with the plots' signals ${(l.engine_ms / 1000).toFixed(2)} s = `
    + `${(l.a.samples / l.engine_ms / 1000).toFixed(2)} M samples/s in wasm, ${(l.analyse_ms / 1000).toFixed(2)} s with the analysis serialised for the page); worker wasm memory ${l.memory_mb.toFixed(0)} MB `
    + `(${(l.memory_mb / mb).toFixed(2)} × the file); page JS heap ${heap.toFixed(0)} MB`);
  assert.equal(r.logs[0].a.steps, nativeSteps(hourFile));
  // Re-runs in the same worker: the spread of the engine's throughput on this machine.
  const runs = [];
  for (let i = 0; i < 3; i++) {
    await page.evaluate(() => { window.__pdrTest.upload.logs[0].engine_ms = undefined; });
    await page.click('#rerun');
    await page.waitForFunction(() => document.documentElement.dataset.upload === 'done' && window.__pdrTest.upload.logs[0].engine_ms !== undefined, null, { timeout: 60_000 });
    runs.push(await page.evaluate(() => window.__pdrTest.upload.logs[0].engine_ms));
  }
  console.log(`one hour, engine re-run in wasm: ${runs.map((ms) => `${(l.a.samples / ms / 1000).toFixed(2)}`).join(', ')} M samples/s`);

  // The same hour as a Sensor Logger (Android) folder: TotalAcceleration, Gyroscope,
  // Orientation and Metadata CSVs, time in ns.
  const dir = path.join(tmp, 'hour-sensor-logger');
  mkdirSync(dir);
  const t0 = 1_795_000_000;
  const acc = ['time,seconds_elapsed,z,y,x'];
  const gyr = ['time,seconds_elapsed,z,y,x'];
  const ori = ['time,seconds_elapsed,qz,qy,qx,qw,roll,pitch,yaw'];
  for (const line of readFileSync(hourFile, 'utf8').split('\n')) {
    if (!line.startsWith('imu,')) continue;
    const f = line.split(',');
    const t = Number(f[1]);
    const ns = `${t0 + Math.floor(t)}${String(Math.round((t % 1) * 1e9)).padStart(9, '0')}`;
    const el = t.toFixed(6);
    acc.push(`${ns},${el},${f[4]},${f[3]},${f[2]}`);
    if (f[5]) gyr.push(`${ns},${el},${f[7]},${f[6]},${f[5]}`);
    if (f[11]) ori.push(`${ns},${el},${f[14]},${f[13]},${f[12]},${f[11]},0,0,0`);
  }
  writeFileSync(path.join(dir, 'TotalAcceleration.csv'), `${acc.join('\n')}\n`);
  writeFileSync(path.join(dir, 'Gyroscope.csv'), `${gyr.join('\n')}\n`);
  writeFileSync(path.join(dir, 'Orientation.csv'), `${ori.join('\n')}\n`);
  writeFileSync(path.join(dir, 'Metadata.csv'), 'version,device name,recording time,platform\n3,Simulated,2026-11-23_09-00-00,android');
  const csvMb = readdirSync(dir).reduce((s, f) => s + statSync(path.join(dir, f)).size, 0) / 1e6;
  await context.close();
  const { context: c2, page: p2 } = await open();
  const before2 = await processMemory();
  const r2 = await upload(p2, dir, { folder: true, timeout: 120_000 });
  const grown2 = memoryGrowth(before2, await processMemory());
  console.log(`one hour, ${csvMb.toFixed(0)} MB Sensor Logger folder: peak memory added, the page's renderer ${grown2.renderer.toFixed(0)} MB `
    + `(${(grown2.renderer / csvMb).toFixed(2)} × the files), all Chromium processes ${grown2.all.toFixed(0)} MB (${(grown2.all / csvMb).toFixed(2)} ×)`);
  assert.deepEqual(r2.errors, []);
  const l2 = r2.logs[0];
  const parse2 = await p2.evaluate(() => window.__pdrTest.upload.parse_ms);
  console.log(`one hour, ${csvMb.toFixed(0)} MB Sensor Logger CSV folder, ${l2.a.samples} samples: parse + engine + first draw ${(r2.ms / 1000).toFixed(2)} s `
    + `(parse ${(parse2 / 1000).toFixed(2)} s, engine ${(l2.engine_ms / 1000).toFixed(2)} s); worker wasm memory ${l2.memory_mb.toFixed(0)} MB `
    + `(${(l2.memory_mb / csvMb).toFixed(2)} × the files)`);
  await c2.close();
});
