//! The hub: the registry of match rooms held in memory. It creates matches
//! (store first, then a room), finds a room by id — loading a match that is
//! not in memory from the store and replaying its record through
//! [`game::Replay`] — resumes every unfinished match on start, routes joins
//! and connections to rooms, enforces the limit on matches in memory, counts
//! WebSocket connections per client address, and shuts every room down
//! cleanly, each finishing the command in hand.
//!
//! The limit on matches holds under concurrent requests: a creation (or a
//! load from the store) reserves its slot under the registry's lock before
//! it writes anything, the room takes the slot over under the same lock,
//! and a creation that fails gives its slot back ([`Slot`]).

use crate::config::Limits;
use crate::limit_key::LimitKey;
use crate::metrics::Metrics;
use crate::play::cluster::{Cluster, Lease, LocalRooms};
use crate::play::hosted::HostedPool;
use crate::play::room::{Claim, Command, Connected, FinishedMatch, MatchListener, Room, RoomHost};
use crate::refusal::Refusal;
#[cfg(test)]
use crate::store::SqliteStore;
use crate::store::{HostedCreated, Status, Store, StoreError, StoredMatch, StoredSeat};
use crate::token::{self, SeatToken, TokenHash};
use bots::Level;
use game::protocol::ErrorCode;
use game::session::{check_turn_seconds, SeatSpec};
use game::{Config, Game, NoiseKey, Replay, ReplayError, Seat};
use prometheus_client::metrics::gauge::ConstGauge;
use prometheus_client::registry::Registry;
use std::collections::HashMap;
use std::future::Future;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::runtime::Handle;
use tokio::sync::{mpsc, oneshot};
use tracing::{error, info, warn};

/// Whether a node of a cluster may relay to a match another node plays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Reach {
    /// Only a match this node plays (taking its lease if it is free).
    Own,
    /// Or a proxy to the node that plays it.
    OwnOrRelay,
}

/// Commands queued for one room before senders wait.
const ROOM_QUEUE: usize = 1024;

/// A room's mailbox.
#[derive(Clone, Debug)]
pub struct RoomHandle {
    pub tx: mpsc::Sender<Command>,
    generation: u64,
    /// A room of this node's (`false`: a proxy relaying to the node that
    /// plays the match, [`crate::play::cluster`]).
    owned: bool,
}

/// Who plays the second seat of a new match.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Opponent {
    Person,
    Bot(Level),
}

/// A request to create a match.
#[derive(Clone, Debug)]
pub struct NewMatch {
    pub name: String,
    /// The creator's account, if signed in (`name` is then the account's).
    pub account: Option<String>,
    pub opponent: Opponent,
    pub config: Config,
    pub turn_seconds: Option<u64>,
    /// Whether the result moves the ratings (both seats need accounts: a
    /// built-in level plays as its computer account).
    pub rated: bool,
    /// A public seed for the match's noise (casual matches only: see
    /// [`Stakes::Seeded`]).
    pub seed: Option<u64>,
}

/// What a new match is played for, and so where its noise comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stakes {
    /// Casual, with a secret nobody knows until the end.
    Casual,
    /// Casual, with the secret `NoiseSecret::from_seed(seed)`: anyone who
    /// knows the seed can draw its noise, the way `bots match --seed`
    /// does locally, and the computer seats are seeded from it too.
    Seeded(u64),
    /// Rated: a secret, and the result moves both accounts' ratings.
    Rated,
}

impl Stakes {
    /// Casual or rated, with a secret.
    pub fn secret(rated: bool) -> Stakes {
        if rated {
            Stakes::Rated
        } else {
            Stakes::Casual
        }
    }

    pub fn rated(self) -> bool {
        self == Stakes::Rated
    }

    pub fn seed(self) -> Option<u64> {
        match self {
            Stakes::Seeded(seed) => Some(seed),
            Stakes::Casual | Stakes::Rated => None,
        }
    }
}

/// Who plays one seat of a match being started.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct NewSeat {
    pub name: Option<String>,
    /// The hash of the seat token (`None`: empty until someone joins, or a
    /// built-in bot's).
    pub token: Option<TokenHash>,
    /// The built-in level playing the seat.
    pub bot: Option<Level>,
    /// The account playing the seat.
    pub account: Option<String>,
    /// The version (SHA-256, hex) of the account's hosted module that the
    /// server plays the seat with.
    pub module: Option<String>,
}

impl NewSeat {
    /// A built-in level's seat: named after it, and in a rated match
    /// played as its computer account.
    pub fn computer(level: Level, name: String, rated: bool) -> NewSeat {
        NewSeat {
            name: Some(name),
            token: None,
            bot: Some(level),
            account: rated.then(|| game::name::computer_account(level)),
            module: None,
        }
    }

    /// A hosted bot's seat: its account, played with its module `hash`
    /// (which the caller holds compiled in the hub's [`HostedPool`] until
    /// the match has started).
    pub fn hosted(account: String, hash: String) -> NewSeat {
        NewSeat {
            name: Some(account.clone()),
            token: None,
            bot: None,
            account: Some(account),
            module: Some(hash),
        }
    }

    /// Whether the server plays the seat (a computer level or a module).
    fn played_by_server(&self) -> bool {
        self.bot.is_some() || self.module.is_some()
    }
}

/// A seat handed out.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SeatGrant {
    pub match_id: String,
    pub seat: Seat,
    /// The seat token, handed to its owner once and kept only as a hash.
    pub token: SeatToken,
}

struct Inner {
    store: Arc<dyn Store>,
    metrics: Arc<Metrics>,
    limits: Limits,
    rt: Handle,
    rooms: Mutex<HashMap<String, RoomHandle>>,
    /// Slots reserved for matches being created or loaded; raised only
    /// under the lock of `rooms`, so `rooms + reserved` never passes the
    /// limit.
    reserved: AtomicUsize,
    /// Open WebSocket connections per client address (an IPv6 client's /64).
    addresses: Mutex<HashMap<LimitKey, usize>>,
    /// Serialises loads so that one match never gets two rooms.
    load_lock: tokio::sync::Mutex<()>,
    next_conn: AtomicU64,
    next_generation: AtomicU64,
    closing: AtomicBool,
    /// Told when a match ends (the account event streams).
    listener: std::sync::OnceLock<Arc<dyn MatchListener>>,
    /// The cluster this node belongs to, if any.
    cluster: std::sync::OnceLock<Arc<Cluster>>,
    /// The hosted bots' budget and modules.
    hosted: HostedPool,
}

