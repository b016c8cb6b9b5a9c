//! Hosted bots playing on the real server: a bot account uploads the
//! starter module (built for wasm32 as its author would), and with no
//! process of its own online it is paired on the ladder, plays a rated
//! match to the end against a computer level, and its rating moves; the
//! match's record names the module version that played, and running that
//! module again on the record's positions gives every one of its moves
//! bit for bit. A version made active during a match plays from the next
//! match on, and the one playing cannot be deleted until its match ends;
//! a match resumed after a restart is played on by its own version, read
//! back from the store, and the bot is not paired again until it ends. On
//! a cluster, the bot plays one ladder match at a time across its nodes.
//! A hostile module (an endless loop) loses on time while a match between
//! people goes on.

mod common;

use common::modules::{self, account, as_key, json, starter};
use common::{shot, Server};
use game::decide::DecideRequest;
use game::{MatchRecord, NoiseKey, RecordedMove, Replay, Side};
use serde_json::Value;
use std::sync::Arc;
use std::time::{Duration, Instant};

async fn bot_account(s: &Server, name: &str) -> String {
    account(s, name, true).await
}

/// Uploads `bytes` as the account's module; its hash.
async fn upload(s: &Server, key: &str, bytes: Vec<u8>) -> String {
    let (status, text) = modules::upload(s, key, bytes).await;
    assert!(status == 200 || status == 201, "{status} {text}");
    json(&text)["hash"].as_str().unwrap().to_string()
}

/// A module that answers `answer` at once (its own bytes for each `k`).
fn answering(answer: &str, k: u32) -> Vec<u8> {
    let escaped = answer.replace('"', "\\\"");
    wat::parse_str(format!(
        r#"(module
            (memory (export "memory") 1)
            (data (i32.const 0) "{escaped}")
            (global i32 (i32.const {k}))
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 1024)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const {len}))"#,
        len = answer.len()
    ))
    .unwrap()
}

/// A module whose decision never ends (it runs out of fuel).
fn endless() -> Vec<u8> {
    wat::parse_str(
        r#"(module
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 1024)
            (func (export "chapaev_decide") (param i32 i32) (result i64)
                (loop $forever (br $forever))
                i64.const 0))"#,
    )
    .unwrap()
}

/// `DELETE`s the account's version `hash`; the status and body.
async fn delete_version(s: &Server, key: &str, hash: &str) -> (u16, String) {
    let path = format!("/api/accounts/me/modules/{hash}");
    as_key(s, "DELETE", &path, key, "").await
}

/// Tries to delete version `hash`, which match `id` plays with: refused
/// with `module-in-use` while the match is not over (with no bot delay, a
/// computer may end it first: then it is deleted). Whether it was.
async fn delete_in_use(s: &Server, key: &str, hash: &str, id: &str) -> bool {
    let (status, text) = delete_version(s, key, hash).await;
    if status == 204 {
        let (_, m) = s.http("GET", &format!("/api/matches/{id}"), "").await;
        assert_eq!(json(&m)["status"], "finished", "deleted while in use");
        return true;
    }
    assert_eq!(status, 409, "{text}");
    assert_eq!(json(&text)["code"], "module-in-use", "{text}");
    false
}

/// The matches `account` played, newest first.
async fn matches_of(s: &Server, account: &str) -> Vec<Value> {
    let (status, text) = s
        .http("GET", &format!("/api/accounts/{account}/matches"), "")
        .await;
    assert_eq!(status, 200, "{text}");
    json(&text).as_array().unwrap().clone()
}

