//! Several server nodes on one PostgreSQL store with Redis between them
//! (`--redis-url`), as real processes: a match created on one node is
//! joined, played and watched from another, and every client sees the
//! same messages in the same order; when the node playing a match is
//! killed with SIGKILL, another node takes it over within the lease plus
//! a second, the clients reconnect, the match finishes, and every
//! acknowledged shot is in its record. A client that asks a node with
//! `follow=1` is sent (`307`) to the node that plays its match when that
//! node has a public URL, plays there instead of being relayed, and after
//! that node dies it reaches the node that took the match over. A
//! browser, which cannot follow a redirect, asks a node for the socket of
//! the node that plays its match (`/api/matches/ID/socket`), and that node
//! accepts the socket from a page the other node served (its origin).
//! Skipped (with a note) where the
//! machine has no PostgreSQL or Redis, unless `CHAPAEV_REQUIRE_POSTGRES`
//! / `CHAPAEV_REQUIRE_REDIS` say they must be there.

mod common;

use common::cluster::{
    node, reconnect, reconnect_following, record, routed_node, services, three_shots, until_shots,
    LEASE,
};
use common::{shot, view, Client};
use game::protocol::{ClientMessage, ServerMessage};
use std::time::{Duration, Instant};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_match_created_on_one_node_is_joined_played_and_watched_from_another_in_the_same_order() {
    let Some((db, redis)) = services("cluster_relay") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Node ids are unique on the Redis the tests share.
    let a = node(dir.path(), &db, &redis, "relay-a");
    let b = node(dir.path(), &db, &redis, "relay-b");
    let (id, white_token) = a.create(r#"{"name":"Petka"}"#).await;
    // The join reaches node A (which plays the match) through node B.
    let black_token = b.join(&id).await;
    let mut white = a.ws(&id, Some(&white_token)).await;
    let mut black = b.ws(&id, Some(&black_token)).await;
    let mut watcher_a = a.ws(&id, None).await;
    let mut watcher_b = b.ws(&id, None).await;
    let first = [
        view(white.next().await),
        view(black.next().await),
        view(watcher_a.next().await),
        view(watcher_b.next().await),
    ];
    assert!(first.iter().all(|v| *v == first[0]), "{first:?}");
    // White knocks a piece off and shoots again, then passes the turn;
    // Black (on node B) answers.
    white.send(&shot(4, 0.0, 2.0)).await;
    white.send(&shot(2, 0.0, 0.5)).await;
    until_shots(&mut black, 2).await;
    black.send(&shot(10, 0.0, -0.5)).await;
    for c in [&mut white, &mut black, &mut watcher_a, &mut watcher_b] {
        until_shots(
            c,
            3 - c
                .received
                .iter()
                .filter(|m| m.contains("shot-played"))
                .count(),
        )
        .await;
    }
    // The spectators, one on each node, saw the same messages in the same
    // order: the same kinds, and the same texts but for the turn clock's
    // remaining time, which each connection is told when it reads it.
    let kinds = |c: &Client| -> Vec<String> {
        c.received
            .iter()
            .map(|m| m.split('"').nth(3).unwrap_or_default().to_string())
            .collect()
    };
    assert_eq!(kinds(&watcher_a), kinds(&watcher_b));
    let texts = |c: &Client| -> Vec<String> {
        c.received
            .iter()
            .filter(|m| !m.contains("\"clock\""))
            .cloned()
            .collect()
    };
    assert!(
        texts(&watcher_a) == texts(&watcher_b),
        "the watchers' messages differ"
    );
    let shots = |c: &Client| -> Vec<String> {
        c.received
            .iter()
            .filter(|m| m.contains("\"shot-played\""))
            .cloned()
            .collect()
    };
    assert!(shots(&white) == shots(&watcher_b) && shots(&black) == shots(&watcher_a));
    assert_eq!(shots(&white).len(), 3);
    // Each node tells its share in its metrics: A plays the match and
    // serves B's two connections; B relays them.
    let gauge = |text: &str, name: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(&format!("{name} ")))?;
        line.split(' ').nth(1)?.parse().ok()
    };
    let (_, metrics_a) = a.http("GET", "/metrics", "").await;
    let (_, metrics_b) = b.http("GET", "/metrics", "").await;
    assert_eq!(gauge(&metrics_a, "chapaev_cluster_matches_owned"), Some(1));
    assert_eq!(
        gauge(&metrics_a, "chapaev_cluster_connections_served"),
        Some(2)
    );
    assert_eq!(
        gauge(&metrics_b, "chapaev_cluster_matches_relayed"),
        Some(1)
    );
    assert_eq!(
        gauge(&metrics_b, "chapaev_cluster_connections_relayed"),
        Some(2)
    );
    // Listings come from the shared store: both nodes list the match.
    for n in [&a, &b] {
        let (status, body) = n.http("GET", &format!("/api/matches/{id}"), "").await;
        assert_eq!(status, 200, "{body}");
        assert!(body.contains("\"shots\":3"), "{body}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn when_the_node_playing_a_match_is_killed_another_takes_it_over_and_no_acknowledged_shot_is_lost(
) {
    let Some((db, redis)) = services("cluster_takeover") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut a = node(dir.path(), &db, &redis, "takeover-a");
    let b = node(dir.path(), &db, &redis, "takeover-b");
    let (id, white_token, black_token) = a.two_player_match("").await;
    let mut white = a.ws(&id, Some(&white_token)).await;
    let mut black = b.ws(&id, Some(&black_token)).await;
    view(white.next().await);
    view(black.next().await);
    three_shots(&mut white, &mut black).await;

    a.kill();
    let killed = Instant::now();
    // Black's connection through node B ends once A's lease expires.
    assert!(black.closes().await);
    let (mut black, state) = reconnect(&b, &id, &black_token).await;
    let took = killed.elapsed();
    assert_eq!(state.shots, 3, "every acknowledged shot came back");
    assert!(
        took <= Duration::from_secs(LEASE + 1),
        "taken over after {took:?} (lease {LEASE} s)"
    );
    println!("takeover after SIGKILL: {took:?} (lease {LEASE} s)");
    let (mut white, again) = reconnect(&b, &id, &white_token).await;
    assert_eq!(again, state);
    // The match goes on on node B and finishes.
    white.send(&shot(3, 0.0, 0.5)).await;
    let ServerMessage::ShotPlayed { outcome, .. } = black.next_of("shot-played").await else {
        unreachable!()
    };
    assert_eq!(outcome.number, 3);
    black.send(&ClientMessage::Resign).await;
    white.next_of("match-over").await;
    let record = record(&b, &id).await;
    assert_eq!(record.moves.len(), 5, "four shots and the resignation");
    let replay = game::Replay::new(record).unwrap();
    assert_eq!(replay.game().view().shots, 4);
}

/// A single-valued metric of a node's `/metrics`.
async fn gauge(node: &common::Server, name: &str) -> Option<u64> {
    let (_, text) = node.http("GET", "/metrics", "").await;
    let line = text.lines().find(|l| l.starts_with(&format!("{name} ")))?;
    line.split(' ').nth(1)?.parse().ok()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_asking_another_node_for_a_match_is_sent_to_the_node_playing_it_and_plays_it_to_the_end(
) {
    let Some((db, redis)) = services("cluster_routed") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let a = routed_node(dir.path(), &db, &redis, "routed-a");
    let b = routed_node(dir.path(), &db, &redis, "routed-b");
    let (id, white_token) = a.create(r#"{"name":"Petka"}"#).await;
    let black_token = b.join(&id).await;
    // Both players and a spectator ask node B; node A plays the match.
    let (mut white, white_at) =
        common::Client::try_connect_following(&b.addr, &id, Some(&white_token))
            .await
            .unwrap();
    let (mut black, black_at) =
        common::Client::try_connect_following(&b.addr, &id, Some(&black_token))
            .await
            .unwrap();
    let (mut watcher, watcher_at) = common::Client::try_connect_following(&b.addr, &id, None)
        .await
        .unwrap();
    assert_eq!([&white_at, &black_at, &watcher_at], [&a.addr; 3]);
    let first = [
        view(white.next().await),
        view(black.next().await),
        view(watcher.next().await),
    ];
    assert!(first.iter().all(|v| *v == first[0]), "{first:?}");
    // Node B sent them on and relays no connection (it keeps the proxy
    // room the join through it started); node A serves nobody for B.
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_routed").await,
        Some(3)
    );
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_relayed").await,
        Some(0)
    );
    assert_eq!(
        gauge(&a, "chapaev_cluster_connections_served").await,
        Some(0)
    );
    assert_eq!(gauge(&a, "chapaev_connections").await, Some(3));
    // A client that does not ask to be sent on is relayed, as before.
    let mut relayed = b.ws(&id, None).await;
    view(relayed.next().await);
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_relayed").await,
        Some(1)
    );
    // Played to the end on node A.
    three_shots(&mut white, &mut black).await;
    black.send(&ClientMessage::Resign).await;
    for c in [&mut white, &mut black, &mut watcher, &mut relayed] {
        c.next_of("match-over").await;
    }
    let record = record(&a, &id).await;
    assert_eq!(record.moves.len(), 4, "three shots and the resignation");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_sent_to_a_node_that_is_killed_reaches_the_node_that_takes_the_match_over() {
    let Some((db, redis)) = services("cluster_routed_takeover") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut a = routed_node(dir.path(), &db, &redis, "routed-takeover-a");
    let b = routed_node(dir.path(), &db, &redis, "routed-takeover-b");
    let (id, white_token, black_token) = a.two_player_match("").await;
    let (mut white, white_at) =
        common::Client::try_connect_following(&b.addr, &id, Some(&white_token))
            .await
            .unwrap();
    let (mut black, black_at) =
        common::Client::try_connect_following(&b.addr, &id, Some(&black_token))
            .await
            .unwrap();
    assert_eq!([&white_at, &black_at], [&a.addr; 2]);
    view(white.next().await);
    view(black.next().await);
    three_shots(&mut white, &mut black).await;

    a.kill();
    let killed = Instant::now();
    assert!(black.closes().await && white.closes().await);
    // They come back through node B, which sends them to A while A's
    // lease lasts (they cannot reach it, so B relays, to nobody), and
    // plays the match itself once it took it over.
    let (mut black, state, black_at) = reconnect_following(&b, &id, &black_token).await;
    let took = killed.elapsed();
    assert_eq!(black_at, b.addr);
    assert_eq!(state.shots, 3, "every acknowledged shot came back");
    println!("routed client back on the new owner after SIGKILL: {took:?} (lease {LEASE} s)");
    let (mut white, again, white_at) = reconnect_following(&b, &id, &white_token).await;
    assert_eq!(white_at, b.addr);
    assert_eq!(again, state);
    assert_eq!(gauge(&b, "chapaev_cluster_matches_owned").await, Some(1));
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_relayed").await,
        Some(0)
    );
    white.send(&shot(3, 0.0, 0.5)).await;
    until_shots(&mut black, 1).await;
    black.send(&ClientMessage::Resign).await;
    white.next_of("match-over").await;
    let record = record(&b, &id).await;
    assert_eq!(record.moves.len(), 5, "four shots and the resignation");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_browser_asking_another_node_is_told_the_owners_socket_which_accepts_that_nodes_page() {
    let Some((db, redis)) = services("cluster_socket") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let a = routed_node(dir.path(), &db, &redis, "socket-a");
    let b = routed_node(dir.path(), &db, &redis, "socket-b");
    let (id, white_token) = a.create(r#"{"name":"Petka"}"#).await;
    let black_token = b.join(&id).await;
    let socket = |node: &common::Server| {
        let path = format!("/api/matches/{id}/socket");
        let node = node.addr.clone();
        async move {
            let (status, body) = common::http(&node, "GET", &path, "").await;
            assert_eq!(status, 200, "{body}");
            serde_json::from_str::<serde_json::Value>(&body).unwrap()
        }
    };
    // Node B names node A's socket; node A, which plays it, none.
    let owner = format!("ws://{}/ws?match={id}", a.addr);
    assert_eq!(socket(&b).await["url"], owner.as_str());
    assert_eq!(socket(&a).await["url"], serde_json::Value::Null);
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_routed").await,
        Some(1)
    );
    let (status, body) = b.http("GET", "/api/matches/no%20such/socket", "").await;
    assert_eq!(status, 400, "{body}");
    // A page node B served opens node A's socket and plays there.
    let page_of_b = format!("http://{}", b.addr);
    let mut white = Client::try_connect_from(&owner, &page_of_b, Some(&white_token))
        .await
        .unwrap();
    let mut black = Client::try_connect_from(&owner, &page_of_b, Some(&black_token))
        .await
        .unwrap();
    assert_eq!(view(white.next().await), view(black.next().await));
    white.send(&shot(4, 0.0, 2.0)).await;
    until_shots(&mut black, 1).await;
    assert_eq!(gauge(&a, "chapaev_connections").await, Some(2));
    assert_eq!(
        gauge(&b, "chapaev_cluster_connections_relayed").await,
        Some(0)
    );
    // A page of a site outside the cluster is still refused (403).
    let stranger = Client::try_connect_from(&owner, "http://evil.example", None).await;
    match stranger {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => assert_eq!(r.status(), 403),
        Err(e) => panic!("refused, but not as expected: {e}"),
        Ok(_) => panic!("a foreign page opened node A's socket"),
    }
}
