//! Playing through the real server: bots, chat, resignation, rematch, the
//! turn clock, dropped players and their grace period, and the HTTP pages.

mod common;

use common::{shot, view, Server};
use game::protocol::{ClientMessage, ForfeitReason, Phrase, ServerMessage};
use game::{MatchResult, Seat, Side, WinReason};

#[tokio::test]
async fn a_bot_answers_shots_over_the_websocket_at_every_level() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    for level in ["easy", "medium", "hard"] {
        let (id, token) = server
            .create(&format!(
                r#"{{"name":"Petka","opponent":"bot","bot_level":"{level}"}}"#
            ))
            .await;
        let mut me = server.ws(&id, Some(&token)).await;
        let ServerMessage::MatchState { you, players, .. } = me.next().await else {
            panic!("match-state first")
        };
        assert_eq!(you, Some(Seat::First));
        assert_eq!(players.second, Some(format!("bot ({level})")));
        me.send(&shot(0, 0.0, 0.4)).await;
        let ServerMessage::ShotPlayed { outcome, .. } = me.next_of("shot-played").await else {
            unreachable!()
        };
        assert_eq!(outcome.shooter, Side::White);
        let ServerMessage::ShotPlayed { outcome, .. } = me.next_of("shot-played").await else {
            unreachable!()
        };
        assert_eq!(outcome.shooter, Side::Black, "{level} bot answered");
    }
}

#[tokio::test]
async fn named_rules_set_the_config_and_an_exhibition_is_watched_from_the_live_list() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, token) = server
        .create(r#"{"name":"MyBot","rules":"standard"}"#)
        .await;
    let mut me = server.ws(&id, Some(&token)).await;
    let config = view(me.next().await).config;
    assert_eq!(config, game::Config::standard());
    for (body, code) in [
        (r#"{"rules":"blitz"}"#, "bad-config"),
        (r#"{"rules":"standard","config":{}}"#, "bad-message"),
        (
            r#"{"opponent":"bot","bot_level":"grandmaster"}"#,
            "bad-message",
        ),
    ] {
        let (status, text) = server.http("POST", "/api/matches", body).await;
        assert_eq!(status, 400, "{body}: {text}");
        assert!(text.contains(code), "{body}: {text}");
    }
    let (status, text) = server
        .http(
            "POST",
            "/api/exhibitions",
            r#"{"first":"easy","second":"hard"}"#,
        )
        .await;
    assert_eq!(status, 201, "{text}");
    let answer: serde_json::Value = serde_json::from_str(&text).unwrap();
    let ex = answer["match_id"].as_str().unwrap().to_string();
    let (_, live) = server.http("GET", "/api/matches?status=live", "").await;
    assert!(live.contains(&ex), "{live}");
    let mut watcher = server.ws(&ex, None).await;
    let ServerMessage::MatchState { you, players, .. } = watcher.next().await else {
        panic!("match-state first")
    };
    assert_eq!(you, None);
    assert_eq!(players.first.as_deref(), Some("bot (easy)"));
    assert_eq!(players.second.as_deref(), Some("bot (hard)"));
    // The bots play on their own (they may have begun before the watcher).
    let ServerMessage::ShotPlayed { outcome, .. } = watcher.next_of("shot-played").await else {
        unreachable!()
    };
    assert!(outcome.number < 2000);
    let (status, text) = server
        .http(
            "POST",
            "/api/exhibitions",
            r#"{"first":"easy","second":"nobody"}"#,
        )
        .await;
    assert_eq!(status, 400, "{text}");
}

#[tokio::test]
async fn chat_resignation_and_rematch_between_two_players() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, a, b) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&a)).await;
    let mut black = server.ws(&id, Some(&b)).await;
    let mut watcher = server.ws(&id, None).await;
    let mut commitments = Vec::new();
    for c in [&mut white, &mut black, &mut watcher] {
        commitments.push(view(c.next().await).noise_commitment);
    }
    // Everyone is shown the same commitment before the first shot.
    assert!(commitments[0].is_some() && commitments.iter().all(|c| *c == commitments[0]));
    black
        .send(&ClientMessage::Chat {
            text: "Vasily Ivanovich!".into(),
        })
        .await;
    for c in [&mut white, &mut watcher] {
        let ServerMessage::Chat {
            from, name, text, ..
        } = c.next_of("chat").await
        else {
            unreachable!()
        };
        assert_eq!(
            (from, name.as_str(), text.as_str()),
            (Some(Seat::Second), "Anka", "Vasily Ivanovich!")
        );
    }
    // A spectator talks under the name it said hello with, and a quick
    // phrase reaches everyone with its code and its English words.
    watcher
        .send(&ClientMessage::Chat { text: "hi".into() })
        .await;
    for c in [&mut white, &mut watcher] {
        let ServerMessage::Chat {
            from, name, text, ..
        } = c.next_of("chat").await
        else {
            unreachable!()
        };
        assert_eq!((from, name.as_str(), text.as_str()), (None, "test", "hi"));
    }
    white
        .send(&ClientMessage::Phrase {
            phrase: Phrase::GoodLuck,
        })
        .await;
    for c in [&mut white, &mut watcher] {
        let ServerMessage::Chat {
            from, text, phrase, ..
        } = c.next_of("chat").await
        else {
            unreachable!()
        };
        assert_eq!(
            (from, text.as_str(), phrase),
            (Some(Seat::First), "Good luck!", Some(Phrase::GoodLuck))
        );
    }
    white.send(&ClientMessage::OfferRematch).await;
    assert_eq!(white.next_error().await, "match-not-over");

    black.send(&ClientMessage::Resign).await;
    let ServerMessage::MatchOver { result, record } = watcher.next_of("match-over").await else {
        unreachable!()
    };
    assert_eq!(
        result,
        MatchResult::Won {
            side: Side::White,
            reason: WinReason::Resignation
        }
    );
    assert_eq!(record.moves.len(), 1);
    // The record reveals the secret of that commitment.
    let verified = game::verify(&record).unwrap();
    assert_eq!(Some(verified.commitment), commitments[0]);
    white.send(&shot(4, 0.0, 2.0)).await;
    assert_eq!(white.next_error().await, "match-over");

    white.send(&ClientMessage::OfferRematch).await;
    assert!(matches!(
        black.next_of("rematch-offered").await,
        ServerMessage::RematchOffered { by: Seat::First }
    ));
    black.send(&ClientMessage::AcceptRematch).await;
    let ServerMessage::RematchStarted { match_id } = white.next_of("rematch-started").await else {
        unreachable!()
    };
    assert_ne!(match_id, id);
    // Same tokens, seats exchanged: the old Black now opens as White.
    let mut new_white = server.ws(&match_id, Some(&b)).await;
    let ServerMessage::MatchState { you, view, .. } = new_white.next().await else {
        panic!()
    };
    assert_eq!(you, Some(Seat::First));
    // A rematch draws a secret of its own.
    assert!(view.noise_commitment.is_some());
    assert_ne!(view.noise_commitment, commitments[0]);
    new_white.send(&shot(4, 0.0, 2.0)).await;
    new_white.next_of("shot-played").await;
}

