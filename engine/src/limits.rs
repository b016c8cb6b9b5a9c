//! When a run stops, and the guards that make sure it does.
//!
//! A caller bounds a run with [`Limits`]; the run reports where and why it
//! stopped as an [`End`] with its [`EndReason`]. Some configurations have no
//! finite answer (a chain pressed between two walls, an inelastic collapse
//! whose hits pile up at one instant, discs rattling in a gap of rounding);
//! the livelock guards here notice them, each from the revision that
//! introduced it: the tuning constants below, the crawl of events that move
//! nothing (`Crawl`) and the repeated gentle hits of one pair at one
//! instant (`Repeats`). The guards read the world through `Watched`, so
//! they name no world of their own: the event loop (`world`)
//! implements it and drives them.

use crate::event::{Event, EventKind};
use crate::id::{BodyId, LineId, PointId};
use serde::{Deserialize, Serialize};

/// When to stop a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Limits {
    /// Compute no further than this time.
    pub until: f64,
    /// Stop after this many collisions in this run.
    pub max_collisions: u64,
    /// Stop after this many events in this run (the hard cap).
    pub max_events: u64,
}

/// The hard cap on events when no other is given.
pub(crate) const DEFAULT_MAX_EVENTS: u64 = 10_000_000;

impl Default for Limits {
    fn default() -> Self {
        Limits {
            until: f64::INFINITY,
            max_collisions: u64::MAX,
            max_events: DEFAULT_MAX_EVENTS,
        }
    }
}

/// Events at one instant (see [`crate::instant::same_instant`]) beyond
/// which a run is [`EndReason::Stuck`]: this many, plus
/// [`STUCK_EVENTS_PER_BODY`] per body.
/// A Newton's cradle of `n` discs resolves in `n - 1` events at one
/// instant; only a configuration with no finite answer comes near this.
pub(crate) const STUCK_EVENTS: u64 = 20_000;

/// See [`STUCK_EVENTS`].
pub(crate) const STUCK_EVENTS_PER_BODY: u64 = 100;

/// Every this many events at one instant, the bodies of the latest
/// [`COLLAPSE_WINDOW`] of them are checked for an inelastic collapse
/// (see `World::collapse`).
pub(crate) const COLLAPSE_EVENTS: u64 = 2_000;

/// See [`COLLAPSE_EVENTS`].
pub(crate) const COLLAPSE_WINDOW: u64 = 64;

/// From the fifth revision, hits of one inelastic pair (two discs, or a
/// disc and an obstacle) at one instant, every one of them gentle (see
/// [`GENTLE`]), after which the instant is taken as an inelastic collapse
/// of the discs pressed together (see `World::collapse_repeated`), and
/// again after as many more. A cluster sliding with unequal braking presses
/// its discs into each other again and again, microseconds apart; each
/// time its hits ring through it hundreds of times at one instant, each
/// slower than the last, until the approach threshold cuts them off.
pub(crate) const REPEAT_HITS: u32 = 16;

/// From the tenth revision, [`REPEAT_HITS`] is this: a light disc jammed
/// between walls and a heavy disc that presses it as it slides by rings
/// at one instant between the discs alone, fewer than 16 hits of a pair
/// (the walls they touch are a rounding of a position away, hit a
/// picosecond later), the ring weaker by a few per cent each time,
/// instant after instant. From the tenth revision, too, a plastic pair's
/// (restitution 0) hits must be gentle only since a plastic pair was last
/// counted, not since the instant began: where an instant's first hits
/// were not gentle, the gentle ring after them (a thousand hits at one
/// instant in mixed-box 758) was never counted. (Pairs with some
/// restitution keep the fifth revision's test: an impact ringing through
/// a cradle is the model's answer.)
pub(crate) const EARLY_REPEAT_HITS: u32 = 8;

/// From the twelfth revision, hits of one plastic pair at one instant from
/// which it is taken as a collapse where its hits slow from one count to
/// the next, gentle or not (see `Repeats::decaying`): a light elastic disc
/// rung between a wall and a heavy plastic one slows by a per cent a
/// cycle, hundreds of hits an instant. Counted from fewer (32, or 128),
/// the rule also took shorter rings whose hits are the model's answer (a
/// light frictionless disc rung among four others and the floor at one
/// impact), and their plastic limit sent runs that reached their horizon
/// under the eleventh revision into the event cap or `stuck`.
pub(crate) const DECAYING_RING_HITS: u32 = 160;

