//! # local-services — throwaway PostgreSQL and Redis for Chapaev's tests
//!
//! The server's tests that need PostgreSQL (the store on both backends,
//! the crash test on PostgreSQL) or PostgreSQL and Redis (several nodes of
//! a cluster) start their own servers with this crate: from the machine's
//! packages, on a free loopback port, keeping nothing once the test
//! process ends. It is a dev-dependency only: nothing here ships in the
//! server.
//!
//! | module | what it owns |
//! | --- | --- |
//! | [`process`] | starting a service's process: its user, its parent-death signal, a free port, once per test process |
//! | [`skip`] | the rule for a test whose service is missing: skipped with a line on stderr, or failed when required |
//! | [`local_postgres`] | [`LocalPostgres`]: `initdb` and `postgres` in a temporary folder; fresh databases on a shared one |
//! | [`local_redis`] | [`LocalRedis`]: `redis-server` without persistence |
//! | [`tcp_link`] | [`TcpLink`]: a forwarder to a service's port that a test can cut (one client losing a service) |
//!
//! A test asks for the shared server by its own name, and returns early
//! when it gets `None` (the skip line is already printed):
//!
//! ```no_run
//! # fn a_test() {
//! let Some(url) = local_services::local_postgres::shared_database("a_test") else {
//!     return; // "skipped: a_test: no PostgreSQL (...)" went to stderr
//! };
//! let mut db = postgres::Client::connect(&url, postgres::NoTls).unwrap();
//! # }
//! ```

pub mod local_postgres;
pub mod local_redis;
pub mod process;
pub mod skip;
pub mod tcp_link;

pub use local_postgres::{LocalPostgres, LocalPostgresError};
pub use local_redis::{LocalRedis, LocalRedisError};
pub use tcp_link::TcpLink;
