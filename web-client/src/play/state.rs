//! The state of a live match as this page follows it, without drawing or
//! I/O: who sits where, the match as last shown, the announcements queued
//! and shown in the order they came (a shot is animated from its exact
//! film before the next announcement is taken), the turn clock, the chat,
//! the shot log, the score and the rematch offer. The screen feeds it the
//! server's messages and the frame time; what it shows is read back from
//! here.

use crate::clip::{Clip, Frame};
use crate::highlight;
use crate::i18n::t;
use crate::platform::Sound;
use crate::story::{self, Score};
use game::protocol::{Phrase, Players, ServerMessage};
use game::{MatchView, Seat, ShotOutcome, Side};
use std::collections::VecDeque;

/// Most chat lines kept (muted ones included, so unmuting shows them).
pub const CHAT_LINES: usize = 40;
/// Most shot-log lines kept.
pub const LOG_LINES: usize = 4;
/// How long a notice shows, in seconds.
const NOTICE: f64 = 5.0;

/// A line of the chat as the server sent it.
#[derive(Clone, Debug, PartialEq)]
pub struct ChatLine {
    /// The seat that said it (none: a spectator).
    pub from: Option<Seat>,
    pub name: String,
    pub text: String,
    /// The quick phrase it is, shown in the reader's language.
    pub phrase: Option<Phrase>,
}

/// Whose chat this page hides.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Mute {
    /// The seated players' chat (for a player: the opponent's; a player's
    /// own lines always show).
    pub players: bool,
    /// The spectators' chat.
    pub spectators: bool,
}

/// A quick phrase in the reader's language.
pub fn phrase_text(p: Phrase) -> String {
    match p {
        Phrase::Hello => t!("phrase-hello"),
        Phrase::GoodLuck => t!("phrase-good-luck"),
        Phrase::GoodShot => t!("phrase-good-shot"),
        Phrase::Oops => t!("phrase-oops"),
        Phrase::WellPlayed => t!("phrase-well-played"),
        Phrase::Thanks => t!("phrase-thanks"),
        Phrase::Gg => t!("phrase-gg"),
        Phrase::Rematch => t!("phrase-rematch"),
    }
}

/// A seat's name as the reader reads it: the computer's seat (the
/// server names it `bot (LEVEL)`, a name no person may take) by its level
/// in the reader's language, anyone else's as it came.
pub fn seat_name(raw: &str) -> String {
    match raw
        .strip_prefix("bot (")
        .and_then(|rest| rest.strip_suffix(')'))
    {
        Some(level) if !level.is_empty() && level.chars().all(|c| c.is_ascii_lowercase()) => {
            t!(
                "computer-level",
                level = crate::lobby::state::level_name(level)
            )
        }
        _ => raw.to_string(),
    }
}

/// The match as this page knows it.
#[derive(Default)]
pub struct MatchState {
    /// The seat this page plays (none while watching).
    pub you: Option<Seat>,
    pub players: Players,
    /// The match as last shown (the announcements queued not yet applied).
    pub view: Option<MatchView>,
    /// Announcements not yet shown, in the order they came.
    queue: VecDeque<ServerMessage>,
    /// The shot being animated and its time.
    pub playing: Option<(Clip, f64)>,
    /// The shot playing is its instant replay, in slow motion.
    pub replaying: bool,
    /// Whose turn the clock counts and when it runs out (on [`Self::now`]'s clock).
    pub clock: Option<(Seat, Side, f64)>,
    /// The chat, oldest first, at most [`CHAT_LINES`].
    pub chat: VecDeque<ChatLine>,
    /// A line shown over the board, and until when.
    pub notice: Option<(String, f64)>,
    /// A shot was sent; waiting for the server's answer.
    pub awaiting: bool,
    /// The seat that offered a rematch.
    pub rematch_offer: Option<Seat>,
    /// Seconds since the screen opened.
    pub now: f64,
    /// One line per shot shown, newest last, at most [`LOG_LINES`].
    pub log: VecDeque<String>,
    /// The outcomes of the shots seen.
    pub outcomes: Vec<ShotOutcome>,
    /// The whole match's score, from the record the server sent at its end.
    pub final_score: Option<Score>,
}

