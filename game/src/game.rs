//! The match state machine: whose turn it is, the board, the rows, the
//! rounds, the pie rule, resignation, and the record of it all.
//!
//! [`Game::play`] checks a shot against the state (refusing it with a
//! [`ShotError`] and changing nothing), adds the execution noise, resolves
//! it with the engine, applies the turn rule, and when a round ends moves
//! the rows and sets up the next round — or ends the match. Every accepted
//! move is appended to the game's [`MatchRecord`].

use crate::board::Board;
use crate::config::{Config, ConfigError};
use crate::film::Film;
use crate::noise::NoiseKey;
use crate::outcome::{ForfeitReason, MatchResult, Next, RoundEnd, ShotOutcome, WinReason};
use crate::physics_version::PhysicsVersion;
use crate::piece::{PieceId, PIECES_PER_SIDE};
use crate::record::{MatchRecord, RecordedMove};
use crate::rows::Rows;
use crate::rules::{after_round, judge, AfterRound, RoundResult, Verdict};
use crate::secret::NoiseCommitment;
use crate::shot::{check_velocity, Shot, ShotError};
use crate::side::{Seat, Side};
use serde::{Deserialize, Serialize};

/// Where the match stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "phase", rename_all = "kebab-case")]
pub enum Phase {
    /// Waiting for a shot by the side whose turn it is.
    Shooting,
    /// Waiting for Black's pie-rule decision.
    PieDecision,
    /// Finished.
    Over { result: MatchResult },
}

/// Why a pie decision or a resignation was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GameError {
    #[error("the match is over")]
    MatchOver,
    #[error("there is no pie-rule decision to make now")]
    NoPieDecision,
    #[error("the pie-rule decision is black's, not {0}'s")]
    NotYourDecision(Side),
    #[error("it is not {0}'s turn")]
    NotYourTurn(Side),
    #[error("black's pie-rule decision comes first")]
    PieDecisionPending,
}

impl GameError {
    /// The stable wire code of this error.
    pub fn code(&self) -> crate::refusal::ErrorCode {
        use crate::refusal::ErrorCode as C;
        match self {
            GameError::MatchOver => C::MatchOver,
            GameError::NoPieDecision => C::NoPieDecision,
            GameError::NotYourDecision(_) => C::NotYourDecision,
            GameError::NotYourTurn(_) => C::NotYourTurn,
            GameError::PieDecisionPending => C::PieDecisionPending,
        }
    }
}

/// An accepted shot: what it did, and its motion to show.
#[derive(Clone, Debug, PartialEq)]
pub struct Played {
    pub outcome: ShotOutcome,
    pub film: Film,
    /// Where the pieces came to rest (before a round end sets up the next
    /// round's board).
    pub after: Board,
}

/// What anyone watching the match may know (never the noise's secret:
/// knowing it would let a player predict the execution noise; only the
/// commitment to it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct MatchView {
    pub config: Config,
    /// The SHA-256 of the match's noise secret (lowercase hex), fixed
    /// before the first shot; the record reveals the secret when the match
    /// is over, so anyone can check both. Absent only for a match played
    /// again from a record of format 1–3 (a plain seed, no secret).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_commitment: Option<NoiseCommitment>,
    pub phase: Phase,
    /// The side to shoot (after the pie decision, if one is pending).
    pub turn: Side,
    /// Whether the pie rule swapped the seats.
    pub swapped: bool,
    /// The current round, 1-based.
    pub round: u32,
    pub rows: Rows,
    pub board: Board,
    /// Shots played in the match so far.
    pub shots: u32,
}

impl MatchView {
    /// The view after an announced shot: what a client that saw only the
    /// `shot-played` message (no seed, no physics) needs to follow the
    /// match. The board is the film's final scene, which is bit for bit the
    /// board the server's [`Game`] kept.
    pub fn after_shot(&self, outcome: &ShotOutcome, film: &Film) -> MatchView {
        let mut v = self.clone();
        v.shots = outcome.number + 1;
        let after = film.scene_at(film.end);
        v.board = Board::from_pieces(after.bodies.iter().filter_map(|b| {
            PieceId::from_body(b.id)
                .ok()
                .map(|id| crate::board::Piece { id, pos: b.pos })
        }));
        if let Some(RoundEnd {
            next_rows: Some(rows),
            ..
        }) = outcome.round_end
        {
            v.round += 1;
            v.rows = rows;
            v.board = Board::setup(&v.config, rows);
        }
        match outcome.next {
            Next::Shoot { side } => {
                v.phase = Phase::Shooting;
                v.turn = side;
            }
            Next::PieDecision { then } => {
                v.phase = Phase::PieDecision;
                v.turn = then;
            }
            Next::MatchOver { result } => v.phase = Phase::Over { result },
        }
        v
    }

    /// The view after Black's announced pie decision.
    pub fn after_pie(&self, swap: bool) -> MatchView {
        let mut v = self.clone();
        v.swapped ^= swap;
        if v.phase == Phase::PieDecision {
            v.phase = Phase::Shooting;
        }
        v
    }

