//! Match statistics as chess engine testers report them: the score, the
//! Elo difference it implies with its 95 % error bar, the likelihood of
//! superiority (LOS), and a sequential probability ratio test (SPRT) that
//! stops a pairing as soon as the evidence decides between two Elo
//! hypotheses.
//!
//! Elo from a score `s`: `-400 log10(1/s - 1)`, taken after a prior of one
//! drawn game (half a win and half a loss added to the counts), so that a
//! perfect score still gives a finite Elo that grows with the games
//! played. Its error bar is the Wilson score interval of those counts,
//! which stays inside (0, 1) and so is finite too. A score's own 95 %
//! interval ([`Wdl::score_error`]) comes from the per-game variance of the
//! score (wins 1, draws ½, losses 0), as White's score is reported. LOS is
//! `½ (1 + erf((W - L) / sqrt(2 (W + L))))`. The SPRT is the generalised
//! (normal-approximation) test used by chess testing frameworks: the log
//! likelihood ratio of score `s1` (Elo1) against `s0` (Elo0) after `N`
//! games with mean `s` and variance `v` is `N (s1 - s0) (2 s - s0 - s1) /
//! (2 v)`, compared with `ln(β / (1 - α))` and `ln((1 - β) / α)`.

use serde::Serialize;

/// Wins, draws and losses of one side of a pairing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Wdl {
    pub wins: u32,
    pub draws: u32,
    pub losses: u32,
}

impl Wdl {
    /// Counts one game scored `points` (1, ½ or 0).
    pub fn add(&mut self, points: f64) {
        if points > 0.75 {
            self.wins += 1;
        } else if points < 0.25 {
            self.losses += 1;
        } else {
            self.draws += 1;
        }
    }

    /// The same games from the other side.
    pub fn flipped(self) -> Wdl {
        Wdl {
            wins: self.losses,
            draws: self.draws,
            losses: self.wins,
        }
    }

    /// Games counted.
    pub fn games(&self) -> u32 {
        self.wins + self.draws + self.losses
    }

    /// Points scored.
    pub fn points(&self) -> f64 {
        self.wins as f64 + 0.5 * self.draws as f64
    }

    /// The mean score, 0–1 (`0.5` before any game).
    pub fn score(&self) -> f64 {
        match self.games() {
            0 => 0.5,
            n => self.points() / n as f64,
        }
    }

    /// The per-game variance of the score.
    fn variance(&self) -> f64 {
        let n = self.games() as f64;
        if n == 0.0 {
            return 0.0;
        }
        let s = self.score();
        (self.wins as f64 * (1.0 - s).powi(2)
            + self.draws as f64 * (0.5 - s).powi(2)
            + self.losses as f64 * s.powi(2))
            / n
    }

    /// The half-width of the 95 % confidence interval of [`Wdl::score`],
    /// from the per-game variance (0 before any game).
    pub fn score_error(&self) -> f64 {
        let n = self.games() as f64;
        if n == 0.0 {
            return 0.0;
        }
        Z95 * (self.variance() / n).sqrt()
    }

    /// Whether the score is even within its 95 % interval: ½ lies inside
    /// it.
    pub fn even_within_error(&self) -> bool {
        (self.score() - 0.5).abs() <= self.score_error()
    }

    /// The Elo difference the score implies after a prior of one drawn game,
    /// with the half-width of its 95 % interval (the Wilson interval of the
    /// same counts): both finite, even at a score of 0 or 1.
    pub fn elo(&self) -> (f64, f64) {
        let n = self.games() as f64 + PRIOR_GAMES;
        let s = (self.points() + 0.5 * PRIOR_GAMES) / n;
        let (lo, hi) = wilson(s, n);
        (elo_of(s), (elo_of(hi) - elo_of(lo)) / 2.0)
    }

    /// The likelihood of superiority: the probability that this side is the
    /// stronger, from wins and losses (draws carry no information).
    pub fn los(&self) -> f64 {
        let (w, l) = (self.wins as f64, self.losses as f64);
        if w == l {
            return 0.5;
        }
        0.5 * (1.0 + erf((w - l) / (2.0 * (w + l)).sqrt()))
    }

    /// The log-likelihood ratio of Elo `elo1` against `elo0`.
    pub fn llr(&self, elo0: f64, elo1: f64) -> f64 {
        let n = self.games() as f64;
        let v = self.variance();
        if n == 0.0 || v == 0.0 {
            return 0.0;
        }
        let (s0, s1) = (score_of(elo0), score_of(elo1));
        n * (s1 - s0) * (2.0 * self.score() - s0 - s1) / (2.0 * v)
    }
}

/// The normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_964;

/// The weight of the Elo prior, in drawn games.
const PRIOR_GAMES: f64 = 1.0;

