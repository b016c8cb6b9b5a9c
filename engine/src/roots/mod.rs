//! Real roots of polynomials of degree at most four: the contact-time solver
//! of the event-driven engine. This module owns the result type [`Roots`],
//! the [`RootSolver`] trait, the three methods behind it ([`Bisection`], the
//! thesis's baseline; [`ClosedForm`], textbook Ferrari/Cardano; and
//! [`Production`], the fast accurate default) and the [`Method`] selector.
//!
//! Conventions shared by every method:
//! - Coefficients are lowest degree first: `c[0] + c[1] x + ... + c[4] x^4`.
//!   Slices of any length are accepted; zero high coefficients reduce the
//!   degree. The zero polynomial and non-zero constants have no roots, and
//!   so has any input with a NaN or infinite coefficient, or with a non-zero
//!   coefficient beyond degree four.
//! - Roots come back sorted ascending. A multiple root is repeated only as
//!   often as the method finds it as a distinct number: [`Production`]
//!   reports a crossing root (odd multiplicity) once and a touching root
//!   (even multiplicity, `p` and `p'` vanish within rounding) once;
//!   [`Bisection`] the same, but with plain evaluation it sees a touching
//!   root only if the extremum evaluates to exactly zero; [`ClosedForm`]
//!   returns whatever its formula branches produce (a zero discriminant
//!   gives one value, two Ferrari factors may give the same value twice).
//! - `roots_in(c, lo, hi)` returns the roots `r` with `lo <= r < hi`; `hi`
//!   (and `lo`) may be infinite; a NaN bound or `lo >= hi` gives no roots.
//! - Nothing allocates and nothing panics.
//!
//! The module depends only on `core`/`std` (its tests also use the
//! dev-dependencies `proptest` and `dashu-float`), so it can be compiled on
//! its own; `benches/roots.rs` times it against peer crates.

// Comparisons are written so that NaN falls on the safe side (`!(lo < hi)`
// rejects a NaN bound, `!(x > a && x < b)` rejects a NaN iterate): the
// negated forms are deliberate.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bisection;
#[cfg(test)]
mod cases;
mod closed_form;
#[cfg(test)]
mod first_root_props;
mod poly;
mod production;
#[cfg(test)]
mod reference;
#[cfg(test)]
mod tests;

pub use bisection::Bisection;
pub use closed_form::ClosedForm;
pub use production::Production;

/// Up to four real roots, sorted ascending.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Roots {
    /// A full word rather than a byte: the struct is padded to 40 bytes
    /// either way, and a byte store followed by the word load of a copy
    /// defeats store-to-load forwarding (a stall of about as long as a
    /// whole fast-path query).
    len: usize,
    /// Slots past `len` are always `0.0`, so the derived `PartialEq` compares
    /// only the roots.
    vals: [f64; 4],
}

impl Roots {
    /// No roots.
    pub const fn new() -> Self {
        Roots {
            len: 0,
            vals: [0.0; 4],
        }
    }

    /// The roots as a slice, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.vals[..self.len]
    }

    /// Number of roots.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there are no roots.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The smallest root.
    pub fn first(&self) -> Option<f64> {
        self.as_slice().first().copied()
    }

    /// Appends a root (ignored when four are already stored or it is not
    /// finite). Callers keep the order themselves or call [`Roots::sort`].
    fn push(&mut self, x: f64) {
        if self.len < 4 && x.is_finite() {
            self.vals[self.len] = x;
            self.len += 1;
        }
    }

    /// Keeps the first `n` roots (restoring the zeroed tail).
    fn truncate(&mut self, n: usize) {
        for i in n.min(4)..4 {
            self.vals[i] = 0.0;
        }
        self.len = self.len.min(n.min(4));
    }

    /// Sorts the roots ascending (insertion sort: at most four values).
    fn sort(&mut self) {
        let n = self.len;
        for i in 1..n {
            let mut j = i;
            while j > 0 && self.vals[j - 1] > self.vals[j] {
                self.vals.swap(j - 1, j);
                j -= 1;
            }
        }
    }

    /// The roots `r` with `lo <= r < hi`.
    fn within(&self, lo: f64, hi: f64) -> Roots {
        let mut out = Roots::new();
        for &r in self.as_slice() {
            if lo <= r && r < hi {
                out.push(r);
            }
        }
        out
    }
}

impl core::ops::Deref for Roots {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        self.as_slice()
    }
}

impl<'a> IntoIterator for &'a Roots {
    type Item = &'a f64;
    type IntoIter = core::slice::Iter<'a, f64>;
    fn into_iter(self) -> Self::IntoIter {
        self.as_slice().iter()
    }
}

/// One way of finding real roots. `real_roots` is the one required method;
/// the others have defaults built on it that a method may override for speed.
pub trait RootSolver {
    /// All real roots, ascending.
    fn real_roots(&self, coeffs: &[f64]) -> Roots;

    /// Roots r with lo <= r < hi, ascending.
    fn roots_in(&self, coeffs: &[f64], lo: f64, hi: f64) -> Roots {
        self.real_roots(coeffs).within(lo, hi)
    }

    /// The smallest root r with lo <= r < hi.
    fn first_root(&self, coeffs: &[f64], lo: f64, hi: f64) -> Option<f64> {
        self.roots_in(coeffs, lo, hi).first()
    }
}

/// Selectable method; `Default` is [`Method::Production`]. Implements
/// [`RootSolver`] by dispatching to the named solver.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Method {
    /// [`Bisection`]: the thesis's baseline.
    Bisection,
    /// [`ClosedForm`]: Ferrari / Cardano, no polishing.
    ClosedForm,
    /// [`Production`]: fast and accurate.
    #[default]
    Production,
}

impl Method {
    /// Every method, baseline first.
    pub const ALL: [Method; 3] = [Method::Bisection, Method::ClosedForm, Method::Production];

    /// A short stable name (for configuration files and reports).
    pub fn name(self) -> &'static str {
        match self {
            Method::Bisection => "bisection",
            Method::ClosedForm => "closed-form",
            Method::Production => "production",
        }
    }
}

impl RootSolver for Method {
    fn real_roots(&self, coeffs: &[f64]) -> Roots {
        match self {
            Method::Bisection => Bisection.real_roots(coeffs),
            Method::ClosedForm => ClosedForm.real_roots(coeffs),
            Method::Production => Production.real_roots(coeffs),
        }
    }

    fn roots_in(&self, coeffs: &[f64], lo: f64, hi: f64) -> Roots {
        match self {
            Method::Bisection => Bisection.roots_in(coeffs, lo, hi),
            Method::ClosedForm => ClosedForm.roots_in(coeffs, lo, hi),
            Method::Production => Production.roots_in(coeffs, lo, hi),
        }
    }

    fn first_root(&self, coeffs: &[f64], lo: f64, hi: f64) -> Option<f64> {
        match self {
            Method::Bisection => Bisection.first_root(coeffs, lo, hi),
            Method::ClosedForm => ClosedForm.first_root(coeffs, lo, hi),
            Method::Production => Production.first_root(coeffs, lo, hi),
        }
    }
}
