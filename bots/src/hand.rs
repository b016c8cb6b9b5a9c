//! A person's hand: how a computer level's intended shot comes out. A
//! person does not miss like an i.i.d. Gaussian: each has a habitual pull
//! (a bias of direction and of strength that persists through a match),
//! misses more on long shots and on thin cuts than on short straight ones,
//! and their "full power" is a flick they can overdo as well as underdo.
//! [`HandModel`] holds these parameters (public per level); [`Hand`] is
//! one hand for one match: the model, the match's bias (drawn once from the
//! level's own generator, redrawn for the next match) and the generator of
//! its shot-to-shot errors. Nothing here ever sees the match's seed: the
//! hand's randomness comes only from the seed the level was made with.
//!
//! The error of one shot depends on its [`Aim`]: the first piece on the
//! shot's line (the target), how far the flicked piece travels to reach
//! it, and how thin the cut is (the target centre's distance from the line,
//! as a fraction of the contact distance, 0 straight to 1 grazing). The
//! standard deviations grow linearly with both:
//! `sigma = base * (1 + distance_growth * distance / board) * (1 + cut_growth * cut)`.

use game::noise::{NoiseDraw, SplitMix64};
use game::{Board, Config, Shot};
use glam::DVec2;
use serde::Serialize;

/// How a hand misses: the parameters of one level's imprecision.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HandModel {
    /// Standard deviation of the direction on a short straight shot, rad.
    pub angle_sigma: f64,
    /// Standard deviation of the speed on a short straight shot, as a
    /// fraction of the intended speed.
    pub speed_sigma: f64,
    /// How much the errors grow over one board's length of travel (0: not
    /// at all; 1: doubled).
    pub distance_growth: f64,
    /// How much the errors grow on a grazing cut (0: not at all; 1:
    /// doubled).
    pub cut_growth: f64,
    /// Standard deviation of the match's persistent pull of direction, rad.
    pub bias_angle: f64,
    /// Standard deviation of the match's persistent over- or underhitting,
    /// as a fraction of the speed.
    pub bias_speed: f64,
    /// The hand's nominal full power as a fraction of the rules' maximum
    /// speed: below 1, so that a full-power flick can come out harder too
    /// (it is then clamped at the maximum, as the game demands).
    pub full_power: f64,
}

impl HandModel {
    /// A perfect hand: every shot exactly as intended, full power at the
    /// maximum.
    pub const PERFECT: HandModel = HandModel {
        angle_sigma: 0.0,
        speed_sigma: 0.0,
        distance_growth: 0.0,
        cut_growth: 0.0,
        bias_angle: 0.0,
        bias_speed: 0.0,
        full_power: 1.0,
    };

    /// The standard deviations `(angle, speed)` of a shot with `aim`
    /// (the bias comes on top).
    pub fn sigmas(&self, config: &Config, aim: &Aim) -> (f64, f64) {
        let along = aim.distance / config.board_size();
        let grow = (1.0 + self.distance_growth * along) * (1.0 + self.cut_growth * aim.cut);
        (self.angle_sigma * grow, self.speed_sigma * grow)
    }

    /// The hand with every error scaled by `factor` (and full power kept).
    pub fn scaled(&self, factor: f64) -> HandModel {
        HandModel {
            angle_sigma: self.angle_sigma * factor,
            speed_sigma: self.speed_sigma * factor,
            bias_angle: self.bias_angle * factor,
            bias_speed: self.bias_speed * factor,
            ..*self
        }
    }

    /// The velocity played when `shot` is flicked with aim `aim`, draw
    /// `draw` (standard normals) and per-match `bias`: turned by
    /// `bias.angle + angle_sigma * draw.angle`, its speed scaled by
    /// `1 + bias.speed + speed_sigma * draw.speed`, clamped to the rules'
    /// maximum (never refused, never replaced by the perfect shot).
    pub fn velocity(
        &self,
        config: &Config,
        shot: &Shot,
        aim: &Aim,
        draw: NoiseDraw,
        bias: Bias,
    ) -> DVec2 {
        let v = shot.velocity();
        let speed = v.length();
        if speed == 0.0 {
            return v;
        }
        let (sa, ss) = self.sigmas(config, aim);
        let turn = bias.angle + sa * draw.angle;
        // A flick never comes out backwards or dead: at least a fifth.
        let factor = (1.0 + bias.speed + ss * draw.speed).max(0.2);
        let new_speed = (speed * factor).min(config.max_speed);
        DVec2::from_angle(turn).rotate(v / speed) * new_speed
    }

    /// `shot` as this hand plays it (see [`HandModel::velocity`]), a valid
    /// shot under `config`.
    pub fn play(
        &self,
        config: &Config,
        board: &Board,
        shot: &Shot,
        draw: NoiseDraw,
        bias: Bias,
    ) -> Shot {
        let aim = Aim::of(config, board, shot);
        self.shot(config, shot, &aim, draw, bias)
    }

