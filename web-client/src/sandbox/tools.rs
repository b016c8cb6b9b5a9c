//! The sandbox's editing tools as a small state machine, free of drawing
//! and input devices: what is under the pointer ([`pick`]), what a press
//! starts ([`press`]), and which engine [`Action`] a release makes of it
//! ([`release`]). The screen feeds it world coordinates and applies the
//! actions; tests drive it directly.

use engine::obstacle::LineGeom;
use engine::{Action, BodyId, Line, LineKind, Point, Scene};
use glam::DVec2;

use super::presets::DiscTemplate;

/// The tool in hand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tool {
    /// Select and move bodies; drag empty space to pan.
    Select,
    /// Drag from a body to give it a velocity.
    Velocity,
    /// Click to place a disc.
    Disc,
    /// Click to place a fixed point.
    Point,
    /// Drag from `a` to `b` to draw a line, ray or segment.
    Line(LineKind),
    /// Click an object to delete it.
    Delete,
}

impl Tool {
    /// The tool's name in the state report and its button.
    pub fn name(self) -> &'static str {
        match self {
            Tool::Select => "select",
            Tool::Velocity => "velocity",
            Tool::Disc => "disc",
            Tool::Point => "point",
            Tool::Line(LineKind::Line) => "line",
            Tool::Line(LineKind::Ray) => "ray",
            Tool::Line(LineKind::Segment) => "segment",
            Tool::Delete => "delete",
        }
    }
}

/// Every tool, in toolbar order.
pub const TOOLS: [Tool; 8] = [
    Tool::Select,
    Tool::Velocity,
    Tool::Disc,
    Tool::Point,
    Tool::Line(LineKind::Line),
    Tool::Line(LineKind::Ray),
    Tool::Line(LineKind::Segment),
    Tool::Delete,
];

/// An object of the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hit {
    Body(BodyId),
    Point(usize),
    Line(usize),
}

/// What is under world point `p`: a body (the one drawn on top, i.e. last,
/// wins), else a point or line within `tol` metres.
pub fn pick(scene: &Scene, p: DVec2, tol: f64) -> Option<Hit> {
    if let Some(b) = scene
        .bodies
        .iter()
        .rev()
        .find(|b| (b.pos - p).length() <= b.radius + tol * 0.5)
    {
        return Some(Hit::Body(b.id));
    }
    let nearest = |d: &mut dyn Iterator<Item = (usize, f64)>| {
        d.filter(|&(_, d)| d <= tol)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)
    };
    if let Some(k) = nearest(
        &mut scene
            .points
            .iter()
            .map(|q| (q.pos - p).length())
            .enumerate(),
    ) {
        return Some(Hit::Point(k));
    }
    nearest(
        &mut scene
            .lines
            .iter()
            .map(|l| LineGeom::new(l).map_or(f64::INFINITY, |g| g.distance(p)))
            .enumerate(),
    )
    .map(Hit::Line)
}

/// An arrow drawn from a body shows where it would be after this many
/// seconds at its velocity (without friction): dragging sets the velocity
/// so, and existing velocities are drawn so.
pub const ARROW_TIME: f64 = 0.25;

/// The velocity a drag of `drag` metres from a body's centre gives it.
pub fn velocity_from_drag(drag: DVec2) -> DVec2 {
    drag / ARROW_TIME
}

/// The arrow (in metres) that shows velocity `vel`.
pub fn arrow_of(vel: DVec2) -> DVec2 {
    vel * ARROW_TIME
}

/// Which pointer button started a gesture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    Primary,
    Secondary,
    Middle,
}

/// A press in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Gesture {
    /// Dragging the view.
    Pan,
    /// Moving body `id`; its centre is `offset` from the pointer.
    Move {
        id: BodyId,
        offset: DVec2,
        to: DVec2,
    },
    /// Aiming body `id`'s velocity at world point `to`.
    Aim { id: BodyId, to: DVec2 },
    /// Drawing a line of `kind` from `a` to `b`.
    Draw { kind: LineKind, a: DVec2, b: DVec2 },
    /// Placing a disc (or, if not `disc`, a point) where released.
    Place { disc: bool, at: DVec2 },
    /// Deleting what was pressed, on release.
    Delete(Hit),
}

