//! The interface's language: every word the player reads, in English and
//! Russian, as Project Fluent messages (`locales/en.ftl`, `locales/ru.ftl`,
//! embedded in the wasm). This module owns the two bundles, the language
//! in use and the lookup: [`t!`] turns a message id and its arguments into
//! the text (Fluent's selectors give Russian its plural forms: "1 шашка,
//! 2 шашки, 5 шашек"). A message missing from Russian falls back to
//! English, and one missing from both shows its id; nothing panics. The
//! first visit picks the browser's language (`navigator.languages`);
//! [`set`] switches it, remembers the choice in `localStorage` and sets the
//! page's `<html lang>`; [`switch`] is the button that does it on screen.

use crate::platform;
use crate::ui::{Ui, TOUCH};
use fluent_bundle::{FluentArgs, FluentBundle, FluentResource};
use macroquad::prelude::Rect;
use std::cell::Cell;
use unic_langid::LanguageIdentifier;

pub use fluent_bundle::FluentValue;

/// Where the player's choice is kept.
const LANG_KEY: &str = "chapaev.lang";

/// The languages of the interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    En,
    Ru,
}

impl Lang {
    /// The BCP 47 tag (`en`, `ru`).
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Ru => "ru",
        }
    }

    /// The language's own name for itself, as the switch shows it.
    pub fn own_name(self) -> &'static str {
        match self {
            Lang::En => "English",
            Lang::Ru => "Русский",
        }
    }

    /// The other one (what the switch turns to).
    pub fn other(self) -> Lang {
        match self {
            Lang::En => Lang::Ru,
            Lang::Ru => Lang::En,
        }
    }

    /// The language a tag such as `ru-RU` or `en_GB.UTF-8` names, if it
    /// is one of ours.
    pub fn from_tag(tag: &str) -> Option<Lang> {
        let tag = tag.trim().split('.').next().unwrap_or_default();
        let id: LanguageIdentifier = tag.replace('_', "-").parse().ok()?;
        match id.language.as_str() {
            "en" => Some(Lang::En),
            "ru" => Some(Lang::Ru),
            _ => None,
        }
    }

    /// The first of the browser's preferred languages (a comma-separated
    /// list, best first) that is one of ours; English when none is.
    pub fn from_preferences(list: &str) -> Lang {
        list.split(',').find_map(Lang::from_tag).unwrap_or(Lang::En)
    }

    fn source(self) -> &'static str {
        match self {
            Lang::En => include_str!("../locales/en.ftl"),
            Lang::Ru => include_str!("../locales/ru.ftl"),
        }
    }
}

/// The messages of `lang`, parsed. A resource with errors keeps every
/// message that parsed (the unit tests prove both parse cleanly).
fn bundle(lang: Lang) -> FluentBundle<FluentResource> {
    let id: LanguageIdentifier = lang.code().parse().unwrap_or_default();
    let mut bundle = FluentBundle::new(vec![id]);
    // The font has no bidi isolation marks, and every text is left to right.
    bundle.set_use_isolating(false);
    let resource = FluentResource::try_new(lang.source().to_string()).unwrap_or_else(|(r, _)| r);
    // Errors here are only duplicate ids: the first one stays.
    let _ = bundle.add_resource(resource);
    bundle
}

thread_local! {
    static BUNDLES: [FluentBundle<FluentResource>; 2] = [bundle(Lang::En), bundle(Lang::Ru)];
    static CURRENT: Cell<Option<Lang>> = const { Cell::new(None) };
}

/// The language in use: the one chosen in this browser before, else the
/// browser's own.
pub fn current() -> Lang {
    CURRENT.with(|c| {
        if let Some(l) = c.get() {
            return l;
        }
        let l = platform::storage_get(LANG_KEY)
            .as_deref()
            .and_then(Lang::from_tag)
            .unwrap_or_else(|| Lang::from_preferences(&preferences()));
        platform::set_document_lang(l.code());
        c.set(Some(l));
        l
    })
}

/// The browser's preferred languages (on the desktop, the locale's). The
/// unit tests, whose expectations are written in English, have none.
fn preferences() -> String {
    if cfg!(test) {
        String::new()
    } else {
        platform::languages()
    }
}

/// Switches the interface to `lang` and remembers the choice.
pub fn set(lang: Lang) {
    CURRENT.with(|c| c.set(Some(lang)));
    platform::storage_set(LANG_KEY, lang.code());
    platform::set_document_lang(lang.code());
}