/// From the fifth revision, the fraction of the speed of the fastest disc
/// they involve under which every approach at one instant must stay for
/// [`REPEAT_HITS`] to take it as a collapse: discs pressed together while
/// they slide, not an impact ringing through a cradle or a cluster (whose
/// sequence of hits is the model's answer, however long).
pub(crate) const GENTLE: f64 = 1e-2;

/// Most discs one collapse is taken to its limit for (see `World::collapse`).
pub(crate) const MAX_COLLAPSE: usize = 256;

/// From the third revision, a run whose events, [`CRAWL_EVENTS`] after
/// [`CRAWL_EVENTS`], move no disc by more than this fraction of the
/// smallest radius — as many events as would end it [`EndReason::Stuck`]
/// at one instant — is stuck too: discs rattling in a gap of rounding (a
/// chain pinned between two walls) advance the time by 1e-16 s an event.
pub(crate) const CRAWL: f64 = 1e-9;

/// See [`CRAWL`].
pub(crate) const CRAWL_EVENTS: u64 = 1_000;

/// From the third revision, a disc whose slide after a hit is shorter than
/// this fraction of its largest coordinate (the rounding of its position)
/// is at rest (see `World::settled`).
pub(crate) const SETTLE: f64 = f64::EPSILON;

/// Sweeps a pressing kick over a cluster (see `World::press_cluster`) may
/// take: it converges within tens where it has an answer at all.
pub(crate) const PRESS_SWEEPS: usize = 200;

/// From the fourth revision, rounds of a pressing kick's projection that
/// may each bias the pairs the one before left pressed (see
/// `World::press_closure`).
pub(crate) const PRESS_ROUNDS: usize = 4;

/// From the nineteenth revision, discs of a cluster beyond which a pressing
/// kick that projected Gauss–Seidel stalls on is not sought by the
/// active-set method (see `Revision::finds_stalled_cluster_kicks_by_active_set`):
/// as many as a mixed box holds. Unbounded, it made nine of plastic-lines
/// seeds 600,000-699,999 slow (revision 18: two), piles of 24 to 31 discs
/// (59 to 77 contacts) searched 85 to 107 times a run (630620: 5.5 s,
/// 65 ms a search); a larger cluster's kick is left to the hit, as
/// before. From the twentieth revision a larger cluster's kick is found by
/// the factored active-set method (see
/// `Revision::finds_large_cluster_kicks_by_factored_active_set`).
pub(crate) const EXACT_KICK_CLUSTER: usize = 14;

/// From the twentieth revision, factored searches for a large cluster's
/// pressing kick made at one instant, beyond which that instant's kicks
/// are left to the hit, as before (see
/// `Revision::finds_large_cluster_kicks_by_factored_active_set`). A ring
/// that the search ends ends within a few of its events (plastic-lines
/// 113176: 12 events at one instant; 220728, 31); one it cannot end went
/// on paying a search at every event (plastic-lines 620478: 3,001 events
/// at one instant, 2.5 s of CPU, against 0.3 s without the search).
pub(crate) const KICK_SEARCHES_PER_INSTANT: u32 = 32;

/// Past this time a run checks, before each event, that every moving body
/// is still within [`MAX_COORDINATE`] (no scene reaches it otherwise:
/// speeds stay below 1e150 and start positions too).
pub(crate) const FAR_FUTURE: f64 = 1e150;

/// Largest coordinate a moving body may reach: its square (contact
/// equations square distances) stays finite.
pub(crate) const MAX_COORDINATE: f64 = 1e154;

/// Relative error of a contact distance beyond which a hit puts the bodies
/// back at exactly touching distance (see [`snap`]).
pub(crate) const SNAP: f64 = 1e-11;

/// How far to move apart two bodies (or a body from an obstacle) that hit
/// at centre distance `dist` where they touch at `s`: nothing where the
/// distance is right to within [`SNAP`] (every hit near the origin), else
/// the error. Far from the origin a position carries the rounding of its
/// coordinates (3e-10 m at 3e6 m), which a hit would otherwise keep as an
/// overlap or a gap; moving the bodies by it is below that rounding.
pub(crate) fn snap(s: f64, dist: f64) -> f64 {
    let err = s - dist;
    if err.abs() > SNAP * s && dist > 0.0 {
        err
    } else {
        0.0
    }
}

