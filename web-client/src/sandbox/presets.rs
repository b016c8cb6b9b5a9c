//! The sandbox's ready-made scenes and the rule its models run under:
//! Galperin's billiard (whose collision count spells the digits of pi), a
//! box of many frictionless discs around one heavy disc (Brownian motion),
//! the Chapaev break (sixteen checkers on the board, one flicked), and an
//! empty table. Each preset also says how to show it (the board, which
//! body to follow) and what a new disc should look like at its scale.

use engine::world::World;
use engine::{BodyId, BodySpec, Event, EventHandler, ExitResponse, LineId, Scene};
use game::{Board, Config, PieceId, Rows, Side};
use glam::DVec2;

/// The sandbox's rule: a disc whose centre crosses a sensor line outwards
/// leaves the scene (a checker falling off the board). Scenes without
/// sensor lines never meet it.
#[derive(Clone, Copy, Debug, Default)]
pub struct FallOff;

impl EventHandler for FallOff {
    fn on_event(&mut self, _world: &World, _event: &Event) {}

    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        ExitResponse::Remove
    }
}

/// Which preset a scene came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Galperin's billiard for `n` digits of pi.
    Galperin(u32),
    /// Many discs in a box around a heavy one.
    Brownian,
    /// The Chapaev break.
    Break,
    /// Nothing but four walls.
    Empty,
    /// A scene the user imported.
    Imported,
}

impl Kind {
    /// The name in the state report and the `?preset=` address parameter.
    pub fn name(self) -> String {
        match self {
            Kind::Galperin(n) => format!("galperin{n}"),
            Kind::Brownian => "brownian".into(),
            Kind::Break => "break".into(),
            Kind::Empty => "empty".into(),
            Kind::Imported => "imported".into(),
        }
    }

    /// Reads a name written by [`Kind::name`] (`galperin` alone is n = 3).
    pub fn parse(s: &str) -> Option<Kind> {
        match s {
            "brownian" | "box" => Some(Kind::Brownian),
            "break" | "chapaev" => Some(Kind::Break),
            "empty" => Some(Kind::Empty),
            "galperin" => Some(Kind::Galperin(3)),
            _ => {
                let n: u32 = s.strip_prefix("galperin")?.parse().ok()?;
                (1..=MAX_GALPERIN).contains(&n).then_some(Kind::Galperin(n))
            }
        }
    }
}

/// The largest Galperin `n` offered (314159 collisions).
pub const MAX_GALPERIN: u32 = 6;

/// Id of the heavy disc of the Brownian box.
pub const BROWNIAN_ID: u64 = 1000;

/// What a new disc is made of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscTemplate {
    pub radius: f64,
    pub mass: f64,
    pub mu: f64,
    pub restitution: f64,
}

impl DiscTemplate {
    /// A disc of this material at `pos`, at rest.
    pub fn at(&self, id: u64, pos: DVec2) -> BodySpec {
        BodySpec::new(id, pos, self.radius, self.mass, self.mu).with_restitution(self.restitution)
    }
}

/// A preset: its scene and how to show it.
#[derive(Clone, Debug, PartialEq)]
pub struct Preset {
    pub kind: Kind,
    pub scene: Scene,
    /// Draw the 8x8 board of this size under the scene (and checkers).
    pub board: Option<f64>,
    /// The body selected (and so followed with a trail) at the start.
    pub follow: Option<BodyId>,
    /// New discs look like this.
    pub template: DiscTemplate,
}

