// Step-length profiles on this device (localStorage): several named profiles, one selected.
// Each is a profile file's JSON (see src/engine/calibration.rs, `ProfileFile`, version field).
import { editStored, readStored } from './util.js';

const LIST = 'pdr-profiles';
const SELECTED = 'pdr-profile';
const WHAT = 'step-length profiles';

/** `{name: json}` of every saved profile (none while the stored list is unreadable). */
export const all = () => readStored(LIST, WHAT) ?? {};

/** Tells the page's other parts (upload mode's profile choice) that the profiles changed. */
const changed = () => window.dispatchEvent(new Event('pdr-profiles-changed'));

export function save(name, json) {
  editStored(LIST, WHAT, (p) => { p[name] = json; });
  changed();
}

export function remove(name) {
  editStored(LIST, WHAT, (p) => { delete p[name]; });
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
