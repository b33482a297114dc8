// End-to-end tests of live mode in a real headless Chromium, against `pdr serve`.
// A simulated walk (`pdr simulate --events`) is dispatched on the page as real DeviceMotionEvent
// and DeviceOrientationEvent objects at the walk's timestamps, faster than real time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, dispatch, dispatchRealTime, holdToUnlock, openPage, useBrowser, tempDir } from './util.mjs';

const tmp = tempDir('live');
const GEO = { latitude: 46.0037, longitude: 8.9511, accuracy: 12 }; // Lugano

/** A simulated walk as browser events of a platform: {truth_steps, distance_m, events}. */
function walk(scenario, platform) {
  const file = path.join(tmp, `${scenario}-${platform}.json`);
  execFileSync(BIN, ['simulate', '--scenario', scenario, '--platform', platform, '--events', file]);
  return JSON.parse(readFileSync(file, 'utf8'));
}

// A name that is not localhost: the page is then an insecure context, as on a LAN.
const browser = useBrowser(['--host-resolver-rules=MAP pdr-lan.test 127.0.0.1']);

/** Opens the page; `ios` makes it look like Safari (its user agent, and a motion permission prompt answering `permission`). */
const IPHONE_UA = 'Mozilla/5.0 (iPhone; CPU iPhone OS 18_1 like Mac OS X) AppleWebKit/605.1.15 (KHTML, like Gecko) Version/18.1 Mobile/15E148 Safari/604.1';

function open({ ios = false, permission = 'granted', context: options = {}, url = URL_HTTP, init } = {}) {
  const safari = [(answer) => {
    // Safari has no `deviceorientationabsolute`; it asks for motion permission.
    delete window.ondeviceorientationabsolute; // [Global]: on the window itself
    DeviceMotionEvent.requestPermission = async () => answer;
    DeviceOrientationEvent.requestPermission = async () => answer;
  }, permission];
  return openPage(browser(), url, {
    options: { ...PHONE, acceptDownloads: true, ...(ios ? { userAgent: IPHONE_UA } : {}), ...options },
    init: [...(init ? [init] : []), ...(ios ? [safari] : [])],
  });
}

/** Taps Start and waits until the page listens to motion events. */
async function start(page) {
  await page.click('#start');
  await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
}

const readouts = (page) => page.evaluate(() => window.__pdrTest?.live?.readouts);
const messages = (page) => page.$$eval('#live-messages li', (els) => els.map((e) => `${e.dataset.key}: ${e.textContent}`));

/** Pixels of a canvas differing from its corner, and the canvas's backing size. */
async function nonBlank(page, id) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 30) n++;
    return { n, total: d.length / 4, width: c.width, cssWidth: c.getBoundingClientRect().width };
  }, id);
}

/** Runs a whole walk through live mode; returns the page, the readouts and the walk. */
async function liveWalk({ ios }) {
  const w = walk('square', ios ? 'ios' : 'android');
  const session = await open({ ios, context: { geolocation: GEO, permissions: ['geolocation', 'accelerometer', 'gyroscope', 'magnetometer'] } });
  const { page } = session;
  await start(page);
  const base = await page.evaluate(() => performance.now());
  const half = Math.floor(w.events.length / 2);
  // A second at a time until the walk's first steps are held (the thigh has not said yet
  // which way is forward): what the heading's card says then.
  let opening = null;
  let i = 0;
  for (; i < half && !opening; i += 100) {
    await dispatch(page, w.events, { base, ios, from: i, to: Math.min(i + 100, half) });
    await page.waitForTimeout(150); // a redraw
    if ((await readouts(page)).held_steps > 0) {
      // The card follows at the next drawing tick (at most ten a second, later on a loaded
      // machine), not at the events: wait for it, then read the count and the card together.
      await page.waitForFunction(() => /waiting$/.test(document.getElementById('r-heading-ref').textContent),
        null, { timeout: 3000 }).catch(() => {});
      const r = await readouts(page);
      opening = { held: r.held_steps, steps: r.steps, ref: await page.textContent('#r-heading-ref') };
      await page.screenshot({ path: path.join(ARTIFACTS, `live-opening-${ios ? 'ios' : 'android'}.png`) });
    }
  }
  await dispatch(page, w.events, { base, ios, from: i, to: half });
  await page.waitForTimeout(150); // a redraw
  const mid = { shown: Number(await page.textContent('#g-steps')), steps: (await readouts(page)).steps };
  await dispatch(page, w.events, { base, ios, from: half });
  await page.waitForTimeout(300); // one more redraw
  return { ...session, w, mid, opening, r: await readouts(page) };
}

