//! Ratings: a player's strength as a Glicko-2 rating (the rating, its
//! deviation — how unsure it still is — and its volatility), and how a rated
//! match's result moves both players' ratings. The arithmetic is the
//! `skillratings` crate's Glicko-2; this module holds the parameters
//! (lichess's: everyone starts at 1500 with deviation 500 and volatility
//! 0.09, tau 0.75, the deviation kept between 45 and 500), says when a
//! rating is still provisional, and refuses ratings that are not numbers,
//! so nothing read from a store or a request can poison a rating table.

use serde::{Deserialize, Serialize};
use skillratings::glicko2::{glicko2, glicko2_rating_period, Glicko2Config, Glicko2Rating};
use skillratings::Outcomes;

/// A player's Glicko-2 rating, on the familiar scale (1500 for a newcomer).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Rating {
    /// The rating itself.
    pub rating: f64,
    /// How unsure the rating is (one standard deviation, rating points).
    pub deviation: f64,
    /// How erratic the player's results are.
    pub volatility: f64,
}

/// A rating that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum RatingError {
    /// A part is not a finite number, or not in its range.
    #[error("the rating's {part} is {value}, which is not a usable {part}")]
    Invalid {
        /// `rating`, `deviation` or `volatility`.
        part: &'static str,
        /// The value given.
        value: f64,
    },
}

impl Rating {
    /// A rating as stored or sent, checked: the rating finite, the deviation
    /// and the volatility finite and positive.
    pub fn new(rating: f64, deviation: f64, volatility: f64) -> Result<Rating, RatingError> {
        let check = |part, value: f64, positive: bool| {
            if value.is_finite() && (!positive || value > 0.0) {
                Ok(value)
            } else {
                Err(RatingError::Invalid { part, value })
            }
        };
        Ok(Rating {
            rating: check("rating", rating, false)?,
            deviation: check("deviation", deviation, true)?,
            volatility: check("volatility", volatility, true)?,
        })
    }

    /// The rating shown to people: rounded to a whole number.
    pub fn shown(&self) -> i64 {
        self.rating.round() as i64
    }

    fn glicko(self) -> Glicko2Rating {
        Glicko2Rating {
            rating: self.rating,
            deviation: self.deviation,
            volatility: self.volatility,
        }
    }
}

/// A rated match's result, for the first of the two players.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Score {
    /// The first player won.
    Win,
    /// The first player lost.
    Loss,
    /// Neither won.
    Draw,
}

impl Score {
    fn outcome(self) -> Outcomes {
        match self {
            Score::Win => Outcomes::WIN,
            Score::Loss => Outcomes::LOSS,
            Score::Draw => Outcomes::DRAW,
        }
    }
}

/// The rating system's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RatingSystem {
    /// Where a newcomer starts.
    pub start: Rating,
    /// The system constant: how fast volatility may change.
    pub tau: f64,
    /// The least deviation a rating keeps, however many games it has.
    pub deviation_floor: f64,
    /// The most deviation a rating can have (a newcomer's).
    pub deviation_ceiling: f64,
    /// A rating is provisional while its deviation is above this.
    pub provisional_above: f64,
}

impl Default for RatingSystem {
    /// Lichess's parameters.
    fn default() -> RatingSystem {
        RatingSystem {
            start: Rating {
                rating: 1500.0,
                deviation: 500.0,
                volatility: 0.09,
            },
            tau: 0.75,
            deviation_floor: 45.0,
            deviation_ceiling: 500.0,
            provisional_above: 110.0,
        }
    }
}

impl RatingSystem {
    /// Whether `rating` is still provisional (too few games to trust it).
    pub fn is_provisional(&self, rating: &Rating) -> bool {
        rating.deviation > self.provisional_above
    }

    /// Both players' ratings after one rated match between them, `score`
    /// being the first player's result.
    pub fn after_match(&self, first: Rating, second: Rating, score: Score) -> (Rating, Rating) {
        let (a, b) = glicko2(
            &first.glicko(),
            &second.glicko(),
            &score.outcome(),
            &self.config(),
        );
        (self.bounded(a), self.bounded(b))
    }