/// Waits (at most `within`) for a match of `account` in `status` other
/// than those in `seen`; its summary.
async fn wait_for(
    s: &Server,
    account: &str,
    status: &str,
    seen: &[String],
    within: Duration,
) -> Value {
    let deadline = Instant::now() + within;
    loop {
        let found = matches_of(s, account).await.into_iter().find(|m| {
            m["status"] == status && !seen.contains(&m["match_id"].as_str().unwrap().to_string())
        });
        if let Some(m) = found {
            return m;
        }
        assert!(
            Instant::now() < deadline,
            "no {status} match of {account} within {within:?}"
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

/// Waits for match `id` to finish; its summary.
async fn wait_finished(s: &Server, id: &str, within: Duration) -> Value {
    let deadline = Instant::now() + within;
    loop {
        let (status, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
        assert_eq!(status, 200, "{text}");
        let m = json(&text);
        if m["status"] == "finished" {
            return m;
        }
        assert!(
            Instant::now() < deadline,
            "match {id} not over within {within:?}"
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

async fn record(s: &Server, id: &str) -> MatchRecord {
    let (status, text) = s
        .http("GET", &format!("/api/matches/{id}/record"), "")
        .await;
    assert_eq!(status, 200, "{text}");
    MatchRecord::from_json(&text).unwrap()
}

/// The seat (0 or 1) of `account` in a summary.
fn seat_of(summary: &Value, account: &str) -> usize {
    if summary["first"] == account {
        0
    } else {
        assert_eq!(summary["second"], account, "{summary}");
        1
    }
}

/// Runs `module` again on the position before each move of its seat in
/// `record` (its random stream derived from the revealed secret) and
/// checks it decides that very move, bit for bit; how many it checked.
fn replay_hosted_moves(record: &MatchRecord, seat: usize, module: &[u8]) -> usize {
    let module = Arc::new(hosted::BotModule::load(module, &hosted::Limits::default()).unwrap());
    let NoiseKey::ChaCha20(secret) = record.key().unwrap() else {
        panic!("a hosted bot's match is keyed by a secret")
    };
    let mut bot = bots::hosted_bot::HostedBot::new(module, secret);
    let replay = Replay::new(record.clone()).expect("the record replays");
    let mut checked = 0;
    for (k, m) in record.moves.iter().enumerate() {
        let view = replay.view_before(k).unwrap().clone();
        let side = if (seat == 0) != view.swapped {
            Side::White
        } else {
            Side::Black
        };
        let request = DecideRequest { me: side, view };
        match m {
            RecordedMove::Shot(o) if o.shooter == side => {
                let bots::Decision::Shot(again) = bot.try_decide(&request).unwrap() else {
                    panic!("move {k}: the module no longer shoots")
                };
                assert_eq!(again.piece(), o.piece, "move {k}");
                assert_eq!(
                    again.velocity().x.to_bits(),
                    o.aimed.x.to_bits(),
                    "move {k}"
                );
                assert_eq!(
                    again.velocity().y.to_bits(),
                    o.aimed.y.to_bits(),
                    "move {k}"
                );
                checked += 1;
            }
            RecordedMove::Pie { swap } if side == Side::Black => {
                assert_eq!(
                    bot.try_decide(&request).unwrap(),
                    bots::Decision::Pie { swap: *swap },
                    "move {k}"
                );
                checked += 1;
            }
            RecordedMove::Resign { side: s } if *s == side => {
                assert_eq!(
                    bot.try_decide(&request).unwrap(),
                    bots::Decision::Resign,
                    "move {k}"
                );
                checked += 1;
            }
            _ => {}
        }
    }
    checked
}

/// The starter as a hosted bot on the ladder, and a new version during its
/// match.
async fn starter_on_the_ladder(extra: &[&str]) {
    let starter = tokio::task::block_in_place(starter);
    let dir = tempfile::tempdir().unwrap();
    let mut flags = vec!["--ladder-seconds", "1", "--hosted-workers", "1"];
    flags.extend_from_slice(extra);
    let s = Server::start(dir.path(), &flags);
    let key = bot_account(&s, "Starter").await;
    let v1 = upload(&s, &key, starter.clone()).await;

    // No stream, no client: the server pairs it and plays it.
    let live = wait_for(&s, "Starter", "live", &[], Duration::from_secs(60)).await;
    let id = live["match_id"].as_str().unwrap().to_string();
    assert_eq!(live["rated"], true, "{live}");
    let seat = seat_of(&live, "Starter");
    let opponent = live[if seat == 0 { "second" } else { "first" }]
        .as_str()
        .unwrap()
        .to_string();
    assert!(opponent.starts_with("computer-"), "{live}");

    // A new version, made active during the match: the match goes on with
    // the version it started with, which is kept until the match ends.
    let resigner = answering(r#"{"type":"resign"}"#, 1);
    let v2 = upload(&s, &key, resigner.clone()).await;
    assert_ne!(v1, v2);
    let deleted = delete_in_use(&s, &key, &v1, &id).await;

    let over = wait_finished(&s, &id, Duration::from_secs(600)).await;
    if !deleted {
        let (status, text) = delete_version(&s, &key, &v1).await;
        assert_eq!(status, 204, "once its match is over: {text}");
    }
    assert!(over["result"].is_object(), "{over}");
    let first = record(&s, &id).await;
    let mut named = [None, None];
    named[seat] = Some(v1.clone());
    assert_eq!(first.hosted, Some(named), "the record names the version");
    game::verify(&first).expect("the record verifies");
    let checked = replay_hosted_moves(&first, seat, &starter);
    // A computer that knocks a piece off shoots again, and now and then
    // sweeps the board after one move of the starter's: one move, checked
    // bit for bit, is the least a match shows.
    assert!(checked >= 1, "none of the starter's moves");
    assert!(
        !first
            .moves
            .iter()
            .any(|m| matches!(m, RecordedMove::Resign { .. })),
        "the new version did not play in the running match"
    );

    // Rated: its rating moved, and it is on the bots' leaderboard.
    let (status, text) = s.http("GET", "/api/accounts/Starter", "").await;
    assert_eq!(status, 200, "{text}");
    let profile = json(&text);
    assert!(profile["games"].as_u64().unwrap() >= 1, "{profile}");
    assert_ne!(profile["rating"], 1500, "{profile}");
    let (status, text) = s.http("GET", "/api/leaderboard?bots=true", "").await;
    assert_eq!(status, 200, "{text}");
    assert!(text.contains("\"Starter\""), "{text}");

    // The next match is the new version's: it resigns at its first move.
    let next = wait_for(&s, "Starter", "finished", &[id], Duration::from_secs(120)).await;
    let id2 = next["match_id"].as_str().unwrap();
    let second = record(&s, id2).await;
    let seat2 = seat_of(&next, "Starter");
    let mut named = [None, None];
    named[seat2] = Some(v2);
    assert_eq!(second.hosted, Some(named));
    assert_eq!(replay_hosted_moves(&second, seat2, &resigner), 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_sqlite_an_uploaded_starter_is_paired_on_the_ladder_plays_a_rated_match_that_replays_and_a_new_version_waits_for_the_next_match(
) {
    starter_on_the_ladder(&[]).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_postgresql_an_uploaded_starter_is_paired_on_the_ladder_plays_a_rated_match_that_replays_and_a_new_version_waits_for_the_next_match(
) {
    let Some(url) = tokio::task::block_in_place(|| {
        local_services::local_postgres::shared_database("hosted_play_on_postgresql")
    }) else {
        return;
    };
    starter_on_the_ladder(&[&format!("--database-url={url}")]).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hosted_match_resumed_after_a_restart_is_played_on_by_its_version_from_the_store() {
    let starter = tokio::task::block_in_place(starter);
    let dir = tempfile::tempdir().unwrap();
    let flags = ["--ladder-seconds", "1", "--hosted-workers", "1"];
    let mut s = Server::start(dir.path(), &flags);
    let key = bot_account(&s, "Starter").await;
    let v1 = upload(&s, &key, starter.clone()).await;
    let live = wait_for(&s, "Starter", "live", &[], Duration::from_secs(60)).await;
    let id = live["match_id"].as_str().unwrap().to_string();
    let seat = seat_of(&live, "Starter");
    // A few moves in, the server dies; a new version is active by the time
    // it is back.
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let (_, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
        if json(&text)["shots"].as_u64().unwrap_or(0) >= 2 {
            break;
        }
        assert!(Instant::now() < deadline, "no shots in match {id}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    // A new version is active, and the one playing cannot be deleted: the
    // match resumes with it.
    let v2 = upload(&s, &key, answering(r#"{"type":"resign"}"#, 2)).await;
    assert_ne!(v1, v2);
    delete_in_use(&s, &key, &v1, &id).await;
    s.kill();
    let s = Server::start(dir.path(), &flags);
    // Round after round (one a second), the bot is not paired again while
    // its resumed match is not over.
    let deadline = Instant::now() + Duration::from_secs(600);
    let over = loop {
        let unfinished: Vec<String> = matches_of(&s, "Starter")
            .await
            .into_iter()
            .filter(|m| m["status"] != "finished")
            .map(|m| m["match_id"].as_str().unwrap().to_string())
            .collect();
        let (status, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
        assert_eq!(status, 200, "{text}");
        let m = json(&text);
        if m["status"] == "finished" {
            break m;
        }
        assert_eq!(
            unfinished,
            std::slice::from_ref(&id),
            "paired while its match resumes"
        );
        assert!(Instant::now() < deadline, "match {id} not over");
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    assert!(over["result"].is_object(), "{over}");
    let r = record(&s, &id).await;
    let mut named = [None, None];
    named[seat] = Some(v1);
    assert_eq!(r.hosted, Some(named));
    assert!(
        !r.moves
            .iter()
            .any(|m| matches!(m, RecordedMove::Resign { .. } | RecordedMove::Pass { .. })),
        "the resumed match was played on by its own version, every decision answered"
    );
    // A computer that sweeps the board may end the match after one move
    // of the starter's.
    assert!(replay_hosted_moves(&r, seat, &starter) >= 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_a_cluster_a_hosted_bot_plays_one_ladder_match_at_a_time_across_its_nodes() {
    let test = "hosted_play_on_a_cluster";
    let Some((db, redis)) = common::cluster::services(test) else {
        return;
    };
    let starter = tokio::task::block_in_place(starter);
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    let flags = ["--ladder-seconds", "1", "--hosted-workers", "1"];
    let nodes: Vec<Server> = ["hosted-a", "hosted-b"]
        .iter()
        .zip(&dirs)
        .map(|(name, dir)| common::cluster::node_with(dir.path(), &db, &redis, name, &flags))
        .collect();
    let key = bot_account(&nodes[0], "Starter").await;
    upload(&nodes[0], &key, starter).await;
    // Both nodes' ladders pair it every second; whichever node asks, it is
    // in one unfinished match at most, until it has played three.
    let deadline = Instant::now() + Duration::from_secs(600);
    let mut k = 0;
    loop {
        let listed = matches_of(&nodes[k % 2], "Starter").await;
        k += 1;
        let unfinished: Vec<&Value> = listed
            .iter()
            .filter(|m| m["status"] != "finished")
            .collect();
        assert!(unfinished.len() <= 1, "{unfinished:?}");
        if listed.len() - unfinished.len() >= 3 {
            break;
        }
        assert!(Instant::now() < deadline, "{listed:?}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hostile_module_loses_on_time_while_a_match_between_people_plays_on() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(
        dir.path(),
        &["--ladder-seconds", "1", "--hosted-workers", "1"],
    );
    let key = bot_account(&s, "Spinner").await;
    let hash = upload(&s, &key, endless()).await;
    let live = wait_for(&s, "Spinner", "live", &[], Duration::from_secs(60)).await;
    let id = live["match_id"].as_str().unwrap().to_string();
    let seat = seat_of(&live, "Spinner");

    // Meanwhile two people play: every shot is acknowledged.
    let (pid, a, b) = s.two_player_match(r#","rules":"casual""#).await;
    let mut white = s.ws(&pid, Some(&a)).await;
    let mut black = s.ws(&pid, Some(&b)).await;
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    black.next_of("shot-played").await;

    let over = wait_finished(&s, &id, Duration::from_secs(300)).await;
    let side = if seat == 0 { "white" } else { "black" };
    assert_ne!(over["result"]["side"], side, "{over}");
    let r = record(&s, &id).await;
    // Its turns run out: it loses on three in a row, or sooner where the
    // computer (shooting again after each piece it knocks off) sweeps the
    // board meanwhile; either way a turn of its passed on the clock.
    let passed = r
        .moves
        .iter()
        .any(|m| matches!(m, RecordedMove::Pass { .. }));
    // (A sweep from the first shot on leaves it no turn at all: then
    // every shot is the winner's.)
    let winner = over["result"]["side"].as_str().unwrap_or_default();
    let only_the_winner_shot = r.moves.iter().all(|m| match m {
        RecordedMove::Shot(o) => format!("{:?}", o.shooter).to_lowercase() == winner,
        _ => true,
    });
    assert!(
        over["result"]["reason"] == "timeouts" || passed || only_the_winner_shot,
        "{over}"
    );
    let mut named = [None, None];
    named[seat] = Some(hash);
    assert_eq!(r.hosted, Some(named));
    game::verify(&r).expect("the record verifies");
    let (status, text) = s.http("GET", "/api/accounts/Spinner", "").await;
    assert_eq!(status, 200, "{text}");
    assert!(json(&text)["rating"].as_i64().unwrap() < 1500, "{text}");
    let (status, _) = s.http("GET", "/healthz", "").await;
    assert_eq!(status, 200);
}
