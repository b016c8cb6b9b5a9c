//! The lobby's state without drawing or I/O: the name typed, the id to
//! join, the three match lists (open, live, finished) and when they were
//! last asked for, the message shown, the signed-in account with its
//! profile and whether new matches are rated. The screen starts the
//! requests and feeds their answers here; how a listed match reads
//! ([`describe`]) and whether it gets a button ([`offered`]) are decided
//! here too.

use crate::account::{self, Account};
use crate::api::{Profile, SeatGrant, Summary};
use crate::i18n::t;
use game::Side;

/// Seconds between refreshes of the match lists.
const REFRESH_SECONDS: f64 = 5.0;

/// One of the three lists.
pub struct MatchList {
    /// The server's name for it (`open`, `live`, `finished`).
    pub status: &'static str,
    /// The message id of its title.
    pub title: &'static str,
    /// The message id of its rows' button.
    pub action: &'static str,
    /// The matches last listed.
    pub items: Vec<Summary>,
}

/// The lobby as it stands.
pub struct LobbyState {
    /// The name typed to play under.
    pub name: String,
    /// The match id typed to join.
    pub join_id: String,
    pub lists: [MatchList; 3],
    /// When the lists were last asked for.
    refreshed: f64,
    /// Seconds since the lobby opened.
    pub now: f64,
    pub message: Option<String>,
    /// The rules are open over the lobby.
    pub help: bool,
    /// The account this browser is signed in to, its profile once fetched.
    pub account: Option<Account>,
    pub profile: Option<Profile>,
    /// New matches are rated (signed in only).
    pub rated: bool,
    /// The server was out of reach when last asked: the computer is
    /// played offline, in the page.
    pub offline: bool,
}

impl LobbyState {
    /// A lobby for `name` (as last typed), signed in to `account` if any,
    /// asking for rated matches if `rated`; the lists are due at once.
    pub fn new(name: String, account: Option<Account>, rated: bool) -> LobbyState {
        let list = |status, title, action| MatchList {
            status,
            title,
            action,
            items: Vec::new(),
        };
        LobbyState {
            name,
            join_id: String::new(),
            lists: [
                list("open", "lobby-list-open", "join"),
                list("live", "lobby-list-live", "watch"),
                list("finished", "lobby-list-finished", "replay"),
            ],
            refreshed: f64::NEG_INFINITY,
            now: 0.0,
            message: None,
            help: false,
            account,
            profile: None,
            rated,
            offline: false,
        }
    }

    /// The name to play under.
    pub fn player_name(&self) -> String {
        clean_name(&self.name)
    }

    /// Whether a new match is asked for rated (signed in with Rated on).
    pub fn rated_request(&self) -> bool {
        self.rated && self.account.is_some()
    }

    /// `dt` seconds went by.
    pub fn tick(&mut self, dt: f64) {
        self.now += dt;
    }

    /// Whether the lists are due to be asked for again (every few
    /// seconds); if so, they count as asked for now.
    pub fn refresh_due(&mut self) -> bool {
        if self.now - self.refreshed > REFRESH_SECONDS {
            self.refreshed = self.now;
            true
        } else {
            false
        }
    }

    /// The server answered for list `i`: its matches, or a message.
    pub fn listed(&mut self, i: usize, r: Result<Vec<Summary>, String>) {
        match r {
            Ok(items) => self.lists[i].items = items,
            Err(e) => self.message = Some(e),
        }
    }

    /// The server answered for the account's profile (`refused`: the key
    /// was refused). Whether the key must be forgotten: then the account
    /// is signed out here and the message says why.
    pub fn profile_answered(&mut self, r: Result<Profile, String>, refused: bool) -> bool {
        match r {
            Ok(profile) => self.profile = Some(profile),
            Err(e) if refused => {
                self.account = None;
                self.message = Some(t!("signed-out-because", reason = e));
                return true;
            }
            Err(e) => self.message = Some(e),
        }
        false
    }

    /// A new match was asked for.
    pub fn creating(&mut self) {
        self.message = Some(t!("lobby-creating"));
    }

    /// The server answered the new match: its seat, or a message.
    pub fn created(&mut self, r: Result<SeatGrant, String>) -> Option<SeatGrant> {
        r.map_err(|e| self.message = Some(e)).ok()
    }

    /// How a request to the server ended (`status`: its HTTP status;
    /// `None`: no answer at all). Whether the server is out of reach now
    /// (no answer, or a gateway's 502 to 504 in front of a server that is
    /// down): then the lobby says so, and plays the computer offline until
    /// the server answers again.
    pub fn heard(&mut self, status: Option<u16>) -> bool {
        let out_of_reach = matches!(status, None | Some(502..=504));
        if out_of_reach {
            self.message = Some(t!("lobby-server-unreachable"));
        } else if self.offline {
            self.message = None;
        }
        self.offline = out_of_reach;
        out_of_reach
    }

