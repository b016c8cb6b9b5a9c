//! The lobby: everything between accounts that is not one match — who is
//! online on the event stream, challenges (made, accepted, declined,
//! withdrawn, expired), quick pairing of seekers, and the bot ladder that
//! pairs online ladder bots (and the built-in computer levels) all day.
//!
//! A hosted bot (a bot account whose WebAssembly module the server plays
//! itself) is always online: it is on the ladder and accepts every
//! challenge at once, without a stream, as long as fewer than
//! [`LobbyLimits::max_hosted_seats`] seats are played by hosted bots.
//! Which hosted bots are mid-match comes from two places: the matches this
//! lobby started, and the store's unfinished matches as the driver reads
//! them with the hosted bots ([`Input::Hosted`]'s `busy`: the matches of
//! every node of a cluster, and those from before a restart).
//!
//! It is a state machine without I/O, like a match's session:
//! [`Lobby::handle`] takes an [`Input`] and the time, and returns the
//! [`Effect`]s for its driver to carry out (send a stream message, start a
//! match). The driver (`crate::web::stream` and the hub) owns the sockets, the
//! store and the timer; tests drive it with a virtual clock.

use crate::session::Moment;
use crate::stream::{ChallengeInfo, StreamClientMessage, StreamServerMessage};
use crate::{protocol::ErrorCode, protocol::Refusal, Preset, Side};
use std::collections::{BTreeMap, HashMap};
use std::time::Duration;

/// One event-stream connection, named by the driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct StreamId(pub u64);

/// The lobby's settings.
#[derive(Clone, Debug)]
pub struct LobbyLimits {
    /// How long a challenge waits for an answer.
    pub challenge_ttl: Duration,
    /// Most open challenges one account may have made.
    pub challenges_per_account: usize,
    /// How often the ladder pairs its bots.
    pub ladder_every: Duration,
    /// Two rated seekers are paired when their ratings are this close.
    pub seek_rating_gap: f64,
    /// Most seats of unfinished matches that hosted bots play at once (a
    /// match between two hosted bots takes two), counting per bot the
    /// larger of its seats in this lobby's matches and in the store's
    /// (`busy`): the ladder pairs no more of them, and a challenge to one
    /// is refused with `server-busy`.
    pub max_hosted_seats: usize,
}

impl Default for LobbyLimits {
    fn default() -> LobbyLimits {
        LobbyLimits {
            challenge_ttl: Duration::from_secs(60),
            challenges_per_account: 20,
            ladder_every: Duration::from_secs(10),
            seek_rating_gap: 300.0,
            max_hosted_seats: 16,
        }
    }
}

/// A signed-in account, as the lobby knows it.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The account's name as registered.
    pub name: String,
    pub bot: bool,
    pub rating: f64,
}

/// What the lobby needs of a built-in computer level (the server's
/// `bots::Level`): a small value to copy and compare, whose `Display` is
/// its wire name (`easy`, …), from which its account's name is made
/// ([`crate::name::computer_account`]). Every such type is one.
pub trait ComputerLevel: Copy + Eq + std::fmt::Debug + std::fmt::Display {}

impl<T: Copy + Eq + std::fmt::Debug + std::fmt::Display> ComputerLevel for T {}

/// Who plays one seat of a match the lobby starts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Player<L> {
    /// A registered account, playing through its own client.
    Account(String),
    /// A built-in computer level, played by the server as its account.
    Computer(L),
    /// A bot account whose hosted module the server plays.
    Hosted(String),
}

/// Why the lobby starts a match.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pairing {
    Challenge(String),
    Seek,
    Ladder,
}

/// What the lobby has its driver do.
#[derive(Clone, Debug, PartialEq)]
pub enum Effect<L> {
    /// Send `msg` on one stream.
    Send(StreamId, StreamServerMessage),
    /// Send `msg` on every stream of the account (none if it is offline).
    Tell(String, StreamServerMessage),
    /// Start a match: `seats[0]` takes the first seat (White unless the pie
    /// rule swaps). The driver tells each account its seat token with
    /// `match-start`, and feeds [`Input::Finished`] when it ends.
    Start {
        seats: [Player<L>; 2],
        rated: bool,
        rules: Preset,
        turn_seconds: Option<u64>,
        why: Pairing,
    },
}

/// What happens to the lobby.
#[derive(Clone, Debug, PartialEq)]
pub enum Input<L> {
    /// A stream said hello as `member`.
    Online { stream: StreamId, member: Member },
    /// A stream closed.
    Offline { stream: StreamId },
    /// A stream sent a message (a challenge's `to` already checked to be an
    /// account, and given as registered).
    Message {
        stream: StreamId,
        msg: StreamClientMessage,
    },
    /// A match the lobby started (or any match between accounts) ended;
    /// `ratings` are the accounts' ratings after it.
    Finished { ratings: Vec<(String, f64)> },
    /// A match the lobby asked for could not be started.
    StartFailed { seats: [Player<L>; 2] },
    /// Time passed (expire challenges, pair the ladder).
    Tick,
    /// The hosted bots now (every bot account with an active module, at
    /// its rating), and the account of each hosted seat of the store's
    /// unfinished matches (`busy`, a name per seat): they replace the ones
    /// known before.
    Hosted {
        bots: Vec<Member>,
        busy: Vec<String>,
    },
}