#[tokio::test]
async fn the_turn_clock_passes_the_turn_and_three_timeouts_in_a_row_forfeit() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, a, _) = server.two_player_match(r#","turn_seconds":1"#).await;
    let mut white = server.ws(&id, Some(&a)).await;
    view(white.next().await);
    // Nobody shoots: White, Black, White, Black time out, then White's third forfeits.
    let expected = [
        (Seat::First, 1),
        (Seat::Second, 1),
        (Seat::First, 2),
        (Seat::Second, 2),
        (Seat::First, 3),
    ];
    for (k, (seat, strikes)) in expected.into_iter().enumerate() {
        let m = white.next_of("turn-timed-out").await;
        assert_eq!(m, ServerMessage::TurnTimedOut { seat, strikes });
        if k < 4 {
            // The turn passes without a shot.
            let side = if seat == Seat::First {
                Side::White
            } else {
                Side::Black
            };
            assert_eq!(
                white.next_of("turn-passed").await,
                ServerMessage::TurnPassed { side }
            );
        }
    }
    assert_eq!(
        white.next_of("forfeited").await,
        ServerMessage::Forfeited {
            seat: Seat::First,
            reason: ForfeitReason::Timeouts
        }
    );
    let ServerMessage::MatchOver { result, .. } = white.next_of("match-over").await else {
        unreachable!()
    };
    assert_eq!(
        result,
        MatchResult::Won {
            side: Side::Black,
            reason: WinReason::Timeouts
        }
    );
}

#[tokio::test]
async fn a_dropped_player_keeps_the_seat_reconnects_with_the_token_and_the_opponent_is_told() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--grace-seconds", "30"]);
    let (id, a, b) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&a)).await;
    let black = server.ws(&id, Some(&b)).await;
    view(white.next().await);
    drop(black);
    let ServerMessage::PlayerLeft { seat, grace_ms } = white.next_of("player-left").await else {
        unreachable!()
    };
    assert_eq!((seat, grace_ms), (Seat::Second, 30_000));
    let mut black = server.ws(&id, Some(&b)).await;
    let ServerMessage::MatchState { you, .. } = black.next().await else {
        panic!()
    };
    assert_eq!(you, Some(Seat::Second));
    assert_eq!(
        white.next_of("player-back").await,
        ServerMessage::PlayerBack { seat: Seat::Second }
    );
    white.send(&shot(2, 0.0, 0.5)).await;
    black.next_of("shot-played").await;
    black.send(&shot(10, 0.0, -0.5)).await;
    white.next_of("shot-played").await;
}

#[tokio::test]
async fn a_player_gone_past_the_grace_period_forfeits() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--grace-seconds", "1"]);
    let (id, a, b) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&a)).await;
    let black = server.ws(&id, Some(&b)).await;
    view(white.next().await);
    drop(black);
    white.next_of("player-left").await;
    assert_eq!(
        white.next_of("forfeited").await,
        ServerMessage::Forfeited {
            seat: Seat::Second,
            reason: ForfeitReason::Abandoned
        }
    );
    let ServerMessage::MatchOver { result, .. } = white.next_of("match-over").await else {
        unreachable!()
    };
    assert_eq!(
        result,
        MatchResult::Won {
            side: Side::White,
            reason: WinReason::Abandoned
        }
    );
}

