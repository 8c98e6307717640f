//! Differential tests of the number layer against exact rationals.

use super::*;
use proptest::prelude::*;

/// Rationals aimed at the hard cases: exact doubles, non-dyadic fractions, tiny and huge
/// magnitudes, values perturbed from 1 by 2^-40..2^-60, exact zero.
fn rational() -> impl Strategy<Value = Rational> {
    prop_oneof![
        any::<f64>()
            .prop_filter("finite", |x| x.is_finite())
            .prop_map(|x| Rational::from_f64(x).unwrap()),
        (-1000i64..1000, 1i64..1000).prop_map(|(p, q)| Rational::from((p, q))),
        (-50i32..50, 40u32..61).prop_map(|(k, e)| {
            Rational::from(1) + Rational::from(k) / Rational::from(rug::Integer::from(1) << e)
        }),
        (-1000i64..1000, 900u32..1100)
            .prop_map(|(p, e)| { Rational::from(p) / Rational::from(rug::Integer::from(1) << e) }),
        Just(Rational::new()),
    ]
}

type Op = fn(&Rational, &Rational) -> Rational;

fn exact_ops() -> [(&'static str, Op); 4] {
    [
        ("add", |a, b| Rational::from(a + b)),
        ("sub", |a, b| Rational::from(a - b)),
        ("mul", |a, b| Rational::from(a * b)),
        ("mid", |a, b| Rational::from(a + b) / 2),
    ]
}

fn apply<N: Number>(name: &str, a: &N, b: &N) -> N {
    match name {
        "add" => a.add(b),
        "sub" => a.sub(b),
        "mul" => a.mul(b),
        _ => a.midpoint(b),
    }
}

fn sign_of(q: &Rational) -> Sign {
    Sign::from_ordering(q.cmp0())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::testing_cases(256)))]

    /// Interval results contain the exact result, and a known sign is the exact sign.
    #[test]
    fn interval_encloses(a in rational(), b in rational()) {
        let (ia, ib) = (Interval::from_rational(&a, Precision::F64), Interval::from_rational(&b, Precision::F64));
        prop_assert!(ia.contains_rational(&a) && ib.contains_rational(&b));
        for (name, op) in exact_ops() {
            let exact = op(&a, &b);
            let r = apply(name, &ia, &ib);
            prop_assert!(r.contains_rational(&exact), "{name}: {r:?} misses {exact}");
            let s = r.sign();
            prop_assert!(!s.is_known() || s == sign_of(&exact), "{name}: sign {s:?} of {exact}");
        }
        prop_assert!(ia.neg().contains_rational(&Rational::from(-&a)));
    }

    /// Interval products round each bound exactly in its direction (the error-free product by
    /// `fma`), where the product is in the range where the error is computed exactly
    /// (`proofs/outward-rounding.md`, item 3).
    #[test]
    fn products_round_in_their_direction(a in -1e150f64..1e150, b in -1e150f64..1e150, sa in -300i32..300) {
        let a = a * 2f64.powi(sa);
        let (lo, hi) = super::interval::mul_rd_ru(a, b);
        let exact = Rational::from_f64(a).unwrap() * Rational::from_f64(b).unwrap();
        let down = rug::Float::with_val_round(53, &exact, rug::float::Round::Down).0.to_f64();
        let up = rug::Float::with_val_round(53, &exact, rug::float::Round::Up).0.to_f64();
        let p = a * b;
        if p.is_finite() && p.abs() >= 1e-250 && p.abs() <= 1e290 {
            prop_assert_eq!((lo, hi), (down, up), "{} * {}", a, b);
        } else {
            prop_assert!(lo <= down && up <= hi);
        }
    }

    /// MPFR intervals contain the exact result at several precisions.
    #[test]
    fn mpfr_interval_encloses(a in rational(), b in rational(), p in prop_oneof![Just(24u32), Just(53), Just(128), Just(300)]) {
        let prec = Precision(p);
        let (ia, ib) = (MpInterval::from_rational(&a, prec), MpInterval::from_rational(&b, prec));
        for (name, op) in exact_ops() {
            let exact = op(&a, &b);
            let r = apply(name, &ia, &ib);
            prop_assert!(r.contains_rational(&exact), "{name}@{p}: misses {exact}");
            let s = r.sign();
            prop_assert!(!s.is_known() || s == sign_of(&exact));
            prop_assert!(r.lower_f64() <= exact && exact <= r.upper_f64());
        }
    }

    /// One rounded `f64` operation is within half an ulp: |fl(x∘y) − x∘y| ≤ 2^-53 |x∘y|
    /// (normal range; operands are exact doubles).
    #[test]
    fn f64_within_half_ulp(x in -1e100f64..1e100, y in -1e100f64..1e100) {
        let (a, b) = (Rational::from_f64(x).unwrap(), Rational::from_f64(y).unwrap());
        for (name, op) in exact_ops() {
            let exact = op(&a, &b);
            let r = apply(name, &x, &y);
            if exact.cmp0() == std::cmp::Ordering::Equal || exact.clone().abs() < 1e-290 {
                continue;
            }
            let err = (Rational::from_f64(r).unwrap() - &exact).abs();
            let bound = exact.abs() / Rational::from(rug::Integer::from(1) << 53);
            prop_assert!(err <= bound, "{name}: {x} {y}");
        }
    }

    /// The two exact types agree (rug against num-rational) on every operation and sign.
    #[test]
    fn exact_types_agree(a in rational(), b in rational()) {
        let (ba, bb) = (BigRational::from_rational(&a, Precision::F64), BigRational::from_rational(&b, Precision::F64));
        for (name, op) in exact_ops() {
            let exact = op(&a, &b);
            let r = apply(name, &ba, &bb);
            prop_assert_eq!(r.clone(), BigRational::from_rational(&exact, Precision::F64));
            prop_assert_eq!(r.sign(), sign_of(&exact));
            prop_assert!(r.lower_f64() <= exact && exact <= r.upper_f64());
        }
    }
}

