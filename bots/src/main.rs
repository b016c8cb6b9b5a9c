//! The `bots` command: tournaments between the scripted bots, a bot
//! playing a match on a real server (`play`, `online`), and checking a
//! finished match's noise against its commitment (`verify`).

use bots::runner::{CreateMatch, Opponent, Runner, RunnerOptions};
use bots::stats::Sprt;
use bots::tournament::{self, TournamentSettings};
use bots::{by_name, ArenaLimits};
use clap::{Parser, Subcommand};
use game::{NoiseConfig, Preset};
use std::path::PathBuf;
use std::process::ExitCode;

/// Chapaev bots: play tournaments between bots, or a match on a server.
#[derive(Parser, Debug)]
#[command(name = "bots", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// A round robin between bots, in this process.
    Tournament(TournamentArgs),
    /// One match on a server: create it, join it, or play a built-in level.
    Play(PlayArgs),
    /// Stay online as a bot account: join the ladder, accept challenges,
    /// play every match given (several at once).
    Online(OnlineArgs),
    /// Simulated shots per CPU-second over random positions: the native
    /// twin of the JavaScript and Python bindings' throughput benchmarks
    /// (the same requests for the same seed).
    Throughput(ThroughputArgs),
    /// Check finished matches' records: the revealed noise secret opens
    /// the commitment published before the first shot, every shot was
    /// played with the secret's draw, and the match replays exactly.
    Verify(VerifyArgs),
    /// One seeded match between two bots in this process, each a built-in
    /// bot, a WebAssembly module (`*.wasm`, run as the server hosts it) or
    /// a program speaking JSON lines on stdin and stdout (quote it with its
    /// arguments: "python3 bot.py").
    Match(MatchArgs),
    /// How the computer levels miss: each plays matches against itself
    /// with its throws logged; prints the sideways miss at the target
    /// (binned), angular misses by shot length and cut, and full power.
    Misses(MissesArgs),
}