    /// `shot`, whose aim is `aim`, as this hand plays it with `draw` and
    /// `bias` (see [`HandModel::velocity`]): a valid shot under `config`.
    pub fn shot(
        &self,
        config: &Config,
        shot: &Shot,
        aim: &Aim,
        draw: NoiseDraw,
        bias: Bias,
    ) -> Shot {
        let v = self.velocity(config, shot, aim, draw, bias);
        // The clamp can leave the length an ulp above the maximum; only a
        // non-finite velocity (never from finite inputs) keeps the aim.
        Shot::new(shot.piece(), v, config)
            .or_else(|_| Shot::new(shot.piece(), v * (1.0 - 1e-12), config))
            .unwrap_or(*shot)
    }
}

/// A hand's persistent pull for one match.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Bias {
    /// Added to every shot's direction, rad.
    pub angle: f64,
    /// Added to every shot's speed factor.
    pub speed: f64,
}

impl Bias {
    /// A bias drawn for `model` from `rng`.
    pub fn draw(model: &HandModel, rng: &mut SplitMix64) -> Bias {
        let d = NoiseDraw::sample(rng);
        Bias {
            angle: model.bias_angle * d.angle,
            speed: model.bias_speed * d.speed,
        }
    }
}

/// What a shot aims at: the first piece on its line, how far the flicked
/// piece goes to touch it and how thin the cut is.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Aim {
    /// The target piece's position (`None`: the line meets no piece).
    #[serde(skip)]
    pub target: Option<DVec2>,
    /// Travel to the contact, m (without a target: how far the piece
    /// slides, at most the board's diagonal).
    pub distance: f64,
    /// 0: straight at the target's centre; 1: grazing it.
    pub cut: f64,
}

impl Aim {
    /// The aim of `shot` on `board`.
    pub fn of(config: &Config, board: &Board, shot: &Shot) -> Aim {
        let v = shot.velocity();
        let dir = v.normalize_or_zero();
        let reach = 2.0 * config.piece_radius;
        let Some(me) = board.piece(shot.piece()) else {
            return Aim::nothing(config, v.length());
        };
        let mut best: Option<Aim> = None;
        for p in board.pieces() {
            if p.id == me.id {
                continue;
            }
            let rel = p.pos - me.pos;
            let ahead = rel.dot(dir);
            let side = rel.perp_dot(dir).abs();
            if ahead <= 0.0 || side >= reach {
                continue;
            }
            let distance = (ahead - (reach * reach - side * side).sqrt()).max(0.0);
            if best.is_none_or(|b| distance < b.distance) {
                best = Some(Aim {
                    target: Some(p.pos),
                    distance,
                    cut: side / reach,
                });
            }
        }
        best.unwrap_or_else(|| Aim::nothing(config, v.length()))
    }

    fn nothing(config: &Config, speed: f64) -> Aim {
        let diagonal = config.board_size() * std::f64::consts::SQRT_2;
        Aim {
            target: None,
            distance: config.stopping_distance(speed).min(diagonal),
            cut: 0.0,
        }
    }
}

/// One hand for one match: a model, the match's bias and the generator of
/// its errors (and of the next match's bias).
#[derive(Clone, Debug)]
pub struct Hand {
    model: HandModel,
    bias: Bias,
    rng: SplitMix64,
}

impl Hand {
    /// A hand of `model` whose bias and errors follow from `seed` alone.
    pub fn new(model: HandModel, seed: u64) -> Hand {
        let mut rng = SplitMix64::new(seed);
        let bias = Bias::draw(&model, &mut rng);
        Hand { model, bias, rng }
    }

    /// The model.
    pub fn model(&self) -> &HandModel {
        &self.model
    }

    /// This match's bias.
    pub fn bias(&self) -> Bias {
        self.bias
    }

    /// Changes the model (an adaptive level's hand steadying or shaking),
    /// keeping the match's bias in proportion.
    pub fn set_model(&mut self, model: HandModel) {
        let ratio = |new: f64, old: f64| if old > 0.0 { new / old } else { 0.0 };
        self.bias = Bias {
            angle: self.bias.angle * ratio(model.bias_angle, self.model.bias_angle),
            speed: self.bias.speed * ratio(model.bias_speed, self.model.bias_speed),
        };
        self.model = model;
    }

    /// A new match: a new bias from the hand's own generator.
    pub fn new_match(&mut self) {
        self.bias = Bias::draw(&self.model, &mut self.rng);
    }

    /// `shot` as this hand plays it now (one fresh draw, this match's bias).
    pub fn play(&mut self, config: &Config, board: &Board, shot: &Shot) -> Shot {
        let draw = NoiseDraw::sample(&mut self.rng);
        self.model.play(config, board, shot, draw, self.bias)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, PieceId, Side};

    fn model() -> HandModel {
        HandModel {
            angle_sigma: 0.05,
            speed_sigma: 0.1,
            distance_growth: 1.5,
            cut_growth: 1.0,
            bias_angle: 0.03,
            bias_speed: 0.05,
            full_power: 0.8,
        }
    }

    fn opening() -> (Config, Board) {
        let g = Game::new(Config::default(), 1).unwrap();
        (g.config().clone(), g.board().clone())
    }

