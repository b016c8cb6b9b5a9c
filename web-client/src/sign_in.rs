//! The account screen of this browser: signed out, it creates an account
//! (a name → `POST /api/accounts`, the key kept) or takes a key exported
//! from another browser (checked with `GET /api/accounts/me`); signed in,
//! it shows the name and rating, exports the key (copied to the clipboard
//! and shown to copy by hand) and signs out.

use crate::account::{self, Account};
use crate::api::{Api, Created, Pending, Profile};
use crate::i18n::t;
use crate::platform;
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use macroquad::prelude::*;

pub struct SignIn {
    api: Api,
    account: Option<Account>,
    /// The signed-in account's profile (its rating), once fetched.
    profile: Option<Profile>,
    fetching: Option<Pending<Profile>>,
    name: String,
    key: String,
    creating: Option<Pending<Created>>,
    /// A pasted key being checked, with the key.
    checking: Option<(Pending<Profile>, String)>,
    /// The key is shown to copy.
    exported: bool,
    message: Option<String>,
}

impl SignIn {
    pub fn new(api: Api) -> SignIn {
        let account = account::signed_in();
        let fetching = account.as_ref().map(|a| api.me(&a.key));
        SignIn {
            api,
            account,
            profile: None,
            fetching,
            name: String::new(),
            key: String::new(),
            creating: None,
            checking: None,
            exported: false,
            message: None,
        }
    }

    /// Takes the answers that have come; where to go after signing in.
    fn poll(&mut self) -> Option<Route> {
        if let Some(p) = &mut self.fetching {
            if let Some(r) = p.poll() {
                self.fetching = None;
                match r {
                    Ok(profile) => self.profile = Some(profile),
                    Err(e) => self.message = Some(e),
                }
            }
        }
        if let Some(p) = &mut self.creating {
            if let Some(r) = p.poll() {
                self.creating = None;
                match r {
                    Ok(created) => {
                        account::sign_in(&created.account.name, &created.key);
                        return Some(Route::Lobby);
                    }
                    Err(e) => self.message = Some(e),
                }
            }
        }
        if let Some((p, key)) = &mut self.checking {
            if let Some(r) = p.poll() {
                let key = key.clone();
                self.checking = None;
                match r {
                    Ok(profile) => {
                        account::sign_in(&profile.name, &key);
                        return Some(Route::Lobby);
                    }
                    Err(e) => self.message = Some(e),
                }
            }
        }
        None
    }

    fn create(&mut self) {
        let name = self.name.trim().to_string();
        if !account::valid_name(&name) {
            self.message = Some(account::name_rule());
        } else if self.creating.is_none() {
            self.creating = Some(self.api.create_account(&name));
            self.message = Some(t!("account-creating"));
        }
    }

    fn use_key(&mut self) {
        let key = self.key.trim().to_string();
        if key.is_empty() {
            self.message = Some(t!("account-paste-key-first"));
        } else if self.checking.is_none() {
            self.checking = Some((self.api.me(&key), key));
            self.message = Some(t!("account-checking-key"));
        }
    }

    /// The signed-out form: create, or paste a key.
    fn signed_out(&mut self, ui: &mut Ui, x0: f32, col: f32, mut y: f32) {
        let gap = 8.0;
        let bw = 112.0;
        ui::text_in(&t!("account-new"), x0, y, 19.0, col, colors::ACCENT);
        y += 26.0;
        // The rule of names, on two lines where the column is narrow.
        for line in crate::help::wrap(&account::name_hint(), 14.0, col) {
            ui::text_in(&line, x0, y, 14.0, col, colors::MUTED);
            y += 17.0;
        }
        y += 5.0;
        let field = Rect::new(x0, y, col - bw - gap, ui::TOUCH);
        let entered = ui.text_field(
            "account-name",
            &mut self.name,
            field,
            &t!("account-name-placeholder"),
            account::MAX_NAME,
        );
        let ok = account::valid_name(self.name.trim());
        let b = Rect::new(x0 + col - bw, y, bw, ui::TOUCH);
        if (ui.button_styled("account-create", &t!("account-create"), b, ok, false) || entered)
            && ok
        {
            self.create();
        }
        y += ui::TOUCH + 28.0;
        ui::text_in(&t!("account-key-heading"), x0, y, 19.0, col, colors::ACCENT);
        y += 30.0;
        let field = Rect::new(x0, y, col - bw - gap, ui::TOUCH);
        let entered = ui.text_field(
            "account-key",
            &mut self.key,
            field,
            &t!("account-key-placeholder"),
            200,
        );
        let ok = !self.key.trim().is_empty();
        let b = Rect::new(x0 + col - bw, y, bw, ui::TOUCH);
        if (ui.button_styled("account-use-key", &t!("account-use-key"), b, ok, false) || entered)
            && ok
        {
            self.use_key();
        }
    }

