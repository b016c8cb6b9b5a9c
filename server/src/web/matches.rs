//! The HTTP API: the page at `/api` that explains how to play through it,
//! `/healthz`, `/metrics`, and under `/api/matches` creating a match
//! (against a person or a built-in bot), joining its empty seat, listing
//! matches, one match's summary and its record for replay. Bodies are JSON;
//! errors are the protocol's `error` message with a fitting HTTP status.
//! Creating matches and exhibitions is limited per client address
//! ([`Creations`]: `--create-per-sec`, `--create-burst`; past it, 429
//! `rate-limited`), and the hub holds the limit on matches in memory.
//! The game itself (`/` and its files) is [`crate::web::assets`].

use crate::metrics;
use crate::play::hub::{Hub, NewMatch, Opponent, SeatGrant};
use crate::refusal::Refusal;
use crate::store::{Status, StoreError};
use crate::web::auth::signed_in;
use crate::web::blocking::blocking_with;
use crate::web::reply::{json, public_host, read_body, refused, Creations};
use actix_web::http::StatusCode;
use actix_web::{web, HttpRequest, HttpResponse};
use bots::Level;
use game::protocol::ErrorCode;
use game::Config;
use prometheus_client::registry::Registry;
use serde::{Deserialize, Serialize};

/// Most matches one listing returns.
pub const MAX_LIST: usize = 100;

fn name(n: Option<String>, default: &str) -> Result<String, Refusal> {
    let n = n.unwrap_or_else(|| default.to_string());
    Ok(game::name::seat_name(&n)?)
}

async fn blocking<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, StoreError> + Send + 'static,
) -> Result<T, Refusal> {
    blocking_with(f, |e| Err(e.to_string())).await
}

/// `GET /api/schema/v1.json`: the protocol's JSON Schema.
pub(crate) async fn schema() -> HttpResponse {
    static SCHEMA: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    let text = SCHEMA.get_or_init(|| game::protocol::schema().to_string());
    HttpResponse::Ok()
        .content_type("application/schema+json")
        .body(text.as_str())
}

pub(crate) async fn api_page(req: HttpRequest) -> HttpResponse {
    HttpResponse::Ok()
        .content_type("text/html; charset=utf-8")
        .body(api_html(&public_host(&req)))
}

/// The API page with its examples addressed to `host`.
pub(crate) fn api_html(host: &str) -> String {
    API_HTML.replace("localhost:8080", host)
}

pub(crate) async fn healthz(hub: web::Data<Hub>) -> HttpResponse {
    json(
        StatusCode::OK,
        &serde_json::json!({
            "status": "ok",
            "protocol": game::protocol::PROTOCOL_VERSION,
            "matches_in_memory": hub.rooms_in_memory(),
            "connections": hub.metrics().connections(),
        }),
    )
}

pub(crate) async fn metrics(hub: web::Data<Hub>) -> HttpResponse {
    let mut registry = Registry::default();
    hub.metrics().register(&mut registry);
    hub.store().register_metrics(&mut registry);
    hub.register_cluster_metrics(&mut registry);
    HttpResponse::Ok()
        .content_type(metrics::CONTENT_TYPE)
        .body(metrics::encode(&registry))
}

/// `POST /api/matches`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CreateBody {
    name: Option<String>,
    /// `person` (default) or `bot`.
    opponent: Option<String>,
    /// `easy`, `medium` (default) or `hard` when the opponent is a bot.
    bot_level: Option<String>,
    /// A named set of rules: `casual` (the default) or `standard`.
    rules: Option<String>,
    /// A full configuration instead of a named one.
    config: Option<Config>,
    turn_seconds: Option<u64>,
    /// Whether the result moves the ratings (needs an account, and the
    /// `standard` rules).
    #[serde(default)]
    rated: bool,
    /// A public seed for the noise (casual matches only): the same noise
    /// as `bots match --seed` draws locally, and known to anyone.
    seed: Option<u64>,
}