#[tokio::test]
async fn the_page_health_metrics_and_match_listing_answer() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (status, page) = server.http("GET", "/api", "").await;
    assert_eq!(status, 200);
    assert!(page.contains("/api/matches") && page.contains("/ws?match="));
    let (status, _) = server.http("GET", "/", "").await;
    assert_eq!(status, 200);
    let (status, health) = server.http("GET", "/healthz", "").await;
    assert_eq!(status, 200);
    assert!(health.contains(r#""status":"ok""#), "{health}");

    let (open, _) = server.create(r#"{"name":"Petka"}"#).await;
    let (live, a, _) = server.two_player_match("").await;
    let mut white = server.ws(&live, Some(&a)).await;
    view(white.next().await);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;

    let (_, list) = server.http("GET", "/api/matches?status=open", "").await;
    assert!(list.contains(&open) && !list.contains(&live), "{list}");
    let (_, list) = server.http("GET", "/api/matches?status=live", "").await;
    assert!(list.contains(&live) && !list.contains(&open), "{list}");
    let (status, one) = server
        .http("GET", &format!("/api/matches/{live}"), "")
        .await;
    assert_eq!(status, 200);
    assert!(one.contains(r#""shots":1"#), "{one}");

    let (_, metrics) = server.http("GET", "/metrics", "").await;
    for line in [
        "chapaev_connections 1",
        "chapaev_live_matches 1",
        "chapaev_shots_resolved_total 1",
        "chapaev_shot_resolution_seconds_count 1",
    ] {
        assert!(metrics.contains(line), "{line} in\n{metrics}");
    }
}

#[tokio::test]
async fn a_casual_match_created_with_a_seed_draws_the_seeds_noise_and_shows_the_seed() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let secret = game::NoiseSecret::from_seed(42);
    // Our first shot, the same in three matches against the computer
    // under the standard rules (which have noise): two seeded with 42 and
    // one with 43.
    let mut outcomes = Vec::new();
    for seed in [42, 42, 43] {
        let (id, token) = server
            .create(&format!(
                r#"{{"name":"Petka","opponent":"bot","bot_level":"easy","rules":"standard","seed":{seed}}}"#
            ))
            .await;
        let (status, summary) = server.http("GET", &format!("/api/matches/{id}"), "").await;
        assert_eq!(status, 200);
        let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
        assert_eq!(summary["seed"], seed, "{summary}");
        let commitment = game::NoiseSecret::from_seed(seed).commitment().to_hex();
        assert_eq!(summary["noise_commitment"], commitment.as_str());
        let mut me = server.ws(&id, Some(&token)).await;
        view(me.next().await);
        me.send(&shot(4, 0.0, 2.0)).await;
        let ServerMessage::ShotPlayed { outcome, .. } = me.next_of("shot-played").await else {
            unreachable!()
        };
        outcomes.push(serde_json::to_string(&outcome).unwrap());
        if seed == 42 {
            // The record reveals the secret the seed makes, as anyone can.
            me.send(&ClientMessage::Resign).await;
            me.next_of("match-over").await;
            let (status, record) = server
                .http("GET", &format!("/api/matches/{id}/record"), "")
                .await;
            assert_eq!(status, 200, "{record}");
            let record: serde_json::Value = serde_json::from_str(&record).unwrap();
            assert_eq!(record["noise"]["secret"], secret.to_hex().as_str());
        }
    }
    assert_eq!(outcomes[0], outcomes[1], "one seed, one noise");
    assert_ne!(outcomes[0], outcomes[2], "another seed, other noise");
    // The noise `bots match --seed 42` and `game::Game::new(config, 42)`
    // draw locally, to the bit.
    let mut local = game::Game::new(game::Preset::Standard.config(), 42).unwrap();
    let piece = game::PieceId::new(Side::White, 4).unwrap();
    let aim = game::Shot::new(piece, glam::DVec2::new(0.0, 2.0), local.config()).unwrap();
    let played = local.play(Side::White, aim).unwrap();
    assert_eq!(serde_json::to_string(&played.outcome).unwrap(), outcomes[0]);

    // A match without a seed shows none; a rated match takes none; a seed
    // past what JSON keeps exact is refused.
    let (id, _) = server.create(r#"{"name":"Petka"}"#).await;
    let (_, summary) = server.http("GET", &format!("/api/matches/{id}"), "").await;
    assert!(!summary.contains("\"seed\""), "{summary}");
    for (body, why) in [
        (
            r#"{"name":"Petka","rules":"standard","rated":true,"seed":1}"#,
            "rated",
        ),
        (r#"{"name":"Petka","seed":9007199254740992}"#, "at most"),
        (r#"{"name":"Petka","seed":-1}"#, "u64"),
    ] {
        let (status, text) = server.http("POST", "/api/matches", body).await;
        assert_eq!(status, 400, "{body}: {text}");
        assert!(text.contains(why), "{body}: {text}");
    }
}