    /// One player's rating after a rating period of several results, each
    /// against an opponent's rating as it was when the period began.
    pub fn after_period(&self, player: Rating, results: &[(Rating, Score)]) -> Rating {
        let results: Vec<(Glicko2Rating, Outcomes)> = results
            .iter()
            .map(|(opponent, score)| (opponent.glicko(), score.outcome()))
            .collect();
        self.bounded(glicko2_rating_period(
            &player.glicko(),
            &results,
            &self.config(),
        ))
    }

    fn config(&self) -> Glicko2Config {
        Glicko2Config {
            tau: self.tau,
            ..Glicko2Config::default()
        }
    }

    fn bounded(&self, r: Glicko2Rating) -> Rating {
        Rating {
            rating: r.rating,
            deviation: r
                .deviation
                .clamp(self.deviation_floor, self.deviation_ceiling),
            volatility: r.volatility,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rating(rating: f64, deviation: f64) -> Rating {
        Rating::new(rating, deviation, 0.06).unwrap()
    }

    #[test]
    fn glickmans_worked_example_gives_1464_06_and_151_52() {
        // Glickman, "Example of the Glicko-2 system", with tau 0.5 and no
        // bounds on the deviation.
        let system = RatingSystem {
            tau: 0.5,
            deviation_floor: 0.0,
            deviation_ceiling: f64::INFINITY,
            ..RatingSystem::default()
        };
        let after = system.after_period(
            rating(1500.0, 200.0),
            &[
                (rating(1400.0, 30.0), Score::Win),
                (rating(1550.0, 100.0), Score::Loss),
                (rating(1700.0, 300.0), Score::Loss),
            ],
        );
        assert!((after.rating - 1464.06).abs() < 0.01, "{after:?}");
        assert!((after.deviation - 151.52).abs() < 0.01, "{after:?}");
        assert!((after.volatility - 0.05999).abs() < 1e-5, "{after:?}");
    }

    #[test]
    fn newcomers_start_at_lichess_1500_500_0_09_and_are_provisional() {
        let system = RatingSystem::default();
        assert_eq!(system.start, Rating::new(1500.0, 500.0, 0.09).unwrap());
        assert_eq!(system.tau, 0.75);
        assert!(system.is_provisional(&system.start));
        assert!(!system.is_provisional(&rating(1500.0, 60.0)));
    }

    #[test]
    fn the_winner_gains_what_the_loser_loses_between_equals() {
        let system = RatingSystem::default();
        let (a, b) = system.after_match(system.start, system.start, Score::Win);
        assert!(a.rating > 1500.0 && b.rating < 1500.0);
        assert!(((a.rating - 1500.0) - (1500.0 - b.rating)).abs() < 1e-9);
        assert!(a.deviation < 500.0 && b.deviation < 500.0);
        let (c, d) = system.after_match(system.start, system.start, Score::Draw);
        assert_eq!((c.rating, d.rating), (1500.0, 1500.0));
    }

    #[test]
    fn the_deviation_never_falls_below_the_floor_however_many_games() {
        let system = RatingSystem::default();
        // Steady players (low volatility) who have played a lot.
        let steady = Rating::new(1500.0, 50.0, 0.001).unwrap();
        let (mut a, mut b) = (steady, steady);
        let mut least = f64::INFINITY;
        for i in 0..500 {
            let score = if i % 3 == 0 { Score::Loss } else { Score::Win };
            (a, b) = system.after_match(a, b, score);
            least = least.min(a.deviation).min(b.deviation);
        }
        assert_eq!(least, 45.0, "held at the floor");
        assert!(
            a.rating > b.rating,
            "the one winning two in three is rated higher"
        );
    }

    #[test]
    fn a_rating_that_is_not_a_number_is_refused_naming_its_part() {
        assert!(matches!(
            Rating::new(f64::NAN, 100.0, 0.06),
            Err(RatingError::Invalid { part: "rating", value }) if value.is_nan()
        ));
        let err = Rating::new(1500.0, 0.0, 0.06).unwrap_err();
        assert!(err.to_string().contains("deviation"), "{err}");
        let err = Rating::new(1500.0, 100.0, f64::INFINITY).unwrap_err();
        assert!(err.to_string().contains("volatility"), "{err}");
        assert!(Rating::new(-30.0, 100.0, 0.06).is_ok());
    }
}
