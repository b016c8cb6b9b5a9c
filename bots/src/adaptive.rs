//! The adaptive level: a [`Planner`] whose hand steadies when it falls
//! behind and shakes when it gets ahead, so that a person of any strength
//! wins about half the time. Its state is one number, the strength (0:
//! shakier than `easy`; 1: nearly perfect), which sets the hand by
//! interpolating between [`AdaptiveSettings::weakest`] and
//! [`AdaptiveSettings::strongest`] (geometrically for the errors, so each
//! step is the same ratio). Before every shot it reads how the match
//! stands from the public view — the rows (rounds won) and the pieces left
//! on the board — and moves the strength against its lead, an integral
//! controller: as long as it leads it keeps weakening, as long as it
//! trails it keeps steadying, so the match is held near even. It learns
//! from the view rather than from [`Bot::on_shot`] because the server asks
//! its built-in levels only to decide; a bot object that plays several
//! matches carries the strength it found into the next.

use crate::bot::{Ask, Bot, Context, Decision};
use crate::candidates::Spread;
use crate::hand::HandModel;
use crate::handed::Handed;
use crate::planner::{PlanSettings, Planner};
use game::noise::SplitMix64;
use game::{MatchRecord, MatchResult, MatchView, Rows, ShotOutcome, Side};

/// How the adaptive level adapts.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveSettings {
    /// The hand at strength 0.
    pub weakest: HandModel,
    /// The hand at strength 1.
    pub strongest: HandModel,
    /// The strength a new bot starts at.
    pub start: f64,
    /// Strength moved per decision per unit of lead.
    pub gain: f64,
    /// A round won counts this much lead (a piece on the board counts
    /// 1/8).
    pub round_weight: f64,
    /// How it chooses its shots.
    pub plan: PlanSettings,
}

impl Default for AdaptiveSettings {
    fn default() -> Self {
        AdaptiveSettings {
            weakest: HandModel {
                angle_sigma: 0.15,
                speed_sigma: 0.30,
                distance_growth: 1.5,
                cut_growth: 1.0,
                bias_angle: 0.06,
                bias_speed: 0.12,
                full_power: 0.75,
            },
            strongest: HandModel {
                angle_sigma: 0.002,
                speed_sigma: 0.005,
                distance_growth: 0.5,
                cut_growth: 0.5,
                bias_angle: 0.001,
                bias_speed: 0.002,
                full_power: 0.99,
            },
            start: 0.5,
            gain: 0.02,
            round_weight: 0.5,
            plan: PlanSettings {
                spread: Spread::wide(),
                keep: 32,
                samples: 6,
            },
        }
    }
}

impl AdaptiveSettings {
    /// The hand at `strength` (clamped to 0–1).
    pub fn hand_at(&self, strength: f64) -> HandModel {
        let s = strength.clamp(0.0, 1.0);
        let geo = |a: f64, b: f64| {
            if a > 0.0 && b > 0.0 {
                a * (b / a).powf(s)
            } else {
                a + (b - a) * s
            }
        };
        let lin = |a: f64, b: f64| a + (b - a) * s;
        let (w, t) = (&self.weakest, &self.strongest);
        HandModel {
            angle_sigma: geo(w.angle_sigma, t.angle_sigma),
            speed_sigma: geo(w.speed_sigma, t.speed_sigma),
            distance_growth: lin(w.distance_growth, t.distance_growth),
            cut_growth: lin(w.cut_growth, t.cut_growth),
            bias_angle: geo(w.bias_angle, t.bias_angle),
            bias_speed: geo(w.bias_speed, t.bias_speed),
            full_power: lin(w.full_power, t.full_power),
        }
    }
}

/// How far `me` leads the match on `view`: rounds won (ranks its row has
/// advanced, less the opponent's) times `round_weight`, plus the pieces
/// on the board (its own less the opponent's) over eight.
pub fn lead(view: &MatchView, me: Side, round_weight: f64) -> f64 {
    let advance = |rows: Rows, side: Side| {
        let start = Rows::initial().rank(side);
        f64::from(rows.rank(side).abs_diff(start))
    };
    let rounds = advance(view.rows, me) - advance(view.rows, me.opponent());
    let pieces = view.board.count(me) as f64 - view.board.count(me.opponent()) as f64;
    round_weight * rounds + pieces / 8.0
}

/// The adaptive level.
#[derive(Clone, Debug)]
pub struct Adaptive {
    settings: AdaptiveSettings,
    strength: f64,
    player: Handed<Planner>,
}

