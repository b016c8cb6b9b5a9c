//! The lease rules: who plays a match, when a node renews, when it must
//! count its leases as lost, when it looks for matches to take over, and
//! when a proxy's match has moved. Each is a decision on what the node
//! knows at `now` (the answers of its last queries, the time of its last
//! renewal), without I/O: the node's queries and its lease-keeping and
//! proxy tasks act on them, and the tests here
//! run them on a virtual clock.

use std::collections::{HashMap, HashSet};
use std::time::Duration;
use tokio::time::Instant;

/// Who holds a match's lease.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Lease {
    /// This node, now.
    Ours,
    /// Another node, unexpired (an empty name: nobody, as the match does
    /// not exist or its lease expired between two queries; the caller
    /// finds no match, or tries again).
    Theirs(String),
}

impl Lease {
    /// Who holds a lease this node could not take, from the unexpired
    /// holder its query found (if any).
    pub fn held_by(holder: Option<String>) -> Lease {
        Lease::Theirs(holder.unwrap_or_default())
    }
}

/// How often a node renews its leases: three times a lease, so one or two
/// failed renewals still leave it holding them.
pub fn renew_every(lease: Duration) -> Duration {
    lease / 3
}

/// How long one of the node's queries on the leases may wait for a
/// PostgreSQL connection (and take to connect) before it counts as
/// failed: a third of a lease (at least a quarter second, at most ten),
/// so that while PostgreSQL is down a renewal fails in time for the node
/// to stop its rooms before its leases can expire, and so that the pool,
/// which tries again after at most half this wait, has its connections
/// back within a sixth of a lease of PostgreSQL's return.
pub fn db_wait(lease: Duration) -> Duration {
    renew_every(lease).clamp(Duration::from_millis(250), Duration::from_secs(10))
}

/// How often a node looks for orphaned matches: every second, or every
/// half lease if that is shorter (a dead node's match is taken within a
/// lease and a second of its death).
pub fn look_for_orphans_every(lease: Duration) -> Duration {
    (lease / 2).min(Duration::from_secs(1))
}

/// Of the matches `asked` to be renewed, those whose lease the renewal
/// did not `kept`: this node lost them (another took them over) and must
/// stop their rooms.
pub fn lost(asked: &[String], kept: &HashSet<String>) -> Vec<String> {
    asked
        .iter()
        .filter(|id| !kept.contains(*id))
        .cloned()
        .collect()
}

/// Of the nodes `asked` about, those not among the `alive` (seen within a
/// lease): dead.
pub fn dead(asked: &[String], alive: &HashSet<String>) -> Vec<String> {
    asked
        .iter()
        .filter(|n| !alive.contains(*n))
        .cloned()
        .collect()
}

/// A node's renewals of its leases, on its clock: while renewals fail,
/// how long it may still count on holding its leases.
#[derive(Clone, Copy, Debug)]
pub struct Renewal {
    lease: Duration,
    /// When the last renewal succeeded (or the node started).
    renewed: Instant,
}

impl Renewal {
    /// Leases of length `lease`, as good as renewed at `now`.
    pub fn new(lease: Duration, now: Instant) -> Renewal {
        Renewal {
            lease,
            renewed: now,
        }
    }

    /// A renewal begun at `now` succeeded (its leases run from when it
    /// reached PostgreSQL, no earlier than this).
    pub fn renewed(&mut self, now: Instant) {
        self.renewed = self.renewed.max(now);
    }

    /// When the leases must count as lost if no renewal succeeds before:
    /// four fifths of a lease after the last success. The node stops its
    /// rooms then, even while a renewal is still waiting on PostgreSQL.
    pub fn deadline(&self) -> Instant {
        self.renewed + self.lease * 4 / 5
    }

    /// A renewal failed at `now`: `true` when the last success is more
    /// than four fifths of a lease ago, so the node can no longer be sure
    /// it holds any lease and stops all its rooms (before another node
    /// may take them over, at a whole lease).
    pub fn failed(&self, now: Instant) -> bool {
        now.saturating_duration_since(self.renewed) > self.lease * 4 / 5
    }
}

