// The step-length calibration wizard and the profiles panel. This only drives the steps: the
// walks run through live mode's session (sensors, pocket guard, wake lock) or come from a
// recording the engine reads (CalibrationWizard.recorded), and every figure —
// eq. 1 and 2, the fits, their warnings, the fuzzy scale, the profile, its chart, the
// refinement — comes from the engine (CalibrationWizard, profile_summary, refine_profile in
// src/web/calibration.rs), and so do the words and the fits box (src/live/wizard.rs).
import {
  CalibrationWizard, gnss_state, import_profile, profile_summary, profiles_view, refine_profile, walk_title,
  wizard_message,
} from './pkg/pdr.js';
import { settings as liveSettings, startWalk } from './live.js';
import * as profiles from './profiles.js';
import { $, dark, download, note, paint, render, safeName, smallButton, test, uploadWasm } from './util.js';

let wizard; // made in setupWizard, once the engine is loaded
let walking = null; // { session, row, button, result, pace, band, target, gnss }

const source = () => document.querySelector('input[name=cal-source]:checked').value;

/** Starts or stops the walk of a pace row. */
async function paceClicked(row) {
  if (walking) {
    if (walking.row === row) await finish();
    return;
  }
  const { pace, band } = row.dataset;
  const gnss = source() === 'gnss';
  const target = Number(gnss ? $('cal-gnss-distance').value : $('cal-distance').value);
  const title = walk_title(pace, target, gnss); // none without a distance
  note('cal-messages', 'distance', title ? null : wizard_message('distance', ''), 'error');
  if (!title) return;
  const button = row.querySelector('button');
  const result = row.querySelector('.result');
  const session = await startWalk({
    gnss: gnss ? 'best_performance' : 'off',
    messages: 'cal-messages',
    title,
    onTick: (s) => {
      if (walking?.session !== s) return;
      const walk = s.live.calibration_walk(target, gnss);
      result.textContent = walk.text;
      if (walk.done) finish();
    },
  });
  if (!session) {
    note('cal-messages', 'busy', wizard_message('busy', ''), 'error');
    return;
  }
  walking = { session, row, button, result, pace, band, target, gnss };
  button.textContent = 'Stop';
  button.classList.add('running');
  result.classList.remove('error');
  document.documentElement.dataset.calibration = 'walking';
}

/** Ends the running walk and adds its point; the comfortable (normal) walk also calibrates the
 * leg-pitch step length (Munoz Diaz 2015 §5.1), when its steps had a leg pitch (engine's walked). */
async function finish() {
  const w = walking;
  if (!w || w.finishing) return;
  w.finishing = true;
  await w.session.stop();
  walking = null;
  w.button.textContent = 'Walk again';
  w.button.classList.remove('running');
  const r = wizard.walked(w.band, w.pace, w.session.live, w.target, w.gnss);
  w.result.textContent = r.text;
  w.result.classList.toggle('error', r.error);
  showPitch(r.pitch);
  document.documentElement.dataset.calibration = 'walked';
  refresh();
}

/** What the normal walk (or a recording) gave the leg-pitch step length, or why it gave nothing. */
function showPitch(pitch) {
  if (!pitch) return;
  $('cal-pitch').textContent = pitch.text;
  $('cal-pitch').dataset.pitch = pitch.ok ? 'ok' : 'refused';
}

/** Adds a recording of a walk over the typed distance as a walking walk: the engine reads the
 * file and runs it with live mode's settings (read_recorded_walk, in upload mode's module), and
 * the wizard adds the walk (CalibrationWizard.recorded). */
async function recordingChosen(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  const { read_recorded_walk } = await uploadWasm();
  const read = read_recorded_walk(file.name, bytes, Number($('cal-distance').value), liveSettings());
  const r = wizard.recorded(file.name, read);
  $('cal-recording-result').textContent = r.text;
  $('cal-recording-result').classList.toggle('error', r.error);
  showPitch(r.pitch);
  document.documentElement.dataset.calibration = 'walked';
  refresh();
}

/** Redraws the fits, warnings and notes from the engine's state (its view trees). */
function refresh() {
  const st = wizard.state();
  const view = wizard.view();
  $('cal-fits').replaceChildren(...view.fits.map(render));
  redraw();
  // The notes end with the fitted fuzzy scale, when the walks measured one (engine's text).
  $('cal-notes').replaceChildren(...view.notes.map(render));
  $('cal-save').disabled = st.walking.points + st.running.points === 0;
  test.calibration = st;
}

/** Draws the fits' charts (canvases `cal-chart-<band>`) at their sizes on the page. */
function redraw() {
  for (const canvas of $('cal-fits').querySelectorAll('canvas')) {
    paint(canvas, (...a) => wizard.draw(...a, canvas.id.replace('cal-chart-', '')));
  }
}

/** Saves the walks' profile (with the leg-pitch offset when the normal walk gave one) and
 * selects it. */
function save() {
  const p = wizard.profile($('cal-name').value);
  profiles.save(p.name, p.json);
  profiles.select(p.name);
  showProfiles();
  note('cal-messages', 'saved', p.text, 'ok');
  document.documentElement.dataset.profile = 'saved';
}

// --- GNSS availability for the GNSS distance source ---------------------------------------
function checkGnss() {
  const say = (state) => { $('cal-gnss-state').textContent = gnss_state(state).text; };
  if (!navigator.geolocation) { say('missing'); return; }
  say('waiting');
  const id = navigator.geolocation.watchPosition((p) => {
    const s = gnss_state('fix', p.coords.accuracy);
    $('cal-gnss-state').textContent = s.text;
    $('cal-gnss-radio').disabled = !s.good;
    if (!s.good && source() === 'gnss') document.querySelector('input[value=typed]').checked = true;
  }, (err) => say(err.code === err.PERMISSION_DENIED ? 'refused' : 'failed'), { enableHighAccuracy: true, maximumAge: 0, timeout: 30_000 });
  setTimeout(() => navigator.geolocation.clearWatch(id), 60_000);
}

// --- profiles ---------------------------------------------------------------------------
function showProfiles() {
  const panel = profiles_view(Object.keys(profiles.all()), profiles.selectedName());
  $('profile-select').replaceChildren(...panel.options.map(render));
  const json = profiles.selected();
  $('profile-in-use').textContent = panel.in_use;
  $('profile-export').disabled = !json;
  $('profile-delete').disabled = !json;
  $('profile-values').textContent = profile_summary(json).text;
}

async function importProfile(file) {
  const text = await file.text();
  const r = import_profile(file.name, text, profiles.all());
  if (r.error) {
    note('profile-messages', 'import', r.error, 'error');
    return;
  }
  profiles.save(r.name, text);
  profiles.select(r.name);
  note('profile-messages', 'import', r.text, 'ok');
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
  li.append(smallButton('Undo', () => { profiles.save(name, json); showProfiles(); li.remove(); }));
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
  $('cal-recording').addEventListener('change', (e) => {
    if (e.target.files[0]) recordingChosen(e.target.files[0]);
    e.target.value = '';
  });
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
  $('cal-fits').addEventListener('click', (e) => {
    if (e.target.dataset.walk != null) { wizard.remove_walk(Number(e.target.dataset.walk)); refresh(); }
  });
  dark.addEventListener('change', redraw);
  showProfiles();
}
