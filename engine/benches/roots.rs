//! Per-query cost of `first_root(c, 0, +inf)` on quartics for every method
//! of `roots` and two peer crates: `kurbo::common::solve_quartic` (a port of
//! Orellana & De Michele's Algorithm 1010) and `roots::find_roots_quartic`.
//! Peers return all roots; the query keeps the smallest one `>= 0`.
//!
//! A last group times `roots_in(c, 0, 10)` on the contact batch, the form
//! the engine itself uses (every contact before a stop time).
//!
//! With `-- --hard-table`, the table is followed by each hard quartic
//! timed on its own (ours and kurbo) instead of criterion's groups; with
//! `-- --classes`, by the mixed batch's queries timed one by one and
//! summed by class (where `production`'s time goes).
//!
//! First of all, before criterion's groups, a table of the same
//! `first_root` queries timed the way this machine allows a fair
//! comparison: every solver in turn on one batch, round after round in one
//! process, in CPU time of this thread (the hypervisor's steal and the wall
//! clock's drift are not counted), with the median round per solver and
//! its ratio to `production` (ours and the two peers only).
//!
//! Batches: `contact` (polynomials `|dp + dv t + da t^2/2|^2 - S^2` from a
//! fixed pseudo-random stream, a quarter of them touching at `t = 0`),
//! `hard` (published hard quartics and clustered/scaled cases) and `mixed`
//! (both). Throughput is set to the batch size, so criterion's time per
//! element is the time per query.

use cpu_time::ThreadTime;
use criterion::{black_box, Criterion, Throughput};
use engine::rng::Rng;
use engine::roots::{Bisection, ClosedForm, Production, RootSolver};

/// `|dp + dv t + da t^2/2|^2 - s^2`, lowest degree first.
fn contact(dp: [f64; 2], dv: [f64; 2], da: [f64; 2], s: f64) -> [f64; 5] {
    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
    [
        dot(dp, dp) - s * s,
        2.0 * dot(dp, dv),
        dot(dv, dv) + dot(dp, da),
        dot(dv, da),
        0.25 * dot(da, da),
    ]
}

fn contact_batch(n: usize) -> Vec<[f64; 5]> {
    // SplitMix64, so the batch is fixed.
    let mut rng = Rng::splitmix64(0x5EED);
    (0..n)
        .map(|i| {
            let s = rng.range(0.5, 2.0);
            let dp = if i % 4 == 0 {
                // Exactly touching at t = 0: |(3k, 4k)| = 5k.
                let k = (1 + rng.next_u64() % 8) as f64 * 0.125;
                let sign = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
                return contact(
                    [3.0 * k * sign, 4.0 * k],
                    [rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)],
                    [rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)],
                    5.0 * k,
                );
            } else {
                [rng.range(-10.0, 10.0), rng.range(-10.0, 10.0)]
            };
            let dv = [rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)];
            let da = [rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)];
            contact(dp, dv, da, s)
        })
        .collect()
}

/// Expands `prod (x - r)` in `f64` (lowest degree first).
fn from_roots(r: [f64; 4]) -> [f64; 5] {
    let mut c = [1.0, 0.0, 0.0, 0.0, 0.0];
    for (k, &x) in r.iter().enumerate() {
        for j in (0..=k + 1).rev() {
            let lower = if j > 0 { c[j - 1] } else { 0.0 };
            c[j] = lower - x * c[j];
        }
    }
    c
}

fn hi_first(c: [f64; 5]) -> [f64; 5] {
    [c[4], c[3], c[2], c[1], c[0]]
}