/// Why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum EndReason {
    /// Nothing moves and nothing is pending.
    Rest,
    /// Bodies still move without friction, but no event can ever happen.
    Free,
    /// The time horizon was reached.
    Until,
    /// The collision limit was reached.
    MaxCollisions,
    /// The event cap was reached.
    MaxEvents,
    /// The model has no finite answer from here: events keep piling up at
    /// one instant without end (a chain pressed between two walls, an
    /// inelastic collapse). The state is frozen at the last event.
    Stuck,
    /// The next event lies so far in the future that positions there would
    /// leave the range of doubles (an inelastic disc bouncing between two
    /// walls pushes its event times towards 1e308). The state is frozen at
    /// the last event.
    OutOfRange,
}

/// Where and why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct End {
    pub t: f64,
    pub reason: EndReason,
}

/// Events that moved nothing (see [`CRAWL`]), counted block by block.
pub(crate) struct Crawl {
    /// From the eighth revision: the block's motion is that of the discs
    /// its latest events involve, not that of the fastest disc anywhere.
    local: bool,
    /// When the current block began.
    since: f64,
    /// Events in the current block.
    events: u64,
    /// Events in the blocks before it, in a row, that moved nothing.
    still: u64,
    /// How long the block just ended took.
    span: f64,
    /// Slots of the latest [`COLLAPSE_WINDOW`] events of the block
    /// (`usize::MAX` for a hit on an obstacle), as `World::collapse` takes.
    recent: Vec<usize>,
}

impl Crawl {
    /// No events yet, the first block beginning at `t`.
    /// With `local` (the eighth revision on), a block is measured on the
    /// discs of its latest events (see [`Watched::fastest_and_smallest_of`]).
    pub(crate) fn new(t: f64, local: bool) -> Self {
        Crawl {
            local,
            since: t,
            events: 0,
            still: 0,
            span: 0.0,
            recent: Vec::new(),
        }
    }

    /// Counts `event`, at `t`. At the end of a block of [`CRAWL_EVENTS`]
    /// in which no disc moved by more than [`CRAWL`] of the smallest radius,
    /// returns the slots of its latest events: a collapse too slow in time
    /// to share one instant (each hit a few units in the last place of the
    /// time after the last), to be taken to its limit.
    #[inline]
    pub(crate) fn note(
        &mut self,
        world: &impl Watched,
        event: &Event,
        t: f64,
    ) -> Option<Vec<usize>> {
        self.events += 1;
        if self.events + COLLAPSE_WINDOW <= CRAWL_EVENTS {
            return None;
        }
        self.block_end(world, event, t)
    }

    /// The latest events of a block, and its end (see [`Crawl::note`]).
    #[cold]
    fn block_end(&mut self, world: &impl Watched, event: &Event, t: f64) -> Option<Vec<usize>> {
        world.remember(&mut self.recent, event);
        if self.events < CRAWL_EVENTS {
            return None;
        }
        let (speed, radius) = if self.local {
            world.fastest_and_smallest_of(&self.recent, t)
        } else {
            world.fastest_and_smallest(t)
        };
        self.span = t - self.since;
        let still = self.span * speed <= CRAWL * radius;
        self.since = t;
        self.events = 0;
        let recent = std::mem::take(&mut self.recent);
        if still {
            self.still += CRAWL_EVENTS;
            Some(recent)
        } else {
            self.still = 0;
            None
        }
    }

    /// Moves the block's start `by` seconds earlier: the world's working
    /// time moved its origin (see `clock`).
    pub(crate) fn rebase(&mut self, by: f64) {
        self.since -= by;
    }

    /// Events, in the blocks just ended, in a row, that moved nothing.
    pub(crate) fn still(&self) -> u64 {
        self.still
    }

    /// How long the block just ended took.
    pub(crate) fn span(&self) -> f64 {
        self.span
    }
}

/// What two bodies hit: two discs (ids in order), or a disc and a line or
/// a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pair {
    Discs(BodyId, BodyId),
    Line(BodyId, LineId),
    Point(BodyId, PointId),
}

/// One pair's hits at the current instant (see [`Repeats`]).
struct PairHits {
    pair: Pair,
    /// The pair's slots (the second `None` for an obstacle).
    slots: (usize, Option<usize>),
    hits: u32,
    /// From the twelfth revision, how fast the pair approached at its
    /// latest count (see [`Repeats::decaying`]).
    counted: Option<f64>,
    /// How fast the pair approached at its two latest hits before this
    /// one, the older first (see [`Repeats::geometric`]).
    approaches: [f64; 2],
}

