// The live recording in IndexedDB: one row per recording, its pdr-log text in small chunks
// appended in order, so that a reload or a crash loses at most the last batch.
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

async function tx(stores, mode, fn) {
  const d = await open();
  const t = d.transaction(stores, mode);
  const done = new Promise((resolve, reject) => {
    t.oncomplete = resolve;
    t.onerror = () => reject(t.error);
    t.onabort = () => reject(t.error);
  });
  const result = fn(...stores.map((s) => t.objectStore(s)));
  await done;
  return result;
}

/** Starts a recording; older finished ones are removed (one is kept until the next Start). */
export async function create(meta) {
  for (const r of await list()) if (r.state === 'done') await remove(r.id);
  await tx(['recordings'], 'readwrite', (rec) => rec.put({ ...meta, state: 'recording', samples: 0 }));
}

/** Appends a chunk `{seq, text}` of pdr-log text, and the running sample count. */
export async function append(id, chunk, samples) {
  await tx(['recordings', 'chunks'], 'readwrite', (rec, chunks) => {
    chunks.add({ rec: id, ...chunk });
    const g = rec.get(id);
    g.onsuccess = () => { if (g.result) rec.put({ ...g.result, samples, updated: Date.now() }); };
  });
}

export async function setState(id, state) {
  await tx(['recordings'], 'readwrite', (rec) => {
    const g = rec.get(id);
    g.onsuccess = () => { if (g.result) rec.put({ ...g.result, state }); };
  });
}

export async function list() {
  const d = await open();
  return request(d.transaction('recordings').objectStore('recordings').getAll());
}

/** Where the chunks not yet written go when the page is closed (see live.js). */
export const tailKey = (id) => `pdr-tail-${id}`;

/**
 * The whole pdr-log text of a recording, and the next chunk number. Chunks saved in
 * localStorage at page close are added first, those IndexedDB lacks.
 */
export async function text(id) {
  const d = await open();
  const get = async () => request(d.transaction('chunks').objectStore('chunks').index('rec').getAll(id));
  let chunks = await get();
  const tail = localStorage.getItem(tailKey(id));
  if (tail) {
    const have = new Set(chunks.map((c) => c.seq));
    const missing = JSON.parse(tail).filter((c) => !have.has(c.seq));
    if (missing.length) {
      await tx(['chunks'], 'readwrite', (store) => { for (const c of missing) store.add({ rec: id, ...c }); });
      chunks = await get();
    }
    localStorage.removeItem(tailKey(id));
  }
  chunks.sort((a, b) => a.seq - b.seq);
  return { text: chunks.map((c) => c.text).join(''), nextSeq: chunks.length ? chunks.at(-1).seq + 1 : 0 };
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
