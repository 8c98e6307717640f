//! The lemmas that exclude, around a vertex two segments share, a box of their crossing system
//! that holds no crossing other than the shared points (`proofs/hidden-lines.md`).

use crate::analysis::visibility::sheets::{
    fold_box_around, injective_box_past, quotient_jet, range_on,
};

use crate::analysis::visibility::hlr::lines::{
    dyadic_ceil, dyadic_floor, find_monotone, monotone_along, narrow_to_curve, param_box,
    strict_sign, sub_domain, Key, Segment, Vertex,
};
use crate::analysis::visibility::hlr::result::LineKind;
use crate::analysis::visibility::scene::Scene;
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::system::DyadicBoxN;

use crate::bernstein::Poly;

/// Two consecutive segments of one line whose images are monotone in a common direction with
/// the same orientation: their union's image is monotone, so they meet only at their shared
/// end (proofs/hidden-lines.md).
pub(super) fn common_monotone(a: &Segment, b: &Segment) -> bool {
    let (Some((ea, sa)), Some((eb, sb))) = (&a.monotone, &b.monotone) else {
        return false;
    };
    monotone_along(&b.tangent, ea, &b.domain) == Some(*sa)
        || monotone_along(&a.tangent, eb, &a.domain) == Some(*sb)
}

/// A box of the pair's product domain around a shared vertex that holds no crossing of the
/// two segments other than points they share in space (which are vertices, where both are
/// cut anyway), proven by one of the lemmas of `proofs/hidden-lines.md`; `None` if none
/// applies.
pub(super) fn vertex_exclusion(
    scene: &Scene,
    a: &Segment,
    b: &Segment,
    va: &Vertex,
    vb: &Vertex,
) -> Option<DyadicBoxN> {
    // A patch both lie on near the vertex: the fold lemma (if one is a silhouette arc of it)
    // or the injective box.
    for (p, lo, hi) in &va.uv {
        let Some((_, lo2, hi2)) = vb.uv.iter().find(|x| x.0 == *p) else {
            continue;
        };
        if !a.on.iter().any(|x| x.0 == *p) || !b.on.iter().any(|x| x.0 == *p) {
            continue;
        }
        let lo: [Rational; 2] = std::array::from_fn(|k| lo[k].clone().min(lo2[k].clone()));
        let hi: [Rational; 2] = std::array::from_fn(|k| hi[k].clone().max(hi2[k].clone()));
        let lo = lo.map(|x| dyadic_floor(&x));
        let hi = hi.map(|x| dyadic_ceil(&x));
        let fold = [a, b]
            .iter()
            .any(|s| s.kind == LineKind::Silhouette && s.patch == *p);
        // The injective box may reach past the square: a vertex on its side then has room
        // around it on every side (lemma I).
        let bx = if fold {
            fold_box_around(scene, *p, &lo, &hi).map(|b| param_box(&b))
        } else {
            injective_box_past(scene, *p, &lo, &hi)
        };
        if let Some(bx) = bx {
            if let (Some(da), Some(db)) = (
                sub_domain(a, *p, &bx, Some(va.param)),
                sub_domain(b, *p, &bx, Some(vb.param)),
            ) {
                return Some(da.into_iter().chain(db).collect());
            }
        }
    }
    // Different patches: two sides leaving an exact corner along one image tangent, or two
    // images leaving the vertex on opposite sides of a line.
    tangent_corner(a, b, va, vb).or_else(|| opposite_monotone(a, b, va, vb))
}