/// The registry of rooms (cheap to clone).
#[derive(Clone)]
pub struct Hub {
    inner: Arc<Inner>,
}

fn random<T>(r: Result<T, token::RandomError>) -> Result<T, Refusal> {
    r.map_err(|e| {
        error!(error = %e, "no randomness");
        Refusal::internal()
    })
}

fn store_failed(e: StoreError) -> Refusal {
    error!(error = %e, "store failure");
    Refusal::internal()
}

impl Hub {
    /// A hub whose rooms run on `rt`.
    pub fn new(store: Arc<dyn Store>, metrics: Arc<Metrics>, limits: Limits, rt: Handle) -> Hub {
        let hosted = HostedPool::new(limits.hosted_workers);
        Hub {
            inner: Arc::new(Inner {
                store,
                metrics,
                limits,
                rt,
                rooms: Mutex::new(HashMap::new()),
                reserved: AtomicUsize::new(0),
                addresses: Mutex::new(HashMap::new()),
                load_lock: tokio::sync::Mutex::new(()),
                next_conn: AtomicU64::new(1),
                next_generation: AtomicU64::new(1),
                closing: AtomicBool::new(false),
                listener: std::sync::OnceLock::new(),
                cluster: std::sync::OnceLock::new(),
                hosted,
            }),
        }
    }

    /// The hosted bots' budget and modules.
    pub fn hosted(&self) -> &HostedPool {
        &self.inner.hosted
    }

    pub fn store(&self) -> &Arc<dyn Store> {
        &self.inner.store
    }

    /// Makes this hub a node of `cluster` (once, before it serves): it
    /// plays only the matches whose lease it holds and relays the others.
    pub fn set_cluster(&self, cluster: Arc<Cluster>) {
        let _ = self.inner.cluster.set(cluster);
    }

    fn cluster(&self) -> Option<&Arc<Cluster>> {
        self.inner.cluster.get()
    }

    /// Sets who hears of matches ending (once; later calls are ignored).
    pub fn set_listener(&self, listener: Arc<dyn MatchListener>) {
        let _ = self.inner.listener.set(listener);
    }

    /// Stores and starts a match whose seats are both decided now (a
    /// challenge accepted, two seekers or two ladder bots paired): a seat
    /// with an account but no bot gets a fresh token, returned for its
    /// player (and only there; the store keeps its hash). A ladder match
    /// (`ladder`) claims its hosted bots in the store: one that plays a
    /// ladder match not finished yet, on any node, is refused with
    /// `server-busy`.
    pub async fn create_between(
        &self,
        mut seats: [NewSeat; 2],
        config: Config,
        turn_seconds: Option<u64>,
        rated: bool,
        ladder: bool,
    ) -> Result<(String, [Option<SeatToken>; 2]), Refusal> {
        let begun = if ladder { Begun::Ladder } else { Begun::Fresh };
        let slot = self.reserve()?;
        let turn_seconds = self.turn_seconds(turn_seconds)?;
        let mut tokens = [None, None];
        for (seat, token) in seats.iter_mut().zip(&mut tokens) {
            if !seat.played_by_server() {
                let t = random(token::seat_token())?;
                seat.token = Some(t.hash());
                *token = Some(t);
            }
        }
        let id = self
            .start(
                slot,
                begun,
                config,
                turn_seconds,
                seats,
                Stakes::secret(rated),
            )
            .await?;
        Ok((id, tokens))
    }
    pub fn metrics(&self) -> &Arc<Metrics> {
        &self.inner.metrics
    }
    pub fn limits(&self) -> &Limits {
        &self.inner.limits
    }
    pub fn next_conn_id(&self) -> u64 {
        self.inner.next_conn.fetch_add(1, Ordering::Relaxed)
    }

    fn rooms(&self) -> std::sync::MutexGuard<'_, HashMap<String, RoomHandle>> {
        // A panic while holding this lock cannot leave the map half-changed.
        self.inner
            .rooms
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Matches held in memory.
    pub fn rooms_in_memory(&self) -> usize {
        self.rooms().len()
    }

    /// Forgets a room that has stopped (unless a newer one took its id).
    pub fn remove(&self, id: &str, generation: u64) {
        let mut rooms = self.rooms();
        if rooms.get(id).is_none_or(|h| h.generation != generation) {
            return;
        }
        let removed = rooms.remove(id);
        drop(rooms);
        // A node of a cluster gives the lease up: another node may play
        // the match now (after a shutdown), or nobody needs to (it ended).
        if let (Some(cluster), Some(true)) = (self.cluster(), removed.map(|h| h.owned)) {
            let (cluster, id) = (cluster.clone(), id.to_string());
            if !self.inner.closing.load(Ordering::Relaxed) {
                self.inner.rt.spawn_blocking(move || {
                    if let Err(e) = cluster.release(&id) {
                        warn!(match_id = %id, error = %e, "giving a lease up failed; it expires");
                    }
                });
            }
        }
    }

