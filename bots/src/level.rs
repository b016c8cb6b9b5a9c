//! The computer levels people play against — `easy`, `medium`, `hard` —
//! and the [`Imprecise`] hand they share: a bot that aims perfectly makes
//! Chapaev a game of who shoots first, so each level misses like a person
//! does, by turning its own chosen shot by a Gaussian angle and scaling
//! its speed by a Gaussian factor drawn from its own generator (never from
//! the match). Each level's imprecision is public ([`Level::hand`]), shown
//! in the lobby, and comes on top of the match's own execution noise, if
//! any.

use crate::bot::{Bot, Context, Decision};
use crate::candidates::Spread;
use crate::greedy::Greedy;
use crate::random::RandomBot;
use crate::search::{Search, SearchSettings};
use game::noise::{NoiseDraw, SplitMix64};
use game::{MatchRecord, MatchResult, NoiseConfig, Shot, ShotOutcome};
use serde::{Deserialize, Serialize};
use std::fmt;

/// A bot whose shots are played by an imprecise hand.
#[derive(Clone, Debug)]
pub struct Imprecise<B> {
    inner: B,
    hand: NoiseConfig,
    rng: SplitMix64,
}

impl<B: Bot> Imprecise<B> {
    /// `inner`'s choices, aimed with `hand`'s imprecision drawn from `seed`.
    pub fn new(inner: B, hand: NoiseConfig, seed: u64) -> Imprecise<B> {
        Imprecise {
            inner,
            hand,
            rng: SplitMix64::new(seed),
        }
    }
}

impl<B: Bot> Bot for Imprecise<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        match self.inner.decide(ctx) {
            Decision::Shot(shot) => {
                let config = ctx.config();
                let draw = NoiseDraw::sample(&mut self.rng);
                let v = draw.apply(&self.hand, shot.velocity(), config.max_speed);
                Decision::Shot(Shot::new(shot.piece(), v, config).unwrap_or(shot))
            }
            other => other,
        }
    }
    fn on_shot(&mut self, outcome: &ShotOutcome) {
        self.inner.on_shot(outcome)
    }
    fn on_match_over(&mut self, result: &MatchResult, record: &MatchRecord) {
        self.inner.on_match_over(result, record)
    }
}

/// A computer level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Level {
    /// Straight shots at the enemies only, with a shaky hand.
    Easy,
    /// Greedy over straight, cut and carom shots, with a fair hand.
    Medium,
    /// The two-ply search under noise, with a steady hand.
    Hard,
}

impl Level {
    /// Every level, weakest first.
    pub const ALL: [Level; 3] = [Level::Easy, Level::Medium, Level::Hard];

    /// The level's wire name.
    pub fn as_str(self) -> &'static str {
        match self {
            Level::Easy => "easy",
            Level::Medium => "medium",
            Level::Hard => "hard",
        }
    }

    /// The level named `name`.
    pub fn parse(name: &str) -> Option<Level> {
        Level::ALL.into_iter().find(|l| l.as_str() == name)
    }

    /// How imprecise the level's own hand is.
    pub fn hand(self) -> NoiseConfig {
        match self {
            Level::Easy => NoiseConfig {
                angle_sigma: 0.10,
                speed_sigma: 0.20,
            },
            Level::Medium => NoiseConfig {
                angle_sigma: 0.03,
                speed_sigma: 0.08,
            },
            Level::Hard => NoiseConfig {
                angle_sigma: 0.015,
                speed_sigma: 0.04,
            },
        }
    }

    /// The level's bot, its choices and its hand following from `seed`.
    pub fn bot(self, seed: u64) -> Box<dyn Bot> {
        let hand = self.hand();
        let mut rng = SplitMix64::new(seed);
        let (a, b) = (rng.next_u64(), rng.next_u64());
        match self {
            Level::Easy => Box::new(Imprecise::new(
                Greedy::with_spread(Spread::narrow()),
                hand,
                a,
            )),
            Level::Medium => Box::new(Imprecise::new(Greedy::default(), hand, a)),
            Level::Hard => {
                let settings = SearchSettings {
                    assumed_noise: hand,
                    ..SearchSettings::default()
                };
                Box::new(Imprecise::new(Search::new(b, settings), hand, a))
            }
        }
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The bots the command line and tournaments know by name: `random`,
/// `greedy`, `search` (perfect hands: for bot-against-bot play, where the
/// match's noise is the only imprecision) and the levels `easy`, `medium`,
/// `hard`.
pub const BOT_NAMES: [&str; 6] = ["random", "greedy", "search", "easy", "medium", "hard"];

/// The bot named `name`, its choices following from `seed`.
pub fn by_name(name: &str, seed: u64) -> Option<Box<dyn Bot>> {
    Some(match name {
        "random" => Box::new(RandomBot::new(seed)),
        "greedy" => Box::new(Greedy::default()),
        "search" => Box::new(Search::new(seed, SearchSettings::default())),
        _ => Level::parse(name)?.bot(seed),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, Side};
    use std::time::Duration;

    #[test]
    fn an_imprecise_hand_turns_the_chosen_shot_a_little_and_keeps_it_legal() {
        let view = Game::new(Config::default(), 3).unwrap().view();
        let ctx = Context::new(&view, Side::White, Duration::from_secs(5));
        let Decision::Shot(aimed) = Greedy::default().decide(&ctx) else {
            panic!()
        };
        let mut bot = Imprecise::new(Greedy::default(), Level::Easy.hand(), 1);
        let Decision::Shot(played) = bot.decide(&ctx) else {
            panic!()
        };
        assert_eq!(played.piece(), aimed.piece());
        assert_ne!(played.velocity(), aimed.velocity());
        let turn = played.velocity().angle_to(aimed.velocity()).abs();
        assert!(turn < 0.5, "{turn}");
        assert!(played.speed() <= view.config.max_speed);
    }

    #[test]
    fn every_named_bot_exists_and_unknown_names_do_not() {
        for name in BOT_NAMES {
            assert!(by_name(name, 1).is_some(), "{name}");
        }
        assert!(by_name("grandmaster", 1).is_none());
        assert_eq!(Level::parse("hard"), Some(Level::Hard));
    }
}
