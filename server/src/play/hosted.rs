//! Hosted bots in play: the server-wide budget their decisions run under
//! and the compiled modules of the matches they play.
//!
//! A hosted seat's decision runs on a blocking thread, never on the
//! runtime's threads, and only while it holds one of the budget's permits
//! (`--hosted-workers`): at most that many decisions run at once, however
//! many hosted matches are being played, so the cores left serve people's
//! matches. A decision waiting for a permit waits in a queue; its match
//! waits with it (a bot seat has no turn clock), the other matches do not.
//!
//! A match's module is compiled once, when the match starts, and kept by
//! its room until the room goes: an author activating another version
//! changes the next match, never the one being played. A match resumed
//! after a restart compiles its seat's version again from the store, which
//! keeps it until the match is finished (deleting it is refused before).

use crate::store::{Store, StoreError};
use bots::hosted_bot::HostedBot;
use game::decide::DecideRequest;
use game::session::BotDecision;
use game::{MatchView, NoiseKey, Side};
use hosted::{BotModule, LoadError};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, Weak};
use tokio::sync::Semaphore;

/// Why a hosted seat's module cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum HostedError {
    #[error("reading the module failed: {0}")]
    Store(#[from] StoreError),
    #[error("account {account} has no module version {hash}")]
    Missing { account: String, hash: String },
    #[error("the stored module does not load: {0}")]
    Load(#[from] LoadError),
    #[error("the stored module's SHA-256 is {found}, not {hash}")]
    WrongHash { hash: String, found: String },
}

/// The hosted bots' share of the server (cheap to clone).
#[derive(Clone)]
pub struct HostedPool {
    inner: Arc<Inner>,
}

struct Inner {
    /// One permit per decision allowed to run at once.
    permits: Arc<Semaphore>,
    workers: usize,
    /// The modules compiled for matches in play, by version (held by
    /// their rooms; an entry whose module is dropped is reloaded).
    modules: Mutex<HashMap<String, Weak<BotModule>>>,
}

impl HostedPool {
    /// A pool letting `workers` decisions run at once (at least one).
    pub fn new(workers: usize) -> HostedPool {
        let workers = workers.max(1);
        HostedPool {
            inner: Arc::new(Inner {
                permits: Arc::new(Semaphore::new(workers)),
                workers,
                modules: Mutex::new(HashMap::new()),
            }),
        }
    }

    /// How many decisions may run at once.
    pub fn workers(&self) -> usize {
        self.inner.workers
    }

    fn modules(&self) -> std::sync::MutexGuard<'_, HashMap<String, Weak<BotModule>>> {
        self.inner
            .modules
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Version `hash`'s module if a match in play holds it compiled.
    pub fn cached(&self, hash: &str) -> Option<Arc<BotModule>> {
        self.modules().get(hash).and_then(Weak::upgrade)
    }

    fn keep(&self, module: &Arc<BotModule>) {
        let mut modules = self.modules();
        modules.retain(|_, m| m.strong_count() > 0);
        modules.insert(module.hash_hex(), Arc::downgrade(module));
    }

    /// `account`'s active module, compiled (blocks: call it from a
    /// blocking thread); `None` if it has none.
    pub fn active(
        &self,
        store: &dyn Store,
        account: &str,
    ) -> Result<Option<Arc<BotModule>>, HostedError> {
        let Some((version, bytes)) = store.active_module(account)? else {
            return Ok(None);
        };
        if let Some(m) = self.cached(&version.hash) {
            return Ok(Some(m));
        }
        let module = Arc::new(BotModule::load(
            &bytes,
            &crate::accounts::modules::limits(),
        )?);
        if module.hash_hex() != version.hash {
            return Err(HostedError::WrongHash {
                hash: version.hash,
                found: module.hash_hex(),
            });
        }
        self.keep(&module);
        Ok(Some(module))
    }

    /// `account`'s version `hash`, compiled (blocks).
    pub fn version(
        &self,
        store: &dyn Store,
        account: &str,
        hash: &str,
    ) -> Result<Arc<BotModule>, HostedError> {
        if let Some(m) = self.cached(hash) {
            return Ok(m);
        }
        let bytes = store
            .module_bytes(account, hash)?
            .ok_or_else(|| HostedError::Missing {
                account: account.to_string(),
                hash: hash.to_string(),
            })?;
        let module = Arc::new(BotModule::load(
            &bytes,
            &crate::accounts::modules::limits(),
        )?);
        if module.hash_hex() != hash {
            return Err(HostedError::WrongHash {
                hash: hash.to_string(),
                found: module.hash_hex(),
            });
        }
        self.keep(&module);
        Ok(module)
    }

    /// Waits for a permit, then runs `f` on a blocking thread holding it.
    pub async fn run<T: Send + 'static>(
        &self,
        f: impl FnOnce() -> T + Send + 'static,
    ) -> Option<T> {
        let permit = self.inner.permits.clone().acquire_owned().await.ok()?;
        tokio::task::spawn_blocking(move || {
            let _permit = permit;
            f()
        })
        .await
        .ok()
    }
}

