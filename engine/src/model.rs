//! The model: the chain of timed scenes of one computation.
//!
//! The chain is stored as the list of events plus, for every body, its
//! *lane*: the trajectories it had, each tagged with the number of events
//! that had happened when it began. The scene right after event `k` is every
//! body's last lane entry with tag `<= k`; the state at any time `t` is that
//! scene advanced in closed form — a binary search per body, `O(log events)`,
//! so showing, scrubbing and rewinding any moment is cheap and exact.
//!
//! Actions (add, remove or change a body, a point, a line, gravity) may be
//! given at any time: one at a past time drops the history after it and the
//! computation continues from there. A [`SceneDiff`] between two times lists
//! only the bodies whose motion differs, small enough to send over a network.

use crate::event::{Event, EventKind};
use crate::id::BodyId;
use crate::limits::{End, EndReason, Limits};
use crate::obstacle::{Line, Point};
use crate::scene::{BodySpec, Scene, SceneError};
use crate::trajectory::Trajectory;
use crate::world::handler::{EventHandler, ExitResponse};
use crate::world::{BodyState, Material, World, WorldConfig};
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A change to the scene, given at a time.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "action", rename_all = "kebab-case")]
pub enum Action {
    /// Put a new disc in the scene.
    AddBody { body: BodySpec },
    /// Take a disc out.
    RemoveBody { id: BodyId },
    /// Give a disc a new velocity (a shot).
    SetVelocity { id: BodyId, vel: DVec2 },
    /// Replace a disc's position, velocity and material.
    UpdateBody { body: BodySpec },
    /// Add a fixed point.
    AddPoint { point: Point },
    /// Remove the point at an index (later points move down one).
    RemovePoint { index: usize },
    /// Add a line.
    AddLine { line: Line },
    /// Remove the line at an index (later lines move down one).
    RemoveLine { index: usize },
    /// Change gravity (and so every disc's deceleration).
    SetGravity { g: f64 },
}

/// An action and the time it takes effect.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TimedAction {
    pub t: f64,
    #[serde(flatten)]
    pub action: Action,
}

/// Why an action was refused (the model is unchanged).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ActionError {
    #[error("the action's time {0} is not a finite time at or after the start")]
    BadTime(f64),
    #[error("no {0} in the scene at that time")]
    NoSuchBody(BodyId),
    #[error("{0} is already in the scene")]
    DuplicateBody(BodyId),
    #[error("no {kind} with index {index}")]
    NoSuchObject { kind: &'static str, index: usize },
    #[error("the scene after the action is invalid: {0}")]
    Invalid(#[from] SceneError),
}

/// Bodies, points, lines and gravity, each body with its trajectory: what a
/// client needs to show any moment until the next event.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Snapshot {
    pub t: f64,
    pub g: f64,
    pub bodies: Vec<BodyState>,
    pub points: Vec<Point>,
    pub lines: Vec<Line>,
}

impl Snapshot {
    /// The scene at time `t` (until the next event after the snapshot).
    pub fn scene_at(&self, t: f64) -> Scene {
        Scene {
            g: self.g,
            t,
            bodies: self.bodies.iter().map(|b| b.spec_at(t)).collect(),
            points: self.points.clone(),
            lines: self.lines.clone(),
        }
    }
}

/// What changed between two times: the bodies whose motion differs (with
/// their state at `to`, or `None` if gone) and, if they changed, the fixed
/// objects and gravity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SceneDiff {
    pub from: f64,
    pub to: f64,
    pub bodies: Vec<(BodyId, Option<BodyState>)>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed: Option<Fixed>,
}

impl SceneDiff {
    /// Turns the snapshot at `from` into the snapshot at `to`.
    pub fn apply(&self, snap: &mut Snapshot) {
        for (id, state) in &self.bodies {
            let at = snap.bodies.iter().position(|b| b.id == *id);
            match (at, state) {
                (Some(k), Some(s)) => snap.bodies[k] = *s,
                (Some(k), None) => {
                    snap.bodies.remove(k);
                }
                (None, Some(s)) => snap.bodies.push(*s),
                (None, None) => {}
            }
        }
        snap.bodies.sort_by_key(|b| b.id);
        if let Some(f) = &self.fixed {
            snap.g = f.g;
            snap.points = f.points.clone();
            snap.lines = f.lines.clone();
        }
        snap.t = self.to;
    }
}

