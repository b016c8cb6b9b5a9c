//! Resolving a shot with the engine: the board becomes an engine scene (the
//! pieces as discs, the edges as four sensor lines), the flicked piece gets
//! its velocity, and the chain is computed to the end. The Chapaev edge rule
//! plugs in as an [`EventHandler`]: a piece whose centre leaves the board
//! is removed at that moment ([`ExitResponse::Remove`]) and takes no
//! further part.

use crate::board::{edges, Board, Piece};
use crate::config::Config;
use crate::film::Film;
use crate::piece::PieceId;
use engine::world::{BodyState, End, World};
use engine::{
    BodyId, BodySpec, Event, EventHandler, ExitResponse, Limits, LineId, Model, Revision, Scene,
    Snapshot, WorldConfig,
};
use glam::DVec2;

/// The edge rule: every region exit takes the piece off the board.
#[derive(Clone, Debug, Default)]
pub struct FallOff {
    /// The pieces that fell off, in order, with the time they fell.
    pub fallen: Vec<(f64, PieceId)>,
}

impl EventHandler for FallOff {
    fn on_event(&mut self, _world: &World, _event: &Event) {}

    fn on_region_exit(&mut self, t: f64, body: BodyId, _line: LineId) -> ExitResponse {
        if let Ok(p) = PieceId::from_body(body) {
            self.fallen.push((t, p));
        }
        ExitResponse::Remove
    }
}

/// What a shot did.
#[derive(Clone, Debug)]
pub struct Resolution {
    /// The engine's event chain.
    pub events: Vec<Event>,
    /// The pieces knocked off, in the order they fell.
    pub knocked_off: Vec<PieceId>,
    /// The pieces left, at rest where they stopped.
    pub board: Board,
    /// How the computation ended.
    pub end: End,
    /// The motion, for showing any moment.
    pub film: Film,
}

/// The engine scene of `board` with `piece` moving at `velocity`.
pub fn scene(config: &Config, board: &Board, piece: PieceId, velocity: DVec2) -> Scene {
    Scene {
        g: config.g,
        t: 0.0,
        bodies: board
            .pieces()
            .iter()
            .map(|p| {
                BodySpec::new(
                    p.id.number() as u64,
                    p.pos,
                    config.piece_radius,
                    config.piece_mass,
                    config.mu,
                )
                .with_restitution(config.restitution)
                .with_velocity(if p.id == piece { velocity } else { DVec2::ZERO })
            })
            .collect(),
        points: Vec::new(),
        lines: edges(config).to_vec(),
    }
}

/// Where a shot left the board, without its motion: what a bot needs to
/// score a candidate. The same computation as [`resolve`], so the same bits.
#[derive(Clone, Debug, PartialEq)]
pub struct Settled {
    /// The pieces knocked off, in the order they fell.
    pub knocked_off: Vec<PieceId>,
    /// The pieces left, at rest where they stopped.
    pub board: Board,
    /// How the computation ended.
    pub end: End,
}

/// The engine model of `piece` flicked at `velocity` on `board`, computed
/// to the end of its chain.
fn computed(
    config: &Config,
    board: &Board,
    piece: PieceId,
    velocity: DVec2,
    revision: Revision,
) -> Result<(Model<FallOff>, End), String> {
    // The board is the engine's own state from the previous shot: pieces
    // left touching may overlap by rounding, which is not bad input, so the
    // model continues from a snapshot rather than re-validating a scene.
    let scene = scene(config, board, piece, velocity);
    let snapshot = Snapshot {
        t: scene.t,
        g: scene.g,
        bodies: scene
            .bodies
            .iter()
            .map(|b| BodyState::from_spec(b, scene.t, scene.g))
            .collect(),
        points: scene.points,
        lines: scene.lines,
    };
    let mut model = Model::from_snapshot(snapshot, FallOff::default(), world_config(revision))
        .map_err(|e| e.to_string())?;
    let end = model.compute(&Limits {
        max_events: config.max_events_per_shot,
        ..Limits::default()
    });
    Ok((model, end))
}

/// The board the model stands at when it ends.
fn board_at(model: &Model<FallOff>, end: &End) -> Result<Board, String> {
    let after = model.scene_at(end.t);
    let mut pieces = Vec::with_capacity(after.bodies.len());
    for b in &after.bodies {
        let id = PieceId::from_body(b.id).map_err(|e| e.to_string())?;
        pieces.push(Piece { id, pos: b.pos });
    }
    Ok(Board::from_pieces(pieces))
}

