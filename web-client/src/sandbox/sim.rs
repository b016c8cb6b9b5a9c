//! The sandbox's simulation state: one engine [`Model`] (the single source
//! of truth), the playback time `t` shown on screen, play/pause and speed,
//! and the running tally of events up to `t`. Playing extends the model's
//! chain lazily, a bounded number of events per frame, and never shows
//! time the chain has not reached; rewinding is only moving `t` back.
//! Edits are engine actions applied at `t` (dropping later history); a
//! refused edit leaves everything as it was. Nothing here draws.

use engine::{Action, End, EndReason, Event, EventKind, Limits, Model, Scene};

use super::presets::FallOff;

/// The sandbox's model type: sensor lines are table edges a disc falls off.
pub type SandboxModel = Model<FallOff>;

/// Events counted by kind among the first `upto` events of a chain.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// How many events of the chain are counted.
    pub upto: usize,
    pub body_body: u64,
    pub body_line: u64,
    pub body_point: u64,
    pub stops: u64,
    pub exits: u64,
    pub entries: u64,
    pub actions: u64,
}

impl Tally {
    /// Body–body, body–line and body–point events.
    pub fn collisions(&self) -> u64 {
        self.body_body + self.body_line + self.body_point
    }

    /// Events other than actions (what the physics did).
    pub fn physical(&self) -> u64 {
        self.upto as u64 - self.actions
    }

    fn slot(&mut self, kind: &EventKind) -> &mut u64 {
        match kind {
            EventKind::BodyBody { .. } => &mut self.body_body,
            EventKind::BodyLine { .. } => &mut self.body_line,
            EventKind::BodyPoint { .. } => &mut self.body_point,
            EventKind::Stop { .. } => &mut self.stops,
            EventKind::RegionExit { .. } => &mut self.exits,
            EventKind::RegionEntry { .. } => &mut self.entries,
            EventKind::Action { .. } => &mut self.actions,
        }
    }

    /// Moves the tally to cover exactly the first `k` events, walking from
    /// where it was (cheap for playback, which moves a little each frame).
    /// The caller resets it when the chain's prefix changes (an edit).
    pub fn seek(&mut self, events: &[Event], k: usize) {
        let k = k.min(events.len());
        if self.upto > events.len() {
            *self = Tally::default();
        }
        while self.upto < k {
            let kind = events[self.upto].kind;
            *self.slot(&kind) += 1;
            self.upto += 1;
        }
        while self.upto > k {
            self.upto -= 1;
            let kind = events[self.upto].kind;
            let n = self.slot(&kind);
            *n = n.saturating_sub(1);
        }
    }

    /// The tally of all events at or before time `t`.
    pub fn seek_time(&mut self, events: &[Event], t: f64) {
        let k = events.partition_point(|e| e.t <= t);
        self.seek(events, k);
    }
}

/// Speeds offered by the playback bar (negative plays backwards).
pub const SPEEDS: [f64; 10] = [-2.0, -1.0, -0.1, 0.01, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0];

/// The model and the playback over it.
pub struct Sim {
    pub model: SandboxModel,
    /// The time shown.
    pub t: f64,
    pub playing: bool,
    pub speed: f64,
    /// The last frame wanted a time the chain had not reached yet.
    pub behind: bool,
    tally: Tally,
}

impl Sim {
    /// A paused simulation of `scene` at its start time, or why the scene
    /// cannot be simulated.
    pub fn new(scene: Scene) -> Result<Sim, String> {
        let t = scene.t;
        let model = Model::with_rules(scene, FallOff, engine::WorldConfig::default())
            .map_err(|e| e.to_string())?;
        Ok(Sim {
            model,
            t,
            playing: false,
            speed: 1.0,
            behind: false,
            tally: Tally::default(),
        })
    }

    /// A simulation of a scene file's text; the error names the object and
    /// field at fault.
    pub fn import(text: &str) -> Result<Sim, String> {
        let scene = Scene::from_json(text).map_err(|e| e.to_string())?;
        Sim::new(scene)
    }

    /// The scene file of the state shown.
    pub fn export(&self) -> String {
        self.model.scene_at(self.t).to_json()
    }

    /// The time the model starts at.
    pub fn start(&self) -> f64 {
        self.model.start().t
    }

    /// The scene at the time shown.
    pub fn scene(&self) -> Scene {
        self.model.scene_at(self.t)
    }