impl MatchState {
    /// Shows `text` over the board for a few seconds.
    pub fn notify(&mut self, text: impl Into<String>) {
        self.notice = Some((text.into(), self.now + NOTICE));
    }

    /// The side this page plays, once the match is known.
    pub fn my_side(&self) -> Option<Side> {
        let v = self.view.as_ref()?;
        self.you.map(|s| s.side(v.swapped))
    }

    /// The name in `seat`, or "(waiting)" while it is empty.
    pub fn name_of(&self, seat: Seat) -> String {
        let n = match seat {
            Seat::First => &self.players.first,
            Seat::Second => &self.players.second,
        };
        n.as_deref()
            .map_or_else(|| t!("play-seat-waiting"), seat_name)
    }

    /// The newest chat lines that `mute` leaves, at most `max`, as the
    /// reader reads them: a phrase in the reader's language, a spectator
    /// marked as one.
    pub fn chat_shown(&self, mute: Mute, max: usize) -> Vec<String> {
        let shown: Vec<String> = self
            .chat
            .iter()
            .filter(|l| match l.from {
                None => !mute.spectators,
                Some(seat) => Some(seat) == self.you || !mute.players,
            })
            .map(|l| {
                let text = l.phrase.map_or_else(|| l.text.clone(), phrase_text);
                match l.from {
                    Some(seat) => t!("chat-line", name = self.name_of(seat), text = text),
                    None => t!("chat-line-spectator", name = l.name.as_str(), text = text),
                }
            })
            .collect();
        shown[shown.len().saturating_sub(max)..].to_vec()
    }

    /// Whether announcements are still being shown.
    pub fn busy(&self) -> bool {
        self.playing.is_some() || !self.queue.is_empty()
    }

    /// Announcements waiting to be shown.
    #[cfg(test)]
    pub fn queued(&self) -> usize {
        self.queue.len()
    }

    /// Whether both seats are taken (a friend's match waits for the friend).
    pub fn both_seated(&self) -> bool {
        self.players.first.is_some() && self.players.second.is_some()
    }

    /// Whether the player may aim now, `connected` or not: both seats are
    /// taken, everything announced is shown, no shot is awaited, and it is
    /// their side's turn.
    pub fn may_aim(&self, connected: bool) -> bool {
        let Some(v) = &self.view else { return false };
        self.both_seated()
            && !self.busy()
            && !self.awaiting
            && connected
            && self.my_side().is_some()
            && v.to_shoot() == self.my_side()
    }

    /// Whether the rematch offer standing is the other seat's.
    pub fn rematch_is_theirs(&self) -> bool {
        self.rematch_offer.is_some_and(|s| Some(s) != self.you)
    }

    /// The rematch button's label, and whether it can be pressed.
    pub fn rematch_label(&self) -> (String, bool) {
        let theirs = self.rematch_is_theirs();
        let mine = self.rematch_offer.is_some() && !theirs;
        if theirs {
            (t!("play-rematch-accept"), true)
        } else if mine {
            (t!("play-rematch-offered"), false)
        } else {
            (t!("play-rematch-offer"), true)
        }
    }

    /// The match's score for the end screen: the record's when it came,
    /// else the shots seen.
    pub fn score(&self) -> Score {
        self.final_score
            .clone()
            .unwrap_or_else(|| Score::of(&self.outcomes))
    }