struct Online {
    member: Member,
    /// On the ladder (bots only).
    ladder: bool,
    /// Seeking a match: rated or not.
    seeking: Option<bool>,
}

/// A challenge as asked for.
struct Asked {
    to: String,
    rated: bool,
    rules: Option<String>,
    turn_seconds: Option<u64>,
    color: Option<Side>,
}

struct Open {
    info: ChallengeInfo,
    rules: Preset,
    turn_seconds: Option<u64>,
    expires: Moment,
}

/// The lobby's state.
pub struct Lobby<L> {
    limits: LobbyLimits,
    streams: BTreeMap<StreamId, Online>,
    challenges: BTreeMap<String, Open>,
    /// Matches the lobby started and not yet finished, per account
    /// (lower-case name): a ladder bot plays one ladder match at a time.
    playing: HashMap<String, u32>,
    /// The computer levels' ratings.
    computers: Vec<(L, f64)>,
    /// The hosted bots, by lower-case name.
    hosted: BTreeMap<String, Member>,
    /// Seats of the store's unfinished matches per hosted bot (lower-case
    /// name), as last read.
    busy: HashMap<String, u32>,
    next_challenge: u64,
    next_ladder: Moment,
    /// Which of an odd number of ladder bots sits out (turns round).
    rounds: u64,
    /// Draws the colours of challenges that leave them open.
    rng: crate::noise::SplitMix64,
    out: Vec<Effect<L>>,
}

fn key(name: &str) -> String {
    name.to_ascii_lowercase()
}

fn refused(code: ErrorCode, message: impl Into<String>) -> Refusal {
    Refusal::new(code, message)
}

impl<L: ComputerLevel> Lobby<L> {
    /// An empty lobby; `computers` are the built-in levels on the ladder,
    /// with their current ratings.
    /// `seed` draws open colours (the driver seeds it from the system's
    /// randomness).
    pub fn new(limits: LobbyLimits, computers: Vec<(L, f64)>, now: Moment, seed: u64) -> Lobby<L> {
        Lobby {
            next_ladder: now + limits.ladder_every,
            limits,
            streams: BTreeMap::new(),
            challenges: BTreeMap::new(),
            playing: HashMap::new(),
            computers,
            hosted: BTreeMap::new(),
            busy: HashMap::new(),
            next_challenge: 1,
            rounds: 0,
            rng: crate::noise::SplitMix64::new(seed),
            out: Vec::new(),
        }
    }

    /// How often the ladder pairs its bots.
    pub fn ladder_every(&self) -> Duration {
        self.limits.ladder_every
    }

    /// When the lobby next needs [`Input::Tick`].
    pub fn next_deadline(&self) -> Moment {
        self.challenges
            .values()
            .map(|c| c.expires)
            .fold(self.next_ladder, std::cmp::min)
    }

    /// The challenges open to or from `account`, for its welcome.
    pub fn challenges_of(&self, account: &str, now: Moment) -> Vec<ChallengeInfo> {
        let k = key(account);
        self.challenges
            .values()
            .filter(|c| key(&c.info.from) == k || key(&c.info.to) == k)
            .map(|c| self.shown(c, now))
            .collect()
    }

    fn shown(&self, c: &Open, now: Moment) -> ChallengeInfo {
        ChallengeInfo {
            expires_in: c.expires.saturating_since(now).as_secs(),
            ..c.info.clone()
        }
    }

    /// Handles one input; what the driver must do, in order.
    pub fn handle(&mut self, input: Input<L>, now: Moment) -> Vec<Effect<L>> {
        match input {
            Input::Online { stream, member } => {
                self.streams.insert(
                    stream,
                    Online {
                        member,
                        ladder: false,
                        seeking: None,
                    },
                );
            }
            Input::Offline { stream } => {
                self.streams.remove(&stream);
            }
            Input::Message { stream, msg } => {
                if let Err(r) = self.message(stream, msg, now) {
                    self.out
                        .push(Effect::Send(stream, StreamServerMessage::refused(&r)));
                }
            }
            Input::Finished { ratings } => {
                for (account, rating) in ratings {
                    self.done_playing(&account);
                    self.rated(&account, rating);
                }
            }
            Input::StartFailed { seats } => {
                for seat in seats {
                    self.done_playing(&self.player_name(&seat));
                }
            }
            Input::Tick => self.tick(now),
            Input::Hosted { bots, busy } => {
                self.hosted = bots.into_iter().map(|m| (key(&m.name), m)).collect();
                self.busy.clear();
                for name in busy {
                    *self.busy.entry(key(&name)).or_insert(0) += 1;
                }
            }
        }
        std::mem::take(&mut self.out)
    }