/// From the fifth revision, each inelastic pair's hits at the current
/// instant (see [`REPEAT_HITS`]).
pub(crate) struct Repeats {
    /// Hits of one pair after which the instant is a collapse
    /// ([`REPEAT_HITS`], or from the tenth revision [`EARLY_REPEAT_HITS`]).
    every: u32,
    /// The instant's first event and the speed of its approach, counted
    /// only once a second event shares the instant (most events have an
    /// instant to themselves).
    first: Option<(Event, f64)>,
    hits: Vec<PairHits>,
    /// The fastest approach of any hit at this instant.
    fastest: f64,
    /// From the tenth revision, the fastest approach since a plastic pair
    /// was last counted (see [`EARLY_REPEAT_HITS`]).
    since_count: f64,
    /// The fastest speed of a disc after a hit at this instant.
    moving: f64,
    /// From the twelfth revision, a plastic pair's count is also taken
    /// where the pair approached slower than at its previous count (see
    /// [`Repeats::decaying`]).
    decaying: bool,
    /// From the thirteenth revision, elastic pairs' hits are kept too (see
    /// [`Repeats::with_elastic`]).
    elastic: bool,
    /// From the sixteenth revision, a plastic pair hit again at an instant
    /// where one of its discs was hit by a third is a collapse (see
    /// [`Repeats::squeezed`]).
    squeezed: bool,
    /// From the sixteenth revision, a squeezed disc's ring whose approach
    /// shrinks by one ratio a turn, gentle or not, is a collapse (see
    /// [`Repeats::geometric`]).
    geometric: bool,
    /// From the seventeenth revision, a ring that fades below the rounding
    /// of its speeds within the count's hits is left to them (see
    /// [`Repeats::lasting`]).
    lasting: bool,
    /// Whether the latest count was taken for a squeezed disc.
    by_squeeze: bool,
    /// Whether that count was taken for its ring's ratio (see
    /// [`Repeats::geometric`]).
    by_ratio: bool,
}

impl Repeats {
    /// No instant yet; a collapse after `every` hits of one pair.
    pub(crate) fn new(every: u32) -> Self {
        Repeats {
            every,
            first: None,
            hits: Vec::new(),
            fastest: 0.0,
            since_count: 0.0,
            moving: 0.0,
            decaying: false,
            elastic: false,
            squeezed: false,
            geometric: false,
            lasting: false,
            by_squeeze: false,
            by_ratio: false,
        }
    }

    /// From the thirteenth revision: the hits of elastic pairs at the
    /// instant are kept as well, never counted towards a collapse nor
    /// towards its gentleness, so that [`Repeats::repeated`] names them
    /// and the collapse takes them in. A light elastic disc between a
    /// heavy plastic one and an elastic disc resting on a wall rang
    /// between them at one instant, losing a few per cent at each plastic
    /// hit; the collapse after eight plastic hits took the plastic pair
    /// alone, which drove the light disc into its elastic neighbour
    /// again, 20,000 hits at one instant. Once the ring has no end, its
    /// limit has no contact of it approaching, elastic or not.
    pub(crate) fn with_elastic(mut self, on: bool) -> Self {
        self.elastic = on;
        self
    }

    /// From the twelfth revision: a plastic pair (restitution 0) hit at
    /// least [`DECAYING_RING_HITS`] times whose count comes round again, its
    /// hits slower than at its previous count, is a collapse however hard
    /// its hits. A plastic hit leaves the pair
    /// no approach; to be hit again at the same instant, something else
    /// must have driven it back, every time with less: a light elastic disc
    /// between a wall and a heavy plastic one pushing it bounces off the
    /// wall and is caught again, its speed a per cent lower each time (the
    /// ratio of the masses), a thousand hits an instant until the crawl
    /// rule took the limit, instant after instant until the run ended
    /// `stuck`. Its hits are not gentle (each approaches at twice the
    /// speed of the discs), but they are no impact ringing through to an
    /// end either: the sequence has none, only a limit.
    pub(crate) fn decaying(mut self, on: bool) -> Self {
        self.decaying = on;
        self
    }

