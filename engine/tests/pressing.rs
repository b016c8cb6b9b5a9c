//! The engine's second revision where the model has no closed form or the
//! arithmetic used to fail: discs pressed together obliquely, collapses
//! into wedges, hits from far away. Each is checked against geometry or a
//! closed form, never against earlier output.

use engine::{
    BodyId, BodySpec, EndReason, Event, EventHandler, Limits, Line, LineKind, Revision, Scene,
    World, WorldConfig,
};
use glam::DVec2;

mod common;
use common::Deepest;

fn disc(id: u64, pos: DVec2, vel: DVec2, radius: f64, mu: f64, e: f64) -> BodySpec {
    BodySpec::new(id, pos, radius, 0.005, mu)
        .with_velocity(vel)
        .with_restitution(e)
}

fn scene(bodies: Vec<BodySpec>, lines: Vec<Line>) -> Scene {
    Scene {
        g: 9.81,
        t: 0.0,
        bodies,
        points: Vec::new(),
        lines,
    }
}

/// The time of the first collision and where body 1 was then.
#[derive(Default)]
struct FirstHit(Option<(f64, DVec2)>);

impl EventHandler for FirstHit {
    fn on_event(&mut self, world: &World, event: &Event) {
        if self.0.is_none() && event.kind.is_collision() {
            let p = world
                .body(BodyId(1))
                .map(|b| b.trajectory.position(event.t));
            self.0 = Some((event.t, p.unwrap_or(DVec2::NAN)));
        }
    }
}

fn latest() -> WorldConfig {
    WorldConfig {
        revision: Revision::LATEST,
        ..WorldConfig::default()
    }
}

#[test]
fn discs_pressed_together_obliquely_never_overlap_and_the_approximation_is_counted() {
    // The rear disc brakes less and presses the front one, whose centre
    // lies 30 degrees off their common direction of travel: the pair turns
    // and slides along each other (no closed form).
    let r = 0.016;
    let off = DVec2::new(30f64.to_radians().cos(), 30f64.to_radians().sin()) * 2.0 * r;
    let v = DVec2::new(1.0, 0.0);
    let s = scene(
        vec![
            disc(1, DVec2::ZERO, v, r, 0.1, 0.9),
            disc(2, off, v, r, 0.5, 0.9),
        ],
        Vec::new(),
    );
    let mut world = World::new(&s, latest()).unwrap();
    let mut deepest = Deepest::default();
    let end = world.run(&Limits::default(), &mut deepest);
    assert_eq!(end.reason, EndReason::Rest);
    assert!(
        deepest.0 <= 1e-12,
        "overlap {:e} of the contact distance",
        deepest.0
    );
    assert!(world.stats().pressed > 0, "{:?}", world.stats());
}

#[test]
fn a_disc_driven_into_a_plastic_wedge_stops_in_its_corner_instead_of_spinning() {
    // Two walls 25 degrees apart; a frictionless plastic disc sliding along
    // the first into the corner bounces between them ever slower at one
    // instant: the limit is rest.
    let angle = 25f64.to_radians();
    let lines = vec![
        Line::new(DVec2::X, DVec2::ZERO, LineKind::Segment),
        Line::new(
            DVec2::ZERO,
            DVec2::new(angle.cos(), angle.sin()),
            LineKind::Segment,
        ),
    ];
    let r = 0.03;
    let s = scene(
        vec![disc(
            1,
            DVec2::new(0.5, r),
            DVec2::new(-1.0, 0.0),
            r,
            0.0,
            0.0,
        )],
        lines,
    );
    let mut world = World::new(&s, latest()).unwrap();
    let end = world.run(&Limits::default(), &mut ());
    assert_eq!(end.reason, EndReason::Rest, "{end:?} {:?}", world.stats());
    // At rest touching both walls: its centre on the bisector, r from each.
    let p = world.body(BodyId(1)).unwrap().trajectory.position(end.t);
    let expected = DVec2::new((angle / 2.0).cos(), (angle / 2.0).sin()) * (r / (angle / 2.0).sin());
    assert!((p - expected).length() <= 1e-12, "{p} against {expected}");
}

#[test]
fn a_frictionless_disc_seven_hundred_kilometres_away_hits_at_the_exact_time() {
    let r = 0.028214309455620812;
    let (x0, u) = (-746018.0303277491, 0.3003819443982404);
    let s = scene(
        vec![
            disc(1, DVec2::new(x0, 0.0), DVec2::new(u, 0.0), r, 0.0, 1.0),
            disc(2, DVec2::ZERO, DVec2::ZERO, r, 0.3, 1.0),
        ],
        Vec::new(),
    );
    let mut world = World::new(&s, latest()).unwrap();
    let mut first = FirstHit::default();
    world.run(&Limits::default(), &mut first);
    // Contact when the gap of centres is 2r: t = (-x0 - 2r) / u.
    let exact = (-x0 - 2.0 * r) / u;
    let (t, _) = first.0.expect("the disc hits");
    assert!(
        (t - exact).abs() <= 4.0 * f64::EPSILON * exact,
        "{t} against {exact}"
    );
}

#[test]
fn a_hit_three_thousand_kilometres_from_its_start_leaves_the_disc_exactly_touching() {
    // Coordinates of 3e6 m carry 5e-10 m of rounding: the hit puts the disc
    // back at exactly its radius from the segment.
    let r = 0.0182932322911238;
    let start = DVec2::new(-1197321.4071733716, 2666599.704487572);
    let s = scene(
        vec![disc(
            1,
            start,
            DVec2::new(1.2098742926103472, -2.694556709512421),
            r,
            0.0,
            0.03,
        )],
        vec![Line::new(
            DVec2::new(-0.9122602579492999, -0.4096110615770487),
            DVec2::new(0.9122602579492999, 0.4096110615770487),
            LineKind::Segment,
        )],
    );
    let geom = engine::obstacle::LineGeom::new(&s.lines[0]).unwrap();
    let mut world = World::new(&s, latest()).unwrap();
    let mut first = FirstHit::default();
    world.run(
        &Limits {
            until: 1e7,
            ..Limits::default()
        },
        &mut first,
    );
    let (_, p) = first.0.expect("the disc hits the segment");
    let err = (geom.distance(p) - r).abs() / r;
    assert!(err <= 1e-13, "distance off by {err:e} of the radius");
}
