// End-to-end tests of the opt-in base map: a local HTTPS tile server (another origin; these
// machines have no internet) serves generated PNG tiles, a checker of two colours, and logs
// each request. With the setting on and a custom template pointing at it, the GNSS demo's map
// and an uploaded GNSS walk's map are drawn over its tiles: the right z/x/y for Florence, tile
// pixels under the track, the credit line, nothing from any other origin; screenshots on a
// desktop and a phone, light and dark. With the setting off, page.test.mjs checks the page
// makes no request to another origin.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawn } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import https from 'node:https';
import net from 'node:net';
import path from 'node:path';
import zlib from 'node:zlib';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, holdToUnlock, openPage, useBrowser, tempDir } from './util.mjs';

// The tile server's certificate is self-signed: the whole browser (the service worker's fetches
// too, which a context's ignoreHTTPSErrors does not cover) accepts it.
const browser = useBrowser(['--ignore-certificate-errors']);
const tmp = tempDir('basemap');

/** The two checker colours of the test tiles (even and odd x + y). */
const EVEN = [0x4c, 0xb0, 0x50];
const ODD = [0x50, 0x60, 0xc8];
/** The light scheme's background and the veil over the tiles (src/plot/basemap.rs). */
const LIGHT_BG = [0xfb, 0xfb, 0xf8];
const LIGHT_VEIL = 0.3;
const DARK_BG = [0x15, 0x18, 0x1d];
const DARK_VEIL = 0.6;

