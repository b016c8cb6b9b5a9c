//! The engine's default solver: exact root isolation by critical points
//! plus safeguarded high-order iteration, after Yuksel ("High-Performance
//! Polynomial Root Finding for Graphics", HPG 2022), with the accuracy of
//! compensated arithmetic (Graillat, Langlois & Louvet 2005) and cheap
//! certified shortcuts for the polynomials the engine mostly asks about.
//!
//! * Degree 1 is one division; degree 2 is the stable quadratic formula with
//!   the discriminant computed from error-free products (Kahan), so a double
//!   root or a near-tangency is classified from an almost exact `b^2 - 4ac`.
//! * Shortcuts (each one exact or certified by an error bound), cheapest
//!   first: a search from exactly `0` with `p(0) = 0` answers `first_root`
//!   at once; there, Descartes' rule of signs on the coefficients proves "no
//!   positive root" (no sign variation) or "exactly one" (one variation,
//!   solved directly). For quartics searched from `lo >= 0`, two
//!   division-free certificates prove "positive on `[0, inf)`": a split
//!   into two quadratics that are nonnegative there, and the square of the
//!   top terms plus a linear remainder (about ten flops each; between them
//!   they settle most separating contacts, including those whose roots are
//!   all in the past). Then a discriminant test with an a-priori rounding
//!   bound proves "no real root at all". `first_root` returns a shortcut's
//!   answer directly, without building the result array. Every shortcut
//!   and the walk take the same steps for `first_root` as for `roots_in`
//!   (the walk just stops at the first root), so `first_root` is bit for
//!   bit `roots_in(..).first()` (property-tested in `first_root_props.rs`).
//! * Otherwise the critical points (roots of `p'`) split the search interval
//!   into pieces on which `p` is monotone; a piece holds a root iff its ends
//!   have opposite signs. A quartic's critical points are the roots of the
//!   cubic `p'`, isolated by the closed-form roots of the quadratic `p''`
//!   (or, from `0`, by Descartes' rule on `p'`). The walk is lazy: pieces are
//!   visited left to right, a critical point is only located as well as the
//!   walk needs (Newton on `p'` stops as soon as `p` there has the sign that
//!   proves a crossing), and `first_root` stops at the first crossing.
//! * Signs at piece ends come from plain Horner when its running error bound
//!   allows, else compensated Horner; a critical value that even the
//!   compensated bound cannot separate from zero is a touching (double)
//!   root, reported once and placed where the compensated `p'` vanishes.
//! * Inside a piece: Halley's method (cubic convergence) from the root of the
//!   quadratic Taylor model at the end nearer the root, kept inside the
//!   bracket with Newton and bisection fallbacks (bisection also after four
//!   steps in a row that fail to halve, a crawl away from a flat start such
//!   as `p'(0) = 0` in `x^4 - 11x^2 - 46`); then the compensated polish:
//!   Newton/secant corrections with residuals from compensated Horner (exact
//!   expansion arithmetic when even that cannot decide), accepted when the
//!   certified sign changes between neighbouring floats or the correction is
//!   below an ulp. Results are within an ulp or two of the exact roots of
//!   the `f64` polynomial, clustered roots included.
//! * Unbounded searches are closed with a Fujiwara bound, whose end signs are
//!   known without evaluating. Extreme coefficients are rescaled by a power
//!   of two, and when evaluation near the roots could overflow, the roots
//!   with `|x| >= 1` are found as reciprocals of the roots of the reversed
//!   polynomial (so roots up to about `1e300` are handled; only the
//!   underflow of sums like `sum |a_k|` is out of range).
//! * Where the processor has the fused multiply-add, everything past the
//!   shortcuts runs compiled for it (chosen at run time): its error-free
//!   products take one instruction instead of Dekker's seventeen flops,
//!   and give the same bits (see `poly::Product`).
//! * No allocation: everything lives in fixed arrays on the stack.

use super::poly::{
    derivative, exponent_above, gamma, horner_bounded, horner_comp, horner_d, horner_exact,
    normalize, root_bound, split_point, Coeffs, Native, Product, U,
};
use super::{RootSolver, Roots};
use core::marker::PhantomData;

/// Certified shortcuts, lazy critical-point walk, safeguarded Halley and
/// compensated polishing (the engine's default).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Production;

impl RootSolver for Production {
    fn real_roots(&self, coeffs: &[f64]) -> Roots {
        solve(coeffs, f64::NEG_INFINITY, f64::INFINITY, false)
    }

    fn roots_in(&self, coeffs: &[f64], lo: f64, hi: f64) -> Roots {
        solve(coeffs, lo, hi, false)
    }

    /// As `solve`, but without the result array on the fast paths: a
    /// shortcut's answer comes back in registers. Inlined, so that a caller
    /// with constant bounds (the usual `0` and `inf`) gets the shortcuts
    /// specialised for them.
    #[inline]
    fn first_root(&self, coeffs: &[f64], lo: f64, hi: f64) -> Option<f64> {
        if !(lo < hi) {
            return None;
        }
        let (a, n) = normalize(coeffs)?;
        // The result array is only built where it is filled (zeroing it
        // up front was a store on every query), and the walk has one call.
        if n <= 2 {
            let mut out = Roots::new();
            low_degree(&a[..=n], lo, hi, &mut out);
            return out.first().filter(|&r| lo <= r && r < hi);
        }
        let single = match classify(&a, n, lo, true) {
            Path::NoRoot => return None,
            Path::Zero => return Some(0.0),
            Path::Deflate => return deflated(&a, n, lo, hi, true).first(),
            Path::Single => true,
            Path::General => false,
        };
        let mut out = Roots::new();
        general(&a, n, lo, hi, true, single, &mut out);
        out.first().filter(|&r| lo <= r && r < hi)
    }
}

#[inline]
fn solve(coeffs: &[f64], lo: f64, hi: f64, first: bool) -> Roots {
    let mut out = Roots::new();
    if !(lo < hi) {
        return out;
    }
    let Some((a, n)) = normalize(coeffs) else {
        return out;
    };
    match n {
        1 | 2 => low_degree(&a[..=n], lo, hi, &mut out),
        _ => match classify(&a, n, lo, first) {
            Path::NoRoot => {}
            Path::Zero => out.push(0.0),
            Path::Deflate => return deflated(&a, n, lo, hi, first),
            Path::Single => general(&a, n, lo, hi, first, true, &mut out),
            Path::General => general(&a, n, lo, hi, first, false, &mut out),
        },
    }
    // A root polished onto the excluded end (a huge leading coefficient
    // beside a subnormal one rounds a root of -8e-73 to `hi = 0`) is not
    // in the interval.
    if out.as_slice().last().is_some_and(|&r| r >= hi) {
        let kept: Vec<f64> = out.as_slice().iter().copied().filter(|&r| r < hi).collect();
        out = Roots::new();
        for r in kept {
            out.push(r);
        }
    }
    out
}

/// What the certified shortcuts make of a cubic or quartic search.
enum Path {
    /// No root in the search interval.
    NoRoot,
    /// `p(0) = 0` and a `first_root` search from exactly `0`: the answer.
    Zero,
    /// `p(0) = 0`: solve the exact deflation `p / x`.
    Deflate,
    /// A search from `0` with exactly one positive root (Descartes).
    Single,
    /// No shortcut applies: the critical-point walk.
    General,
}

/// The shortcuts in order of cost: the deflation test, Descartes' rule at
/// `0`, the half-line positivity certificate, the discriminant test.
#[inline(always)]
fn classify(a: &Coeffs, n: usize, lo: f64, first: bool) -> Path {
    if a[0] == 0.0 {
        return if first && lo == 0.0 {
            Path::Zero
        } else {
            Path::Deflate
        };
    }
    if lo == 0.0 {
        match descartes_at_zero(a, n) {
            Some(true) => return Path::NoRoot,
            Some(false) => return Path::Single,
            None => {}
        }
    }
    if n == 4
        && ((lo >= 0.0 && (positive_from_zero(a) || positive_by_square(a))) || no_real_roots(a))
    {
        return Path::NoRoot;
    }
    Path::General
}

/// The roots in `[lo, hi)` of a linear or quadratic `a` (closed form; the
/// quadratic's discriminant from error-free products).
#[inline]
fn low_degree(a: &[f64], lo: f64, hi: f64, out: &mut Roots) {
    let (k, r) = if a.len() == 2 {
        (1, [-a[0] / a[1] + 0.0, 0.0])
    } else {
        quadratic::<Native>(a[0], a[1], a[2])
    };
    for &x in &r[..k] {
        if lo <= x && x < hi {
            out.push(x);
        }
    }
}

