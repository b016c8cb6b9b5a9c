// The web client's service worker: it keeps this build's page, scripts,
// wasm, manifest and icons in a cache of their own, so the game opens
// without a network: the physics sandbox then works, and so do matches
// against the computer, played in the page (the levels are in the wasm,
// the noise secret comes from chapaev.js; matches against people need the
// server). The server's build fills in
// the cache's name (this build's page hash) and the list of files (their
// build-hashed addresses); a new build installs a new worker, which drops
// the old cache once it takes over.
"use strict";
const CACHE = "chapaev-__CHAPAEV_BUILD__";
const FILES = __CHAPAEV_FILES__;

self.addEventListener("install", (e) => {
    e.waitUntil(caches.open(CACHE).then((c) => c.addAll(FILES)).then(() => self.skipWaiting()));
});

self.addEventListener("activate", (e) => {
    e.waitUntil(
        caches.keys()
            .then((keys) => Promise.all(keys
                .filter((k) => k.startsWith("chapaev-") && k !== CACHE)
                .map((k) => caches.delete(k))))
            .then(() => self.clients.claim())
    );
});

self.addEventListener("fetch", (e) => {
    const req = e.request;
    if (req.method !== "GET") return;
    const url = new URL(req.url);
    // The API and the WebSockets always go to the server.
    if (url.origin !== self.location.origin || url.pathname.startsWith("/api") || url.pathname === "/ws") return;
    if (req.mode === "navigate") {
        // The page: from the network when there is one (it may name a new
        // build), else the cached page.
        e.respondWith(fetch(req).catch(() => caches.open(CACHE).then((c) => c.match("/"))));
        return;
    }
    // Every other file is named by its build: the cached copy first.
    e.respondWith(caches.match(req).then((hit) => hit || fetch(req)));
});
