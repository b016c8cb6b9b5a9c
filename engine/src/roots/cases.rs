//! Test-only data: the hard-polynomial table shared by the method tests
//! (and by outside accuracy reports on peer solvers), with the accuracy
//! each method is expected to reach on every entry, and the helpers that
//! build its polynomials from roots in high precision.

use dashu_float::round::mode::HalfEven;
use dashu_float::FBig;

type F = FBig<HalfEven, 2>;

fn big(x: f64) -> F {
    F::try_from(x).unwrap().with_precision(320).value()
}

/// Coefficients (lowest degree first, rounded once to `f64`) of
/// `prod (x - r) * prod ((x - re)^2 + im^2)`, expanded in 320-bit arithmetic.
fn expand(real: &[f64], pairs: &[(f64, f64)]) -> Vec<f64> {
    let mut c = vec![big(1.0)];
    let mul = |c: &Vec<F>, f: &[F]| {
        let mut out = vec![big(0.0); c.len() + f.len() - 1];
        for (i, a) in c.iter().enumerate() {
            for (j, b) in f.iter().enumerate() {
                out[i + j] = out[i + j].clone() + a.clone() * b;
            }
        }
        out
    };
    for &r in real {
        c = mul(&c, &[-big(r), big(1.0)]);
    }
    for &(re, im) in pairs {
        let (re, im) = (big(re), big(im));
        let q = [
            re.clone() * &re + im.clone() * &im,
            -(re * big(2.0)),
            big(1.0),
        ];
        c = mul(&c, &q);
    }
    c.iter().map(|v| v.to_f64().value()).collect()
}

/// Coefficients given highest degree first (as the papers print them).
fn high_first(c: &[f64]) -> Vec<f64> {
    c.iter().rev().copied().collect()
}

/// What a method is expected to achieve on a case, measured against the
/// f64-exact reference as the larger of the two one-sided distances
/// (every returned root near a reference root and vice versa).
#[derive(Clone, Copy, Debug)]
pub enum Expect {
    /// Within this many ulps.
    Ulps(u64),
    /// Within this relative error.
    Rel(f64),
    /// Known to miss, invent or badly misplace roots here: only checked
    /// for not panicking and returning sorted finite values.
    Wrong,
}
use Expect::{Rel, Ulps, Wrong};

/// One entry of the hard table.
pub struct Case {
    pub name: &'static str,
    pub coeffs: Vec<f64>,
    pub production: Expect,
    pub closed_form: Expect,
    pub bisection: Expect,
}

impl Case {
    fn cf(mut self, e: Expect) -> Self {
        self.closed_form = e;
        self
    }
    fn bis(mut self, e: Expect) -> Self {
        self.bisection = e;
        self
    }
}

/// Defaults: Production and Bisection within 4 ulps, ClosedForm within a
/// relative 1e-13; the table overrides them case by case.
fn case(name: &'static str, coeffs: Vec<f64>) -> Case {
    Case {
        name,
        coeffs,
        production: Ulps(4),
        closed_form: Rel(1e-13),
        bisection: Ulps(4),
    }
}