#[derive(Parser, Debug)]
struct VerifyArgs {
    /// Record files (JSON, as `GET /api/matches/ID/record` serves them);
    /// `-` reads one from standard input.
    #[arg(required = true)]
    records: Vec<PathBuf>,
    /// Print each verdict as one JSON line instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Parser, Debug)]
struct MatchArgs {
    /// The two bots, first seat first: a built-in name (random, greedy,
    /// search, easy, medium, hard, adaptive), a `.wasm` file, or a command.
    #[arg(long, required = true, num_args = 1)]
    bot: Vec<String>,
    /// The match's seed: its noise, the built-in bots' choices and the
    /// WebAssembly bots' random streams all follow from it.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The rules: `standard` or `casual`.
    #[arg(long, default_value = "standard", value_parser = parse_rules)]
    rules: Preset,
    /// Write the match record (JSON, replayable) here.
    #[arg(long)]
    record: Option<PathBuf>,
    /// Milliseconds a program may take to answer.
    #[arg(long, default_value_t = 5000)]
    think_ms: u64,
}

#[derive(Parser, Debug)]
struct MissesArgs {
    /// Comma-separated levels with a fixed hand: easy, medium, hard.
    #[arg(long, value_delimiter = ',', default_value = "easy,medium,hard")]
    levels: Vec<String>,
    /// Matches of each level against itself.
    #[arg(long, default_value_t = 10)]
    games: u32,
    /// Match and bot seeds.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The rules: `standard` or `casual` (what people play the computer at).
    #[arg(long, default_value = "casual", value_parser = parse_rules)]
    rules: Preset,
    /// Write the reports as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
}

#[derive(Parser, Debug)]
struct ThroughputArgs {
    /// How many random requests to simulate.
    #[arg(long, default_value_t = 20_000)]
    count: u32,
    /// Their seed (`game::simulate::random_request` from one generator).
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

#[derive(Parser, Debug)]
struct OnlineArgs {
    /// The server, `http://HOST:PORT`.
    #[arg(long, default_value = "http://127.0.0.1:8080")]
    server: String,
    /// The bot account's key (create the account with `POST /api/accounts`
    /// `{"name":...,"bot":true}`); read from CHAPAEV_KEY if not given.
    #[arg(long, env = "CHAPAEV_KEY", hide_env_values = true)]
    key: String,
    /// The bot: random, greedy, search, easy, medium, hard, adaptive.
    #[arg(long, default_value = "greedy")]
    bot: String,
    /// Stay off the ladder (only accept challenges).
    #[arg(long)]
    no_ladder: bool,
    /// Most matches played at once.
    #[arg(long, default_value_t = 4)]
    max_matches: usize,
    /// Stop after this many matches (default: never).
    #[arg(long)]
    matches: Option<u64>,
    /// The bots' seed (each match's bot gets its own, from this).
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

#[derive(Parser, Debug)]
struct PlayArgs {
    /// The server, `http://HOST:PORT`.
    #[arg(long, default_value = "http://127.0.0.1:8080")]
    server: String,
    /// The bot: random, greedy, search, easy, medium, hard, adaptive.
    #[arg(long, default_value = "greedy")]
    bot: String,
    /// The name the bot plays under.
    #[arg(long)]
    name: Option<String>,
    /// The rules of a created match: `standard` (execution noise and the
    /// pie rule) or `casual`.
    #[arg(long, default_value = "standard", value_parser = parse_rules)]
    rules: Preset,
    #[command(flatten)]
    how: HowToPlay,
    /// The turn clock of a created match, seconds (the server's default if absent).
    #[arg(long)]
    turn_seconds: Option<u64>,
    /// The bot's seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// A public seed for a created match's noise: the noise `bots match
    /// --seed` draws locally with the same seed (the server refuses it for
    /// a rated match).
    #[arg(long)]
    match_seed: Option<u64>,
}

#[derive(clap::Args, Debug)]
#[group(required = true, multiple = false)]
struct HowToPlay {
    /// Create a match for someone to join.
    #[arg(long)]
    create: bool,
    /// Join the match with this id.
    #[arg(long, value_name = "MATCH_ID")]
    join: Option<String>,
    /// Create a match against the server's built-in level.
    #[arg(long, value_name = "LEVEL", value_parser = ["easy", "medium", "hard", "adaptive"])]
    against: Option<String>,
}

#[derive(Parser, Debug)]
struct TournamentArgs {
    /// Comma-separated bot names: random, greedy, search, easy, medium, hard, adaptive.
    #[arg(long, value_delimiter = ',', default_value = "random,greedy,search")]
    bots: Vec<String>,
    /// Games per pairing (played in pairs with the seats swapped).
    #[arg(long, default_value_t = 20)]
    games: u32,
    /// The tournament's seed (match seeds and the bots' generators).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The rules: `standard` (execution noise and the pie rule) or `casual`.
    #[arg(long, default_value = "standard", value_parser = parse_rules)]
    rules: Preset,
    /// Play under the configuration in this JSON file instead of `--rules`
    /// (a `game::Config`; missing fields take the defaults): how a rule
    /// variant is measured before it becomes a preset.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Override the rules' execution noise: `ANGLE,SPEED` standard
    /// deviations (radians, fraction of the speed); `0,0` turns it off.
    #[arg(long, value_parser = parse_noise)]
    noise: Option<NoiseConfig>,
    /// Stop a pairing once an SPRT between these two Elo differences
    /// decides, e.g. `0,50`.
    #[arg(long, value_parser = parse_sprt)]
    sprt: Option<Sprt>,
    /// Write the results as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write every game's record (JSON, replayable) into this folder.
    #[arg(long)]
    records: Option<PathBuf>,
    /// Milliseconds a bot may think per move.
    #[arg(long, default_value_t = 1000)]
    think_ms: u64,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Play every game on this running server (`http://HOST:PORT`) instead
    /// of in this process; the records stay there, replayable in the web
    /// client.
    #[arg(long)]
    server: Option<String>,
}

fn parse_rules(s: &str) -> Result<Preset, String> {
    Preset::parse(s).ok_or_else(|| format!("unknown rules {s:?}: standard or casual"))
}

fn parse_noise(s: &str) -> Result<NoiseConfig, String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| "expected ANGLE,SPEED, e.g. 0.03,0.05".to_string())?;
    let parse = |x: &str| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}"));
    let noise = NoiseConfig {
        angle_sigma: parse(a)?,
        speed_sigma: parse(b)?,
    };
    if !(0.0..=1.0).contains(&noise.angle_sigma) || !(0.0..=1.0).contains(&noise.speed_sigma) {
        return Err("noise standard deviations are between 0 and 1".into());
    }
    Ok(noise)
}

