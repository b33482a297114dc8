// Thin glue: load the WebAssembly engine, fill the choices, show the demo walks' figures, draw
// their tracks.
import init, { Demo, FusionDemo, choices } from './pkg/pdr.js';
import { setupLive } from './live.js';
import { setupWizard } from './wizard.js';
import { setupUpload } from './upload.js';
import { setupBasemap } from './basemap.js';
import { $, dark, fill, paint, test } from './util.js';

/** Fills every select marked `data-choice` with the options of the setting it is named after. */
function fillChoices() {
  const byKey = new Map(choices().map((c) => [c.key, c]));
  for (const sel of document.querySelectorAll('select[data-choice]')) {
    const prefix = sel.dataset.prefix ?? '';
    sel.replaceChildren(...byKey.get(sel.name).options.map(([value, label]) => new Option(prefix + label, value)));
  }
}

function fail(err) {
  document.documentElement.dataset.state = 'error';
  const box = $('error');
  box.hidden = false;
  box.textContent = `The engine could not start: ${err && err.message ? err.message : err}`;
  console.error(err);
}

async function main() {
  await init();
  fillChoices();
  setupBasemap();
  setupLive();
  setupWizard();
  setupUpload();
  const demo = new Demo();
  const s = demo.summary();
  fill(demo.texts());

  keepDrawn($('track'), demo);
  test.demo = { steps: s.steps, distance_m: s.distance_m, ready_ms: performance.now() };
  document.documentElement.dataset.state = 'ready';

  // The GNSS walk takes a moment to simulate: after the first paint.
  await new Promise((resolve) => setTimeout(resolve, 0));
  const fusion = new FusionDemo();
  const f = fusion.summary();
  fill(fusion.texts());
  keepDrawn($('fusion'), fusion);
  test.demo.fusion = f;
  document.documentElement.dataset.fusion = 'ready';
}

/** Draws `what` on `canvas` at the device pixel ratio, again on resize, scheme change and base
 * map change (see basemap.js). */
function keepDrawn(canvas, what) {
  const draw = () => paint(canvas, (...a) => what.draw(...a));
  draw();
  new ResizeObserver(draw).observe(canvas);
  dark.addEventListener('change', draw);
  window.addEventListener('pdr-basemap', draw);
}

main().catch(fail);

// Offline once visited (the worker sits at the site's root; see www/sw.js).
if ('serviceWorker' in navigator && window.isSecureContext) {
  navigator.serviceWorker.register('sw.js').catch((err) => console.warn('no offline support:', err));
}
