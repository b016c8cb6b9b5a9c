//! High-precision numbers and polynomial roots: the arithmetic under the
//! yardstick. Values are 320-bit binary floats (`dashu-float`, pure Rust);
//! every `f64` input converts exactly. [`first_root`] finds the smallest
//! real root of a polynomial in an interval by the textbook recursion —
//! the roots of the derivative split the interval into monotone pieces,
//! each piece with a sign change is solved by safeguarded Newton to ~300
//! bits — so a root is never skipped, and a root at a critical point whose
//! value is below `2^-280` of the polynomial's scale counts (an exact
//! double root). Nothing here shares code with the engine.

use dashu_float::ops::SquareRoot;
use dashu_float::round::mode::HalfEven;
use dashu_float::FBig;

/// A 320-bit binary float.
pub type F = FBig<HalfEven, 2>;

/// Working precision in bits.
pub const PREC: usize = 320;

/// Exact conversion of a finite `f64` (non-finite input becomes zero; the
/// callers validate first).
pub fn big(x: f64) -> F {
    match F::try_from(x) {
        Ok(v) => v.with_precision(PREC).value(),
        Err(_) => zero(),
    }
}

/// Zero at working precision (never `F::ZERO`, whose unlimited precision
/// would make divisions panic).
pub fn zero() -> F {
    F::try_from(0.0f64)
        .map(|v| v.with_precision(PREC).value())
        .unwrap_or(F::ZERO)
}

/// The nearest `f64`.
pub fn to_f64(x: &F) -> f64 {
    x.to_f64().value()
}

/// Square root (of a non-negative value; negative input gives zero).
pub fn sqrt(x: &F) -> F {
    if *x <= F::ZERO {
        zero()
    } else {
        x.sqrt()
    }
}

/// Absolute value.
pub fn abs(x: &F) -> F {
    if *x < F::ZERO {
        -x.clone()
    } else {
        x.clone()
    }
}

/// `2^k` at working precision.
pub fn pow2(k: i32) -> F {
    big(2f64.powi(k))
}

/// Horner evaluation, coefficients lowest degree first.
pub fn eval(a: &[F], x: &F) -> F {
    let mut s = a[a.len() - 1].clone();
    for c in a[..a.len() - 1].iter().rev() {
        s = s * x + c;
    }
    s
}

/// `sum |a_i| |x|^i`: the scale against which a value counts as zero.
fn magnitude(a: &[F], x: &F) -> F {
    let ax = abs(x);
    let mut s = abs(&a[a.len() - 1]);
    for c in a[..a.len() - 1].iter().rev() {
        s = s * &ax + abs(c);
    }
    s
}

fn negligible(a: &[F], x: &F, v: &F) -> bool {
    abs(v) <= magnitude(a, x) * pow2(-280)
}

fn derivative(a: &[F]) -> Vec<F> {
    (1..a.len()).map(|i| a[i].clone() * big(i as f64)).collect()
}

/// Drops zero high coefficients.
fn trim(a: &[F]) -> &[F] {
    let mut n = a.len();
    while n > 0 && a[n - 1] == F::ZERO {
        n -= 1;
    }
    &a[..n]
}

/// A bound on the absolute value of every real root (Cauchy).
fn root_bound(a: &[F]) -> F {
    let n = a.len() - 1;
    let lead = abs(&a[n]);
    let mut m = zero();
    for c in &a[..n] {
        let q = abs(c) / &lead;
        if q > m {
            m = q;
        }
    }
    m + big(1.0)
}

/// All distinct real roots in `[lo, hi]`, ascending (a polynomial that is
/// zero everywhere has none).
pub fn roots_in(a: &[F], lo: &F, hi: &F) -> Vec<F> {
    let a = trim(a);
    if a.len() < 2 || lo > hi {
        return Vec::new();
    }
    isolate(a, lo, hi)
}

fn isolate(a: &[F], lo: &F, hi: &F) -> Vec<F> {
    if a.len() == 2 {
        let r = -(a[0].clone() / &a[1]);
        return if &r >= lo && &r <= hi {
            vec![r]
        } else {
            vec![]
        };
    }
    let crit = isolate(&derivative(a), lo, hi);
    let mut pts = vec![lo.clone()];
    pts.extend(crit.into_iter().filter(|c| c > lo && c < hi));
    pts.push(hi.clone());
    let vals: Vec<F> = pts.iter().map(|x| eval(a, x)).collect();
    let zero_at: Vec<bool> = pts
        .iter()
        .zip(&vals)
        .map(|(x, v)| negligible(a, x, v))
        .collect();
    let mut out: Vec<F> = Vec::new();
    for k in 0..pts.len() {
        if k > 0
            && !zero_at[k - 1]
            && !zero_at[k]
            && ((vals[k - 1] < F::ZERO) != (vals[k] < F::ZERO))
        {
            out.push(solve_monotone(a, &pts[k - 1], &pts[k], &vals[k - 1]));
        }
        if zero_at[k] {
            out.push(pts[k].clone());
        }
    }
    out
}

