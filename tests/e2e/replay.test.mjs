// A real pocket walk replayed through live mode: one TyrEx walk (../shared/data/tyrex-pocket, a
// Nexus 5 in a front trouser pocket, motion-capture truth) is set, reading by reading at its own
// pace in wall time, on Chromium's virtual sensors (CDP `Emulation.setSensorOverrideReadings`).
// The page reads them as on an Android phone (the Generic Sensor API, or devicemotion where that
// is missing); Chromium samples them at about 60 Hz of wall time, so the replay takes the walk's
// ~2 minutes.
//
// What is compared:
// - Live against the page's own recording of this session, replayed by `pdr run`: the same
//   samples through the same engine, so every step, the distance within 1 % (exactly once Stop
//   has placed the steps a bout's opening held) and the track's end.
// - Printed, not asserted: `pdr run` of the original folder (~200 Hz, with the magnetometer),
//   the same walk rewritten in the test the way the browser delivers it (no magnetometer; at a
//   steady 60 Hz, sample-and-hold, with and without Chromium's rounding; and cut to exactly the
//   samples the page received) to show where the differences come from, the holes in what the
//   page received, and the motion-capture truth's distance (`pdr eval`). See docs/live-mode.md.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { performance } from 'node:perf_hooks';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, holdToUnlock, openPage, useBrowser, tempDir } from './util.mjs';

const WALK = path.resolve(import.meta.dirname, '../../../shared/data/tyrex-pocket/Guillaume_Nexus5_NoDist_FrontPocket');
const tmp = tempDir('replay');
const browser = useBrowser();
// PDR_REPLAY_EVENTS=1: the page without the Generic Sensor API, so that it reads the same
// virtual sensors as devicemotion and deviceorientationabsolute events (as a browser without it).
const EVENTS = process.env.PDR_REPLAY_EVENTS === '1';
const noGenericSensors = () => {
  for (const name of ['Accelerometer', 'Gyroscope', 'AbsoluteOrientationSensor']) delete window[name];
};

/** Standard gravity, m/s²: what Android's gravity sensor reports at rest. */
const G = 9.80665;

/** A TyrEx text file as rows of numbers (the first column the phone's time in s). */
function rows(file) {
  return readFileSync(path.join(WALK, file), 'utf8').trim().split('\n').map((l) => l.trim().split(/\s+/).map(Number));
}

/**
 * The readings Chromium's virtual sensors take for one moment of the walk, derived from the
 * files. The files' Android axes are the browser's: device frame, x right, y up the screen, z out
 * of it (the pdr-log convention; `src/live/events.rs` converts only iOS and the event units), so
 * the accelerometer (m/s², gravity included) and gyroscope (rad/s) pass unchanged. The rotation
 * vector (x, y, z, w: device to East-North-Up) is the absolute orientation as it is; what the
 * files lack is derived from it: gravity in the device frame, R(q)ᵀ·(0, 0, g) (the third row of
 * R(q) times g), and linear acceleration, the accelerometer minus that gravity.
 */
function browserReadings(acc, gyr, rv) {
  const n = Math.hypot(rv[1], rv[2], rv[3], rv[4]);
  const [x, y, z, w] = [rv[1] / n, rv[2] / n, rv[3] / n, rv[4] / n];
  const gravity = [2 * (x * z - w * y) * G, 2 * (y * z + w * x) * G, (1 - 2 * (x * x + y * y)) * G];
  const a = acc.slice(1, 4);
  return {
    accelerometer: a,
    gyroscope: gyr.slice(1, 4),
    gravity,
    'linear-acceleration': a.map((v, i) => v - gravity[i]),
    quaternion: { x, y, z, w },
  };
}

/** The walk as one list, a row per accelerometer sample with the latest gyroscope and rotation vector. */
function walkSamples() {
  const acc = rows('accelerometer.txt');
  const gyr = rows('gyroscope-calibrated.txt');
  const rv = rows('rotation-vector.txt');
  const out = [];
  let g = 0;
  let r = 0;
  for (const a of acc) {
    while (g + 1 < gyr.length && gyr[g + 1][0] <= a[0]) g++;
    while (r + 1 < rv.length && rv[r + 1][0] <= a[0]) r++;
    // The gyroscope and rotation vector start later than the accelerometer (see the data's README).
    if (gyr[g][0] > a[0] || rv[r][0] > a[0]) continue;
    out.push({ t: a[0], ...browserReadings(a, gyr[g], rv[r]) });
  }
  return out;
}

