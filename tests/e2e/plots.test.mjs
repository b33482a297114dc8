// End-to-end test of upload mode's diagnostics plots staying legible: a whole real walk (an
// IPIN 2023 log when ../shared/data is there, else the simulated 12.7-minute city walk) at full
// zoom, at a 10 s and at a 1 s window, on a desktop and a phone, in light and dark. Each plot's
// canvas is read back: no one colour (other than the background, grid and axes) may cover more
// than MAX_DOMINANT_SHARE of its plot area, the bound of the native test
// (src/plot/upload/legibility.rs). Screenshots: artifacts/plots-<zoom>-<device>-<theme>.png.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { ARTIFACTS, BIN, PHONE, URL_HTTP, openPage, useBrowser, tempDir } from './util.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const IPIN = path.join(here, '../../../shared/data/ipin2023/IPIN2023_T3_TrainingTrial01_repetition01.txt');
const tmp = tempDir('plots');
const MAX_DOMINANT_SHARE = 0.35;
// The colours a plot may cover any amount of: grid lines and axes (src/plot/theme.rs).
const NEUTRAL = {
  light: [[0xe3, 0xe4, 0xe0], [0x22, 0x26, 0x2e]],
  dark: [[0x2a, 0x2f, 0x37], [0xe6, 0xe8, 0xeb]],
};

const browser = useBrowser();

/** The walk to look at: the real IPIN log, or the simulated city walk without ../shared. */
function walk() {
  if (existsSync(IPIN)) return IPIN;
  console.log(`${IPIN} is absent: using the simulated city walk`);
  const city = path.join(tmp, 'city.pdrlog');
  if (!existsSync(city)) execFileSync(BIN, ['simulate', '--scenario', 'gnss-city', '--out', city]);
  return city;
}

/** Per plot canvas of the first result: its kind, dominant colour and that colour's share of the plot area. */
function shares(page, theme) {
  return page.evaluate((neutral) => [...document.querySelectorAll('.log-result canvas.plot')].map((c) => {
    const [left, right, top, bottom] = c.area;
    const d = c.getContext('2d').getImageData(left, top, right - left, bottom - top).data;
    const bg = c.getContext('2d').getImageData(0, 0, 1, 1).data;
    const skip = [[bg[0], bg[1], bg[2]], ...neutral].map(([r, g, b]) => (r << 16) | (g << 8) | b);
    const counts = new Map();
    for (let i = 0; i < d.length; i += 4) {
      const k = (d[i] << 16) | (d[i + 1] << 8) | d[i + 2];
      if (!skip.includes(k)) counts.set(k, (counts.get(k) ?? 0) + 1);
    }
    const [colour, n] = [...counts].reduce((m, e) => (e[1] > m[1] ? e : m), [0, 0]);
    return { kind: c.dataset.kind, colour: `#${colour.toString(16).padStart(6, '0')}`, share: n / (d.length / 4) };
  }), NEUTRAL[theme]);
}

for (const [device, options] of [['desktop', { viewport: { width: 1100, height: 900 } }], ['phone', PHONE]]) {
  for (const theme of ['light', 'dark']) {
    test(`${device}, ${theme}: every plot of a whole walk, 10 s and 1 s is no block of one colour`, async () => {
      const { context, page, errors } = await openPage(browser(), URL_HTTP, { options: { ...options, colorScheme: theme } });
      await page.setInputFiles('#upload-files', walk());
      await page.waitForFunction(() => document.documentElement.dataset.upload === 'done', null, { timeout: 60_000 });
      const [f0, f1] = await page.evaluate(() => window.__pdrTest.upload.full(0));
      const mid = (f0 + f1) / 2;
      for (const [zoom, span] of [['full', [f0, f1]], ['10s', [mid, mid + 10]], ['1s', [mid, mid + 1]]]) {
        await page.evaluate(([t0, t1]) => window.__pdrTest.upload.setSpan(0, t0, t1), span);
        await page.locator('.log-result .plots').screenshot({ path: path.join(ARTIFACTS, `plots-${zoom}-${device}-${theme}.png`) });
        for (const s of await shares(page, theme)) {
          console.log(`${device} ${theme} ${zoom} ${s.kind}: ${s.colour} covers ${(100 * s.share).toFixed(1)} %`);
          assert.ok(s.share < MAX_DOMINANT_SHARE, `${zoom} ${s.kind}: ${s.colour} covers ${(100 * s.share).toFixed(1)} % of the plot`);
        }
      }
      assert.deepEqual(errors, []);
      await context.close();
    });
  }
}
