//! The server's HTTP API as the client uses it: create a match (against a
//! person or a bot), join one, list matches, fetch a finished match's
//! record. Each call is a [`Pending`] the screen polls every frame until
//! it yields a typed answer or the server's error message.

use crate::platform::{HttpReply, Request};
use game::protocol::ServerMessage;
use game::MatchResult;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::marker::PhantomData;

/// A seat handed out by the server (`POST /api/matches`, `.../join`).
#[derive(Clone, Debug, Deserialize)]
pub struct SeatGrant {
    pub match_id: String,
    pub token: String,
}

/// One match in a listing.
#[derive(Clone, Debug, Deserialize)]
pub struct Summary {
    pub match_id: String,
    pub first: Option<String>,
    pub second: Option<String>,
    pub bot: Option<String>,
    pub shots: u32,
    pub result: Option<MatchResult>,
}

#[derive(Deserialize)]
struct Listing {
    matches: Vec<Summary>,
}

/// Who to play in a new match.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Opponent {
    Person,
    Bot(&'static str),
}

#[derive(Serialize)]
struct CreateBody<'a> {
    name: &'a str,
    opponent: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    bot_level: Option<&'static str>,
}

/// A request in flight whose answer is read as `T`.
pub struct Pending<T> {
    request: Request,
    parse: fn(&str) -> Result<T, String>,
    _t: PhantomData<T>,
}

fn json<T: DeserializeOwned>(body: &str) -> Result<T, String> {
    serde_json::from_str(body).map_err(|e| format!("unexpected answer from the server: {e}"))
}

fn listing(body: &str) -> Result<Vec<Summary>, String> {
    json::<Listing>(body).map(|l| l.matches)
}

impl<T> Pending<T> {
    fn start(
        method: &str,
        url: &str,
        body: Option<&str>,
        parse: fn(&str) -> Result<T, String>,
    ) -> Pending<T> {
        Pending {
            request: Request::start(method, url, body),
            parse,
            _t: PhantomData,
        }
    }

    /// The answer once it has come: the value, or a message for the player.
    pub fn poll(&mut self) -> Option<Result<T, String>> {
        Some(match self.request.poll()? {
            HttpReply::Done { status, body } if (200..300).contains(&status) => (self.parse)(&body),
            HttpReply::Done { status, body } => Err(error_text(status, &body)),
            HttpReply::Failed(e) => Err(format!("cannot reach the server ({e})")),
        })
    }
}

/// The server's error message, or the status if the body is not one.
fn error_text(status: u16, body: &str) -> String {
    match ServerMessage::from_json(body) {
        Ok(ServerMessage::Error { code, message }) => format!("{message} ({code})"),
        _ => format!("the server answered {status}"),
    }
}

/// The API of the server at `origin` (`http://host:port`).
#[derive(Clone, Debug)]
pub struct Api {
    pub origin: String,
}

impl Api {
    pub fn create(&self, name: &str, opponent: Opponent) -> Pending<SeatGrant> {
        let body = CreateBody {
            name,
            opponent: match opponent {
                Opponent::Person => "person",
                Opponent::Bot(_) => "bot",
            },
            bot_level: match opponent {
                Opponent::Person => None,
                Opponent::Bot(level) => Some(level),
            },
        };
        let text = serde_json::to_string(&body).unwrap_or_else(|_| "{}".into());
        Pending::start(
            "POST",
            &format!("{}/api/matches", self.origin),
            Some(&text),
            json,
        )
    }

    pub fn join(&self, match_id: &str, name: &str) -> Pending<SeatGrant> {
        let text = serde_json::json!({ "name": name }).to_string();
        let url = format!("{}/api/matches/{match_id}/join", self.origin);
        Pending::start("POST", &url, Some(&text), json)
    }

    /// Matches with `status` `open`, `live` or `finished`, newest first.
    pub fn list(&self, status: &str, limit: usize) -> Pending<Vec<Summary>> {
        let url = format!("{}/api/matches?status={status}&limit={limit}", self.origin);
        Pending::start("GET", &url, None, listing)
    }

    /// The record of a finished match, as its JSON text.
    pub fn record(&self, match_id: &str) -> Pending<String> {
        let url = format!("{}/api/matches/{match_id}/record", self.origin);
        Pending::start("GET", &url, None, |b| Ok(b.to_string()))
    }
}

/// Where this browser keeps its seat tokens (so a reload keeps the seat).
pub fn token_key(match_id: &str) -> String {
    format!("chapaev.token.{match_id}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_server_error_reads_as_its_message_and_code() {
        let body = r#"{"type":"error","code":"match-full","message":"both seats are taken"}"#;
        assert_eq!(error_text(409, body), "both seats are taken (match-full)");
        assert_eq!(error_text(502, "<html>"), "the server answered 502");
    }

    #[test]
    fn a_listing_reads_the_servers_summary_fields() {
        let body = r#"{"matches":[{"match_id":"ab","status":"live","created_at":1,"updated_at":2,
            "first":"Petka","second":null,"bot":"easy","shots":3,"turn_seconds":60,"result":null}]}"#;
        let l = listing(body).unwrap();
        assert_eq!(l.len(), 1);
        assert_eq!(l[0].first.as_deref(), Some("Petka"));
        assert_eq!(l[0].shots, 3);
    }
}