fn hard_batch() -> Vec<[f64; 5]> {
    let mut v = vec![
        // Flocke, Algorithm 954 (ACM TOMS 2015), published quartics.
        hi_first([
            1.0,
            -1001001001.0,
            1001002001001000.0,
            -1001001001000000000.0,
            1e18,
        ]),
        hi_first([1.0, -4.006, 6.018011, -4.018022006, 1.006011006]),
        hi_first([
            1.0,
            -1.00000000000002e14,
            1.99999999999999e14,
            1.00000000000002e14,
            -2e14,
        ]),
        hi_first([1.0, 1e7, -2.00000000000001e14, -1e7, 2e14]),
        hi_first([1.0, -9.000002e6, -0.9999981999998e13, 1.9999982e13, -2e13]),
        hi_first([1.0, 2.000011e6, 1.010022000028e12, 1.1110056e13, 2.828e13]),
        hi_first([
            1.0,
            -1.00002011e8,
            2.01101022001e11,
            -1.02200111000011e14,
            1.1000011e15,
        ]),
        hi_first([
            1.0,
            -2.0000002e7,
            1.01000040000005e14,
            -2.020001e14,
            5.05e14,
        ]),
        hi_first([
            1.0,
            -1.9986e4,
            1.00720058e8,
            -1.8600979874e10,
            1.00004909000441e14,
        ]),
        hi_first([
            1.0,
            -4.006,
            5.6008018e1,
            -1.04148036024e2,
            6.75896068064016e2,
        ]),
        hi_first([1.0, -4e3, 6.00001e6, -4.00002e9, 1.000010000009e12]),
        hi_first([1.0, -6.0, 1.01000013e8, -2.04000012e8, 1.00000104000004e14]),
        // Orellana & De Michele, Algorithm 1010 (ACM TOMS 2020), cases 23, 24.
        [0.001, 0.375, 1.0, 1.0, 1.0],
        [-1e30, 1e60 + 1e30, 1e-30 - 1e60, -(1.0 + 1e-30), 1.0],
        // Multiple and clustered roots.
        [6.0, -17.0, 17.0, -7.0, 1.0],
        [4.0, -12.0, 13.0, -6.0, 1.0],
        [1.0, -4.0, 6.0, -4.0, 1.0],
    ];
    for r in [
        [2.003, 2.002, 2.001, 2.0],
        [1e14, 2.0, 1.0, -1.0],
        [-2e7, 1e7, 1.0, -1.0],
        [1e4, 10001.0, 10010.0, 10100.0],
        [1e14, 1e7, 1e7, 1.0],
        [1.0, 1.0 + 1e-7, 2.0, 3.0],
        [0.1, 0.1, 0.3, -0.7],
        [1e-8, 1e-3, 1e3, 1e8],
        [1e3, 1e3, 1e3, 2f64.powi(-48)],
    ] {
        v.push(from_roots(r));
    }
    v
}

type Query = fn(&[f64; 5]) -> Option<f64>;

fn smallest_nonneg(it: impl Iterator<Item = f64>) -> Option<f64> {
    it.filter(|&x| x >= 0.0)
        .fold(None, |m, x| Some(m.map_or(x, |m: f64| m.min(x))))
}

fn solvers() -> Vec<(&'static str, Query)> {
    vec![
        ("production", |c| {
            Production.first_root(c, 0.0, f64::INFINITY)
        }),
        ("closed_form", |c| {
            ClosedForm.first_root(c, 0.0, f64::INFINITY)
        }),
        ("bisection", |c| Bisection.first_root(c, 0.0, f64::INFINITY)),
        ("kurbo", |c| {
            smallest_nonneg(kurbo::common::solve_quartic(c[0], c[1], c[2], c[3], c[4]).into_iter())
        }),
        ("roots_crate", |c| {
            let r = roots::find_roots_quartic(c[4], c[3], c[2], c[1], c[0]);
            smallest_nonneg(r.as_ref().iter().copied())
        }),
    ]
}

type RangeQuery = fn(&[f64; 5]) -> usize;

