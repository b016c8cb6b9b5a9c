//! The active-set method of [`super::active_set`] with the pushing set's
//! equalities kept factored: the matrix of the set (each contact's
//! normal-velocity change per unit impulse of every other) is symmetric
//! and positive definite while its contacts are independent, so its
//! Cholesky factor is extended by one row where a contact joins the set
//! and mended by plane rotations where one leaves, each a square of the
//! set's size in work, instead of the cube of a fresh elimination at every
//! step. A contact whose new pivot is rounding only depends on those
//! pushing already and is left out for good, as the eliminating method
//! leaves out a contact whose solve is singular. The answer is the same
//! limit (the velocities of least kinetic energy that non-negative
//! impulses reach) to rounding, not to the bit.

use super::{Contact, Solver};
use glam::DVec2;

/// A new pivot of the factor under this fraction of the largest diagonal
/// entry of the set's matrix is rounding: the contact depends on the set
/// (the eliminating solve's singularity threshold, see `super::solve`).
const DEPENDENT: f64 = 1e-12;

/// The Cholesky factor `L` (lower triangular, `L Lᵀ` the set's matrix) of
/// the contacts pushing, in the order they joined.
struct Factor {
    /// Contacts of the set (indices into the contacts).
    set: Vec<usize>,
    /// Row-major, `stride` wide: row `r` of `L` holds `r + 1` entries.
    l: Vec<f64>,
    stride: usize,
    /// The largest diagonal entry of the set's matrix so far.
    largest: f64,
}

impl Factor {
    fn new(contacts: usize) -> Self {
        Factor {
            set: Vec::new(),
            l: vec![0.0; contacts * contacts],
            stride: contacts,
            largest: 0.0,
        }
    }

    fn at(&self, r: usize, c: usize) -> f64 {
        self.l[r * self.stride + c]
    }

    /// `L y = b` for `y`, in place.
    fn forward(&self, b: &mut [f64]) {
        for r in 0..b.len() {
            let row = &self.l[r * self.stride..][..r];
            let sum: f64 = row.iter().zip(&b[..r]).map(|(x, y)| x * y).sum();
            b[r] = (b[r] - sum) / self.at(r, r);
        }
    }

    /// `Lᵀ x = y` for `x`, in place.
    fn backward(&self, y: &mut [f64]) {
        let m = y.len();
        for r in (0..m).rev() {
            let mut sum = y[r];
            for (q, &yq) in y.iter().enumerate().skip(r + 1) {
                sum -= self.at(q, r) * yq;
            }
            y[r] = sum / self.at(r, r);
        }
    }

    /// Adds contact `j`, whose matrix entries against the set are `g` and
    /// whose own is `gjj`; `false` (the factor unchanged) where it depends
    /// on the set.
    fn add(&mut self, j: usize, mut g: Vec<f64>, gjj: f64) -> bool {
        let m = self.set.len();
        self.forward(&mut g);
        let d = gjj - g.iter().map(|x| x * x).sum::<f64>();
        let largest = self.largest.max(gjj);
        if !(d > DEPENDENT * largest) {
            return false;
        }
        let row = &mut self.l[m * self.stride..][..m + 1];
        row[..m].copy_from_slice(&g);
        row[m] = d.sqrt();
        self.set.push(j);
        self.largest = largest;
        true
    }

    /// Removes the contact at position `p` of the set: its row goes, and
    /// the rows below, one entry too long, are turned back to a triangle
    /// by plane rotations of neighbouring columns.
    fn remove(&mut self, p: usize) {
        let m = self.set.len();
        let s = self.stride;
        for r in p + 1..m {
            let (above, below) = self.l.split_at_mut(r * s);
            above[(r - 1) * s..][..r + 1].copy_from_slice(&below[..r + 1]);
        }
        self.set.remove(p);
        let m = m - 1;
        for c in p..m {
            let (x, y) = (self.at(c, c), self.at(c, c + 1));
            let h = x.hypot(y);
            let (cos, sin) = if h == 0.0 { (1.0, 0.0) } else { (x / h, y / h) };
            for r in c..m {
                let (u, w) = (self.l[r * s + c], self.l[r * s + c + 1]);
                self.l[r * s + c] = cos * u + sin * w;
                self.l[r * s + c + 1] = -sin * u + cos * w;
            }
            self.l[c * s + c + 1] = 0.0;
        }
    }
}