/// The module playing one seat of a match, and its account.
pub struct HostedSeat {
    pub account: String,
    /// The version (SHA-256, hex).
    pub hash: String,
    /// The bot, once its module is compiled (out of its slot while it
    /// thinks).
    pub bot: Option<HostedBot>,
    pub thinking: bool,
}

/// One decision of a hosted seat: compiles its module first if needed
/// (a match resumed after a restart). Any failure is no answer.
pub fn decide(
    pool: &HostedPool,
    store: &dyn Store,
    seat: (&str, &str),
    noise: &NoiseKey,
    bot: Option<HostedBot>,
    side: Side,
    view: MatchView,
) -> (BotDecision, Option<HostedBot>, Option<String>) {
    let (account, hash) = seat;
    let bot = match bot {
        Some(b) => b,
        None => {
            let NoiseKey::ChaCha20(secret) = noise else {
                return (
                    BotDecision::NoAnswer,
                    None,
                    Some("a match keyed by a plain seed has no hosted bots".into()),
                );
            };
            match pool.version(store, account, hash) {
                Ok(m) => HostedBot::new(m, *secret),
                Err(e) => return (BotDecision::NoAnswer, None, Some(e.to_string())),
            }
        }
    };
    let mut bot = bot;
    let request = DecideRequest { me: side, view };
    match bot.try_decide(&request) {
        Ok(d) => (to_session(d), Some(bot), None),
        Err(e) => (BotDecision::NoAnswer, Some(bot), Some(e.to_string())),
    }
}

fn to_session(d: bots::Decision) -> BotDecision {
    match d {
        bots::Decision::Shot(shot) => BotDecision::Shot(shot),
        bots::Decision::Pie { swap } => BotDecision::Pie { swap },
        bots::Decision::Resign => BotDecision::Resign,
        bots::Decision::NoAnswer => BotDecision::NoAnswer,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::time::Duration;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn no_more_decisions_run_at_once_than_the_pool_has_workers() {
        let pool = HostedPool::new(2);
        let running = Arc::new(AtomicUsize::new(0));
        let most = Arc::new(AtomicUsize::new(0));
        let mut tasks = Vec::new();
        for _ in 0..8 {
            let (pool, running, most) = (pool.clone(), running.clone(), most.clone());
            tasks.push(tokio::spawn(async move {
                pool.run(move || {
                    let now = running.fetch_add(1, Ordering::SeqCst) + 1;
                    most.fetch_max(now, Ordering::SeqCst);
                    std::thread::sleep(Duration::from_millis(20));
                    running.fetch_sub(1, Ordering::SeqCst);
                })
                .await
            }));
        }
        for t in tasks {
            assert_eq!(t.await.unwrap(), Some(()));
        }
        assert_eq!(most.load(Ordering::SeqCst), 2);
    }
}