    /// From the sixteenth revision: a plastic pair of discs hit a second
    /// time at one instant, one of its discs hit by a third disc at that
    /// instant too, is a collapse at once, where every hit of the
    /// instant was [`GENTLE`]. The disc they share is squeezed between the
    /// two: each hit of one pair drives it into the other, whose hit drives
    /// it back, a ring through it whose relative speeds shrink by a
    /// constant ratio a turn (a half to two thirds in the rows below) and which
    /// has no end, only its plastic limit. A light
    /// frictionless disc on the floor between a braking one at rest and
    /// one pressed into it from above rang between the two 16 hits an
    /// instant before [`EARLY_REPEAT_HITS`] took the limit, every few
    /// microseconds as the disc above was pressed again, until the event
    /// cap (mixed-box 567963); so did rows of three on the floor, the
    /// middle one's brakings pooled with one neighbour and then the other
    /// (mixed-box 196517, 435983) and a disc between two in a corner
    /// (mixed-box 266709). A pair hit twice with nothing between (one
    /// driven back into the other by a wall, or by a disc it alone
    /// touches) is left to the count: with every pair taken at its second
    /// gentle hit, 12 of the first 100,000 mixed boxes failed against the
    /// fifteenth revision's 2. The collapse is the plastic limit alone,
    /// without the kick of the pairs it leaves pressed (as
    /// `World::cluster_ring` takes its limit): kicked, a light disc on the
    /// floor was parted from the braking one pressing it from above every
    /// 3.7e-8 s until the event cap (mixed-box 84278), and a light disc
    /// rang against the disc above it at one instant until the event cap
    /// (mixed-box 37640). With the rule the first 100,000 mixed boxes
    /// fail 3: the fifteenth revision's 2 and 81351, a row on the floor
    /// at rest after the rule's limit sent off again at each hit of a
    /// disc sliding down the wall beside it.
    pub(crate) fn squeezed(mut self, on: bool) -> Self {
        self.squeezed = on;
        self
    }

    /// From the sixteenth revision: a plastic pair of discs one of which a
    /// third disc hit at the instant too, whose approach at its latest
    /// three hits shrank by one ratio a turn (within [`ONE_RATIO`]), is a
    /// collapse, gentle or not: see [`Repeats::squeezed`].
    pub(crate) fn geometric(mut self, on: bool) -> Self {
        self.geometric = on;
        self
    }

    /// From the seventeenth revision: a ring that [`Repeats::geometric`]
    /// would take only where it lasts, its ratio a turn above
    /// [`FADING_RATIO`]; one that shrinks faster falls below the rounding
    /// of its speeds within [`EARLY_REPEAT_HITS`] more hits and ends by
    /// itself, hit by hit. A striker's ring on the top of a packed plastic
    /// pile, 0.0021 of its approach left a turn, was taken to the plastic
    /// limit of the whole pile, which set its discs sliding at a few
    /// millimetres a second, each pressed into the next, a pressed hit
    /// every 4e-11 s for 4e-7 s; hit by hit it ends in nine events.
    pub(crate) fn lasting(mut self, on: bool) -> Self {
        self.lasting = on;
        self
    }

    /// A new instant, begun by `event`, whose bodies approached at
    /// `approach`. It is counted when a second event joins the instant, with
    /// the speeds of its discs as they are then.
    pub(crate) fn start(&mut self, event: Event, approach: f64) {
        self.first = Some((event, approach));
        self.hits.clear();
        self.fastest = 0.0;
        self.since_count = 0.0;
        self.moving = 0.0;
    }

    /// Counts `event`'s hit, one more at the instant (the world's state
    /// right after it), whose bodies approached at `approach`; `true` when its pair, an inelastic one, has now
    /// been hit a multiple of `every` (see [`Repeats::new`]) times at this instant, and
    /// every hit so far was [`GENTLE`]. Elastic hits lose no energy: their
    /// sequences are finite, however long (a light disc between heavy
    /// ones), and are not counted.
    pub(crate) fn note(&mut self, world: &impl Watched, event: &Event, approach: f64) -> bool {
        if let Some((first, first_approach)) = self.first.take() {
            self.count(world, &first, first_approach);
        }
        self.count(world, event, approach)
    }

