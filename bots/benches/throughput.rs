//! Simulated shots per CPU-second on one core, and the time of one
//! decision of `greedy` and `search`, as medians over rounds. CPU time
//! (this thread's, from `/proc/thread-self/stat`) rather than wall time,
//! so that other work on the machine and the hypervisor's steal blur it
//! less. `cargo bench -p bots --bench throughput`.
use bots::candidates::{candidates, Spread};
use bots::{by_name, Bot, Context, Decision, Greedy, Simulator};
use game::{Config, Game, MatchView, Phase};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// This thread's CPU time (user + system), in seconds, at 10 ms resolution.
fn thread_cpu() -> f64 {
    cpu_of("/proc/thread-self/stat")
}

/// The whole process's CPU time (every thread: the search's rayon pool).
fn process_cpu() -> f64 {
    cpu_of("/proc/self/stat")
}

fn cpu_of(path: &str) -> f64 {
    let stat = std::fs::read_to_string(path).unwrap_or_default();
    // The fields after the command name (which may hold spaces) start at ')'.
    let rest = stat.rsplit_once(')').map(|(_, r)| r).unwrap_or("");
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok()).unwrap_or(0.0);
    // utime and stime are fields 14 and 15 of the line, 12 and 13 after ')'.
    (ticks(11) + ticks(12)) / 100.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// A mid-game position: greedy against greedy for a dozen shots.
fn mid_game() -> MatchView {
    let mut config = Config::standard();
    config.variants.pie_rule = false;
    let mut game = Game::new(config, 3).unwrap();
    let mut bot = Greedy::default();
    while game.shots() < 12 && game.phase() == Phase::Shooting {
        let side = game.to_shoot().unwrap();
        let view = game.view();
        let Decision::Shot(shot) = bot.decide(&Context::new(&view, side, Duration::from_secs(5)))
        else {
            break;
        };
        game.play(side, shot).unwrap();
    }
    game.view()
}

fn main() {
    if std::env::args().any(|a| a == "--list") {
        println!("throughput: bench");
        return;
    }
    let view = mid_game();
    let side = view.turn;
    let shots = candidates(&view.config, &view.board, side, &Spread::wide());
    let sim = Simulator::new(&view);
    let mut rates = Vec::new();
    for _ in 0..9 {
        let (cpu0, mut n) = (thread_cpu(), 0u64);
        let wall = Instant::now();
        while wall.elapsed() < Duration::from_millis(1500) {
            for s in &shots {
                black_box(sim.play(side, black_box(s)).ok());
            }
            n += shots.len() as u64;
        }
        let cpu = thread_cpu() - cpu0;
        if cpu > 0.0 {
            rates.push(n as f64 / cpu);
        }
    }
    println!(
        "simulator: mid-game board ({} pieces, {} candidates): median {:.0} simulated shots per CPU-second on one core",
        view.board.pieces().len(),
        shots.len(),
        median(rates)
    );
    for name in ["greedy", "search"] {
        let (mut walls, mut cpus) = (Vec::new(), Vec::new());
        for k in 0..9 {
            let mut bot = by_name(name, k).unwrap();
            let (cpu0, wall) = (process_cpu(), Instant::now());
            black_box(bot.decide(&Context::new(&view, side, Duration::from_secs(10))));
            walls.push(wall.elapsed().as_secs_f64());
            cpus.push(process_cpu() - cpu0);
        }
        println!(
            "{name}: one decision on the mid-game board: median {:.1} ms wall ({} threads), {:.0} ms CPU in all",
            1e3 * median(walls),
            rayon::current_num_threads(),
            1e3 * median(cpus)
        );
    }
}
