// Step-length profiles on this device (localStorage): several named profiles, one selected.
// Each is a profile file's JSON (see src/engine/calibration.rs, `ProfileFile`, version field).
const LIST = 'pdr-profiles';
const SELECTED = 'pdr-profile';

/** `{name: json}` of every saved profile. */
export function all() {
  try { return JSON.parse(localStorage.getItem(LIST) ?? '{}'); } catch { return {}; }
}

/** Tells the page's other parts (upload mode's profile choice) that the profiles changed. */
const changed = () => window.dispatchEvent(new Event('pdr-profiles-changed'));

export function save(name, json) {
  const p = all();
  p[name] = json;
  localStorage.setItem(LIST, JSON.stringify(p));
  changed();
}

export function remove(name) {
  const p = all();
  delete p[name];
  localStorage.setItem(LIST, JSON.stringify(p));
  if (selectedName() === name) select('');
  changed();
}

/** The selected profile's name ('' for the built-in default). */
export function selectedName() {
  const n = localStorage.getItem(SELECTED) ?? '';
  return n in all() ? n : '';
}

export function select(name) {
  localStorage.setItem(SELECTED, name);
  changed();
}

/** The selected profile's JSON, or undefined for the built-in default. */
export function selected() {
  const n = selectedName();
  return n ? all()[n] : undefined;
}