/** A 256 × 256 PNG of one colour with a 3-pixel darker border (so tile edges show). */
function png([r, g, b]) {
  const size = 256;
  const raw = Buffer.alloc(size * (1 + size * 3));
  for (let y = 0; y < size; y++) {
    raw[y * (1 + size * 3)] = 0; // filter: none
    for (let x = 0; x < size; x++) {
      const edge = x < 3 || y < 3 || x >= size - 3 || y >= size - 3;
      const o = y * (1 + size * 3) + 1 + x * 3;
      raw[o] = edge ? r >> 1 : r;
      raw[o + 1] = edge ? g >> 1 : g;
      raw[o + 2] = edge ? b >> 1 : b;
    }
  }
  const chunk = (type, data) => {
    const len = Buffer.alloc(4);
    len.writeUInt32BE(data.length);
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(zlib.crc32(body));
    return Buffer.concat([len, body, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(size, 0);
  ihdr.writeUInt32BE(size, 4);
  ihdr.set([8, 2, 0, 0, 0], 8); // 8-bit RGB
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}
const TILE = { even: png(EVEN), odd: png(ODD) };

function freePort() {
  return new Promise((resolve) => {
    const s = net.createServer().listen(0, '127.0.0.1', () => { const { port } = s.address(); s.close(() => resolve(port)); });
  });
}

/** A self-signed certificate for 127.0.0.1, made by `pdr serve` (which keeps it in a folder). */
async function certificate() {
  const dir = path.join(tmp, 'cert');
  writeFileSync(path.join(tmp, 'index.html'), ''); // pdr serve wants a site to serve
  const server = spawn(BIN, ['serve', '--root', tmp, '--http-port', String(await freePort()),
    '--https-port', String(await freePort()), '--cert-dir', dir], { stdio: 'ignore' });
  for (let i = 0; i < 100 && !(existsSync(path.join(dir, 'cert.pem')) && existsSync(path.join(dir, 'key.pem'))); i++) {
    await new Promise((r) => setTimeout(r, 100));
  }
  server.kill();
  return { cert: readFileSync(path.join(dir, 'cert.pem')), key: readFileSync(path.join(dir, 'key.pem')) };
}

let tiles; // the server
let TILE_ORIGIN;
const served = []; // {z, x, y} of every tile request
// The tiles are sent `no-store`, so that what the browser shows offline can only come from the
// service worker's tile cache, not from its HTTP cache.

before(async () => {
  const port = await freePort();
  tiles = https.createServer(await certificate(), (req, res) => {
    const m = req.url.match(/^\/(\d+)\/(\d+)\/(\d+)\.png$/);
    if (!m) { res.writeHead(404).end(); return; }
    const [z, x, y] = m.slice(1).map(Number);
    served.push({ z, x, y });
    res.writeHead(200, { 'Content-Type': 'image/png', 'Access-Control-Allow-Origin': '*', 'Cache-Control': 'no-store' });
    res.end((x + y) % 2 ? TILE.odd : TILE.even);
  });
  await new Promise((r) => tiles.listen(port, '127.0.0.1', r));
  TILE_ORIGIN = `https://127.0.0.1:${port}`;
});
after(() => tiles?.close());

/** The tile column and row of a place at zoom z (the slippy-map formulas). */
function tileOf(lat, lon, z) {
  const n = 2 ** z;
  const phi = lat * Math.PI / 180;
  return [Math.floor((lon + 180) / 360 * n), Math.floor((1 - Math.asinh(Math.tan(phi)) / Math.PI) / 2 * n)];
}
/** Where the GNSS demo walks (src/sim/gnss.rs): Florence. */
const FLORENCE = [43.7696, 11.2558];

/** Opens the page with every request of the context (page and service worker) collected. */
async function open(options = {}) {
  const requests = [];
  const r = await openPage(browser(), URL_HTTP, {
    options: { ignoreHTTPSErrors: true, ...options },
    onPage: (page) => page.context().on('request', (q) => requests.push(q.url())),
  });
  return { ...r, requests };
}

/** Turns the base map on with the test server's template through the settings form. */
async function turnOn(page, credit = 'Test tiles') {
  await page.fill('#basemap-template', `${TILE_ORIGIN}/{z}/{x}/{y}.png`);
  await page.fill('#basemap-attribution', credit);
  await page.check('#basemap-on');
}

/** Waits until `selector`'s canvas is drawn with every tile it shows; its credit and counts. */
async function tilesDrawn(page, selector) {
  await page.waitForFunction((s) => {
    const c = document.querySelector(s);
    const t = c?.dataset.tiles?.split(' ').map(Number);
    return t && t[0] > 0 && t[1] === 0;
  }, selector, { timeout: 20_000 });
  return page.evaluate((s) => {
    const c = document.querySelector(s);
    return { credit: c.dataset.basemap, tiles: c.dataset.tiles.split(' ').map(Number) };
  }, selector);
}

/** Shares of a canvas's pixels near each of the veiled checker colours. */
function tileShare(page, selector, bg, veil) {
  const expect = [EVEN, ODD].map((c) => c.map((v, i) => Math.round(v * (1 - veil) + bg[i] * veil)));
  return page.evaluate(([s, expect]) => {
    const c = document.querySelector(s);
    const { data } = c.getContext('2d').getImageData(0, 0, c.width, c.height);
    let n = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (expect.some((e) => Math.abs(data[i] - e[0]) <= 3 && Math.abs(data[i + 1] - e[1]) <= 3 && Math.abs(data[i + 2] - e[2]) <= 3)) n++;
    }
    return n / (data.length / 4);
  }, [selector, expect]);
}

test('base map on: the demo map is drawn over the chosen server\'s tiles of Florence, credited; no other origin', async () => {
  served.length = 0;
  const { context, page, errors, requests } = await open({ viewport: { width: 1100, height: 900 } });
  await page.waitForFunction(() => document.documentElement.dataset.fusion === 'ready', null, { timeout: 30_000 });
  assert.equal(await page.getAttribute('#fusion', 'data-tiles'), null, 'the base map is off by default');
  assert.deepEqual(served, [], 'no tile is requested while the setting is off');
  await turnOn(page);
  const shown = await tilesDrawn(page, '#fusion');
  assert.equal(shown.credit, 'Test tiles');
  assert.deepEqual(shown.tiles.slice(1), [0, 0], 'no tile failed');
  // The tiles asked for are Florence's at a walk's zoom, each once (the page keeps them).
  assert.ok(served.length >= shown.tiles[0], `${served.length} requests for ${shown.tiles[0]} tiles`);
  for (const { z, x, y } of served) {
    assert.ok(z >= 13 && z <= 18, `zoom ${z}`);
    const [tx, ty] = tileOf(...FLORENCE, z);
    assert.ok(Math.abs(x - tx) <= 4 && Math.abs(y - ty) <= 4, `tile ${z}/${x}/${y} is not near Florence's ${z}/${tx}/${ty}`);
  }
  const keys = served.map(({ z, x, y }) => `${z}/${x}/${y}`);
  assert.equal(new Set(keys).size, keys.length, `a tile was fetched twice: ${keys}`);
  // Every request to another origin went to the tile server.
  const page0 = new URL(URL_HTTP).origin;
  const foreign = requests.filter((u) => !u.startsWith(page0) && !u.startsWith('data:'));
  assert.ok(foreign.length > 0 && foreign.every((u) => u.startsWith(TILE_ORIGIN)), foreign.join('\n'));
  // The veiled tiles show under most of the map; the track is drawn over them.
  const share = await tileShare(page, '#fusion', LIGHT_BG, LIGHT_VEIL);
  assert.ok(share > 0.3, `tile pixels: ${(share * 100).toFixed(1)} %`);
  await page.locator('#fusion').scrollIntoViewIfNeeded();
  await page.locator('#fusion').screenshot({ path: path.join(ARTIFACTS, 'basemap-demo-desktop.png') });
  await page.locator('#basemap').screenshot({ path: path.join(ARTIFACTS, 'basemap-setting-desktop.png') });
  // The setting persists: a reload draws the tiles again (from the page's service worker
  // cache or the server), and turning it off removes them.
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.fusion === 'ready', null, { timeout: 30_000 });
  assert.equal(await page.isChecked('#basemap-on'), true);
  await tilesDrawn(page, '#fusion');
  // By now the service worker controls the page and keeps the tiles for offline reuse; the
  // page can forget them.
  const cached = await page.evaluate(async () => (await (await caches.open('pdr-tiles-v1')).keys()).map((r) => r.url));
  assert.ok(cached.length > 0 && cached.every((u) => u.startsWith(TILE_ORIGIN)), cached.join('\n'));
  // Offline, the map is drawn over the same tiles, from that cache.
  await context.setOffline(true);
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.fusion === 'ready', null, { timeout: 30_000 });
  const offline = await tilesDrawn(page, '#fusion');
  assert.deepEqual(offline.tiles.slice(1), [0, 0], `offline: ${offline.tiles}`);
  await context.setOffline(false);
  await page.click('#basemap-forget');
  await page.waitForFunction(() => document.querySelector('#basemap-messages li.ok'));
  assert.equal(await page.evaluate(() => caches.has('pdr-tiles-v1')), false);
  await page.uncheck('#basemap-on');
  await page.waitForFunction(() => !document.querySelector('#fusion').dataset.tiles);
  assert.deepEqual(errors, []);
  await context.close();
});

