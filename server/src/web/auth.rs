//! Who a request proves to be: the account whose key it carries in an
//! `Authorization: Bearer KEY` header, if any. A bot's key is refused when
//! it comes from a web page, so that a page's scripts never play as a bot.

use crate::play::hub::Hub;
use crate::store::Profile;
use crate::token::SeatToken;
use crate::web::blocking::run_account;
use actix_web::HttpRequest;
use game::protocol::{ErrorCode, Refusal};

fn no_key() -> Refusal {
    Refusal::new(
        ErrorCode::BadKey,
        "send the account key as 'Authorization: Bearer KEY'",
    )
}

/// The key in the request's `Authorization: Bearer` header.
fn bearer(req: &HttpRequest) -> Result<SeatToken, Refusal> {
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

/// Whether a request comes from a web page: browsers send `Origin` with
/// every request that can change something, and `Sec-Fetch-Site` with all
/// of them; bot processes send neither.
pub(crate) fn from_browser(req: &HttpRequest) -> bool {
    let h = req.headers();
    h.contains_key(actix_web::http::header::ORIGIN) || h.contains_key("sec-fetch-site")
}

/// The account the request's `Authorization: Bearer KEY` proves, and the
/// key; `Ok(None)` without the header. A bot's key sent from a web page is
/// refused (`bot-key-in-browser`): a page's scripts are not the bot.
pub async fn signed_in(
    req: &HttpRequest,
    hub: &Hub,
) -> Result<Option<(SeatToken, Profile)>, Refusal> {
    if !req
        .headers()
        .contains_key(actix_web::http::header::AUTHORIZATION)
    {
        return Ok(None);
    }
    let key = bearer(req)?;
    let account = account_of_key(hub, key.clone(), from_browser(req)).await?;
    Ok(Some((key, account)))
}

/// The account `key` proves, from a request that came from a web page or
/// not: a bot's key from a page is refused (`bot-key-in-browser`).
pub(crate) async fn account_of_key(
    hub: &Hub,
    key: SeatToken,
    browser: bool,
) -> Result<Profile, Refusal> {
    let store = hub.store().clone();
    let account = run_account(move || store.account_of_key(&key)).await?;
    if account.bot && browser {
        return Err(Refusal::new(
            ErrorCode::BotKeyInBrowser,
            "a bot's key is for its bot process, not for a web page",
        ));
    }
    Ok(account)
}

/// [`signed_in`], the header required.
pub(crate) async fn proven(req: &HttpRequest, hub: &Hub) -> Result<(SeatToken, Profile), Refusal> {
    signed_in(req, hub).await?.ok_or_else(no_key)
}