    /// On a node of a cluster, registers its share in `registry`:
    /// matches it plays and relays, and the connections it relays and
    /// serves, as they are now.
    pub fn register_cluster_metrics(&self, registry: &mut Registry) {
        let Some(cluster) = self.cluster() else {
            return;
        };
        let (owned, relayed) = {
            let rooms = self.rooms();
            let owned = rooms.values().filter(|h| h.owned).count();
            (owned, rooms.len() - owned)
        };
        let (links, served) = cluster.connection_counts();
        let routed = usize::try_from(cluster.routed()).unwrap_or(usize::MAX);
        for (name, help, value) in [
            (
                "chapaev_cluster_matches_owned",
                "Matches this node plays (holds the lease of)",
                owned,
            ),
            (
                "chapaev_cluster_matches_relayed",
                "Matches played on other nodes that this node relays",
                relayed,
            ),
            (
                "chapaev_cluster_connections_relayed",
                "This node's connections to matches played elsewhere",
                links,
            ),
            (
                "chapaev_cluster_connections_served",
                "Connections of other nodes' clients to matches played here",
                served,
            ),
            (
                "chapaev_cluster_connections_routed",
                "Connections this node sent on to the node playing their match (since it started)",
                routed,
            ),
        ] {
            let value = i64::try_from(value).unwrap_or(i64::MAX);
            registry.register(name, help, ConstGauge::new(value));
        }
    }

    /// The ids of the matches this node plays (not those it relays).
    pub fn owned_matches(&self) -> Vec<String> {
        self.rooms()
            .iter()
            .filter(|(_, h)| h.owned)
            .map(|(id, _)| id.clone())
            .collect()
    }

    /// Stops the room of `id` (its lease is lost): it finishes the command
    /// in hand, and its connections end (their clients reconnect).
    pub async fn stop_room(&self, id: &str) {
        let handle = self.rooms().get(id).cloned();
        if let Some(h) = handle {
            let (done, _) = oneshot::channel();
            let _ = h.tx.send(Command::Shutdown { done }).await;
            self.remove(id, h.generation);
        }
    }

    /// Reserves room for one more match in memory (refused with
    /// `server-busy` at the limit or while shutting down); the slot is
    /// given back when dropped unless a room took it over.
    fn reserve(&self) -> Result<Slot, Refusal> {
        if self.inner.closing.load(Ordering::Relaxed) {
            return Err(Refusal::new(
                ErrorCode::ServerBusy,
                "the server is shutting down",
            ));
        }
        let rooms = self.rooms();
        let reserved = self.inner.reserved.load(Ordering::SeqCst);
        if rooms.len() + reserved >= self.inner.limits.max_matches {
            return Err(Refusal::new(
                ErrorCode::ServerBusy,
                "the server holds as many matches as it can; try later",
            ));
        }
        self.inner.reserved.fetch_add(1, Ordering::SeqCst);
        drop(rooms);
        Ok(Slot {
            hub: self.clone(),
            held: true,
        })
    }

    /// A slot even past the limit (new matches are refused until the
    /// count is back under it).
    fn reserve_past_limit(&self) -> Slot {
        self.inner.reserved.fetch_add(1, Ordering::SeqCst);
        Slot {
            hub: self.clone(),
            held: true,
        }
    }

    /// Counts one more WebSocket connection from `addr`; `None` when the
    /// address already holds as many as allowed. The count drops with the
    /// guard.
    pub fn admit_address(&self, addr: LimitKey) -> Option<AddressGuard> {
        let mut addresses = self
            .inner
            .addresses
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let n = addresses.entry(addr).or_insert(0);
        if *n >= self.inner.limits.max_connections_per_address {
            return None;
        }
        *n += 1;
        Some(AddressGuard {
            hub: self.clone(),
            addr,
        })
    }

    /// Spawns the room of a stored match replayed into `game`.
    /// The room takes over `slot` (under the registry's lock, so the count
    /// of matches never dips or doubles meanwhile).
    fn spawn(&self, stored: &StoredMatch, game: Game, mut slot: Slot) -> RoomHandle {
        let generation = self.inner.next_generation.fetch_add(1, Ordering::Relaxed);
        let (tx, rx) = mpsc::channel(ROOM_QUEUE);
        let room = Room::new(stored, game, self.clone(), generation);
        let handle = RoomHandle {
            tx,
            generation,
            owned: true,
        };
        {
            let mut rooms = self.rooms();
            rooms.insert(stored.id.clone(), handle.clone());
            slot.held = false;
            self.inner.reserved.fetch_sub(1, Ordering::SeqCst);
        }
        self.inner.rt.spawn(room.run(rx));
        handle
    }

    /// A new match's turn clock: the one asked for, checked, or the
    /// server's.
    fn turn_seconds(&self, asked: Option<u64>) -> Result<u64, Refusal> {
        check_turn_seconds(asked.unwrap_or(self.inner.limits.turn.as_secs()))
    }

    /// Stores and starts a new match; the creator gets the first seat.
    pub async fn create(&self, req: NewMatch) -> Result<SeatGrant, Refusal> {
        let slot = self.reserve()?;
        let turn_seconds = self.turn_seconds(req.turn_seconds)?;
        let token = random(token::seat_token())?;
        let stakes = match (req.rated, req.seed) {
            (true, Some(_)) => {
                return Err(Refusal::new(
                    ErrorCode::BadMessage,
                    "a rated match takes no seed: its noise stays secret to both players",
                ))
            }
            (rated, None) => Stakes::secret(rated),
            (false, Some(seed)) => Stakes::Seeded(seed),
        };
        if req.rated && req.account.is_none() {
            return Err(Refusal::new(
                ErrorCode::BadKey,
                "a rated match needs an account: send its key as 'Authorization: Bearer KEY'",
            ));
        }
        let second = match req.opponent {
            Opponent::Person => NewSeat::default(),
            Opponent::Bot(level) => NewSeat::computer(level, format!("bot ({level})"), req.rated),
        };
        let seats = [
            NewSeat {
                name: Some(req.name),
                token: Some(token.hash()),
                bot: None,
                account: req.account,
                module: None,
            },
            second,
        ];
        let id = self
            .start(slot, Begun::Fresh, req.config, turn_seconds, seats, stakes)
            .await?;
        Ok(SeatGrant {
            match_id: id,
            seat: Seat::First,
            token,
        })
    }

