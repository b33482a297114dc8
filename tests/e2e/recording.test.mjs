// End-to-end tests of live mode's recording when things go wrong: storage refusing writes (a
// full disk), and a recording damaged in IndexedDB. (Crashes are in crash.test.mjs.)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, dispatch, holdToUnlock, openPage, useBrowser, tempDir } from './util.mjs';

const tmp = tempDir('recording');
const browser = useBrowser();

/** A simulated walk as browser events: {truth_steps, distance_m, events}. */
function walk(scenario) {
  const file = path.join(tmp, `${scenario}.json`);
  execFileSync(BIN, ['simulate', '--scenario', scenario, '--events', file]);
  return JSON.parse(readFileSync(file, 'utf8'));
}

const open = (init = []) => openPage(browser(), URL_HTTP, { options: { ...PHONE, acceptDownloads: true }, init });
const readouts = (page) => page.evaluate(() => window.__pdrTest?.live?.readouts);
const messages = (page) => page.$$eval('#live-messages li', (els) => els.map((e) => `${e.dataset.key}: ${e.textContent}`));
const imuLines = (text) => text.split('\n').filter((l) => l.startsWith('imu,'));
const runSteps = (file) => Number(execFileSync(BIN, ['run', file], { encoding: 'utf8' }).match(/^steps\s+(\d+)/m)[1]);

async function start(page) {
  await page.click('#start');
  await page.waitForFunction(() => document.documentElement.dataset.source, null, { timeout: 10_000 });
}

/** Pixels of a canvas differing from its corner. */
async function drawn(page, id) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 30) n++;
    return n / (d.length / 4);
  }, id);
}

async function downloadFrom(page, selector) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
  const file = path.join(tmp, `${Date.now()}-${dl.suggestedFilename()}`);
  await dl.saveAs(file);
  return file;
}

/**
 * A full disk: IndexedDB's `add` on the chunks refuses every write after the first `after`
 * (`window.__quota.mode`: 'throw' throws a QuotaExceededError as the call; 'abort' lets the
 * requests start and aborts their transaction before it commits, as a failed commit does; 'free'
 * writes again).
 */
function fullDisk(after) {
  let adds = 0;
  window.__quota = { mode: 'throw', refused: 0 };
  const add = IDBObjectStore.prototype.add;
  IDBObjectStore.prototype.add = function (...args) {
    if (this.name === 'chunks' && window.__quota.mode !== 'free' && ++adds > after) {
      window.__quota.refused++;
      if (window.__quota.mode === 'abort') {
        const t = this.transaction;
        if (!t.__aborting) { t.__aborting = true; queueMicrotask(() => t.abort()); }
        return add.apply(this, args);
      }
      throw new DOMException('The quota has been exceeded (simulated).', 'QuotaExceededError');
    }
    return add.apply(this, args);
  };
}

test('storage full: the page says so, the walk goes on, and the download holds every sample', async () => {
  const w = walk('square');
  const { context, page, errors } = await open([[fullDisk, 1]]);
  await start(page);
  const base = await page.evaluate(() => performance.now());
  const third = Math.floor(w.events.length / 3);
  // In two goes, a batch apart: the first chunk is written, the next refused.
  await dispatch(page, w.events, { base, to: third >> 1 });
  await page.waitForTimeout(400);
  await dispatch(page, w.events, { base, from: third >> 1, to: third });
  await page.waitForSelector('#live-messages li[data-key="storage"]', { timeout: 5000 });
  const shown = (await messages(page)).join('\n');
  assert.match(shown, /cannot be saved on this device.*walk goes on.*kept in memory.*Download recording.*QuotaExceededError/);
  // A failed commit (the transaction aborted) is the same.
  await page.evaluate(() => { window.__quota.mode = 'abort'; });
  await dispatch(page, w.events, { base, from: third, to: 2 * third });
  await page.waitForTimeout(1500); // a retry
  await dispatch(page, w.events, { base, from: 2 * third });
  await page.waitForTimeout(400);
  const r = await readouts(page);
  const held = await page.evaluate(() => ({ unsaved: window.__pdrTest.live.unsaved, refused: window.__quota.refused }));
  console.log(`storage full after the first chunk: ${held.refused} writes refused, ${held.unsaved} chunks held in memory; `
    + `${r.steps} steps of ${w.truth_steps}, ${r.samples} samples`);
  assert.ok(held.unsaved > 5 && held.refused > 2, JSON.stringify(held));
  assert.ok(Math.abs(r.steps - w.truth_steps) <= 0.02 * w.truth_steps, `${r.steps} of ${w.truth_steps}`);
  assert.equal(await page.textContent('#g-steps'), String(r.steps));
  // The plots are still drawn.
  await holdToUnlock(page, 2300);
  await page.waitForFunction(() => document.documentElement.dataset.guard === 'off');
  await page.waitForTimeout(300);
  assert.ok(await drawn(page, 'live-map') > 0.02, 'the map is blank');
  assert.ok(await drawn(page, 'live-scope') > 0.02, 'the scope is blank');
  await page.locator('#live').screenshot({ path: path.join(ARTIFACTS, 'live-storage-full-phone.png') });
  await page.locator('#live-messages li[data-key="storage"]').screenshot({ path: path.join(ARTIFACTS, 'live-storage-full-message.png') });
  // Stop, download: every sample, and `pdr run` counts the page's steps.
  await page.click('#stop');
  await page.waitForFunction(() => document.documentElement.dataset.live === 'stopped');
  const file = await downloadFrom(page, '#download');
  const text = readFileSync(file, 'utf8');
  const motion = w.events.filter((e) => e.type === 'motion').length;
  console.log(`downloaded: ${imuLines(text).length} samples of ${r.samples} used (${motion} sent)`);
  assert.equal(imuLines(text).length, r.samples);
  assert.equal(r.samples, motion);
  assert.equal(runSteps(file), r.steps);
  assert.deepEqual(errors, []);
  await context.close();
});

