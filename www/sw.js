// Service worker: the app shell is cached so that the page opens offline once visited.
// Network first (a new build is picked up at once), the cache when the network fails.
// Copied to the site's root by `./dev build`, so that its scope is the whole app.
const CACHE = 'pdr-shell-v4';
const SHELL = [
  './', 'index.html', 'www/app.js', 'www/live.js', 'www/store.js', 'www/wizard.js', 'www/profiles.js', 'www/upload.js', 'www/recipes.js', 'www/worker.js', 'www/util.js', 'www/style.css',
  'www/pkg/pdr.js', 'www/pkg/pdr_bg.wasm', 'www/manifest.webmanifest', 'www/icon.svg',
];

self.addEventListener('install', (event) => {
  event.waitUntil(caches.open(CACHE).then((c) => c.addAll(SHELL)).then(() => self.skipWaiting()));
});

self.addEventListener('activate', (event) => {
  event.waitUntil((async () => {
    for (const key of await caches.keys()) if (key !== CACHE) await caches.delete(key);
    await self.clients.claim();
  })());
});

self.addEventListener('fetch', (event) => {
  const req = event.request;
  if (req.method !== 'GET' || new URL(req.url).origin !== self.location.origin) return;
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