/// The fixed part of a scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Fixed {
    pub g: f64,
    pub points: Vec<Point>,
    pub lines: Vec<Line>,
}

/// What a model is made of, as JSON: the starting scene, the actions in
/// effect and how far it was computed. [`Model::from_record`] recomputes the
/// same chain bit for bit (the engine is deterministic), so this is what the
/// sandbox exports and imports.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelRecord {
    pub scene: Scene,
    #[serde(default)]
    pub actions: Vec<TimedAction>,
    /// The time the chain was computed to (absent: to its natural end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub until: Option<f64>,
}

#[derive(Clone, Debug)]
struct Entry {
    /// Number of events in the chain when this entry began.
    seq: u32,
    /// The body's motion from then on, or `None` once it left the scene.
    state: Option<(Material, Trajectory)>,
}

#[derive(Clone, Debug)]
struct Lane {
    id: BodyId,
    entries: Vec<Entry>,
}

impl Lane {
    fn at(&self, k: u32) -> Option<&Entry> {
        let n = self.entries.partition_point(|e| e.seq <= k);
        n.checked_sub(1).map(|i| &self.entries[i])
    }
}

/// The chain of timed scenes of one computation, with the rules that made it.
pub struct Model<H: EventHandler = ()> {
    start: Scene,
    config: WorldConfig,
    rules: H,
    actions: Vec<TimedAction>,
    events: Vec<Event>,
    lanes: Vec<Lane>,
    lane_of: HashMap<BodyId, usize>,
    fixed: Vec<(u32, Fixed)>,
    world: World,
    end: Option<End>,
}

impl Model<()> {
    /// A model of `scene` with the engine's default rules.
    pub fn new(scene: Scene) -> Result<Self, SceneError> {
        Model::with_rules(scene, (), WorldConfig::default())
    }
}

impl<H: EventHandler> Model<H> {
    /// A model of `scene` whose region exits are decided by `rules`.
    pub fn with_rules(scene: Scene, rules: H, config: WorldConfig) -> Result<Self, SceneError> {
        let world = World::new(&scene, config)?;
        Ok(Model::with_world(scene, rules, config, world))
    }

    fn with_world(scene: Scene, rules: H, config: WorldConfig, world: World) -> Self {
        let mut lanes = Vec::with_capacity(scene.bodies.len());
        let mut lane_of = HashMap::with_capacity(scene.bodies.len());
        for b in world.bodies() {
            lane_of.insert(b.id, lanes.len());
            lanes.push(Lane {
                id: b.id,
                entries: vec![Entry {
                    seq: 0,
                    state: Some((b.material, b.trajectory)),
                }],
            });
        }
        let fixed = vec![(
            0,
            Fixed {
                g: scene.g,
                points: scene.points.clone(),
                lines: scene.lines.clone(),
            },
        )];
        Model {
            start: scene,
            config,
            rules,
            actions: Vec::new(),
            events: Vec::new(),
            lanes,
            lane_of,
            fixed,
            world,
            end: None,
        }
    }

    /// A model that continues from a snapshot this engine produced (the
    /// bodies keep their trajectories as they are). Unlike a scene from
    /// outside, it is not checked for overlaps: contacts left touching by
    /// rounding are the engine's own state, not bad input. Numbers must still
    /// be finite and materials valid.
    pub fn from_snapshot(
        snapshot: Snapshot,
        rules: H,
        config: WorldConfig,
    ) -> Result<Self, SceneError> {
        let mut scene = snapshot.scene_at(snapshot.t);
        let check_overlaps = false;
        scene.validate_with(check_overlaps)?;
        let world = World::from_parts(
            snapshot.t,
            snapshot.g,
            snapshot.bodies.clone(),
            snapshot.points.clone(),
            snapshot.lines.clone(),
            config,
        );
        scene.bodies.sort_by_key(|b| b.id);
        let mut model = Model::with_world(scene, rules, config, world);
        model.fixed[0].1 = Fixed {
            g: snapshot.g,
            points: snapshot.points,
            lines: snapshot.lines,
        };
        Ok(model)
    }

