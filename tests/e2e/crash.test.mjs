// Crashes while recording: a live recording driven by Chromium's virtual sensors (the Generic
// Sensor API path, as on an Android phone) is killed at random moments — the renderer crashed
// (CDP `Page.crash`), the whole browser killed (SIGKILL), the tab closed — and the page,
// opened again on the same profile, recovers it through its own recovery offer.
//
// What is compared:
// - Samples. Each virtual reading is set, then the test waits until the page has counted it
//   (`readouts.samples`), noting when. Just before the kill the test reads how many samples the
//   page's recorder has had written (`saved.samples`: chunks IndexedDB has confirmed): every one
//   must be in the recovered log, whatever the machine's load. The page must also keep writing:
//   the oldest sample not yet written at that moment may be at most WRITE_LAG_MS old (it writes
//   every 250 ms; the bound leaves room for a loaded machine's stalls). The recorded
//   accelerations are checked against the fed ones, in order.
// - Steps. The page stores with each chunk the step count the engine had when the chunk was
//   taken; the recovered log ends with the last chunk written, so `pdr run` of it must count
//   exactly that many (the engine is causal: the same samples give the same steps). What the
//   pocket guard showed at the test's last look before the kill is printed beside it: it is
//   read at most 100 ms apart from a flush and may differ by a step.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { ARTIFACTS, BIN, URL_HTTP, loadPage, tempDir } from './util.mjs';

const WRITE_LAG_MS = 2000; // live.js writes every 250 ms
const tmp = tempDir('crash');
const profile = tempDir('crash-profile');
const TRIALS = ['crash', 'kill-browser', 'close-tab', 'crash', 'kill-browser'];
const seed = Number(process.env.PDR_CRASH_SEED ?? Date.now() % 1e6);
/** Progress on stderr with PDR_DEBUG=1. */
const dbg = (...a) => process.env.PDR_DEBUG && console.error(new Date().toISOString(), ...a);

/** A small seeded generator: the kill moments of a run can be repeated with PDR_CRASH_SEED. */
function rng(s) {
  let x = s >>> 0 || 1;
  return () => { x ^= x << 13; x >>>= 0; x ^= x >> 17; x ^= x << 5; x >>>= 0; return x / 2 ** 32; };
}

/** Chromium on a profile that outlives it (IndexedDB survives a kill), driven over CDP. */
async function launch() {
  const proc = spawn('/usr/bin/chromium', ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', `--user-data-dir=${profile}`,
    '--remote-debugging-port=0', 'about:blank'], { stdio: ['ignore', 'ignore', 'pipe'], detached: true });
  const ws = await new Promise((resolve, reject) => {
    let err = '';
    proc.stderr.on('data', (d) => {
      err += d;
      const m = err.match(/DevTools listening on (ws:\/\/\S+)/);
      if (m) resolve(m[1]);
    });
    proc.on('exit', (code) => reject(new Error(`chromium exited (${code}): ${err}`)));
  });
  const browser = await chromium.connectOverCDP(ws);
  const context = browser.contexts()[0];
  await context.grantPermissions(['accelerometer', 'gyroscope', 'magnetometer'], { origin: new URL(URL_HTTP).origin });
  return { proc, browser, context };
}

/** Kills the browser and every process it started, at once. */
async function killBrowser(b) {
  if (b.proc.exitCode !== null || b.proc.signalCode !== null) return;
  const gone = new Promise((resolve) => b.proc.once('exit', resolve));
  process.kill(-b.proc.pid, 'SIGKILL');
  await gone;
}

