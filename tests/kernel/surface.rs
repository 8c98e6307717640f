//! The exact normal of rational patches, against its defining identities and closed forms.

use limn::number::Rational;
use limn::testing::{shapes, strategies, ArbitraryPatch};
use proptest::prelude::*;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

fn eval3(
    p: &[limn::bernstein::Bernstein<Rational>; 3],
    u: &Rational,
    v: &Rational,
) -> [Rational; 3] {
    let x = [u.clone(), v.clone()];
    [p[0].eval(&x), p[1].eval(&x), p[2].eval(&x)]
}

fn cross(a: &[Rational; 3], b: &[Rational; 3]) -> [Rational; 3] {
    [
        Rational::from(&a[1] * &b[2]) - Rational::from(&a[2] * &b[1]),
        Rational::from(&a[2] * &b[0]) - Rational::from(&a[0] * &b[2]),
        Rational::from(&a[0] * &b[1]) - Rational::from(&a[1] * &b[0]),
    ]
}

fn params() -> impl Strategy<Value = (Rational, Rational)> {
    ((0i64..=12), (0i64..=12)).prop_map(|(a, b)| (q(a, 12), q(b, 12)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(limn::testing_cases(48)))]

    /// Ñ · W = T_u × T_v exactly (so Ñ = W³ S_u × S_v), and the degree bound of
    /// proofs/normal-degree.md holds.
    #[test]
    fn normal_identity_and_degree(p in strategies::degenerate_patch(3), (u, v) in params()) {
        let n = p.normal();
        let (tu, tv) = p.tangents();
        let [m, nn] = p.degree();
        let w = p.homogeneous()[3].eval(&[u.clone(), v.clone()]);
        let lhs = eval3(&n, &u, &v);
        let rhs = cross(&eval3(&tu, &u, &v), &eval3(&tv, &u, &v));
        if p.is_polynomial() {
            prop_assert_eq!(lhs, rhs);
            for c in &n {
                prop_assert!(c.degrees()[0] < 2 * m && c.degrees()[1] < 2 * nn, "degrees {:?} for ({m},{nn})", c.degrees());
            }
        } else {
            let scaled: Vec<Rational> = lhs.iter().map(|c| Rational::from(c * &w)).collect();
            prop_assert_eq!(scaled, rhs.to_vec());
            for c in &n {
                prop_assert!(c.degrees()[0] <= 3 * m - 2 && c.degrees()[1] <= 3 * nn - 2, "degrees {:?} for ({m},{nn})", c.degrees());
            }
        }
    }

    /// A planar patch's normal is perpendicular to its plane's directions: Ñ × n₀ = 0.
    #[test]
    fn planar_normal_is_constant_direction(p in strategies::planar_patch(3), (u, v) in params()) {
        let n = eval3(&p.normal(), &u, &v);
        // The plane is the image of z = 0 under a rotation; the normal of the plane is the
        // rotated z axis, which is the cross product of two rotated axes: any two chords.
        let pts = p.points();
        let a = [0, 1, 2].map(|k| Rational::from(&pts[1][k] - &pts[0][k]));
        let b = [0, 1, 2].map(|k| Rational::from(&pts[pts.len() - 1][k] - &pts[0][k]));
        let n0 = cross(&a, &b);
        if n0.iter().any(|c| *c != 0) {
            prop_assert!(cross(&n, &n0).iter().all(|c| *c == 0));
        }
    }
}

#[test]
fn sphere_normal_points_outward_and_vanishes_at_poles() {
    let r = q(5, 2);
    for patch in shapes::sphere(&r) {
        let n = patch.normal();
        for (a, b) in [(1, 3), (2, 5), (6, 1), (3, 3)] {
            let (u, v) = (q(a, 7), q(b, 7));
            let s = patch.eval(&u, &v);
            let nv = eval3(&n, &u, &v);
            assert!(
                cross(&nv, &s).iter().all(|c| *c == 0),
                "normal parallel to the radius"
            );
            let dot: Rational = (0..3).map(|k| Rational::from(&nv[k] * &s[k])).sum();
            assert!(dot > 0, "outward");
        }
        // The pole side: v = 0 for the southern patches, v = 1 for the northern ones.
        let pole = if patch.point(0, 0)[2] < 0 {
            q(0, 1)
        } else {
            q(1, 1)
        };
        let nv = eval3(&n, &q(1, 3), &pole);
        assert!(
            nv.iter().all(|c| *c == 0),
            "the normal vanishes on the collapsed side"
        );
    }
}

#[test]
fn rational_normal_degree_is_tight_for_the_torus() {
    // A biquadratic rational patch: formal degree (5,5), reduced bound (4,4); the torus patch
    // reaches it in at least one coordinate, so the bound is not loose.
    let t = shapes::torus(&q(3, 1), &q(1, 1));
    let n = t[5].normal();
    let max_u = n.iter().map(|c| c.degrees()[0]).max().unwrap();
    let max_v = n.iter().map(|c| c.degrees()[1]).max().unwrap();
    assert!(max_u <= 4 && max_v <= 4);
    assert!(max_u == 4 || max_v == 4, "degrees ({max_u},{max_v})");
}

quickcheck::quickcheck! {
    /// Points of a patch lie in the box of its control points (positive weights).
    fn points_lie_in_the_control_box(p: ArbitraryPatch, a: u8, b: u8) -> bool {
        let (u, v) = (q(i64::from(a), 255), q(i64::from(b), 255));
        let s = p.0.eval(&u, &v);
        let [lo, hi] = p.0.control_box();
        (0..3).all(|k| lo[k] <= s[k] && s[k] <= hi[k])
    }
}

#[test]
fn bilinear_plane_has_constant_normal() {
    let sq = shapes::plane_square(&q(2, 1));
    let n = sq.normal();
    for c in &n {
        assert_eq!(c.degrees(), &[0, 0]);
    }
    assert_eq!(eval3(&n, &q(1, 2), &q(1, 3)), [q(0, 1), q(0, 1), q(4, 1)]);
}