    /// The signed-in account: its rating, the key, sign-out.
    fn signed_in(
        &mut self,
        ui: &mut Ui,
        a: &Account,
        x0: f32,
        col: f32,
        mut y: f32,
    ) -> Option<Route> {
        let gap = 8.0;
        ui::text(
            &ui::fit(
                &t!("account-signed-in-as", name = a.name.as_str()),
                19.0,
                col,
            ),
            x0,
            y,
            19.0,
            colors::ACCENT,
        );
        y += 28.0;
        let rating = match &self.profile {
            Some(p) => t!(
                "account-rating",
                rating = account::profile_rating(p),
                games = p.games
            ),
            None => t!("account-rating-unknown"),
        };
        ui::text(&ui::fit(&rating, 16.0, col), x0, y, 16.0, colors::TEXT);
        y += 30.0;
        let bw = (col - 2.0 * gap) / 3.0;
        let mut go = None;
        if ui.button(
            "account-page",
            &t!("account-my-page"),
            Rect::new(x0, y, bw, ui::TOUCH),
        ) {
            go = Some(Route::Account {
                name: a.name.clone(),
            });
        }
        if ui.button(
            "export-key",
            &t!("account-export-key"),
            Rect::new(x0 + bw + gap, y, bw, ui::TOUCH),
        ) {
            platform::copy_text(&a.key);
            self.exported = true;
            self.message = Some(t!("account-key-copied"));
        }
        if ui.button(
            "sign-out",
            &t!("sign-out"),
            Rect::new(x0 + 2.0 * (bw + gap), y, bw, ui::TOUCH),
        ) {
            account::sign_out();
            go = Some(Route::Lobby);
        }
        y += ui::TOUCH + 16.0;
        if self.exported {
            ui::text(
                &ui::fit(&t!("account-your-key"), 14.0, col),
                x0,
                y,
                14.0,
                colors::MUTED,
            );
            y += 20.0;
            // The key in lines that fit, to copy by hand where the
            // clipboard is closed to the page.
            let per_line = 28;
            let chars: Vec<char> = a.key.chars().collect();
            for chunk in chars.chunks(per_line) {
                let line: String = chunk.iter().collect();
                ui::text(&line, x0, y, 16.0, colors::TEXT);
                y += 20.0;
            }
        }
        go
    }
}

impl Screen for SignIn {
    fn frame(&mut self, ui: &mut Ui, _dt: f64) -> Option<Route> {
        let mut go = self.poll();
        let (w, _) = crate::scale::size().into();
        let pad = if w < 600.0 { 12.0 } else { 20.0 };
        let col = (w - 2.0 * pad).min(560.0);
        let x0 = (w - col) / 2.0;
        let mut y = 12.0;
        if ui.button("lobby", &t!("lobby"), Rect::new(x0, y, 96.0, ui::TOUCH)) {
            go = Some(Route::Lobby);
        }
        // Between the lobby's button and the language switch, smaller
        // (down to 12 units) where that is narrow.
        let lang_w = if w < 600.0 { 48.0 } else { 110.0 };
        ui::text_in(
            &t!("account-title"),
            x0 + 108.0,
            y + 9.0,
            24.0,
            col - lang_w - 8.0 - 108.0,
            colors::ACCENT,
        );
        crate::i18n::switch_top(ui, x0 + col, y);
        y += ui::TOUCH + 24.0;
        match self.account.clone() {
            Some(a) => {
                if let Some(r) = self.signed_in(ui, &a, x0, col, y) {
                    go = Some(r);
                }
            }
            None => self.signed_out(ui, x0, col, y),
        }
        if let Some(m) = &self.message {
            let (_, h) = crate::scale::size().into();
            ui::text(&ui::fit(m, 15.0, col), x0, h - 32.0, 15.0, colors::MUTED);
        }
        go
    }

    fn name(&self) -> &'static str {
        "account"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert(
            "signed_in".into(),
            self.account.as_ref().map(|a| a.name.clone()).into(),
        );
        m.insert(
            "rating".into(),
            self.profile.as_ref().map(account::profile_rating).into(),
        );
        m.insert("message".into(), self.message.clone().into());
        m
    }
}
