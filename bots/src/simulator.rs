//! The [`Simulator`]: a candidate shot played on a copy of the board with
//! exactly the server's engine and rules ([`game::physics::settle`] and
//! [`game::rules::judge`], the same bits as a real shot), noiseless or with
//! a noise draw the bot made itself. It never holds a match's seed, so
//! whatever a bot learns from it, a player could learn too.

use game::noise::NoiseDraw;
use game::simulate;
use game::{Board, Config, MatchView, NoiseConfig, Shot, ShotError, Side};

/// What a simulated shot did (the pieces knocked off, where the others
/// rest, the verdict of the turn rule).
pub use game::Simulation as Simulated;

/// Plays candidate shots on one position.
#[derive(Clone, Debug)]
pub struct Simulator<'a> {
    config: &'a Config,
    board: &'a Board,
}

impl<'a> Simulator<'a> {
    /// A simulator for the position of `view`.
    pub fn new(view: &'a MatchView) -> Simulator<'a> {
        Simulator::on(&view.config, &view.board)
    }

    /// A simulator for `board` under `config`.
    pub fn on(config: &'a Config, board: &'a Board) -> Simulator<'a> {
        Simulator { config, board }
    }

    /// The board it plays on.
    pub fn board(&self) -> &'a Board {
        self.board
    }

    /// The configuration it plays under.
    pub fn config(&self) -> &'a Config {
        self.config
    }

    /// `shot` by `shooter`, played exactly as aimed.
    pub fn play(&self, shooter: Side, shot: &Shot) -> Result<Simulated, ShotError> {
        self.play_velocity(shooter, shot, shot.velocity())
    }

    /// `shot` by `shooter` with the match's public noise model applied
    /// with `draw` (a draw the bot made from its own generator). Without a
    /// noise model in the config the shot is played as aimed.
    pub fn play_noisy(
        &self,
        shooter: Side,
        shot: &Shot,
        draw: NoiseDraw,
    ) -> Result<Simulated, ShotError> {
        match &self.config.variants.noise {
            Some(noise) => self.play_with(shooter, shot, noise, draw),
            None => self.play(shooter, shot),
        }
    }

    /// `shot` by `shooter` with any noise model and draw (for a bot that
    /// assumes its own imprecision where the match has none).
    pub fn play_with(
        &self,
        shooter: Side,
        shot: &Shot,
        noise: &NoiseConfig,
        draw: NoiseDraw,
    ) -> Result<Simulated, ShotError> {
        let v = draw.apply(noise, shot.velocity(), self.config.max_speed);
        self.play_velocity(shooter, shot, v)
    }

    fn play_velocity(
        &self,
        shooter: Side,
        shot: &Shot,
        velocity: glam::DVec2,
    ) -> Result<Simulated, ShotError> {
        let piece = shot.piece();
        if piece.side() != shooter {
            return Err(ShotError::NotYourPiece {
                piece,
                side: shooter,
            });
        }
        simulate::play(self.config, self.board, shot, velocity, false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, Phase, PieceId};
    use glam::DVec2;

    #[test]
    fn a_simulated_shot_ends_bit_for_bit_where_the_real_shot_ends() {
        let mut config = Config::standard();
        config.variants.pie_rule = false;
        let mut game = Game::new(config, 99).unwrap();
        let mut rng = game::noise::SplitMix64::new(5);
        for k in 0..60 {
            if game.phase() != Phase::Shooting {
                break;
            }
            let side = game.to_shoot().unwrap();
            let view = game.view();
            let piece = view
                .board
                .of(side)
                .nth(k % view.board.count(side))
                .unwrap()
                .id;
            let a = rng.next_f64() * std::f64::consts::TAU;
            let v = DVec2::new(a.cos(), a.sin()) * (0.3 + 1.7 * rng.next_f64());
            let shot = Shot::new(piece, v, &view.config).unwrap();
            // The draw the server will make: known here only because the
            // test holds the seed.
            let draw = game.noise_key().draw(game.shots());
            let sim = Simulator::new(&view).play_noisy(side, &shot, draw).unwrap();
            let real = game.play(side, shot).unwrap();
            assert_eq!(sim.knocked_off, real.outcome.knocked_off);
            if real.outcome.round_end.is_none() {
                assert_eq!(sim.board.pieces().len(), game.board().pieces().len());
                for (a, b) in sim.board.pieces().iter().zip(game.board().pieces()) {
                    assert_eq!(
                        (a.id, a.pos.x.to_bits(), a.pos.y.to_bits()),
                        (b.id, b.pos.x.to_bits(), b.pos.y.to_bits())
                    );
                }
            }
        }
    }

    #[test]
    fn the_simulator_refuses_another_sides_piece_and_a_piece_off_the_board() {
        let view = Game::new(Config::default(), 1).unwrap().view();
        let black = PieceId::new(Side::Black, 0).unwrap();
        let shot = Shot::new(black, DVec2::new(0.0, -1.0), &view.config).unwrap();
        let sim = Simulator::new(&view);
        assert!(matches!(
            sim.play(Side::White, &shot),
            Err(ShotError::NotYourPiece { .. })
        ));
        let board = Board::from_pieces(
            view.board
                .pieces()
                .iter()
                .copied()
                .filter(|p| p.id != black),
        );
        let sim = Simulator::on(&view.config, &board);
        assert_eq!(
            sim.play(Side::Black, &shot),
            Err(ShotError::PieceOffBoard(black))
        );
    }
}
