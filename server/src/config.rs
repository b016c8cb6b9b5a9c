//! Command-line flags and environment variables (`clap`): where to listen,
//! where the store lives, how much to log, and every limit that bounds the
//! server's memory and protects it from abusive clients. Each flag has an
//! environment variable of the same name in capitals with a `CHAPAEV_`
//! prefix (`--max-matches` is `CHAPAEV_MAX_MATCHES`).

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::time::Duration;

/// Chapaev online match server: HTTP API, WebSocket play, built-in bots,
/// turn clock and a crash-safe store (SQLite, or PostgreSQL).
#[derive(Parser, Debug, Clone)]
#[command(name = "server", version, about, long_about = None)]
pub struct Config {
    /// Without a command, the server runs; `backup` and `restore` copy
    /// its store out and back in (see docs/operations.md).
    #[command(subcommand)]
    pub command: Option<Command>,

    /// Address to listen on (`host:port`; port 0 picks a free port, printed on start).
    #[arg(long, env = "CHAPAEV_ADDR", default_value = "127.0.0.1:8080")]
    pub addr: String,

    /// Folder of the SQLite store (`chapaev.sqlite3`), created if missing
    /// (unused with `--database-url`).
    #[arg(
        long,
        env = "CHAPAEV_DATA_DIR",
        default_value = "./data",
        global = true
    )]
    pub data_dir: PathBuf,

    /// Store everything in PostgreSQL instead of SQLite
    /// (`postgres://user:password@host:port/database`); its schema is
    /// created or migrated on start. Several server nodes may share one.
    #[arg(long, env = "CHAPAEV_DATABASE_URL", global = true)]
    pub database_url: Option<String>,

    /// Run as one node of a cluster (`redis://host:port`): nodes share the
    /// PostgreSQL store (`--database-url`, required), each live match is
    /// played on the node holding its lease, and Redis relays the messages
    /// of clients connected to other nodes.
    #[arg(long, env = "CHAPAEV_REDIS_URL", requires = "database_url")]
    pub redis_url: Option<String>,

    /// This node's name in the cluster (unique among live nodes; default:
    /// the host's name and the process id).
    #[arg(long, env = "CHAPAEV_NODE_ID", value_parser = parse_node_id)]
    pub node_id: Option<String>,

    /// Where clients reach this node of a cluster, directly or through a
    /// proxy's route to this node alone (`https://play.example/n/node-1`).
    /// A node asked with `/ws?match=ID&follow=1` for a match another node
    /// plays answers `307` with that node's URL, so the client talks to
    /// the node playing its match instead of being relayed. Without it,
    /// other nodes relay this node's matches to their clients.
    #[arg(long, env = "CHAPAEV_PUBLIC_URL", requires = "redis_url", value_parser = parse_public_url)]
    pub public_url: Option<String>,

    /// Seconds a node's lease on a match lasts unrenewed: after a node
    /// dies, its matches move to another node within about this long.
    #[arg(long, env = "CHAPAEV_LEASE_SECONDS", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=600))]
    pub lease_seconds: u64,

    /// Log filter in tracing's EnvFilter syntax, e.g. `info` or `server=debug,warn`.
    #[arg(long, env = "CHAPAEV_LOG", default_value = "info")]
    pub log: String,

    /// HTTP/WebSocket worker threads (each serves its share of the
    /// connections). The default is one less than the cores (at least
    /// one), leaving a core to the game thread and the store's writer:
    /// on two cores at 10,000 connections that cost 550 µs of CPU per shot
    /// against 600–650 with four workers and two game threads.
    #[arg(long, env = "CHAPAEV_HTTP_WORKERS", default_value_t = default_http_workers(), value_parser = clap::value_parser!(u16).range(1..=64))]
    pub http_workers: u16,

    /// Game threads: the matches' rooms (shot resolution takes about 10 µs,
    /// so one thread serves thousands of shots a second; the computer
    /// levels think on blocking threads of their own).
    #[arg(long, env = "CHAPAEV_GAME_THREADS", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=64))]
    pub game_threads: u16,

    /// Most matches held in memory at once (open, live and recently
    /// finished); creating one more is refused with `server-busy`.
    #[arg(long, env = "CHAPAEV_MAX_MATCHES", default_value_t = 1000)]
    pub max_matches: usize,

    /// Most WebSocket connections at once; more are refused with HTTP 503.
    #[arg(long, env = "CHAPAEV_MAX_CONNECTIONS", default_value_t = 5000)]
    pub max_connections: usize,

    /// Most WebSocket connections from one client address at once; more
    /// are refused with HTTP 503 `server-busy`.
    #[arg(long, env = "CHAPAEV_MAX_CONNECTIONS_PER_ADDRESS", default_value_t = 50, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_connections_per_address: u64,

    /// Most WebSocket connections (players and spectators) on one match.
    #[arg(long, env = "CHAPAEV_MAX_CONNECTIONS_PER_MATCH", default_value_t = 200)]
    pub max_connections_per_match: usize,

    /// Largest WebSocket message or HTTP body accepted, in bytes.
    #[arg(long, env = "CHAPAEV_MAX_MESSAGE_BYTES", default_value_t = 16 * 1024)]
    pub max_message_bytes: usize,

    /// Messages a connection may send per second, sustained.
    #[arg(long, env = "CHAPAEV_RATE_PER_SEC", default_value_t = 20.0)]
    pub rate_per_sec: f64,

    /// Messages a connection may send in a burst above the sustained rate.
    #[arg(long, env = "CHAPAEV_RATE_BURST", default_value_t = 40.0)]
    pub rate_burst: f64,

    /// Messages queued for one connection before it is dropped as too slow
    /// to follow its match (and its socket closed).
    #[arg(long, env = "CHAPAEV_OUTBOUND_QUEUE", default_value_t = 256, value_parser = clap::value_parser!(u64).range(1..=65_536))]
    pub outbound_queue: u64,

    /// Milliseconds one write to a WebSocket may take; a connection whose
    /// write takes longer (a client that stopped reading) is closed.
    #[arg(long, env = "CHAPAEV_WRITE_TIMEOUT_MS", default_value_t = 10_000, value_parser = clap::value_parser!(u64).range(1..))]
    pub write_timeout_ms: u64,

    /// Matches (`POST /api/matches`, `POST /api/exhibitions`) one client
    /// address may create per second, sustained; past it, HTTP 429
    /// `rate-limited`.
    #[arg(long, env = "CHAPAEV_CREATE_PER_SEC", default_value_t = 2.0)]
    pub create_per_sec: f64,

    /// Matches one client address may create at once.
    #[arg(long, env = "CHAPAEV_CREATE_BURST", default_value_t = 10.0)]
    pub create_burst: f64,

    /// Origins besides the server's own (scheme and `Host`) whose pages may
    /// create, join and play matches, comma-separated (e.g. the public
    /// address of a proxy in front: `https://chapaev.example`). A node of
    /// a cluster also accepts the origins of the live nodes' `--public-url`s
    /// without being told.
    #[arg(long, env = "CHAPAEV_ALLOWED_ORIGINS", value_delimiter = ',')]
    pub allowed_origins: Vec<String>,

    /// Reverse proxies in front of the server, trusted to say whom they
    /// forward for (CIDR networks or addresses, comma-separated or the
    /// flag repeated: `--trusted-proxy 10.0.0.0/8,::1`). A request from one
    /// of them counts against the limits of the client address its
    /// `Forwarded` (or else `X-Forwarded-For`) header names: the right-most
    /// hop that is not itself a trusted proxy. Those headers are ignored
    /// from any other peer. None by default: every limit counts by the TCP
    /// peer, so behind a proxy all clients would share one address.
    #[arg(long, env = "CHAPAEV_TRUSTED_PROXY", value_delimiter = ',', value_parser = parse_trusted_proxy)]
    pub trusted_proxy: Vec<ipnet::IpNet>,

    /// Shots `POST /api/simulate` computes per second for one client
    /// address, sustained.
    #[arg(long, env = "CHAPAEV_SIMULATE_PER_SEC", default_value_t = 50.0)]
    pub simulate_per_sec: f64,

    /// Shots `POST /api/simulate` computes at once for one address.
    #[arg(long, env = "CHAPAEV_SIMULATE_BURST", default_value_t = 100.0)]
    pub simulate_burst: f64,

    /// Default turn clock, seconds to shoot (a match may ask for its own
    /// between 1 and 3600). Timing out passes the turn; three in a row forfeit.
    #[arg(long, env = "CHAPAEV_TURN_SECONDS", default_value_t = 60, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub turn_seconds: u64,

    /// Seconds a disconnected player keeps the seat before forfeiting.
    #[arg(long, env = "CHAPAEV_GRACE_SECONDS", default_value_t = 60, value_parser = clap::value_parser!(u64).range(1..=86400))]
    pub grace_seconds: u64,

    /// Milliseconds a built-in bot waits before it shoots (so people can follow).
    #[arg(long, env = "CHAPAEV_BOT_DELAY_MS", default_value_t = 400)]
    pub bot_delay_ms: u64,

    /// Milliseconds a computer level may think at most on one move (a safety
    /// cap: `hard` needs about 0.1 s of CPU on a mid-game board).
    #[arg(long, env = "CHAPAEV_BOT_THINK_MS", default_value_t = 5000, value_parser = clap::value_parser!(u64).range(10..=60_000))]
    pub bot_think_ms: u64,

    /// Seconds a finished (or still open) match with nobody connected stays in memory.
    #[arg(long, env = "CHAPAEV_IDLE_SECONDS", default_value_t = 30)]
    pub idle_seconds: u64,

    /// Seconds after which an open match that nobody joined, nobody waits
    /// in and nobody touched is deleted (checked every minute and on start).
    #[arg(long, env = "CHAPAEV_OPEN_MATCH_EXPIRY_SECONDS", default_value_t = 3600, value_parser = clap::value_parser!(u64).range(10..=30 * 24 * 3600))]
    pub open_match_expiry_seconds: u64,

    /// Seconds between two rounds of the bot ladder, which pairs the
    /// online ladder bots (and the computer levels) in rated matches.
    #[arg(long, env = "CHAPAEV_LADDER_SECONDS", default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..=24 * 3600))]
    pub ladder_seconds: u64,

    /// Hosted bots' decisions that may run at once, server-wide (on a
    /// cluster, on this node), each on a blocking thread of its own
    /// (default: a quarter of the cores, at least one); the others wait
    /// their turn, so hosted bots never take more than these cores from
    /// people's matches.
    #[arg(long, env = "CHAPAEV_HOSTED_WORKERS", default_value_t = default_hosted_workers(), value_parser = clap::value_parser!(u16).range(1..=256))]
    pub hosted_workers: u16,

    /// Most seats of ladder matches and challenges that hosted bots play
    /// at once (a match between two hosted bots takes two); past it the
    /// ladder pairs no more of them and a challenge to one is refused
    /// with `server-busy`. The seats are counted from the store too, so on
    /// a cluster this bounds all its nodes' seats together (give every
    /// node the same value).
    #[arg(long, env = "CHAPAEV_HOSTED_MATCHES", default_value_t = 16, value_parser = clap::value_parser!(u32).range(0..=100_000))]
    pub hosted_matches: u32,

    /// Seconds a challenge waits for an answer before it expires.
    #[arg(long, env = "CHAPAEV_CHALLENGE_SECONDS", default_value_t = 60, value_parser = clap::value_parser!(u64).range(5..=24 * 3600))]
    pub challenge_seconds: u64,

    /// How hard SQLite syncs each accepted move: `full` survives power loss,
    /// `normal` survives a crash of the server process only.
    #[arg(long, env = "CHAPAEV_SYNC", value_enum, default_value_t = SyncMode::Full)]
    pub sync: SyncMode,

    /// A folder built by `scripts/build-sdk` (the Python wheel and the npm
    /// tarball of the simulator, with their manifest) to hand out at
    /// `/sdk/`; it must match this server's physics version.
    #[arg(long, env = "CHAPAEV_SDK_DIR", value_name = "DIR")]
    pub sdk_dir: Option<PathBuf>,

    /// Seconds to let connections and writes finish on SIGTERM or Ctrl-C.
    #[arg(long, env = "CHAPAEV_SHUTDOWN_SECONDS", default_value_t = 10)]
    pub shutdown_seconds: u64,
}

