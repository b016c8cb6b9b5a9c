//! The batch form of `Simulator.play`: many shots in one flat array of
//! numbers, answered in one flat array of doubles with a fixed stride, so
//! a bot scoring thousands of candidates pays the boundary once, not once
//! per shot. The JavaScript (`Simulator.playMany`) and Python
//! (`Simulator.play_many`) packages both answer with it.
//!
//! A request is [`SHOT_FIELDS`] numbers per shot: `piece, vx, vy,
//! noise_angle, noise_speed`. The noise draw is applied (with the
//! configuration's noise model, when it has one) unless both noise numbers
//! are NaN: `NaN, NaN` means no draw, as `play(piece, velocity)` without
//! one; a draw with exactly one NaN, or an infinity, is refused
//! (`not-finite`), as `play` refuses it.
//!
//! The answer is [`STRIDE`] doubles per shot:
//!
//! | offset | value |
//! |---|---|
//! | 0 | status: 0 played, else the refusal ([`status_code`]) |
//! | 1 | verdict: 0 shoot-again, 1 pass-turn, 2 round over (White won), 3 round over (Black won), 4 round over (draw) |
//! | 2, 3 | the velocity played (after noise) |
//! | 4 | duration, s |
//! | 5 | end reason: 0 rest, 1 free, 2 until, 3 max-collisions, 4 max-events |
//! | 6, 7 | White pieces knocked off, Black pieces knocked off |
//! | 8..24 | the ids knocked off, in the order they fell, NaN after the last |
//! | 24..56 | `x, y` of piece id `k` at rest at `24 + 2k`, NaN when it is not on the board |
//!
//! A refused shot has its status and NaN everywhere else.

use crate::refusal::ErrorCode;
use crate::rules::Verdict;
use crate::simulate::{self, Simulation};
use crate::{Board, Config, PieceId, RoundResult, Shot, Side};
use glam::DVec2;

/// Numbers per shot in a request.
pub const SHOT_FIELDS: usize = 5;
/// Doubles per shot in an answer.
pub const STRIDE: usize = 56;
/// Offset of the knocked-off ids.
const KNOCKED: usize = 8;
/// Offset of the resting positions.
const POSITIONS: usize = 24;

/// The status number of a refusal: 1 bad-message (the piece is not an
/// integer id 0 to 15), 2 not-finite, 3 zero-speed, 4 too-fast,
/// 5 piece-off-board, 6 internal (the engine failed), 7 any other code.
pub fn status_code(code: ErrorCode) -> f64 {
    match code {
        ErrorCode::BadMessage => 1.0,
        ErrorCode::NotFinite => 2.0,
        ErrorCode::ZeroSpeed => 3.0,
        ErrorCode::TooFast => 4.0,
        ErrorCode::PieceOffBoard => 5.0,
        ErrorCode::Internal => 6.0,
        _ => 7.0,
    }
}

/// Plays every shot of `shots` (a multiple of [`SHOT_FIELDS`] long) on
/// `board` under `config`, exactly as `Simulator.play` does, and returns
/// the answer ([`STRIDE`] doubles per shot).
pub fn play_many(config: &Config, board: &Board, shots: &[f64]) -> Vec<f64> {
    let mut out = vec![f64::NAN; shots.len() / SHOT_FIELDS * STRIDE];
    for (shot, row) in shots
        .chunks_exact(SHOT_FIELDS)
        .zip(out.chunks_exact_mut(STRIDE))
    {
        match play_one(config, board, shot) {
            Ok(sim) => write(&sim, row),
            Err(code) => row[0] = status_code(code),
        }
    }
    out
}