    /// Turns Rated over; what to remember ("on" or "off").
    pub fn toggle_rated(&mut self) -> &'static str {
        self.rated = !self.rated;
        if self.rated {
            "on"
        } else {
            "off"
        }
    }

    /// Signed out by the player.
    pub fn signed_out(&mut self) {
        self.account = None;
        self.profile = None;
    }

    /// The match to join by the id typed, if it is one (letters and digits).
    pub fn join_target(&self) -> Option<String> {
        let id = self.join_id.trim().to_string();
        let ok = !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric());
        ok.then_some(id)
    }
}

/// A name the server accepts: trimmed, at most 40 characters, `Player` if empty.
pub fn clean_name(n: &str) -> String {
    let n: String = n
        .trim()
        .chars()
        .filter(|c| !c.is_control())
        .take(40)
        .collect();
    if n.is_empty() {
        t!("player-default-name")
    } else {
        n
    }
}

/// A match in two lines: who plays whom (with their ratings where the
/// seats have them), then how it stands.
pub fn describe(s: &Summary) -> (String, String) {
    // The bot column: the second seat's level, or `FIRST/SECOND` for an
    // exhibition (both seats the computer).
    let levels = s.bot.as_deref().map(|b| match b.split_once('/') {
        Some((a, b)) => (Some(a), b),
        None => (None, b),
    });
    let computer = |level: &str| t!("computer-level", level = level_name(level));
    let first = match levels {
        Some((Some(level), _)) => account::with_rating(&computer(level), s.first_rating),
        _ => account::with_rating(s.first.as_deref().unwrap_or("?"), s.first_rating),
    };
    let second = match (&s.second, levels) {
        (_, Some((_, level))) if !level.is_empty() => {
            account::with_rating(&computer(level), s.second_rating)
        }
        (Some(n), _) => account::with_rating(n, s.second_rating),
        (None, _) => "...".to_string(),
    };
    let mut facts = Vec::new();
    if s.rated {
        facts.push(t!("lobby-fact-rated"));
    }
    if !s.playable {
        facts.push(t!("lobby-fact-not-playable"));
    }
    match s.result {
        Some(r) => match r.winner() {
            Some(Side::White) => facts.push(t!("lobby-fact-white-won")),
            Some(Side::Black) => facts.push(t!("lobby-fact-black-won")),
            None => facts.push(t!("lobby-fact-drawn")),
        },
        None if s.second.is_none() && s.bot.is_none() => facts.push(t!("lobby-fact-waiting")),
        None => {}
    }
    facts.push(t!("shots-count", count = s.shots));
    (
        t!("lobby-versus", first = first, second = second),
        facts.join(" · "),
    )
}

/// The computer's level (`easy`, `medium`, `hard`, `adaptive`) in words;
/// a level this client does not know shows as the server named it.
pub fn level_name(level: &str) -> String {
    match level {
        "easy" => t!("level-easy"),
        "medium" => t!("level-medium"),
        "hard" => t!("level-hard"),
        "adaptive" => t!("level-adaptive"),
        other => other.to_string(),
    }
}