    fn player_name(&self, p: &Player<L>) -> String {
        match p {
            Player::Account(a) | Player::Hosted(a) => a.clone(),
            Player::Computer(l) => crate::name::computer_account(*l),
        }
    }

    /// Whether `account` is a hosted bot.
    pub fn is_hosted(&self, account: &str) -> bool {
        self.hosted.contains_key(&key(account))
    }

    /// Seats of unfinished matches that hosted bots play: per bot, the
    /// larger of the lobby's count and the store's (which lags the lobby's
    /// own starts, and has every node's and those from before a restart).
    fn hosted_seats(&self) -> usize {
        self.hosted
            .keys()
            .map(|k| {
                let here = self.playing.get(k).copied().unwrap_or(0);
                let stored = self.busy.get(k).copied().unwrap_or(0);
                here.max(stored) as usize
            })
            .sum()
    }

    /// Whether hosted bot `k` (lower-case) is mid-match, as far as the
    /// lobby or the store knows.
    fn hosted_busy(&self, k: &str) -> bool {
        self.playing.contains_key(k) || self.busy.contains_key(k)
    }

    fn done_playing(&mut self, account: &str) {
        if let Some(n) = self.playing.get_mut(&key(account)) {
            *n = n.saturating_sub(1);
            if *n == 0 {
                self.playing.remove(&key(account));
            }
        }
    }

    fn rated(&mut self, account: &str, rating: f64) {
        for s in self.streams.values_mut() {
            if key(&s.member.name) == key(account) {
                s.member.rating = rating;
            }
        }
        if let Some(m) = self.hosted.get_mut(&key(account)) {
            m.rating = rating;
        }
        for (level, r) in &mut self.computers {
            if key(&crate::name::computer_account(*level)) == key(account) {
                *r = rating;
            }
        }
    }

    fn member(&self, stream: StreamId) -> Result<&Member, Refusal> {
        self.streams
            .get(&stream)
            .map(|s| &s.member)
            .ok_or_else(Refusal::internal)
    }

    fn message(
        &mut self,
        stream: StreamId,
        msg: StreamClientMessage,
        now: Moment,
    ) -> Result<(), Refusal> {
        let me = self.member(stream)?.clone();
        match msg {
            StreamClientMessage::Hello { .. } => Err(refused(
                ErrorCode::BadMessage,
                "hello is the first message of a stream, and only the first",
            )),
            StreamClientMessage::Challenge {
                to,
                rated,
                rules,
                turn_seconds,
                color,
            } => {
                let asked = Asked {
                    to,
                    rated,
                    rules,
                    turn_seconds,
                    color,
                };
                self.challenge(&me, asked, now)
            }
            StreamClientMessage::Accept { challenge } => {
                let c = self.addressed_to(&me, &challenge)?;
                self.challenges.remove(&challenge);
                let white = match c.info.color {
                    Some(side) => side == Side::White,
                    None => self.rng.next_u64() & 1 == 0,
                };
                let (from, to) = (Player::Account(c.info.from), Player::Account(c.info.to));
                self.start(
                    if white { [from, to] } else { [to, from] },
                    c.info.rated,
                    c.rules,
                    c.turn_seconds,
                    Pairing::Challenge(challenge),
                );
                Ok(())
            }
            StreamClientMessage::Decline { challenge, reason } => {
                let c = self.addressed_to(&me, &challenge)?;
                self.challenges.remove(&challenge);
                self.closed(
                    &c,
                    "declined",
                    reason.map(|r| r.chars().take(200).collect()),
                );
                Ok(())
            }
            StreamClientMessage::Withdraw { challenge } => {
                match self.challenges.get(&challenge) {
                    Some(c) if key(&c.info.from) == key(&me.name) => {}
                    _ => return Err(no_challenge(&challenge)),
                }
                if let Some(c) = self.challenges.remove(&challenge) {
                    self.closed(&c, "withdrawn", None);
                }
                Ok(())
            }
            StreamClientMessage::Seek { rated, cancel } => {
                if let Some(s) = self.streams.get_mut(&stream) {
                    s.seeking = (!cancel).then_some(rated);
                }
                if !cancel {
                    self.pair_seekers(stream, rated);
                }
                Ok(())
            }
            StreamClientMessage::Ladder { join } => {
                if !me.bot {
                    return Err(refused(
                        ErrorCode::BadMessage,
                        "the ladder is for bot accounts; people seek a match instead",
                    ));
                }
                if let Some(s) = self.streams.get_mut(&stream) {
                    s.ladder = join;
                }
                Ok(())
            }
        }
    }

