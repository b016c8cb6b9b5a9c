//! The outside world as the client sees it, one API on both targets: a
//! WebSocket, HTTP requests (with an optional `Authorization` header), the page address, persistent key-value
//! storage, saving and opening files, pasted text, short sounds, random
//! bits (the browser's cryptographic generator), native
//! text inputs laid over the canvas's text fields on touch screens (a
//! phone's keyboard never opens for a canvas), and the readiness flag and
//! state report that the browser test reads.
//!
//! In the browser every call goes to the small miniquad plugin in
//! `js/chapaev.js` (loaded after macroquad's `mq_js_bundle.js`); on the
//! desktop the same calls run a blocking WebSocket and HTTP client on
//! background threads, files live in the working folder and the storage in
//! memory. Everything is polled from the frame loop: nothing blocks a frame.

/// Where a WebSocket stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SocketState {
    Connecting,
    Open,
    /// Closed by either side, or failed to connect.
    Closed,
}

/// What an HTTP request came to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HttpReply {
    /// The server answered with this status and body.
    Done { status: u16, body: String },
    /// No answer (the server is unreachable).
    Failed(String),
}

/// The game's short sounds, synthesised by the browser (no sound files):
/// wood on wood. On by default; the player's choice is remembered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sound {
    /// A finger flicked a piece.
    Flick,
    /// Two pieces met; `loudness` 0..1 grows with how hard. On a phone a
    /// firm hit also buzzes briefly, where the browser allows it.
    Clack { loudness: f32 },
    /// A knocked-off piece landed on the table below.
    Fall,
    /// It is your turn.
    YourTurn,
}

impl Sound {
    /// The kind number and loudness the page's synthesiser takes.
    fn code(self) -> (i32, f32) {
        match self {
            Sound::Flick => (0, 0.5),
            Sound::Fall => (1, 0.8),
            Sound::YourTurn => (2, 0.5),
            Sound::Clack { loudness } => (3, loudness.clamp(0.0, 1.0)),
        }
    }
}

/// What a native text input reports (see [`field_flags`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FieldFlags {
    /// It has the keyboard focus.
    pub focused: bool,
    /// Enter was pressed in it since the last call.
    pub entered: bool,
}

#[cfg(target_arch = "wasm32")]
mod imp {
    use super::{HttpReply, SocketState};

    extern "C" {
        fn chapaev_ws_open(ptr: *const u8, len: usize) -> i32;
        fn chapaev_ws_state(id: i32) -> i32;
        fn chapaev_ws_send(id: i32, ptr: *const u8, len: usize) -> i32;
        fn chapaev_ws_next_len(id: i32) -> i32;
        fn chapaev_ws_take(id: i32, ptr: *mut u8, cap: usize) -> i32;
        fn chapaev_ws_close(id: i32);
        fn chapaev_http_start(
            m: *const u8,
            ml: usize,
            u: *const u8,
            ul: usize,
            b: *const u8,
            bl: usize,
            a: *const u8,
            al: usize,
        ) -> i32;
        fn chapaev_http_status(id: i32) -> i32;
        fn chapaev_http_body_len(id: i32) -> i32;
        fn chapaev_http_take(id: i32, ptr: *mut u8, cap: usize) -> i32;
        fn chapaev_location_len() -> i32;
        fn chapaev_staged_take(ptr: *mut u8, cap: usize) -> i32;
        fn chapaev_set_hash(ptr: *const u8, len: usize);
        fn chapaev_storage_get_len(k: *const u8, kl: usize) -> i32;
        fn chapaev_storage_set(k: *const u8, kl: usize, v: *const u8, vl: usize);
        fn chapaev_download(n: *const u8, nl: usize, d: *const u8, dl: usize);
        fn chapaev_pick_file();
        fn chapaev_picked_len() -> i32;
        fn chapaev_copy(ptr: *const u8, len: usize);
        fn chapaev_set_ready();
        fn chapaev_report(ptr: *const u8, len: usize);
        fn chapaev_pasted_len() -> i32;
        fn chapaev_sound(kind: i32, loudness: f32);
        fn chapaev_coarse_pointer() -> i32;
        fn chapaev_random_u32() -> i32;
        fn chapaev_field_sweep();
        #[allow(clippy::too_many_arguments)]
        fn chapaev_field_place(
            n: *const u8,
            nl: usize,
            x: f32,
            y: f32,
            w: f32,
            h: f32,
            v: *const u8,
            vl: usize,
            p: *const u8,
            pl: usize,
            max: u32,
        );
        fn chapaev_field_take_len(n: *const u8, nl: usize) -> i32;
        fn chapaev_field_flags(n: *const u8, nl: usize) -> i32;
        fn chapaev_languages_len() -> i32;
        fn chapaev_set_document_lang(ptr: *const u8, len: usize);
    }

