//! The engine's default solver: exact-structure root isolation plus
//! safeguarded Newton, after Yuksel ("High-Performance Polynomial Root
//! Finding for Graphics", HPG 2022) with the accuracy safeguards of
//! compensated arithmetic (Graillat, Langlois & Louvet 2005).
//!
//! * Degree 1 is one division; degree 2 is the stable quadratic formula with
//!   the discriminant computed with error-free products (Kahan), so a double
//!   root or a near-tangency is classified from an almost exact `b^2 - 4ac`.
//! * Degrees 3 and 4: the critical points (roots of `p'`) split the search
//!   interval into pieces on which `p` is monotone; a piece holds a root iff
//!   its ends have opposite signs. For a quartic the critical points are the
//!   roots of the cubic `p'`, isolated in turn by the closed-form roots of
//!   the quadratic `p''`. Everything is lazy: `first_root` walks the pieces
//!   left to right, computes a critical point only when it reaches it, and
//!   stops at the first piece with a sign change.
//! * Signs at piece ends are decided by plain Horner when its running error
//!   bound allows, otherwise by compensated Horner; a value that even the
//!   compensated bound cannot separate from zero is a root there (a double
//!   root at a critical point, reported once).
//! * Inside a piece: Newton started from a quadratic model at the critical
//!   end (or a secant point), kept inside the bracket, falling back to
//!   bisection (in the floating-point sense, so at most ~64 halvings); then
//!   one or two Newton corrections with a compensated residual, accepted once
//!   the compensated sign changes between adjacent iterates, so the result
//!   is within an ulp or two of the exact root of the `f64` polynomial even
//!   for clustered roots.
//! * Unbounded searches are closed with a Fujiwara bound (`poly::root_bound`),
//!   whose end signs are known without evaluating.
//!
//! Range: coefficients and roots must keep `p` finite near the roots (for a
//! monic quartic, roots below about `1e75` in magnitude); beyond that the
//! result is still returned without panicking but may miss roots.

use super::poly::{
    derivative, gamma, horner_bounded, horner_comp, horner_d, horner_exact, normalize,
    root_bound, split_point, two_prod, Coeffs, U,
};
use super::{RootSolver, Roots};

/// Lazy critical-point walk + safeguarded Newton + compensated polishing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Production;

impl RootSolver for Production {
    fn real_roots(&self, coeffs: &[f64]) -> Roots {
        solve(coeffs, f64::NEG_INFINITY, f64::INFINITY, false)
    }

    fn roots_in(&self, coeffs: &[f64], lo: f64, hi: f64) -> Roots {
        solve(coeffs, lo, hi, false)
    }

    fn first_root(&self, coeffs: &[f64], lo: f64, hi: f64) -> Option<f64> {
        solve(coeffs, lo, hi, true).first()
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
        1 => {
            let r = -a[0] / a[1] + 0.0;
            if lo <= r && r < hi {
                out.push(r);
            }
        }
        2 => {
            let (k, r) = quadratic(a[0], a[1], a[2]);
            for &x in &r[..k] {
                if lo <= x && x < hi {
                    out.push(x);
                }
            }
        }
        _ => {
            if lo == 0.0 && descartes_at_zero(&a, n, hi, first, &mut out) {
                return out;
            }
            if n == 3 {
                cubic(&a, lo, hi, first, &mut out);
            } else if !no_real_roots(&a) {
                quartic(&a, lo, hi, first, &mut out);
            }
        }
    }
    out
}

/// Fast paths for a search starting at exactly `0` (the engine's usual
/// query), where the coefficients themselves are the Taylor coefficients:
/// `p(0) = 0` answers a `first_root` query at once, and by Descartes' rule
/// of signs no sign variation means no positive root and one variation
/// means exactly one (simple) positive root, which is then solved on its
/// own without locating critical points. Returns true when `out` is final.
#[inline(always)]
fn descartes_at_zero(a: &Coeffs, n: usize, hi: f64, first: bool, out: &mut Roots) -> bool {
    if a[0] == 0.0 {
        if first {
            out.push(0.0);
            return true;
        }
        return false;
    }
    let mut variations = 0;
    let mut last_neg = a[0] < 0.0;
    for (i, &c) in a.iter().enumerate().skip(1) {
        if i <= n && c != 0.0 {
            let neg = c < 0.0;
            variations += usize::from(neg != last_neg);
            last_neg = neg;
        }
    }
    match variations {
        0 => true,
        1 => {
            if n == 3 {
                single_positive_root::<3>(a, hi, out);
            } else {
                single_positive_root::<4>(a, hi, out);
            }
            true
        }
        _ => false,
    }
}

