// The web client's miniquad plugin: what the wasm needs from the browser
// beyond macroquad's own bundle. WebSockets, HTTP requests, the page
// address, localStorage, file download and upload, pasted text, short
// sounds, native text inputs over the canvas on touch screens, and the
// readiness flag and state report that the end-to-end test reads.
//
// Strings and bytes cross the boundary by copy: Rust passes (pointer,
// length) into its memory; JS results are queued and Rust asks for their
// length, allocates, then asks JS to copy them in. Everything is polled
// from the frame loop, so no callback ever re-enters the wasm.
"use strict";
(function () {
    const enc = new TextEncoder();
    const dec = new TextDecoder();
    function bytes(ptr, len) {
        return new Uint8Array(wasm_memory.buffer, ptr, len);
    }
    function str(ptr, len) {
        return dec.decode(bytes(ptr, len));
    }
    // Copies `data` (a Uint8Array) into wasm memory at `ptr` (capacity `cap`).
    function put(data, ptr, cap) {
        const n = Math.min(data.length, cap);
        bytes(ptr, n).set(data.subarray(0, n));
        return n;
    }

    // The last string a `*_len` call measured, waiting for its `*_take`.
    let staged = new Uint8Array(0);
    function stage(s) {
        staged = typeof s === "string" ? enc.encode(s) : s;
        return staged.length;
    }

    // ---- Waking the frame loop ---------------------------------------
    // In the browser the app draws only while something changes
    // (web-client/src/pace.rs) and miniquad's loop then waits for an
    // event. Whatever the app would poll for next (a message, a reply,
    // pasted text, a picked file, what was typed in a text input, an edited address)
    // wakes a frame at once; a heartbeat wakes one twice a second for
    // clocks and polls.
    let schedule_update = null;
    function wake() {
        if (schedule_update !== null && window.blocking_event_loop) schedule_update();
    }
    setInterval(wake, 500);
    window.addEventListener("hashchange", wake);

    // ---- WebSockets --------------------------------------------------
    const sockets = new Map();
    let next_socket = 1;

    function ws_open(ptr, len) {
        const id = next_socket++;
        const entry = { state: 0, inbox: [], ws: null };
        sockets.set(id, entry);
        try {
            const ws = new WebSocket(str(ptr, len));
            ws.binaryType = "arraybuffer";
            ws.onopen = () => { entry.state = 1; wake(); };
            ws.onmessage = (e) => {
                entry.inbox.push(typeof e.data === "string" ? enc.encode(e.data) : new Uint8Array(e.data));
                wake();
            };
            ws.onerror = () => { entry.state = 2; wake(); };
            ws.onclose = () => { entry.state = 2; wake(); };
            entry.ws = ws;
        } catch (e) {
            console.error(e);
            entry.state = 2;
        }
        return id;
    }
    // 0 connecting, 1 open, 2 closed or failed, 3 no such socket.
    function ws_state(id) {
        const s = sockets.get(id);
        return s ? s.state : 3;
    }
    function ws_send(id, ptr, len) {
        const s = sockets.get(id);
        if (!s || s.state !== 1) return 0;
        s.ws.send(str(ptr, len));
        return 1;
    }
    // Length of the next message, or -1 when none is waiting.
    function ws_next_len(id) {
        const s = sockets.get(id);
        if (!s || s.inbox.length === 0) return -1;
        return s.inbox[0].length;
    }
    function ws_take(id, ptr, cap) {
        const s = sockets.get(id);
        if (!s || s.inbox.length === 0) return 0;
        return put(s.inbox.shift(), ptr, cap);
    }
    function ws_close(id) {
        const s = sockets.get(id);
        if (!s) return;
        try { if (s.ws) s.ws.close(); } catch (e) { /* already closed */ }
        sockets.delete(id);
    }

    // ---- HTTP --------------------------------------------------------
    const requests = new Map();
    let next_request = 1;

    // `aptr, alen`: an Authorization header's value (empty: none).
    function http_start(mptr, mlen, uptr, ulen, bptr, blen, aptr, alen) {
        const id = next_request++;
        const entry = { status: 0, body: new Uint8Array(0) };
        requests.set(id, entry);
        const init = { method: str(mptr, mlen), headers: {} };
        if (blen > 0) {
            init.body = str(bptr, blen);
            init.headers["content-type"] = "application/json";
        }
        if (alen > 0) init.headers["authorization"] = str(aptr, alen);
        fetch(str(uptr, ulen), init)
            .then(async (r) => {
                entry.body = new Uint8Array(await r.arrayBuffer());
                entry.status = r.status;
                wake();
            })
            .catch((e) => {
                entry.body = enc.encode(String(e));
                entry.status = -1;
                wake();
            });
        return id;
    }
    // 0 pending, -1 network failure, else the HTTP status.
    function http_status(id) {
        const r = requests.get(id);
        return r ? r.status : -1;
    }
    function http_body_len(id) {
        const r = requests.get(id);
        return r ? r.body.length : 0;
    }
    function http_take(id, ptr, cap) {
        const r = requests.get(id);
        if (!r) return 0;
        requests.delete(id);
        return put(r.body, ptr, cap);
    }

    // ---- Page, storage, files ------------------------------------------
    function location_len() {
        return stage(window.location.href);
    }
    function staged_take(ptr, cap) {
        return put(staged, ptr, cap);
    }
    function set_hash(ptr, len) {
        const hash = str(ptr, len);
        if (window.location.hash !== hash) history.replaceState(null, "", hash || "#");
    }
    function storage_get_len(kptr, klen) {
        let v = null;
        try { v = window.localStorage.getItem(str(kptr, klen)); } catch (e) { v = null; }
        return v === null ? -1 : stage(v);
    }
    function storage_set(kptr, klen, vptr, vlen) {
        try { window.localStorage.setItem(str(kptr, klen), str(vptr, vlen)); } catch (e) { /* private mode */ }
    }
    function download(nptr, nlen, dptr, dlen) {
        const blob = new Blob([bytes(dptr, dlen).slice()], { type: "application/json" });
        const a = document.createElement("a");
        a.href = URL.createObjectURL(blob);
        a.download = str(nptr, nlen);
        document.body.appendChild(a);
        a.click();
        setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
    }
    let picked = null;
    function pick_file() {
        const input = document.createElement("input");
        input.type = "file";
        input.accept = ".json,application/json";
        input.onchange = async () => {
            if (input.files.length > 0) picked = new Uint8Array(await input.files[0].arrayBuffer());
            wake();
        };
        input.click();
    }
    function picked_len() {
        if (picked === null) return -1;
        const n = stage(picked);
        picked = null;
        return n;
    }

    function copy_text(ptr, len) {
        const text = str(ptr, len);
        if (navigator.clipboard && navigator.clipboard.writeText) {
            navigator.clipboard.writeText(text).catch((e) => console.warn(e));
        }
    }

    // ---- Paste and sound -------------------------------------------------
    // Pasted text waits here until the frame loop takes it (macroquad only
    // keeps it for its own clipboard call, which nothing polls).
    let pasted = null;
    window.addEventListener("paste", (e) => {
        const data = e.clipboardData || window.clipboardData;
        const text = data ? data.getData("text") : "";
        if (text) pasted = pasted === null ? text : pasted + text;
        wake();
    }, true);
    function pasted_len() {
        if (pasted === null) return -1;
        const n = stage(pasted);
        pasted = null;
        return n;
    }
    // Wood on wood, synthesised (no sound files to download): a flick is a
    // dry tick, a collision a clack (a burst of noise through a resonant
    // band-pass, louder and brighter the harder the pieces met), a piece
    // landing on the table below a low thud, your turn a soft tone. On a
    // phone a firm hit also buzzes (navigator.vibrate, where allowed).
    // Every sound asked for is noted in window.chapaevSounds (the last
    // 500), which the browser test reads.
    let audio = null;
    let noise = null;
    const heard = [];
    window.chapaevSounds = heard;
    function context() {
        audio = audio || new (window.AudioContext || window.webkitAudioContext)();
        if (audio.state === "suspended") audio.resume().catch(() => {});
        return audio;
    }
    function noiseBuffer(a) {
        if (!noise) {
            noise = a.createBuffer(1, Math.round(a.sampleRate * 0.2), a.sampleRate);
            const d = noise.getChannelData(0);
            for (let i = 0; i < d.length; i++) d[i] = Math.random() * 2 - 1;
        }
        return noise;
    }
    function knock(a, t, freq, q, seconds, gain) {
        const src = a.createBufferSource();
        src.buffer = noiseBuffer(a);
        const band = a.createBiquadFilter();
        band.type = "bandpass";
        band.frequency.value = freq;
        band.Q.value = q;
        const g = a.createGain();
        g.gain.setValueAtTime(gain, t);
        g.gain.exponentialRampToValueAtTime(0.0001, t + seconds);
        src.connect(band).connect(g).connect(a.destination);
        src.start(t);
        src.stop(t + seconds + 0.01);
    }
    function tone(a, t, from, to, seconds, gain) {
        const osc = a.createOscillator();
        const g = a.createGain();
        osc.type = "sine";
        osc.frequency.setValueAtTime(from, t);
        osc.frequency.exponentialRampToValueAtTime(to, t + seconds);
        g.gain.setValueAtTime(gain, t);
        g.gain.exponentialRampToValueAtTime(0.0001, t + seconds);
        osc.connect(g).connect(a.destination);
        osc.start(t);
        osc.stop(t + seconds + 0.02);
    }
    function sound(kind, loudness) {
        const name = ["flick", "fall", "turn", "clack"][kind] || "other";
        heard.push({ kind: name, loudness });
        if (heard.length > 500) heard.shift();
        if (name === "clack" && loudness > 0.3 && navigator.vibrate) {
            const ms = Math.round(8 + 22 * loudness);
            try {
                if (navigator.vibrate(ms)) heard.push({ kind: "vibrate", loudness: ms });
            } catch (e) { /* not allowed here */ }
        }
        try {
            const a = context();
            const t = a.currentTime;
            if (name === "flick") {
                knock(a, t, 3400, 1.2, 0.03, 0.12);
            } else if (name === "clack") {
                const l = Math.min(Math.max(loudness, 0), 1);
                knock(a, t, 1500 + 900 * l + 200 * Math.random(), 9, 0.06 + 0.05 * l, 0.05 + 0.55 * l);
                tone(a, t, 1150 + 150 * l, 1050, 0.05, 0.04 * l);
            } else if (name === "fall") {
                tone(a, t, 170, 55, 0.22, 0.35);
                knock(a, t, 420, 1.5, 0.14, 0.25);
            } else {
                tone(a, t, 880, 880, 0.12, 0.12);
            }
        } catch (e) { /* no audio here */ }
    }

    // ---- Text on touch screens ------------------------------------------
    // A canvas never raises a phone's keyboard. On a touch screen each text
    // field the client draws gets a real <input> laid exactly over it (same
    // place, size and colours), so a tap reaches the input itself and the
    // keyboard opens, with the browser's own editing, autocorrect and input
    // methods. The wasm places the inputs every frame (field_place), takes
    // what was typed (field_take_len) and learns of focus and Enter
    // (field_flags); an input not placed in the last frame is removed
    // (field_sweep, at the start of each frame).
    // 32 random bits from the browser's cryptographic generator (an
    // offline match's noise secret and its computer's seed).
    function random_u32() {
        const word = new Uint32Array(1);
        crypto.getRandomValues(word);
        return word[0] | 0;
    }
    function coarse_pointer() {
        return window.matchMedia && window.matchMedia("(pointer: coarse)").matches ? 1 : 0;
    }
    function languages_len() {
        const list = navigator.languages && navigator.languages.length
            ? navigator.languages : [navigator.language || ""];
        return stage(list.join(","));
    }
    function set_document_lang(ptr, len) {
        document.documentElement.lang = str(ptr, len);
    }
    const fields = new Map();
    let field_frame = 0;
    function field_sweep() {
        field_frame += 1;
        for (const [name, f] of fields) {
            if (f.placed < field_frame - 1) {
                f.el.remove();
                fields.delete(name);
            }
        }
    }
    function field_place(nptr, nlen, x, y, w, h, vptr, vlen, pptr, plen, max) {
        const name = str(nptr, nlen);
        let f = fields.get(name);
        if (!f) {
            const el = document.createElement("input");
            el.type = "text";
            el.autocomplete = "off";
            el.spellcheck = false;
            el.enterKeyHint = "done";
            el.setAttribute("data-chapaev-field", name);
            Object.assign(el.style, {
                position: "absolute", boxSizing: "border-box", margin: "0",
                padding: "0 8px", border: "1.5px solid #e0a040", borderRadius: "0",
                outline: "none", background: "#1a140f", color: "#f0e6d2",
                fontFamily: "sans-serif", zIndex: "2",
            });
            f = { el, placed: 0, changed: null, entered: false };
            el.addEventListener("input", () => { f.changed = el.value; wake(); });
            el.addEventListener("keydown", (e) => {
                if (e.key === "Enter") { f.entered = true; wake(); }
            });
            el.addEventListener("focus", wake);
            el.addEventListener("blur", wake);
            // Pasting is the input's own: keep it from macroquad's page-wide
            // handler, which would cancel it.
            el.addEventListener("paste", (e) => e.stopPropagation());
            document.body.appendChild(el);
            fields.set(name, f);
        }
        f.placed = field_frame;
        const el = f.el;
        Object.assign(el.style, {
            left: x + "px", top: y + "px", width: w + "px", height: h + "px",
            fontSize: Math.max(12, Math.min(20, h * 0.45)) + "px",
        });
        el.placeholder = str(pptr, plen);
        el.maxLength = max;
        const value = str(vptr, vlen);
        if (f.changed === null && el.value !== value) el.value = value;
    }
    function field_take_len(nptr, nlen) {
        const f = fields.get(str(nptr, nlen));
        if (!f || f.changed === null) return -1;
        const n = stage(f.changed);
        f.changed = null;
        return n;
    }
    function field_flags(nptr, nlen) {
        const f = fields.get(str(nptr, nlen));
        if (!f) return 0;
        let flags = document.activeElement === f.el ? 1 : 0;
        if (f.entered) {
            flags |= 2;
            f.entered = false;
        }
        return flags;
    }

    // ---- Test hooks ------------------------------------------------------
    function set_ready() {
        window.chapaev_ready_ms = performance.now();
        window.chapaev_ready = true;
    }
    function report(ptr, len) {
        try { window.chapaev_state = JSON.parse(str(ptr, len)); } catch (e) { console.error(e); }
    }

    function register_plugin(importObject) {
        const env = importObject.env;
        schedule_update = env.sapp_schedule_update;
        env.chapaev_ws_open = ws_open;
        env.chapaev_ws_state = ws_state;
        env.chapaev_ws_send = ws_send;
        env.chapaev_ws_next_len = ws_next_len;
        env.chapaev_ws_take = ws_take;
        env.chapaev_ws_close = ws_close;
        env.chapaev_http_start = http_start;
        env.chapaev_http_status = http_status;
        env.chapaev_http_body_len = http_body_len;
        env.chapaev_http_take = http_take;
        env.chapaev_location_len = location_len;
        env.chapaev_staged_take = staged_take;
        env.chapaev_set_hash = set_hash;
        env.chapaev_storage_get_len = storage_get_len;
        env.chapaev_storage_set = storage_set;
        env.chapaev_download = download;
        env.chapaev_pick_file = pick_file;
        env.chapaev_picked_len = picked_len;
        env.chapaev_copy = copy_text;
        env.chapaev_set_ready = set_ready;
        env.chapaev_report = report;
        env.chapaev_pasted_len = pasted_len;
        env.chapaev_sound = sound;
        env.chapaev_coarse_pointer = coarse_pointer;
        env.chapaev_random_u32 = random_u32;
        env.chapaev_field_sweep = field_sweep;
        env.chapaev_field_place = field_place;
        env.chapaev_field_take_len = field_take_len;
        env.chapaev_field_flags = field_flags;
        env.chapaev_languages_len = languages_len;
        env.chapaev_set_document_lang = set_document_lang;
    }
    // macroquad listens for the mouse on the canvas only: a slingshot pulled
    // past the page's edge would never be released. Forward what happens
    // elsewhere during a drag.
    function on_init() {
        const canvas = document.querySelector("#glcanvas");
        // The right button aims and pans in the sandbox: no context menu.
        canvas.addEventListener("contextmenu", (e) => e.preventDefault());
        // In device pixels, as miniquad's own handlers report them.
        const at = (e) => {
            const r = canvas.getBoundingClientRect();
            const dpr = window.devicePixelRatio || 1;
            return [(e.clientX - r.left) * dpr, (e.clientY - r.top) * dpr];
        };
        window.addEventListener("mousemove", (e) => {
            if (e.target === canvas) return;
            const [x, y] = at(e);
            wasm_exports.mouse_move(Math.floor(x), Math.floor(y));
        });
        window.addEventListener("mouseup", (e) => {
            if (e.target === canvas) return;
            const [x, y] = at(e);
            wasm_exports.mouse_up(x, y, e.button === 2 ? 1 : e.button === 1 ? 2 : e.button);
        });
    }

    miniquad_add_plugin({ register_plugin, on_init, version: 1, name: "chapaev" });
})();
