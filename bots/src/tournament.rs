//! Round-robin tournaments between bots, in this process: every pairing
//! plays games in pairs from the same seed with the seats swapped (so both
//! bots meet the same noise and the same first move), the bots' own
//! generators seeded from the tournament's seed, so a tournament is
//! repeatable for its seed. Each pairing reports wins, draws, losses, the
//! Elo difference with its 95 % error bar and the LOS, and may stop early
//! on an SPRT verdict. Beside the first seat's score it reports White's:
//! under the pie rule the seat that opens is not the colour that ends up
//! White, and only the colour's score says whether the rules are fair. An
//! overall table sums each distinct bot's games against the others (a
//! bot's games against itself say nothing of its strength).

use crate::arena::{play_match, ArenaLimits, MatchReport};
use crate::level::by_name;
use crate::remote::play_on_server;
use crate::stats::{Sprt, SprtVerdict, Wdl};
use game::noise::SplitMix64;
use game::{Config, MatchRecord, Seat, Side};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;

/// What to play.
#[derive(Clone, Debug)]
pub struct TournamentSettings {
    /// Bot names (see [`crate::level::BOT_NAMES`]).
    pub bots: Vec<String>,
    /// Games per pairing (rounded up to an even number).
    pub games: u32,
    /// The tournament's seed: match seeds and the bots' generators.
    pub seed: u64,
    /// The rules every game is played under.
    pub config: Config,
    /// Stop a pairing early when this test decides.
    pub sprt: Option<Sprt>,
    /// Per-match limits.
    pub limits: ArenaLimits,
    /// Show a progress bar on standard error.
    pub progress: bool,
    /// Play every game on this server (`http://HOST:PORT`) instead of in
    /// this process: real, but the server draws the seeds.
    pub server: Option<String>,
}

/// A tournament setting that cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum TournamentError {
    #[error("unknown bot {0:?} (known: random, greedy, search, easy, medium, hard)")]
    UnknownBot(String),
    #[error("a tournament needs at least two bots")]
    TooFewBots,
    #[error("the rules cannot be played: {0}")]
    Config(#[from] game::ConfigError),
    #[error("a game on the server failed: {0}")]
    Server(#[from] crate::runner::RunnerError),
}

/// One game of a pairing.
#[derive(Clone, Debug, Serialize)]
pub struct GameResult {
    /// The bot in the first seat (White, unless the pie rule swapped).
    pub first: String,
    pub second: String,
    /// The match seed (both games of a pair share it).
    pub seed: u64,
    /// Points of the first seat.
    pub first_score: f64,
    /// The bot that played White (the colour, after any pie swap).
    pub white: String,
    /// The colour that won the match (`null`: drawn or stopped).
    pub winner: Option<Side>,
    /// Points of White (the colour, after any pie swap): 1, ½ or 0.
    pub white_score: f64,
    pub shots: u32,
    /// Whether Black took White's side under the pie rule.
    pub swapped: bool,
    /// The full record, replayable.
    #[serde(skip)]
    pub record: MatchRecord,
}

/// One pairing's games and statistics, from `a`'s side.
#[derive(Clone, Debug, Serialize)]
pub struct Pairing {
    pub a: String,
    pub b: String,
    pub wdl: Wdl,
    pub score: f64,
    pub elo: f64,
    pub elo_error: f64,
    pub los: f64,
    /// The SPRT's verdict, when one was asked for.
    pub sprt: Option<SprtVerdict>,
    /// The first seat's score over the pairing's games.
    pub first_seat_score: f64,
    /// The half-width of its 95 % interval.
    pub first_seat_error: f64,
    /// White's score (the colour, after any pie swap) over the games.
    pub white_score: f64,
    /// The half-width of its 95 % interval.
    pub white_error: f64,
    /// White's wins, draws and losses.
    pub white_wdl: Wdl,
    /// Games in which Black took White's side under the pie rule.
    pub swaps: u32,
    pub games: Vec<GameResult>,
}

/// One bot's games over the whole tournament.
#[derive(Clone, Debug, Serialize)]
pub struct Standing {
    pub bot: String,
    pub wdl: Wdl,
    pub score: f64,
    pub elo: f64,
    pub elo_error: f64,
}

/// A finished tournament.
#[derive(Clone, Debug, Serialize)]
pub struct TournamentReport {
    pub seed: u64,
    pub config: Config,
    pub pairings: Vec<Pairing>,
    pub standings: Vec<Standing>,
}

fn mix(seed: u64, a: u64, b: u64) -> u64 {
    let mut r = SplitMix64::new(seed ^ a.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ b.rotate_left(32));
    r.next_u64()
}

/// Plays the tournament.
pub fn run(settings: &TournamentSettings) -> Result<TournamentReport, TournamentError> {
    if settings.bots.len() < 2 {
        return Err(TournamentError::TooFewBots);
    }
    for name in &settings.bots {
        if by_name(name, 0).is_none() {
            return Err(TournamentError::UnknownBot(name.clone()));
        }
    }
    settings.config.validate()?;
    let pairs_per = settings.games.div_ceil(2).max(1);
    let n = settings.bots.len();
    let pairings_total = n * (n - 1) / 2;
    let bar = if settings.progress {
        let bar = ProgressBar::new(pairings_total as u64 * pairs_per as u64 * 2);
        bar.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} games {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let mut pairings = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (&settings.bots[i], &settings.bots[j]);
            bar.set_message(format!("{a} v {b}"));
            pairings.push(pairing(settings, i, j, pairs_per, &bar)?);
        }
    }
    bar.finish_and_clear();
    Ok(TournamentReport {
        seed: settings.seed,
        config: settings.config.clone(),
        standings: standings(&settings.bots, &pairings),
        pairings,
    })
}

