//! The pie-rule decision: after White's first shot, Black may take White's
//! side. The right choice is whichever side is more likely to win from
//! here, so the decider plays the round out a number of times — both sides
//! shooting the narrow greedy shot under the match's public noise model
//! (or an assumed one where the match has none), with draws from the
//! decider's own generator — and swaps when White wins more than half of
//! those playouts. A playout that runs long is scored by the material on
//! the board. The playouts run on all cores, each with its own stream.

use crate::candidates::Spread;
use crate::eval;
use crate::greedy::best_shot;
use crate::simulator::Simulator;
use game::noise::{NoiseDraw, SplitMix64};
use game::rules::{RoundResult, Verdict};
use game::{Board, MatchView, NoiseConfig, Side};
use rayon::prelude::*;

/// How the decider plays the round out.
#[derive(Clone, Debug, PartialEq)]
pub struct PieSettings {
    /// Playouts of the round.
    pub playouts: u32,
    /// Shots after which a playout is scored by the material left.
    pub max_shots: u32,
    /// Noise assumed when the match has none.
    pub assumed_noise: NoiseConfig,
}

impl Default for PieSettings {
    fn default() -> Self {
        PieSettings {
            playouts: 12,
            max_shots: 30,
            assumed_noise: NoiseConfig {
                angle_sigma: 0.03,
                speed_sigma: 0.08,
            },
        }
    }
}

/// White's expected share of the round from `view`'s position (the side to
/// shoot is `view.turn`), 0–1.
pub fn white_share(view: &MatchView, settings: &PieSettings, seed: u64) -> f64 {
    let noise = view.config.variants.noise.unwrap_or(settings.assumed_noise);
    let total: f64 = (0..settings.playouts)
        .into_par_iter()
        .map(|k| {
            let mut rng =
                SplitMix64::new(seed ^ (k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            playout(view, &noise, settings.max_shots, &mut rng)
        })
        .sum();
    total / settings.playouts.max(1) as f64
}

/// One playout: White's share (1 won, 0 lost, ½ drawn, or by material).
fn playout(view: &MatchView, noise: &NoiseConfig, max_shots: u32, rng: &mut SplitMix64) -> f64 {
    let config = &view.config;
    let mut board: Board = view.board.clone();
    let mut turn = view.turn;
    for _ in 0..max_shots {
        let Some((shot, _)) = best_shot(config, &board, turn, &Spread::narrow()) else {
            break;
        };
        let draw = NoiseDraw::sample(rng);
        let Ok(r) = Simulator::on(config, &board).play_with(turn, &shot, noise, draw) else {
            break;
        };
        match r.verdict {
            Verdict::RoundOver(RoundResult::Won(Side::White)) => return 1.0,
            Verdict::RoundOver(RoundResult::Won(Side::Black)) => return 0.0,
            Verdict::RoundOver(RoundResult::Draw) => return 0.5,
            Verdict::ShootAgain => {}
            Verdict::PassTurn => turn = turn.opponent(),
        }
        board = r.board;
    }
    // Unfinished: the material and the turn, through a logistic.
    let v = eval::position(config, &board, Side::White, turn);
    1.0 / (1.0 + (-v / (2.0 * eval::PIECE)).exp())
}

/// Whether Black should take White's side: White's share above a half.
pub fn swap(view: &MatchView, settings: &PieSettings, seed: u64) -> bool {
    white_share(view, settings, seed) > 0.5
}

/// A seed for the playouts that follows from the position alone (for bots
/// without a generator of their own: the same position, the same choice).
pub fn position_seed(view: &MatchView) -> u64 {
    let mut h = SplitMix64::new(view.shots as u64);
    let mut acc = h.next_u64();
    for p in view.board.pieces() {
        acc = acc.rotate_left(7)
            ^ p.pos.x.to_bits()
            ^ p.pos.y.to_bits().rotate_left(31)
            ^ p.id.number() as u64;
        acc = SplitMix64::new(acc).next_u64();
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, PieceId, Shot};
    use glam::DVec2;

    #[test]
    fn black_keeps_its_side_when_white_opened_by_losing_its_own_piece() {
        let mut config = Config::standard();
        config.variants.pie_rule = true;
        let mut g = Game::new(config, 4).unwrap();
        // White flicks its corner piece off its own back edge.
        let piece = PieceId::new(Side::White, 0).unwrap();
        let shot = Shot::new(piece, DVec2::new(-2.0, 0.0), g.config()).unwrap();
        g.play(Side::White, shot).unwrap();
        let view = g.view();
        assert_eq!(view.board.count(Side::White), 7);
        let share = white_share(&view, &PieSettings::default(), 1);
        assert!(share < 0.5, "{share}");
        assert!(!swap(&view, &PieSettings::default(), 1));
    }

    #[test]
    fn the_position_seed_follows_the_position() {
        let a = Game::new(Config::default(), 1).unwrap().view();
        let b = Game::new(Config::default(), 2).unwrap().view();
        assert_eq!(
            position_seed(&a),
            position_seed(&b),
            "the match seed plays no part"
        );
        let mut c = a.clone();
        c.shots = 1;
        assert_ne!(position_seed(&a), position_seed(&c));
    }
}
