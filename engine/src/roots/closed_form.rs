//! The textbook closed-form solver: the stable quadratic formula, Cardano's
//! formula for cubics (Viète's trigonometric form when there are three real
//! roots, as in *Numerical Recipes* §5.6) and Ferrari's method for quartics
//! (depress, solve the resolvent cubic, split into two quadratics). No
//! polishing: the point of this method is to show how closed forms lose
//! accuracy (clustered roots, wide scaling) and even miss or invent roots
//! when a discriminant lands on the wrong side of zero.

use super::poly::normalize;
use super::{RootSolver, Roots};

/// Ferrari / Cardano / quadratic formula, unpolished.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ClosedForm;

impl RootSolver for ClosedForm {
    fn real_roots(&self, coeffs: &[f64]) -> Roots {
        let mut out = Roots::new();
        let Some((a, n)) = normalize(coeffs) else {
            return out;
        };
        match n {
            1 => out.push(-a[0] / a[1]),
            2 => quadratic(a[2], a[1], a[0], &mut out),
            3 => {
                let mut r = [0.0; 3];
                let k = cubic_monic(a[2] / a[3], a[1] / a[3], a[0] / a[3], &mut r);
                for &x in &r[..k] {
                    out.push(x);
                }
            }
            _ => quartic_monic(a[3] / a[4], a[2] / a[4], a[1] / a[4], a[0] / a[4], &mut out),
        }
        out.sort();
        out
    }
}

/// Real roots of `a x^2 + b x + c` by the stable formula
/// `q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2`, `x = q / a`, `x = c / q`.
fn quadratic(a: f64, b: f64, c: f64, out: &mut Roots) {
    let d = b * b - 4.0 * a * c;
    if d < 0.0 {
        return;
    }
    if d == 0.0 {
        out.push(-b / (2.0 * a));
        return;
    }
    let q = -0.5 * (b + d.sqrt().copysign(b));
    out.push(q / a);
    if q != 0.0 {
        out.push(c / q);
    }
}

/// Real roots of `x^3 + a x^2 + b x + c` (Cardano / Viète), unsorted.
fn cubic_monic(a: f64, b: f64, c: f64, r: &mut [f64; 3]) -> usize {
    let q = (a * a - 3.0 * b) / 9.0;
    let rr = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
    let shift = a / 3.0;
    let q3 = q * q * q;
    if rr * rr < q3 {
        // Three real roots: x = -2 sqrt(q) cos((theta + 2 pi k) / 3) - a/3.
        let theta = (rr / q3.sqrt()).clamp(-1.0, 1.0).acos();
        let m = -2.0 * q.sqrt();
        let tau = core::f64::consts::TAU;
        r[0] = m * (theta / 3.0).cos() - shift;
        r[1] = m * ((theta + tau) / 3.0).cos() - shift;
        r[2] = m * ((theta - tau) / 3.0).cos() - shift;
        3
    } else {
        // One real root: x = s + q/s - a/3 with s = -sign(r) cbrt(|r| + sqrt(r^2 - q^3)).
        let s = -(rr.abs() + (rr * rr - q3).sqrt()).cbrt().copysign(rr);
        let t = if s == 0.0 { 0.0 } else { q / s };
        r[0] = s + t - shift;
        1
    }
}

/// Real roots of `x^4 + a x^3 + b x^2 + c x + d` by Ferrari's method.
fn quartic_monic(a: f64, b: f64, c: f64, d: f64, out: &mut Roots) {
    // Depress with x = y - a/4: y^4 + p y^2 + q y + r = 0.
    let a2 = a * a;
    let p = b - 3.0 * a2 / 8.0;
    let q = c - a * b / 2.0 + a2 * a / 8.0;
    let r = d - a * c / 4.0 + a2 * b / 16.0 - 3.0 * a2 * a2 / 256.0;
    let shift = a / 4.0;
    let mut ys = Roots::new();
    // Resolvent cubic m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0: take its
    // largest real root, which is positive whenever q != 0.
    let mut mr = [0.0; 3];
    let k = cubic_monic(p, p * p / 4.0 - r, -q * q / 8.0, &mut mr);
    let m = mr[..k].iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if q == 0.0 || !(m > 0.0) {
        // Biquadratic: z^2 + p z + r = 0 with z = y^2.
        let mut zs = Roots::new();
        quadratic(1.0, p, r, &mut zs);
        for &z in zs.as_slice() {
            if z >= 0.0 {
                let s = z.sqrt();
                ys.push(s);
                if s != 0.0 {
                    ys.push(-s);
                }
            }
        }
    } else {
        // (y^2 + s y + p/2 + m - q/(2s)) (y^2 - s y + p/2 + m + q/(2s)), s = sqrt(2m).
        let s = (2.0 * m).sqrt();
        let h = p / 2.0 + m;
        let t = q / (2.0 * s);
        quadratic(1.0, s, h - t, &mut ys);
        quadratic(1.0, -s, h + t, &mut ys);
    }
    for &y in ys.as_slice() {
        out.push(y - shift);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_solves_simple_cases_exactly() {
        assert_eq!(ClosedForm.real_roots(&[-2.0, 1.0]).as_slice(), &[2.0]);
        assert_eq!(
            ClosedForm.real_roots(&[2.0, -3.0, 1.0]).as_slice(),
            &[1.0, 2.0]
        );
        let r = ClosedForm.real_roots(&[-6.0, 11.0, -6.0, 1.0]);
        assert_eq!(r.len(), 3);
        for (x, e) in r.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - e).abs() < 1e-12);
        }
        let r = ClosedForm.real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0]);
        assert_eq!(r.len(), 4);
        for (x, e) in r.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((x - e).abs() < 1e-12);
        }
    }

    #[test]
    fn closed_form_biquadratic_and_one_real_root_branches() {
        // x^4 - 5x^2 + 4 = (x^2 - 1)(x^2 - 4)
        let r = ClosedForm.real_roots(&[4.0, 0.0, -5.0, 0.0, 1.0]);
        assert_eq!(r.as_slice(), &[-2.0, -1.0, 1.0, 2.0]);
        // x^3 - 1: one real root
        let r = ClosedForm.real_roots(&[-1.0, 0.0, 0.0, 1.0]);
        assert_eq!(r.len(), 1);
        assert!((r[0] - 1.0).abs() < 1e-15);
    }
}
