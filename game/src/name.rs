//! Names people see: the one rule for them, shared by the server (which
//! refuses a name that breaks it) and the browser client (which checks a
//! name before asking, and builds its hints and its text field's length
//! from the same constants). Pure functions, each refusal with its typed
//! reason ([`NameError`]).
//!
//! Every name a person sees — a casual seat's name ([`seat_name`]), an
//! account's name ([`check_new`]) and so a chat message's author, which is
//! its seat's name — follows one rule ([`check_visible`]): no control
//! characters, no bidirectional controls (which reorder what follows
//! them), no line or paragraph separators, no invisible characters (those
//! Unicode declares default-ignorable: zero-width spaces and joiners, soft
//! hyphens, variation selectors, …), and no impostor of the computer's
//! names ([`is_reserved`]: `bot`, `bot (hard)`, `computer-easy`, … in any
//! case and spelled with any look-alike letters). A seat's name is first
//! normalised (NFKC, so full-width and compatibility forms become the
//! plain letters they stand for) and trimmed.
//!
//! An account name is in addition [`MIN_NAME`] to [`MAX_NAME`] ASCII
//! letters, digits, `_` or `-`, starting with a letter or digit
//! ([`check`]). Names stored before this rule are not checked again: old
//! records and accounts load as they are.

/// Shortest account name, in characters.
pub const MIN_NAME: usize = 3;
/// Longest account name, in characters.
pub const MAX_NAME: usize = 20;
/// Longest name of a casual seat, in characters (after normalising).
pub const MAX_SEAT_NAME: usize = 40;
/// The prefix of the computer levels' account names (`computer-easy`, …),
/// reserved ([`is_reserved`]).
pub const COMPUTER_PREFIX: &str = "computer-";
/// The words the computer's names are made of (`bot (hard)` seats,
/// `computer-hard` accounts, `computer (hard)` in listings): a name that
/// is one of them, or starts with one followed by anything but a letter
/// or digit, is reserved ([`is_reserved`]).
pub const RESERVED_WORDS: [&str; 2] = ["bot", "computer"];

/// Why a character may not stand in any name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Forbidden {
    /// A control character (C0, DEL, C1: tabs, newlines, escapes, …).
    Control,
    /// A bidirectional control (marks, embeddings, overrides, isolates),
    /// which reorders the text around it.
    Bidi,
    /// A line or paragraph separator.
    LineBreak,
    /// An invisible character (default-ignorable: zero-width spaces and
    /// joiners, soft hyphens, variation selectors, tags, fillers, …).
    Invisible,
}

impl std::fmt::Display for Forbidden {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Forbidden::Control => "a control character",
            Forbidden::Bidi => "a bidirectional control",
            Forbidden::LineBreak => "a line or paragraph separator",
            Forbidden::Invisible => "an invisible character",
        })
    }
}

/// Why a name is not an account name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NameError {
    /// Fewer than [`MIN_NAME`] characters.
    #[error("an account name is at least {} characters", MIN_NAME)]
    TooShort,
    /// More than [`MAX_NAME`] characters.
    #[error("an account name is at most {} characters", MAX_NAME)]
    TooLong,
    /// A character other than an ASCII letter, digit, `_` or `-`.
    #[error("an account name has only letters, digits, '_' or '-', not {0:?}")]
    BadCharacter(char),
    /// Starts with `_` or `-`.
    #[error("an account name starts with a letter or digit, not {0:?}")]
    BadStart(char),
    /// An impostor of the computer's names ([`is_reserved`]; only for a
    /// new name, never for one already stored).
    #[error("names like 'bot', 'bot (hard)' or 'computer-hard', in any case or look-alike letters, are the computer's")]
    Reserved,
    /// A seat's name with nothing left once trimmed.
    #[error("a name has at least one visible character")]
    Empty,
    /// A seat's name of more than [`MAX_SEAT_NAME`] characters.
    #[error("a name is at most {} characters", MAX_SEAT_NAME)]
    SeatTooLong,
    /// A character no name may hold.
    #[error("a name may not hold {why} (U+{code:04X})", why = .1, code = *.0 as u32)]
    Forbidden(char, Forbidden),
}

/// The rule in words: "3 to 20 letters, digits, '_' or '-', starting with
/// a letter or digit".
pub fn rule() -> String {
    format!("{MIN_NAME} to {MAX_NAME} letters, digits, '_' or '-', starting with a letter or digit")
}

/// Whether `c` may stand in an account name.
fn allowed(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || c == '-'
}