fn parse_sprt(s: &str) -> Result<Sprt, String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| "expected ELO0,ELO1, e.g. 0,50".to_string())?;
    let parse = |x: &str| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}"));
    let (e0, e1) = (parse(a)?, parse(b)?);
    if !e0.is_finite() || !e1.is_finite() || e0 >= e1 {
        return Err("ELO0 must be below ELO1, both finite".into());
    }
    Ok(Sprt::new(e0, e1))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let done = match cli.command {
        Command::Tournament(args) => tournament_command(args),
        Command::Play(args) => play_command(args),
        Command::Online(args) => online_command(args),
        Command::Throughput(args) => throughput_command(args),
        Command::Verify(args) => verify_command(args),
        Command::Misses(args) => misses_command(args),
        Command::Match(args) => match_command(args),
    };
    match done {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            let mut source = e.source();
            while let Some(s) = source {
                eprintln!("  caused by: {s}");
                source = s.source();
            }
            ExitCode::FAILURE
        }
    }
}

/// A record that failed `bots verify`.
#[derive(Debug, thiserror::Error)]
#[error("{failed} of {total} records did not verify")]
struct NotVerified {
    failed: usize,
    total: usize,
}

fn verify_command(args: VerifyArgs) -> Result<(), Box<dyn std::error::Error>> {
    use std::io::Read;
    let mut failed = 0;
    for path in &args.records {
        let text = if path.as_os_str() == "-" {
            let mut text = String::new();
            std::io::stdin().read_to_string(&mut text)?;
            text
        } else {
            std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?
        };
        let checked = game::verify_json(&text);
        failed += usize::from(checked.is_err());
        let name = path.display();
        match (&checked, args.json) {
            (Ok(v), true) => println!(
                "{}",
                serde_json::json!({"record": name.to_string(), "verified": true,
                    "scheme": v.scheme, "commitment": v.commitment.to_hex(), "shots": v.shots})
            ),
            (Err(e), true) => println!(
                "{}",
                serde_json::json!({"record": name.to_string(), "verified": false,
                    "code": e.code(), "error": e.to_string()})
            ),
            (Ok(v), false) => println!(
                "{name}: verified: the secret opens commitment {}, and all {} shots were played with its {} draws and replay exactly",
                v.commitment,
                v.shots,
                v.scheme
            ),
            (Err(e), false) => println!("{name}: NOT VERIFIED ({}): {e}", e.code()),
        }
    }
    if failed > 0 {
        return Err(NotVerified {
            failed,
            total: args.records.len(),
        }
        .into());
    }
    Ok(())
}

fn misses_command(args: MissesArgs) -> Result<(), Box<dyn std::error::Error>> {
    use bots::misses;
    let config = args.rules.config();
    let mut reports = Vec::new();
    for name in &args.levels {
        let level = bots::Level::parse(name)
            .ok_or_else(|| format!("unknown level {name:?}: easy, medium or hard"))?;
        let throws = misses::collect(level, args.games, args.seed, &config)?
            .ok_or_else(|| format!("{name} has no fixed hand to measure"))?;
        reports.push(misses::report(
            name,
            &config,
            level.hand().full_power,
            &throws,
        ));
    }
    println!(
        "rules {}, {} matches per level, seed {}\n",
        args.rules, args.games, args.seed
    );
    print!("{}", misses::table(&reports));
    if let Some(path) = args.json {
        std::fs::write(&path, serde_json::to_string_pretty(&reports)?)?;
        println!("\nresults: {}", path.display());
    }
    Ok(())
}

fn throughput_command(args: ThroughputArgs) -> Result<(), Box<dyn std::error::Error>> {
    use game::noise::SplitMix64;
    use game::simulate::{self, random_request};
    let mut rng = SplitMix64::new(args.seed);
    let requests: Vec<_> = (0..args.count).map(|_| random_request(&mut rng)).collect();
    // Each position checked and converted once, as a binding's `Simulator`
    // does; the timed part is the shot itself.
    let mut prepared = Vec::with_capacity(requests.len());
    for r in &requests {
        prepared.push((r, r.validate()?));
    }
    let clock = cpu_time::ProcessTime::now();
    let mut knocked = 0usize;
    for (r, (board, shot)) in &prepared {
        let v = r.played_velocity(shot);
        knocked += simulate::play(&r.config, board, shot, v, false)?
            .knocked_off
            .len();
    }
    let cpu = clock.elapsed().as_secs_f64();
    println!(
        "{}",
        serde_json::json!({
            "binding": "native",
            "shots": args.count,
            "knocked_off": knocked,
            "cpu_seconds": cpu,
            "shots_per_cpu_second": f64::from(args.count) / cpu,
        })
    );
    Ok(())
}

