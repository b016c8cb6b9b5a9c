//! The match told in words: one line per shot for the panel's shot log
//! ("you knocked off 2 — shoot again") and the end-of-match summary
//! (rounds won by each side, shots played), both from the shots'
//! announced outcomes alone.

use crate::i18n::t;
use game::{Next, RoundResult, ShotOutcome, Side};

/// The side's name for people ("White", "Белые").
pub fn side_name(s: Side) -> String {
    match s {
        Side::White => t!("side-white"),
        Side::Black => t!("side-black"),
    }
}

/// The side as the messages' selectors name it (`white`, `black`).
pub fn side_key(s: Side) -> &'static str {
    match s {
        Side::White => "white",
        Side::Black => "black",
    }
}

/// One line about a shot, told to the player of `me` (`None`: a spectator).
/// `goes_on`: whether the match went on after it (false once it ended by
/// resignation or forfeit), so "shoot again" is said only of a shot that
/// is really followed by the same side's next one.
pub fn shot_line(o: &ShotOutcome, me: Option<Side>, goes_on: bool) -> String {
    let mine = me == Some(o.shooter);
    let who = if mine {
        t!("shot-who-you")
    } else {
        side_name(o.shooter)
    };
    let theirs = o
        .knocked_off
        .iter()
        .filter(|p| p.side() != o.shooter)
        .count();
    let own = o.knocked_off.len() - theirs;
    let mut line = match (theirs, own) {
        (0, 0) => t!("shot-nothing", who = who),
        (t, 0) => t!("shot-knocked", who = who, taken = t),
        (0, l) => t!("shot-lost", who = who, lost = l),
        (t, l) => t!("shot-knocked-lost", who = who, taken = t, lost = l),
    };
    let next = match (o.round_end.map(|r| r.result), o.next) {
        (_, Next::MatchOver { .. }) => Some(t!("shot-then-match-over")),
        (Some(RoundResult::Won(s)), _) if me == Some(s) => Some(t!("shot-then-you-won-round")),
        (Some(RoundResult::Won(s)), _) => Some(t!("shot-then-side-won-round", side = side_key(s))),
        (Some(RoundResult::Draw), _) => Some(t!("shot-then-round-drawn")),
        (None, Next::Shoot { side }) | (None, Next::PieDecision { then: side })
            if side == o.shooter && goes_on =>
        {
            if mine {
                Some(t!("shot-then-you-again"))
            } else {
                Some(t!("shot-then-again"))
            }
        }
        (None, _) => None,
    };
    if let Some(next) = next {
        line.push_str(" — ");
        line.push_str(&next);
    }
    line
}

/// How a match went, round by round.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Score {
    pub white_rounds: u32,
    pub black_rounds: u32,
    pub drawn_rounds: u32,
    pub shots: u32,
}

impl Score {
    /// The score of the shots `outcomes` (in order).
    pub fn of<'a>(outcomes: impl IntoIterator<Item = &'a ShotOutcome>) -> Score {
        let mut s = Score::default();
        for o in outcomes {
            s.shots += 1;
            match o.round_end.map(|r| r.result) {
                Some(RoundResult::Won(Side::White)) => s.white_rounds += 1,
                Some(RoundResult::Won(Side::Black)) => s.black_rounds += 1,
                Some(RoundResult::Draw) => s.drawn_rounds += 1,
                None => {}
            }
        }
        s
    }

    /// "Rounds: White 2 · Black 1" (and the drawn ones, if any).
    pub fn rounds_line(&self) -> String {
        let mut l = t!(
            "score-rounds-won",
            white = self.white_rounds,
            black = self.black_rounds
        );
        if self.drawn_rounds > 0 {
            l.push_str(" · ");
            l.push_str(&t!("score-rounds-drawn", drawn = self.drawn_rounds));
        }
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{PieceId, RoundEnd};

    fn pid(side: Side, file: u8) -> PieceId {
        PieceId::new(side, file).expect("a file on the board")
    }

    /// An outcome of `shooter` that knocked off `off` and leads to `next`.
    fn outcome(
        shooter: Side,
        off: &[PieceId],
        next: Next,
        round: Option<RoundResult>,
    ) -> ShotOutcome {
        let json = serde_json::json!({
            "number": 0, "round": 1, "shooter": shooter, "piece": pid(shooter, 0),
            "aimed": [0.0, 1.0], "played": [0.0, 1.0], "events": [], "knocked_off": off,
            "duration": 1.0, "end_reason": "rest",
            "round_end": round.map(|result| RoundEnd { result, next_rows: None }),
            "next": next,
        });
        serde_json::from_value(json).expect("an outcome")
    }

    #[test]
    fn a_shot_that_knocks_off_enemies_tells_you_to_shoot_again() {
        let off = [pid(Side::Black, 2), pid(Side::Black, 5)];
        let o = outcome(Side::White, &off, Next::Shoot { side: Side::White }, None);
        assert_eq!(
            shot_line(&o, Some(Side::White), true),
            "You knocked off 2 pieces — shoot again"
        );
        assert_eq!(
            shot_line(&o, Some(Side::Black), true),
            "White knocked off 2 pieces — shoots again"
        );
    }

    #[test]
    fn a_shot_followed_by_a_resignation_never_says_shoot_again() {
        let off = [pid(Side::Black, 2)];
        let o = outcome(Side::White, &off, Next::Shoot { side: Side::White }, None);
        assert_eq!(
            shot_line(&o, Some(Side::White), false),
            "You knocked off 1 piece"
        );
        assert_eq!(
            shot_line(&o, Some(Side::Black), false),
            "White knocked off 1 piece"
        );
    }

    #[test]
    fn a_miss_and_a_lost_piece_pass_the_turn_quietly() {
        let o = outcome(Side::Black, &[], Next::Shoot { side: Side::White }, None);
        assert_eq!(shot_line(&o, None, true), "Black: nothing fell");
        let own = [pid(Side::Black, 1)];
        let o = outcome(Side::Black, &own, Next::Shoot { side: Side::White }, None);
        assert_eq!(shot_line(&o, Some(Side::Black), true), "You lost 1 piece");
    }

    #[test]
    fn the_score_counts_rounds_by_their_winner_and_every_shot() {
        let next = Next::Shoot { side: Side::White };
        let shots = [
            outcome(Side::White, &[], next, None),
            outcome(Side::White, &[], next, Some(RoundResult::Won(Side::White))),
            outcome(Side::Black, &[], next, Some(RoundResult::Won(Side::Black))),
            outcome(Side::White, &[], next, Some(RoundResult::Won(Side::White))),
        ];
        let s = Score::of(&shots);
        assert_eq!((s.white_rounds, s.black_rounds, s.shots), (2, 1, 4));
        assert_eq!(s.rounds_line(), "Rounds won: White 2 · Black 1");
        assert_eq!(
            shot_line(&shots[1], Some(Side::White), true),
            "You: nothing fell — you won the round"
        );
    }
}
