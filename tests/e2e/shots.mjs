// Scratch: screenshots of the live page at desktop size, light and dark.
import { chromium } from 'playwright-core';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
execFileSync('../../target/release/pdr', ['simulate', '--scenario', 'demo', '--events', '/tmp/demo-ev.json']);
const w = JSON.parse(readFileSync('/tmp/demo-ev.json', 'utf8'));
const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', args: ['--headless','--no-sandbox','--disable-gpu'] });
for (const [name, opts] of [['desktop', { viewport: { width: 1100, height: 900 } }], ['dark-phone', { viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, colorScheme: 'dark', isMobile: true }]]) {
  const context = await browser.newContext({ ...opts, permissions: ['geolocation', 'accelerometer', 'gyroscope'], geolocation: { latitude: 46, longitude: 9, accuracy: 8 } });
  const page = await context.newPage();
  await page.goto('http://127.0.0.1:8080/');
  await page.waitForFunction(() => document.documentElement.dataset.state === 'ready');
  await page.click('#start');
  await page.waitForFunction(() => document.documentElement.dataset.source);
  await page.evaluate(({ events }) => {
    const base = performance.now();
    let k = 0;
    for (const e of events) {
      if (e.t > 60000 && e.t < 66000) continue; // a gap
      let ev = e.type === 'motion'
        ? new DeviceMotionEvent('devicemotion', { accelerationIncludingGravity: { x: e.x, y: e.y, z: e.z }, rotationRate: { alpha: e.alpha, beta: e.beta, gamma: e.gamma }, interval: e.interval })
        : new DeviceOrientationEvent('deviceorientationabsolute', { alpha: e.alpha, beta: e.beta, gamma: e.gamma, absolute: true });
      Object.defineProperty(ev, 'timeStamp', { value: base + e.t });
      window.dispatchEvent(ev);
    }
  }, { events: w.events });
  const box = await page.locator('#unlock').boundingBox();
  await page.mouse.move(box.x + 10, box.y + 10); await page.mouse.down(); await page.waitForTimeout(2200); await page.mouse.up();
  await page.waitForTimeout(400);
  await page.locator('#live').screenshot({ path: `artifacts/scratch-${name}.png` });
  await context.close();
}
await browser.close();