/**
 * The walk as a pdr-log, as the browser would deliver it: `picks` are `{t, i}`, sample `i` at
 * time `t` (s; by default every sample at its own time); `round` rounds as Chromium does
 * (0.1 m/s², 0.1 °/s). No magnetometer: the page's Generic Sensor path reads none.
 */
function pdrlog(samples, { picks = samples.map((s, i) => ({ t: s.t, i })), round = false } = {}) {
  const r = (v, step) => (round ? Math.round(v / step) * step : v);
  const deg = Math.PI / 180;
  const lines = ['# pdr-log 1'];
  for (const { t, i } of picks) {
    const s = samples[i];
    const { x, y, z, w } = s.quaternion;
    lines.push(['imu', t.toFixed(6), ...s.accelerometer.map((v) => r(v, 0.1)),
      ...s.gyroscope.map((v) => r(v, 0.1 * deg)), '', '', '', w, x, y, z].join(','));
  }
  return `${lines.join('\n')}\n`;
}

/** Every 1/`hz` s over the walk, the latest sample then (sample-and-hold): picks for `pdrlog`. */
function grid(samples, hz) {
  const out = [];
  let i = 0;
  for (let t = samples[0].t; t <= samples.at(-1).t; t += 1 / hz) {
    while (i + 1 < samples.length && samples[i + 1].t <= t) i++;
    out.push({ t, i });
  }
  return out;
}

/**
 * Which sample of the walk each line of the page's recording holds, from the readings the test
 * set (`sets`: {at: Unix ms once set, i}): the newest set by the line's time whose accelerometer
 * rounds to the line's (0.1 m/s²), looking back a few; else the newest set then. Returns the
 * picks for `pdrlog` (the recording's own times) and how many matched by value.
 */
function delivered(sets, samples, imu) {
  let p = 0;
  let matched = 0;
  const picks = imu.map((line) => {
    const f = line.split(',').map(Number);
    while (p + 1 < sets.length && sets[p + 1].at <= f[1] * 1000 + 20) p++;
    for (let q = p; q >= Math.max(0, p - 40); q--) {
      if (samples[sets[q].i].accelerometer.every((v, k) => Math.abs(v - f[2 + k]) < 0.051)) {
        matched++;
        return { t: f[1], i: sets[q].i };
      }
    }
    return { t: f[1], i: sets[p].i };
  });
  return { picks, matched };
}

/**
 * `pdr run` of a file or folder: {steps, distance_m, end}, `end` its track's last [east, north]
 * (m). The steps and distance are `pdr eval --json`'s (the same replay, full precision, where
 * `pdr run` prints 0.1 m).
 */
function pdrRun(file) {
  const csv = path.join(tmp, 'track.csv');
  const out = execFileSync(BIN, ['run', file, '--track', csv], { encoding: 'utf8' });
  const [head, ...track] = readFileSync(csv, 'utf8').trim().split('\n').map((l) => l.split(','));
  const last = track.at(-1);
  const { steps, distance_m } = JSON.parse(execFileSync(BIN, ['eval', '--json', file], { encoding: 'utf8' })).logs[0];
  assert.equal(steps, Number(out.match(/^steps\s+(\d+)/m)[1]), `${file}: pdr eval and pdr run differ`);
  assert.equal(track.length, steps, `${file}: the track's rows are not its steps`);
  return { steps, distance_m, end: [Number(last[head.indexOf('east_m')]), Number(last[head.indexOf('north_m')])] };
}

/**
 * The virtual sensors the page reads: the Generic Sensor API's accelerometer, gyroscope and
 * absolute orientation; devicemotion needs all four motion sensors (accelerometer, gyroscope,
 * linear acceleration, gravity), deviceorientationabsolute the absolute orientation. Only these
 * are set at each sample (fewer CDP messages: the replay's timing is real).
 */
const SENSORS = ['accelerometer', 'gyroscope', 'linear-acceleration', 'gravity',
  'absolute-orientation', 'relative-orientation'];
const READ = EVENTS
  ? ['gyroscope', 'gravity', 'linear-acceleration', 'accelerometer', 'absolute-orientation']
  : ['gyroscope', 'accelerometer', 'absolute-orientation'];

