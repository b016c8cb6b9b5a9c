//! The pie-rule decision: after White's first shot, Black may take White's
//! side. The right choice is the colour more likely to win the *match*
//! from here, so the decider swaps exactly when White's estimated match
//! score is above a half.
//!
//! A match is a chain of rounds, and every round after the first starts
//! from a fixed setup: the two rows and the side that opens. So White's
//! match score is estimated in two parts, both by playouts in which both
//! sides play the greedy shot under the match's public noise model (or an
//! assumed one where the match has none), with draws from the decider's
//! own generator:
//!
//! - **The current round, played out** from the position after White's
//!   first shot, with the side to shoot next (`view.turn`: White again when
//!   its first shot knocked off an enemy and none of its own), choosing
//!   from the cheap narrow spread.
//! - **The match's value after it** ([`MatchValues`]): the playouts of
//!   every setup the match can reach give each setup's chances, and the
//!   rules between rounds ([`game::rules::after_round`]: rows, far edge,
//!   who opens next) chain them into White's match score from each setup.
//!   These carry most of the weight, so they choose from the wide spread
//!   the built-in bots play. A setup is not pooled with its mirror image:
//!   a deterministic bot may open the two differently (that asymmetry is
//!   what made White lose under the earlier rules), and a decider that
//!   assumed them equal swapped into White 83 times of 100 there, where
//!   White scored 22 %. They depend only on the rules, so they are computed
//!   once per configuration (about 10 s of CPU, spread over the cores) and
//!   kept; the standard rules' values ship with the crate
//!   (`pie_values_standard.json`), so a standard match's first decision
//!   costs no more than any other.
//!
//! A playout that runs long is scored by the material on the board.
//!
//! The earlier decider swapped when White won more than half of 12 narrow
//! playouts of round 1 alone. Under the old `standard` rules White won
//! round 1 about 60 % of the time yet the match about 30 %: the rounds
//! after it favoured Black. So it swapped into the losing colour.

use crate::candidates::Spread;
use crate::eval;
use crate::eval::best_shot;
use crate::simulator::Simulator;
use game::noise::{NoiseDraw, SplitMix64};
use game::rules::{after_round, AfterRound, RoundResult, Verdict};
use game::{Board, Config, MatchResult, MatchView, NoiseConfig, Rows, Side};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// How the decider plays out.
#[derive(Clone, Debug, PartialEq)]
pub struct PieSettings {
    /// Playouts of the current round.
    pub playouts: u32,
    /// Playouts of each setup the match can reach, for [`MatchValues`].
    pub setup_playouts: u32,
    /// Shots after which a playout is scored by the material left.
    pub max_shots: u32,
    /// Noise assumed when the match has none.
    pub assumed_noise: NoiseConfig,
    /// The shots both sides choose from in the playouts of the current
    /// round (the greedy shot of this spread).
    pub spread: Spread,
    /// The same for the setups' playouts. They carry most of the weight
    /// (how much winning round 1 is worth), so they play the shots the
    /// built-in bots really choose from, once per configuration.
    pub setup_spread: Spread,
}

impl Default for PieSettings {
    fn default() -> Self {
        PieSettings {
            playouts: 32,
            setup_playouts: 16,
            max_shots: 40,
            assumed_noise: NoiseConfig {
                angle_sigma: 0.03,
                speed_sigma: 0.08,
            },
            spread: Spread::narrow(),
            setup_spread: Spread::wide(),
        }
    }
}

/// How one playout of a round ended.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ending {
    /// The round is over; `flawless`: its winner lost no piece.
    Over { result: RoundResult, flawless: bool },
    /// Unfinished after the shots allowed: White's share by material.
    Unfinished { white: f64 },
}

/// A round played out from `board` with `turn` to shoot.
fn play_round(
    config: &Config,
    spread: &Spread,
    noise: &NoiseConfig,
    board: &Board,
    turn: Side,
    max_shots: u32,
    rng: &mut SplitMix64,
) -> Ending {
    let mut board = board.clone();
    let mut turn = turn;
    for _ in 0..max_shots {
        let Some((shot, _)) = best_shot(config, &board, turn, spread) else {
            break;
        };
        let draw = NoiseDraw::sample(rng);
        let Ok(r) = Simulator::on(config, &board).play_with(turn, &shot, noise, draw) else {
            break;
        };
        match r.verdict {
            Verdict::RoundOver(result) => {
                let flawless = match result {
                    RoundResult::Won(w) => r.board.count(w) == board_pieces(config),
                    RoundResult::Draw => false,
                };
                return Ending::Over { result, flawless };
            }
            Verdict::ShootAgain => {}
            Verdict::PassTurn => turn = turn.opponent(),
        }
        board = r.board;
    }
    // Unfinished: the material and the turn, through a logistic.
    let v = eval::position(config, &board, Side::White, turn);
    Ending::Unfinished {
        white: 1.0 / (1.0 + (-v / (2.0 * eval::PIECE)).exp()),
    }
}

