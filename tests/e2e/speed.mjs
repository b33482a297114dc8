// The wasm's speed in headless Chromium: a benchmark that prints figures, not a test.
//
// Figures (each the median of `--loads` fresh browser contexts, so every load fetches and
// compiles the wasm anew, as a first visit does):
// - first drawn track: the page's own mark `__pdrTest.demo.ready_ms`, ms after navigation;
// - demo engine: one `new Demo()` (the demo walk simulated and run through the engine), ms;
// - GNSS demo engine: one `new FusionDemo()` (the city walk with fixes, fused), ms;
// - live session: 100 000 motion events pushed through `Live` (as in page.test.mjs), events/s.
// It compares builds of the page (for instance opt-levels of the wasm): serve each build's
// `dist/` and give their addresses; the loads alternate between them, so that a machine busy
// with other work slows every build alike.
//
// Usage: node tests/e2e/speed.mjs [--loads 9] [URL ...]   (default: PDR_E2E_URL as for the tests)
import { chromium } from 'playwright-core';

const i = process.argv.indexOf('--loads');
const LOADS = i > 0 ? Number(process.argv[i + 1]) : 9;
const given = process.argv.slice(2).filter((a, k, all) => a !== '--loads' && all[k - 1] !== '--loads');
const URLS = given.length > 0 ? given : [process.env.PDR_E2E_URL ?? 'http://127.0.0.1:8080/'];

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

/** One fresh load: the first-track mark, then the engine timed in the loaded page. */
async function once(browser, url) {
  const context = await browser.newContext({ viewport: { width: 1100, height: 900 } });
  const page = await context.newPage();
  await page.goto(url);
  await page.waitForFunction(() => document.documentElement.dataset.state === 'ready', null, { timeout: 60_000 });
  const r = await page.evaluate(async () => {
    const { Demo, FusionDemo, Live } = await import('./www/pkg/pdr.js');
    const ready = window.__pdrTest.demo.ready_ms;
    let t0 = performance.now();
    new Demo().free();
    const demo = performance.now() - t0;
    t0 = performance.now();
    new FusionDemo().free();
    const fusion = performance.now() - t0;
    const live = new Live(undefined, false, 0);
    const n = 100_000;
    const at = (ev, t) => Object.defineProperty(ev, 'timeStamp', { value: t });
    const motion = [];
    for (let i = 0; i < n; i++) {
      const t = i * 10; // 100 Hz, a 1.8 Hz walk
      const ph = (2 * Math.PI * 1.8 * t) / 1000;
      motion.push(at(new DeviceMotionEvent('devicemotion', {
        accelerationIncludingGravity: { x: 0.5 * Math.sin(ph / 2), y: 9.81 + 3 * Math.cos(ph), z: 0.3 },
        rotationRate: { alpha: 10 * Math.sin(ph), beta: 5, gamma: 2 },
        interval: 10,
      }), t));
    }
    t0 = performance.now();
    for (let i = 0; i < n; i++) live.push_motion(motion[i]);
    const rate = n / ((performance.now() - t0) / 1000);
    return { ready, demo, fusion, rate };
  });
  await context.close();
  return r;
}

async function main() {
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
  const runs = URLS.map(() => []);
  for (let k = 0; k < LOADS; k++) {
    for (const [u, url] of URLS.entries()) runs[u].push(await once(browser, url));
  }
  await browser.close();
  for (const [u, url] of URLS.entries()) {
    const m = (key) => median(runs[u].map((r) => r[key]));
    console.log(`${url} (${LOADS} loads, medians)`);
    console.log(`  first drawn track: ${m('ready').toFixed(0)} ms after navigation`);
    console.log(`  demo engine (new Demo): ${m('demo').toFixed(1)} ms; GNSS demo (new FusionDemo): ${m('fusion').toFixed(1)} ms`);
    console.log(`  live session: ${Math.round(m('rate'))} motion events/s`);
  }
}

main().catch((e) => { console.error(e); process.exit(1); });
