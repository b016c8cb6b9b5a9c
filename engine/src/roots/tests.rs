//! Cross-method tests: the hard-polynomial table of `cases.rs` (published
//! cases from Algorithm 1010 and Algorithm 954, clustered, multiple and
//! widely scaled roots, low degrees and degenerate input) checked against
//! high-precision reference roots of the polynomial as rounded to `f64`;
//! property tests on random products of linear factors and on arbitrary
//! input; and contact polynomials `|dp + dv t + da t^2/2|^2 - S^2` as the
//! engine builds them.

use super::cases::{hard_table, Expect, Expect::Rel, Expect::Ulps, Expect::Wrong};
use super::reference::{reference_roots, set_distance_rel, set_distance_ulps};
use super::{Bisection, ClosedForm, Method, Production, RootSolver, Roots};

fn methods() -> [(&'static str, &'static dyn RootSolver); 3] {
    [
        ("production", &Production),
        ("closed-form", &ClosedForm),
        ("bisection", &Bisection),
    ]
}

fn fmt_dist(u: u64) -> String {
    if u == u64::MAX {
        "count".into()
    } else {
        format!("{u}")
    }
}

fn meets(e: Expect, got: &[f64], reference: &[f64]) -> bool {
    match e {
        Ulps(n) => set_distance_ulps(got, reference) <= n,
        Rel(r) => set_distance_rel(got, reference) <= r,
        Wrong => true,
    }
}

fn well_formed(r: &Roots) -> bool {
    r.iter().all(|x| x.is_finite()) && r.windows(2).all(|w| w[0] <= w[1])
}

/// Every method on every case of the hard table, against the exact roots
/// of the polynomial as rounded to `f64`. Prints the whole table (run with
/// `--nocapture`) and fails on any case where a method does worse than the
/// table says. `Wrong` entries document where a method legitimately fails.
#[test]
fn hard_table_each_method_meets_its_documented_accuracy() {
    let mut failures = Vec::new();
    let mut worst_production = 0u64;
    for c in hard_table() {
        let reference = reference_roots(&c.coeffs);
        let mut line = format!("{:<42} ref n={}", c.name, reference.len());
        for (name, m) in methods() {
            let expect = match name {
                "production" => c.production,
                "closed-form" => c.closed_form,
                _ => c.bisection,
            };
            let got = m.real_roots(&c.coeffs);
            let ulps = set_distance_ulps(&got, &reference);
            if name == "production" && !matches!(expect, Wrong) {
                worst_production = worst_production.max(ulps);
            }
            line += &format!(
                " | {name} n={} ulps={} rel={:.1e}",
                got.len(),
                fmt_dist(ulps),
                set_distance_rel(&got, &reference)
            );
            if !well_formed(&got) || !meets(expect, &got, &reference) {
                failures.push(format!(
                    "{name} on {}: expected {expect:?}, got {:?} vs {reference:?}",
                    c.name,
                    got.as_slice()
                ));
            }
        }
        println!("{line}");
    }
    println!("worst Production error on the supported cases: {worst_production} ulps");
    assert!(failures.is_empty(), "{failures:#?}");
}

/// `first_root` and `roots_in` on the hard table, for many intervals: the
/// roots stay inside `[lo, hi)`, `first_root` is `roots_in(..).first()`, and
/// every reference root well inside the interval is found.
#[test]
fn hard_table_production_intervals_match_reference() {
    for c in hard_table() {
        if matches!(c.production, Wrong) {
            continue;
        }
        let reference = reference_roots(&c.coeffs);
        let mut cuts = vec![f64::NEG_INFINITY, 0.0, f64::INFINITY];
        for &r in &reference {
            cuts.extend([r, r * 0.5, r * 1.5 + 1.0, r - 1.0]);
        }
        for &lo in &cuts {
            for &hi in &cuts {
                let got = Production.roots_in(&c.coeffs, lo, hi);
                assert!(well_formed(&got), "{}", c.name);
                assert!(
                    got.iter().all(|&r| lo <= r && r < hi),
                    "{} [{lo}, {hi}) {got:?}",
                    c.name
                );
                assert_eq!(
                    Production.first_root(&c.coeffs, lo, hi),
                    got.first(),
                    "{} [{lo}, {hi})",
                    c.name
                );
                for &r in &reference {
                    let margin = 1e-9 * r.abs().max(1e-300);
                    if r > lo + margin && r < hi - margin {
                        let near = got.iter().any(|&x| set_distance_ulps(&[x], &[r]) <= 4);
                        assert!(near, "{} [{lo}, {hi}): missed {r}, got {got:?}", c.name);
                    }
                }
            }
        }
    }
}