    fn piece(side: Side, k: u8) -> PieceId {
        PieceId::new(side, k).unwrap()
    }

    #[test]
    fn the_aim_finds_the_first_piece_on_the_line_and_how_thin_the_cut_is() {
        let (c, b) = opening();
        let me = b.piece(piece(Side::White, 3)).unwrap().pos;
        let target = b.piece(piece(Side::Black, 3)).unwrap().pos;
        let straight = Shot::aimed(piece(Side::White, 3), target - me, 1.0, &c).unwrap();
        let aim = Aim::of(&c, &b, &straight);
        assert_eq!(aim.target, Some(target));
        assert!(aim.cut < 1e-9);
        let gap = target.distance(me) - 2.0 * c.piece_radius;
        assert!((aim.distance - gap).abs() < 1e-9, "{aim:?}");
        // Aimed half a piece's width to the side: a cut of a quarter.
        let across = (target - me).perp().normalize() * c.piece_radius;
        let cut = Shot::aimed(piece(Side::White, 3), target + across - me, 1.0, &c).unwrap();
        let aim = Aim::of(&c, &b, &cut);
        assert_eq!(aim.target, Some(target));
        assert!((aim.cut - 0.5).abs() < 0.01, "{aim:?}");
    }

    #[test]
    fn long_shots_and_thin_cuts_are_given_more_error_than_short_straight_ones() {
        let (c, _) = opening();
        let m = model();
        let short = Aim {
            target: None,
            distance: 0.02,
            cut: 0.0,
        };
        let long = Aim {
            distance: 0.25,
            ..short
        };
        let thin = Aim { cut: 0.8, ..short };
        assert!(m.sigmas(&c, &long).0 > 1.5 * m.sigmas(&c, &short).0);
        assert!(m.sigmas(&c, &thin).0 > 1.5 * m.sigmas(&c, &short).0);
        assert!(m.sigmas(&c, &long).1 > m.sigmas(&c, &short).1);
    }

    #[test]
    fn full_power_can_come_out_harder_and_is_clamped_at_the_maximum_not_refused() {
        let (c, b) = opening();
        let m = model();
        let full = c.max_speed * m.full_power;
        let shot = Shot::aimed(piece(Side::White, 0), DVec2::Y, full, &c).unwrap();
        let mut rng = SplitMix64::new(9);
        let (mut harder, mut clamped, mut softer) = (0, 0, 0);
        for _ in 0..400 {
            let played = m.play(&c, &b, &shot, NoiseDraw::sample(&mut rng), Bias::default());
            assert!(played.speed() <= c.max_speed);
            assert_ne!(played, shot, "never the perfect shot as a fallback");
            if played.speed() > full * 1.01 {
                harder += 1;
            }
            if played.speed() > c.max_speed * 0.999_999 {
                clamped += 1;
            }
            if played.speed() < full * 0.99 {
                softer += 1;
            }
        }
        assert!(
            harder > 100 && softer > 100,
            "{harder} harder, {softer} softer"
        );
        assert!(clamped > 0, "a wild flick is clamped at the maximum");
    }

    #[test]
    fn the_bias_persists_within_a_match_and_is_redrawn_for_the_next() {
        let (c, b) = opening();
        // A pull larger than the shot-to-shot spread, to see it plainly.
        let steady_but_pulling = HandModel {
            angle_sigma: 0.01,
            bias_angle: 0.05,
            ..model()
        };
        // The first seed whose pull is at least 0.02 rad (a 0.4 sigma draw).
        let mut hand = (1..)
            .map(|seed| Hand::new(steady_but_pulling, seed))
            .find(|h| h.bias().angle.abs() > 0.02)
            .unwrap();
        let first = hand.bias();
        let shot = Shot::aimed(piece(Side::White, 0), DVec2::Y, 1.0, &c).unwrap();
        // Many shots of one match pull the same way on average.
        let mean_turn = |hand: &mut Hand| {
            (0..300)
                .map(|_| {
                    shot.velocity()
                        .angle_to(hand.play(&c, &b, &shot).velocity())
                })
                .sum::<f64>()
                / 300.0
        };
        let turn = mean_turn(&mut hand);
        assert_eq!(hand.bias(), first);
        assert!((turn - first.angle).abs() < 0.005, "{turn} vs {first:?}");
        hand.new_match();
        assert_ne!(hand.bias(), first);
        let next = mean_turn(&mut hand);
        assert!((next - hand.bias().angle).abs() < 0.005);
    }

    #[test]
    fn the_same_seed_gives_the_same_hand_and_another_seed_another() {
        let (c, b) = opening();
        let shot = Shot::aimed(piece(Side::White, 0), DVec2::Y, 1.0, &c).unwrap();
        let plays = |seed| {
            let mut h = Hand::new(model(), seed);
            (0..5).map(|_| h.play(&c, &b, &shot)).collect::<Vec<_>>()
        };
        assert_eq!(plays(3), plays(3));
        assert_ne!(plays(3), plays(4));
    }
}