test('base map on a phone, in the dark, and under an uploaded GNSS walk', async () => {
  const walk = path.join(tmp, 'city.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--format', 'pdr-log', '--out', walk]);
  const { context, page, errors } = await open({ ...PHONE, colorScheme: 'dark' });
  await turnOn(page, '');
  await page.waitForFunction(() => document.documentElement.dataset.fusion === 'ready', null, { timeout: 30_000 });
  const shown = await tilesDrawn(page, '#fusion');
  // Without a credit of its own, the server's host is named.
  assert.equal(shown.credit, `Map tiles: ${new URL(TILE_ORIGIN).host}`);
  // Under the dark scheme's heavier veil the tiles still show under most of the map.
  const share = await tileShare(page, '#fusion', DARK_BG, DARK_VEIL);
  assert.ok(share > 0.3, `tile pixels: ${(share * 100).toFixed(1)} %`);
  await page.locator('#fusion').scrollIntoViewIfNeeded();
  await page.locator('#fusion').screenshot({ path: path.join(ARTIFACTS, 'basemap-demo-phone-dark.png') });
  await page.setInputFiles('#upload-files', [walk]);
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done', null, { timeout: 60_000 });
  const up = await tilesDrawn(page, '.log-result canvas.map');
  assert.ok(up.tiles[0] > 0 && up.tiles[2] === 0, `upload map tiles ${up.tiles}`);
  const upShare = await tileShare(page, '.log-result canvas.map', DARK_BG, DARK_VEIL);
  assert.ok(upShare > 0.3, `upload map tile pixels: ${(upShare * 100).toFixed(1)} %`);
  await page.locator('.log-result canvas.map').scrollIntoViewIfNeeded();
  await page.locator('.log-result canvas.map').screenshot({ path: path.join(ARTIFACTS, 'basemap-upload-phone-dark.png') });
  // A template the page cannot use is refused with the reason, and the map stays plain.
  await page.fill('#basemap-template', 'http://tiles.invalid/{z}/{x}/{y}.png');
  await page.click('#basemap-apply');
  await page.waitForFunction(() => document.querySelector('#basemap-messages li.error'));
  assert.match(await page.textContent('#basemap-messages'), /Base map off: tile URL template: .* must start with https:\/\//);
  await page.waitForFunction(() => !document.querySelector('#fusion').dataset.tiles);
  assert.deepEqual(errors, []);
  await context.close();
});

