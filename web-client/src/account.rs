//! The player's account as this browser keeps it: the secret key (in
//! localStorage, so it lasts) and the account's name beside it, saved on
//! sign-in and forgotten on sign-out; plus how names and ratings read on
//! screen ("1500?" while a rating is provisional). Without a key the
//! player is anonymous and plays under a free-form name.

use crate::api::{Profile, SeatRating};
use crate::i18n::t;
use crate::platform;
pub use game::name::{MAX_NAME, MIN_NAME};

const KEY_KEY: &str = "chapaev.account.key";
const NAME_KEY: &str = "chapaev.account.name";

/// The signed-in account: its name and key.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Account {
    pub name: String,
    pub key: String,
}

/// The account this browser is signed in to, if any.
pub fn signed_in() -> Option<Account> {
    let key = platform::storage_get(KEY_KEY)?.trim().to_string();
    let name = platform::storage_get(NAME_KEY)?.trim().to_string();
    (!key.is_empty() && valid_name(&name)).then_some(Account { name, key })
}

/// Keeps `key` as proving the account named `name`.
pub fn sign_in(name: &str, key: &str) {
    platform::storage_set(KEY_KEY, key.trim());
    platform::storage_set(NAME_KEY, name);
}

/// Forgets the key (the account itself stays on the server).
pub fn sign_out() {
    platform::storage_set(KEY_KEY, "");
    platform::storage_set(NAME_KEY, "");
}

/// Whether `name` has the shape of an account name (the shared rule,
/// [`game::name::check`]): [`MIN_NAME`] to [`MAX_NAME`] ASCII letters,
/// digits, `_` or `-`, starting with a letter or digit.
pub fn valid_name(name: &str) -> bool {
    game::name::check(name).is_ok()
}

/// The rule as the account screen's hint says it, from the shared limits:
/// "a name of 3 to 20 letters, digits, _ or -".
pub fn name_hint() -> String {
    t!("account-name-hint", min = MIN_NAME, max = MAX_NAME)
}

/// The rule as the account screen says it when a name breaks it:
/// "a name is 3 to 20 letters, digits, _ or -".
pub fn name_rule() -> String {
    t!("account-name-rule", min = MIN_NAME, max = MAX_NAME)
}

/// A rating as shown: rounded, with a `?` while provisional ("1500?").
pub fn rating_label(rating: f64, provisional: bool) -> String {
    let r = if rating.is_finite() {
        rating.round() as i64
    } else {
        0
    };
    if provisional {
        format!("{r}?")
    } else {
        r.to_string()
    }
}

/// A profile's rating as shown.
pub fn profile_rating(p: &Profile) -> String {
    rating_label(p.rating, p.provisional)
}

/// A seat's name with its rating when it has one ("Petka (1523)").
pub fn with_rating(name: &str, rating: Option<SeatRating>) -> String {
    match rating {
        Some(r) => format!("{name} ({})", rating_label(r.rating, r.provisional)),
        None => name.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_provisional_rating_reads_with_a_question_mark() {
        assert_eq!(rating_label(1500.0, true), "1500?");
        assert_eq!(rating_label(1523.4, false), "1523");
        assert_eq!(rating_label(f64::NAN, false), "0");
    }

    #[test]
    fn a_seat_shows_its_rating_only_when_it_has_one() {
        let r = SeatRating {
            rating: 1611.0,
            provisional: false,
        };
        assert_eq!(with_rating("Petka", Some(r)), "Petka (1611)");
        assert_eq!(with_rating("Petka", None), "Petka");
    }

    #[test]
    fn account_names_follow_the_servers_rules() {
        for ok in ["Anka", "abc", "Petka_2", "a-b-c", "x2345678901234567890"] {
            assert!(valid_name(ok), "{ok}");
        }
        for bad in [
            "",
            "ab",
            "_abc",
            "-abc",
            "has space",
            "Чапаев",
            "x23456789012345678901",
        ] {
            assert!(!valid_name(bad), "{bad}");
        }
    }

    #[test]
    fn the_hints_state_the_shared_limits() {
        assert_eq!(name_hint(), "a name of 3 to 20 letters, digits, _ or -");
        assert_eq!(name_rule(), "a name is 3 to 20 letters, digits, _ or -");
    }

    #[test]
    fn signing_in_keeps_the_key_and_signing_out_forgets_it() {
        sign_in("Anka", " k3y ");
        assert_eq!(
            signed_in(),
            Some(Account {
                name: "Anka".into(),
                key: "k3y".into()
            })
        );
        sign_out();
        assert_eq!(signed_in(), None);
    }
}