    /// Counts one hit (see [`Repeats::note`]).
    fn count(&mut self, world: &impl Watched, event: &Event, approach: f64) -> bool {
        let (pair, a, b) = match event.kind {
            EventKind::BodyBody { a, b } => (Pair::Discs(a.min(b), a.max(b)), a, Some(b)),
            EventKind::BodyLine { body, line, .. } => (Pair::Line(body, line), body, None),
            EventKind::BodyPoint { body, point } => (Pair::Point(body, point), body, None),
            _ => return false,
        };
        let Some(sa) = world.slot_of(a) else {
            return false;
        };
        let sb = match b.map(|b| world.slot_of(b)) {
            Some(None) => return false,
            Some(sb) => sb,
            None => None,
        };
        let restitution = world.restitution(sa, sb);
        if restitution >= 1.0 {
            if self.elastic {
                self.keep(pair, (sa, sb));
            }
            return false;
        }
        let plastic = restitution == 0.0;
        self.fastest = self.fastest.max(approach.abs());
        self.since_count = self.since_count.max(approach.abs());
        let speed = |c: usize| world.speed_at_last_event(c);
        self.moving = self.moving.max(speed(sa)).max(sb.map_or(0.0, speed));
        let k = match self.hits.iter().position(|h| h.pair == pair) {
            Some(k) => {
                self.hits[k].hits += 1;
                k
            }
            None => {
                self.hits.push(PairHits {
                    pair,
                    slots: (sa, sb),
                    hits: 1,
                    counted: None,
                    approaches: [f64::NAN; 2],
                });
                self.hits.len() - 1
            }
        };
        let before = self.hits[k].approaches;
        self.hits[k].approaches = [before[1], approach.abs()];
        // From the sixteenth revision, a ring through a squeezed disc.
        self.by_squeeze = false;
        self.by_ratio = false;
        if self.squeezed && plastic && self.squeezes(k) {
            self.by_squeeze = self.fastest <= GENTLE * self.moving;
            return self.by_squeeze;
        }
        // From the sixteenth revision, the same ring shrinking by one ratio
        // a turn, gentle or not.
        // From the seventeenth revision, only one that lasts.
        if self.geometric
            && plastic
            && self.shares_disc(k)
            && shrinks_by_one_ratio(before, approach.abs())
            && !(self.lasting && approach.abs() <= FADING_RATIO * before[1])
        {
            self.by_squeeze = true;
            self.by_ratio = true;
            return true;
        }
        if !self.hits[k].hits.is_multiple_of(self.every) {
            return false;
        }
        // From the twelfth revision, a plastic pair hit slower than at its
        // previous count (see `Repeats::decaying`).
        let decayed = self.decaying
            && plastic
            && self.hits[k].hits >= DECAYING_RING_HITS
            && self.hits[k]
                .counted
                .is_some_and(|before| approach.abs() < before);
        if self.decaying && plastic {
            self.hits[k].counted = Some(approach.abs());
        }
        // From the tenth revision, a plastic pair's count is also taken where
        // the hits since the last such count were gentle (see
        // `EARLY_REPEAT_HITS`).
        let window = self.every == EARLY_REPEAT_HITS && plastic;
        let gentle = self.fastest <= GENTLE * self.moving
            || (window && self.since_count <= GENTLE * self.moving);
        if window {
            self.since_count = 0.0;
        }
        gentle || decayed
    }

    /// Whether the pair of `self.hits[k]` is two discs hit for the second
    /// time at this instant, one of which another pair of discs hit at
    /// this instant shares (see [`Repeats::squeezed`]).
    fn squeezes(&self, k: usize) -> bool {
        let h = &self.hits[k];
        h.hits == 2 && self.shares_disc(k)
    }

    /// Whether the pair of `self.hits[k]` is two discs one of which another
    /// pair of discs hit at this instant shares.
    fn shares_disc(&self, k: usize) -> bool {
        let (a, Some(b)) = self.hits[k].slots else {
            return false;
        };
        self.hits.iter().enumerate().any(|(o, g)| {
            let (c, Some(d)) = g.slots else {
                return false;
            };
            o != k && [c, d].iter().any(|&x| x == a || x == b)
        })
    }

    /// Whether the latest collapse [`Repeats::note`] called for was a
    /// squeezed disc's (see [`Repeats::squeezed`]).
    pub(crate) fn by_squeeze(&self) -> bool {
        self.by_squeeze
    }

    /// Whether it was taken for its ring's ratio (see
    /// [`Repeats::geometric`]).
    pub(crate) fn by_ratio(&self) -> bool {
        self.by_ratio
    }

    /// Adds a hit of an elastic pair (see [`Repeats::with_elastic`]).
    fn keep(&mut self, pair: Pair, slots: (usize, Option<usize>)) {
        match self.hits.iter_mut().find(|h| h.pair == pair) {
            Some(h) => h.hits = h.hits.saturating_add(1),
            None => self.hits.push(PairHits {
                pair,
                slots,
                hits: 1,
                counted: None,
                approaches: [f64::NAN; 2],
            }),
        }
    }

    /// The pairs hit more than once at this instant (slots; `None` for an
    /// obstacle); from the thirteenth revision, elastic ones too.
    pub(crate) fn repeated(&self) -> Vec<(usize, Option<usize>)> {
        self.hits
            .iter()
            .filter(|h| h.hits > 1)
            .map(|h| h.slots)
            .collect()
    }
}

