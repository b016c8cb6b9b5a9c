//! Accounts: a name that lasts beyond one match, whether it is a person or a
//! bot, its rating, and the secret keys that prove it (a person's browser
//! keeps one; a bot process holds one as its API token). Keys are 128
//! random bits; the store keeps only their SHA-256 hashes, checks a
//! presented key by its hash and compares in constant time
//! ([`game::token`]), and a key can be revoked. Names are checked here
//! (3 to 20 letters, digits, `_` and `-`) and unique without regard to
//! case. The tables live in the match store's SQLite file, so a match's
//! result and the ratings it moves can be written in one transaction.

use crate::store::{now, Store, StoreError};
use crate::token::{seat_token, RandomError, SeatToken, TokenHash};
use game::protocol::ErrorCode;
use game::protocol::Refusal;
use game::rating::{Rating, RatingSystem};
use rusqlite::{params, Connection, OptionalExtension};
use serde::Serialize;

/// Shortest account name, in characters.
pub const MIN_NAME: usize = 3;
/// Longest account name, in characters.
pub const MAX_NAME: usize = 20;
/// Shortest password, in characters.
pub const MIN_PASSWORD: usize = 8;
/// Longest password, in characters.
pub const MAX_PASSWORD: usize = 128;

/// Most accounts one leaderboard lists.
pub const MAX_LEADERBOARD: usize = 100;