/** The page's virtual sensors, with a fixed attitude (heading 45°). */
async function sensors(context, page) {
  const cdp = await context.newCDPSession(page);
  for (const type of ['accelerometer', 'linear-acceleration', 'gravity', 'gyroscope', 'absolute-orientation', 'relative-orientation']) {
    await cdp.send('Emulation.setSensorOverrideEnabled', { enabled: true, type });
  }
  for (const type of ['absolute-orientation', 'relative-orientation']) {
    await cdp.send('Emulation.setSensorOverrideReadings', { type, reading: { quaternion: { x: 0, y: 0, z: 0.3826834, w: 0.9238795 } } });
  }
  const xyz = (type, x, y, z) => cdp.send('Emulation.setSensorOverrideReadings', { type, reading: { xyz: { x, y, z } } });
  await xyz('gravity', 0, 0, 9.81);
  await xyz('linear-acceleration', 0, 0, 0);
  return { cdp, xyz };
}

const round1 = (v) => Math.round(v * 10) / 10;
const look = (page) => page.evaluate(() => {
  const r = window.__pdrTest.live.readouts;
  return { samples: r.samples, steps: r.steps, shown: Number(document.getElementById('g-steps').textContent),
    written: window.__pdrTest.live.saved.samples, at: Date.now() };
});

/**
 * Walks with the virtual sensors until `until` (Unix ms), and on until the page has counted
 * `MIN_FED` samples (a loaded machine delivers fewer readings a second; at most 30 s more): a
 * 1.8 Hz vertical bounce of ±3 m/s² at the test's clock, each reading changed (Chromium sends a
 * reading only on a change) and waited for. Returns the samples the page counted:
 * `[{at, az, shown, steps}]`, index = sample.
 */
const MIN_FED = 60;
async function walkUntil(page, xyz, until) {
  const fed = [];
  let { samples: counted } = await look(page);
  let last = null;
  let k = 0;
  while (Date.now() < until || (fed.length < MIN_FED && Date.now() < until + 30_000)) {
    const t = Date.now() / 1000;
    let az = round1(9.81 + 3 * Math.sin(2 * Math.PI * 1.8 * t));
    if (az === last) az = round1(az + 0.1);
    last = az;
    const ax = round1(0.5 * Math.sin(2 * Math.PI * 0.9 * t));
    await xyz('gyroscope', 0.01 * (k % 3), 0.02, 0.03 + 0.01 * (k++ % 2));
    await xyz('accelerometer', ax, 0.2, az);
    // Wait for the reading to be counted (a few ms; seconds on a loaded machine): a reading still
    // in flight when the next is set would be counted with the next one's values.
    for (const t0 = Date.now(); Date.now() - t0 < 3000;) {
      const r = await look(page);
      if (r.samples > counted) {
        for (let i = counted; i < r.samples; i++) fed.push({ n: i + 1, at: Date.now(), az, ax, shown: r.shown, steps: r.steps });
        counted = r.samples;
        break;
      }
    }
  }
  return fed;
}

