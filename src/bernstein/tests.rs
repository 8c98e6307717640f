//! Differential tests: every operation in f64, intervals and MPFR intervals against the same
//! operation in exact rationals.

use super::*;
use crate::number::{Interval, MpInterval, Number, Precision, Rational};
use proptest::prelude::*;

fn coeff() -> impl Strategy<Value = Rational> {
    prop_oneof![
        (-64i64..64, 1i64..17).prop_map(|(p, q)| Rational::from((p, q))),
        (-5i64..5).prop_map(|k| Rational::from(1)
            + Rational::from(k) / Rational::from(rug::Integer::from(1) << 45u32)),
        Just(Rational::new()),
    ]
}

fn poly(max_vars: usize, max_deg: usize) -> impl Strategy<Value = Bernstein<Rational>> {
    prop::collection::vec(0..=max_deg, 1..=max_vars).prop_flat_map(|degs| {
        let n: usize = degs.iter().map(|d| d + 1).product();
        prop::collection::vec(coeff(), n).prop_map(move |c| Bernstein::new(&degs, c).unwrap())
    })
}

/// Two polynomials with the same number of variables (1 or 2).
fn poly_pair(max_deg: usize) -> impl Strategy<Value = (Bernstein<Rational>, Bernstein<Rational>)> {
    (1usize..=2).prop_flat_map(move |k| {
        let one = move || {
            prop::collection::vec(0..=max_deg, k).prop_flat_map(|degs| {
                let n: usize = degs.iter().map(|d| d + 1).product();
                prop::collection::vec(coeff(), n)
                    .prop_map(move |c| Bernstein::new(&degs, c).unwrap())
            })
        };
        (one(), one())
    })
}

fn param() -> impl Strategy<Value = Rational> {
    prop_oneof![
        (0i64..=64).prop_map(|k| Rational::from((k, 64))),
        (1i64..10).prop_map(|k| Rational::from((k, 10)))
    ]
}

fn encloses_i(p: &Bernstein<Interval>, e: &Bernstein<Rational>) -> bool {
    p.degrees() == e.degrees()
        && p.coeffs()
            .iter()
            .zip(e.coeffs())
            .all(|(i, q)| i.contains_rational(q))
}

