//! Account names: the one rule for them, shared by the server (which
//! refuses a new account whose name breaks it) and the browser client
//! (which checks a name before asking, and builds its hints and its text
//! field's length from the same constants). A name is [`MIN_NAME`] to
//! [`MAX_NAME`] ASCII letters, digits, `_` or `-`, starting with a letter
//! or digit; a new account may not take a name starting with
//! [`COMPUTER_PREFIX`] in any case (the computer levels' accounts have
//! those). Pure functions, each refusal with its typed reason
//! ([`NameError`]).

/// Shortest account name, in characters.
pub const MIN_NAME: usize = 3;
/// Longest account name, in characters.
pub const MAX_NAME: usize = 20;
/// The prefix of the computer levels' account names (`computer-easy`, …),
/// reserved: no new account may start with it, in any case.
pub const COMPUTER_PREFIX: &str = "computer-";

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
    /// Starts with [`COMPUTER_PREFIX`] (only for a new account).
    #[error("names starting with {} are the computer levels'", COMPUTER_PREFIX)]
    Reserved,
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

/// Whether `name` starts with [`COMPUTER_PREFIX`], in any case.
pub fn is_reserved(name: &str) -> bool {
    name.get(..COMPUTER_PREFIX.len())
        .is_some_and(|p| p.eq_ignore_ascii_case(COMPUTER_PREFIX))
}

/// Whether a new account may take `name`: not reserved (checked first, so
/// a reserved name is refused as reserved whatever else is wrong with
/// it), and of the shape [`check`] asks.
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

/// A refused name, as the protocol's `bad-name` error.
impl From<NameError> for crate::refusal::Refusal {
    fn from(e: NameError) -> Self {
        crate::refusal::Refusal::new(crate::refusal::ErrorCode::BadName, e.to_string())
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
        assert!(!is_reserved("computer"));
        assert!(!is_reserved("computers"));
        assert!(!is_reserved("Чапаев-computer-"));
        assert_eq!(check_new("computerx"), Ok(()));
    }

    #[test]
    fn the_rule_in_words_names_the_limits() {
        assert_eq!(
            rule(),
            "3 to 20 letters, digits, '_' or '-', starting with a letter or digit"
        );
        assert_eq!(
            NameError::Reserved.to_string(),
            "names starting with computer- are the computer levels'"
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
        assert_eq!(computer_account("easy"), "computer-easy");
    }
}