/// `p(0) = 0`: `p = x q(x)` with `q`'s coefficients those of `p` shifted
/// down, an exact deflation. The roots are `0` and those of `q` (a root of
/// `q` at `0` too is the same, multiple, root and is reported once).
#[inline(never)]
fn deflated(a: &Coeffs, n: usize, lo: f64, hi: f64, first: bool) -> Roots {
    let zero_in = lo <= 0.0 && 0.0 < hi;
    let mut out = Roots::new();
    if first && zero_in && lo == 0.0 {
        out.push(0.0);
        return out;
    }
    let rest = solve(&a[1..=n], lo, hi, first);
    let mut zero_done = !zero_in;
    for &r in rest.as_slice() {
        if !zero_done && r >= 0.0 {
            out.push(0.0);
            zero_done = true;
            if first {
                return out;
            }
        }
        if r != 0.0 {
            out.push(r);
        }
    }
    if !zero_done {
        out.push(0.0);
    }
    if first {
        out.truncate(1);
    }
    out
}

/// Everything past the fast paths: root bound, range safety, and the
/// general walks (kept out of line so the fast paths stay small). Where the
/// processor has the fused multiply-add, the walk runs compiled for it
/// (see [`Product`]: the same bits, its error-free products in one
/// instruction instead of seventeen).
#[inline(never)]
fn general(a: &Coeffs, n: usize, lo: f64, hi: f64, first: bool, single: bool, out: &mut Roots) {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
    if std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the processor has the one feature `walk_fused` is
        // compiled for (checked just above).
        unsafe { walk_fused(a, n, lo, hi, first, single, out) };
        return;
    }
    walk::<Native>(a, n, lo, hi, first, single, out);
}

/// [`walk`] compiled for processors with the fused multiply-add.
#[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
#[target_feature(enable = "fma")]
fn walk_fused(a: &Coeffs, n: usize, lo: f64, hi: f64, first: bool, single: bool, out: &mut Roots) {
    walk::<super::poly::Fused>(a, n, lo, hi, first, single, out);
}

/// The body of [`general`], with error-free products formed by `P`.
#[inline(always)]
fn walk<P: Product>(
    a: &Coeffs,
    n: usize,
    lo: f64,
    hi: f64,
    first: bool,
    single: bool,
    out: &mut Roots,
) {
    let r = root_bound(a, n);
    let (a, extreme) = balanced(a, n, r);
    if extreme {
        split_at_unit_circle(&a, n, lo, hi, first, out);
    } else if single {
        if n == 3 {
            single_positive_root::<3, P>(&a, r, hi, out);
        } else {
            single_positive_root::<4, P>(&a, r, hi, out);
        }
    } else if n == 3 {
        cubic::<P>(&a, r, lo, hi, first, out);
    } else {
        quartic::<P>(&a, r, lo, hi, first, out);
    }
}

/// The coefficients scaled by a power of two (exactly; the roots do not
/// change) when their magnitudes are extreme, centring their exponent
/// range on zero so that derivative coefficients and the error-free
/// products of compensated evaluation (Dekker's split overflows above about
/// `2^996`) stay finite and away from underflow; and whether Horner
/// evaluation near the roots could still overflow (some term `a_k x^k`
/// with `|x|` up to the root bound `r` above about `2^900`).
#[inline(always)]
fn balanced(a: &Coeffs, n: usize, r: f64) -> (Coeffs, bool) {
    let er = exponent_above(r);
    let (mut hi, mut lo, mut worst) = (i32::MIN, i32::MAX, i32::MIN);
    for (k, &c) in a.iter().enumerate().take(n + 1) {
        if c != 0.0 {
            let e = exponent_above(c.abs());
            hi = hi.max(e);
            lo = lo.min(e);
            worst = worst.max(e + k as i32 * er);
        }
    }
    if hi <= 600 && lo >= -600 {
        return (*a, worst > 900);
    }
    let shift = (hi + lo) / 2;
    let s = super::poly::pow2(-shift);
    let mut b = *a;
    for c in b.iter_mut() {
        *c *= s;
    }
    (b, worst - shift > 900)
}

/// Roots of a polynomial whose roots are so large that evaluating it near
/// them would overflow: the roots inside the unit interval are found
/// directly (there `|p(x)| <= sum |a_k|`), those with `|x| >= 1` as the
/// reciprocals of the roots in `[-1, 1]` of the reversed polynomial
/// `x^n p(1/x)` (same coefficients, reversed), whose values there are
/// bounded the same way. The reciprocal costs at most half an ulp more.
#[cold]
#[inline(never)]
fn split_at_unit_circle(a: &Coeffs, n: usize, lo: f64, hi: f64, first: bool, out: &mut Roots) {
    let mut all = Roots::new();
    let inner = solve_bounded(a, n, lo.max(-1.0), hi.min(1.0));
    for &x in inner.as_slice() {
        if x > -1.0 {
            all.push(x);
        }
    }
    let mut rev = [0.0; 5];
    for k in 0..=n {
        rev[k] = a[n - k];
    }
    if let Some((q, m)) = normalize(&rev[..=n]) {
        let (q, _) = balanced(&q, m, 1.0);
        let outer = solve_bounded(&q, m, -1.0, f64::from_bits(1.0f64.to_bits() + 1));
        for &y in outer.as_slice() {
            let x = 1.0 / y;
            if y != 0.0 && x.abs() >= 1.0 && lo <= x && x < hi {
                all.push(x);
            }
        }
    }
    all.sort();
    for &x in all.as_slice() {
        out.push(x);
        if first {
            return;
        }
    }
}

/// The general solver on `[lo, hi)` without the overflow split (used on
/// the two halves of [`split_at_unit_circle`], where evaluation is safe).
fn solve_bounded(a: &Coeffs, n: usize, lo: f64, hi: f64) -> Roots {
    let mut out = Roots::new();
    if !(lo < hi) {
        return out;
    }
    match n {
        1 | 2 => low_degree(&a[..=n], lo, hi, &mut out),
        3 => cubic::<Native>(a, root_bound(a, 3), lo, hi, false, &mut out),
        _ => quartic::<Native>(a, root_bound(a, 4), lo, hi, false, &mut out),
    }
    out
}

/// Fast paths for a search starting at exactly `0` (the engine's usual
/// query; `p(0) != 0` here), where the coefficients themselves are the
/// Taylor coefficients: by Descartes' rule of signs no sign variation means
/// no positive root and one variation means exactly one (simple) positive
/// root, which can be solved on its own without locating critical points.
/// Returns `Some(true)` for "no positive root", `Some(false)` for "exactly
/// one", `None` when the rule does not decide.
#[inline(always)]
fn descartes_at_zero(a: &Coeffs, n: usize) -> Option<bool> {
    match sign_variations(a, n) {
        0 => Some(true),
        1 => Some(false),
        _ => None,
    }
}

/// The sign variations of `a[0..=n]`, zeros skipped, read from a table
/// ([`VARIATIONS`]) indexed by which coefficients are negative and which
/// are non-zero: no branch on any sign (they are as good as random in a
/// batch of queries, and mispredicted branches were a tenth of the time of
/// the whole shortcut path), and no chain of comparisons from one
/// coefficient to the next (a select per coefficient carrying the last
/// non-zero sign was the largest spot of the shortcut path). The
/// coefficients above degree `n` are zero (see [`normalize`]), so all five
/// are read; a zero of either sign counts as zero.
#[inline(always)]
fn sign_variations(a: &Coeffs, n: usize) -> u32 {
    debug_assert!(a[n + 1..].iter().all(|&c| c == 0.0));
    let mut index = 0;
    for (i, &c) in a.iter().enumerate() {
        let bits = c.to_bits();
        index |= ((bits >> 63) as usize) << i;
        index |= usize::from(bits << 1 != 0) << (i + 5);
    }
    u32::from(VARIATIONS[index & 1023])
}

/// [`sign_variations`] for every pattern of five coefficients: bit `i` of
/// the index says that coefficient `i` is negative, bit `i + 5` that it is
/// non-zero (the sign of a zero is ignored).
static VARIATIONS: [u8; 1024] = variations_table();

const fn variations_table() -> [u8; 1024] {
    let mut table = [0; 1024];
    let mut index = 0;
    while index < 1024 {
        let (mut count, mut last_neg, mut seen) = (0, false, false);
        let mut i = 0;
        while i < 5 {
            if (index >> (i + 5)) & 1 == 1 {
                let neg = (index >> i) & 1 == 1;
                if seen && neg != last_neg {
                    count += 1;
                }
                (last_neg, seen) = (neg, true);
            }
            i += 1;
        }
        table[index] = count;
        index += 1;
    }
    table
}