test('crashes while recording: every sample but the last batch is recovered, and replays to the steps shown', async () => {
  const random = rng(seed);
  console.log(`crash trials: seed ${seed} (PDR_CRASH_SEED repeats the kill moments)`);
  let b = await launch();
  let { page, errors } = await loadPage(b.context, URL_HTTP);
  const rows = [];
  try {
    for (const [n, how] of TRIALS.entries()) {
      await page.selectOption('#gnss-mode', 'off');
      dbg('trial', n, how);
      const { xyz } = await sensors(b.context, page);
      dbg('sensors');
      await xyz('accelerometer', 0, 0.2, 9.81);
      await xyz('gyroscope', 0, 0.02, 0.03);
      await page.click('#start');
      await page.waitForFunction(() => document.documentElement.dataset.source === 'sensors', null, { timeout: 10_000 });
      const delay = 3000 + Math.round(random() * 5000);
      const startAt = Date.now();
      dbg('started');
      const fed = await walkUntil(page, xyz, startAt + delay);
      dbg('walked', fed.length);
      const seen = await look(page);
      // The kill.
      if (how === 'crash') {
        const cdp = await b.context.newCDPSession(page);
        const crashed = page.waitForEvent('crash', { timeout: 10_000 });
        cdp.send('Page.crash').catch(() => {}); // answered by no one: the renderer is gone
        await crashed;
        dbg('crashed');
        page.close().catch(() => {});
      } else if (how === 'close-tab') {
        await page.close({ runBeforeUnload: false });
      } else {
        await killBrowser(b);
        b = await launch();
      }
      // Open again: the page offers the recording.
      ({ page, errors } = await loadPage(b.context, URL_HTTP));
      await page.waitForFunction(() => document.documentElement.dataset.recovery === 'offered', null, { timeout: 10_000 });
      const offer = await page.evaluate(() => window.__pdrTest.recovery);
      dbg('offered', offer);
      const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#recover-save')]);
      const file = path.join(tmp, `trial-${n}.pdrlog`);
      await dl.saveAs(file);
      const imu = readFileSync(file, 'utf8').split('\n').filter((l) => l.startsWith('imu,')).map((l) => l.split(','));
      const run = execFileSync(BIN, ['run', file], { encoding: 'utf8' });
      const replayed = Number(run.match(/^steps\s+(\d+)/m)[1]);
      // Every sample the page had written before the kill is there.
      const lost = Math.max(0, seen.written - imu.length);
      const lastBatch = Math.max(0, fed.length - imu.length);
      // The oldest sample the page had not yet written, ms before the last look.
      const lag = seen.at - (fed.find((f) => f.n > seen.written)?.at ?? seen.at);
      // In order, with the accelerations fed.
      const wrong = imu.filter((l, i) => i < fed.length && (Math.abs(Number(l[4]) - fed[i].az) > 0.051 || Math.abs(Number(l[2]) - fed[i].ax) > 0.051)).length;
      rows.push({ trial: n + 1, how, 'kill at (s)': (delay / 1000).toFixed(2), fed: fed.length, recovered: imu.length,
        'written at the kill': seen.written, 'unwritten for (ms)': lag, lost, 'in the last batch, not saved': lastBatch,
        'wrong values': wrong,
        'steps at last chunk': offer.steps, 'pdr run': replayed, 'guard showed': seen.shown });
      assert.equal(offer.samples, imu.length);
      assert.ok(fed.length > 50, `only ${fed.length} samples fed`);
      assert.equal(lost, 0, `trial ${n + 1} (${how}): ${lost} of the ${seen.written} samples written lost`);
      assert.ok(lag <= WRITE_LAG_MS, `trial ${n + 1}: a sample counted ${lag} ms before the kill was not yet written`);
      assert.ok(imu.length <= fed.length + 2, `${imu.length} recorded of ${fed.length} fed`);
      assert.equal(wrong, 0, 'recorded accelerations differ from those fed');
      assert.equal(replayed, offer.steps, `trial ${n + 1}: pdr run ${replayed} steps, the page had ${offer.steps} at its last chunk`);
      // Within two steps of the last chunk; but the walk's first steps come together, when the
      // motion detector confirms the gait (the onset look-back releases up to 3 s of them, at
      // 1.8 Hz 6 steps): a kill just after that, before the next chunk, finds them shown and not
      // yet saved.
      const burst = offer.steps === 0 ? 6 : 2;
      assert.ok(Math.abs(seen.shown - offer.steps) <= burst, `the guard showed ${seen.shown}, the last chunk ${offer.steps}`);
      assert.deepEqual(errors, []);
      await page.waitForFunction(() => document.documentElement.dataset.recovery === 'done');
    }
  } finally {
    console.table(rows);
    const total = rows.reduce((a, r) => ({ fed: a.fed + r.fed, lost: a.lost + r.lost, batch: a.batch + r['in the last batch, not saved'] }), { fed: 0, lost: 0, batch: 0 });
    console.log(`crash trials: ${rows.length}; samples fed ${total.fed}; lost beyond the last batch ${total.lost}; lost in the last batch ${total.batch}`);
    await page?.screenshot({ path: path.join(ARTIFACTS, 'live-after-crashes.png') }).catch(() => {});
    await b.browser.close().catch(() => {});
    await killBrowser(b).catch(() => {});
  }
});