/// The plastic limit with biases (as [`super::active_set`]) by the
/// factored active-set method; `None` where the answer leaves a contact
/// approaching beyond rounding (or the method does not end).
pub(crate) fn active_set(
    vel: &[DVec2],
    inv_mass: &[f64],
    contacts: &[Contact],
) -> Option<Vec<DVec2>> {
    let solver = match Solver::new(vel, inv_mass, contacts) {
        Ok(s) => s,
        Err(known) => return Some(known),
    };
    let k_all = contacts.len();
    // What each contact needs (its bias less its normal velocity before).
    let rhs: Vec<f64> = contacts
        .iter()
        .map(|c| c.bias - solver.normal(vel, c))
        .collect();
    // Each contact's normal-velocity change per unit impulse of every
    // contact, row by row.
    let gram: Vec<f64> = contacts
        .iter()
        .flat_map(|ck| contacts.iter().map(|cq| solver.effect(ck, cq)))
        .collect();
    let mut impulse = vec![0.0f64; k_all];
    let mut left_out = vec![false; k_all];
    let mut factor = Factor::new(k_all);
    let mut v = vel.to_vec();
    for _ in 0..3 * k_all + 8 {
        // The contact approaching fastest (or parting slowest under its
        // bias) beyond the tolerance, neither pushing nor left out.
        let next = (0..k_all)
            .filter(|&k| !left_out[k] && !factor.set.contains(&k))
            .map(|k| (k, contacts[k].bias - solver.normal(&v, &contacts[k])))
            .filter(|&(_, w)| w > solver.tolerance)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        let Some((j, _)) = next else {
            let set = factor.set.clone();
            return solver.accept(v, &set, &impulse);
        };
        let g: Vec<f64> = factor.set.iter().map(|&q| gram[q * k_all + j]).collect();
        let gjj = gram[j * k_all + j];
        if !factor.add(j, g, gjj) {
            left_out[j] = true;
            continue;
        }
        // Solve the pushing set; step back where an impulse would pull.
        for _ in 0..k_all + 1 {
            let z = solve(&factor, &gram, &rhs);
            if z.iter().all(|&p| p > 0.0) {
                for (&k, &p) in factor.set.iter().zip(&z) {
                    impulse[k] = p;
                }
                break;
            }
            // The contact just added would not push at all (rounding let
            // it join): left out, for good.
            if let Some(p) = factor
                .set
                .iter()
                .zip(&z)
                .position(|(&k, &p)| k == j && impulse[k] == 0.0 && p <= 0.0)
            {
                factor.remove(p);
                left_out[j] = true;
                break;
            }
            // Every other contact of the set pushes: step towards `z` as
            // far as they all still do.
            let mut step = 1.0f64;
            for (&k, &p) in factor.set.iter().zip(&z) {
                let fall = impulse[k] - p;
                if p <= 0.0 && fall > 0.0 {
                    step = step.min(impulse[k] / fall);
                }
            }
            for (&k, &p) in factor.set.iter().zip(&z) {
                impulse[k] += step * (p - impulse[k]);
                if impulse[k] <= 0.0 {
                    impulse[k] = 0.0;
                }
            }
            while let Some(p) = factor.set.iter().position(|&k| impulse[k] <= 0.0) {
                factor.remove(p);
            }
            if factor.set.is_empty() {
                break;
            }
        }
        v = apply(vel, inv_mass, contacts, &impulse);
    }
    None
}

/// The impulses of the set of `factor` solved as equalities (each contact
/// of it parting at its bias: `rhs` what each needs, `gram` the matrix of
/// every contact), refined once by the solve of what the first answer
/// leaves (its residual computed from the matrix itself, not the factor):
/// on a pile whose contacts depend on each other a contact left out of the
/// set approaches by what the set's equalities leave unmet.
fn solve(factor: &Factor, gram: &[f64], rhs: &[f64]) -> Vec<f64> {
    let k_all = rhs.len();
    let mut z: Vec<f64> = factor.set.iter().map(|&k| rhs[k]).collect();
    factor.forward(&mut z);
    factor.backward(&mut z);
    let mut left: Vec<f64> = factor
        .set
        .iter()
        .map(|&k| {
            let row = &gram[k * k_all..][..k_all];
            let met: f64 = factor.set.iter().zip(&z).map(|(&q, &p)| row[q] * p).sum();
            rhs[k] - met
        })
        .collect();
    factor.forward(&mut left);
    factor.backward(&mut left);
    for (p, d) in z.iter_mut().zip(&left) {
        *p += d;
    }
    z
}

/// The velocities `vel` after the impulses `impulse` of the contacts.
fn apply(vel: &[DVec2], inv_mass: &[f64], contacts: &[Contact], impulse: &[f64]) -> Vec<DVec2> {
    let mut v = vel.to_vec();
    for (c, &p) in contacts.iter().zip(impulse) {
        if p != 0.0 {
            v[c.a] += c.n * (p * inv_mass[c.a]);
            if let Some(b) = c.b {
                v[b] -= c.n * (p * inv_mass[b]);
            }
        }
    }
    v
}