/// Pieces per side at a round's start.
fn board_pieces(config: &Config) -> usize {
    Board::setup(config, Rows::initial()).count(Side::White)
}

/// White's match score at the start of every round setup the match can
/// reach (the rows, and the side that opens), for one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct MatchValues {
    white: HashMap<(Rows, Side), f64>,
    variants: game::Variants,
}

/// How the rounds from one setup ended in its playouts: the weight of each
/// ending.
type Tally = Vec<(RoundResult, bool, f64)>;

/// Every setup (rows, the side that opens) a match under `variants` can
/// reach from its first round, whatever the rounds' results, sorted.
fn reachable(variants: &game::Variants) -> Vec<(Rows, Side)> {
    let mut seen: Vec<(Rows, Side)> = Vec::new();
    let mut todo = vec![(Rows::initial(), Side::White)];
    while let Some(state) = todo.pop() {
        if seen.contains(&state) {
            continue;
        }
        seen.push(state);
        let (rows, opens) = state;
        for result in [
            RoundResult::Won(Side::White),
            RoundResult::Won(Side::Black),
            RoundResult::Draw,
        ] {
            for flawless in [false, true] {
                if let AfterRound::Next { rows, opens: next } =
                    after_round(variants, rows, opens, result, flawless)
                {
                    todo.push((rows, next));
                }
            }
        }
    }
    seen.sort_by_key(|&(rows, opens)| setup_order(rows, opens));
    seen
}

/// The order setups are listed in: White's rank, Black's, the opener.
fn setup_order(rows: Rows, opens: Side) -> (u8, u8, usize) {
    (
        rows.rank(Side::White),
        rows.rank(Side::Black),
        opens.index(),
    )
}

/// The match values shipped with the crate, so that the first pie decision
/// of a standard match costs no more than the others (computing them takes
/// about 10 s of CPU). `the_shipped_match_values_are_the_computed_ones`
/// checks them against [`MatchValues::compute`] and rewrites the file when
/// run with `CHAPAEV_BLESS=1`.
const SHIPPED: &str = include_str!("pie_values_standard.json");

/// The file [`SHIPPED`] is read from: what the values were computed for,
/// and White's match score from each setup.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct ShippedValues {
    rules: Config,
    setup_playouts: u32,
    max_shots: u32,
    assumed_noise: NoiseConfig,
    setup_spread: Spread,
    /// (White's rank, Black's rank, the side that opens, White's score).
    white: Vec<(u8, u8, Side, f64)>,
}

impl ShippedValues {
    /// `values` as shipped, computed for `config` under `settings`.
    #[cfg(test)]
    fn of(config: &Config, settings: &PieSettings, values: &MatchValues) -> ShippedValues {
        let mut setups: Vec<(&(Rows, Side), &f64)> = values.white.iter().collect();
        setups.sort_by_key(|(&(rows, opens), _)| setup_order(rows, opens));
        let white = setups
            .into_iter()
            .map(|(&(rows, opens), &v)| (rows.rank(Side::White), rows.rank(Side::Black), opens, v))
            .collect();
        ShippedValues {
            rules: config.clone(),
            setup_playouts: settings.setup_playouts,
            max_shots: settings.max_shots,
            assumed_noise: settings.assumed_noise,
            setup_spread: settings.setup_spread.clone(),
            white,
        }
    }

    /// The values, if they were computed for `config` and `settings`.
    fn values_for(&self, config: &Config, settings: &PieSettings) -> Option<MatchValues> {
        let same = self.rules == *config
            && self.setup_playouts == settings.setup_playouts
            && self.max_shots == settings.max_shots
            && self.assumed_noise == settings.assumed_noise
            && self.setup_spread == settings.setup_spread;
        if !same {
            return None;
        }
        let mut white = HashMap::new();
        for &(w, b, opens, v) in &self.white {
            white.insert((Rows::new(w, b).ok()?, opens), v);
        }
        Some(MatchValues {
            white,
            variants: config.variants.clone(),
        })
    }
}