/// The Wilson score interval (95 %) of a mean score `s` over `n` games:
/// strictly inside (0, 1) for any `n > 0`.
fn wilson(s: f64, n: f64) -> (f64, f64) {
    let z2 = Z95 * Z95;
    let centre = (s + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (s * (1.0 - s) / n + z2 / (4.0 * n * n)).sqrt();
    (centre - half, centre + half)
}

/// The Elo difference a mean score implies.
pub fn elo_of(score: f64) -> f64 {
    if score <= 0.0 {
        return f64::NEG_INFINITY;
    }
    if score >= 1.0 {
        return f64::INFINITY;
    }
    -400.0 * (1.0 / score - 1.0).log10()
}

/// The mean score an Elo difference predicts.
pub fn score_of(elo: f64) -> f64 {
    1.0 / (1.0 + 10f64.powf(-elo / 400.0))
}

/// The error function: `libm`'s (a port of FreeBSD's msun, pure Rust, the
/// same bits on every platform, within an ulp or so of the true value).
pub fn erf(x: f64) -> f64 {
    libm::erf(x)
}

/// A sequential probability ratio test between two Elo hypotheses.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sprt {
    /// The null hypothesis: the first bot is `elo0` stronger.
    pub elo0: f64,
    /// The alternative: `elo1` stronger.
    pub elo1: f64,
    /// False positive rate.
    pub alpha: f64,
    /// False negative rate.
    pub beta: f64,
}

/// What an SPRT says so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SprtVerdict {
    /// Keep playing.
    Continue,
    /// `elo1` holds: accept the alternative.
    H1,
    /// `elo0` holds: accept the null.
    H0,
}

impl Sprt {
    /// An SPRT of `elo0` against `elo1` at α = β = 0.05.
    pub fn new(elo0: f64, elo1: f64) -> Sprt {
        Sprt {
            elo0,
            elo1,
            alpha: 0.05,
            beta: 0.05,
        }
    }

    /// The lower and upper bounds of the log-likelihood ratio.
    pub fn bounds(&self) -> (f64, f64) {
        (
            (self.beta / (1.0 - self.alpha)).ln(),
            ((1.0 - self.beta) / self.alpha).ln(),
        )
    }

    /// The verdict after `wdl`.
    pub fn verdict(&self, wdl: &Wdl) -> SprtVerdict {
        let llr = wdl.llr(self.elo0, self.elo1);
        let (lo, hi) = self.bounds();
        if llr >= hi {
            SprtVerdict::H1
        } else if llr <= lo {
            SprtVerdict::H0
        } else {
            SprtVerdict::Continue
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_even_score_is_zero_elo_and_three_quarters_is_about_191() {
        let even = Wdl {
            wins: 10,
            draws: 0,
            losses: 10,
        };
        assert_eq!(even.elo().0, 0.0);
        assert!((elo_of(0.75) - 190.848).abs() < 1e-3);
        assert!((score_of(elo_of(0.63)) - 0.63).abs() < 1e-12);
    }

    #[test]
    fn the_error_bar_shrinks_as_the_square_root_of_the_games() {
        let small = Wdl {
            wins: 60,
            draws: 0,
            losses: 40,
        };
        let big = Wdl {
            wins: 600,
            draws: 0,
            losses: 400,
        };
        let (e1, e2) = (small.elo().1, big.elo().1);
        assert!((e1 / e2 - 10f64.sqrt()).abs() < 0.2, "{e1} {e2}");
        // 60 % over 100 games: about 70 ± 70 Elo (the prior of one drawn
        // game pulls 70.4 to 69.7).
        assert!((small.elo().0 - 69.7).abs() < 0.1, "{}", small.elo().0);
        assert!((e1 - 70.0).abs() < 5.0, "{e1}");
        // The score's own interval: 60 % ± 9.6 % over 100 games.
        assert!((small.score_error() - 0.096).abs() < 0.001);
        assert!(!small.even_within_error());
        assert!(Wdl {
            wins: 55,
            draws: 0,
            losses: 45
        }
        .even_within_error());
    }

    #[test]
    fn a_perfect_score_has_a_finite_elo_that_grows_with_the_games() {
        let perfect = |n| Wdl {
            wins: n,
            draws: 0,
            losses: 0,
        };
        let (e10, err10) = perfect(10).elo();
        let (e200, err200) = perfect(200).elo();
        for x in [e10, err10, e200, err200] {
            assert!(x.is_finite() && x > 0.0, "{x}");
        }
        assert!(e200 > e10 + 200.0, "{e10} {e200}");
        let (lost, lost_err) = perfect(200).flipped().elo();
        assert!((lost + e200).abs() < 1e-9 && (lost_err - err200).abs() < 1e-9);
        // Before any game: even, with a wide but finite bar.
        let (e0, err0) = Wdl::default().elo();
        assert_eq!(e0, 0.0);
        assert!(err0.is_finite());
    }

    #[test]
    fn los_is_a_half_when_even_and_near_one_when_far_ahead() {
        assert_eq!(
            Wdl {
                wins: 5,
                draws: 3,
                losses: 5
            }
            .los(),
            0.5
        );
        assert!(
            Wdl {
                wins: 30,
                draws: 0,
                losses: 10
            }
            .los()
                > 0.999
        );
        assert!((erf(1.0) - 0.842_700_79).abs() < 2e-7);
        assert!((erf(-0.5) + 0.520_499_88).abs() < 2e-7);
    }

    #[test]
    fn the_sprt_accepts_a_clear_winner_and_rejects_an_even_pairing() {
        let sprt = Sprt::new(0.0, 50.0);
        assert_eq!(
            sprt.verdict(&Wdl {
                wins: 80,
                draws: 0,
                losses: 20
            }),
            SprtVerdict::H1
        );
        assert_eq!(
            sprt.verdict(&Wdl {
                wins: 200,
                draws: 0,
                losses: 200
            }),
            SprtVerdict::H0
        );
        assert_eq!(
            sprt.verdict(&Wdl {
                wins: 6,
                draws: 0,
                losses: 4
            }),
            SprtVerdict::Continue
        );
    }
}
