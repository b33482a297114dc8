// Service worker: the app shell is cached so that the page opens offline once visited.
// Network first (a new build is picked up at once), the cache when the network fails.
// Copied to the site's root by `./dev build`, so that its scope is the whole app.
//
// Base map tiles (the only images the page loads from another origin, and only when the user
// turned the base map on) are kept in their own cache for offline reuse: cache first, at most
// TILES_MAX of them, the oldest stored evicted first.
const CACHE = 'pdr-shell-v6';
const TILES = 'pdr-tiles-v1';
const TILES_MAX = 2000;
const SHELL = [
  './', 'index.html', 'www/app.js', 'www/live.js', 'www/store.js', 'www/wizard.js', 'www/profiles.js', 'www/upload.js', 'www/recipes.js', 'www/worker.js', 'www/util.js', 'www/style.css',
  'www/basemap.js',
  'www/pkg/pdr.js', 'www/pkg/pdr_bg.wasm', 'www/pkg-upload/pdr.js', 'www/pkg-upload/pdr_bg.wasm',
  'www/manifest.webmanifest', 'www/icon.svg',
];

self.addEventListener('install', (event) => {
  event.waitUntil(caches.open(CACHE).then((c) => c.addAll(SHELL)).then(() => self.skipWaiting()));
});

self.addEventListener('activate', (event) => {
  event.waitUntil((async () => {
    for (const key of await caches.keys()) if (key !== CACHE && key !== TILES) await caches.delete(key);
    await self.clients.claim();
  })());
});

/** A base map tile: from the tile cache, else fetched and stored (CORS responses only, so that
 * the page's canvas stays readable), the cache trimmed to TILES_MAX. */
async function tile(req) {
  const cache = await caches.open(TILES);
  const hit = await cache.match(req);
  if (hit) return hit;
  const res = await fetch(req);
  if (res.ok && res.type === 'cors') {
    await cache.put(req, res.clone());
    const keys = await cache.keys(); // in the order they were stored
    for (const k of keys.slice(0, Math.max(0, keys.length - TILES_MAX))) await cache.delete(k);
  }
  return res;
}

self.addEventListener('fetch', (event) => {
  const req = event.request;
  if (req.method !== 'GET') return;
  if (new URL(req.url).origin !== self.location.origin) {
    if (req.destination === 'image' && req.mode === 'cors') event.respondWith(tile(req));
    return;
  }
  event.respondWith((async () => {
    const cache = await caches.open(CACHE);
    try {
      const res = await fetch(req);
      if (res.ok) cache.put(req, res.clone());
      return res;
    } catch (err) {
      const hit = await cache.match(req, { ignoreSearch: true })
        ?? (req.mode === 'navigate' ? await cache.match('index.html') : undefined);
      if (hit) return hit;
      throw err;
    }
  })());
});
