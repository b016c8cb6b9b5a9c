//! The engine's third revision on the hostile scenes that revision 2 got
//! wrong (kept in `tests/hostile/`, each named by its generator kind and
//! seed in `lab::hostile`). Each test runs the scene under both revisions:
//! revision 2 must still fail as it did (records made under it replay bit
//! for bit, and the test proves it exercises the fix), revision 3 must end
//! as the model says, within the hostile generator's event cap and without
//! overlap.

use engine::{EndReason, Event, EventHandler, Limits, Revision, Scene, World, WorldConfig};

/// The hostile generator's event cap (a run reaching it is a livelock).
const CAP: u64 = 100_000;

/// The deepest overlap between any two discs at any event, as a fraction
/// of their contact distance.
#[derive(Default)]
struct Deepest(f64);

impl EventHandler for Deepest {
    fn on_event(&mut self, world: &World, event: &Event) {
        let bodies: Vec<_> = world.bodies().collect();
        for (k, a) in bodies.iter().enumerate() {
            for b in &bodies[k + 1..] {
                let s = a.material.radius + b.material.radius;
                let d = (a.trajectory.position(event.t) - b.trajectory.position(event.t)).length();
                self.0 = self.0.max((s - d) / s);
            }
        }
    }
}

/// How a run of a scene ended.
struct Outcome {
    reason: EndReason,
    events: u64,
    overlap: f64,
    pressed: u64,
}

fn run(name: &str, revision: Revision) -> Outcome {
    let path = format!("{}/tests/hostile/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the scene file is in the repository");
    let scene = Scene::from_json(&text).expect("a valid scene");
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let mut world = World::new(&scene, config).expect("a valid scene");
    let mut deepest = Deepest::default();
    let limits = Limits {
        max_events: CAP,
        ..Limits::default()
    };
    let end = world.run(&limits, &mut deepest);
    Outcome {
        reason: end.reason,
        events: world.stats().events,
        overlap: deepest.0,
        pressed: world.stats().pressed,
    }
}

/// Revision 2 ends `before`; revision 3 ends `after`, inside the cap and
/// without overlap beyond 1e-9 of a contact distance.
fn fixed(name: &str, before: EndReason, after: EndReason) -> Outcome {
    let old = run(name, Revision::R2);
    assert_eq!(old.reason, before, "{name} under revision 2");
    let new = run(name, Revision::R3);
    assert_eq!(new.reason, after, "{name} under revision 3");
    assert!(new.events < CAP, "{name}: {} events", new.events);
    assert!(new.overlap < 1e-9, "{name}: overlap {:e}", new.overlap);
    new
}

#[test]
fn a_disc_pressing_obliquely_on_a_pushed_chain_is_kicked_off_the_whole_chain() {
    // Disc 1 slides up past disc 2, which a hard-braking disc 3 pushes: a
    // kick between 1 and 2 alone was absorbed by 3 at the same instant.
    let out = fixed("wall-contact-277", EndReason::Stuck, EndReason::Rest);
    assert!(out.pressed > 0);
}

#[test]
fn discs_slower_than_their_positions_can_show_come_to_rest() {
    // Two discs against a wall hit each other at 5e-17 m/s, each hit
    // putting off the stop it was about to make.
    fixed("wall-contact-614", EndReason::Stuck, EndReason::Rest);
}

#[test]
fn a_light_disc_jammed_in_a_corner_by_a_heavy_one_stops_dead() {
    // Projected Gauss-Seidel moved mostly the light disc each sweep and
    // stalled on rounding; the exact solve on the pushing contacts ends it.
    fixed("mixed-477", EndReason::Stuck, EndReason::Rest);
    // Jammed between a wall, a post and a heavy disc.
    fixed("mixed-2371", EndReason::Stuck, EndReason::Rest);
}

#[test]
fn a_dense_pressed_cluster_comes_to_rest_within_the_cap() {
    // Revision 2 bounced its pressed pairs down to the rounding of their
    // speeds: 136,016 events, over the cap.
    fixed("cluster-38", EndReason::MaxEvents, EndReason::Rest);
    // Revision 2 managed this one; revision 3 must too.
    let out = run("cluster-1884", Revision::R3);
    assert_eq!(out.reason, EndReason::Rest);
    assert!(out.overlap < 1e-9, "{:e}", out.overlap);
}

#[test]
fn an_elastic_chain_pinned_between_two_walls_is_reported_stuck() {
    // No finite answer in the model: the chain rattles in a gap of
    // rounding, 1e-16 s an event, for ever.
    let out = fixed("pinned-chain-1320", EndReason::MaxEvents, EndReason::Stuck);
    assert!(out.events < 30_000, "{} events", out.events);
}

#[test]
fn discs_sliding_together_for_hundreds_of_metres_do_not_drift_into_each_other() {
    // Three discs on ice (mu = 2.8e-4) slide 269 m side by side, one
    // approaching the next below rounding noise: revision 2 let them
    // drift 1.1e-8 of a contact distance into each other.
    let old = run("cradle-12420", Revision::R2);
    assert!(old.overlap > 1e-8, "{:e}", old.overlap);
    fixed("cradle-12420", EndReason::Rest, EndReason::Rest);
}
