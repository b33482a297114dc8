// End-to-end tests of the first page in a real headless Chromium, against `pdr serve`.
// Run by `./dev test` (which starts the server and sets the variables below).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, DIST, URL_HTTP, URL_HTTPS, openPage, useBrowser } from './util.mjs';

const browser = useBrowser();

/** Opens the page, collecting console errors, page errors, requests and failed responses. */
async function open(url, options = {}) {
  const requests = [];
  const failures = [];
  const { context, page, errors } = await openPage(browser(), url, {
    options,
    states: ['ready', 'error'],
    onPage: (page) => {
      page.on('request', (r) => requests.push(r.url()));
      page.on('response', (r) => { if (r.status() >= 400) failures.push(`${r.status()} ${r.url()}`); });
    },
  });
  const state = await page.evaluate(() => document.documentElement.dataset.state);
  const message = await page.evaluate(() => document.getElementById('error')?.textContent ?? '');
  assert.equal(state, 'ready', `page did not become ready: ${message}`);
  return { context, page, errors, requests, failures };
}

/** Pixel statistics of a canvas (the demo track by default). */
async function canvasStats(page, id = 'track') {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const ctx = c.getContext('2d');
    const { data } = ctx.getImageData(0, 0, c.width, c.height);
    const bg = [data[0], data[1], data[2]];
    let differing = 0;
    let blue = 0;
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      if (Math.abs(r - bg[0]) + Math.abs(g - bg[1]) + Math.abs(b - bg[2]) > 30) differing++;
      if (b > 150 && b > r + 60 && b > g + 20) blue++; // the track's blue, light or dark scheme
    }
    const rect = c.getBoundingClientRect();
    return { width: c.width, height: c.height, cssWidth: rect.width, cssHeight: rect.height, differing, blue, total: data.length / 4 };
  }, id);
}

