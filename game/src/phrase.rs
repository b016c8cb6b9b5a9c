//! The match chat's quick phrases: a short fixed set of things players say
//! ("good shot", "gg", "rematch?"), sent by code rather than as text, so
//! each reader's client can show a phrase in the reader's own language.
//! The server still puts the English words in the chat message's `text`,
//! so a client or bot that knows no codes reads them too.
//!
//! ```
//! use game::phrase::Phrase;
//! assert_eq!(Phrase::GoodShot.code(), "good-shot");
//! assert_eq!(Phrase::from_code("gg"), Some(Phrase::Gg));
//! assert_eq!(Phrase::Gg.english(), "gg");
//! ```

use serde::{Deserialize, Serialize};

/// A quick phrase of the match chat.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Phrase {
    /// "Hi!"
    Hello,
    /// "Good luck!"
    GoodLuck,
    /// "Good shot!"
    GoodShot,
    /// "Oops!"
    Oops,
    /// "Well played!"
    WellPlayed,
    /// "Thanks!"
    Thanks,
    /// "gg" (good game).
    Gg,
    /// "Rematch?"
    Rematch,
}

impl Phrase {
    /// Every phrase, in the order a client offers them.
    pub const ALL: [Phrase; 8] = [
        Phrase::Hello,
        Phrase::GoodLuck,
        Phrase::GoodShot,
        Phrase::Oops,
        Phrase::WellPlayed,
        Phrase::Thanks,
        Phrase::Gg,
        Phrase::Rematch,
    ];

    /// Its code on the wire (`good-shot`).
    pub fn code(self) -> &'static str {
        match self {
            Phrase::Hello => "hello",
            Phrase::GoodLuck => "good-luck",
            Phrase::GoodShot => "good-shot",
            Phrase::Oops => "oops",
            Phrase::WellPlayed => "well-played",
            Phrase::Thanks => "thanks",
            Phrase::Gg => "gg",
            Phrase::Rematch => "rematch",
        }
    }

    /// The phrase of `code`, if there is one.
    pub fn from_code(code: &str) -> Option<Phrase> {
        Phrase::ALL.into_iter().find(|p| p.code() == code)
    }

    /// Its English words, the chat message's `text` for readers that know
    /// no codes.
    pub fn english(self) -> &'static str {
        match self {
            Phrase::Hello => "Hi!",
            Phrase::GoodLuck => "Good luck!",
            Phrase::GoodShot => "Good shot!",
            Phrase::Oops => "Oops!",
            Phrase::WellPlayed => "Well played!",
            Phrase::Thanks => "Thanks!",
            Phrase::Gg => "gg",
            Phrase::Rematch => "Rematch?",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_phrase_travels_as_its_code_and_comes_back() {
        for p in Phrase::ALL {
            let json = serde_json::to_string(&p).unwrap();
            assert_eq!(json, format!("\"{}\"", p.code()));
            assert_eq!(serde_json::from_str::<Phrase>(&json).unwrap(), p);
            assert_eq!(Phrase::from_code(p.code()), Some(p));
            assert!(!p.english().is_empty());
        }
        assert!(serde_json::from_str::<Phrase>("\"teleport\"").is_err());
        assert_eq!(Phrase::from_code("teleport"), None);
    }
}
