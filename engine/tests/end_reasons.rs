//! The two end reasons that say the model has no answer from here,
//! `stuck` and `out-of-range`, each in a scene where its definition in
//! docs/model.md holds, checked on the state the run ends in. (The others,
//! `rest`, `free`, `until`, `max-collisions` and `max-events`, are
//! checked where their limits are in `physics.rs`.)

use engine::{BodySpec, EndReason, Limits, Line, LineKind, Revision, Scene, World, WorldConfig};
use glam::DVec2;

fn world(scene: &Scene, revision: Revision) -> World {
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    World::new(scene, config).expect("a valid scene")
}

fn energy(world: &World, t: f64) -> f64 {
    world
        .bodies()
        .map(|b| 0.5 * b.material.mass * b.trajectory.velocity(t).length_squared())
        .sum()
}

/// Three elastic, frictionless discs of unequal masses touching each other
/// in a row along `d`, the row touching a wall at each end; the middle
/// one moving.
fn pinned_cradle(d: DVec2) -> Scene {
    let r = 0.02;
    let masses = [0.01, 0.037, 0.002];
    let bodies = (0..3)
        .map(|k| {
            let vel = if k == 1 { d * 1.5 } else { DVec2::ZERO };
            BodySpec::new(
                k as u64 + 1,
                d * (r + 2.0 * r * k as f64),
                r,
                masses[k],
                0.0,
            )
            .with_velocity(vel)
        })
        .collect();
    let (side, front) = (d.perp(), d * 6.0 * r);
    Scene {
        g: engine::scene::DEFAULT_G,
        t: 0.0,
        bodies,
        points: Vec::new(),
        lines: vec![
            Line::new(-side, side, LineKind::Line),
            Line::new(front + side, front - side, LineKind::Line),
        ],
    }
}

#[test]
fn an_elastic_chain_pinned_between_two_walls_ends_stuck_with_all_its_energy() {
    // Along an axis the energy is kept to 1e-12; in an oblique frame the
    // rounding of the normals over some 20,000 hits leaves 2.7e-12.
    for (d, kept) in [(DVec2::X, 1e-12), (DVec2::new(0.6, 0.8), 1e-11)] {
        let scene = pinned_cradle(d);
        let mut w = world(&scene, Revision::LATEST);
        let before = energy(&w, 0.0);
        let end = w.run(&Limits::default(), &mut ());
        assert_eq!(end.reason, EndReason::Stuck, "{d}");
        assert_eq!(w.stats().collapses, 0);
        let after = energy(&w, end.t);
        assert!(
            (after - before).abs() <= kept * before,
            "{d}: energy {before} -> {after}"
        );
        // The definition: something moves, and the next event comes before
        // the fastest disc has moved 1e-9 of the smallest radius.
        let fastest = w
            .bodies()
            .map(|b| b.trajectory.velocity(end.t).length())
            .fold(0.0, f64::max);
        assert!(fastest > 1.0, "{fastest}");
        let next = w
            .step(f64::INFINITY, &mut ())
            .expect("events still pending");
        assert!((next.t - end.t) * fastest <= 1e-9 * 0.02, "{next:?}");
    }
}

#[test]
fn the_sixth_revision_took_a_pinned_elastic_chain_as_a_collapse_and_lost_its_energy() {
    let scene = pinned_cradle(DVec2::X);
    let mut w = world(&scene, Revision::R6);
    let end = w.run(&Limits::default(), &mut ());
    assert_eq!(end.reason, EndReason::Rest);
    assert!(w.stats().collapses > 0);
    assert_eq!(energy(&w, end.t), 0.0);
}

#[test]
fn a_run_whose_next_event_is_past_1e150_s_with_a_disc_past_1e154_m_ends_out_of_range() {
    // Disc 1 creeps towards a wall 2 m away at 1e-150 m/s (a hit at
    // 2e150 s); disc 2 flies off without friction at 1e5 m/s (2e155 m from
    // the origin by then).
    let bodies = vec![
        BodySpec::new(1, DVec2::ZERO, 0.5, 1.0, 0.0).with_velocity(DVec2::new(1e-150, 0.0)),
        BodySpec::new(2, DVec2::new(0.0, 10.0), 0.5, 1.0, 0.0).with_velocity(DVec2::new(0.0, 1e5)),
    ];
    let scene = Scene {
        g: engine::scene::DEFAULT_G,
        t: 0.0,
        bodies,
        points: Vec::new(),
        lines: vec![Line::new(
            DVec2::new(2.5, -1.0),
            DVec2::new(2.5, 1.0),
            LineKind::Line,
        )],
    };
    let mut w = world(&scene, Revision::LATEST);
    let end = w.run(&Limits::default(), &mut ());
    assert_eq!(end.reason, EndReason::OutOfRange);
    assert_eq!(end.t, 0.0, "frozen at the last event");
    let next = w.step(f64::INFINITY, &mut ()).expect("the hit is pending");
    assert!(next.t > 1e150, "{next:?}");
    let far = w
        .bodies()
        .map(|b| b.trajectory.position(next.t).abs().max_element())
        .fold(0.0, f64::max);
    assert!(far > 1e154, "{far:e}");
}

#[test]
fn the_same_disc_without_the_fast_one_creeps_to_its_hit_and_then_is_free() {
    let bodies =
        vec![BodySpec::new(1, DVec2::ZERO, 0.5, 1.0, 0.0).with_velocity(DVec2::new(1e-150, 0.0))];
    let scene = Scene {
        g: engine::scene::DEFAULT_G,
        t: 0.0,
        bodies,
        points: Vec::new(),
        lines: vec![Line::new(
            DVec2::new(2.5, -1.0),
            DVec2::new(2.5, 1.0),
            LineKind::Line,
        )],
    };
    let mut w = world(&scene, Revision::LATEST);
    let end = w.run(&Limits::default(), &mut ());
    // It hits the wall at 2e150 s and creeps away for ever.
    assert_eq!(end.reason, EndReason::Free);
    assert_eq!(w.stats().collisions(), 1);
    assert!((end.t - 2e150).abs() <= 1e-12 * 2e150, "{end:?}");
}
