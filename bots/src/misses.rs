//! How a level misses, measured: a level plays whole matches against
//! itself with both hands logging their throws ([`crate::Handed`]), and
//! each throw's miss is read off geometrically — the angle between the
//! intended and the played direction, the speed played over the speed
//! intended, and the sideways miss at the target (how far the played line
//! passes the target's centre from where the intended line passed it:
//! 0 is the intended contact, a piece's diameter or more misses the
//! target entirely). The report bins the sideways misses, compares short
//! shots with long ones and straight shots with thin cuts, and counts the
//! full-power flicks that came out harder than nominal. `bots misses`
//! prints it.

use crate::arena::{play_match, ArenaLimits};
use crate::hand::Aim;
use crate::handed::Throw;
use crate::level::Level;
use game::noise::SplitMix64;
use game::{Config, ConfigError};
use serde::Serialize;
use std::fmt::Write as _;

/// One throw's miss.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Miss {
    /// What the intended shot aimed at.
    pub aim: Aim,
    /// The angle between intended and played direction, rad (≥ 0).
    pub angle: f64,
    /// Played speed over intended speed.
    pub speed_ratio: f64,
    /// How far the played line passes the target's centre from where the
    /// intended line passed it, m (`None`: the intended line met no piece).
    pub sideways: Option<f64>,
    /// Whether the played line still meets the target.
    pub hit: Option<bool>,
}

impl Miss {
    /// The miss of `throw` under `config`.
    pub fn of(config: &Config, throw: &Throw) -> Miss {
        let aim = Aim::of(config, &throw.board, &throw.intended);
        let (u, p) = (throw.intended.velocity(), throw.played.velocity());
        let angle = u.angle_to(p).abs();
        let speed_ratio = p.length() / u.length();
        let start = throw.board.piece(throw.intended.piece()).map(|m| m.pos);
        let (sideways, hit) = match (aim.target, start) {
            (Some(t), Some(s)) => {
                let rel = t - s;
                let off = |d: glam::DVec2| rel.perp_dot(d.normalize_or_zero());
                let played = off(p);
                let reach = 2.0 * config.piece_radius;
                let ahead = rel.dot(p) > 0.0;
                (
                    Some((played - off(u)).abs()),
                    Some(ahead && played.abs() < reach),
                )
            }
            _ => (None, None),
        };
        Miss {
            aim,
            angle,
            speed_ratio,
            sideways,
            hit,
        }
    }
}

/// The upper edges of the sideways-miss bins, mm (the last bin is open).
pub const SIDEWAYS_BINS_MM: [f64; 6] = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0];

/// A level's misses, summed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MissReport {
    pub level: String,
    pub throws: usize,
    /// Throws aimed at a piece, per sideways-miss bin
    /// ([`SIDEWAYS_BINS_MM`], then the open bin).
    pub sideways_bins: Vec<usize>,
    /// Throws aimed at a piece whose played line missed it.
    pub target_missed: usize,
    pub aimed_at_a_piece: usize,
    /// Median angular miss, rad: all throws; short shots (contact within
    /// two squares) and long (beyond four); straight (cut under 0.1) and
    /// thin cuts (0.4 or more).
    pub median_angle: f64,
    pub median_angle_short: Option<f64>,
    pub median_angle_long: Option<f64>,
    pub median_angle_straight: Option<f64>,
    pub median_angle_thin: Option<f64>,
    /// Shots intended at the level's full power, and how many of them came
    /// out harder (by more than 1 %) and softer.
    pub full_power: usize,
    pub full_power_harder: usize,
    pub full_power_softer: usize,
    /// Mean intended speed over the maximum.
    pub mean_power: f64,
}

fn median(mut xs: Vec<f64>) -> Option<f64> {
    if xs.is_empty() {
        return None;
    }
    xs.sort_by(f64::total_cmp);
    Some(xs[xs.len() / 2])
}

/// The report of `level`'s `throws` under `config`.
pub fn report(level: &str, config: &Config, full_power: f64, throws: &[Throw]) -> MissReport {
    let misses: Vec<Miss> = throws.iter().map(|t| Miss::of(config, t)).collect();
    let mut bins = vec![0; SIDEWAYS_BINS_MM.len() + 1];
    let (mut aimed, mut missed) = (0, 0);
    for m in &misses {
        if let Some(s) = m.sideways {
            aimed += 1;
            let mm = s * 1000.0;
            let k = SIDEWAYS_BINS_MM
                .iter()
                .position(|&edge| mm < edge)
                .unwrap_or(SIDEWAYS_BINS_MM.len());
            bins[k] += 1;
        }
        if m.hit == Some(false) {
            missed += 1;
        }
    }
    let sq = config.square;
    let angles = |keep: &dyn Fn(&Miss) -> bool| {
        median(misses.iter().filter(|m| keep(m)).map(|m| m.angle).collect())
    };
    let nominal = config.max_speed * full_power;
    let full: Vec<(&Throw, &Miss)> = throws
        .iter()
        .zip(&misses)
        .filter(|(t, _)| t.intended.speed() >= 0.999 * nominal)
        .collect();
    MissReport {
        level: level.to_string(),
        throws: throws.len(),
        sideways_bins: bins,
        target_missed: missed,
        aimed_at_a_piece: aimed,
        median_angle: angles(&|_| true).unwrap_or(0.0),
        median_angle_short: angles(&|m| m.aim.target.is_some() && m.aim.distance < 2.0 * sq),
        median_angle_long: angles(&|m| m.aim.target.is_some() && m.aim.distance >= 4.0 * sq),
        median_angle_straight: angles(&|m| m.aim.target.is_some() && m.aim.cut < 0.1),
        median_angle_thin: angles(&|m| m.aim.target.is_some() && m.aim.cut >= 0.4),
        full_power: full.len(),
        full_power_harder: full.iter().filter(|(_, m)| m.speed_ratio > 1.01).count(),
        full_power_softer: full.iter().filter(|(_, m)| m.speed_ratio < 0.99).count(),
        mean_power: throws
            .iter()
            .map(|t| t.intended.speed() / config.max_speed)
            .sum::<f64>()
            / throws.len().max(1) as f64,
    }
}