    /// The plugin's version, checked by miniquad's loader against `chapaev.js`.
    #[no_mangle]
    pub extern "C" fn chapaev_crate_version() -> u32 {
        1
    }

    fn take(len: i32, fill: impl FnOnce(*mut u8, usize) -> i32) -> String {
        let mut buf = vec![0u8; len.max(0) as usize];
        let n = fill(buf.as_mut_ptr(), buf.len()).max(0) as usize;
        buf.truncate(n);
        String::from_utf8_lossy(&buf).into_owned()
    }

    pub struct Socket(i32);

    impl Socket {
        pub fn open(url: &str) -> Socket {
            Socket(unsafe { chapaev_ws_open(url.as_ptr(), url.len()) })
        }
        pub fn state(&self) -> SocketState {
            match unsafe { chapaev_ws_state(self.0) } {
                0 => SocketState::Connecting,
                1 => SocketState::Open,
                _ => SocketState::Closed,
            }
        }
        pub fn send(&self, text: &str) -> bool {
            unsafe { chapaev_ws_send(self.0, text.as_ptr(), text.len()) == 1 }
        }
        pub fn recv(&self) -> Option<String> {
            let len = unsafe { chapaev_ws_next_len(self.0) };
            if len < 0 {
                return None;
            }
            Some(take(len, |p, c| unsafe { chapaev_ws_take(self.0, p, c) }))
        }
    }

    impl Drop for Socket {
        fn drop(&mut self) {
            unsafe { chapaev_ws_close(self.0) }
        }
    }

    pub struct Request(i32);

    impl Request {
        /// `auth`: the value of an `Authorization` header to send.
        pub fn start(method: &str, url: &str, body: Option<&str>, auth: Option<&str>) -> Request {
            let b = body.unwrap_or("");
            let a = auth.unwrap_or("");
            Request(unsafe {
                chapaev_http_start(
                    method.as_ptr(),
                    method.len(),
                    url.as_ptr(),
                    url.len(),
                    b.as_ptr(),
                    b.len(),
                    a.as_ptr(),
                    a.len(),
                )
            })
        }
        pub fn poll(&mut self) -> Option<HttpReply> {
            let status = unsafe { chapaev_http_status(self.0) };
            if status == 0 {
                return None;
            }
            let len = unsafe { chapaev_http_body_len(self.0) };
            let body = take(len, |p, c| unsafe { chapaev_http_take(self.0, p, c) });
            Some(match u16::try_from(status) {
                Ok(status) => HttpReply::Done { status, body },
                Err(_) => HttpReply::Failed(body),
            })
        }
    }

    pub fn location() -> String {
        let len = unsafe { chapaev_location_len() };
        take(len, |p, c| unsafe { chapaev_staged_take(p, c) })
    }

    pub fn set_hash(hash: &str) {
        unsafe { chapaev_set_hash(hash.as_ptr(), hash.len()) }
    }

    pub fn storage_get(key: &str) -> Option<String> {
        let len = unsafe { chapaev_storage_get_len(key.as_ptr(), key.len()) };
        (len >= 0).then(|| take(len, |p, c| unsafe { chapaev_staged_take(p, c) }))
    }

    pub fn storage_set(key: &str, value: &str) {
        unsafe { chapaev_storage_set(key.as_ptr(), key.len(), value.as_ptr(), value.len()) }
    }

    pub fn save_file(name: &str, contents: &str) -> Result<String, String> {
        unsafe { chapaev_download(name.as_ptr(), name.len(), contents.as_ptr(), contents.len()) }
        Ok(crate::i18n::t!("file-downloaded", name = name))
    }

    pub fn request_file() {
        unsafe { chapaev_pick_file() }
    }

    pub fn picked_file() -> Option<String> {
        let len = unsafe { chapaev_picked_len() };
        (len >= 0).then(|| take(len, |p, c| unsafe { chapaev_staged_take(p, c) }))
    }

    pub fn copy_text(text: &str) {
        unsafe { chapaev_copy(text.as_ptr(), text.len()) }
    }

    pub fn set_ready() {
        unsafe { chapaev_set_ready() }
    }

    pub fn report(json: &str) {
        unsafe { chapaev_report(json.as_ptr(), json.len()) }
    }

    pub fn pasted() -> Option<String> {
        let len = unsafe { chapaev_pasted_len() };
        (len >= 0).then(|| take(len, |p, c| unsafe { chapaev_staged_take(p, c) }))
    }

    pub fn play_sound(sound: super::Sound) {
        let (kind, loudness) = sound.code();
        unsafe { chapaev_sound(kind, loudness) }
    }

    pub fn coarse_pointer() -> bool {
        unsafe { chapaev_coarse_pointer() == 1 }
    }