    /// Rebuilds a model from its record, with `rules`, recomputing the chain.
    pub fn from_record(
        record: &ModelRecord,
        rules: H,
        config: WorldConfig,
    ) -> Result<Self, ActionError> {
        let mut model = Model::with_rules(record.scene.clone(), rules, config)?;
        for a in &record.actions {
            model.apply(a.t, a.action.clone())?;
        }
        model.compute(&Limits {
            until: record.until.unwrap_or(f64::INFINITY),
            ..Limits::default()
        });
        Ok(model)
    }

    /// The record that rebuilds this model.
    pub fn record(&self) -> ModelRecord {
        let until = self.computed_to();
        ModelRecord {
            scene: self.start.clone(),
            actions: self.actions.clone(),
            until: until.is_finite().then_some(until),
        }
    }

    /// The scene the model started from.
    pub fn start(&self) -> &Scene {
        &self.start
    }

    /// The rules.
    pub fn rules(&self) -> &H {
        &self.rules
    }

    /// Every event so far, in time order.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// The actions in effect, in time order.
    pub fn actions(&self) -> &[TimedAction] {
        &self.actions
    }

    /// How the last computation ended.
    pub fn end(&self) -> Option<End> {
        self.end
    }

    /// The time up to which the chain is known.
    pub fn computed_to(&self) -> f64 {
        match self.end {
            Some(End {
                reason: EndReason::Rest | EndReason::Free,
                ..
            }) => f64::INFINITY,
            _ => self.world.time(),
        }
    }

    /// The live computation (its statistics, its current trajectories).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Extends the chain until a limit (`until` is absolute; the counts are
    /// for this call) or until nothing more can happen.
    pub fn compute(&mut self, limits: &Limits) -> End {
        let mut rec = Recorder {
            events: &mut self.events,
            lanes: &mut self.lanes,
            lane_of: &self.lane_of,
            rules: &mut self.rules,
        };
        let end = self.world.run(limits, &mut rec);
        self.end = Some(end);
        end
    }

    /// Number of events at or before `t`.
    fn count_at(&self, t: f64) -> u32 {
        self.events.partition_point(|e| e.t <= t) as u32
    }

    /// Bodies, fixed objects and trajectories in effect at time `t`.
    pub fn snapshot_at(&self, t: f64) -> Snapshot {
        self.snapshot_after(self.count_at(t), t)
    }

    fn snapshot_after(&self, k: u32, t: f64) -> Snapshot {
        let mut bodies: Vec<BodyState> = self
            .lanes
            .iter()
            .filter_map(|lane| {
                let (material, trajectory) = lane.at(k)?.state?;
                Some(BodyState {
                    id: lane.id,
                    material,
                    trajectory,
                })
            })
            .collect();
        bodies.sort_by_key(|b| b.id);
        let fixed = self.fixed_at(k);
        Snapshot {
            t,
            g: fixed.g,
            bodies,
            points: fixed.points.clone(),
            lines: fixed.lines.clone(),
        }
    }

    fn fixed_at(&self, k: u32) -> &Fixed {
        let n = self.fixed.partition_point(|(seq, _)| *seq <= k);
        &self.fixed[n - 1].1
    }

    /// The scene at any time `t` (bodies in id order). Past the computed
    /// time it extrapolates the last known motion.
    pub fn scene_at(&self, t: f64) -> Scene {
        self.snapshot_at(t).scene_at(t)
    }

    /// One body at time `t`, if it is in the scene then.
    pub fn body_at(&self, id: BodyId, t: f64) -> Option<BodySpec> {
        let lane = &self.lanes[*self.lane_of.get(&id)?];
        let (material, trajectory) = lane.at(self.count_at(t))?.state?;
        Some(
            BodyState {
                id,
                material,
                trajectory,
            }
            .spec_at(t),
        )
    }

    /// What differs between the snapshots at `from` and at `to` (either order).
    pub fn diff(&self, from: f64, to: f64) -> SceneDiff {
        let (ka, kb) = (self.count_at(from), self.count_at(to));
        let (lo, hi) = (ka.min(kb), ka.max(kb));
        let mut bodies = Vec::new();
        for lane in &self.lanes {
            let first_after = lane.entries.partition_point(|e| e.seq <= lo);
            let touched = lane.entries.get(first_after).is_some_and(|e| e.seq <= hi);
            if touched {
                let state = lane
                    .at(kb)
                    .and_then(|e| e.state)
                    .map(|(material, trajectory)| BodyState {
                        id: lane.id,
                        material,
                        trajectory,
                    });
                bodies.push((lane.id, state));
            }
        }
        let fixed = (self.fixed_at(ka) != self.fixed_at(kb)).then(|| self.fixed_at(kb).clone());
        SceneDiff {
            from,
            to,
            bodies,
            fixed,
        }
    }