    fn challenge(&mut self, me: &Member, asked: Asked, now: Moment) -> Result<(), Refusal> {
        let Asked {
            to,
            rated,
            rules,
            turn_seconds,
            color,
        } = asked;
        if key(&to) == key(&me.name) {
            return Err(refused(
                ErrorCode::SameAccount,
                "a challenge is to someone else",
            ));
        }
        if to
            .to_ascii_lowercase()
            .starts_with(crate::name::COMPUTER_PREFIX)
        {
            return Err(refused(
                ErrorCode::BadMessage,
                "the computer levels are played from POST /api/matches (opponent bot)",
            ));
        }
        let rules = match rules.as_deref() {
            None => Preset::Standard,
            Some(name) => Preset::parse(name)
                .ok_or_else(|| refused(ErrorCode::BadConfig, "rules are standard or casual"))?,
        };
        if rated && rules != Preset::Standard {
            return Err(refused(
                ErrorCode::BadConfig,
                "a rated match is played under the standard rules",
            ));
        }
        if let Some(t) = turn_seconds {
            crate::session::check_turn_seconds(t)?;
        }
        let made = self
            .challenges
            .values()
            .filter(|c| key(&c.info.from) == key(&me.name))
            .count();
        if made >= self.limits.challenges_per_account {
            return Err(refused(
                ErrorCode::RateLimited,
                "too many open challenges; wait for answers or withdraw some",
            ));
        }
        if let Some(bot) = self.hosted.get(&key(&to)).map(|m| m.name.clone()) {
            return self.challenge_hosted(me, bot, rated, rules, turn_seconds, color);
        }
        let id = format!("c{}", self.next_challenge);
        self.next_challenge += 1;
        let open = Open {
            info: ChallengeInfo {
                id: id.clone(),
                from: me.name.clone(),
                to,
                rated,
                rules: rules.as_str().to_string(),
                turn_seconds: turn_seconds.unwrap_or(0),
                color,
                expires_in: 0,
            },
            rules,
            turn_seconds,
            expires: now + self.limits.challenge_ttl,
        };
        let shown = self.shown(&open, now);
        for who in [&open.info.from, &open.info.to] {
            self.out.push(Effect::Tell(
                who.clone(),
                StreamServerMessage::Challenge {
                    challenge: shown.clone(),
                },
            ));
        }
        self.challenges.insert(id, open);
        Ok(())
    }

    /// A challenge to a hosted bot: accepted at once (the match starts and
    /// both are told `match-start` by the driver), unless hosted bots play
    /// as many seats as they may.
    fn challenge_hosted(
        &mut self,
        me: &Member,
        bot: String,
        rated: bool,
        rules: Preset,
        turn_seconds: Option<u64>,
        color: Option<Side>,
    ) -> Result<(), Refusal> {
        if self.hosted_seats() >= self.limits.max_hosted_seats {
            return Err(refused(
                ErrorCode::ServerBusy,
                "the server plays as many hosted bots as it can; try later",
            ));
        }
        let white = match color {
            Some(side) => side == Side::White,
            None => self.rng.next_u64() & 1 == 0,
        };
        let id = format!("c{}", self.next_challenge);
        self.next_challenge += 1;
        let (from, to) = (Player::Account(me.name.clone()), Player::Hosted(bot));
        self.start(
            if white { [from, to] } else { [to, from] },
            rated,
            rules,
            turn_seconds,
            Pairing::Challenge(id),
        );
        Ok(())
    }

    /// The open challenge `id`, if it is addressed to `me`.
    fn addressed_to(&self, me: &Member, id: &str) -> Result<Open, Refusal> {
        match self.challenges.get(id) {
            Some(c) if key(&c.info.to) == key(&me.name) => Ok(Open {
                info: c.info.clone(),
                rules: c.rules,
                turn_seconds: c.turn_seconds,
                expires: c.expires,
            }),
            _ => Err(no_challenge(id)),
        }
    }

    fn closed(&mut self, c: &Open, why: &str, reason: Option<String>) {
        for who in [&c.info.from, &c.info.to] {
            self.out.push(Effect::Tell(
                who.clone(),
                StreamServerMessage::ChallengeClosed {
                    id: c.info.id.clone(),
                    why: why.into(),
                    reason: reason.clone(),
                },
            ));
        }
    }

    fn start(
        &mut self,
        seats: [Player<L>; 2],
        rated: bool,
        rules: Preset,
        turn_seconds: Option<u64>,
        why: Pairing,
    ) {
        for s in &seats {
            *self.playing.entry(key(&self.player_name(s))).or_insert(0) += 1;
        }
        self.out.push(Effect::Start {
            seats,
            rated,
            rules,
            turn_seconds,
            why,
        });
    }

