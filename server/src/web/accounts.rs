//! The HTTP API of [`crate::accounts`]: creating an account (a person's or
//! a bot's), reading anyone's profile, proving one's own with the key in an
//! `Authorization: Bearer KEY` header, making a further key or revoking the
//! one presented, and the leaderboards of people and of bots. Creating
//! accounts shares the per-address limit on creating matches.

use crate::play::hub::Hub;
use crate::store::MAX_LISTED;
use crate::store::{Profile, MAX_LEADERBOARD};
use crate::token::SeatToken;
use crate::web::auth::proven;
use crate::web::blocking::run_account;
use crate::web::reply::{json, read_body, refused, Creations};
use actix_web::http::StatusCode;
use actix_web::{web, HttpRequest, HttpResponse};
use game::name::AccountName;
use game::protocol::{ErrorCode, Refusal};
use serde::{Deserialize, Serialize};

/// Registers the account routes.
pub fn routes(cfg: &mut web::ServiceConfig) {
    cfg.route("/api/accounts", web::post().to(create))
        .route("/api/accounts/me", web::get().to(me))
        .route("/api/accounts/me/keys", web::post().to(add_key))
        .route("/api/accounts/me/keys/current", web::delete().to(revoke))
        .route("/api/accounts/me/password", web::put().to(set_password))
        .route("/api/accounts/sign-in", web::post().to(sign_in))
        .route("/api/accounts/{name}", web::get().to(profile))
        .route("/api/accounts/{name}/history", web::get().to(history))
        .route("/api/accounts/{name}/matches", web::get().to(matches))
        .route("/api/leaderboard", web::get().to(leaderboard));
}

/// `POST /api/accounts`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct CreateBody {
    name: String,
    /// A bot's account (default: a person's).
    #[serde(default)]
    bot: bool,
}

/// An account with a key for it (shown once).
#[derive(Debug, Serialize)]
struct WithKey {
    account: Profile,
    /// The secret key: `Authorization: Bearer KEY` proves the account.
    key: String,
}

impl From<(Profile, SeatToken)> for WithKey {
    fn from((account, key): (Profile, SeatToken)) -> WithKey {
        WithKey {
            account,
            key: key.expose().to_string(),
        }
    }
}

fn answer<T: Serialize>(status: StatusCode, r: Result<T, Refusal>) -> HttpResponse {
    match r {
        Ok(body) => json(status, &body),
        Err(refusal) => refused(&refusal),
    }
}

async fn create(
    req: HttpRequest,
    hub: web::Data<Hub>,
    creations: web::Data<Creations>,
    bytes: web::Bytes,
) -> HttpResponse {
    let made = async {
        creations.check(&req)?;
        let body: CreateBody = read_body(&bytes)?;
        let name = AccountName::parse(body.name.trim())?;
        let store = hub.store().clone();
        let made = WithKey::from(run_account(move || store.create_account(&name, body.bot)).await?);
        tracing::info!(account = %made.account.name, bot = made.account.bot, "account created");
        Ok(made)
    };
    answer(StatusCode::CREATED, made.await)
}

async fn me(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let found = async { Ok(proven(&req, &hub).await?.1) };
    answer(StatusCode::OK, found.await)
}

async fn add_key(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let made = async {
        let (key, _) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        Ok(WithKey::from(
            run_account(move || store.add_key(&key)).await?,
        ))
    };
    answer(StatusCode::CREATED, made.await)
}

/// `PUT /api/accounts/me/password`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PasswordBody {
    password: String,
}

async fn set_password(req: HttpRequest, hub: web::Data<Hub>, bytes: web::Bytes) -> HttpResponse {
    let done = async {
        let body: PasswordBody = read_body(&bytes)?;
        let (key, _) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        run_account(move || store.set_password(&key, &body.password)).await
    };
    match done.await {
        Ok(()) => HttpResponse::NoContent().finish(),
        Err(r) => refused(&r),
    }
}

/// `POST /api/accounts/sign-in`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SignInBody {
    name: String,
    password: String,
}

/// Signs in with a password: a new key. Attempts share the per-address
/// limit on creating matches and accounts, so passwords cannot be tried
/// fast.
async fn sign_in(
    req: HttpRequest,
    hub: web::Data<Hub>,
    creations: web::Data<Creations>,
    bytes: web::Bytes,
) -> HttpResponse {
    let made = async {
        creations.check(&req)?;
        let body: SignInBody = read_body(&bytes)?;
        let store = hub.store().clone();
        let made = run_account(move || store.sign_in(body.name.trim(), &body.password)).await?;
        Ok(WithKey::from(made))
    };
    answer(StatusCode::CREATED, made.await)
}

async fn revoke(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let done = async {
        let (key, _) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        run_account(move || store.revoke_key(&key)).await
    };
    match done.await {
        Ok(()) => HttpResponse::NoContent().finish(),
        Err(r) => refused(&r),
    }
}

/// The account named `name`, or `no-such-account`.
async fn existing(hub: &Hub, name: String) -> Result<Profile, Refusal> {
    let store = hub.store().clone();
    let wanted = name.clone();
    run_account(move || Ok(store.account(&wanted)?))
        .await?
        .ok_or_else(|| Refusal::new(ErrorCode::NoSuchAccount, format!("no account {name}")))
}

async fn profile(hub: web::Data<Hub>, name: web::Path<String>) -> HttpResponse {
    answer(StatusCode::OK, existing(&hub, name.into_inner()).await)
}

/// `?limit=N` of an account's listings.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ListingQuery {
    limit: Option<usize>,
}

fn listing_limit(req: &HttpRequest) -> Result<usize, Refusal> {
    let q: ListingQuery = web::Query::from_query(req.query_string())
        .map(web::Query::into_inner)
        .map_err(|e| Refusal::new(ErrorCode::BadMessage, e.to_string()))?;
    Ok(q.limit.unwrap_or(MAX_LISTED).min(MAX_LISTED))
}

/// `GET /api/accounts/{name}/history`: the rating after each rated match.
async fn history(hub: web::Data<Hub>, name: web::Path<String>, req: HttpRequest) -> HttpResponse {
    let listed = async {
        let limit = listing_limit(&req)?;
        let account = existing(&hub, name.into_inner()).await?;
        let store = hub.store().clone();
        run_account(move || Ok(store.rating_history(&account.name, limit)?)).await
    };
    answer(StatusCode::OK, listed.await)
}

/// `GET /api/accounts/{name}/matches`: the matches it played, newest first.
async fn matches(hub: web::Data<Hub>, name: web::Path<String>, req: HttpRequest) -> HttpResponse {
    let listed = async {
        let limit = listing_limit(&req)?;
        let account = existing(&hub, name.into_inner()).await?;
        let store = hub.store().clone();
        run_account(move || Ok(store.matches_of(&account.name, limit)?)).await
    };
    answer(StatusCode::OK, listed.await)
}

/// `GET /api/leaderboard?bots=true&limit=N`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LeaderboardQuery {
    #[serde(default)]
    bots: bool,
    limit: Option<usize>,
}

async fn leaderboard(hub: web::Data<Hub>, req: HttpRequest) -> HttpResponse {
    let listed = async {
        let q: LeaderboardQuery = web::Query::from_query(req.query_string())
            .map(web::Query::into_inner)
            .map_err(|e| Refusal::new(ErrorCode::BadMessage, e.to_string()))?;
        let limit = q.limit.unwrap_or(MAX_LEADERBOARD);
        let store = hub.store().clone();
        run_account(move || Ok(store.leaderboard(q.bots, limit)?)).await
    };
    answer(StatusCode::OK, listed.await)
}