    /// Drops everything after time `t` and continues from there (rewind).
    pub fn rewind(&mut self, t: f64) -> Result<(), ActionError> {
        if !t.is_finite() || t < self.start.t {
            return Err(ActionError::BadTime(t));
        }
        self.compute_through(t);
        let k = self.count_at(t);
        let snap = self.snapshot_after(k, t);
        self.truncate(k);
        self.world = world_from(&snap, t, self.config);
        Ok(())
    }

    /// Applies `action` at time `t`. A past time drops the later history.
    /// On error nothing changes (not even how far the chain is computed).
    pub fn apply(&mut self, t: f64, action: Action) -> Result<(), ActionError> {
        if !t.is_finite() || t < self.start.t {
            return Err(ActionError::BadTime(t));
        }
        // Reaching a future time computes the chain up to it; keep what is
        // needed to undo that if the action is refused.
        let checkpoint = (t > self.world.time() && self.computed_to() < f64::INFINITY)
            .then(|| (self.world.clone(), self.events.len() as u32, self.end));
        self.compute_through(t);
        let k = self.count_at(t);
        let mut snap = self.snapshot_after(k, t);
        let checked = apply_to(&mut snap, t, &action)
            .and_then(|changed| Ok((changed, snap.scene_at(t).validate()?)));
        let changed = match checked {
            Ok((changed, ())) => changed,
            Err(e) => {
                if let Some((world, k0, end)) = checkpoint {
                    self.truncate(k0);
                    self.world = world;
                    self.end = end;
                }
                return Err(e);
            }
        };
        // Accepted: commit.
        self.truncate(k);
        let index = self.actions.len() as u32;
        self.actions.push(TimedAction { t, action });
        self.events.push(Event {
            t,
            kind: EventKind::Action { index },
        });
        let seq = self.events.len() as u32;
        for id in changed {
            let state = snap
                .bodies
                .iter()
                .find(|b| b.id == id)
                .map(|b| (b.material, b.trajectory));
            let lane = match self.lane_of.get(&id) {
                Some(&l) => l,
                None => {
                    self.lane_of.insert(id, self.lanes.len());
                    self.lanes.push(Lane {
                        id,
                        entries: Vec::new(),
                    });
                    self.lanes.len() - 1
                }
            };
            self.lanes[lane].entries.push(Entry { seq, state });
        }
        let fixed = Fixed {
            g: snap.g,
            points: snap.points.clone(),
            lines: snap.lines.clone(),
        };
        if &fixed != self.fixed_at(seq) {
            self.fixed.push((seq, fixed));
        }
        self.world = world_from(&snap, t, self.config);
        self.end = None;
        Ok(())
    }

    /// Makes sure every event up to and including time `t` is in the chain.
    fn compute_through(&mut self, t: f64) {
        if self.world.time() <= t && self.computed_to() < f64::INFINITY {
            self.compute(&Limits {
                until: t,
                ..Limits::default()
            });
        }
    }

    fn truncate(&mut self, k: u32) {
        self.events.truncate(k as usize);
        for lane in &mut self.lanes {
            let keep = lane.entries.partition_point(|e| e.seq <= k);
            lane.entries.truncate(keep);
        }
        let keep = self.fixed.partition_point(|(seq, _)| *seq <= k);
        self.fixed.truncate(keep);
        let kept_actions = self
            .events
            .iter()
            .filter(|e| matches!(e.kind, EventKind::Action { .. }))
            .count();
        self.actions.truncate(kept_actions);
        self.end = None;
    }
}