/// The throws of `games` matches of `level` against itself under
/// `config`, both seats logging; match and bot seeds follow from `seed`.
/// `None` for a level without a fixed hand (`adaptive`).
pub fn collect(
    level: Level,
    games: u32,
    seed: u64,
    config: &Config,
) -> Result<Option<Vec<Throw>>, ConfigError> {
    let mut rng = SplitMix64::new(seed);
    let mut throws = Vec::new();
    let limits = ArenaLimits::default();
    for _ in 0..games {
        let (a, b, m) = (rng.next_u64(), rng.next_u64(), rng.next_u64());
        let (Some(first), Some(second)) = (level.handed(a), level.handed(b)) else {
            return Ok(None);
        };
        let (mut first, mut second) = (first.logging(), second.logging());
        play_match(config.clone(), m, &mut first, &mut second, &limits)?;
        throws.extend_from_slice(first.throws());
        throws.extend_from_slice(second.throws());
    }
    Ok(Some(throws))
}

/// One row of the summary table: a report's figure as text.
type Cell<'a> = dyn Fn(&MissReport) -> String + 'a;

/// The reports as the tables a person reads.
pub fn table(reports: &[MissReport]) -> String {
    let mut out = String::new();
    let pct = |n: usize, of: usize| 100.0 * n as f64 / of.max(1) as f64;
    let _ = write!(out, "{:<22}", "sideways miss at target");
    for r in reports {
        let _ = write!(out, " {:>9}", r.level);
    }
    out.push('\n');
    let mut lower = 0.0;
    for (k, edge) in SIDEWAYS_BINS_MM
        .iter()
        .map(Some)
        .chain(std::iter::once(None))
        .enumerate()
    {
        let label = match edge {
            Some(e) => format!("{lower:>4}-{e} mm"),
            None => format!(">= {lower} mm"),
        };
        let _ = write!(out, "{label:<22}");
        for r in reports {
            let _ = write!(
                out,
                " {:>8.1}%",
                pct(r.sideways_bins[k], r.aimed_at_a_piece)
            );
        }
        out.push('\n');
        if let Some(e) = edge {
            lower = *e;
        }
    }
    let deg = |x: Option<f64>| x.map_or("-".to_string(), |r| format!("{:.2}°", r.to_degrees()));
    let rows: [(&str, &Cell); 10] = [
        ("throws", &|r| r.throws.to_string()),
        ("target missed", &|r| {
            format!("{:.1}%", pct(r.target_missed, r.aimed_at_a_piece))
        }),
        ("median angle, all", &|r| deg(Some(r.median_angle))),
        ("  short (< 2 sq)", &|r| deg(r.median_angle_short)),
        ("  long (>= 4 sq)", &|r| deg(r.median_angle_long)),
        ("  straight (cut<.1)", &|r| deg(r.median_angle_straight)),
        ("  thin (cut>=.4)", &|r| deg(r.median_angle_thin)),
        ("mean power / max", &|r| format!("{:.2}", r.mean_power)),
        ("full-power shots", &|r| r.full_power.to_string()),
        ("  harder / softer", &|r| {
            format!(
                "{:.0}/{:.0}%",
                pct(r.full_power_harder, r.full_power),
                pct(r.full_power_softer, r.full_power)
            )
        }),
    ];
    out.push('\n');
    for (name, f) in rows {
        let _ = write!(out, "{name:<22}");
        for r in reports {
            let _ = write!(out, " {:>9}", f(r));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shaky_level_misses_wider_than_a_steady_one_and_long_shots_miss_more_than_short() {
        let config = Config::default();
        let easy = collect(Level::Easy, 1, 4, &config).unwrap().unwrap();
        let medium = collect(Level::Medium, 1, 4, &config).unwrap().unwrap();
        let e = report("easy", &config, Level::Easy.hand().full_power, &easy);
        let m = report("medium", &config, Level::Medium.hand().full_power, &medium);
        assert!(e.throws > 10 && m.throws > 10, "{e:?} {m:?}");
        assert!(e.median_angle > 1.5 * m.median_angle, "{e:?} {m:?}");
        // Every throw logged has a miss, and the bins count every aimed one.
        assert_eq!(e.sideways_bins.iter().sum::<usize>(), e.aimed_at_a_piece);
        let all: Vec<Miss> = easy.iter().map(|t| Miss::of(&config, t)).collect();
        let sq = config.square;
        let mean = |f: &dyn Fn(&Miss) -> bool| {
            let xs: Vec<f64> = all.iter().filter(|m| f(m)).map(|m| m.angle).collect();
            xs.iter().sum::<f64>() / xs.len().max(1) as f64
        };
        let short = mean(&|m| m.aim.target.is_some() && m.aim.distance < 2.0 * sq);
        let long = mean(&|m| m.aim.target.is_some() && m.aim.distance >= 3.0 * sq);
        assert!(long > short, "long {long} short {short}");
        assert!(collect(Level::Adaptive, 1, 4, &config).unwrap().is_none());
    }
}
