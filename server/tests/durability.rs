//! Nothing accepted is lost: the real server, killed with SIGKILL in the
//! middle of a match or stopped with SIGTERM, comes back with every shot it
//! broadcast, and the match goes on.

mod common;

use common::{shot, view, Server};
use game::protocol::ServerMessage;

#[tokio::test]
async fn a_match_survives_sigkill_and_resumes_with_the_same_state_and_the_next_shot_works() {
    let dir = tempfile::tempdir().unwrap();
    let mut server = Server::start(dir.path(), &[]);
    let (id, white_token, black_token) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    let mut black = server.ws(&id, Some(&black_token)).await;
    view(white.next().await);
    view(black.next().await);
    // White knocks Black's e-piece off (and shoots again), then a gentle
    // shot passes the turn; Black answers.
    white.send(&shot(4, 0.0, 2.0)).await;
    white.send(&shot(2, 0.0, 0.5)).await;
    for _ in 0..2 {
        black.next_of("shot-played").await;
    }
    black.send(&shot(10, 0.0, -0.5)).await;
    for number in 0..3 {
        let ServerMessage::ShotPlayed { outcome, .. } = white.next_of("shot-played").await else {
            unreachable!()
        };
        assert_eq!(outcome.number, number);
    }
    // The state everyone sees now.
    let mut watcher = server.ws(&id, None).await;
    let before = view(watcher.next().await);
    assert_eq!(before.shots, 3);

    server.kill();
    let server = Server::start(dir.path(), &[]);
    let mut white = server.ws(&id, Some(&white_token)).await;
    let after = view(white.next().await);
    assert_eq!(
        after, before,
        "the resumed match is the very match that was broadcast"
    );
    // And it goes on: it is White's turn.
    white.send(&shot(3, 0.0, 0.5)).await;
    let ServerMessage::ShotPlayed { outcome, .. } = white.next_of("shot-played").await else {
        unreachable!()
    };
    assert_eq!(outcome.number, 3);
    let mut watcher = server.ws(&id, None).await;
    assert_eq!(view(watcher.next().await).shots, 4);
}

#[tokio::test]
async fn sigterm_stops_cleanly_and_a_finished_match_replays_after_restart() {
    let dir = tempfile::tempdir().unwrap();
    let mut server = Server::start(dir.path(), &[]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    view(white.next().await);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    white.send(&game::protocol::ClientMessage::Resign).await;
    let ServerMessage::MatchOver { record, .. } = white.next_of("match-over").await else {
        unreachable!()
    };
    assert!(server.terminate(), "SIGTERM ends the server with success");
    let server = Server::start(dir.path(), &[]);
    let (status, body) = server
        .http("GET", &format!("/api/matches/{id}/record"), "")
        .await;
    assert_eq!(status, 200, "{body}");
    let stored = game::MatchRecord::from_json(&body).unwrap();
    assert_eq!(stored.physics, game::PHYSICS_VERSION);
    assert_eq!(stored, record);
    let replay = game::Replay::new(stored).unwrap();
    assert!(replay.game().is_over());
    assert_eq!(replay.shot_count(), 1);
}

#[tokio::test]
async fn after_a_kill_live_matches_resume_first_and_always_while_open_ones_wait_in_the_store() {
    let dir = tempfile::tempdir().unwrap();
    let roomy = ["--max-matches", "40", "--create-burst", "100"];
    let mut server = Server::start(dir.path(), &roomy);
    // Many open matches nobody joined, created before and after two live ones.
    let mut open = Vec::new();
    for _ in 0..8 {
        open.push(server.create(r#"{"name":"Waiting"}"#).await.0);
    }
    let mut live = Vec::new();
    for _ in 0..2 {
        let (id, white_token, _) = server.two_player_match("").await;
        let mut white = server.ws(&id, Some(&white_token)).await;
        view(white.next().await);
        white.send(&shot(4, 0.0, 2.0)).await;
        white.next_of("shot-played").await;
        live.push((id, white_token));
    }
    for _ in 0..8 {
        open.push(server.create(r#"{"name":"Waiting"}"#).await.0);
    }
    server.kill();
    // Room for only four matches now: the live ones must all be back.
    let server = Server::start(dir.path(), &["--max-matches", "4"]);
    let (_, health) = server.http("GET", "/healthz", "").await;
    let health: serde_json::Value = serde_json::from_str(&health).unwrap();
    assert_eq!(health["matches_in_memory"], 2, "{health}");
    for (id, token) in &live {
        let mut white = server.ws(id, Some(token)).await;
        assert_eq!(view(white.next().await).shots, 1);
    }
    // An open match is loaded when someone comes for it.
    let (status, text) = server
        .http(
            "POST",
            &format!("/api/matches/{}/join", open[0]),
            r#"{"name":"Anka"}"#,
        )
        .await;
    assert_eq!(status, 200, "{text}");
}