test('live walk: steps within 2 %, track drawn, readouts update, GNSS fix shown, pocket guard looks deliberate', async () => {
  const { context, page, w, r, mid, opening, errors } = await liveWalk({ ios: false });
  // The walk's first steps waited for their side, counted, and the heading's card said so.
  assert.ok(opening, 'no step was held at the walk\'s opening');
  assert.equal(opening.ref, `${opening.held} step${opening.held > 1 ? 's' : ''} waiting`);
  assert.ok(opening.steps >= opening.held, `${opening.steps} counted, ${opening.held} held`);
  // Halfway, the guard showed the steps so far.
  assert.ok(mid.shown > 0.3 * w.truth_steps && mid.shown < 0.7 * w.truth_steps, `halfway: ${mid.shown} shown`);
  assert.ok(Math.abs(mid.shown - mid.steps) <= 3, `halfway: ${mid.shown} shown, ${mid.steps} counted`);
  const err = Math.abs(r.steps - w.truth_steps) / w.truth_steps;
  console.log(`live walk (Android events): ${r.steps} steps of ${w.truth_steps} (${(100 * err).toFixed(1)} %), `
    + `${r.distance_m.toFixed(1)} m of ${w.distance_m.toFixed(1)} m, source ${await page.evaluate(() => window.__pdrTest.live.source)}`);
  assert.ok(err <= 0.02, `step count ${r.steps} against ${w.truth_steps}`);
  assert.equal(r.refused, 0, `refused events: ${r.last_error}`);
  assert.equal(r.orientation, 'os');
  assert.ok(r.absolute_heading);
  assert.ok(r.fixes >= 1 && Math.abs(r.gnss_accuracy_m - GEO.accuracy) < 1e-9, `fixes ${r.fixes}`);
  assert.deepEqual(errors, []);
  // The pocket guard is up: the readouts on it update, the page below cannot be touched.
  assert.equal(await page.isVisible('#guard'), true);
  assert.equal(await page.textContent('#g-steps'), String(r.steps));
  // The guard names the activity in words (and the floor change, none on a flat walk).
  assert.ok(['Walking', 'Still', 'Standing', 'Sitting', 'Running', 'Walking upstairs', 'Walking downstairs'].includes(r.activity), `activity ${r.activity}`);
  assert.equal(await page.textContent('#g-note'), [r.activity, r.floor_change].filter(Boolean).join(' · '));
  await page.screenshot({ path: path.join(ARTIFACTS, 'live-guard-phone.png') });
  await page.mouse.click(195, 400); // a stray touch
  await holdToUnlock(page, 600); // too short
  assert.equal(await page.isVisible('#guard'), true, 'a short press unlocked the guard');
  await holdToUnlock(page, 2300);
  await page.waitForFunction(() => document.documentElement.dataset.guard === 'off');
  await page.waitForTimeout(250);
  assert.equal(await page.textContent('#r-steps'), String(r.steps));
  assert.equal(await page.textContent('#r-gnss'), '±12 m');
  // The activity, then where the phone is carried once the engine decided ("Walking · In a pocket").
  assert.equal(await page.textContent('#r-motion'), [r.activity, r.carry].filter(Boolean).join(' · '));
  assert.equal(await page.textContent('#r-floor'), r.floor_change ?? 'start floor');
  assert.match(await page.textContent('#r-heading'), /^\d+° [NESW]{1,2}$/);
  assert.match(await page.textContent('#r-spm'), /^1\d\d steps\/min$/);
  // What the fusion learnt, ± 1σ, and its notice when it waits or distrusts the fixes (here
  // they stand still while the walker walks). The values are the filter's: their format only.
  console.log(`live walk: scale ${r.scale_text}, correction ${r.correction_text}, verdict ${r.gnss_verdict}`);
  assert.equal(await page.textContent('#r-scale'), r.scale_text ?? '–');
  if (r.scale_text != null) {
    assert.match(r.scale_text, /^\d\.\d\d ± \d\.\d\d$/);
    assert.match(await page.textContent('#r-correction'), /^heading −?\d+\.\d° ± \d+\.\d°$/);
  }
  assert.equal(await page.isVisible('#gnss-notice'), r.gnss_notice != null);
  if (r.gnss_notice) assert.equal(await page.textContent('#gnss-notice'), r.gnss_notice);
  assert.ok(['distrusted', 'waiting'].includes(r.gnss_verdict) === (r.gnss_notice != null), `verdict ${r.gnss_verdict}`);
  const map = await nonBlank(page, 'live-map');
  const scope = await nonBlank(page, 'live-scope');
  assert.ok(map.n > 0.02 * map.total, `map looks blank: ${map.n} of ${map.total}`);
  assert.ok(scope.n > 0.02 * scope.total, `scope looks blank: ${scope.n} of ${scope.total}`);
  assert.equal(map.width, Math.round(map.cssWidth * 3), 'the map is not drawn at the device pixel ratio');
  await page.locator('#live').screenshot({ path: path.join(ARTIFACTS, 'live-phone.png') });
  await context.close();
});

