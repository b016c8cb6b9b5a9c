//! The thesis's baseline solver: the real roots of the derivative, found
//! recursively (degree 1 and 2 directly by formula), split the line into
//! intervals on which the polynomial is monotone; each interval whose ends
//! have opposite signs holds exactly one root, found by plain bisection
//! with plain Horner evaluation. The two unbounded end intervals are closed
//! with Cauchy's root bound `1 + max |c_k / c_n|`. Slow but simple; its
//! accuracy is limited by plain evaluation (clustered roots come out with
//! errors of order `sqrt(eps)` or worse, and a double root whose computed
//! extremum is not exactly zero can be missed or split).

use super::poly::{normalize, Coeffs};
use super::{RootSolver, Roots};

/// Derivative-recursive bisection (the baseline).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Bisection;

impl RootSolver for Bisection {
    fn real_roots(&self, coeffs: &[f64]) -> Roots {
        self.roots_in(coeffs, f64::NEG_INFINITY, f64::INFINITY)
    }

    fn roots_in(&self, coeffs: &[f64], lo: f64, hi: f64) -> Roots {
        if !(lo < hi) {
            return Roots::new();
        }
        let Some((a, n)) = normalize(coeffs) else {
            return Roots::new();
        };
        let mut bound = 0.0f64;
        for &c in &a[..n] {
            bound = bound.max((c / a[n]).abs());
        }
        let bound = (1.0 + bound).min(f64::MAX);
        let (l, h) = (lo.max(-bound), hi.min(bound));
        if !(l <= h) {
            return Roots::new();
        }
        roots_between(&a, n, l, h).within(lo, hi)
    }
}

fn eval(a: &Coeffs, n: usize, x: f64) -> f64 {
    let mut s = a[n];
    for i in (0..n).rev() {
        s = s * x + a[i];
    }
    s
}

/// Roots in the closed interval `[lo, hi]`, ascending.
fn roots_between(a: &Coeffs, n: usize, lo: f64, hi: f64) -> Roots {
    let mut out = Roots::new();
    match n {
        1 => out.push(-a[0] / a[1]),
        2 => {
            let (qa, qb, qc) = (a[2], a[1], a[0]);
            let d = qb * qb - 4.0 * qa * qc;
            if d == 0.0 {
                out.push(-qb / (2.0 * qa));
            } else if d > 0.0 {
                let q = -0.5 * (qb + d.sqrt().copysign(qb));
                out.push(q / qa);
                out.push(qc / q);
            }
            out.sort();
        }
        _ => {
            let mut d = [0.0; 5];
            for i in 1..=n {
                d[i - 1] = a[i] * i as f64;
            }
            let crit = roots_between(&d, n - 1, lo, hi);
            let mut pts = [0.0; 5];
            pts[0] = lo;
            let mut m = 1;
            for &c in crit.as_slice() {
                if c > lo && c < hi {
                    pts[m] = c;
                    m += 1;
                }
            }
            pts[m] = hi;
            m += 1;
            let mut prev = eval(a, n, pts[0]);
            if prev == 0.0 {
                out.push(pts[0]);
            }
            for i in 1..m {
                let (x0, x1) = (pts[i - 1], pts[i]);
                let f1 = eval(a, n, x1);
                if f1 == 0.0 {
                    out.push(x1);
                } else if prev != 0.0 && (prev < 0.0) != (f1 < 0.0) {
                    out.push(bisect(a, n, x0, x1, prev));
                }
                prev = f1;
            }
            return out;
        }
    }
    let mut closed = Roots::new();
    for &r in out.as_slice() {
        if lo <= r && r <= hi {
            closed.push(r);
        }
    }
    closed
}

/// Plain bisection of `[lo, hi]` where `p(lo)` has the sign of `flo` and
/// `p(hi)` the opposite one.
fn bisect(a: &Coeffs, n: usize, mut lo: f64, mut hi: f64, flo: f64) -> f64 {
    let neg = flo < 0.0;
    for _ in 0..2200 {
        let mid = 0.5 * lo + 0.5 * hi;
        if !(mid > lo && mid < hi) {
            break;
        }
        let fm = eval(a, n, mid);
        if fm == 0.0 {
            return mid;
        }
        if (fm < 0.0) == neg {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * lo + 0.5 * hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_well_separated_roots() {
        let r = Bisection.real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0]);
        assert_eq!(r.len(), 4);
        for (x, e) in r.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((x - e).abs() <= 4.0 * f64::EPSILON * e);
        }
    }

    #[test]
    fn bisection_respects_the_half_open_interval() {
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        // Plain Horner stops the bisection wherever the computed value is
        // exactly zero, a few ulps from the true root.
        let r = Bisection.roots_in(&c, 2.0, 4.0);
        assert_eq!(r.len(), 2);
        assert!((r[0] - 2.0).abs() < 1e-14 && (r[1] - 3.0).abs() < 1e-14);
        let f = Bisection.first_root(&c, 2.5, f64::INFINITY).unwrap();
        assert!((f - 3.0).abs() < 1e-14);
        assert!(Bisection.roots_in(&c, 4.5, 9.0).is_empty());
    }
}
