//! `server backup` and `server restore`: copying the store out while the
//! server plays, and back into an empty store, proven whole by replaying
//! every match in it.
//!
//! - SQLite: the backup is SQLite's own consistent copy of the database
//!   (`VACUUM INTO`), taken in one read transaction beside the running
//!   server's writes (the write-ahead log lets both go on), so it holds
//!   every move committed before it began and nothing half written. The
//!   restore checks the file (`PRAGMA integrity_check`, the store's
//!   tables) and copies it into an empty data folder the same way.
//! - PostgreSQL: `pg_dump` (custom format) and `pg_restore` into an empty
//!   database, which must be on PATH; without them, a clear error.
//!
//! Either way a file is written under a temporary name beside its
//! destination and linked into place only when complete, never over an
//! existing file. After a restore the store is opened (its schema brought
//! up to date) and every match replayed through [`game::Replay`].

use crate::config::{Command, Config};
use crate::store::{postgres::PostgresStore, sqlite, SqliteStore, Store, StoreError};
use rusqlite::{Connection, OpenFlags};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// A backup or restore that could not be made; nothing is left half done.
#[derive(Debug, thiserror::Error)]
pub enum BackupError {
    #[error("{0} already exists: a backup is never written over a file")]
    Exists(PathBuf),
    #[error("there is no SQLite store at {0}")]
    NoStore(PathBuf),
    #[error(
        "{0} already holds a store: restore into an empty store (move the old one away first)"
    )]
    NotEmpty(String),
    #[error("{path} is not a backup of this server's store: {why}")]
    NotABackup { path: PathBuf, why: String },
    #[error("{0} is not a UTF-8 path, which SQLite needs")]
    Path(PathBuf),
    #[error(
        "{0} is not on PATH: a PostgreSQL store is backed up and restored with the \
         PostgreSQL client tools (pg_dump, pg_restore) of the server's major version"
    )]
    NoTool(&'static str),
    #[error("running {tool}: {source}")]
    Spawn {
        tool: &'static str,
        source: std::io::Error,
    },
    #[error("{tool} failed ({status}): {stderr}")]
    ToolFailed {
        tool: &'static str,
        status: std::process::ExitStatus,
        stderr: String,
    },
    #[error("{what} {path}: {source}")]
    Io {
        what: &'static str,
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("sqlite: {0}")]
    Sqlite(#[from] rusqlite::Error),
    #[error("postgresql: {0}")]
    Postgres(#[from] ::postgres::Error),
    #[error(transparent)]
    Store(#[from] StoreError),
    #[error("match {id} of the restored store does not replay: {source}")]
    Replay {
        id: String,
        source: game::ReplayError,
    },
}

/// What a restored store holds, every match of it replayed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Restored {
    /// Matches in the store.
    pub matches: usize,
    /// Moves in them.
    pub moves: usize,
    /// Matches of a physics version this server cannot play: kept as
    /// they are, not replayed.
    pub other_physics: usize,
}

/// Runs `command` on the store `config` names; what it did, in a line.
pub fn run(command: &Command, config: &Config) -> Result<String, BackupError> {
    match command {
        Command::Backup { to } => {
            let bytes = backup(config, to)?;
            Ok(format!("backed up to {} ({bytes} bytes)", to.display()))
        }
        Command::Restore { from } => {
            let r = restore(config, from)?;
            Ok(format!(
                "restored from {}: {} matches and {} moves, every one replayed{}",
                from.display(),
                r.matches,
                r.moves,
                if r.other_physics > 0 {
                    format!(
                        " ({} of another physics version kept unplayed)",
                        r.other_physics
                    )
                } else {
                    String::new()
                }
            ))
        }
    }
}

/// Copies the store into `to` (which must not exist); its size in bytes.
pub fn backup(config: &Config, to: &Path) -> Result<u64, BackupError> {
    if to.exists() {
        return Err(BackupError::Exists(to.to_path_buf()));
    }
    let partial = partial(to);
    remove_leftover(&partial)?;
    match &config.database_url {
        None => {
            let db = config.data_dir.join(sqlite::FILE_NAME);
            if !db.is_file() {
                return Err(BackupError::NoStore(db));
            }
            let conn = Connection::open_with_flags(
                &db,
                OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_NO_MUTEX,
            )?;
            conn.busy_timeout(Duration::from_secs(30))?;
            vacuum_into(&conn, &partial)?;
        }
        Some(url) => {
            let file = utf8(&partial)?;
            tool(
                "pg_dump",
                &[
                    "--format=custom",
                    "--no-owner",
                    "--file",
                    file,
                    "--dbname",
                    url,
                ],
            )?;
        }
    }
    put_in_place(&partial, to)
}

/// Restores the backup `from` into the empty store `config` names, then
/// replays every match in it.
pub fn restore(config: &Config, from: &Path) -> Result<Restored, BackupError> {
    if !from.is_file() {
        return Err(BackupError::NotABackup {
            path: from.to_path_buf(),
            why: "no such file".into(),
        });
    }
    match &config.database_url {
        None => {
            let target = config.data_dir.join(sqlite::FILE_NAME);
            if target.exists() {
                return Err(BackupError::NotEmpty(config.data_dir.display().to_string()));
            }
            let source = check_sqlite_backup(from)?;
            std::fs::create_dir_all(&config.data_dir).map_err(|source| BackupError::Io {
                what: "creating",
                path: config.data_dir.clone(),
                source,
            })?;
            let partial = partial(&target);
            remove_leftover(&partial)?;
            vacuum_into(&source, &partial)?;
            put_in_place(&partial, &target)?;
            let store = SqliteStore::open(&config.data_dir, config.sync)?;
            let restored = verify(&store)?;
            store.checkpoint()?;
            Ok(restored)
        }
        Some(url) => {
            let mut client = ::postgres::Client::connect(url, ::postgres::NoTls)?;
            let taken: bool = client
                .query_one("SELECT to_regclass('matches') IS NOT NULL", &[])?
                .get(0);
            drop(client);
            if taken {
                return Err(BackupError::NotEmpty("the PostgreSQL database".into()));
            }
            let file = utf8(from)?;
            tool(
                "pg_restore",
                &["--no-owner", "--exit-on-error", "--dbname", url, file],
            )?;
            let store = PostgresStore::connect(url)?;
            verify(&store)
        }
    }
}

/// Matches replayed per page of ids.
const PAGE: usize = 500;

/// Replays every match of `store`: how many, with how many moves.
pub fn verify(store: &dyn Store) -> Result<Restored, BackupError> {
    let mut restored = Restored::default();
    let mut after: Option<String> = None;
    loop {
        let ids = store.match_ids(after.as_deref(), PAGE)?;
        let Some(last) = ids.last().cloned() else {
            return Ok(restored);
        };
        for id in ids {
            let Some((_, record)) = store.load(&id)? else {
                continue;
            };
            restored.matches += 1;
            restored.moves += record.moves.len();
            match game::Replay::new(record) {
                Ok(_) => {}
                Err(game::ReplayError::Physics(_)) => restored.other_physics += 1,
                Err(source) => return Err(BackupError::Replay { id, source }),
            }
        }
        after = Some(last);
    }
}

/// Opens `path` as a backup of the SQLite store, once it proved to be one.
fn check_sqlite_backup(path: &Path) -> Result<Connection, BackupError> {
    let not_one = |why: String| BackupError::NotABackup {
        path: path.to_path_buf(),
        why,
    };
    let conn = Connection::open_with_flags(
        path,
        OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    )?;
    let integrity: String = conn
        .query_row("PRAGMA integrity_check", [], |r| r.get(0))
        .map_err(|e| not_one(e.to_string()))?;
    if integrity != "ok" {
        return Err(not_one(format!("integrity check: {integrity}")));
    }
    let tables: i64 = conn.query_row(
        "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name IN ('matches', 'moves')",
        [],
        |r| r.get(0),
    )?;
    if tables != 2 {
        return Err(not_one("it has no matches and moves tables".into()));
    }
    Ok(conn)
}

/// SQLite's consistent copy of `conn`'s database into the new file `to`.
fn vacuum_into(conn: &Connection, to: &Path) -> Result<(), BackupError> {
    conn.execute("VACUUM INTO ?1", [utf8(to)?])?;
    Ok(())
}

/// Runs a PostgreSQL client tool with `args`.
fn tool(name: &'static str, args: &[&str]) -> Result<(), BackupError> {
    let out = std::process::Command::new(name)
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(|source| match source.kind() {
            std::io::ErrorKind::NotFound => BackupError::NoTool(name),
            _ => BackupError::Spawn { tool: name, source },
        })?;
    if out.status.success() {
        Ok(())
    } else {
        Err(BackupError::ToolFailed {
            tool: name,
            status: out.status,
            stderr: String::from_utf8_lossy(&out.stderr).trim().to_string(),
        })
    }
}

fn utf8(path: &Path) -> Result<&str, BackupError> {
    path.to_str()
        .ok_or_else(|| BackupError::Path(path.to_path_buf()))
}

/// Where a file is written before it is complete: beside `to`.
fn partial(to: &Path) -> PathBuf {
    let mut name = to.as_os_str().to_owned();
    name.push(".partial");
    PathBuf::from(name)
}

/// Removes what an interrupted run of ours left at `partial`.
fn remove_leftover(partial: &Path) -> Result<(), BackupError> {
    match std::fs::remove_file(partial) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(BackupError::Io {
            what: "removing the leftover",
            path: partial.to_path_buf(),
            source: e,
        }),
        _ => Ok(()),
    }
}

/// Syncs the complete file `partial` to disk and links it in as `to`,
/// never over an existing file; its size.
fn put_in_place(partial: &Path, to: &Path) -> Result<u64, BackupError> {
    let io = |what, path: &Path| {
        let path = path.to_path_buf();
        move |source| BackupError::Io { what, path, source }
    };
    let file = std::fs::File::open(partial).map_err(io("opening", partial))?;
    file.sync_all().map_err(io("syncing", partial))?;
    let bytes = file.metadata().map_err(io("reading", partial))?.len();
    std::fs::hard_link(partial, to).map_err(|e| match e.kind() {
        std::io::ErrorKind::AlreadyExists => BackupError::Exists(to.to_path_buf()),
        _ => io("linking into place", to)(e),
    })?;
    std::fs::remove_file(partial).map_err(io("removing", partial))?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn config(dir: &Path) -> Config {
        Config::parse_from(["server", "--data-dir", dir.to_str().unwrap()])
    }

    #[test]
    fn a_backup_never_overwrites_and_needs_a_store() {
        let dir = tempfile::tempdir().unwrap();
        let to = dir.path().join("b.sqlite3");
        let empty = config(&dir.path().join("none"));
        assert!(matches!(backup(&empty, &to), Err(BackupError::NoStore(_))));
        std::fs::write(&to, "x").unwrap();
        assert!(matches!(backup(&empty, &to), Err(BackupError::Exists(_))));
        assert_eq!(std::fs::read(&to).unwrap(), b"x");
    }

    #[test]
    fn a_restore_refuses_a_non_backup_and_a_store_that_is_not_empty() {
        let dir = tempfile::tempdir().unwrap();
        let junk = dir.path().join("junk");
        std::fs::write(&junk, "not a database at all, just some text").unwrap();
        let fresh = config(&dir.path().join("fresh"));
        assert!(matches!(
            restore(&fresh, &junk),
            Err(BackupError::NotABackup { .. })
        ));
        assert!(!dir.path().join("fresh").join(sqlite::FILE_NAME).exists());
        // A real backup, into a folder that already holds a store.
        let used = dir.path().join("used");
        drop(SqliteStore::open(&used, crate::config::SyncMode::Full).unwrap());
        let to = dir.path().join("b.sqlite3");
        backup(&config(&used), &to).unwrap();
        assert!(matches!(
            restore(&config(&used), &to),
            Err(BackupError::NotEmpty(_))
        ));
        // Into a fresh folder it goes, and the empty store replays.
        assert_eq!(restore(&fresh, &to).unwrap(), Restored::default());
    }

    #[test]
    fn without_pg_dump_on_path_a_postgres_backup_says_so() {
        assert!(matches!(
            tool("pg_dump-not-installed-here", &[]),
            Err(BackupError::NoTool(_))
        ));
        let e = BackupError::NoTool("pg_dump").to_string();
        assert!(e.starts_with("pg_dump is not on PATH"), "{e}");
    }
}