    /// Takes what the server said; the id of the rematch when one started.
    pub fn receive(&mut self, m: ServerMessage) -> Option<String> {
        match m {
            ServerMessage::MatchState {
                you, players, view, ..
            } => {
                // The full state supersedes anything not yet shown.
                self.you = you;
                self.players = players;
                self.view = Some(view);
                self.queue.clear();
                self.playing = None;
                self.replaying = false;
                self.awaiting = false;
            }
            m @ (ServerMessage::ShotPlayed { .. }
            | ServerMessage::PieDecided { .. }
            | ServerMessage::TurnPassed { .. }
            | ServerMessage::MatchOver { .. }) => {
                if matches!(m, ServerMessage::ShotPlayed { .. }) {
                    self.awaiting = false;
                }
                self.queue.push_back(m);
            }
            ServerMessage::RematchOffered { by } => {
                self.rematch_offer = Some(by);
                if Some(by) != self.you {
                    self.notify(t!("play-notice-rematch", name = self.name_of(by)));
                }
            }
            ServerMessage::RematchStarted { match_id } => return Some(match_id),
            ServerMessage::Chat {
                from,
                name,
                text,
                phrase,
            } => {
                self.chat.push_back(ChatLine {
                    from,
                    name,
                    text,
                    phrase,
                });
                while self.chat.len() > CHAT_LINES {
                    self.chat.pop_front();
                }
            }
            ServerMessage::Error { code, message } => {
                self.awaiting = false;
                self.notify(format!("{message} ({code})"));
            }
            ServerMessage::PlayerJoined { seat, name } => {
                match seat {
                    Seat::First => self.players.first = Some(name.clone()),
                    Seat::Second => self.players.second = Some(name.clone()),
                }
                self.notify(t!("play-notice-joined", name = name));
            }
            ServerMessage::PlayerLeft { seat, grace_ms } => {
                let n = self.name_of(seat);
                self.notify(t!("play-notice-left", name = n, seconds = grace_ms / 1000));
            }
            ServerMessage::PlayerBack { seat } => {
                let n = self.name_of(seat);
                self.notify(t!("play-notice-back", name = n));
            }
            ServerMessage::Clock {
                seat,
                side,
                remaining_ms,
            } => self.clock = Some((seat, side, self.now + remaining_ms as f64 / 1000.0)),
            ServerMessage::TurnTimedOut { seat, strikes } => {
                let n = self.name_of(seat);
                self.notify(t!("play-notice-timeout", name = n, strikes = strikes));
            }
            ServerMessage::Forfeited { seat, .. } => {
                let n = self.name_of(seat);
                self.notify(t!("play-notice-forfeited", name = n));
            }
            ServerMessage::Welcome { .. } | ServerMessage::MatchCreated { .. } => {}
        }
        None
    }

