//! The square-system solver (subdivision + Krawczyk) against systems with known roots:
//! completeness (every root in the domain is found, once) and soundness (every reported
//! root's enclosure holds a true root) checked separately; a double root is left unresolved.

use limn::bernstein::Bernstein;
use limn::number::Rational;
use limn::solver::system::{simplest_rational, solve_system, SystemOptions};
use limn::solver::Dyadic;
use proptest::prelude::*;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// Π (t_axis − r) as a Bernstein polynomial in two variables (degree 0 in the other).
fn product(axis: usize, roots: &[Rational]) -> Bernstein<Rational> {
    let mut degrees = [0usize; 2];
    degrees[axis] = 0;
    let mut p = Bernstein::new(&degrees, vec![q(1, 1)]).unwrap();
    for r in roots {
        let mut d = [0usize; 2];
        d[axis] = 1;
        let lin = Bernstein::new(&d, vec![Rational::from(-r), Rational::from(1 - r)]).unwrap();
        p = &p * &lin;
    }
    p
}

fn unit() -> Vec<(Dyadic, Dyadic)> {
    vec![(Dyadic::ZERO, Dyadic::ONE); 2]
}

/// (f, g) mixed by an invertible constant matrix: the same roots.
fn mixed(
    f: &Bernstein<Rational>,
    g: &Bernstein<Rational>,
    m: [i64; 4],
) -> [Bernstein<Rational>; 2] {
    let d = [
        f.degrees()[0].max(g.degrees()[0]),
        f.degrees()[1].max(g.degrees()[1]),
    ];
    let (f, g) = (f.elevate_to(&d), g.elevate_to(&d));
    [
        &f.scale(&q(m[0], 1)) + &g.scale(&q(m[1], 1)),
        &f.scale(&q(m[2], 1)) + &g.scale(&q(m[3], 1)),
    ]
}

fn check(us: &[Rational], vs: &[Rational], m: [i64; 4]) {
    let [f, g] = mixed(&product(0, us), &product(1, vs), m);
    let r = solve_system(&[f, g], &[], &unit(), &SystemOptions::default());
    let inside = |x: &Rational| *x > 0 && *x < 1;
    let truth: Vec<(f64, f64)> = us
        .iter()
        .filter(|x| inside(x))
        .flat_map(|a| {
            vs.iter()
                .filter(|x| inside(x))
                .map(move |b| (a.to_f64(), b.to_f64()))
        })
        .collect();
    // Roots on the square's boundary may be reported (flagged as not inside).
    let closed = |x: &Rational| *x >= 0 && *x <= 1;
    let truth_closed: Vec<(f64, f64)> = us
        .iter()
        .filter(|x| closed(x))
        .flat_map(|a| {
            vs.iter()
                .filter(|x| closed(x))
                .map(move |b| (a.to_f64(), b.to_f64()))
        })
        .collect();
    let holds = |e: &Vec<[f64; 2]>, (a, b): (f64, f64)| {
        e[0][0] <= a && a <= e[0][1] && e[1][0] <= b && b <= e[1][1]
    };
    // Soundness: each reported root encloses a true one.
    for root in &r.roots {
        assert!(
            truth_closed.iter().any(|t| holds(&root.enclosure, *t)),
            "spurious root {root:?} (us {us:?}, vs {vs:?})"
        );
        assert!(
            root.enclosure.iter().all(|b| b[1] - b[0] <= 1e-9),
            "{root:?}"
        );
    }
    // Completeness: each true root is in exactly one reported enclosure, or the solver says
    // it could not decide a box holding it.
    for t in &truth {
        let n = r
            .roots
            .iter()
            .filter(|root| holds(&root.enclosure, *t))
            .count();
        let undecided = r.unresolved.iter().any(|b| holds(b, *t));
        assert!(
            n == 1 || (n == 0 && undecided),
            "root {t:?} found {n} times: {r:?}"
        );
    }
}

#[test]
fn grid_roots_with_some_on_box_faces() {
    check(&[q(1, 2), q(1, 3)], &[q(1, 4), q(2, 3)], [1, 2, -1, 1]);
    check(&[q(1, 2)], &[q(1, 2)], [1, 0, 0, 1]);
    check(
        &[q(3, 7), q(5, 9), q(-1, 2)],
        &[q(1, 5), q(3, 2)],
        [2, 1, 1, 1],
    );
}

