// End-to-end test of the step-length calibration wizard in headless Chromium: three paces walked
// (simulated motion events dispatched on the page) over a typed distance, the fit, the saved
// profile, a replay with it, and a profile's export and import.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, dispatch, holdToUnlock, openPage, useBrowser, tempDir } from './util.mjs';

const tmp = tempDir('wizard');
// The walker: SL = 0.30·f + 0.20 m, longer steps than the built-in profile's 0.25·f + 0.17.
const A = 0.30;
const B = 0.20;
const METRES = 40;

function simulate(cadence, metres, out) {
  const file = path.join(tmp, out);
  const kind = out.endsWith('.json') ? '--events' : '--out';
  execFileSync(BIN, ['simulate', '--scenario', 'calibration', '--cadence', String(cadence), '--metres', String(metres),
    '--sl-a', String(A), '--sl-b', String(B), kind, file]);
  return readFileSync(file, 'utf8');
}

const browser = useBrowser();

/** Holds the pocket guard's unlock button until the guard is off. */
async function unlock(page) {
  await holdToUnlock(page, 2300);
  await page.waitForFunction(() => document.documentElement.dataset.guard === 'off');
}

test('calibration wizard: three paces over a typed distance give the walker\'s line, a saved profile that fixes the distance, and a profile survives export and import', async () => {
  const { context, page, errors } = await openPage(browser(), URL_HTTP, {
    options: { ...PHONE, acceptDownloads: true, permissions: ['accelerometer', 'gyroscope', 'magnetometer'] },
  });
  await page.click('#cal-open');
  await page.fill('#cal-distance', String(METRES));
  await page.locator('#calibrate').screenshot({ path: path.join(ARTIFACTS, 'wizard-1-start-phone.png') });

  for (const [pace, cadence] of [['slow', 1.5], ['normal', 1.8], ['fast', 2.1]]) {
    const w = JSON.parse(simulate(cadence, METRES, `${pace}.json`));
    // The walker takes whole steps: the measured distance is that of the simulated walk.
    await page.fill('#cal-distance', w.distance_m.toFixed(1));
    await page.click(`tr[data-pace="${pace}"] button`);
    await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
    assert.equal(await page.isVisible('#guard'), true, 'no pocket guard during a calibration walk');
    assert.match(await page.textContent('#guard-title'), new RegExp(`Calibration, ${pace} walk`));
    if (pace === 'slow') await page.screenshot({ path: path.join(ARTIFACTS, 'wizard-2-walking-phone.png') });
    await dispatch(page, w.events, { base: await page.evaluate(() => performance.now()) });
    await unlock(page);
    await page.click(`tr[data-pace="${pace}"] button`);
    await page.waitForFunction(() => document.documentElement.dataset.calibration === 'walked');
    const result = await page.textContent(`tr[data-pace="${pace}"] .result`);
    console.log(`${pace}: ${result}`);
    const n = Number(result.match(/N = (\d+) steps/)[1]);
    assert.ok(Math.abs(n - w.truth_steps) <= 1, `${pace}: ${n} steps of ${w.truth_steps}`);
    assert.match(result, /f̄ = \d\.\d\d Hz \(eq\. 1\) · SL̄ = D\/N = \d\.\d{3} m \(eq\. 2\)/);
  }
  const st = await page.evaluate(() => window.__pdrTest.calibration);
  console.log(`fit: a ${st.walking.a.toFixed(4)} (true ${A}), b ${st.walking.b.toFixed(4)} (true ${B}), R² ${st.walking.r2.toFixed(4)}`);
  assert.ok(Math.abs(st.walking.a - A) < 0.02 * A, `a = ${st.walking.a}`);
  assert.ok(Math.abs(st.walking.b - B) < 0.02 * B, `b = ${st.walking.b}`);
  assert.deepEqual(st.walking.warnings, []);
  const chart = await page.evaluate(() => {
    const c = document.getElementById('cal-chart-walking');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 30) n++;
    return { n, total: d.length / 4 };
  });
  assert.ok(chart.n > 0.02 * chart.total, `fit chart looks blank: ${chart.n} of ${chart.total}`);
  assert.deepEqual(errors, []);
  await page.locator('#cal-wizard').screenshot({ path: path.join(ARTIFACTS, 'wizard-3-fit-phone.png') });

  // Save: stored, selected, shown.
  await page.fill('#cal-name', 'tester');
  await page.click('#cal-save');
  await page.waitForFunction(() => document.documentElement.dataset.profile === 'saved');
  const saved = await page.evaluate(() => JSON.parse(localStorage.getItem('pdr-profiles')).tester);
  assert.ok(saved, 'the profile was not saved');
  assert.equal(await page.evaluate(() => localStorage.getItem('pdr-profile')), 'tester');
  assert.equal(await page.textContent('#profile-in-use'), 'tester');
  assert.match(await page.textContent('#profile-values'), /Walking SL = 0\.\d{3}·f/);
  // The walks measured the fuzzy lengths too: the profile carries the fitted fuzzy scale, and
  // the wizard shows it.
  const k = JSON.parse(saved).fuzzy_scale;
  console.log(`fuzzy scale: k ${k}`);
  assert.ok(Number.isFinite(k) && k > 0.5 && k < 2, `fuzzy_scale ${k}`);
  assert.ok(Math.abs(st.fuzzy_scale - k) < 1e-12, `state ${st.fuzzy_scale}, saved ${k}`);
  assert.match(await page.textContent('#cal-notes'), /fuzzy step length \(Ibarra 2015\): scale k = \d\.\d{3}/);
  assert.match(await page.textContent('#profile-values'), /Fuzzy scale k = \d\.\d{3}/);
  // The leg-pitch calibration (Munoz Diaz 2015 §5.1) after the normal walk: given when its
  // steps had a leg pitch (then saved with the profile), else refused with the reason.
  const pitchState = await page.getAttribute('#cal-pitch', 'data-pitch');
  console.log(`pitch calibration: ${pitchState}: ${await page.textContent('#cal-pitch')}`);
  if (pitchState === 'ok') {
    assert.ok(Number.isFinite(JSON.parse(saved).pitch_offset_m), 'the pitch offset was not saved');
  } else {
    assert.equal(pitchState, 'refused');
    assert.match(await page.textContent('#cal-pitch'), /not calibrated: .*leg pitch.*pocket/);
    assert.equal(JSON.parse(saved).pitch_offset_m, undefined);
  }
  // The engine's one-walk formula on synthetic strides: b comes back exactly, is saved beside
  // the lines and read back; a walk without a leg pitch is refused.
  const pitch = await page.evaluate(async (profile) => {
    const { pitch_calibration, profile_with_pitch_offset, profile_summary } = await import('./www/pkg/pdr.js');
    const strides = Array.from({ length: 30 }, (_, k) => 30 + 0.5 * k);
    const a = 0.0314;
    const distance = strides.reduce((s, d) => s + a * d + 0.17, 0);
    const r = pitch_calibration(distance, strides.flatMap((d) => [d, d]));
    const json = profile_with_pitch_offset(profile, r.offset_m);
    return { r, back: profile_summary(json).pitch_offset_m, none: pitch_calibration(40, Array(60).fill(NaN)) };
  }, saved);
  assert.ok(pitch.r.ok && Math.abs(pitch.r.offset_m - 0.17) < 1e-9, JSON.stringify(pitch.r));
  assert.equal(pitch.back, pitch.r.offset_m);
  assert.equal(pitch.none.ok, false);
  assert.match(pitch.none.why, /leg pitch/);

  // Another walk by the same walker, replayed with and without the profile.
  const other = simulate(1.7, 120, 'other.pdrlog');
  const [withProfile, builtIn] = await page.evaluate(async ({ text, profile }) => {
    const { replay_log } = await import('./www/pkg/pdr.js');
    return [replay_log(text, { profile }), replay_log(text, undefined)];
  }, { text: other, profile: saved });
  const errWith = Math.abs(withProfile.distance_m - 120) / 120;
  const errBuiltIn = Math.abs(builtIn.distance_m - 120) / 120;
  console.log(`120 m at 1.7 Hz: ${withProfile.distance_m.toFixed(1)} m with the profile (${(100 * errWith).toFixed(1)} %), `
    + `${builtIn.distance_m.toFixed(1)} m built-in (${(100 * errBuiltIn).toFixed(1)} %)`);
  assert.ok(errWith < 0.02, `with the profile: ${(100 * errWith).toFixed(1)} %`);
  assert.ok(errBuiltIn > 0.08, `built-in: ${(100 * errBuiltIn).toFixed(1)} %`);
  // Upload mode uses the selected profile.
  await page.setInputFiles('#upload-files', path.join(tmp, 'other.pdrlog'));
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done' && window.__pdrTest.upload.logs[0]?.a);
  const uploaded = await page.evaluate(() => window.__pdrTest.upload.logs[0].a.score.distance_m);
  assert.ok(Math.abs(uploaded - withProfile.distance_m) < 1e-9, `upload with the profile: ${uploaded} m`);
  // The fuzzy model with the profile applies its scale: the replay with the fuzzy model and the
  // profile, and upload mode's rerun with the fuzzy model chosen, agree and measure 120 m.
  const fuzzy = await page.evaluate(async ({ text, profile }) => {
    const { replay_log } = await import('./www/pkg/pdr.js');
    const set = { 'step_length.kind': 'fuzzy' };
    return [replay_log(text, { set, profile }), replay_log(text, { set })];
  }, { text: other, profile: saved });
  const errFuzzy = Math.abs(fuzzy[0].distance_m - 120) / 120;
  console.log(`120 m at 1.7 Hz, fuzzy: ${fuzzy[0].distance_m.toFixed(1)} m with the profile's scale (${(100 * errFuzzy).toFixed(1)} %), `
    + `${fuzzy[1].distance_m.toFixed(1)} m unscaled`);
  assert.ok(errFuzzy < 0.03, `fuzzy with the profile: ${(100 * errFuzzy).toFixed(1)} %`);
  await page.selectOption('.config[data-config="a"] [name="step_length.kind"]', 'fuzzy');
  await page.click('#rerun');
  await page.waitForFunction((d) => Math.abs(window.__pdrTest.upload.logs[0].a.score.distance_m - d) < 1e-9, fuzzy[0].distance_m, { timeout: 20_000 });
  await page.selectOption('.config[data-config="a"] [name="step_length.kind"]', 'frequency');
  // Re-run with the built-in step length chosen instead: the distance becomes the built-in one.
  await page.selectOption('.config[data-config="a"] [name=profile]', '');
  await page.click('#rerun');
  await page.waitForFunction((d) => Math.abs(window.__pdrTest.upload.logs[0].a.score.distance_m - d) < 1e-9, builtIn.distance_m, { timeout: 20_000 });

  // Export, delete, import: the same profile back.
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#profile-export')]);
  const file = path.join(tmp, dl.suggestedFilename());
  await dl.saveAs(file);
  assert.equal(readFileSync(file, 'utf8'), saved);
  assert.equal(JSON.parse(saved).version, 1);
  await page.click('#profile-delete');
  assert.equal(await page.evaluate(() => localStorage.getItem('pdr-profiles')), '{}');
  await page.setInputFiles('#profile-import', file);
  await page.waitForFunction(() => JSON.parse(localStorage.getItem('pdr-profiles') ?? '{}').tester);
  assert.equal(await page.evaluate(() => JSON.parse(localStorage.getItem('pdr-profiles')).tester), saved);
  assert.equal(await page.textContent('#profile-in-use'), 'tester');
  // A damaged file is refused with the field named.
  const bad = path.join(tmp, 'bad.json');
  execFileSync('sh', ['-c', `sed 's/"version": 1/"version": 9/' '${file}' > '${bad}'`]);
  await page.setInputFiles('#profile-import', bad);
  await page.waitForSelector('#profile-messages li.error');
  assert.match(await page.textContent('#profile-messages li.error'), /bad\.json: .*profile\.version/);
  // Opt-in refinement after a live walk whose fusion learnt a step-length scale of 0.95 ± 0.01
  // over 40 fixes used, the filter calibrated (the event live mode sends at Stop): b moves
  // halfway, and Undo restores it.
  const before = JSON.parse(saved).profile.walking.b;
  const ended = (k, sd = 0.01, verdict = 'calibrated') => page.evaluate(([k, sd, verdict]) => window.dispatchEvent(new CustomEvent('pdr-walk-ended', {
    detail: { evidence: { fixes: 40, fixes_used: 40, verdict, scale: [k, sd], step_freqs_hz: Array(100).fill(1.8) } },
  })), [k, sd, verdict]);
  await ended(0.95);
  assert.equal(await page.evaluate(() => document.querySelectorAll('#profile-messages li[data-key="refined"]').length), 0,
    'refined without the opt-in');
  await page.check('#refine');
  // A scale the fixes did not make certain, or a filter that distrusted them, refines nothing
  // and says why.
  const notRefined = '#profile-messages li[data-key="not-refined"]';
  await ended(0.81, 0.06);
  await page.waitForSelector(notRefined);
  assert.match(await page.textContent(notRefined), /not certain enough of your step length: scale \d\.\d\d ± \d\.\d\d/);
  await ended(0.95, 0.01, 'distrusted');
  assert.match(await page.textContent(notRefined), /GNSS disagreed with your steps/);
  assert.equal(await page.evaluate(() => JSON.parse(localStorage.getItem('pdr-profiles')).tester), saved, 'refused walks left the profile');
  await ended(0.95);
  assert.equal(await page.evaluate((s) => document.querySelectorAll(s).length, notRefined), 0, 'the reason stays after a refinement');
  await page.waitForSelector('#profile-messages li[data-key="refined"]');
  const refined = await page.evaluate(() => JSON.parse(JSON.parse(localStorage.getItem('pdr-profiles')).tester).profile.walking);
  const sl = A * 1.8 + B; // about the profile's SL at 1.8 Hz
  console.log(`refinement: b ${before.toFixed(4)} → ${refined.b.toFixed(4)} m`);
  assert.ok(Math.abs(refined.b - (before - 0.5 * 0.05 * sl)) < 0.005, `b ${refined.b}`);
  assert.match(await page.textContent('#profile-messages li[data-key="refined"]'), /walking offset b .* → .* m/);
  await page.locator('#calibrate .profiles').screenshot({ path: path.join(ARTIFACTS, 'wizard-4-profiles-phone.png') });
  await page.click('#profile-messages li[data-key="refined"] button');
  assert.equal(await page.evaluate(() => JSON.parse(localStorage.getItem('pdr-profiles')).tester), saved);
  assert.deepEqual(errors, []);
  await context.close();
});