fn online_command(args: OnlineArgs) -> Result<(), Box<dyn std::error::Error>> {
    if by_name(&args.bot, args.seed).is_none() {
        return Err(format!(
            "unknown bot {:?}: one of {}",
            args.bot,
            bots::BOT_NAMES.join(", ")
        )
        .into());
    }
    let runner = Runner::new(&args.server)?;
    let (name, seed) = (args.bot.clone(), args.seed);
    let make = move |n: u64| {
        // Checked above: the name is a bot's.
        by_name(&name, seed.wrapping_add(n)).expect("a known bot")
    };
    let options = bots::online::OnlineOptions {
        ladder: !args.no_ladder,
        max_matches: args.max_matches,
        stop_after: args.matches,
    };
    let online = bots::online::Online::new(runner, &args.key, make, options);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    let report = runtime.block_on(online.run())?;
    println!(
        "{}",
        serde_json::json!({
            "finished": report.finished,
            "failed": report.failed,
            "rating": report.rating,
        })
    );
    Ok(())
}

fn play_command(args: PlayArgs) -> Result<(), Box<dyn std::error::Error>> {
    let bot = by_name(&args.bot, args.seed).ok_or_else(|| {
        format!(
            "unknown bot {:?}: one of {}",
            args.bot,
            bots::BOT_NAMES.join(", ")
        )
    })?;
    let name = args.name.clone().unwrap_or_else(|| args.bot.clone());
    let runner = Runner::new(&args.server)?.with_options(RunnerOptions {
        name: name.clone(),
        ..RunnerOptions::default()
    });
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let create = |opponent: Opponent| CreateMatch {
            name: Some(name.clone()),
            opponent,
            config: args.rules.config(),
            turn_seconds: args.turn_seconds,
            seed: args.match_seed,
        };
        let grant = match (&args.how.join, &args.how.against) {
            (Some(id), _) => runner.join(id, Some(&name)).await?,
            (None, Some(level)) => runner.create(&create(Opponent::Level(level.clone()))).await?,
            (None, None) => runner.create(&create(Opponent::Person)).await?,
        };
        println!("match {} (seat {:?})", grant.match_id, grant.seat);
        if args.how.create {
            println!(
                "invite: bots play --server {} --join {}",
                runner.server(),
                grant.match_id
            );
        }
        let (report, _) = runner.play(&grant, bot).await?;
        let result = match &report.result {
            Some(r) => serde_json::to_string(r)?,
            None => "unknown".into(),
        };
        let verdict = match (report.result.map(|r| r.winner()), report.side) {
            (Some(None), _) => "drew",
            (Some(Some(w)), Some(me)) if w == me => "won",
            (Some(Some(_)), _) => "lost",
            (None, _) => "unknown",
        };
        println!(
            "result: {result}; {name} played {} and {verdict}; {} shots ({} its own), {} reconnects",
            report.side.map_or("?".to_string(), |s| s.to_string()),
            report.shots,
            report.my_shots,
            report.reconnects
        );
        for e in &report.errors {
            println!("refused: {}: {}", e.code, e.message);
        }
        Ok::<(), Box<dyn std::error::Error>>(())
    })
}