/** Sets the virtual sensors `types` to one sample's readings (sent together, awaited together). */
function setReadings(cdp, s, types = READ) {
  return Promise.all(types.map((type) => cdp.send('Emulation.setSensorOverrideReadings', {
    type,
    reading: type.endsWith('orientation')
      ? { quaternion: s.quaternion }
      : { xyz: { x: s[type][0], y: s[type][1], z: s[type][2] } },
  })));
}

/**
 * Replays `samples` on the virtual sensors in real time: each is set when the wall clock since
 * the start reaches its time since the first (later samples due at the same moment replace
 * earlier ones: only the newest is set). Appends each set to `sets` ({at: Unix ms, the clock of
 * the page's recording, once set; i: the sample}).
 */
async function replay(cdp, samples, sets) {
  const start = performance.now();
  const t0 = samples[0].t;
  let i = 0;
  while (i < samples.length - 1) {
    const now = t0 + (performance.now() - start) / 1000;
    let j = i;
    while (j + 1 < samples.length && samples[j + 1].t <= now) j++;
    if (j > i) {
      i = j;
      await setReadings(cdp, samples[i]);
      sets.push({ at: Date.now(), i });
    }
    await new Promise((resolve) => setTimeout(resolve, 2));
  }
}

const fmt = (r) => `${r.steps} steps, ${r.distance_m.toFixed(1)} m`;