/// `roots_in(c, 0, 10)` as the engine calls it (all contacts before a stop
/// time), returning the count.
fn range_solvers() -> Vec<(&'static str, RangeQuery)> {
    vec![
        ("production", |c| Production.roots_in(c, 0.0, 10.0).len()),
        ("closed_form", |c| ClosedForm.roots_in(c, 0.0, 10.0).len()),
        ("bisection", |c| Bisection.roots_in(c, 0.0, 10.0).len()),
        ("kurbo", |c| {
            kurbo::common::solve_quartic(c[0], c[1], c[2], c[3], c[4])
                .iter()
                .filter(|x| (0.0..10.0).contains(*x))
                .count()
        }),
        ("roots_crate", |c| {
            let r = roots::find_roots_quartic(c[4], c[3], c[2], c[1], c[0]);
            r.as_ref()
                .iter()
                .filter(|x| (0.0..10.0).contains(*x))
                .count()
        }),
    ]
}

/// The batches by name: `contact`, `hard` and `mixed` (both).
fn batches() -> [(&'static str, Vec<[f64; 5]>); 3] {
    let contact = contact_batch(512);
    let hard = hard_batch();
    let mixed: Vec<[f64; 5]> = contact.iter().chain(hard.iter()).copied().collect();
    [("contact", contact), ("hard", hard), ("mixed", mixed)]
}

/// One pass of `query` over `batch`: how many queries find a root.
fn hits(query: Query, batch: &[[f64; 5]]) -> usize {
    batch
        .iter()
        .filter(|&p| query(black_box(p)).is_some())
        .count()
}

fn bench(c: &mut Criterion, batches: &[(&str, Vec<[f64; 5]>)]) {
    for (name, batch) in batches {
        let mut g = c.benchmark_group(format!("first_root/{name}"));
        g.throughput(Throughput::Elements(batch.len() as u64));
        for (solver, query) in solvers() {
            g.bench_function(solver, |b| b.iter(|| hits(query, batch)));
        }
        g.finish();
    }
    let contact = &batches[0].1;
    let mut g = c.benchmark_group("roots_in_0_10/contact");
    g.throughput(Throughput::Elements(contact.len() as u64));
    for (solver, query) in range_solvers() {
        g.bench_function(solver, |b| {
            b.iter(|| contact.iter().map(|p| query(black_box(p))).sum::<usize>())
        });
    }
    g.finish();
}

/// The solvers in the interleaved table: ours and the two peers.
const PEERS: [&str; 3] = ["production", "kurbo", "roots_crate"];

/// Rounds of the interleaved CPU-time table per batch.
const ROUNDS: usize = 301;

/// Passes over the batch per timed round (a round of the contact batch is
/// then about a millisecond, far above the clock's resolution).
const PASSES: usize = 40;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The interleaved CPU-time table (see the module doc).
fn cpu_table(batches: &[(&str, Vec<[f64; 5]>)]) {
    let solvers: Vec<(&str, Query)> = solvers()
        .into_iter()
        .filter(|s| PEERS.contains(&s.0))
        .collect();
    let names: Vec<&str> = solvers.iter().map(|s| s.0).collect();
    println!("first_root(c, 0, inf): CPU time per query, median of {ROUNDS} interleaved rounds");
    println!(
        "| batch | queries | {} | {} |",
        names.join(" | "),
        names[1..]
            .iter()
            .map(|n| format!("{n} / production"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|---:|{}", "---:|".repeat(2 * names.len() - 1));
    for (name, batch) in batches {
        let mut t: Vec<Vec<f64>> = vec![Vec::with_capacity(ROUNDS); solvers.len()];
        for _ in 0..ROUNDS {
            for (k, (_, query)) in solvers.iter().enumerate() {
                let start = ThreadTime::now();
                for _ in 0..PASSES {
                    black_box(hits(*query, batch));
                }
                let per_query = start.elapsed().as_secs_f64() / (PASSES * batch.len()) as f64;
                t[k].push(per_query);
            }
        }
        let m: Vec<f64> = t.into_iter().map(median).collect();
        println!(
            "| {name} | {} | {} | {} |",
            batch.len(),
            m.iter()
                .map(|s| format!("{:.1} ns", s * 1e9))
                .collect::<Vec<_>>()
                .join(" | "),
            m[1..]
                .iter()
                .map(|s| format!("{:.2}", s / m[0]))
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
}

/// Rounds and repetitions per round of [`hard_table`].
const HARD_ROUNDS: usize = 31;
const HARD_REPS: usize = 2000;

/// Each hard quartic on its own: the median round's CPU time per query of
/// `production` and `kurbo`, interleaved, and `production`'s first root
/// (where the hard batch's time goes).
fn hard_table(hard: &[[f64; 5]]) {
    let ours = solvers()[0].1;
    let kurbo = solvers()[3].1;
    println!("hard quartics one by one: CPU time per query, median of {HARD_ROUNDS} rounds");
    println!("| # | production | kurbo | kurbo / production | first root |");
    println!("|---:|---:|---:|---:|---|");
    for (k, c) in hard.iter().enumerate() {
        let (mut t_ours, mut t_kurbo) = (Vec::new(), Vec::new());
        for _ in 0..HARD_ROUNDS {
            for (query, t) in [(ours, &mut t_ours), (kurbo, &mut t_kurbo)] {
                let start = ThreadTime::now();
                for _ in 0..HARD_REPS {
                    black_box(query(black_box(c)));
                }
                t.push(start.elapsed().as_secs_f64() / HARD_REPS as f64);
            }
        }
        let (a, b) = (median(t_ours), median(t_kurbo));
        println!(
            "| {k} | {:.1} ns | {:.1} ns | {:.2} | {:?} |",
            a * 1e9,
            b * 1e9,
            b / a,
            ours(c)
        );
    }
}

/// Rounds and repetitions per round of [`class_table`].
const CLASS_ROUNDS: usize = 15;
const CLASS_REPS: usize = 500;

/// The mixed batch's queries to `production`, each timed on its own (the
/// median round's CPU time per query; alone, its branches are better
/// predicted than in the batch), summed by class: the batch it comes from,
/// its answer (`0` when `p(0) = 0`, a positive first root, or none) and
/// how many real roots the quartic has.
fn class_table(batches: &[(&str, Vec<[f64; 5]>)]) {
    let ours = solvers()[0].1;
    let mut classes: Vec<((&str, &str, usize), usize, f64)> = Vec::new();
    for (name, batch) in &batches[..2] {
        for c in batch {
            let mut t = Vec::with_capacity(CLASS_ROUNDS);
            for _ in 0..CLASS_ROUNDS {
                let start = ThreadTime::now();
                for _ in 0..CLASS_REPS {
                    black_box(ours(black_box(c)));
                }
                t.push(start.elapsed().as_secs_f64() / CLASS_REPS as f64);
            }
            let answer = match ours(c) {
                Some(0.0) => "0",
                Some(_) => "a positive root",
                None => "none",
            };
            let key = (*name, answer, Production.real_roots(c).len());
            let time = median(t);
            match classes.iter_mut().find(|e| e.0 == key) {
                Some(e) => {
                    e.1 += 1;
                    e.2 += time;
                }
                None => classes.push((key, 1, time)),
            }
        }
    }
    classes.sort_by(|a, b| b.2.total_cmp(&a.2));
    let total: f64 = classes.iter().map(|e| e.2).sum();
    println!("mixed batch by class: production's CPU time per query alone, median of {CLASS_ROUNDS} rounds");
    println!("| batch | first root | real roots | queries | mean | share of the sum |");
    println!("|---|---|---:|---:|---:|---:|");
    for ((batch, answer, real), n, time) in classes {
        println!(
            "| {batch} | {answer} | {real} | {n} | {:.1} ns | {:.1} % |",
            time / n as f64 * 1e9,
            100.0 * time / total
        );
    }
}

fn main() {
    let batches = batches();
    cpu_table(&batches);
    if std::env::args().any(|a| a == "--classes") {
        class_table(&batches);
        return;
    }
    if std::env::args().any(|a| a == "--hard-table") {
        hard_table(&batches[1].1);
        return;
    }
    let mut c = Criterion::default()
        .sample_size(30)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2))
        .configure_from_args();
    bench(&mut c, &batches);
    c.final_summary();
}