/// Each distinct bot's games against the other bots, in the order first
/// named; a bot that only played itself has no row.
fn standings(bots: &[String], pairings: &[Pairing]) -> Vec<Standing> {
    let mut distinct: Vec<&String> = Vec::new();
    for bot in bots {
        if !distinct.contains(&bot) {
            distinct.push(bot);
        }
    }
    distinct
        .into_iter()
        .filter_map(|bot| {
            let mut wdl = Wdl::default();
            for p in pairings.iter().filter(|p| p.a != p.b) {
                let w = if &p.a == bot {
                    p.wdl
                } else if &p.b == bot {
                    p.wdl.flipped()
                } else {
                    continue;
                };
                wdl.wins += w.wins;
                wdl.draws += w.draws;
                wdl.losses += w.losses;
            }
            if wdl.games() == 0 {
                return None;
            }
            let (elo, elo_error) = wdl.elo();
            Some(Standing {
                bot: bot.clone(),
                wdl,
                score: wdl.score(),
                elo,
                elo_error,
            })
        })
        .collect()
}

/// Games played between SPRT checks (a fixed batch keeps the stop point
/// independent of how many threads play).
const BATCH: u32 = 8;

fn pairing(
    settings: &TournamentSettings,
    i: usize,
    j: usize,
    pairs: u32,
    bar: &ProgressBar,
) -> Result<Pairing, TournamentError> {
    let (a, b) = (settings.bots[i].clone(), settings.bots[j].clone());
    let mut games: Vec<GameResult> = Vec::new();
    let mut wdl = Wdl::default();
    let mut verdict = settings.sprt.map(|_| SprtVerdict::Continue);
    let mut next = 0;
    while next < pairs {
        let batch: Vec<u32> = (next..(next + BATCH).min(pairs)).collect();
        next += batch.len() as u32;
        let played: Vec<Result<[GameResult; 2], TournamentError>> = batch
            .par_iter()
            .map(|&k| {
                let seed = mix(settings.seed, (i * 64 + j) as u64, k as u64);
                // Two copies of one bot: the swapped game would repeat the
                // first move for move, so it gets a seed of its own.
                let same = a == b;
                let one = |first: &str, second: &str, fi: usize, si: usize| {
                    let seed = if same && fi > si {
                        mix(seed, 7, 7)
                    } else {
                        seed
                    };
                    let mut f = by_name(first, mix(seed, fi as u64 + 1, 1)).expect("checked");
                    let mut s = by_name(second, mix(seed, si as u64 + 1, 2)).expect("checked");
                    let r: MatchReport = match &settings.server {
                        Some(url) => play_on_server(url, &settings.config, f, s, [first, second])?,
                        None => play_match(
                            settings.config.clone(),
                            seed,
                            &mut f,
                            &mut s,
                            &settings.limits,
                        )?,
                    };
                    bar.inc(1);
                    let winner = r.result.as_ref().and_then(|m| m.winner());
                    let white = if r.swapped { second } else { first };
                    Ok::<_, TournamentError>(GameResult {
                        first: first.to_string(),
                        second: second.to_string(),
                        seed,
                        first_score: r.score(Seat::First),
                        white: white.to_string(),
                        winner,
                        white_score: match winner {
                            Some(Side::White) => 1.0,
                            Some(Side::Black) => 0.0,
                            None => 0.5,
                        },
                        shots: r.shots,
                        swapped: r.swapped,
                        record: r.record,
                    })
                };
                Ok([one(&a, &b, i, j)?, one(&b, &a, j, i)?])
            })
            .collect();
        for pair in played {
            let [ab, ba] = pair?;
            wdl.add(ab.first_score);
            wdl.add(1.0 - ba.first_score);
            games.push(ab);
            games.push(ba);
        }
        if let (Some(sprt), Some(v)) = (settings.sprt, verdict.as_mut()) {
            *v = sprt.verdict(&wdl);
            if *v != SprtVerdict::Continue {
                bar.inc(((pairs - next) * 2) as u64);
                break;
            }
        }
    }
    let (elo, elo_error) = wdl.elo();
    let (mut first_seat, mut white_wdl) = (Wdl::default(), Wdl::default());
    for g in &games {
        first_seat.add(g.first_score);
        white_wdl.add(g.white_score);
    }
    Ok(Pairing {
        a,
        b,
        wdl,
        score: wdl.score(),
        elo,
        elo_error,
        los: wdl.los(),
        sprt: verdict,
        first_seat_score: first_seat.score(),
        first_seat_error: first_seat.score_error(),
        white_score: white_wdl.score(),
        white_error: white_wdl.score_error(),
        white_wdl,
        swaps: games.iter().filter(|g| g.swapped).count() as u32,
        games,
    })
}

