//! The server's HTTP API as the client uses it: create a match (against a
//! person or a bot, rated or not), join one, list matches, fetch a finished
//! match's record, and the accounts (create one, check a key, a profile,
//! the leaderboard, an account's rating history and matches). Calls made
//! for a signed-in player carry its key (`Authorization: Bearer`). Each
//! call is a [`Pending`] the screen polls every frame until it yields a
//! typed answer or the server's error message.

use crate::i18n::t;
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

/// A seat's rating in a listing (a seat without an account has none).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
pub struct SeatRating {
    pub rating: f64,
    pub provisional: bool,
}

/// One match in a listing. The fields a server may not send yet default:
/// not rated, no ratings, playable.
#[derive(Clone, Debug, Deserialize)]
pub struct Summary {
    pub match_id: String,
    pub first: Option<String>,
    pub second: Option<String>,
    pub bot: Option<String>,
    pub shots: u32,
    pub result: Option<MatchResult>,
    #[serde(default)]
    pub rated: bool,
    #[serde(default)]
    pub first_rating: Option<SeatRating>,
    #[serde(default)]
    pub second_rating: Option<SeatRating>,
    /// Whether this server can play the match's physics version.
    #[serde(default = "playable_by_default")]
    pub playable: bool,
}

fn playable_by_default() -> bool {
    true
}

/// Where to open a match's socket (`GET /api/matches/{id}/socket`): the
/// socket of the node of a cluster that plays it, or `None` (the page's
/// own node).
#[derive(Clone, Debug, Deserialize)]
pub struct SocketAt {
    #[serde(default)]
    pub url: Option<String>,
}

/// A listing: `{"matches": [...]}` or the bare array.
#[derive(Deserialize)]
#[serde(untagged)]
enum Listing {
    Wrapped { matches: Vec<Summary> },
    Bare(Vec<Summary>),
}

/// An account as the server shows it (PROFILE in `docs/protocol.md`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Profile {
    pub name: String,
    pub bot: bool,
    #[serde(default)]
    pub created_at: u64,
    pub rating: f64,
    pub deviation: f64,
    pub provisional: bool,
    pub games: u32,
}

/// A new account and the key that proves it (shown this once).
#[derive(Clone, Debug, Deserialize)]
pub struct Created {
    pub account: Profile,
    pub key: String,
}

/// One point of an account's rating over time (one per rated match).
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct HistoryPoint {
    pub match_id: String,
    pub at: u64,
    pub rating: f64,
    pub deviation: f64,
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
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    rated: bool,
}

/// A request in flight whose answer is read as `T`.
pub struct Pending<T> {
    request: Request,
    parse: fn(&str) -> Result<T, String>,
    /// The HTTP status, once answered.
    status: Option<u16>,
    _t: PhantomData<T>,
}

fn json<T: DeserializeOwned>(body: &str) -> Result<T, String> {
    serde_json::from_str(body).map_err(|e| t!("api-unexpected-answer", error = e.to_string()))
}

fn listing(body: &str) -> Result<Vec<Summary>, String> {
    json::<Listing>(body).map(|l| match l {
        Listing::Wrapped { matches } | Listing::Bare(matches) => matches,
    })
}

impl<T> Pending<T> {
    fn start(
        method: &str,
        url: &str,
        body: Option<&str>,
        key: Option<&str>,
        parse: fn(&str) -> Result<T, String>,
    ) -> Pending<T> {
        let auth = key.map(|k| format!("Bearer {k}"));
        Pending {
            request: Request::start(method, url, body, auth.as_deref()),
            parse,
            status: None,
            _t: PhantomData,
        }
    }

    /// The answer once it has come: the value, or a message for the player.
    pub fn poll(&mut self) -> Option<Result<T, String>> {
        Some(match self.request.poll()? {
            HttpReply::Done { status, body } if (200..300).contains(&status) => {
                self.status = Some(status);
                (self.parse)(&body)
            }
            HttpReply::Done { status, body } => {
                self.status = Some(status);
                Err(error_text(status, &body))
            }
            HttpReply::Failed(e) => Err(t!("api-unreachable", error = e)),
        })
    }

    /// The HTTP status of the answer (`None` before it, or when the
    /// server was not reached).
    pub fn status(&self) -> Option<u16> {
        self.status
    }
}

/// The server's error message, or the status if the body is not one.
fn error_text(status: u16, body: &str) -> String {
    match ServerMessage::from_json(body) {
        Ok(ServerMessage::Error { code, message }) => format!("{message} ({code})"),
        _ => t!("api-status", status = status),
    }
}

/// The API of the server at `origin` (`http://host:port`), for the
/// signed-in player with `key` (none: anonymous).
#[derive(Clone, Debug)]
pub struct Api {
    pub origin: String,
    pub key: Option<String>,
}