/// From the sixteenth revision, how far apart the ratios of a pair's
/// approaches from one of its hits to the next may lie for its ring to be
/// taken as a geometric sequence (see [`Repeats::geometric`]), as a
/// fraction of what the ring loses a turn.
pub(crate) const ONE_RATIO: f64 = 1e-2;

/// From the seventeenth revision, the ratio a turn at or below which a
/// ring shrinking by one ratio falls below the rounding of its speeds
/// (`f64::EPSILON` of its approach) within [`EARLY_REPEAT_HITS`] more
/// hits, and is left to them (see [`Repeats::lasting`]): 0.011.
pub(crate) const FADING_RATIO: f64 = 0.011;

/// Whether approaches `before` (the older first) and `now` at a pair's
/// three latest hits shrink by one ratio a turn (see [`ONE_RATIO`]).
fn shrinks_by_one_ratio(before: [f64; 2], now: f64) -> bool {
    let [a, b] = before;
    if !(a > 0.0 && b > 0.0 && now > 0.0) {
        return false;
    }
    let (r1, r2) = (b / a, now / b);
    r1 < 1.0 && r2 < 1.0 && (r2 - r1).abs() <= ONE_RATIO * (1.0 - r1.max(r2))
}

/// What the guards read of the world they watch. The event loop's world
/// implements it; through it the guards need no world type of their own.
pub(crate) trait Watched {
    /// The slot of a body still in the scene.
    fn slot_of(&self, id: BodyId) -> Option<usize>;

    /// The speed of the fastest live disc at `t` and the smallest radius.
    fn fastest_and_smallest(&self, t: f64) -> (f64, f64);

    /// The same among the live discs of `slots` (`usize::MAX`, an
    /// obstacle, is passed over): from the eighth revision, what a block of
    /// the crawl is measured on, so that a pile hitting itself ever closer
    /// is seen as still while a disc elsewhere keeps moving.
    fn fastest_and_smallest_of(&self, slots: &[usize], t: f64) -> (f64, f64);

    /// The restitution of a hit between the discs in slots `a` and `b`
    /// (the smaller of theirs), or of `a` on an obstacle (`b` = `None`).
    fn restitution(&self, a: usize, b: Option<usize>) -> f64;

    /// The speed of the disc in slot `c` at the latest event.
    fn speed_at_last_event(&self, c: usize) -> f64;