/// Applies an action to a snapshot at time `t`; returns the bodies it changed.
fn apply_to(snap: &mut Snapshot, t: f64, action: &Action) -> Result<Vec<BodyId>, ActionError> {
    let find = |snap: &Snapshot, id: BodyId| {
        snap.bodies
            .iter()
            .position(|b| b.id == id)
            .ok_or(ActionError::NoSuchBody(id))
    };
    let state = |spec: &BodySpec, g: f64| BodyState::from_spec(spec, t, g);
    let changed = match action {
        Action::AddBody { body } => {
            if snap.bodies.iter().any(|b| b.id == body.id) {
                return Err(ActionError::DuplicateBody(body.id));
            }
            snap.bodies.push(state(body, snap.g));
            vec![body.id]
        }
        Action::RemoveBody { id } => {
            let k = find(snap, *id)?;
            snap.bodies.remove(k);
            vec![*id]
        }
        Action::SetVelocity { id, vel } => {
            let k = find(snap, *id)?;
            let mut spec = snap.bodies[k].spec_at(t);
            spec.vel = *vel;
            snap.bodies[k] = state(&spec, snap.g);
            vec![*id]
        }
        Action::UpdateBody { body } => {
            let k = find(snap, body.id)?;
            snap.bodies[k] = state(body, snap.g);
            vec![body.id]
        }
        Action::AddPoint { point } => {
            snap.points.push(*point);
            vec![]
        }
        Action::RemovePoint { index } => {
            if *index >= snap.points.len() {
                return Err(ActionError::NoSuchObject {
                    kind: "point",
                    index: *index,
                });
            }
            snap.points.remove(*index);
            vec![]
        }
        Action::AddLine { line } => {
            snap.lines.push(*line);
            vec![]
        }
        Action::RemoveLine { index } => {
            if *index >= snap.lines.len() {
                return Err(ActionError::NoSuchObject {
                    kind: "line",
                    index: *index,
                });
            }
            snap.lines.remove(*index);
            vec![]
        }
        Action::SetGravity { g } => {
            snap.g = *g;
            let mut ids = Vec::new();
            for b in &mut snap.bodies {
                if b.trajectory.is_moving_at(t) {
                    b.trajectory = b.trajectory.with_alpha(t, b.material.mu * g);
                    ids.push(b.id);
                } else {
                    b.trajectory =
                        Trajectory::at_rest(t, b.trajectory.position(t), b.material.mu * g);
                }
            }
            ids
        }
    };
    snap.bodies.sort_by_key(|b| b.id);
    Ok(changed)
}

fn world_from(snap: &Snapshot, t: f64, config: WorldConfig) -> World {
    World::from_parts(
        t,
        snap.g,
        snap.bodies.clone(),
        snap.points.clone(),
        snap.lines.clone(),
        config,
    )
}

/// Records every event of a run into the chain, passing rules through.
struct Recorder<'a, H> {
    events: &'a mut Vec<Event>,
    lanes: &'a mut Vec<Lane>,
    lane_of: &'a HashMap<BodyId, usize>,
    rules: &'a mut H,
}

