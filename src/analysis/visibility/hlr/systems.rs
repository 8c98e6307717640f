//! The polynomial systems of a hidden-line drawing: image crossings of two segments, a side
//! crossing itself, a segment passing through a patch.

use crate::analysis::projection::{lift, ImagePolys};
use crate::analysis::visibility::hlr::lines::Segment;
use crate::bernstein::antisymmetric_quotient;
use crate::solver::dyadic::Dyadic;
use crate::solver::system::DyadicBoxN;

use crate::bernstein::Poly;

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

/// The crossing system of two segments: image coincidence and their constraints, in the
/// variables of `a` then of `b`.
pub(super) fn crossing_system(a: &Segment, b: &Segment) -> (Vec<Poly>, DyadicBoxN) {
    let (na, nb) = (a.domain.len(), b.domain.len());
    let n = na + nb;
    let la = |p: &Poly| lift(p, n, 0);
    let lb = |p: &Poly| lift(p, n, na);
    let coincide =
        |fa: &Poly, fb: &Poly| &(&la(fa) * &lb(&b.image.q)) - &(&lb(fb) * &la(&a.image.q));
    let mut eqs = vec![
        coincide(&a.image.x, &b.image.x),
        coincide(&a.image.y, &b.image.y),
    ];
    eqs.extend(a.constraint.iter().map(la));
    eqs.extend(b.constraint.iter().map(lb));
    let mut domain = a.domain.clone();
    domain.extend(b.domain.iter().copied());
    (eqs, domain)
}

/// The penetration system of a segment and a patch: the same point in space.
pub(super) fn penetration_system(a: &Segment, j: &ImagePolys) -> (Vec<Poly>, DyadicBoxN) {
    let na = a.domain.len();
    let n = na + 2;
    let la = |p: &Poly| lift(p, n, 0);
    let lj = |p: &Poly| lift(p, n, na);
    let coincide =
        |fa: &Poly, fj: &Poly, da: &Poly, dj: &Poly| &(&la(fa) * &lj(dj)) - &(&lj(fj) * &la(da));
    let mut eqs = vec![
        coincide(&a.image.x, &j.x, &a.image.q, &j.q),
        coincide(&a.image.y, &j.y, &a.image.q, &j.q),
        coincide(&a.image.depth, &j.depth, &a.image.w, &j.w),
    ];
    eqs.extend(a.constraint.iter().map(la));
    let mut domain = a.domain.clone();
    domain.extend([(Dyadic::ZERO, Dyadic::ONE), (Dyadic::ZERO, Dyadic::ONE)]);
    (eqs, domain)
}
