// Thin glue: load the WebAssembly engine, fill the choices, show the demo walks' figures, draw
// their tracks.
import init, { Demo, FusionDemo, choices } from './pkg/pdr.js';
import { setupLive } from './live.js';
import { setupWizard } from './wizard.js';
import { setupUpload } from './upload.js';
import { setupBasemap } from './basemap.js';
import { $, dark, fit, test } from './util.js';

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
  $('steps').textContent = String(s.steps);
  $('steps-truth').textContent = `true: ${s.truth_steps}`;
  $('distance').textContent = s.distance_m.toFixed(1);
  $('distance-truth').textContent = `true: ${s.truth_distance_m.toFixed(1)} m`;
  $('end-error').textContent = s.end_error_m.toFixed(1);

  keepDrawn($('track'), demo);
  test.demo = { steps: s.steps, distance_m: s.distance_m, ready_ms: performance.now() };
  document.documentElement.dataset.state = 'ready';

  // The GNSS walk takes a moment to simulate: after the first paint.
  await new Promise((resolve) => setTimeout(resolve, 0));
  const fusion = new FusionDemo();
  const f = fusion.summary();
  $('gnss-p75').textContent = f.gnss_p75_m.toFixed(1);
  $('fused-p75').textContent = f.fused_p75_m.toFixed(1);
  $('smoothed-p75').textContent = f.smoothed_p75_m.toFixed(1);
  $('fused-note').textContent = `PDR only: ${f.pdr_p75_m.toFixed(1)} m`;
  $('fusion-caption').textContent = `${f.fixes} fixes, ${f.fixes_gated} refused as outliers. ` +
    `Learnt: step length × ${f.scale.toFixed(3)} (true ${f.true_scale.toFixed(3)}), `
    + `heading ${f.heading_correction_deg.toFixed(1)}° (true ${f.true_heading_correction_deg.toFixed(0).replace('-', '−')}°), ` +
    `declination ${f.declination_deg.toFixed(1)}° from the World Magnetic Model. Grey: the true path.`;
  keepDrawn($('fusion'), fusion);
  test.demo.fusion = f;
  document.documentElement.dataset.fusion = 'ready';
}

/** Draws `what` on `canvas` at the device pixel ratio, again on resize, scheme change and base
 * map change (see basemap.js). */
function keepDrawn(canvas, what) {
  const draw = () => {
    const dpr = fit(canvas);
    if (dpr) what.draw(canvas, dark.matches, dpr);
  };
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
