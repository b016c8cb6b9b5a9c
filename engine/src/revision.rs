//! Revisions of the engine's computation: which rules decide what a scene
//! does, down to the last bit.
//!
//! A change that alters any result (one bit of one time or position) is a
//! new revision, and the old one keeps computing exactly what it computed,
//! so that a record made under it replays bit for bit for ever (the game's
//! physics versions each name one). [`Revision::LATEST`] is what a
//! [`crate::WorldConfig`] runs unless told otherwise.

use serde::{Deserialize, Serialize};

/// One revision of the engine's computation.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Revision {
    /// The first: exact where the model has a closed form; two discs pressed
    /// together obliquely drift into each other once their chatter falls
    /// below the approach threshold.
    R1,
    /// The second, as the first but:
    /// - discs pressed together obliquely keep bouncing apart by a bounded
    ///   gap (an approximation, counted in `Stats::pressed`; see
    ///   `push::pressing_kick`) instead of drifting into each other,
    ///   and touching discs that press are a contact at once;
    /// - a hit puts bodies whose distance is off by more than
    ///   `limits::SNAP` back at touching distance (positions far
    ///   from the origin carry the rounding of their coordinates);
    /// - a contact from more than 100 contact distances away takes its
    ///   discriminant from Lagrange's identity (exact to rounding from
    ///   any distance);
    /// - an inelastic collapse of discs that do not all lie on one line,
    ///   or against obstacles, is taken to its limit at once (the plastic
    ///   projection, see `World::collapse`).
    R2,
    /// The third, as the second but:
    /// - a pressed disc that touches others (a chain, a wall) is kicked
    ///   apart from the whole touching cluster where a kick between the
    ///   two alone would drive one into its next neighbour (which would hit
    ///   it back at the same instant, without end): one projection of every
    ///   contact, the pressed ones parting at their bounce speed (see
    ///   `World::press_cluster`); a pair of a pushed chain presses with the
    ///   chain's braking;
    /// - a pressed pair that would slide no further than the approximation's
    ///   gap before it stops comes to rest at once, and whatever touches it
    ///   and would run into it is stopped against it;
    /// - a collapse's plastic limit is solved exactly on the contacts that
    ///   push whenever projected Gauss–Seidel stalls (a light disc between
    ///   heavy ones or walls), takes a chain that touches an obstacle with
    ///   the obstacle, and is followed by the pressing kick where it leaves
    ///   discs pressed;
    /// - a chatter whose next bounce would fall within the rounding of the
    ///   time ends at once (a plastic hit), as one slower than the capture
    ///   speed does;
    /// - discs whose slides after a hit are all shorter than the rounding
    ///   of their positions are at rest (`limits::SETTLE`);
    /// - a touching pair (or a disc touching a line) approaching slower
    ///   than rounding noise meets 1e-10 of the contact distance inside it,
    ///   and the hit puts it back at touching distance, instead of drifting
    ///   in for as long as it slides;
    /// - events that no longer move any disc by more than
    ///   `limits::CRAWL` of a radius, block after block (a collapse
    ///   whose hits are each a few units in the last place of the time
    ///   apart, a chain pinned between two walls), are taken as a collapse
    ///   to its limit, and a run that goes on so ends `stuck` instead of
    ///   running to the event cap.
    R3,
    /// The fourth, as the third but:
    /// - a pressing kick over a cluster also gives their bounce speed to
    ///   the pairs its own projection leaves pressed, round after round
    ///   (see `World::press_closure`): biased only where they pressed
    ///   before it, two pressed pairs of one cluster hit again at once,
    ///   each in turn, trading the kick between them at one instant;
    /// - where a pressed pair comes to rest, so does every disc touching it
    ///   (or touching one that does) that still slides, but no further than
    ///   the approximation's gap: left moving, it pushed the pair off its
    ///   rest at once, at the same instant, again and again.
    R4,
    /// The fifth, as the fourth but an instant at which one inelastic pair
    /// has been hit `limits::REPEAT_HITS` times, every hit at it
    /// gentle (`limits::GENTLE`: discs pressed together as they
    /// slide, not an impact), is taken as an inelastic collapse of the
    /// pairs hit more than once to its limit at once, however few events
    /// it has had (see `World::collapse_repeated`).
    R5,
    /// The sixth, as the fifth but the approximated pressing contact keeps
    /// a pair within `push::WIDE_PRESS_GAP` (1e-4 of the contact
    /// distance) instead of 1e-6: a tenth of the bounces, so that a disc
    /// pressed for seconds between others and a wall comes to rest well
    /// within the event cap.
    R6,
    /// The seventh, as the sixth but with time resolved as finely as the
    /// events need (see `clock`): where events come closer together than
    /// `clock::REBASE` of the time, the world moves the zero of its
    /// working time up to the latest event, so that a sequence of hits
    /// 1.8e-18 s apart at t = 3 s (Galperin's billiard at ten digits) no
    /// longer falls onto one number; and events count as one instant only
    /// while no disc moves beyond the rounding of a position between them
    /// (`World::instant_tick`), not whenever their times share the
    /// rounding of the time.
    ///
    /// It also changes the collapse rule: a run of events that looks like an
    /// inelastic collapse (`limits::COLLAPSE_EVENTS` at one instant, or
    /// blocks of `limits::CRAWL_EVENTS` that move nothing) among discs
    /// that are all elastic (restitution 1, and so every contact between
    /// them and with obstacles) is not taken to a plastic limit: an
    /// elastic chain loses no energy, and one pinned between two walls,
    /// which has no finite answer, ends `stuck` with its energy.
    R7,
    /// The eighth, as the seventh but the crawl of events that move nothing
    /// (`limits::CRAWL`) is measured on the discs the block's latest events
    /// involve, not on the fastest disc of the whole scene: a pile whose
    /// hits come ever closer (a frictionless plastic disc sliding between
    /// braking ones) is seen as still while an elastic disc crosses the
    /// box; and where a still block follows one already taken as a
    /// collapse, its discs, which moved less than `limits::CRAWL` of a
    /// radius in two blocks of events, come to rest (`World::crawl_rest`).
    R8,
    /// The ninth, as the eighth but where the plastic limit of a collapse
    /// has no answer that projected Gauss–Seidel or the exact solve of its
    /// pushing contacts finds (a struck pile on a line, whose contacts are
    /// more than its discs can move independently: the exact solve is
    /// singular), it is found by an active-set method
    /// (`collapse::active_set`) instead of being left to the hits: the
    /// eighth revision took only the limit of the few discs hit last, and
    /// the chain of discs behind them, still driving them, hit them again
    /// at once, 2,000 more events at one instant each time, until the run
    /// ended `stuck`.
    R9,
    /// The tenth, as the ninth but:
    /// - an instant at which one inelastic pair has been hit
    ///   `limits::EARLY_REPEAT_HITS` times (8), every hit of the instant
    ///   gentle (or, for a plastic pair, every hit since a plastic pair
    ///   was last counted), is taken as a collapse, as the fifth revision
    ///   takes one after `limits::REPEAT_HITS` (16): a disc jammed between
    ///   walls and a heavy one that presses it as it slides past rings at
    ///   one instant among the discs alone, fewer than 16 hits of a pair
    ///   (the walls they touch are a rounding of a position away, and are
    ///   hit a picosecond later), and where an instant's first hits were
    ///   not gentle, the gentle ring after them was never counted; either
    ///   way the ring came back, instant after instant, until the event
    ///   cap;
    /// - a cluster of elastic discs no longer counts as losing no energy
    ///   (and so is taken to a plastic limit when it crawls) where one of
    ///   them moves so slowly that its friction would stop it within the
    ///   block of events taken as a collapse (`World::all_elastic`).
    R10,
    /// The eleventh, as the tenth but a pressed pair whose kinetic energy
    /// is no more than the braking of its lightest-braked braking disc
    /// dissipates over the approximation's gap (`push::spent_within_gap`)
    /// comes to rest as the third revision's slow pair does, though one of
    /// the two is frictionless and whether or not the hit already parts
    /// it faster than its bounce speed: its braking discs are held where they are
    /// and a frictionless one keeps only what does not run into them (the
    /// plastic limit against the held discs). A heavy frictionless disc
    /// slowly pressing a light braking one kicked it off its rest at every
    /// hit, the light one stopped a few tens of nanoseconds later, and the
    /// heavy one, losing a few parts in a million of its speed each time,
    /// caught it again, until the event cap.
    ///
    /// Two more rules close rings the tenth left open:
    /// - the collapse after repeated gentle hits at one instant
    ///   (`World::collapse_repeated`) takes in every obstacle its discs
    ///   touch: a light elastic disc in a corner, rung against the floor by
    ///   a heavy disc sliding past it, was pushed into the side wall, hit
    ///   it a picosecond later, and the ring came back;
    /// - a cluster of elastic discs with a braking disc at rest among them
    ///   is not lossless (`World::all_elastic`): a frictionless disc
    ///   rattling at one instant against a resting braking one, each hit
    ///   settling it back to rest, ended `stuck` with no collapse taken.
    R11,
    /// The twelfth, as the eleventh but:
    /// - a pressing kick over a cluster adds no more than 0.01 of the
    ///   scene's kinetic energy, twice the bound of the kick between a
    ///   pressed pair alone (`push::CLUSTER_PRESS_GAIN`): where one of the
    ///   pair is jammed, the projection gave the whole separation to what
    ///   it could move, a disc forty times heavier set moving at the light
    ///   one's bounce speed (7.3e-2 of a scene's energy at one event);
    ///   held, the kick is the blend of the cluster's plastic limit and the
    ///   biased projection within that bound
    ///   (`Revision::bounds_cluster_kick_energy`);
    /// - the eleventh revision's rest of a pressed pair, its braking discs
    ///   held, is found by the active-set method where the projection
    ///   stalls on more contacts than the free discs have directions (a
    ///   frictionless disc caged by held discs), instead of kicking the
    ///   whole pack, which crept at 1e-8 m/s until the run ended `stuck`
    ///   (`Revision::rests_caged_discs_by_active_set`);
    /// - a plastic pair hit again and again at one instant (160 times at
    ///   least), each count of its hits slower than the last, is a
    ///   collapse however hard the hits (a light elastic disc between a
    ///   wall and a heavy plastic one, caught a per cent slower each time,
    ///   a thousand hits an instant, instant after instant, until `stuck`)
    ///   (`Revision::collapses_decaying_plastic_rings`);
    /// - a touching pair of moving discs that neither approaches nor parts
    ///   faster than rounding noise is still sought 1e-10 of its contact
    ///   distance inside it (as the third revision seeks one approaching
    ///   below that noise), where its braking brings it together later
    ///   (`contact::turns_in_after_touch`):
    ///   two discs left side by side by a plastic ring at one instant,
    ///   braked differently along a normal turning as one pulls ahead,
    ///   came together from a tangent, below the noise of an approach, and
    ///   went 1.8e-8 of their contact distance into each other;
    /// - a plastic hit between two discs, gentle (its approach within 1e-3
    ///   of the faster disc's speed), on the lighter one
    ///   where it is plastic and lies in a corner (touches two obstacles
    ///   that are not parallel), is taken at once as the plastic limit of
    ///   the two, every disc touching either through a plastic contact,
    ///   and the obstacles the plastic ones touch (`World::cornered_hit`).
    ///   A light plastic disc in a corner, pressed by a heavier one
    ///   sliding past, was sent by each hit into one wall, which it hit a
    ///   picosecond to a nanosecond later, its partner hitting it again
    ///   at that same instant and losing only the light disc's share of
    ///   its approach: two or three hits an instant, never the tenth
    ///   revision's eight hits of a pair, until the event cap.
    R12,
    /// The thirteenth, as the twelfth but:
    /// - a plastic hit between two discs that drives one of them into an
    ///   obstacle it touches, where the hits that follow (that disc off the
    ///   obstacle, its partner meeting it again), played in memory, still
    ///   ring after eight turns with a fifth of their approach left, is
    ///   taken at once as the plastic limit of
    ///   the two, the discs touching them through plastic contacts and the
    ///   obstacles of the plastic and ringing ones
    ///   (`World::hit_into_wall`), however hard or straight the hit: a
    ///   heavy disc driven slowly into a light plastic one against a wall
    ///   lost a few parts in a thousand of its speed a turn, each obstacle
    ///   hit moving the light disc by the rounding of its position, so that
    ///   its partner met it again picoseconds later at a new instant, three
    ///   events a turn until the event cap; a light elastic disc between a
    ///   wall and a heavy plastic one rang so at one instant, ring after
    ///   ring (`Revision::takes_hit_into_wall_with_wall`);
    /// - an elastic ring (every disc touching it elastic) at one instant or
    ///   crawling, with a braking disc in it, whose contacts approach and
    ///   part no faster than `limits::GENTLE` of its fastest disc, is
    ///   taken as the seventh revision takes an inelastic collapse (and
    ///   the eighth its crawl): it rests on itself, a chatter to rest over
    ///   more than two discs, not a chain rattling between walls. A
    ///   frictionless disc behind a pushed elastic pair, its velocity
    ///   1.4e-9 of theirs off, hit the middle disc 20,000 times at one
    ///   instant, each hit giving it its own braking back, until `stuck`
    ///   (`Revision::collapses_resting_elastic_rings`);
    /// - the collapse of an instant's repeated inelastic hits
    ///   (`World::collapse_repeated`) takes in the elastic pairs hit more
    ///   than once at that instant too: a light elastic disc between a
    ///   heavy plastic one and an elastic one resting on a wall rang
    ///   between them, a few per cent slower each time, and the collapse
    ///   of the plastic pair alone drove it into its elastic neighbour
    ///   again, 20,000 hits at one instant, until `stuck`
    ///   (`Revision::collapses_rings_with_elastic_pairs`);
    /// - a pair with restitution sliding head-on (both along the line of
    ///   centres) pressed together by its braking so hard
    ///   that its bounce would stay within 1e-9 of its contact distance
    ///   (half of `push::TOUCHING`) is taken as the end of its chatter, one
    ///   plastic hit, as the second revision takes a pair parting slower
    ///   than `push::CAPTURE`: a heavy frictionless elastic disc pushing a
    ///   light braking elastic one sent it off at every hit at the same
    ///   speed, 7.5e-6 of theirs, its braking bringing it back 1.7e-7 s
    ///   later, millions of hits until the event cap
    ///   (`Revision::ends_bounces_within_touch`);
    /// - a plastic hit between two discs that touch no other disc through
    ///   a plastic contact, which drives the lighter one, plastic, into an
    ///   obstacle it touches, is taken at once as the plastic limit of the
    ///   pair and the obstacle, unless their braking presses them together
    ///   (`World::walled_hit`): a heavy disc sliding along a light one on a
    ///   wall hit it into the wall, which it hit 1.2e-13 s later, and hit
    ///   it again at that instant, losing a fraction of its approach, one
    ///   hit of the pair an instant, until the event cap
    ///   (`Revision::takes_walled_hit_with_wall`).
    R13,
    /// The fourteenth, as the thirteenth but:
    /// - a hit of a pair with restitution taken as the end of its chatter
    ///   (one plastic hit, `push::chatters`, `push::bounces_within_touch`)
    ///   that drives one of the two into an obstacle it touches, where the
    ///   turns that follow, played in memory, ring as the thirteenth
    ///   revision's hit into a wall does, is taken at once as the plastic
    ///   limit of the two, their plastic neighbours and the obstacles
    ///   (`World::hit_into_wall`), their own contact with them: a light
    ///   elastic disc against a wall, a heavy elastic one sliding into it,
    ///   each hit of the pair a chatter's end that left the light disc
    ///   moving into the wall, which sent it back into its partner at the
    ///   same instant, the partner losing twice the light disc's share of
    ///   its speed a turn, 20,000 hits at one instant until the event cap
    ///   (`Revision::takes_captured_hit_into_wall_with_wall`);
    /// - a gentle plastic hit (its approach within `limits::GENTLE` of the
    ///   faster disc's speed: discs pressed together as they slide, not an
    ///   impact) that drives a plastic disc into an obstacle its normal
    ///   meets at an angle, the disc then coming back into its partner, is
    ///   taken at once as that same plastic limit (`World::hit_into_wall`)
    ///   unless their braking presses them together or it lies in a pile
    ///   (more than four discs with the plastic neighbours),
    ///   however fast the ring would fade, not only where it keeps a fifth
    ///   of its approach over eight turns: a plastic disc on the floor,
    ///   rung by a lighter plastic one sliding against it, stopped against
    ///   the floor and was caught again at one instant, a tenth of the
    ///   approach left each turn, until the rounding of the speeds ended
    ///   the ring, and the light disc, pressed between it and a third,
    ///   drove into it again tens of microseconds later, until the event
    ///   cap
    ///   (`Revision::takes_gentle_hit_into_wall_with_wall`);
    /// - the pressing kick after a collapse's plastic limit adds no more
    ///   than 0.01 of the scene's kinetic energy over the limit, as the
    ///   twelfth revision holds a kick over a cluster: a light frictionless
    ///   disc sliding down a wall along a resting one 440 times heavier,
    ///   each hit taken to a plastic limit, set the heavy one moving with
    ///   the whole separation, 2.4e-2 of the scene's largest energy at one
    ///   event (`Revision::bounds_collapse_kick_energy`);
    /// - a plastic hit between two discs whose touching cluster (at most
    ///   twelve discs and the obstacles they touch), its hits played in
    ///   memory from the hit, contact after contact with each one's
    ///   restitution, still rings after sixteen sweeps with a fifth of its
    ///   approach left, is taken at once as the plastic limit of the
    ///   contacts that ring (`World::cluster_ring`): a heavy disc pressing
    ///   a light plastic one against a disc resting on a wall, or a pushed
    ///   chain driven into a disc in a corner, lost a per cent of its
    ///   approach a turn, each turn a new instant picoseconds after the
    ///   last with a few hits, never the eight hits of one pair that the
    ///   collapse after repeated hits counts, until the event cap
    ///   (`Revision::takes_cluster_rings_at_once`);
    /// - a disc sliding nearly past a harder-braked one, touching something
    ///   else that holds it to its line (a wall, a disc), and pressing it
    ///   obliquely so that it has to wedge it aside, takes it along as one
    ///   sliding body, once an instant: the pushed disc along the normal,
    ///   the pair stopping together where the pushed disc's friction,
    ///   along the tractrix it follows, has spent the pair's energy, or,
    ///   where the pusher has the energy to pass, the pusher paying that
    ///   friction at once (`push::carried`), unless the hit drives the
    ///   pusher into an obstacle it touches. A heavy frictionless disc
    ///   sliding past a light braking one kicked it aside at every hit by
    ///   the pressing contact's capped bounce; it stopped a microsecond
    ///   later and was caught again, two events a cycle until the event
    ///   cap (`Revision::carries_wedged_discs`).
    R14,
    /// The fifteenth, as the fourteenth but:
    /// - the plastic limit of a ring (`World::cluster_ring`,
    ///   `World::hit_into_wall`) takes in each obstacle one of its discs
    ///   touches that the limit of the ringing contacts alone would drive
    ///   it into (pushing it there), solved again with it
    ///   (`world::reached_walls`): a light
    ///   plastic disc sliding past an elastic one in a corner rang it
    ///   against the floor, and the limit of that ring slid it into the
    ///   side wall at 3.9e-9 m/s; it met the wall 3.5e-9 s later, bounced
    ///   into its partner at that instant, and the same limit sent it back,
    ///   10,000 turns until the event cap
    ///   (`Revision::takes_ring_limits_with_walls_they_reach`).
    /// - a plastic hit whose touching cluster rings (`World::cluster_ring`)
    ///   and whose ringing discs have no more kinetic energy than the
    ///   friction of each of their braking discs does over the rounding of
    ///   its position comes to rest: its braking discs held, its
    ///   frictionless discs keeping only what does not run into them (the
    ///   plastic limit against them): a frictionless disc sliding into a
    ///   corner along a wall, its contact with a disc on the floor tilted a
    ///   millionth from its motion, drove a braking pile at a millionth of
    ///   its speed, each limit of the ring taking only that share of its
    ///   motion, 20,000 limits at one instant until `stuck`
    ///   (`Revision::rests_spent_rings`).
    /// - a disc carried aside by one sliding past it (`push::carried`)
    ///   where the plastic hit would drive the pushing disc into the one
    ///   obstacle it slides along is taken with that obstacle holding it to
    ///   its line through the hit (`push::plastic_along_wall`): a heavy
    ///   frictionless disc sliding along the floor pressed a light braking
    ///   one up and forward, each hit sending it into the floor by the
    ///   light one's share of the approach, so that the carry was refused
    ///   and the pressing contact kicked the pair apart every 1.8e-5 s
    ///   until the event cap; only where the pair stops together and the
    ///   pushing disc touches no other disc
    ///   (`Revision::carries_wedged_discs_along_walls`);
    /// - an elastic pair pressed head-on by its braking whose bounce stays
    ///   within the pressing contact's gap (1e-4 of the contact distance)
    ///   and would repeat at least 10,000 times before the pair stops is
    ///   taken as the end of its chatter, one plastic hit, as the
    ///   thirteenth revision takes one within 1e-9 of touching: a heavy
    ///   frictionless elastic disc pushing a light braking one, its bounce
    ///   6.6e-9 of the contact distance high, made 170,000 hits, a true
    ///   sequence of constant-height bounces, beyond the event cap
    ///   (`Revision::ends_long_bounces_within_gap`);
    /// - a disc that wedges a harder-braked one aside as it slides along
    ///   the one obstacle it touches, the hit driving it into that
    ///   obstacle, takes the hit with the obstacle (it keeps to the
    ///   obstacle's line, the obstacle taking the normal share of the
    ///   impulse) and carries the other along as the fourteenth revision
    ///   carries a wedged disc, where the carried disc's whole slide keeps
    ///   clear of every other disc (`World::hit_along_wall`): a heavy
    ///   frictionless disc sliding along the floor under a light braking
    ///   one kicked it up at every hit, the fourteenth revision refusing the
    ///   carry because the free hit drove the heavy disc into the floor; it
    ///   stopped 2e-5 s later and was caught again, two events a cycle
    ///   until the event cap; only where the pusher passes, carrying the
    ///   other ahead (stopped together a few nanometres on, the pair parted
    ///   by less than the rounding of a position and was hit again before
    ///   it stopped, carry after carry) (`Revision::carries_along_walls`).
    R15,
    /// The sixteenth, as the fifteenth but:
    /// - a gentle plastic hit (its approach within `limits::GENTLE` of the
    ///   faster disc's speed) that drives an elastic disc into an obstacle
    ///   its normal meets at an angle, the disc bouncing back into its
    ///   partner, is taken at once as the fourteenth revision takes one
    ///   on a plastic disc (`World::hit_into_wall`), the elastic disc's
    ///   contact with the obstacle plastic in the limit, where that limit
    ///   drives no disc of it into a disc outside it: a light elastic disc
    ///   on the floor under a plastic one nine times heavier, pressed by a
    ///   pile a heavy frictionless disc pushed at 1e-2 m/s, bounced off
    ///   the floor back into it, 0.29 of its speed into the floor left a
    ///   turn, the collapse after repeated hits ending each ring at its
    ///   instant only for the next to begin microseconds later: 17,700 of
    ///   the last 20,000 events until the event cap; unguarded, the limit
    ///   of a disc grazing over an elastic one at the end of a frictionless
    ///   row on the floor pushed the row into the corner, 10,102 limits
    ///   until the event cap
    ///   (`Revision::takes_gentle_hit_on_elastic_disc_into_wall`);
    /// - a plastic hit into a wall that rings (`World::hit_into_wall`) and
    ///   whose discs have no more kinetic energy than the friction of each
    ///   of their braking discs does over the rounding of its position
    ///   comes to rest as the fifteenth revision rests a spent cluster's
    ///   ring (`World::spent_ring_rest`): a light frictionless disc on the
    ///   side wall, 5.3e-8 m above the floor, slid down at 7.1e-9 m/s
    ///   into a heavy braking one on the floor, their contact tilted
    ///   1.45e-6 from level; each hit was taken with the wall and the
    ///   pressing kick sent the braking disc off at 3.5e-10 m/s, to stop
    ///   3.1e-11 s later 5e-21 m on (below the rounding of its position)
    ///   and be hit again at once, 9,837 of the last 20,000 events before
    ///   `stuck`, with
    ///   4.4e-19 J against the 5.6e-16 J its friction does over that
    ///   rounding; two frictionless discs on the side wall sliding at
    ///   6.6e-17 m/s into a braking one did the same, 19,845 of them
    ///   (`Revision::rests_spent_hits_into_walls`);
    /// - a pair resting by its energy (`push::spent_within_gap`) whose
    ///   plastic limit against its held braking discs stalls the
    ///   projection on no more contacts than its free discs have
    ///   directions is solved by the active-set method, as the twelfth
    ///   revision solves a caged disc's: a frictionless disc on the side
    ///   wall sliding down at 1.5e-8 m/s into a braking one on the floor,
    ///   the wall's contact and the pair's 2e-5 from parallel, stalled the
    ///   projection, so the pair was kicked apart instead of resting; the
    ///   braking disc stopped 1e-10 s later and was hit again at that
    ///   instant, the wedging disc gaining speed from the kicks, 6,640
    ///   cycles of the last 20,000 events before `stuck` (`Revision::rests_wedged_spent_pairs`);
    /// - a plastic pair of discs hit a second time at one gentle instant,
    ///   one of its discs hit by a third disc at that instant too, is taken
    ///   at once as the collapse of the instant's repeated pairs (their
    ///   plastic limit alone, not kicked apart after it): the disc
    ///   they share is squeezed between its two neighbours, each hit
    ///   driving it into the other, a ring whose relative speeds shrink by
    ///   a half to a third a turn and never end; a light frictionless disc on the floor between
    ///   a braking one at rest and one pressed into it from above rang 16
    ///   hits an instant before the eighth hit of a pair took the limit,
    ///   again every few microseconds as the disc above was pressed, until
    ///   the event cap (mixed-box 567963; rows of three on the floor in
    ///   196517 and 435983, a disc between two in a corner in 266709)
    ///   (`Revision::collapses_rings_through_squeezed_discs`);
    /// - a light disc lying against the one obstacle it touches, wedged
    ///   aside by a heavy disc sliding past it (at least 60 degrees off
    ///   their line of centres) and braking less, held by another disc
    ///   and touching no obstacle, is taken with the obstacle holding
    ///   the light disc to its line and the heavy one to its own through
    ///   the hit, and carried along the obstacle as the heavy one slides
    ///   past (`wedge::carried_along_wall`): a heavy frictionless disc
    ///   sliding towards a wall at 3.7e-4 m/s along a disc in the corner
    ///   pressed a 1.6 g disc braking at 4.2 m/s^2 up the wall, one hit
    ///   every 9.7e-6 s until the event cap at 5.6 s (7 s of such hits were
    ///   left), the fourteenth revision's carry refused because the pushed
    ///   disc touched the wall; it reaches the 100 s horizon in 11,039
    ///   events (`Revision::carries_wedged_discs_along_their_walls`);
    /// - a pushing disc carried aside (`push::carried`) that touches no
    ///   wall but slides past a disc at rest pinned in a corner by its two
    ///   walls against the push is held to the tangent at their contact
    ///   through the hit, as the fifteenth revision holds one sliding
    ///   along a wall (`World::pinning_disc`): carried along the line of
    ///   centres, the heavy disc (0.98 kg, braking at 0.013 m/s^2) sliding
    ///   at 2.1e-3 m/s past a frictionless disc in the corner was driven
    ///   into it, hit it 1e-9 s later and lost the carried braking, and
    ///   the light disc (2.4 g, braking at 99 m/s^2) it wedged aside was
    ///   kicked, stopped and caught again every 2.3e-6 s until the event
    ///   cap at 1.68 s (mixed-box 211562; a frictionless disc squeezed up
    ///   at 1.3e-6 m/s between a disc in the corner and a braking one,
    ///   to the cap at 3.7 s, in 549516); the boxes rest at 1.76 s and
    ///   reach the 100 s horizon (`Revision::holds_pushers_on_pinned_discs`);
    /// - a plastic pair of discs, one of which a third disc hit at that
    ///   instant too, whose approach at its three latest hits shrank by one
    ///   ratio a turn, gentle or not, is taken at once as the instant's
    ///   collapse, its plastic limit alone, solved by the active-set method
    ///   where a short projection does not reach it: a light plastic disc
    ///   (1.1 g) on the floor between a 0.62 kg disc in the corner and a
    ///   106 g frictionless one pushed into it every 1e-4 s rang between
    ///   the two at one instant, each hit at
    ///   the discs' full speed and 0.9879 of the one before, taken only
    ///   at the 160th hit of a pair, 9,328 hits of one pair in the last
    ///   20,000 events before the event cap at 6.04 s (mixed-box 143264;
    ///   a light elastic disc between a heavy one in the corner and a
    ///   plastic one, 52,923 events and 1.2 s to the horizon, in 376685)
    ///   (`Revision::collapses_geometric_rings_through_squeezed_discs`).
    R16,
    /// The seventeenth, as the sixteenth but:
    /// - a touching pair that parts so slowly that its braking brings it
    ///   back into contact within the rounding of the time is taken at its
    ///   hit as the pushed pair it is, its normal velocities made one (the
    ///   plastic hit that comes then, taken now; momentum kept): a row of
    ///   three on the floor, sliding at 8.8e-13 m/s behind a 77 g disc
    ///   braking at 2.9 m/s^2, parted from it at 3e-18 m/s, its braking
    ///   bringing the two back 2e-18 s later, below the rounding of the
    ///   time at 15.7 s; the contact fell on the same instant, the pair
    ///   still parting, and the hit changed nothing, 19,667 of the last
    ///   20,000 events before `stuck` (mixed-box 452272)
    ///   (`Revision::rejoins_pairs_parting_within_instant`);
    /// - a pair resting by its energy (`push::spent_within_gap`) whose
    ///   free disc the held projection leaves running into its held
    ///   partner, below the projection's tolerance (1e-15 of the cluster's
    ///   fastest disc) but not below the pair's own contact noise, has that
    ///   approach taken off against the held disc, as against a wall: a
    ///   frictionless disc (0.24 kg) sliding at 3.9e-10 m/s past a braking
    ///   one on the floor, 2.3e-10 of its speed into it, its cluster's
    ///   fastest disc at 0.098 m/s, was hit 19,859 times at one instant
    ///   until `stuck` (mixed-box 502923; a frictionless disc sliding down
    ///   the side wall into a braking one on the floor, the same rest
    ///   earlier in its run, in 595125)
    ///   (`Revision::rests_free_disc_on_held_partner`);
    /// - a light disc wedged aside by a heavy one sliding past it
    ///   (`push::carried`) that the push drives into a braking disc at
    ///   rest, whose friction takes the load the light disc passes on, is
    ///   carried round that disc (`pivot::carried_around`): both stop
    ///   where the light disc's friction round it spends the pair's
    ///   energy, or the heavy one pays that friction at once and passes.
    ///   A heavy frictionless disc (0.72 kg) sliding along the floor
    ///   under a 2.2 g disc braking at 2.9 m/s^2 pressed it into a 14 g
    ///   disc at rest, which the pressing contact kicked off at every
    ///   hit; it stopped 8e-6 s later, the light disc ran into it, and the
    ///   heavy one caught it again 1e-5 s on, three events a cycle, its
    ///   speed 4.5e-5 lower each, until the event cap at 7.58 s
    ///   (mixed-box 403865); it reaches the 100 s horizon in 8,420 events
    ///   (`Revision::carries_discs_round_held_discs`);
    /// - a hit that leaves both its discs at rest (their slides below the
    ///   rounding of their positions) stops whatever runs into them (and
    ///   whatever runs into that), each keeping only what does not: the
    ///   plastic limit with the pair held, as the third revision stops it
    ///   against a pressed pair that rests, where the energy of what runs
    ///   in is no more than the weaker braking disc of the pair spends
    ///   over the pressing contact's gap (`World::settled_hit`). A
    ///   frictionless disc (0.31 kg) at 5.6e-9 m/s pushing a 1.9 g disc
    ///   into one braking at 240 m/s^2, the light disc settled by each
    ///   hit against it and caught again at once, 0.63 per cent slower a
    ///   turn, ran 1,708 events at one instant until `stuck` (mixed-box
    ///   425978; the box rests at 14.4 s); a heavy frictionless disc
    ///   running at 5e-9 m/s into a light one on the side wall, which
    ///   wedged a braking disc aside and settled with it, drove it again
    ///   every 1.3e-10 s until `stuck` (512700; to the 100 s horizon in
    ///   4,386 events) (`Revision::stops_discs_running_into_settled_hits`);
    /// - a ring resting by its spent energy (`World::spent_ring_rest`:
    ///   its braking discs held, its frictionless ones keeping what does
    ///   not run into them) weighs the kinetic energy the rest takes away,
    ///   not all its discs have: a disc grazing the ring along its tangent
    ///   keeps its motion and spends none of it on the held discs. A
    ///   frictionless disc (0.20 kg) sliding up the left wall at 3.8e-13
    ///   m/s into a braking one (1.3 g) beside it, their contact tilted
    ///   2.4e-7 from level, held 1.5e-26 J against the 2.1e-19 J the
    ///   braking disc's friction does over the rounding of its position;
    ///   a frictionless disc sliding past the first at 6.1e-5 m/s brought
    ///   2.5e-10 J to the ring, which was taken with the wall and kicked
    ///   apart instead, the braking disc stopping 6.2e-15 s later and hit
    ///   again at that instant, 9,960 hits in the last 20,000 events before
    ///   `stuck` (mixed-box 439482)
    ///   (`Revision::rests_rings_spent_by_what_runs_into_them`);
    /// - a ring that the sixteenth revision's geometric rule takes, whose
    ///   approach shrinks to 0.011 or less of the last a turn
    ///   (`limits::FADING_RATIO`), falls below the rounding of its speeds
    ///   within the eight hits a count waits for, and is left to them: a
    ///   striker's ring on the top of a hex-packed plastic pile, 0.0021
    ///   of the approach left a turn, was taken to the plastic limit of
    ///   the whole pile, which set its rows sliding at a few millimetres a
    ///   second, pressed into each other, a pressed hit every 4e-11 s,
    ///   46,630 events to rest where the fifteenth revision rests in 83
    ///   (plastic-lines 1082; 70 events now)
    ///   (`Revision::leaves_fading_rings_to_their_hits`);
    /// - a pair whose energy cannot move its braking discs beyond the
    ///   pressing contact's gap (`push::spent_within_gap`) rests as the
    ///   eleventh revision rests one pressed or parted by its hit, where
    ///   the hit leaves it neither (`World::press_cluster`): a heavy
    ///   frictionless disc (0.99 kg) pushing a light frictionless one
    ///   (1 g) into a braking one (72 g) at 2.9e-12 m/s, each hit leaving
    ///   the pair parting at 4e-19 m/s, which the braking turned within
    ///   the rounding of the time, was met again at once, the hit changing
    ///   nothing, 19,698 hits at one instant until `stuck` (mixed-box
    ///   79139, which the rule before this one sent there)
    ///   (`Revision::rests_spent_pairs_left_as_they_were`).
    R17,
    /// The eighteenth, as the seventeenth but:
    /// - the discs a settled hit stops (`World::settled_hit`) take in,
    ///   too, a disc that runs into one of them only once the limit has
    ///   stopped it, solved again until none does: a frictionless disc
    ///   (20 g) sliding down the side wall at 3e-5 m/s along a light
    ///   plastic one on the floor, their contact tilted 9.6e-7 from level,
    ///   shared its motion along their normal, so that the settled hit of
    ///   the braking discs ahead (0.73 kg and 0.26 kg, pushed at 2.8e-11
    ///   m/s by each limit of the ring) stopped the light disc but not
    ///   it, and it ran into the light one again at that instant, 18,615
    ///   of the last 20,000 events at one time until the event cap at 31.2
    ///   s (mixed-box 531237; to the 100 s horizon in 17,175 events)
    ///   (`Revision::stops_discs_running_into_stopped_discs`);
    /// - a braking disc that the pressing kick after a plastic limit sets
    ///   moving so slowly that it stops within the rounding of its
    ///   position, the limit having left it so too, is held by its
    ///   friction instead, where what the limit moves has no more kinetic
    ///   energy than the held disc's friction spends over the pressing
    ///   contact's gap: the limit is solved again with it still, and no
    ///   kick follows (`World::held_against_kick`). A disc (6.7 g) on the
    ///   side wall, pressed down by a heavy one sliding over it, slid at
    ///   1.6e-7 m/s into a plastic disc (0.52 kg, braking at 137 m/s^2)
    ///   at rest on the floor, their contact tilted 6.5e-4 from level;
    ///   each hit was taken with the wall, the kick sent the heavy disc
    ///   off at 8e-9 m/s, it stopped 6e-11 s later 2.4e-19 m on and was hit
    ///   again at that instant, 9,980 hits in the last 20,000 events before
    ///   `stuck` at 26.2 s (mixed-box 170741; to the 100 s horizon in
    ///   10,851 events) (`Revision::holds_discs_kicks_cannot_move`);
    /// - an elastic hit between two frictionless discs that drives one of
    ///   them into a wall it lies against, the two then ringing between
    ///   the wall and each other within the rounding of their positions,
    ///   is played in memory to the ring's end and taken at once (the
    ///   same elastic impulses, no energy lost): a frictionless elastic
    ///   disc (2.0 g) in the corner, pressed by a frictionless one (0.15
    ///   kg) that a row pushed by a heavy disc sliding over it squeezed
    ///   along the floor, rang between the side wall and its partner some
    ///   2e-12 m apart, a hit every 4e-7 s, 10,735 of the last 20,000
    ///   events before the event cap at 3.44 s (mixed-box 401789; to the
    ///   100 s horizon in 82,546 events)
    ///   (`Revision::plays_elastic_wall_rings_at_once`);
    /// - a light braking disc wedged along the wall it lies against by a
    ///   heavy disc sliding past it (`wedge::carried_along_wall`) is so
    ///   carried where the heavy disc is held to its line not by a disc
    ///   but by the one wall it slides along, the push from the light
    ///   disc driving it into that wall: a frictionless disc (0.64 kg)
    ///   sliding down the side wall into the corner at 3.9e-4 m/s past a
    ///   6.6 g disc braking at 2.0 m/s^2 on the floor pushed it along the
    ///   floor, a hit and a stop every 4.3e-5 s, 4.4e-6 of its speed lost
    ///   a turn, until the event cap at 20.3 s (mixed-box 1037739; to the
    ///   100 s horizon in 2,945 events)
    ///   (`Revision::carries_wedged_discs_between_walls`);
    /// - a touching pair whose straight relative path closes in by no
    ///   more than the rounding of its positions before it parts (the
    ///   sagitta of one's path over the other, `graze::within_rounding`)
    ///   is a graze, not a contact: no hit is predicted for a disc moving
    ///   against one at rest, and the ring of a plastic hit
    ///   (`World::cluster_ring`) is played without it. A light
    ///   frictionless disc (16 g) sliding down the side wall at 5.3e-4
    ///   m/s, 2.6e-10 m above the line of a row on the floor (a
    ///   frictionless disc, then two braking ones), wedged the row at
    ///   3.7e-12 m/s, 9.2e-19 m of carry left before it reached the floor,
    ///   1/60 of a position's rounding; each hit of the row's frictionless
    ///   disc into the braking one was taken as a ring with the wedging
    ///   disc and the wall, which gave the two the wedge's speed again,
    ///   and the braking disc, kicked off the next, was caught again
    ///   1.5e-13 s later: 22,000 events at 0.463 s, no more than 3 at one
    ///   instant, until `stuck` (mixed-box 129558; the horizon in 41
    ///   events) (`Revision::passes_grazes_within_rounding`).
    R18,
    /// The nineteenth, as the eighteenth but:
    /// - a plastic hit that drives a disc sliding along the one obstacle
    ///   it touches into it, as that disc wedges a braking one aside, is
    ///   carried (`World::carried_press`, the disc held to its wall
    ///   through the hit) before it is taken as a ring into that obstacle
    ///   (`World::hit_into_wall`), whose pressing kick sent the braking
    ///   disc off to stop and be caught again: a light frictionless disc
    ///   (1.5 g) sliding up the side wall at 6.5e-6 m/s into a braking
    ///   one (20 g, 2.9 m/s^2), their contact tilted 1.0e-4 from level
    ///   (passing it would cost 370 times its energy), kicked it off at
    ///   3.3e-7 m/s at every hit, a hit and a stop every 2.7e-5 s, 3e-5 of
    ///   its speed lost a turn, until the event cap at 5.77 s (mixed-box
    ///   1076279; the two now stop together 1.6e-3 s after the first such
    ///   hit, to the 100 s horizon in 181 events; a frictionless disc
    ///   sliding up the wall into a braking row of two, four events a
    ///   cycle until the event cap at 5.86 s, in 258784, to the horizon in
    ///   474 events) (`Revision::carries_wedges_before_wall_rings`).
    /// - a pair resting by its energy (`push::spent_within_gap`) no longer
    ///   holds with it a braking disc of its cluster that slides beyond
    ///   the pressing contact's gap on its own and, given its velocity
    ///   back after the rest, runs into nothing of the cluster: it keeps
    ///   that velocity. The eleventh revision's rest held every braking disc that
    ///   the pair's energy could not move beyond the gap, however fast it
    ///   slid: over the first 20,000 mixed boxes under the eighteenth, 7,543
    ///   rests held such a disc, 7,471 of them sliding faster than 1e-3 m/s,
    ///   in 1,637 boxes, up to 9.2 m/s (a disc that would have slid 14 m);
    ///   in mixed-box 142 an elastic disc (11.6 g, braking at 0.80 m/s^2)
    ///   leaving a row at 0.80 m/s was stopped dead (3.7 mJ) when a pair
    ///   of the row rested. A sliding disc that runs into a held one is
    ///   still held: freed, with its approach taken off, four of the first
    ///   100,000 mixed boxes ended stuck or at the event cap
    ///   (`Revision::leaves_sliding_discs_out_of_spent_rests`).
    /// - the pressing kick over a cluster (`World::press_closure`: every
    ///   pressed pair parting at its bounce speed, no other contact
    ///   approaching) is found by the active-set method where projected
    ///   Gauss–Seidel stalls on its biased contacts, as the ninth
    ///   revision finds a collapse's limit, instead of being given up
    ///   (given up, the hit left the pair as it was and it pressed again
    ///   at once), in clusters of up to fourteen discs: three pressed
    ///   pairs of mixed-box 6759 took turns for 4,750 pressed hits, 8,686
    ///   events to the horizon, now 93. Over whole plastic piles the
    ///   search was too slow (nine held-out piles over a second)
    ///   (`Revision::finds_stalled_cluster_kicks_by_active_set`).
    R19,
    /// The twentieth, as the nineteenth but:
    /// - a pressed pair coming to rest (`World::press_cluster`, its slide
    ///   within the pressing contact's gap), a disc of which brakes with a
    ///   pushed chain, whose plastic limit against its held discs stalls
    ///   projected Gauss–Seidel in every try, is found by the active-set
    ///   method (in clusters of up to `EXACT_KICK_CLUSTER` discs) instead
    ///   of being given up: given up, the hit gave the chain's disc its
    ///   own braking back, it ran into the disc it pushed and the chain
    ///   formed again, and the pressing disc ran into it again, at one
    ///   instant. A disc (35 g, braking at 4.1 m/s^2) on the floor pushing
    ///   a heavy one (0.48 kg, 78 m/s^2) at 8.3e-5 m/s, the two braking
    ///   together at 73 m/s^2, was pressed from above by a plastic disc
    ///   (1.3 g) whose rest over a cluster of eleven discs stalled: the
    ///   two pairs took turns, 19,974 of the last 20,000 events at 14.19
    ///   s, until the event cap (mixed-box 544105; to the 100 s horizon in
    ///   340 events). Taken for every stalled rest, it sent mixed-box
    ///   70365, whose resting pairs brake on their own, to `stuck`
    ///   (`Revision::finds_stalled_cluster_rests_by_active_set`).
    /// - a pair resting by its energy (`push::spent_within_gap`) whose
    ///   rest has no answer because a disc sliding along one obstacle into
    ///   the corner is wedged against a row lying along the other (its two
    ///   contacts nearly opposite, so that every solve stalls) has that
    ///   row carried as one body along its obstacle, as the sixteenth
    ///   revision carries one wedged disc (`wedge::carried_row_along_wall`,
    ///   `World::corner_jam`): the two stop together where the row's
    ///   friction spends the sliding disc's energy, or it pays that
    ///   friction at once and passes. A frictionless disc (20.7 g) on the
    ///   side wall 1.8e-8 m above a braking row on the floor, sliding down
    ///   at 2.7e-7 m/s (passing would cost 30 times its energy), was
    ///   kicked off each rest with the row at 1.4e-8 m/s, and the row's
    ///   pressed pairs hit every 4.7e-10 s, 19,945 of the last 20,000
    ///   events until `stuck` at 0.258 s (mixed-box 156823; to the 100 s
    ///   horizon in 342 events; discs passing rows 1.8e-9, 5.9e-10 and
    ///   4.0e-8 m below them in 157590, 371709 and 241710, `stuck` at 6.02,
    ///   0.274 and 0.0856 s, to the horizon in 1,402, 2,785 and 3,081
    ///   events) (`Revision::carries_rows_wedged_into_corners`).
    /// - the pressing kick over a cluster of more than fourteen discs (a
    ///   plastic pile) that projected Gauss–Seidel stalls on is found by the
    ///   active-set method with its pushing set's equalities kept as a
    ///   Cholesky factor, extended by a row as a contact joins and mended
    ///   by plane rotations as one leaves (`collapse::factored_active_set`),
    ///   instead of being given up: the nineteenth revision's search solved
    ///   every set afresh, 65 ms a search over a pile's 59 to 98 contacts,
    ///   and was bounded to fourteen discs. Struck plastic piles of 25 to
    ///   41 discs whose pressed pairs took turns (plastic-lines 113176:
    ///   21,085 events, 19,921 at one instant; fourteen such seeds of 3,000
    ///   to 24,133 events, or `stuck`, 0.9 to 5.1 s) end their rings in 2 to
    ///   35 events at one instant, each in under 0.05 s of CPU. At most
    ///   32 searches are made at one instant (`KICK_SEARCHES_PER_INSTANT`):
    ///   a ring the search cannot end paid one at every event
    ///   (plastic-lines 620478: 3,001 events at one instant, 2.5 s of CPU;
    ///   0.3 s bounded)
    ///   (`Revision::finds_large_cluster_kicks_by_factored_active_set`).
    /// - the plastic limit of a collapse over such a cluster is sought by
    ///   the projection within a pressing kick's sweeps, then by the
    ///   factored method; a ring's collapse stops there, a hit's tries the
    ///   full sweeps and the eliminating method after it. With the kicks
    ///   found, piles went on to collapses the projection stalls on, each
    ///   running its 10,000 sweeps (plastic-lines 32437: 1,293 events at
    ///   one instant, 9 s; 69441, 75314, 78612 over a second); now 7 to
    ///   195 events at one instant, at most 0.32 s. With both rules, one
    ///   of the first 100,000 plastic-lines fails (94329, 1.9 s of CPU, a
    ///   ring of 1,967 events at one instant; under the nineteenth, ten)
    ///   (`Revision::solves_large_collapses_by_factored_active_set`).
    #[default]
    R20,
}