#[test]
fn roots_type_behaves_like_a_sorted_slice() {
    let r: Roots = Production.real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0]);
    assert_eq!(r.len(), 4);
    assert!(!r.is_empty());
    assert_eq!(r.first(), Some(1.0));
    assert_eq!(&r[1..3], &[2.0, 3.0]);
    assert_eq!(r.iter().sum::<f64>(), 10.0);
    assert_eq!(Roots::default(), Roots::new());
    assert!(Roots::default().is_empty());
    assert_eq!(Roots::default().first(), None);
}

#[test]
fn method_dispatch_names_and_default() {
    assert_eq!(Method::default(), Method::Production);
    let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
    assert_eq!(names, ["bisection", "closed-form", "production"]);
    let c = [2.0, -3.0, 1.0];
    for m in Method::ALL {
        assert_eq!(m.real_roots(&c).as_slice(), &[1.0, 2.0], "{}", m.name());
        assert_eq!(m.first_root(&c, 1.5, f64::INFINITY), Some(2.0));
        assert_eq!(m.roots_in(&c, 0.0, 2.0).as_slice(), &[1.0]);
    }
}

// ---------------------------------------------------------------------
// Property tests: random products of linear factors.
// ---------------------------------------------------------------------

use super::poly::{horner_comp, horner_exact, normalize, Native};
use proptest::prelude::*;

/// `lead * prod (x - r)` expanded in `f64` (lowest degree first): the test
/// polynomial *is* this rounded expansion; the reference is computed from it.
fn expand_f64(lead: f64, roots: &[f64]) -> Vec<f64> {
    let mut c = vec![lead];
    for &r in roots {
        let mut next = vec![0.0; c.len() + 1];
        for (i, &ci) in c.iter().enumerate() {
            next[i + 1] += ci;
            next[i] -= r * ci;
        }
        c = next;
    }
    c
}

/// A root drawn from one of several regimes: moderate, widely scaled, or
/// part of a cluster around a shared centre.
fn root_strategy() -> impl Strategy<Value = f64> {
    prop_oneof![
        -10.0..10.0f64,
        (-8i32..8, prop::bool::ANY, 1.0..9.99f64)
            .prop_map(|(e, neg, m)| if neg { -m } else { m } * 10f64.powi(e)),
        (-3.0..3.0f64, 0u32..4, 1i32..10).prop_map(|(c, k, e)| c + k as f64 * 10f64.powi(-e)),
    ]
}

fn poly_strategy() -> impl Strategy<Value = Vec<f64>> {
    (
        prop::collection::vec(root_strategy(), 1..=4),
        (-3i32..3, prop::bool::ANY),
    )
        .prop_map(|(roots, (e, neg))| {
            let lead = if neg { -1.0 } else { 1.0 } * 10f64.powi(e) * 1.37;
            expand_f64(lead, &roots)
        })
}

/// Evaluates the exact sign of `p` (as given) at `x`.
fn exact_value(c: &[f64], x: f64) -> f64 {
    let (a, n) = normalize(c).unwrap();
    match n {
        1 => horner_exact::<1, Native>(&a, x),
        2 => horner_exact::<2, Native>(&a, x),
        3 => horner_exact::<3, Native>(&a, x),
        _ => horner_exact::<4, Native>(&a, x),
    }
}

fn comp_bound(c: &[f64], x: f64) -> f64 {
    let (a, n) = normalize(c).unwrap();
    match n {
        1 => horner_comp::<1, Native>(&a, x).1,
        2 => horner_comp::<2, Native>(&a, x).1,
        3 => horner_comp::<3, Native>(&a, x).1,
        _ => horner_comp::<4, Native>(&a, x).1,
    }
}