/// True when the quartic is certainly positive on `[0, inf)`, by the
/// certificate `p = (a0 + a1 x + s x^2) + x^2 ((a2 - s) + a3 x + a4 x^2)`
/// with both quadratics nonnegative for `x >= 0`: with `a0, a4 > 0` some
/// split `s` works iff `4 a0 a4 a2 > a4 min(a1, 0)^2 + a0 min(a3, 0)^2`.
/// About ten flops, no division: it settles most separating contacts (whose
/// Taylor coefficients at the start are mostly positive, with a negative
/// `a1` or `a3` when approaching) before the discriminant test. Certified:
/// the sides carry at most three roundings each, the margin covers them,
/// and the absolute term covers underflow in the right side (the left side
/// is kept clear of it by `t` being normal and `l` large).
#[inline(always)]
fn positive_from_zero(q: &Coeffs) -> bool {
    let (a0, a1, a2, a3, a4) = (q[0], q[1], q[2], q[3], q[4]);
    let (n1, n3) = (a1.min(0.0), a3.min(0.0));
    let t = 4.0 * a0 * a4;
    let l = t * a2;
    let r = a4 * n1 * n1 + a0 * n3 * n3;
    a0 > 0.0
        && a4 > 0.0
        && t >= f64::MIN_POSITIVE
        && l < f64::INFINITY
        && l > r * (1.0 + gamma(8)) + TINY_SUM
}

/// Absolute slack for the half-line certificates: far above what underflow
/// in their products can lose (under `2^-1020`), far below any real value.
const TINY_SUM: f64 = 1e-300;

/// True when the quartic is certainly positive on `[0, inf)`, by completing
/// the square of its top terms: `p = a4 (x^2 + u x + v)^2 + r1 x + r0` with
/// `u = a3 / (2 a4)` and `v` chosen to leave a linear remainder, which is
/// positive for `x >= 0` when `r0 > 0` and `r1 >= 0`. (For a contact this
/// splits the motion along the relative acceleration from the motion
/// across it.) Without divisions, with `w = 4 a2 a4 - a3^2 = 8 a4^2 v`:
/// `r0 > 0` iff `64 a0 a4^3 > w^2`, and `r1 >= 0` iff `8 a1 a4^2 >= a3 w`.
/// It catches most of what [`positive_from_zero`] leaves (a negative or
/// small `a2`), for about fifteen flops. Certified: `w` carries the error
/// bound `ew` into both tests, `a4` is kept in a range where its powers
/// are exact to a rounding, and the absolute slack covers underflow.
#[inline(always)]
fn positive_by_square(q: &Coeffs) -> bool {
    let (a0, a1, a2, a3, a4) = (q[0], q[1], q[2], q[3], q[4]);
    let a4s = a4 * a4;
    let (p, s) = (4.0 * a2 * a4, a3 * a3);
    let w = p - s;
    let ew = gamma(4) * (p.abs() + s) + TINY_SUM;
    let wa = w.abs() + ew;
    let l1 = 64.0 * a4s * a4 * a0;
    let l2 = 8.0 * a4s * a1;
    let t = a3 * w;
    let e2 = a3.abs() * ew + gamma(4) * (l2.abs() + t.abs()) + TINY_SUM;
    a0 > 0.0
        && (A4_MIN..=A4_MAX).contains(&a4)
        && (L1_MIN..f64::INFINITY).contains(&l1)
        && l1 > wa * wa * (1.0 + gamma(8))
        && l2 - t > e2 * (1.0 + gamma(4))
}

/// The range of `a4` where [`positive_by_square`] applies: `a4^3` is a
/// normal number. `l1` above `L1_MIN` is normal too, so its one rounding
/// that could underflow does not.
const A4_MIN: f64 = f64::from_bits((1023 - 300) << 52); // 2^-300
const A4_MAX: f64 = f64::from_bits((1023 + 300) << 52); // 2^300
const L1_MIN: f64 = f64::from_bits((1023 - 900) << 52); // 2^-900

/// True when the quartic certainly has no real root: its discriminant is
/// positive and `P = 8ac - 3b^2` or `D = 64a^3e - 16a^2c^2 + 16ab^2c -
/// 16a^2bd - 3b^4` is positive (two pairs of complex conjugate roots), every
/// sign certified by an a-priori rounding-error bound on the monomial sums.
/// About 80 flops and no division: it settles most separating contacts
/// without locating a single critical point. Inconclusive (false) near
/// degenerate cases and when the degree-6 products over- or underflow.
#[inline(always)]
fn no_real_roots(q: &Coeffs) -> bool {
    let (a, b, c, d, e) = (q[4], q[3], q[2], q[1], q[0]);
    let (b2, c2, d2) = (b * b, c * c, d * d);
    let ae = a * e;
    let ac = a * c;
    // P first, D only when P does not decide: one of them must be
    // certainly positive before the discriminant is worth computing.
    let p1 = 8.0 * ac;
    let p2 = 3.0 * b2;
    let p_pos = p1 - p2 > gamma(4) * (p1.abs() + p2) * (1.0 + 4.0 * U);
    let a2 = a * a;
    if !p_pos {
        let dt = [
            64.0 * a2 * ae,
            -16.0 * a2 * c2,
            16.0 * ac * b2,
            -16.0 * a2 * b * d,
            -3.0 * b2 * b2,
        ];
        let dd = dt[0] + dt[1] + dt[2] + dt[3] + dt[4];
        let ds = dt[0].abs() + dt[1].abs() + dt[2].abs() + dt[3].abs() + dt[4].abs();
        if !(dd > gamma(10) * ds * (1.0 + 8.0 * U)) {
            return false;
        }
    }
    // The discriminant grouped by powers of e (Horner in e). A quartic with
    // two real roots (the usual case that gets here) fails on its sign;
    // otherwise the same expression on absolute values with every sign
    // positive, which is the sum of the magnitudes of its 16 monomials,
    // bounds its rounding error: below gamma(k) times that, k the longest
    // chain of roundings (Higham, Accuracy and Stability, 3.1). The two
    // are formed at once in the lanes of a [`Pair`] (lane 0 signed, lane 1
    // magnitudes: one packed instruction per operation instead of two
    // chains). Each lane does exactly the operations of its scalar
    // expression (`x - k y` is `x + (-k) y` to the bit), so the decision
    // is that of the scalar code.
    let bd = b * d;
    let (ta, tac, tbd, tc, te) = (
        Pair::new(a, a.abs()),
        Pair::new(ac, ac.abs()),
        Pair::new(bd, bd.abs()),
        Pair::new(c, c.abs()),
        Pair::new(e, e.abs()),
    );
    let k = |signed: f64| Pair::new(signed, -signed);
    let s = |x: f64| Pair::new(x, x);
    let m3 = s(256.0 * a2) * ta;
    let m2 = ta * (ta * (k(-192.0) * tbd + k(-128.0) * s(c2)) + s(144.0 * b2) * tc)
        + k(-27.0 * b2) * s(b2);
    let m1 = ta
        * (s(d2) * (s(144.0) * tac + k(-6.0) * s(b2)) + s(c2) * (s(16.0 * c2) + k(-80.0) * tbd))
        + s(b2) * tc * (s(18.0) * tbd + k(-4.0) * s(c2));
    let m0 = s(d2)
        * (tac * (s(18.0) * tbd + k(-4.0) * s(c2))
            + k(-27.0 * a2) * s(d2)
            + s(b2) * (s(c2) + k(-4.0) * tbd));
    let (disc, mag) = (((m3 * te + m2) * te + m1) * te + m0).lanes();
    disc > 0.0 && disc > gamma(24) * mag * (1.0 + 32.0 * U) && mag < f64::INFINITY && mag > 1e-250
}

/// Two `f64` lanes computed side by side (see [`no_real_roots`]): one
/// packed SSE2 register on x86-64 (the compiler left the two chains scalar
/// when written as a pair of numbers), a pair of numbers elsewhere. Either
/// way each lane is rounded as its own scalar operation would be.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Pair(core::arch::x86_64::__m128d);

#[cfg(target_arch = "x86_64")]
impl Pair {
    #[inline(always)]
    fn new(lane0: f64, lane1: f64) -> Pair {
        // SAFETY: SSE2 is part of every x86-64 processor (the target's
        // baseline), and the intrinsic only computes on registers.
        Pair(unsafe { core::arch::x86_64::_mm_set_pd(lane1, lane0) })
    }

    #[inline(always)]
    fn lanes(self) -> (f64, f64) {
        use core::arch::x86_64::{_mm_cvtsd_f64, _mm_unpackhi_pd};
        // SAFETY: as in `new`.
        unsafe {
            (
                _mm_cvtsd_f64(self.0),
                _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)),
            )
        }
    }
}

#[cfg(target_arch = "x86_64")]
impl core::ops::Add for Pair {
    type Output = Pair;
    #[inline(always)]
    fn add(self, o: Pair) -> Pair {
        // SAFETY: as in `Pair::new`.
        Pair(unsafe { core::arch::x86_64::_mm_add_pd(self.0, o.0) })
    }
}

#[cfg(target_arch = "x86_64")]
impl core::ops::Mul for Pair {
    type Output = Pair;
    #[inline(always)]
    fn mul(self, o: Pair) -> Pair {
        // SAFETY: as in `Pair::new`.
        Pair(unsafe { core::arch::x86_64::_mm_mul_pd(self.0, o.0) })
    }
}