    /// Stores and starts an exhibition: two built-in levels play each
    /// other, and anyone may watch (no seat has a token).
    pub async fn create_exhibition(
        &self,
        first: Level,
        second: Level,
        config: Config,
        turn_seconds: Option<u64>,
    ) -> Result<String, Refusal> {
        let slot = self.reserve()?;
        let turn_seconds = self.turn_seconds(turn_seconds)?;
        let seat = |l: Level| NewSeat::computer(l, format!("bot ({l})"), false);
        self.start(
            slot,
            Begun::Fresh,
            config,
            turn_seconds,
            [seat(first), seat(second)],
            Stakes::Casual,
        )
        .await
    }

    /// Starts the rematch of `of`: the same configuration, clock and
    /// rating, the players' seats (and so their colours) exchanged; a bot
    /// keeps the second seat. The players keep their tokens and accounts.
    pub async fn create_rematch(
        &self,
        of: &str,
        config: Config,
        turn: Duration,
        seats: [NewSeat; 2],
        rated: bool,
    ) -> Result<String, Refusal> {
        let slot = self.reserve()?;
        let [first, second] = seats;
        let seats = if second.bot.is_some() {
            [first, second]
        } else {
            [second, first]
        };
        self.start(
            slot,
            Begun::Rematch(of.to_string()),
            config,
            turn.as_secs(),
            seats,
            // A seeded match's rematch gets a secret of its own.
            Stakes::secret(rated),
        )
        .await
    }

    async fn start(
        &self,
        slot: Slot,
        begun: Begun,
        config: Config,
        turn_seconds: u64,
        seats: [NewSeat; 2],
        stakes: Stakes,
    ) -> Result<String, Refusal> {
        let noise = match stakes.seed() {
            Some(seed) => NoiseKey::from(seed),
            None => NoiseKey::ChaCha20(random(token::noise_secret())?),
        };
        let game = Game::new(config.clone(), noise)
            .map_err(|e| Refusal::new(ErrorCode::BadConfig, e.to_string()))?;
        let id = random(token::match_id())?;
        let bot = StoredMatch::bots_column([seats[0].bot, seats[1].bot]);
        let both = seats
            .iter()
            .all(|s| s.token.is_some() || s.played_by_server());
        let stored = StoredMatch {
            id: id.clone(),
            created_at: 0,
            config,
            noise,
            physics: game.physics().number(),
            status: if both { Status::Live } else { Status::Open },
            bot,
            turn_seconds,
            seats: seats.map(|s| StoredSeat {
                name: s.name,
                token: s.token,
                account: s.account,
                module: s.module,
            }),
            rematch_of: match &begun {
                Begun::Rematch(of) => Some(of.clone()),
                Begun::Fresh | Begun::Ladder => None,
            },
            rated: stakes.rated(),
            seed: stakes.seed(),
        };
        let store = self.inner.store.clone();
        let row = stored.clone();
        let cluster = self.cluster().cloned();
        if let Some(c) = &cluster {
            c.ensure_reachable()?;
        }
        let hosted = row.seats.iter().any(|s| s.module.is_some());
        let ladder = matches!(begun, Begun::Ladder);
        tokio::task::spawn_blocking(move || {
            if hosted {
                match store.create_hosted(&row, ladder)? {
                    HostedCreated::Created => {}
                    HostedCreated::Busy(bot) => return Ok(Err(hosted_busy(&bot))),
                    HostedCreated::NoVersion(bot) => {
                        return Ok(Err(Refusal::new(
                            ErrorCode::NoSuchVersion,
                            format!("{bot}'s module version was deleted"),
                        )))
                    }
                }
            } else {
                store.create(&row)?;
            }
            // A node of a cluster holds the new match's lease from the start.
            match cluster.map(|c| c.acquire(&row.id)).transpose()? {
                None | Some(Lease::Ours) => Ok(Ok(())),
                Some(Lease::Theirs(node)) => Err(StoreError::Corrupt(format!(
                    "a new match's lease is held by node {node}"
                ))),
            }
        })
        .await
        .map_err(|e| {
            error!(error = %e, "store task failed");
            Refusal::internal()
        })?
        .map_err(store_failed)??;
        self.spawn(&stored, game, slot);
        info!(match_id = %id, bot = ?stored.bot, "match created");
        Ok(id)
    }

    /// The room of match `id`, loading it from the store if needed;
    /// `within_limit: false` loads past the limit on
    /// matches in memory (a live match resuming after a restart); with
    /// [`Reach::Own`], a node of a cluster refuses a match another node
    /// plays instead of relaying to it.
    async fn room_within(
        &self,
        id: &str,
        within_limit: bool,
        reach: Reach,
    ) -> Result<RoomHandle, Refusal> {
        let wanted = |h: &RoomHandle| h.owned || reach == Reach::OwnOrRelay;
        if let Some(h) = self.rooms().get(id).filter(|h| wanted(h)) {
            return Ok(h.clone());
        }
        if !token::is_match_id(id) {
            return Err(no_such_match(id));
        }
        let _loading = self.inner.load_lock.lock().await;
        let present = self.rooms().get(id).cloned();
        if let Some(h) = present.as_ref().filter(|h| wanted(h)) {
            return Ok(h.clone());
        }
        if let Some(cluster) = self.cluster().cloned() {
            // Cut off from the other nodes, this node can neither play nor
            // relay: its client goes to another node.
            cluster.ensure_reachable()?;
            let key = id.to_string();
            let lease = tokio::task::spawn_blocking(move || cluster.acquire(&key))
                .await
                .map_err(|e| {
                    error!(error = %e, "lease task failed");
                    Refusal::internal()
                })?
                .map_err(|e| store_failed(e.into()))?;
            match lease {
                Lease::Ours => {}
                Lease::Theirs(node) if node.is_empty() => return Err(no_such_match(id)),
                Lease::Theirs(node) => {
                    // A proxy already here stays: its clients reach the
                    // node that plays the match.
                    return match reach {
                        Reach::Own => Err(Refusal::new(
                            ErrorCode::ServerBusy,
                            format!("match {id} is played on node {node}"),
                        )),
                        Reach::OwnOrRelay => Ok(self.spawn_proxy(id, node)),
                    };
                }
            }
        }
        if let Some(h) = present {
            // A proxy, but this node is to play the match (it holds the
            // lease now): the proxy goes.
            self.remove(id, h.generation);
            let (done, _) = oneshot::channel();
            let _ = h.tx.send(Command::Shutdown { done }).await;
        }
        let slot = if within_limit {
            match self.reserve() {
                Ok(slot) => slot,
                Err(full) => {
                    // Too full to play it: the lease just taken goes back.
                    if let Some(cluster) = self.cluster().cloned() {
                        let key = id.to_string();
                        self.inner.rt.spawn_blocking(move || cluster.release(&key));
                    }
                    return Err(full);
                }
            }
        } else {
            self.reserve_past_limit()
        };
        let store = self.inner.store.clone();
        let key = id.to_string();
        let loaded = tokio::task::spawn_blocking(move || -> Result<_, Refusal> {
            let Some((stored, record)) = store.load(&key).map_err(store_failed)? else {
                return Ok(None);
            };
            let replay = Replay::new(record).map_err(|e| match e {
                ReplayError::Physics(e) => {
                    warn!(
                        match_id = %key,
                        physics = e.found,
                        error = %e,
                        "a stored match of a physics version this server cannot play is not \
                         resumed; it stays stored as it is, for a server that can"
                    );
                    Refusal::new(
                        ErrorCode::UnsupportedPhysics,
                        format!("match {key}: {e}; it is kept for a server that can play it"),
                    )
                }
                e => {
                    error!(match_id = %key, error = %e, "a stored match does not replay");
                    Refusal::internal()
                }
            })?;
            Ok(Some((stored, replay.game().clone())))
        })
        .await
        .map_err(|e| {
            error!(error = %e, "load task failed");
            Refusal::internal()
        })??;
        let (stored, game) = loaded.ok_or_else(|| no_such_match(id))?;
        Ok(self.spawn(&stored, game, slot))
    }

