// End-to-end test of the calibration wizard's walk from a recording, in headless Chromium: a
// recorded walk of a typed distance is opened in the wizard, the engine counts its steps, the
// profile is saved as the live walks' is, and upload mode then measures another walk of the
// same walker with it. A file that is not a recording, or no distance, is refused in words.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, openPage, useBrowser, tempDir } from './util.mjs';

const tmp = tempDir('wizard-recording');
// The walker: SL = 0.30·f + 0.20 m, longer steps than the built-in profile's 0.25·f + 0.17.
const A = 0.30;
const B = 0.20;

/** A simulated calibration walk written as a pdr-log, and its truth (steps, distance). */
function simulate(cadence, metres, name) {
  const file = path.join(tmp, `${name}.pdrlog`);
  const events = path.join(tmp, `${name}.json`);
  execFileSync(BIN, ['simulate', '--scenario', 'calibration', '--cadence', String(cadence), '--metres', String(metres),
    '--sl-a', String(A), '--sl-b', String(B), '--out', file, '--events', events]);
  const { truth_steps, distance_m } = JSON.parse(readFileSync(events, 'utf8'));
  return { file, truth_steps, distance_m };
}

const browser = useBrowser();

test('calibration wizard: a recorded walk of a typed distance makes a profile that is saved and applied', async () => {
  const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: PHONE });
  await page.click('#cal-open');
  const result = '#cal-recording-result';

  // Refusals: no distance typed, then a file that is not a recording, named.
  const walk = simulate(1.8, 60, 'normal');
  await page.fill('#cal-distance', '');
  await page.setInputFiles('#cal-recording', walk.file);
  await page.waitForFunction((s) => document.querySelector(s).classList.contains('error'), result);
  assert.equal(await page.textContent(result), 'Type the distance in metres first.');
  const notes = path.join(tmp, 'notes.txt');
  writeFileSync(notes, 'shopping list\n');
  await page.fill('#cal-distance', '60');
  await page.setInputFiles('#cal-recording', notes);
  await page.waitForFunction((s) => /notes\.txt/.test(document.querySelector(s).textContent), result);
  assert.match(await page.textContent(result), /^notes\.txt: no recording the app reads/);
  assert.equal(await page.isDisabled('#cal-save'), true, 'a refused file added a walk');

  // The walk: its steps counted by the engine, one point of the walking line (quick mode).
  await page.fill('#cal-distance', walk.distance_m.toFixed(2));
  await page.setInputFiles('#cal-recording', walk.file);
  await page.waitForFunction((s) => /N = \d+ steps/.test(document.querySelector(s).textContent), result);
  const text = await page.textContent(result);
  console.log(`recording: ${text}`);
  assert.match(text, /^normal\.pdrlog: N = \d+ steps over \d+\.\d m · f̄ = 1\.\d\d Hz \(eq\. 1\)/);
  assert.match(text, /the engine measured \d+\.\d m before calibration$/);
  const n = Number(text.match(/N = (\d+) steps/)[1]);
  assert.ok(Math.abs(n - walk.truth_steps) <= 1, `${n} steps of ${walk.truth_steps}`);
  const st = await page.evaluate(() => window.__pdrTest.calibration);
  assert.equal(st.walking.points, 1);
  assert.equal(st.walks[0].pace, 'recording');
  assert.match(await page.textContent('#cal-notes'), /walking: quick mode, slope 0\.25 m\/Hz kept, offset from 1 walk/);
  assert.equal(await page.isDisabled('#cal-save'), false);
  await page.locator('#cal-wizard').screenshot({ path: path.join(ARTIFACTS, 'wizard-recording-phone.png') });

  // Saved and selected as the live wizard's profile is.
  await page.fill('#cal-name', 'recorded');
  await page.click('#cal-save');
  await page.waitForFunction(() => document.documentElement.dataset.profile === 'saved');
  const saved = await page.evaluate(() => JSON.parse(localStorage.getItem('pdr-profiles') ?? '{}').recorded);
  assert.ok(saved, 'the profile was not saved');
  const profile = JSON.parse(saved);
  assert.equal(profile.version, 1);
  assert.equal(profile.walking_points.length, 1);
  assert.ok(Number.isFinite(profile.fuzzy_scale), 'the recording measured no fuzzy lengths');
  assert.equal(await page.evaluate(() => localStorage.getItem('pdr-profile')), 'recorded');
  assert.equal(await page.textContent('#profile-in-use'), 'recorded');
  assert.match(await page.textContent('#profile-values'), /Walking SL = 0\.250·f \+ 0\.\d{3} m \(1 walks\)/);

  // Applied: upload mode measures another walk at the same pace with the profile.
  const other = simulate(1.8, 120, 'other');
  await page.setInputFiles('#upload-files', other.file);
  await page.waitForFunction(() => document.documentElement.dataset.upload === 'done'
    && window.__pdrTest.upload.logs[0]?.a);
  const measured = await page.evaluate(() => window.__pdrTest.upload.logs[0].a.score.distance_m);
  const err = Math.abs(measured - other.distance_m) / other.distance_m;
  const pct = (100 * err).toFixed(1);
  console.log(`${other.distance_m.toFixed(1)} m at 1.8 Hz with the profile: ${measured.toFixed(1)} m (${pct} %)`);
  assert.ok(err < 0.02, `with the profile: ${pct} %`);
  assert.deepEqual(errors, []);
  await context.close();
});