    pub fn random_u64() -> u64 {
        let word = || unsafe { chapaev_random_u32() } as u32 as u64;
        word() << 32 | word()
    }

    pub fn field_sweep() {
        unsafe { chapaev_field_sweep() }
    }

    pub fn field_place(name: &str, css: [f32; 4], value: &str, placeholder: &str, max: usize) {
        let [x, y, w, h] = css;
        let max = u32::try_from(max).unwrap_or(u32::MAX);
        unsafe {
            chapaev_field_place(
                name.as_ptr(),
                name.len(),
                x,
                y,
                w,
                h,
                value.as_ptr(),
                value.len(),
                placeholder.as_ptr(),
                placeholder.len(),
                max,
            )
        }
    }

    pub fn field_take(name: &str) -> Option<String> {
        let len = unsafe { chapaev_field_take_len(name.as_ptr(), name.len()) };
        (len >= 0).then(|| take(len, |p, c| unsafe { chapaev_staged_take(p, c) }))
    }

    pub fn field_flags(name: &str) -> super::FieldFlags {
        let bits = unsafe { chapaev_field_flags(name.as_ptr(), name.len()) };
        super::FieldFlags {
            focused: bits & 1 != 0,
            entered: bits & 2 != 0,
        }
    }

    /// The browser's preferred languages, best first, comma-separated
    /// (`navigator.languages`).
    pub fn languages() -> String {
        let len = unsafe { chapaev_languages_len() };
        take(len, |p, c| unsafe { chapaev_staged_take(p, c) })
    }

    /// Sets the page's `<html lang>`.
    pub fn set_document_lang(code: &str) {
        unsafe { chapaev_set_document_lang(code.as_ptr(), code.len()) }
    }
}

#[cfg(not(target_arch = "wasm32"))]
mod imp {
    use super::{HttpReply, SocketState};
    use std::cell::RefCell;
    use std::collections::HashMap;
    use std::sync::mpsc::{channel, Receiver, Sender, TryRecvError};
    use std::sync::{Arc, Mutex};
    use std::thread;
    use std::time::Duration;

    /// A WebSocket served by a thread: frames in and out through channels.
    pub struct Socket {
        state: Arc<Mutex<SocketState>>,
        outbox: Sender<String>,
        inbox: Receiver<String>,
    }

    impl Socket {
        pub fn open(url: &str) -> Socket {
            let state = Arc::new(Mutex::new(SocketState::Connecting));
            let (outbox, out_rx) = channel::<String>();
            let (in_tx, inbox) = channel::<String>();
            let url = url.to_string();
            let st = state.clone();
            thread::spawn(move || {
                let set = |s| {
                    if let Ok(mut g) = st.lock() {
                        *g = s
                    }
                };
                let Ok((mut ws, _)) = tungstenite::connect(url.as_str()) else {
                    set(SocketState::Closed);
                    return;
                };
                if let tungstenite::stream::MaybeTlsStream::Plain(s) = ws.get_ref() {
                    let _ = s.set_read_timeout(Some(Duration::from_millis(5)));
                }
                set(SocketState::Open);
                loop {
                    loop {
                        match out_rx.try_recv() {
                            Ok(text) => {
                                if ws.send(tungstenite::Message::text(text)).is_err() {
                                    set(SocketState::Closed);
                                    return;
                                }
                            }
                            Err(TryRecvError::Empty) => break,
                            Err(TryRecvError::Disconnected) => {
                                let _ = ws.close(None);
                                return;
                            }
                        }
                    }
                    match ws.read() {
                        Ok(tungstenite::Message::Text(t)) => {
                            let _ = in_tx.send(t.to_string());
                        }
                        Ok(_) => {}
                        Err(tungstenite::Error::Io(e))
                            if e.kind() == std::io::ErrorKind::WouldBlock
                                || e.kind() == std::io::ErrorKind::TimedOut => {}
                        Err(_) => {
                            set(SocketState::Closed);
                            return;
                        }
                    }
                }
            });
            Socket {
                state,
                outbox,
                inbox,
            }
        }
        pub fn state(&self) -> SocketState {
            self.state.lock().map(|g| *g).unwrap_or(SocketState::Closed)
        }
        pub fn send(&self, text: &str) -> bool {
            self.state() == SocketState::Open && self.outbox.send(text.to_string()).is_ok()
        }
        pub fn recv(&self) -> Option<String> {
            self.inbox.try_recv().ok()
        }
    }

    /// An HTTP request run on a thread.
    pub struct Request(Receiver<HttpReply>);

