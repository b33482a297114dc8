// Thin glue: load the WebAssembly engine, show the demo walk's figures, draw its track.
import init, { Demo } from './pkg/pdr.js';

const $ = (id) => document.getElementById(id);
const dark = window.matchMedia('(prefers-color-scheme: dark)');

function fail(err) {
  document.documentElement.dataset.state = 'error';
  const box = $('error');
  box.hidden = false;
  box.textContent = `The engine could not start: ${err && err.message ? err.message : err}`;
  console.error(err);
}

async function main() {
  await init();
  const demo = new Demo();
  const s = demo.summary();
  $('steps').textContent = String(s.steps);
  $('steps-truth').textContent = `true: ${s.truth_steps}`;
  $('distance').textContent = s.distance_m.toFixed(1);
  $('distance-truth').textContent = `true: ${s.truth_distance_m.toFixed(1)} m`;
  $('end-error').textContent = s.end_error_m.toFixed(1);

  const canvas = $('track');
  const draw = () => {
    const dpr = window.devicePixelRatio || 1;
    const rect = canvas.getBoundingClientRect();
    const w = Math.round(rect.width * dpr);
    const h = Math.round(rect.height * dpr);
    if (w === 0 || h === 0) return;
    canvas.width = w;
    canvas.height = h;
    demo.draw(canvas, dark.matches, dpr);
  };
  draw();
  new ResizeObserver(draw).observe(canvas);
  dark.addEventListener('change', draw);

  window.__pdr = { steps: s.steps, distance_m: s.distance_m, ready_ms: performance.now() };
  document.documentElement.dataset.state = 'ready';
}

main().catch(fail);
