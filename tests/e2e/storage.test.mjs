// End-to-end test of stored settings the page cannot read: damaged JSON in localStorage (the
// step-length profiles, the recipes) is kept aside unchanged, the page says so in words, and
// saving a new profile or recipe does not write over it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { ARTIFACTS, URL_HTTP, loadPage, openPage, useBrowser } from './util.mjs';

const browser = useBrowser();
const DAMAGED_PROFILES = '{"me": "{\\"version\\": 2, \\"na';
const DAMAGED_RECIPES = '[not json';

test('damaged profiles and recipes in localStorage are kept aside, told, and never saved over', async () => {
  const { context, page, errors } = await openPage(browser(), URL_HTTP);
  await page.evaluate(([p, r]) => {
    localStorage.setItem('pdr-profiles', p);
    localStorage.setItem('pdr-recipes', r);
  }, [DAMAGED_PROFILES, DAMAGED_RECIPES]);
  await page.close();
  const { page: again, errors: errors2 } = await loadPage(context, URL_HTTP);

  // The page tells the user, in words, where the text is kept.
  const list = again.locator('#storage-messages');
  await list.waitFor({ state: 'visible', timeout: 10_000 });
  const profiles = await again.textContent('#storage-messages li[data-key="pdr-profiles"]');
  assert.match(profiles, /step-length profiles stored on this device could not be read/);
  assert.match(profiles, /pdr-profiles-unreadable-/);
  assert.match(await again.textContent('#storage-messages li[data-key="pdr-recipes"]'), /recipes stored on this device could not be read/);
  await list.screenshot({ path: path.join(ARTIFACTS, 'storage-unreadable-desktop.png') });

  // The text is kept, byte for byte, under its own key.
  const kept = () => again.evaluate(() => Object.fromEntries(Object.keys(localStorage)
    .filter((k) => k.includes('-unreadable-')).map((k) => [k.replace(/-unreadable-.*/, ''), localStorage.getItem(k)])));
  assert.deepEqual(await kept(), { 'pdr-profiles': DAMAGED_PROFILES, 'pdr-recipes': DAMAGED_RECIPES });

  // Saving a profile (an import) writes a fresh list and leaves the kept text alone.
  await again.evaluate(async () => {
    const profiles = await import('./www/profiles.js');
    profiles.save('new', '{"x": 1}');
  });
  assert.deepEqual(JSON.parse(await again.evaluate(() => localStorage.getItem('pdr-profiles'))), { new: '{"x": 1}' });
  assert.deepEqual(await kept(), { 'pdr-profiles': DAMAGED_PROFILES, 'pdr-recipes': DAMAGED_RECIPES });

  // Reloaded, the page still says so; deleting it is the user's choice.
  await again.reload();
  await again.waitForFunction(() => document.documentElement.dataset.state === 'ready');
  await again.locator('#storage-messages li[data-key="pdr-profiles"]').waitFor({ timeout: 10_000 });
  await again.click('#storage-messages li[data-key="pdr-profiles"] button:has-text("Delete it")');
  assert.deepEqual(await kept(), { 'pdr-recipes': DAMAGED_RECIPES });
  assert.equal(await again.locator('#storage-messages li[data-key="pdr-profiles"]').count(), 0);

  assert.deepEqual([...errors, ...errors2], []);
  await context.close();
});
