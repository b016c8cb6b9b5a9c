//! Fair play: a bot decides from the public view alone, so the match's
//! noise secret (which fixes the execution noise of every shot) can make no
//! difference to what it chooses. The view carries only the commitment to
//! the secret, never the secret.

use bots::{by_name, Bot, Context, Decision};
use game::{Config, Game, Phase, Side};
use std::time::Duration;

/// The views a match passes through, played by `greedy` under the
/// standard rules with match seed `seed`.
fn views(seed: u64, shots: u32) -> Vec<game::MatchView> {
    let mut game = Game::new(Config::standard(), seed).unwrap();
    let mut bot = by_name("greedy", 0).unwrap();
    let mut out = vec![game.view()];
    while game.shots() < shots && !game.is_over() {
        let side = match game.phase() {
            Phase::PieDecision => Side::Black,
            _ => game.to_shoot().unwrap(),
        };
        let view = game.view();
        match bot.decide(&Context::new(&view, side, Duration::from_secs(5))) {
            Decision::Shot(s) => {
                game.play(side, s).unwrap();
            }
            Decision::Pie { swap } => game.decide_pie(side, swap).unwrap(),
            Decision::Resign | Decision::NoAnswer => break,
        }
        out.push(game.view());
    }
    out
}

fn decide(name: &str, view: &game::MatchView) -> Decision {
    let side = match view.phase {
        Phase::PieDecision => Side::Black,
        _ => view.turn,
    };
    // The same bot seed each time: only the match seed differs.
    by_name(name, 42)
        .unwrap()
        .decide(&Context::new(view, side, Duration::from_secs(30)))
}

#[test]
fn a_bot_cannot_see_the_secret() {
    // Matches that differ only in their secret (and so in the noise every
    // shot will get) hand a bot views equal field for field but for the
    // commitment: the secret is in no view. A bot that could see it would
    // pick the shot whose noisy outcome it knew to be best, differently per
    // secret; ours choose alike.
    let game = Game::new(Config::standard(), 1).unwrap();
    let first = game.view();
    let json = serde_json::to_string(&first).unwrap();
    let game::NoiseKey::ChaCha20(secret) = game.noise_key() else {
        unreachable!("a new match is keyed by a secret")
    };
    assert!(
        !json.contains(&secret.to_hex()) && !json.contains("seed"),
        "{json}"
    );
    assert!(json.contains(&secret.commitment().to_hex()), "{json}");
    for name in bots::BOT_NAMES {
        let reference = decide(name, &first);
        for seed in [2, 77, 1 << 40, u64::MAX] {
            let view = Game::new(Config::standard(), seed).unwrap().view();
            assert_ne!(view.noise_commitment, first.noise_commitment);
            let mut bare = view.clone();
            bare.noise_commitment = first.noise_commitment;
            assert_eq!(bare, first);
            assert_eq!(
                decide(name, &view),
                reference,
                "{name} under the secret of seed {seed}"
            );
        }
    }
    // Later positions too: the decision is a function of the view alone.
    for view in views(1, 5).iter().skip(1) {
        for name in ["greedy", "search"] {
            assert_eq!(decide(name, view), decide(name, view), "{name}");
        }
    }
}

#[test]
fn the_same_seed_for_a_bot_gives_the_same_match_and_another_match_seed_another() {
    let a = views(3, 8);
    let b = views(3, 8);
    assert_eq!(a, b, "deterministic for the same seeds");
    let c = views(4, 8);
    assert_ne!(a, c, "the noise follows the match seed");
}