/// Builds a preset (an [`Kind::Imported`] gives the empty table).
pub fn build(kind: Kind) -> Preset {
    match kind {
        Kind::Galperin(n) => Preset {
            kind,
            scene: engine::presets::galperin(n.clamp(1, MAX_GALPERIN)),
            board: None,
            follow: None,
            template: DiscTemplate {
                radius: 0.1,
                mass: 1.0,
                mu: 0.0,
                restitution: 1.0,
            },
        },
        Kind::Brownian => Preset {
            kind,
            scene: brownian(200),
            board: None,
            follow: Some(BodyId(BROWNIAN_ID)),
            template: DiscTemplate {
                radius: 0.01,
                mass: 0.01,
                mu: 0.0,
                restitution: 1.0,
            },
        },
        Kind::Break => {
            let c = Config::default();
            Preset {
                kind,
                scene: chapaev_break(&c),
                board: Some(c.board_size()),
                follow: None,
                template: DiscTemplate {
                    radius: c.piece_radius,
                    mass: c.piece_mass,
                    mu: c.mu,
                    restitution: c.restitution,
                },
            }
        }
        Kind::Empty | Kind::Imported => Preset {
            kind: Kind::Empty,
            scene: Scene {
                lines: engine::presets::square_walls(1.0),
                ..Scene::default()
            },
            board: None,
            follow: None,
            template: DiscTemplate {
                radius: 0.03,
                mass: 0.05,
                mu: 0.2,
                restitution: 1.0,
            },
        },
    }
}

/// `n` small frictionless discs in a closed box (the engine's
/// `box_of_discs`) with a heavy disc six times their radius at rest in the
/// middle: its jittery walk under the small discs' hits is Brownian motion.
pub fn brownian(n: usize) -> Scene {
    let mut scene = engine::presets::box_of_discs(n, 0.0, 11);
    let side = scene
        .lines
        .iter()
        .map(|l| l.a.x.max(l.b.x))
        .fold(0.0, f64::max);
    let centre = DVec2::splat(side / 2.0);
    let (radius, mass) = (0.06, 0.36);
    scene
        .bodies
        .retain(|b| (b.pos - centre).length() > radius + b.radius + 0.002);
    scene
        .bodies
        .push(BodySpec::new(BROWNIAN_ID, centre, radius, mass, 0.0));
    scene
}

/// The sixteen checkers in their rows on the board, whose edges are sensor
/// lines (a checker whose centre leaves falls off), White's e-piece
/// flicked up the board at almost full power, a hair off straight.
pub fn chapaev_break(c: &Config) -> Scene {
    let board = Board::setup(c, Rows::initial());
    match PieceId::new(Side::White, 4) {
        Some(shooter) => game::physics::scene(c, &board, shooter, DVec2::new(0.04, 1.9)),
        None => Scene::default(),
    }
}

/// The checker a body plays on the board, if its id names one.
pub fn checker_side(id: BodyId) -> Option<Side> {
    PieceId::from_body(id).ok().map(|p| p.side())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sandbox::sim::Sim;

    #[test]
    fn every_preset_is_a_valid_scene() {
        for kind in [
            Kind::Galperin(1),
            Kind::Galperin(6),
            Kind::Brownian,
            Kind::Break,
            Kind::Empty,
        ] {
            let p = build(kind);
            p.scene.validate().unwrap();
            assert_eq!(Kind::parse(&p.kind.name()), Some(kind));
            if let Some(id) = p.follow {
                assert!(p.scene.bodies.iter().any(|b| b.id == id));
            }
        }
        assert_eq!(Kind::parse("galperin9"), None);
    }

    #[test]
    fn the_brownian_box_has_one_heavy_disc_among_many_light_ones() {
        let s = brownian(200);
        let heavy: Vec<_> = s.bodies.iter().filter(|b| b.mass > 0.1).collect();
        assert_eq!(heavy.len(), 1);
        assert!(s.bodies.len() > 180, "{}", s.bodies.len());
        assert!(s.bodies.iter().all(|b| b.mu == 0.0));
        assert_eq!(heavy[0].vel, DVec2::ZERO);
    }

    #[test]
    fn the_break_knocks_checkers_off_the_board() {
        let mut sim = Sim::new(build(Kind::Break).scene).unwrap();
        assert_eq!(sim.scene().bodies.len(), 16);
        sim.playing = true;
        for _ in 0..200 {
            sim.advance(0.05, 100_000);
        }
        assert!(!sim.playing, "the break comes to rest");
        let tally = sim.tally();
        assert!(tally.body_body >= 1);
        assert!(tally.exits >= 1, "{tally:?}");
        assert_eq!(sim.scene().bodies.len() as u64, 16 - tally.exits);
    }
}