#[cfg(not(target_arch = "x86_64"))]
#[derive(Clone, Copy)]
struct Pair(f64, f64);

#[cfg(not(target_arch = "x86_64"))]
impl Pair {
    #[inline(always)]
    fn new(lane0: f64, lane1: f64) -> Pair {
        Pair(lane0, lane1)
    }

    #[inline(always)]
    fn lanes(self) -> (f64, f64) {
        (self.0, self.1)
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl core::ops::Add for Pair {
    type Output = Pair;
    #[inline(always)]
    fn add(self, o: Pair) -> Pair {
        Pair(self.0 + o.0, self.1 + o.1)
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl core::ops::Mul for Pair {
    type Output = Pair;
    #[inline(always)]
    fn mul(self, o: Pair) -> Pair {
        Pair(self.0 * o.0, self.1 * o.1)
    }
}

/// The one positive root of `p` (Descartes: one sign variation), if below
/// `hi`; `r` bounds the roots.
#[inline(always)]
fn single_positive_root<const N: usize, P: Product>(a: &Coeffs, r: f64, hi: f64, out: &mut Roots) {
    let f0 = a[0];
    let (h, fh) = if hi >= r {
        (r, f64::MAX.copysign(a[N]))
    } else {
        (hi, signed_value::<N, P>(a, hi))
    };
    if fh == 0.0 || (fh < 0.0) == (f0 < 0.0) {
        // p(hi) = 0 (excluded) or the root lies beyond hi.
        return;
    }
    // The Newton point from 0 as the start, kept in the bracket (0, h).
    let mut start = -a[0] / a[1];
    if !(start > 0.0 && start < h) {
        start = split_point(0.0, h);
    }
    let (x, d) = halley::<N>(a, 0.0, h, f0, start, ROOT_TOL);
    out.push(polish::<N, P>(a, x, 0.0, h, f0, d));
}

/// Real roots of `c2 x^2 + c1 x + c0` (`c2 != 0`), ascending, a double root
/// once. The discriminant is formed from error-free products, so its sign
/// is right unless it is below the rounding level of its own error terms.
#[inline(always)]
pub(super) fn quadratic<P: Product>(c0: f64, c1: f64, c2: f64) -> (usize, [f64; 2]) {
    let (bb, ebb) = P::two_prod(c1, c1);
    let (ac, eac) = P::two_prod(4.0 * c2, c0);
    let d = (bb - ac) + (ebb - eac);
    if !(d >= 0.0) {
        // Negative, or NaN from overflow of the products.
        if d.is_nan() {
            return quadratic_scaled(c0, c1, c2);
        }
        return (0, [0.0; 2]);
    }
    if d == 0.0 {
        return (1, [-c1 / (2.0 * c2) + 0.0, 0.0]);
    }
    let q = -0.5 * (c1 + d.sqrt().copysign(c1));
    let (r1, r2) = (q / c2, c0 / q);
    if !(r1.is_finite() && r2.is_finite()) {
        return quadratic_scaled(c0, c1, c2);
    }
    let (r1, r2) = (r1 + 0.0, r2 + 0.0);
    if r1 <= r2 {
        (2, [r1, r2])
    } else {
        (2, [r2, r1])
    }
}

/// The quadratic formula on coefficients rescaled by a power of two (exact)
/// when the direct form overflows.
#[cold]
fn quadratic_scaled(c0: f64, c1: f64, c2: f64) -> (usize, [f64; 2]) {
    let m = c0.abs().max(c1.abs()).max(c2.abs());
    if !(m.is_finite() && m > 0.0) || (0.25..=4.0).contains(&m) {
        // Already balanced: give up quietly (only reachable with extreme
        // coefficient ratios).
        return (0, [0.0; 2]);
    }
    let s = super::poly::pow2(-(m.log2().round() as i32));
    quadratic::<Native>(c0 * s, c1 * s, c2 * s)
}

/// The value of `p(x)` when its sign can be trusted: plain Horner when its
/// error bound allows, compensated Horner otherwise, and `0.0` when even the
/// compensated value cannot be told apart from zero.
#[inline(always)]
fn signed_value<const N: usize, P: Product>(p: &Coeffs, x: f64) -> f64 {
    let (v, e) = horner_bounded::<N>(p, x);
    if v.abs() > e || !v.is_finite() {
        return v;
    }
    let (v, e) = horner_comp::<N, P>(p, x);
    if v.abs() > e {
        v
    } else {
        0.0
    }
}

/// `p(x)`, `p'(x)` and `p''(x) / 2` of a degree-`N` polynomial (the
/// quadratic Taylor model at `x`).
#[inline(always)]
fn taylor2<const N: usize>(p: &Coeffs, x: f64) -> (f64, f64, f64) {
    let mut v = p[N];
    let mut d = 0.0;
    let mut h = 0.0;
    let mut i = N;
    while i > 0 {
        i -= 1;
        h = h * x + d;
        d = d * x + v;
        v = v * x + p[i];
    }
    (v, d, h)
}

/// Halley iterations (cubic convergence: `x - f f' / (f'^2 - f f''/2)`),
/// kept inside the bracket `(a, b)` that holds the only root of `p` there:
/// a step leaving the bracket falls back to Newton, then to bisection
/// (arithmetic first, in the floating-point sense after repeated failures,
/// so any finite bracket is exhausted in about 64 more steps). `fa` is
/// `p(a)` (only its sign is used). Stops when a step is below `tol * |x|`
/// (returning the stepped point) or when `|p|` stops shrinking (rounding
/// noise next to a cluster: the compensated polish takes over). Returns the
/// point and `p'` near it.
#[inline(always)]
fn halley<const N: usize>(
    p: &Coeffs,
    mut a: f64,
    mut b: f64,
    fa: f64,
    x0: f64,
    tol: f64,
) -> (f64, f64) {
    let neg_a = fa < 0.0;
    let mut x = x0;
    let mut d = 0.0;
    let mut last = f64::INFINITY;
    let mut stalls = 0;
    let mut fallbacks = 0;
    let mut last_step = f64::INFINITY;
    let mut crawl = 0;
    for _ in 0..128 {
        let (f, df, h2) = taylor2::<N>(p, x);
        d = df;
        if f == 0.0 {
            return (x, d);
        }
        if (f < 0.0) == neg_a {
            a = x;
        } else {
            b = x;
        }
        if f.abs() > 0.5 * last {
            stalls += 1;
            // Stop only in rounding noise (|p| within a few times the
            // error bound of its Horner evaluation): slow progress far from
            // the root is bisection at work, and the walk must go on.
            if stalls >= 3 {
                let mag = (0..=N).rev().fold(0.0, |m, k| m * x.abs() + p[k].abs());
                if f.abs() <= 8.0 * gamma(2 * N) * mag {
                    return (x, d);
                }
                stalls = 0;
            }
        }
        last = f.abs();
        let denom = df * df - f * h2;
        let mut step = f * df / denom;
        let mut xn = x - step;
        if xn == x && df != 0.0 {
            // The step is below half an ulp: converged. (With `df = 0` the
            // step is zero at a flat point, not at the root: bisect.)
            return (x, d);
        }
        if !(xn > a && xn < b) {
            step = f / df;
            xn = x - step;
        }
        // A step not below half the one before does not converge: after
        // four in a row (a crawl, e.g. from next to a flat `p' = 0` where
        // each step only triples the distance from it) bisect instead.
        crawl = if step.abs() > 0.5 * last_step {
            crawl + 1
        } else {
            0
        };
        last_step = step.abs();
        if xn > a && xn < b && crawl < 4 {
            fallbacks = 0;
            x = xn;
            if step.abs() <= tol * xn.abs() {
                return (x, d);
            }
        } else {
            crawl = 0;
            fallbacks += 1;
            let m = if fallbacks < 4 {
                a + 0.5 * (b - a)
            } else {
                split_point(a, b)
            };
            if !(m > a && m < b) {
                return (x, d);
            }
            x = m;
        }
    }
    (x, d)
}

/// `p(x)` with a sign that can be trusted, and a bound on its error:
/// compensated Horner, or exact evaluation (error below an ulp of the
/// value) when the compensated bound cannot decide.
#[inline(always)]
fn certain_value<const N: usize, P: Product>(p: &Coeffs, x: f64) -> (f64, f64) {
    let (v, e) = horner_comp::<N, P>(p, x);
    if v.abs() > e {
        (v, e)
    } else {
        let v = horner_exact::<N, Native>(p, x);
        (v, v.abs() * f64::EPSILON)
    }
}

/// Final polishing of a root of `p` near `x` inside the bracket `(a, b)`
/// (`fa` = `p(a)`), which stays certified because every sign comes from
/// [`certain_value`]. Newton corrections with that residual, then secant
/// corrections through the last two certified values (plain derivatives are
/// poor next to clusters), until the sign changes between two iterates at
/// most an ulp or two apart or the correction vanishes. When the iterates
/// creep towards the root from one side (as next to a cluster), each
/// further correction is doubled until one overshoots and brackets the root
/// tightly. `d` estimates `p'` near the root.
#[inline(always)]
fn polish<const N: usize, P: Product>(p: &Coeffs, x: f64, a: f64, b: f64, fa: f64, d: f64) -> f64 {
    let value = Value::<N, P> {
        p,
        product: PhantomData,
    };
    polish_with(&value, x, a, b, fa, d)
}

/// A function whose value at a point comes with a sign that can be trusted
/// and a bound on its error (as [`certain_value`]; a value of exactly `0.0`
/// means "at the root within what it can tell"): what [`polish_with`]
/// refines a root of. A trait with an always-inlined method rather than a
/// closure, so that the evaluation is compiled into the walk that calls
/// it, with the walk's instructions (see [`general`]); a closure the
/// compiler kept out of line took its fused multiply-adds as library calls.
trait Certain {
    fn at(&self, x: f64) -> (f64, f64);
}

/// `p` by [`certain_value`].
struct Value<'a, const N: usize, P> {
    p: &'a Coeffs,
    product: PhantomData<P>,
}

impl<const N: usize, P: Product> Certain for Value<'_, N, P> {
    #[inline(always)]
    fn at(&self, x: f64) -> (f64, f64) {
        certain_value::<N, P>(self.p, x)
    }
}

/// The derivative `d` of the quartic `p` by [`certain_slope`].
struct Slope<'a> {
    p: &'a Coeffs,
    d: &'a Coeffs,
}

impl Certain for Slope<'_> {
    #[inline(always)]
    fn at(&self, x: f64) -> (f64, f64) {
        certain_slope::<Native>(self.p, self.d, x)
    }
}