fn tournament_command(args: TournamentArgs) -> Result<(), Box<dyn std::error::Error>> {
    let mut config = match &args.config {
        Some(path) => serde_json::from_str(&std::fs::read_to_string(path)?)?,
        None => args.rules.config(),
    };
    if let Some(noise) = args.noise {
        config.variants.noise =
            (noise.angle_sigma > 0.0 || noise.speed_sigma > 0.0).then_some(noise);
    }
    let settings = TournamentSettings {
        bots: args.bots,
        games: args.games,
        seed: args.seed,
        config,
        sprt: args.sprt,
        limits: ArenaLimits {
            think: std::time::Duration::from_millis(args.think_ms),
            ..ArenaLimits::default()
        },
        progress: !args.quiet,
        server: args.server,
    };
    let started = std::time::Instant::now();
    let report = tournament::run(&settings)?;
    let rules = match &args.config {
        Some(path) => path.display().to_string(),
        None => args.rules.to_string(),
    };
    println!(
        "rules {rules}, seed {}, {:.1} s\n",
        args.seed,
        started.elapsed().as_secs_f64()
    );
    print!("{}", tournament::table(&report));
    if let Some(path) = args.json {
        std::fs::write(&path, serde_json::to_string_pretty(&report)?)?;
        println!("\nresults: {}", path.display());
    }
    if let Some(dir) = args.records {
        std::fs::create_dir_all(&dir)?;
        for p in &report.pairings {
            for (k, g) in p.games.iter().enumerate() {
                let name = format!("{}-v-{}-{k:03}.json", g.first, g.second);
                std::fs::write(dir.join(name), serde_json::to_string(&g.record)?)?;
            }
        }
        println!("records: {}", dir.display());
    }
    Ok(())
}

/// A bot of `bots match`, kept by kind so a hosted one reports its fuel.
enum Contestant {
    Boxed(Box<dyn bots::Bot>),
    Hosted(bots::hosted_bot::HostedBot),
}

impl Contestant {
    fn new(spec: &str, seed: u64) -> Result<Contestant, Box<dyn std::error::Error>> {
        if let Some(bot) = by_name(spec, seed) {
            return Ok(Contestant::Boxed(bot));
        }
        if spec.ends_with(".wasm") {
            let bytes = std::fs::read(spec).map_err(|e| format!("{spec}: {e}"))?;
            let module = hosted::BotModule::load(&bytes, &hosted::Limits::default())?;
            // The secret the arena's match is keyed by (Game::new with the seed).
            let secret = game::NoiseSecret::from_seed(seed);
            return Ok(Contestant::Hosted(bots::hosted_bot::HostedBot::new(
                std::sync::Arc::new(module),
                secret,
            )));
        }
        Ok(Contestant::Boxed(Box::new(
            bots::program::ProgramBot::spawn(spec)?,
        )))
    }

    fn bot(&mut self) -> &mut dyn bots::Bot {
        match self {
            Contestant::Boxed(b) => b.as_mut(),
            Contestant::Hosted(h) => h,
        }
    }
}

fn match_command(args: MatchArgs) -> Result<(), Box<dyn std::error::Error>> {
    let [a, b] = args.bot.as_slice() else {
        return Err("give exactly two --bot".into());
    };
    let mut first = Contestant::new(a, args.seed)?;
    let mut second = Contestant::new(b, args.seed.wrapping_add(1))?;
    let limits = ArenaLimits {
        think: std::time::Duration::from_millis(args.think_ms),
        ..ArenaLimits::default()
    };
    let clock = cpu_time::ProcessTime::now();
    let report = bots::play_match(
        args.rules.config(),
        args.seed,
        first.bot(),
        second.bot(),
        &limits,
    )?;
    let cpu = clock.elapsed().as_secs_f64();
    if let Some(path) = &args.record {
        std::fs::write(path, serde_json::to_string(&report.record)?)?;
    }
    let usage = |c: &Contestant| match c {
        Contestant::Hosted(h) => {
            let u = h.usage();
            serde_json::json!({
                "decisions": u.decisions,
                "fuel": u.fuel,
                "fuel_per_decision": u.fuel.checked_div(u.decisions),
                "shots_simulated": u.shots,
                "failures": u.failures,
            })
        }
        Contestant::Boxed(_) => serde_json::Value::Null,
    };
    println!(
        "{}",
        serde_json::json!({
            "result": report.result,
            "shots": report.shots,
            "swapped": report.swapped,
            "refusals": report.refusals,
            "timeouts": report.timeouts,
            "first": {"bot": a, "score": report.score(game::Seat::First), "hosted": usage(&first)},
            "second": {"bot": b, "score": report.score(game::Seat::Second), "hosted": usage(&second)},
            "cpu_seconds": cpu,
            "record": args.record.as_ref().map(|p| p.display().to_string()),
        })
    );
    Ok(())
}