/// The rules of a new match: a preset by name, or a configuration (not
/// both); `casual` when neither is given.
fn rules(rules: Option<&str>, config: Option<Config>) -> Result<Config, Refusal> {
    match (rules, config) {
        (Some(_), Some(_)) => Err(Refusal::new(
            ErrorCode::BadMessage,
            "give either rules or config, not both",
        )),
        (None, Some(config)) => Ok(config),
        (Some(name), None) => game::Preset::parse(name)
            .map(game::Preset::config)
            .ok_or_else(|| Refusal::new(ErrorCode::BadConfig, "rules are casual or standard")),
        (None, None) => Ok(Config::default()),
    }
}

/// The largest seed a match takes: the largest integer a JSON number
/// carries exactly everywhere (a JavaScript `Number`).
pub const MAX_SEED: u64 = (1 << 53) - 1;

/// A seed asked for, checked: one a JSON client can read back unchanged.
fn public_seed(seed: u64) -> Result<u64, Refusal> {
    if seed > MAX_SEED {
        return Err(Refusal::new(
            ErrorCode::BadMessage,
            format!("a seed is at most {MAX_SEED}, which every JSON reader keeps exact"),
        ));
    }
    Ok(seed)
}

fn level(name: Option<&str>) -> Result<Level, Refusal> {
    Level::parse(name.unwrap_or("medium"))
        .ok_or_else(|| Refusal::new(ErrorCode::BadMessage, "a bot level is easy, medium or hard"))
}

/// A seat handed out, as JSON.
#[derive(Debug, Serialize, Deserialize)]
pub struct SeatResponse {
    pub match_id: String,
    pub seat: game::Seat,
    /// The seat token: shown here once, kept by the server only as a hash,
    /// and presented in the WebSocket's `hello`.
    pub token: String,
    /// Path and query of the WebSocket to play on (no secret in it).
    pub ws: String,
}

impl From<SeatGrant> for SeatResponse {
    fn from(g: SeatGrant) -> SeatResponse {
        SeatResponse {
            ws: format!("/ws?match={}", g.match_id),
            token: g.token.expose().to_string(),
            match_id: g.match_id,
            seat: g.seat,
        }
    }
}

pub(crate) async fn create(
    hub: web::Data<Hub>,
    creations: web::Data<Creations>,
    req: HttpRequest,
    bytes: web::Bytes,
) -> HttpResponse {
    let result = async {
        creations.check(&req)?;
        let b: CreateBody = read_body(&bytes)?;
        let opponent = match b.opponent.as_deref().unwrap_or("person") {
            "person" => Opponent::Person,
            "bot" => Opponent::Bot(level(b.bot_level.as_deref())?),
            _ => {
                return Err(Refusal::new(
                    ErrorCode::BadMessage,
                    "opponent is person or bot",
                ))
            }
        };
        let account = signed_in(&req, &hub).await?.map(|(_, a)| a.name);
        let config = match (b.rated, b.rules.as_deref(), b.config) {
            (true, None | Some("standard"), None) => game::Preset::Standard.config(),
            (true, ..) => {
                return Err(Refusal::new(
                    ErrorCode::BadConfig,
                    "a rated match is played under the standard rules",
                ))
            }
            (false, r, c) => rules(r, c)?,
        };
        let req = NewMatch {
            name: match &account {
                Some(a) => a.clone(),
                None => name(b.name, "first")?,
            },
            account,
            opponent,
            config,
            turn_seconds: b.turn_seconds,
            rated: b.rated,
            seed: b.seed.map(public_seed).transpose()?,
        };
        hub.create(req).await
    }
    .await;
    match result {
        Ok(g) => json(StatusCode::CREATED, &SeatResponse::from(g)),
        Err(r) => refused(&r),
    }
}

/// `POST /api/exhibitions`: two computer levels play each other.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExhibitionBody {
    /// The first seat's level (White, unless the pie rule swaps).
    first: Option<String>,
    second: Option<String>,
    /// `standard` (the default for bots against bots) or `casual`.
    rules: Option<String>,
    config: Option<Config>,
    turn_seconds: Option<u64>,
}

