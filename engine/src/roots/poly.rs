//! Polynomial arithmetic shared by the solvers: normalising a coefficient
//! slice (trimming zero high coefficients, rejecting NaN/inf), derivatives,
//! Horner evaluation (plain, with its running error bound, and with the
//! first derivative), the error-free transformations `two_sum`/`two_prod`,
//! compensated Horner (Graillat, Langlois & Louvet 2005) with its a-priori
//! error bound, exact evaluation with floating-point expansions (Shewchuk
//! 1997) as the last resort, a Fujiwara-type bound on all roots from
//! exponent arithmetic alone, and bisection in the floating-point sense.
//!
//! Coefficients are stored lowest degree first in a fixed `[f64; 5]`, so
//! nothing here allocates. Evaluation routines are generic over the degree
//! `N` so that their loops unroll completely.

/// Coefficients `c[0] + c[1] x + ... + c[4] x^4`, padded with zeros.
pub(super) type Coeffs = [f64; 5];

/// Unit roundoff of `f64` (half an ulp of 1.0).
pub(super) const U: f64 = f64::EPSILON * 0.5;

/// Trims zero high coefficients and validates the input.
///
/// Returns the padded coefficients and the degree (1..=4), or `None` when
/// the polynomial has no roots to look for: a non-finite coefficient, the
/// zero polynomial, a non-zero constant, or a non-zero coefficient beyond
/// degree 4 (outside this module's contract).
#[inline(always)]
pub(super) fn normalize(c: &[f64]) -> Option<(Coeffs, usize)> {
    if c.len() > 5 && c[5..].iter().any(|&v| v != 0.0) {
        return None;
    }
    // Fixed-size copy (no memcpy/memset calls for this hot path).
    let mut a = [0.0; 5];
    if c.len() >= 5 {
        a.copy_from_slice(&c[..5]);
    } else {
        let m = c.len();
        for (i, slot) in a.iter_mut().enumerate() {
            if i < m {
                *slot = c[i];
            }
        }
    }
    // `v * 0` is NaN exactly for an infinite or NaN `v` (a zero
    // otherwise), and a NaN survives the sum: one test instead of a branch
    // per coefficient.
    let nan_if_not_finite = a.iter().fold(0.0, |s, &v| s + v * 0.0);
    if nan_if_not_finite.is_nan() {
        return None;
    }
    let mut deg = 4;
    while deg > 0 && a[deg] == 0.0 {
        deg -= 1;
    }
    if deg == 0 {
        None
    } else {
        Some((a, deg))
    }
}

/// Coefficients of the derivative of a degree-`N` polynomial.
#[inline(always)]
pub(super) fn derivative<const N: usize>(a: &Coeffs) -> Coeffs {
    let mut d = [0.0; 5];
    let mut i = 1;
    while i <= N {
        d[i - 1] = a[i] * i as f64;
        i += 1;
    }
    d
}

/// Horner evaluation of `p(x)` and `p'(x)` together.
#[inline(always)]
pub(super) fn horner_d<const N: usize>(a: &Coeffs, x: f64) -> (f64, f64) {
    let mut p = a[N];
    let mut d = 0.0;
    let mut i = N;
    while i > 0 {
        i -= 1;
        d = d * x + p;
        p = p * x + a[i];
    }
    (p, d)
}

/// `gamma(k) = k u / (1 - k u)`, the classic bound on `k` roundings.
#[inline(always)]
pub(super) const fn gamma(k: usize) -> f64 {
    let ku = k as f64 * U;
    ku / (1.0 - ku)
}

/// Smallest magnitude we treat as meaningful in error bounds (guards the
/// bounds against underflow).
const TINY: f64 = 4.0 * f64::MIN_POSITIVE;

/// Plain Horner value together with a rigorous bound on its rounding error:
/// `|value - p(x)| <= bound` (Higham, *Accuracy and Stability*, 5.1).
#[inline(always)]
pub(super) fn horner_bounded<const N: usize>(a: &Coeffs, x: f64) -> (f64, f64) {
    let ax = x.abs();
    let mut s = a[N];
    let mut m = a[N].abs();
    let mut i = N;
    while i > 0 {
        i -= 1;
        s = s * x + a[i];
        m = m * ax + a[i].abs();
    }
    (s, gamma(2 * N + 1) * m * (1.0 + 4.0 * U) + TINY)
}

/// Error-free sum: `a + b == s + e` exactly (Knuth's TwoSum).
#[inline(always)]
pub(super) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// How the error-free product `a * b == p + e` is formed:
/// Dekker's splitting ([`Split`], any processor) or one fused multiply-add
/// ([`Fused`]). Both give the exact error `a * b - p`, so the same bits,
/// whenever that error is a normal number and `|a|`, `|b|` stay below
/// `2^996` (where the splitting overflows): every product the solvers form
/// after [`super::production`] balances the coefficients. The solver
/// picks `Fused` at run time where the processor has the instruction.
pub(super) trait Product {
    /// `(p, e)` with `p = a * b` rounded and `a * b == p + e` exactly.
    fn two_prod(a: f64, b: f64) -> (f64, f64);
}

