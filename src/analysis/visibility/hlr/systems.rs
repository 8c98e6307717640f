//! The polynomial systems of a hidden-line drawing: image crossings of two segments, a side
//! crossing itself, a segment passing through a patch.

use crate::analysis::projection::ImagePolys;
use crate::analysis::visibility::hlr::lines::Segment;
use crate::bernstein::antisymmetric_quotient;
use crate::bernstein::Poly;
use crate::solver::system::separable::{Equation, Group, SeparableSystem};
use crate::solver::system::DyadicBoxN;

/// The self-crossings of a side's image: both coincidence equations divided by `t − s`.
pub(super) fn self_crossing_system(s: &Segment) -> (Vec<Poly>, DyadicBoxN) {
    let im = &s.image;
    let eqs = vec![
        antisymmetric_quotient(&im.x, &im.q),
        antisymmetric_quotient(&im.y, &im.q),
    ];
    let mut domain = s.domain.clone();
    domain.extend(s.domain.iter().copied());
    (eqs, domain)
}

/// The equations of a segment's variables: the silhouette function of an arc, the three of an
/// intersection curve, none for a curve of one parameter.
fn constraints(s: &Segment) -> impl Iterator<Item = &Poly> {
    s.constraint
        .iter()
        .chain(s.meet.iter().flat_map(|m| m.eqs.iter()))
}

/// The same image point, `x_a / q_a = x_b / q_b` and `y_a / q_a = y_b / q_b`, for groups whose
/// polynomials start with x, y, q.
fn image_coincidence() -> Vec<Equation> {
    vec![
        Equation::Ratio {
            first: [0, 2],
            second: [0, 2],
        },
        Equation::Ratio {
            first: [1, 2],
            second: [1, 2],
        },
    ]
}

/// The crossing system of two segments, separable: image coincidence (`x_a / q_a = x_b / q_b`,
/// the same for `y`) and their constraints, in the variables of `a` then of `b`.
pub(super) fn crossing_system<'a>(a: &'a Segment, b: &'a Segment) -> SeparableSystem<'a> {
    let group = |s: &'a Segment| Group {
        polys: [&s.image.x, &s.image.y, &s.image.q]
            .into_iter()
            .chain(constraints(s))
            .collect(),
        domain: &s.domain,
    };
    let mut equations = image_coincidence();
    for (g, s) in [a, b].into_iter().enumerate() {
        for k in 0..constraints(s).count() {
            equations.push(Equation::Zero {
                group: g,
                poly: 3 + k,
            });
        }
    }
    SeparableSystem {
        groups: [group(a), group(b)],
        equations,
    }
}

/// The penetration system of a segment and a patch, separable: the same point in space
/// (image coincidence and the same depth, `depth_a / w_a = depth_j / w_j`) and the segment's
/// constraint, in the variables of `a` then the patch's `(u, v)` on `unit`, the unit square.
pub(super) fn penetration_system<'a>(
    a: &'a Segment,
    j: &'a ImagePolys,
    unit: &'a DyadicBoxN,
) -> SeparableSystem<'a> {
    let polys = |im: &'a ImagePolys| vec![&im.x, &im.y, &im.q, &im.depth, &im.w];
    let mut first = polys(&a.image);
    first.extend(constraints(a));
    let mut equations = image_coincidence();
    equations.push(Equation::Ratio {
        first: [3, 4],
        second: [3, 4],
    });
    for k in 0..constraints(a).count() {
        equations.push(Equation::Zero {
            group: 0,
            poly: 5 + k,
        });
    }
    SeparableSystem {
        groups: [
            Group {
                polys: first,
                domain: &a.domain,
            },
            Group {
                polys: polys(j),
                domain: unit,
            },
        ],
        equations,
    }
}