    /// Starts a proxy room relaying match `id` to `node`, which plays it.
    fn spawn_proxy(&self, id: &str, node: String) -> RoomHandle {
        let generation = self.inner.next_generation.fetch_add(1, Ordering::Relaxed);
        let (tx, rx) = mpsc::channel(ROOM_QUEUE);
        let handle = RoomHandle {
            tx,
            generation,
            owned: false,
        };
        self.rooms().insert(id.to_string(), handle.clone());
        if let Some(cluster) = self.cluster() {
            let (hub, key) = (self.clone(), id.to_string());
            let done = move || hub.remove(&key, generation);
            cluster.proxy(id.to_string(), node, rx, done, &self.inner.rt);
        }
        handle
    }

    /// Makes sure this node plays match `id` if nobody else does (a node
    /// of a cluster taking over a match whose node stopped): `true` if it
    /// started playing it now.
    pub async fn own(&self, id: &str) -> Result<bool, Refusal> {
        if self.rooms().get(id).is_some_and(|h| h.owned) {
            return Ok(false);
        }
        self.room_within(id, false, Reach::Own).await.map(|_| true)
    }

    /// Asks the room of `id` something, once more if it stopped meanwhile.
    async fn ask<T>(
        &self,
        id: &str,
        reach: Reach,
        make: impl Fn(oneshot::Sender<Result<T, Refusal>>) -> Command,
    ) -> Result<(RoomHandle, T), Refusal> {
        for _ in 0..3 {
            let h = self.room_within(id, true, reach).await?;
            let (tx, rx) = oneshot::channel();
            if h.tx.send(make(tx)).await.is_err() {
                self.remove(id, h.generation);
                continue;
            }
            match rx.await {
                Ok(r) => return r.map(|t| (h, t)),
                Err(_) => self.remove(id, h.generation),
            }
        }
        Err(Refusal::internal())
    }

    /// Takes the empty second seat of `id`.
    pub async fn join(
        &self,
        id: &str,
        name: String,
        account: Option<String>,
    ) -> Result<SeatGrant, Refusal> {
        let token = random(token::seat_token())?;
        let seat = self
            .join_with(id, name, token.hash(), account, Reach::OwnOrRelay)
            .await?;
        Ok(SeatGrant {
            match_id: id.to_string(),
            seat,
            token,
        })
    }

    /// Takes the empty second seat of `id`, which this node plays, for the
    /// holder of the token with this hash (a join relayed from another
    /// node of the cluster).
    pub async fn join_owned(
        &self,
        id: &str,
        name: String,
        token: TokenHash,
        account: Option<String>,
    ) -> Result<Seat, Refusal> {
        self.join_with(id, name, token, account, Reach::Own).await
    }

    async fn join_with(
        &self,
        id: &str,
        name: String,
        token: TokenHash,
        account: Option<String>,
        reach: Reach,
    ) -> Result<Seat, Refusal> {
        let (_, seat) = self
            .ask(id, reach, |reply| Command::Join {
                name: name.clone(),
                token,
                account: account.clone(),
                reply,
            })
            .await?;
        Ok(seat)
    }

    #[cfg(test)]
    /// Admits a connection to `id` (with a seat token, or as a spectator).
    pub async fn connect(
        &self,
        id: &str,
        token: Option<SeatToken>,
    ) -> Result<(RoomHandle, Connected), Refusal> {
        self.connect_as(id, token.map_or(Claim::Watch(String::new()), Claim::Token))
            .await
    }

    /// Admits a connection to `id` with what it claims.
    pub async fn connect_as(
        &self,
        id: &str,
        claim: Claim,
    ) -> Result<(RoomHandle, Connected), Refusal> {
        self.ask(id, Reach::OwnOrRelay, |reply| Command::Connect {
            claim: claim.clone(),
            reply,
        })
        .await
    }

    /// On a node of a cluster, where a client asking this node for match
    /// `id` had better connect: the public URL of the node that plays it
    /// ([`Cluster::route`]). `None` when this node plays the match, takes
    /// it, or does not know where the owner is reached (it then relays,
    /// as it does for a client that does not ask to be routed).
    pub async fn route(&self, id: &str) -> Option<String> {
        let cluster = self.cluster()?.clone();
        if !token::is_match_id(id) || self.rooms().get(id).is_some_and(|h| h.owned) {
            return None;
        }
        let key = id.to_string();
        match tokio::task::spawn_blocking(move || cluster.route(&key)).await {
            Ok(Ok(url)) => url,
            Ok(Err(e)) => {
                warn!(match_id = %id, error = %e, "looking up the node that plays a match failed; relaying");
                None
            }
            Err(e) => {
                error!(error = %e, "route task failed");
                None
            }
        }
    }

