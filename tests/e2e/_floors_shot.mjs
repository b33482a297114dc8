// Ad-hoc: screenshots of the upload page drawing a hand-made three-floor analysis.
import { chromium } from 'playwright';
import { readFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
const URL = process.env.PDR_E2E_URL;
const bytes = [...readFileSync('/tmp/three-floor.bin')];
execFileSync(process.env.PDR_BIN, ['simulate', '--scenario', 'demo', '--out', '/tmp/demo18.pdrlog']);
const browser = await chromium.launch();
for (const [name, opts] of [['desktop', { viewport: { width: 1100, height: 900 } }], ['phone', { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true }]]) {
  for (const scheme of ['light', 'dark']) {
    const page = await browser.newPage({ ...opts, colorScheme: scheme });
    page.on('pageerror', (e) => console.log('pageerror', e));
    await page.goto(URL + '#upload');
    await page.waitForFunction(() => document.documentElement.dataset.ready !== undefined || true);
    await page.waitForTimeout(1500);
    await page.setInputFiles('#upload-files', '/tmp/demo18.pdrlog');
    await page.waitForFunction(() => document.documentElement.dataset.upload === 'done', null, { timeout: 60000 });
    await page.locator('.log-result').screenshot({ path: `artifacts/floors-real-${name}-${scheme}.png` });
    await page.evaluate(async ({ bytes, dark }) => {
      const m = await import('./pkg/pdr.js');
      const v = m.AnalysisView.from_bytes(new Uint8Array(bytes));
      const s = v.summary();
      const dpr = window.devicePixelRatio;
      const map = document.querySelector('.log-result .mapbox canvas');
      v.draw_map(map, dark, dpr, [], undefined);
      for (const c of document.querySelectorAll('.log-result canvas.plot')) v.draw_plot(c, dark, dpr, c.dataset.kind, s.t0, s.t1, undefined);
      const fig = document.querySelector('.log-result .stepinfo');
      fig.textContent = v.step_text(300) + ' | ' + JSON.stringify(v.figures().filter((r) => r[0] === 'Height'));
    }, { bytes, dark: scheme === 'dark' });
    await page.locator('.log-result').screenshot({ path: `artifacts/floors-${name}-${scheme}.png` });
    await page.close();
  }
}
await browser.close();
