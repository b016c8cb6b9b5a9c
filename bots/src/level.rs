//! The computer levels people play against — `easy`, `medium`, `hard` and
//! `adaptive` — and the older [`Imprecise`] hand. Each fixed level is a
//! chooser that knows its own hand ([`Planner`] for easy and medium, the
//! two-ply [`Search`] for hard, each planning under draws of its own
//! hand's error) played through a person-like [`crate::hand::Hand`]
//! ([`Handed`]): a pull that persists through a match, more error on long
//! shots and thin cuts, and a full power below the maximum that can come
//! out harder. The adaptive level ([`Adaptive`]) tunes its hand during a
//! match to keep the person's chances even. All their randomness comes
//! from the seed they are made with, never from the match. Each level's
//! hand is public ([`Level::hand`]).
//!
//! [`Imprecise`] is the earlier model, kept as a plain stand-in for a
//! person: the chosen shot turned and scaled by one i.i.d. Gaussian draw,
//! with the same spread whatever the shot.

use crate::adaptive::{Adaptive, AdaptiveSettings};
use crate::bot::{Bot, Context, Decision};
use crate::candidates::Spread;
use crate::greedy::Greedy;
use crate::hand::HandModel;
use crate::handed::Handed;
use crate::planner::{PlanSettings, Planner};
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
    /// Straight shots at the enemies only, chosen for a shaky hand.
    Easy,
    /// Straight, cut and carom shots, chosen for a fair hand.
    Medium,
    /// The two-ply search, planned for a steady hand.
    Hard,
    /// A hand that steadies while it trails and shakes while it leads, so
    /// that the person wins about half the time.
    Adaptive,
}

impl Level {
    /// Every level: the fixed ones weakest first, then the adaptive one.
    pub const ALL: [Level; 4] = [Level::Easy, Level::Medium, Level::Hard, Level::Adaptive];