/// True when the quartic certainly has no real root: its discriminant is
/// positive and `P = 8ac - 3b^2` or `D = 64a^3e - 16a^2c^2 + 16ab^2c -
/// 16a^2bd - 3b^4` is positive (two pairs of complex conjugate roots), every
/// sign certified by an a-priori rounding-error bound on the monomial sums.
/// About 70 flops and no division: it settles most separating contacts
/// without locating a single critical point. Inconclusive (false) near
/// degenerate cases and when the degree-6 products over- or underflow.
#[inline(always)]
fn no_real_roots(q: &Coeffs) -> bool {
    let (a, b, c, d, e) = (q[4], q[3], q[2], q[1], q[0]);
    let (b2, c2, d2, e2) = (b * b, c * c, d * d, e * e);
    let ae = a * e;
    let ac = a * c;
    // P and D first: they are cheap and often decide alone that the
    // discriminant is needed at all.
    let p1 = 8.0 * ac;
    let p2 = 3.0 * b2;
    let pp = p1 - p2;
    let p_pos = pp > gamma(4) * (p1.abs() + p2) * (1.0 + 4.0 * U);
    let a2 = a * a;
    let dt = [
        64.0 * a2 * ae,
        -16.0 * a2 * c2,
        16.0 * ac * b2,
        -16.0 * a2 * b * d,
        -3.0 * b2 * b2,
    ];
    let dd = dt[0] + dt[1] + dt[2] + dt[3] + dt[4];
    let ds = dt[0].abs() + dt[1].abs() + dt[2].abs() + dt[3].abs() + dt[4].abs();
    let d_pos = dd > gamma(10) * ds * (1.0 + 8.0 * U);
    if !(p_pos || d_pos) {
        return false;
    }
    let bd = b * d;
    let t = [
        256.0 * ae * ae * ae,
        -192.0 * ae * ae * bd,
        -128.0 * ae * ae * c2,
        144.0 * ae * ac * d2,
        -27.0 * a2 * d2 * d2,
        144.0 * ae * e * b2 * c,
        -6.0 * ae * b2 * d2,
        -80.0 * ae * bd * c2,
        18.0 * ac * bd * d2,
        16.0 * ae * c2 * c2,
        -4.0 * ac * c2 * d2,
        -27.0 * b2 * b2 * e2,
        18.0 * b2 * bd * c * e,
        -4.0 * b2 * bd * d2,
        -4.0 * b2 * c2 * c * e,
        b2 * c2 * d2,
    ];
    let mut disc = 0.0;
    let mut mag = 0.0;
    for v in t {
        disc += v;
        mag += v.abs();
    }
    // Each monomial carries at most 8 roundings, the sum 15 more.
    disc > gamma(24) * mag * (1.0 + 32.0 * U) && mag < f64::INFINITY && mag > 1e-250
}

/// The one positive root of `p` (Descartes: one sign variation), if below
/// `hi`.
#[inline(never)]
fn single_positive_root<const N: usize>(a: &Coeffs, hi: f64, out: &mut Roots) {
    let r = root_bound(a, N);
    let f0 = a[0];
    let (h, fh) = if hi >= r {
        (r, f64::MAX.copysign(a[N]))
    } else {
        (hi, signed_value::<N>(a, hi))
    };
    if fh == 0.0 || (fh < 0.0) == (f0 < 0.0) {
        // p(hi) = 0 (excluded) or the root lies beyond hi.
        return;
    }
    // Newton from 0 as the start, kept in the bracket (0, h).
    let mut start = -a[0] / a[1];
    if !(start > 0.0 && start < h) {
        start = split_point(0.0, h);
    }
    let (x, d) = halley::<N>(a, 0.0, h, f0, start, ROOT_TOL);
    out.push(polish::<N>(a, x, 0.0, h, f0, d));
}

/// Real roots of `c2 x^2 + c1 x + c0` (`c2 != 0`), ascending, a double root
/// once. The discriminant is formed from error-free products, so its sign
/// is right unless it is below the rounding level of its own error terms.
#[inline]
pub(super) fn quadratic(c0: f64, c1: f64, c2: f64) -> (usize, [f64; 2]) {
    let (bb, ebb) = two_prod(c1, c1);
    let (ac, eac) = two_prod(4.0 * c2, c0);
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
    quadratic(c0 * s, c1 * s, c2 * s)
}