/// Products near `f64::MAX` are enclosed (a review's counterexample to an error-free product
/// without an upper bound on |a b|).
#[test]
fn products_near_the_largest_double_are_enclosed() {
    let a = 2f64.powi(512) * (1.0 - 3.0 * f64::EPSILON / 2.0);
    let b = 2f64.powi(512) * (1.0 + f64::EPSILON);
    let (lo, hi) = super::interval::mul_rd_ru(a, b);
    let exact = Rational::from_f64(a).unwrap() * Rational::from_f64(b).unwrap();
    assert!(Rational::from_f64(lo).unwrap() <= exact, "{lo}");
    assert!(
        hi == f64::INFINITY || exact <= Rational::from_f64(hi).unwrap(),
        "{hi}"
    );
}

#[test]
fn exact_zero_is_decided_by_intervals() {
    // 0.5 + 0.25 - 0.75 is exact in binary: the interval must be the point 0.
    let i = |x: f64| Interval::point(x);
    let z = i(0.5).add(&i(0.25)).sub(&i(0.75));
    assert_eq!(z.sign(), Sign::Zero);
    // 0.1 is not exact: its enclosure has width one ulp, and 3 * 0.1 - 0.3 is undecided.
    let tenth = Interval::from_rational(&Rational::from((1, 10)), Precision::F64);
    assert!(tenth.lo() < tenth.hi());
    let three = Interval::from_i64(3, Precision::F64);
    let tenth3 = Interval::from_rational(&Rational::from((3, 10)), Precision::F64);
    assert_eq!(three.mul(&tenth).sub(&tenth3).sign(), Sign::Unknown);
    // ... and exact rationals decide it.
    let q = Rational::from((1, 10));
    assert_eq!(
        Rational::from(3)
            .mul(&q)
            .sub(&Rational::from((3, 10)))
            .sign(),
        Sign::Zero
    );
}

#[test]
fn overflow_and_infinities_stay_sound() {
    let big = Interval::point(f64::MAX);
    let s = big.add(&big);
    assert_eq!(s.lo(), f64::MAX);
    assert_eq!(s.hi(), f64::INFINITY);
    assert_eq!(s.sign(), Sign::Positive);
    let p = big.mul(&Interval::point(-2.0));
    assert_eq!(p.sign(), Sign::Negative);
    let whole = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
    assert_eq!(whole.add(&whole).sign(), Sign::Unknown);
    assert_eq!(whole.mul(&Interval::point(0.0)).sign(), Sign::Zero);
    // Subnormal products are widened, never collapsed to a wrong point.
    let tiny = Interval::point(f64::MIN_POSITIVE);
    let t = tiny.mul(&Interval::point(0.3));
    assert!(t.lo() <= t.hi() && t.sign() != Sign::Negative);
    let h = Interval::point(f64::from_bits(1)).midpoint(&Interval::point(0.0));
    assert!(h.contains(0.0) || h.lo() > 0.0);
    assert!(
        h.lo() <= f64::from_bits(1) / 2.0 && f64::from_bits(1) / 2.0 <= h.hi() || h.contains(0.0)
    );
}

#[test]
fn parse_then_enclose() {
    let q = parse_exact("0.1").unwrap();
    let i = Interval::from_rational(&q, Precision::F64);
    assert!(i.contains_rational(&q));
    assert_eq!(i.hi().next_down(), i.lo());
    let m = MpInterval::from_rational(&q, Precision(200));
    assert!(m.contains_rational(&q));
    assert_eq!(m.precision(), Precision(200));
}

#[test]
fn mpfr_interval_zero_times_unbounded_is_zero() {
    use rug::Float;
    let whole = MpInterval::try_new(
        Float::with_val(64, f64::NEG_INFINITY),
        Float::with_val(64, f64::INFINITY),
    )
    .unwrap();
    let zero = MpInterval::from_i64(0, Precision(64));
    assert_eq!(zero.mul(&whole).sign(), Sign::Zero);
    assert_eq!(whole.add(&whole).sign(), Sign::Unknown);
}