    /// On a node of a cluster, the public URLs of its live nodes (read at
    /// most once a second); none elsewhere or when they cannot be read.
    pub async fn cluster_urls(&self) -> Vec<String> {
        let Some(cluster) = self.cluster().cloned() else {
            return Vec::new();
        };
        let read = tokio::task::spawn_blocking(move || cluster.public_urls(Duration::from_secs(1)));
        match read.await {
            Ok(Ok(urls)) => urls,
            Ok(Err(e)) => {
                warn!(error = %e, "reading the cluster's public URLs failed");
                Vec::new()
            }
            Err(e) => {
                error!(error = %e, "public URLs task failed");
                Vec::new()
            }
        }
    }

    /// Admits a connection to `id`, which this node plays (a connection
    /// relayed from another node of the cluster).
    pub async fn connect_owned(
        &self,
        id: &str,
        claim: Claim,
    ) -> Result<(RoomHandle, Connected), Refusal> {
        self.ask(id, Reach::Own, |reply| Command::Connect {
            claim: claim.clone(),
            reply,
        })
        .await
    }

    /// Loads and starts every live match in the store, the most recently
    /// played first, whatever the limit on matches in memory (they were
    /// being played: their players come back for them). Open matches stay
    /// in the store until someone comes for one, or it expires.
    pub async fn resume_all(&self) -> Result<usize, StoreError> {
        let store = self.inner.store.clone();
        let ids = tokio::task::spawn_blocking(move || store.live())
            .await
            .map_err(|e| StoreError::Corrupt(e.to_string()))??;
        let mut resumed = 0;
        let mut unplayable = 0;
        for id in ids {
            match self.room_within(&id, false, Reach::Own).await {
                Ok(_) => resumed += 1,
                // Logged, with its version, where it was found.
                Err(r) if r.code == ErrorCode::UnsupportedPhysics => unplayable += 1,
                // Another node of the cluster plays it.
                Err(r) if self.cluster().is_some() && r.code == ErrorCode::ServerBusy => {}
                Err(r) => warn!(match_id = %id, refusal = %r, "could not resume a match"),
            }
        }
        if unplayable > 0 {
            warn!(
                unplayable,
                "unfinished matches of physics versions this server cannot play were left as stored"
            );
        }
        Ok(resumed)
    }

    /// Deletes the open matches nobody joined that have not been touched
    /// for `after` and are not in memory (a room in memory is still
    /// waited for); how many. Loads wait meanwhile, so a match is never
    /// loaded as it goes.
    pub async fn expire_open(&self, after: Duration) -> Result<usize, StoreError> {
        let _loading = self.inner.load_lock.lock().await;
        let in_memory: std::collections::HashSet<String> = self.rooms().keys().cloned().collect();
        let store = self.inner.store.clone();
        let expired = tokio::task::spawn_blocking(move || {
            store.expire_open(after.as_secs(), &|id: &str| in_memory.contains(id))
        })
        .await
        .map_err(|e| StoreError::Corrupt(e.to_string()))??;
        for id in &expired {
            info!(match_id = %id, "an open match nobody joined expired");
        }
        Ok(expired.len())
    }

    /// Stops every room once it has finished the command in hand (so every
    /// accepted move is stored); refuses new matches from now on.
    pub async fn shutdown(&self, within: Duration) {
        self.inner.closing.store(true, Ordering::Relaxed);
        let handles: Vec<RoomHandle> = self.rooms().values().cloned().collect();
        let mut waits = Vec::new();
        for h in handles {
            let (done, rx) = oneshot::channel();
            if h.tx.send(Command::Shutdown { done }).await.is_ok() {
                waits.push(rx);
            }
        }
        let all = async {
            for w in waits {
                let _ = w.await;
            }
        };
        if tokio::time::timeout(within, all).await.is_err() {
            warn!("some matches did not stop in time");
        }
        // Every accepted move is stored: the other nodes may take the
        // matches over at once instead of after their leases expire.
        if let Some(cluster) = self.cluster().cloned() {
            let released = tokio::task::spawn_blocking(move || cluster.release_all()).await;
            if !matches!(released, Ok(Ok(()))) {
                warn!("giving the leases up failed; they expire");
            }
        }
    }
}

/// The cluster reaches this node's rooms through these, each the
/// inherent method of the same name.
impl LocalRooms for Hub {
    async fn connect_owned(
        &self,
        id: &str,
        claim: Claim,
    ) -> Result<(mpsc::Sender<Command>, Connected), Refusal> {
        let (room, connected) = Hub::connect_owned(self, id, claim).await?;
        Ok((room.tx, connected))
    }

    async fn join_owned(
        &self,
        id: &str,
        name: String,
        token: TokenHash,
        account: Option<String>,
    ) -> Result<Seat, Refusal> {
        Hub::join_owned(self, id, name, token, account).await
    }

    async fn own(&self, id: &str) -> Result<bool, Refusal> {
        Hub::own(self, id).await
    }

    fn owned_matches(&self) -> Vec<String> {
        Hub::owned_matches(self)
    }

    async fn stop_room(&self, id: &str) {
        Hub::stop_room(self, id).await
    }
}