/// [`polish`] for any [`Certain`] function `value`: its root in `(a, b)`,
/// where `fa` is its value at `a` and `d` estimates its derivative near
/// the root.
#[inline(always)]
fn polish_with(value: &impl Certain, x: f64, mut a: f64, mut b: f64, fa: f64, d: f64) -> f64 {
    let neg_a = fa < 0.0;
    let mut x = x;
    let mut d = d;
    let (mut v, mut e) = value.at(x);
    let mut mult = 1.0;
    for _ in 0..100 {
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == neg_a {
            a = x;
        } else {
            b = x;
        }
        let correction = v / d;
        if mult == 1.0 {
            let xn = x - correction;
            if xn == x {
                // The correction is below half an ulp.
                return x;
            }
            if v.abs() > 16.0 * e
                && (xn - x).abs() <= 2.0 * f64::EPSILON * xn.abs()
                && xn > a
                && xn < b
            {
                // A correction of an ulp or two from a residual known to
                // better than 1/16: even with `d` off by half, the corrected
                // point is within about an ulp of the root, so no second
                // evaluation.
                return xn;
            }
        }
        let mut xn = x - mult * correction;
        if !(xn > a && xn < b) {
            // Out of the certified bracket: go halfway to its far side.
            let end = if xn <= a { a } else { b };
            xn = x + 0.5 * (end - x);
            if !(xn > a && xn < b) {
                // The bracket is as tight as the format allows, or the
                // correction points out at the end that `x` now is. A small
                // one is rounding at the root: `x` is it. A large one comes
                // from a derivative estimate of the wrong sign (a flat
                // point next to a cluster): go halfway to the other end.
                let other = if end == a { b } else { a };
                xn = x + 0.5 * (other - x);
                if (mult * correction).abs() <= 4.0 * f64::EPSILON * x.abs() || !(xn > a && xn < b)
                {
                    return x;
                }
            }
        }
        let (vn, en) = value.at(xn);
        let slope = (vn - v) / (xn - x);
        if slope.is_finite() && slope != 0.0 && (slope < 0.0) == (d < 0.0) {
            d = slope;
        }
        if (vn < 0.0) != (v < 0.0) || vn == 0.0 {
            if (xn - x).abs() <= 2.0 * f64::EPSILON * xn.abs() || vn == 0.0 {
                return if vn.abs() <= v.abs() { xn } else { x };
            }
            mult = 1.0;
        } else {
            mult *= 2.0;
        }
        x = xn;
        v = vn;
        e = en;
    }
    // Out of iterations (secant steps that creep from one side towards a
    // root with a flat neighbour): the certified bracket is still right.
    bisect_bracket(value, a, b, neg_a, x)
}

/// The root of `value` (as in [`polish_with`]) in the certified bracket
/// `(a, b)` whose left end has the sign `neg_a`, by bisection down to
/// neighbouring floats: at most about 64 steps from any finite bracket.
/// Falls back to `x` when the bracket is not finite.
#[cold]
#[inline(never)]
fn bisect_bracket(value: &impl Certain, mut a: f64, mut b: f64, neg_a: bool, x: f64) -> f64 {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return x;
    }
    let (mut va, mut vb) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..200 {
        let m = split_point(a, b);
        if !(m > a && m < b) {
            break;
        }
        let v = value.at(m).0;
        if v == 0.0 {
            return m;
        }
        if (v < 0.0) == neg_a {
            a = m;
            va = v.abs();
        } else {
            b = m;
            vb = v.abs();
        }
    }
    if va <= vb {
        a
    } else {
        b
    }
}

/// Relative step below which Halley hands over (the error after such a step
/// is of order its cube): for the roots themselves the compensated polish
/// does the last correction; critical points only need a few ulps.
const ROOT_TOL: f64 = 1e-6;
const CRIT_TOL: f64 = 1e-9;

/// A starting point for iteration in `(x0, x1)` where `p(x0) = f0` and
/// `p(x1) = f1` have opposite signs: the root of the quadratic Taylor model
/// at the end nearer the root by `|p|`, which is exact to second order and
/// excellent next to an extremum (where `p'` vanishes and Newton alone would
/// crawl); the secant point when the model has no root inside. `model1`
/// may carry `p'(x1)` and `p''(x1) / 2` when the caller already has them.
#[inline(always)]
fn start_point<const N: usize>(
    p: &Coeffs,
    (x0, f0): (f64, f64),
    (x1, f1): (f64, f64),
    model1: Option<(f64, f64)>,
) -> f64 {
    let right = f1.abs() <= f0.abs();
    let (c, f) = if right { (x1, f1) } else { (x0, f0) };
    if f.is_finite() {
        let (d1, h2) = match model1 {
            Some(m) if right => m,
            _ => {
                let (_, d1, h2) = taylor2::<N>(p, c);
                (d1, h2)
            }
        };
        // Roots of h2 t^2 + d1 t + f = 0, the small one first (stable form).
        let disc = d1 * d1 - 4.0 * h2 * f;
        if disc >= 0.0 {
            let q = -0.5 * (d1 + disc.sqrt().copysign(d1));
            let small = f / q;
            let guess = c + small;
            if guess > x0 && guess < x1 {
                return guess;
            }
            let guess = c + q / h2;
            if guess > x0 && guess < x1 {
                return guess;
            }
        }
    }
    let s = x0 - f0 * ((x1 - x0) / (f1 - f0));
    if s > x0 && s < x1 {
        s
    } else {
        split_point(x0, x1)
    }
}

/// Walks the monotone pieces of a degree-`N` polynomial left to right.
struct Walker<'a, const N: usize, P: Product> {
    p: &'a Coeffs,
    /// Left end of the current piece and `p` there (`0.0`: a root, already
    /// reported).
    x: f64,
    f: f64,
    first: bool,
    out: &'a mut Roots,
    product: PhantomData<P>,
}

impl<'a, const N: usize, P: Product> Walker<'a, N, P> {
    /// Starts at `lo` (`p(lo) = f`); reports `lo` if it is a root. Returns
    /// `None` when that already answers a `first_root` query.
    #[inline(always)]
    fn start(p: &'a Coeffs, lo: f64, f: f64, first: bool, out: &'a mut Roots) -> Option<Self> {
        if f == 0.0 {
            out.push(lo);
            if first {
                return None;
            }
        }
        Some(Walker {
            p,
            x: lo,
            f,
            first,
            out,
            product: PhantomData,
        })
    }

    /// Advances to the breakpoint `c` (> current end) where `p(c) = fc`,
    /// solving the piece in between if it holds a root. Returns true when a
    /// `first_root` query is answered.
    #[inline(always)]
    fn advance(&mut self, c: f64, fc: f64) -> bool {
        self.advance_with(c, fc, None)
    }

    /// [`Walker::advance`] when `p'(c)` and `p''(c) / 2` are already known.
    #[inline(always)]
    fn advance_with(&mut self, c: f64, fc: f64, model: Option<(f64, f64)>) -> bool {
        if fc == 0.0 {
            self.out.push(c);
            if self.first {
                return true;
            }
        } else if self.f != 0.0 && (self.f < 0.0) != (fc < 0.0) {
            let start = start_point::<N>(self.p, (self.x, self.f), (c, fc), model);
            let (x, d) = halley::<N>(self.p, self.x, c, self.f, start, ROOT_TOL);
            let r = polish::<N, P>(self.p, x, self.x, c, self.f, d);
            self.out.push(r);
            if self.first {
                return true;
            }
        }
        self.x = c;
        self.f = fc;
        false
    }