impl MatchValues {
    /// Plays out every reachable setup `settings.setup_playouts` times (the
    /// draws seeded by the setup alone, so the values depend only on the
    /// rules and the settings) and chains them by value iteration. The
    /// playouts run on plain threads, one per core: not on rayon's pool,
    /// whose waiting workers take up other jobs (a decision that waits on
    /// [`MatchValues::cached`]'s lock would deadlock there).
    pub fn compute(config: &Config, settings: &PieSettings) -> MatchValues {
        let noise = config.variants.noise.unwrap_or(settings.assumed_noise);
        let variants = config.variants.clone();
        let states = reachable(&variants);
        // One job per playout: (the setup's index in `states`, the playout).
        let jobs: Vec<(usize, u32)> = (0..states.len())
            .flat_map(|s| (0..settings.setup_playouts).map(move |k| (s, k)))
            .collect();
        // One playout, its draws seeded by the setup and its number alone.
        let play = |&(s, k): &(usize, u32)| {
            let (rows, opens): (Rows, Side) = states[s];
            let seed = (rows.rank(Side::White) as u64) << 40
                ^ (rows.rank(Side::Black) as u64) << 32
                ^ (opens.index() as u64) << 24
                ^ k as u64;
            let mut rng = SplitMix64::new(seed ^ 0x005E_ED0F_9A1E);
            let board = Board::setup(config, rows);
            play_round(
                config,
                &settings.setup_spread,
                &noise,
                &board,
                opens,
                settings.max_shots,
                &mut rng,
            )
        };
        #[cfg(feature = "parallel")]
        let endings: Vec<Ending> = {
            let threads = std::thread::available_parallelism()
                .map_or(1, |n| n.get())
                .clamp(1, jobs.len().max(1));
            std::thread::scope(|scope| {
                let workers: Vec<_> = (0..threads)
                    .map(|t| {
                        let (jobs, play) = (&jobs, &play);
                        scope.spawn(move || {
                            jobs.iter()
                                .enumerate()
                                .filter(|(i, _)| i % threads == t)
                                .map(|(i, job)| (i, play(job)))
                                .collect::<Vec<_>>()
                        })
                    })
                    .collect();
                let mut all: Vec<(usize, Ending)> = workers
                    .into_iter()
                    .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                    .collect();
                all.sort_by_key(|(i, _)| *i);
                all.into_iter().map(|(_, e)| e).collect()
            })
        };
        // Without threads (the browser), one after the other.
        #[cfg(not(feature = "parallel"))]
        let endings: Vec<Ending> = jobs.iter().map(play).collect();
        let mut tallies: Vec<((Rows, Side), Tally)> =
            states.iter().map(|&s| (s, Vec::new())).collect();
        for (&(s, _), ending) in jobs.iter().zip(&endings) {
            let tally = &mut tallies[s].1;
            let mut add = |result: RoundResult, flawless: bool, w: f64| match tally
                .iter_mut()
                .find(|t| t.0 == result && t.1 == flawless)
            {
                Some(t) => t.2 += w,
                None => tally.push((result, flawless, w)),
            };
            match *ending {
                Ending::Over { result, flawless } => add(result, flawless, 1.0),
                Ending::Unfinished { white } => {
                    add(RoundResult::Won(Side::White), false, white);
                    add(RoundResult::Won(Side::Black), false, 1.0 - white);
                }
            }
        }
        let mut values = MatchValues {
            white: states.iter().map(|&s| (s, 0.5)).collect(),
            variants,
        };
        // Value iteration, in the setups' order (so the result is the same
        // in every process): every round moves the match on or ends it, so
        // this converges (a drawn round repeats at most).
        for _ in 0..100_000 {
            let mut change: f64 = 0.0;
            for &((rows, opens), ref tally) in &tallies {
                let total: f64 = tally.iter().map(|t| t.2).sum();
                if total <= 0.0 {
                    continue;
                }
                let v: f64 = tally
                    .iter()
                    .map(|&(result, flawless, w)| w * values.after(rows, opens, result, flawless))
                    .sum::<f64>()
                    / total;
                let old = values.white.insert((rows, opens), v).unwrap_or(0.5);
                change = change.max((v - old).abs());
            }
            if change < 1e-12 {
                break;
            }
        }
        values
    }

    /// White's match score at the start of the round on `rows` opened by
    /// `opens` (a half for a setup the match cannot reach).
    pub fn white(&self, rows: Rows, opens: Side) -> f64 {
        self.white.get(&(rows, opens)).copied().unwrap_or(0.5)
    }

    /// White's match score after a round on `rows` opened by `opened`
    /// ended with `result`.
    pub fn after(&self, rows: Rows, opened: Side, result: RoundResult, flawless: bool) -> f64 {
        match after_round(&self.variants, rows, opened, result, flawless) {
            AfterRound::Next { rows, opens } => self.white(rows, opens),
            AfterRound::Over(MatchResult::Won { side, .. }) => {
                if side == Side::White {
                    1.0
                } else {
                    0.0
                }
            }
            AfterRound::Over(MatchResult::Draw) => 0.5,
        }
    }