/// What the `server` binary does besides serving.
#[derive(Subcommand, Debug, Clone, PartialEq, Eq)]
pub enum Command {
    /// Copies the store into FILE while the server may be running and
    /// playing: SQLite's own consistent copy (`VACUUM INTO`), or `pg_dump`
    /// for PostgreSQL (which must then be on PATH). FILE must not exist.
    Backup {
        /// The file to write.
        #[arg(long, value_name = "FILE")]
        to: PathBuf,
    },
    /// Restores a backup into the store the flags name (`--data-dir`, or
    /// `--database-url`), which must be empty; then replays every match
    /// in it to prove it whole. Run it with no server on that store.
    Restore {
        /// The backup to read.
        #[arg(long, value_name = "FILE")]
        from: PathBuf,
    },
}

/// One less than the cores this process may use, at least one, at most 64.
fn default_http_workers() -> u16 {
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    cores.saturating_sub(1).clamp(1, 64) as u16
}

/// A quarter of the cores this process may use, at least one.
fn default_hosted_workers() -> u16 {
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    (cores / 4).clamp(1, 256) as u16
}

/// SQLite's `synchronous` setting under the write-ahead log.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SyncMode {
    Full,
    Normal,
}

impl SyncMode {
    /// The value of SQLite's `synchronous` pragma.
    pub fn pragma(self) -> &'static str {
        match self {
            SyncMode::Full => "FULL",
            SyncMode::Normal => "NORMAL",
        }
    }
}