/// Whether `name` has the shape of an account name, as every account's
/// name has, the computer levels' included (what a link to a player's
/// profile may name). The first reason found: length, then characters,
/// then the first character.
pub fn check(name: &str) -> Result<(), NameError> {
    let len = name.chars().count();
    if len < MIN_NAME {
        return Err(NameError::TooShort);
    }
    if len > MAX_NAME {
        return Err(NameError::TooLong);
    }
    if let Some(c) = name.chars().find(|&c| !allowed(c)) {
        return Err(NameError::BadCharacter(c));
    }
    match name.chars().next() {
        Some(c) if !c.is_ascii_alphanumeric() => Err(NameError::BadStart(c)),
        _ => Ok(()),
    }
}

/// Why `c` may stand in no name, if it may not.
pub fn forbidden(c: char) -> Option<Forbidden> {
    match c {
        _ if c.is_control() => Some(Forbidden::Control),
        '\u{061C}'
        | '\u{200E}'
        | '\u{200F}'
        | '\u{202A}'..='\u{202E}'
        | '\u{2066}'..='\u{2069}' => Some(Forbidden::Bidi),
        '\u{2028}' | '\u{2029}' => Some(Forbidden::LineBreak),
        // The confusables' skeleton drops exactly the default-ignorable
        // code points (UTS #39), so it tells them without a second table.
        _ if unicode_security::skeleton(c.encode_utf8(&mut [0; 4]))
            .next()
            .is_none() =>
        {
            Some(Forbidden::Invisible)
        }
        _ => None,
    }
}

/// `name` folded for comparison: its confusables' skeleton (UTS #39),
/// lower-cased, and the skeleton again (so that `ВОТ`, `B0T` and `bot`
/// fold alike).
fn fold(name: &str) -> String {
    let lower = unicode_security::skeleton(name)
        .collect::<String>()
        .to_lowercase();
    unicode_security::skeleton(&lower).collect()
}

/// Whether `a` and `b` pass for one another on screen: equal once folded
/// (confusables' skeleton, case), so `Anka`, `АNKA` and `Ankа` (with
/// Cyrillic letters) are one name.
pub fn passes_for(a: &str, b: &str) -> bool {
    fold(a) == fold(b)
}

/// Whether `name` passes for one of the computer's names: once folded, it
/// is one of [`RESERVED_WORDS`] or starts with one followed by something
/// other than a letter or digit (`bot (hard)`, `Computer-Easy`, `B0T`,
/// `ВОТ` in Cyrillic capitals; not `Botvinnik` or `computers`).
pub fn is_reserved(name: &str) -> bool {
    let folded = fold(name.trim());
    RESERVED_WORDS.iter().any(|word| {
        folded
            .strip_prefix(fold(word).as_str())
            .is_some_and(|rest| rest.chars().next().is_none_or(|c| !c.is_alphanumeric()))
    })
}

/// The rule every name a person sees follows: no forbidden character
/// ([`forbidden`]; the first one found is named), and not an impostor
/// of the computer's names ([`is_reserved`]).
pub fn check_visible(name: &str) -> Result<(), NameError> {
    if let Some((c, why)) = name.chars().find_map(|c| forbidden(c).map(|w| (c, w))) {
        return Err(NameError::Forbidden(c, why));
    }
    if is_reserved(name) {
        return Err(NameError::Reserved);
    }
    Ok(())
}

/// A casual seat's name as it will be shown: `raw` normalised (NFKC) and
/// trimmed, 1 to [`MAX_SEAT_NAME`] characters, following
/// [`check_visible`]; or why it may not be one.
pub fn seat_name(raw: &str) -> Result<String, NameError> {
    use unicode_normalization::UnicodeNormalization;
    let normal: String = raw.nfkc().collect();
    let name = normal.trim();
    if name.is_empty() {
        return Err(NameError::Empty);
    }
    if name.chars().count() > MAX_SEAT_NAME {
        return Err(NameError::SeatTooLong);
    }
    check_visible(name)?;
    Ok(name.to_string())
}

/// Whether a new account may take `name`: not reserved (checked first, so
/// a reserved name is refused as reserved whatever else is wrong with
/// it), and of the shape [`check`] asks (whose ASCII leaves no other
/// character [`check_visible`] refuses).
pub fn check_new(name: &str) -> Result<(), NameError> {
    if is_reserved(name) {
        return Err(NameError::Reserved);
    }
    check(name)
}

/// A name a new account may take: it passed [`check_new`]. The store takes
/// only these, so no account is ever created under a name the rule
/// refuses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AccountName(String);

impl AccountName {
    /// `name` as a new account's name, or why it may not be one.
    pub fn parse(name: &str) -> Result<AccountName, NameError> {
        check_new(name).map(|()| AccountName(name.to_string()))
    }

