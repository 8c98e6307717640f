//! proptest strategies for random and degenerate inputs.
//!
//! The degenerate families are exactly degenerate (a planar patch, a cylinder, a collapsed
//! edge, a patch with a zero-length row of control points) or perturbed from exact
//! degeneracy by 2^-40..2^-50, where floating-point predicates break first.

use super::shapes;
use crate::bernstein::Bernstein;
use crate::number::Rational;
use crate::surface::{Point3, RationalPatch};
use proptest::prelude::*;

/// A small exact rational: p / q with |p| <= 64, 1 <= q <= 16.
pub fn small_rational() -> impl Strategy<Value = Rational> {
    (-64i64..=64, 1i64..=16).prop_map(|(p, q)| Rational::from((p, q)))
}

/// 2^-e for e in 40..=50: the size of the perturbations.
pub fn tiny() -> impl Strategy<Value = Rational> {
    (40u32..=50, prop::bool::ANY).prop_map(|(e, neg)| {
        let t = Rational::from((rug::Integer::from(1), rug::Integer::from(1) << e));
        if neg {
            -t
        } else {
            t
        }
    })
}

/// A positive weight: 1/4 .. 4, rational.
pub fn weight() -> impl Strategy<Value = Rational> {
    (1i64..=16).prop_map(|k| Rational::from((k, 4)))
}

fn point() -> impl Strategy<Value = Point3> {
    [small_rational(), small_rational(), small_rational()]
}

/// A generic random rational patch of degree (m, n) with 1 <= m, n <= `max_degree`.
pub fn patch(max_degree: usize) -> impl Strategy<Value = RationalPatch> {
    (1..=max_degree, 1..=max_degree, prop::bool::ANY).prop_flat_map(|(m, n, rational)| {
        let count = (m + 1) * (n + 1);
        (
            prop::collection::vec(point(), count),
            prop::collection::vec(weight(), count),
        )
            .prop_map(move |(pts, ws)| {
                if rational {
                    RationalPatch::new([m, n], pts, ws).expect("valid")
                } else {
                    RationalPatch::polynomial([m, n], pts).expect("valid")
                }
            })
    })
}

/// A patch whose control points all lie in one plane (z = 0, then rotated exactly).
pub fn planar_patch(max_degree: usize) -> impl Strategy<Value = RationalPatch> {
    (patch(max_degree), 0usize..3, 1i64..5, 1i64..5).prop_map(|(p, axis, a, b)| {
        let flat = p.map_points(|q| [q[0].clone(), q[1].clone(), Rational::new()]);
        shapes::transform(
            &flat,
            &shapes::rotation(axis, a, b),
            &[Rational::new(), Rational::new(), Rational::new()],
        )
    })
}

/// A patch with its v = 0 side collapsed to one point (a pole, a cone apex).
pub fn collapsed_edge_patch(max_degree: usize) -> impl Strategy<Value = RationalPatch> {
    patch(max_degree).prop_map(|p| {
        let [m, n] = p.degree();
        let apex = p.point(0, 0).clone();
        let pts = (0..=m)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                if j == 0 {
                    apex.clone()
                } else {
                    p.point(i, j).clone()
                }
            })
            .collect();
        RationalPatch::new([m, n], pts, p.weights().to_vec()).expect("valid")
    })
}

/// A quarter cylinder, exactly rotated and scaled (parabolic everywhere).
pub fn cylinder_patch() -> impl Strategy<Value = RationalPatch> {
    (1i64..8, 1i64..8, 0usize..3, 1i64..5, 1i64..5).prop_map(|(r, h, axis, a, b)| {
        let c = shapes::cylinder_quarter(&Rational::from((r, 2)), &Rational::from(h));
        shapes::transform(
            &c,
            &shapes::rotation(axis, a, b),
            &[Rational::new(), Rational::new(), Rational::new()],
        )
    })
}

/// A patch perturbed from `base` by 2^-40..2^-50 in one control point coordinate.
pub fn perturbed(
    base: impl Strategy<Value = RationalPatch>,
) -> impl Strategy<Value = RationalPatch> {
    (base, any::<prop::sample::Index>(), 0usize..3, tiny()).prop_map(|(p, idx, k, eps)| {
        let which = idx.index(p.points().len());
        let pts = p
            .points()
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let mut q = q.clone();
                if i == which {
                    q[k] += &eps;
                }
                q
            })
            .collect();
        RationalPatch::new(p.degree(), pts, p.weights().to_vec()).expect("valid")
    })
}

/// Any of the degenerate families, exact or perturbed, mixed with generic patches.
pub fn degenerate_patch(max_degree: usize) -> impl Strategy<Value = RationalPatch> {
    prop_oneof![
        patch(max_degree),
        planar_patch(max_degree),
        collapsed_edge_patch(max_degree),
        cylinder_patch(),
        perturbed(planar_patch(max_degree)),
        perturbed(collapsed_edge_patch(max_degree)),
        perturbed(cylinder_patch()),
    ]
}

/// A random exact Bernstein polynomial in 1..=`max_vars` variables of degree <= `max_degree`
/// in each, with some exactly-zero and near-degenerate coefficients.
pub fn bernstein(max_vars: usize, max_degree: usize) -> impl Strategy<Value = Bernstein<Rational>> {
    let coeff = prop_oneof![
        4 => small_rational(),
        1 => Just(Rational::new()),
        1 => tiny(),
    ];
    prop::collection::vec(0..=max_degree, 1..=max_vars).prop_flat_map(move |degs| {
        let n: usize = degs.iter().map(|d| d + 1).product();
        prop::collection::vec(coeff.clone(), n)
            .prop_map(move |c| Bernstein::new(&degs, c).expect("valid"))
    })
}

/// A random system for the n-variable curve solver: `nvars − 1` exact polynomials in `nvars`
/// variables (2..=4), each of degree ≤ `max_degree` in every variable, with exactly-zero and
/// tiny coefficients mixed in (curves through grid points, near-tangencies, identically zero
/// equations).
pub fn space_curve_system(
    nvars: usize,
    max_degree: usize,
) -> impl Strategy<Value = Vec<Bernstein<Rational>>> {
    assert!((2..=4).contains(&nvars), "2 to 4 variables");
    let coeff = prop_oneof![
        4 => small_rational(),
        1 => Just(Rational::new()),
        1 => tiny(),
    ];
    let poly = prop::collection::vec(0..=max_degree, nvars).prop_flat_map(move |degs| {
        let n: usize = degs.iter().map(|d| d + 1).product();
        prop::collection::vec(coeff.clone(), n)
            .prop_map(move |c| Bernstein::new(&degs, c).expect("valid"))
    });
    prop::collection::vec(poly, nvars - 1)
}
