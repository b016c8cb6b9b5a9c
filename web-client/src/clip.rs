//! One shot ready to show at any moment: the server's [`Film`] (exact
//! trajectories) plus what the eye needs beyond positions — where and when
//! pieces hit something (a ring), and how each knocked-off piece left the
//! board (it keeps sliding over the edge, shrinking and fading as it
//! drops). Every frame is a pure function of the time, so playing, pausing
//! and scrubbing backwards all draw the same thing for the same `t`. The
//! shot's sounds ([`Clip::sounds`]) come from the same events: a clack at
//! each collision, as loud as the pieces met hard, and a thud when a
//! knocked-off piece lands.

use crate::platform::Sound;
use ::glam::DVec2;
use engine::{EventKind, Scene};
use game::{Film, PieceId, ShotOutcome};

/// How long a hit ring lasts, in seconds of shot time.
pub const HIT_SECONDS: f64 = 0.25;
/// How long a piece takes to drop off the edge, in seconds of shot time.
pub const FALL_SECONDS: f64 = 0.6;
/// The closing speed (m/s) of a collision that clacks at full loudness.
pub const LOUDEST_HIT: f64 = 2.0;
/// Collisions closing slower than this (m/s) make no sound: pieces that
/// barely touch, or rest against each other.
pub const SILENT_HIT: f64 = 0.005;
/// The most clacks one call of [`Clip::sounds`] gives (the loudest): a
/// cluster of pieces can touch dozens of times in a frame.
pub const MOST_CLACKS: usize = 4;

/// A collision to flash (and hear).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub at: DVec2,
    /// How fast the two pieces closed along the line of their centres just
    /// before they met, m/s.
    pub speed: f64,
}

/// A piece leaving the board.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fall {
    pub piece: PieceId,
    /// When its centre crossed the edge.
    pub t: f64,
    pub pos: DVec2,
    pub vel: DVec2,
}

/// What to draw at one moment of a shot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Pieces on the board and where.
    pub pieces: Vec<(PieceId, DVec2)>,
    /// Pieces dropping off: where, and how far along the drop (0..1).
    pub falling: Vec<(PieceId, DVec2, f32)>,
    /// Hit rings: where, and how far along (0..1).
    pub hits: Vec<(DVec2, f32)>,
}

/// A shot prepared for display.
#[derive(Clone, Debug)]
pub struct Clip {
    pub film: Film,
    pub outcome: ShotOutcome,
    pub hits: Vec<Hit>,
    pub falls: Vec<Fall>,
}

/// The largest float below `t` (the instant just before an event).
fn just_before(t: f64) -> f64 {
    if t > 0.0 {
        f64::from_bits(t.to_bits() - 1)
    } else {
        t
    }
}

fn body_in(scene: &Scene, id: engine::BodyId) -> Option<&engine::BodySpec> {
    scene.bodies.iter().find(|b| b.id == id)
}

impl Clip {
    pub fn new(outcome: ShotOutcome, film: Film) -> Clip {
        let mut hits = Vec::new();
        let mut falls = Vec::new();
        for e in &outcome.events {
            match e.kind {
                EventKind::BodyBody { a, b } => {
                    // Positions at the contact, velocities from just before.
                    let s = film.snapshot_at(just_before(e.t)).scene_at(e.t);
                    if let (Some(a), Some(b)) = (body_in(&s, a), body_in(&s, b)) {
                        let normal = (b.pos - a.pos).normalize_or_zero();
                        hits.push(Hit {
                            t: e.t,
                            at: (a.pos + b.pos) / 2.0,
                            speed: (a.vel - b.vel).dot(normal).max(0.0),
                        });
                    }
                }
                EventKind::RegionExit {
                    body,
                    removed: true,
                    ..
                } => {
                    let Ok(piece) = PieceId::from_body(body) else {
                        continue;
                    };
                    // Still on the board an instant before; evaluate its
                    // trajectory at the crossing itself.
                    let s = film.snapshot_at(just_before(e.t)).scene_at(e.t);
                    if let Some(b) = body_in(&s, body) {
                        falls.push(Fall {
                            piece,
                            t: e.t,
                            pos: b.pos,
                            vel: b.vel,
                        });
                    }
                }
                _ => {}
            }
        }
        Clip {
            film,
            outcome,
            hits,
            falls,
        }
    }