    /// The name.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

/// The account name of a built-in computer level (`computer-easy`, …),
/// from its wire name.
pub fn computer_account(level: impl std::fmt::Display) -> String {
    format!("{COMPUTER_PREFIX}{level}")
}

/// A refused name, as the protocol's `reserved-name` error for an
/// impostor of the computer's names and `bad-name` for any other reason.
impl From<NameError> for crate::refusal::Refusal {
    fn from(e: NameError) -> Self {
        let code = match e {
            NameError::Reserved => crate::refusal::ErrorCode::ReservedName,
            _ => crate::refusal::ErrorCode::BadName,
        };
        crate::refusal::Refusal::new(code, e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_3_to_20_letters_digits_underscores_and_hyphens_pass() {
        for ok in [
            "abc",
            "Anka",
            "7up",
            "Petka_2",
            "a-b-c",
            "Anka-the_2nd",
            "x2345678901234567890",
        ] {
            assert_eq!(check(ok), Ok(()), "{ok}");
            assert_eq!(check_new(ok), Ok(()), "{ok}");
        }
    }

    #[test]
    fn a_name_under_the_minimum_is_too_short() {
        assert_eq!(check(""), Err(NameError::TooShort));
        assert_eq!(check("ab"), Err(NameError::TooShort));
        assert_eq!(check(&"a".repeat(MIN_NAME)), Ok(()));
    }

    #[test]
    fn a_name_over_the_maximum_is_too_long() {
        assert_eq!(check("x23456789012345678901"), Err(NameError::TooLong));
        assert_eq!(check(&"a".repeat(MAX_NAME)), Ok(()));
        assert_eq!(check(&"a".repeat(MAX_NAME + 1)), Err(NameError::TooLong));
    }

    #[test]
    fn length_counts_characters_not_bytes() {
        // Six characters, twelve bytes: long enough, but not ASCII.
        assert_eq!(check("Чапаев"), Err(NameError::BadCharacter('Ч')));
        // Two characters, four bytes: too short however many bytes.
        assert_eq!(check("Чп"), Err(NameError::TooShort));
    }

    #[test]
    fn a_character_other_than_ascii_letters_digits_underscore_or_hyphen_is_refused() {
        assert_eq!(check("a b c"), Err(NameError::BadCharacter(' ')));
        assert_eq!(check("has space"), Err(NameError::BadCharacter(' ')));
        assert_eq!(check("a\u{0}bc"), Err(NameError::BadCharacter('\u{0}')));
        assert_eq!(check("dot.name"), Err(NameError::BadCharacter('.')));
    }

    #[test]
    fn a_name_starting_with_underscore_or_hyphen_is_refused() {
        assert_eq!(check("_abc"), Err(NameError::BadStart('_')));
        assert_eq!(check("-abc"), Err(NameError::BadStart('-')));
        assert_eq!(check("a_-"), Ok(()));
    }

    #[test]
    fn computer_levels_names_have_the_shape_but_no_new_account_may_take_them() {
        for level in ["computer-easy", "computer-adaptive"] {
            assert_eq!(check(level), Ok(()), "{level}");
            assert_eq!(check_new(level), Err(NameError::Reserved), "{level}");
        }
        assert_eq!(check_new("Computer-Hard"), Err(NameError::Reserved));
        // Reserved wins over every other reason.
        assert_eq!(
            check_new("computer-far-too-long-a-name"),
            Err(NameError::Reserved)
        );
        assert!(is_reserved("computer"));
        assert!(!is_reserved("computers"));
        assert!(!is_reserved("Чапаев-computer-"));
        assert_eq!(check_new("computerx"), Ok(()));
        assert_eq!(check_new("Bot"), Err(NameError::Reserved));
        assert_eq!(check_new("b0t-2"), Err(NameError::Reserved));
        assert_eq!(check_new("Botvinnik"), Ok(()));
    }

    #[test]
    fn the_rule_in_words_names_the_limits() {
        assert_eq!(
            rule(),
            "3 to 20 letters, digits, '_' or '-', starting with a letter or digit"
        );
        assert_eq!(
            NameError::Reserved.to_string(),
            "names like 'bot', 'bot (hard)' or 'computer-hard', in any case or look-alike letters, are the computer's"
        );
        assert_eq!(
            NameError::Forbidden('\u{202E}', Forbidden::Bidi).to_string(),
            "a name may not hold a bidirectional control (U+202E)"
        );
        assert_eq!(
            NameError::TooLong.to_string(),
            "an account name is at most 20 characters"
        );
    }

    #[test]
    fn an_account_name_is_only_made_from_a_name_a_new_account_may_take() {
        assert_eq!(AccountName::parse("Anka").unwrap().as_str(), "Anka");
        assert_eq!(AccountName::parse("ab"), Err(NameError::TooShort));
        assert_eq!(
            AccountName::parse("computer-hard"),
            Err(NameError::Reserved)
        );
        let refusal = crate::refusal::Refusal::from(NameError::TooLong);
        assert_eq!(refusal.code, crate::refusal::ErrorCode::BadName);
        let refusal = crate::refusal::Refusal::from(NameError::Reserved);
        assert_eq!(refusal.code, crate::refusal::ErrorCode::ReservedName);
        assert_eq!(computer_account("easy"), "computer-easy");
    }

    #[test]
    fn a_seat_name_is_normalised_and_trimmed() {
        assert_eq!(seat_name("  Petka  ").as_deref(), Ok("Petka"));
        assert_eq!(
            seat_name("Анка-пулемётчица").as_deref(),
            Ok("Анка-пулемётчица")
        );
        // Full-width letters and the ligature "ﬁ" become plain ones (NFKC).
        assert_eq!(seat_name("Ｐｅｔｋａ").as_deref(), Ok("Petka"));
        assert_eq!(seat_name("ﬁsh").as_deref(), Ok("fish"));
        // A no-break space is a space, and trimmed like one.
        assert_eq!(
            seat_name("\u{00A0}Vasily Ivanovich\u{3000}").as_deref(),
            Ok("Vasily Ivanovich")
        );
        assert_eq!(
            seat_name(&"я".repeat(MAX_SEAT_NAME)),
            Ok("я".repeat(MAX_SEAT_NAME))
        );
    }

    #[test]
    fn an_empty_or_too_long_seat_name_is_refused() {
        assert_eq!(seat_name(""), Err(NameError::Empty));
        assert_eq!(seat_name(" \u{3000} "), Err(NameError::Empty));
        assert_eq!(
            seat_name(&"я".repeat(MAX_SEAT_NAME + 1)),
            Err(NameError::SeatTooLong)
        );
    }

    #[test]
    fn hostile_characters_are_refused_with_their_reason() {
        for (name, c, why) in [
            ("Pet\u{202E}akt", '\u{202E}', Forbidden::Bidi),
            ("\u{2067}Anka", '\u{2067}', Forbidden::Bidi),
            ("Anka\u{200F}", '\u{200F}', Forbidden::Bidi),
            ("Pet\u{200B}ka", '\u{200B}', Forbidden::Invisible),
            ("Pet\u{200D}ka", '\u{200D}', Forbidden::Invisible),
            ("Pet\u{FEFF}ka", '\u{FEFF}', Forbidden::Invisible),
            ("Pet\u{00AD}ka", '\u{00AD}', Forbidden::Invisible),
            ("Pet\u{2060}ka", '\u{2060}', Forbidden::Invisible),
            ("Petka\u{E0041}", '\u{E0041}', Forbidden::Invisible),
            ("Pet\u{180E}ka", '\u{180E}', Forbidden::Invisible),
            ("Pet\u{2028}ka", '\u{2028}', Forbidden::LineBreak),
            ("Pet\u{2029}ka", '\u{2029}', Forbidden::LineBreak),
            ("Pet\nka", '\n', Forbidden::Control),
            ("Pet\tka", '\t', Forbidden::Control),
            ("Pet\u{1B}[31mka", '\u{1B}', Forbidden::Control),
            ("Pet\u{85}ka", '\u{85}', Forbidden::Control),
        ] {
            assert_eq!(
                seat_name(name),
                Err(NameError::Forbidden(c, why)),
                "{name:?}"
            );
            assert_eq!(
                check_visible(name),
                Err(NameError::Forbidden(c, why)),
                "{name:?}"
            );
        }
    }

    #[test]
    fn impostors_of_the_computers_names_are_reserved_whatever_their_spelling() {
        for impostor in [
            "bot",
            "Bot",
            "BOT",
            "bot (hard)",
            "bot (medium)",
            "Bot (Easy)",
            "bot(adaptive)",
            "bot-hard",
            "computer",
            "computer-hard",
            "Computer-Adaptive",
            "computer (hard)",
            "cоmputer-hard", // a Cyrillic о
            "ВОТ (hard)",    // Cyrillic capitals
            "ΒΟΤ",           // Greek capitals
            "b0t",
            "ｂｏｔ （ｈａｒｄ）", // full width, normalised first
            "  bot  ",
        ] {
            assert_eq!(
                seat_name(impostor),
                Err(NameError::Reserved),
                "{impostor:?}"
            );
        }
        // Zero-width tricks are refused before they can hide anything.
        assert!(matches!(
            seat_name("b\u{200B}ot"),
            Err(NameError::Forbidden(..))
        ));
        for fine in [
            "Botvinnik",
            "robot",
            "computers",
            "a bot",
            "Petka vs bot",
            "bo",
            "Ботаник",
        ] {
            assert_eq!(seat_name(fine).as_deref(), Ok(fine), "{fine:?}");
        }
    }
}
