// The step-length calibration wizard and the profiles panel. This only drives the steps: the
// walks run through live mode's session (sensors, pocket guard, wake lock), and every figure —
// eq. 1 and 2, the fits, their warnings, the fuzzy scale, the profile, its chart, the
// refinement — comes from the engine (CalibrationWizard, profile_summary, refine_profile in
// src/web/calibration.rs).
import { CalibrationWizard, gnss_limit_m, pitch_calibration, profile_summary, profile_with_pitch_offset, refine_profile } from './pkg/pdr.js';
import { startWalk, stopWalk } from './live.js';
import * as profiles from './profiles.js';
import { $, dark, download, el, fit, note, safeName, test } from './util.js';

const PACES = { slow: 'slow walk', normal: 'normal walk', fast: 'fast walk', jog: 'jog', run: 'run' };

let wizard; // made in setupWizard, once the engine is loaded
let walking = null; // { session, row, pace, band, target }
let pitch = null; // the normal walk's leg-pitch calibration (engine's pitch_calibration), or null

const source = () => document.querySelector('input[name=cal-source]:checked').value;

/** Starts or stops the walk of a pace row. */
async function paceClicked(row) {
  if (walking) {
    if (walking.row === row) await finish();
    return;
  }
  const pace = row.dataset.pace;
  const band = row.dataset.band;
  const gnss = source() === 'gnss';
  const target = Number(gnss ? $('cal-gnss-distance').value : $('cal-distance').value);
  if (!(target > 0)) {
    note('cal-messages', 'distance', 'Type the distance in metres first.', 'error');
    return;
  }
  note('cal-messages', 'distance', null);
  const button = row.querySelector('button');
  const result = row.querySelector('.result');
  const session = await startWalk({
    gnss: gnss ? 'best_performance' : 'off',
    messages: 'cal-messages',
    title: gnss
      ? `Calibration, ${PACES[pace]}: walk; the wizard stops you at ${target} m`
      : `Calibration, ${PACES[pace]}: walk the ${target} m, then unlock and tap Stop`,
    onTick: (r, s) => {
      if (walking?.session !== s) return;
      const path = gnss ? s.live.fix_path_m(gnss_limit_m()) : null;
      result.textContent = `${r.steps} steps` + (gnss ? ` · ${path.toFixed(0)} of ${target} m by GNSS` : '');
      if (gnss && path >= target) finish();
    },
  });
  if (!session) {
    note('cal-messages', 'busy', 'A live recording is running: stop it first.', 'error');
    return;
  }
  walking = { session, row, pace, band, target, gnss };
  button.textContent = 'Stop';
  button.classList.add('running');
  result.classList.remove('error');
  document.documentElement.dataset.calibration = 'walking';
}

/** Ends the running walk and adds its point. */
async function finish() {
  const w = walking;
  if (!w || w.finishing) return;
  w.finishing = true;
  await stopWalk(w.session);
  walking = null;
  const button = w.row.querySelector('button');
  const result = w.row.querySelector('.result');
  button.textContent = 'Walk again';
  button.classList.remove('running');
  const distance = w.gnss ? w.session.live.fix_path_m(gnss_limit_m()) : w.target;
  try {
    const p = wizard.add_walk(w.band, w.pace, distance, w.session.live.step_freqs(), w.session.live.fuzzy_lengths());
    result.textContent = p.text;
  } catch (err) {
    result.textContent = String(err?.message ?? err);
    result.classList.add('error');
  }
  // The comfortable (normal) walk also calibrates the leg-pitch step length (Munoz Diaz 2015
  // §5.1), when its steps had a leg pitch.
  if (w.pace === 'normal') {
    try {
      pitch = pitch_calibration(distance, w.session.live.pitch_amplitudes());
    } catch (err) {
      pitch = { ok: false, why: String(err?.message ?? err), text: `Leg-pitch step length not calibrated: ${err?.message ?? err}.` };
    }
    showPitch();
  }
  document.documentElement.dataset.calibration = 'walked';
  refresh();
}

/** Redraws the fits, warnings and notes from the engine's state. */
function refresh() {
  const st = wizard.state();
  const fits = $('cal-fits');
  fits.replaceChildren();
  for (const band of ['walking', 'running']) {
    const f = st[band];
    if (!f.points) continue;
    const canvas = el('canvas', { id: `cal-chart-${band}` });
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', `Calibration points, line and residuals, ${band}`);
    const box = el('div', { className: 'fit' }, canvas);
    if (f.warnings.length) {
      box.append(el('ul', {}, ...f.warnings.map((w) => {
        const li = el('li', { textContent: w.message });
        li.dataset.kind = w.kind;
        if (w.walk != null) {
          const drop = el('button', { type: 'button', className: 'small', textContent: `Drop walk ${w.walk + 1}` });
          drop.addEventListener('click', () => { wizard.remove_walk(w.walk); refresh(); });
          li.append(' ', drop);
        }
        return li;
      })));
    }
    fits.append(box);
    draw(canvas, band);
  }
  // The notes end with the fitted fuzzy scale, when the walks measured one (engine's text).
  $('cal-notes').replaceChildren(...st.notes.map((n) => el('li', { textContent: n })));
  $('cal-save').disabled = st.walking.points + st.running.points === 0;
  test.calibration = { ...st, pitch };
}

