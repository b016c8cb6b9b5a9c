//! The peer a user would pick instead: `rapier2d-f64`, a time-stepping
//! impulse solver, set up to be as close to the model as it allows. Discs
//! are balls with the scene's mass, restitution 1 (combined by `max`, so
//! the scene's own value when below 1 is not used: rapier has no "softer
//! body decides" rule), zero friction and damping, no gravity (the table is
//! seen from above). Coulomb friction is applied as the issue asks: each
//! step a force `-mu m g v/|v|`, clamped so that it can at most stop the
//! disc. Lines are half-spaces (infinite) or segments; discs whose centre
//! leaves the board are removed. A collision is counted when a contact pair
//! starts carrying an impulse (it carried none the step before). The speed
//! cap (400 m/s by default) is lifted.

use crate::outcome::{BodyEnd, Outcome};
use crate::scenes::Case;
use engine::LineKind;
use glam::DVec2;
use rapier2d_f64::na::Unit;
use rapier2d_f64::prelude::*;
use std::collections::HashSet;
use std::time::Instant;

fn vec2(p: DVec2) -> Vector {
    Vector::new(p.x, p.y)
}

fn dvec(v: Vector) -> DVec2 {
    DVec2::new(v.x, v.y)
}

/// Computes `case` with rapier at time step `dt`, with or without CCD.
pub fn run(case: &Case, dt: f64, ccd: bool, max_steps: u64) -> Outcome {
    let start = Instant::now();
    let sc = &case.scene;
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0);
    world.integration_parameters.dt = dt;
    world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
    world.integration_parameters.length_unit = (case.min_radius() * 10.0).min(1.0);
    if !ccd {
        world.integration_parameters.max_ccd_substeps = 0;
    }
    let mut handles = Vec::with_capacity(sc.bodies.len());
    for b in &sc.bodies {
        let body = RigidBodyBuilder::dynamic()
            .translation(vec2(b.pos))
            .linvel(vec2(b.vel))
            .linear_damping(0.0)
            .angular_damping(0.0)
            .can_sleep(false)
            .ccd_enabled(ccd);
        let area = std::f64::consts::PI * b.radius * b.radius;
        let collider = ColliderBuilder::ball(b.radius)
            .density(b.mass / area)
            .restitution(1.0)
            .restitution_combine_rule(CoefficientCombineRule::Max)
            .friction(0.0)
            .friction_combine_rule(CoefficientCombineRule::Min);
        let (h, _) = world.insert(body, collider);
        handles.push(h);
    }
    for l in sc.lines.iter().filter(|l| !l.sensor) {
        let shape = match l.kind {
            LineKind::Line => {
                // Outward normal towards the side the first disc is on.
                let t = (l.b - l.a).normalize();
                let mut n = t.perp();
                if let Some(b) = sc.bodies.first() {
                    if n.dot(b.pos - l.a) < 0.0 {
                        n = -n;
                    }
                }
                ColliderBuilder::halfspace(Unit::new_unchecked(vec2(n))).translation(vec2(l.a))
            }
            LineKind::Ray => ColliderBuilder::segment(vec2(l.a), vec2(l.a + (l.b - l.a) * 1e6)),
            LineKind::Segment => ColliderBuilder::segment(vec2(l.a), vec2(l.b)),
        };
        let fixed = world.insert_body(RigidBodyBuilder::fixed());
        let c = shape
            .restitution(1.0)
            .restitution_combine_rule(CoefficientCombineRule::Max)
            .friction(0.0)
            .friction_combine_rule(CoefficientCombineRule::Min);
        world.insert_collider(c, Some(fixed));
    }
    for q in &sc.points {
        let fixed = world.insert_body(RigidBodyBuilder::fixed().translation(vec2(q.pos)));
        let c = ColliderBuilder::ball(1e-9).restitution(1.0).friction(0.0);
        world.insert_collider(c, Some(fixed));
    }
    let board = case.board();
    let mu_g: Vec<f64> = sc.bodies.iter().map(|b| b.mu * sc.g).collect();
    let mass: Vec<f64> = sc.bodies.iter().map(|b| b.mass).collect();
    let mut alive = vec![true; sc.bodies.len()];
    let mut last: Vec<BodyEnd> = sc
        .bodies
        .iter()
        .map(|b| BodyEnd {
            id: b.id.0,
            pos: b.pos,
            vel: b.vel,
            removed: false,
        })
        .collect();
    let mut active: HashSet<(ColliderHandle, ColliderHandle)> = HashSet::new();
    let mut collisions = 0u64;
    let mut max_overlap: f64 = 0.0;
    let steps_needed = (case.until / dt).ceil() as u64;
    let steps = steps_needed.min(max_steps);
    for _ in 0..steps {
        for (i, h) in handles.iter().enumerate() {
            if !alive[i] {
                continue;
            }
            if let Some(rb) = world.bodies.get_mut(*h) {
                rb.reset_forces(false);
                let v = dvec(rb.linvel());
                let speed = v.length();
                if speed > 0.0 && mu_g[i] > 0.0 {
                    let f = if speed > mu_g[i] * dt {
                        -v / speed * (mass[i] * mu_g[i])
                    } else {
                        -v * (mass[i] / dt)
                    };
                    rb.add_force(vec2(f), true);
                }
            }
        }
        world.step();
        let mut now = HashSet::new();
        for pair in world.contact_pairs() {
            if pair.has_any_active_contact() && pair.total_impulse_magnitude() > 0.0 {
                let key = (pair.collider1, pair.collider2);
                if !active.contains(&key) {
                    collisions += 1;
                }
                now.insert(key);
            }
        }
        active = now;
        for (i, h) in handles.iter().enumerate() {
            if !alive[i] {
                continue;
            }
            let Some(rb) = world.bodies.get(*h) else {
                continue;
            };
            last[i].pos = dvec(rb.translation());
            last[i].vel = dvec(rb.linvel());
            if let Some(b) = &board {
                if !b.contains(last[i].pos) {
                    alive[i] = false;
                    last[i].removed = true;
                    world.remove_body(*h);
                }
            }
        }
        for i in 0..last.len() {
            for j in i + 1..last.len() {
                if alive[i] && alive[j] {
                    let s = sc.bodies[i].radius + sc.bodies[j].radius;
                    let d = (last[i].pos - last[j].pos).length();
                    max_overlap = max_overlap.max((s - d) / s);
                }
            }
        }
    }
    last.sort_by_key(|b| b.id);
    Outcome {
        bodies: last,
        collisions,
        capped: steps < steps_needed,
        max_overlap,
        secs: start.elapsed().as_secs_f64(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    #[test]
    fn rapier_with_ccd_keeps_the_fast_tiny_disc_on_its_side() {
        let out = run(&scenes::fast_tiny(), 1e-3, true, u64::MAX);
        assert!(out.bodies[0].pos.x < 0.5, "{:?}", out.bodies[0]);
    }

    #[test]
    fn rapier_friction_force_stops_a_lone_disc_near_the_closed_form_distance() {
        let mut case = scenes::fast_tiny();
        case.scene.lines.clear();
        case.scene.bodies[0].vel = DVec2::new(1.0, 0.0);
        case.until = 0.5;
        let out = run(&case, 1e-4, false, u64::MAX);
        let expected = case.scene.bodies[0].pos.x + 1.0 / (2.0 * 0.3 * 9.81);
        assert!(
            (out.bodies[0].pos.x - expected).abs() < 1e-3,
            "{:?}",
            out.bodies[0]
        );
        assert!(out.bodies[0].vel.length() < 1e-9);
    }
}