    /// The view after the side to shoot passed its turn.
    pub fn after_pass(&self) -> MatchView {
        let mut v = self.clone();
        if v.phase == Phase::Shooting {
            v.turn = v.turn.opponent();
        }
        v
    }

    /// The view once the match is over with `result`.
    pub fn after_result(&self, result: MatchResult) -> MatchView {
        let mut v = self.clone();
        v.phase = Phase::Over { result };
        v
    }

    /// The side that may shoot now, if any.
    pub fn to_shoot(&self) -> Option<Side> {
        (self.phase == Phase::Shooting).then_some(self.turn)
    }
}

/// A match in progress (or over).
#[derive(Clone, Debug)]
pub struct Game {
    config: Config,
    noise: NoiseKey,
    physics: PhysicsVersion,
    rows: Rows,
    board: Board,
    round: u32,
    round_first: Side,
    turn: Side,
    phase: Phase,
    swapped: bool,
    shots: u32,
    record: MatchRecord,
}

impl Game {
    /// A new match: round 1, White on the first row, Black on the last,
    /// White to shoot. `key` drives the execution noise (if enabled): a
    /// server's random [`crate::NoiseSecret`], or a number for a
    /// reproducible local game (see [`NoiseKey`]'s `From<u64>`). The record
    /// commits to the key's secret and reveals it when the match is over.
    /// It is played under the current physics ([`PhysicsVersion::CURRENT`]).
    pub fn new(config: Config, key: impl Into<NoiseKey>) -> Result<Game, ConfigError> {
        Game::with_physics(config, key, PhysicsVersion::CURRENT)
    }

    /// A new match played under `physics`: how a recorded match is played
    /// again, under the physics it was recorded with.
    pub fn with_physics(
        config: Config,
        key: impl Into<NoiseKey>,
        physics: PhysicsVersion,
    ) -> Result<Game, ConfigError> {
        config.validate()?;
        let noise = key.into();
        let rows = Rows::initial();
        Ok(Game {
            board: Board::setup(&config, rows),
            record: MatchRecord::new(config.clone(), &noise, physics),
            config,
            noise,
            physics,
            rows,
            round: 1,
            round_first: Side::White,
            turn: Side::White,
            phase: Phase::Shooting,
            swapped: false,
            shots: 0,
        })
    }

    pub fn config(&self) -> &Config {
        &self.config
    }
    /// What the match's noise is drawn from (the server's secret: never
    /// show it before the match is over).
    pub fn noise_key(&self) -> &NoiseKey {
        &self.noise
    }
    /// The public commitment to the noise's secret.
    pub fn noise_commitment(&self) -> Option<NoiseCommitment> {
        self.record.commitment()
    }
    /// The physics the match is played under.
    pub fn physics(&self) -> PhysicsVersion {
        self.physics
    }
    pub fn board(&self) -> &Board {
        &self.board
    }
    pub fn rows(&self) -> Rows {
        self.rows
    }
    /// The current round, 1-based.
    pub fn round(&self) -> u32 {
        self.round
    }
    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// Shots played so far.
    pub fn shots(&self) -> u32 {
        self.shots
    }
    /// The record of every move so far: the public one, which commits to
    /// the noise's secret and reveals it only once the match is over.
    pub fn record(&self) -> &MatchRecord {
        &self.record
    }
    /// The record with the noise's secret revealed even while the match is
    /// on: what a server's own store keeps to resume the match from. Never
    /// publish it before the match is over ([`Game::record`] is the public
    /// one).
    pub fn private_record(&self) -> MatchRecord {
        let mut record = self.record.clone();
        record.reveal(&self.noise);
        record
    }
    /// Whether the pie rule swapped the seats.
    pub fn swapped(&self) -> bool {
        self.swapped
    }
    /// The colour a seat plays.
    pub fn side_of(&self, seat: Seat) -> Side {
        seat.side(self.swapped)
    }
    /// The seat playing a colour.
    pub fn seat_of(&self, side: Side) -> Seat {
        Seat::of(side, self.swapped)
    }

    /// The side that may shoot now (`None` while a pie decision is pending
    /// or once the match is over).
    pub fn to_shoot(&self) -> Option<Side> {
        (self.phase == Phase::Shooting).then_some(self.turn)
    }

    /// How the match ended, if it has.
    pub fn result(&self) -> Option<MatchResult> {
        match self.phase {
            Phase::Over { result } => Some(result),
            _ => None,
        }
    }

    /// Whether the match is over.
    pub fn is_over(&self) -> bool {
        self.result().is_some()
    }

    /// The state a client needs to show the match.
    pub fn view(&self) -> MatchView {
        MatchView {
            config: self.config.clone(),
            noise_commitment: self.noise_commitment(),
            phase: self.phase,
            turn: self.turn,
            swapped: self.swapped,
            round: self.round,
            rows: self.rows,
            board: self.board.clone(),
            shots: self.shots,
        }
    }