    /// How long the shot lasts, falls included.
    pub fn duration(&self) -> f64 {
        let last_fall = self.falls.iter().map(|f| f.t + FALL_SECONDS);
        last_fall.fold(self.film.end, f64::max)
    }

    /// The sounds of the moments after `from` up to `to` (shot time): a
    /// clack for each collision (louder the harder the pieces met; the
    /// [`MOST_CLACKS`] loudest), then a thud for each piece that lands
    /// after dropping off the edge. Nothing when `to <= from`, so a paused
    /// or rewound shot is silent.
    pub fn sounds(&self, from: f64, to: f64) -> Vec<Sound> {
        let within = |t: f64| t > from && t <= to;
        let mut clacks: Vec<f64> = self
            .hits
            .iter()
            .filter(|h| within(h.t) && h.speed >= SILENT_HIT)
            .map(|h| h.speed)
            .collect();
        clacks.sort_by(|a, b| b.total_cmp(a));
        clacks.truncate(MOST_CLACKS);
        let mut sounds: Vec<Sound> = clacks
            .into_iter()
            .map(|v| Sound::Clack {
                loudness: (v / LOUDEST_HIT).sqrt().clamp(0.05, 1.0) as f32,
            })
            .collect();
        sounds.extend(
            self.falls
                .iter()
                .filter(|f| within(f.t + FALL_SECONDS))
                .map(|_| Sound::Fall),
        );
        sounds
    }