fn encloses_m(p: &Bernstein<MpInterval>, e: &Bernstein<Rational>) -> bool {
    p.degrees() == e.degrees()
        && p.coeffs()
            .iter()
            .zip(e.coeffs())
            .all(|(i, q)| i.contains_rational(q))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::testing_cases(96)))]

    #[test]
    fn subdivision_encloses(p in poly(4, 5), axis in 0usize..4, t in param()) {
        let axis = axis % p.nvars();
        let (el, er) = p.subdivide_half(axis);
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        let (il, ir) = pi.subdivide_half(axis);
        prop_assert!(encloses_i(&il, &el) && encloses_i(&ir, &er));
        let pm: Bernstein<MpInterval> = p.convert(Precision(128));
        let (ml, mr) = pm.subdivide_half(axis);
        prop_assert!(encloses_m(&ml, &el) && encloses_m(&mr, &er));
        // General t, with t itself enclosed.
        let (el, er) = p.subdivide(axis, &t);
        let (il, ir) = pi.subdivide(axis, &Interval::from_rational(&t, Precision::F64));
        prop_assert!(encloses_i(&il, &el) && encloses_i(&ir, &er));
        // The halves glue: left at 1 equals right at 0, and they evaluate to the whole.
        let mut x: Vec<Rational> = vec![Rational::from((1, 3)); p.nvars()];
        x[axis] = Rational::from((1, 3));
        let mut y = x.clone();
        y[axis] = &t * Rational::from((1, 3));
        prop_assert_eq!(el.eval(&x), p.eval(&y));
    }

    #[test]
    fn restriction_is_exact_and_encloses(p in poly(3, 5), axis in 0usize..3, a in param(), b in param()) {
        let axis = axis % p.nvars();
        let r = p.restrict(axis, &a, &b);
        // r(s) = p(a + s (b - a)) along the axis, checked at s = 2/7.
        let s = Rational::from((2, 7));
        let mut x: Vec<Rational> = vec![Rational::from((3, 5)); p.nvars()];
        x[axis] = s.clone();
        let mut y = x.clone();
        y[axis] = &a + &s * Rational::from(&b - &a);
        prop_assert_eq!(r.eval(&x), p.eval(&y));
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        let ri = pi.restrict(axis, &Interval::from_rational(&a, Precision::F64), &Interval::from_rational(&b, Precision::F64));
        prop_assert!(encloses_i(&ri, &r));
        // The two-split version: exact on exact input, an enclosure on intervals.
        prop_assert_eq!(p.restrict_rational(axis, &a, &b), r.clone());
        prop_assert!(encloses_i(&pi.restrict_rational(axis, &a, &b), &r));
    }

    /// The in-place two-split restriction of interval polynomials to an f64 box (any reals,
    /// inside or outside the unit box, a side of zero width among them) encloses the exact
    /// restriction.
    #[test]
    fn box_restriction_encloses(p in poly(3, 5), ends in prop::collection::vec((-16i64..=80, 0i64..=48), 3)) {
        let n = p.nvars();
        let lo: Vec<f64> = ends[..n].iter().map(|e| e.0 as f64 / 64.0).collect();
        let hi: Vec<f64> = ends[..n].iter().map(|e| (e.0 + e.1) as f64 / 64.0).collect();
        let q = |x: &f64| Rational::from_f64(*x).unwrap();
        let (lq, hq): (Vec<Rational>, Vec<Rational>) = (lo.iter().map(q).collect(), hi.iter().map(q).collect());
        let mut exact = p.clone();
        for axis in 0..n {
            exact = exact.restrict(axis, &lq[axis], &hq[axis]);
        }
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        prop_assert!(encloses_i(&pi.restrict_box_f64(&lo, &hi), &exact));
    }

    /// The hull of the derivative without forming it holds every exact derivative coefficient.
    #[test]
    fn derivative_hull_encloses(p in poly(4, 5), axis in 0usize..4) {
        let axis = axis % p.nvars();
        let h = p.convert::<Interval>(Precision::F64).deriv_hull(axis);
        prop_assert!(p.deriv(axis).coeffs().iter().all(|c| h.contains_rational(c)));
    }

    #[test]
    fn evaluation_encloses(p in poly(4, 6), t in prop::collection::vec(param(), 4)) {
        let x = &t[..p.nvars()];
        let exact = p.eval(x);
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        let xi: Vec<Interval> = x.iter().map(|q| Interval::from_rational(q, Precision::F64)).collect();
        prop_assert!(pi.eval(&xi).contains_rational(&exact));
        let pm: Bernstein<MpInterval> = p.convert(Precision(200));
        let xm: Vec<MpInterval> = x.iter().map(|q| MpInterval::from_rational(q, Precision(200))).collect();
        prop_assert!(pm.eval(&xm).contains_rational(&exact));
        // f64 evaluation stays near the exact value (a loose sanity bound, not a proof).
        let pf: Bernstein<f64> = p.convert(Precision::F64);
        let xf: Vec<f64> = x.iter().map(|q| q.to_f64()).collect();
        let scale = pf.coeffs().iter().fold(1.0f64, |m, c| m.max(c.abs()));
        prop_assert!((pf.eval(&xf) - exact.to_f64()).abs() <= 1e-12 * scale);
        // The coefficient range bounds the value.
        let (lo, hi) = pi.range_f64();
        let inside = x.iter().all(|q| *q >= 0 && *q <= 1);
        prop_assert!(!inside || (lo <= exact && exact <= hi));
    }

    #[test]
    fn elevation_keeps_the_polynomial(p in poly(3, 4), axis in 0usize..3, by in 1usize..3, t in prop::collection::vec(param(), 3)) {
        let axis = axis % p.nvars();
        let e = p.elevate(axis, by);
        prop_assert_eq!(e.degrees()[axis], p.degrees()[axis] + by);
        prop_assert_eq!(e.eval(&t[..p.nvars()]), p.eval(&t[..p.nvars()]));
        let (re, rp) = (e.reduce_degree_exact(), p.reduce_degree_exact());
        prop_assert_eq!(re.degrees(), rp.degrees());
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        prop_assert!(encloses_i(&pi.elevate(axis, by), &e));
    }

    #[test]
    fn product_sum_and_derivative((p, q) in poly_pair(4), t in prop::collection::vec(param(), 2)) {
        let x = &t[..p.nvars()];
        let pq = &p * &q;
        prop_assert_eq!(pq.eval(x), p.eval(x) * q.eval(x));
        prop_assert_eq!((&p + &q).eval(x), p.eval(x) + q.eval(x));
        prop_assert_eq!((&p - &q).eval(x), p.eval(x) - q.eval(x));
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        let qi: Bernstein<Interval> = q.convert(Precision::F64);
        prop_assert!(encloses_i(&(&pi * &qi), &pq));
        // Derivative against a divided difference of the exact polynomial: p is a polynomial,
        // so (p(x+h) - p(x-h)) / 2h - p'(x) = O(h^2); check with the exact identity for the
        // degree instead: the derivative of the product rule.
        let lhs = pq.deriv(0).eval(x);
        let rhs = p.deriv(0).eval(x) * q.eval(x) + p.eval(x) * q.deriv(0).eval(x);
        prop_assert_eq!(lhs, rhs);
        prop_assert!(encloses_i(&pi.deriv(0), &p.deriv(0)));
    }

    #[test]
    fn the_value_at_the_centre_is_the_value_at_one_half(p in poly(4, 6)) {
        // The weighted sum is exact in rationals and encloses in intervals (MPFR and f64).
        let half = vec![Rational::from((1, 2)); p.nvars()];
        let exact = p.eval(&half);
        prop_assert_eq!(&p.value_at_centre(), &exact);
        let pi: Bernstein<Interval> = p.convert(Precision::F64);
        prop_assert!(pi.value_at_centre().contains_rational(&exact));
        let pm: Bernstein<MpInterval> = p.convert(Precision(200));
        prop_assert!(pm.value_at_centre().contains_rational(&exact));
    }

    #[test]
    fn products_of_polynomials_in_disjoint_variables(
        (p, q) in poly_pair(4),
        zero_in_p in prop::collection::vec(any::<bool>(), 2),
    ) {
        // Each variable set to degree 0 in one of the two (the lifted products of the ray
        // and crossing systems): the tensor product is the general product, exactly, and
        // encloses it in intervals.
        let k = p.nvars();
        let flatten = |r: &Bernstein<Rational>, keep: &dyn Fn(usize) -> bool| {
            let degs: Vec<usize> = (0..k).map(|a| if keep(a) { r.degrees()[a] } else { 0 }).collect();
            let n: usize = degs.iter().map(|d| d + 1).product();
            Bernstein::new(&degs, r.coeffs()[..n].to_vec()).unwrap()
        };
        let a = flatten(&p, &|x| !zero_in_p[x]);
        let b = flatten(&q, &|x| zero_in_p[x]);
        let fast = &a * &b;
        prop_assert_eq!(&fast, &a.mul_generic(&b).unwrap());
        let (ai, bi): (Bernstein<Interval>, Bernstein<Interval>) =
            (a.convert(Precision::F64), b.convert(Precision::F64));
        prop_assert!(encloses_i(&(&ai * &bi), &fast));
        // Sums at equal degrees borrow both operands; at unequal ones one is elevated.
        prop_assert_eq!(&fast - &fast, fast.scale(&Rational::new()));
    }
}