const TABLES: &str = "
CREATE TABLE IF NOT EXISTS accounts (
    name TEXT PRIMARY KEY COLLATE NOCASE,
    bot INTEGER NOT NULL,
    created_at INTEGER NOT NULL,
    rating REAL NOT NULL,
    deviation REAL NOT NULL,
    volatility REAL NOT NULL,
    games INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX IF NOT EXISTS accounts_by_rating ON accounts (bot, rating DESC);
CREATE TABLE IF NOT EXISTS account_passwords (
    account TEXT PRIMARY KEY COLLATE NOCASE REFERENCES accounts (name),
    hash TEXT NOT NULL,
    set_at INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS account_keys (
    hash TEXT PRIMARY KEY,
    account TEXT NOT NULL REFERENCES accounts (name) COLLATE NOCASE,
    created_at INTEGER NOT NULL,
    revoked_at INTEGER
);
";

/// Creates the account tables if the store has none yet.
pub(crate) fn create_tables(conn: &Connection) -> Result<(), StoreError> {
    conn.execute_batch(TABLES)?;
    Ok(())
}

/// An account name that passed the rules.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AccountName(String);

impl AccountName {
    /// `name` if it is 3 to 20 ASCII letters, digits, `_` or `-`, starting
    /// with a letter or digit, and not one of the computer levels'
    /// (`computer-…`).
    pub fn parse(name: &str) -> Result<AccountName, Refusal> {
        let ok = (MIN_NAME..=MAX_NAME).contains(&name.chars().count())
            && name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
            && name
                .bytes()
                .next()
                .is_some_and(|b| b.is_ascii_alphanumeric());
        let reserved = name
            .get(..crate::ratings::COMPUTER_PREFIX.len())
            .is_some_and(|p| p.eq_ignore_ascii_case(crate::ratings::COMPUTER_PREFIX));
        if reserved {
            return Err(Refusal::new(
                ErrorCode::BadName,
                format!(
                    "names starting with {} are the computer levels'",
                    crate::ratings::COMPUTER_PREFIX
                ),
            ));
        }
        if ok {
            Ok(AccountName(name.to_string()))
        } else {
            Err(Refusal::new(
                ErrorCode::BadName,
                format!(
                    "an account name is {MIN_NAME} to {MAX_NAME} letters, digits, '_' or '-', \
                     starting with a letter or digit"
                ),
            ))
        }
    }

    /// The name.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

/// A person's or a bot's account as everyone may see it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Profile {
    pub name: String,
    /// Whether the account is a bot's.
    pub bot: bool,
    pub created_at: u64,
    /// The rating, rounded.
    pub rating: i64,
    /// Its deviation, rounded.
    pub deviation: i64,
    /// Whether the rating is still provisional (too few rated games).
    pub provisional: bool,
    /// Rated matches played.
    pub games: u64,
}

/// Why an account could not be created or used.
#[derive(Debug, thiserror::Error)]
pub enum AccountError {
    /// The request itself is refused (its code says why).
    #[error("{0}")]
    Refused(Refusal),
    #[error(transparent)]
    Store(#[from] StoreError),
    #[error(transparent)]
    Random(#[from] RandomError),
}

impl From<rusqlite::Error> for AccountError {
    fn from(e: rusqlite::Error) -> AccountError {
        AccountError::Store(e.into())
    }
}

fn refused(code: ErrorCode, message: impl Into<String>) -> AccountError {
    AccountError::Refused(Refusal::new(code, message))
}

fn bad_key() -> AccountError {
    refused(
        ErrorCode::BadKey,
        "the account key is missing, wrong or revoked",
    )
}

const PROFILE_COLUMNS: &str = "name, bot, created_at, rating, deviation, volatility, games";

fn profile(row: &rusqlite::Row<'_>) -> rusqlite::Result<(Profile, f64)> {
    let deviation: f64 = row.get(4)?;
    Ok((
        Profile {
            name: row.get(0)?,
            bot: row.get(1)?,
            created_at: row.get::<_, i64>(2)?.max(0) as u64,
            rating: row.get::<_, f64>(3)?.round() as i64,
            deviation: deviation.round() as i64,
            provisional: false,
            games: row.get::<_, i64>(6)?.max(0) as u64,
        },
        deviation,
    ))
}

fn finish((mut p, deviation): (Profile, f64)) -> Profile {
    p.provisional = deviation > RatingSystem::default().provisional_above;
    p
}

impl Store {
    /// Creates an account and its first key (returned once: only its hash
    /// is kept). A name already taken, in any case, is refused.
    pub fn create_account(
        &self,
        name: &AccountName,
        bot: bool,
    ) -> Result<(Profile, SeatToken), AccountError> {
        let key = seat_token()?;
        let start: Rating = RatingSystem::default().start;
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let taken: bool = tx.query_row(
            "SELECT count(*) FROM accounts WHERE name = ?1",
            params![name.as_str()],
            |r| r.get::<_, i64>(0).map(|n| n > 0),
        )?;
        if taken {
            return Err(refused(
                ErrorCode::NameTaken,
                format!("the name {} is taken", name.as_str()),
            ));
        }
        let t = now() as i64;
        tx.execute(
            "INSERT INTO accounts (name, bot, created_at, rating, deviation, volatility)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
            params![
                name.as_str(),
                bot,
                t,
                start.rating,
                start.deviation,
                start.volatility
            ],
        )?;
        tx.execute(
            "INSERT INTO account_keys (hash, account, created_at) VALUES (?1, ?2, ?3)",
            params![key.hash().to_hex(), name.as_str(), t],
        )?;
        tx.commit()?;
        drop(conn);
        let profile = self
            .account(name.as_str())?
            .ok_or_else(|| StoreError::Corrupt(format!("account {} vanished", name.as_str())))?;
        Ok((profile, key))
    }

    /// The account named `name` (in any case), if there is one.
    pub fn account(&self, name: &str) -> Result<Option<Profile>, StoreError> {
        let conn = self.read()?;
        let row = conn
            .query_row(
                &format!("SELECT {PROFILE_COLUMNS} FROM accounts WHERE name = ?1"),
                params![name],
                profile,
            )
            .optional()?;
        Ok(row.map(finish))
    }

    /// The account a key proves, if the key is one of its keys and not
    /// revoked.
    pub fn account_of_key(&self, key: &SeatToken) -> Result<Profile, AccountError> {
        let hash = key.hash();
        let conn = self.read()?;
        let found: Option<(String, String)> = conn
            .query_row(
                "SELECT hash, account FROM account_keys WHERE hash = ?1 AND revoked_at IS NULL",
                params![hash.to_hex()],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .optional()?;
        drop(conn);
        let Some((stored, account)) = found else {
            return Err(bad_key());
        };
        // Found by its hash; compared again in constant time, as every key.
        let stored = TokenHash::from_hex(&stored)
            .map_err(|_| StoreError::Corrupt("an account key hash is not hex".into()))?;
        if !stored.matches(key) {
            return Err(bad_key());
        }
        self.account(&account)?.ok_or_else(bad_key)
    }

    /// A further key for the account `key` proves (to carry the account to
    /// another browser, or to give a bot process its own).
    pub fn add_key(&self, key: &SeatToken) -> Result<(Profile, SeatToken), AccountError> {
        let account = self.account_of_key(key)?;
        let new = seat_token()?;
        let conn = self.lock()?;
        conn.execute(
            "INSERT INTO account_keys (hash, account, created_at) VALUES (?1, ?2, ?3)",
            params![new.hash().to_hex(), account.name, now() as i64],
        )?;
        Ok((account, new))
    }

    /// Sets (or replaces) the password of the person's account `key`
    /// proves: 8 to 128 characters, kept only as an Argon2id hash. Bots
    /// use keys only.
    pub fn set_password(&self, key: &SeatToken, password: &str) -> Result<(), AccountError> {
        let account = self.account_of_key(key)?;
        if account.bot {
            return Err(refused(
                ErrorCode::BadMessage,
                "a bot account signs in with its keys only",
            ));
        }
        let n = password.chars().count();
        if !(MIN_PASSWORD..=MAX_PASSWORD).contains(&n) {
            return Err(refused(
                ErrorCode::BadPassword,
                format!("a password is {MIN_PASSWORD} to {MAX_PASSWORD} characters"),
            ));
        }
        use argon2::password_hash::{rand_core::OsRng, PasswordHasher, SaltString};
        let salt = SaltString::generate(&mut OsRng);
        let hash = argon2::Argon2::default()
            .hash_password(password.as_bytes(), &salt)
            .map_err(|e| StoreError::Corrupt(format!("hashing a password: {e}")))?
            .to_string();
        let conn = self.lock()?;
        conn.execute(
            "INSERT INTO account_passwords (account, hash, set_at) VALUES (?1, ?2, ?3)
             ON CONFLICT (account) DO UPDATE SET hash = ?2, set_at = ?3",
            params![account.name, hash, now() as i64],
        )?;
        Ok(())
    }

    /// Signs in to `name` with its password: a new key for this browser.
    /// A wrong password, an unknown name and an account without a
    /// password are refused alike (`bad-password`).
    pub fn sign_in(
        &self,
        name: &str,
        password: &str,
    ) -> Result<(Profile, SeatToken), AccountError> {
        let wrong = || refused(ErrorCode::BadPassword, "wrong name or password");
        let stored: Option<(String, String)> = self
            .read()?
            .query_row(
                "SELECT account, hash FROM account_passwords WHERE account = ?1",
                params![name],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .optional()?;
        let Some((account, hash)) = stored else {
            return Err(wrong());
        };
        use argon2::password_hash::{PasswordHash, PasswordVerifier};
        let parsed = PasswordHash::new(&hash)
            .map_err(|e| StoreError::Corrupt(format!("a stored password hash: {e}")))?;
        if argon2::Argon2::default()
            .verify_password(password.as_bytes(), &parsed)
            .is_err()
        {
            return Err(wrong());
        }
        let key = seat_token()?;
        self.lock()?.execute(
            "INSERT INTO account_keys (hash, account, created_at) VALUES (?1, ?2, ?3)",
            params![key.hash().to_hex(), account, now() as i64],
        )?;
        let profile = self
            .account(&account)?
            .ok_or_else(|| StoreError::Corrupt(format!("account {account} vanished")))?;
        Ok((profile, key))
    }

    /// Revokes `key`: from now on it proves nothing.
    pub fn revoke_key(&self, key: &SeatToken) -> Result<(), AccountError> {
        self.account_of_key(key)?;
        let conn = self.lock()?;
        let n = conn.execute(
            "UPDATE account_keys SET revoked_at = ?2 WHERE hash = ?1 AND revoked_at IS NULL",
            params![key.hash().to_hex(), now() as i64],
        )?;
        if n == 1 {
            Ok(())
        } else {
            Err(bad_key())
        }
    }

    /// The accounts of people (or of bots) by rating, highest first, those
    /// whose rating is established before the provisional ones.
    pub fn leaderboard(&self, bots: bool, limit: usize) -> Result<Vec<Profile>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(&format!(
            "SELECT {PROFILE_COLUMNS} FROM accounts WHERE bot = ?1
             ORDER BY deviation > ?2, rating DESC, name LIMIT ?3"
        ))?;
        let rows = stmt
            .query_map(
                params![
                    bots,
                    RatingSystem::default().provisional_above,
                    limit.min(MAX_LEADERBOARD) as i64
                ],
                profile,
            )?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(rows.into_iter().map(finish).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name(s: &str) -> AccountName {
        AccountName::parse(s).unwrap()
    }

    fn code(e: AccountError) -> ErrorCode {
        match e {
            AccountError::Refused(r) => r.code,
            other => panic!("not a refusal: {other}"),
        }
    }

    #[test]
    fn names_are_3_to_20_plain_characters() {
        for ok in ["abc", "Anka-the_2nd", "x2345678901234567890", "7up"] {
            assert!(AccountName::parse(ok).is_ok(), "{ok}");
        }
        for bad in [
            "ab",
            "",
            "a b c",
            "-abc",
            "x23456789012345678901",
            "Чапаев",
            "a\u{0}bc",
        ] {
            let err = AccountName::parse(bad).unwrap_err();
            assert_eq!(err.code, ErrorCode::BadName, "{bad:?}");
        }
    }

    #[test]
    fn a_new_account_starts_provisional_at_1500_and_its_key_proves_it() {
        let store = Store::in_memory().unwrap();
        let (profile, key) = store.create_account(&name("Anka"), false).unwrap();
        assert_eq!(
            (profile.rating, profile.deviation, profile.provisional),
            (1500, 500, true)
        );
        assert_eq!(store.account_of_key(&key).unwrap().name, "Anka");
        assert_eq!(store.account("anka").unwrap().unwrap().name, "Anka");
        assert!(store.account("Petka").unwrap().is_none());
    }

    #[test]
    fn a_name_taken_in_any_case_is_refused_and_changes_nothing() {
        let store = Store::in_memory().unwrap();
        let (_, key) = store.create_account(&name("Anka"), false).unwrap();
        let err = store.create_account(&name("ANKA"), true).unwrap_err();
        assert_eq!(code(err), ErrorCode::NameTaken);
        let anka = store.account_of_key(&key).unwrap();
        assert!(!anka.bot);
        assert!(store
            .leaderboard(true, 10)
            .unwrap()
            .iter()
            .all(|p| p.name.starts_with(crate::ratings::COMPUTER_PREFIX)));
    }

    #[test]
    fn a_wrong_or_revoked_key_proves_nothing() {
        let store = Store::in_memory().unwrap();
        let (_, key) = store.create_account(&name("Furmanov"), true).unwrap();
        let wrong = SeatToken::new("0".repeat(32));
        assert_eq!(
            code(store.account_of_key(&wrong).unwrap_err()),
            ErrorCode::BadKey
        );
        let (_, second) = store.add_key(&key).unwrap();
        store.revoke_key(&key).unwrap();
        assert_eq!(
            code(store.account_of_key(&key).unwrap_err()),
            ErrorCode::BadKey
        );
        assert_eq!(code(store.revoke_key(&key).unwrap_err()), ErrorCode::BadKey);
        assert_eq!(store.account_of_key(&second).unwrap().name, "Furmanov");
    }

    #[test]
    fn the_leaderboard_lists_one_kind_established_ratings_first() {
        let store = Store::in_memory().unwrap();
        for (n, bot) in [("greedy", true), ("search", true), ("Anka", false)] {
            store.create_account(&name(n), bot).unwrap();
        }
        {
            let conn = store.lock().unwrap();
            conn.execute(
                "UPDATE accounts SET rating = 1620, deviation = 80 WHERE name = 'search'",
                [],
            )
            .unwrap();
            conn.execute(
                "UPDATE accounts SET rating = 1700 WHERE name = 'greedy'",
                [],
            )
            .unwrap();
        }
        let bots: Vec<(String, bool)> = store
            .leaderboard(true, 10)
            .unwrap()
            .into_iter()
            .filter(|p| !p.name.starts_with(crate::ratings::COMPUTER_PREFIX))
            .map(|p| (p.name, p.provisional))
            .collect();
        assert_eq!(
            bots,
            [("search".to_string(), false), ("greedy".to_string(), true)]
        );
        assert_eq!(store.leaderboard(false, 10).unwrap().len(), 1);
    }

    #[test]
    fn a_person_may_add_a_password_and_sign_in_with_it_for_a_new_key() {
        let store = Store::in_memory().unwrap();
        let (_, key) = store.create_account(&name("Anka"), false).unwrap();
        let short = store.set_password(&key, "short").unwrap_err();
        assert_eq!(code(short), ErrorCode::BadPassword);
        store.set_password(&key, "machine-gun cart").unwrap();
        let stored: String = store
            .read()
            .unwrap()
            .query_row("SELECT hash FROM account_passwords", [], |r| r.get(0))
            .unwrap();
        assert!(stored.starts_with("$argon2id$") && !stored.contains("machine-gun"));
        let (profile, new_key) = store.sign_in("anka", "machine-gun cart").unwrap();
        assert_eq!(profile.name, "Anka");
        assert_eq!(store.account_of_key(&new_key).unwrap().name, "Anka");
        for (who, password) in [("Anka", "machine-gun car"), ("Petka", "machine-gun cart")] {
            let e = store.sign_in(who, password).unwrap_err();
            assert_eq!(code(e), ErrorCode::BadPassword, "{who}");
        }
        let (_, bot) = store.create_account(&name("Furmanov"), true).unwrap();
        let e = store.set_password(&bot, "machine-gun cart").unwrap_err();
        assert_eq!(code(e), ErrorCode::BadMessage);
    }
}