test('page loads without errors, WASM initialises and the track is drawn', async () => {
  const { context, page, errors } = await open(URL_HTTP, { viewport: { width: 1100, height: 900 } });
  const s = await canvasStats(page);
  assert.ok(s.differing > 0.01 * s.total, `canvas looks blank: ${s.differing} of ${s.total} pixels differ from the background`);
  assert.ok(s.blue > 500, `too few track-coloured pixels: ${s.blue}`);
  // Before the screenshot: Playwright's screenshot injects a style the page's CSP refuses.
  assert.deepEqual(errors, []);
  const shot = path.join(ARTIFACTS, 'desktop.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot: ${shot}`);
  const ready = await page.evaluate(() => window.__pdrTest.demo.ready_ms);
  console.log(`load to first drawn track: ${ready.toFixed(0)} ms`);
  await context.close();
});

test('the GNSS demo draws fixes and tracks, and its figures match the native engine', async () => {
  const native = JSON.parse(execFileSync(BIN, ['demo', '--json'], { encoding: 'utf8' })).fusion;
  const { context, page, errors } = await open(URL_HTTP, { viewport: { width: 1100, height: 900 } });
  await page.waitForFunction(() => document.documentElement.dataset.fusion === 'ready', null, { timeout: 30_000 });
  const s = await canvasStats(page, 'fusion');
  assert.ok(s.differing > 0.02 * s.total, `fusion canvas looks blank: ${s.differing} of ${s.total}`);
  assert.ok(s.blue > 500, `too few fused-track pixels: ${s.blue}`);
  const wasm = await page.evaluate(() => window.__pdrTest.demo.fusion);
  assert.equal(wasm.fused_p75_m, native.fused_p75_m, 'wasm and native fused errors differ');
  assert.equal(wasm.smoothed_p75_m, native.smoothed_p75_m);
  assert.equal(await page.textContent('#fused-p75'), native.fused_p75_m.toFixed(1));
  assert.ok(native.fused_p75_m <= 0.5 * native.gnss_p75_m);
  assert.deepEqual(errors, []);
  await page.locator('#fusion').screenshot({ path: path.join(ARTIFACTS, 'fusion.png') });
  await context.close();
});

test('Chromium motion events reach the engine with the right axes, units and sign (virtual sensors)', async () => {
  const { context, page } = await open(URL_HTTP, { permissions: ['accelerometer', 'gyroscope', 'magnetometer'] });
  const cdp = await context.newCDPSession(page);
  for (const type of ['accelerometer', 'linear-acceleration', 'gravity', 'gyroscope']) {
    await cdp.send('Emulation.setSensorOverrideEnabled', { enabled: true, type });
  }
  const set = (type, x, y, z) => cdp.send('Emulation.setSensorOverrideReadings', { type, reading: { xyz: { x, y, z } } });
  // Face up, turning about the device's x axis at 1 rad/s, y 0.5, z 0.25.
  await set('accelerometer', 0.3, -0.2, 9.81);
  await set('linear-acceleration', 0.3, -0.2, 0);
  await set('gravity', 0, 0, 9.81);
  await set('gyroscope', 1.0, 0.5, 0.25);
  // Then the live session in the page, fed by the browser's own devicemotion events (a listener
  // added before the sensors exist gets none in headless Chromium).
  await page.evaluate(async () => {
    const { Live } = await import('./www/pkg/pdr.js');
    window.__live = new Live(undefined, false, 0);
    window.__events = 0;
    window.__errors = [];
    window.addEventListener('devicemotion', (e) => {
      try {
        window.__live.push_motion(e);
      } catch (err) {
        window.__errors.push(String(err));
      }
      window.__events++;
    });
  });
  // Without orientation events the session waits a second for an attitude, then goes on.
  await page.waitForFunction(() => window.__live.readouts().samples >= 5, null, { timeout: 10_000 });
  assert.deepEqual(await page.evaluate(() => window.__errors), [], 'the engine refused motion events');
  const log = await page.evaluate(() => window.__live.take_log());
  const imu = log.split('\n').filter((l) => l.startsWith('imu,')).map((l) => l.split(',').map(Number));
  assert.ok(imu.length >= 5, `only ${imu.length} samples recorded`);
  const [, , ax, ay, az, gx, gy, gz] = imu.at(-1);
  // Chromium rounds acceleration to 0.1 m/s² and rotation rate to 0.1 °/s.
  assert.ok(Math.abs(ax - 0.3) < 0.06 && Math.abs(ay + 0.2) < 0.06 && Math.abs(az - 9.81) < 0.06, `accel ${ax} ${ay} ${az}`);
  assert.ok(Math.abs(gx - 1.0) < 0.003 && Math.abs(gy - 0.5) < 0.003 && Math.abs(gz - 0.25) < 0.003, `gyro ${gx} ${gy} ${gz} rad/s`);
  const r = await page.evaluate(() => window.__live.readouts());
  assert.ok(r.sample_rate_hz > 20, `sample rate ${r.sample_rate_hz}`);
  await context.close();
});

test('benchmark: motion events handled per second by the live session in wasm (printed, not asserted)', async () => {
  const { context, page } = await open(URL_HTTP);
  const r = await page.evaluate(async () => {
    const { Live } = await import('./www/pkg/pdr.js');
    const live = new Live(undefined, false, 0);
    const n = 100_000;
    // The browser's own event objects, made beforehand (making them is not the engine's time).
    const at = (ev, t) => Object.defineProperty(ev, 'timeStamp', { value: t });
    const motion = [];
    const orientation = [];
    for (let i = 0; i < n; i++) {
      const t = i * 10; // 100 Hz, a 1.8 Hz walk
      const ph = (2 * Math.PI * 1.8 * t) / 1000;
      motion.push(at(new DeviceMotionEvent('devicemotion', {
        accelerationIncludingGravity: { x: 0.5 * Math.sin(ph / 2), y: 9.81 + 3 * Math.cos(ph), z: 0.3 },
        rotationRate: { alpha: 10 * Math.sin(ph), beta: 5, gamma: 2 },
        interval: 10,
      }), t));
      if (i % 10 === 0) {
        orientation.push(at(new DeviceOrientationEvent('deviceorientationabsolute', { alpha: 30, beta: 80, gamma: 5, absolute: true }), t));
      }
    }
    const t0 = performance.now();
    for (let i = 0; i < n; i++) {
      live.push_motion(motion[i]);
      if (i % 10 === 0) live.push_orientation(orientation[i / 10], true, 0);
      if (i % 1000 === 0) live.take_log();
    }
    const ms = performance.now() - t0;
    return { rate: n / (ms / 1000), steps: live.readouts().steps };
  });
  console.log(`live session in wasm: ${Math.round(r.rate)} motion events/s (${(r.rate / 100).toFixed(0)} x a 100 Hz sensor)`);
  assert.ok(r.steps > 1700, `the synthetic walk was not counted: ${r.steps} steps`);
  await context.close();
});

test('the step count shown matches the engine run natively on the same demo walk', async () => {
  const native = JSON.parse(execFileSync(BIN, ['demo', '--json'], { encoding: 'utf8' }));
  const { context, page } = await open(URL_HTTP);
  const shown = Number(await page.textContent('#steps'));
  const fromWasm = await page.evaluate(() => window.__pdrTest.demo);
  assert.equal(shown, native.steps);
  assert.equal(fromWasm.steps, native.steps);
  assert.equal(fromWasm.distance_m, native.distance_m, 'wasm and native distances differ');
  assert.equal(await page.textContent('#distance'), native.distance_m.toFixed(1));
  await context.close();
});

test('on a phone-sized screen the canvas fills the width and is sharp at the device pixel ratio', async () => {
  const { context, page } = await open(URL_HTTP, { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true });
  const s = await canvasStats(page);
  assert.equal(s.width, Math.round(s.cssWidth * 3));
  assert.equal(s.height, Math.round(s.cssHeight * 3));
  const bodyWidth = await page.evaluate(() => document.documentElement.clientWidth);
  assert.ok(s.cssWidth > 0.8 * bodyWidth, `canvas ${s.cssWidth}px of ${bodyWidth}px`);
  const noOverflow = await page.evaluate(() => document.documentElement.scrollWidth <= document.documentElement.clientWidth);
  assert.ok(noOverflow, 'the page scrolls sideways on a phone');
  const shot = path.join(ARTIFACTS, 'phone.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot: ${shot}`);
  await context.close();
});

test('dark scheme draws on a dark background', async () => {
  const { context, page } = await open(URL_HTTP, { colorScheme: 'dark', viewport: { width: 800, height: 800 } });
  const bg = await page.evaluate(() => {
    const d = document.getElementById('track').getContext('2d').getImageData(2, 2, 1, 1).data;
    return d[0] + d[1] + d[2];
  });
  assert.ok(bg < 150, `background is not dark: ${bg}`);
  const s = await canvasStats(page);
  assert.ok(s.blue > 500);
  await page.screenshot({ path: path.join(ARTIFACTS, 'dark.png') });
  await context.close();
});

test('HTTPS with the self-signed certificate serves the same working page', async () => {
  const { context, page, errors } = await open(URL_HTTPS, { ignoreHTTPSErrors: true });
  assert.ok(await page.evaluate(() => window.isSecureContext));
  // Chromium refuses a service worker from a certificate it does not trust, and says so: on
  // a phone over the LAN with the self-signed certificate the page works but not offline.
  // Over a reused connection Chromium names the certificate; over a new one (pdr serve closes
  // each connection after one response) its TLS handshake fails with CertificateUnknown (the
  // server logs it) and Chromium calls that an unknown error.
  await page.waitForTimeout(500);
  assert.deepEqual(errors.filter((e) => !/(SSL certificate|An unknown) error occurred when fetching the script/.test(e)), []);
  await context.close();
});

test('static deployment: dist/ holds every file the page loads', async () => {
  const { context, requests, failures } = await open(URL_HTTP);
  const origin = new URL(URL_HTTP).origin;
  const local = requests.filter((u) => u.startsWith(origin)).map((u) => new URL(u).pathname);
  assert.ok(local.some((p) => p.endsWith('.wasm')), 'the page did not load the wasm module');
  for (const p of local) {
    const file = path.join(DIST, p === '/' ? 'index.html' : decodeURIComponent(p));
    assert.ok(existsSync(file), `dist/ lacks ${p}`);
  }
  assert.deepEqual(failures, []);
  assert.deepEqual(requests.filter((u) => !u.startsWith(origin) && !u.startsWith('data:')), [], 'the page fetches from another origin');
  await context.close();
});
