//! The faults a cluster of nodes must survive, each scripted end to end
//! with real processes: two server nodes on PostgreSQL and Redis started
//! for the test, one match played by node A, White connected to A and
//! Black through B (relayed). Three shots are acknowledged, then:
//!
//! - Redis is stopped for longer than a lease and started again (empty);
//! - PostgreSQL is stopped and started again;
//! - node A is frozen (SIGSTOP) for two leases and then continued: it
//!   must not write after losing its lease, and its clients move;
//! - node A alone loses Redis (its connection goes through a link the test
//!   cuts), while B and PostgreSQL stay reachable.
//!
//! Each time, White also shoots into the fault. Afterwards both players
//! find the match again (on whichever node answers), play a shot and end
//! it, and the verdict is checked and printed: every shot acknowledged to
//! a player (a `shot-played` it received) is in the match's record,
//! unchanged; the match resumed; and how long it took. A fault test takes
//! 10 to 30 s; they run one at a time. Run them with the verdicts shown:
//!
//! ```sh
//! cargo test -p server --test cluster_faults -- --nocapture
//! ```
//!
//! Skipped (with a note) where the machine has no PostgreSQL or Redis,
//! unless `CHAPAEV_REQUIRE_POSTGRES` / `CHAPAEV_REQUIRE_REDIS` say they
//! must be there.

mod common;

use common::cluster::{
    node, private_postgres, private_redis, reconnect, reconnect_any, record, three_shots, LEASE,
};
use common::{shot, view, Client, Server};
use game::outcome::ShotOutcome;
use game::protocol::{ClientMessage, ServerMessage};
use game::{MatchView, Seat, Side};
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

/// One fault test at a time: each runs several processes and measures
/// how long recovery takes.
static ONE_AT_A_TIME: tokio::sync::Mutex<()> = tokio::sync::Mutex::const_new(());

/// The shots acknowledged to the players: `shot-played` messages they
/// received, by shot number.
#[derive(Default)]
struct Ledger(BTreeMap<u32, ShotOutcome>);

impl Ledger {
    /// Notes every shot `client` was told of (call before replacing it).
    fn take(&mut self, client: &Client) {
        for text in &client.received {
            if let Ok(ServerMessage::ShotPlayed { outcome, .. }) = ServerMessage::from_json(text) {
                let known = self.0.entry(outcome.number).or_insert(outcome.clone());
                assert_eq!(*known, outcome, "two outcomes acknowledged for one shot");
            }
        }
    }

    /// The acknowledged shots missing from `record`, or different there.
    fn lost_in(&self, record: &game::MatchRecord) -> usize {
        let stored: BTreeMap<u32, &ShotOutcome> = record
            .moves
            .iter()
            .filter_map(|m| match m {
                game::RecordedMove::Shot(o) => Some((o.number, o)),
                _ => None,
            })
            .collect();
        self.0
            .iter()
            .filter(|(n, o)| stored.get(*n) != Some(o))
            .count()
    }
}

/// A match played on `a`, White connected to `a` and Black through `b`,
/// after three shots acknowledged to both: (id, White's token, Black's
/// token, White, Black). White is to shoot.
async fn opening(a: &Server, b: &Server) -> (String, String, String, Client, Client) {
    let (id, white_token, black_token) = a.two_player_match("").await;
    let mut white = a.ws(&id, Some(&white_token)).await;
    let mut black = b.ws(&id, Some(&black_token)).await;
    view(white.next().await);
    view(black.next().await);
    // White knocks a piece off and shoots again, then passes the turn;
    // Black answers.
    three_shots(&mut white, &mut black).await;
    (id, white_token, black_token, white, black)
}

/// Reads `client` for up to `within` (or until its connection ends), so
/// that whatever it was sent is in its `received`.
async fn drain(client: &mut Client, within: Duration) {
    let _ = tokio::time::timeout(within, client.closes()).await;
}

/// Plays one gentle shot by the side to move in `view` (White or Black,
/// whoever that is), and waits until the other player sees it.
async fn one_more_shot(white: &mut Client, black: &mut Client, view: &MatchView) {
    let white_side = Seat::First.side(view.swapped);
    let (shooter, other) = if view.turn == white_side {
        (white, black)
    } else {
        (black, white)
    };
    let piece = view
        .board
        .of(view.turn)
        .next()
        .expect("a piece to shoot")
        .id;
    let vy = if view.turn == Side::White { 0.3 } else { -0.3 };
    shooter
        .send(&ClientMessage::Shot {
            piece,
            velocity: glam::DVec2::new(0.0, vy),
        })
        .await;
    let ServerMessage::ShotPlayed { outcome, .. } = other.next_of("shot-played").await else {
        unreachable!()
    };
    assert_eq!(outcome.number, view.shots, "the next shot after the state");
}