/// What a press at world point `p` over `hit` starts, and the selection it
/// makes (`Some(None)` clears it, `None` keeps it).
pub fn press(
    tool: Tool,
    button: Button,
    hit: Option<Hit>,
    p: DVec2,
    scene: &Scene,
) -> (Gesture, Option<Option<BodyId>>) {
    let body = match hit {
        Some(Hit::Body(id)) => scene.bodies.iter().find(|b| b.id == id),
        _ => None,
    };
    match (button, tool, body) {
        (Button::Middle, ..) => (Gesture::Pan, None),
        (Button::Secondary, _, Some(b)) | (Button::Primary, Tool::Velocity, Some(b)) => {
            (Gesture::Aim { id: b.id, to: p }, Some(Some(b.id)))
        }
        (Button::Secondary, _, None) | (Button::Primary, Tool::Velocity, None) => {
            (Gesture::Pan, None)
        }
        (Button::Primary, Tool::Select | Tool::Disc, Some(b)) => (
            Gesture::Move {
                id: b.id,
                offset: b.pos - p,
                to: p,
            },
            Some(Some(b.id)),
        ),
        (Button::Primary, Tool::Select, None) => (Gesture::Pan, Some(None)),
        (Button::Primary, Tool::Disc, None) => (Gesture::Place { disc: true, at: p }, None),
        (Button::Primary, Tool::Point, _) => (Gesture::Place { disc: false, at: p }, None),
        (Button::Primary, Tool::Line(kind), _) => (Gesture::Draw { kind, a: p, b: p }, None),
        (Button::Primary, Tool::Delete, _) => match hit {
            Some(h) => (Gesture::Delete(h), None),
            None => (Gesture::Pan, None),
        },
    }
}

/// The gesture after the pointer moved to world point `p`.
pub fn drag(g: Gesture, p: DVec2) -> Gesture {
    match g {
        Gesture::Move { id, offset, .. } => Gesture::Move { id, offset, to: p },
        Gesture::Aim { id, .. } => Gesture::Aim { id, to: p },
        Gesture::Draw { kind, a, .. } => Gesture::Draw { kind, a, b: p },
        Gesture::Place { disc, .. } => Gesture::Place { disc, at: p },
        other => other,
    }
}

/// Options for what a release makes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Make {
    /// What a new disc is made of.
    pub disc: DiscTemplate,
    /// New lines are sensors (edges a disc falls off) rather than walls.
    pub sensor: bool,
    /// Drags shorter than this (metres) are clicks.
    pub slop: f64,
}

/// The engine action a finished gesture asks for, if any.
pub fn release(g: Gesture, scene: &Scene, make: &Make) -> Option<Action> {
    let body = |id| scene.bodies.iter().find(|b| b.id == id);
    match g {
        Gesture::Pan => None,
        Gesture::Move { id, offset, to } => {
            let b = body(id)?;
            let pos = to + offset;
            ((pos - b.pos).length() > make.slop).then_some(Action::UpdateBody {
                body: engine::BodySpec { pos, ..*b },
            })
        }
        Gesture::Aim { id, to } => {
            let b = body(id)?;
            let drag = to - b.pos;
            let vel = if drag.length() <= make.slop {
                DVec2::ZERO
            } else {
                velocity_from_drag(drag)
            };
            Some(Action::SetVelocity { id, vel })
        }
        Gesture::Draw { kind, a, b } => ((b - a).length() > make.slop).then_some(Action::AddLine {
            line: Line {
                a,
                b,
                kind,
                sensor: make.sensor,
            },
        }),
        Gesture::Place { disc: true, at } => Some(Action::AddBody {
            body: make.disc.at(next_id(scene), at),
        }),
        Gesture::Place { disc: false, at } => Some(Action::AddPoint {
            point: Point { pos: at },
        }),
        Gesture::Delete(Hit::Body(id)) => Some(Action::RemoveBody { id }),
        Gesture::Delete(Hit::Point(index)) => Some(Action::RemovePoint { index }),
        Gesture::Delete(Hit::Line(index)) => Some(Action::RemoveLine { index }),
    }
}

