//! Test support: random players that play whole matches.

use crate::config::{Config, NoiseConfig};
use crate::film::Film;
use crate::game::{Game, Phase};
use crate::noise::SplitMix64;
use crate::shot::Shot;
use crate::side::Side;
use glam::DVec2;

/// A random but not hopeless player: mostly aims one of its pieces at a
/// random enemy piece, sometimes shoots anywhere, at a random speed.
/// Makes one random move; returns the film if it was a shot.
pub(crate) fn random_move(game: &mut Game, rng: &mut SplitMix64) -> Option<Film> {
    match game.phase() {
        Phase::Over { .. } => None,
        Phase::PieDecision => {
            let swap = rng.next_u64() & 1 == 0;
            game.decide_pie(Side::Black, swap).unwrap();
            None
        }
        Phase::Shooting => {
            let side = game.to_shoot().unwrap();
            if rng.next_f64() < 1.0 / 2000.0 {
                game.resign(side).unwrap();
                return None;
            }
            let shot = random_shot(game, side, rng);
            Some(game.play(side, shot).unwrap().film)
        }
    }
}

/// A random legal shot for `side`.
pub(crate) fn random_shot(game: &Game, side: Side, rng: &mut SplitMix64) -> Shot {
    let config: &Config = game.config();
    let own: Vec<_> = game.board().of(side).collect();
    let enemy: Vec<_> = game.board().of(side.opponent()).collect();
    let me = own[(rng.next_u64() % own.len() as u64) as usize];
    let dir = if rng.next_f64() < 0.75 {
        let target = enemy[(rng.next_u64() % enemy.len() as u64) as usize];
        let d = target.pos - me.pos;
        d + DVec2::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5) * config.square
    } else {
        let (s, c) = crate::noise::sin_cos(rng.next_f64() * std::f64::consts::TAU);
        DVec2::new(c, s)
    };
    let speed = config.max_speed * (0.05 + 0.95 * rng.next_f64());
    Shot::aimed(me.id, dir, speed, config).unwrap()
}

/// Plays a whole match between two random players, returning it and the
/// film of every shot; panics if it does not end within `max_moves`.
pub(crate) fn random_match(config: Config, seed: u64, max_moves: usize) -> (Game, Vec<Film>) {
    let mut game = Game::new(config, seed).unwrap();
    let mut rng = SplitMix64::new(seed ^ 0xC4A9_AE5E);
    let mut films = Vec::new();
    for _ in 0..max_moves {
        if game.is_over() {
            return (game, films);
        }
        films.extend(random_move(&mut game, &mut rng));
    }
    panic!("match with seed {seed} did not end in {max_moves} moves");
}

/// The configurations the random-match tests cycle through: every variant
/// on its own and all of them together.
pub(crate) fn variant_config(k: u64) -> Config {
    let mut c = Config::default();
    let noise = Some(NoiseConfig {
        angle_sigma: 0.01,
        speed_sigma: 0.03,
    });
    match k % 5 {
        0 => {}
        1 => c.variants.noise = noise,
        2 => c.variants.pie_rule = true,
        3 => c.variants.two_row_advance = true,
        _ => {
            c.variants.noise = noise;
            c.variants.pie_rule = true;
            c.variants.two_row_advance = true;
        }
    }
    c
}