    /// Whether `side` may play `shot` now.
    pub fn check(&self, side: Side, shot: &Shot) -> Result<(), ShotError> {
        match self.phase {
            Phase::Over { .. } => return Err(ShotError::MatchOver),
            Phase::PieDecision => return Err(ShotError::PieDecisionPending),
            Phase::Shooting => {}
        }
        if side != self.turn {
            return Err(ShotError::NotYourTurn {
                side,
                turn: self.turn,
            });
        }
        let piece = shot.piece();
        if piece.side() != side {
            return Err(ShotError::NotYourPiece { piece, side });
        }
        if !self.board.contains(piece) {
            return Err(ShotError::PieceOffBoard(piece));
        }
        // The shot may have been built against another configuration.
        check_velocity(shot.velocity(), self.config.max_speed)
    }

    /// Plays `shot` for `side`: resolves it to the end of its chain and
    /// applies the rules. A refused shot changes nothing.
    pub fn play(&mut self, side: Side, shot: Shot) -> Result<Played, ShotError> {
        self.check(side, &shot)?;
        let aimed = shot.velocity();
        let played = self
            .physics
            .played(&self.config, &self.noise, self.shots, aimed);
        let res = self
            .physics
            .resolve(&self.config, &self.board, shot.piece(), played)
            .map_err(ShotError::Physics)?;
        // Accepted: commit.
        let number = self.shots;
        let round = self.round;
        self.shots += 1;
        self.board = res.board.clone();
        let mut round_end = None;
        match judge(side, &res.knocked_off, &self.board) {
            Verdict::ShootAgain => {}
            Verdict::PassTurn => self.turn = side.opponent(),
            Verdict::RoundOver(result) => {
                let next_rows = self.end_round(result);
                round_end = Some(RoundEnd { result, next_rows });
            }
        }
        if self.config.variants.pie_rule && number == 0 && !self.is_over() {
            self.phase = Phase::PieDecision;
        }
        let next = match self.phase {
            Phase::Shooting => Next::Shoot { side: self.turn },
            Phase::PieDecision => Next::PieDecision { then: self.turn },
            Phase::Over { result } => Next::MatchOver { result },
        };
        let outcome = ShotOutcome {
            number,
            round,
            shooter: side,
            piece: shot.piece(),
            aimed,
            played,
            events: res.events,
            knocked_off: res.knocked_off,
            duration: res.end.t,
            end_reason: res.end.reason,
            round_end,
            next,
        };
        self.log(RecordedMove::Shot(outcome.clone()));
        Ok(Played {
            outcome,
            film: res.film,
            after: res.board,
        })
    }

    /// Ends the round; returns the next round's rows, or `None` if the match
    /// is over.
    fn end_round(&mut self, result: RoundResult) -> Option<Rows> {
        let flawless = match result {
            RoundResult::Won(w) => self.board.count(w) == PIECES_PER_SIDE as usize,
            RoundResult::Draw => false,
        };
        let variants = &self.config.variants;
        match after_round(variants, self.rows, self.round_first, result, flawless) {
            AfterRound::Over(result) => {
                self.phase = Phase::Over { result };
                None
            }
            AfterRound::Next { rows, opens } => {
                self.rows = rows;
                self.start_round(opens);
                Some(rows)
            }
        }
    }

    fn start_round(&mut self, first: Side) {
        self.round += 1;
        self.round_first = first;
        self.turn = first;
        self.board = Board::setup(&self.config, self.rows);
    }

    /// Black's pie-rule decision: `swap` exchanges the seats (the player who
    /// was Black takes White's position and White's turn, if it has one).
    pub fn decide_pie(&mut self, side: Side, swap: bool) -> Result<(), GameError> {
        match self.phase {
            Phase::Over { .. } => return Err(GameError::MatchOver),
            Phase::Shooting => return Err(GameError::NoPieDecision),
            Phase::PieDecision => {}
        }
        if side != Side::Black {
            return Err(GameError::NotYourDecision(side));
        }
        self.swapped ^= swap;
        self.phase = Phase::Shooting;
        self.log(RecordedMove::Pie { swap });
        Ok(())
    }

    /// `side` resigns: the other side wins the match.
    pub fn resign(&mut self, side: Side) -> Result<MatchResult, GameError> {
        self.concede(side, WinReason::Resignation, RecordedMove::Resign { side })
    }

    /// Ends the match with a win for `side`'s opponent, recording `recorded`.
    fn concede(
        &mut self,
        side: Side,
        reason: WinReason,
        recorded: RecordedMove,
    ) -> Result<MatchResult, GameError> {
        if self.is_over() {
            return Err(GameError::MatchOver);
        }
        let result = MatchResult::Won {
            side: side.opponent(),
            reason,
        };
        self.phase = Phase::Over { result };
        self.log(recorded);
        Ok(result)
    }