/// The engine's settings for a shot under the engine `revision`.
fn world_config(revision: Revision) -> WorldConfig {
    WorldConfig {
        revision,
        ..WorldConfig::default()
    }
}

/// Plays `piece` at `velocity` on `board` to the end of its chain, under
/// the engine `revision` (what a physics version names).
pub fn resolve(
    config: &Config,
    board: &Board,
    piece: PieceId,
    velocity: DVec2,
    revision: Revision,
) -> Result<Resolution, String> {
    let (model, end) = computed(config, board, piece, velocity, revision)?;
    Ok(Resolution {
        events: model.events().to_vec(),
        knocked_off: model.rules().fallen.iter().map(|&(_, p)| p).collect(),
        board: board_at(&model, &end)?,
        end,
        film: Film::of(&model, end.t),
    })
}

/// Plays `piece` at `velocity` on `board` to rest like [`resolve`] — the
/// very same computation, so the very same bits — but runs the engine's
/// [`World`] without the model's record of every event and trajectory, and
/// keeps only where the pieces ended (a bot scores thousands of candidates
/// a second this way).
pub fn settle(
    config: &Config,
    board: &Board,
    piece: PieceId,
    velocity: DVec2,
    revision: Revision,
) -> Result<Settled, String> {
    let scene = scene(config, board, piece, velocity);
    // As `Model::from_snapshot` checks: finite numbers, valid materials,
    // overlaps by rounding allowed.
    scene.validate_with(false).map_err(|e| e.to_string())?;
    let bodies = scene
        .bodies
        .iter()
        .map(|b| BodyState::from_spec(b, scene.t, scene.g))
        .collect();
    let mut world = World::from_parts(
        scene.t,
        scene.g,
        bodies,
        scene.points,
        scene.lines,
        world_config(revision),
    );
    let mut rules = FallOff::default();
    let end = world.run(
        &Limits {
            max_events: config.max_events_per_shot,
            ..Limits::default()
        },
        &mut rules,
    );
    let mut pieces = Vec::with_capacity(board.pieces().len());
    for b in world.bodies() {
        let id = PieceId::from_body(b.id).map_err(|e| e.to_string())?;
        pieces.push(Piece {
            id,
            pos: b.spec_at(end.t).pos,
        });
    }
    Ok(Settled {
        knocked_off: rules.fallen.iter().map(|&(_, p)| p).collect(),
        board: Board::from_pieces(pieces),
        end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::board::square_centre;
    use crate::side::Side;
    use engine::{EndReason, EventKind};

    fn w(file: u8) -> PieceId {
        PieceId::new(Side::White, file).unwrap()
    }
    fn b(file: u8) -> PieceId {
        PieceId::new(Side::Black, file).unwrap()
    }

    #[test]
    fn a_gentle_shot_moves_a_lone_piece_exactly_one_square_in_the_engine() {
        let c = Config::default();
        let start = square_centre(&c, 3, 3);
        let board = Board::from_pieces([Piece {
            id: w(3),
            pos: start,
        }]);
        let r = resolve(
            &c,
            &board,
            w(3),
            DVec2::new(0.0, c.speed_for_distance(c.square)),
            Revision::LATEST,
        )
        .unwrap();
        assert_eq!(r.end.reason, EndReason::Rest);
        let moved = r.board.piece(w(3)).unwrap().pos - start;
        assert!((moved.y - c.square).abs() < 1e-12, "{moved}");
        assert_eq!(moved.x, 0.0);
    }

    #[test]
    fn a_full_power_shot_carries_a_piece_across_the_board_and_off_it() {
        let c = Config::default();
        let start = square_centre(&c, 0, 0);
        let board = Board::from_pieces([Piece {
            id: w(0),
            pos: start,
        }]);
        let r = resolve(
            &c,
            &board,
            w(0),
            DVec2::new(0.0, c.max_speed),
            Revision::LATEST,
        )
        .unwrap();
        assert_eq!(r.knocked_off, vec![w(0)]);
        assert!(r.board.pieces().is_empty());
    }

    #[test]
    fn a_piece_falls_off_the_moment_its_centre_leaves_the_board() {
        let c = Config::default();
        let start = square_centre(&c, 4, 7);
        let board = Board::from_pieces([Piece {
            id: w(4),
            pos: start,
        }]);
        let v = 1.0;
        let r = resolve(&c, &board, w(4), DVec2::new(0.0, v), Revision::LATEST).unwrap();
        assert_eq!(r.knocked_off, vec![w(4)]);
        let exit = r
            .events
            .iter()
            .find(|e| matches!(e.kind, EventKind::RegionExit { removed: true, .. }))
            .unwrap();
        // Half a square to the edge: d = v t - a t² / 2.
        let (a, d) = (c.deceleration(), c.square / 2.0);
        let t = (v - (v * v - 2.0 * a * d).sqrt()) / a;
        assert!((exit.t - t).abs() < 1e-12, "{} vs {t}", exit.t);
        // It takes no further part: no event names it after it fell.
        let after: Vec<_> = r.events.iter().filter(|e| e.t > exit.t).collect();
        assert!(after
            .iter()
            .all(|e| !e.kind.bodies().any(|b| b == w(4).body())));
    }

    #[test]
    fn a_piece_just_touching_the_edge_with_its_rim_stays_on() {
        let c = Config::default();
        let board = Board::from_pieces([Piece {
            id: w(0),
            pos: DVec2::new(c.piece_radius * 0.5, 0.1),
        }]);
        let r = resolve(&c, &board, w(0), DVec2::new(0.0, 0.3), Revision::LATEST).unwrap();
        assert!(r.knocked_off.is_empty());
        assert_eq!(r.board.pieces().len(), 1);
    }

    #[test]
    fn settle_ends_exactly_where_resolve_ends() {
        let c = Config::default();
        let board = Board::setup(&c, crate::rows::Rows::new(2, 5).unwrap());
        for k in 0..40 {
            let v = DVec2::new(0.05 * (k as f64 - 20.0), 0.3 + 0.04 * k as f64);
            let r = resolve(&c, &board, w((k % 8) as u8), v, Revision::LATEST).unwrap();
            let s = settle(&c, &board, w((k % 8) as u8), v, Revision::LATEST).unwrap();
            assert_eq!(s.knocked_off, r.knocked_off);
            assert_eq!(s.end, r.end);
            for (a, b) in s.board.pieces().iter().zip(r.board.pieces()) {
                assert_eq!(a.id, b.id);
                assert_eq!(a.pos.x.to_bits(), b.pos.x.to_bits());
                assert_eq!(a.pos.y.to_bits(), b.pos.y.to_bits());
            }
            assert_eq!(s.board.pieces().len(), r.board.pieces().len());
        }
    }

    #[test]
    fn a_head_on_hit_knocks_the_target_off_and_the_shooter_stays() {
        let c = Config::default();
        let board = Board::from_pieces([
            Piece {
                id: w(2),
                pos: square_centre(&c, 2, 4),
            },
            Piece {
                id: b(2),
                pos: square_centre(&c, 2, 7),
            },
        ]);
        let r = resolve(&c, &board, w(2), DVec2::new(0.0, 1.5), Revision::LATEST).unwrap();
        assert_eq!(r.knocked_off, vec![b(2)]);
        assert!(r.board.contains(w(2)));
        assert!(r.events.iter().any(|e| e.kind.name() == "body-body"));
    }

    #[test]
    fn the_film_shows_the_same_bits_as_the_engine_model_at_any_time() {
        let c = Config::default();
        let board = Board::setup(&c, crate::rows::Rows::initial());
        let scene = scene(&c, &board, w(4), DVec2::new(0.01, 2.0));
        let mut model =
            Model::with_rules(scene, FallOff::default(), world_config(Revision::LATEST)).unwrap();
        let end = model.compute(&Limits::default());
        let film = Film::of(&model, end.t);
        assert!(film.diffs.len() >= 3, "{}", film.diffs.len());
        for k in 0..=200 {
            let t = end.t * k as f64 / 200.0;
            let a = film.scene_at(t);
            let b = model.scene_at(t);
            assert_eq!(a.bodies.len(), b.bodies.len(), "at {t}");
            for (x, y) in a.bodies.iter().zip(&b.bodies) {
                assert_eq!(x.id, y.id);
                assert_eq!(x.pos.x.to_bits(), y.pos.x.to_bits());
                assert_eq!(x.pos.y.to_bits(), y.pos.y.to_bits());
                assert_eq!(x.vel.x.to_bits(), y.vel.x.to_bits());
            }
        }
        let back: Film = serde_json::from_str(&serde_json::to_string(&film).unwrap()).unwrap();
        assert_eq!(back, film);
    }
}
