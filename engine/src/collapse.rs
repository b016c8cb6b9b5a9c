//! The limit of an inelastic collapse: discs touching each other and
//! obstacles, hitting again and again at one instant, each hit slower than
//! the last.
//!
//! Such a sequence converges (every hit takes energy out of the approach
//! it stops) but never ends: a disc sliding into a wedge of two plastic
//! walls bounces from one to the other, its speed shrinking by the cosine
//! of the angle each time; a striker pressing a cluster into a wall does
//! the same over many contacts. Its limit is the plastic impact of all the
//! touching contacts at once: the velocities nearest to the ones before
//! (in kinetic energy, so momentum and the centre of mass are kept where
//! no obstacle takes part) at which no contact approaches. `plastic`
//! computes it by projected Gauss–Seidel on the contact impulses (each
//! impulse a push, never a pull), which is the same sequence of hits run
//! in memory until it has converged to rounding.

use glam::DVec2;
use std::cmp::Ordering;

mod factored;

pub(crate) use factored::active_set as factored_active_set;

/// A touching contact: disc `a` against disc `b`, or against an obstacle
/// (`b` is `None`); `n` is the unit normal pointing from `b` (or the
/// obstacle) to `a`; `bias` the speed at which the two must part at least
/// (zero for a plastic contact; a pressed pair's bounce speed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Contact {
    pub a: usize,
    pub b: Option<usize>,
    pub n: DVec2,
    pub bias: f64,
}

impl Contact {
    /// A plastic contact (no bias).
    pub(crate) fn plastic(a: usize, b: Option<usize>, n: DVec2) -> Self {
        Contact { a, b, n, bias: 0.0 }
    }
}

/// Speed, as a fraction of the fastest before the collapse, under which a
/// disc after it is at rest.
pub(crate) const REST: f64 = 1e-12;

/// A speed (m/s) under which a disc after a collapse is at rest whatever
/// it began with: in the 1e150 s a run may reach, it would not move 1e-50 m.
/// (A collapse that went on long enough has driven speeds this far down.)
pub(crate) const NEGLIGIBLE: f64 = 1e-200;

/// Sweeps over the contacts at most (each sweep is one hit per contact).
pub(crate) const MAX_SWEEPS: usize = 10_000;

/// The velocities `vel` (of discs with inverse masses `inv_mass`) after a
/// plastic impact of every contact at once: no contact approaches faster
/// than `1e-15` of the fastest speed (or, with a bias, parts slower than
/// its bias by that much). `None` if the impulses have not
/// converged within [`MAX_SWEEPS`] (the caller keeps the velocities).
pub(crate) fn plastic(vel: &[DVec2], inv_mass: &[f64], contacts: &[Contact]) -> Option<Vec<DVec2>> {
    project(vel, inv_mass, contacts, MAX_SWEEPS, false)
}

/// Sweeps of projected Gauss–Seidel between two tries of the exact
/// solution on the contacts that push (see [`resolve`]).
const BLOCK: usize = 8;

/// Most contacts pushing at once that [`resolve`] solves exactly (a dense
/// elimination, cubic in their number).
const MAX_EXACT: usize = 64;

/// Rounding allowed in the exact solution, per contact pushing, as a
/// fraction of the largest velocity change (a few units in the last place).
const EXACT_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// As [`plastic`] (the engine's third revision on), within `sweeps`
/// sweeps, and for contacts with biases too (the pressing kick of a
/// cluster). Projected Gauss–Seidel alone converges slowly where a light
/// disc sits between heavy ones or walls (each sweep moves mostly the light
/// one), and stalls once the heavy one's share of a hit falls below the
/// rounding of its velocity; so every [`BLOCK`] sweeps the contacts that
/// push so far are solved exactly as equalities, and that answer is taken
/// if every impulse is a push and no other contact is left approaching.
pub(crate) fn resolve(
    vel: &[DVec2],
    inv_mass: &[f64],
    contacts: &[Contact],
    sweeps: usize,
) -> Option<Vec<DVec2>> {
    project(vel, inv_mass, contacts, sweeps, true)
}

/// Up to `sweeps` sweeps of projected Gauss–Seidel, trying the exact
/// solution every [`BLOCK`] of them if `exact` (see [`resolve`]).
fn project(
    vel: &[DVec2],
    inv_mass: &[f64],
    contacts: &[Contact],
    sweeps: usize,
    exact: bool,
) -> Option<Vec<DVec2>> {
    let mut solver = match Solver::new(vel, inv_mass, contacts) {
        Ok(s) => s,
        Err(known) => return Some(known),
    };
    for k in 0..sweeps {
        solver.sweep();
        if !solver.violated() || (exact && k % BLOCK == BLOCK - 1 && solver.exact()) {
            return Some(solver.finish());
        }
    }
    None
}