impl Adaptive {
    /// An adaptive bot; its choices and its hand follow from `seed`.
    pub fn new(settings: AdaptiveSettings, seed: u64) -> Adaptive {
        let mut rng = SplitMix64::new(seed);
        let (a, b) = (rng.next_u64(), rng.next_u64());
        let strength = settings.start.clamp(0.0, 1.0);
        let model = settings.hand_at(strength);
        let planner = Planner::new(model, settings.plan.clone(), a);
        Adaptive {
            player: Handed::new(planner, model, b),
            settings,
            strength,
        }
    }

    /// The strength now, 0–1.
    pub fn strength(&self) -> f64 {
        self.strength
    }

    /// The hand it plays with now.
    pub fn hand(&self) -> &HandModel {
        self.player.hand().model()
    }

    /// Moves the strength against `me`'s lead on `view` and sets the hand.
    pub fn observe(&mut self, view: &MatchView, me: Side) {
        let lead = lead(view, me, self.settings.round_weight).clamp(-2.0, 2.0);
        self.strength = (self.strength - self.settings.gain * lead).clamp(0.0, 1.0);
        let model = self.settings.hand_at(self.strength);
        self.player.inner_mut().set_model(model);
        self.player.hand_mut().set_model(model);
    }
}

impl Bot for Adaptive {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Shoot) {
            self.observe(ctx.view, ctx.me);
        }
        self.player.decide(ctx)
    }
    fn on_shot(&mut self, outcome: &ShotOutcome) {
        self.player.on_shot(outcome)
    }
    fn on_match_over(&mut self, result: &MatchResult, record: &MatchRecord) {
        self.player.on_match_over(result, record)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Board, Config, Game, Phase};
    use std::time::Duration;

    /// The opening, with `lost` of `side`'s pieces taken off.
    fn without(side: Side, lost: usize) -> MatchView {
        let mut view = Game::new(Config::default(), 1).unwrap().view();
        let mut gone = 0;
        view.board = Board::from_pieces(view.board.pieces().iter().copied().filter(|p| {
            let take = p.id.side() == side && gone < lost;
            gone += usize::from(take);
            !take
        }));
        view
    }

    fn strength_after(view: &MatchView, decisions: usize) -> f64 {
        let mut bot = Adaptive::new(AdaptiveSettings::default(), 3);
        for _ in 0..decisions {
            bot.observe(view, Side::White);
        }
        bot.strength()
    }

    #[test]
    fn the_adaptive_level_weakens_while_ahead_and_steadies_while_behind() {
        let start = AdaptiveSettings::default().start;
        let even = strength_after(&without(Side::Black, 0), 5);
        assert_eq!(even, start, "an even board leaves it as it was");
        let ahead = strength_after(&without(Side::Black, 4), 5);
        let behind = strength_after(&without(Side::White, 4), 5);
        assert!(ahead < start && behind > start, "{ahead} {behind}");
        // A won round weighs more than a few pieces.
        let mut won = without(Side::Black, 0);
        won.rows = Rows::new(1, 7).unwrap();
        assert!(strength_after(&won, 5) < ahead);
    }

    #[test]
    fn a_weaker_adaptive_hand_misses_more_and_its_strength_stays_within_bounds() {
        let s = AdaptiveSettings::default();
        let (weak, strong) = (s.hand_at(0.2), s.hand_at(0.8));
        assert!(weak.angle_sigma > 2.0 * strong.angle_sigma);
        assert!(weak.speed_sigma > 2.0 * strong.speed_sigma);
        assert!(weak.full_power < strong.full_power);
        assert_eq!(s.hand_at(-3.0), s.weakest);
        assert_eq!(s.hand_at(7.0), s.strongest);
        let crushed = strength_after(&without(Side::White, 7), 500);
        assert_eq!(crushed, 1.0);
    }

    #[test]
    fn the_adaptive_level_shoots_with_the_hand_its_lead_calls_for() {
        let view = without(Side::Black, 5);
        let mut bot = Adaptive::new(AdaptiveSettings::default(), 8);
        let before = bot.hand().angle_sigma;
        let ctx = Context::new(&view, Side::White, Duration::from_secs(30));
        assert_eq!(view.phase, Phase::Shooting);
        let Decision::Shot(shot) = bot.decide(&ctx) else {
            panic!("it shoots");
        };
        assert!(bot.hand().angle_sigma > before, "ahead, it shakes more");
        assert_eq!(shot.piece().side(), Side::White);
        assert!(shot.speed() <= view.config.max_speed);
    }
}