/// The report as the table a person reads: each pairing with its score,
/// Elo and LOS, the first seat's score and White's (each ± its 95 %
/// interval) and the pie swaps; then each distinct bot against the others.
pub fn table(report: &TournamentReport) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "{:<22} {:>6} {:>5} {:>5} {:>5} {:>7} {:>14} {:>7} {:>13} {:>13} {:>6}\n",
        "pairing",
        "games",
        "W",
        "D",
        "L",
        "score",
        "Elo (95%)",
        "LOS",
        "1st seat",
        "White",
        "swaps"
    ));
    for p in &report.pairings {
        out.push_str(&format!(
            "{:<22} {:>6} {:>5} {:>5} {:>5} {:>6.1}% {:>14} {:>6.1}% {:>13} {:>13} {:>6}{}\n",
            format!("{} v {}", p.a, p.b),
            p.wdl.games(),
            p.wdl.wins,
            p.wdl.draws,
            p.wdl.losses,
            100.0 * p.score,
            elo_text(p.elo, p.elo_error),
            100.0 * p.los,
            percent(p.first_seat_score, p.first_seat_error),
            percent(p.white_score, p.white_error),
            p.swaps,
            match p.sprt {
                Some(v) => format!("  SPRT {v:?}"),
                None => String::new(),
            }
        ));
    }
    if report.standings.is_empty() {
        return out;
    }
    out.push_str(&format!(
        "\n{:<22} {:>6} {:>5} {:>5} {:>5} {:>7} {:>14}\n",
        "bot", "games", "W", "D", "L", "score", "Elo (95%)"
    ));
    for s in &report.standings {
        out.push_str(&format!(
            "{:<22} {:>6} {:>5} {:>5} {:>5} {:>6.1}% {:>14}\n",
            s.bot,
            s.wdl.games(),
            s.wdl.wins,
            s.wdl.draws,
            s.wdl.losses,
            100.0 * s.score,
            elo_text(s.elo, s.elo_error)
        ));
    }
    out
}