/// The limits and timings the match rooms and sessions run under.
#[derive(Clone, Debug)]
pub struct Limits {
    pub max_matches: usize,
    pub max_connections: usize,
    pub max_connections_per_match: usize,
    /// Most WebSocket connections from one client address.
    pub max_connections_per_address: usize,
    pub max_message_bytes: usize,
    pub rate_per_sec: f64,
    pub rate_burst: f64,
    pub turn: Duration,
    pub grace: Duration,
    pub bot_delay: Duration,
    /// The most a computer level thinks on one move.
    pub bot_think: Duration,
    pub idle: Duration,
    /// Messages queued for one connection before it is dropped as too slow.
    pub outbound_queue: usize,
    /// The most one write to a WebSocket may take.
    pub write_timeout: Duration,
    /// Hosted bots' decisions that may run at once.
    pub hosted_workers: usize,
}

/// A node id: 1 to 64 letters, digits, `-`, `_` or `.`.
fn parse_node_id(s: &str) -> Result<String, String> {
    let ok = (1..=64).contains(&s.len())
        && s.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b));
    if ok {
        Ok(s.to_string())
    } else {
        Err("a node id is 1 to 64 letters, digits, '-', '_' or '.'".into())
    }
}

/// A `--public-url`: `http://` or `https://`, a host, perhaps a port
/// and a path; no query, fragment or space. Kept without a trailing `/`.
fn parse_public_url(s: &str) -> Result<String, String> {
    let rest = s
        .strip_prefix("http://")
        .or_else(|| s.strip_prefix("https://"))
        .ok_or("a public URL starts with http:// or https://")?;
    let host = rest.split('/').next().unwrap_or_default();
    if host.is_empty() {
        return Err("a public URL names a host".into());
    }
    if s.len() > 512
        || s.chars()
            .any(|c| c.is_whitespace() || c.is_control() || c == '?' || c == '#')
    {
        return Err(
            "a public URL has no query, fragment or space (and at most 512 characters)".into(),
        );
    }
    Ok(s.trim_end_matches('/').to_string())
}