    /// Visits the critical point `c`.
    #[inline(always)]
    fn visit(&mut self, c: f64) -> bool {
        if !(c > self.x) {
            return false;
        }
        let fc = signed_value::<N, P>(self.p, c);
        self.advance(c, fc)
    }

    /// Closes the walk at `hi` (exclusive) where `p(hi) = fh`.
    #[inline(always)]
    fn finish(&mut self, hi: f64, fh: f64) {
        if fh != 0.0 && hi > self.x {
            self.advance(hi, fh);
        }
    }
}

/// Effective search interval: `[lo, hi)` clipped to the root bound, with
/// `p` at both ends (the sign at a bound end is known: no evaluation).
#[inline(always)]
fn search_interval<const N: usize, P: Product>(
    a: &Coeffs,
    r: f64,
    lo: f64,
    hi: f64,
) -> Option<(f64, f64, f64, f64)> {
    let lead = a[N];
    // Beyond the bound only the sign matters: the largest magnitude of that
    // sign also tells `start_point` to model the function at the other end.
    let (l, fl) = if lo <= -r {
        let s = if N & 1 == 0 { lead } else { -lead };
        (-r, f64::MAX.copysign(s))
    } else if lo == 0.0 {
        (lo, a[0])
    } else {
        (lo, signed_value::<N, P>(a, lo))
    };
    let (h, fh) = if hi >= r {
        (r, f64::MAX.copysign(lead))
    } else {
        (hi, signed_value::<N, P>(a, hi))
    };
    if l < h {
        Some((l, fl, h, fh))
    } else {
        None
    }
}

#[inline(always)]
fn cubic<P: Product>(a: &Coeffs, r: f64, lo: f64, hi: f64, first: bool, out: &mut Roots) {
    let Some((l, fl, h, fh)) = search_interval::<3, P>(a, r, lo, hi) else {
        return;
    };
    // Critical points: the roots of the quadratic p'.
    let (k, cp) = quadratic::<P>(a[1], 2.0 * a[2], 3.0 * a[3]);
    let Some(mut w) = Walker::<3, P>::start(a, l, fl, first, out) else {
        return;
    };
    for &c in &cp[..k] {
        if c > l && c < h && w.visit(c) {
            return;
        }
    }
    w.finish(h, fh);
}

/// The critical point of the quartic `p` in `(lo, hi)`, where its
/// derivative `d` changes sign (`g_lo` = `p'(lo)`), located only as well as
/// the walk needs. Newton on `p'` (kept in the bracket, bisection as
/// fallback) also evaluates `p` at each iterate `y`: as soon as `p(y)`
/// certainly has the sign opposite to `f_prev`, the value at the walk's
/// current left end, a crossing is bracketed by `y` and the search stops.
/// (That `y` is a valid breakpoint even though `p'(y) != 0`: between `y` and
/// the true critical point `p` keeps the sign of `p(y)`, because the
/// extremum lies beyond `p(y)` from zero.) Otherwise Newton converges and
/// the critical point comes back with `p`'s trusted value there. Returns
/// the point, `p` there and, after an early stop, `p'` and `p''/2` there
/// (for the quadratic model that starts the root search).
#[inline(always)]
fn critical_point<P: Product>(
    p: &Coeffs,
    d: &Coeffs,
    (mut lo, mut hi): (f64, f64),
    g_lo: f64,
    start: f64,
    f_prev: f64,
) -> (f64, f64, Option<(f64, f64)>) {
    let neg_lo = g_lo < 0.0;
    let bracket = (lo, hi);
    let mut y = start;
    for _ in 0..128 {
        let (g, dg) = horner_d::<3>(d, y);
        if f_prev != 0.0 {
            let (f, e) = horner_bounded::<4>(p, y);
            if f.abs() > e && (f < 0.0) != (f_prev < 0.0) {
                return (y, f, Some((g, 0.5 * dg)));
            }
        }
        if g == 0.0 {
            break;
        }
        if (g < 0.0) == neg_lo {
            lo = y;
        } else {
            hi = y;
        }
        let step = g / dg;
        let yn = y - step;
        if yn == y {
            break;
        }
        if yn > lo && yn < hi {
            y = yn;
            if step.abs() <= CRIT_TOL * yn.abs() {
                break;
            }
        } else {
            let m = split_point(lo, hi);
            if !(m > lo && m < hi) {
                break;
            }
            y = m;
        }
    }
    let mut f = signed_value::<4, P>(p, y);
    if f == 0.0 || !critical_value_is_settled(d, y, f) {
        // Inside a cluster of roots plain Newton on p' stops wherever its
        // rounding noise hides the true critical point, which may be
        // further away than the neighbouring roots; and a touching (double)
        // root belongs where p' vanishes, to an ulp, not where plain Newton
        // stopped. Locate it with certified signs of p' instead, in the
        // bracket the caller proved.
        y = certified_critical_point(p, d, bracket, g_lo, y);
        f = signed_value::<4, P>(p, y);
    }
    (y, f, None)
}

/// True when `p(y) = f` (a trusted sign) settles the walk at the
/// approximate critical point `y` of the quartic `p` (derivative `d`):
/// plain Horner puts the true critical point within `delta = (|p'(y)| +
/// err) / |p''(y)|` of `y`, over which `p` changes by about
/// `p'' delta^2 / 2`; with `|f|` four times above that bound, `p` keeps the
/// sign of `f` from `y` to the true critical point, so no root lies
/// between them and the extremum has the sign of `f`. (Away from clusters
/// `delta` is a few ulps and the test always passes.)
#[inline(always)]
fn critical_value_is_settled(d: &Coeffs, y: f64, f: f64) -> bool {
    let (g, eg) = horner_bounded::<3>(d, y);
    let eg = eg + 2.0 * U * d[2].abs() * (y * y);
    let dg = horner_d::<3>(d, y).1;
    let delta = (g.abs() + eg) / dg.abs();
    f.abs() > 4.0 * dg.abs() * delta * delta
}

/// The critical point of the quartic `p` in `bracket`, where `p'` has the
/// sign of `g_lo` at the left end and the opposite one at the right end,
/// located by the certified polish on `p'` from `y`: every sign of `p'`
/// from compensated Horner on coefficients that are exact (the rounding
/// of `3 a3` is carried as its own term), so the point is right to within
/// what that precision can tell, even inside a tight cluster of roots.
#[cold]
#[inline(never)]
fn certified_critical_point(p: &Coeffs, d: &Coeffs, bracket: (f64, f64), g_lo: f64, y: f64) -> f64 {
    let dg = horner_d::<3>(d, y).1;
    if !(y > bracket.0 && y < bracket.1 && dg.is_finite() && dg != 0.0) {
        return y;
    }
    polish_with(&Slope { p, d }, y, bracket.0, bracket.1, g_lo, dg)
}

/// `p'(x)` of the quartic `p` (`d` = [`derivative`] of it) with a sign that
/// can be trusted, and a bound on its error: compensated Horner on `d`,
/// plus the rounding of `d`'s one inexact coefficient (`3 a3`; the others
/// are exact multiples by powers of two) carried as its own term. Exact
/// evaluation when that cannot decide and `3 a3` was exact; otherwise
/// `0.0` ("a critical point, as far as this precision can tell").
#[inline(always)]
fn certain_slope<P: Product>(p: &Coeffs, d: &Coeffs, x: f64) -> (f64, f64) {
    let low = P::two_prod(p[3], 3.0).1;
    let (v, e) = horner_comp::<3, P>(d, x);
    let t = low * x * x;
    let w = v + t;
    let bound = e + gamma(3) * t.abs() + 2.0 * U * w.abs();
    if w.abs() > bound {
        (w, bound)
    } else if low == 0.0 {
        let w = horner_exact::<3, Native>(d, x);
        (w, w.abs() * f64::EPSILON)
    } else {
        (0.0, bound)
    }
}

/// `p'(x)` of the quartic `p` when its sign can be trusted (`0.0` when it
/// cannot be told from zero), as [`signed_value`] but with the rounding of
/// `d`'s coefficient `3 a3` in the plain bound and in the fallback.
#[inline(always)]
fn signed_slope<P: Product>(p: &Coeffs, d: &Coeffs, x: f64) -> f64 {
    let (v, e) = horner_bounded::<3>(d, x);
    if v.abs() > e + 2.0 * U * d[2].abs() * (x * x) || !v.is_finite() {
        return v;
    }
    certain_slope::<P>(p, d, x).0
}

