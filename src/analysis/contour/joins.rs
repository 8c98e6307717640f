//! Joining the crossings of two patches on a shared edge, where the join is proven
//! (`proofs/silhouette-join.md`): proportional side polynomials, exactly parallel normals, the
//! quotient tests, and the ends of curves at edges where the function jumps.

use crate::analysis::contour::curves::Node;
use crate::analysis::contour::sides::{
    both_on, corner_index, side_axis, side_crossings, side_of, side_point, side_polynomial,
};
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::model::SideUse;
use crate::number::Rational;
use crate::solver::plane_curve::zero_lines::{add_line, line_point};
use crate::solver::plane_curve::ArcKind;
use crate::solver::precision::Policy;
use crate::solver::{CrossingId, CurveTopology, Dyadic};
use crate::surface::{Edge, RationalPatch};
use std::collections::BTreeMap;

/// Whether two univariate polynomials are exact nonzero multiples of each other (after
/// reversing the second's parameter if asked): then they have the same zeros.
pub(crate) fn proportional(
    p: &Bernstein<Rational>,
    q: &Bernstein<Rational>,
    reversed: bool,
) -> bool {
    let q = if reversed {
        let mut c = q.coeffs().to_vec();
        c.reverse();
        Bernstein::new(q.degrees(), c).expect("same shape")
    } else {
        q.clone()
    };
    let d = p.degrees()[0].max(q.degrees()[0]);
    let (p, q) = (p.elevate_to(&[d]), q.elevate_to(&[d]));
    let Some(k) = p
        .coeffs()
        .iter()
        .position(|c| c.cmp0() != std::cmp::Ordering::Equal)
    else {
        return false;
    };
    if q.coeffs()[k].cmp0() == std::cmp::Ordering::Equal {
        return false;
    }
    p.coeffs()
        .iter()
        .zip(q.coeffs())
        .all(|(a, b)| Rational::from(a * &q.coeffs()[k]) == Rational::from(b * &p.coeffs()[k]))
}
/// The unnormalized normal `Ñ` of [`RationalPatch::normal`] on one side, in the side's
/// parameter: the same formula with every factor restricted to the side first (restriction
/// commutes with products and sums, and the derivatives are taken before it), so products of
/// univariate polynomials instead of bivariate ones.
fn normal_on_side(patch: &RationalPatch, e: Edge) -> [Bernstein<Rational>; 3] {
    use crate::surface::normal::cross;
    let on = |p: &Bernstein<Rational>| side_polynomial(p, e);
    if patch.is_polynomial() {
        let (tu, tv) = patch.tangents();
        return cross(&tu.each_ref().map(on), &tv.each_ref().map(on));
    }
    let [px, py, pz, w] = patch.homogeneous();
    let p = [px, py, pz];
    let pu = p.each_ref().map(|c| on(&c.deriv(0)));
    let pv = p.each_ref().map(|c| on(&c.deriv(1)));
    let (wu, wv) = (on(&w.deriv(0)), on(&w.deriv(1)));
    let (p, w) = (p.each_ref().map(on), on(&w));
    let a = cross(&pu, &pv);
    let b = cross(&pv, &p);
    let c = cross(&p, &pu);
    [0, 1, 2].map(|k| &(&(&w * &a[k]) + &(&wu * &b[k])) + &(&wv * &c[k]))
}

