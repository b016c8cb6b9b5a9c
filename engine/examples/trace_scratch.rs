use engine::{Event, EventHandler, Limits, Revision, Scene, World, WorldConfig};
struct T {
    from: u64,
    to: u64,
    n: u64,
    e: f64,
    pressed: u64,
    scale: f64,
    vel: Vec<(engine::BodyId, glam::DVec2)>,
}
impl EventHandler for T {
    fn on_event(&mut self, w: &World, ev: &Event) {
        self.n += 1;
        let mut energy = 0.0;
        for b in w.bodies() {
            let v = b.trajectory.velocity(ev.t);
            energy += 0.5 * b.material.mass * v.length_squared();
        }
        let p = w.stats().pressed;
        self.scale = self.scale.max(energy);
        let gain = (energy - self.e) / self.scale;
        if (self.n >= self.from && self.n <= self.to) || gain > 1e-3 {
            println!("GAIN {:.3e}", gain);
            for b in w.bodies() {
                let v = b.trajectory.velocity(ev.t);
                if let Some(&(_, old)) = self.vel.iter().find(|x| x.0 == b.id) {
                    if old != v {
                        println!(
                            "   changed {:?} {:?} -> {:?} m={:.4e} a={} p={:?}",
                            b.id,
                            old,
                            v,
                            b.material.mass,
                            b.trajectory.alpha(),
                            b.trajectory.position(ev.t)
                        );
                    }
                }
            }
            println!(
                "#{} t={:.17e} {:?} E={:.6e} dE={:.3e} pressed+{}",
                self.n,
                ev.t,
                ev.kind,
                energy,
                energy - self.e,
                p - self.pressed
            );
            for id in ev.kind.bodies() {
                let b = w.body(id).unwrap();
                let m = b.material;
                println!(
                    "   {:?} p={:?} v={:?} a={} m={:.4e} mu={} e={} r={}",
                    id,
                    b.trajectory.position(ev.t),
                    b.trajectory.velocity(ev.t),
                    b.trajectory.alpha(),
                    m.mass,
                    m.mu,
                    m.restitution,
                    m.radius
                );
            }
        }
        self.e = energy;
        self.pressed = p;
        self.vel = w
            .bodies()
            .map(|b| (b.id, b.trajectory.velocity(ev.t)))
            .collect();
    }
}
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let scene = Scene::from_json(&std::fs::read_to_string(&a[1]).unwrap()).unwrap();
    let rev: Revision = a[2].parse().unwrap();
    let from: u64 = a[3].parse().unwrap();
    let to: u64 = a[4].parse().unwrap();
    let mut w = World::new(
        &scene,
        WorldConfig {
            revision: rev,
            ..WorldConfig::default()
        },
    )
    .unwrap();
    let e0: f64 = scene
        .bodies
        .iter()
        .map(|b| 0.5 * b.mass * b.vel.length_squared())
        .sum();
    let mut t = T {
        from,
        to,
        n: 0,
        e: e0,
        pressed: 0,
        scale: e0,
        vel: vec![],
    };
    let end = w.run(
        &Limits {
            until: 100.0,
            max_events: std::env::var("CAP")
                .map(|c| c.parse().unwrap())
                .unwrap_or(100_000),
            ..Limits::default()
        },
        &mut t,
    );
    println!(
        "end {:?} events {} stats {:?}",
        end.reason,
        w.stats().events,
        w.stats()
    );
}