/// A `--trusted-proxy` value: a network in CIDR notation (`10.0.0.0/8`,
/// `fd00::/8`) or a single address.
pub fn parse_trusted_proxy(s: &str) -> Result<ipnet::IpNet, String> {
    s.parse::<ipnet::IpNet>()
        .or_else(|_| s.parse::<std::net::IpAddr>().map(ipnet::IpNet::from))
        .map_err(|_| format!("{s:?} is neither a network (10.0.0.0/8) nor an address"))
}

impl Config {
    /// This node's id when it runs in a cluster (`--redis-url`); `None`
    /// for a server on its own.
    pub fn cluster_node(&self) -> Option<String> {
        self.redis_url.as_ref()?;
        Some(self.node_id.clone().unwrap_or_else(|| {
            let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
                .map(|h| h.trim().to_string())
                .unwrap_or_default();
            let host: String = host
                .chars()
                .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
                .take(40)
                .collect();
            format!(
                "{}-{}",
                if host.is_empty() { "node" } else { &host },
                std::process::id()
            )
        }))
    }

    /// The limits part of the configuration.
    /// The lobby's settings.
    pub fn lobby_limits(&self) -> game::lobby::LobbyLimits {
        game::lobby::LobbyLimits {
            challenge_ttl: Duration::from_secs(self.challenge_seconds),
            ladder_every: Duration::from_secs(self.ladder_seconds),
            max_hosted_seats: self.hosted_matches as usize,
            ..Default::default()
        }
    }