/// An id no body of `scene` has.
pub fn next_id(scene: &Scene) -> u64 {
    scene
        .bodies
        .iter()
        .map(|b| b.id.0.saturating_add(1))
        .max()
        .unwrap_or(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sandbox::sim::Sim;
    use engine::BodySpec;

    fn scene() -> Scene {
        Scene {
            bodies: vec![
                BodySpec::new(1, DVec2::new(0.0, 0.0), 0.1, 1.0, 0.2),
                BodySpec::new(2, DVec2::new(1.0, 0.0), 0.1, 1.0, 0.2),
                BodySpec::new(7, DVec2::new(2.0, 0.0), 0.1, 1.0, 0.2),
            ],
            points: vec![Point {
                pos: DVec2::new(0.0, 1.0),
            }],
            lines: vec![Line::new(
                DVec2::new(-1.0, -1.0),
                DVec2::new(3.0, -1.0),
                LineKind::Segment,
            )],
            ..Scene::default()
        }
    }

    fn make() -> Make {
        Make {
            disc: DiscTemplate {
                radius: 0.1,
                mass: 1.0,
                mu: 0.2,
                restitution: 1.0,
            },
            sensor: false,
            slop: 0.01,
        }
    }

    /// Press, drag to `to`, release: the action made.
    fn gesture(tool: Tool, button: Button, from: DVec2, to: DVec2, s: &Scene) -> Option<Action> {
        let (g, _) = press(tool, button, pick(s, from, 0.05), from, s);
        release(drag(g, to), s, &make())
    }

    #[test]
    fn pick_finds_bodies_then_points_then_lines() {
        let s = scene();
        let p = |x, y| pick(&s, DVec2::new(x, y), 0.05);
        assert_eq!(p(1.05, 0.0), Some(Hit::Body(BodyId(2))));
        assert_eq!(p(0.02, 1.0), Some(Hit::Point(0)));
        assert_eq!(p(2.5, -1.03), Some(Hit::Line(0)));
        assert_eq!(p(0.5, 0.5), None);
        // Beyond the segment's end it is not hit.
        assert_eq!(p(3.5, -1.0), None);
    }

    #[test]
    fn delete_removes_exactly_the_object_clicked() {
        let s = scene();
        let at = DVec2::new(1.0, 0.0);
        let a = gesture(Tool::Delete, Button::Primary, at, at, &s);
        assert_eq!(a, Some(Action::RemoveBody { id: BodyId(2) }));
        let mut sim = Sim::new(s.clone()).unwrap();
        sim.edit(a.unwrap()).unwrap();
        let ids: Vec<u64> = sim.scene().bodies.iter().map(|b| b.id.0).collect();
        assert_eq!(ids, vec![1, 7]);
        assert_eq!(sim.scene().points, s.points);
        assert_eq!(sim.scene().lines, s.lines);
        let at = DVec2::new(0.0, -1.0);
        assert_eq!(
            gesture(Tool::Delete, Button::Primary, at, at, &s),
            Some(Action::RemoveLine { index: 0 })
        );
        let empty = DVec2::new(0.5, 0.5);
        assert_eq!(
            gesture(Tool::Delete, Button::Primary, empty, empty, &s),
            None
        );
    }

    #[test]
    fn dragging_from_a_body_sets_its_velocity_scaled_by_the_arrow_time() {
        let s = scene();
        let from = DVec2::new(0.0, 0.0);
        let to = DVec2::new(0.5, 0.25);
        let want = Some(Action::SetVelocity {
            id: BodyId(1),
            vel: DVec2::new(2.0, 1.0),
        });
        assert_eq!(gesture(Tool::Velocity, Button::Primary, from, to, &s), want);
        // The right button aims from a body whatever the tool...
        assert_eq!(gesture(Tool::Point, Button::Secondary, from, to, &s), want);
        // ...and pans from empty space.
        let (g, sel) = press(Tool::Select, Button::Secondary, None, to, &s);
        assert_eq!((g, sel), (Gesture::Pan, None));
        assert_eq!(arrow_of(velocity_from_drag(to)), to);
        // A click on the body without dragging stops it.
        let stop = gesture(Tool::Velocity, Button::Primary, from, from, &s);
        assert_eq!(
            stop,
            Some(Action::SetVelocity {
                id: BodyId(1),
                vel: DVec2::ZERO
            })
        );
    }

    #[test]
    fn select_moves_a_body_keeping_the_grab_point_and_clicks_only_select() {
        let s = scene();
        let (g, sel) = press(
            Tool::Select,
            Button::Primary,
            Some(Hit::Body(BodyId(7))),
            DVec2::new(2.05, 0.0),
            &s,
        );
        assert_eq!(sel, Some(Some(BodyId(7))));
        match release(drag(g, DVec2::new(2.05, 0.5)), &s, &make()) {
            Some(Action::UpdateBody { body }) => {
                assert_eq!(body.id, BodyId(7));
                assert!((body.pos - DVec2::new(2.0, 0.5)).length() < 1e-12);
                assert_eq!(body.radius, 0.1);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(release(g, &s, &make()), None);
        // Empty space clears the selection and pans.
        let (g, sel) = press(Tool::Select, Button::Primary, None, DVec2::ZERO, &s);
        assert_eq!((g, sel), (Gesture::Pan, Some(None)));
    }

    #[test]
    fn placing_and_drawing_make_new_objects() {
        let s = scene();
        let at = DVec2::new(0.5, 0.5);
        match gesture(Tool::Disc, Button::Primary, at, at, &s) {
            Some(Action::AddBody { body }) => {
                assert_eq!(body.id, BodyId(8));
                assert_eq!(body.pos, at);
                assert_eq!(body.radius, 0.1);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            gesture(Tool::Point, Button::Primary, at, at, &s),
            Some(Action::AddPoint {
                point: Point { pos: at }
            })
        );
        let b = DVec2::new(1.5, 1.5);
        let ray = gesture(Tool::Line(LineKind::Ray), Button::Primary, at, b, &s);
        assert_eq!(
            ray,
            Some(Action::AddLine {
                line: Line::new(at, b, LineKind::Ray)
            })
        );
        // A click with a line tool draws nothing (its two points coincide).
        assert_eq!(
            gesture(Tool::Line(LineKind::Line), Button::Primary, at, at, &s),
            None
        );
        assert_eq!(next_id(&Scene::default()), 1);
    }
}