    /// The level's wire name.
    pub fn as_str(self) -> &'static str {
        match self {
            Level::Easy => "easy",
            Level::Medium => "medium",
            Level::Hard => "hard",
            Level::Adaptive => "adaptive",
        }
    }

    /// The level named `name`.
    pub fn parse(name: &str) -> Option<Level> {
        Level::ALL.into_iter().find(|l| l.as_str() == name)
    }

    /// How the level's hand misses (for `adaptive`: the hand it starts a
    /// match with, which then changes).
    pub fn hand(self) -> HandModel {
        match self {
            Level::Easy => HandModel {
                angle_sigma: 0.05,
                speed_sigma: 0.12,
                distance_growth: 1.5,
                cut_growth: 1.0,
                bias_angle: 0.025,
                bias_speed: 0.06,
                full_power: 0.8,
            },
            Level::Medium => HandModel {
                angle_sigma: 0.02,
                speed_sigma: 0.06,
                distance_growth: 1.0,
                cut_growth: 0.8,
                bias_angle: 0.01,
                bias_speed: 0.03,
                full_power: 0.88,
            },
            Level::Hard => HandModel {
                angle_sigma: 0.008,
                speed_sigma: 0.03,
                distance_growth: 0.5,
                cut_growth: 0.5,
                bias_angle: 0.004,
                bias_speed: 0.015,
                full_power: 0.94,
            },
            Level::Adaptive => {
                let s = AdaptiveSettings::default();
                s.hand_at(s.start)
            }
        }
    }

    /// How a fixed level chooses (`None` for `hard`, which searches, and
    /// `adaptive`).
    pub fn plan(self) -> Option<PlanSettings> {
        match self {
            Level::Easy => Some(PlanSettings {
                spread: Spread {
                    speeds: vec![0.4, 0.6, 0.8, 1.0],
                    cuts: vec![0.0],
                    caroms: false,
                },
                keep: 24,
                samples: 6,
            }),
            Level::Medium => Some(PlanSettings {
                spread: Spread::wide(),
                keep: 24,
                samples: 8,
            }),
            Level::Hard | Level::Adaptive => None,
        }
    }

    /// A fixed level's bot as the chooser and its hand, which can log its
    /// throws (`None` for `adaptive`, whose hand changes).
    pub fn handed(self, seed: u64) -> Option<Handed<Box<dyn Bot>>> {
        let hand = self.hand();
        let mut rng = SplitMix64::new(seed);
        let (a, b) = (rng.next_u64(), rng.next_u64());
        let chooser: Box<dyn Bot> = match self {
            Level::Easy | Level::Medium => Box::new(Planner::new(hand, self.plan()?, b)),
            Level::Hard => {
                let settings = SearchSettings {
                    hand: Some(hand),
                    ..SearchSettings::default()
                };
                Box::new(Search::new(b, settings))
            }
            Level::Adaptive => return None,
        };
        Some(Handed::new(chooser, hand, a))
    }

    /// The level's bot, its choices and its hand following from `seed`.
    pub fn bot(self, seed: u64) -> Box<dyn Bot> {
        match self.handed(seed) {
            Some(bot) => Box::new(bot),
            None => Box::new(Adaptive::new(AdaptiveSettings::default(), seed)),
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
/// `hard`, `adaptive`.
pub const BOT_NAMES: [&str; 7] = [
    "random", "greedy", "search", "easy", "medium", "hard", "adaptive",
];

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
        let hand = NoiseConfig {
            angle_sigma: 0.10,
            speed_sigma: 0.20,
        };
        let mut bot = Imprecise::new(Greedy::default(), hand, 1);
        let Decision::Shot(played) = bot.decide(&ctx) else {
            panic!()
        };
        assert_eq!(played.piece(), aimed.piece());
        assert_ne!(played.velocity(), aimed.velocity());
        let turn = played.velocity().angle_to(aimed.velocity()).abs();
        assert!(turn < 0.5, "{turn}");
        assert!(played.speed() <= view.config.max_speed);
    }

    /// Two white pieces against four black: a short shot at a piece one
    /// square ahead, or a long cut across the board.
    fn set_position() -> game::MatchView {
        use game::board::{square_centre, Piece};
        use game::{Board, PieceId};
        let mut view = Game::new(Config::default(), 1).unwrap().view();
        let c = view.config.clone();
        let p = |side, k, file, rank| Piece {
            id: PieceId::new(side, k).unwrap(),
            pos: square_centre(&c, file, rank),
        };
        view.board = Board::from_pieces([
            p(Side::White, 0, 1, 1),
            p(Side::White, 1, 6, 0),
            p(Side::Black, 0, 1, 2),
            p(Side::Black, 1, 6, 4),
            p(Side::Black, 2, 6, 7),
            p(Side::Black, 3, 3, 6),
        ]);
        view
    }

    #[test]
    fn a_shaky_hand_prefers_a_short_shot_where_a_steady_one_goes_long() {
        let view = set_position();
        let ctx = Context::new(&view, Side::White, Duration::from_secs(30));
        // The same candidates for both: only the hand differs.
        let plan = Level::Medium.plan().unwrap();
        let chosen = |model: HandModel| {
            let mut planner = Planner::new(model, plan.clone(), 5);
            let (shot, _) = planner.ranked(&ctx, Side::White)[0];
            crate::hand::Aim::of(&view.config, &view.board, &shot)
        };
        let steady = chosen(HandModel::PERFECT);
        let shaky = chosen(Level::Easy.hand());
        assert!(steady.distance > 3.0 * view.config.square, "{steady:?}");
        assert!(shaky.distance < view.config.square, "{shaky:?}");
    }

    #[test]
    fn the_same_seed_gives_the_same_choices_and_another_seed_another_hand() {
        let view = Game::new(Config::default(), 3).unwrap().view();
        let ctx = Context::new(&view, Side::White, Duration::from_secs(30));
        for level in Level::ALL {
            let a = level.bot(7).decide(&ctx);
            assert_eq!(a, level.bot(7).decide(&ctx), "{level}");
            assert_ne!(a, level.bot(8).decide(&ctx), "{level}");
        }
    }

    #[test]
    fn the_levels_hands_steady_from_easy_to_hard_and_each_can_overhit_full_power() {
        let [easy, medium, hard] = [Level::Easy, Level::Medium, Level::Hard].map(Level::hand);
        assert!(easy.angle_sigma > medium.angle_sigma && medium.angle_sigma > hard.angle_sigma);
        assert!(easy.speed_sigma > medium.speed_sigma && medium.speed_sigma > hard.speed_sigma);
        for h in [easy, medium, hard] {
            // Full power is below the maximum, and a three-sigma overhit reaches it.
            assert!(h.full_power < 1.0 && h.full_power * (1.0 + 3.0 * h.speed_sigma) > 1.0);
        }
    }

    #[test]
    fn every_named_bot_exists_and_unknown_names_do_not() {
        for name in BOT_NAMES {
            assert!(by_name(name, 1).is_some(), "{name}");
        }
        assert!(by_name("grandmaster", 1).is_none());
        assert_eq!(Level::parse("hard"), Some(Level::Hard));
        assert_eq!(Level::parse("adaptive"), Some(Level::Adaptive));
        for level in Level::ALL {
            assert_eq!(Level::parse(level.as_str()), Some(level));
        }
    }
}