/// Whether a match in the list of `status` gets its button: a match this
/// server cannot play (another physics version) is neither joined nor
/// watched, only replayed once finished.
pub fn offered(status: &str, s: &Summary) -> bool {
    s.playable || status == "finished"
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(json: serde_json::Value) -> Summary {
        serde_json::from_value(json).expect("a summary")
    }

    #[test]
    fn a_server_out_of_reach_turns_the_lobby_offline_until_it_answers_again() {
        let mut s = LobbyState::new("Petka".into(), None, false);
        assert!(!s.offline);
        assert!(s.heard(None), "no answer at all");
        assert!(s.offline);
        assert_eq!(s.message, Some(t!("lobby-server-unreachable")));
        assert!(s.heard(Some(503)), "the gateway of a server that is down");
        assert!(!s.heard(Some(200)));
        assert!(!s.offline);
        assert_eq!(s.message, None);
        // A refusal is an answer: the server is there.
        assert!(!s.heard(Some(400)));
        assert!(!s.offline);
    }

    #[test]
    fn an_exhibition_names_both_computers_by_their_levels() {
        let s = summary(serde_json::json!({
            "match_id": "x", "status": "live", "created_at": 0, "updated_at": 0,
            "first": "bot (medium)", "second": "bot (hard)", "bot": "medium/hard",
            "shots": 3, "turn_seconds": 30, "result": null, "physics": 1, "playable": true
        }));
        assert_eq!(describe(&s).0, "computer (medium) vs computer (hard)");
    }

    #[test]
    fn a_rated_match_shows_each_seats_rating_and_is_marked_rated() {
        let s = summary(serde_json::json!({
            "match_id": "ab", "first": "Petka", "second": null, "bot": "hard", "shots": 2,
            "result": null, "rated": true,
            "first_rating": {"rating": 1523, "provisional": false},
            "second_rating": {"rating": 1500, "provisional": true}}));
        let (names, facts) = describe(&s);
        assert_eq!(names, "Petka (1523) vs computer (hard) (1500?)");
        assert_eq!(facts, "rated · 2 shots");
    }

    #[test]
    fn a_match_this_server_cannot_play_is_only_replayed() {
        let s = summary(serde_json::json!({
            "match_id": "ab", "first": "Anka", "second": "Petka", "bot": null, "shots": 0,
            "result": null, "playable": false}));
        assert!(!offered("open", &s) && !offered("live", &s));
        assert!(offered("finished", &s));
        assert_eq!(describe(&s).1, "not playable here · 0 shots");
        let playable = summary(serde_json::json!({
            "match_id": "ab", "first": "Anka", "second": null, "bot": null, "shots": 0,
            "result": null}));
        assert!(offered("open", &playable));
        assert_eq!(describe(&playable).0, "Anka vs ...");
    }

    fn petka() -> Account {
        Account {
            name: "Petka".into(),
            key: "k".into(),
        }
    }

    fn listing(ids: &[&str]) -> Vec<Summary> {
        ids.iter()
            .map(|id| {
                summary(serde_json::json!({
                    "match_id": id, "first": "Anka", "second": null, "bot": null,
                    "shots": 0, "result": null}))
            })
            .collect()
    }

    #[test]
    fn the_lists_are_due_at_once_then_every_five_seconds() {
        let mut s = LobbyState::new(String::new(), None, true);
        assert!(s.refresh_due());
        assert!(!s.refresh_due());
        s.tick(4.9);
        assert!(!s.refresh_due());
        s.tick(0.2);
        assert!(s.refresh_due());
        s.tick(1.0);
        assert!(!s.refresh_due());
    }

    #[test]
    fn an_answer_fills_its_list_and_an_error_only_sets_the_message() {
        let mut s = LobbyState::new(String::new(), None, true);
        s.listed(1, Ok(listing(&["a", "b"])));
        let ids = |s: &LobbyState, i: usize| -> Vec<String> {
            s.lists[i]
                .items
                .iter()
                .map(|m| m.match_id.clone())
                .collect()
        };
        assert_eq!(ids(&s, 1), ["a", "b"]);
        assert!(s.lists[0].items.is_empty() && s.message.is_none());
        s.listed(1, Err("server down".into()));
        assert_eq!(ids(&s, 1), ["a", "b"], "the last listing stays");
        assert_eq!(s.message.as_deref(), Some("server down"));
        let statuses: Vec<&str> = s.lists.iter().map(|l| l.status).collect();
        assert_eq!(statuses, ["open", "live", "finished"]);
    }

    #[test]
    fn a_refused_key_signs_out_and_other_profile_errors_only_say_so() {
        let mut s = LobbyState::new(String::new(), Some(petka()), true);
        assert!(s.rated_request());
        assert!(!s.profile_answered(Err("busy".into()), false));
        assert_eq!(s.account, Some(petka()));
        assert_eq!(s.message.as_deref(), Some("busy"));
        assert!(s.profile_answered(Err("unknown key".into()), true));
        assert_eq!(s.account, None);
        assert_eq!(s.message.as_deref(), Some("signed out: unknown key"));
        assert!(!s.rated_request(), "rated only while signed in");
    }

    #[test]
    fn a_fetched_profile_is_kept_until_signing_out() {
        let mut s = LobbyState::new(String::new(), Some(petka()), false);
        let profile: Profile = serde_json::from_value(serde_json::json!({
            "name": "Petka", "bot": false, "rating": 1523.0, "deviation": 80.0,
            "provisional": false, "games": 12}))
        .expect("a profile");
        assert!(!s.profile_answered(Ok(profile.clone()), false));
        assert_eq!(s.profile, Some(profile));
        s.signed_out();
        assert!(s.account.is_none() && s.profile.is_none());
    }

    #[test]
    fn rated_turns_over_and_says_what_to_remember() {
        let mut s = LobbyState::new(String::new(), Some(petka()), true);
        assert_eq!(s.toggle_rated(), "off");
        assert!(!s.rated && !s.rated_request());
        assert_eq!(s.toggle_rated(), "on");
        assert!(s.rated_request());
    }

    #[test]
    fn a_new_match_says_it_is_coming_and_a_refusal_says_why() {
        let mut s = LobbyState::new("  Anka ".into(), None, true);
        assert_eq!(s.player_name(), "Anka");
        s.creating();
        assert_eq!(s.message.as_deref(), Some("creating the match..."));
        assert!(s.created(Err("too many matches".into())).is_none());
        assert_eq!(s.message.as_deref(), Some("too many matches"));
        let grant: SeatGrant =
            serde_json::from_value(serde_json::json!({"match_id": "m1", "token": "t"}))
                .expect("a grant");
        assert_eq!(
            s.created(Ok(grant)).map(|g| g.match_id).as_deref(),
            Some("m1")
        );
    }

    #[test]
    fn only_letters_and_digits_make_an_id_to_join() {
        let mut s = LobbyState::new(String::new(), None, true);
        for (typed, target) in [
            ("", None),
            ("   ", None),
            (" ab12 ", Some("ab12")),
            ("ab-12", None),
            ("../x", None),
        ] {
            s.join_id = typed.into();
            assert_eq!(s.join_target().as_deref(), target, "{typed:?}");
        }
        assert_eq!(clean_name("   "), "Player");
        assert_eq!(clean_name(&"x".repeat(50)).len(), 40);
    }
}
