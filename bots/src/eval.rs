//! How good a position, or a shot's result, is for one side: the scripted
//! bots' judgement. Material first (a piece is worth [`PIECE`]), then
//! whether the shot keeps the turn, then the safety of each side's pieces:
//! a piece whose centre stands near an edge is easy to knock off, and it
//! matters most for the side that does not shoot next. [`best_shot`] plays
//! each candidate shot and keeps the one this judgement likes best.

use crate::candidates::{candidates, Spread};
use crate::simulator::{Simulated, Simulator};
use game::rules::{RoundResult, Verdict};
use game::{Board, Config, Shot, Side};

/// The value of winning the round (losing it is the negative).
pub const ROUND: f64 = 1000.0;
/// The value of one piece on the board.
pub const PIECE: f64 = 10.0;
/// The value of shooting next rather than the opponent.
pub const TURN: f64 = 4.0;

/// How exposed a piece at `pos` is, 0 (safe, two squares or more from
/// every edge) to 1 (centre on an edge).
pub fn exposure(config: &Config, pos: glam::DVec2) -> f64 {
    let l = config.board_size();
    let d = pos.x.min(pos.y).min(l - pos.x).min(l - pos.y).max(0.0);
    let reach = 2.0 * config.square;
    if d >= reach {
        0.0
    } else {
        let x = 1.0 - d / reach;
        x * x
    }
}

/// The value of `board` for `me` when `next` shoots next (round not over).
pub fn position(config: &Config, board: &Board, me: Side, next: Side) -> f64 {
    let (mut material, mut danger_mine, mut danger_theirs) = (0.0, 0.0, 0.0);
    for p in board.pieces() {
        let e = exposure(config, p.pos);
        if p.id.side() == me {
            material += PIECE;
            danger_mine += e;
        } else {
            material -= PIECE;
            danger_theirs += e;
        }
    }
    // The side to shoot threatens the other's exposed pieces.
    let (mine_w, theirs_w) = if next == me { (0.5, 2.5) } else { (2.5, 0.5) };
    let turn = if next == me { TURN } else { -TURN };
    material + turn - mine_w * danger_mine + theirs_w * danger_theirs
}

/// The value for `me` (who shot) of a simulated shot's result.
pub fn after_shot(config: &Config, sim: &Simulated, me: Side) -> f64 {
    match sim.verdict {
        Verdict::RoundOver(RoundResult::Won(w)) if w == me => ROUND,
        Verdict::RoundOver(RoundResult::Won(_)) => -ROUND,
        Verdict::RoundOver(RoundResult::Draw) => 0.0,
        Verdict::ShootAgain => position(config, &sim.board, me, me),
        Verdict::PassTurn => position(config, &sim.board, me, me.opponent()),
    }
}

/// Whether a result ends the round.
pub fn round_over(sim: &Simulated) -> bool {
    matches!(sim.verdict, Verdict::RoundOver(_))
}

/// The side that shoots after a result (for a round that goes on).
pub fn next_to_shoot(sim: &Simulated, shooter: Side) -> Side {
    match sim.verdict {
        Verdict::ShootAgain => shooter,
        _ => shooter.opponent(),
    }
}

/// The best of `spread`'s candidates for `side` on `board` with its value
/// (first of equals in candidate order; `None` without a legal shot).
pub fn best_shot(
    config: &Config,
    board: &Board,
    side: Side,
    spread: &Spread,
) -> Option<(Shot, f64)> {
    let sim = Simulator::on(config, board);
    let mut best: Option<(Shot, f64)> = None;
    for shot in candidates(config, board, side, spread) {
        let Ok(result) = sim.play(side, &shot) else {
            continue;
        };
        let v = after_shot(config, &result, side);
        let better = match &best {
            Some((_, b)) => v > *b,
            None => true,
        };
        if better {
            best = Some((shot, v));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, Rows};

    #[test]
    fn a_piece_on_the_edge_is_fully_exposed_and_one_in_the_middle_is_safe() {
        let c = Config::default();
        assert_eq!(exposure(&c, glam::DVec2::new(0.0, 0.16)), 1.0);
        assert_eq!(exposure(&c, glam::DVec2::new(0.16, 0.16)), 0.0);
        assert!(exposure(&c, glam::DVec2::new(0.02, 0.16)) > 0.5);
    }

    #[test]
    fn the_opening_is_even_but_for_whose_turn_it_is() {
        let g = Game::new(Config::default(), 1).unwrap();
        let c = g.config();
        let b = Board::setup(c, Rows::initial());
        let white_to_shoot = position(c, &b, Side::White, Side::White);
        let black_view = position(c, &b, Side::Black, Side::White);
        assert!((white_to_shoot + black_view).abs() < 1e-12);
        assert!(white_to_shoot > 0.0);
    }
}