    /// Everything to draw at time `t` of the shot (clamped to the shot).
    pub fn frame(&self, t: f64) -> Frame {
        let t = t.clamp(0.0, self.duration());
        let scene = self.film.scene_at(t.min(self.film.end));
        let pieces = scene
            .bodies
            .iter()
            .filter_map(|b| PieceId::from_body(b.id).ok().map(|p| (p, b.pos)))
            .collect();
        let falling = self
            .falls
            .iter()
            .filter(|f| t >= f.t && t < f.t + FALL_SECONDS)
            .map(|f| {
                let k = (t - f.t) / FALL_SECONDS;
                // Keeps sliding at its exit speed, slowing as it tips over.
                let travel = f.vel * FALL_SECONDS * (k - 0.5 * k * k);
                (f.piece, f.pos + travel, k as f32)
            })
            .collect();
        let hits = self
            .hits
            .iter()
            .filter(|h| t >= h.t && t < h.t + HIT_SECONDS)
            .map(|h| (h.at, ((t - h.t) / HIT_SECONDS) as f32))
            .collect();
        Frame {
            pieces,
            falling,
            hits,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, Shot, Side};

    /// White's a-piece shot straight at Black's a-piece, hard enough to
    /// knock it off the far edge.
    fn knock_off() -> (Game, Clip) {
        let config = Config::default();
        let mut g = Game::new(config.clone(), 7).unwrap();
        let piece = PieceId::new(Side::White, 0).unwrap();
        let shot = Shot::new(piece, DVec2::new(0.0, 2.0), &config).unwrap();
        let p = g.play(Side::White, shot).unwrap();
        (g, Clip::new(p.outcome, p.film))
    }

    #[test]
    fn the_clip_starts_at_the_set_up_board_and_ends_at_the_games_board() {
        let (g, clip) = knock_off();
        let start = clip.frame(0.0);
        assert_eq!(start.pieces.len(), 16);
        let end = clip.frame(clip.duration());
        let board: Vec<_> = g.board().pieces().iter().map(|p| (p.id, p.pos)).collect();
        let mut shown = end.pieces.clone();
        shown.sort_by_key(|(id, _)| u8::from(*id));
        let mut want = board;
        want.sort_by_key(|(id, _)| u8::from(*id));
        assert_eq!(
            shown, want,
            "the last frame is the board the server kept, bit for bit"
        );
    }

    #[test]
    fn a_knocked_off_piece_falls_from_the_edge_it_crossed() {
        let (g, clip) = knock_off();
        assert!(
            !clip.outcome.knocked_off.is_empty(),
            "the test shot knocks a piece off"
        );
        assert_eq!(clip.falls.len(), clip.outcome.knocked_off.len());
        let size = g.config().board_size();
        for f in &clip.falls {
            let edge = f.pos.x.min(f.pos.y).min(size - f.pos.x).min(size - f.pos.y);
            assert!(
                edge.abs() < 1e-9,
                "{:?} crossed at {} from the edge",
                f.piece,
                edge
            );
            assert!(f.vel.length() > 0.0);
            // Drawn falling just after, gone from the board pieces.
            let fr = clip.frame(f.t + FALL_SECONDS / 2.0);
            assert!(fr
                .falling
                .iter()
                .any(|(p, _, k)| *p == f.piece && *k > 0.4 && *k < 0.6));
            assert!(!fr.pieces.iter().any(|(p, _)| *p == f.piece));
        }
        assert!(clip.duration() > clip.film.end);
    }

    #[test]
    fn each_collision_clacks_once_as_loud_as_it_was_hard_and_each_fall_thuds_on_landing() {
        let (_, clip) = knock_off();
        let end = clip.duration();
        // Played in small steps, every moment is heard once.
        let mut heard = Vec::new();
        let mut t = 0.0;
        while t < end {
            heard.extend(clip.sounds(t, t + 1.0 / 240.0));
            t += 1.0 / 240.0;
        }
        let audible = clip.hits.iter().filter(|h| h.speed >= SILENT_HIT).count();
        let clacks: Vec<f32> = heard
            .iter()
            .filter_map(|s| match s {
                Sound::Clack { loudness } => Some(*loudness),
                _ => None,
            })
            .collect();
        assert_eq!(clacks.len(), audible);
        assert!(clacks.iter().all(|l| (0.05..=1.0).contains(l)));
        let falls = heard.iter().filter(|s| **s == Sound::Fall).count();
        assert_eq!(falls, clip.outcome.knocked_off.len());
        // The first hit of a 2 m/s shot is hard: loud.
        assert!(clacks[0] > 0.5, "{clacks:?}");
        // Paused or rewound: silent.
        assert!(clip.sounds(end, end).is_empty());
        assert!(clip.sounds(end, 0.0).is_empty());
    }

    #[test]
    fn a_harder_hit_clacks_louder() {
        let config = Config::default();
        let loudness = |speed: f64| {
            let mut g = Game::new(config.clone(), 7).unwrap();
            let piece = PieceId::new(Side::White, 0).unwrap();
            let shot = Shot::new(piece, DVec2::new(0.0, speed), &config).unwrap();
            let p = g.play(Side::White, shot).unwrap();
            let clip = Clip::new(p.outcome, p.film);
            let first = clip.hits.first().expect("the shot hits").t;
            match clip.sounds(0.0, first).as_slice() {
                [Sound::Clack { loudness }] => *loudness,
                other => panic!("{other:?}"),
            }
        };
        assert!(loudness(1.9) > loudness(1.5));
    }

    #[test]
    fn hits_ring_only_for_a_moment_at_the_contact_point() {
        let (_, clip) = knock_off();
        assert!(!clip.hits.is_empty());
        let h = clip.hits[0];
        assert_eq!(clip.frame(h.t - 1e-6).hits.len(), 0);
        assert_eq!(clip.frame(h.t + HIT_SECONDS / 2.0).hits.len(), 1);
        assert!(clip
            .frame(h.t + HIT_SECONDS * 1.01)
            .hits
            .iter()
            .all(|(at, _)| *at != h.at));
        // The contact point lies between the two pieces: one radius from each.
        let s = clip.film.scene_at(h.t);
        let near = s
            .bodies
            .iter()
            .filter(|b| (b.pos - h.at).length() < 0.0161)
            .count();
        assert_eq!(near, 2);
    }
}