    /// `side`'s turn passes without a shot (its turn clock ran out).
    pub fn pass(&mut self, side: Side) -> Result<(), GameError> {
        match self.phase {
            Phase::Over { .. } => return Err(GameError::MatchOver),
            Phase::PieDecision => return Err(GameError::PieDecisionPending),
            Phase::Shooting => {}
        }
        if side != self.turn {
            return Err(GameError::NotYourTurn(side));
        }
        self.turn = side.opponent();
        self.log(RecordedMove::Pass { side });
        Ok(())
    }

    /// `side` loses without playing on (`reason` says why): the other side
    /// wins the match.
    pub fn forfeit(&mut self, side: Side, reason: ForfeitReason) -> Result<MatchResult, GameError> {
        self.concede(
            side,
            reason.win_reason(),
            RecordedMove::Forfeit { side, reason },
        )
    }

    /// Appends an accepted move to the record, revealing the noise's
    /// secret there once the match is over.
    fn log(&mut self, accepted: RecordedMove) {
        self.record.moves.push(accepted);
        if self.is_over() {
            self.record.reveal(&self.noise);
        }
    }

    /// Sets up a position by hand (tests of particular situations).
    #[cfg(test)]
    pub(crate) fn set_position(&mut self, board: Board, rows: Rows, turn: Side) {
        self.board = board;
        self.rows = rows;
        self.turn = turn;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::board::{square_centre, Piece};
    use crate::config::NoiseConfig;
    use crate::piece::PieceId;
    use glam::DVec2;

    fn w(f: u8) -> PieceId {
        PieceId::new(Side::White, f).unwrap()
    }
    fn b(f: u8) -> PieceId {
        PieceId::new(Side::Black, f).unwrap()
    }
    fn at(c: &Config, id: PieceId, file: u8, rank: u8) -> Piece {
        Piece {
            id,
            pos: square_centre(c, file, rank),
        }
    }
    fn shot(g: &Game, id: PieceId, vx: f64, vy: f64) -> Shot {
        Shot::new(id, DVec2::new(vx, vy), g.config()).unwrap()
    }
    fn game_with(variants: impl FnOnce(&mut Config)) -> Game {
        let mut c = Config::default();
        variants(&mut c);
        Game::new(c, 11).unwrap()
    }
    /// A position where a horizontal shot of White's piece cuts Black's
    /// piece (standing half a square from the right edge) at 45 degrees:
    /// Black's piece flies off the right edge, White's carries on up and
    /// off the top edge. `extra` pieces stand far away.
    fn cut_shot_position(g: &mut Game, extra: &[Piece]) -> Shot {
        let c = g.config().clone();
        let l = c.board_size();
        let target = DVec2::new(l - 0.5 * c.square, l - 1.5 * c.square);
        let offset = 2.0 * c.piece_radius * std::f64::consts::FRAC_1_SQRT_2;
        let shooter = DVec2::new(l - 4.5 * c.square, target.y + offset);
        let mut pieces = vec![
            Piece {
                id: w(0),
                pos: shooter,
            },
            Piece {
                id: b(0),
                pos: target,
            },
        ];
        pieces.extend_from_slice(extra);
        g.set_position(Board::from_pieces(pieces), g.rows(), Side::White);
        shot(g, w(0), c.max_speed, 0.0)
    }

    #[test]
    fn a_view_followed_through_announcements_alone_equals_the_games_own_view() {
        use crate::noise::SplitMix64;
        use crate::testing::{random_shot, variant_config};
        for k in 0..6u64 {
            let mut g = Game::new(variant_config(k), 100 + k).unwrap();
            let mut rng = SplitMix64::new(k);
            let mut view = g.view();
            for _ in 0..300 {
                match g.phase() {
                    Phase::Over { .. } => break,
                    Phase::PieDecision => {
                        let swap = k % 2 == 0;
                        g.decide_pie(Side::Black, swap).unwrap();
                        view = view.after_pie(swap);
                    }
                    Phase::Shooting => {
                        let side = g.to_shoot().unwrap();
                        let shot = random_shot(&g, side, &mut rng);
                        let p = g.play(side, shot).unwrap();
                        view = view.after_shot(&p.outcome, &p.film);
                    }
                }
                assert_eq!(view, g.view(), "variant {k} after {} shots", g.shots());
            }
        }
    }

    #[test]
    fn a_pass_hands_the_turn_over_without_moving_anything_and_is_recorded() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let before = g.board().clone();
        assert_eq!(
            g.pass(Side::Black),
            Err(GameError::NotYourTurn(Side::Black))
        );
        let view = g.view();
        g.pass(Side::White).unwrap();
        assert_eq!(g.to_shoot(), Some(Side::Black));
        assert_eq!(g.board(), &before);
        assert_eq!(g.shots(), 0);
        assert_eq!(g.view(), view.after_pass());
        assert_eq!(
            g.record().moves.last(),
            Some(&RecordedMove::Pass { side: Side::White })
        );
        let replayed = crate::Replay::new(g.private_record()).unwrap();
        assert_eq!(replayed.game().view(), g.view());
    }