impl Api {
    /// A new match; `rated` asks for a rated one (the server needs the key).
    pub fn create(&self, name: &str, opponent: Opponent, rated: bool) -> Pending<SeatGrant> {
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
            rated,
        };
        let text = serde_json::to_string(&body).unwrap_or_else(|_| "{}".into());
        Pending::start(
            "POST",
            &format!("{}/api/matches", self.origin),
            Some(&text),
            self.key.as_deref(),
            json,
        )
    }

    pub fn join(&self, match_id: &str, name: &str) -> Pending<SeatGrant> {
        let text = serde_json::json!({ "name": name }).to_string();
        let url = format!("{}/api/matches/{match_id}/join", self.origin);
        Pending::start("POST", &url, Some(&text), self.key.as_deref(), json)
    }

    /// Matches with `status` `open`, `live` or `finished`, newest first.
    pub fn list(&self, status: &str, limit: usize) -> Pending<Vec<Summary>> {
        let url = format!("{}/api/matches?status={status}&limit={limit}", self.origin);
        Pending::start("GET", &url, None, None, listing)
    }

    /// `GET /api/matches/{id}`: one match's summary (its players).
    pub fn summary(&self, match_id: &str) -> Pending<Summary> {
        let url = format!("{}/api/matches/{match_id}", self.origin);
        Pending::start("GET", &url, None, None, json)
    }

    /// `GET /api/matches/{id}/socket`: where to open the match's socket.
    pub fn socket(&self, match_id: &str) -> Pending<SocketAt> {
        let url = format!("{}/api/matches/{match_id}/socket", self.origin);
        Pending::start("GET", &url, None, None, json)
    }

    /// `GET /api/matches/{id}/record`: the record's JSON text.
    pub fn record(&self, match_id: &str) -> Pending<String> {
        let url = format!("{}/api/matches/{match_id}/record", self.origin);
        Pending::start("GET", &url, None, None, |b| Ok(b.to_string()))
    }

    /// A new person's account named `name`, and its key.
    pub fn create_account(&self, name: &str) -> Pending<Created> {
        let text = serde_json::json!({ "name": name, "bot": false }).to_string();
        let url = format!("{}/api/accounts", self.origin);
        Pending::start("POST", &url, Some(&text), None, json)
    }

    /// The account that `key` proves (`401` if none).
    pub fn me(&self, key: &str) -> Pending<Profile> {
        let url = format!("{}/api/accounts/me", self.origin);
        Pending::start("GET", &url, None, Some(key), json)
    }

    /// The account named `name`.
    pub fn account(&self, name: &str) -> Pending<Profile> {
        let url = format!("{}/api/accounts/{name}", self.origin);
        Pending::start("GET", &url, None, None, json)
    }

    /// The people's (or the bots') accounts, best first.
    pub fn leaderboard(&self, bots: bool, limit: usize) -> Pending<Vec<Profile>> {
        let url = format!("{}/api/leaderboard?bots={bots}&limit={limit}", self.origin);
        Pending::start("GET", &url, None, None, json)
    }

    /// The rating of account `name` after each of its rated matches, oldest first.
    pub fn history(&self, name: &str) -> Pending<Vec<HistoryPoint>> {
        let url = format!("{}/api/accounts/{name}/history", self.origin);
        Pending::start("GET", &url, None, None, json)
    }

    /// The matches of account `name`, newest first.
    pub fn account_matches(&self, name: &str, limit: usize) -> Pending<Vec<Summary>> {
        let url = format!("{}/api/accounts/{name}/matches?limit={limit}", self.origin);
        Pending::start("GET", &url, None, None, listing)
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
        assert!(!l[0].rated && l[0].playable, "missing fields default");
        assert_eq!(l[0].first_rating, None);
    }

    #[test]
    fn a_listing_reads_ratings_rated_and_playable_and_a_bare_array() {
        let body = r#"[{"match_id":"ab","first":"Petka","second":null,"bot":"easy","shots":0,
            "result":null,"rated":true,"playable":false,
            "first_rating":{"rating":1523,"provisional":false},"second_rating":null}]"#;
        let l = listing(body).unwrap();
        assert!(l[0].rated && !l[0].playable);
        assert_eq!(
            l[0].first_rating,
            Some(SeatRating {
                rating: 1523.0,
                provisional: false
            })
        );
    }

    #[test]
    fn a_profile_and_a_history_read_the_servers_fields() {
        let p: Profile = json(
            r#"{"name":"Furmanov","bot":true,"created_at":1764000000,
            "rating":1500,"deviation":500,"provisional":true,"games":0}"#,
        )
        .unwrap();
        assert_eq!(
            (p.name.as_str(), p.rating, p.provisional),
            ("Furmanov", 1500.0, true)
        );
        let h: Vec<HistoryPoint> =
            json(r#"[{"match_id":"ab","at":5,"rating":1540,"deviation":300}]"#).unwrap();
        assert_eq!(h[0].rating, 1540.0);
    }
}
