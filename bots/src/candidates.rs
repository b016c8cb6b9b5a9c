//! Candidate shots for the scripted bots: every own piece at every other
//! piece — straight through its centre, and cut to either side (the aim
//! point moved sideways by a fraction of a piece's diameter, which sends
//! the target off at an angle) — each at a spread of speeds. Aiming at an
//! own piece plays a combination (a carom into what stands behind it).

use game::{Board, Config, Shot, Side};
use glam::DVec2;

/// Which candidates to make.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Spread {
    /// Speeds, as fractions of the maximum.
    pub speeds: Vec<f64>,
    /// Sideways aim offsets, as fractions of a piece's diameter (0 is
    /// straight at the centre; ±1 only grazes).
    pub cuts: Vec<f64>,
    /// Also aim at own pieces (combinations).
    pub caroms: bool,
}

impl Spread {
    /// Straight shots at enemies only, three speeds (the cheap spread).
    pub fn narrow() -> Spread {
        Spread {
            speeds: vec![0.55, 0.8, 1.0],
            cuts: vec![0.0],
            caroms: false,
        }
    }

    /// Straight and cut shots at enemies and own pieces, four speeds.
    pub fn wide() -> Spread {
        Spread {
            speeds: vec![0.45, 0.65, 0.85, 1.0],
            cuts: vec![0.0, -0.3, 0.3, -0.6, 0.6],
            caroms: true,
        }
    }
}

/// Every candidate of `spread` for `side` on `board`, in a fixed order.
pub fn candidates(config: &Config, board: &Board, side: Side, spread: &Spread) -> Vec<Shot> {
    let diameter = 2.0 * config.piece_radius;
    let mut out = Vec::new();
    for me in board.of(side) {
        for target in board.pieces() {
            if target.id == me.id || (target.id.side() == side && !spread.caroms) {
                continue;
            }
            // A carom is only worth trying at a piece with an enemy near it.
            if target.id.side() == side {
                let near = board
                    .of(side.opponent())
                    .any(|e| e.pos.distance(target.pos) < 2.5 * config.square);
                if !near {
                    continue;
                }
            }
            let line = target.pos - me.pos;
            let len = line.length();
            if len == 0.0 {
                continue;
            }
            let across = DVec2::new(-line.y, line.x) / len;
            for &cut in &spread.cuts {
                let aim = target.pos + across * (cut * diameter) - me.pos;
                for &fraction in &spread.speeds {
                    if let Ok(shot) = Shot::aimed(me.id, aim, config.max_speed * fraction, config) {
                        out.push(shot);
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, Phase};

    #[test]
    fn the_opening_has_a_candidate_for_every_pair_cut_and_speed_and_all_are_legal() {
        let g = Game::new(Config::default(), 1).unwrap();
        let c = g.config();
        let narrow = candidates(c, g.board(), Side::White, &Spread::narrow());
        assert_eq!(narrow.len(), 8 * 8 * 3);
        let wide = candidates(c, g.board(), Side::White, &Spread::wide());
        assert_eq!(
            wide.len(),
            8 * 8 * 5 * 4,
            "no own piece stands near an enemy"
        );
        for s in &wide {
            assert!(g.check(Side::White, s).is_ok());
        }
        assert_eq!(g.phase(), Phase::Shooting);
    }
}
