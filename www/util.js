// What the page's modules share: element lookup, the colour scheme, canvas sizing, downloads,
// and the lists of messages. Browser APIs only; the words are the engine's.
import { stored_not_saved, stored_unreadable } from './pkg/pdr.js';

export const $ = (id) => document.getElementById(id);

/** The colour scheme; `dark.matches` is true in dark mode, `change` fires when it changes. */
export const dark = window.matchMedia('(prefers-color-scheme: dark)');

/** Writes texts from the engine, `[[element id, text]]`, into the page (only those that changed). */
export function fill(texts) {
  for (const [id, text] of texts) { const e = $(id); if (e.textContent !== text) e.textContent = text; }
}

/** Sizes a canvas's backing store to its CSS size × the device pixel ratio (only when it
 * changed), then calls `draw(canvas, dark, ratio)` and returns what it returns; nothing while
 * the canvas has no size. */
export function paint(canvas, draw) {
  const dpr = window.devicePixelRatio || 1;
  const r = canvas.getBoundingClientRect();
  const w = Math.round(r.width * dpr);
  const h = Math.round(r.height * dpr);
  if (w === 0 || h === 0) return undefined;
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  return draw(canvas, dark.matches, dpr);
}

/** Saves `data` (text or a Blob) as a file named `name`. */
export function download(data, name, type = 'text/plain') {
  const url = URL.createObjectURL(data instanceof Blob ? data : new Blob([data], { type }));
  const a = Object.assign(document.createElement('a'), { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Shows `text` as the message `key` of the list `listId` (`kind`: error, warn or ok), or
 * removes it when `text` is empty. Returns the item. */
export function note(listId, key, text, kind = 'warn') {
  const list = $(listId);
  let li = list.querySelector(`[data-key="${key}"]`);
  if (!text) { li?.remove(); return null; }
  if (!li) {
    li = document.createElement('li');
    li.dataset.key = key;
    list.append(li);
  }
  li.className = kind;
  li.textContent = text;
  return li;
}

/** An element: `tag` with `props` assigned and `children` appended. */
export function el(tag, props = {}, ...children) {
  const e = Object.assign(document.createElement(tag), props);
  e.append(...children);
  return e;
}

/** A small button saying `text` that calls `onclick`. */
export const smallButton = (text, onclick) =>
  el('button', { type: 'button', className: 'small', textContent: text, onclick });

/** The values of the controls `selector` finds in `root`, by name (a setting's path); numbers as
 * numbers. */
export const values = (root, selector) => Object.fromEntries([...root.querySelectorAll(selector)]
  .map((c) => [c.name, c.type === 'number' ? c.valueAsNumber : c.value]));

/** The elements a view tree from the engine describes (src/view.rs): `[tag, {attribute: value},
 * [children]]`, a child being a tree or text. */
export function render(node) {
  if (typeof node === 'string') return node;
  const [tag, attrs, children] = node;
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  e.append(...children.map(render));
  return e;
}

/** `name` as a file name: every run of characters other than letters, digits, `_` (and those in
 * `keep`, `.-` by default) becomes one `_`. */
export const safeName = (name, keep = '.-') => name.replace(new RegExp(`[^\\w${keep}]+`, 'g'), '_');

/** Upload mode's wasm module (`pkg-upload/`: the importers, the analyses' views and their gestures,
 * the recipe form), which the page's own module leaves out so that the page starts sooner:
 * loaded and started at the first call; its exports once loaded, `null` before. */
export let uploadExports = null;
const uploadLoaded = []; // called with the exports once they are loaded
let uploadLoading = null;
export function uploadWasm() {
  uploadLoading ??= import('./pkg-upload/pdr.js').then(async (m) => {
    await m.default();
    uploadExports = m;
    for (const f of uploadLoaded) f(m);
    return m;
  });
  return uploadLoading;
}

/** Calls `f(exports)` once upload mode's module is loaded (at once when it is). */
export function onUploadWasm(f) {
  if (uploadExports) f(uploadExports);
  else uploadLoaded.push(f);
}

/** The page's state for the end-to-end tests and the curious, in one place: `demo`, `upload`,
 * `live`, `recovery`, `calibration`, `storage` (each set by the part it describes). */
export const test = (window.__pdrTest ??= {});

/**
 * The object stored as JSON under `key` in localStorage (`{}` when there is none). Text that
 * does not read as one (damaged by hand, by an old version, by a full disk) is never overwritten:
 * it is moved to `<key>-unreadable-<time>` and stays there until the user deletes it; the page
 * says so in the list `storage-messages` (`what` names the store in words). When it cannot be
 * moved (storage full), it stays under `key` and `null` is returned: the caller must not save.
 */
export function readStored(key, what) {
  const text = localStorage.getItem(key);
  let value = {};
  try { if (text != null) value = JSON.parse(text); } catch { value = null; }
  if (value && typeof value === 'object' && !Array.isArray(value)) {
    showAside(key, what);
    return value;
  }
  try {
    localStorage.setItem(`${key}-unreadable-${new Date().toISOString()}`, text);
    localStorage.removeItem(key);
  } catch {
    storageNote(key, stored_unreadable(what, []));
    return null;
  }
  showAside(key, what);
  return {};
}

/** Changes the object stored as JSON under `key` (see `readStored`) with `edit(object)`;
 * refused while the stored text can be neither read nor kept aside. */
export function editStored(key, what, edit) {
  const value = readStored(key, what);
  if (!value) throw new Error(stored_not_saved(what));
  edit(value);
  localStorage.setItem(key, JSON.stringify(value));
}

/** The message about the unreadable texts kept aside for `key`, with a download and a delete. */
function showAside(key, what) {
  const kept = Object.keys(localStorage).filter((k) => k.startsWith(`${key}-unreadable-`)).sort();
  if (!kept.length) { storageNote(key, null); return; }
  const li = storageNote(key, stored_unreadable(what, kept));
  const save = () => { for (const k of kept) download(localStorage.getItem(k), `${safeName(k)}.json`, 'application/json'); };
  const forget = () => { for (const k of kept) localStorage.removeItem(k); storageNote(key, null); };
  li.append(smallButton('Download it', save), ' ', smallButton('Delete it', forget));
}

function storageNote(key, text) {
  const li = note('storage-messages', key, text, 'error');
  $('storage-messages').hidden = !$('storage-messages').children.length;
  return li;
}
