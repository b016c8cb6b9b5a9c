//! How near 50 % the adaptive level holds each fixed level, as a person
//! who plays it again and again would meet it: one adaptive bot object per
//! series of matches against the same opponent (so it carries its starting
//! strength from match to match, as the server does per account), colours
//! alternating, independent series in parallel.
//!
//! ```text
//! cargo run --release -p bots --example adaptive_series -- --series 6 --matches 16
//! ```
//!
//! Prints, per opponent, the opponent's score over all matches and over
//! the matches after the first third of each series (once the level has
//! found the person), with a 95 % interval, and the mean starting strength.

use bots::adaptive::{Adaptive, AdaptiveSettings};
use bots::arena::{play_match, ArenaLimits};
use bots::level::Level;
use clap::Parser;
use game::{Preset, Seat};
use rayon::prelude::*;

#[derive(Parser)]
struct Args {
    /// Opponents (fixed levels), comma-separated.
    #[arg(long, default_value = "easy,medium,hard", value_delimiter = ',')]
    opponents: Vec<String>,
    /// Independent series per opponent.
    #[arg(long, default_value_t = 6)]
    series: u64,
    /// Matches per series.
    #[arg(long, default_value_t = 16)]
    matches: u64,
    /// Rules: casual (what people play the computer on) or standard.
    #[arg(long, default_value = "casual")]
    rules: String,
    /// Seed of the series.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// The opponent's score (1, ½, 0) and the level's starting strength.
type Played = (f64, f64);

fn summary(x: &[Played]) -> String {
    let n = x.len() as f64;
    let score = x.iter().map(|r| r.0).sum::<f64>() / n;
    let start = x.iter().map(|r| r.1).sum::<f64>() / n;
    let half = 1.96 * (score * (1.0 - score) / n).sqrt();
    format!(
        "{:5.1} % ± {:4.1} ({:3})   start {:.2}",
        100.0 * score,
        100.0 * half,
        x.len(),
        start
    )
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    let config = Preset::parse(&args.rules)
        .ok_or_else(|| format!("unknown rules {:?} (casual, standard)", args.rules))?
        .config();
    if args.series == 0 || args.matches == 0 {
        return Err("--series and --matches must be at least 1".into());
    }
    println!(
        "adaptive against each level: {} series of {} matches, {} rules, seed {}",
        args.series, args.matches, args.rules, args.seed
    );
    println!(
        "{:8} {:38} after the first third",
        "opponent", "opponent's score, all matches"
    );
    for name in &args.opponents {
        let level = Level::parse(name)
            .filter(|l| *l != Level::Adaptive)
            .ok_or_else(|| format!("unknown fixed level {name:?}"))?;
        let series: Vec<Vec<Played>> = (0..args.series)
            .into_par_iter()
            .map(|g| {
                let seed = args.seed.wrapping_mul(1_000_003).wrapping_add(g);
                let mut adaptive = Adaptive::new(AdaptiveSettings::default(), seed);
                (0..args.matches)
                    .map(|m| {
                        let mut person = level.bot(seed.wrapping_mul(7777).wrapping_add(m));
                        let adaptive_first = (g + m) % 2 == 0;
                        let start = adaptive.start();
                        let limits = ArenaLimits::default();
                        let match_seed = seed.wrapping_mul(99).wrapping_add(13 * m);
                        let (first, second): (&mut dyn bots::Bot, &mut dyn bots::Bot) =
                            if adaptive_first {
                                (&mut adaptive, person.as_mut())
                            } else {
                                (person.as_mut(), &mut adaptive)
                            };
                        let report = play_match(config.clone(), match_seed, first, second, &limits)
                            .expect("the preset's configuration is valid");
                        let seat = if adaptive_first {
                            Seat::Second
                        } else {
                            Seat::First
                        };
                        (report.score(seat), start)
                    })
                    .collect()
            })
            .collect();
        let all: Vec<Played> = series.iter().flatten().copied().collect();
        let later: Vec<Played> = series
            .iter()
            .flat_map(|s| s[s.len() / 3..].iter().copied())
            .collect();
        println!("{:8} {:38} {}", name, summary(&all), summary(&later));
    }
    Ok(())
}