/// From the engine's ninth revision, the same limit as [`resolve`] by an
/// active-set method (Lawson and Hanson's, for non-negative least squares):
/// the plastic limit is the velocities of least kinetic energy that
/// non-negative contact impulses reach, and the method adds the contact
/// approaching fastest to the set of those pushing, solves that set
/// exactly, and drops from it any whose impulse would turn into a pull,
/// until none approaches. A contact that depends on those pushing already
/// (a packed pile on a line has more contacts than its discs can move
/// independently) approaches by no more than their rounding once they are
/// solved; where that rounding still lets it join, the set's solve is
/// singular and the contact is left out for good (the answer is checked
/// against every contact at the end). Where projected Gauss–Seidel
/// stalls on such a pile and the exact solve of its pushing contacts is
/// singular, this finds the limit in as many steps as contacts push.
/// `None` where a solve is singular anyway, or the answer leaves a contact
/// approaching beyond rounding.
pub(crate) fn active_set(
    vel: &[DVec2],
    inv_mass: &[f64],
    contacts: &[Contact],
) -> Option<Vec<DVec2>> {
    let mut solver = match Solver::new(vel, inv_mass, contacts) {
        Ok(s) => s,
        Err(known) => return Some(known),
    };
    let k_all = contacts.len();
    let mut impulse = vec![0.0f64; k_all];
    let mut pushing: Vec<usize> = Vec::new();
    let mut dependent: Vec<usize> = Vec::new();
    let apply = |imp: &[f64]| {
        let mut v = vel.to_vec();
        for (c, &p) in contacts.iter().zip(imp) {
            if p != 0.0 {
                v[c.a] += c.n * (p * inv_mass[c.a]);
                if let Some(b) = c.b {
                    v[b] -= c.n * (p * inv_mass[b]);
                }
            }
        }
        v
    };
    for _ in 0..3 * k_all + 8 {
        let v = apply(&impulse);
        // The contact approaching fastest (or parting slowest under its
        // bias) beyond the tolerance, not pushing yet.
        let next = (0..k_all)
            .filter(|k| !pushing.contains(k) && !dependent.contains(k))
            .map(|k| (k, contacts[k].bias - solver.normal(&v, &contacts[k])))
            .filter(|&(_, w)| w > solver.tolerance)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        let Some((j, _)) = next else {
            return solver.accept(v, &pushing, &impulse);
        };
        pushing.push(j);
        // Solve the pushing set; step back where an impulse would pull.
        for _ in 0..k_all + 1 {
            let Some(z) = solver.equalities(&pushing) else {
                // The contact just added depends on those pushing (it
                // approaches by their rounding only): left out, for good.
                pushing.retain(|&k| k != j);
                dependent.push(j);
                break;
            };
            if z.iter().all(|&p| p > 0.0) {
                for (&k, &p) in pushing.iter().zip(&z) {
                    impulse[k] = p;
                }
                break;
            }
            // The contact just added would not push at all (rounding let
            // it join): left out, for good.
            if pushing
                .iter()
                .zip(&z)
                .any(|(&k, &p)| k == j && impulse[k] == 0.0 && p <= 0.0)
            {
                pushing.retain(|&k| k != j);
                dependent.push(j);
                break;
            }
            // Every other contact of the set pushes: step towards `z` as
            // far as they all still do.
            let mut step = 1.0f64;
            for (&k, &p) in pushing.iter().zip(&z) {
                let fall = impulse[k] - p;
                if p <= 0.0 && fall > 0.0 {
                    step = step.min(impulse[k] / fall);
                }
            }
            for (&k, &p) in pushing.iter().zip(&z) {
                impulse[k] += step * (p - impulse[k]);
            }
            for &k in &pushing {
                if impulse[k] <= 0.0 {
                    impulse[k] = 0.0;
                }
            }
            pushing.retain(|&k| impulse[k] > 0.0);
            if pushing.is_empty() {
                break;
            }
        }
    }
    None
}

/// Projected Gauss–Seidel on the contact impulses.
struct Solver<'a> {
    vel: &'a [DVec2],
    inv_mass: &'a [f64],
    contacts: &'a [Contact],
    v: Vec<DVec2>,
    scale: f64,
    tolerance: f64,
    /// Accumulated impulse of each contact.
    impulse: Vec<f64>,
    /// What a sweep reads of each contact, side by side.
    links: Vec<Link>,
    /// The rows of the contacts' equalities (see [`Rows`]).
    rows: Rows,
    /// The augmented matrix of the last system solved, kept for its
    /// allocation.
    system: Vec<f64>,
    /// The last set of pushing contacts whose exact solution
    /// [`Solver::exact`] rejected: the answer depends on the set alone, so
    /// the same set is rejected again without a solve (a stalled
    /// projection keeps the same contacts pushing for thousands of
    /// sweeps).
    rejected: Vec<usize>,
    /// The contact [`Solver::violated`] found violated last.
    last_violated: usize,
}

/// A contact as [`Solver::sweep`] reads it: the discs' indices (`b`
/// unused against an obstacle, `wall`), and the normal, bias, effective
/// inverse mass and each disc's inverse mass.
#[derive(Clone, Copy, Debug)]
struct Link {
    a: usize,
    b: usize,
    wall: bool,
    n: DVec2,
    bias: f64,
    weight: f64,
    inv_a: f64,
    inv_b: f64,
}

/// Each contact's row of the equalities (its normal velocity's change per
/// unit impulse of every contact, then the change that parts it at its
/// bias), computed the first time the contact takes part in a solve and
/// copied from then on: every solve of a collapse draws its rows from the
/// same contacts.
struct Rows {
    /// Where each contact's row starts in `values` (`NONE`: not yet).
    start: Vec<usize>,
    /// The rows computed, `contacts + 1` values each.
    values: Vec<f64>,
}