#[inline(always)]
fn quartic<P: Product>(a: &Coeffs, r: f64, lo: f64, hi: f64, first: bool, out: &mut Roots) {
    let Some((l, fl, h, fh)) = search_interval::<4, P>(a, r, lo, hi) else {
        return;
    };
    let d = derivative::<4>(a);
    let Some(mut w) = Walker::<4, P>::start(a, l, fl, first, out) else {
        return;
    };
    if l == 0.0 {
        // From exactly 0, Descartes' rule on p' = a1 + 2a2 x + 3a3 x^2 +
        // 4a4 x^3 (the signs of a1..a4) bounds the positive critical points:
        // with at most one sign variation there is at most one, and it needs
        // no inflection points to isolate.
        let variations = sign_variations(&[a[1], a[2], a[3], a[4], 0.0], 3);
        let g0 = d[0];
        if variations == 0 || (variations == 1 && g0 != 0.0) {
            let gh = if fh.abs() == f64::MAX {
                f64::MAX.copysign(d[3])
            } else {
                signed_slope::<P>(a, &d, h)
            };
            if variations == 1 && g0 != 0.0 && gh != 0.0 && (g0 < 0.0) != (gh < 0.0) {
                let start = start_point::<3>(&d, (0.0, g0), (h, gh), None);
                let (c, fc, model) = critical_point::<P>(a, &d, (0.0, h), g0, start, w.f);
                if c > w.x && w.advance_with(c, fc, model) {
                    return;
                }
            }
            w.finish(h, fh);
            return;
        }
    }
    // The critical points are the roots of the cubic p', which is monotone
    // between the roots of the quadratic p'' (the inflection points).
    let (k, infl) = quadratic::<P>(d[1], 2.0 * d[2], 3.0 * d[3]);
    let mut x = l;
    let mut gx = signed_slope::<P>(a, &d, l);
    let mut i = 0;
    loop {
        let (e, ge, is_infl) = if i < k {
            let e = infl[i];
            i += 1;
            if !(e > x && e < h) {
                continue;
            }
            (e, signed_slope::<P>(a, &d, e), true)
        } else {
            (h, signed_slope::<P>(a, &d, h), false)
        };
        if gx != 0.0 && ge != 0.0 && (gx < 0.0) != (ge < 0.0) {
            let start = start_point::<3>(&d, (x, gx), (e, ge), None);
            let (c, fc, model) = critical_point::<P>(a, &d, (x, e), gx, start, w.f);
            if c > w.x && w.advance_with(c, fc, model) {
                return;
            }
        } else if ge == 0.0 && e < h && w.visit(e) {
            return;
        }
        if !is_infl {
            break;
        }
        x = e;
        gx = ge;
    }
    w.finish(h, fh);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_classifies_tangency_from_an_accurate_discriminant() {
        // (x - 0.1)^2 with rounded coefficients: b^2 - 4ac is a few ulps
        // either side of zero and the plain formula gets its sign wrong.
        let (k, r) = quadratic::<Native>(1.0, -2.0, 1.0);
        assert_eq!((k, r[0]), (1, 1.0));
        let (k, r) = quadratic::<Native>(-1.0, 0.0, 1.0);
        assert_eq!((k, r), (2, [-1.0, 1.0]));
        let (k, _) = quadratic::<Native>(1.0, 0.0, 1.0);
        assert_eq!(k, 0);
    }

    #[test]
    fn linear_and_quadratic_respect_the_half_open_interval() {
        assert_eq!(Production.first_root(&[-2.0, 1.0], 0.0, 2.0), None);
        assert_eq!(Production.first_root(&[-2.0, 1.0], 2.0, 3.0), Some(2.0));
        assert_eq!(
            Production.roots_in(&[2.0, -3.0, 1.0], 1.0, 2.0).as_slice(),
            &[1.0]
        );
    }

    /// A fixed xorshift stream of numbers uniform in `[-1, 1)`.
    fn uniform_stream(seed: u64) -> impl FnMut() -> f64 {
        let mut rng = crate::rng::Rng::xorshift64(seed);
        move || rng.symmetric()
    }

    #[test]
    fn no_real_roots_is_never_wrong_and_usually_decides() {
        // Products of two quadratic factors with random (mostly complex)
        // roots, including near-real pairs: whenever the discriminant test
        // claims "no real root", the f64-exact reference agrees.
        let mut next = uniform_stream(0x1234_5678_9abc_def0);
        let (mut clear, mut decided) = (0, 0);
        for _ in 0..400 {
            // (x - re)^2 + s: a complex pair when s > 0 (sometimes very
            // close to the real axis), two real roots otherwise.
            let mut factor = || {
                let re = next() * 10.0;
                let s = if next() > 0.0 {
                    0.5 + 10.0 * next().abs()
                } else {
                    next() * next().abs().powi(6)
                };
                ([re * re + s, -2.0 * re, 1.0], s, re)
            };
            let ((q1, s1, re1), (q2, s2, re2)) = (factor(), factor());
            let lead = 10f64.powf(next() * 3.0);
            let mut c = [0.0; 5];
            for i in 0..3 {
                for j in 0..3 {
                    c[i + j] += lead * q1[i] * q2[j];
                }
            }
            let claims = no_real_roots(&c);
            if claims {
                let reference = super::super::reference::reference_roots(&c);
                assert!(
                    reference.is_empty(),
                    "{c:?}: claimed no real root, reference {reference:?}"
                );
            }
            if s1 >= 0.5 && s2 >= 0.5 && (re1 - re2).abs() > 1.0 {
                clear += 1;
                decided += usize::from(claims);
            }
        }
        println!("decided {decided} of {clear} clearly complex quartics");
        assert!(
            decided * 10 >= clear * 9,
            "decided only {decided} of {clear}"
        );
    }

    /// [`no_real_roots`] as it was written before its discriminant and
    /// magnitude shared the lanes of a [`Pair`]: two scalar chains.
    fn no_real_roots_scalar(q: &Coeffs) -> bool {
        let (a, b, c, d, e) = (q[4], q[3], q[2], q[1], q[0]);
        let (b2, c2, d2) = (b * b, c * c, d * d);
        let (ae, ac, a2) = (a * e, a * c, a * a);
        let (p1, p2) = (8.0 * ac, 3.0 * b2);
        if !(p1 - p2 > gamma(4) * (p1.abs() + p2) * (1.0 + 4.0 * U)) {
            let dt = [
                64.0 * a2 * ae,
                -16.0 * a2 * c2,
                16.0 * ac * b2,
                -16.0 * a2 * b * d,
                -3.0 * b2 * b2,
            ];
            let dd = dt[0] + dt[1] + dt[2] + dt[3] + dt[4];
            let ds = dt[0].abs() + dt[1].abs() + dt[2].abs() + dt[3].abs() + dt[4].abs();
            if !(dd > gamma(10) * ds * (1.0 + 8.0 * U)) {
                return false;
            }
        }
        let bd = b * d;
        let a3 = 256.0 * a2 * a;
        let a2_ = a * (a * (-192.0 * bd - 128.0 * c2) + 144.0 * b2 * c) - 27.0 * b2 * b2;
        let a1 = a * (d2 * (144.0 * ac - 6.0 * b2) + c2 * (16.0 * c2 - 80.0 * bd))
            + b2 * c * (18.0 * bd - 4.0 * c2);
        let a0 = d2 * (ac * (18.0 * bd - 4.0 * c2) - 27.0 * a2 * d2 + b2 * (c2 - 4.0 * bd));
        let disc = ((a3 * e + a2_) * e + a1) * e + a0;
        if !(disc > 0.0) {
            return false;
        }
        let (aa, ac_, bd_, cc, ee) = (a.abs(), ac.abs(), bd.abs(), c.abs(), e.abs());
        let m3 = 256.0 * a2 * aa;
        let m2 = aa * (aa * (192.0 * bd_ + 128.0 * c2) + 144.0 * b2 * cc) + 27.0 * b2 * b2;
        let m1 = aa * (d2 * (144.0 * ac_ + 6.0 * b2) + c2 * (16.0 * c2 + 80.0 * bd_))
            + b2 * cc * (18.0 * bd_ + 4.0 * c2);
        let m0 = d2 * (ac_ * (18.0 * bd_ + 4.0 * c2) + 27.0 * a2 * d2 + b2 * (c2 + 4.0 * bd_));
        let mag = ((m3 * ee + m2) * ee + m1) * ee + m0;
        disc > gamma(24) * mag * (1.0 + 32.0 * U) && mag < f64::INFINITY && mag > 1e-250
    }

    #[test]
    fn paired_discriminant_test_decides_as_the_two_scalar_chains() {
        // Random coefficients of every sign over wide scales (so both the
        // sign and the magnitude test decide, and some products overflow
        // or underflow), products of two quadratic factors with complex or
        // nearly real roots, and the hard table: the same answer every
        // time, and both answers occur.
        let mut next = uniform_stream(0x7a1d_0c0d_e5ee_d123);
        let (mut yes, mut total) = (0, 0);
        let mut check = |c: &Coeffs| {
            let paired = no_real_roots(c);
            assert_eq!(paired, no_real_roots_scalar(c), "{c:?}");
            yes += usize::from(paired);
            total += 1;
        };
        for i in 0..200_000 {
            let mut c = [0.0; 5];
            if i % 2 == 0 {
                for v in c.iter_mut() {
                    *v = next() * super::super::poly::pow2((next() * 200.0) as i32);
                }
            } else {
                let (re1, s1, re2, s2) = (next() * 10.0, next(), next() * 10.0, next());
                let s1 = s1 * s1.abs().powi(4);
                let q1 = [re1 * re1 + s1, -2.0 * re1, 1.0];
                let q2 = [re2 * re2 + s2, -2.0 * re2, 1.0];
                let lead = super::super::poly::pow2((next() * 300.0) as i32);
                for i in 0..3 {
                    for j in 0..3 {
                        c[i + j] += lead * q1[i] * q2[j];
                    }
                }
            }
            check(&c);
        }
        for case in super::super::cases::hard_table() {
            let mut c = [0.0; 5];
            c[..case.coeffs.len()].copy_from_slice(&case.coeffs);
            check(&c);
        }
        println!("{yes} of {total} certified without a real root");
        assert!(yes * 20 > total && yes < total, "{yes} of {total}");
    }

    #[test]
    fn half_line_certificates_are_never_wrong() {
        // Contacts (some grazing, some with the touch just after 0) and
        // products of factors with small or nearly double positive roots,
        // at scales from 2^-600 to 2^600: whenever a certificate claims
        // "positive on [0, inf)", the f64-exact reference finds no root
        // >= 0.
        let mut next = uniform_stream(0x0bad_5eed_1234_5678);
        let (mut claims, mut total) = (0, 0);
        for i in 0..4000 {
            let mut c = [0.0; 5];
            if i % 2 == 0 {
                let v = |next: &mut dyn FnMut() -> f64, r: f64| [r * next(), r * next()];
                let (dp, dv, da) = (v(&mut next, 10.0), v(&mut next, 5.0), v(&mut next, 2.0));
                let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
                // A radius just below the closest approach on some draws.
                let s = if i % 6 == 0 {
                    dot(dp, dp).sqrt() * (1.0 - next().abs() * 1e-6)
                } else {
                    2.0 * next().abs()
                };
                c = [
                    dot(dp, dp) - s * s,
                    2.0 * dot(dp, dv),
                    dot(dv, dv) + dot(dp, da),
                    dot(dv, da),
                    0.25 * dot(da, da),
                ];
            } else {
                // (x - r1)(x - r2)((x - re)^2 + t) with r1, r2 small, close
                // together, or negative.
                let r1 = next() * 10f64.powf(-8.0 * next().abs());
                let r2 = r1 + next() * 10f64.powf(-12.0 * next().abs());
                let (re, t) = (next() * 5.0, next() * 3.0);
                let q = [re * re + t, -2.0 * re, 1.0];
                let l = [r1 * r2, -(r1 + r2), 1.0];
                for i in 0..3 {
                    for j in 0..3 {
                        c[i + j] += l[i] * q[j];
                    }
                }
            }
            let scale = super::super::poly::pow2((next() * 600.0) as i32);
            let x_scale = super::super::poly::pow2((next() * 60.0) as i32);
            let mut m = 1.0;
            for v in c.iter_mut() {
                *v *= scale * m;
                m *= x_scale;
            }
            if !(c[4] != 0.0 && c.iter().all(|v| v.is_finite())) {
                continue;
            }
            total += 1;
            let (a, b) = (positive_from_zero(&c), positive_by_square(&c));
            if a || b {
                claims += 1;
                let reference = super::super::reference::reference_roots(&c);
                assert!(
                    reference.iter().all(|&r| r < 0.0),
                    "{c:?}: claimed ({a}, {b}) positive on [0, inf), reference {reference:?}"
                );
            }
        }
        println!("certified {claims} of {total}");
        assert!(claims * 4 > total, "certified only {claims} of {total}");
    }

    #[test]
    fn sign_variations_count_every_sign_pattern_with_zeros_of_either_sign_skipped() {
        // All 4^5 patterns of -, 0, +, -0 (the degree is where the last
        // non-zero one sits), against the count read off the non-zero
        // signs: a zero counts as zero whatever its sign bit.
        for code in 0..1024u32 {
            let mut a = [0.0; 5];
            let mut k = code;
            for slot in a.iter_mut() {
                *slot = [-1.5, 0.0, 2.5, -0.0][(k % 4) as usize];
                k /= 4;
            }
            let Some(n) = (0..5).rev().find(|&i| a[i] != 0.0) else {
                continue;
            };
            let signs: Vec<bool> = a.iter().filter(|&&c| c != 0.0).map(|&c| c < 0.0).collect();
            let expected = signs.windows(2).filter(|w| w[0] != w[1]).count() as u32;
            assert_eq!(sign_variations(&a, n), expected, "{a:?}");
        }
    }

    #[test]
    fn zero_roots_are_deflated_exactly_and_reported_once() {
        // x^2 (x - 1)(x + 2) = x^4 + x^3 - 2x^2
        let c = [0.0, 0.0, -2.0, 1.0, 1.0];
        assert_eq!(Production.real_roots(&c).as_slice(), &[-2.0, 0.0, 1.0]);
        assert_eq!(Production.first_root(&c, -3.0, 9.0), Some(-2.0));
        assert_eq!(Production.first_root(&c, -1.0, 9.0), Some(0.0));
        assert_eq!(Production.first_root(&c, 0.0, 9.0), Some(0.0));
        assert_eq!(Production.first_root(&c, 0.5, 9.0), Some(1.0));
        assert_eq!(Production.roots_in(&c, -2.0, 0.0).as_slice(), &[-2.0]);
        assert_eq!(Production.roots_in(&c, 0.0, 1.0).as_slice(), &[0.0]);
        // x (x - 3): the quadratic path deflates too.
        assert_eq!(
            Production.roots_in(&[0.0, -3.0, 1.0], -1.0, 5.0).as_slice(),
            &[0.0, 3.0]
        );
    }

    /// The walk with products by splitting and by the fused multiply-add,
    /// on the same normalised polynomial and interval.
    fn both_walks(c: &[f64], lo: f64, hi: f64, first: bool) -> Option<(Roots, Roots)> {
        let (a, n) = normalize(c)?;
        if n < 3 || a[0] == 0.0 {
            return None;
        }
        let single = lo == 0.0 && sign_variations(&a, n) == 1;
        let (mut split, mut fused) = (Roots::new(), Roots::new());
        walk::<super::super::poly::Split>(&a, n, lo, hi, first, single, &mut split);
        walk::<super::super::poly::Fused>(&a, n, lo, hi, first, single, &mut fused);
        Some((split, fused))
    }

    #[test]
    fn the_fused_walk_finds_the_same_roots_to_the_bit() {
        // The hard table (every search the method tests make of it) and
        // random contact quartics, some touching at 0: whichever way the
        // processor forms its error-free products, the roots are the same
        // bits, so no record depends on the machine that computed it.
        let bits = |r: &Roots| r.as_slice().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut compared = 0;
        let mut check = |c: &[f64], lo: f64, hi: f64| {
            for first in [false, true] {
                if let Some((split, fused)) = both_walks(c, lo, hi, first) {
                    assert_eq!(bits(&split), bits(&fused), "{c:?} on [{lo}, {hi})");
                    compared += 1;
                }
            }
        };
        for case in super::super::cases::hard_table() {
            check(&case.coeffs, f64::NEG_INFINITY, f64::INFINITY);
            check(&case.coeffs, 0.0, f64::INFINITY);
        }
        let mut next = uniform_stream(0x00f0_5ed5_0123_4567);
        for i in 0..20_000 {
            let v = |next: &mut dyn FnMut() -> f64, r: f64| [r * next(), r * next()];
            let (dv, da) = (v(&mut next, 5.0), v(&mut next, 2.0));
            let (dp, s) = if i % 4 == 0 {
                let k = 0.125 * (1.0 + (4.0 * (next() + 1.0)).floor());
                ([3.0 * k, 4.0 * k], 5.0 * k)
            } else {
                (v(&mut next, 10.0), 0.5 + next().abs() * 1.5)
            };
            let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
            let c = [
                dot(dp, dp) - s * s,
                2.0 * dot(dp, dv),
                dot(dv, dv) + dot(dp, da),
                dot(dv, da),
                0.25 * dot(da, da),
            ];
            check(&c, 0.0, f64::INFINITY);
            check(&c, 0.0, 10.0);
        }
        assert!(compared > 40_000, "compared {compared}");
    }

    #[test]
    fn quartic_with_four_simple_roots() {
        let r = Production.real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0]);
        assert_eq!(r.as_slice(), &[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(
            Production.first_root(&[24.0, -50.0, 35.0, -10.0, 1.0], 1.5, 10.0),
            Some(2.0)
        );
    }
}