impl RoomHost for Hub {
    fn store(&self) -> &Arc<dyn Store> {
        Hub::store(self)
    }
    fn finished(&self, m: FinishedMatch) {
        if let Some(l) = self.inner.listener.get() {
            l.finished(m);
        }
    }
    fn metrics(&self) -> &Arc<Metrics> {
        Hub::metrics(self)
    }
    fn limits(&self) -> &Limits {
        Hub::limits(self)
    }
    fn next_conn_id(&self) -> u64 {
        Hub::next_conn_id(self)
    }
    fn start_rematch(
        &self,
        of: String,
        config: Config,
        turn: Duration,
        seats: [SeatSpec; 2],
        accounts: [Option<String>; 2],
        rated: bool,
    ) -> impl Future<Output = Result<String, Refusal>> + Send {
        let hub = self.clone();
        let [a, b] = accounts;
        let [s, t] = seats;
        let seat = |s: SeatSpec, account| NewSeat {
            module: None,
            bot: s.bot.as_deref().and_then(Level::parse),
            name: s.name,
            token: s.token,
            account,
        };
        let seats = [seat(s, a), seat(t, b)];
        async move { hub.create_rematch(&of, config, turn, seats, rated).await }
    }
    fn remove(&self, id: &str, generation: u64) {
        Hub::remove(self, id, generation)
    }
    fn hosted(&self) -> Option<&HostedPool> {
        Some(Hub::hosted(self))
    }
}

/// Room reserved for one match in memory; given back when dropped unless
/// the match's room took it over.
struct Slot {
    hub: Hub,
    held: bool,
}

impl Drop for Slot {
    fn drop(&mut self) {
        if self.held {
            self.hub.inner.reserved.fetch_sub(1, Ordering::SeqCst);
        }
    }
}

/// One WebSocket connection counted against its client address.
pub struct AddressGuard {
    hub: Hub,
    addr: LimitKey,
}

impl Drop for AddressGuard {
    fn drop(&mut self) {
        let mut addresses = self
            .hub
            .inner
            .addresses
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(n) = addresses.get_mut(&self.addr) {
            *n -= 1;
            if *n == 0 {
                addresses.remove(&self.addr);
            }
        }
    }
}

/// How a match comes to be, as far as storing it goes.
enum Begun {
    /// Made, challenged or paired (not on the ladder).
    Fresh,
    /// The rematch of this match.
    Rematch(String),
    /// Paired on the ladder: its hosted bots are claimed.
    Ladder,
}

fn hosted_busy(bot: &str) -> Refusal {
    Refusal::new(
        ErrorCode::ServerBusy,
        format!("{bot} plays a ladder match already"),
    )
}