test('storage full, then free again: the chunks held in memory are written in order', async () => {
  const w = walk('straight');
  const { context, page, errors } = await open([[fullDisk, 1]]);
  await start(page);
  const base = await page.evaluate(() => performance.now());
  const half = Math.floor(w.events.length / 2);
  await dispatch(page, w.events, { base, to: half >> 1 });
  await page.waitForTimeout(400);
  await dispatch(page, w.events, { base, from: half >> 1, to: half });
  await page.waitForSelector('#live-messages li[data-key="storage"]', { timeout: 5000 });
  await page.waitForTimeout(1200); // a retry refused too
  assert.ok(await page.evaluate(() => window.__pdrTest.live.unsaved) > 0);
  await page.evaluate(() => { window.__quota.mode = 'free'; });
  await page.waitForFunction(() => window.__pdrTest.live.unsaved === 0, null, { timeout: 10_000 });
  await page.waitForSelector('#live-messages li[data-key="storage"]', { state: 'detached' });
  await dispatch(page, w.events, { base, from: half });
  await page.waitForTimeout(400);
  const r = await readouts(page);
  await holdToUnlock(page, 2300);
  await page.click('#stop');
  await page.waitForFunction(() => document.documentElement.dataset.live === 'stopped');
  // IndexedDB itself now holds the whole recording: every chunk once, in order.
  const stored = await page.evaluate(async () => {
    const store = await import('./www/store.js');
    const [rec] = (await store.list()).filter((x) => x.state === 'done');
    const { pieces } = await store.pieces(rec.id);
    return { seqs: pieces.map((c) => c.seq), text: pieces.map((c) => c.text).join('') };
  });
  assert.deepEqual(stored.seqs, stored.seqs.map((_, i) => i));
  assert.equal(imuLines(stored.text).length, r.samples);
  const file = path.join(tmp, 'freed.pdrlog');
  execFileSync('sh', ['-c', 'cat > "$0"', file], { input: stored.text });
  assert.equal(runSteps(file), r.steps);
  console.log(`storage freed: IndexedDB holds ${stored.seqs.length} chunks, ${imuLines(stored.text).length} samples of ${r.samples}`);
  assert.deepEqual(errors, []);
  await context.close();
});

/** Writes a recording's pieces into the page's IndexedDB (the `pdr` database, as store.js has it). */
async function writeRecording(page, id, pieces) {
  await page.evaluate(async ({ id, pieces }) => {
    const db = await new Promise((ok, fail) => {
      const r = indexedDB.open('pdr', 1);
      r.onsuccess = () => ok(r.result);
      r.onerror = () => fail(r.error);
    });
    await new Promise((ok, fail) => {
      const t = db.transaction(['recordings', 'chunks'], 'readwrite');
      t.objectStore('recordings').put({ id, started: Date.now() - 120_000, state: 'recording', samples: 0, ios: false });
      for (const p of pieces) t.objectStore('chunks').add({ rec: id, ...p });
      t.oncomplete = ok;
      t.onerror = () => fail(t.error);
    });
    db.close();
  }, { id, pieces });
}

