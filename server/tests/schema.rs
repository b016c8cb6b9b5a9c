//! Real server traffic validated against the protocol's JSON Schema, as
//! the server itself serves it at `/api/schema/v1.json`.

mod common;

use common::{shot, view, Client, Server};
use game::protocol::{ClientMessage, SCHEMA_PATH};
use std::time::Duration;

/// A validator for one root of the served schema document.
fn validator(schema: &serde_json::Value, root: &str) -> jsonschema::Validator {
    let mut doc = schema.clone();
    doc["$ref"] = serde_json::json!(format!("#/$defs/{root}"));
    doc.as_object_mut().map(|o| o.remove("anyOf"));
    jsonschema::validator_for(&doc).expect("the schema compiles")
}

fn check(v: &jsonschema::Validator, texts: &[String], root: &str) -> usize {
    for text in texts {
        let value: serde_json::Value = serde_json::from_str(text).unwrap();
        let errors: Vec<String> = v.iter_errors(&value).map(|e| e.to_string()).collect();
        assert!(errors.is_empty(), "{root} {text}: {errors:?}");
    }
    texts.len()
}

#[tokio::test]
async fn every_message_of_a_match_validates_against_the_served_schema() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--grace-seconds", "30"]);
    let (status, text) = server.http("GET", SCHEMA_PATH, "").await;
    assert_eq!(status, 200);
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let (id, a) = server
        .create(r#"{"name":"Petka","rules":"standard","turn_seconds":1}"#)
        .await;
    let mut white = server.ws(&id, Some(&a)).await;
    // The client said hello (with the token) and took the welcome.
    assert!(white.sent[0].contains(r#""type":"hello""#));
    assert!(white.received[0].contains(r#""type":"welcome""#));
    let b = server.join(&id).await;
    white.next_of("player-joined").await;
    let mut black = server.ws(&id, Some(&b)).await;
    let mut watcher = server.ws(&id, None).await;
    view(black.next().await);
    view(watcher.next().await);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    black
        .send(&ClientMessage::PieDecision { swap: false })
        .await;
    white.next_of("pie-decided").await;
    black.send(&shot(12, 0.0, -2.0)).await;
    black.next_of("error").await;
    black
        .send(&ClientMessage::Chat {
            text: "Vasily Ivanovich!".into(),
        })
        .await;
    white.next_of("chat").await;
    // White lets its 1 s clock run out: the turn passes.
    white.next_of("turn-timed-out").await;
    white.next_of("turn-passed").await;
    // Black drops and comes back.
    drop(black);
    white.next_of("player-left").await;
    let mut black = Client::connect(&server.addr, &id, Some(&b)).await;
    white.next_of("player-back").await;
    black.send(&ClientMessage::Resign).await;
    white.next_of("match-over").await;
    white.send(&ClientMessage::OfferRematch).await;
    black.next_of("rematch-offered").await;
    black.send(&ClientMessage::AcceptRematch).await;
    white.next_of("rematch-started").await;
    tokio::time::sleep(Duration::from_millis(100)).await;
    // Drain what the watcher saw.
    watcher.next_of("rematch-started").await;

    let server_messages = validator(&schema, "ServerMessage");
    let client_messages = validator(&schema, "ClientMessage");
    let mut n = 0;
    for c in [&white, &black, &watcher] {
        n += check(&server_messages, &c.received, "ServerMessage");
        check(&client_messages, &c.sent, "ClientMessage");
    }
    let kinds: std::collections::BTreeSet<String> = [&white, &black, &watcher]
        .iter()
        .flat_map(|c| c.received.iter())
        .map(|t| serde_json::from_str::<serde_json::Value>(t).unwrap()["type"].to_string())
        .collect();
    assert!(
        kinds.len() >= 14,
        "{n} messages of {} kinds: {kinds:?}",
        kinds.len()
    );

    // The simulate endpoint's answer validates too.
    let req = game::simulate::random_request(&mut game::noise::SplitMix64::new(2));
    let body = serde_json::to_string(&req).unwrap();
    let (status, answer) = server.http("POST", "/api/simulate", &body).await;
    assert_eq!(status, 200);
    check(
        &validator(&schema, "SimulateRequest"),
        &[body],
        "SimulateRequest",
    );
    check(&validator(&schema, "Simulation"), &[answer], "Simulation");
    // And a match's record.
    let (_, record) = server
        .http("GET", &format!("/api/matches/{id}/record"), "")
        .await;
    check(&validator(&schema, "MatchRecord"), &[record], "MatchRecord");
}