impl Revision {
    /// The revision new computations use.
    pub const LATEST: Revision = Revision::R20;

    /// Every revision, oldest first.
    pub const ALL: [Revision; 20] = [
        Revision::R1,
        Revision::R2,
        Revision::R3,
        Revision::R4,
        Revision::R5,
        Revision::R6,
        Revision::R7,
        Revision::R8,
        Revision::R9,
        Revision::R10,
        Revision::R11,
        Revision::R12,
        Revision::R13,
        Revision::R14,
        Revision::R15,
        Revision::R16,
        Revision::R17,
        Revision::R18,
        Revision::R19,
        Revision::R20,
    ];

    /// Whether this revision has the second revision's rules.
    pub fn at_least_r2(self) -> bool {
        self >= Revision::R2
    }

    /// Whether this revision has the third revision's rules.
    pub fn at_least_r3(self) -> bool {
        self >= Revision::R3
    }

    /// Whether this revision has the fourth revision's rules.
    pub fn at_least_r4(self) -> bool {
        self >= Revision::R4
    }

    /// Whether this revision has the fifth revision's rules.
    pub fn at_least_r5(self) -> bool {
        self >= Revision::R5
    }

    /// Whether this revision has the sixth revision's rules.
    pub fn at_least_r6(self) -> bool {
        self >= Revision::R6
    }