/// [`Product`] by Veltkamp/Dekker splitting: 17 flops, no special
/// instruction.
pub(super) enum Split {}

/// [`Product`] by one fused multiply-add. Only fast in code compiled for
/// a processor that has it (elsewhere `mul_add` is a library call, exact
/// but slow), so only built where the solver can pick it.
#[cfg(any(test, target_arch = "x86_64", target_feature = "fma"))]
pub(super) enum Fused {}

/// The [`Product`] the target was compiled for.
#[cfg(target_feature = "fma")]
pub(super) type Native = Fused;
#[cfg(not(target_feature = "fma"))]
pub(super) type Native = Split;

impl Product for Split {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let p = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
    }
}

#[cfg(any(test, target_arch = "x86_64", target_feature = "fma"))]
impl Product for Fused {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let p = a * b;
        (p, a.mul_add(b, -p))
    }
}

/// Veltkamp/Dekker splitting of `a` into two 26-bit halves.
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const FACTOR: f64 = 134_217_729.0; // 2^27 + 1
    let c = FACTOR * a;
    let h = c - (c - a);
    (h, a - h)
}

/// Compensated Horner: the value of `p(x)` as if computed in twice the
/// working precision and rounded once, with a rigorous error bound
/// `|value - p(x)| <= bound` (Langlois & Louvet 2007:
/// `u |p(x)| + gamma(2N)^2 p~(|x|)`, plus slack for computing the bound).
#[inline(always)]
pub(super) fn horner_comp<const N: usize, P: Product>(a: &Coeffs, x: f64) -> (f64, f64) {
    let ax = x.abs();
    let mut s = a[N];
    let mut c = 0.0;
    let mut m = a[N].abs();
    let mut i = N;
    while i > 0 {
        i -= 1;
        let (p, pi) = P::two_prod(s, x);
        let (t, sigma) = two_sum(p, a[i]);
        s = t;
        c = c * x + (pi + sigma);
        m = m * ax + a[i].abs();
    }
    let v = s + c;
    let g = gamma(2 * N);
    let bound = (g * g * m) * (1.0 + gamma(2 * N + 2)) + 2.0 * U * v.abs() + TINY;
    (v, bound)
}

/// `p(x)` evaluated exactly with floating-point expansions (Shewchuk,
/// "Adaptive precision floating-point arithmetic", 1997) and rounded once:
/// the sign is always right and the value is faithful (barring overflow or
/// underflow in the products). About 30x the cost of compensated Horner, so
/// it is only the last resort when the compensated bound cannot decide.
#[cold]
#[inline(never)]
pub(super) fn horner_exact<const N: usize, P: Product>(a: &Coeffs, x: f64) -> f64 {
    // Horner on expansions: lengths grow 1, 3, 7, 15, 31 at most.
    let mut e = [0.0f64; 32];
    let mut len = 1;
    e[0] = a[N];
    let mut h = [0.0f64; 32];
    let mut i = N;
    while i > 0 {
        i -= 1;
        // h = e * x (scale-expansion with zero elimination)
        let mut hl = 0;
        let (mut q, hh) = P::two_prod(e[0], x);
        if hh != 0.0 {
            h[hl] = hh;
            hl += 1;
        }
        for &ej in &e[1..len] {
            let (t1, t0) = P::two_prod(ej, x);
            let (q2, hh) = two_sum(q, t0);
            if hh != 0.0 {
                h[hl] = hh;
                hl += 1;
            }
            let s = t1 + q2;
            let hh = q2 - (s - t1);
            q = s;
            if hh != 0.0 {
                h[hl] = hh;
                hl += 1;
            }
        }
        if q != 0.0 || hl == 0 {
            h[hl] = q;
            hl += 1;
        }
        // e = h + a[i] (grow-expansion with zero elimination)
        len = 0;
        let mut q = a[i];
        for &hj in &h[..hl] {
            let (s, hh) = two_sum(q, hj);
            q = s;
            if hh != 0.0 {
                e[len] = hh;
                len += 1;
            }
        }
        if q != 0.0 || len == 0 {
            e[len] = q;
            len += 1;
        }
    }
    // Components are non-overlapping and increasing: summing from the
    // smallest keeps the sign and gives a faithful value.
    let mut v = 0.0;
    for &c in &e[..len] {
        v += c;
    }
    v
}