    /// Pairs the seeker on `stream` with the longest-waiting other seeker
    /// of the same kind (rated: within the rating gap), if there is one.
    fn pair_seekers(&mut self, stream: StreamId, rated: bool) {
        let me = match self.streams.get(&stream) {
            Some(s) => s.member.clone(),
            None => return,
        };
        let other = self.streams.iter().find(|(id, s)| {
            **id != stream
                && s.seeking == Some(rated)
                && key(&s.member.name) != key(&me.name)
                && (!rated || (s.member.rating - me.rating).abs() <= self.limits.seek_rating_gap)
        });
        let Some((&other_id, other)) = other else {
            return;
        };
        let them = other.member.name.clone();
        for id in [stream, other_id] {
            if let Some(s) = self.streams.get_mut(&id) {
                s.seeking = None;
            }
        }
        let rules = if rated {
            Preset::Standard
        } else {
            Preset::Casual
        };
        self.start(
            [Player::Account(them), Player::Account(me.name)],
            rated,
            rules,
            None,
            Pairing::Seek,
        );
    }

    fn tick(&mut self, now: Moment) {
        let expired: Vec<String> = self
            .challenges
            .iter()
            .filter(|(_, c)| c.expires <= now)
            .map(|(id, _)| id.clone())
            .collect();
        for id in expired {
            if let Some(c) = self.challenges.remove(&id) {
                self.closed(&c, "expired", None);
            }
        }
        if now >= self.next_ladder {
            self.next_ladder = now + self.limits.ladder_every;
            self.pair_ladder();
        }
    }

    /// One round of the ladder: every ladder bot that is not playing a
    /// ladder match, and every idle computer level, sorted by rating and
    /// paired with its neighbour — the one above in one round, the one
    /// below in the next; a pair of two computer levels is skipped (the
    /// ladder is for the registered bots). With an odd number, one sits out:
    /// a computer level if one is there (a different one each round), so
    /// that a registered bot alone with the computer levels plays at once.
    fn pair_ladder(&mut self) {
        let mut pool: Vec<(Player<L>, f64)> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for s in self.streams.values() {
            let k = key(&s.member.name);
            if s.ladder && !self.playing.contains_key(&k) && seen.insert(k) {
                pool.push((Player::Account(s.member.name.clone()), s.member.rating));
            }
        }
        let mut room = self
            .limits
            .max_hosted_seats
            .saturating_sub(self.hosted_seats());
        for (k, m) in &self.hosted {
            if room == 0 {
                break;
            }
            if !self.hosted_busy(k) && seen.insert(k.clone()) {
                pool.push((Player::Hosted(m.name.clone()), m.rating));
                room -= 1;
            }
        }
        if pool.is_empty() {
            return;
        }
        for (level, rating) in &self.computers {
            let k = key(&crate::name::computer_account(*level));
            if !self.playing.contains_key(&k) {
                pool.push((Player::Computer(*level), *rating));
            }
        }
        pool.sort_by(|a, b| b.1.total_cmp(&a.1));
        // Every other round the pairs shift by one (the top one sits out),
        // so that each meets both its neighbours, not always the same one.
        let registered = pool
            .iter()
            .filter(|(p, _)| !matches!(p, Player::Computer(_)))
            .count();
        if self.rounds & 1 == 1 && pool.len() >= 4 && registered >= 2 {
            pool.remove(0);
        }
        if pool.len() % 2 == 1 {
            let computers: Vec<usize> = pool
                .iter()
                .enumerate()
                .filter(|(_, (p, _))| matches!(p, Player::Computer(_)))
                .map(|(i, _)| i)
                .collect();
            let out = match computers.len() {
                0 => (self.rounds as usize) % pool.len(),
                n => computers[(self.rounds as usize) % n],
            };
            pool.remove(out);
        }
        self.rounds += 1;
        let mut pairs = Vec::new();
        for pair in pool.chunks(2) {
            let (a, b) = (pair[0].0.clone(), pair[1].0.clone());
            if matches!((&a, &b), (Player::Computer(_), Player::Computer(_))) {
                continue;
            }
            // Colours alternate round by round.
            pairs.push(if self.rounds & 1 == 0 { [a, b] } else { [b, a] });
        }
        for seats in pairs {
            self.start(seats, true, Preset::Standard, None, Pairing::Ladder);
        }
    }
}