test('iOS-style events (sign flipped, interval in s, compass heading) give the Android result', async () => {
  const a = await liveWalk({ ios: false });
  const i = await liveWalk({ ios: true });
  console.log(`Android ${a.r.steps} steps ${a.r.distance_m.toFixed(3)} m; iOS ${i.r.steps} steps ${i.r.distance_m.toFixed(3)} m`);
  assert.equal(await i.page.evaluate(() => window.__pdrTest.live.source), 'devicemotion events');
  assert.equal(i.r.steps, a.r.steps);
  assert.ok(Math.abs(i.r.distance_m - a.r.distance_m) < 0.01);
  assert.ok(i.r.absolute_heading, 'the compass heading was not used');
  assert.ok(Math.abs(((i.r.heading_deg - a.r.heading_deg + 540) % 360) - 180) < 0.5, `${i.r.heading_deg} vs ${a.r.heading_deg}`);
  await a.context.close();
  await i.context.close();
});

test('Stop, download: the recording replays through `pdr run` to the same step count', async () => {
  const { context, page, r } = await liveWalk({ ios: false });
  await holdToUnlock(page, 2300);
  await page.click('#stop');
  await page.waitForFunction(() => document.documentElement.dataset.live === 'stopped');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
  const file = path.join(tmp, dl.suggestedFilename());
  await dl.saveAs(file);
  assert.match(dl.suggestedFilename(), /^pdr-.*\.pdrlog$/);
  const out = execFileSync(BIN, ['run', file], { encoding: 'utf8' });
  const steps = Number(out.match(/^steps\s+(\d+)/m)[1]);
  console.log(`downloaded ${dl.suggestedFilename()}: pdr run counts ${steps}, the page showed ${r.steps}`);
  assert.equal(steps, r.steps);
  // And through the engine in the page (the upload path's replay).
  const inPage = await page.evaluate(async (text) => {
    const { replay_log } = await import('./www/pkg/pdr.js');
    return replay_log(text);
  }, readFileSync(file, 'utf8'));
  assert.equal(inPage.steps, r.steps);
  assert.equal(inPage.skipped_lines, 0);
  await page.screenshot({ path: path.join(ARTIFACTS, 'live-stopped-phone.png'), fullPage: true });
  await context.close();
});