    /// Whether this revision has the seventh revision's rules (its fine
    /// clock and its collapse rule for elastic clusters).
    pub fn at_least_r7(self) -> bool {
        self >= Revision::R7
    }

    /// Whether this revision has the eighth revision's rules (the crawl
    /// measured on the discs involved, and their rest).
    pub fn at_least_r8(self) -> bool {
        self >= Revision::R8
    }

    /// Whether this revision has the ninth revision's rules (a collapse's
    /// limit by the active-set method where the projection fails).
    pub fn at_least_r9(self) -> bool {
        self >= Revision::R9
    }

    /// Whether this revision has the tenth revision's rules (a collapse
    /// taken after fewer repeated hits at one instant, and elastic
    /// clusters with a disc braking to a stop taken as losing energy).
    pub fn at_least_r10(self) -> bool {
        self >= Revision::R10
    }

    /// Whether this revision has the eleventh revision's rules (a pressed
    /// pair with a frictionless disc in it brought to rest where its energy
    /// cannot move its braking discs beyond the approximation's gap).
    pub fn at_least_r11(self) -> bool {
        self >= Revision::R11
    }

    /// Whether this revision has the twelfth revision's rules.
    pub fn at_least_r12(self) -> bool {
        self >= Revision::R12
    }

    /// Whether this revision has the thirteenth revision's rules.
    pub fn at_least_r13(self) -> bool {
        self >= Revision::R13
    }