/// One shot: the steps of `Simulator.play` (and of `SimulateRequest::run`
/// after its board check), in their order.
fn play_one(config: &Config, board: &Board, shot: &[f64]) -> Result<Simulation, ErrorCode> {
    let [piece, vx, vy, angle, speed] = [shot[0], shot[1], shot[2], shot[3], shot[4]];
    if piece.fract() != 0.0 || !(0.0..=15.0).contains(&piece) {
        return Err(ErrorCode::BadMessage);
    }
    let piece = PieceId::try_from(piece as u8).map_err(|_| ErrorCode::BadMessage)?;
    let noise = if angle.is_nan() && speed.is_nan() {
        None
    } else if !angle.is_finite() || !speed.is_finite() {
        return Err(simulate::SimulateError::NoiseNotFinite.code());
    } else {
        Some(crate::noise::NoiseDraw { angle, speed })
    };
    let shot = Shot::new(piece, DVec2::new(vx, vy), config).map_err(|e| e.code())?;
    let played = match (&config.variants.noise, &noise) {
        (Some(model), Some(draw)) => draw.apply(model, shot.velocity(), config.max_speed),
        _ => shot.velocity(),
    };
    simulate::play(config, board, &shot, played, false).map_err(|e| e.code())
}

/// Numbers in a board given as positions: `x, y` of piece id `k` at `2k`,
/// NaN when it is not on the board (the layout of an answer's resting
/// positions, so a bot can play on from a simulated board).
pub const BOARD_FIELDS: usize = 32;

/// `board` as [`BOARD_FIELDS`] numbers.
pub fn positions(board: &Board) -> [f64; BOARD_FIELDS] {
    let mut out = [f64::NAN; BOARD_FIELDS];
    for p in board.pieces() {
        let k = 2 * usize::from(u8::from(p.id));
        out[k] = p.pos.x;
        out[k + 1] = p.pos.y;
    }
    out
}

/// The board of [`BOARD_FIELDS`] numbers, checked as hostile input (a
/// piece with one coordinate NaN is off the board; see
/// [`simulate::check_board`]).
pub fn board_from_positions(
    config: &Config,
    numbers: &[f64; BOARD_FIELDS],
) -> Result<Board, simulate::SimulateError> {
    let mut pieces = Vec::new();
    for id in PieceId::all() {
        let k = 2 * usize::from(u8::from(id));
        let (x, y) = (numbers[k], numbers[k + 1]);
        if x.is_nan() && y.is_nan() {
            continue;
        }
        pieces.push(crate::Piece {
            id,
            pos: DVec2::new(x, y),
        });
    }
    simulate::check_board(config, &pieces)
}

fn write(sim: &Simulation, row: &mut [f64]) {
    row[0] = 0.0;
    row[1] = match sim.verdict {
        Verdict::ShootAgain => 0.0,
        Verdict::PassTurn => 1.0,
        Verdict::RoundOver(RoundResult::Won(Side::White)) => 2.0,
        Verdict::RoundOver(RoundResult::Won(Side::Black)) => 3.0,
        Verdict::RoundOver(RoundResult::Draw) => 4.0,
    };
    row[2] = sim.played.x;
    row[3] = sim.played.y;
    row[4] = sim.duration;
    row[5] = match serde_json::to_value(sim.end_reason) {
        Ok(serde_json::Value::String(s)) => match s.as_str() {
            "rest" => 0.0,
            "free" => 1.0,
            "until" => 2.0,
            "max-collisions" => 3.0,
            "max-events" => 4.0,
            _ => f64::NAN,
        },
        _ => f64::NAN,
    };
    row[6] = sim.lost(Side::White) as f64;
    row[7] = sim.lost(Side::Black) as f64;
    for (k, id) in sim.knocked_off.iter().enumerate().take(16) {
        row[KNOCKED + k] = f64::from(u8::from(*id));
    }
    for p in sim.board.pieces() {
        let k = POSITIONS + 2 * usize::from(u8::from(p.id));
        row[k] = p.pos.x;
        row[k + 1] = p.pos.y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_board_round_trips_through_positions_and_a_hostile_one_is_refused() {
        let config = Config::standard();
        let board = crate::Game::new(config.clone(), 1).unwrap().board().clone();
        let numbers = positions(&board);
        assert_eq!(board_from_positions(&config, &numbers).unwrap(), board);
        let mut overlapping = numbers;
        overlapping[2] = overlapping[0];
        overlapping[3] = overlapping[1];
        assert!(board_from_positions(&config, &overlapping).is_err());
        let mut half = numbers;
        half[0] = f64::NAN;
        assert!(board_from_positions(&config, &half).is_err());
    }
}