test('reload while recording: the recovery offer holds every sample, and resuming continues the walk', async () => {
  const w = walk('square', 'android');
  const { context, page } = await open();
  await start(page);
  const half = Math.floor(w.events.length / 2);
  // The first half's timestamps end now, so that the reloaded page's clock comes after them.
  const base = await page.evaluate((d) => performance.now() - d, w.events[half - 1].t + 20);
  await dispatch(page, w.events, { base, to: half });
  const before = (await readouts(page)).samples;
  await page.reload(); // at once: the last batch is written on pagehide
  await page.waitForFunction(() => document.documentElement.dataset.recovery === 'offered', null, { timeout: 10_000 });
  const offered = await page.evaluate(() => window.__pdrTest.recovery);
  console.log(`recovery after reload: ${offered.samples} samples recorded of ${before} sent`);
  assert.equal(offered.samples, before);
  assert.match(await page.textContent('#recovery-text'), new RegExp(`\\(${before} samples, \\d+ steps\\)`));
  await page.click('#recover-resume');
  await page.waitForFunction(() => document.documentElement.dataset.source);
  const resumed = await readouts(page);
  assert.equal(resumed.samples, before);
  // The second half, on the new page's clock, after a pause.
  const base2 = await page.evaluate(() => performance.now());
  await dispatch(page, w.events, { base: base2 - w.events[half].t, from: half });
  await page.waitForTimeout(250);
  const r = await readouts(page);
  assert.ok(r.gaps >= 1, 'the reload is not a gap');
  assert.ok(Math.abs(r.steps - w.truth_steps) <= 0.04 * w.truth_steps, `${r.steps} of ${w.truth_steps}`);
  await context.close();
});

test('a hidden page is a gap on the track, not phantom steps', async () => {
  const w = walk('straight', 'android');
  const { context, page } = await open();
  await start(page);
  const third = Math.floor(w.events.length / 3);
  // The first third's timestamps end now.
  const base = await page.evaluate((d) => performance.now() - d, w.events[third - 1].t + 20);
  await dispatch(page, w.events, { base, to: third });
  await page.evaluate(() => {
    Object.defineProperty(document, 'visibilityState', { value: 'hidden', configurable: true });
    document.dispatchEvent(new Event('visibilitychange'));
  });
  await page.waitForTimeout(500); // hidden: no events
  await page.evaluate(() => {
    Object.defineProperty(document, 'visibilityState', { value: 'visible', configurable: true });
    document.dispatchEvent(new Event('visibilitychange'));
  });
  const back = await page.evaluate(() => performance.now());
  // The walk goes on, skipping the second third (walked while hidden).
  await dispatch(page, w.events, { base: back + 100 - w.events[2 * third].t, from: 2 * third });
  await page.waitForTimeout(250);
  const r = await readouts(page);
  assert.equal(r.gaps, 1);
  assert.ok(r.steps < 0.75 * w.truth_steps, `${r.steps} steps: the hidden third was bridged`);
  assert.match(await page.textContent('#r-time'), /1 gap/);
  await context.close();
});