/// Of this node's proxy rooms (`current`: match, proxy number, the node
/// it relays to), those that have moved: asked about in the last check
/// (`asked`: match and proxy number; a newer proxy waits for the next
/// check) and whose match's unexpired lease (`owners`) is not held by the
/// node they relay to (expired, or taken by another).
pub fn moved<'a>(
    current: impl IntoIterator<Item = (&'a String, u64, &'a str)>,
    asked: &HashMap<String, u64>,
    owners: &HashMap<String, String>,
) -> Vec<String> {
    current
        .into_iter()
        .filter(|(id, number, _)| asked.get(*id) == Some(number))
        .filter(|(id, _, owner)| owners.get(*id).map(String::as_str) != Some(*owner))
        .map(|(id, _, _)| id.clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const LEASE: Duration = Duration::from_millis(3_000);

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    fn ids(names: &[&str]) -> Vec<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    fn set(names: &[&str]) -> HashSet<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn a_lease_is_renewed_three_times_a_lease_and_orphans_are_sought_at_least_every_second() {
        assert_eq!(renew_every(LEASE), ms(1_000));
        assert_eq!(look_for_orphans_every(LEASE), ms(1_000));
        assert_eq!(look_for_orphans_every(ms(1_000)), ms(500));
        assert_eq!(look_for_orphans_every(ms(60_000)), ms(1_000));
    }

    #[test]
    fn while_renewals_fail_the_leases_count_as_held_for_four_fifths_of_a_lease() {
        let t0 = Instant::now();
        let mut r = Renewal::new(LEASE, t0);
        assert!(!r.failed(t0 + ms(1_000)));
        assert!(!r.failed(t0 + ms(2_400)), "exactly four fifths still holds");
        assert!(r.failed(t0 + ms(2_401)));
        // A success starts the count again.
        r.renewed(t0 + ms(2_000));
        assert!(!r.failed(t0 + ms(4_000)));
        assert!(r.failed(t0 + ms(4_401)));
    }

    #[test]
    fn the_leases_count_as_lost_just_after_the_deadline_and_a_late_success_moves_it_on() {
        let t0 = Instant::now();
        let mut r = Renewal::new(LEASE, t0);
        assert_eq!(r.deadline(), t0 + ms(2_400));
        assert!(!r.failed(r.deadline()));
        assert!(r.failed(r.deadline() + ms(1)));
        r.renewed(t0 + ms(1_000));
        assert_eq!(r.deadline(), t0 + ms(3_400));
        // A renewal begun earlier that answers later never moves it back.
        r.renewed(t0 + ms(500));
        assert_eq!(r.deadline(), t0 + ms(3_400));
    }

    #[test]
    fn a_query_on_the_leases_waits_a_third_of_a_lease_for_postgresql_within_bounds() {
        assert_eq!(db_wait(LEASE), ms(1_000));
        assert_eq!(db_wait(ms(2_000)), ms(2_000) / 3);
        assert_eq!(db_wait(ms(300)), ms(250));
        assert_eq!(db_wait(ms(600_000)), ms(10_000));
        // Shorter than the time a node may go without renewing.
        assert!(db_wait(LEASE) < LEASE * 4 / 5);
    }

    #[test]
    fn a_node_gives_up_its_leases_before_another_may_take_them() {
        let t0 = Instant::now();
        let r = Renewal::new(LEASE, t0);
        // Another node takes an expired lease: a whole lease after the
        // last renewal at the earliest. By then this node stopped.
        let first_give_up = (0..=LEASE.as_millis() as u64)
            .find(|&n| r.failed(t0 + ms(n)))
            .unwrap();
        assert!(ms(first_give_up) < LEASE);
    }

    #[test]
    fn a_clock_read_before_the_last_renewal_is_not_a_failure() {
        let t0 = Instant::now();
        let r = Renewal::new(LEASE, t0 + ms(500));
        assert!(!r.failed(t0));
    }

    #[test]
    fn the_matches_a_renewal_did_not_keep_are_lost() {
        let asked = ids(&["m1", "m2", "m3"]);
        assert_eq!(lost(&asked, &set(&["m1", "m3"])), ids(&["m2"]));
        assert!(lost(&asked, &set(&["m1", "m2", "m3"])).is_empty());
        assert_eq!(lost(&asked, &set(&[])), asked);
        assert!(lost(&[], &set(&["m1"])).is_empty());
    }

    #[test]
    fn the_nodes_not_seen_within_a_lease_are_dead() {
        let asked = ids(&["a", "b"]);
        assert_eq!(dead(&asked, &set(&["a"])), ids(&["b"]));
        assert!(dead(&asked, &set(&["a", "b"])).is_empty());
    }

    #[test]
    fn a_lease_this_node_could_not_take_belongs_to_its_holder_or_to_nobody() {
        assert_eq!(Lease::held_by(Some("b".into())), Lease::Theirs("b".into()));
        assert_eq!(Lease::held_by(None), Lease::Theirs(String::new()));
    }

    #[test]
    fn a_proxy_moved_when_its_node_no_longer_holds_the_lease_and_a_newer_proxy_waits() {
        let (m1, m2, m3, m4) = (
            "m1".to_string(),
            "m2".to_string(),
            "m3".to_string(),
            "m4".to_string(),
        );
        let current = [
            (&m1, 1, "a"), // still a's
            (&m2, 2, "a"), // taken by b
            (&m3, 3, "a"), // expired: nobody's
            (&m4, 9, "a"), // a newer proxy than the one asked about
        ];
        let asked: HashMap<String, u64> = [("m1", 1), ("m2", 2), ("m3", 3), ("m4", 4)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        let owners: HashMap<String, String> = [("m1", "a"), ("m2", "b")]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        let mut moved = moved(current, &asked, &owners);
        moved.sort();
        assert_eq!(moved, ids(&["m2", "m3"]));
    }
}
