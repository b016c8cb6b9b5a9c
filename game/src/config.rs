//! The match configuration: board geometry, piece material, shot power and
//! the rule variants, in one serde [`Config`] recorded with every match.
//!
//! Units are SI. The defaults model a real board: 4 cm squares (a 32 cm
//! board), wooden checkers 3.2 cm across (0.8 of a square), 5 g, sliding
//! with friction 0.3. A piece shot at speed `v` slides `v² / (2 mu g)`, so
//! the default maximum speed of 2 m/s carries a lone piece about 68 cm —
//! more than the board's diagonal — while a quarter of it (0.5 m/s) moves a
//! piece about one square. The tests below prove both in closed form.

pub use crate::rules::Opening;
use serde::{Deserialize, Serialize};

/// Squares along each side of the board.
pub const BOARD_SQUARES: u8 = 8;

/// Everything that defines the physics and rules of a match.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Side of one square, m.
    pub square: f64,
    /// Radius of a piece, m (must be less than half a square).
    pub piece_radius: f64,
    /// Mass of a piece, kg.
    pub piece_mass: f64,
    /// Sliding friction coefficient of a piece on the board.
    pub mu: f64,
    /// Gravity, m/s².
    pub g: f64,
    /// Coefficient of restitution of piece–piece hits, 0–1.
    pub restitution: f64,
    /// Fastest shot allowed, m/s.
    pub max_speed: f64,
    /// Hard cap on engine events for one shot (the engine's safety net;
    /// a shot that reaches it is frozen where it stands).
    pub max_events_per_shot: u64,
    /// Rule variants.
    pub variants: Variants,
}

/// Optional rules.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Variants {
    /// A round won without losing a piece moves the winner two rows.
    pub two_row_advance: bool,
    /// After White's first shot of the match, Black may swap seats.
    pub pie_rule: bool,
    /// The match is a single round (a draw is a drawn match).
    pub quick_match: bool,
    /// Execution noise on every shot, drawn from the match's seed.
    pub noise: Option<NoiseConfig>,
    /// Who opens each round after the first (left out of a recorded
    /// configuration when it is the winner, as before this rule existed).
    #[serde(skip_serializing_if = "Opening::is_winner")]
    pub opening: Opening,
    /// The rows meet two ranks apart instead of adjacent, and stay so: the
    /// winner advances and pushes the loser back, with a clear rank between
    /// them (left out of a recorded configuration when off).
    #[serde(skip_serializing_if = "is_false")]
    pub rows_keep_apart: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// Gaussian execution noise (standard deviations).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NoiseConfig {
    /// Of the direction, radians.
    pub angle_sigma: f64,
    /// Of the speed, as a fraction of the aimed speed.
    pub speed_sigma: f64,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            square: 0.04,
            piece_radius: 0.016,
            piece_mass: 0.005,
            mu: 0.3,
            g: 9.81,
            restitution: 0.9,
            max_speed: 2.0,
            max_events_per_shot: 100_000,
            variants: Variants::default(),
        }
    }
}

/// The execution noise of competitive play (`standard` on the wire), whose
/// rules are this noise on every shot (as real hands miss), the pie rule
/// (after White's first shot Black may take White's side) and rows that
/// stop two ranks apart (`rows_keep_apart`). They were chosen by
/// measurement so that between two copies of the same bot each *colour*
/// scores half: with the rows meeting adjacent, greedy v greedy scored
/// White 30 % (see `bots/README.md` for the figures and the commands).
pub const STANDARD_NOISE: NoiseConfig = NoiseConfig {
    angle_sigma: 0.03,
    speed_sigma: 0.05,
};

/// A named set of rules a match can be created with.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// The defaults: shots played exactly as aimed, no pie rule.
    #[default]
    Casual,
    /// Competitive play: [`STANDARD_NOISE`], the pie rule and the rows
    /// kept apart.
    Standard,
}