    /// Whether this revision has the fourteenth revision's rules.
    pub fn at_least_r14(self) -> bool {
        self >= Revision::R14
    }

    /// Whether this revision has the fifteenth revision's rules.
    pub fn at_least_r15(self) -> bool {
        self >= Revision::R15
    }

    /// Whether this revision has the sixteenth revision's rules.
    pub fn at_least_r16(self) -> bool {
        self >= Revision::R16
    }

    /// Whether this revision has the seventeenth revision's rules.
    pub fn at_least_r17(self) -> bool {
        self >= Revision::R17
    }

    /// Whether this revision has the eighteenth revision's rules.
    pub fn at_least_r18(self) -> bool {
        self >= Revision::R18
    }

    /// Whether this revision has the nineteenth revision's rules.
    pub fn at_least_r19(self) -> bool {
        self >= Revision::R19
    }

    /// Whether this revision has the twentieth revision's rules.
    pub fn at_least_r20(self) -> bool {
        self >= Revision::R20
    }

    /// Whether a ring of a touching cluster whose kinetic energy each of
    /// its braking discs would spend within the rounding of its position
    /// comes to rest, its braking discs held and its frictionless ones
    /// projected against them, instead of being taken to its plastic
    /// limit (a fifteenth revision rule, see `World::spent_ring_rest`).
    pub fn rests_spent_rings(self) -> bool {
        self.at_least_r15()
    }