    /// The values of `config` under `settings`, computed once per process.
    pub fn cached(config: &Config, settings: &PieSettings) -> Arc<MatchValues> {
        type Key = (Config, u32, u32, NoiseConfig, Spread);
        type Cache = Vec<(Key, Arc<MatchValues>)>;
        static CACHE: Mutex<Cache> = Mutex::new(Vec::new());
        let key = (
            config.clone(),
            settings.setup_playouts,
            settings.max_shots,
            settings.assumed_noise,
            settings.setup_spread.clone(),
        );
        // Computed while holding the lock, on plain threads (see
        // `compute`): a thread that waits in rayon could otherwise take up
        // another decision that needs the same lock.
        let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, v)) = cache.iter().find(|(k, _)| *k == key) {
            return v.clone();
        }
        let shipped = serde_json::from_str::<ShippedValues>(SHIPPED)
            .ok()
            .and_then(|s| s.values_for(config, settings));
        let values = Arc::new(shipped.unwrap_or_else(|| MatchValues::compute(config, settings)));
        cache.push((key, values.clone()));
        values
    }
}

/// White's expected match score from `view`'s position in round 1 (opened
/// by White; the side to shoot is `view.turn`), 0–1.
pub fn white_share(view: &MatchView, settings: &PieSettings, seed: u64) -> f64 {
    let config = &view.config;
    let values = MatchValues::cached(config, settings);
    white_share_with(view, settings, seed, &values)
}