impl Preset {
    /// The preset's wire name.
    pub fn as_str(self) -> &'static str {
        match self {
            Preset::Casual => "casual",
            Preset::Standard => "standard",
        }
    }

    /// The preset named `name`, if there is one.
    pub fn parse(name: &str) -> Option<Preset> {
        match name {
            "casual" => Some(Preset::Casual),
            "standard" => Some(Preset::Standard),
            _ => None,
        }
    }

    /// The configuration of this preset.
    pub fn config(self) -> Config {
        match self {
            Preset::Casual => Config::default(),
            Preset::Standard => Config::standard(),
        }
    }
}

impl std::fmt::Display for Preset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A configuration that cannot be played.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ConfigError {
    #[error("config field \"{0}\" must be a finite number")]
    NotFinite(&'static str),
    #[error("config field \"{0}\" must be > 0")]
    NotPositive(&'static str),
    #[error("config field \"{0}\" must be >= 0")]
    Negative(&'static str),
    #[error("restitution must be between 0 and 1")]
    Restitution,
    #[error("a piece (radius {radius}) must fit inside a square (side {square})")]
    PieceTooBig { radius: f64, square: f64 },
    #[error("config field \"{name}\" must be at most {max}")]
    TooLarge { name: &'static str, max: f64 },
    #[error("config field \"{name}\" must be at least {min}")]
    TooSmall { name: &'static str, min: f64 },
    #[error("a piece (radius {radius}) must be at least a thousandth of a square (side {square})")]
    PieceTooSmall { radius: f64, square: f64 },
}

/// The smallest square, m (a millimetre): below it the engine's times and
/// distances lose their meaning in double precision.
const MIN_SQUARE: f64 = 1e-3;

/// The largest value each field may take: far beyond any real board, and
/// well inside what the engine's arithmetic resolves.
const UPPER_BOUNDS: [(&str, f64); 6] = [
    ("square", 10.0),
    ("piece_mass", 1000.0),
    ("mu", 10.0),
    ("g", 1000.0),
    ("max_speed", 1000.0),
    ("max_events_per_shot", 1_000_000.0),
];

/// The smallest friction and gravity: far more slippery than any real
/// board, and still enough that the fastest shot stops within the distances
/// the engine computes with (it refuses a scene whose discs friction might
/// only stop beyond 1e150 m).
const LOWER_BOUNDS: [(&str, f64); 2] = [("mu", 1e-6), ("g", 1e-6)];

impl Config {
    /// The `standard` rules of competitive play ([`Preset::Standard`]):
    /// the default board with [`STANDARD_NOISE`], the pie rule and the rows
    /// kept two ranks apart.
    pub fn standard() -> Config {
        Config {
            variants: Variants {
                pie_rule: true,
                noise: Some(STANDARD_NOISE),
                rows_keep_apart: true,
                ..Variants::default()
            },
            ..Config::default()
        }
    }

    /// Side of the whole board, m.
    pub fn board_size(&self) -> f64 {
        self.square * BOARD_SQUARES as f64
    }

    /// Deceleration of a sliding piece, `mu * g`.
    pub fn deceleration(&self) -> f64 {
        self.mu * self.g
    }

    /// How far a lone piece shot at `speed` slides: `v² / (2 mu g)`.
    pub fn stopping_distance(&self, speed: f64) -> f64 {
        speed * speed / (2.0 * self.deceleration())
    }

    /// The speed that slides a lone piece exactly `distance`.
    pub fn speed_for_distance(&self, distance: f64) -> f64 {
        (2.0 * self.deceleration() * distance).sqrt()
    }

    /// Checks that the configuration can be played.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let positive = [
            ("square", self.square),
            ("piece_radius", self.piece_radius),
            ("piece_mass", self.piece_mass),
            ("mu", self.mu),
            ("g", self.g),
            ("max_speed", self.max_speed),
        ];
        for (name, x) in positive {
            if !x.is_finite() {
                return Err(ConfigError::NotFinite(name));
            }
            if x <= 0.0 {
                return Err(ConfigError::NotPositive(name));
            }
        }
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(ConfigError::Restitution);
        }
        if self.max_events_per_shot == 0 {
            return Err(ConfigError::NotPositive("max_events_per_shot"));
        }
        if self.piece_radius >= self.square / 2.0 {
            return Err(ConfigError::PieceTooBig {
                radius: self.piece_radius,
                square: self.square,
            });
        }
        if self.square < MIN_SQUARE {
            return Err(ConfigError::TooSmall {
                name: "square",
                min: MIN_SQUARE,
            });
        }
        if self.piece_radius < self.square / 1000.0 {
            return Err(ConfigError::PieceTooSmall {
                radius: self.piece_radius,
                square: self.square,
            });
        }
        let values = [
            self.square,
            self.piece_mass,
            self.mu,
            self.g,
            self.max_speed,
            self.max_events_per_shot as f64,
        ];
        for ((name, max), x) in UPPER_BOUNDS.into_iter().zip(values) {
            if x > max {
                return Err(ConfigError::TooLarge { name, max });
            }
        }
        for ((name, min), x) in LOWER_BOUNDS.into_iter().zip([self.mu, self.g]) {
            if x < min {
                return Err(ConfigError::TooSmall { name, min });
            }
        }
        if let Some(n) = &self.variants.noise {
            for (name, x) in [
                ("angle_sigma", n.angle_sigma),
                ("speed_sigma", n.speed_sigma),
            ] {
                if !x.is_finite() {
                    return Err(ConfigError::NotFinite(name));
                }
                if x < 0.0 {
                    return Err(ConfigError::Negative(name));
                }
                if x > 1.0 {
                    return Err(ConfigError::TooLarge { name, max: 1.0 });
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_config_is_valid() {
        assert_eq!(Config::default().validate(), Ok(()));
    }

    #[test]
    fn the_standard_preset_turns_noise_the_pie_rule_and_rows_kept_apart_on_and_is_valid() {
        let c = Preset::Standard.config();
        assert!(c.variants.pie_rule);
        assert!(c.variants.rows_keep_apart);
        assert_eq!(c.variants.opening, Opening::Winner);
        assert_eq!(c.variants.noise, Some(STANDARD_NOISE));
        assert_eq!(c.validate(), Ok(()));
        assert_eq!(Preset::Casual.config(), Config::default());
        assert_eq!(Preset::parse("standard"), Some(Preset::Standard));
        assert_eq!(Preset::parse("blitz"), None);
        let name = serde_json::to_string(&Preset::Standard).unwrap();
        assert_eq!(name, r#""standard""#);
    }

    #[test]
    fn absurd_configs_are_refused_with_the_field_named() {
        let c = Config {
            max_speed: 2e300,
            ..Config::default()
        };
        assert_eq!(
            c.validate(),
            Err(ConfigError::TooLarge {
                name: "max_speed",
                max: 1000.0
            })
        );
        let c = Config {
            max_events_per_shot: u64::MAX,
            ..Config::default()
        };
        assert!(matches!(c.validate(), Err(ConfigError::TooLarge { .. })));
        let c = Config {
            piece_radius: 1e-300,
            ..Config::default()
        };
        assert!(matches!(
            c.validate(),
            Err(ConfigError::PieceTooSmall { .. })
        ));
        let c = Config {
            square: 1e-300,
            piece_radius: 4e-301,
            ..Config::default()
        };
        assert!(matches!(c.validate(), Err(ConfigError::TooSmall { .. })));
        let mut c = Config::standard();
        c.variants.noise = Some(NoiseConfig {
            angle_sigma: 0.03,
            speed_sigma: 5.0,
        });
        assert!(matches!(c.validate(), Err(ConfigError::TooLarge { .. })));
    }

    #[test]
    fn a_board_too_slippery_for_the_engine_is_refused_and_the_most_slippery_allowed_plays() {
        let c = Config {
            mu: 1e-300,
            ..Config::default()
        };
        assert_eq!(
            c.validate(),
            Err(ConfigError::TooSmall {
                name: "mu",
                min: 1e-6
            })
        );
        let c = Config {
            g: 1e-7,
            ..Config::default()
        };
        assert!(matches!(
            c.validate(),
            Err(ConfigError::TooSmall { name: "g", .. })
        ));
        // The fastest shot on the most slippery board allowed, with the
        // lightest and the heaviest pieces: the engine resolves it.
        for piece_mass in [1e-300, 1000.0] {
            let c = Config {
                mu: 1e-6,
                g: 1e-6,
                max_speed: 1000.0,
                piece_mass,
                ..Config::default()
            };
            let mut game = crate::Game::new(c, 1).unwrap();
            let piece = crate::PieceId::new(crate::Side::White, 4).unwrap();
            let shot =
                crate::Shot::new(piece, glam::DVec2::new(0.0, 1000.0), game.config()).unwrap();
            game.play(crate::Side::White, shot).unwrap();
        }
    }

    #[test]
    fn a_real_checker_is_about_four_fifths_of_a_square_across() {
        let c = Config::default();
        assert!((2.0 * c.piece_radius / c.square - 0.8).abs() < 1e-12);
    }

    #[test]
    fn full_power_shot_crosses_the_board_even_diagonally() {
        let c = Config::default();
        // v² / (2 mu g) = 4 / 5.886 = 0.6796 m; the diagonal is 0.4525 m.
        let d = c.stopping_distance(c.max_speed);
        assert!((d - 4.0 / (2.0 * 0.3 * 9.81)).abs() < 1e-12);
        assert!(d > c.board_size() * std::f64::consts::SQRT_2);
    }

    #[test]
    fn gentle_quarter_power_shot_moves_a_piece_about_one_square() {
        let c = Config::default();
        let one_square = c.speed_for_distance(c.square);
        // sqrt(2 * 0.3 * 9.81 * 0.04) = 0.4852 m/s, about a quarter of the maximum.
        assert!((one_square - 0.235_44_f64.sqrt()).abs() < 1e-12);
        assert!(one_square > 0.2 * c.max_speed && one_square < 0.3 * c.max_speed);
        let quarter = c.stopping_distance(c.max_speed / 4.0);
        assert!(
            (quarter / c.square - 1.0).abs() < 0.1,
            "{}",
            quarter / c.square
        );
        assert!((c.stopping_distance(one_square) - c.square).abs() < 1e-15);
    }

    #[test]
    fn unplayable_configs_are_rejected_naming_the_field() {
        let bad = |f: fn(&mut Config)| {
            let mut c = Config::default();
            f(&mut c);
            c.validate().unwrap_err()
        };
        assert_eq!(bad(|c| c.mu = 0.0), ConfigError::NotPositive("mu"));
        assert_eq!(
            bad(|c| c.square = f64::NAN),
            ConfigError::NotFinite("square")
        );
        assert_eq!(bad(|c| c.restitution = 1.5), ConfigError::Restitution);
        assert!(matches!(
            bad(|c| c.piece_radius = 0.03),
            ConfigError::PieceTooBig { .. }
        ));
        assert_eq!(
            bad(|c| c.variants.noise = Some(NoiseConfig {
                angle_sigma: -1.0,
                speed_sigma: 0.0
            })),
            ConfigError::Negative("angle_sigma")
        );
        assert!(bad(|c| c.max_events_per_shot = 0)
            .to_string()
            .contains("max_events_per_shot"));
    }

    #[test]
    fn partial_json_config_takes_defaults_and_unknown_fields_are_refused() {
        let c: Config = serde_json::from_str(r#"{"variants": {"pie_rule": true}}"#).unwrap();
        assert!(c.variants.pie_rule);
        assert_eq!(c.max_speed, Config::default().max_speed);
        assert!(serde_json::from_str::<Config>(r#"{"speed": 3}"#).is_err());
        let back: Config = serde_json::from_str(&serde_json::to_string(&c).unwrap()).unwrap();
        assert_eq!(back, c);
    }

    #[test]
    fn a_config_recorded_before_the_new_variants_reads_with_them_off() {
        let old = r#"{"variants": {"two_row_advance": false, "pie_rule": true,
            "quick_match": false, "noise": {"angle_sigma": 0.03, "speed_sigma": 0.05}}}"#;
        let c: Config = serde_json::from_str(old).unwrap();
        assert!(!c.variants.rows_keep_apart);
        assert_eq!(c.variants.opening, Opening::Winner);
        // And a config with them off is written as before.
        let json = serde_json::to_string(&c).unwrap();
        assert!(
            !json.contains("rows_keep_apart") && !json.contains("opening"),
            "{json}"
        );
    }
}
