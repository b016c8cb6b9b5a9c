//! The adaptive level: a [`Planner`] whose hand is set, shot by shot, to
//! the strength the person has shown, so that a person of any strength
//! wins about half the time. Its strength (0: shakier than `easy`; 1:
//! nearly perfect) sets the hand by interpolating between
//! [`AdaptiveSettings::weakest`] and [`AdaptiveSettings::strongest`]
//! (geometrically for the errors, so each step is the same ratio).
//!
//! In Chapaev a shot that knocks off an enemy keeps the turn, and a
//! round's winner opens the next, so a side that rarely misses sweeps
//! round after round: the match turns on how often each side keeps the
//! turn. The level therefore watches the *person's* shots — read from the
//! public view before each of its own: `k` shots since its last turn mean
//! its own missed and the person kept the turn `k - 2` times before
//! missing — as a turn-keeping rate with a long, fading memory and a prior.
//! It maps that rate to the strength that plays even with such a person
//! (a line through two measured points, [`AdaptiveSettings::even`]), and
//! corrects the map as the match goes: a step down for every round it
//! wins, a larger step up for every round it loses, each scaled by the
//! winner's margin. It never learns from its own hits: a level that
//! weakened while it swept would hand a good person the turn for the rest
//! of the match. It reads the view rather than [`Bot::on_shot`] because
//! the server asks its built-in levels only to decide; a bot object that
//! plays several matches carries what it learned into the next.

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
    /// Two (person's turn-keeping rate, strength that plays even with
    /// that person) points; the strength for other rates is on their line.
    pub even: [(f64, f64); 2],
    /// The person's rate assumed before any shot is seen, and how many
    /// shots that assumption weighs.
    pub prior: (f64, f64),
    /// How much of the rate's memory is kept per shot seen (0.97: about
    /// the last thirty shots count).
    pub memory: f64,
    /// Correction moved down by a round won with all eight pieces left (a
    /// quarter of it with none: the step grows with the margin).
    pub round_step: f64,
    /// Correction moved up by a round lost to all eight of the person's
    /// pieces (larger than down: a hand that weakens too far hands a good
    /// person the turn, perhaps for the rest of the match).
    pub round_step_up: f64,
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
            even: [(0.74, 0.28), (0.84, 0.45)],
            prior: (0.78, 4.0),
            memory: 0.97,
            round_step: 0.04,
            round_step_up: 0.06,
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

    /// The strength that plays even with a person who keeps the turn at
    /// `rate` (not clamped).
    pub fn even_with(&self, rate: f64) -> f64 {
        let [(r0, s0), (r1, s1)] = self.even;
        if r1 == r0 {
            return s0;
        }
        s0 + (rate - r0) * (s1 - s0) / (r1 - r0)
    }
}

/// How often a side kept the turn, with a fading memory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TurnRate {
    kept: f64,
    shots: f64,
}

impl TurnRate {
    /// A rate of `rate` weighing `shots` shots.
    pub fn prior(rate: f64, shots: f64) -> TurnRate {
        TurnRate {
            kept: rate * shots,
            shots,
        }
    }

    /// The share of shots that kept the turn.
    pub fn rate(&self) -> f64 {
        if self.shots > 0.0 {
            self.kept / self.shots
        } else {
            0.5
        }
    }

    /// One more shot seen, older ones fading by `memory`.
    pub fn add(&mut self, kept: bool, memory: f64) {
        self.kept = self.kept * memory + f64::from(u8::from(kept));
        self.shots = self.shots * memory + 1.0;
    }
}

/// Ranks `me`'s row has advanced less the opponent's: rounds won, net.
pub fn rounds_lead(view: &MatchView, me: Side) -> f64 {
    let advance = |side: Side| {
        let start = Rows::initial().rank(side);
        f64::from(view.rows.rank(side).abs_diff(start))
    };
    advance(me) - advance(me.opponent())
}

/// What the adaptive level saw at its last turn.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Seen {
    shots: u32,
    rounds: f64,
    mine: usize,
    theirs: usize,
}

/// The adaptive level.
#[derive(Clone, Debug)]
pub struct Adaptive {
    settings: AdaptiveSettings,
    person: TurnRate,
    correction: f64,
    strength: f64,
    last: Option<Seen>,
    player: Handed<Planner>,
}

impl Adaptive {
    /// An adaptive bot; its choices and its hand follow from `seed`.
    pub fn new(settings: AdaptiveSettings, seed: u64) -> Adaptive {
        let mut rng = SplitMix64::new(seed);
        let (a, b) = (rng.next_u64(), rng.next_u64());
        let person = TurnRate::prior(settings.prior.0, settings.prior.1);
        let strength = settings.even_with(person.rate()).clamp(0.0, 1.0);
        let model = settings.hand_at(strength);
        let planner = Planner::new(model, settings.plan.clone(), a);
        Adaptive {
            player: Handed::new(planner, model, b),
            settings,
            person,
            correction: 0.0,
            strength,
            last: None,
        }
    }

    /// The strength now, 0–1.
    pub fn strength(&self) -> f64 {
        self.strength
    }