    #[test]
    fn a_forfeit_ends_the_match_for_the_other_side_with_its_reason() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let r = g.forfeit(Side::White, ForfeitReason::Timeouts).unwrap();
        assert_eq!(
            r,
            MatchResult::Won {
                side: Side::Black,
                reason: WinReason::Timeouts
            }
        );
        assert_eq!(g.pass(Side::White), Err(GameError::MatchOver));
        assert_eq!(
            g.forfeit(Side::Black, ForfeitReason::Abandoned),
            Err(GameError::MatchOver)
        );
        let replayed = crate::Replay::new(g.record().clone()).unwrap();
        assert_eq!(replayed.game().result(), Some(r));
    }

    #[test]
    fn round_one_starts_with_white_on_the_first_row_to_shoot() {
        let g = Game::new(Config::default(), 0).unwrap();
        assert_eq!(g.to_shoot(), Some(Side::White));
        assert_eq!(g.round(), 1);
        assert_eq!(g.rows(), Rows::initial());
        assert_eq!(g.board().count(Side::White), 8);
        assert_eq!(g.board().count(Side::Black), 8);
        assert_eq!(g.phase(), Phase::Shooting);
    }

    #[test]
    fn an_unplayable_config_is_refused() {
        let c = Config {
            g: -1.0,
            ..Config::default()
        };
        assert!(Game::new(c, 0).is_err());
    }

    #[test]
    fn a_shot_out_of_turn_is_refused_and_changes_nothing() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let before = g.view();
        let e = g.play(Side::Black, shot(&g, b(0), 0.0, -1.0)).unwrap_err();
        assert_eq!(
            e,
            ShotError::NotYourTurn {
                side: Side::Black,
                turn: Side::White
            }
        );
        assert_eq!(g.view(), before);
        assert!(g.record().moves.is_empty());
    }

    #[test]
    fn shooting_an_enemy_piece_is_refused() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let e = g.play(Side::White, shot(&g, b(0), 0.0, -1.0)).unwrap_err();
        assert_eq!(
            e,
            ShotError::NotYourPiece {
                piece: b(0),
                side: Side::White
            }
        );
        assert_eq!(g.shots(), 0);
    }

    #[test]
    fn a_piece_no_longer_on_the_board_cannot_be_shot() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        // Knock Black's e-piece off: White shoots again.
        g.play(Side::White, shot(&g, w(4), 0.0, 2.0)).unwrap();
        // White's a-piece straight off its own edge: the turn passes.
        let out = g
            .play(Side::White, shot(&g, w(0), 0.0, -0.5))
            .unwrap()
            .outcome;
        assert_eq!(out.knocked_off, vec![w(0)]);
        g.set_position(g.board().clone(), g.rows(), Side::White);
        let before = g.view();
        assert_eq!(
            g.play(Side::White, shot(&g, w(0), 0.0, 1.0)),
            Err(ShotError::PieceOffBoard(w(0)))
        );
        assert_eq!(g.view(), before);
    }

    #[test]
    fn a_shot_built_for_a_faster_config_is_refused_as_too_fast() {
        let fast = Config {
            max_speed: 10.0,
            ..Config::default()
        };
        let mut g = Game::new(Config::default(), 0).unwrap();
        let s = Shot::new(w(0), DVec2::new(0.0, 5.0), &fast).unwrap();
        assert!(matches!(
            g.play(Side::White, s),
            Err(ShotError::TooFast { .. })
        ));
    }

    #[test]
    fn a_shot_that_hits_nothing_is_legal_and_passes_the_turn() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let v = g.config().speed_for_distance(g.config().square);
        let out = g.play(Side::White, shot(&g, w(2), 0.0, v)).unwrap().outcome;
        assert!(out.knocked_off.is_empty());
        assert_eq!(out.next, Next::Shoot { side: Side::Black });
        assert_eq!(g.to_shoot(), Some(Side::Black));
        let moved = g.board().piece(w(2)).unwrap().pos - square_centre(g.config(), 2, 0);
        assert!((moved.y - g.config().square).abs() < 1e-12);
    }

    #[test]
    fn knocking_off_an_enemy_and_none_of_your_own_earns_another_shot() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let out = g
            .play(Side::White, shot(&g, w(4), 0.0, 2.0))
            .unwrap()
            .outcome;
        assert_eq!(out.knocked_off, vec![b(4)]);
        assert_eq!(out.next, Next::Shoot { side: Side::White });
        assert_eq!(g.to_shoot(), Some(Side::White));
        assert_eq!(g.board().count(Side::Black), 7);
    }

    #[test]
    fn losing_your_own_piece_while_knocking_off_an_enemy_passes_the_turn() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let c = g.config().clone();
        let s = cut_shot_position(&mut g, &[at(&c, w(1), 0, 0), at(&c, b(1), 1, 0)]);
        let out = g.play(Side::White, s).unwrap().outcome;
        let mut off = out.knocked_off.clone();
        off.sort();
        assert_eq!(off, vec![w(0), b(0)], "the position must knock both off");
        assert_eq!(out.round_end, None);
        assert_eq!(g.to_shoot(), Some(Side::Black));
    }

    #[test]
    fn the_last_pieces_of_both_sides_falling_on_one_shot_draw_the_round_and_keep_the_rows() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let s = cut_shot_position(&mut g, &[]);
        let out = g.play(Side::White, s).unwrap().outcome;
        assert_eq!(out.knocked_off.len(), 2);
        assert_eq!(
            out.round_end,
            Some(RoundEnd {
                result: RoundResult::Draw,
                next_rows: Some(Rows::initial())
            })
        );
        assert_eq!(g.round(), 2);
        assert_eq!(g.rows(), Rows::initial());
        // The side that started the drawn round starts again, on a fresh board.
        assert_eq!(g.to_shoot(), Some(Side::White));
        assert_eq!(g.board(), &Board::setup(g.config(), Rows::initial()));
    }

    /// White knocks off Black's last piece (on file e, straight ahead).
    fn white_wins_round(g: &mut Game, rows: Rows, white: &[Piece]) -> ShotOutcome {
        let c = g.config().clone();
        let mut pieces = white.to_vec();
        pieces.push(at(&c, b(4), 4, 7));
        pieces.push(at(&c, w(4), 4, 3));
        g.set_position(Board::from_pieces(pieces), rows, Side::White);
        g.play(Side::White, shot(g, w(4), 0.0, 2.0))
            .unwrap()
            .outcome
    }

    #[test]
    fn the_round_winner_moves_its_row_forward_and_shoots_first() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let out = white_wins_round(&mut g, Rows::initial(), &[]);
        assert_eq!(out.knocked_off, vec![b(4)]);
        let next = Rows::new(1, 7).unwrap();
        assert_eq!(
            out.round_end,
            Some(RoundEnd {
                result: RoundResult::Won(Side::White),
                next_rows: Some(next)
            })
        );
        assert_eq!(
            (g.round(), g.rows(), g.to_shoot()),
            (2, next, Some(Side::White))
        );
        assert_eq!(g.board(), &Board::setup(g.config(), next));
        assert_eq!(
            g.board().piece(w(0)).unwrap().pos,
            square_centre(g.config(), 0, 1)
        );
    }

    #[test]
    fn under_the_alternate_and_loser_openings_black_opens_the_round_after_whites_win() {
        use crate::rules::Opening;
        for opening in [Opening::Alternate, Opening::Loser] {
            let mut g = game_with(|c| c.variants.opening = opening);
            let out = white_wins_round(&mut g, Rows::initial(), &[]);
            assert_eq!(out.next, Next::Shoot { side: Side::Black });
            assert_eq!((g.round(), g.to_shoot()), (2, Some(Side::Black)));
            assert_eq!(g.rows(), Rows::new(1, 7).unwrap(), "the rows move as ever");
        }
        // Alternating after a drawn round: the other side opens.
        let mut g = game_with(|c| c.variants.opening = Opening::Alternate);
        let s = cut_shot_position(&mut g, &[]);
        g.play(Side::White, s).unwrap();
        assert_eq!(
            (g.rows(), g.to_shoot()),
            (Rows::initial(), Some(Side::Black))
        );
    }

    #[test]
    fn a_config_with_the_default_opening_is_written_as_before_and_reads_back() {
        let json = serde_json::to_string(&Config::standard()).unwrap();
        assert!(!json.contains("opening"), "{json}");
        let mut c = Config::standard();
        c.variants.opening = crate::rules::Opening::Alternate;
        let json = serde_json::to_string(&c).unwrap();
        assert!(json.contains(r#""opening":"alternate""#), "{json}");
        assert_eq!(serde_json::from_str::<Config>(&json).unwrap(), c);
    }

    #[test]
    fn a_black_round_win_moves_blacks_row_down_and_black_shoots_first() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let c = g.config().clone();
        let board = Board::from_pieces([at(&c, w(4), 4, 0), at(&c, b(4), 4, 4)]);
        g.set_position(board, Rows::initial(), Side::Black);
        let out = g
            .play(Side::Black, shot(&g, b(4), 0.0, -2.0))
            .unwrap()
            .outcome;
        assert_eq!(out.knocked_off, vec![w(4)]);
        assert_eq!(g.rows(), Rows::new(0, 6).unwrap());
        assert_eq!(g.to_shoot(), Some(Side::Black));
    }

    #[test]
    fn once_the_rows_meet_the_winner_advances_and_the_loser_is_pushed_back() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        white_wins_round(&mut g, Rows::new(3, 4).unwrap(), &[]);
        assert_eq!(g.rows(), Rows::new(4, 5).unwrap());
        assert_eq!(
            g.board().piece(b(0)).unwrap().pos,
            square_centre(g.config(), 0, 5)
        );
    }

    #[test]
    fn a_row_reaching_the_far_edge_wins_the_match_and_then_nothing_more_is_played() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let out = white_wins_round(&mut g, Rows::new(6, 7).unwrap(), &[]);
        let result = MatchResult::Won {
            side: Side::White,
            reason: WinReason::FarEdge,
        };
        assert_eq!(out.next, Next::MatchOver { result });
        assert_eq!(out.round_end.unwrap().next_rows, None);
        assert_eq!(g.result(), Some(result));
        assert_eq!(g.to_shoot(), None);
        let before = g.view();
        assert_eq!(
            g.play(Side::White, shot(&g, w(4), 0.0, 1.0)),
            Err(ShotError::MatchOver)
        );
        assert_eq!(
            g.play(Side::Black, shot(&g, b(4), 0.0, 1.0)),
            Err(ShotError::MatchOver)
        );
        assert_eq!(g.resign(Side::Black), Err(GameError::MatchOver));
        assert_eq!(g.view(), before);
    }

    #[test]
    fn two_row_variant_advances_two_rows_after_a_round_won_without_losing_a_piece() {
        let c = Config::default();
        let full_row: Vec<Piece> = (0..8)
            .filter(|&f| f != 4)
            .map(|f| at(&c, w(f), f, 0))
            .collect();
        let mut g = game_with(|c| c.variants.two_row_advance = true);
        white_wins_round(&mut g, Rows::initial(), &full_row);
        assert_eq!(g.rows(), Rows::new(2, 7).unwrap());
        // A piece short: one row only.
        let mut g = game_with(|c| c.variants.two_row_advance = true);
        white_wins_round(&mut g, Rows::initial(), &full_row[1..]);
        assert_eq!(g.rows(), Rows::new(1, 7).unwrap());
        // Without the variant: one row.
        let mut g = Game::new(c.clone(), 0).unwrap();
        white_wins_round(&mut g, Rows::initial(), &full_row);
        assert_eq!(g.rows(), Rows::new(1, 7).unwrap());
    }

    #[test]
    fn quick_match_is_decided_by_its_single_round() {
        let mut g = game_with(|c| c.variants.quick_match = true);
        let out = white_wins_round(&mut g, Rows::initial(), &[]);
        let result = MatchResult::Won {
            side: Side::White,
            reason: WinReason::QuickMatch,
        };
        assert_eq!(out.next, Next::MatchOver { result });
        assert_eq!(g.round(), 1);
        let mut g = game_with(|c| c.variants.quick_match = true);
        let s = cut_shot_position(&mut g, &[]);
        g.play(Side::White, s).unwrap();
        assert_eq!(g.result(), Some(MatchResult::Draw));
    }

    #[test]
    fn pie_rule_lets_black_swap_seats_after_whites_first_shot() {
        let mut g = game_with(|c| c.variants.pie_rule = true);
        assert_eq!(
            g.decide_pie(Side::Black, true),
            Err(GameError::NoPieDecision)
        );
        let v = g.config().speed_for_distance(g.config().square);
        let out = g.play(Side::White, shot(&g, w(0), 0.0, v)).unwrap().outcome;
        assert_eq!(out.next, Next::PieDecision { then: Side::Black });
        assert_eq!(g.phase(), Phase::PieDecision);
        assert_eq!(g.to_shoot(), None);
        // No shot until Black decides, and only Black decides.
        assert_eq!(
            g.play(Side::Black, shot(&g, b(0), 0.0, -1.0)),
            Err(ShotError::PieDecisionPending)
        );
        assert_eq!(
            g.decide_pie(Side::White, true),
            Err(GameError::NotYourDecision(Side::White))
        );
        assert_eq!(g.side_of(Seat::First), Side::White);
        g.decide_pie(Side::Black, true).unwrap();
        assert!(g.swapped());
        assert_eq!(g.side_of(Seat::First), Side::Black);
        assert_eq!(g.seat_of(Side::White), Seat::Second);
        assert_eq!(g.to_shoot(), Some(Side::Black));
        assert_eq!(
            g.decide_pie(Side::Black, false),
            Err(GameError::NoPieDecision)
        );
        // The decision is offered once per match.
        g.play(Side::Black, shot(&g, b(0), 0.0, -0.3)).unwrap();
        g.play(Side::White, shot(&g, w(1), 0.0, 0.3)).unwrap();
        assert_eq!(g.phase(), Phase::Shooting);
    }

    #[test]
    fn pie_rule_declined_keeps_the_seats() {
        let mut g = game_with(|c| c.variants.pie_rule = true);
        g.play(Side::White, shot(&g, w(0), 0.0, 0.3)).unwrap();
        g.decide_pie(Side::Black, false).unwrap();
        assert!(!g.swapped());
        assert_eq!(g.side_of(Seat::Second), Side::Black);
        assert_eq!(g.to_shoot(), Some(Side::Black));
    }

    #[test]
    fn pie_decision_after_a_first_shot_that_earned_another_keeps_whites_turn() {
        let mut g = game_with(|c| c.variants.pie_rule = true);
        let out = g
            .play(Side::White, shot(&g, w(4), 0.0, 2.0))
            .unwrap()
            .outcome;
        assert_eq!(out.next, Next::PieDecision { then: Side::White });
        g.decide_pie(Side::Black, true).unwrap();
        // The swapped-in player (seat Second) now plays White's extra shot.
        assert_eq!(g.to_shoot(), Some(Side::White));
        assert_eq!(g.seat_of(Side::White), Seat::Second);
    }

    #[test]
    fn resigning_gives_the_match_to_the_other_side() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let r = g.resign(Side::White).unwrap();
        assert_eq!(
            r,
            MatchResult::Won {
                side: Side::Black,
                reason: WinReason::Resignation
            }
        );
        assert_eq!(r.winner(), Some(Side::Black));
        assert!(g.is_over());
        assert_eq!(
            g.record().moves,
            vec![RecordedMove::Resign { side: Side::White }]
        );
    }

    #[test]
    fn execution_noise_changes_the_played_velocity_reproducibly() {
        let noisy = |c: &mut Config| {
            c.variants.noise = Some(NoiseConfig {
                angle_sigma: 0.02,
                speed_sigma: 0.05,
            })
        };
        let mut g1 = game_with(noisy);
        let mut g2 = game_with(noisy);
        let o1 = g1
            .play(Side::White, shot(&g1, w(3), 0.0, 1.0))
            .unwrap()
            .outcome;
        let o2 = g2
            .play(Side::White, shot(&g2, w(3), 0.0, 1.0))
            .unwrap()
            .outcome;
        assert_eq!(o1.aimed, DVec2::new(0.0, 1.0));
        assert_ne!(o1.played, o1.aimed);
        assert_eq!(o1.played.x.to_bits(), o2.played.x.to_bits());
        assert_eq!(o1.played.y.to_bits(), o2.played.y.to_bits());
        assert!((o1.played.length() - 1.0).abs() < 0.3);
    }

    #[test]
    fn every_accepted_move_is_recorded_with_its_outcome() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let p1 = g.play(Side::White, shot(&g, w(4), 0.0, 2.0)).unwrap();
        let p2 = g.play(Side::White, shot(&g, w(0), 0.0, 0.2)).unwrap();
        assert_eq!(
            g.record().moves,
            vec![
                RecordedMove::Shot(p1.outcome.clone()),
                RecordedMove::Shot(p2.outcome.clone())
            ]
        );
        assert_eq!((p1.outcome.number, p2.outcome.number), (0, 1));
        assert!(p1
            .outcome
            .events
            .iter()
            .any(|e| e.kind.name() == "region-exit"));
        assert_eq!(p1.outcome.duration, p1.film.end);
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::noise::SplitMix64;
    use crate::testing::{random_match, random_shot, variant_config};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

        #[test]
        fn piece_counts_never_grow_within_a_round(seed in any::<u64>(), variant in 0u64..5) {
            let mut game = Game::new(variant_config(variant), seed).unwrap();
            let mut rng = SplitMix64::new(seed);
            for _ in 0..60 {
                if game.is_over() {
                    break;
                }
                if game.phase() == Phase::PieDecision {
                    game.decide_pie(Side::Black, seed & 1 == 0).unwrap();
                    continue;
                }
                let side = game.to_shoot().unwrap();
                let before = [game.board().count(Side::White), game.board().count(Side::Black)];
                let round = game.round();
                let out = game.play(side, random_shot(&game, side, &mut rng)).unwrap().outcome;
                if game.round() == round {
                    let after = [game.board().count(Side::White), game.board().count(Side::Black)];
                    prop_assert!(after[0] <= before[0] && after[1] <= before[1]);
                    prop_assert_eq!(before[0] + before[1] - after[0] - after[1], out.knocked_off.len());
                } else {
                    prop_assert!(out.round_end.is_some());
                }
                prop_assert!(game.board().pieces().len() <= 16);
            }
        }

        #[test]
        fn a_match_between_random_players_always_ends(seed in any::<u64>(), variant in 0u64..5) {
            let (game, _) = random_match(variant_config(variant), seed, 20_000);
            prop_assert!(game.is_over());
            prop_assert!(game.to_shoot().is_none());
        }

        #[test]
        fn a_quick_match_between_random_players_always_ends(seed in any::<u64>()) {
            let mut c = variant_config(seed);
            c.variants.quick_match = true;
            let (game, _) = random_match(c, seed, 5_000);
            prop_assert_eq!(game.round(), 1);
            prop_assert!(game.is_over());
        }
    }
}