impl Rows {
    const NONE: usize = usize::MAX;

    fn new(contacts: usize) -> Self {
        Rows {
            start: vec![Self::NONE; contacts],
            values: Vec::new(),
        }
    }
}

impl<'a> Solver<'a> {
    /// `Err(velocities)` where the answer is known at once.
    fn new(
        vel: &'a [DVec2],
        inv_mass: &'a [f64],
        contacts: &'a [Contact],
    ) -> Result<Solver<'a>, Vec<DVec2>> {
        // The largest coordinate, not the length: squares of tiny speeds underflow.
        let scale = vel
            .iter()
            .map(|u| u.abs().max_element())
            .fold(0.0, f64::max);
        if contacts.is_empty() || scale == 0.0 || !scale.is_finite() {
            return Err(vel.to_vec());
        }
        if scale <= NEGLIGIBLE {
            return Err(vec![DVec2::ZERO; vel.len()]);
        }
        Ok(Solver {
            vel,
            inv_mass,
            contacts,
            v: vel.to_vec(),
            scale,
            tolerance: 1e-15 * scale,
            impulse: vec![0.0f64; contacts.len()],
            links: contacts
                .iter()
                .map(|c| Link {
                    a: c.a,
                    b: c.b.unwrap_or(c.a),
                    wall: c.b.is_none(),
                    n: c.n,
                    bias: c.bias,
                    weight: inv_mass[c.a] + c.b.map_or(0.0, |b| inv_mass[b]),
                    inv_a: inv_mass[c.a],
                    inv_b: c.b.map_or(0.0, |b| inv_mass[b]),
                })
                .collect(),
            rows: Rows::new(contacts.len()),
            system: Vec::new(),
            rejected: Vec::new(),
            last_violated: 0,
        })
    }

    /// The normal velocity of contact `c` (positive: parting).
    fn normal(&self, v: &[DVec2], c: &Contact) -> f64 {
        (v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b])).dot(c.n)
    }

    /// One hit per contact.
    fn sweep(&mut self) {
        for (l, impulse) in self.links.iter().zip(&mut self.impulse) {
            let other = if l.wall { DVec2::ZERO } else { self.v[l.b] };
            let rel = self.v[l.a] - other;
            let approach = l.bias - rel.dot(l.n);
            // A contact that does not push and does not approach stays so:
            // with a positive weight the quotient is at most zero (or NaN),
            // the sum with a zero impulse too, and its `max` with zero and
            // the difference from the impulse are zeros, `delta == 0.0`.
            // Skipping the division here changes no value.
            if *impulse == 0.0 && !(approach > 0.0) && l.weight > 0.0 {
                continue;
            }
            let next = (*impulse + approach / l.weight).max(0.0);
            let delta = next - *impulse;
            if delta == 0.0 {
                continue;
            }
            *impulse = next;
            self.v[l.a] += l.n * (delta * l.inv_a);
            if !l.wall {
                self.v[l.b] -= l.n * (delta * l.inv_b);
            }
        }
    }

    /// Whether a contact still approaches (or parts slower than its bias)
    /// beyond the tolerance (impulses are never negative: none pulls). The
    /// contact found last is asked first: while the projection stalls it
    /// is the same sweep after sweep (the answer does not depend on the
    /// order of asking).
    fn violated(&mut self) -> bool {
        let violates = |c: &Contact| self.normal(&self.v, c) < c.bias - self.tolerance;
        if self.contacts.get(self.last_violated).is_some_and(violates) {
            return true;
        }
        match self.contacts.iter().position(violates) {
            Some(k) => {
                self.last_violated = k;
                true
            }
            None => false,
        }
    }

    /// Solves the contacts whose impulse is a push so far as equalities
    /// (Gaussian elimination with partial pivoting); keeps that answer and
    /// returns `true` if every impulse is a push and no contact is
    /// violated.
    fn exact(&mut self) -> bool {
        let active: Vec<usize> = (0..self.contacts.len())
            .filter(|&k| self.impulse[k] > 0.0)
            .collect();
        let m = active.len();
        if m == 0 || m > MAX_EXACT || active == self.rejected {
            return false;
        }
        let accepted = self.try_exact(&active);
        if !accepted {
            self.rejected = active;
        }
        accepted
    }

    /// [`Solver::exact`] for the contacts `active`: a function of the set
    /// alone (and of the velocities before), which changes nothing unless
    /// it returns `true`.
    fn try_exact(&mut self, active: &[usize]) -> bool {
        let m = active.len();
        let Some(x) = self.equalities(active) else {
            return false;
        };
        if x.iter().any(|&p| !(p >= 0.0)) {
            return false;
        }
        let mut v = self.vel.to_vec();
        // The largest velocity change: a light disc jammed between heavy
        // ones and walls takes impulses whose changes cancel, leaving their
        // rounding as its velocity.
        let mut change: f64 = 0.0;
        for (&k, &p) in active.iter().zip(&x) {
            let c = &self.contacts[k];
            v[c.a] += c.n * (p * self.inv_mass[c.a]);
            change = change.max(p * self.inv_mass[c.a]);
            if let Some(b) = c.b {
                v[b] -= c.n * (p * self.inv_mass[b]);
                change = change.max(p * self.inv_mass[b]);
            }
        }
        let tolerance = self.tolerance.max(EXACT_ROUNDING * m as f64 * change);
        if self
            .contacts
            .iter()
            .any(|c| self.normal(&v, c) < c.bias - tolerance)
        {
            return false;
        }
        self.v = v;
        true
    }

    /// The impulses of the contacts `set` (indices) solved as equalities
    /// (each contact parting at its bias) from the velocities before;
    /// `None` if that system is singular to rounding.
    fn equalities(&mut self, set: &[usize]) -> Option<Vec<f64>> {
        let k_all = self.contacts.len();
        for &k in set {
            if self.rows.start[k] == Rows::NONE {
                self.rows.start[k] = self.rows.values.len();
                let ck = &self.contacts[k];
                for cq in self.contacts {
                    let e = self.effect(ck, cq);
                    self.rows.values.push(e);
                }
                let rhs = ck.bias - self.normal(self.vel, ck);
                self.rows.values.push(rhs);
            }
        }
        let m = set.len();
        let mut a = std::mem::take(&mut self.system);
        a.clear();
        for &k in set {
            let row = &self.rows.values[self.rows.start[k]..][..k_all + 1];
            a.extend(set.iter().map(|&q| row[q]));
            a.push(row[k_all]);
        }
        let x = solve(&mut a, m);
        self.system = a;
        x
    }

    /// The change of contact `k`'s normal velocity per unit impulse of
    /// contact `l`.
    fn effect(&self, k: &Contact, l: &Contact) -> f64 {
        let mut w = 0.0;
        if k.a == l.a {
            w += self.inv_mass[l.a];
        }
        if k.b == Some(l.a) {
            w -= self.inv_mass[l.a];
        }
        if let Some(lb) = l.b {
            if k.a == lb {
                w -= self.inv_mass[lb];
            }
            if k.b == Some(lb) {
                w += self.inv_mass[lb];
            }
        }
        w * k.n.dot(l.n)
    }

    /// The velocities `v` that the impulses `impulse` of the contacts
    /// `set` reach, where no contact is left approaching beyond the
    /// rounding of those impulses (as [`Solver::exact`] checks), with what
    /// is left slower than rounding stopped (see [`Solver::finish`]).
    fn accept(mut self, v: Vec<DVec2>, set: &[usize], impulse: &[f64]) -> Option<Vec<DVec2>> {
        let change = set
            .iter()
            .map(|&k| {
                let c = &self.contacts[k];
                let b = c.b.map_or(0.0, |b| self.inv_mass[b]);
                impulse[k] * self.inv_mass[c.a].max(b)
            })
            .fold(0.0, f64::max);
        let tolerance = self
            .tolerance
            .max(EXACT_ROUNDING * set.len() as f64 * change);
        if !change.is_finite() || v.iter().any(|u| !u.is_finite()) {
            return None;
        }
        if self
            .contacts
            .iter()
            .any(|c| self.normal(&v, c) < c.bias - tolerance)
        {
            return None;
        }
        self.v = v;
        Some(self.finish())
    }

    /// The velocities, with what the collapse left moving slower than
    /// rounding of the speeds it began with stopped (a disc in a plastic
    /// wedge).
    fn finish(mut self) -> Vec<DVec2> {
        for u in &mut self.v {
            if u.abs().max_element() <= (REST * self.scale).max(NEGLIGIBLE) {
                *u = DVec2::ZERO;
            }
        }
        self.v
    }
}