    /// Whether a ring's rest by its spent energy (`World::spent_ring_rest`)
    /// weighs the energy the rest takes, what runs into its held braking
    /// discs, rather than all the kinetic energy of its discs (a
    /// seventeenth revision rule).
    pub fn rests_rings_spent_by_what_runs_into_them(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a plastic pair of discs hit a second time at one instant,
    /// every hit of it gentle, one of its discs hit by a third disc at that
    /// instant too, is taken at once as the instant's collapse, its
    /// plastic limit alone, instead of at the eighth hit of a pair and
    /// kicked (a sixteenth revision rule, see `limits::Repeats::squeezed`).
    pub fn collapses_rings_through_squeezed_discs(self) -> bool {
        self.at_least_r16()
    }

    /// Whether a plastic pair of discs one of which a third disc hit at
    /// the same instant, its approach shrinking by one ratio over its three
    /// latest hits, is taken at once as the instant's collapse, its
    /// plastic limit alone, gentle or not (a sixteenth revision rule, see
    /// `limits::Repeats::geometric`).
    pub fn collapses_geometric_rings_through_squeezed_discs(self) -> bool {
        self.at_least_r16()
    }

    /// Whether a ring that the sixteenth revision's geometric rule would
    /// take (`Revision::collapses_geometric_rings_through_squeezed_discs`)
    /// is left to its hits where it shrinks so fast a turn
    /// (`limits::FADING_RATIO`) that it falls below the rounding of its
    /// speeds within the count's hits (a seventeenth revision rule, see
    /// `limits::Repeats::lasting`).
    pub fn leaves_fading_rings_to_their_hits(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a plastic hit whose touching cluster, its hits played in
    /// memory, rings without end is taken at once as the plastic limit of
    /// the contacts that ring (a fourteenth revision rule, see
    /// `World::cluster_ring`).
    pub fn takes_cluster_rings_at_once(self) -> bool {
        self.at_least_r14()
    }

    /// Whether a pressing kick over a cluster adds no more than 0.01 of the
    /// scene's kinetic energy, twice what the kick between a pressed pair
    /// alone may add of the pair's (the twelfth revision; see
    /// `World::press_cluster`).
    pub fn bounds_cluster_kick_energy(self) -> bool {
        self.at_least_r12()
    }

    /// Whether the rest of a pressed pair's braking discs (the eleventh
    /// revision's held projection) is found by the active-set method where
    /// projected Gauss–Seidel stalls (the twelfth revision; see
    /// `World::press_cluster`).
    pub fn rests_caged_discs_by_active_set(self) -> bool {
        self.at_least_r12()
    }

    /// Whether a plastic pair hit at one instant again and again, each
    /// count of its hits slower than the last, is taken as a collapse
    /// however hard its hits (the twelfth revision; see
    /// `limits::Repeats::decaying`).
    pub fn collapses_decaying_plastic_rings(self) -> bool {
        self.at_least_r12()
    }

    /// Whether an elastic cluster with a braking disc, ringing at one
    /// instant or crawling while its contacts approach and part no faster
    /// than `limits::GENTLE` of its fastest disc, is taken to its plastic
    /// limit as an inelastic collapse is (the thirteenth revision; see
    /// `World::elastic_ring_rests`).
    pub fn collapses_resting_elastic_rings(self) -> bool {
        self.at_least_r13()
    }

    /// Whether the collapse of an instant's repeated inelastic hits also
    /// takes in the elastic pairs hit more than once at that instant (the
    /// thirteenth revision; see `limits::Repeats::with_elastic`).
    pub fn collapses_rings_with_elastic_pairs(self) -> bool {
        self.at_least_r13()
    }

    /// Whether a pair with restitution whose braking presses it together
    /// so hard that its bounce never leaves touching distance is taken as
    /// the end of its chatter, one plastic hit (the thirteenth revision;
    /// see `push::bounces_within_touch`).
    pub fn ends_bounces_within_touch(self) -> bool {
        self.at_least_r13()
    }

    /// Whether a plastic hit that drives a light plastic disc into an
    /// obstacle it touches, the pair touching no other disc, is taken as
    /// one plastic limit with that obstacle, however hard (a thirteenth
    /// revision rule, see `World::walled_hit`).
    pub fn takes_walled_hit_with_wall(self) -> bool {
        self.at_least_r13()
    }

    /// Whether the pressing kick that follows a collapse's plastic limit
    /// (`World::take_plastic_limit`) adds no more than 0.01 of the scene's
    /// kinetic energy over the limit, as the twelfth revision holds a
    /// pressing kick over a cluster (a fourteenth revision rule, see
    /// `within_press_bound`).
    pub fn bounds_collapse_kick_energy(self) -> bool {
        self.at_least_r14()
    }

    /// Whether a gentle plastic hit on a light plastic disc lying in a
    /// corner is taken as one plastic limit with the walls it touches and
    /// the discs pressing on it (a twelfth revision rule, see
    /// `World::cornered_hit`).
    pub fn takes_cornered_hit_with_walls(self) -> bool {
        self.at_least_r12()
    }

    /// Whether a disc that wedges a harder-braked one aside as it slides
    /// past, held to its line by something else it touches, takes it along
    /// as one sliding body to their common stop (a fourteenth revision
    /// rule, see `push::carried`).
    pub fn carries_wedged_discs(self) -> bool {
        self.at_least_r14()
    }

    /// Whether a disc that wedges a harder-braked one aside while it slides
    /// along the one obstacle it touches, the hit driving it into that
    /// obstacle, takes the hit with the obstacle and carries the other
    /// along as the fourteenth revision carries a wedged disc (a fifteenth
    /// revision rule, see `World::hit_along_wall`).
    pub fn carries_along_walls(self) -> bool {
        self.at_least_r15()
    }

    /// Whether a plastic hit that drives a disc into an obstacle it
    /// touches, the two then ringing between the obstacle and each other,
    /// is taken at once as one plastic limit with the obstacles (a
    /// thirteenth revision rule, see `World::hit_into_wall`).
    pub fn takes_hit_into_wall_with_wall(self) -> bool {
        self.at_least_r13()
    }

    /// Whether a hit taken as a chatter's end (one plastic hit of a pair
    /// with restitution) that drives a disc into an obstacle it touches,
    /// the two then ringing between the obstacle and each other, is taken
    /// at once as one plastic limit with the obstacles, their own contact
    /// with them (a fourteenth revision rule, see `World::hit_into_wall`).
    pub fn takes_captured_hit_into_wall_with_wall(self) -> bool {
        self.at_least_r14()
    }

    /// Whether a gentle plastic hit (its approach within `limits::GENTLE`
    /// of the faster disc's speed) that drives a plastic disc into an
    /// obstacle it touches, the disc then coming back into its partner, is
    /// taken at once as one plastic limit with the obstacles, however fast
    /// the ring would fade (a fourteenth revision rule, see
    /// `World::hit_into_wall`).
    pub fn takes_gentle_hit_into_wall_with_wall(self) -> bool {
        self.at_least_r14()
    }

    /// Whether a gentle plastic hit that drives an elastic disc into an
    /// obstacle it touches, the disc bouncing back into its partner, is
    /// taken at once as one plastic limit with the obstacles, as the
    /// fourteenth revision takes one on a plastic disc, where the limit
    /// drives none of its discs into a disc outside it (a sixteenth
    /// revision rule, see `World::hit_into_wall` and
    /// `World::drives_into_others`).
    pub fn takes_gentle_hit_on_elastic_disc_into_wall(self) -> bool {
        self.at_least_r16()
    }

    /// Whether the plastic limit of a ring (`World::cluster_ring`,
    /// `World::hit_into_wall`) takes in the obstacles its discs touch that
    /// the limit of the ringing contacts alone would drive them into (a
    /// fifteenth revision rule, see `world::reached_walls`).
    pub fn takes_ring_limits_with_walls_they_reach(self) -> bool {
        self.at_least_r15()
    }

    /// Whether a disc carried aside by one sliding along a wall
    /// (`push::carried`) is taken with the wall holding the pushing disc
    /// to its line through the hit, where the hit would drive it into the
    /// wall (a fifteenth revision rule, see `World::hit_along_wall`).
    pub fn carries_wedged_discs_along_walls(self) -> bool {
        self.at_least_r15()
    }

    /// Whether a disc carried aside by one sliding past it
    /// (`push::carried`) while it lies against the one obstacle it
    /// touches is carried along that obstacle, which holds it to its line
    /// (a sixteenth revision rule, see `wedge::carried_along_wall` and
    /// `World::wedged_along_wall`).
    pub fn carries_wedged_discs_along_their_walls(self) -> bool {
        self.at_least_r16()
    }

    /// Whether an elastic pair pressed head-on whose bounces stay within
    /// the pressing contact's gap and would number at least
    /// `push::LONG_BOUNCES` before it stops is taken as the end of its
    /// chatter, one plastic hit (a fifteenth revision rule, see
    /// `push::bounces_long_within_gap`).
    pub fn ends_long_bounces_within_gap(self) -> bool {
        self.at_least_r15()
    }

    /// Whether a plastic hit into a wall that rings (`World::hit_into_wall`)
    /// and whose discs have no more kinetic energy than the friction of each
    /// of their braking discs does over the rounding of its position comes
    /// to rest, as the fifteenth revision rests a spent cluster's ring (a
    /// sixteenth revision rule, see `World::spent_ring_rest`).
    pub fn rests_spent_hits_into_walls(self) -> bool {
        self.at_least_r16()
    }

    /// Whether a pair resting by its energy (`push::spent_within_gap`)
    /// whose plastic limit against its held braking discs stalls the
    /// projection on no more contacts than its free discs have directions
    /// is solved by the active-set method (a sixteenth revision rule, see
    /// `World::press_cluster`).
    pub fn rests_wedged_spent_pairs(self) -> bool {
        self.at_least_r16()
    }

    /// Whether a pair resting by its energy (`push::spent_within_gap`)
    /// rests where its hit leaves it neither pressed nor parted, as the
    /// eleventh revision rests one pressed or parted (a seventeenth
    /// revision rule, see `World::press_cluster`).
    pub fn rests_spent_pairs_left_as_they_were(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a pushing disc carried aside (`push::carried`) that touches
    /// no wall but slides past a disc at rest pinned by its walls against
    /// the push is held to that disc's tangent through the hit, as the
    /// fifteenth revision holds one sliding along a wall (a sixteenth
    /// revision rule, see `World::pinning_disc` and
    /// `push::plastic_along_wall`).
    pub fn holds_pushers_on_pinned_discs(self) -> bool {
        self.at_least_r16()
    }

    /// Whether a touching pair that parts so slowly that its braking
    /// brings it back into contact within the rounding of the time is
    /// taken as the pushed pair it is at its hit, its normal velocities
    /// made one (a seventeenth revision rule, see `push::rejoined_at_once`).
    pub fn rejoins_pairs_parting_within_instant(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a pair resting by its energy (`push::spent_within_gap`)
    /// whose free disc the held projection leaves running into its held
    /// partner, below the projection's tolerance, has that approach taken
    /// off against the held disc (a seventeenth revision rule, see
    /// `World::press_cluster`).
    pub fn rests_free_disc_on_held_partner(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a pushed disc carried aside (`push::carried`) that the push
    /// drives into a braking disc at rest, whose friction holds it, is
    /// carried round that disc (a seventeenth revision rule, see
    /// `World::carried_around_held` and `pivot::carried_around`).
    pub fn carries_discs_round_held_discs(self) -> bool {
        self.at_least_r17()
    }

    /// Whether a disc carried along the one obstacle it touches by one
    /// sliding past it (`wedge::carried_along_wall`) is so carried where
    /// the pushing disc is held to its line by the one obstacle it slides
    /// along, as by a disc it touches (an eighteenth revision rule, see
    /// `World::held_on_own_wall` and `World::wedged_along_wall`).
    pub fn carries_wedged_discs_between_walls(self) -> bool {
        self.at_least_r18()
    }

    /// Whether an elastic hit of two frictionless discs that drives one
    /// of them into an obstacle it touches, the two then ringing between
    /// the obstacle and each other, is played to the ring's end at once (an
    /// eighteenth revision rule, see `World::elastic_wall_ring` and
    /// `ring::elastic_end`).
    pub fn plays_elastic_wall_rings_at_once(self) -> bool {
        self.at_least_r18()
    }

    /// Whether a hit that leaves both its discs at rest (their slides
    /// below the rounding of their positions) stops the discs touching
    /// them that run into them, the plastic limit with the pair held (a
    /// seventeenth revision rule, see `World::settled_hit`).
    pub fn stops_discs_running_into_settled_hits(self) -> bool {
        self.at_least_r17()
    }

    /// Whether the discs a settled hit stops (see
    /// `Revision::stops_discs_running_into_settled_hits`) take in, too,
    /// a disc that runs into one of them only once it is stopped (an
    /// eighteenth revision rule, see `World::settled_hit`).
    pub fn stops_discs_running_into_stopped_discs(self) -> bool {
        self.at_least_r18()
    }

    /// Whether a braking disc that the pressing kick after a plastic limit
    /// sets moving so slowly that it stops within the rounding of its
    /// position is held by its friction instead, the limit solved again
    /// with it still and no kick (an eighteenth revision rule, see
    /// `World::held_against_kick`).
    pub fn holds_discs_kicks_cannot_move(self) -> bool {
        self.at_least_r18()
    }

    /// Whether a touching pair whose straight relative path closes in by
    /// no more than the rounding of its positions before it parts is a
    /// graze, not a contact: no hit predicted for a disc moving against
    /// one at rest (`contact::disc_point`), and the ring of a plastic hit
    /// (`World::cluster_ring`) played without it where it approaches
    /// beyond the ring's noise (an eighteenth revision rule, see
    /// `graze::within_rounding`).
    pub fn passes_grazes_within_rounding(self) -> bool {
        self.at_least_r18()
    }

    /// Whether a hit whose pushing disc slides along the one obstacle it
    /// touches and wedges a braking disc aside is carried
    /// (`World::carried_press`) before it is taken as a ring into that
    /// obstacle (a nineteenth revision rule, see `World::collide`).
    pub fn carries_wedges_before_wall_rings(self) -> bool {
        self.at_least_r19()
    }

    /// Whether a pair resting by its energy (`push::spent_within_gap`)
    /// gives back, after its rest, their velocities to the braking discs
    /// of its cluster that slide beyond the pressing contact's gap on
    /// their own and then run into nothing of the cluster, instead of
    /// holding them with the pair (a nineteenth revision rule, see
    /// `World::press_cluster`).
    pub fn leaves_sliding_discs_out_of_spent_rests(self) -> bool {
        self.at_least_r19()
    }

    /// Whether the pressing kick over a cluster (`World::press_closure`)
    /// is found by the active-set method where projected Gauss–Seidel
    /// stalls on its biased contacts, instead of being given up, in
    /// clusters of up to `EXACT_KICK_CLUSTER` discs (a nineteenth revision
    /// rule, see `World::press_cluster`).
    pub fn finds_stalled_cluster_kicks_by_active_set(self) -> bool {
        self.at_least_r19()
    }

    /// Whether a pressed pair coming to rest (`World::press_cluster`), a
    /// disc of which brakes with a pushed chain, whose plastic limit
    /// against its held discs stalls projected Gauss–Seidel in every try
    /// is found by the active-set method, the tries taken in the same
    /// order, in clusters of up to `EXACT_KICK_CLUSTER` discs, instead of
    /// being given up: given up, the hit gives that disc its own braking
    /// back and the chain forms again at once (a twentieth revision rule,
    /// see `World::press_cluster`).
    pub fn finds_stalled_cluster_rests_by_active_set(self) -> bool {
        self.at_least_r20()
    }

    /// Whether a pair resting by its energy whose rest has no answer,
    /// a disc sliding along one obstacle into the corner wedging a row
    /// along the other, has that row carried as one body
    /// (`wedge::carried_row_along_wall`) instead of kicked (a twentieth
    /// revision rule, see `World::corner_jam`).
    pub fn carries_rows_wedged_into_corners(self) -> bool {
        self.at_least_r20()
    }

    /// Whether the pressing kick over a cluster of more than
    /// `EXACT_KICK_CLUSTER` discs that projected Gauss–Seidel stalls on is
    /// found by the active-set method with its set's equalities kept
    /// factored (`collapse::factored_active_set`), instead of being given
    /// up (a twentieth revision rule, see `World::press_closure`).
    pub fn finds_large_cluster_kicks_by_factored_active_set(self) -> bool {
        self.at_least_r20()
    }

    /// Whether the plastic limit of a collapse over a cluster of more than
    /// `EXACT_KICK_CLUSTER` discs is sought by projected Gauss–Seidel
    /// within a pressing kick's sweeps (`PRESS_SWEEPS`), then by the
    /// factored active-set method (`collapse::factored_active_set`), and
    /// only for a hit's collapse (not a ring's) by the projection's full
    /// sweeps and the eliminating method after it (a twentieth revision
    /// rule, see `World::collapse_contacts_kicked`).
    pub fn solves_large_collapses_by_factored_active_set(self) -> bool {
        self.at_least_r20()
    }
}

/// A revision name that names no revision.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no engine revision named {0:?} (r1, r2, ...)")]
pub struct UnknownRevision(pub String);

impl std::str::FromStr for Revision {
    type Err = UnknownRevision;

    /// A revision by its name in records and on command lines (`r1`, `r2`,
    /// ...).
    fn from_str(name: &str) -> Result<Revision, UnknownRevision> {
        serde_json::from_value(serde_json::Value::String(name.to_owned()))
            .map_err(|_| UnknownRevision(name.to_owned()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_revision_parses_from_its_record_name_and_nothing_else() {
        for (k, r) in Revision::ALL.into_iter().enumerate() {
            assert_eq!(format!("r{}", k + 1).parse(), Ok(r));
        }
        let err = "r21".parse::<Revision>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "no engine revision named \"r21\" (r1, r2, ...)"
        );
    }
}