/** Says what the normal walk gave the leg-pitch step length, or why it gave nothing. */
function showPitch() {
  $('cal-pitch').textContent = pitch.text;
  $('cal-pitch').dataset.pitch = pitch.ok ? 'ok' : 'refused';
  if (test.calibration) test.calibration.pitch = pitch;
}

function draw(canvas, band) {
  const dpr = fit(canvas);
  if (dpr) wizard.draw(canvas, dark.matches, dpr, band);
}

function save() {
  const name = $('cal-name').value.trim() || 'me';
  let json = wizard.profile_json(name);
  if (pitch?.ok) json = profile_with_pitch_offset(json, pitch.offset_m);
  profile_summary(json); // checks it
  profiles.save(name, json);
  profiles.select(name);
  showProfiles();
  note('cal-messages', 'saved', `Saved “${name}” and selected it: live mode now uses it.`, 'ok');
  document.documentElement.dataset.profile = 'saved';
}

// --- GNSS availability for the GNSS distance source ---------------------------------------
function checkGnss() {
  if (!navigator.geolocation) { $('cal-gnss-state').textContent = 'this browser has no geolocation'; return; }
  $('cal-gnss-state').textContent = 'waiting for a fix…';
  const id = navigator.geolocation.watchPosition((p) => {
    const acc = p.coords.accuracy;
    const good = acc <= gnss_limit_m();
    $('cal-gnss-state').textContent = `±${acc.toFixed(0)} m now: ${good ? 'good enough' : 'not good enough (go into the open)'}`;
    $('cal-gnss-radio').disabled = !good;
    if (!good && source() === 'gnss') document.querySelector('input[value=typed]').checked = true;
  }, (err) => {
    $('cal-gnss-state').textContent = err.code === err.PERMISSION_DENIED ? 'location refused' : 'no fix';
  }, { enableHighAccuracy: true, maximumAge: 0, timeout: 30_000 });
  setTimeout(() => navigator.geolocation.clearWatch(id), 60_000);
}

// --- profiles ---------------------------------------------------------------------------
function showProfiles() {
  const sel = $('profile-select');
  const names = Object.keys(profiles.all()).sort();
  sel.replaceChildren(new Option('built-in (no calibration)', ''), ...names.map((n) => new Option(n, n)));
  sel.value = profiles.selectedName();
  const json = profiles.selected();
  $('profile-in-use').textContent = json ? profiles.selectedName() : 'built-in';
  $('profile-export').disabled = !json;
  $('profile-delete').disabled = !json;
  $('profile-values').textContent = profile_summary(json).text;
}

async function importProfile(file) {
  const text = await file.text();
  let s;
  try {
    s = profile_summary(text);
  } catch (err) {
    note('profile-messages', 'import', `${file.name}: ${err?.message ?? err}`, 'error');
    return;
  }
  let name = s.name || file.name.replace(/\.json$/, '');
  for (let k = 2; name in profiles.all() && profiles.all()[name] !== text; k++) name = `${s.name} (${k})`;
  profiles.save(name, text);
  profiles.select(name);
  note('profile-messages', 'import', `Imported “${name}”.`, 'ok');
  showProfiles();
}

/** Opt-in refinement after a live walk with fixes, when the engine finds the walk says enough
 * (`refine_profile`), with an undo; else the engine's reason, and the profile stays. */
function refineAfterWalk(e) {
  const name = profiles.selectedName();
  const json = profiles.selected();
  if (!$('refine').checked || !json) return;
  const r = refine_profile(json, e.detail.evidence, name);
  note('profile-messages', r.why ? 'refined' : 'not-refined', null);
  if (r.why) { note('profile-messages', 'not-refined', r.text, 'note'); return; }
  profiles.save(name, r.json);
  showProfiles();
  const li = note('profile-messages', 'refined', r.text, 'ok');
  const undo = el('button', { type: 'button', className: 'small', textContent: 'Undo' });
  undo.addEventListener('click', () => { profiles.save(name, json); showProfiles(); li.remove(); });
  li.append(undo);
}

export function setupWizard() {
  wizard = new CalibrationWizard();
  $('cal-open').addEventListener('click', () => {
    $('cal-wizard').hidden = false;
    $('cal-open').hidden = true;
    document.documentElement.dataset.calibration = 'open';
  });
  for (const row of document.querySelectorAll('.paces tr')) {
    row.querySelector('button').addEventListener('click', () => paceClicked(row));
  }
  $('cal-save').addEventListener('click', save);
  $('cal-gnss-check').addEventListener('click', checkGnss);
  $('profile-select').addEventListener('change', (e) => { profiles.select(e.target.value); showProfiles(); });
  $('profile-export').addEventListener('click', () => {
    const name = profiles.selectedName();
    download(profiles.selected(), `pdr-profile-${safeName(name, '-')}.json`, 'application/json');
  });
  $('profile-import').addEventListener('change', (e) => { if (e.target.files[0]) importProfile(e.target.files[0]); e.target.value = ''; });
  $('profile-delete').addEventListener('click', () => { profiles.remove(profiles.selectedName()); showProfiles(); });
  $('refine').checked = localStorage.getItem('pdr-refine') === 'on';
  $('refine').addEventListener('change', (e) => localStorage.setItem('pdr-refine', e.target.checked ? 'on' : 'off'));
  window.addEventListener('pdr-walk-ended', refineAfterWalk);
  const redraw = () => { for (const band of ['walking', 'running']) { const c = $(`cal-chart-${band}`); if (c) draw(c, band); } };
  dark.addEventListener('change', redraw);
  showProfiles();
}
