// End-to-end test of recipes (README, "Logs from any recorder"): a folder of header-less CSVs
// that no format reader recognises is uploaded; the page offers the form with a first guess,
// a wrong unit raises the engine's sanity warning, fixing it clears it, the mapping runs (the
// same steps as `pdr run --recipe`), is saved, and the next upload is read with it at once.
// Screenshots of the form on a desktop and a phone go to tests/e2e/artifacts/.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, openPage, useBrowser, tempDir } from './util.mjs';

const browser = useBrowser();
const tmp = tempDir('recipe');

/** A simulated straight walk as a header-less folder (acc, gyr, mag, bar) and its recipe. */
function plainFolder() {
  const { folder, recipe } = plainWalk();
  return { folder, recipe };
}

/** The simulated folder and its recipe, and the directory holding both. */
function plainWalk() {
  const out = mkdtempSync(path.join(tmp, 'walk-'));
  execFileSync(BIN, ['simulate', '--scenario', 'straight', '--format', 'plain-csv', '--out', out]);
  const dir = readdirSync(out).find((n) => n.startsWith('plain_'));
  return { folder: path.join(out, dir), recipe: path.join(out, 'recipe.json'), both: out };
}

const done = (page) => page.waitForFunction(() => document.documentElement.dataset.upload === 'done', null, { timeout: 30_000 });
const accUnit = 'fieldset.recipe-file[data-file$="acc.csv"] select[data-k="unit"]';
const warnings = (page) => page.locator('#recipe-warnings li.warn').allTextContents();

test('a header-less folder: the form, a wrong unit flagged, run, save, and read again by the recipe', async () => {
  const { folder, recipe } = plainFolder();
  const native = execFileSync(BIN, ['run', folder, '--recipe', recipe], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
  const nativeSteps = Number(native.match(/^steps\s+(\d+)/m)[1]);
  const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: { viewport: { width: 1100, height: 900 }, acceptDownloads: true } });
  try {
    await page.setInputFiles('#upload-folder', folder);
    await done(page);
    await page.locator('#recipe-form').waitFor({ state: 'visible' });
    // The first guess: sensors from the names, columns 1–4, time in ms; the preview in SI units.
    const sensors = await page.locator('fieldset.recipe-file select[data-k="sensor"]').evaluateAll((s) => s.map((x) => x.value));
    assert.deepEqual(sensors, ['accelerometer', 'pressure', 'gyroscope', 'magnetometer']);
    await page.locator('.recipe-table table').first().waitFor();
    const firstRow = await page.locator('.recipe-table').first().locator('tbody tr').first().locator('td').allTextContents();
    assert.equal(firstRow.length, 4);
    assert.ok(Math.abs(Number(firstRow[2]) - 9.8) < 1, `acceleration y in m/s²: ${firstRow}`);
    assert.deepEqual(await warnings(page), [], 'right units: no warning');
    assert.ok((await page.locator('#recipe-warnings li.note').allTextContents()).some((n) => /pressure samples read and checked; the engine uses them for the height and floor changes/.test(n)));
    // The wrong unit: g for data in m/s².
    await page.selectOption(accUnit, 'g');
    await page.waitForFunction(() => [...document.querySelectorAll('#recipe-warnings li.warn')].some((l) => /not near 9\.81/.test(l.textContent)));
    const w = await warnings(page);
    assert.ok(w[0].includes('acc.csv') && w[0].includes('m/s² read as g'), w.join('\n'));
    await page.locator('#recipe-form').screenshot({ path: path.join(ARTIFACTS, 'recipe-form-desktop.png') });
    // Fixed.
    await page.selectOption(accUnit, 'm/s2');
    await page.waitForFunction(() => !document.querySelector('#recipe-warnings li.warn'));
    await page.fill('#recipe-name', 'Test logger');
    await page.click('#recipe-save');
    assert.match(await page.locator('#recipe-saved').textContent(), /Saved as recipe "Test logger"/);
    // The download is the JSON the CLI reads.
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#recipe-download')]);
    const saved = path.join(tmp, 'downloaded.recipe.json');
    await dl.saveAs(saved);
    const viaDownload = execFileSync(BIN, ['run', folder, '--recipe', saved], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    assert.equal(Number(viaDownload.match(/^steps\s+(\d+)/m)[1]), nativeSteps);
    // Run it.
    await page.click('#recipe-run');
    await done(page);
    let logs = await page.evaluate(() => window.__pdrTest.upload.logs);
    assert.equal(logs.length, 1);
    assert.equal(logs[0].a.steps, nativeSteps, 'the page counts the steps pdr run --recipe counts');
    assert.ok(nativeSteps > 50);
    assert.equal(await page.locator('#recipe-form').isHidden(), true);
    assert.match(await page.locator('.log-result .hint').first().textContent(), /read with your recipe "Test logger"/);
    // Upload again: read with the saved recipe at once, no form.
    await page.setInputFiles('#upload-folder', folder);
    await done(page);
    logs = await page.evaluate(() => window.__pdrTest.upload.logs);
    assert.equal(logs[0].a.steps, nativeSteps);
    assert.equal(await page.locator('#recipe-form').isHidden(), true);
    assert.match(await page.locator('.log-result .hint').first().textContent(), /recipe · .*read with your recipe "Test logger"/);
    await page.locator('.log-result').first().screenshot({ path: path.join(ARTIFACTS, 'recipe-result-desktop.png') });
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});

test('the recipe form on a phone, dark: fits the width', async () => {
  const { folder } = plainFolder();
  const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: { ...PHONE, colorScheme: 'dark' } });
  try {
    await page.setInputFiles('#upload-folder', folder);
    await done(page);
    await page.locator('.recipe-table table').first().waitFor();
    await page.selectOption(accUnit, 'g');
    await page.waitForFunction(() => document.querySelector('#recipe-warnings li.warn'));
    const fits = await page.evaluate(() => document.documentElement.scrollWidth <= document.documentElement.clientWidth);
    assert.ok(fits, 'the page scrolls sideways on a phone');
    await page.locator('#recipe-form').screenshot({ path: path.join(ARTIFACTS, 'recipe-form-phone.png') });
    // What the phone's screen shows: the top of the form, then the warning and the preview.
    await page.evaluate(() => document.getElementById('recipe-form').scrollIntoView());
    await page.screenshot({ path: path.join(ARTIFACTS, 'recipe-form-phone-top.png') });
    await page.evaluate(() => document.getElementById('recipe-warnings').scrollIntoView());
    await page.screenshot({ path: path.join(ARTIFACTS, 'recipe-preview-phone.png') });
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});