test('energy saving: the geolocation watch is really stopped between windows and started again', async () => {
  const w = walk('straight', 'android');
  // A spy on the real geolocation: every watchPosition, clearWatch and delivered fix, on the page's clock.
  const spy = () => {
    const g = navigator.geolocation;
    const watch = g.watchPosition.bind(g);
    const clear = g.clearWatch.bind(g);
    window.__geo = [];
    g.watchPosition = (ok, fail, opts) => {
      const id = watch((p) => { window.__geo.push({ what: 'fix', t: performance.now() }); ok(p); }, fail, opts);
      window.__geo.push({ what: 'watch', t: performance.now() });
      return id;
    };
    g.clearWatch = (id) => { window.__geo.push({ what: 'clear', t: performance.now() }); clear(id); };
  };
  const fixAt = ([, east, north]) => ({
    latitude: GEO.latitude + north / 111_320,
    longitude: GEO.longitude + east / (111_320 * Math.cos(GEO.latitude * Math.PI / 180)),
    accuracy: 1,
  });
  const { context, page, errors } = await open({
    init: spy,
    context: { geolocation: fixAt(w.path[0]), permissions: ['geolocation', 'accelerometer', 'gyroscope', 'magnetometer'] },
  });
  await page.selectOption('#gnss-mode', 'energy_saving');
  assert.equal(await page.isVisible('#duty'), true, 'the window and period inputs are hidden');
  const WINDOW = 3;
  const PERIOD = 8;
  await page.fill('#gnss-window', String(WINDOW));
  await page.fill('#gnss-period', String(PERIOD));
  await start(page);
  assert.equal(await page.isDisabled('#gnss-period'), true);
  const base = await page.evaluate(() => performance.now());
  await dispatchRealTime(page, w.events, base);
  // Walk in real time, the browser's location following the true path, until the watch has
  // been stopped and started again twice after the receiver's calibration. Chromium delivers a
  // fix at each change of its location override: here about four a second, which lets the
  // filter learn the scale and heading correction within the 70 s walk.
  const count = (log, what) => log.filter((e) => e.what === what).length;
  let log = [];
  for (let now = 0; now < w.events.at(-1).t; now = (await page.evaluate(() => performance.now())) - base) {
    await context.setGeolocation(fixAt(w.path.find((p) => p[0] >= now) ?? w.path.at(-1)));
    log = await page.evaluate(() => window.__geo);
    if (count(log, 'clear') >= 2 && count(log, 'watch') >= 3) break;
    await page.waitForTimeout(250);
  }
  const r = await readouts(page);
  const fixesText = await page.textContent('#r-fixes');
  await page.evaluate(() => { window.__pdrWalked = Infinity; }); // the walk stops here
  const rel = log.map((e) => ({ ...e, t: (e.t - base) / 1000 }));
  const watches = rel.filter((e) => e.what === 'watch');
  const clears = rel.filter((e) => e.what === 'clear');
  console.log(`energy saving ${WINDOW} s every ${PERIOD} s: watch at ${watches.map((e) => e.t.toFixed(1)).join(', ')} s; `
    + `cleared at ${clears.map((e) => e.t.toFixed(1)).join(', ')} s; ${count(log, 'fix')} fixes delivered, ${r.fixes} used; `
    + `receiver on ${r.gnss_on_s?.[0].toFixed(1)} of ${r.gnss_on_s?.[1].toFixed(1)} s; "${fixesText}"`);
  assert.ok(clears.length >= 2 && watches.length >= 3, 'the watch was not stopped and started again twice');
  // Watches and clears alternate, and no fix arrives while the watch is stopped.
  let on = false;
  for (const e of rel) {
    if (e.what === 'watch') { assert.equal(on, false, `a second watch at ${e.t} s`); on = true; }
    if (e.what === 'clear') { assert.equal(on, true, `a clear without a watch at ${e.t} s`); on = false; }
    if (e.what === 'fix') assert.equal(on, true, `a fix at ${e.t} s while the watch was stopped`);
  }
  // After calibration (the first watch), the receiver is off for period − window and on for the window.
  for (let k = 1; k < clears.length; k++) {
    const off = watches[k].t - clears[k - 1].t;
    const onFor = clears[k].t - watches[k].t;
    assert.ok(Math.abs(off - (PERIOD - WINDOW)) < 1.5, `off for ${off.toFixed(1)} s, not ${PERIOD - WINDOW} s`);
    assert.ok(Math.abs(onFor - WINDOW) < 1.5, `on for ${onFor.toFixed(1)} s, not ${WINDOW} s`);
  }
  // The saving is shown.
  assert.ok(r.gnss_on_s[0] < r.gnss_on_s[1] - PERIOD + WINDOW, `on ${r.gnss_on_s}`);
  assert.match(fixesText, /^\d+ fixes( · off)? · on \d+ %$/);
  // The fixes follow the walk: the fusion has a scale and a correction, each ± 1σ.
  assert.match(r.scale_text ?? '', /^\d\.\d\d ± \d\.\d\d$/);
  assert.match(r.correction_text ?? '', /^−?\d+\.\d° ± \d+\.\d°$/);
  assert.match(await page.getAttribute('#r-fixes', 'title'), /on \d+:\d\d of the \d+:\d\d since the first fix/);
  assert.deepEqual(errors, []);
  await holdToUnlock(page, 2300);
  await page.waitForFunction(() => document.documentElement.dataset.guard === 'off');
  await page.locator('#live').screenshot({ path: path.join(ARTIFACTS, 'live-energy-phone.png') });
  await context.close();
});