    impl Request {
        /// `auth`: the value of an `Authorization` header to send.
        pub fn start(method: &str, url: &str, body: Option<&str>, auth: Option<&str>) -> Request {
            let (tx, rx) = channel();
            let (method, url, body) = (method.to_string(), url.to_string(), body.map(String::from));
            let auth = auth.map(String::from);
            thread::spawn(move || {
                let mut req = ureq::request(&method, &url).set("content-type", "application/json");
                if let Some(a) = &auth {
                    req = req.set("authorization", a);
                }
                let res = match body {
                    Some(b) => req.send_string(&b),
                    None => req.call(),
                };
                let reply = match res {
                    Ok(r) | Err(ureq::Error::Status(_, r)) => HttpReply::Done {
                        status: r.status(),
                        body: r.into_string().unwrap_or_default(),
                    },
                    Err(e) => HttpReply::Failed(e.to_string()),
                };
                let _ = tx.send(reply);
            });
            Request(rx)
        }
        pub fn poll(&mut self) -> Option<HttpReply> {
            match self.0.try_recv() {
                Ok(r) => Some(r),
                Err(TryRecvError::Empty) => None,
                Err(TryRecvError::Disconnected) => {
                    Some(HttpReply::Failed("the request thread ended".into()))
                }
            }
        }
    }

    thread_local! {
        static STORAGE: RefCell<HashMap<String, String>> = RefCell::new(HashMap::new());
        static HASH: RefCell<String> = const { RefCell::new(String::new()) };
        static PICKED: RefCell<Option<String>> = const { RefCell::new(None) };
    }

    /// The server to talk to: `CHAPAEV_SERVER` (default `http://127.0.0.1:8080`)
    /// with the address hash the app last set.
    pub fn location() -> String {
        let base =
            std::env::var("CHAPAEV_SERVER").unwrap_or_else(|_| "http://127.0.0.1:8080".into());
        let hash = HASH.with(|h| h.borrow().clone());
        format!("{}/{}", base.trim_end_matches('/'), hash)
    }

    pub fn set_hash(hash: &str) {
        HASH.with(|h| *h.borrow_mut() = hash.to_string());
    }

    pub fn storage_get(key: &str) -> Option<String> {
        STORAGE.with(|s| s.borrow().get(key).cloned())
    }

    pub fn storage_set(key: &str, value: &str) {
        STORAGE.with(|s| s.borrow_mut().insert(key.to_string(), value.to_string()));
    }

    pub fn save_file(name: &str, contents: &str) -> Result<String, String> {
        std::fs::write(name, contents)
            .map(|()| crate::i18n::t!("file-saved", name = name))
            .map_err(|e| crate::i18n::t!("file-save-failed", name = name, error = e.to_string()))
    }

    /// On the desktop "opening" reads `scene.json` from the working folder.
    pub fn request_file() {
        let text = std::fs::read_to_string("scene.json").ok();
        PICKED.with(|p| *p.borrow_mut() = text);
    }

    pub fn picked_file() -> Option<String> {
        PICKED.with(|p| p.borrow_mut().take())
    }

    /// On the desktop the text goes to the log (no clipboard crate).
    pub fn copy_text(text: &str) {
        println!("{text}");
    }

    pub fn set_ready() {}

    pub fn report(_json: &str) {}

    /// On the desktop nothing is pasted (no clipboard crate).
    pub fn pasted() -> Option<String> {
        None
    }

    /// On the desktop the game is silent.
    pub fn play_sound(sound: super::Sound) {
        let _ = sound.code();
    }

    /// The desktop has a mouse and a keyboard.
    pub fn coarse_pointer() -> bool {
        false
    }

    /// 64 random bits: the keys std draws from the system for each
    /// `RandomState`, hashed.
    pub fn random_u64() -> u64 {
        use std::hash::{BuildHasher, Hasher};
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u64(0x0FF1_1AE5);
        h.finish()
    }

    /// The desktop types into the canvas: no native inputs.
    pub fn field_sweep() {}

    pub fn field_place(_name: &str, _css: [f32; 4], _value: &str, _placeholder: &str, _max: usize) {
    }

    pub fn field_take(_name: &str) -> Option<String> {
        None
    }

    pub fn field_flags(_name: &str) -> super::FieldFlags {
        super::FieldFlags::default()
    }

    /// On the desktop the locale's variables say the language.
    pub fn languages() -> String {
        ["LC_ALL", "LC_MESSAGES", "LANG"]
            .iter()
            .find_map(|v| std::env::var(v).ok().filter(|s| !s.is_empty()))
            .unwrap_or_default()
    }

    pub fn set_document_lang(_code: &str) {}
}

pub use imp::{
    coarse_pointer, copy_text, field_flags, field_place, field_sweep, field_take, languages,
    location, pasted, picked_file, play_sound, random_u64, report, request_file, save_file,
    set_document_lang, set_hash, set_ready, storage_get, storage_set, Request, Socket,
};