#[test]
fn a_double_root_is_not_claimed() {
    let f = product(0, &[q(1, 3), q(1, 3)]);
    let g = product(1, &[q(2, 5)]);
    let r = solve_system(&[f, g], &[], &unit(), &SystemOptions::default());
    assert!(r.roots.is_empty(), "{r:?}");
    assert!(!r.unresolved.is_empty());
}

#[test]
fn filters_exclude_roots_off_their_zero_set() {
    // Roots (1/3, 1/4) and (2/3, 1/4); the filter u − 2/3 keeps only boxes near the second.
    let f = product(0, &[q(1, 3), q(2, 3)]);
    let g = product(1, &[q(1, 4)]);
    let filter = product(0, &[q(2, 3)]);
    let r = solve_system(&[f, g], &[filter], &unit(), &SystemOptions::default());
    assert_eq!(r.roots.len(), 1, "{r:?}");
    assert!(r.roots[0].enclosure[0][0] > 0.5);
}

#[test]
fn simplest_rationals() {
    assert_eq!(simplest_rational(&q(3, 10), &q(4, 10)), q(1, 3));
    assert_eq!(simplest_rational(&q(1, 2), &q(1, 2)), q(1, 2));
    assert_eq!(simplest_rational(&q(0, 1), &q(1, 10)), q(0, 1));
    assert_eq!(simplest_rational(&q(21, 100), &q(22, 100)), q(3, 14));
}

fn root() -> impl Strategy<Value = Rational> {
    (
        -2i64..=18,
        prop_oneof![Just(16i64), Just(9), Just(7), Just(13)],
    )
        .prop_map(|(a, b)| q(a, b))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("LIMN_PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(24)
    ))]
    /// Random grids of roots (some outside the square, some on box faces), mixed by a random
    /// invertible matrix.
    #[test]
    fn random_grids(
        us in prop::collection::vec(root(), 1..4),
        vs in prop::collection::vec(root(), 1..4),
        m in (1i64..4, -3i64..4, -3i64..4, 1i64..4),
    ) {
        let m = [m.0, m.1, m.2, m.3];
        prop_assume!(m[0] * m[3] - m[1] * m[2] != 0);
        let distinct = |xs: &[Rational]| xs.iter().enumerate().all(|(i, a)| xs[..i].iter().all(|b| a != b));
        prop_assume!(distinct(&us) && distinct(&vs));
        check(&us, &vs, m);
    }
}

#[test]
fn refinement_climbs_the_callers_ladder_and_counts_it() {
    // Roots (1/3, 2/7) and (3/5, 2/7), refined to 1e-14 on small boxes restricted from the exact
    // input: exactly with the default ladder, in MPFR without its exact level; both proven,
    // and each settled test counted at its level.
    let [f, g] = mixed(
        &product(0, &[q(1, 3), q(3, 5)]),
        &product(1, &[q(2, 7)]),
        [2, 1, -1, 1],
    );
    let mut opts = SystemOptions::default();
    opts.refine_width = 1e-14;
    let exact = solve_system(&[f.clone(), g.clone()], &[], &unit(), &opts);
    opts.ladder = limn::solver::Ladder {
        exact: false,
        ..limn::solver::Ladder::default()
    };
    let mpfr = solve_system(&[f, g], &[], &unit(), &opts);
    for (r, name) in [(&exact, "exact"), (&mpfr, "mpfr")] {
        assert_eq!(r.roots.len(), 2, "{name}: {r:?}");
        for root in &r.roots {
            let (u, v) = (root.enclosure[0], root.enclosure[1]);
            let on = |x: [f64; 2], t: f64| x[0] <= t && t <= x[1];
            assert!(
                on(v, 2.0 / 7.0) && (on(u, 1.0 / 3.0) || on(u, 0.6)),
                "{name}: {root:?}"
            );
        }
    }
    assert!(
        exact.escalations.exact > 0 && exact.escalations.mpfr.is_empty(),
        "{:?}",
        exact.escalations
    );
    assert!(
        mpfr.escalations.exact == 0 && !mpfr.escalations.mpfr.is_empty(),
        "{:?}",
        mpfr.escalations
    );
}