/// A bound `R` with `|z| < R` for every complex root `z` of the degree-`n`
/// polynomial `a`: twice Fujiwara's bound
/// `2 max(|a_{n-1}/a_n|, |a_{n-2}/a_n|^(1/2), ..., |a_0/(2 a_n)|^(1/n))`,
/// each term rounded up to a power of two using only exponent arithmetic
/// (no `powf`). By Gauss–Lucas the bound also holds for every derivative.
pub(super) fn root_bound(a: &Coeffs, n: usize) -> f64 {
    match n {
        1 => root_bound_n::<1>(a),
        2 => root_bound_n::<2>(a),
        3 => root_bound_n::<3>(a),
        _ => root_bound_n::<4>(a),
    }
}

/// [`root_bound`] for degree `N`: the loop unrolls and every root index
/// `N - k` is a constant.
#[inline(always)]
fn root_bound_n<const N: usize>(a: &Coeffs) -> f64 {
    let inv = 1.0 / a[N].abs();
    let mut e_max = i32::MIN;
    let mut finite = true;
    let mut k = 0;
    // Branch-free selects, so that the loop unrolls into straight code.
    while k < N {
        let t = a[k].abs() * inv * if k == 0 { 0.5 } else { 1.0 };
        finite &= t < f64::INFINITY;
        // t < 2^e  =>  t^(1/m) < 2^ceil(e/m)
        let r = ceil_div(exponent_above(t), N - k);
        e_max = if t != 0.0 { e_max.max(r) } else { e_max };
        k += 1;
    }
    if !finite {
        return f64::INFINITY;
    }
    if e_max == i32::MIN {
        // p = a_n x^n: every root is zero.
        return f64::MIN_POSITIVE;
    }
    // Fujiwara's factor 2, and another 2 to make the bound strict.
    pow2(e_max + 2)
}

/// `ceil(e / m)` for `m` in `1..=4`, by shifts and a division by the
/// constant 3 (a division by a variable `m` is an integer `div`, which
/// costs more than the rest of [`root_bound`] together; with `m` a
/// constant the `match` folds away).
#[inline(always)]
fn ceil_div(e: i32, m: usize) -> i32 {
    // `>>` on i32 is an arithmetic shift: floor division by a power of two.
    match m {
        1 => e,
        2 => (e + 1) >> 1,
        3 => (e + 2).div_euclid(3),
        _ => (e + 3) >> 2,
    }
}

/// The smallest `e` with `t < 2^e`, for finite positive `t`.
#[inline(always)]
pub(super) fn exponent_above(t: f64) -> i32 {
    let bits = t.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    // Subnormal (biased exponent 0): t < 2^-1022.
    biased.max(1) - 1023 + 1
}

/// `2^e`, saturating to `f64::MAX`/`f64::MIN_POSITIVE` outside the normal range.
#[inline(always)]
pub(super) fn pow2(e: i32) -> f64 {
    if e > 1023 {
        f64::MAX
    } else if e < -1022 {
        f64::MIN_POSITIVE
    } else {
        f64::from_bits(((e + 1023) as u64) << 52)
    }
}