impl<H: EventHandler> EventHandler for Recorder<'_, H> {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.events.push(*event);
        let seq = self.events.len() as u32;
        for id in event.kind.bodies() {
            if let Some(&l) = self.lane_of.get(&id) {
                let state = world.body(id).map(|b| (b.material, b.trajectory));
                self.lanes[l].entries.push(Entry { seq, state });
            }
        }
        self.rules.on_event(world, event);
    }

    fn on_region_exit(&mut self, t: f64, body: BodyId, line: crate::id::LineId) -> ExitResponse {
        self.rules.on_region_exit(t, body, line)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacle::LineKind;

    fn table() -> Scene {
        let mut bodies = Vec::new();
        for k in 0..6u64 {
            let x = 0.1 * k as f64;
            bodies.push(BodySpec::new(
                k + 1,
                DVec2::new(x, 0.02 * (k % 2) as f64),
                0.03,
                0.01,
                0.2,
            ));
        }
        bodies[0].vel = DVec2::new(0.3, 2.5);
        bodies[3].vel = DVec2::new(-1.5, 1.8);
        bodies[5].vel = DVec2::new(-2.0, 0.05);
        let corners = [
            DVec2::new(-0.3, -0.3),
            DVec2::new(0.8, -0.3),
            DVec2::new(0.8, 0.8),
            DVec2::new(-0.3, 0.8),
        ];
        let lines = (0..4)
            .map(|k| Line::new(corners[k], corners[(k + 1) % 4], LineKind::Segment))
            .collect();
        Scene {
            bodies,
            lines,
            ..Scene::default()
        }
    }

    fn bits(scene: &Scene) -> Vec<u64> {
        scene
            .bodies
            .iter()
            .flat_map(|b| [b.pos.x, b.pos.y, b.vel.x, b.vel.y])
            .map(f64::to_bits)
            .collect()
    }

    #[test]
    fn state_between_events_is_the_closed_form_advance_of_the_last_scene() {
        let mut m = Model::new(table()).unwrap();
        m.compute(&Limits::default());
        let e = m.events()[2];
        let t = e.t + 1e-3;
        let snap = m.snapshot_at(e.t);
        assert_eq!(m.scene_at(t), snap.scene_at(t));
    }

    #[test]
    fn a_record_rebuilds_the_same_chain_bit_for_bit() {
        let mut m = Model::new(table()).unwrap();
        m.compute(&Limits {
            until: 0.4,
            ..Limits::default()
        });
        m.apply(
            0.2,
            Action::SetVelocity {
                id: BodyId(5),
                vel: DVec2::new(0.5, 0.5),
            },
        )
        .unwrap();
        m.compute(&Limits::default());
        let json = serde_json::to_string(&m.record()).unwrap();
        let record: ModelRecord = serde_json::from_str(&json).unwrap();
        let again = Model::from_record(&record, (), WorldConfig::default()).unwrap();
        assert_eq!(again.events(), m.events());
        for t in [0.0, 0.1, 0.2, 0.35, 1.0, 5.0] {
            assert_eq!(bits(&again.scene_at(t)), bits(&m.scene_at(t)), "t = {t}");
        }
    }

    #[test]
    fn an_action_in_the_past_drops_later_history_and_recomputes_from_there() {
        let mut m = Model::new(table()).unwrap();
        m.compute(&Limits::default());
        let before = m.events().len();
        let t = m.events()[before / 2].t;
        let kept = m.events().iter().filter(|e| e.t <= t).count();
        m.apply(t, Action::RemoveBody { id: BodyId(6) }).unwrap();
        assert_eq!(m.events().len(), kept + 1);
        assert!(matches!(
            m.events()[kept].kind,
            EventKind::Action { index: 0 }
        ));
        m.compute(&Limits::default());
        assert!(m.events().iter().skip(kept + 1).all(|e| e.t >= t));
        assert!(m.body_at(BodyId(6), t + 1e-9).is_none());
        assert!(m.body_at(BodyId(6), t * 0.5).is_some());
        // Same as starting fresh from the state at t with the body removed.
        let mut fresh_scene = m.scene_at(t);
        fresh_scene.bodies.retain(|b| b.id != BodyId(6));
        let mut fresh = Model::new(fresh_scene).unwrap();
        fresh.compute(&Limits::default());
        let tail: Vec<EventKind> = m.events()[kept + 1..].iter().map(|e| e.kind).collect();
        let fresh_kinds: Vec<EventKind> = fresh.events().iter().map(|e| e.kind).collect();
        assert_eq!(tail, fresh_kinds);
    }

    #[test]
    fn a_refused_action_changes_nothing() {
        let mut m = Model::new(table()).unwrap();
        m.compute(&Limits::default());
        let events = m.events().to_vec();
        let scene = m.scene_at(0.3);
        let overlapping = BodySpec::new(99, DVec2::new(0.0, 0.0), 0.05, 1.0, 0.1);
        assert!(matches!(
            m.apply(0.0, Action::AddBody { body: overlapping }),
            Err(ActionError::Invalid(_))
        ));
        assert_eq!(
            m.apply(0.1, Action::RemoveBody { id: BodyId(42) }),
            Err(ActionError::NoSuchBody(BodyId(42)))
        );
        assert!(matches!(
            m.apply(f64::NAN, Action::SetGravity { g: 1.0 }),
            Err(ActionError::BadTime(_))
        ));
        assert_eq!(m.events(), &events[..]);
        assert_eq!(m.scene_at(0.3), scene);
    }

    #[test]
    fn a_diff_turns_one_snapshot_into_the_other_both_ways() {
        let mut m = Model::new(table()).unwrap();
        m.compute(&Limits::default());
        let (a, b) = (0.05, 0.6);
        let mut snap = m.snapshot_at(a);
        let diff = m.diff(a, b);
        assert!(diff.bodies.len() <= m.start().bodies.len());
        diff.apply(&mut snap);
        assert_eq!(snap, m.snapshot_at(b));
        let mut back = m.snapshot_at(b);
        m.diff(b, a).apply(&mut back);
        assert_eq!(back, m.snapshot_at(a));
    }
}
