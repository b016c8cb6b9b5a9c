//! The web layer: every HTTP route and the two WebSocket endpoints, from
//! request to the play layer ([`crate::play`]) and back.
//!
//! - [`matches`]: the match API (`/api/matches`, exhibitions, records),
//!   `/api`, `/healthz`, `/metrics` and the protocol's schema;
//! - [`accounts`]: the accounts API; [`auth`]: who a request proves to be;
//! - [`modules`]: a bot account's hosted module and its versions;
//! - [`assets`]: the embedded web client at `/`;
//! - [`simulate`]: `POST /api/simulate`; [`sdk`]: the bot-author packages
//!   at `/sdk/`;
//! - [`ws`]: a match's WebSocket; [`stream`]: the lobby's event stream;
//!   [`pump`]: the WebSocket loop both run on;
//! - [`reply`]: the shapes every answer shares; [`origin`]: cross-site
//!   requests refused; [`client_addr`]: who a request comes from, behind
//!   trusted proxies; [`ratelimit`]: token buckets per connection and per
//!   address; [`blocking`]: store work off the async threads.

pub(crate) mod accounts;
pub(crate) mod assets;
pub(crate) mod auth;
pub(crate) mod blocking;
pub(crate) mod client_addr;
pub(crate) mod matches;
pub(crate) mod modules;
pub(crate) mod origin;
pub(crate) mod pump;
pub(crate) mod ratelimit;
pub(crate) mod reply;
pub(crate) mod sdk;
pub(crate) mod simulate;
pub(crate) mod stream;
pub(crate) mod ws;

use actix_web::web;

/// Registers every route.
pub fn routes(cfg: &mut web::ServiceConfig) {
    crate::web::assets::routes(cfg);
    crate::web::accounts::routes(cfg);
    crate::web::sdk::routes(cfg);
    crate::web::modules::routes(cfg);
    cfg.route("/api", web::get().to(matches::api_page))
        .route("/healthz", web::get().to(matches::healthz))
        .route("/metrics", web::get().to(matches::metrics))
        .route("/ws", web::get().to(crate::web::ws::handler))
        .route("/api/stream", web::get().to(crate::web::stream::handler))
        .route("/api/matches", web::post().to(matches::create))
        .route("/api/matches", web::get().to(matches::list))
        .route("/api/matches/{id}", web::get().to(matches::summary))
        .route("/api/matches/{id}/join", web::post().to(matches::join))
        .route(
            "/api/matches/{id}/socket",
            web::get().to(crate::web::ws::socket),
        )
        .route("/api/exhibitions", web::post().to(matches::exhibition))
        .route(
            "/api/simulate",
            web::post().to(crate::web::simulate::handler),
        )
        .route(game::protocol::SCHEMA_PATH, web::get().to(matches::schema))
        .route("/api/matches/{id}/record", web::get().to(matches::record));
}