test('a recipe uploaded beside its files is applied to them', async () => {
  const { recipe, both } = plainWalk();
  const native = execFileSync(BIN, ['run', both, '--recipe', recipe], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
  const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: { viewport: { width: 1100, height: 900 } } });
  try {
    await page.setInputFiles('#upload-folder', both);
    await done(page);
    const logs = await page.evaluate(() => window.__pdrTest.upload.logs);
    assert.equal(logs.length, 1);
    assert.equal(logs[0].a.steps, Number(native.match(/^steps\s+(\d+)/m)[1]));
    assert.equal(await page.locator('#recipe-form').isHidden(), true);
    assert.match(await page.locator('.log-result .hint').first().textContent(), /read with your recipe "plain CSV, ms"/);
    assert.equal(await page.locator('#upload-banners li.warn').count(), 0, 'right units: no warning');
    // The same with a recipe that says g for the m/s² data: read, and the warning shown.
    writeFileSync(recipe, readFileSync(recipe, 'utf8').replace('"unit": "m/s2"', '"unit": "g"'));
    await page.setInputFiles('#upload-folder', both);
    await done(page);
    const banners = await page.locator('#upload-banners li.warn').allTextContents();
    assert.ok(banners.some((b) => /read with the recipe "plain CSV, ms": acc\.csv: the median acceleration is .* not near 9\.81/.test(b)), banners.join('\n'));
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});

test('one file with several sensors: a row per sensor, run, and the downloaded recipe reads the same', async () => {
  // t, ax, ay, az, gx, gy, gz in one header-less file, joined from the simulated folder.
  const { folder } = plainFolder();
  const acc = readFileSync(path.join(folder, 'acc.csv'), 'utf8').trim().split('\n');
  const gyr = readFileSync(path.join(folder, 'gyr.csv'), 'utf8').trim().split('\n');
  assert.equal(acc.length, gyr.length);
  const lines = acc.map((a, i) => {
    const [t, ...g] = gyr[i].split(',');
    assert.equal(a.split(',')[0], t, `line ${i + 1}: the same time in both files`);
    return `${a},${g.join(',')}`;
  });
  const dir = mkdtempSync(path.join(tmp, 'imu-'));
  const file = path.join(dir, 'imu.csv');
  writeFileSync(file, `${lines.join('\n')}\n`);
  const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: { viewport: { width: 1100, height: 900 }, acceptDownloads: true } });
  try {
    await page.setInputFiles('#upload-files', file);
    await done(page);
    await page.locator('#recipe-form').waitFor({ state: 'visible' });
    const fs = page.locator('fieldset.recipe-file[data-file$="imu.csv"]');
    // No sensor in the name: nothing guessed. The accelerometer on columns 2–4, then a second
    // row for the gyroscope, which takes the next three columns (5–7).
    await fs.locator('.recipe-sensor').nth(0).locator('select[data-k="sensor"]').selectOption('accelerometer');
    await fs.locator('.recipe-more').click();
    await fs.locator('.recipe-sensor').nth(1).locator('select[data-k="sensor"]').selectOption('gyroscope');
    const cols = await fs.locator('.recipe-sensor').nth(1).locator('[data-col]').evaluateAll((s) => s.map((x) => `${x.dataset.col}=${x.value}`));
    assert.deepEqual(cols, ['t=1', 'x=5', 'y=6', 'z=7']);
    await page.waitForFunction(() => document.querySelectorAll('.recipe-table').length === 2);
    assert.deepEqual(await warnings(page), [], 'right columns and units: no warning');
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#recipe-download')]);
    const saved = path.join(dir, 'imu.recipe.json');
    await dl.saveAs(saved);
    assert.deepEqual(JSON.parse(readFileSync(saved, 'utf8')).files.map((f) => [f.match, f.sensor]), [['imu.csv', 'accelerometer'], ['imu.csv', 'gyroscope']]);
    await fs.screenshot({ path: path.join(ARTIFACTS, 'recipe-two-sensors-desktop.png') });
    await page.click('#recipe-run');
    await done(page);
    const logs = await page.evaluate(() => window.__pdrTest.upload.logs);
    const native = execFileSync(BIN, ['run', file, '--recipe', saved], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    const steps = Number(native.match(/^steps\s+(\d+)/m)[1]);
    assert.ok(steps > 50, `${steps} steps`);
    assert.equal(logs[0].a.steps, steps, 'the page counts the steps pdr run --recipe counts');
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
  }
});