    /// How often the person has kept the turn, as far as it has seen.
    pub fn person(&self) -> TurnRate {
        self.person
    }

    /// The hand it plays with now.
    pub fn hand(&self) -> &HandModel {
        self.player.hand().model()
    }

    /// Learns from the shots played since its last turn (`me` on `view`),
    /// and sets its strength and hand.
    pub fn observe(&mut self, view: &MatchView, me: Side) {
        let s = &self.settings;
        let now = Seen {
            shots: view.shots,
            rounds: rounds_lead(view, me),
            mine: view.board.count(me),
            theirs: view.board.count(me.opponent()),
        };
        // The person's shots since: all but the last kept the turn.
        let last = self.last.filter(|l| now.shots >= l.shots);
        let person = match last {
            None => view.shots,
            Some(l) => (now.shots - l.shots).saturating_sub(1),
        };
        for k in 0..person {
            self.person.add(k + 1 < person, s.memory);
        }
        if let Some(l) = last {
            // The winner's pieces left (as last seen) say by how much.
            let margin = |left: usize| 0.25 + 0.75 * (left as f64 / 8.0).min(1.0);
            if now.rounds > l.rounds {
                self.correction -= s.round_step * margin(l.mine);
            } else if now.rounds < l.rounds {
                self.correction += s.round_step_up * margin(l.theirs);
            }
        }
        self.correction = self.correction.clamp(-1.0, 1.0);
        self.last = Some(now);
        let even = s.even_with(self.person.rate());
        self.strength = (even + self.correction).clamp(0.0, 1.0);
        let model = s.hand_at(self.strength);
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
        self.last = None;
        self.player.on_match_over(result, record)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, Phase};
    use std::time::Duration;

    fn opening() -> MatchView {
        Game::new(Config::default(), 1).unwrap().view()
    }

    #[test]
    fn the_adaptive_level_steadies_after_the_person_keeps_the_turn_and_shakes_after_misses() {
        let mut view = opening();
        let start = Adaptive::new(AdaptiveSettings::default(), 3);
        // The person ran nine shots before missing: a strong hand.
        let mut strong = start.clone();
        strong.observe(&view, Side::White);
        view.shots = 10;
        strong.observe(&view, Side::White);
        assert!(strong.person().rate() > 0.8);
        assert!(
            strong.strength() > start.strength(),
            "{}",
            strong.strength()
        );
        // Between each of its shots the person missed at once: a weak hand.
        let mut weak = start.clone();
        for k in 0..6 {
            view.shots = 2 * k;
            weak.observe(&view, Side::White);
        }
        assert!(weak.person().rate() < 0.6);
        assert!(weak.strength() < start.strength());
        assert!(weak.hand().angle_sigma > strong.hand().angle_sigma);
    }

    #[test]
    fn a_round_won_weakens_the_adaptive_level_and_a_round_lost_steadies_it_more() {
        let mut view = opening();
        let mut won = Adaptive::new(AdaptiveSettings::default(), 3);
        let mut lost = won.clone();
        let before = won.strength();
        won.observe(&view, Side::White);
        lost.observe(&view, Side::White);
        view.shots = 1;
        view.rows = Rows::new(1, 7).unwrap();
        won.observe(&view, Side::White);
        view.rows = Rows::new(0, 6).unwrap();
        lost.observe(&view, Side::White);
        assert!(won.strength() < before, "{}", won.strength());
        assert!(lost.strength() - before > before - won.strength());
    }

    #[test]
    fn a_weaker_adaptive_hand_misses_more_and_the_map_is_the_measured_line() {
        let s = AdaptiveSettings::default();
        let (weak, strong) = (s.hand_at(0.2), s.hand_at(0.8));
        assert!(weak.angle_sigma > 2.0 * strong.angle_sigma);
        assert!(weak.speed_sigma > 2.0 * strong.speed_sigma);
        assert!(weak.full_power < strong.full_power);
        assert_eq!(s.hand_at(-3.0), s.weakest);
        assert_eq!(s.hand_at(7.0), s.strongest);
        for (rate, strength) in s.even {
            assert!((s.even_with(rate) - strength).abs() < 1e-12);
        }
        assert!(s.even_with(0.9) > s.even_with(0.7));
    }

    #[test]
    fn the_adaptive_level_shoots_with_the_hand_it_learned() {
        let mut view = opening();
        let mut bot = Adaptive::new(AdaptiveSettings::default(), 8);
        let before = bot.hand().angle_sigma;
        // Black ran twelve shots before this turn.
        view.shots = 12;
        assert_eq!(view.phase, Phase::Shooting);
        let ctx = Context::new(&view, Side::White, Duration::from_secs(30));
        let Decision::Shot(shot) = bot.decide(&ctx) else {
            panic!("it shoots");
        };
        assert!(
            bot.hand().angle_sigma < before,
            "steadier against a strong hand"
        );
        assert_eq!(shot.piece().side(), Side::White);
        assert!(shot.speed() <= view.config.max_speed);
    }
}
