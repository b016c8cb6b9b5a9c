//! One shot simulated on any position, with exactly the server's physics
//! and turn rule: the computation every bot scores candidates with, in
//! every language.
//!
//! [`play`] is the core (Rust bots reach it through `bots::Simulator`);
//! [`SimulateRequest`] and [`Simulation`] are the same call as plain data,
//! the shape shared by `POST /api/simulate`, the JavaScript (wasm) package
//! and the Python package, so a bot in any language gets the very bits the
//! server gets. A request is checked as hostile input: pieces named once,
//! finite centres on the board, no two pieces overlapping, a playable
//! configuration and a valid shot; a refused request computes nothing.

use crate::board::{is_on_board, Board, Piece};
use crate::config::{Config, ConfigError};
use crate::film::Film;
use crate::noise::{NoiseDraw, SplitMix64};
use crate::physics;
use crate::physics_version::PhysicsVersion;
use crate::piece::PieceId;
use crate::rules::{judge, Verdict};
use crate::shot::{Shot, ShotError};
use crate::side::Side;
use engine::EndReason;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// The engine revision every simulation runs: the current physics version's.
const CURRENT: engine::Revision = PhysicsVersion::CURRENT.revision();

/// How far two pieces given in a request may overlap (m): what rounding
/// leaves between pieces that came to rest touching, and no more.
pub const OVERLAP_TOLERANCE: f64 = 1e-9;

/// What one simulated shot did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Simulation {
    /// The velocity played: the aimed one with the noise draw applied.
    #[schemars(with = "[f64; 2]")]
    pub played: DVec2,
    /// The pieces knocked off, in the order they fell.
    pub knocked_off: Vec<PieceId>,
    /// Where the pieces came to rest (the pieces left, in id order).
    pub board: Board,
    /// What the turn rule makes of it.
    pub verdict: Verdict,
    /// When the last piece came to rest, s after the flick.
    pub duration: f64,
    /// How the engine's computation ended (`rest` unless a cap was hit).
    pub end_reason: EndReason,
    /// Every piece's motion, when asked for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film: Option<Film>,
}

impl Simulation {
    /// Pieces of `side` knocked off.
    pub fn lost(&self, side: Side) -> usize {
        self.knocked_off.iter().filter(|p| p.side() == side).count()
    }
}

/// `shot` played on `board` under `config` at `velocity` (the aimed
/// velocity, or the one after noise), by the side that owns the piece.
/// With `film`, the motion is recorded too (the same bits either way).
pub fn play(
    config: &Config,
    board: &Board,
    shot: &Shot,
    velocity: DVec2,
    film: bool,
) -> Result<Simulation, ShotError> {
    let piece = shot.piece();
    if !board.contains(piece) {
        return Err(ShotError::PieceOffBoard(piece));
    }
    let shooter = piece.side();
    let (knocked_off, after, end, film) = if film {
        let r = physics::resolve(config, board, piece, velocity, CURRENT)
            .map_err(ShotError::Physics)?;
        (r.knocked_off, r.board, r.end, Some(r.film))
    } else {
        let s =
            physics::settle(config, board, piece, velocity, CURRENT).map_err(ShotError::Physics)?;
        (s.knocked_off, s.board, s.end, None)
    };
    let verdict = judge(shooter, &knocked_off, &after);
    Ok(Simulation {
        played: velocity,
        knocked_off,
        board: after,
        verdict,
        duration: end.t,
        end_reason: end.reason,
        film,
    })
}

/// One shot to simulate, as plain data (the body of `POST /api/simulate`
/// and the argument of the language bindings).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SimulateRequest {
    /// The configuration (a match's `view.config`); the default (casual)
    /// configuration when left out.
    #[serde(default)]
    pub config: Config,
    /// The pieces on the board, each named once (a match's `view.board`).
    pub board: Vec<Piece>,
    /// The piece flicked; its side is the shooter.
    pub piece: PieceId,
    /// The velocity as aimed, m/s.
    #[schemars(with = "[f64; 2]")]
    pub velocity: DVec2,
    /// A noise draw to apply with the configuration's noise model
    /// (ignored without one); the shot is played as aimed when left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise: Option<NoiseDraw>,
    /// Whether to return the film of the shot (every piece's motion).
    #[serde(default)]
    pub film: bool,
}

