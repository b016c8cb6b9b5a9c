//! Hosted bots' modules: a bot account uploads a WebAssembly module, the
//! server checks it with the [`hosted`] runtime (it must load: valid
//! WebAssembly, no import but the host's two, the documented exports) and
//! keeps it as a version named by its SHA-256, with its upload time. The
//! newest upload is the active version; the author lists the versions and
//! may make any earlier one active again, or delete one that is not
//! active (an account keeps at most [`MAX_VERSIONS`]). A module refused,
//! or a version the account does not have, changes nothing.

use crate::accounts::AccountError;
use crate::store::{ModuleDeleted, ModuleStored, ModuleVersion, Profile, Store};
use game::protocol::{ErrorCode, Refusal};
use hosted::{BotModule, Limits, LoadError};

/// Largest module accepted, in bytes (4 MiB).
pub const MAX_MODULE_BYTES: usize = 4 << 20;

/// The first bytes of every WebAssembly module.
const WASM_MAGIC: &[u8] = b"\0asm";

/// Most versions one account keeps.
pub const MAX_VERSIONS: usize = 32;

/// The limits a hosted module is checked (and run) under: the runtime's
/// own, with the server's module size.
pub fn limits() -> Limits {
    Limits {
        max_module_bytes: MAX_MODULE_BYTES,
        ..Limits::default()
    }
}

fn refused(code: ErrorCode, message: impl Into<String>) -> AccountError {
    AccountError::Refused(Refusal::new(code, message))
}

/// Only a bot's account hosts a module.
fn must_be_bot(account: &Profile) -> Result<(), AccountError> {
    if account.bot {
        Ok(())
    } else {
        Err(refused(
            ErrorCode::NotABot,
            "only a bot's account can host a module (create one with \"bot\": true)",
        ))
    }
}

/// The refusal of a module the runtime would not load.
fn load_refusal(e: LoadError) -> AccountError {
    match e {
        LoadError::TooLarge { limit, .. } => refused(
            ErrorCode::MessageTooLarge,
            format!("a module is at most {limit} bytes"),
        ),
        other => refused(ErrorCode::BadModule, other.to_string()),
    }
}

/// A version's hash as the client gave it: 64 hex digits, any case.
fn parse_hash(text: &str) -> Result<String, AccountError> {
    let text = text.trim();
    if text.len() == 64 && text.bytes().all(|b| b.is_ascii_hexdigit()) {
        Ok(text.to_ascii_lowercase())
    } else {
        Err(refused(
            ErrorCode::NoSuchVersion,
            "a version is named by its SHA-256: 64 hex digits",
        ))
    }
}

impl dyn Store {
    /// Checks `bytes` as a hosted module and stores it as `account`'s
    /// active version; whether it was new. Blocks: the module is compiled.
    pub fn upload_module(
        &self,
        account: &Profile,
        bytes: &[u8],
    ) -> Result<(bool, ModuleVersion), AccountError> {
        must_be_bot(account)?;
        if !bytes.starts_with(WASM_MAGIC) {
            return Err(refused(
                ErrorCode::BadModule,
                "not a WebAssembly module: it does not start with \\0asm",
            ));
        }
        let module = BotModule::load(bytes, &limits()).map_err(load_refusal)?;
        match self.insert_module(&account.name, &module.hash_hex(), bytes, MAX_VERSIONS)? {
            ModuleStored::New(v) => Ok((true, v)),
            ModuleStored::Existing(v) => Ok((false, v)),
            ModuleStored::TooMany { limit } => Err(refused(
                ErrorCode::TooManyVersions,
                format!("an account keeps at most {limit} module versions"),
            )),
        }
    }

    /// `account`'s versions, newest first.
    pub fn module_versions(&self, account: &Profile) -> Result<Vec<ModuleVersion>, AccountError> {
        must_be_bot(account)?;
        Ok(self.modules(&account.name)?)
    }

    /// Makes `account`'s version `hash` the active one.
    pub fn activate_version(
        &self,
        account: &Profile,
        hash: &str,
    ) -> Result<ModuleVersion, AccountError> {
        must_be_bot(account)?;
        let hash = parse_hash(hash)?;
        self.activate_module(&account.name, &hash)?.ok_or_else(|| {
            refused(
                ErrorCode::NoSuchVersion,
                format!("this account has no module version {hash}"),
            )
        })
    }

    /// Deletes `account`'s version `hash`, which must not be the active one
    /// nor play a seat of a match not finished yet.
    pub fn delete_version(&self, account: &Profile, hash: &str) -> Result<(), AccountError> {
        must_be_bot(account)?;
        let hash = parse_hash(hash)?;
        match self.delete_module(&account.name, &hash)? {
            ModuleDeleted::Deleted => Ok(()),
            ModuleDeleted::Active => Err(refused(
                ErrorCode::BadMessage,
                "the active version cannot be deleted: make another one active first",
            )),
            ModuleDeleted::InUse => Err(refused(
                ErrorCode::ModuleInUse,
                "a match not finished yet plays with this version: delete it once the match ends",
            )),
            ModuleDeleted::Missing => Err(refused(
                ErrorCode::NoSuchVersion,
                format!("this account has no module version {hash}"),
            )),
        }
    }
}