    pub fn limits(&self) -> Limits {
        Limits {
            max_matches: self.max_matches,
            max_connections: self.max_connections,
            max_connections_per_match: self.max_connections_per_match,
            max_connections_per_address: usize::try_from(self.max_connections_per_address)
                .unwrap_or(usize::MAX),
            max_message_bytes: self.max_message_bytes,
            rate_per_sec: self.rate_per_sec,
            rate_burst: self.rate_burst,
            turn: Duration::from_secs(self.turn_seconds),
            grace: Duration::from_secs(self.grace_seconds),
            bot_delay: Duration::from_millis(self.bot_delay_ms),
            bot_think: Duration::from_millis(self.bot_think_ms),
            idle: Duration::from_secs(self.idle_seconds),
            outbound_queue: usize::try_from(self.outbound_queue).unwrap_or(256),
            write_timeout: Duration::from_millis(self.write_timeout_ms),
            hosted_workers: usize::from(self.hosted_workers),
        }
    }
}

impl Default for Limits {
    fn default() -> Self {
        Config::parse_from(["server"]).limits()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn defaults_listen_on_localhost_8080_with_data_under_data() {
        let c = Config::parse_from(["server"]);
        assert_eq!(c.addr, "127.0.0.1:8080");
        assert_eq!(c.data_dir, PathBuf::from("./data"));
        assert_eq!(c.sync, SyncMode::Full);
        assert_eq!(c.limits().turn, Duration::from_secs(60));
    }

    #[test]
    fn flags_override_defaults_and_bad_values_are_refused() {
        let c = Config::parse_from(["server", "--addr", "0.0.0.0:9", "--turn-seconds", "5"]);
        assert_eq!(c.addr, "0.0.0.0:9");
        assert_eq!(c.turn_seconds, 5);
        assert!(Config::try_parse_from(["server", "--turn-seconds", "0"]).is_err());
        assert!(Config::try_parse_from(["server", "--sync", "sometimes"]).is_err());
        Config::command().debug_assert();
    }

    #[test]
    fn a_public_url_is_http_or_https_with_a_host_and_no_query() {
        assert_eq!(
            parse_public_url("https://play.example/n/node-1/").as_deref(),
            Ok("https://play.example/n/node-1")
        );
        assert_eq!(
            parse_public_url("http://10.0.0.5:8080").as_deref(),
            Ok("http://10.0.0.5:8080")
        );
        for bad in [
            "play.example",
            "ftp://play.example",
            "https://",
            "https:///path",
            "https://play.example/?x=1",
            "https://play.example/#a",
            "https://play example",
        ] {
            assert!(parse_public_url(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn backup_and_restore_are_commands_taking_the_stores_flags_before_or_after() {
        assert_eq!(Config::parse_from(["server"]).command, None);
        let c = Config::parse_from(["server", "backup", "--to", "b.sqlite3", "--data-dir", "d"]);
        assert_eq!(
            c.command,
            Some(Command::Backup {
                to: "b.sqlite3".into()
            })
        );
        assert_eq!(c.data_dir, PathBuf::from("d"));
        let c = Config::parse_from(["server", "--data-dir", "e", "restore", "--from", "b"]);
        assert_eq!(c.command, Some(Command::Restore { from: "b".into() }));
        assert_eq!(c.data_dir, PathBuf::from("e"));
        assert!(Config::try_parse_from(["server", "backup"]).is_err());
    }

    #[test]
    fn trusted_proxies_are_networks_or_addresses_listed_or_repeated() {
        let c = Config::parse_from([
            "server",
            "--trusted-proxy",
            "10.0.0.0/8,::1",
            "--trusted-proxy",
            "192.0.2.7",
        ]);
        let shown: Vec<String> = c.trusted_proxy.iter().map(|n| n.to_string()).collect();
        assert_eq!(shown, ["10.0.0.0/8", "::1/128", "192.0.2.7/32"]);
        assert!(Config::parse_from(["server"]).trusted_proxy.is_empty());
        assert!(Config::try_parse_from(["server", "--trusted-proxy", "10.0.0.0/40"]).is_err());
        assert!(Config::try_parse_from(["server", "--trusted-proxy", "proxy.example"]).is_err());
    }
}
