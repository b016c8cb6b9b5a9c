//! Test-only reference roots: the exact real roots of a polynomial whose
//! coefficients are the given `f64` values, computed with 320-bit binary
//! floating point (`dashu-float`) by the same derivative-recursive isolation
//! as the baseline (critical points split the line into monotone pieces,
//! each sign change is bisected to ~300 bits, so that the value at a
//! critical point is accurate enough to classify a double root) and rounded
//! to the nearest `f64`. A value at a critical point within `2^-280` of the
//! polynomial's scale counts as zero (a double root, listed twice). Also:
//! helpers that measure errors in ulps.

use dashu_float::round::mode::HalfEven;
use dashu_float::FBig;

type F = FBig<HalfEven, 2>;

const PREC: usize = 320;

fn big(x: f64) -> F {
    F::try_from(x)
        .expect("finite coefficient")
        .with_precision(PREC)
        .value()
}

fn abs(x: F) -> F {
    if x < F::ZERO {
        -x
    } else {
        x
    }
}

fn eval(a: &[F], x: &F) -> F {
    let mut s = a[a.len() - 1].clone();
    for c in a[..a.len() - 1].iter().rev() {
        s = s * x + c;
    }
    s
}

fn magnitude(a: &[F], x: &F) -> F {
    let ax = abs(x.clone());
    let mut s = abs(a[a.len() - 1].clone());
    for c in a[..a.len() - 1].iter().rev() {
        s = s * &ax + abs(c.clone());
    }
    s
}

fn is_negligible(a: &[F], x: &F, v: &F) -> bool {
    let tiny = magnitude(a, x) * big(2f64.powi(-280));
    abs(v.clone()) <= tiny
}

fn roots_rec(a: &[F], lo: &F, hi: &F) -> Vec<F> {
    let n = a.len() - 1;
    if n == 1 {
        let r = -(a[0].clone() / &a[1]);
        return if &r >= lo && &r <= hi {
            vec![r]
        } else {
            vec![]
        };
    }
    let d: Vec<F> = (1..=n).map(|i| a[i].clone() * big(i as f64)).collect();
    let crit = roots_rec(&d, lo, hi);
    let mut pts = vec![lo.clone()];
    pts.extend(crit.into_iter().filter(|c| c > lo && c < hi));
    pts.push(hi.clone());
    let vals: Vec<F> = pts.iter().map(|x| eval(a, x)).collect();
    let mut out = Vec::new();
    for i in 0..pts.len() {
        if i > 0 {
            let (f0, f1) = (&vals[i - 1], &vals[i]);
            let z0 = is_negligible(a, &pts[i - 1], f0);
            let z1 = is_negligible(a, &pts[i], f1);
            if !z0 && !z1 && (f0.sign() != f1.sign()) {
                out.push(bisect(a, pts[i - 1].clone(), pts[i].clone(), f0));
            }
        }
        if is_negligible(a, &pts[i], &vals[i]) {
            // A root at a critical point: even multiplicity, list it twice.
            out.push(pts[i].clone());
            if i > 0 && i + 1 < pts.len() {
                out.push(pts[i].clone());
            }
        }
    }
    out
}

fn bisect(a: &[F], mut lo: F, mut hi: F, flo: &F) -> F {
    let neg = flo.sign();
    let half = big(0.5);
    let rel = big(2f64.powi(-300));
    let floor = big(2f64.powi(-1070));
    for _ in 0..4000 {
        let mid = (lo.clone() + &hi) * &half;
        let width = hi.clone() - &lo;
        let scale = abs(mid.clone());
        if width <= scale * &rel || width <= floor {
            return mid;
        }
        let fm = eval(a, &mid);
        if fm.sign() == neg {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo + hi) * half
}

/// The exact real roots of the `f64` polynomial `c` (lowest degree first),
/// rounded to the nearest `f64`, ascending; multiple roots repeated.
pub fn reference_roots(c: &[f64]) -> Vec<f64> {
    let mut n = c.len();
    while n > 0 && c[n - 1] == 0.0 {
        n -= 1;
    }
    if n <= 1 || c.iter().any(|x| !x.is_finite()) {
        return vec![];
    }
    let mut coeffs: Vec<f64> = c[..n].to_vec();
    let mut out = Vec::new();
    // Exact zero roots: deflate by x.
    while coeffs.len() > 1 && coeffs[0] == 0.0 {
        out.push(0.0);
        coeffs.remove(0);
    }
    if coeffs.len() > 1 {
        let a: Vec<F> = coeffs.iter().map(|&x| big(x)).collect();
        let lead = abs(a[a.len() - 1].clone());
        let mut m = big(0.0);
        for c in &a[..a.len() - 1] {
            let t = abs(c.clone()) / &lead;
            if t > m {
                m = t;
            }
        }
        let bound = m + big(1.0);
        let lo = -bound.clone();
        for r in roots_rec(&a, &lo, &bound) {
            out.push(r.to_f64().value());
        }
    }
    out.sort_by(|x, y| x.partial_cmp(y).unwrap());
    out
}

/// Distance in ulps between two finite `f64` values (counting the
/// representable numbers between them).
pub fn ulps(a: f64, b: f64) -> u64 {
    fn key(x: f64) -> i64 {
        let b = x.to_bits() as i64;
        if b < 0 {
            i64::MIN - b
        } else {
            b
        }
    }
    key(a).abs_diff(key(b))
}

/// The largest distance in ulps from any value in `xs` to the nearest value
/// in `ys` and vice versa (a Hausdorff distance); `u64::MAX` when exactly one
/// side is empty.
pub fn set_distance_ulps(xs: &[f64], ys: &[f64]) -> u64 {
    if xs.is_empty() && ys.is_empty() {
        return 0;
    }
    if xs.is_empty() || ys.is_empty() {
        return u64::MAX;
    }
    let one_way = |p: &[f64], q: &[f64]| {
        p.iter()
            .map(|&x| q.iter().map(|&y| ulps(x, y)).min().unwrap())
            .max()
            .unwrap()
    };
    one_way(xs, ys).max(one_way(ys, xs))
}

/// The largest relative error from any value in `xs` to the nearest value
/// in `ys` and vice versa (`f64::INFINITY` when exactly one side is empty).
pub fn set_distance_rel(xs: &[f64], ys: &[f64]) -> f64 {
    if xs.is_empty() && ys.is_empty() {
        return 0.0;
    }
    if xs.is_empty() || ys.is_empty() {
        return f64::INFINITY;
    }
    let rel = |x: f64, y: f64| {
        if x == y {
            0.0
        } else {
            (x - y).abs() / x.abs().max(y.abs())
        }
    };
    let one_way = |p: &[f64], q: &[f64]| {
        p.iter()
            .map(|&x| q.iter().map(|&y| rel(x, y)).fold(f64::INFINITY, f64::min))
            .fold(0.0, f64::max)
    };
    one_way(xs, ys).max(one_way(ys, xs))
}