/// Lemma L3 (proofs/hidden-lines.md): two sides leave an exact corner V in the same image
/// direction τ. Near V each is a graph `ν = f(σ)` over the coordinate σ along τ (σ' > 0
/// moving away from V), with `f(0)` and `f'(0)` equal for both; if the second derivatives
/// `f''` of the two have disjoint ranges, `f_a − f_b` is strictly convex or concave with a
/// double zero at 0, so the images meet only at V.
pub(super) fn tangent_corner(
    a: &Segment,
    b: &Segment,
    va: &Vertex,
    vb: &Vertex,
) -> Option<DyadicBoxN> {
    if a.constraint.is_some() || b.constraint.is_some() || !matches!(va.key, Key::Corner(_)) {
        return None;
    }
    // The exact image tangent at the corner, oriented away from it.
    let away = |s: &Segment, v: &Vertex| -> Option<([Rational; 2], bool)> {
        let at_start = v.param[1] <= 0.0;
        let at_end = v.param[0] >= 1.0;
        if at_start == at_end {
            return None;
        }
        let t = Rational::from(i32::from(at_end));
        let d = s.tangent.clone().map(|p| p.eval(std::slice::from_ref(&t)));
        Some((if at_start { d } else { d.map(|x| -x) }, at_start))
    };
    let (da, up_a) = away(a, va)?;
    let (db, up_b) = away(b, vb)?;
    let cross = Rational::from(&da[0] * &db[1]) - Rational::from(&da[1] * &db[0]);
    let dot = Rational::from(&da[0] * &db[0]) + Rational::from(&da[1] * &db[1]);
    if cross != 0 || dot <= 0 {
        return None;
    }
    let tau = da;
    let nu = [Rational::from(-&tau[1]), tau[0].clone()];
    for k in 1..=10u32 {
        let w = Dyadic::new(1, k);
        let piece = |up: bool| {
            if up {
                (Dyadic::ZERO, w)
            } else {
                (w.one_minus(), Dyadic::ONE)
            }
        };
        let (pa, pb) = (piece(up_a), piece(up_b));
        let (Some(ka), Some(kb)) = (
            graph_curvature(a, pa, up_a, &tau, &nu),
            graph_curvature(b, pb, up_b, &tau, &nu),
        ) else {
            continue;
        };
        if ka.lo() > kb.hi() || kb.lo() > ka.hi() {
            return Some(vec![pa, pb]);
        }
    }
    None
}

/// The range of `d²ν/dσ²` along a side's image over a parameter interval, with σ = τ·c and
/// ν = ν·c, `None` unless σ is strictly increasing in the direction `up` (increasing t) or
/// its reverse.
pub(super) fn graph_curvature(
    s: &Segment,
    piece: (Dyadic, Dyadic),
    up: bool,
    tau: &[Rational; 2],
    nu: &[Rational; 2],
) -> Option<Interval> {
    let (lo, hi) = ([piece.0.to_f64()], [piece.1.to_f64()]);
    let jet = |p: &Poly| -> [Interval; 6] {
        let r = |q: &Poly| range_on(&q.convert(Precision::F64), &lo, &hi);
        let zero = Interval::point(0.0);
        [
            r(p),
            r(&p.deriv(0)),
            zero,
            r(&p.deriv(0).deriv(0)),
            zero,
            zero,
        ]
    };
    let q = jet(&s.image.q);
    let x = quotient_jet(&jet(&s.image.x), &q)?;
    let y = quotient_jet(&jet(&s.image.y), &q)?;
    let t = |e: &[Rational; 2]| {
        let (e0, e1) = (
            Interval::from_rational(&e[0], Precision::F64),
            Interval::from_rational(&e[1], Precision::F64),
        );
        // First and second derivatives along the away orientation (d/ds = ∓ d/dt).
        let d1 = e0.mul(&x[1]).add(&e1.mul(&y[1]));
        let d2 = e0.mul(&x[3]).add(&e1.mul(&y[3]));
        (if up { d1 } else { d1.neg() }, d2)
    };
    let (s1, s2) = t(tau);
    let (n1, n2) = t(nu);
    if s1.lo() <= 0.0 {
        return None;
    }
    let cube = s1.mul(&s1).mul(&s1);
    Some(n2.mul(&s1).sub(&n1.mul(&s2)).mul(&cube.recip()?))
}

/// Lemma F (the fold lemma, `proofs/ray-count.md`) for a pair where one segment is a
/// silhouette arc of a patch the other lies on: on a box B around the arc's cell where it
/// holds, every crossing of the arc with a curve of the patch inside B is a point the two
/// share in space (a vertex, where both are cut), so the product of the arc's cell and the
/// other's part inside B is excluded.
pub(super) fn arc_fold_exclusion(
    a: &Segment,
    b: &Segment,
    covers: &[Vec<(DyadicBoxN, DyadicBoxN)>],
    ia: usize,
    ib: usize,
) -> Vec<DyadicBoxN> {
    let (arc, other, cover, arc_first) =
        if a.kind == LineKind::Silhouette && b.on.iter().any(|x| x.0 == a.patch) {
            (a, b, &covers[ia], true)
        } else if b.kind == LineKind::Silhouette && a.on.iter().any(|x| x.0 == b.patch) {
            (b, a, &covers[ib], false)
        } else {
            return Vec::new();
        };
    cover
        .iter()
        .filter_map(|(d, bx)| {
            let near = sub_domain(other, arc.patch, &param_box(bx), None)?;
            Some(if arc_first {
                d.iter().copied().chain(near).collect()
            } else {
                near.into_iter().chain(d.iter().copied()).collect()
            })
        })
        .collect()
}