#[test]
fn derivative_of_monomials() {
    // t^2 in degree 2: coefficients 0, 0, 1; derivative 2t: coefficients 0, 2.
    let p = Bernstein::new(
        &[2],
        vec![Rational::new(), Rational::new(), Rational::from(1)],
    )
    .unwrap();
    assert_eq!(p.deriv(0).coeffs(), &[Rational::new(), Rational::from(2)]);
    // An elevated linear polynomial reduces back to degree 1.
    let l = Bernstein::new(&[1], vec![Rational::from(3), Rational::from(-1)]).unwrap();
    assert_eq!(l.elevate(0, 5).reduce_degree_exact(), l);
    // A genuine quadratic does not reduce.
    assert_eq!(p.reduce_degree_exact().degrees(), &[2]);
}

#[test]
fn range_sign_is_conservative() {
    let q = |n: i64| Rational::from(n);
    let pos = Bernstein::new(&[1, 1], vec![q(1), q(2), q(3), q(4)]).unwrap();
    assert!(pos.range_sign().is_positive());
    // Mixed coefficients: the polynomial (1 - 2u)^2 >= 0, yet the range test cannot tell.
    let sq = Bernstein::new(&[2], vec![q(1), q(-1), q(1)]).unwrap();
    assert!(!sq.range_sign().is_known());
    let z = Bernstein::new(&[2], vec![q(0), q(0), q(0)]).unwrap();
    assert!(z.range_sign().is_zero() && z.is_zero());
    assert!(Bernstein::<Rational>::new(&[1, 2], vec![q(0); 5]).is_err());
    assert!(Bernstein::<Rational>::new(&[], vec![q(0)]).is_err());
    assert!(
        Bernstein::<Rational>::new(&[1; MAX_VARS + 1], vec![q(0); 1 << (MAX_VARS + 1)]).is_err()
    );
    assert!(Bernstein::<Rational>::new(&[1; MAX_VARS], vec![q(0); 1 << MAX_VARS]).is_ok());
}