/// Whether the two patches' exact normals are parallel and nonzero along the shared edge
/// (tangent-plane continuity, proven exactly): `Ñ_a × Ñ_b ≡ 0` there and `Ñ_a · Ñ_b` has no
/// root on the edge. Then `g_a = λ g_b` with `λ ≠ 0` along the edge, for every view, so the
/// silhouette functions have the same zeros on it (`proofs/silhouette-join.md`).
pub(crate) fn parallel_normals(
    pa: &RationalPatch,
    ea: Edge,
    pb: &RationalPatch,
    eb: Edge,
    reversed: bool,
    policy: &mut Policy,
) -> bool {
    let side = |patch: &RationalPatch, e: Edge, rev: bool| -> [Bernstein<Rational>; 3] {
        let n = normal_on_side(patch, e);
        n.map(|p| {
            if rev {
                let mut c = p.coeffs().to_vec();
                c.reverse();
                Bernstein::new(p.degrees(), c).expect("same shape")
            } else {
                p
            }
        })
    };
    let (a, b) = (side(pa, ea, false), side(pb, eb, reversed));
    let cross_zero = (0..3).all(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        (&(&a[i] * &b[j]) - &(&a[j] * &b[i])).is_zero()
    });
    if !cross_zero {
        return false;
    }
    let dot = &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2]);
    let roots = crate::solver::isolate_roots(&dot, 40, policy);
    // A normal vanishing exactly at an end of the edge is a corner, which is joined by vertex
    // identity and excluded from the side's crossings: only interior zeros matter.
    let interior = |r: &crate::solver::Root| !matches!(r, crate::solver::Root::At { t } if *t == Dyadic::ZERO || *t == Dyadic::ONE);
    !roots.identically_zero && !roots.roots.iter().any(interior) && roots.unresolved.is_empty()
}
/// Union-find over model nodes.
pub(crate) struct Joins {
    pub(crate) parent: BTreeMap<Node, Node>,
}
impl Joins {
    pub(crate) fn find(&mut self, x: Node) -> Node {
        let p = *self.parent.get(&x).unwrap_or(&x);
        if p == x {
            return x;
        }
        let r = self.find(p);
        self.parent.insert(x, r);
        r
    }
    pub(crate) fn union(&mut self, a: Node, b: Node) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent.insert(hi, lo);
        }
    }
}
/// Joins the crossings on a shared edge, if the silhouette functions of the two patches are
/// proportional on it (so their zeros are the same points). Returns whether it did.
pub(crate) fn join_side(
    tops: &[CurveTopology],
    gs: &[Bernstein<Rational>],
    patches: Option<&[&RationalPatch]>,
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
    policy: &mut Policy,
) -> bool {
    let pa = side_polynomial(&gs[a.patch], a.edge);
    let pb = side_polynomial(&gs[b.patch], b.edge);
    let reversed = a.reversed != b.reversed;
    if pa.is_zero() || pb.is_zero() {
        return false;
    }
    if !proportional(&pa, &pb, reversed)
        && !patches.is_some_and(|p| {
            parallel_normals(p[a.patch], a.edge, p[b.patch], b.edge, reversed, policy)
        })
    {
        return false;
    }
    let ca = side_crossings(&tops[a.patch], a.edge);
    let mut cb = side_crossings(&tops[b.patch], b.edge);
    if ca.len() != cb.len() {
        return false;
    }
    if reversed {
        cb.reverse();
    }
    // Same zero set, both lists sorted along the edge: the i-th are the same point. Check
    // that the certified intervals agree (a consistency check, not needed for the proof).
    let map = |d: Dyadic| {
        if reversed {
            1.0 - d.to_f64()
        } else {
            d.to_f64()
        }
    };
    for ((alo, ahi, ida), (blo, bhi, idb)) in ca.iter().zip(&cb) {
        let (b0, b1) = (map(*blo).min(map(*bhi)), map(*blo).max(map(*bhi)));
        if b1 < alo.to_f64() || b0 > ahi.to_f64() {
            return false;
        }
        joins.union((a.patch, *ida), (b.patch, *idb));
    }
    true
}
/// Where the function jumps across a shared edge (both side polynomials nonzero, not
/// proportional): crossings of the two patches at the same exact parameter are the same point
/// of both curves and are joined; every other crossing of either patch must be proven not to
/// be a zero of the other patch's function there (its exact location, a point or its isolating
/// interval on the side mapped through the reversal, holds no root of the other side
/// polynomial: exact evaluation, or root isolation on the interval), so the curve ends there.
/// Returns whether all of it was proven (then the joins are made).
pub(crate) fn ends_at_edge(
    tops: &[CurveTopology],
    gs: &[Bernstein<Rational>],
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
    policy: &mut Policy,
) -> bool {
    let reversed = a.reversed != b.reversed;
    let (pa, pb) = (
        side_polynomial(&gs[a.patch], a.edge),
        side_polynomial(&gs[b.patch], b.edge),
    );
    if pa.is_zero() || pb.is_zero() {
        return false;
    }
    let mut avoids = |crossings: Vec<(Dyadic, Dyadic, CrossingId)>,
                      t: &CurveTopology,
                      other: &Bernstein<Rational>| {
        crossings.into_iter().all(|(lo, hi, id)| {
            let (lo, hi) = match id {
                CrossingId::Segment { .. } => t.intervals.get(&id).copied().unwrap_or((lo, hi)),
                CrossingId::Exact { .. } => (lo, hi),
            };
            let (lo, hi) = if reversed {
                (hi.one_minus(), lo.one_minus())
            } else {
                (lo, hi)
            };
            if lo == hi {
                return other.eval(&[lo.to_rational()]).cmp0() != std::cmp::Ordering::Equal;
            }
            let r = crate::solver::isolate_roots_in(other, lo, hi, 40, policy);
            r.roots.is_empty() && r.unresolved.is_empty() && !r.identically_zero
        })
    };
    // Exact crossings at the same parameter (in a's parameter along the edge).
    let exact = |t: &CurveTopology, edge: Edge, map: bool| -> Vec<(Dyadic, CrossingId)> {
        side_crossings(t, edge)
            .into_iter()
            .filter(|(lo, hi, _)| lo == hi)
            .map(|(lo, _, id)| (if map && reversed { lo.one_minus() } else { lo }, id))
            .collect()
    };
    let (ea, eb) = (
        exact(&tops[a.patch], a.edge, false),
        exact(&tops[b.patch], b.edge, true),
    );
    let pairs: Vec<(CrossingId, CrossingId)> = ea
        .iter()
        .filter_map(|(t, ida)| eb.iter().find(|(s, _)| s == t).map(|(_, idb)| (*ida, *idb)))
        .collect();
    let unpaired = |t: &CurveTopology, edge: Edge, mine: bool| {
        side_crossings(t, edge)
            .into_iter()
            .filter(|x| {
                !pairs
                    .iter()
                    .any(|p| if mine { p.0 == x.2 } else { p.1 == x.2 })
            })
            .collect::<Vec<_>>()
    };
    let proven = avoids(unpaired(&tops[a.patch], a.edge, true), &tops[a.patch], &pb)
        && avoids(unpaired(&tops[b.patch], b.edge, false), &tops[b.patch], &pa);
    if proven {
        for (ida, idb) in pairs {
            joins.union((a.patch, ida), (b.patch, idb));
        }
    }
    proven
}
/// Joins the crossings of two patches with a side on which the silhouette lies, when the
/// solved polynomials (the silhouette functions with the side's factor divided out) are exactly
/// proportional on it: then their roots on the side, where each patch's curve meets it, are the
/// same points, and the i-th crossings along the side are joined. Patch `b`'s arcs along the
/// side have been dropped already (patch `a`'s, split at the same points, stand for both).
pub(crate) fn join_by_quotients(
    tops: &[CurveTopology],
    solved: &[Bernstein<Rational>],
    a: SideUse,
    b: SideUse,
    reversed: bool,
    joins: &mut Joins,
) -> bool {
    // Every root on the side must be a listed crossing: nothing undecided in either patch.
    if !tops[a.patch].unresolved.is_empty() || !tops[b.patch].unresolved.is_empty() {
        return false;
    }
    let pa = side_polynomial(&solved[a.patch], a.edge);
    let pb = side_polynomial(&solved[b.patch], b.edge);
    if pa.is_zero() || pb.is_zero() || !proportional(&pa, &pb, reversed) {
        return false;
    }
    // Crossings inside the side (corners are joined as vertices), in order along it.
    let inside = |t: &CurveTopology, edge: Edge| -> Vec<(Dyadic, Dyadic, CrossingId)> {
        let mut v: Vec<(Dyadic, Dyadic, CrossingId)> = Vec::new();
        let ids = t
            .arcs
            .iter()
            .filter(|a| a.kind != ArcKind::OnEdge)
            .flat_map(|a| [a.from, a.to])
            .chain(t.touches.iter().copied());
        for id in ids {
            let sides = side_of(&id);
            let Some(&(_, s0, s1)) = sides.iter().find(|s| s.0 == edge) else {
                continue;
            };
            if sides.len() > 1 || corner_index(&id).is_some() {
                continue;
            }
            let (lo, hi) = match id {
                CrossingId::Exact { .. } => (s0, s1),
                CrossingId::Segment { .. } => t.intervals.get(&id).copied().unwrap_or((s0, s1)),
            };
            if !v.iter().any(|x| x.2 == id) {
                v.push((lo, hi, id));
            }
        }
        v.sort();
        v
    };
    let ca = inside(&tops[a.patch], a.edge);
    let mut cb = inside(&tops[b.patch], b.edge);
    if ca.len() != cb.len() {
        return false;
    }
    if reversed {
        cb.reverse();
    }
    for (x, y) in ca.iter().zip(&cb) {
        joins.union((a.patch, x.2), (b.patch, y.2));
    }
    true
}
/// Joins a shared edge on which both silhouette functions vanish identically: the edge is
/// part of the silhouette, exactly. Both patches' arcs along it are replaced by one chain
/// (kept in patch `a`) through all their points, and `b`'s crossings on the edge are joined to
/// `a`'s at the same (exact, dyadic) parameter (`proofs/silhouette-join.md`).
pub(crate) fn join_zero_side(
    tops: &mut [CurveTopology],
    gs: &[Bernstein<Rational>],
    solved: &[Bernstein<Rational>],
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
) -> bool {
    let (za, zb) = (
        side_polynomial(&gs[a.patch], a.edge).is_zero(),
        side_polynomial(&gs[b.patch], b.edge).is_zero(),
    );
    match (za, zb) {
        (false, false) => return false,
        (true, false) => return join_one_sided(tops, a, b, joins),
        (false, true) => return join_one_sided(tops, b, a, joins),
        (true, true) => {}
    }
    let reversed = a.reversed != b.reversed;
    // The exact parameter along the side of a crossing on it: an exact point, or a root
    // located exactly (a point interval). `Err` for a crossing only known in an interval.
    let param = |t: &CurveTopology, id: &CrossingId, edge: Edge| -> Option<Result<Dyadic, ()>> {
        let side = side_of(id).into_iter().find(|s| s.0 == edge)?;
        if side.1 == side.2 {
            return Some(Ok(side.1));
        }
        match t.intervals.get(id) {
            Some(&(lo, hi)) if lo == hi => Some(Ok(lo)),
            _ => Some(Err(())),
        }
    };
    let mut ts = vec![Dyadic::ZERO, Dyadic::ONE];
    // Crossings that are not the side point itself, to join to it: (patch, id, t along a).
    let mut nodes = Vec::new();
    for (patch, edge, is_b) in [(a.patch, a.edge, false), (b.patch, b.edge, true)] {
        for arc in &tops[patch].arcs {
            for id in [arc.from, arc.to] {
                match param(&tops[patch], &id, edge) {
                    None => {}
                    // Where the curve meets the side at a point known only within an
                    // interval, its order among the other patch's points is not proven: keep
                    // the side once (patch a's arcs along it; b's are the same curve) and
                    // leave b's crossings on it unjoined.
                    Some(Err(())) => {
                        tops[b.patch].arcs.retain(|arc| {
                            !(arc.kind == ArcKind::OnEdge && both_on(&arc.from, &arc.to, b.edge))
                        });
                        return join_by_quotients(tops, solved, a, b, reversed, joins);
                    }
                    Some(Ok(t)) => {
                        let ta = if is_b && reversed { t.one_minus() } else { t };
                        ts.push(ta);
                        if is_b || side_point(edge, t) != id {
                            nodes.push((patch, id, ta));
                        }
                    }
                }
            }
        }
    }
    for (patch, edge) in [(a.patch, a.edge), (b.patch, b.edge)] {
        tops[patch]
            .arcs
            .retain(|arc| !(arc.kind == ArcKind::OnEdge && both_on(&arc.from, &arc.to, edge)));
    }
    ts.sort();
    ts.dedup();
    let ta = &mut tops[a.patch];
    for w in ts.windows(2) {
        let (from, to) = (side_point(a.edge, w[0]), side_point(a.edge, w[1]));
        for id in [from, to] {
            if let CrossingId::Exact { u, v } = id {
                let p = [u.to_f64(), v.to_f64()];
                ta.locations.insert(id, Rect::point(p));
            }
        }
        ta.arcs.push(crate::solver::plane_curve::Arc {
            from,
            to,
            cell: crate::solver::DyadicBox::UNIT,
            kind: ArcKind::OnEdge,
        });
    }
    for (patch, id, t) in nodes {
        joins.union((patch, id), (a.patch, side_point(a.edge, t)));
    }
    true
}
/// Joins a shared edge that lies on the curve of patch `zero` only (its function vanishes on
/// the side, the other's does not: the function jumps across the edge). Every point of the edge
/// is on the curve, so each crossing of `other` on it is joined to the point of `zero`'s side
/// arcs with the same parameter, which is inserted as a node. Proven only for crossings at exact
/// (dyadic) parameters that do not fall strictly inside an isolating interval of `zero`'s own
/// crossings on the side; otherwise nothing is changed and the edge stays unjoined.
pub(crate) fn join_one_sided(
    tops: &mut [CurveTopology],
    zero: SideUse,
    other: SideUse,
    joins: &mut Joins,
) -> bool {
    let reversed = zero.reversed != other.reversed;
    let own = side_crossings(&tops[zero.patch], zero.edge);
    let mut extra = Vec::new();
    for (lo, hi, id) in side_crossings(&tops[other.patch], other.edge) {
        if corner_index(&id).is_some() {
            continue; // corners are joined as vertices
        }
        let t = match id {
            CrossingId::Exact { .. } => lo,
            CrossingId::Segment { .. } => match tops[other.patch].intervals.get(&id) {
                Some(&(l, h)) if l == h => l,
                _ => return false,
            },
        };
        debug_assert!(lo <= t && t <= hi);
        let t = if reversed { t.one_minus() } else { t };
        let inside = own.iter().any(|&(l, h, oid)| {
            let (l, h) = match oid {
                CrossingId::Segment { .. } => tops[zero.patch]
                    .intervals
                    .get(&oid)
                    .copied()
                    .unwrap_or((l, h)),
                CrossingId::Exact { .. } => (l, h),
            };
            l < t && t < h
        });
        if inside {
            return false;
        }
        extra.push((id, t));
    }
    let (fixed, at_one) = side_axis(zero.edge);
    let c = if at_one { Dyadic::ONE } else { Dyadic::ZERO };
    let tz = &mut tops[zero.patch];
    tz.arcs
        .retain(|arc| !(arc.kind == ArcKind::OnEdge && both_on(&arc.from, &arc.to, zero.edge)));
    let at: Vec<Dyadic> = extra.iter().map(|e| e.1).collect();
    add_line(tz, fixed, c, &at);
    for (id, t) in extra {
        joins.union((other.patch, id), (zero.patch, line_point(fixed, c, t)));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::shapes;

    /// The normal restricted to a side equals the side of the normal, for rational patches
    /// (a torus, a sphere with poles) and a polynomial one.
    #[test]
    fn the_normal_on_a_side_is_the_side_of_the_normal() {
        let mut patches = shapes::torus(&Rational::from(3), &Rational::from(1));
        patches.extend(shapes::sphere(&Rational::from(2)));
        patches.push(shapes::double_well(false));
        for (i, patch) in patches.iter().enumerate() {
            let full = patch.normal();
            for e in Edge::ALL {
                let side = normal_on_side(patch, e);
                for k in 0..3 {
                    let want = side_polynomial(&full[k], e);
                    for t in [0, 1, 2, 5, 7] {
                        let t = [Rational::from((t, 7))];
                        assert_eq!(side[k].eval(&t), want.eval(&t), "patch {i} {e:?} {k}");
                    }
                }
            }
        }
    }
}
