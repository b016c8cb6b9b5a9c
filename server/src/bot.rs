//! The built-in bots, which play a seat from inside the server. `easy`
//! flicks a random piece of its own, mostly towards a random enemy, at a
//! random speed. `medium` aims each of the pieces nearest an enemy straight
//! at that enemy at a few speeds, plays every candidate on a copy of the
//! match through [`game::Game::play`] and keeps the one that scores best
//! (enemies knocked off, own pieces kept, turn kept, round won).

use game::noise::SplitMix64;
use game::{Game, Next, Phase, RoundResult, Shot, Side};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// How strong a bot plays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BotLevel {
    Easy,
    Medium,
}

impl BotLevel {
    pub fn as_str(self) -> &'static str {
        match self {
            BotLevel::Easy => "easy",
            BotLevel::Medium => "medium",
        }
    }
    pub fn parse(s: &str) -> Option<BotLevel> {
        match s {
            "easy" => Some(BotLevel::Easy),
            "medium" => Some(BotLevel::Medium),
            _ => None,
        }
    }
}

/// The bot's move when it is to act.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BotMove {
    Shot(Shot),
    Pie { swap: bool },
}

/// What `level` does for `side` now (`None` when it has nothing to do).
pub fn choose(level: BotLevel, game: &Game, side: Side, rng: &mut SplitMix64) -> Option<BotMove> {
    match game.phase() {
        Phase::Over { .. } => None,
        Phase::PieDecision => (side == Side::Black).then(|| BotMove::Pie {
            // Take White's seat if White's first shot left it ahead.
            swap: level == BotLevel::Medium
                && game.board().count(Side::White) > game.board().count(Side::Black),
        }),
        Phase::Shooting if game.to_shoot() == Some(side) => {
            let shot = match level {
                BotLevel::Easy => random_shot(game, side, rng),
                BotLevel::Medium => best_shot(game, side).or_else(|| random_shot(game, side, rng)),
            };
            shot.map(BotMove::Shot)
        }
        Phase::Shooting => None,
    }
}

fn pick<'a, T>(items: &'a [T], rng: &mut SplitMix64) -> Option<&'a T> {
    if items.is_empty() {
        return None;
    }
    items.get((rng.next_u64() % items.len() as u64) as usize)
}

/// A random legal shot.
pub fn random_shot(game: &Game, side: Side, rng: &mut SplitMix64) -> Option<Shot> {
    let config = game.config();
    let own: Vec<_> = game.board().of(side).collect();
    let enemy: Vec<_> = game.board().of(side.opponent()).collect();
    let me = pick(&own, rng)?;
    let dir = match pick(&enemy, rng) {
        Some(target) if rng.next_f64() < 0.7 => target.pos - me.pos,
        _ => {
            let a = rng.next_f64() * std::f64::consts::TAU;
            DVec2::new(a.cos(), a.sin())
        }
    };
    let speed = config.max_speed * (0.3 + 0.7 * rng.next_f64());
    Shot::aimed(me.id, dir, speed, config).ok()
}

/// How good the position after a candidate is for `side`.
fn score(before: &Game, after: &Game, side: Side, next: &Next, round: Option<RoundResult>) -> f64 {
    let lost = |s: Side| before.board().count(s) as f64 - after.board().count(s) as f64;
    let mut total = 0.0;
    match round {
        Some(RoundResult::Won(w)) if w == side => total += 100.0,
        Some(RoundResult::Won(_)) => total -= 100.0,
        Some(RoundResult::Draw) => {}
        None => total += 10.0 * lost(side.opponent()) - 12.0 * lost(side),
    }
    if let Next::Shoot { side: s } = next {
        if *s == side {
            total += 3.0;
        }
    }
    total
}

/// The best of a handful of straight shots at the nearest enemies.
pub fn best_shot(game: &Game, side: Side) -> Option<Shot> {
    let config = game.config();
    let enemy: Vec<_> = game.board().of(side.opponent()).collect();
    // Each own piece with its nearest enemy, nearest pairs first.
    let mut pairs: Vec<_> = game
        .board()
        .of(side)
        .filter_map(|me| {
            enemy
                .iter()
                .map(|e| (me, *e, (e.pos - me.pos).length()))
                .min_by(|a, b| a.2.total_cmp(&b.2))
        })
        .collect();
    pairs.sort_by(|a, b| a.2.total_cmp(&b.2));
    let mut best: Option<(f64, Shot)> = None;
    for (me, target, _) in pairs.into_iter().take(4) {
        for fraction in [0.55, 0.8, 1.0] {
            let Ok(shot) = Shot::aimed(
                me.id,
                target.pos - me.pos,
                config.max_speed * fraction,
                config,
            ) else {
                continue;
            };
            let mut trial = game.clone();
            let Ok(played) = trial.play(side, shot) else {
                continue;
            };
            let round = played.outcome.round_end.map(|r| r.result);
            let s = score(game, &trial, side, &played.outcome.next, round);
            let better = match &best {
                Some((b, _)) => s > *b,
                None => true,
            };
            if better {
                best = Some((s, shot));
            }
        }
    }
    best.map(|(_, shot)| shot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::Config;

    #[test]
    fn both_bots_always_find_a_legal_shot_and_finish_a_match() {
        for level in [BotLevel::Easy, BotLevel::Medium] {
            let mut g = Game::new(Config::default(), 9).unwrap();
            let mut rng = SplitMix64::new(1);
            for _ in 0..400 {
                if g.is_over() {
                    break;
                }
                let side = g.to_shoot().unwrap_or(Side::Black);
                match choose(level, &g, side, &mut rng).unwrap() {
                    BotMove::Shot(s) => {
                        g.play(side, s).unwrap();
                    }
                    BotMove::Pie { swap } => g.decide_pie(side, swap).unwrap(),
                }
            }
            assert!(g.shots() > 0, "{level:?}");
        }
    }

    #[test]
    fn medium_knocks_off_a_piece_straight_ahead_from_the_opening() {
        let g = Game::new(Config::default(), 1).unwrap();
        let shot = best_shot(&g, Side::White).unwrap();
        let mut trial = g.clone();
        let out = trial.play(Side::White, shot).unwrap().outcome;
        assert!(!out.knocked_off.is_empty(), "{out:?}");
    }

    #[test]
    fn a_bot_does_nothing_out_of_turn() {
        let g = Game::new(Config::default(), 1).unwrap();
        let mut rng = SplitMix64::new(1);
        assert_eq!(choose(BotLevel::Easy, &g, Side::Black, &mut rng), None);
        assert_eq!(BotLevel::parse("medium"), Some(BotLevel::Medium));
        assert_eq!(BotLevel::parse("hard"), None);
    }
}