/// The fold boxes of a silhouette arc (computed once per arc): its cell, or pieces of it
/// along its parameter where one box does not do, each with a box of its patch around it on
/// which the fold lemma holds.
pub(super) fn fold_cover(scene: &Scene, arc: &Segment) -> Vec<(DyadicBoxN, DyadicBoxN)> {
    if arc.kind != LineKind::Silhouette {
        return Vec::new();
    }
    // A silhouette line inside its patch: pieces of its parameter, each a thin box of the patch.
    if let Some((axis, at)) = arc.line {
        let mut out = Vec::new();
        let mut stack = vec![(arc.domain[0], 0u32)];
        while let Some(((l, h), depth)) = stack.pop() {
            let mut lo = [at.to_rational(), at.to_rational()];
            let mut hi = lo.clone();
            lo[1 - axis] = l.to_rational();
            hi[1 - axis] = h.to_rational();
            if let Some(bx) = fold_box_around(scene, arc.patch, &lo, &hi) {
                out.push((vec![(l, h)], bx));
                continue;
            }
            if depth < 5 {
                if let Some(mid) = l.midpoint(h) {
                    stack.push(((l, mid), depth + 1));
                    stack.push(((mid, h), depth + 1));
                }
            }
        }
        return out;
    }
    let Some(g) = &arc.constraint else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut stack = vec![(arc.domain.clone(), 0u32)];
    while let Some((d, depth)) = stack.pop() {
        let lo = [d[0].0.to_rational(), d[1].0.to_rational()];
        let hi = [d[0].1.to_rational(), d[1].1.to_rational()];
        if let Some(bx) = fold_box_around(scene, arc.patch, &lo, &hi) {
            out.push((d, bx));
            continue;
        }
        if depth >= 4 {
            continue;
        }
        let (l, h) = d[arc.axis];
        let Some(mid) = l.midpoint(h) else { continue };
        for half in [(l, mid), (mid, h)] {
            let mut e = d.clone();
            e[arc.axis] = half;
            stack.push((narrow_to_curve(g, &e, arc.axis), depth + 1));
        }
    }
    out
}

/// The near part of a segment at one of its ends, and the sign of moving away from it along
/// the segment's orientation (+1: increasing parameter / the tangent field's direction).
pub(super) fn near_end(s: &Segment, v: &Vertex, depth: u32) -> Option<(DyadicBoxN, bool)> {
    // The vertex that defines the start (end) of the segment's parameter extent.
    let at_start = v.param[0] <= s.range[0];
    let at_end = v.param[1] >= s.range[1];
    if at_start == at_end {
        return None;
    }
    // The parameter axis restricted to the first (last) 2^-depth of the domain's width.
    let (lo, hi) = s.domain[s.axis];
    let mut d = s.domain.clone();
    d[s.axis] = if at_start {
        let mut c = hi;
        for _ in 0..depth {
            c = lo.midpoint(c)?;
        }
        (lo, c)
    } else {
        let mut c = lo;
        for _ in 0..depth {
            c = c.midpoint(hi)?;
        }
        (c, hi)
    };
    let away_up = match &s.constraint {
        // A side: moving away from its start increases the parameter.
        None => at_start,
        // An arc: the field (−g_v, g_u) moves along the parameter axis with the sign of −g_v
        // (axis u) or g_u (axis v), strict on the cell.
        Some(g) => {
            let field_up = if s.axis == 0 {
                !strict_sign(&g.deriv(1), &s.domain)?
            } else {
                strict_sign(&g.deriv(0), &s.domain)?
            };
            at_start == field_up
        }
    };
    Some((d, away_up))
}

/// Lemma L1: if near the vertex both images are strictly monotone along one direction e, one
/// moving to larger e and the other to smaller e as they leave the vertex, they meet only at
/// the vertex's image.
pub(super) fn opposite_monotone(
    a: &Segment,
    b: &Segment,
    va: &Vertex,
    vb: &Vertex,
) -> Option<DyadicBoxN> {
    for depth in 0..=6 {
        let (da, away_a) = near_end(a, va, depth)?;
        let (db, away_b) = near_end(b, vb, depth)?;
        let Some((e, _)) = find_monotone(&a.tangent, &da) else {
            continue;
        };
        let (Some(sa), Some(sb)) = (
            monotone_along(&a.tangent, &e, &da),
            monotone_along(&b.tangent, &e, &db),
        ) else {
            continue;
        };
        // Leaving the vertex: e increases along a iff sa == away_a.
        if (sa == away_a) != (sb == away_b) {
            return Some(da.into_iter().chain(db).collect());
        }
    }
    None
}