test('a damaged recording is offered with every good line, and says what was skipped', async () => {
  const log = path.join(tmp, 'straight.pdrlog');
  execFileSync(BIN, ['simulate', '--scenario', 'straight', '--out', log]);
  const lines = readFileSync(log, 'utf8').split(/(?<=\n)/);
  const head = lines.findIndex((l) => !l.startsWith('#'));
  // Pieces of 200 lines, as the page writes them (the first with the preamble).
  const pieces = [];
  for (let i = head; i < lines.length; i += 200) pieces.push(lines.slice(i === head ? 0 : i, i + 200));
  const lost = new Set(); // the record lines that damage takes
  const text = pieces.map((p) => p.join(''));
  // Piece 3 cut in the middle of its last line; piece 5 with garbage in place of a line and a
  // number that is not; piece 7 missing; piece 9 not text.
  text[3] = text[3].slice(0, -25);
  lost.add(pieces[3].at(-1));
  lost.add(pieces[5][10]);
  lost.add(pieces[5][20]);
  text[5] = pieces[5].map((l, i) => (i === 10 ? '\u0000\u0007 garbage ∑∑∑,,,\n' : i === 20 ? l.replace(/^imu,([^,]*),[^,]*,/, 'imu,$1,NaN,') : l)).join('');
  for (const l of pieces[7]) lost.add(l);
  for (const l of pieces[9]) lost.add(l);
  const stored = text.map((t, seq) => ({ seq, text: seq === 9 ? 12345 : t, samples: 0 })).filter((p) => p.seq !== 7);
  const good = lines.filter((l) => l.startsWith('imu,') && !lost.has(l));

  const { context, page, errors } = await open();
  await writeRecording(page, 'rec-damaged', stored);
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.recovery === 'offered', null, { timeout: 10_000 });
  const offer = await page.evaluate(() => window.__pdrTest.recovery);
  const said = await page.textContent('#recovery-text');
  console.log(`damaged recording: offered ${offer.samples} samples of ${good.length} good; ${offer.skipped_lines} lines skipped, `
    + `${offer.missing_pieces} piece missing; "${said}"`);
  assert.equal(offer.samples, good.length);
  assert.equal(offer.skipped_lines, 4); // the cut line, the garbage, the NaN, the piece that is not text
  assert.equal(offer.missing_pieces, 1);
  assert.match(said, /4 damaged lines were skipped, 1 piece is missing.*everything else is kept.*piece 3 ends in the middle of a line/);
  await page.locator('#recovery').screenshot({ path: path.join(ARTIFACTS, 'live-recovery-damaged-phone.png') });
  // Download: every good line, as written, and a gap where the pieces are missing.
  const file = await downloadFrom(page, '#recover-save');
  const got = readFileSync(file, 'utf8');
  assert.deepEqual(imuLines(got), good.map((l) => l.trimEnd()));
  assert.equal(got.split('\n').filter((l) => l.startsWith('gap,')).length, 2);
  const run = execFileSync(BIN, ['run', file], { encoding: 'utf8' });
  assert.match(run, /\(0 lines skipped, 0 records refused\)/);
  assert.ok(runSteps(file) > 0);

  // Resume: the first piece (the version tag) gone as well; the engine replays every good line.
  await writeRecording(page, 'rec-damaged-2', stored.filter((p) => p.seq !== 0));
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.recovery === 'offered', null, { timeout: 10_000 });
  const offer2 = await page.evaluate(() => window.__pdrTest.recovery);
  const good2 = good.filter((l) => !pieces[0].includes(l));
  assert.equal(offer2.id, 'rec-damaged-2');
  assert.equal(offer2.samples, good2.length);
  assert.match(await page.textContent('#recovery-text'), /piece 0 is missing/);
  await page.click('#recover-resume');
  await page.waitForFunction(() => document.documentElement.dataset.source);
  const r = await readouts(page);
  console.log(`resumed without its first piece: ${r.samples} samples of ${good2.length}, ${r.steps} steps, refused ${r.refused}`);
  assert.equal(r.samples, good2.length);
  assert.equal(r.refused, 0, r.last_error);
  assert.ok(r.steps > 0 && Number.isFinite(r.distance_m));
  assert.equal(await page.textContent('#g-steps'), String(r.steps));
  assert.deepEqual(errors, []);
  await context.close();
});
