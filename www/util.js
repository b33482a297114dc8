// What the page's modules share: element lookup, the colour scheme, canvas sizing, downloads,
// and the lists of messages. Browser APIs only.

export const $ = (id) => document.getElementById(id);

/** The colour scheme; `dark.matches` is true in dark mode, `change` fires when it changes. */
export const dark = window.matchMedia('(prefers-color-scheme: dark)');

/** Sizes a canvas's backing store to its CSS size × the device pixel ratio (only when it
 * changed); returns the ratio, or 0 while the canvas has no size. */
export function fit(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const r = canvas.getBoundingClientRect();
  const w = Math.round(r.width * dpr);
  const h = Math.round(r.height * dpr);
  if (w === 0 || h === 0) return 0;
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  return dpr;
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