test('a real pocket walk (TyrEx) through live mode: the page\'s steps, distance and track are pdr run\'s of its recording',
  { skip: !existsSync(WALK) && `no ${WALK} (the shared TyrEx data is not in a user's clone)` }, async () => {
    const began = performance.now();
    const samples = walkSamples();
    const { context, page, errors } = await openPage(browser(), URL_HTTP, {
      // At one device pixel: the map's redraws cost the shared machine less (the test's timing is real).
      options: {
        ...PHONE, deviceScaleFactor: 1, acceptDownloads: true, permissions: ['accelerometer', 'gyroscope', 'magnetometer'],
      },
      init: EVENTS ? [noGenericSensors] : [],
    });
    const cdp = await context.newCDPSession(page);
    for (const type of SENSORS) {
      await cdp.send('Emulation.setSensorOverrideEnabled', { enabled: true, type });
    }
    await setReadings(cdp, samples[0], SENSORS);
    const sets = [{ at: Date.now(), i: 0 }];
    await page.selectOption('#gnss-mode', 'off');
    await page.click('#start');
    await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
    await replay(cdp, samples, sets);
    await page.waitForTimeout(500); // the last readings, and a redraw
    const live = await page.evaluate(() => window.__pdrTest.live.readouts);
    const source = await page.evaluate(() => window.__pdrTest.live.source);
    assert.equal(await page.textContent('#g-steps'), String(live.steps));
    await holdToUnlock(page, 2300);
    await page.waitForFunction(() => document.documentElement.dataset.guard === 'off');
    await page.waitForTimeout(300);
    await page.locator('#live').screenshot({ path: path.join(ARTIFACTS, 'replay-tyrex-phone.png') });
    await page.click('#stop');
    await page.waitForFunction(() => document.documentElement.dataset.live === 'stopped');
    // Stop ends the session: the steps a bout's opening still held join the track.
    const stopped = await page.evaluate(() => window.__pdrTest.live.readouts);
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
    const recording = path.join(tmp, 'live.pdrlog');
    await dl.saveAs(recording);
    await context.close();

    // The same walk by pdr run: the page's recording, the original folder, and the original as
    // the browser delivers it (to tell the sampling from the rest).
    const recorded = pdrRun(recording);
    const imu = readFileSync(recording, 'utf8').split('\n').filter((l) => l.startsWith('imu,'));
    const original = pdrRun(WALK);
    // What the page received, sample by sample: the walk's own values at the page's times.
    const got = delivered(sets, samples, imu);
    const variants = [
      ['original, every sample', {}],
      ['original at 60 Hz', { picks: grid(samples, 60) }],
      ['original at 60 Hz, rounded as Chromium', { picks: grid(samples, 60), round: true }],
      ['original, the samples the page received', { picks: got.picks }],
      ['original, the samples the page received, rounded', { picks: got.picks, round: true }],
    ].map(([name, opts]) => {
      const file = path.join(tmp, `${name.replace(/\W+/g, '-')}.pdrlog`);
      writeFileSync(file, pdrlog(samples, opts));
      return [`${name}, no magnetometer`, pdrRun(file)];
    });
    const dt = got.picks.slice(1).map((p, k) => p.t - got.picks[k].t);
    const holes = dt.filter((d) => d > 0.05);
    // Holes in the test's own setting (its event loop or CDP held up), beside the page's.
    const setHoles = sets.slice(1).map((x, k) => x.at - sets[k].at).filter((d) => d > 50);
    const ev = JSON.parse(execFileSync(BIN, ['eval', '--json', WALK], { encoding: 'utf8' })).logs[0].trajectory;
    const pct = (a, b) => `${(100 * (a - b) / b).toFixed(1)} %`;
    const seconds = (performance.now() - began) / 1000;
    console.log(`TyrEx replay (${path.basename(WALK)}), ${sets.length} readings set on the virtual sensors, `
      + `source ${source}, `
      + `${live.samples} samples at ${live.sample_rate_hz.toFixed(1)} Hz; ${holes.length} holes over 50 ms between them `
      + `(${holes.reduce((a, d) => a + d, 0).toFixed(1)} s in all, the longest ${(1000 * Math.max(...dt)).toFixed(0)} ms); `
      + `${got.matched} of them found among the readings set by value; the test's own setting had ${setHoles.length} holes `
      + `over 50 ms (${(setHoles.reduce((a, d) => a + d, 0) / 1000).toFixed(1)} s):`);
    console.table([
      { walk: `live (the page), ${live.held_steps} held at the end`, ...row(live) },
      { walk: 'live, stopped', ...row(stopped) },
      { walk: 'pdr run of the page\'s recording', ...row(recorded) },
      { walk: 'pdr run of the original folder', ...row(original) },
      ...variants.map(([walk, r]) => ({ walk, ...row(r) })),
      { walk: 'motion-capture truth (pdr eval, smoothed)', steps: '', distance_m: ev.truth_distance_m.toFixed(1) },
    ]);
    console.log(`TyrEx replay: the live track ends at (${stopped.end_m.map((v) => v.toFixed(1)).join(', ')}) m, `
      + `pdr run's of the recording at (${recorded.end.map((v) => v.toFixed(1)).join(', ')}) m, `
      + `the original's at (${original.end.map((v) => v.toFixed(1)).join(', ')}) m`);
    console.log(`TyrEx replay: live ${fmt(live)}; its recording ${fmt(recorded)}; original ${fmt(original)} `
      + `(live ${pct(live.distance_m, original.distance_m)}); truth ${ev.truth_distance_m.toFixed(1)} m `
      + `(live ${pct(live.distance_m, ev.truth_distance_m)}, original ${pct(original.distance_m, ev.truth_distance_m)}); `
      + `test wall time ${seconds.toFixed(0)} s`);

    assert.equal(live.refused, 0, live.last_error);
    // (devicemotion fires on after the walk, the last readings held, until Stop.)
    assert.equal(imu.length, stopped.samples, 'the recording is not the samples the page used');
    assert.ok(live.sample_rate_hz > 30, `the page received ${live.sample_rate_hz} Hz`);
    assert.equal(stopped.steps, recorded.steps,
      `stopped ${stopped.steps} steps, pdr run of its recording ${recorded.steps}`);
    assert.ok(Math.abs(stopped.distance_m - recorded.distance_m) < 1e-6,
      `stopped ${stopped.distance_m} m, pdr run of its recording ${recorded.distance_m} m`);
    // The track: where its last step ended (the CSV's metres have three decimals).
    const apart = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);
    assert.ok(apart(stopped.end_m, recorded.end) < 0.002, `stopped at ${stopped.end_m}, pdr run's track at ${recorded.end}`);
    assert.equal(live.steps, recorded.steps, `live ${live.steps} steps, pdr run of its recording ${recorded.steps}`);
    // Before Stop: the steps a bout's opening still holds are counted, not yet walked; none held, the same distance.
    const tolerance = live.held_steps === 0 ? 1e-6 : 0.01 * recorded.distance_m;
    assert.ok(Math.abs(live.distance_m - recorded.distance_m) <= tolerance,
      `live ${live.distance_m} m (${live.held_steps} steps held), pdr run of its recording ${recorded.distance_m} m`);
    assert.deepEqual(errors, []);
  });

/** A table row: steps and distance in m. */
function row(r) {
  return { steps: r.steps, distance_m: r.distance_m.toFixed(1) };
}