test('base map under live mode: the setting kept from last time, the tiles of the first fix\'s place', async () => {
  served.length = 0;
  const lugano = { latitude: 46.0037, longitude: 8.9511, accuracy: 8 };
  const { context, page, errors } = await open({
    ...PHONE,
    geolocation: lugano,
    permissions: ['geolocation', 'accelerometer', 'gyroscope', 'magnetometer'],
  });
  // The setting as a previous visit left it.
  await page.evaluate((t) => localStorage.setItem('pdr-basemap', JSON.stringify({ on: true, template: t, attribution: 'Test tiles' })), `${TILE_ORIGIN}/{z}/{x}/{y}.png`);
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.state === 'ready');
  assert.equal(await page.isChecked('#basemap-on'), true);
  await page.click('#start');
  await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
  await holdToUnlock(page, 2200); // the pocket guard hides the plots
  await page.waitForFunction(() => window.__pdrTest?.live?.readouts.fixes > 0, null, { timeout: 10_000 });
  await page.evaluate(() => window.__pdrTest.live.draw());
  const shown = await tilesDrawn(page, '#live-map');
  assert.equal(shown.credit, 'Test tiles');
  // The page asked for Lugano's tiles for the live map, and otherwise only for Florence's (the
  // GNSS demo's map further down the page).
  const near = ([lat, lon], { z, x, y }) => {
    const [tx, ty] = tileOf(lat, lon, z);
    return Math.abs(x - tx) <= 4 && Math.abs(y - ty) <= 4;
  };
  const here = served.filter((t) => near([lugano.latitude, lugano.longitude], t));
  assert.ok(here.length >= shown.tiles[0], `${here.length} of Lugano's tiles requested for ${shown.tiles[0]} on the map`);
  for (const t of served) assert.ok(near([lugano.latitude, lugano.longitude], t) || near(FLORENCE, t), `tile ${t.z}/${t.x}/${t.y}`);
  await page.locator('#live-map').scrollIntoViewIfNeeded();
  await page.locator('#live-map').screenshot({ path: path.join(ARTIFACTS, 'basemap-live-phone.png') });
  assert.deepEqual(errors, []);
  await context.close();
});