test('two taps on Start while the permission prompt is open start one recording', async () => {
  // A prompt the user answers after half a second, as on iOS.
  const { context, page } = await open({ init: () => {
    DeviceMotionEvent.requestPermission = () => new Promise((resolve) => setTimeout(() => resolve('granted'), 500));
  } });
  await page.click('#start');
  await page.waitForTimeout(100); // the second tap, on another millisecond: another recording's id
  await page.click('#start');
  await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
  await page.waitForTimeout(500); // the second tap's prompt, had it been asked, has been answered
  const recordings = await page.evaluate(async () => (await import('./www/store.js')).list());
  assert.equal(recordings.filter((r) => r.state === 'recording').length, 1, JSON.stringify(recordings));
  await context.close();
});

test('permission denied, no sensors, no location, insecure page: each says what to do', async () => {
  // iOS, motion refused.
  {
    const { context, page } = await open({ ios: true, permission: 'denied' });
    await page.click('#start');
    await page.waitForSelector('#live-messages li[data-key="motionDenied"]');
    assert.match((await messages(page)).join('\n'), /Motion access was refused.*tap Start again/);
    assert.equal(await page.isVisible('#guard'), false);
    await page.screenshot({ path: path.join(ARTIFACTS, 'live-denied-phone.png') });
    await context.close();
  }
  // No motion events at all, and location refused.
  {
    // Every change of the message list, with the page's clock, for a failure to show.
    const { context, page } = await open({ init: () => document.addEventListener('DOMContentLoaded', () => {
      window.__messageHistory = [];
      new MutationObserver(() => {
        const keys = [...document.querySelectorAll('#live-messages li')].map((e) => e.dataset.key);
        window.__messageHistory.push(`${performance.now().toFixed(0)} ms: [${keys.join(', ')}] samples ${window.__pdrTest?.live?.readouts?.samples}`);
      }).observe(document.getElementById('live-messages'), { childList: true });
    }) });
    await start(page);
    await page.waitForSelector('#live-messages li[data-key="noSensor"]', { timeout: 10_000 });
    await page.waitForSelector('#live-messages li[data-key="locationDenied"]', { timeout: 10_000 });
    const m = (await messages(page)).join('\n');
    const r = await readouts(page);
    const seen = `messages:\n${m}\nsamples ${r.samples}, refused ${r.refused} (${r.last_error})\n` +
      (await page.evaluate(() => window.__messageHistory ?? [])).join('\n');
    assert.match(m, /No motion data has arrived/, seen);
    assert.match(m, /Location was refused.*allow location/, seen);
    await context.close();
  }
  // Energy saving with a window longer than its period: refused, naming the setting.
  {
    const { context, page } = await open();
    await page.selectOption('#gnss-mode', 'energy_saving');
    await page.fill('#gnss-window', '20');
    await page.fill('#gnss-period', '10');
    await page.click('#start');
    await page.waitForSelector('#live-messages li[data-key="cannotStart"]');
    assert.match((await messages(page)).join('\n'), /could not start.*fusion\.mode\.window_s.*period_s/);
    assert.equal(await page.isVisible('#guard'), false);
    assert.equal(await page.isVisible('#start'), true);
    await context.close();
  }
  // HTTP on a LAN name: not a secure context.
  {
    const lan = URL_HTTP.replace('127.0.0.1', 'pdr-lan.test');
    const { context, page } = await open({ url: lan });
    assert.equal(await page.evaluate(() => window.isSecureContext), false);
    assert.match((await messages(page)).join('\n'), /need a secure page.*https:\/\//);
    assert.equal(await page.isDisabled('#start'), true);
    await context.close();
  }
});

test('Chromium virtual sensors: the page reads the Generic Sensor API', async () => {
  const { context, page, errors } = await open({ context: { permissions: ['accelerometer', 'gyroscope', 'magnetometer'] } });
  const cdp = await context.newCDPSession(page);
  for (const type of ['accelerometer', 'linear-acceleration', 'gravity', 'gyroscope', 'absolute-orientation', 'relative-orientation']) {
    await cdp.send('Emulation.setSensorOverrideEnabled', { enabled: true, type });
  }
  const xyz = (type, x, y, z) => cdp.send('Emulation.setSensorOverrideReadings', { type, reading: { xyz: { x, y, z } } });
  await xyz('accelerometer', 0.3, -0.2, 9.81);
  await xyz('linear-acceleration', 0.3, -0.2, 0);
  await xyz('gravity', 0, 0, 9.81);
  await xyz('gyroscope', 0.01, 0.02, 0.03);
  for (const type of ['absolute-orientation', 'relative-orientation']) {
    await cdp.send('Emulation.setSensorOverrideReadings', { type, reading: { quaternion: { x: 0, y: 0, z: 0.3826834, w: 0.9238795 } } });
  }
  await start(page);
  assert.equal(await page.evaluate(() => document.documentElement.dataset.source), 'sensors');
  // A Generic Sensor fires `reading` only when the value changes: a phone's noise, here a wobble.
  // Its rate is this loop's, which a loaded machine slows: the page's rate readout (over its
  // last 2 s of samples) is checked against the samples it counted per second over the same
  // span of the page's clock.
  const counted = () => page.evaluate(() => [window.__pdrTest.live.readouts.samples, performance.now()]);
  const marks = [];
  for (let i = 0; i < 150 && (await readouts(page)).samples <= 30; i++) {
    await xyz('accelerometer', 0.3, -0.2, 9.81 + 0.05 * (i % 2));
    await xyz('gyroscope', 0.01, 0.02, 0.03 + 0.001 * (i % 2));
    await page.waitForTimeout(15);
    marks.push(await counted());
  }
  const r = await readouts(page);
  assert.ok(r.samples > 30, `${r.samples} samples`);
  const last = marks[marks.length - 1];
  const from = marks.find(([n, t]) => n >= 5 && t >= last[1] - 2000);
  const rate = ((last[0] - from[0]) / (last[1] - from[1])) * 1000;
  console.log(`Generic Sensor API: ${r.sample_rate_hz.toFixed(0)} Hz (counted ${rate.toFixed(0)}), orientation ${r.orientation}`);
  assert.equal(r.orientation, 'os');
  assert.ok(r.absolute_heading);
  assert.ok(Math.abs(r.sample_rate_hz / rate - 1) < 0.35, `rate ${r.sample_rate_hz} Hz, counted ${rate} Hz`);
  assert.equal(r.refused, 0, r.last_error);
  assert.deepEqual(errors, []);
  await context.close();
});

test('installable and private: manifest, service worker, offline reload, CSP', async () => {
  const { context, page, errors } = await open({ context: { viewport: { width: 1000, height: 800 } } });
  const manifest = await page.evaluate(async () => {
    const href = document.querySelector('link[rel=manifest]').href;
    return (await fetch(href)).json();
  });
  assert.equal(manifest.display, 'standalone');
  assert.ok(manifest.icons.length >= 1);
  await page.waitForFunction(async () => {
    const reg = await navigator.serviceWorker.getRegistration();
    return reg?.active?.state === 'activated';
  }, null, { timeout: 15_000, polling: 200 });
  await page.reload();
  await page.waitForFunction(() => !!navigator.serviceWorker.controller);
  await context.setOffline(true);
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.state === 'ready', null, { timeout: 30_000 });
  assert.ok(await page.isVisible('#start'));
  await context.setOffline(false);
  const csp = await page.getAttribute('meta[http-equiv="Content-Security-Policy"]', 'content');
  assert.match(csp, /default-src 'self'/);
  assert.match(csp, /connect-src 'self'/);
  assert.doesNotMatch(csp, /unsafe-inline|http:/);
  // Only images may come from another origin (https:, for the opt-in base map's tiles; see the
  // README's "Base map"); every other directive stays on the page's origin.
  const directives = Object.fromEntries(csp.split(';').map((d) => d.trim().split(/\s+/)).filter((d) => d[0]).map(([k, ...v]) => [k, v]));
  assert.deepEqual(directives['img-src'], ["'self'", 'data:', 'blob:', 'https:']);
  for (const [k, v] of Object.entries(directives)) {
    if (k !== 'img-src') assert.ok(!v.some((x) => /^https?:|^\*/.test(x)), `${k} ${v.join(' ')} allows another origin`);
  }
  assert.match(await page.textContent('#live .lede'), /never leave/);
  assert.deepEqual(errors, []);
  await context.close();
});