/// A point strictly between `a < b` that halves the interval in the
/// floating-point (bit-pattern) sense when both ends have the same sign and
/// differ a lot in magnitude, and arithmetically otherwise; so bisection
/// ends after at most about 64 steps on any finite interval.
#[inline]
pub(super) fn split_point(a: f64, b: f64) -> f64 {
    if a < 0.0 && b > 0.0 {
        return 0.0;
    }
    // `abs` also clears the sign bit of a -0.0 end before the bit average.
    if a >= 0.0 && b > 4.0 * a.max(f64::MIN_POSITIVE) {
        f64::from_bits((a.abs().to_bits() / 2) + (b.to_bits() / 2))
    } else if b <= 0.0 && -a > 4.0 * (-b).max(f64::MIN_POSITIVE) {
        -f64::from_bits((b.abs().to_bits() / 2) + (a.abs().to_bits() / 2))
    } else {
        a + 0.5 * (b - a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalize_trims_zero_high_coefficients_and_rejects_bad_input() {
        assert_eq!(normalize(&[1.0, 2.0, 0.0, 0.0]).map(|(_, n)| n), Some(1));
        assert_eq!(
            normalize(&[1.0, 2.0, 3.0, 4.0, 5.0]).map(|(_, n)| n),
            Some(4)
        );
        assert!(normalize(&[]).is_none());
        assert!(normalize(&[0.0, 0.0]).is_none());
        assert!(normalize(&[3.0]).is_none());
        assert!(normalize(&[1.0, f64::NAN]).is_none());
        assert!(normalize(&[1.0, 1.0, f64::INFINITY]).is_none());
        assert!(normalize(&[1.0, 1.0, 0.0, 0.0, 0.0, 0.0]).is_some());
        assert!(normalize(&[1.0, 1.0, 0.0, 0.0, 0.0, 1.0]).is_none());
    }

    #[test]
    fn two_sum_and_two_prod_are_error_free() {
        let (s, e) = two_sum(1.0, 1e-20);
        assert_eq!((s, e), (1.0, 1e-20));
        let a = 1.0 + f64::EPSILON;
        for (p, e) in [Split::two_prod(a, a), Fused::two_prod(a, a)] {
            // (1+eps)^2 = 1 + 2 eps + eps^2
            assert_eq!(p, 1.0 + 2.0 * f64::EPSILON);
            assert_eq!(e, f64::EPSILON * f64::EPSILON);
        }
    }

    #[test]
    fn split_and_fused_products_give_the_same_bits() {
        // Random operands over the exponent range the balanced solver
        // works in (coefficients within 2^±600, points within their
        // bounds), products whose error is a normal number: the two ways
        // of forming it agree to the bit, so the solver's answer does not
        // depend on the processor.
        let mut rng = crate::rng::Rng::xorshift64(0x5eed_f00d_1234_5678);
        for _ in 0..200_000 {
            let e1 = (rng.symmetric() * 450.0) as i32;
            let e2 = (rng.symmetric() * 450.0) as i32;
            let a = rng.symmetric() * pow2(e1);
            let b = rng.symmetric() * pow2(e2);
            let (s, f) = (Split::two_prod(a, b), Fused::two_prod(a, b));
            assert_eq!(
                (s.0.to_bits(), s.1.to_bits()),
                (f.0.to_bits(), f.1.to_bits()),
                "{a:e} * {b:e}"
            );
        }
    }

    #[test]
    fn compensated_horner_resolves_what_plain_horner_cannot() {
        // (x - 1)^4 expanded, evaluated next to its quadruple root: the plain
        // value is pure rounding noise, the compensated one is exact here.
        let a = [1.0, -4.0, 6.0, -4.0, 1.0];
        let x = 1.0 + 1.0 / 1024.0;
        let exact = (1.0f64 / 1024.0).powi(4);
        let (v, bound) = horner_comp::<4, Native>(&a, x);
        assert!((v - exact).abs() <= bound);
        assert!((v - exact).abs() <= 2.0 * U * exact);
        let (pv, pbound) = horner_bounded::<4>(&a, x);
        assert!((pv - exact).abs() <= pbound);
    }

    #[test]
    fn exact_horner_gets_the_sign_where_compensated_cannot() {
        // (x - 1)^4 at 1 + 2^-30: the exact value 2^-120 is far below the
        // compensated bound but exact evaluation recovers it.
        let a = [1.0, -4.0, 6.0, -4.0, 1.0];
        let x = 1.0 + 2f64.powi(-30);
        assert_eq!(horner_exact::<4, Native>(&a, x), 2f64.powi(-120));
        let (_, bound) = horner_comp::<4, Native>(&a, x);
        assert!(bound > 2f64.powi(-120));
        assert_eq!(horner_exact::<4, Native>(&a, 1.0), 0.0);
        // Where compensated Horner is decisive the two agree.
        let b = [0.1, -0.7, 0.3, 0.0, 0.0];
        let (vc, ec) = horner_comp::<2, Native>(&b, 3.0);
        assert!((horner_exact::<2, Native>(&b, 3.0) - vc).abs() <= ec);
    }

    #[test]
    fn root_bound_encloses_every_root() {
        let cases: [(Coeffs, usize, f64); 4] = [
            ([-2.0, 1.0, 0.0, 0.0, 0.0], 1, 2.0),
            ([1e16, 0.0, 0.0, 0.0, 1.0], 4, 1e4),
            ([0.0, 0.0, 0.0, -1e-9, 1.0], 4, 1e-9),
            ([-1e-40, 1.0, 0.0, 0.0, 0.0], 1, 1e-40),
        ];
        for (a, n, r) in cases {
            let b = root_bound(&a, n);
            assert!(b > r && b < 64.0 * r, "{b} vs {r}");
        }
    }

    #[test]
    fn ceil_div_rounds_up_for_every_sign() {
        for e in -1100i32..1100 {
            for m in 1..=4usize {
                let mi = m as i32;
                let want = e.div_euclid(mi) + i32::from(e.rem_euclid(mi) != 0);
                assert_eq!(ceil_div(e, m), want, "{e} / {m}");
            }
        }
    }

    #[test]
    fn split_point_is_strictly_inside() {
        for (a, b) in [
            (1.0, 2.0),
            (1e-300, 1e300),
            (-1e300, -1e-300),
            (-1.0, 3.0),
            (0.0, 1.0),
        ] {
            let m = split_point(a, b);
            assert!(a < m && m < b, "{a} {m} {b}");
        }
    }
}