    /// How far the chain is known (infinite once nothing more can happen).
    pub fn computed_to(&self) -> f64 {
        self.model.computed_to()
    }

    /// How the model's last computation ended.
    pub fn end(&self) -> Option<End> {
        self.model.end()
    }

    /// Extends the chain towards `until` with at most `budget` events;
    /// returns how far it is known now.
    pub fn compute_to(&mut self, until: f64, budget: u64) -> f64 {
        if self.model.computed_to() < until {
            self.model.compute(&Limits {
                until,
                max_collisions: u64::MAX,
                max_events: budget.max(1),
            });
        }
        self.model.computed_to()
    }

    /// One frame of playback: `dt` seconds of wall time at the current
    /// speed, computing at most `budget` events. Stops at the start when
    /// playing backwards and once everything is at rest.
    pub fn advance(&mut self, dt: f64, budget: u64) {
        if !self.playing {
            self.behind = false;
            return;
        }
        let target = self.t + dt * self.speed;
        if self.speed >= 0.0 {
            let known = self.compute_to(target, budget);
            if target > known {
                self.t = self.t.max(known);
                self.behind = true;
            } else {
                self.t = target;
                self.behind = false;
            }
            if let Some(End {
                reason: EndReason::Rest,
                t,
            }) = self.model.end()
            {
                if self.t >= t {
                    self.playing = false;
                }
            }
        } else {
            self.behind = false;
            self.t = target.max(self.start());
            if self.t <= self.start() {
                self.playing = false;
            }
        }
    }

    /// Starts playing. At the end of a chain that came to rest it starts
    /// over from the beginning; backwards at the start it turns forwards.
    pub fn play(&mut self) {
        if let Some(End {
            reason: EndReason::Rest,
            t,
        }) = self.model.end()
        {
            if self.t >= t && self.speed > 0.0 {
                self.t = self.start();
            }
        }
        if self.speed < 0.0 && self.t <= self.start() {
            self.speed = 1.0;
        }
        self.playing = true;
    }

    /// Shows time `t` (clamped to the start and to what is computed).
    pub fn seek(&mut self, t: f64) {
        let t = if t.is_finite() { t } else { self.t };
        self.t = t.clamp(self.start(), self.computed_to().max(self.start()));
    }

    /// Applies `action` at the time shown. On refusal the model is unchanged
    /// and the engine's reason comes back.
    pub fn edit(&mut self, action: Action) -> Result<(), String> {
        self.model
            .apply(self.t, action)
            .map_err(|e| e.to_string())?;
        self.tally = Tally::default();
        self.behind = false;
        Ok(())
    }

    /// Events by kind up to the time shown.
    pub fn tally(&mut self) -> Tally {
        self.tally.seek_time(self.model.events(), self.t);
        self.tally
    }