fn elo_text(elo: f64, err: f64) -> String {
    format!("{elo:+.0} ± {err:.0}")
}

fn percent(score: f64, err: f64) -> String {
    format!("{:.1}±{:.1}%", 100.0 * score, 100.0 * err)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(seed: u64) -> TournamentSettings {
        TournamentSettings {
            bots: vec!["random".into(), "easy".into()],
            games: 4,
            seed,
            config: Config::standard(),
            sprt: None,
            limits: ArenaLimits::default(),
            progress: false,
            server: None,
        }
    }

    #[test]
    fn a_tournament_is_repeatable_for_its_seed() {
        let one = run(&small(5)).unwrap();
        let two = run(&small(5)).unwrap();
        let json = |r: &TournamentReport| serde_json::to_string(r).unwrap();
        assert_eq!(json(&one), json(&two));
        let games = &one.pairings[0].games;
        assert_eq!(games.len(), 4);
        assert_eq!(
            games[0].seed, games[1].seed,
            "colours swap from the same seed"
        );
        assert_eq!(games[0].first, games[1].second);
        assert_eq!(one.standings[0].wdl.games(), 4);
        let other = run(&small(6)).unwrap();
        assert_ne!(json(&one), json(&other));
    }

    #[test]
    fn every_game_reports_whites_colour_score_beside_the_first_seats() {
        let report = run(&small(9)).unwrap();
        let p = &report.pairings[0];
        for g in &p.games {
            let white_is_first = g.white == g.first && !g.swapped;
            let white_is_second = g.white == g.second && g.swapped;
            assert!(white_is_first || white_is_second, "{g:?}");
            let expected = if g.swapped {
                1.0 - g.first_score
            } else {
                g.first_score
            };
            assert_eq!(g.white_score, expected, "{g:?}");
        }
        let n = p.games.len() as f64;
        let white: f64 = p.games.iter().map(|g| g.white_score).sum();
        assert_eq!(p.white_score, white / n);
        assert_eq!(p.white_wdl.games() as usize, p.games.len());
        assert_eq!(
            p.swaps as usize,
            p.games.iter().filter(|g| g.swapped).count()
        );
        let json = serde_json::to_value(&report).unwrap();
        let game = &json["pairings"][0]["games"][0];
        for field in ["white", "winner", "white_score", "first_score", "swapped"] {
            assert!(game.get(field).is_some(), "{field} missing from {game}");
        }
        let table = table(&report);
        assert!(
            table.contains("White") && table.contains("1st seat"),
            "{table}"
        );
    }

    #[test]
    fn a_bot_paired_with_itself_gets_one_standing_row_without_those_games() {
        let mut s = small(3);
        s.bots = vec!["random".into(), "random".into(), "easy".into()];
        let report = run(&s).unwrap();
        assert_eq!(report.pairings.len(), 3);
        let names: Vec<&str> = report.standings.iter().map(|s| s.bot.as_str()).collect();
        assert_eq!(names, ["random", "easy"]);
        // random's games are the eight against easy, not those against itself.
        assert_eq!(report.standings[0].wdl.games(), 8);
        let t = table(&report);
        let rows = |bot: &str| {
            t.lines()
                .filter(|l| l.starts_with(&format!("{bot} ")) && !l.contains(" v "))
                .count()
        };
        assert_eq!((rows("random"), rows("easy")), (1, 1), "{t}");
        assert!(!t.contains("inf"), "{t}");
        // A tournament of one bot against itself: the pairing, no standings.
        s.bots = vec!["random".into(), "random".into()];
        let alone = run(&s).unwrap();
        assert!(alone.standings.is_empty());
        assert_eq!(table(&alone).lines().count(), 2);
    }

    #[test]
    fn unknown_bots_and_lonely_tournaments_are_refused() {
        let mut s = small(1);
        s.bots = vec!["random".into(), "deep-blue".into()];
        assert!(matches!(run(&s), Err(TournamentError::UnknownBot(n)) if n == "deep-blue"));
        s.bots = vec!["random".into()];
        assert!(matches!(run(&s), Err(TournamentError::TooFewBots)));
    }
}