/// Message `id` of `lang` with `args`, if `lang` has it.
fn format_in(lang: Lang, id: &str, args: Option<&FluentArgs>) -> Option<String> {
    BUNDLES.with(|b| {
        let bundle = &b[lang as usize];
        let pattern = bundle.get_message(id)?.value()?;
        let mut errors = Vec::new();
        Some(
            bundle
                .format_pattern(pattern, args, &mut errors)
                .into_owned(),
        )
    })
}

/// Message `id` of `lang` without arguments, if `lang` has it (for the
/// layout tests, which check the labels of both languages).
#[cfg(test)]
pub fn message_in(lang: Lang, id: &str) -> Option<String> {
    format_in(lang, id, None)
}

/// Message `id` in the current language with `args` (name, value), falling
/// back to English, then to the id itself.
pub fn text(id: &str, args: &[(&str, FluentValue)]) -> String {
    let fluent_args = (!args.is_empty()).then(|| {
        let mut a = FluentArgs::new();
        for (k, v) in args {
            a.set(*k, v.clone());
        }
        a
    });
    let lang = current();
    format_in(lang, id, fluent_args.as_ref())
        .or_else(|| format_in(Lang::En, id, fluent_args.as_ref()))
        .unwrap_or_else(|| id.to_string())
}

/// `t!("id")` or `t!("id", count = n, name = &s)`: the message in the
/// current language (see [`text`]).
macro_rules! t {
    ($id:literal) => {
        $crate::i18n::text($id, &[])
    };
    ($id:literal, $($k:ident = $v:expr),+ $(,)?) => {
        $crate::i18n::text(
            $id,
            &[$((stringify!($k), $crate::i18n::FluentValue::from($v))),+],
        )
    };
}
pub(crate) use t;

/// The language switch: one button that turns the interface to the other
/// language (named in that language: "English" or "Русский"; on a narrow
/// screen its code), remembered in this browser.
pub fn switch(ui: &mut Ui, r: Rect, narrow: bool) {
    let other = current().other();
    let label = if narrow {
        other.code().to_uppercase()
    } else {
        other.own_name().to_string()
    };
    if ui.button("lang", &label, r) {
        set(other);
    }
}

/// The language switch at the right end of a screen's top row: `right`
/// is the row's right edge, `y` its top.
pub fn switch_top(ui: &mut Ui, right: f32, y: f32) {
    let narrow = crate::scale::size().x < 600.0;
    let w = if narrow { 48.0 } else { 110.0 };
    switch(ui, Rect::new(right - w, y, w, TOUCH), narrow);
}

#[cfg(test)]
mod tests {
    use super::*;
    use fluent_syntax::ast::Entry;
    use std::collections::BTreeSet;

    /// The message ids of `lang`, failing on any syntax error.
    fn ids(lang: Lang) -> BTreeSet<String> {
        let resource = match FluentResource::try_new(lang.source().to_string()) {
            Ok(r) => r,
            Err((_, errors)) => panic!("{}.ftl does not parse: {errors:?}", lang.code()),
        };
        resource
            .entries()
            .filter_map(|e| match e {
                Entry::Message(m) => Some(m.id.name.to_string()),
                _ => None,
            })
            .collect()
    }

    fn in_lang(lang: Lang, id: &str, args: &[(&str, FluentValue)]) -> String {
        CURRENT.with(|c| c.set(Some(lang)));
        text(id, args)
    }

    #[test]
    fn both_languages_parse_and_have_the_same_messages() {
        let en = ids(Lang::En);
        let ru = ids(Lang::Ru);
        let only_en: Vec<_> = en.difference(&ru).collect();
        let only_ru: Vec<_> = ru.difference(&en).collect();
        assert!(only_en.is_empty(), "missing in ru.ftl: {only_en:?}");
        assert!(only_ru.is_empty(), "missing in en.ftl: {only_ru:?}");
        assert!(en.len() > 100, "only {} messages", en.len());
        for lang in [Lang::En, Lang::Ru] {
            let b = bundle(lang);
            for id in &en {
                let msg = b.get_message(id).expect("listed");
                assert!(msg.value().is_some(), "{id} has no value in {lang:?}");
            }
        }
    }