/// The value of `p(x)` when its sign can be trusted: plain Horner when its
/// error bound allows, compensated Horner otherwise, and `0.0` when even the
/// compensated value cannot be told apart from zero.
#[inline(always)]
fn signed_value<const N: usize>(p: &Coeffs, x: f64) -> f64 {
    let (v, e) = horner_bounded::<N>(p, x);
    if v.abs() > e || !v.is_finite() {
        return v;
    }
    let (v, e) = horner_comp::<N>(p, x);
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
fn halley<const N: usize>(p: &Coeffs, mut a: f64, mut b: f64, fa: f64, x0: f64, tol: f64) -> (f64, f64) {
    let neg_a = fa < 0.0;
    let mut x = x0;
    let mut d = 0.0;
    let mut last = f64::INFINITY;
    let mut stalls = 0;
    let mut fallbacks = 0;
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
            if stalls >= 3 {
                return (x, d);
            }
        }
        last = f.abs();
        let denom = df * df - f * h2;
        let mut step = f * df / denom;
        let mut xn = x - step;
        if !(xn > a && xn < b) {
            step = f / df;
            xn = x - step;
        }
        if xn > a && xn < b {
            fallbacks = 0;
            x = xn;
            if step.abs() <= tol * xn.abs() {
                return (x, d);
            }
        } else {
            fallbacks += 1;
            let m = if fallbacks < 4 { a + 0.5 * (b - a) } else { split_point(a, b) };
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
fn certain_value<const N: usize>(p: &Coeffs, x: f64) -> (f64, f64) {
    let (v, e) = horner_comp::<N>(p, x);
    if v.abs() > e {
        (v, e)
    } else {
        let v = horner_exact::<N>(p, x);
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
fn polish<const N: usize>(p: &Coeffs, x: f64, mut a: f64, mut b: f64, fa: f64, d: f64) -> f64 {
    let neg_a = fa < 0.0;
    let mut x = x;
    let mut d = d;
    let (mut v, mut e) = certain_value::<N>(p, x);
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
                // The bracket is as tight as the format allows.
                return x;
            }
        }
        let (vn, en) = certain_value::<N>(p, xn);
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
    x
}

/// Relative step below which Halley hands over (the error after such a step
/// is of order its cube): for the roots themselves the compensated polish
/// does the last correction; critical points only need a few ulps.
const ROOT_TOL: f64 = 1e-6;
const CRIT_TOL: f64 = 1e-9;

/// A starting point for Newton in `(x0, x1)` where `p(x0) = f0` and
/// `p(x1) = f1` have opposite signs: the root of the quadratic Taylor model
/// at the end nearer the root by `|p|`, which is exact to second order and
/// excellent next to an extremum (where `p'` vanishes and Newton alone would
/// crawl); the secant point when the model has no root inside.
#[inline(always)]
fn start_point<const N: usize>(p: &Coeffs, (x0, f0): (f64, f64), (x1, f1): (f64, f64)) -> f64 {
    let right = f1.abs() <= f0.abs();
    let (c, f) = if right { (x1, f1) } else { (x0, f0) };
    if f.is_finite() {
        let (_, d1, h2) = taylor2::<N>(p, c);
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
struct Walker<'a, const N: usize> {
    p: &'a Coeffs,
    /// Left end of the current piece and `p` there (`0.0`: a root, already
    /// reported).
    x: f64,
    f: f64,
    first: bool,
    out: &'a mut Roots,
}

impl<'a, const N: usize> Walker<'a, N> {
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
        })
    }

    /// Advances to the breakpoint `c` (> current end) where `p(c) = fc`,
    /// solving the piece in between if it holds a root. Returns true when a
    /// `first_root` query is answered.
    #[inline(always)]
    fn advance(&mut self, c: f64, fc: f64) -> bool {
        if fc == 0.0 {
            self.out.push(c);
            if self.first {
                return true;
            }
        } else if self.f != 0.0 && (self.f < 0.0) != (fc < 0.0) {
            let start = start_point::<N>(self.p, (self.x, self.f), (c, fc));
            let (x, d) = halley::<N>(self.p, self.x, c, self.f, start, ROOT_TOL);
            let r = polish::<N>(self.p, x, self.x, c, self.f, d);
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
        let fc = signed_value::<N>(self.p, c);
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
fn search_interval<const N: usize>(a: &Coeffs, lo: f64, hi: f64) -> Option<(f64, f64, f64, f64)> {
    let r = root_bound(a, N);
    let lead = a[N];
    // Beyond the bound only the sign matters: the largest magnitude of that
    // sign also tells `start_point` to model the function at the other end.
    let (l, fl) = if lo <= -r {
        let s = if N % 2 == 0 { lead } else { -lead };
        (-r, f64::MAX.copysign(s))
    } else if lo == 0.0 {
        (lo, a[0])
    } else {
        (lo, signed_value::<N>(a, lo))
    };
    let (h, fh) = if hi >= r {
        (r, f64::MAX.copysign(lead))
    } else {
        (hi, signed_value::<N>(a, hi))
    };
    if l < h {
        Some((l, fl, h, fh))
    } else {
        None
    }
}

#[inline(never)]
fn cubic(a: &Coeffs, lo: f64, hi: f64, first: bool, out: &mut Roots) {
    let Some((l, fl, h, fh)) = search_interval::<3>(a, lo, hi) else {
        return;
    };
    // Critical points: the roots of the quadratic p'.
    let (k, cp) = quadratic(a[1], 2.0 * a[2], 3.0 * a[3]);
    let Some(mut w) = Walker::<3>::start(a, l, fl, first, out) else {
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
/// the point and `p` there.
#[inline(always)]
fn critical_point(
    p: &Coeffs,
    d: &Coeffs,
    (mut lo, mut hi): (f64, f64),
    g_lo: f64,
    start: f64,
    f_prev: f64,
) -> (f64, f64) {
    let neg_lo = g_lo < 0.0;
    let mut y = start;
    for _ in 0..128 {
        let (g, dg) = horner_d::<3>(d, y);
        if f_prev != 0.0 {
            let (f, e) = horner_bounded::<4>(p, y);
            if f.abs() > e && (f < 0.0) != (f_prev < 0.0) {
                return (y, f);
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
    (y, signed_value::<4>(p, y))
}

#[inline(never)]
fn quartic(a: &Coeffs, lo: f64, hi: f64, first: bool, out: &mut Roots) {
    let Some((l, fl, h, fh)) = search_interval::<4>(a, lo, hi) else {
        return;
    };
    let d = derivative::<4>(a);
    let Some(mut w) = Walker::<4>::start(a, l, fl, first, out) else {
        return;
    };
    if l == 0.0 {
        // From exactly 0, Descartes' rule on p' = a1 + 2a2 x + 3a3 x^2 +
        // 4a4 x^3 (the signs of a1..a4) bounds the positive critical points:
        // with at most one sign variation there is at most one, and it needs
        // no inflection points to isolate.
        let mut variations = 0;
        let mut last = 0.0f64;
        for &c in &a[1..=4] {
            if c != 0.0 {
                variations += usize::from(last != 0.0 && (c < 0.0) != (last < 0.0));
                last = c;
            }
        }
        let g0 = d[0];
        if variations == 0 || (variations == 1 && g0 != 0.0) {
            let gh = if fh.abs() == f64::MAX {
                f64::MAX.copysign(d[3])
            } else {
                signed_value::<3>(&d, h)
            };
            if variations == 1 && g0 != 0.0 && gh != 0.0 && (g0 < 0.0) != (gh < 0.0) {
                let start = start_point::<3>(&d, (0.0, g0), (h, gh));
                let (c, fc) = critical_point(a, &d, (0.0, h), g0, start, w.f);
                if c > w.x && w.advance(c, fc) {
                    return;
                }
            }
            w.finish(h, fh);
            return;
        }
    }
    // The critical points are the roots of the cubic p', which is monotone
    // between the roots of the quadratic p'' (the inflection points).
    let (k, infl) = quadratic(d[1], 2.0 * d[2], 3.0 * d[3]);
    let mut x = l;
    let mut gx = signed_value::<3>(&d, l);
    let mut i = 0;
    loop {
        let (e, ge, is_infl) = if i < k {
            let e = infl[i];
            i += 1;
            if !(e > x && e < h) {
                continue;
            }
            (e, signed_value::<3>(&d, e), true)
        } else {
            (h, signed_value::<3>(&d, h), false)
        };
        if gx != 0.0 && ge != 0.0 && (gx < 0.0) != (ge < 0.0) {
            let start = start_point::<3>(&d, (x, gx), (e, ge));
            let (c, fc) = critical_point(a, &d, (x, e), gx, start, w.f);
            if c > w.x && w.advance(c, fc) {
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
        let (k, r) = quadratic(1.0, -2.0, 1.0);
        assert_eq!((k, r[0]), (1, 1.0));
        let (k, r) = quadratic(-1.0, 0.0, 1.0);
        assert_eq!((k, r), (2, [-1.0, 1.0]));
        let (k, _) = quadratic(1.0, 0.0, 1.0);
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
