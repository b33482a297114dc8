// Step-length profiles on this device (localStorage): several named profiles, one selected.
// Each is a profile file's JSON (see src/engine/calibration.rs, `ProfileFile`, version field).
import { readStored } from './util.js';

const LIST = 'pdr-profiles';
const SELECTED = 'pdr-profile';

/** `{name: json}` of every saved profile (none while the stored list is unreadable). */
export const all = () => readStored(LIST, 'step-length profiles') ?? {};

/** Tells the page's other parts (upload mode's profile choice) that the profiles changed. */
const changed = () => window.dispatchEvent(new Event('pdr-profiles-changed'));

/** Changes the stored list with `edit(list)`; refused while the stored list cannot be read. */
function update(edit) {
  const p = readStored(LIST, 'step-length profiles');
  if (!p) throw new Error('The stored profiles cannot be read and cannot be kept aside: nothing was saved.');
  edit(p);
  localStorage.setItem(LIST, JSON.stringify(p));
}

export function save(name, json) {
  update((p) => { p[name] = json; });
  changed();
}

export function remove(name) {
  update((p) => { delete p[name]; });
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