/// Why a simulation request was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimulateError {
    #[error("unplayable config: {0}")]
    Config(#[from] ConfigError),
    #[error("{0} is on the board twice")]
    DuplicatePiece(PieceId),
    #[error("{piece} stands at ({x}, {y}), which is not a finite point on the board")]
    OffBoard { piece: PieceId, x: f64, y: f64 },
    #[error("{a} and {b} overlap by {overlap} m")]
    Overlap {
        a: PieceId,
        b: PieceId,
        overlap: f64,
    },
    #[error("the noise draw must be finite numbers")]
    NoiseNotFinite,
    #[error(transparent)]
    Shot(#[from] ShotError),
}

impl SimulateError {
    /// The stable wire code of this error.
    pub fn code(&self) -> crate::refusal::ErrorCode {
        use crate::refusal::ErrorCode as C;
        match self {
            SimulateError::Config(_) => C::BadConfig,
            SimulateError::DuplicatePiece(_)
            | SimulateError::OffBoard { .. }
            | SimulateError::Overlap { .. } => C::BadBoard,
            SimulateError::NoiseNotFinite => C::NotFinite,
            SimulateError::Shot(e) => e.code(),
        }
    }
}

/// The board of `pieces`, checked as hostile input under `config`: each
/// piece named once, at a finite point on the board, no two overlapping
/// by more than [`OVERLAP_TOLERANCE`].
pub fn check_board(config: &Config, pieces: &[Piece]) -> Result<Board, SimulateError> {
    let r = config.piece_radius;
    for (k, p) in pieces.iter().enumerate() {
        if !is_on_board(config, p.pos) {
            return Err(SimulateError::OffBoard {
                piece: p.id,
                x: p.pos.x,
                y: p.pos.y,
            });
        }
        for q in &pieces[..k] {
            if q.id == p.id {
                return Err(SimulateError::DuplicatePiece(p.id));
            }
            let overlap = 2.0 * r - p.pos.distance(q.pos);
            if overlap > OVERLAP_TOLERANCE {
                return Err(SimulateError::Overlap {
                    a: q.id,
                    b: p.id,
                    overlap,
                });
            }
        }
    }
    Ok(Board::from_pieces(pieces.iter().copied()))
}

impl SimulateRequest {
    /// Checks the request and returns the board and the shot it describes.
    pub fn validate(&self) -> Result<(Board, Shot), SimulateError> {
        self.config.validate()?;
        let board = check_board(&self.config, &self.board)?;
        if let Some(n) = &self.noise {
            if !n.angle.is_finite() || !n.speed.is_finite() {
                return Err(SimulateError::NoiseNotFinite);
            }
        }
        let shot = Shot::new(self.piece, self.velocity, &self.config)?;
        Ok((board, shot))
    }

    /// The velocity `shot` is played at: the request's noise draw applied
    /// with the configuration's noise model, or as aimed.
    pub fn played_velocity(&self, shot: &Shot) -> DVec2 {
        match (&self.config.variants.noise, &self.noise) {
            (Some(model), Some(draw)) => draw.apply(model, shot.velocity(), self.config.max_speed),
            _ => shot.velocity(),
        }
    }

    /// Validates and simulates the request.
    pub fn run(&self) -> Result<Simulation, SimulateError> {
        let (board, shot) = self.validate()?;
        let velocity = self.played_velocity(&shot);
        Ok(play(&self.config, &board, &shot, velocity, self.film)?)
    }
}

/// A random request, for tests and benchmarks of every binding: the
/// casual or the standard configuration, a random set of pieces (at least
/// one of each side) standing apart anywhere on the board, one of them
/// flicked in a random direction at a random speed, and half the time a
/// noise draw.
pub fn random_request(rng: &mut SplitMix64) -> SimulateRequest {
    let config = if rng.next_u64().is_multiple_of(2) {
        Config::default()
    } else {
        Config::standard()
    };
    let l = config.board_size();
    let r = config.piece_radius;
    let mut board: Vec<Piece> = Vec::new();
    for id in PieceId::all() {
        let keep = rng.next_f64() < 0.6 || PieceId::of(id.side()).last() == Some(id);
        if !keep {
            continue;
        }
        // Rejection sampling: a free spot exists (16 discs on 64 squares).
        for _ in 0..1000 {
            let pos = DVec2::new(rng.next_f64() * l, rng.next_f64() * l);
            if board.iter().all(|p| p.pos.distance(pos) > 2.0 * r) {
                board.push(Piece { id, pos });
                break;
            }
        }
    }
    let piece = board[(rng.next_u64() % board.len() as u64) as usize].id;
    let angle = rng.next_f64() * std::f64::consts::TAU;
    let speed = config.max_speed * (0.05 + 0.95 * rng.next_f64());
    let (s, c) = crate::noise::sin_cos(angle);
    let noise = (rng.next_u64().is_multiple_of(2)).then(|| NoiseDraw::sample(rng));
    SimulateRequest {
        config,
        board,
        piece,
        velocity: DVec2::new(c, s) * speed,
        noise,
        film: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::board::square_centre;
    use crate::{Game, Rows};

    fn opening() -> SimulateRequest {
        let config = Config::default();
        let board = Board::setup(&config, Rows::initial());
        SimulateRequest {
            config,
            board: board.pieces().to_vec(),
            piece: PieceId::new(Side::White, 4).unwrap(),
            velocity: DVec2::new(0.0, 2.0),
            noise: None,
            film: false,
        }
    }

    #[test]
    fn a_request_gives_the_bits_of_the_real_shot_with_or_without_film() {
        let mut config = Config::standard();
        config.variants.pie_rule = false;
        let mut game = Game::new(config.clone(), 3).unwrap();
        let draw = game.noise_key().draw(0);
        let req = SimulateRequest {
            config,
            board: game.board().pieces().to_vec(),
            piece: PieceId::new(Side::White, 3).unwrap(),
            velocity: DVec2::new(0.3, 1.9),
            noise: Some(draw),
            film: false,
        };
        let sim = req.run().unwrap();
        let with_film = SimulateRequest {
            film: true,
            ..req.clone()
        }
        .run()
        .unwrap();
        let shot = Shot::new(req.piece, req.velocity, game.config()).unwrap();
        let real = game.play(Side::White, shot).unwrap();
        assert_eq!(sim.played, real.outcome.played);
        assert_eq!(sim.knocked_off, real.outcome.knocked_off);
        assert_eq!(sim.duration, real.outcome.duration);
        assert_eq!(&sim.board, game.board());
        assert_eq!(with_film.film.as_ref(), Some(&real.film));
        assert_eq!(with_film.board, sim.board);
    }

    #[test]
    fn the_opening_shot_up_the_e_file_knocks_blacks_e_piece_off_and_shoots_again() {
        let sim = opening().run().unwrap();
        assert!(sim
            .knocked_off
            .contains(&PieceId::new(Side::Black, 4).unwrap()));
        assert_eq!(sim.verdict, Verdict::ShootAgain);
        let json = serde_json::to_value(&sim).unwrap();
        assert_eq!(
            json["verdict"],
            serde_json::json!({"verdict": "shoot-again"})
        );
        let back: Simulation = serde_json::from_value(json).unwrap();
        assert_eq!(back, sim);
    }

    #[test]
    fn hostile_requests_are_refused_with_their_reason() {
        let mut r = opening();
        r.board.push(r.board[0]);
        assert!(matches!(r.run(), Err(SimulateError::DuplicatePiece(_))));

        let mut r = opening();
        r.board[1].pos = DVec2::new(f64::NAN, 0.1);
        assert!(matches!(r.run(), Err(SimulateError::OffBoard { .. })));

        let mut r = opening();
        r.board[1].pos = r.board[0].pos + DVec2::new(0.01, 0.0);
        assert!(matches!(r.run(), Err(SimulateError::Overlap { .. })));

        let mut r = opening();
        r.velocity = DVec2::new(0.0, 1e9);
        assert_eq!(r.run().unwrap_err().code().as_str(), "too-fast");

        let mut r = opening();
        r.piece = PieceId::new(Side::Black, 0).unwrap();
        r.board.retain(|p| p.id != r.piece);
        assert_eq!(r.run().unwrap_err().code().as_str(), "piece-off-board");

        let mut r = opening();
        r.config.mu = -1.0;
        assert_eq!(r.run().unwrap_err().code().as_str(), "bad-config");

        let mut r = opening();
        r.noise = Some(NoiseDraw {
            angle: f64::INFINITY,
            speed: 0.0,
        });
        assert_eq!(r.run().unwrap_err().code().as_str(), "not-finite");
    }

    #[test]
    fn random_requests_are_valid_and_play() {
        let mut rng = SplitMix64::new(11);
        let mut knocked = 0;
        for _ in 0..300 {
            let req = random_request(&mut rng);
            let sim = req.run().unwrap();
            knocked += sim.knocked_off.len();
            let json = serde_json::to_string(&req).unwrap();
            let back: SimulateRequest = serde_json::from_str(&json).unwrap();
            assert_eq!(back, req);
        }
        assert!(knocked > 50, "random shots knock pieces off: {knocked}");
    }

    #[test]
    fn pieces_resting_exactly_in_contact_are_accepted() {
        let config = Config::default();
        let a = square_centre(&config, 3, 3);
        let r = SimulateRequest {
            board: vec![
                Piece {
                    id: PieceId::new(Side::White, 0).unwrap(),
                    pos: a,
                },
                Piece {
                    id: PieceId::new(Side::Black, 0).unwrap(),
                    pos: a + DVec2::new(2.0 * config.piece_radius, 0.0),
                },
            ],
            piece: PieceId::new(Side::White, 0).unwrap(),
            velocity: DVec2::new(1.0, 0.0),
            config,
            noise: None,
            film: false,
        };
        let sim = r.run().unwrap();
        assert_eq!(sim.knocked_off, vec![PieceId::new(Side::Black, 0).unwrap()]);
    }
}