    /// Every source file of the client, by path.
    fn sources() -> Vec<(std::path::PathBuf, String)> {
        let mut out = Vec::new();
        let mut stack = vec![std::path::PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/src"
        ))];
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).expect("src is readable") {
                let path = entry.expect("a directory entry").path();
                if path.is_dir() {
                    stack.push(path);
                } else {
                    let code = std::fs::read_to_string(&path).expect("a source file");
                    out.push((path, code));
                }
            }
        }
        out
    }

    #[test]
    fn every_message_is_asked_for_somewhere_in_the_code() {
        let code: String = sources().into_iter().map(|(_, c)| c).collect();
        let unused: Vec<String> = ids(Lang::En)
            .into_iter()
            .filter(|id| !code.contains(&format!("\"{id}\"")))
            .collect();
        assert!(unused.is_empty(), "messages no code asks for: {unused:?}");
    }

    #[test]
    fn every_message_the_code_asks_for_exists() {
        let en = ids(Lang::En);
        let mut missing = Vec::new();
        let mut used = 0;
        for (path, code) in sources() {
            // The macro's calls, not the ends of other macros' names.
            let calls = code.match_indices("t!(\"").filter(|(at, _)| {
                !code[..*at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_')
            });
            for (at, _) in calls {
                let rest = &code[at + 4..];
                let id = rest.split('"').next().unwrap_or_default();
                used += 1;
                if id != "id" && !en.contains(id) {
                    missing.push(format!("{}: {id}", path.display()));
                }
            }
        }
        assert!(missing.is_empty(), "ids not in en.ftl: {missing:#?}");
        assert!(used > 100, "only {used} lookups found");
    }

    /// The message the page shows until the game has loaded: the server's
    /// build writes it into the page (`index.html`) in each language, and
    /// the page picks the language as [`current`] does.
    const PAGE_LOADING: &str = "page-loading";

    #[test]
    fn the_pages_loader_has_its_words_in_every_language_on_one_line() {
        // The server's build reads the line `page-loading = …` of each file.
        for lang in [Lang::En, Lang::Ru] {
            let line = lang
                .source()
                .lines()
                .find_map(|l| l.strip_prefix(&format!("{PAGE_LOADING} =")));
            let words = in_lang(lang, PAGE_LOADING, &[]);
            assert_eq!(line.map(str::trim), Some(words.as_str()), "{lang:?}");
        }
        assert_eq!(
            in_lang(Lang::Ru, PAGE_LOADING, &[]),
            "Загружается «Чапаев»…"
        );
    }

    #[test]
    fn russian_counts_take_their_one_few_and_many_forms() {
        let n = |k: i64| in_lang(Lang::Ru, "shots-count", &[("count", k.into())]);
        assert_eq!(n(1), "1 щелчок");
        assert_eq!(n(2), "2 щелчка");
        assert_eq!(n(5), "5 щелчков");
        assert_eq!(n(21), "21 щелчок");
        assert_eq!(n(12), "12 щелчков");
        let knocked = |k: i64| {
            let args = [("who", "Вы".into()), ("taken", k.into())];
            in_lang(Lang::Ru, "shot-knocked", &args)
        };
        assert_eq!(knocked(1), "Вы сбили 1 шашку");
        assert_eq!(knocked(3), "Вы сбили 3 шашки");
        assert_eq!(knocked(5), "Вы сбили 5 шашек");
        let e = |k: i64| in_lang(Lang::En, "shots-count", &[("count", k.into())]);
        assert_eq!(e(1), "1 shot");
        assert_eq!(e(5), "5 shots");
    }

    #[test]
    fn a_missing_message_falls_back_to_english_then_to_its_id() {
        assert_eq!(in_lang(Lang::Ru, "no-such-message", &[]), "no-such-message");
        assert_eq!(in_lang(Lang::Ru, "app-title", &[]), "Чапаев онлайн");
        assert_eq!(in_lang(Lang::En, "app-title", &[]), "Chapaev online");
    }

    #[test]
    fn the_browser_language_picks_ours_or_english() {
        assert_eq!(Lang::from_preferences("ru-RU,ru,en-US"), Lang::Ru);
        assert_eq!(Lang::from_preferences("de-DE,ru"), Lang::Ru);
        assert_eq!(Lang::from_preferences("en-GB,ru"), Lang::En);
        assert_eq!(Lang::from_preferences("fr,de"), Lang::En);
        assert_eq!(Lang::from_preferences(""), Lang::En);
        assert_eq!(Lang::from_tag("ru_RU.UTF-8"), Some(Lang::Ru));
        assert_eq!(Lang::from_tag("not a tag!"), None);
    }
}