    /// The events in the time window `(from, to]`, newest last, at most `max`.
    pub fn recent_events(&self, from: f64, to: f64, max: usize) -> &[Event] {
        let ev = self.model.events();
        let hi = ev.partition_point(|e| e.t <= to);
        let lo = ev
            .partition_point(|e| e.t <= from)
            .max(hi.saturating_sub(max));
        &ev[lo..hi]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::{BodyId, BodySpec};
    use glam::DVec2;

    fn two_discs() -> Scene {
        Scene {
            bodies: vec![
                BodySpec::new(1, DVec2::new(0.0, 0.0), 0.016, 0.01, 0.3)
                    .with_velocity(DVec2::new(2.0, 0.0)),
                BodySpec::new(2, DVec2::new(0.5, 0.0), 0.016, 0.01, 0.3),
                BodySpec::new(3, DVec2::new(0.5, 0.3), 0.016, 0.01, 0.3),
            ],
            ..Scene::default()
        }
    }

    #[test]
    fn galperin_three_run_to_the_end_counts_314_collisions() {
        let mut sim = Sim::new(engine::presets::galperin(3)).unwrap();
        sim.playing = true;
        // Play in frames with a small event budget, as the screen does.
        for _ in 0..2000 {
            sim.advance(0.05, 50);
        }
        assert!(sim.computed_to().is_infinite(), "{:?}", sim.end());
        let tally = sim.tally();
        assert_eq!(tally.body_body + tally.body_line, 314);
        assert_eq!(tally.collisions(), engine::presets::pi_digits(3));
        // Rewinding is just moving t: the tally follows it back.
        sim.seek(0.0);
        assert_eq!(sim.tally().collisions(), 0);
    }

    #[test]
    fn playback_never_shows_time_the_chain_has_not_reached() {
        let mut sim = Sim::new(engine::presets::box_of_discs(100, 0.0, 3)).unwrap();
        sim.playing = true;
        sim.speed = 4.0;
        sim.advance(0.1, 10);
        assert!(sim.behind);
        assert!(sim.t <= sim.computed_to());
        assert_eq!(sim.model.events().len(), 10);
    }

    #[test]
    fn playing_backwards_stops_at_the_start() {
        let mut sim = Sim::new(two_discs()).unwrap();
        sim.playing = true;
        sim.advance(0.2, 1000);
        assert!(sim.t > 0.0);
        sim.speed = -2.0;
        sim.advance(1.0, 1000);
        assert_eq!(sim.t, 0.0);
        assert!(!sim.playing);
        assert_eq!(sim.scene(), sim.model.scene_at(0.0));
    }

    #[test]
    fn play_pauses_itself_once_everything_rests() {
        let mut sim = Sim::new(two_discs()).unwrap();
        sim.playing = true;
        for _ in 0..100 {
            sim.advance(0.1, 1000);
        }
        assert!(!sim.playing);
        assert!(sim.scene().bodies.iter().all(|b| b.vel == DVec2::ZERO));
        let tally = sim.tally();
        assert_eq!(tally.body_body, 1);
        // Equal masses head on: the striker stops dead at the hit (no stop
        // event), the target slides on and stops later.
        assert_eq!(tally.stops, 1);
        // Play again at the end: it starts over.
        sim.play();
        assert_eq!(sim.t, 0.0);
        assert!(sim.playing);
    }

    #[test]
    fn a_malformed_import_names_the_field_and_a_refused_edit_changes_nothing() {
        let mut sim = Sim::new(two_discs()).unwrap();
        let bad = r#"{"bodies":[{"id":1,"pos":[0,0],"vel":[0,0],"radius":0.1,"mass":-1,"mu":0}]}"#;
        let err = Sim::import(bad).err().unwrap();
        assert!(err.contains("bodies[0]") && err.contains("mass"), "{err}");
        assert!(Sim::import("{ not json").is_err());
        // An overlapping disc is refused and the scene stays as it was.
        let before = sim.scene();
        let events = sim.model.events().len();
        let overlapping = BodySpec::new(9, DVec2::new(0.01, 0.0), 0.016, 0.01, 0.3);
        let err = sim.edit(Action::AddBody { body: overlapping }).unwrap_err();
        assert!(err.contains("overlaps"), "{err}");
        assert_eq!(sim.scene(), before);
        assert_eq!(sim.model.events().len(), events);
    }

    #[test]
    fn export_then_import_gives_the_same_scene() {
        let mut sim = Sim::new(two_discs()).unwrap();
        sim.playing = true;
        sim.advance(0.1, 1000);
        sim.playing = false;
        let again = Sim::import(&sim.export()).unwrap();
        assert_eq!(again.scene(), sim.scene());
        assert_eq!(again.t, sim.t);
    }

    #[test]
    fn delete_removes_exactly_that_body_from_then_on() {
        let mut sim = Sim::new(two_discs()).unwrap();
        sim.compute_to(1.0, 1000);
        sim.seek(0.1);
        sim.edit(Action::RemoveBody { id: BodyId(3) }).unwrap();
        let ids: Vec<u64> = sim.scene().bodies.iter().map(|b| b.id.0).collect();
        assert_eq!(ids, vec![1, 2]);
        assert!(sim.model.body_at(BodyId(3), 0.05).is_some());
        // Later history was dropped: the chain ends at the edit.
        assert_eq!(sim.computed_to(), 0.1);
    }

    #[test]
    fn the_tally_walks_both_ways_and_matches_a_fresh_count() {
        let mut sim = Sim::new(engine::presets::box_of_discs(30, 0.2, 5)).unwrap();
        sim.compute_to(f64::INFINITY, 1_000_000);
        let events = sim.model.events().to_vec();
        let mut walking = Tally::default();
        for k in [10, 200, 50, events.len(), 0, 77] {
            let k = k.min(events.len());
            walking.seek(&events, k);
            let mut fresh = Tally::default();
            fresh.seek(&events, k);
            assert_eq!(walking, fresh, "k = {k}");
            let by_hand = events[..k].iter().filter(|e| e.kind.is_collision()).count();
            assert_eq!(walking.collisions(), by_hand as u64);
        }
    }
}