fn no_such_match(id: &str) -> Refusal {
    Refusal::new(
        ErrorCode::NoSuchMatch,
        format!("no match {id:?} (an open match nobody joins expires)"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::play::room::Inbox;
    use game::protocol::{ClientMessage, ServerMessage};
    use game::{PieceId, Side};
    use glam::DVec2;

    fn hub() -> Hub {
        let limits = Limits {
            bot_delay: Duration::ZERO,
            ..Limits::default()
        };
        Hub::new(
            Arc::new(SqliteStore::in_memory().unwrap()),
            Arc::new(Metrics::default()),
            limits,
            Handle::current(),
        )
    }

    async fn next(rx: &mut Inbox) -> ServerMessage {
        let text = tokio::time::timeout(Duration::from_secs(10), rx.recv())
            .await
            .expect("a message in time")
            .expect("the room is open");
        ServerMessage::from_json(&text).unwrap()
    }

    async fn next_of(rx: &mut Inbox, kind: &str) -> ServerMessage {
        loop {
            let m = next(rx).await;
            if m.to_json().contains(&format!("\"type\":\"{kind}\"")) {
                return m;
            }
        }
    }

    fn person(name: &str) -> NewMatch {
        NewMatch {
            name: name.into(),
            account: None,
            opponent: Opponent::Person,
            config: Config::default(),
            turn_seconds: None,
            rated: false,
            seed: None,
        }
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_shot_is_stored_before_it_is_broadcast_and_only_the_seat_token_can_shoot() {
        let hub = hub();
        let a = hub.create(person("Petka")).await.unwrap();
        let b = hub.join(&a.match_id, "Anka".into(), None).await.unwrap();
        assert_eq!(b.seat, Seat::Second);
        assert_ne!(a.token, b.token);
        let (room, mut white) = hub
            .connect(&a.match_id, Some(a.token.clone()))
            .await
            .unwrap();
        assert!(matches!(
            next(&mut white.rx).await,
            ServerMessage::MatchState {
                you: Some(Seat::First),
                ..
            }
        ));
        let (_, mut watcher) = hub.connect(&a.match_id, None).await.unwrap();
        assert!(matches!(
            next(&mut watcher.rx).await,
            ServerMessage::MatchState { you: None, .. }
        ));
        let bad = hub
            .connect(&a.match_id, Some(SeatToken::new("f".repeat(32))))
            .await
            .unwrap_err();
        assert_eq!(bad.code, ErrorCode::BadToken);
        // A spectator cannot shoot.
        let shot = ClientMessage::Shot {
            piece: PieceId::new(Side::White, 4).unwrap(),
            velocity: DVec2::new(0.0, 2.0),
        };
        room.tx
            .send(Command::message(watcher.conn, shot.clone()))
            .await
            .unwrap();
        assert!(matches!(
            next_of(&mut watcher.rx, "error").await,
            ServerMessage::Error {
                code: ErrorCode::NotInMatch,
                ..
            }
        ));
        room.tx
            .send(Command::message(white.conn, shot))
            .await
            .unwrap();
        let played = next_of(&mut watcher.rx, "shot-played").await;
        // By the time anyone hears of it, the store has it.
        let moves = hub.store().moves(&a.match_id).unwrap();
        assert_eq!(moves.len(), 1);
        let ServerMessage::ShotPlayed { outcome, .. } = played else {
            unreachable!()
        };
        assert_eq!(moves[0], game::RecordedMove::Shot(outcome));
        assert_eq!(hub.metrics().shots(), 1);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_match_not_in_memory_is_loaded_from_the_store_with_its_moves() {
        let store = Arc::new(SqliteStore::in_memory().unwrap());
        let mk = |store: Arc<dyn Store>| {
            Hub::new(
                store,
                Arc::new(Metrics::default()),
                Limits::default(),
                Handle::current(),
            )
        };
        let first = mk(store.clone());
        let a = first.create(person("a")).await.unwrap();
        first.join(&a.match_id, "b".into(), None).await.unwrap();
        let (room, mut c) = first
            .connect(&a.match_id, Some(a.token.clone()))
            .await
            .unwrap();
        let msg = ClientMessage::Shot {
            piece: PieceId::new(Side::White, 2).unwrap(),
            velocity: DVec2::new(0.0, 0.5),
        };
        room.tx.send(Command::message(c.conn, msg)).await.unwrap();
        let ServerMessage::MatchState { view: before, .. } = next(&mut c.rx).await else {
            panic!()
        };
        next_of(&mut c.rx, "shot-played").await;
        first.shutdown(Duration::from_secs(5)).await;
        // A second hub on the same store: the match comes back as it was.
        let second = mk(store);
        assert_eq!(second.resume_all().await.unwrap(), 1);
        let (_, mut again) = second.connect(&a.match_id, Some(a.token)).await.unwrap();
        let ServerMessage::MatchState { view, .. } = next(&mut again.rx).await else {
            panic!()
        };
        assert_eq!(view.shots, 1);
        assert_ne!(view, before);
        assert_eq!(
            second.connect("nope", None).await.unwrap_err().code,
            ErrorCode::NoSuchMatch
        );
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_stored_match_of_a_physics_version_this_server_cannot_play_is_not_resumed() {
        let hub = hub();
        let a = hub.create(person("a")).await.unwrap();
        let stored = hub.store().get(&a.match_id).unwrap().unwrap();
        assert_eq!(stored.physics, game::PHYSICS_VERSION);
        let id = "0123456789abcdef";
        assert!(token::is_match_id(id));
        hub.store()
            .create(&StoredMatch {
                id: id.into(),
                physics: game::PHYSICS_VERSION + 1,
                ..stored
            })
            .unwrap();
        // Both live (only live matches resume on start).
        for m in [id, a.match_id.as_str()] {
            hub.store()
                .seat_second(m, "Anka", &TokenHash::of("b"), None)
                .unwrap();
        }
        // A fresh hub on the same store, as after a restart.
        let again = Hub::new(
            hub.store().clone(),
            Arc::new(Metrics::default()),
            Limits::default(),
            Handle::current(),
        );
        assert_eq!(
            again.resume_all().await.unwrap(),
            1,
            "only the playable one"
        );
        let refused = again.connect(id, None).await.unwrap_err();
        assert_eq!(refused.code, ErrorCode::UnsupportedPhysics);
        assert!(
            refused.message.contains("cannot play"),
            "{}",
            refused.message
        );
        let summary = again.store().summary(id).unwrap().unwrap();
        assert_eq!(summary.physics, game::PHYSICS_VERSION + 1);
        assert!(!summary.playable);
        assert_eq!(summary.status, Status::Live, "left as stored");
        assert!(
            again
                .store()
                .summary(&a.match_id)
                .unwrap()
                .unwrap()
                .playable
        );
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn an_exhibition_between_two_levels_plays_to_the_end_for_a_spectator_and_stores_both_bots(
    ) {
        let hub = hub();
        let id = hub
            .create_exhibition(
                Level::Easy,
                Level::Medium,
                game::Preset::Standard.config(),
                None,
            )
            .await
            .unwrap();
        let stored = hub.store().get(&id).unwrap().unwrap();
        assert_eq!(stored.bots(), [Some(Level::Easy), Some(Level::Medium)]);
        assert_eq!(stored.status, Status::Live);
        let (_, mut watcher) = hub.connect(&id, None).await.unwrap();
        let ServerMessage::MatchState { players, view, .. } = next(&mut watcher.rx).await else {
            panic!("match-state first")
        };
        assert_eq!(players.first.as_deref(), Some("bot (easy)"));
        assert_eq!(players.second.as_deref(), Some("bot (medium)"));
        assert!(view.config.variants.pie_rule, "standard rules by default");
        let over = tokio::time::timeout(Duration::from_secs(120), async {
            loop {
                if let ServerMessage::MatchOver { result, .. } = next(&mut watcher.rx).await {
                    return result;
                }
            }
        })
        .await
        .expect("the bots finish the match");
        assert!(over.winner().is_some(), "{over:?}");
        let summary = hub.store().get(&id).unwrap().unwrap();
        assert_eq!(summary.status, Status::Finished);
        assert_eq!(
            StoredMatch::bots_column([None, Some(Level::Hard)]).as_deref(),
            Some("hard")
        );
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_bot_answers_a_shot_and_a_full_server_refuses_new_matches() {
        let hub = hub();
        let a = hub
            .create(NewMatch {
                opponent: Opponent::Bot(Level::Medium),
                ..person("p")
            })
            .await
            .unwrap();
        assert_eq!(
            hub.join(&a.match_id, "x".into(), None)
                .await
                .unwrap_err()
                .code,
            ErrorCode::MatchFull
        );
        let (room, mut c) = hub.connect(&a.match_id, Some(a.token)).await.unwrap();
        let msg = ClientMessage::Shot {
            piece: PieceId::new(Side::White, 0).unwrap(),
            velocity: DVec2::new(0.0, 0.5),
        };
        room.tx.send(Command::message(c.conn, msg)).await.unwrap();
        let ServerMessage::ShotPlayed { outcome, .. } = next_of(&mut c.rx, "shot-played").await
        else {
            panic!()
        };
        assert_eq!(outcome.shooter, Side::White);
        let ServerMessage::ShotPlayed { outcome, .. } = next_of(&mut c.rx, "shot-played").await
        else {
            panic!()
        };
        assert_eq!(outcome.shooter, Side::Black);

        let small = Hub::new(
            Arc::new(SqliteStore::in_memory().unwrap()),
            Arc::new(Metrics::default()),
            Limits {
                max_matches: 1,
                ..Limits::default()
            },
            Handle::current(),
        );
        small.create(person("a")).await.unwrap();
        assert_eq!(
            small.create(person("b")).await.unwrap_err().code,
            ErrorCode::ServerBusy
        );
    }
}