/// The root of `a` in `(lo, hi)`, where `a` is monotone and changes sign;
/// `flo` is `a(lo)`. Newton steps that stay inside the bracket, bisection
/// otherwise.
fn solve_monotone(a: &[F], lo: &F, hi: &F, flo: &F) -> F {
    let d = derivative(a);
    let neg_lo = *flo < F::ZERO;
    let (mut lo, mut hi) = (lo.clone(), hi.clone());
    let half = big(0.5);
    let rel = pow2(-(PREC as i32) + 12);
    let floor = pow2(-1070);
    let mut x = (lo.clone() + &hi) * &half;
    for _ in 0..3000 {
        let fx = eval(a, &x);
        if fx == F::ZERO {
            return x;
        }
        if (fx < F::ZERO) == neg_lo {
            lo = x.clone();
        } else {
            hi = x.clone();
        }
        let width = hi.clone() - &lo;
        let scale = abs(&x);
        if width <= scale.clone() * &rel || width <= floor {
            return x;
        }
        let dfx = eval(&d, &x);
        let mut next = None;
        if dfx != F::ZERO {
            let step = fx / &dfx;
            let cand = x.clone() - &step;
            if cand > lo && cand < hi {
                if abs(&step) <= scale * &rel {
                    return cand;
                }
                next = Some(cand);
            }
        }
        // Bisect when Newton leaves the bracket; for very wide brackets
        // around zero, halve the magnitude instead of the interval.
        x = next.unwrap_or_else(|| (lo.clone() + &hi) * &half);
    }
    x
}

/// The smallest real root `r` of `a` with `lo <= r < hi` (`hi = None`:
/// unbounded above; `lo = None`: unbounded below).
pub fn first_root(a: &[F], lo: Option<&F>, hi: Option<&F>) -> Option<F> {
    let a = trim(a);
    if a.len() < 2 {
        return None;
    }
    let b = root_bound(a);
    let lo = match lo {
        Some(l) => l.clone(),
        None => -b.clone(),
    };
    let hi_b = match hi {
        Some(h) if *h < b => h.clone(),
        _ => b,
    };
    if lo > hi_b {
        return None;
    }
    roots_in(a, &lo, &hi_b)
        .into_iter()
        .find(|r| hi.is_none_or(|h| r < h))
}

/// All distinct real roots `r >= lo` (and `< hi` when given), ascending.
pub fn roots_from(a: &[F], lo: &F, hi: Option<&F>) -> Vec<F> {
    let a = trim(a);
    if a.len() < 2 {
        return Vec::new();
    }
    let b = root_bound(a);
    let top = match hi {
        Some(h) if *h < b => h.clone(),
        _ => b,
    };
    if *lo > top {
        return Vec::new();
    }
    let mut v = roots_in(a, lo, &top);
    if let Some(h) = hi {
        v.retain(|r| r < h);
    }
    v
}

/// The exact smallest real root of the `f64` polynomial `c` (lowest degree
/// first) in `[lo, hi)`, rounded to the nearest `f64`; infinite bounds are
/// allowed.
pub fn first_root_f64(c: &[f64], lo: f64, hi: f64) -> Option<f64> {
    if c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let a: Vec<F> = c.iter().map(|&x| big(x)).collect();
    let lo_b = lo.is_finite().then(|| big(lo));
    let hi_b = hi.is_finite().then(|| big(hi));
    first_root(&a, lo_b.as_ref(), hi_b.as_ref()).map(|r| to_f64(&r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_root_of_well_separated_quartic_is_exact() {
        // (x-1)(x-2)(x-3)(x-4) = 24 - 50x + 35x^2 - 10x^3 + x^4
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        assert_eq!(
            first_root_f64(&c, f64::NEG_INFINITY, f64::INFINITY),
            Some(1.0)
        );
        assert_eq!(first_root_f64(&c, 1.5, f64::INFINITY), Some(2.0));
        assert_eq!(first_root_f64(&c, 1.5, 2.0), None);
    }

    #[test]
    fn exact_double_and_quadruple_roots_are_found() {
        assert_eq!(
            first_root_f64(&[1.0, -4.0, 6.0, -4.0, 1.0], -10.0, 10.0),
            Some(1.0)
        );
        assert_eq!(
            first_root_f64(&[4.0, -12.0, 13.0, -6.0, 1.0], 1.5, 10.0),
            Some(2.0)
        );
    }

    #[test]
    fn irrational_root_is_correctly_rounded() {
        // x^2 - 2
        let r = first_root_f64(&[-2.0, 0.0, 1.0], 0.0, f64::INFINITY).unwrap();
        assert_eq!(r, 2f64.sqrt());
    }

    #[test]
    fn widely_scaled_roots_keep_full_relative_accuracy() {
        // (x - 1e-8)(x - 1e8) = 1 - (1e8 + 1e-8) x + x^2, rounded to f64.
        let c = [1.0, -(1e8 + 1e-8), 1.0];
        let r = first_root_f64(&c, f64::NEG_INFINITY, f64::INFINITY).unwrap();
        assert!((r - 1e-8).abs() <= 1e-8 * 1e-15);
    }

    #[test]
    fn polynomials_without_real_roots_give_none() {
        assert_eq!(first_root_f64(&[1.0, 0.0, 1.0], -1e9, 1e9), None);
        assert_eq!(first_root_f64(&[5.0], -1.0, 1.0), None);
        assert_eq!(first_root_f64(&[1.0, f64::NAN], -1.0, 1.0), None);
    }
}