/// Solves the `m` equations of the augmented row-major matrix `a`
/// (`m` rows of `m + 1`) by Gaussian elimination with partial pivoting;
/// `None` if it is singular to rounding. The pivot is the last of the
/// largest magnitudes in its column (as `Iterator::max_by` under
/// `f64::total_cmp` picks), and every value read later is computed by
/// the same operations in the same order as a textbook loop over the
/// indices (the reference in the tests), to the bit: the loops run over
/// slices only, so they carry no bounds checks.
fn solve(a: &mut [f64], m: usize) -> Option<Vec<f64>> {
    let w = m + 1;
    if a.len() != m * w {
        return None;
    }
    let size = a.iter().fold(0.0f64, |x, y| x.max(y.abs()));
    for col in 0..m {
        let mut pivot = col;
        let mut largest = a[col * w + col].abs();
        for (r, row) in a.chunks_exact(w).enumerate().skip(col + 1) {
            let e = row[col].abs();
            if e.total_cmp(&largest) != Ordering::Less {
                (pivot, largest) = (r, e);
            }
        }
        if !(largest > 1e-12 * size) {
            return None;
        }
        let (above, below) = a.split_at_mut((col + 1) * w);
        let top = &mut above[col * w..];
        if pivot != col {
            top.swap_with_slice(&mut below[(pivot - col - 1) * w..][..w]);
        }
        let top = &top[col..];
        let d = top[0];
        for row in below.chunks_exact_mut(w) {
            let f = row[col] / d;
            if f != 0.0 {
                // The entry in the pivot's column is never read again.
                for (x, &p) in row[col + 1..].iter_mut().zip(&top[1..]) {
                    *x -= f * p;
                }
            }
        }
    }
    let mut x = vec![0.0; m];
    for r in (0..m).rev() {
        let row = &a[r * w..][..w];
        let mut sum = row[m];
        for (&e, &y) in row[r + 1..m].iter().zip(&x[r + 1..]) {
            sum -= e * y;
        }
        x[r] = sum / row[r];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// The solve as it was before the rows were cached: the matrix built
    /// from `effect` afresh, eliminated by the index loops with
    /// `Iterator::max_by` picking the pivot. The reference the solve is
    /// held to, bit for bit.
    fn reference_equalities(s: &Solver, set: &[usize]) -> Option<Vec<f64>> {
        let m = set.len();
        let mut a = vec![0.0f64; m * (m + 1)];
        for (r, &kr) in set.iter().enumerate() {
            let ck = &s.contacts[kr];
            for (q, &kq) in set.iter().enumerate() {
                a[r * (m + 1) + q] = s.effect(ck, &s.contacts[kq]);
            }
            a[r * (m + 1) + m] = ck.bias - s.normal(s.vel, ck);
        }
        reference_solve(&mut a, m)
    }

    fn reference_solve(a: &mut [f64], m: usize) -> Option<Vec<f64>> {
        let w = m + 1;
        let size = a.iter().fold(0.0f64, |x, y| x.max(y.abs()));
        for col in 0..m {
            let pivot =
                (col..m).max_by(|&x, &y| a[x * w + col].abs().total_cmp(&a[y * w + col].abs()))?;
            if !(a[pivot * w + col].abs() > 1e-12 * size) {
                return None;
            }
            if pivot != col {
                for q in 0..w {
                    a.swap(pivot * w + q, col * w + q);
                }
            }
            for r in col + 1..m {
                let f = a[r * w + col] / a[col * w + col];
                if f != 0.0 {
                    for q in col..w {
                        a[r * w + q] -= f * a[col * w + q];
                    }
                }
            }
        }
        let mut x = vec![0.0; m];
        for r in (0..m).rev() {
            let mut sum = a[r * w + m];
            for q in r + 1..m {
                sum -= a[r * w + q] * x[q];
            }
            x[r] = sum / a[r * w + r];
        }
        Some(x)
    }

    /// The sweep as it was before it skipped the division of contacts
    /// that neither push nor approach.
    fn reference_sweep(s: &mut Solver) {
        for (k, c) in s.contacts.iter().enumerate() {
            let rel = s.v[c.a] - c.b.map_or(DVec2::ZERO, |b| s.v[b]);
            let approach = c.bias - rel.dot(c.n);
            let weight = s.inv_mass[c.a] + c.b.map_or(0.0, |b| s.inv_mass[b]);
            let next = (s.impulse[k] + approach / weight).max(0.0);
            let delta = next - s.impulse[k];
            if delta == 0.0 {
                continue;
            }
            s.impulse[k] = next;
            s.v[c.a] += c.n * (delta * s.inv_mass[c.a]);
            if let Some(b) = c.b {
                s.v[b] -= c.n * (delta * s.inv_mass[b]);
            }
        }
    }

    /// `project` as it was before `exact` remembered the set it rejected
    /// last and `violated` the contact it found (and with the sweep
    /// above).
    fn reference_project(
        vel: &[DVec2],
        inv_mass: &[f64],
        contacts: &[Contact],
        sweeps: usize,
    ) -> Option<Vec<DVec2>> {
        let mut s = match Solver::new(vel, inv_mass, contacts) {
            Ok(s) => s,
            Err(known) => return Some(known),
        };
        for k in 0..sweeps {
            reference_sweep(&mut s);
            let violated = s
                .contacts
                .iter()
                .any(|c| s.normal(&s.v, c) < c.bias - s.tolerance);
            if !violated {
                return Some(s.finish());
            }
            if k % BLOCK == BLOCK - 1 {
                let active: Vec<usize> = (0..contacts.len())
                    .filter(|&k| s.impulse[k] > 0.0)
                    .collect();
                if !active.is_empty() && active.len() <= MAX_EXACT && s.try_exact(&active) {
                    return Some(s.finish());
                }
            }
        }
        None
    }

    /// A contact system shaped like the engine's: `shape` 0 a chain of
    /// discs on a line (turned at random or not) between two walls, 1 a
    /// hexagonal pile on a floor between walls, 2 contacts at random among
    /// a few discs; masses over six decades, some contacts given twice,
    /// some biased, some discs still.
    fn system(rng: &mut Rng, shape: u64) -> (Vec<DVec2>, Vec<f64>, Vec<Contact>) {
        let turn = if rng.chance(0.5) {
            DVec2::X
        } else {
            rng.direction()
        };
        let mut contacts = Vec::new();
        let n;
        match shape {
            0 => {
                n = 2 + rng.below(30) as usize;
                let along = turn.rotate(DVec2::NEG_X);
                for i in 0..n - 1 {
                    contacts.push(Contact::plastic(i, Some(i + 1), along));
                }
                contacts.push(Contact::plastic(0, None, -along));
                if rng.chance(0.7) {
                    contacts.push(Contact::plastic(n - 1, None, along));
                }
            }
            1 => {
                let rows = 2 + rng.below(6) as usize;
                let mut at = Vec::new();
                for r in 0..rows {
                    for i in 0..rows - r {
                        at.push(DVec2::new(
                            i as f64 + 0.5 * r as f64,
                            r as f64 * 0.75f64.sqrt(),
                        ));
                    }
                }
                n = at.len();
                for a in 0..n {
                    for b in 0..n {
                        let d = at[a] - at[b];
                        if a != b
                            && (d.length() - 1.0).abs() < 1e-9
                            && d.y >= 0.0
                            && (d.y > 0.0 || d.x > 0.0)
                        {
                            contacts.push(Contact::plastic(a, Some(b), turn.rotate(d.normalize())));
                        }
                    }
                    if at[a].y == 0.0 {
                        contacts.push(Contact::plastic(a, None, turn.rotate(DVec2::Y)));
                    }
                }
                contacts.push(Contact::plastic(0, None, turn.rotate(DVec2::X)));
                contacts.push(Contact::plastic(rows - 1, None, turn.rotate(DVec2::NEG_X)));
            }
            _ => {
                n = 1 + rng.below(8) as usize;
                for _ in 0..1 + rng.below(20) {
                    let a = rng.below(n as u64) as usize;
                    let b = rng.below(n as u64 + 1) as usize;
                    let normal = if rng.chance(0.3) {
                        turn
                    } else {
                        rng.direction()
                    };
                    let b = (b < n && b != a).then_some(b);
                    contacts.push(Contact::plastic(a, b, normal));
                }
            }
        }
        for _ in 0..rng.below(3) {
            let k = rng.below(contacts.len() as u64) as usize;
            contacts.push(contacts[k]);
        }
        for c in &mut contacts {
            if rng.chance(0.1) {
                c.bias = rng.log_range(1e-6, 1.0);
            }
        }
        let inv = (0..n).map(|_| rng.log_range(1e-3, 1e3)).collect();
        let vel = (0..n)
            .map(|_| {
                if rng.chance(0.3) {
                    DVec2::ZERO
                } else {
                    rng.direction() * rng.log_range(1e-6, 10.0)
                }
            })
            .collect();
        (vel, inv, contacts)
    }

    fn same_bits(x: &Option<Vec<f64>>, y: &Option<Vec<f64>>) -> bool {
        match (x, y) {
            (None, None) => true,
            (Some(x), Some(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
            }
            _ => false,
        }
    }

    fn same_vectors(x: &[DVec2], y: &[DVec2]) -> bool {
        x.len() == y.len()
            && x.iter()
                .zip(y)
                .all(|(p, q)| p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits())
    }

    #[test]
    fn the_cached_solve_matches_the_reference_to_the_bit_on_chains_piles_and_random_systems() {
        let mut rng = Rng::splitmix64(0xC011_A95E);
        let (mut solved, mut singular, mut signed_zeros) = (0, 0, 0);
        for case in 0..3000 {
            let (vel, inv, contacts) = system(&mut rng, case % 3);
            let Ok(mut solver) = Solver::new(&vel, &inv, &contacts) else {
                continue;
            };
            let k_all = contacts.len();
            // One solver for every set, as a collapse uses it: rows
            // computed for one set are copied into the next.
            for _ in 0..12 {
                let mut set: Vec<usize> = (0..k_all).filter(|_| rng.chance(0.6)).collect();
                if set.is_empty() {
                    set.push(rng.below(k_all as u64) as usize);
                }
                for i in (1..set.len()).rev() {
                    set.swap(i, rng.below(i as u64 + 1) as usize);
                }
                let new = solver.equalities(&set);
                let old = reference_equalities(&solver, &set);
                assert!(
                    same_bits(&new, &old),
                    "case {case}, set {set:?}: {new:?} against {old:?}"
                );
                match &new {
                    Some(x) => {
                        solved += 1;
                        signed_zeros += x
                            .iter()
                            .filter(|p| **p == 0.0 && p.is_sign_negative())
                            .count();
                    }
                    None => singular += 1,
                }
            }
        }
        // Both outcomes, and answers with -0.0 in them, were compared.
        assert!(
            solved > 1000 && singular > 1000,
            "{solved} solved, {singular} singular"
        );
        assert!(signed_zeros > 0, "no -0.0 among the answers");
    }

    #[test]
    fn the_solve_picks_the_last_of_equal_pivots_as_max_by_does() {
        // Columns whose largest magnitudes tie, with both signs: the pivot
        // row decides the rounding of every later step.
        let mut rng = Rng::splitmix64(7);
        for _ in 0..2000 {
            let m = 1 + rng.below(7) as usize;
            let pick = [-2.0, -1.0, -0.0, 0.0, 1.0, 2.0, 3.0];
            let mut a: Vec<f64> = (0..m * (m + 1))
                .map(|_| {
                    if rng.chance(0.7) {
                        pick[rng.below(pick.len() as u64) as usize]
                    } else {
                        rng.symmetric()
                    }
                })
                .collect();
            let mut b = a.clone();
            let new = solve(&mut a, m);
            let old = reference_solve(&mut b, m);
            assert!(same_bits(&new, &old), "{new:?} against {old:?}");
        }
    }

    #[test]
    fn the_projection_matches_the_reference_to_the_bit() {
        let mut rng = Rng::splitmix64(0x5EED);
        let mut stalled = 0;
        for case in 0..1500 {
            let (vel, inv, contacts) = system(&mut rng, case % 3);
            let sweeps = [8, 64, 400][case as usize % 3];
            let new = resolve(&vel, &inv, &contacts, sweeps);
            let old = reference_project(&vel, &inv, &contacts, sweeps);
            match (&new, &old) {
                (None, None) => stalled += 1,
                (Some(x), Some(y)) => {
                    assert!(same_vectors(x, y), "case {case}: {x:?} against {y:?}")
                }
                _ => panic!("case {case}: {new:?} against {old:?}"),
            }
            let mut a = Solver::new(&vel, &inv, &contacts);
            let mut b = Solver::new(&vel, &inv, &contacts);
            if let (Ok(a), Ok(b)) = (&mut a, &mut b) {
                for _ in 0..20 {
                    a.sweep();
                    reference_sweep(b);
                    assert!(same_vectors(&a.v, &b.v), "case {case}");
                    assert!(same_bits(
                        &Some(a.impulse.clone()),
                        &Some(b.impulse.clone())
                    ));
                }
            }
        }
        assert!(stalled > 0, "no projection stalled");
    }

    #[test]
    fn the_factored_active_set_reaches_the_eliminating_ones_limit_on_chains_piles_and_random_systems(
    ) {
        let mut rng = Rng::splitmix64(0xFAC7_0BED);
        let (mut both, mut neither) = (0, 0);
        for case in 0..3000 {
            let (vel, inv, contacts) = system(&mut rng, case % 3);
            let old = active_set(&vel, &inv, &contacts);
            let new = factored_active_set(&vel, &inv, &contacts);
            match (&old, &new) {
                (Some(x), Some(y)) => {
                    both += 1;
                    let scale = vel.iter().map(|u| u.length()).fold(0.0, f64::max);
                    let change = x.iter().chain(y).map(|u| u.length()).fold(scale, f64::max);
                    for (p, q) in x.iter().zip(y) {
                        assert!(
                            (*p - *q).length() <= 1e-6 * change,
                            "case {case}: {x:?} against {y:?}"
                        );
                    }
                }
                (None, None) => neither += 1,
                // Rounding may decide a contact's dependence either way.
                _ => {}
            }
            if let (Some(y), false) = (&new, contacts.iter().any(|c| c.bias > 0.0)) {
                let energy = |v: &[DVec2]| -> f64 {
                    v.iter()
                        .zip(&inv)
                        .map(|(u, m)| u.length_squared() / m)
                        .sum()
                };
                assert!(
                    energy(y) <= energy(&vel) * (1.0 + 1e-12) + 1e-30,
                    "case {case}: energy gained"
                );
            }
        }
        assert!(both > 1500, "{both} solved by both, {neither} by neither");
    }

    #[test]
    fn the_factored_active_set_stops_a_pile_struck_from_above_as_the_eliminating_one_does() {
        // A hexagonal pile of 28 discs on a floor between walls (84
        // contacts, many dependent), its top disc driven down.
        let mut rng = Rng::splitmix64(11);
        let mut compared = 0;
        for _ in 0..40 {
            let (mut vel, inv, contacts) = loop {
                let (vel, inv, contacts) = system(&mut rng, 1);
                if vel.len() >= 21 {
                    break (vel, inv, contacts);
                }
            };
            let top = vel.len() - 1;
            for u in &mut vel[..top] {
                *u = DVec2::ZERO;
            }
            vel[top] = DVec2::new(0.3, -2.0);
            if let (Some(x), Some(y)) = (
                active_set(&vel, &inv, &contacts),
                factored_active_set(&vel, &inv, &contacts),
            ) {
                compared += 1;
                for (p, q) in x.iter().zip(&y) {
                    assert!((*p - *q).length() < 2e-9, "{x:?} against {y:?}");
                }
            }
        }
        assert!(compared > 10, "{compared} compared");
    }

    #[test]
    fn a_disc_driven_into_a_plastic_wedge_stops_dead() {
        // Walls with normals at +-60 degrees from the direction of travel.
        let (c, s) = (0.5f64, 0.75f64.sqrt());
        let contacts = [
            Contact::plastic(0, None, DVec2::new(-c, s)),
            Contact::plastic(0, None, DVec2::new(-c, -s)),
        ];
        let v = plastic(&[DVec2::new(1.0, 0.3)], &[1.0], &contacts).unwrap();
        assert!(v[0].length() < 1e-14, "{v:?}");
    }

    #[test]
    fn a_disc_sliding_out_of_a_wedge_is_left_alone() {
        let contacts = [Contact::plastic(0, None, DVec2::Y)];
        let v = plastic(&[DVec2::new(1.0, 0.5)], &[1.0], &contacts).unwrap();
        assert_eq!(v[0], DVec2::new(1.0, 0.5));
    }

    #[test]
    fn a_plastic_impact_between_discs_keeps_momentum_and_stops_the_approach() {
        // Disc 0 runs into disc 1, which touches disc 2 obliquely.
        let n01 = DVec2::new(-1.0, 0.0);
        let n12 = DVec2::new(-0.6, -0.8);
        let contacts = [
            Contact::plastic(0, Some(1), n01),
            Contact::plastic(1, Some(2), n12),
        ];
        let (m, inv) = ([1.0, 2.0, 3.0], [1.0, 0.5, 1.0 / 3.0]);
        let vel = [DVec2::new(2.0, 0.0), DVec2::ZERO, DVec2::ZERO];
        let v = plastic(&vel, &inv, &contacts).unwrap();
        let p: DVec2 = (0..3).map(|k| v[k] * m[k]).sum();
        assert!((p - DVec2::new(2.0, 0.0)).length() < 1e-14, "{p}");
        for c in &contacts {
            let rel = v[c.a] - v[c.b.unwrap()];
            assert!(rel.dot(c.n) >= -1e-14, "{v:?}");
        }
        let energy = |v: &[DVec2]| (0..3).map(|k| m[k] * v[k].length_squared()).sum::<f64>();
        assert!(energy(&v) < energy(&vel));
    }

    #[test]
    fn a_light_disc_jammed_between_walls_and_a_heavy_one_stops_dead_at_once() {
        // A heavy disc drives a light one into a corner post and a wall:
        // Gauss-Seidel alone stalls on rounding (each sweep moves mostly the
        // light disc); the exact solve on the pushing contacts ends it.
        let contacts = [
            Contact::plastic(
                0,
                Some(1),
                DVec2::new(-0.7380744299894785, -0.6747193014844813),
            ),
            Contact::plastic(1, None, DVec2::new(0.0, -1.0)),
            Contact::plastic(1, None, DVec2::new(-0.8081542333247913, 0.5889709119805651)),
        ];
        let vel = [DVec2::new(0.6586, -0.3144), DVec2::new(0.1288, 0.1767)];
        let inv = [1.0 / 1.107, 1.0 / 0.006656];
        assert_eq!(plastic(&vel, &inv, &contacts), None);
        let v = resolve(&vel, &inv, &contacts, 64).unwrap();
        assert_eq!(v[1], DVec2::ZERO);
        let rel = v[0] - v[1];
        // Parted to the rounding of the impulses (45 m/s of changes on the
        // light disc cancel).
        assert!(rel.dot(contacts[0].n).abs() < 1e-12, "{v:?}");
    }

    #[test]
    fn the_active_set_limit_of_redundant_contacts_is_the_plastic_limit() {
        // A disc driven down onto two others that rest on a floor, every
        // contact given twice: the exact solve of the doubled contacts is
        // singular, the active-set method takes each once.
        let (c, s) = (0.5f64, 0.75f64.sqrt());
        let mut contacts = vec![
            Contact::plastic(0, Some(1), DVec2::new(c, s)),
            Contact::plastic(0, Some(2), DVec2::new(-c, s)),
            Contact::plastic(1, None, DVec2::Y),
            Contact::plastic(2, None, DVec2::Y),
        ];
        contacts.extend(contacts.clone());
        let vel = [DVec2::new(0.3, -2.0), DVec2::ZERO, DVec2::ZERO];
        let inv = [1.0, 2.0, 0.5];
        let v = active_set(&vel, &inv, &contacts).unwrap();
        let projected = plastic(&vel, &inv, &contacts[..4]).unwrap();
        for (a, b) in v.iter().zip(&projected) {
            assert!((*a - *b).length() < 1e-12, "{v:?} against {projected:?}");
        }
        for c in &contacts {
            let rel = v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b]);
            assert!(rel.dot(c.n) >= -1e-15, "{v:?}");
        }
        let energy = |v: &[DVec2]| (0..3).map(|k| v[k].length_squared() / inv[k]).sum::<f64>();
        assert!(energy(&v) < energy(&vel));
    }

    #[test]
    fn a_biased_contact_parts_at_its_bias_and_pushes_what_the_disc_touches() {
        // Disc 0 presses on disc 1, which rests against disc 2 along the
        // same line: to part 0 and 1 at 0.01 m/s, 1 must push 2 as well.
        let mut kick = Contact::plastic(0, Some(1), DVec2::new(-1.0, 0.0));
        kick.bias = 0.01;
        let contacts = [kick, Contact::plastic(1, Some(2), DVec2::new(-1.0, 0.0))];
        let (m, inv) = ([1.0, 0.01, 1.0], [1.0, 100.0, 1.0]);
        let vel = [DVec2::new(0.1, 0.2); 3];
        let v = resolve(&vel, &inv, &contacts, 64).unwrap();
        let part = (v[0] - v[1]).dot(DVec2::new(-1.0, 0.0));
        assert!((part - 0.01).abs() < 1e-15, "{v:?}");
        assert!((v[1] - v[2]).dot(DVec2::new(-1.0, 0.0)) >= -1e-15, "{v:?}");
        let p: DVec2 = (0..3).map(|k| v[k] * m[k]).sum();
        assert!((p - DVec2::new(0.1, 0.2) * 2.01).length() < 1e-14, "{p}");
    }
}
