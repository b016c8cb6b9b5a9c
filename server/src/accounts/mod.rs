//! Accounts: a name that lasts beyond one match, whether it is a person or a
//! bot, its rating, and the secret keys that prove it (a person's browser
//! keeps one; a bot process holds one as its API token). Keys are 128
//! random bits; the store keeps only their SHA-256 hashes, checks a
//! presented key by its hash and compares in constant time
//! ([`game::token`]), and a key can be revoked. Names follow
//! [`game::name`]'s rule and are unique without regard to
//! case. The tables live in the match store (either backend), so a
//! match's result and the ratings it moves can be written in one
//! transaction. A bot account may also upload the module the server hosts
//! it with ([`modules`]).

pub mod modules;

use crate::store::{Profile, Store, StoreError};
use crate::token::{seat_token, RandomError, SeatToken, TokenHash};
use game::name::AccountName;
use game::protocol::ErrorCode;
use game::protocol::Refusal;
use game::rating::{Rating, RatingSystem};

/// Shortest password, in characters.
pub const MIN_PASSWORD: usize = 8;
/// Longest password, in characters.
pub const MAX_PASSWORD: usize = 128;

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

fn refused(code: ErrorCode, message: impl Into<String>) -> AccountError {
    AccountError::Refused(Refusal::new(code, message))
}

fn bad_key() -> AccountError {
    refused(
        ErrorCode::BadKey,
        "the account key is missing, wrong or revoked",
    )
}

/// The rules of accounts, on whichever store: keys are drawn here and
/// only their hashes stored, passwords are hashed here (Argon2id) and
/// checked here, and every refusal has its code.
impl dyn Store {
    /// Creates an account and its first key (returned once: only its hash
    /// is kept). A name already taken, in any case, is refused.
    pub fn create_account(
        &self,
        name: &AccountName,
        bot: bool,
    ) -> Result<(Profile, SeatToken), AccountError> {
        let key = seat_token()?;
        let start: Rating = RatingSystem::default().start;
        if !self.insert_account(name, bot, start, &key.hash())? {
            return Err(refused(
                ErrorCode::NameTaken,
                format!("the name {} is taken", name.as_str()),
            ));
        }
        let profile = self
            .account(name.as_str())?
            .ok_or_else(|| StoreError::Corrupt(format!("account {} vanished", name.as_str())))?;
        Ok((profile, key))
    }

    /// The account a key proves, if the key is one of its keys and not
    /// revoked.
    pub fn account_of_key(&self, key: &SeatToken) -> Result<Profile, AccountError> {
        let Some((stored, account)) = self.key(&key.hash())? else {
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
        self.insert_key(&account.name, &new.hash())?;
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
        self.put_password(&account.name, &hash)?;
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
        let Some((account, hash)) = self.password(name)? else {
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
        self.insert_key(&account, &key.hash())?;
        let profile = self
            .account(&account)?
            .ok_or_else(|| StoreError::Corrupt(format!("account {account} vanished")))?;
        Ok((profile, key))
    }

    /// Revokes `key`: from now on it proves nothing.
    pub fn revoke_key(&self, key: &SeatToken) -> Result<(), AccountError> {
        self.account_of_key(key)?;
        if self.revoke(&key.hash())? {
            Ok(())
        } else {
            Err(bad_key())
        }
    }
}