/// The hard table. Sources:
/// - "A1010 n": Orellana & De Michele, "Algorithm 1010: Boosting Efficiency
///   in Solving Quartic Equations with No Compromise in Accuracy", ACM TOMS
///   46(2), Article 20 (2020), accuracy test cases 1-24 (the roots, or for
///   23-24 the coefficients, as listed with the paper's test driver).
/// - "F954 cubic n" / "F954 quartic n": Flocke, "Algorithm 954: An Accurate
///   and Efficient Cubic and Quartic Equation Solver for Physical
///   Applications", ACM TOMS 41(4), Article 30 (2015), the published test
///   polynomials (coefficients as printed, highest degree first).
pub fn hard_table() -> Vec<Case> {
    let s = 1e30;
    vec![
        // --- Algorithm 1010 ---
        case("A1010 1: 1e9,1e6,1e3,1", expand(&[1e9, 1e6, 1e3, 1.0], &[])).cf(Wrong),
        case(
            "A1010 2: 2.003,2.002,2.001,2",
            expand(&[2.003, 2.002, 2.001, 2.0], &[]),
        )
        .cf(Rel(1e-5))
        .bis(Rel(1e-5)),
        case(
            "A1010 3: 1e53,1e50,1e49,1e47",
            expand(&[1e53, 1e50, 1e49, 1e47], &[]),
        )
        .cf(Wrong),
        case("A1010 4: 1e14,2,1,-1", expand(&[1e14, 2.0, 1.0, -1.0], &[])).cf(Wrong),
        case(
            "A1010 5: -2e7,1e7,1,-1",
            expand(&[-2e7, 1e7, 1.0, -1.0], &[]),
        )
        .cf(Rel(1e-3)),
        case(
            "A1010 6: 1e7,-1e6,1+-i",
            expand(&[1e7, -1e6], &[(1.0, 1.0)]),
        ),
        case(
            "A1010 7: -7,-4,-1e6+-1e5i",
            expand(&[-7.0, -4.0], &[(-1e6, 1e5)]),
        ),
        case(
            "A1010 8: 1e8,11,1e3+-i",
            expand(&[1e8, 11.0], &[(1e3, 1.0)]),
        )
        .cf(Wrong),
        case(
            "A1010 9: complex only",
            expand(&[], &[(1e7, 1e6), (1.0, 2.0)]),
        ),
        case(
            "A1010 10: complex only",
            expand(&[], &[(1e4, 3.0), (-7.0, 1e3)]),
        ),
        case(
            "A1010 11: complex only",
            expand(&[], &[(1.001, 4.998), (1.0, 5.001)]),
        ),
        case(
            "A1010 12: complex only",
            expand(&[], &[(1e3, 3.0), (1e3, 1.0)]),
        ),
        case(
            "A1010 13: complex only",
            expand(&[], &[(2.0, 1e4), (1.0, 1e3)]),
        ),
        case("A1010 14: 1000 x4", expand(&[1e3, 1e3, 1e3, 1e3], &[])),
        case(
            "A1010 15: 1000 x3, 2^-48",
            expand(&[1e3, 1e3, 1e3, 2f64.powi(-48)], &[]),
        )
        .cf(Wrong)
        .bis(Rel(1e-5)),
        case(
            "A1010 16: complex only",
            expand(&[], &[(1e16, 1e7), (1.0, 0.1)]),
        )
        .cf(Wrong),
        case(
            "A1010 17: 1e4,1e4+1,1e4+10,1e4+100",
            expand(&[1e4, 10001.0, 10010.0, 10100.0], &[]),
        )
        .cf(Rel(1e-6))
        .bis(Rel(1e-6)),
        case(
            "A1010 18: complex only",
            expand(&[], &[(4e5, 3e2), (3e4, 7e3)]),
        ),
        case(
            "A1010 19: 1e44,1e30,1e30,1",
            expand(&[1e44, 1e30, 1e30, 1.0], &[]),
        )
        .cf(Wrong),
        case(
            "A1010 20: 1e14,1e7,1e7,1",
            expand(&[1e14, 1e7, 1e7, 1.0], &[]),
        )
        .cf(Wrong),
        case(
            "A1010 21: 1e15,1e7,1e7,1",
            expand(&[1e15, 1e7, 1e7, 1.0], &[]),
        )
        .cf(Wrong)
        .bis(Rel(1e-7)),
        case(
            "A1010 22: 1e154,1e152,10,1",
            expand(&[1e154, 1e152, 10.0, 1.0], &[]),
        )
        .cf(Wrong)
        .bis(Wrong),
        case(
            "A1010 23: x^4+x^3+x^2+3x/8+1e-3",
            vec![0.001, 0.375, 1.0, 1.0, 1.0],
        ),
        case(
            "A1010 24: S=1e30",
            vec![-s, s * s + s, 1.0 / s - s * s, -(1.0 + 1.0 / s), 1.0],
        )
        .cf(Wrong),
        // --- Algorithm 954 (coefficients as published, highest first) ---
        case(
            "F954 cubic 1: 1,1e7,1e14",
            high_first(&[1.0, -1.00000010000001e14, 1.00000010000001e21, -1e21]),
        )
        .cf(Wrong),
        case(
            "F954 cubic 2: 1,1.000001,1.000002",
            high_first(&[1.0, -3.000003, 3.000006000002, -1.000003000002]),
        )
        .cf(Rel(1e-5))
        .bis(Rel(1e-4)),
        case(
            "F954 cubic 3: 1e80,1e77,-1e81",
            high_first(&[1.0, 8.999e80, -1.0009e161, 1e238]),
        )
        .cf(Wrong),
        case(
            "F954 cubic 4: 1,-1,-1e24",
            high_first(&[1.0, 1e24, -1.0, -1e24]),
        )
        .cf(Wrong),
        case(
            "F954 cubic 5: 1e14,1e14,-1",
            high_first(&[1.0, -1.99999999999999e14, 0.99999999999998e28, 1e28]),
        )
        .cf(Rel(1e-8))
        .bis(Rel(1e-8)),
        case(
            "F954 cubic 6: 1e5, 1e5+-i",
            high_first(&[1.0, -3e5, 3.0000000001e10, -1.0000000001e15]),
        )
        .bis(Rel(1e-6)),
        case(
            "F954 cubic 7: 1, 1+-1e7i",
            high_first(&[1.0, -3.0, 1.00000000000003e14, -1.00000000000001e14]),
        )
        .cf(Rel(1e-8)),
        case(
            "F954 cubic 8: 1, 1e7+-i",
            high_first(&[1.0, -2.0000001e7, 1.00000020000001e14, -1.00000000000001e14]),
        ),
        case(
            "F954 cubic 9: -1e14, 1+-i",
            high_first(&[1.0, 0.99999999999998e14, -1.99999999999998e14, 2e14]),
        ),
        case(
            "F954 quartic 1",
            high_first(&[
                1.0,
                -1001001001.0,
                1001002001001000.0,
                -1001001001000000000.0,
                1e18,
            ]),
        )
        .cf(Wrong),
        case(
            "F954 quartic 2",
            high_first(&[1.0, -4.006, 6.018011, -4.018022006, 1.006011006]),
        )
        .cf(Rel(1e-6))
        .bis(Rel(1e-6)),
        case(
            "F954 quartic 3: 1e80,-1e74,-1e76,-1e77",
            high_first(&[1.0, -9.98899e79, -1.1008989e157, -1.010999e233, -1e307]),
        )
        .cf(Wrong),
        case(
            "F954 quartic 4",
            high_first(&[
                1.0,
                -1.00000000000002e14,
                1.99999999999999e14,
                1.00000000000002e14,
                -2e14,
            ]),
        )
        .cf(Wrong),
        case(
            "F954 quartic 5",
            high_first(&[1.0, 1e7, -2.00000000000001e14, -1e7, 2e14]),
        )
        .cf(Rel(1e-3)),
        case(
            "F954 quartic 6",
            high_first(&[1.0, -9.000002e6, -0.9999981999998e13, 1.9999982e13, -2e13]),
        ),
        case(
            "F954 quartic 7",
            high_first(&[1.0, 2.000011e6, 1.010022000028e12, 1.1110056e13, 2.828e13]),
        ),
        case(
            "F954 quartic 8",
            high_first(&[
                1.0,
                -1.00002011e8,
                2.01101022001e11,
                -1.02200111000011e14,
                1.1000011e15,
            ]),
        )
        .cf(Wrong),
        case(
            "F954 quartic 9",
            high_first(&[
                1.0,
                -2.0000002e7,
                1.01000040000005e14,
                -2.020001e14,
                5.05e14,
            ]),
        ),
        case(
            "F954 quartic 10",
            high_first(&[
                1.0,
                -1.9986e4,
                1.00720058e8,
                -1.8600979874e10,
                1.00004909000441e14,
            ]),
        ),
        case(
            "F954 quartic 11",
            high_first(&[
                1.0,
                -4.006,
                5.6008018e1,
                -1.04148036024e2,
                6.75896068064016e2,
            ]),
        ),
        case(
            "F954 quartic 12",
            high_first(&[1.0, -4e3, 6.00001e6, -4.00002e9, 1.000010000009e12]),
        ),
        case(
            "F954 quartic 13",
            high_first(&[1.0, -6.0, 1.01000013e8, -2.04000012e8, 1.00000104000004e14]),
        ),
        // --- clustered, multiple, scaled ---
        case(
            "cluster 1,1+1e-7,1+2e-7,1+3e-7",
            expand(&[1.0, 1.0 + 1e-7, 1.0 + 2e-7, 1.0 + 3e-7], &[]),
        )
        .cf(Rel(1e-4))
        .bis(Rel(1e-3)),
        case(
            "cluster 1,1+1e-7 and 2,3",
            expand(&[1.0, 1.0 + 1e-7, 2.0, 3.0], &[]),
        )
        .cf(Wrong)
        .bis(Rel(1e-7)),
        case(
            "cluster 1e-3 +- 1e-12, -1, 5",
            expand(&[1e-3 - 1e-12, 1e-3 + 1e-12, -1.0, 5.0], &[]),
        )
        .bis(Wrong),
        case(
            "pair 0.5, 0.5+1e-4 above complex",
            expand(&[0.5, 0.5 + 1e-4], &[(0.5, 1e-3)]),
        )
        .cf(Rel(1e-5))
        .bis(Rel(1e-5)),
        case("double 1 (exact), 2, 3", vec![6.0, -17.0, 17.0, -7.0, 1.0])
            .bis(Wrong)
            .bis(Wrong),
        case(
            "double 0.1 (rounded), 0.3, -0.7",
            expand(&[0.1, 0.1, 0.3, -0.7], &[]),
        )
        .cf(Wrong)
        .bis(Rel(1e-7)),
        case(
            "two doubles 1 and 2 (exact)",
            vec![4.0, -12.0, 13.0, -6.0, 1.0],
        )
        .bis(Wrong),
        case("quadruple 1 (exact)", vec![1.0, -4.0, 6.0, -4.0, 1.0]),
        case("triple 2 (exact), -1", vec![8.0, -4.0, -6.0, 5.0, -1.0]),
        case(
            "quadruple 0.3 (rounded)",
            expand(&[0.3, 0.3, 0.3, 0.3], &[]),
        )
        .cf(Rel(1e-4))
        .bis(Rel(1e-3)),
        case(
            "scaled 1e-8,1e-3,1e3,1e8",
            expand(&[1e-8, 1e-3, 1e3, 1e8], &[]),
        )
        .cf(Wrong),
        case(
            "scaled -1e8,-1e-8,1e-4,1e4",
            expand(&[-1e8, -1e-8, 1e-4, 1e4], &[]),
        )
        .cf(Wrong),
        case(
            "zero root x(x-1)(x+2)(x-3)",
            expand(&[0.0, 1.0, -2.0, 3.0], &[]),
        ),
        case(
            "tiny leading 1e-12 x^4 + ...",
            vec![-1.0, 0.0, 1.0, 0.0, 1e-12],
        ),
        // --- cubics, quadratics, linear, degenerate ---
        case("cubic 1,2,3", vec![-6.0, 11.0, -6.0, 1.0]),
        case("cubic triple 2 (exact)", vec![-8.0, 12.0, -6.0, 1.0]),
        case("cubic 0.1,0.2,0.3 (rounded)", expand(&[0.1, 0.2, 0.3], &[])),
        case("cubic one real, 1e3 +- i", expand(&[-2.0], &[(1e3, 1.0)])),
        case("quadratic double 1 (exact)", vec![1.0, -2.0, 1.0]),
        case("quadratic 1e-10, 1e10", expand(&[1e-10, 1e10], &[])),
        case(
            "quadratic 1/3 double (rounded)",
            expand(&[1.0 / 3.0, 1.0 / 3.0], &[]),
        )
        .cf(Wrong)
        .bis(Wrong),
        case("quadratic no real root", vec![1.0, 0.0, 1.0]),
        case("linear 2x - 1", vec![-1.0, 2.0]),
        case("constant 5", vec![5.0]),
        case("zero polynomial", vec![0.0, 0.0, 0.0]),
        case("empty", vec![]),
        case(
            "leading zeros: x^2 - 3x + 2 padded",
            vec![2.0, -3.0, 1.0, 0.0, 0.0],
        ),
        case("NaN coefficient", vec![1.0, f64::NAN, 1.0]),
        case("infinite coefficient", vec![-1.0, 0.0, 0.0, f64::INFINITY]),
    ]
}