    /// Adds the slots of `event`'s bodies to `recent`, and `usize::MAX`
    /// for a hit on an obstacle (what `World::collapse` takes).
    fn remember(&self, recent: &mut Vec<usize>, event: &Event) {
        recent.extend(event.kind.bodies().filter_map(|id| self.slot_of(id)));
        if !matches!(event.kind, EventKind::BodyBody { .. }) {
            recent.push(usize::MAX);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two discs (slots 0 and 1, ids 1 and 2) of one restitution, each
    /// moving at 1 m/s after every hit.
    struct Pair(f64);

    impl Watched for Pair {
        fn slot_of(&self, id: BodyId) -> Option<usize> {
            (id.0 >= 1 && id.0 <= 2).then(|| id.0 as usize - 1)
        }
        fn fastest_and_smallest(&self, _: f64) -> (f64, f64) {
            (1.0, 1.0)
        }
        fn fastest_and_smallest_of(&self, _: &[usize], _: f64) -> (f64, f64) {
            (1.0, 1.0)
        }
        fn restitution(&self, _: usize, _: Option<usize>) -> f64 {
            self.0
        }
        fn speed_at_last_event(&self, _: usize) -> f64 {
            1.0
        }
    }

    fn hit() -> Event {
        Event {
            t: 1.0,
            kind: EventKind::BodyBody {
                a: BodyId(1),
                b: BodyId(2),
            },
        }
    }

    /// The hit (1-based, up to the 400th) at which `repeats` first takes
    /// the instant as a collapse, the pair approaching at `approach(k)` at
    /// its `k`-th hit.
    fn collapse_at(
        world: &Pair,
        mut repeats: Repeats,
        approach: impl Fn(u32) -> f64,
    ) -> Option<u32> {
        repeats.start(hit(), approach(1));
        (2..=400).find(|&k| repeats.note(world, &hit(), approach(k)))
    }

    #[test]
    fn a_plastic_pair_rung_ever_slower_but_never_gently_is_a_collapse_from_the_twelfth_revision() {
        // Each hit approaches a per cent slower than the one before, at
        // twice the discs' speed at first and still above 1/100 of it at the
        // 400th: never gentle.
        let decaying = |k: u32| 2.0 * 0.99f64.powi(k as i32);
        let plastic = Pair(0.0);
        let r11 = Repeats::new(EARLY_REPEAT_HITS);
        assert_eq!(collapse_at(&plastic, r11, decaying), None);
        let r12 = Repeats::new(EARLY_REPEAT_HITS).decaying(true);
        assert_eq!(
            collapse_at(&plastic, r12, decaying),
            Some(DECAYING_RING_HITS)
        );
    }

    #[test]
    fn elastic_pairs_are_named_among_the_repeated_from_the_thirteenth_revision_but_never_decide() {
        // The elastic pair is hit again and again, gently: no collapse
        // either way, and only from the thirteenth revision is it named.
        let elastic = Pair(1.0);
        for on in [false, true] {
            let slow = |_: u32| 1e-6;
            let repeats = Repeats::new(EARLY_REPEAT_HITS)
                .decaying(true)
                .with_elastic(on);
            assert_eq!(collapse_at(&elastic, repeats, slow), None);
            let mut repeats = Repeats::new(EARLY_REPEAT_HITS)
                .decaying(true)
                .with_elastic(on);
            repeats.start(hit(), 1e-6);
            assert!(!repeats.note(&elastic, &hit(), 1e-6));
            let named = if on { vec![(0, Some(1))] } else { vec![] };
            assert_eq!(repeats.repeated(), named);
        }
    }

    #[test]
    fn a_plastic_pair_collapses_at_the_same_hit_whether_elastic_pairs_are_kept_or_not() {
        let decaying = |k: u32| 2.0 * 0.99f64.powi(k as i32);
        let plastic = Pair(0.0);
        let without = Repeats::new(EARLY_REPEAT_HITS).decaying(true);
        let with = Repeats::new(EARLY_REPEAT_HITS)
            .decaying(true)
            .with_elastic(true);
        assert_eq!(
            collapse_at(&plastic, without, decaying),
            collapse_at(&plastic, with, decaying)
        );
    }

    /// Three plastic discs (slots 0 to 2, ids 1 to 3), each moving at
    /// 1 m/s after every hit.
    struct Row;

    impl Watched for Row {
        fn slot_of(&self, id: BodyId) -> Option<usize> {
            (id.0 >= 1 && id.0 <= 3).then(|| id.0 as usize - 1)
        }
        fn fastest_and_smallest(&self, _: f64) -> (f64, f64) {
            (1.0, 1.0)
        }
        fn fastest_and_smallest_of(&self, _: &[usize], _: f64) -> (f64, f64) {
            (1.0, 1.0)
        }
        fn restitution(&self, _: usize, _: Option<usize>) -> f64 {
            0.0
        }
        fn speed_at_last_event(&self, _: usize) -> f64 {
            1.0
        }
    }

    #[test]
    fn a_disc_rung_between_two_by_one_ratio_a_turn_is_a_collapse_at_a_pairs_third_hit_from_the_sixteenth_revision(
    ) {
        // Disc 2 rings between discs 1 and 3, hits of 2-1 and 2-3 in
        // turn, each approaching at 0.99 of the one before: never gentle.
        let hit = |k: u32| Event {
            t: 1.0,
            kind: EventKind::BodyBody {
                a: BodyId(2),
                b: BodyId(if k % 2 == 1 { 1 } else { 3 }),
            },
        };
        let approach = |k: u32| 2.0 * 0.99f64.powi(k as i32);
        let collapse_at = |mut repeats: Repeats| {
            repeats.start(hit(1), approach(1));
            (2..=400).find(|&k| repeats.note(&Row, &hit(k), approach(k)))
        };
        let r15 = Repeats::new(EARLY_REPEAT_HITS).decaying(true);
        assert_eq!(collapse_at(r15), Some(2 * DECAYING_RING_HITS - 1));
        let r16 = Repeats::new(EARLY_REPEAT_HITS)
            .decaying(true)
            .squeezed(true)
            .geometric(true);
        // The third hit of 2-1 is the instant's fifth.
        assert_eq!(collapse_at(r16), Some(5));
    }

    #[test]
    fn a_ring_that_does_not_slow_or_has_restitution_is_left_to_its_hits() {
        let steady = |_: u32| 2.0;
        let r12 = || Repeats::new(EARLY_REPEAT_HITS).decaying(true);
        assert_eq!(collapse_at(&Pair(0.0), r12(), steady), None);
        let decaying = |k: u32| 2.0 * 0.99f64.powi(k as i32);
        assert_eq!(collapse_at(&Pair(0.5), r12(), decaying), None);
    }
}