#[test]
fn face_factors_divide_exactly() {
    let q = |n: i64| Rational::from(n);
    // p(u, v, w) = v (1 - w) h(u, v, w), h an arbitrary trilinear polynomial.
    let lin = |c: [i64; 8]| Bernstein::new(&[1, 1, 1], c.iter().map(|&k| q(k)).collect()).unwrap();
    let v = lin([0, 0, 1, 1, 0, 0, 1, 1]);
    let one_minus_w = lin([1, 0, 1, 0, 1, 0, 1, 0]);
    let h = lin([1, -2, 3, 0, 2, -1, 4, 1]);
    let p = &(&v * &one_minus_w) * &h;
    let d = p
        .divide_face_factor(1, false)
        .unwrap()
        .divide_face_factor(2, true)
        .unwrap();
    let x = [
        Rational::from((2, 7)),
        Rational::from((3, 11)),
        Rational::from((5, 13)),
    ];
    assert_eq!(d.eval(&x), h.eval(&x));
    // No factor where the face does not vanish.
    assert!(h.divide_face_factor(0, false).is_none());
    assert!(p.divide_face_factor(1, true).is_none());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// `W^{d0+d1} p(U/W, V/W)` from the composition equals that product evaluated at rational
    /// parameters (exactly), for random bivariate `p` and curves with positive weights.
    #[test]
    fn the_homogeneous_composition_is_p_along_the_curve(
        p in (0usize..=3, 0usize..=2).prop_flat_map(|(a, b)| {
            prop::collection::vec(coeff(), (a + 1) * (b + 1))
                .prop_map(move |c| Bernstein::new(&[a, b], c).unwrap())
        }),
        n in 1usize..=3,
        seed in prop::collection::vec((-8i64..8, -8i64..8, 1i64..6), 4),
    ) {
        let pick = |k: usize, f: fn(&(i64, i64, i64)) -> i64| -> Bernstein<Rational> {
            let c: Vec<Rational> = (0..=n).map(|i| Rational::from((f(&seed[i % 4]) + k as i64, 7))).collect();
            Bernstein::new(&[n], c).unwrap()
        };
        let u = pick(0, |s| s.0);
        let v = pick(1, |s| s.1);
        let w = Bernstein::new(&[n], (0..=n).map(|i| Rational::from((seed[i % 4].2, 3))).collect()).unwrap();
        let h = compose_homogeneous(&p, [&u, &v, &w]);
        prop_assert_eq!(h.degrees(), &[n * (p.degrees()[0] + p.degrees()[1])][..]);
        for t in [Rational::new(), Rational::from((1, 3)), Rational::from((5, 7)), Rational::from(1)] {
            let at = std::slice::from_ref(&t);
            let (uu, vv, ww) = (u.eval(at), v.eval(at), w.eval(at));
            let x = [Rational::from(&uu / &ww), Rational::from(&vv / &ww)];
            let mut scale = Rational::from(1);
            for _ in 0..(p.degrees()[0] + p.degrees()[1]) {
                scale *= &ww;
            }
            prop_assert_eq!(h.eval(at), p.eval(&x) * scale);
        }
    }
}