    /// Shows queued announcements in order, animating shots, `dt` seconds
    /// on; the sounds the shots taken up make, in order.
    pub fn advance(&mut self, dt: f64) -> Vec<Sound> {
        let mut sounds = Vec::new();
        // Catch up faster when several shots are waiting.
        let speed = if self.replaying {
            highlight::SLOW
        } else if self.queue.len() > 1 {
            3.0
        } else {
            1.0
        };
        let me = self.my_side();
        if let Some((clip, t)) = &mut self.playing {
            let before = *t;
            *t += dt * speed;
            sounds.extend(clip.sounds(before, *t));
            // A shot worth seeing again plays once more, slowly, unless
            // more shots wait to be shown.
            let again = !self.replaying
                && self.queue.len() <= 1
                && highlight::worth_replaying(&clip.outcome);
            if *t >= clip.duration() && again {
                *t = 0.0;
                self.replaying = true;
            } else if *t >= clip.duration() {
                self.replaying = false;
                if let Some(v) = &self.view {
                    self.view = Some(v.after_shot(&clip.outcome, &clip.film));
                }
                // Told once the film has shown it.
                let line = story::shot_line(&clip.outcome, me, true);
                self.log.push_back(line);
                while self.log.len() > LOG_LINES {
                    self.log.pop_front();
                }
                self.playing = None;
            }
        }
        while self.playing.is_none() {
            let Some(m) = self.queue.pop_front() else {
                break;
            };
            match m {
                ServerMessage::ShotPlayed { outcome, film, .. } => {
                    // The clacks and falls come as the film reaches them.
                    sounds.push(Sound::Flick);
                    self.outcomes.push(outcome.clone());
                    self.playing = Some((Clip::new(outcome, film), 0.0));
                }
                ServerMessage::PieDecided { swap } => {
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_pie(swap));
                    }
                }
                ServerMessage::TurnPassed { .. } => {
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_pass());
                    }
                }
                ServerMessage::MatchOver { result, record } => {
                    // The last shot's line was written while the match
                    // went on: after a resignation or forfeit nobody
                    // shoots again.
                    let me = self.my_side();
                    if let (Some(o), Some(line)) = (self.outcomes.last(), self.log.back_mut()) {
                        *line = story::shot_line(o, me, false);
                    }
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_result(result));
                    }
                    // The record has every shot, also those played before
                    // this page connected.
                    self.final_score = game::Replay::new(record)
                        .ok()
                        .map(|r| Score::of((0..r.shot_count()).filter_map(|n| r.outcome(n))));
                }
                _ => {}
            }
        }
        sounds
    }

    /// Skips the instant replay playing, if one is.
    pub fn skip_replay(&mut self) {
        if let (true, Some((clip, t))) = (self.replaying, &mut self.playing) {
            *t = clip.duration();
        }
    }

    /// The moment to draw: the animated shot, or the board at rest.
    pub fn current_frame(&self) -> Frame {
        match (&self.playing, &self.view) {
            (Some((clip, t)), _) => clip.frame(*t),
            (None, Some(v)) => Frame {
                pieces: v.board.pieces().iter().map(|p| (p.id, p.pos)).collect(),
                ..Frame::default()
            },
            _ => Frame::default(),
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use game::{Config, Game, MatchResult, Phase, PieceId, Shot, WinReason};
    use glam::DVec2;

    /// A match just begun, seen from `you`'s seat, both seats taken.
    pub(crate) fn seated(you: Option<Seat>) -> MatchState {
        let game = Game::new(Config::default(), 7).unwrap();
        let mut s = MatchState::default();
        s.receive(ServerMessage::MatchState {
            match_id: "m".into(),
            you,
            players: Players {
                first: Some("Anka".into()),
                second: Some("Petka".into()),
            },
            view: game.view(),
        });
        s
    }

    /// White's e-piece flicked straight up at full power, as announced.
    fn white_shot() -> ServerMessage {
        let mut game = Game::new(Config::default(), 7).unwrap();
        let piece = PieceId::new(Side::White, 4).unwrap();
        let shot = Shot::new(piece, DVec2::new(0.0, 2.0), game.config()).unwrap();
        let played = game.play(Side::White, shot).unwrap();
        ServerMessage::ShotPlayed {
            outcome: played.outcome,
            film: played.film,
            after: played.after,
            view: game.view(),
        }
    }

    #[test]
    fn announcements_are_shown_one_after_another_in_the_order_they_came() {
        let mut s = seated(Some(Seat::First));
        s.receive(white_shot());
        s.receive(ServerMessage::TurnPassed { side: Side::White });
        assert_eq!(s.queued(), 2);
        // The shot is taken up first and plays; the pass waits behind it.
        let sounds = s.advance(0.0);
        assert_eq!(sounds, vec![Sound::Flick]);
        assert!(s.playing.is_some());
        assert_eq!(s.queued(), 1);
        // The shot is told once its film has shown it.
        assert_eq!(s.log.len(), 0);
        assert_eq!(s.view.as_ref().unwrap().shots, 0);
        // Once the film has run (at normal speed: only one announcement
        // waits behind it), its result shows, then the pass.
        let duration = s.playing.as_ref().unwrap().0.duration();
        let knocked = s.playing.as_ref().unwrap().0.outcome.knocked_off.len();
        let mut sounds = s.advance(duration * 0.9);
        assert!(s.playing.is_some());
        sounds.extend(s.advance(duration * 0.1 + 0.01));
        // Heard as the film showed them: its collisions, then its falls.
        assert!(
            matches!(sounds.first(), Some(Sound::Clack { .. })),
            "{sounds:?}"
        );
        assert_eq!(
            sounds.iter().filter(|s| **s == Sound::Fall).count(),
            knocked
        );
        assert!(!s.busy());
        let v = s.view.as_ref().unwrap();
        assert_eq!(v.shots, 1);
        assert_eq!(s.outcomes.len(), 1);
        assert_eq!(s.log.len(), 1);
    }

    #[test]
    fn a_shot_knocking_off_two_pieces_is_replayed_at_a_quarter_speed_and_can_be_skipped() {
        let mut s = seated(Some(Seat::First));
        let mut shot = white_shot();
        if let ServerMessage::ShotPlayed { outcome, .. } = &mut shot {
            let p = outcome.knocked_off[0];
            outcome.knocked_off = vec![p, p];
        }
        s.receive(shot);
        s.advance(0.0);
        let duration = s.playing.as_ref().unwrap().0.duration();
        s.advance(duration + 0.01);
        assert!(s.replaying, "the replay follows the shot");
        assert_eq!(s.view.as_ref().unwrap().shots, 0, "its result waits");
        // A quarter speed: half the film's time shows an eighth of it.
        s.advance(duration / 2.0);
        let t = s.playing.as_ref().unwrap().1;
        assert!((t - duration / 8.0).abs() < 1e-9, "{t}");
        s.skip_replay();
        s.advance(0.0);
        assert!(!s.replaying && !s.busy());
        assert_eq!(s.view.as_ref().unwrap().shots, 1);
    }

    #[test]
    fn a_shot_knocking_off_one_piece_is_not_replayed() {
        let mut s = seated(Some(Seat::First));
        s.receive(white_shot());
        s.advance(0.0);
        let duration = s.playing.as_ref().unwrap().0.duration();
        s.advance(duration + 0.01);
        assert!(!s.replaying && !s.busy());
    }

    #[test]
    fn a_full_state_drops_the_announcements_not_yet_shown() {
        let mut s = seated(Some(Seat::First));
        s.receive(white_shot());
        s.advance(0.0);
        s.receive(ServerMessage::PieDecided { swap: false });
        assert!(s.busy());
        let game = Game::new(Config::default(), 7).unwrap();
        s.receive(ServerMessage::MatchState {
            match_id: "m".into(),
            you: Some(Seat::First),
            players: Players::default(),
            view: game.view(),
        });
        assert!(!s.busy());
    }

    #[test]
    fn nobody_aims_in_a_friends_match_until_the_friend_has_joined() {
        let mut s = seated(Some(Seat::First));
        s.players.second = None;
        assert!(!s.may_aim(true));
        s.receive(ServerMessage::PlayerJoined {
            seat: Seat::Second,
            name: "Petka".into(),
        });
        assert!(s.may_aim(true));
    }

    #[test]
    fn a_shot_announced_ends_the_wait_for_the_answer() {
        let mut s = seated(Some(Seat::First));
        s.awaiting = true;
        assert!(!s.may_aim(true));
        s.receive(white_shot());
        assert!(!s.awaiting);
    }

    #[test]
    fn only_the_side_to_shoot_may_aim_and_only_while_connected_and_idle() {
        let white = seated(Some(Seat::First));
        assert!(white.may_aim(true));
        assert!(!white.may_aim(false));
        assert!(!seated(Some(Seat::Second)).may_aim(true));
        assert!(!seated(None).may_aim(true));
        let mut busy = seated(Some(Seat::First));
        busy.receive(ServerMessage::TurnPassed { side: Side::White });
        assert!(!busy.may_aim(true));
    }

    #[test]
    fn the_rematch_button_offers_accepts_or_waits() {
        let mut s = seated(Some(Seat::First));
        assert_eq!(s.rematch_label(), ("Offer a rematch".into(), true));
        s.receive(ServerMessage::RematchOffered { by: Seat::First });
        assert_eq!(s.rematch_label(), ("Rematch offered...".into(), false));
        assert!(s.notice.is_none(), "one's own offer is not announced");
        let mut s = seated(Some(Seat::First));
        s.receive(ServerMessage::RematchOffered { by: Seat::Second });
        assert_eq!(s.rematch_label(), ("Accept the rematch".into(), true));
        assert!(s.rematch_is_theirs());
        assert_eq!(s.notice.unwrap().0, "Petka offers a rematch");
    }

    #[test]
    fn a_started_rematch_names_its_match() {
        let mut s = seated(Some(Seat::First));
        let id = s.receive(ServerMessage::RematchStarted {
            match_id: "next".into(),
        });
        assert_eq!(id.as_deref(), Some("next"));
    }

    #[test]
    fn chat_keeps_only_the_newest_lines() {
        let mut s = seated(None);
        for i in 0..CHAT_LINES + 3 {
            s.receive(ServerMessage::Chat {
                from: Some(Seat::First),
                name: "Anka".into(),
                text: format!("line {i}"),
                phrase: None,
            });
        }
        assert_eq!(s.chat.len(), CHAT_LINES);
        assert_eq!(
            s.chat_shown(Mute::default(), 1),
            [format!("Anka: line {}", CHAT_LINES + 2)]
        );
    }

    fn chat(s: &mut MatchState, from: Option<Seat>, name: &str, phrase: Option<Phrase>) {
        s.receive(ServerMessage::Chat {
            from,
            name: name.into(),
            text: phrase.map_or("hi", Phrase::english).into(),
            phrase,
        });
    }

    #[test]
    fn a_phrase_reads_in_the_readers_language_and_a_spectator_is_marked() {
        let mut s = seated(Some(Seat::First));
        chat(&mut s, Some(Seat::Second), "Petka", Some(Phrase::GoodShot));
        chat(&mut s, None, "Furmanov", None);
        assert_eq!(
            s.chat_shown(Mute::default(), 6),
            ["Petka: Good shot!", "Furmanov (watching): hi"]
        );
    }

    #[test]
    fn muting_hides_the_opponents_or_the_spectators_lines_never_ones_own() {
        let mut s = seated(Some(Seat::First));
        chat(&mut s, Some(Seat::First), "Anka", None);
        chat(&mut s, Some(Seat::Second), "Petka", Some(Phrase::Gg));
        chat(&mut s, None, "Furmanov", Some(Phrase::WellPlayed));
        let players = Mute {
            players: true,
            spectators: false,
        };
        assert_eq!(
            s.chat_shown(players, 6),
            ["Anka: hi", "Furmanov (watching): Well played!"]
        );
        let spectators = Mute {
            players: false,
            spectators: true,
        };
        assert_eq!(s.chat_shown(spectators, 6), ["Anka: hi", "Petka: gg"]);
        // Unmuted, everything said shows again.
        assert_eq!(s.chat_shown(Mute::default(), 6).len(), 3);
    }

    #[test]
    fn the_computers_seat_reads_as_the_computer_of_its_level() {
        assert_eq!(seat_name("bot (easy)"), "computer (easy)");
        assert_eq!(seat_name("Petka"), "Petka");
        assert_eq!(seat_name("bot (Petka)"), "bot (Petka)");
        let mut s = seated(None);
        s.players.second = Some("bot (hard)".into());
        assert_eq!(s.name_of(Seat::Second), "computer (hard)");
    }

    #[test]
    fn the_clock_counts_from_when_it_was_heard() {
        let mut s = seated(Some(Seat::First));
        s.now = 10.0;
        s.receive(ServerMessage::Clock {
            seat: Seat::First,
            side: Side::White,
            remaining_ms: 30_000,
        });
        assert_eq!(s.clock, Some((Seat::First, Side::White, 40.0)));
    }

    #[test]
    fn the_match_over_shows_after_the_shots_before_it() {
        let mut s = seated(Some(Seat::First));
        let mut game = Game::new(Config::default(), 7).unwrap();
        let result = game.resign(Side::Black).unwrap();
        assert!(matches!(
            result,
            MatchResult::Won {
                reason: WinReason::Resignation,
                ..
            }
        ));
        s.receive(white_shot());
        s.receive(ServerMessage::MatchOver {
            result,
            record: game.record().clone(),
        });
        s.advance(0.0);
        assert_eq!(s.view.as_ref().unwrap().phase, Phase::Shooting);
        s.advance(100.0);
        assert_eq!(s.view.as_ref().unwrap().phase, Phase::Over { result });
        assert!(s.final_score.is_some());
    }
}