pub(crate) async fn exhibition(
    hub: web::Data<Hub>,
    creations: web::Data<Creations>,
    req: HttpRequest,
    bytes: web::Bytes,
) -> HttpResponse {
    let result = async {
        creations.check(&req)?;
        let b: ExhibitionBody = read_body(&bytes)?;
        let config = match (b.rules.as_deref(), b.config) {
            (None, None) => game::Preset::Standard.config(),
            (r, c) => rules(r, c)?,
        };
        let first = level(b.first.as_deref())?;
        let second = level(b.second.as_deref())?;
        hub.create_exhibition(first, second, config, b.turn_seconds)
            .await
    }
    .await;
    match result {
        Ok(id) => json(
            StatusCode::CREATED,
            &serde_json::json!({ "match_id": id, "ws": format!("/ws?match={id}") }),
        ),
        Err(r) => refused(&r),
    }
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct JoinBody {
    name: Option<String>,
}

pub(crate) async fn join(
    hub: web::Data<Hub>,
    id: web::Path<String>,
    req: HttpRequest,
    bytes: web::Bytes,
) -> HttpResponse {
    let result = async {
        let b: JoinBody = read_body(&bytes)?;
        match signed_in(&req, &hub).await? {
            Some((_, a)) => hub.join(&id, a.name.clone(), Some(a.name)).await,
            None => hub.join(&id, name(b.name, "second")?, None).await,
        }
    }
    .await;
    match result {
        Ok(g) => json(StatusCode::OK, &SeatResponse::from(g)),
        Err(r) => refused(&r),
    }
}

#[derive(Debug, Deserialize)]
struct ListQuery {
    status: Option<String>,
    limit: Option<usize>,
}

pub(crate) async fn list(hub: web::Data<Hub>, req: HttpRequest) -> HttpResponse {
    let q = match web::Query::<ListQuery>::from_query(req.query_string()) {
        Ok(q) => q.into_inner(),
        Err(e) => return refused(&Refusal::new(ErrorCode::BadMessage, e.to_string())),
    };
    let status = match q.status.as_deref() {
        None => None,
        Some(s) => match Status::parse(s) {
            Some(s) => Some(s),
            None => {
                return refused(&Refusal::new(
                    ErrorCode::BadMessage,
                    "status is open, live or finished",
                ))
            }
        },
    };
    let limit = q.limit.unwrap_or(50).min(MAX_LIST);
    let store = hub.store().clone();
    match blocking(move || store.list(status, limit)).await {
        Ok(list) => json(StatusCode::OK, &serde_json::json!({ "matches": list })),
        Err(r) => refused(&r),
    }
}

fn no_such_match(id: &str) -> Refusal {
    Refusal::new(ErrorCode::NoSuchMatch, format!("no match {id:?}"))
}

pub(crate) async fn summary(hub: web::Data<Hub>, id: web::Path<String>) -> HttpResponse {
    let store = hub.store().clone();
    let key = id.clone();
    match blocking(move || store.summary(&key)).await {
        Ok(Some(s)) => json(StatusCode::OK, &s),
        Ok(None) => refused(&no_such_match(&id)),
        Err(r) => refused(&r),
    }
}

pub(crate) async fn record(hub: web::Data<Hub>, id: web::Path<String>) -> HttpResponse {
    let store = hub.store().clone();
    let key = id.clone();
    match blocking(move || store.load(&key)).await {
        Ok(Some((m, record))) if m.status == Status::Finished => HttpResponse::Ok()
            .content_type("application/json")
            .body(record.to_json()),
        Ok(Some(_)) => refused(&Refusal::new(
            ErrorCode::MatchNotOver,
            "the record (with its seed) is public once the match is over",
        )),
        Ok(None) => refused(&no_such_match(&id)),
        Err(r) => refused(&r),
    }
}

/// The page at `/api`: how to play through the API (and, when the build
/// embedded no web client, the page at `/`).
pub(crate) const API_HTML: &str = r#"<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Chapaev online</title>
<style>body{font-family:sans-serif;max-width:50em;margin:2em auto;line-height:1.45;padding:0 1em}
code,pre{background:#f3f3f3}pre{padding:.6em;overflow-x:auto}</style></head>
<body>
<h1>Chapaev online</h1>
<p>Russian flick-checkers on an exact physics engine. <a href="/">Play in the browser</a>;
this page is about playing through the API, by hand or with a bot of your own, in any language.
The full protocol is in <code>docs/protocol.md</code>.</p>
<h2>1. Create a match</h2>
<pre>curl -s -XPOST localhost:8080/api/matches -d '{"name":"Petka"}'
curl -s -XPOST localhost:8080/api/matches -d '{"name":"Petka","opponent":"bot","bot_level":"hard"}'
curl -s -XPOST localhost:8080/api/matches -d '{"name":"MyBot","rules":"standard"}'</pre>
<p>Computer levels: <code>easy</code>, <code>medium</code>, <code>hard</code>, <code>adaptive</code> (tunes its hand to keep the match even). Rules: <code>casual</code> (the default: shots
played as aimed) or <code>standard</code> (competitive play and bot against bot: execution noise on every shot and
the pie rule). A casual match may take a public <code>"seed":N</code>: the same noise as
<code>bots match --seed N</code> draws locally, known to anyone (its summary shows the seed).</p>
<p>The answer holds the <code>match_id</code>, your <code>seat</code> and a secret <code>token</code>:
only that token can shoot for your seat. Share the match id (never the token) with your opponent.</p>
<h2>2. Join the empty seat</h2>
<pre>curl -s -XPOST localhost:8080/api/matches/MATCH_ID/join -d '{"name":"Anka"}'</pre>
<h2>3. Play over the WebSocket</h2>
<pre>websocat 'ws://localhost:8080/ws?match=MATCH_ID'
{"type":"hello","protocol":1,"name":"Petka","token":"TOKEN"}</pre>
<p>The first message is a <code>hello</code> carrying your token (never put it in the URL); the server
answers <code>welcome</code>, then the whole <code>match-state</code>, then every update.
Shoot by sending <code>{"type":"shot","piece":4,"velocity":[0.0,2.0]}</code>: pieces 0&ndash;7 are White's
(files a&ndash;h), 8&ndash;15 Black's; velocity in m/s on a 0.32 m board, at most 2 m/s.
Also: <code>{"type":"resign"}</code>, <code>{"type":"chat","text":"..."}</code>,
<code>{"type":"offer-rematch"}</code>, <code>{"type":"accept-rematch"}</code>,
<code>{"type":"pie-decision","swap":true}</code>. A hello without a token watches.</p>
<p>Each turn has a clock: miss it and the turn passes; three misses in a row forfeit.
A dropped player keeps the seat for a grace period and reconnects with the same token.</p>
<h2>Other endpoints</h2>
<ul><li><code>GET /</code> &mdash; the game in the browser; <code>GET /api</code> &mdash; this page</li>
<li><code>GET /api/matches?status=open|live|finished</code> &mdash; list matches</li>
<li><code>GET /api/matches/ID</code> &mdash; one match's summary</li>
<li><code>GET /api/matches/ID/socket</code> &mdash; where to open the match's WebSocket: <code>{"url": null}</code> (this server's <code>/ws</code>) or, on a cluster, the socket of the node that plays it</li>
<li><code>GET /api/matches/ID/record</code> &mdash; the record of a finished match, for replay</li>
<li><code>POST /api/exhibitions</code> with <code>{"first":"medium","second":"hard"}</code> &mdash; two computer
levels play each other (standard rules) for anyone to watch</li>
<li><code>POST /api/simulate</code> with <code>{"board":[...],"piece":4,"velocity":[0,2]}</code> &mdash; one shot on any
position with the server's exact physics (for bots in any language; limited per address)</li>
<li><code>GET /api/schema/v1.json</code> &mdash; the JSON Schema of every message</li>
<li><code>GET /healthz</code>, <code>GET /metrics</code> (Prometheus)</li></ul>
</body></html>
"#;
