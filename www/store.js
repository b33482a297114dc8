// The live recording in IndexedDB: one row per recording, its pdr-log text in small chunks
// appended in order, so that a reload or a crash loses at most the last batch.
import { pieces_in_order, tail_missing } from './pkg/pdr.js';

const DB = 'pdr';

function request(r) {
  return new Promise((resolve, reject) => {
    r.onsuccess = () => resolve(r.result);
    r.onerror = () => reject(r.error);
  });
}

let db;
async function open() {
  if (db) return db;
  const r = indexedDB.open(DB, 1);
  r.onupgradeneeded = () => {
    const d = r.result;
    d.createObjectStore('recordings', { keyPath: 'id' });
    d.createObjectStore('chunks', { autoIncrement: true }).createIndex('rec', 'rec');
  };
  db = await request(r);
  return db;
}

/**
 * Runs `fn(...objectStores)` in one transaction; resolves once it has committed, rejects when it
 * aborts (a quota error, a request refused) or `fn` throws (then nothing of it is written).
 */
async function tx(stores, mode, fn) {
  const d = await open();
  const t = d.transaction(stores, mode);
  const why = (e) => t.error ?? e?.target?.error ?? new DOMException('the transaction was aborted before it was committed', 'AbortError');
  const done = new Promise((resolve, reject) => {
    t.oncomplete = resolve;
    t.onerror = (e) => reject(why(e));
    t.onabort = (e) => reject(why(e));
  });
  let result;
  try {
    result = fn(...stores.map((s) => t.objectStore(s)));
  } catch (err) {
    done.catch(() => {});
    try { t.abort(); } catch { /* already finished */ }
    throw err;
  }
  await done;
  return result;
}

/** Starts a recording; older finished ones are removed (one is kept until the next Start). */
export async function create(meta) {
  for (const r of await list()) if (r.state === 'done') await remove(r.id);
  await tx(['recordings'], 'readwrite', (rec) => rec.put({ ...meta, state: 'recording', samples: 0 }));
}

/**
 * Appends chunks `{seq, text, samples, steps}` of pdr-log text, in order, all or none, and the
 * running sample count.
 */
export async function append(id, chunks) {
  const last = chunks.at(-1);
  await tx(['recordings', 'chunks'], 'readwrite', (rec, store) => {
    for (const c of chunks) store.add({ rec: id, ...c });
    update(rec, id, { samples: last.samples, updated: Date.now() });
  });
}

export async function setState(id, state) {
  await tx(['recordings'], 'readwrite', (rec) => update(rec, id, { state }));
}

/** Sets `fields` of the recording `id` in the store `rec` (in its transaction), if it exists. */
function update(rec, id, fields) {
  const g = rec.get(id);
  g.onsuccess = () => { if (g.result) rec.put({ ...g.result, ...fields }); };
}

export async function list() {
  const d = await open();
  return request(d.transaction('recordings').objectStore('recordings').getAll());
}

/** Where the chunks not yet written go when the page is closed (see live.js). */
export const tailKey = (id) => `pdr-tail-${id}`;

/**
 * The stored pieces of a recording, `[{seq, text, samples, steps}]` in order of `seq` (each seq
 * once), with the pieces `extra` (those not yet written) and those saved in localStorage at page
 * close (`tail_missing`); and the next piece number (`pieces_in_order`). What they hold, damaged
 * or not, is for the engine to read (`recover_recording`).
 */
export async function pieces(id, extra = []) {
  const d = await open();
  const get = async () => request(d.transaction('chunks').objectStore('chunks').index('rec').getAll(id));
  let chunks = await get();
  const missing = tail_missing(localStorage.getItem(tailKey(id)), chunks);
  let saved = true;
  if (missing.length) {
    try {
      await tx(['chunks'], 'readwrite', (store) => { for (const c of missing) store.add({ rec: id, ...c }); });
      chunks = await get();
    } catch {
      saved = false; // storage refused: kept in localStorage, read from there again next time
      chunks = chunks.concat(missing);
    }
  }
  if (saved) localStorage.removeItem(tailKey(id));
  return pieces_in_order([...chunks, ...extra]);
}

export async function remove(id) {
  localStorage.removeItem(tailKey(id));
  await tx(['recordings', 'chunks'], 'readwrite', (rec, chunks) => {
    rec.delete(id);
    const c = chunks.index('rec').openKeyCursor(IDBKeyRange.only(id));
    c.onsuccess = () => {
      const cur = c.result;
      if (cur) { chunks.delete(cur.primaryKey); cur.continue(); }
    };
  });
}