/// After the fault: both players find the match again (trying `nodes` in
/// turn), play one more shot, and Black resigns. Returns the time it took
/// both to have the match back, and checks and prints the verdict.
#[allow(clippy::too_many_arguments)]
async fn resume_and_judge(
    fault: &str,
    nodes: &[&Server],
    id: &str,
    tokens: (&str, &str),
    mut ledger: Ledger,
    since: Instant,
) -> Duration {
    let (mut white, white_view) = reconnect_any(nodes, id, tokens.0).await;
    let (mut black, black_view) = reconnect_any(nodes, id, tokens.1).await;
    let recovered = since.elapsed();
    assert_eq!(white_view, black_view, "both players see one match");
    assert!(
        white_view.shots as usize >= ledger.0.len(),
        "the match came back with {} shots, {} were acknowledged",
        white_view.shots,
        ledger.0.len()
    );
    one_more_shot(&mut white, &mut black, &white_view).await;
    black.send(&ClientMessage::Resign).await;
    white.next_of("match-over").await;
    ledger.take(&white);
    ledger.take(&black);
    let record = record(nodes[0], id).await;
    let replay = game::Replay::new(record.clone()).expect("the record replays");
    assert!(replay.game().result().is_some(), "the match ended");
    let lost = ledger.lost_in(&record);
    println!(
        "fault: {fault}: acknowledged shots lost: {lost} of {}; matches not resuming: 0 of 1; \
         both players back {:.2} s after the fault began (lease {LEASE} s)",
        ledger.0.len(),
        recovered.as_secs_f64()
    );
    assert_eq!(lost, 0, "acknowledged shots lost");
    recovered
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_redis_restart_mid_play_loses_no_acknowledged_shot_and_the_match_resumes() {
    let _one = ONE_AT_A_TIME.lock().await;
    let test = "fault_redis_restart";
    let Some(db) =
        tokio::task::block_in_place(|| local_services::local_postgres::shared_database(test))
    else {
        return;
    };
    let Some(mut redis) = private_redis(test) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let a = node(dir.path(), &db, &redis.url(), "a");
    let b = node(dir.path(), &db, &redis.url(), "b");
    let (id, wt, bt, mut white, mut black) = opening(&a, &b).await;
    let mut ledger = Ledger::default();

    let began = Instant::now();
    tokio::task::block_in_place(|| redis.stop());
    // White's node still reaches PostgreSQL: the shot may be played (and
    // then it must be kept) until the node gives its leases up.
    white.send(&shot(3, 0.0, 0.5)).await;
    // Down for longer than a lease: every node lets its leases go.
    let down = Duration::from_secs(LEASE + 1);
    drain(&mut white, down).await;
    tokio::time::sleep(down.saturating_sub(began.elapsed())).await;
    tokio::task::block_in_place(|| redis.start_again()).expect("Redis starts again");
    let back = began.elapsed();
    drain(&mut black, Duration::from_millis(100)).await;
    ledger.take(&white);
    ledger.take(&black);
    let took = resume_and_judge("Redis restarted", &[&b, &a], &id, (&wt, &bt), ledger, began).await;
    println!(
        "fault: Redis restarted: down {:.2} s; play back {:.2} s after Redis was",
        back.as_secs_f64(),
        (took - back).as_secs_f64()
    );
    assert!(took - back < Duration::from_secs(2 * LEASE + 2), "{took:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_postgresql_restart_mid_play_loses_no_acknowledged_shot_and_the_match_resumes() {
    let _one = ONE_AT_A_TIME.lock().await;
    let test = "fault_postgres_restart";
    let Some((mut pg, db)) = private_postgres(test) else {
        return;
    };
    let Some(redis) = tokio::task::block_in_place(|| local_services::local_redis::shared(test))
    else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let a = node(dir.path(), &db, &redis.url(), "pg-a");
    let b = node(dir.path(), &db, &redis.url(), "pg-b");
    let (id, wt, bt, mut white, mut black) = opening(&a, &b).await;
    let mut ledger = Ledger::default();

    let began = Instant::now();
    tokio::task::block_in_place(|| pg.stop());
    // The shot cannot be stored: it must be refused, not acknowledged.
    white.send(&shot(3, 0.0, 0.5)).await;
    let down = Duration::from_secs(LEASE);
    drain(&mut white, down).await;
    tokio::time::sleep(down.saturating_sub(began.elapsed())).await;
    tokio::task::block_in_place(|| pg.start_again()).expect("PostgreSQL starts again");
    let back = began.elapsed();
    drain(&mut black, Duration::from_millis(100)).await;
    ledger.take(&white);
    ledger.take(&black);
    let took = resume_and_judge(
        "PostgreSQL restarted",
        &[&a, &b],
        &id,
        (&wt, &bt),
        ledger,
        began,
    )
    .await;
    println!(
        "fault: PostgreSQL restarted: down {:.2} s; play back {:.2} s after PostgreSQL was",
        back.as_secs_f64(),
        (took - back).as_secs_f64()
    );
    assert!(took - back < Duration::from_secs(2 * LEASE + 2), "{took:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_node_frozen_past_its_lease_writes_nothing_after_it_and_its_clients_move() {
    let _one = ONE_AT_A_TIME.lock().await;
    let test = "fault_frozen_node";
    let Some((db, redis)) = common::cluster::services(test) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut a = node(dir.path(), &db, &redis, "frozen-a");
    let b = node(dir.path(), &db, &redis, "frozen-b");
    let (id, wt, bt, mut white, mut black) = opening(&a, &b).await;
    let mut ledger = Ledger::default();
    ledger.take(&white);
    ledger.take(&black);

    a.signal("STOP");
    let began = Instant::now();
    // Into the frozen node: when it runs again its lease is gone, so this
    // shot must never be stored nor acknowledged.
    white.send(&shot(3, 0.0, 0.7)).await;
    // Black's connection through B ends once A's lease expires; both
    // players find the match on B (A does not answer).
    assert!(black.closes().await);
    let (mut black, state) = reconnect(&b, &id, &bt).await;
    assert_eq!(state.shots, 3);
    let (mut white_on_b, again) = reconnect(&b, &id, &wt).await;
    assert_eq!(again, state);
    let recovered = began.elapsed();
    // Thawed after two leases: its room learns the lease is lost.
    let freeze = Duration::from_secs(2 * LEASE);
    tokio::time::sleep(freeze.saturating_sub(began.elapsed())).await;
    a.signal("CONT");
    // White's old connection to A is refused or closed, never told of a
    // shot after the three before the freeze.
    drain(&mut white, Duration::from_secs(2 * LEASE)).await;
    let told_after = white.received.iter().any(|m| {
        matches!(ServerMessage::from_json(m),
            Ok(ServerMessage::ShotPlayed { outcome, .. }) if outcome.number >= 3)
    });
    assert!(
        !told_after,
        "the frozen node acknowledged a shot after losing its lease"
    );
    assert!(a.running(), "the thawed node lives on");
    // B plays shot 3, White's from B: had A written its shot 3, this
    // write would fail on the stored one.
    white_on_b.send(&shot(3, 0.0, 0.5)).await;
    let ServerMessage::ShotPlayed { outcome, .. } = black.next_of("shot-played").await else {
        unreachable!()
    };
    assert_eq!((outcome.number, outcome.aimed.y), (3, 0.5));
    ledger.take(&white);
    ledger.take(&white_on_b);
    ledger.take(&black);
    assert_eq!(reconnect(&b, &id, &bt).await.1.shots, 4);
    // The thawed node plays the match no more: it relays to B.
    let (status, metrics) = a.http("GET", "/metrics", "").await;
    assert_eq!(status, 200);
    assert!(
        metrics.contains("chapaev_cluster_matches_owned 0"),
        "the thawed node still plays a match"
    );
    let took = resume_and_judge(
        "node frozen (SIGSTOP) for two leases",
        &[&a, &b],
        &id,
        (&wt, &bt),
        ledger,
        began,
    )
    .await;
    println!(
        "fault: node frozen: both players on the other node {:.2} s after the freeze \
         (lease {LEASE} s); whole test part {:.2} s",
        recovered.as_secs_f64(),
        took.as_secs_f64()
    );
    assert!(recovered < Duration::from_secs(LEASE + 3), "{recovered:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_node_cut_off_from_redis_alone_hands_its_match_over_and_loses_no_acknowledged_shot() {
    let _one = ONE_AT_A_TIME.lock().await;
    let test = "fault_redis_cut";
    let Some(db) =
        tokio::task::block_in_place(|| local_services::local_postgres::shared_database(test))
    else {
        return;
    };
    let Some(redis) = private_redis(test) else {
        return;
    };
    let port: u16 = redis.url().rsplit(':').next().unwrap().parse().unwrap();
    let link = local_services::TcpLink::start(port).unwrap();
    let through_link = format!("redis://127.0.0.1:{}", link.port());
    let dir = tempfile::tempdir().unwrap();
    let a = node(dir.path(), &db, &through_link, "cut-a");
    let b = node(dir.path(), &db, &redis.url(), "cut-b");
    let (id, wt, bt, mut white, mut black) = opening(&a, &b).await;
    let mut ledger = Ledger::default();

    link.cut();
    let began = Instant::now();
    // A still reaches PostgreSQL: the shot may be played (and then it must
    // be kept) until A lets its lease go.
    white.send(&shot(3, 0.0, 0.5)).await;
    drain(&mut white, Duration::from_secs(LEASE + 1)).await;
    drain(&mut black, Duration::from_millis(100)).await;
    ledger.take(&white);
    ledger.take(&black);
    // A refuses the players (it cannot reach the other nodes); they find
    // the match on B.
    let took = resume_and_judge(
        "one node cut off from Redis",
        &[&a, &b],
        &id,
        (&wt, &bt),
        ledger,
        began,
    )
    .await;
    assert!(took < Duration::from_secs(2 * LEASE + 4), "{took:?}");
    // Reconnected, A serves its clients again (relaying to B).
    link.restore();
    let (_, view) = reconnect(&a, &id, &bt).await;
    assert!(view.shots >= 4);
}