fn no_challenge(id: &str) -> Refusal {
    refused(
        ErrorCode::NoSuchChallenge,
        format!("no open challenge {id:?} for you"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    type Lobby = super::Lobby<Level>;
    type Effect = super::Effect<Level>;
    type Input = super::Input<Level>;
    type Player = super::Player<Level>;

    /// A computer level of the tests' own (the server's is `bots::Level`).
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    enum Level {
        Easy,
    }

    impl std::fmt::Display for Level {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("easy")
        }
    }

    fn at(s: u64) -> Moment {
        Moment::new(Duration::from_secs(s))
    }

    fn member(name: &str, bot: bool, rating: f64) -> Member {
        Member {
            name: name.into(),
            bot,
            rating,
        }
    }

    fn lobby() -> Lobby {
        Lobby::new(
            LobbyLimits::default(),
            vec![(Level::Easy, 1500.0)],
            at(0),
            7,
        )
    }

    fn online(l: &mut Lobby, id: u64, m: Member) -> StreamId {
        let s = StreamId(id);
        l.handle(
            Input::Online {
                stream: s,
                member: m,
            },
            at(0),
        );
        s
    }

    fn say(l: &mut Lobby, s: StreamId, msg: StreamClientMessage, t: u64) -> Vec<Effect> {
        l.handle(Input::Message { stream: s, msg }, at(t))
    }

    fn error_code(effects: &[Effect]) -> Option<ErrorCode> {
        effects.iter().find_map(|e| match e {
            Effect::Send(_, StreamServerMessage::Error { code, .. }) => Some(*code),
            _ => None,
        })
    }

    fn challenge_to(to: &str) -> StreamClientMessage {
        StreamClientMessage::Challenge {
            to: to.into(),
            rated: true,
            rules: None,
            turn_seconds: None,
            color: None,
        }
    }

    #[test]
    fn a_challenge_is_told_to_both_accepted_once_and_starts_a_rated_match() {
        let mut l = lobby();
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let p = online(&mut l, 2, member("Petka", false, 1500.0));
        let fx = say(&mut l, a, challenge_to("Petka"), 1);
        assert_eq!(fx.len(), 2, "{fx:?}");
        let id = match &fx[1] {
            Effect::Tell(who, StreamServerMessage::Challenge { challenge }) => {
                assert_eq!(who, "Petka");
                assert_eq!(challenge.expires_in, 60);
                challenge.id.clone()
            }
            other => panic!("{other:?}"),
        };
        // Only the one challenged may accept; then it is gone.
        let fx = say(
            &mut l,
            a,
            StreamClientMessage::Accept {
                challenge: id.clone(),
            },
            2,
        );
        assert_eq!(error_code(&fx), Some(ErrorCode::NoSuchChallenge));
        let fx = say(
            &mut l,
            p,
            StreamClientMessage::Accept {
                challenge: id.clone(),
            },
            2,
        );
        assert!(matches!(
            &fx[..],
            [Effect::Start {
                rated: true,
                rules: Preset::Standard,
                why: Pairing::Challenge(_),
                ..
            }]
        ));
        let fx = say(&mut l, p, StreamClientMessage::Accept { challenge: id }, 3);
        assert_eq!(error_code(&fx), Some(ErrorCode::NoSuchChallenge));
    }

    #[test]
    fn a_challenge_can_be_declined_with_a_reason_withdrawn_or_left_to_expire() {
        let mut l = lobby();
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let p = online(&mut l, 2, member("Petka", false, 1500.0));
        say(&mut l, a, challenge_to("Petka"), 0);
        let decline = StreamClientMessage::Decline {
            challenge: "c1".into(),
            reason: Some("later".into()),
        };
        let fx = say(&mut l, p, decline, 1);
        assert!(fx.iter().all(|e| matches!(e,
            Effect::Tell(_, StreamServerMessage::ChallengeClosed { why, reason: Some(r), .. })
                if why == "declined" && r == "later")));
        say(&mut l, a, challenge_to("Petka"), 1);
        let fx = say(
            &mut l,
            p,
            StreamClientMessage::Withdraw {
                challenge: "c2".into(),
            },
            2,
        );
        assert_eq!(
            error_code(&fx),
            Some(ErrorCode::NoSuchChallenge),
            "only its maker"
        );
        assert_eq!(l.challenges_of("petka", at(2)).len(), 1);
        assert_eq!(
            l.next_deadline(),
            at(10),
            "the ladder's next round comes first"
        );
        let fx = l.handle(Input::Tick, at(61));
        assert!(
            fx.iter().any(|e| matches!(e,
            Effect::Tell(_, StreamServerMessage::ChallengeClosed { why, .. }) if why == "expired"))
        );
        assert!(l.challenges_of("Anka", at(61)).is_empty());
    }

    #[test]
    fn bad_challenges_are_refused_with_a_code() {
        let mut l = lobby();
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let cases = [
            (challenge_to("anka"), ErrorCode::SameAccount),
            (
                StreamClientMessage::Challenge {
                    to: "Petka".into(),
                    rated: true,
                    rules: Some("casual".into()),
                    turn_seconds: None,
                    color: None,
                },
                ErrorCode::BadConfig,
            ),
            (
                StreamClientMessage::Challenge {
                    to: "Petka".into(),
                    rated: false,
                    rules: None,
                    turn_seconds: Some(0),
                    color: None,
                },
                ErrorCode::BadConfig,
            ),
            (
                StreamClientMessage::Ladder { join: true },
                ErrorCode::BadMessage,
            ),
        ];
        for (msg, code) in cases {
            let fx = say(&mut l, a, msg.clone(), 0);
            assert_eq!(error_code(&fx), Some(code), "{msg:?}");
        }
        for _ in 0..20 {
            say(&mut l, a, challenge_to("Petka"), 0);
        }
        let fx = say(&mut l, a, challenge_to("Petka"), 0);
        assert_eq!(error_code(&fx), Some(ErrorCode::RateLimited));
    }

    #[test]
    fn two_rated_seekers_of_similar_rating_are_paired_and_distant_ones_wait() {
        let mut l = lobby();
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let p = online(&mut l, 2, member("Petka", false, 2100.0));
        let v = online(&mut l, 3, member("Vasya", false, 1600.0));
        let seek = StreamClientMessage::Seek {
            rated: true,
            cancel: false,
        };
        assert!(say(&mut l, a, seek.clone(), 0).is_empty());
        assert!(say(&mut l, p, seek.clone(), 0).is_empty(), "too far apart");
        let fx = say(&mut l, v, seek, 0);
        assert!(
            matches!(&fx[..], [Effect::Start { seats, why: Pairing::Seek, .. }]
            if seats == &[Player::Account("Anka".into()), Player::Account("Vasya".into())])
        );
    }

    #[test]
    fn the_ladder_pairs_idle_bots_by_rating_with_the_computer_and_not_twice_at_once() {
        let mut l = lobby();
        let bots = [("random", 1200.0), ("greedy", 1550.0), ("search", 1800.0)];
        for (i, (name, r)) in bots.iter().enumerate() {
            let s = online(&mut l, i as u64, member(name, true, *r));
            assert!(say(&mut l, s, StreamClientMessage::Ladder { join: true }, 0).is_empty());
        }
        assert!(l.handle(Input::Tick, at(5)).is_empty(), "not yet");
        let fx = l.handle(Input::Tick, at(10));
        let starts: Vec<&[Player; 2]> = fx
            .iter()
            .filter_map(|e| match e {
                Effect::Start {
                    seats,
                    rated: true,
                    why: Pairing::Ladder,
                    ..
                } => Some(seats),
                _ => None,
            })
            .collect();
        assert_eq!(starts.len(), 2, "{fx:?}");
        // Sorted: search 1800, greedy 1550, computer 1500, random 1200.
        let names = |p: &[Player; 2]| p.clone().map(|x| format!("{x:?}"));
        assert!(names(starts[0]).contains(&"Account(\"search\")".to_string()));
        assert!(names(starts[0]).contains(&"Account(\"greedy\")".to_string()));
        assert!(names(starts[1]).contains(&"Computer(Easy)".to_string()));
        // While those play, the next round pairs nobody.
        assert!(l.handle(Input::Tick, at(20)).is_empty());
        let finished = Input::Finished {
            ratings: vec![("search".into(), 1810.0), ("greedy".into(), 1540.0)],
        };
        l.handle(finished, at(21));
        let fx = l.handle(Input::Tick, at(30));
        assert_eq!(fx.len(), 1, "search and greedy again: {fx:?}");
    }

    fn starts(fx: &[Effect]) -> Vec<[Player; 2]> {
        fx.iter()
            .filter_map(|e| match e {
                Effect::Start { seats, .. } => Some(seats.clone()),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn a_hosted_bot_is_on_the_ladder_without_a_stream_and_plays_one_ladder_match_at_a_time() {
        let mut l = lobby();
        let hosted = Input::Hosted {
            bots: vec![member("Wasm", true, 1500.0)],
            busy: Vec::new(),
        };
        assert!(l.handle(hosted, at(0)).is_empty());
        assert!(l.is_hosted("wasm"));
        let fx = l.handle(Input::Tick, at(10));
        let paired = starts(&fx);
        assert_eq!(paired.len(), 1, "{fx:?}");
        assert!(paired[0].contains(&Player::Hosted("Wasm".into())));
        assert!(paired[0].contains(&Player::Computer(Level::Easy)));
        assert!(l.handle(Input::Tick, at(20)).is_empty(), "still playing");
        let finished = Input::Finished {
            ratings: vec![("Wasm".into(), 1600.0), ("computer-easy".into(), 1400.0)],
        };
        l.handle(finished, at(21));
        assert_eq!(starts(&l.handle(Input::Tick, at(30))).len(), 1);
        // Gone from the list (its module deleted): off the ladder.
        l.handle(
            Input::Hosted {
                bots: Vec::new(),
                busy: Vec::new(),
            },
            at(31),
        );
        l.handle(
            Input::Finished {
                ratings: vec![("Wasm".into(), 1600.0), ("computer-easy".into(), 1400.0)],
            },
            at(32),
        );
        assert!(l.handle(Input::Tick, at(40)).is_empty());
    }

    #[test]
    fn a_bot_alone_with_an_odd_number_of_computer_levels_is_paired_in_the_first_round() {
        let mut l = Lobby::new(
            LobbyLimits::default(),
            vec![(Level::Easy, 1500.0), (Level::Easy, 1400.0)],
            at(0),
            7,
        );
        l.handle(
            Input::Hosted {
                bots: vec![member("Wasm", true, 1600.0)],
                busy: Vec::new(),
            },
            at(0),
        );
        // Three in the pool, the bot on top: a computer level sits out.
        let paired = starts(&l.handle(Input::Tick, at(10)));
        assert_eq!(paired.len(), 1);
        assert!(paired[0].contains(&Player::Hosted("Wasm".into())));
    }

    #[test]
    fn a_challenge_to_a_hosted_bot_starts_at_once_until_hosted_bots_fill_their_seats() {
        let mut l = Lobby::new(
            LobbyLimits {
                max_hosted_seats: 1,
                ..LobbyLimits::default()
            },
            vec![(Level::Easy, 1500.0)],
            at(0),
            7,
        );
        l.handle(
            Input::Hosted {
                bots: vec![member("Wasm", true, 1500.0)],
                busy: Vec::new(),
            },
            at(0),
        );
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let white = StreamClientMessage::Challenge {
            to: "wasm".into(),
            rated: true,
            rules: None,
            turn_seconds: None,
            color: Some(Side::White),
        };
        let fx = say(&mut l, a, white.clone(), 1);
        assert_eq!(
            starts(&fx),
            [[
                Player::Account("Anka".into()),
                Player::Hosted("Wasm".into())
            ]],
            "{fx:?}"
        );
        // Its one hosted seat is taken: the next is refused, and the
        // ladder pairs no hosted bot.
        let fx = say(&mut l, a, white, 2);
        assert_eq!(error_code(&fx), Some(ErrorCode::ServerBusy));
        assert!(l.handle(Input::Tick, at(10)).is_empty());
    }

    #[test]
    fn a_hosted_bot_the_store_has_mid_match_is_not_paired_and_its_seats_count_until_it_is_not() {
        let mut l = Lobby::new(
            LobbyLimits {
                max_hosted_seats: 2,
                ..LobbyLimits::default()
            },
            vec![(Level::Easy, 1500.0)],
            at(0),
            7,
        );
        let bots = vec![member("Wasm", true, 1500.0), member("Asm", true, 1500.0)];
        // After a restart (or on another node) Wasm plays a match this
        // lobby did not start: only Asm is paired.
        l.handle(
            Input::Hosted {
                bots: bots.clone(),
                busy: vec!["wasm".into()],
            },
            at(0),
        );
        let paired = starts(&l.handle(Input::Tick, at(10)));
        assert_eq!(paired.len(), 1, "{paired:?}");
        assert!(paired[0].contains(&Player::Hosted("Asm".into())));
        // Both hosted seats are taken (Wasm's in the store, Asm's here):
        // a challenge to Wasm is refused.
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let challenge = StreamClientMessage::Challenge {
            to: "Wasm".into(),
            rated: false,
            rules: None,
            turn_seconds: None,
            color: None,
        };
        let fx = say(&mut l, a, challenge, 11);
        assert_eq!(error_code(&fx), Some(ErrorCode::ServerBusy));
        // Both matches are over, in the store too: Wasm is paired again.
        l.handle(
            Input::Finished {
                ratings: vec![("Asm".into(), 1500.0), ("computer-easy".into(), 1500.0)],
            },
            at(12),
        );
        l.handle(
            Input::Hosted {
                bots,
                busy: Vec::new(),
            },
            at(13),
        );
        let paired = starts(&l.handle(Input::Tick, at(20)));
        assert_eq!(paired.len(), 1, "{paired:?}");
        assert!(paired[0].contains(&Player::Hosted("Wasm".into())));
    }

    #[test]
    fn a_challenger_who_asks_for_black_takes_the_second_seat() {
        let mut l = lobby();
        let a = online(&mut l, 1, member("Anka", false, 1500.0));
        let p = online(&mut l, 2, member("Petka", false, 1500.0));
        let black = StreamClientMessage::Challenge {
            to: "Petka".into(),
            rated: true,
            rules: None,
            turn_seconds: None,
            color: Some(Side::Black),
        };
        say(&mut l, a, black, 0);
        let fx = say(
            &mut l,
            p,
            StreamClientMessage::Accept {
                challenge: "c1".into(),
            },
            1,
        );
        assert!(matches!(&fx[..], [Effect::Start { seats, .. }]
            if seats == &[Player::Account("Petka".into()), Player::Account("Anka".into())]));
    }
}