/// [`white_share`] with the match values given.
pub fn white_share_with(
    view: &MatchView,
    settings: &PieSettings,
    seed: u64,
    values: &MatchValues,
) -> f64 {
    let config = &view.config;
    let noise = config.variants.noise.unwrap_or(settings.assumed_noise);
    // The pie decision comes in round 1, which White opened.
    let opened = Side::White;
    let playout = |k: u32| {
        let mut rng = SplitMix64::new(seed ^ (k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let ending = play_round(
            config,
            &settings.spread,
            &noise,
            &view.board,
            view.turn,
            settings.max_shots,
            &mut rng,
        );
        match ending {
            Ending::Over { result, flawless } => values.after(view.rows, opened, result, flawless),
            Ending::Unfinished { white } => {
                let won = |s| values.after(view.rows, opened, RoundResult::Won(s), false);
                white * won(Side::White) + (1.0 - white) * won(Side::Black)
            }
        }
    };
    #[cfg(feature = "parallel")]
    let total: f64 = {
        use rayon::prelude::*;
        (0..settings.playouts).into_par_iter().map(playout).sum()
    };
    // Without threads (the browser), one after the other.
    #[cfg(not(feature = "parallel"))]
    let total: f64 = (0..settings.playouts).map(playout).sum();
    total / settings.playouts.max(1) as f64
}

/// Whether Black should take White's side: White's match score above a
/// half.
pub fn swap(view: &MatchView, settings: &PieSettings, seed: u64) -> bool {
    white_share(view, settings, seed) > 0.5
}

/// A seed for the playouts that follows from the position alone (for bots
/// without a generator of their own: the same position, the same choice).
pub fn position_seed(view: &MatchView) -> u64 {
    let mut h = SplitMix64::new(view.shots as u64);
    let mut acc = h.next_u64();
    for p in view.board.pieces() {
        acc = acc.rotate_left(7)
            ^ p.pos.x.to_bits()
            ^ p.pos.y.to_bits().rotate_left(31)
            ^ p.id.number() as u64;
        acc = SplitMix64::new(acc).next_u64();
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, PieceId, Shot};
    use glam::DVec2;

    /// Few playouts: enough for positions that are far from even.
    fn quick() -> PieSettings {
        PieSettings {
            playouts: 12,
            setup_playouts: 16,
            setup_spread: Spread::narrow(),
            ..PieSettings::default()
        }
    }

    /// A standard match after White's first shot, with the board then set
    /// to `white` and `black` pieces (by file, on the opening ranks). The
    /// match is a single round, so the position alone decides it.
    fn position(white: &[u8], black: &[u8], turn: Side) -> MatchView {
        let g = Game::new(one_round(), 4).unwrap();
        let mut view = g.view();
        let c = &view.config;
        let pieces = white
            .iter()
            .map(|&f| (PieceId::new(Side::White, f).unwrap(), f, 0))
            .chain(
                black
                    .iter()
                    .map(|&f| (PieceId::new(Side::Black, f).unwrap(), f, 7)),
            )
            .map(|(id, f, r)| game::Piece {
                id,
                pos: game::board::square_centre(c, f, r),
            });
        view.board = Board::from_pieces(pieces);
        view.turn = turn;
        view.shots = 1;
        view.phase = game::Phase::PieDecision;
        view
    }

    /// The standard rules in a single round.
    fn one_round() -> Config {
        let mut config = Config::standard();
        config.variants.quick_match = true;
        config
    }

    #[test]
    fn black_takes_whites_side_when_white_is_far_ahead_and_keeps_its_own_when_behind() {
        let all: Vec<u8> = (0..8).collect();
        // White kept all eight and Black has two left: White is winning.
        let ahead = position(&all, &[0, 7], Side::White);
        let share = white_share(&ahead, &quick(), 1);
        assert!(share > 0.7, "{share}");
        assert!(swap(&ahead, &quick(), 1));
        // The other way round: keep Black.
        let behind = position(&[0, 7], &all, Side::Black);
        let share = white_share(&behind, &quick(), 1);
        assert!(share < 0.3, "{share}");
        assert!(!swap(&behind, &quick(), 1));
    }

    #[test]
    fn black_keeps_its_side_when_white_opened_by_losing_its_own_piece() {
        let mut g = Game::new(one_round(), 4).unwrap();
        // White flicks its corner piece off its own back edge.
        let piece = PieceId::new(Side::White, 0).unwrap();
        let shot = Shot::new(piece, DVec2::new(-2.0, 0.0), g.config()).unwrap();
        g.play(Side::White, shot).unwrap();
        let view = g.view();
        assert_eq!(view.board.count(Side::White), 7);
        assert_eq!(view.turn, Side::Black, "a lost own piece passes the turn");
        let share = white_share(&view, &quick(), 1);
        assert!(share < 0.5, "{share}");
        assert!(!swap(&view, &quick(), 1));
    }

    #[test]
    fn the_match_values_follow_the_rows_a_side_whose_row_is_about_to_win_is_ahead() {
        let rows = |w, b| Rows::new(w, b).unwrap();
        // Under the standard rules the rows stop two ranks apart, so the
        // last rounds are played on 5–7 and 0–2.
        let values = MatchValues::cached(&Config::standard(), &quick());
        let start = values.white(Rows::initial(), Side::White);
        let near_white_win = values.white(rows(5, 7), Side::White);
        let near_black_win = values.white(rows(0, 2), Side::Black);
        assert!(
            near_white_win > start && start > near_black_win,
            "{near_white_win} {start} {near_black_win}"
        );
        // White's round win on 5–7 wins the match; Black's on 0–2 loses it.
        let won = RoundResult::Won(Side::White);
        assert_eq!(values.after(rows(5, 7), Side::White, won, false), 1.0);
        let lost = RoundResult::Won(Side::Black);
        assert_eq!(values.after(rows(0, 2), Side::Black, lost, false), 0.0);
        // Adjacent rows cannot be reached: they count as even.
        assert_eq!(values.white(rows(3, 4), Side::White), 0.5);
    }

    #[test]
    fn the_shipped_match_values_are_the_computed_ones() {
        let (config, settings) = (Config::standard(), PieSettings::default());
        let computed = MatchValues::compute(&config, &settings);
        let fresh = ShippedValues::of(&config, &settings, &computed);
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/pie_values_standard.json");
        if std::env::var_os("CHAPAEV_BLESS").is_some() {
            let text = serde_json::to_string_pretty(&fresh).expect("plain data");
            std::fs::write(path, text + "\n").expect("the source tree is writable");
            return;
        }
        let shipped: ShippedValues =
            serde_json::from_str(SHIPPED).expect("the shipped values parse");
        assert_eq!(
            shipped, fresh,
            "{path} is stale: rerun this test with CHAPAEV_BLESS=1 to rewrite it"
        );
        assert_eq!(shipped.values_for(&config, &settings), Some(computed));
        let mut other = config.clone();
        other.variants.quick_match = true;
        assert_eq!(shipped.values_for(&other, &settings), None);
    }

    #[test]
    fn the_position_seed_follows_the_position() {
        let a = Game::new(Config::default(), 1).unwrap().view();
        let b = Game::new(Config::default(), 2).unwrap().view();
        assert_eq!(
            position_seed(&a),
            position_seed(&b),
            "the match seed plays no part"
        );
        let mut c = a.clone();
        c.shots = 1;
        assert_ne!(position_seed(&a), position_seed(&c));
    }
}
