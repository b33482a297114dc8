// What the end-to-end test files share: where the server, the binary and the artifacts are; the
// browser; opening the page with its errors collected; and a simulated walk dispatched as the
// browser's own motion and orientation events.
import { before, after } from 'node:test';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = path.dirname(fileURLToPath(import.meta.url));
// `./dev e2e` starts `pdr serve` on free ports and sets these.
export const URL_HTTP = process.env.PDR_E2E_URL ?? 'http://127.0.0.1:8080/';
export const URL_HTTPS = process.env.PDR_E2E_HTTPS_URL ?? 'https://127.0.0.1:8443/';
export const BIN = process.env.PDR_BIN ?? path.join(here, '../../target/release/pdr');
export const DIST = process.env.PDR_DIST ?? path.join(here, '../../dist');
export const ARTIFACTS = path.join(here, 'artifacts');
mkdirSync(ARTIFACTS, { recursive: true });

/**
 * A fresh directory `pdr-NAME-…` in the system's temporary folder for the file's tests, removed
 * after them (some hold hundreds of MB: the one-hour log, browser profiles).
 */
export function tempDir(name) {
  const dir = mkdtempSync(path.join(os.tmpdir(), `pdr-${name}-`));
  after(() => rmSync(dir, { recursive: true, force: true }));
  return dir;
}

/** A phone: 390×844 CSS px at three device pixels each, touch. */
export const PHONE = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true };

/**
 * Launches headless Chromium before the file's tests and closes it after them; returns a
 * getter for it. Playwright gives each launch a fresh temporary profile (user data dir).
 */
export function useBrowser(extraArgs = []) {
  let browser;
  before(async () => {
    browser = await chromium.launch({
      executablePath: '/usr/bin/chromium',
      args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
        '--disable-component-update', '--disable-sync', ...extraArgs],
    });
  });
  after(async () => { await browser?.close(); });
  return () => browser;
}

/**
 * Opens `url` in a new context of `browser` with `options`, after the context's init scripts
 * `init` (functions, or [function, argument] pairs), collecting console errors and uncaught
 * exceptions; `onPage(page)` runs before the page loads. Waits until the page's state is one
 * of `states` and returns `{ context, page, errors }`.
 */
export async function openPage(browser, url, { options = {}, init = [], onPage, states = ['ready'] } = {}) {
  const context = await browser.newContext(options);
  for (const script of [...init, fireScript]) {
    if (Array.isArray(script)) await context.addInitScript(...script);
    else await context.addInitScript(script);
  }
  return { context, ...await loadPage(context, url, { onPage, states }) };
}

/**
 * Opens `url` in a new page of `context`, collecting console errors and uncaught exceptions;
 * `onPage(page)` runs before the page loads. Waits until the page's state is one of `states`
 * and returns `{ page, errors }`.
 */
export async function loadPage(context, url, { onPage, states = ['ready'] } = {}) {
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  onPage?.(page);
  await page.goto(url);
  await page.waitForFunction((s) => s.includes(document.documentElement.dataset.state), states, { timeout: 30_000 });
  return { page, errors };
}

// window.__pdrFire(e, base, ios) dispatches one event of a walk (`pdr simulate --events`) at
// timeStamp base + e.t. iOS orientation events carry `webkitCompassHeading` and a relative
// alpha, as Safari's do.
function fireScript() {
  window.__pdrFire = (e, base, ios) => {
    let ev;
    if (e.type === 'motion') {
      ev = new DeviceMotionEvent('devicemotion', {
        accelerationIncludingGravity: { x: e.x, y: e.y, z: e.z },
        rotationRate: e.alpha == null ? null : { alpha: e.alpha, beta: e.beta, gamma: e.gamma },
        interval: e.interval,
      });
    } else if (ios) {
      ev = new DeviceOrientationEvent('deviceorientation', { alpha: (e.alpha + 123) % 360, beta: e.beta, gamma: e.gamma, absolute: false });
      Object.defineProperty(ev, 'webkitCompassHeading', { value: (360 - e.alpha) % 360 });
    } else {
      ev = new DeviceOrientationEvent('deviceorientationabsolute', { alpha: e.alpha, beta: e.beta, gamma: e.gamma, absolute: true });
    }
    Object.defineProperty(ev, 'timeStamp', { value: base + e.t });
    window.dispatchEvent(ev);
  };
}

/**
 * Dispatches events `from`..`to` of a walk on the page at once, in chunks, with
 * timeStamp = base + t (the walk's own times on the page's clock from `base`).
 */
export async function dispatch(page, events, { base, ios = false, from = 0, to = events.length }) {
  const CHUNK = 400;
  for (let i = from; i < to; i += CHUNK) {
    await page.evaluate(({ chunk, base, ios }) => {
      for (const e of chunk) window.__pdrFire(e, base, ios);
    }, { chunk: events.slice(i, Math.min(i + CHUNK, to)), base, ios });
  }
}

/**
 * Starts dispatching a walk's events in real time, each when the page's clock reaches
 * base + e.t (as a phone fires them); `window.__pdrWalked` counts the events fired so far.
 */
export async function dispatchRealTime(page, events, base) {
  await page.evaluate(({ events, base }) => {
    window.__pdrWalked = 0;
    const timer = setInterval(() => {
      const now = performance.now();
      while (window.__pdrWalked < events.length && base + events[window.__pdrWalked].t <= now) {
        window.__pdrFire(events[window.__pdrWalked++], base, false);
      }
      if (window.__pdrWalked >= events.length) clearInterval(timer);
    }, 10);
  }, { events, base });
}

/** Presses the pocket guard's unlock button for `ms`. */
export async function holdToUnlock(page, ms) {
  const box = await page.locator('#unlock').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.waitForTimeout(ms);
  await page.mouse.up();
}