/// `r` is a genuine root: the exact value changes sign within a few ulps
/// of `r`, or is zero, or is below the compensated error bound (a touching
/// root reported once).
fn is_genuine_root(c: &[f64], r: f64) -> bool {
    let step = |x: f64, k: i32| {
        let mut y = x;
        for _ in 0..k.abs() {
            // One ulp away from zero or towards it (y is finite, non-zero).
            let bits = y.to_bits();
            y = f64::from_bits(if (k > 0) == (y > 0.0) {
                bits + 1
            } else {
                bits - 1
            });
        }
        y
    };
    let v = exact_value(c, r);
    if v == 0.0 || v.abs() <= 4.0 * comp_bound(c, r) {
        return true;
    }
    (-4..=4).any(|k| {
        let w = exact_value(c, step(r, k));
        w == 0.0 || (w < 0.0) != (v < 0.0)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    /// Production finds every real root of the f64 polynomial, and nothing
    /// else, to within a few ulps.
    #[test]
    fn production_matches_the_f64_exact_roots_of_random_products(c in poly_strategy()) {
        let reference = reference_roots(&c);
        let got = Production.real_roots(&c);
        let d = set_distance_ulps(&got, &reference);
        prop_assert!(d <= 8, "{c:?}: got {:?}, reference {reference:?} ({d} ulps)", got.as_slice());
    }

    /// `first_root` is exactly `roots_in(..).first()`, and `roots_in` keeps
    /// to `[lo, hi)`, for arbitrary intervals.
    #[test]
    fn first_root_agrees_with_roots_in_first(
        c in poly_strategy(),
        lo in prop_oneof![Just(f64::NEG_INFINITY), Just(0.0), -20.0..20.0f64],
        width in prop_oneof![Just(f64::INFINITY), 0.0..40.0f64],
    ) {
        let hi = lo + width;
        let all = Production.roots_in(&c, lo, hi);
        prop_assert!(all.iter().all(|&r| lo <= r && r < hi));
        prop_assert_eq!(Production.first_root(&c, lo, hi), all.first());
        for m in Method::ALL {
            let r = m.roots_in(&c, lo, hi);
            prop_assert!(r.iter().all(|&x| lo <= x && x < hi));
            prop_assert_eq!(m.first_root(&c, lo, hi), r.first());
        }
    }

    /// No spurious roots: the exact polynomial changes sign within a few
    /// ulps of every reported root (or the root is a touching point whose
    /// value is within the compensated error bound).
    #[test]
    fn production_reports_no_spurious_roots(c in poly_strategy()) {
        for &r in Production.real_roots(&c).iter() {
            prop_assert!(is_genuine_root(&c, r), "{c:?}: {r} is not a root");
        }
    }

    /// The baselines on well-separated moderate roots: Bisection to a few
    /// ulps, ClosedForm to a loose relative tolerance (unpolished Ferrari).
    #[test]
    fn baselines_on_well_separated_roots(
        base in prop::collection::vec(-8.0..8.0f64, 1..=4),
    ) {
        let mut roots = base.clone();
        roots.sort_by(|a, b| a.partial_cmp(b).unwrap());
        prop_assume!(roots.windows(2).all(|w| w[1] - w[0] > 0.5));
        let c = expand_f64(1.0, &roots);
        let reference = reference_roots(&c);
        let bis = Bisection.real_roots(&c);
        prop_assert!(set_distance_rel(&bis, &reference) <= 1e-13, "bisection {:?} vs {reference:?}", bis.as_slice());
        let cf = ClosedForm.real_roots(&c);
        prop_assert!(set_distance_rel(&cf, &reference) <= 1e-8, "closed form {:?} vs {reference:?}", cf.as_slice());
    }
}

// ---------------------------------------------------------------------
// Contact polynomials, as the engine builds them.
// ---------------------------------------------------------------------

/// `f(t) = |dp + dv t + da t^2/2|^2 - s^2`, lowest degree first.
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

fn vec2(r: f64) -> impl Strategy<Value = [f64; 2]> {
    (-r..r, -r..r).prop_map(|(x, y)| [x, y])
}

fn contact_strategy() -> impl Strategy<Value = [f64; 5]> {
    (
        vec2(10.0),
        vec2(5.0),
        prop_oneof![Just([0.0, 0.0]), vec2(2.0)],
        0.1..2.0f64,
        prop::bool::weighted(0.25),
        0.0..std::f64::consts::TAU,
    )
        .prop_map(|(dp, dv, da, s, touching, angle)| {
            if touching {
                // Exactly touching at t = 0: |(3k, 4k)| = 5k in exact arithmetic,
                // rotated by a quarter turn or not.
                let k = (s * 8.0).round().max(1.0) / 8.0;
                let dp = if angle < 3.0 {
                    [3.0 * k, -4.0 * k]
                } else {
                    [-4.0 * k, 3.0 * k]
                };
                contact(dp, dv, da, 5.0 * k)
            } else {
                contact(dp, dv, da, s)
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, .. ProptestConfig::default() })]

    /// The engine's query: the first contact at or after `t = 0`.
    #[test]
    fn contact_first_root_matches_reference(c in contact_strategy()) {
        let reference: Vec<f64> = reference_roots(&c).into_iter().filter(|&r| r >= 0.0).collect();
        let got = Production.first_root(&c, 0.0, f64::INFINITY);
        match (got, reference.first()) {
            (None, None) => {}
            (Some(g), Some(&r)) => {
                let d = set_distance_ulps(&[g], &[r]);
                prop_assert!(d <= 8, "{c:?}: got {g}, reference {r} ({d} ulps)");
            }
            (g, r) => prop_assert!(false, "{c:?}: got {g:?}, reference {r:?}"),
        }
        if c[0] == 0.0 {
            prop_assert_eq!(got, Some(0.0));
        }
        let all = Production.roots_in(&c, 0.0, f64::INFINITY);
        prop_assert!(set_distance_ulps(&all, &reference) <= 8, "{c:?}: {all:?} vs {reference:?}");
    }

    /// Every method agrees with Production on the count of contacts in
    /// `[0, 10)` when the polynomial is well conditioned there.
    #[test]
    fn contact_methods_agree_on_well_conditioned_cases(c in contact_strategy()) {
        let reference: Vec<f64> = reference_roots(&c);
        let isolated = reference.windows(2).all(|w| w[1] - w[0] > 1e-3)
            && reference.iter().all(|r| (r.abs() > 1e-3 && (r - 10.0).abs() > 1e-3) || *r == 0.0);
        prop_assume!(isolated);
        let expected = reference.iter().filter(|&&r| (0.0..10.0).contains(&r)).count();
        prop_assert_eq!(Production.roots_in(&c, 0.0, 10.0).len(), expected);
        prop_assert_eq!(Bisection.roots_in(&c, 0.0, 10.0).len(), expected);
    }
}

#[test]
fn contact_grazing_touch_is_reported_once() {
    // Passing at exactly distance S: f(t) = (t - 1)^2, a touching root at 1.
    let c = contact([-1.0, 0.5], [1.0, 0.0], [0.0, 0.0], 0.5);
    assert_eq!(c, [1.0, -2.0, 1.0, 0.0, 0.0]);
    assert_eq!(Production.first_root(&c, 0.0, f64::INFINITY), Some(1.0));
    assert_eq!(Production.roots_in(&c, 0.0, f64::INFINITY).len(), 1);
    // Decelerating along the line of motion and stopping exactly at the
    // touching point: f(t) = (t - 2)^4 / 16, a quadruple touching root.
    let c = contact([-1.0, 0.5], [1.0, 0.0], [-0.5, 0.0], 0.5);
    assert_eq!(c, [1.0, -2.0, 1.5, -0.5, 0.0625]);
    assert_eq!(Production.first_root(&c, 0.0, f64::INFINITY), Some(2.0));
    assert_eq!(
        Production.roots_in(&c, 0.0, f64::INFINITY).as_slice(),
        &[2.0]
    );
}

#[test]
fn contact_touching_at_zero_and_separating() {
    // Touching at t = 0 and moving apart: the root at 0 is reported (the
    // engine decides from f'(0) >= 0 that it is not a new contact); no later
    // root.
    let c = contact([3.0, 4.0], [1.0, 1.0], [0.0, 0.0], 5.0);
    assert_eq!(c[0], 0.0);
    assert_eq!(Production.first_root(&c, 0.0, f64::INFINITY), Some(0.0));
    assert_eq!(
        Production.first_root(&c, f64::MIN_POSITIVE, f64::INFINITY),
        None
    );
    // Touching at 0 and approaching: overlap, then separation later.
    let c = contact([3.0, 4.0], [-1.0, -1.0], [0.0, 0.0], 5.0);
    let later = Production
        .first_root(&c, f64::MIN_POSITIVE, f64::INFINITY)
        .unwrap();
    assert!((later - 7.0).abs() <= 4.0 * f64::EPSILON * 7.0, "{later}");
}

#[test]
fn degenerate_inputs_never_panic_and_give_no_roots() {
    let bad: [&[f64]; 7] = [
        &[],
        &[0.0],
        &[3.0],
        &[f64::NAN, 1.0],
        &[1.0, f64::INFINITY, 1.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        &[f64::NEG_INFINITY, 0.0, 0.0, 0.0, 1.0],
    ];
    for c in bad {
        for m in Method::ALL {
            assert!(m.real_roots(c).is_empty(), "{} {c:?}", m.name());
            assert_eq!(m.first_root(c, 0.0, f64::INFINITY), None);
        }
    }
    // NaN or empty intervals.
    for m in Method::ALL {
        let c = [-1.0, 0.0, 1.0];
        assert!(m.roots_in(&c, f64::NAN, 1.0).is_empty());
        assert!(m.roots_in(&c, 0.0, f64::NAN).is_empty());
        assert!(m.roots_in(&c, 2.0, 2.0).is_empty());
        assert!(m.roots_in(&c, 3.0, -3.0).is_empty());
        assert_eq!(m.roots_in(&c, 1.0, 1.0 + 1e-12).as_slice(), &[1.0]);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, .. ProptestConfig::default() })]

    /// Arbitrary bit patterns (NaN, infinities, subnormals, huge values) and
    /// arbitrary intervals: no panic, no overflow trap (tests run with debug
    /// assertions), and the result is always sorted, finite and in range.
    #[test]
    fn arbitrary_input_never_panics(
        c in prop::collection::vec(prop_oneof![
            any::<f64>(),
            -1e3..1e3f64,
            Just(0.0),
            (-300i32..300).prop_map(|e| 10f64.powi(e)),
        ], 0..7),
        lo in prop_oneof![any::<f64>(), Just(f64::NEG_INFINITY), Just(0.0), -10.0..10.0f64],
        hi in prop_oneof![any::<f64>(), Just(f64::INFINITY), -10.0..10.0f64],
    ) {
        for m in Method::ALL {
            let all = m.roots_in(&c, lo, hi);
            prop_assert!(well_formed(&all));
            prop_assert!(all.iter().all(|&r| lo <= r && r < hi));
            prop_assert_eq!(m.first_root(&c, lo, hi), all.first());
            prop_assert!(well_formed(&m.real_roots(&c)));
        }
    }
}

/// Found by the contact property test: the one positive root of a deflated
/// contact cubic on `[0, 10)`. Bisection steps far from the root once
/// looked like a stall in rounding noise and a non-root (where p = -12.9)
/// came back.
#[test]
fn roots_in_a_finite_interval_never_returns_a_point_where_bisection_paused() {
    let c = [
        0.0,
        -8.681208096070977,
        -0.09135777362785058,
        -1.1602515661065396,
        0.3134908614437712,
    ];
    let exact = reference_roots(&c);
    let got = Production.roots_in(&c, 0.0, 10.0);
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(got[0], 0.0);
    assert!(
        set_distance_ulps(&got[1..], &exact[1..]) <= 2,
        "{got:?} vs {exact:?}"
    );
}

/// Found by `arbitrary_input_never_panics`: a quartic with a huge leading
/// coefficient and a subnormal one, searched on `[-4.05, 0)`.
#[test]
fn a_huge_leading_coefficient_beside_a_subnormal_one_gives_well_formed_roots() {
    let c = [
        -381981.46306435304,
        0.0,
        1.831774374608786e-309,
        -369.762703204847,
        1.0000000000000005e294,
    ];
    let (lo, hi) = (-4.049888306990507, 0.0);
    for m in Method::ALL {
        let all = m.roots_in(&c, lo, hi);
        assert!(well_formed(&all), "{m:?}: {all:?}");
        assert!(all.iter().all(|&r| lo <= r && r < hi), "{m:?}: {all:?}");
        assert_eq!(m.first_root(&c, lo, hi), all.first(), "{m:?}");
        assert!(well_formed(&m.real_roots(&c)), "{m:?}");
    }
}
