//! The HTTP API of [`crate::accounts`]: creating an account (a person's or
//! a bot's), reading anyone's profile, proving one's own with the key in an
//! `Authorization: Bearer KEY` header, making a further key or revoking the
//! one presented, and the leaderboards of people and of bots. Creating
//! accounts shares the per-address limit on creating matches.

use crate::accounts::{AccountError, AccountName, Profile, MAX_LEADERBOARD};
use crate::http::{blocking_with, json, read_body, refused, Creations};
use crate::hub::Hub;
use crate::token::SeatToken;
use actix_web::http::StatusCode;
use actix_web::{web, HttpRequest, HttpResponse};
use game::protocol::{ErrorCode, Refusal};
use serde::{Deserialize, Serialize};

/// Registers the account routes.
pub fn routes(cfg: &mut web::ServiceConfig) {
    cfg.route("/api/accounts", web::post().to(create))
        .route("/api/accounts/me", web::get().to(me))
        .route("/api/accounts/me/keys", web::post().to(add_key))
        .route("/api/accounts/me/keys/current", web::delete().to(revoke))
        .route("/api/accounts/{name}", web::get().to(profile))
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

/// Runs an account operation on a blocking thread.
async fn run<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, AccountError> + Send + 'static,
) -> Result<T, Refusal> {
    blocking_with(f, |e| match e {
        AccountError::Refused(r) => Ok(r),
        AccountError::Store(e) => Err(e.to_string()),
        AccountError::Random(e) => Err(e.to_string()),
    })
    .await
}

/// The key in the request's `Authorization: Bearer` header.
fn bearer(req: &HttpRequest) -> Result<SeatToken, Refusal> {
    let no_key = || {
        Refusal::new(
            ErrorCode::BadKey,
            "send the account key as 'Authorization: Bearer KEY'",
        )
    };
    let header = req
        .headers()
        .get(actix_web::http::header::AUTHORIZATION)
        .ok_or_else(no_key)?;
    let text = header.to_str().map_err(|_| no_key())?;
    let key = text.strip_prefix("Bearer ").ok_or_else(no_key)?.trim();
    if key.is_empty() || key.len() > 128 {
        return Err(no_key());
    }
    Ok(SeatToken::new(key))
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
        let made = WithKey::from(run(move || store.create_account(&name, body.bot)).await?);
        tracing::info!(account = %made.account.name, bot = made.account.bot, "account created");
        Ok(made)
    };
    answer(StatusCode::CREATED, made.await)
}

async fn me(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let found = async {
        let key = bearer(&req)?;
        let store = hub.store().clone();
        run(move || store.account_of_key(&key)).await
    };
    answer(StatusCode::OK, found.await)
}

async fn add_key(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let made = async {
        let key = bearer(&req)?;
        let store = hub.store().clone();
        Ok(WithKey::from(run(move || store.add_key(&key)).await?))
    };
    answer(StatusCode::CREATED, made.await)
}

async fn revoke(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let done = async {
        let key = bearer(&req)?;
        let store = hub.store().clone();
        run(move || store.revoke_key(&key)).await
    };
    match done.await {
        Ok(()) => HttpResponse::NoContent().finish(),
        Err(r) => refused(&r),
    }
}

async fn profile(hub: web::Data<Hub>, name: web::Path<String>) -> HttpResponse {
    let name = name.into_inner();
    let found = async {
        let store = hub.store().clone();
        let wanted = name.clone();
        run(move || Ok(store.account(&wanted)?))
            .await?
            .ok_or_else(|| Refusal::new(ErrorCode::NoSuchAccount, format!("no account {name}")))
    };
    answer(StatusCode::OK, found.await)
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
        run(move || Ok(store.leaderboard(q.bots, limit)?)).await
    };
    answer(StatusCode::OK, listed.await)
}
