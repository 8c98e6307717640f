//! Curves on trimmed faces: each patch's arcs clipped to the faces of its surface
//! (`proofs/trimmed-faces.md`, 8).
//!
//! For a patch whose surface has faces, the crossings of the curve `g = 0` with every loop
//! piece `c = (U, V, W)` (mapped into the patch's parameters) are the roots of the univariate
//! polynomial `W^{d₀+d₁} g(U/W, V/W)`, isolated exactly. An arc that holds such a crossing is
//! split at two dyadic levels of its graph variable just either side of it; every other arc
//! holds no crossing, so it lies wholly inside or wholly outside the faces, decided at one
//! point of it by a box that misses every loop ([`box_in_faces`]). Arcs outside are dropped;
//! the short arc around a crossing is dropped where its two neighbours disagree, and the curve
//! then ends at the level next to the crossing, within the arc's proven extent in space of
//! the true end. Every joined node that lost an arc to the clip but keeps others is such an
//! end (a curve leaving the faces there). What cannot be decided is unresolved.

use crate::analysis::contour::curves::Node;
use crate::analysis::contour::joins::Joins;
use crate::analysis::projection::fix_axis;
use crate::bernstein::{compose_homogeneous, Bernstein};
use crate::geometry::Rect;
use crate::model::Model;
use crate::number::{margin, Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::plane_curve::Arc;
use crate::solver::point_in_face::{
    box_in_faces, curve_box, curve_misses_box, FacesOnPatch, Membership,
};
use crate::solver::precision::Policy;
use crate::solver::univariate::{isolate_roots, isolate_roots_in, refine_root};
use crate::solver::{CrossingId, CurveTopology, Dyadic, DyadicBox};
use crate::surface::RationalPatch;
use std::collections::{BTreeMap, BTreeSet};

/// What clipping the curves to the faces found.
#[derive(Debug, Default)]
pub(crate) struct Clipped {
    /// Joined nodes where a curve leaves the faces, with the proven distance in space between
    /// that drawn end and the true end on the trimming curve.
    pub(crate) trim_ends: BTreeMap<Node, f64>,
    /// What was not decided: (patch, box, reason).
    pub(crate) unresolved: Vec<(usize, DyadicBox, Reason)>,
    /// Crossings of the curves with trimming curves, proven.
    pub(crate) crossings: usize,
    /// Arcs dropped as outside the faces.
    pub(crate) dropped: usize,
}

/// A dyadic strictly between `a` and `b` (f64 in `[0, 1]`), on the grid `2^-52`.
fn dyadic_between(a: f64, b: f64) -> Option<Dyadic> {
    let mid = 0.5 * a + 0.5 * b;
    let scale = (1u64 << 52) as f64;
    let d = Dyadic::new((mid * scale).floor().clamp(0.0, scale) as u64, 52);
    (a < d.to_f64() && d.to_f64() < b).then_some(d)
}

/// The dyadic box of an f64 rectangle (rounded outwards to `2^-52`, clamped to `[0, 1]²`).
fn dyadic_box(r: &Rect) -> DyadicBox {
    let scale = (1u64 << 52) as f64;
    let lo = |x: f64| Dyadic::new((x * scale).floor().clamp(0.0, scale) as u64, 52);
    let hi = |x: f64| Dyadic::new((x * scale).ceil().clamp(0.0, scale) as u64, 52);
    DyadicBox {
        lo: [lo(r.axis(0)[0]), lo(r.axis(1)[0])],
        hi: [hi(r.axis(0)[1]), hi(r.axis(1)[1])],
    }
}

/// The crossing of an arc with the line `axis = c` inside its cell: the only root of `g` on
/// that line in the cell's range of the other variable, isolated exactly.
fn fibre_crossing(
    g: &Bernstein<Rational>,
    cell: &DyadicBox,
    axis: usize,
    c: Dyadic,
    policy: &mut Policy,
) -> Option<(CrossingId, Rect, (Dyadic, Dyadic))> {
    let m = 1 - axis;
    let line = fix_axis(g, axis, &c.to_rational());
    let roots = isolate_roots_in(&line, cell.lo[m], cell.hi[m], 52, policy);
    if roots.identically_zero || !roots.unresolved.is_empty() || roots.roots.len() != 1 {
        return None;
    }
    let root = refine_root(&line, roots.roots[0], 1e-15, policy);
    let (lo, hi) = (root.lo(), root.hi());
    let mut r = Rect::from_axes([0.0, 0.0], [0.0, 0.0]);
    let (c0, c1) = c.to_f64_bounds();
    r.set_axis(axis, [c0, c1]);
    r.set_axis(m, [lo.to_f64_bounds().0, hi.to_f64_bounds().1]);
    let id = CrossingId::Segment {
        fixed: axis,
        c,
        s0: cell.lo[m],
        s1: cell.hi[m],
        k: 0,
    };
    Some((id, r, (lo, hi)))
}

/// The arc's range of its graph variable `o`, as the hull of its ends' locations, split into
/// the lower end's range and the upper end's.
fn end_ranges(t: &CurveTopology, a: &Arc, o: usize) -> ([f64; 2], [f64; 2], bool) {
    let f = t.locations[&a.from].axis(o);
    let e = t.locations[&a.to].axis(o);
    if f[0] <= e[0] {
        (f, e, true)
    } else {
        (e, f, false)
    }
}

/// The proven diameter in space of the patch over a box of its parameters.
fn extent(patch: &RationalPatch, r: &Rect) -> f64 {
    let lo = [r.axis(0)[0], r.axis(1)[0]];
    let hi = [r.axis(0)[1], r.axis(1)[1]];
    patch
        .enclosure(lo, hi)
        .map_or(f64::INFINITY, |b| diameter(&b))
}

/// An upper bound of the diameter of a box in space.
pub(crate) fn diameter(b: &[Interval; 3]) -> f64 {
    let mut sum = 0.0f64;
    for x in b {
        let w = margin::up(x.hi() - x.lo(), margin::FEW);
        sum = margin::up(sum + margin::up(w * w, margin::FEW), margin::FEW);
    }
    margin::up(sum.sqrt(), margin::FEW)
}

/// An enclosure of the arc of `g = 0` in `cell` (a graph over `o`) for `o ∈ [c1, c2]`,
/// from its point on `o = c1` (the m-interval `at`) and the slope bound
/// `|dm/do| ≤ sup |g_o| / inf |g_m|` over the strip of the cell.
fn arc_box(
    g: &Bernstein<Rational>,
    cell: &DyadicBox,
    o: usize,
    c: [Dyadic; 2],
    at: [f64; 2],
) -> Rect {
    let m = 1 - o;
    let mut strip = cell.to_f64();
    strip.set_axis(o, [c[0].to_f64_bounds().0, c[1].to_f64_bounds().1]);
    let lo = [strip.axis(0)[0], strip.axis(1)[0]];
    let hi = [strip.axis(0)[1], strip.axis(1)[1]];
    let range = |axis: usize| {
        g.deriv(axis)
            .convert::<Interval>(Precision::F64)
            .restrict_box_f64(&lo, &hi)
            .hull()
    };
    let (go, gm) = (range(o), range(m));
    let inf_gm = if gm.lo() > 0.0 {
        gm.lo()
    } else if gm.hi() < 0.0 {
        -gm.hi()
    } else {
        0.0
    };
    let sup_go = go.lo().abs().max(go.hi().abs());
    let width = strip.axis(o)[1] - strip.axis(o)[0];
    let reach = margin::up(
        margin::up(sup_go / inf_gm, margin::FEW) * width,
        margin::FEW,
    );
    let cm = cell.to_f64().axis(m);
    let mut out = strip;
    if reach.is_finite() {
        out.set_axis(m, [(at[0] - reach).max(cm[0]), (at[1] + reach).min(cm[1])]);
    }
    out
}

/// How an arc of a clipped patch was decided.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Decision {
    Keep,
    Drop,
    /// The short arc around a crossing, with its extent in space.
    Around(f64),
    Unresolved,
}

/// The membership of an arc that holds no crossing with a loop: at a point inside it.
fn arc_membership(
    on: &FacesOnPatch,
    g: &Bernstein<Rational>,
    t: &CurveTopology,
    a: &Arc,
    policy: &mut Policy,
) -> Membership {
    let Some(mono) = a.kind.monotone_axis() else {
        return segment_membership(on, t, a, policy);
    };
    let o = 1 - mono;
    let (low, high, _) = end_ranges(t, a, o);
    let span = high[0] - low[1];
    for frac in [0.5, 0.25, 0.75] {
        let Some(c) = (span > 0.0)
            .then(|| dyadic_between(low[1] + (frac - 0.1) * span, low[1] + (frac + 0.1) * span))
            .flatten()
        else {
            break;
        };
        if let Some((_, r, _)) = fibre_crossing(g, &a.cell, o, c, policy) {
            match on.membership(&r) {
                Membership::Undecided => continue,
                m => return m,
            }
        }
    }
    // A short arc: its whole cell.
    on.membership(&a.cell.to_f64())
}

/// An arc on a line `x_f = c` (a segment on which the function vanishes): the line, and the
/// ranges of its lower and upper ends along the other variable.
struct OnLine {
    f: usize,
    c: Rational,
    low: [f64; 2],
    high: [f64; 2],
}

impl OnLine {
    /// The line of an arc on an edge: the coordinate both ends share exactly.
    fn of(t: &CurveTopology, a: &Arc) -> Option<OnLine> {
        let (from, to) = (t.locations[&a.from], t.locations[&a.to]);
        let f = (0..2).find(|&k| {
            from.width(k) == 0.0 && to.width(k) == 0.0 && from.axis(k)[0] == to.axis(k)[0]
        })?;
        let c = Rational::from_f64(from.axis(f)[0])?;
        let ends = [from.axis(1 - f), to.axis(1 - f)];
        let (low, high) = if ends[0][0] <= ends[1][0] {
            (ends[0], ends[1])
        } else {
            (ends[1], ends[0])
        };
        Some(OnLine { f, c, low, high })
    }

    /// The open segment's range (between its ends' locations).
    fn open(&self) -> [f64; 2] {
        [self.low[1], self.high[0]]
    }

    /// The loops on the open segment: the ranges of the pieces along the line, and the
    /// enclosures (along the line) of the crossings of the others with it, the roots of
    /// `X_f − c W` placed on the open segment (exactly for an exact root or a piece whose other
    /// coordinate is constant, by the enclosure otherwise). `None` if a root is not isolated
    /// where it may lie on the segment.
    #[allow(clippy::type_complexity)]
    fn loops(
        &self,
        on: &FacesOnPatch,
        policy: &mut Policy,
    ) -> Option<(Vec<[f64; 2]>, Vec<[f64; 2]>)> {
        let (f, s, c, open) = (self.f, 1 - self.f, &self.c, self.open());
        let end = |e: f64| Rational::from_f64(e).expect("finite");
        let mut along = Vec::new();
        let mut crossings = Vec::new();
        for piece in on.pieces() {
            let at = |x: &Rational| {
                let x = std::slice::from_ref(x);
                Rational::from(&piece[s].eval(x) / &piece[2].eval(x))
            };
            let k = piece[f].try_sub(&piece[2].scale(c)).expect("one degree");
            if k.is_zero() {
                // Along the line: it covers at least the range between its ends (continuity),
                // and its ends on the open segment are loop vertices there.
                let (e0, e1) = (at(&Rational::new()), at(&Rational::from(1)));
                let (lo, hi) = if e0 <= e1 { (e0, e1) } else { (e1, e0) };
                along.push([lo.lower_f64(), hi.upper_f64()]);
                for e in [lo, hi] {
                    if e > end(open[0]) && e < end(open[1]) {
                        crossings.push([e.lower_f64(), e.upper_f64()]);
                    }
                }
                continue;
            }
            // A piece along a line of the other coordinate has that coordinate exactly.
            let k0 = Rational::from(&piece[s].coeffs()[0] / &piece[2].coeffs()[0]);
            let constant = piece[s]
                .try_sub(&piece[2].scale(&k0))
                .expect("one degree")
                .is_zero();
            let place = |lo: &Rational, hi: &Rational| -> Option<[f64; 2]> {
                let exact = if constant {
                    Some(k0.clone())
                } else {
                    (lo == hi).then(|| at(lo))
                };
                match exact {
                    Some(x) => (x > end(open[0]) && x < end(open[1])).then(|| {
                        let (a, b) = (x.lower_f64(), x.upper_f64());
                        [a, b]
                    }),
                    None => {
                        let r = curve_box(&piece, lo, hi)
                            .map_or([f64::NEG_INFINITY, f64::INFINITY], |r| r.axis(s));
                        (r[1] > open[0] && r[0] < open[1]).then_some(r)
                    }
                }
            };
            let roots = isolate_roots(&k, 52, policy);
            for (lo, hi) in &roots.unresolved {
                if place(&lo.to_rational(), &hi.to_rational()).is_some() {
                    return None;
                }
            }
            for root in &roots.roots {
                let root = refine_root(&k, *root, 1e-13, policy);
                if let Some(r) = place(&root.lo().to_rational(), &root.hi().to_rational()) {
                    crossings.push(r);
                }
            }
        }
        // Crossings at one loop vertex (the ends of two pieces), or not separated: one.
        crossings.sort_by(|x, y| x[0].total_cmp(&y[0]));
        let mut merged: Vec<[f64; 2]> = Vec::new();
        for x in crossings {
            match merged.last_mut() {
                Some(m) if x[0] <= m[1] => m[1] = m[1].max(x[1]),
                _ => merged.push(x),
            }
        }
        // The pieces along the line that overlap the open segment.
        along.retain(|r| r[1] > open[0] && r[0] < open[1]);
        Some((along, merged))
    }
}

/// The membership of an arc on a line `x_f = c`: when no loop crosses the open segment, its
/// interior is in or out as a whole, decided at its midpoint; when loop pieces along the line
/// cover the whole segment, it lies on the faces' boundary, in the closed faces.
fn segment_membership(
    on: &FacesOnPatch,
    t: &CurveTopology,
    a: &Arc,
    policy: &mut Policy,
) -> Membership {
    let Some(line) = OnLine::of(t, a) else {
        return Membership::Undecided;
    };
    let (f, s, open) = (line.f, 1 - line.f, line.open());
    if open[0] >= open[1] {
        return Membership::Undecided;
    }
    let Some((mut along, crossings)) = line.loops(on, policy) else {
        return Membership::Undecided;
    };
    if !crossings.is_empty() {
        return Membership::Undecided;
    }
    if !along.is_empty() {
        // Pieces along the line: the segment is in the closed faces when they cover it. A
        // gap between them inside the open segment would be a loop vertex on it from which a
        // piece leaves the line, a root placed on the open segment above (undecided); the
        // pieces' ends are rounded to f64, hence the margin.
        along.sort_by(|x, y| x[0].total_cmp(&y[0]));
        let eps = 1e-12;
        let mut reach = f64::NEG_INFINITY;
        for r in &along {
            if r[0] <= open[0] + eps || r[0] <= reach + eps {
                reach = reach.max(r[1]);
            }
        }
        return if reach >= open[1] - eps {
            Membership::Inside
        } else {
            Membership::Undecided
        };
    }
    let mut mid = Rect::from_axes([0.0, 0.0], [0.0, 0.0]);
    let c = line.c;
    mid.set_axis(f, [c.lower_f64(), c.upper_f64()]);
    let m = 0.5 * open[0] + 0.5 * open[1];
    mid.set_axis(s, [m, m]);
    // On a side of a face's domain, off its loops: the region inside an outer loop lies in
    // the open domain (the loop is in the closed, convex domain), so the side is outside it;
    // without an outer loop the domain's boundary bounds the face, and the side is in it.
    let line = &on.origin[f] + Rational::from(&on.size[f] * &c);
    let mut out = Membership::Outside;
    for face in &on.faces {
        let m = if face.domain[f].contains(&line) {
            if face.outer.is_none() {
                Membership::Inside
            } else {
                Membership::Outside
            }
        } else {
            box_in_faces([face], &on.surface_box(&mid))
        };
        match m {
            Membership::Inside => return Membership::Inside,
            Membership::Undecided => out = Membership::Undecided,
            Membership::Outside => {}
        }
    }
    out
}

/// Clips the arcs of every patch whose surface has faces to those faces (see the module
/// documentation). `gs` are the polynomials the topologies were solved for.
pub(crate) fn clip_to_faces(
    model: &Model,
    tops: &mut [CurveTopology],
    gs: &[Bernstein<Rational>],
    joins: &mut Joins,
    policy: &mut Policy,
) -> Clipped {
    let mut out = Clipped::default();
    if model.faces.is_empty() {
        return out;
    }
    let mut removed: Vec<(Node, f64)> = Vec::new();
    for (p, mp) in model.patches.iter().enumerate() {
        // A patch on which the function vanishes identically is reported as degenerate
        // (edge-on) as a whole; there is no curve to clip.
        if tops[p].arcs.is_empty() || tops[p].identically_zero {
            continue;
        }
        let on = match FacesOnPatch::of(model, p) {
            None => continue,
            Some(Ok(on)) => on,
            Some(Err(_)) => {
                for a in std::mem::take(&mut tops[p].arcs) {
                    out.unresolved.push((p, a.cell, Reason::TrimMembership));
                }
                continue;
            }
        };
        let decisions = clip_patch(&on, &mp.surface, &gs[p], &mut tops[p], p, &mut out, policy);
        let t = &mut tops[p];
        let arcs = std::mem::take(&mut t.arcs);
        for (a, d) in arcs.into_iter().zip(decisions) {
            match d {
                Decision::Keep => t.arcs.push(a),
                Decision::Drop => {
                    out.dropped += 1;
                    removed.push(((p, a.from), 0.0));
                    removed.push(((p, a.to), 0.0));
                }
                Decision::Around(e) => {
                    removed.push(((p, a.from), e));
                    removed.push(((p, a.to), e));
                }
                Decision::Unresolved => out.unresolved.push((p, a.cell, Reason::TrimMembership)),
            }
        }
    }
    // The nodes that keep an arc after the clip: a curve ends there on a trimming curve.
    let mut kept: BTreeSet<Node> = BTreeSet::new();
    for (p, t) in tops.iter().enumerate() {
        for a in &t.arcs {
            kept.insert(joins.find((p, a.from)));
            kept.insert(joins.find((p, a.to)));
        }
    }
    for (n, e) in removed {
        let n = joins.find(n);
        if kept.contains(&n) {
            let slot = out.trim_ends.entry(n).or_insert(0.0);
            *slot = slot.max(e);
        }
    }
    out
}

/// The decisions for the arcs of one patch (after splitting the arcs that hold crossings;
/// one per arc of `t` on return).
fn clip_patch(
    on: &FacesOnPatch,
    patch: &RationalPatch,
    g: &Bernstein<Rational>,
    t: &mut CurveTopology,
    p: usize,
    out: &mut Clipped,
    policy: &mut Policy,
) -> Vec<Decision> {
    let square = [[0.0, 1.0], [0.0, 1.0]];
    let unresolved_all = |t: &CurveTopology| vec![Decision::Unresolved; t.arcs.len()];
    // 1. The crossings of the curve with the loops, inside the open square.
    let mut inner: Vec<Rect> = Vec::new();
    for c in on.pieces() {
        let enclosed = c.clone().map(|x| x.convert::<Interval>(Precision::F64));
        if curve_misses_box(&enclosed, &square) {
            continue;
        }
        let h = compose_homogeneous(g, [&c[0], &c[1], &c[2]]);
        if h.is_zero() {
            out.unresolved
                .push((p, DyadicBox::UNIT, Reason::TrimAlongCurve));
            return unresolved_all(t);
        }
        let roots = isolate_roots(&h, 52, policy);
        for (lo, hi) in &roots.unresolved {
            if let Some(r) = curve_box(&c, &lo.to_rational(), &hi.to_rational()) {
                if r.meets(&Rect::from_axes([0.0, 1.0], [0.0, 1.0])) {
                    out.unresolved
                        .push((p, dyadic_box(&r), Reason::TrimCrossing));
                }
            }
        }
        // A piece along a side of the square meets the curve only there: at arcs' ends.
        let along_side =
            (0..2).any(|a| c[a].is_zero() || c[a].try_sub(&c[2]).is_ok_and(|d| d.is_zero()));
        for root in &roots.roots {
            let root = refine_root(&h, *root, 1e-13, policy);
            let Some(r) = curve_box(&c, &root.lo().to_rational(), &root.hi().to_rational()) else {
                out.unresolved
                    .push((p, DyadicBox::UNIT, Reason::TrimCrossingPlace));
                continue;
            };
            let strictly_inside = (0..2).all(|a| r.axis(a)[0] > 0.0 && r.axis(a)[1] < 1.0);
            let outside = (0..2).any(|a| r.axis(a)[1] < 0.0 || r.axis(a)[0] > 1.0);
            if strictly_inside {
                inner.push(r);
            } else if !outside && !along_side {
                out.unresolved
                    .push((p, dyadic_box(&r), Reason::TrimCrossingPlace));
            }
        }
    }
    out.crossings += inner.len();
    // 2. Each arc holding a crossing split around it.
    let mut around: BTreeMap<usize, Rect> = BTreeMap::new();
    let mut undecided: BTreeSet<usize> = BTreeSet::new();
    for x in inner {
        let candidates: Vec<usize> = (0..t.arcs.len())
            .filter(|&k| {
                let a = &t.arcs[k];
                if !a.cell.to_f64().meets(&x) {
                    return false;
                }
                match a.kind.monotone_axis() {
                    None => true,
                    Some(m) => {
                        let (low, high, _) = end_ranges(t, a, 1 - m);
                        let o = x.axis(1 - m);
                        o[1] >= low[0] && o[0] <= high[1]
                    }
                }
            })
            .collect();
        let split = match candidates.as_slice() {
            [k] if !around.contains_key(k) => split_around(g, t, *k, &x, policy),
            _ => None,
        };
        match split {
            Some((k2, r)) => {
                around.insert(k2, r);
            }
            None => {
                out.unresolved
                    .push((p, dyadic_box(&x), Reason::TrimCrossingPlace));
                undecided.extend(candidates);
            }
        }
    }
    // 2b. Each arc on a line split around the loops' crossings with it.
    for k in 0..t.arcs.len() {
        if t.arcs[k].kind.monotone_axis().is_some() || undecided.contains(&k) {
            continue;
        }
        match split_segment(on, t, k, policy) {
            Some(middles) => around.extend(middles),
            None => {
                out.unresolved
                    .push((p, t.arcs[k].cell, Reason::TrimCrossingPlace));
                undecided.insert(k);
            }
        }
    }
    // 3. Every other arc decided at a point of it; the arcs around crossings by their
    //    neighbours.
    let mut decisions: Vec<Decision> = (0..t.arcs.len())
        .map(|k| {
            if undecided.contains(&k) {
                return Decision::Unresolved;
            }
            if around.contains_key(&k) {
                return Decision::Keep;
            }
            match arc_membership(on, g, t, &t.arcs[k], policy) {
                Membership::Inside => Decision::Keep,
                Membership::Outside => Decision::Drop,
                Membership::Undecided => Decision::Unresolved,
            }
        })
        .collect();
    for (&k2, r) in &around {
        // Its neighbours: the one other arc at each of its two (new) ends.
        let a = &t.arcs[k2];
        let next = |id: CrossingId| {
            (0..t.arcs.len())
                .find(|&j| j != k2 && (t.arcs[j].from == id || t.arcs[j].to == id))
                .map_or(Decision::Unresolved, |j| decisions[j])
        };
        decisions[k2] = match (next(a.from), next(a.to)) {
            (Decision::Keep, Decision::Keep) => Decision::Keep,
            (Decision::Drop, Decision::Drop) => Decision::Drop,
            (Decision::Unresolved, _) | (_, Decision::Unresolved) => Decision::Unresolved,
            _ => Decision::Around(extent(patch, r)),
        };
    }
    decisions
}

/// Splits the arc `k` on a line at exact dyadic points either side of each crossing of a loop
/// with its open segment (the arc is replaced by its first piece, the rest appended): the
/// middle pieces with their boxes (exact segments). The ends of loop pieces along the line are
/// such crossings too, so that each piece is covered by pieces along the line or meets none.
/// Nothing to split is an empty list ([`segment_membership`] decides, undecided where a root
/// is not isolated); `None` if the crossings are not separated from each other and the ends.
fn split_segment(
    on: &FacesOnPatch,
    t: &mut CurveTopology,
    k: usize,
    policy: &mut Policy,
) -> Option<Vec<(usize, Rect)>> {
    let a = t.arcs[k].clone();
    let Some(line) = OnLine::of(t, &a) else {
        return Some(Vec::new());
    };
    let Some((_, crossings)) = line.loops(on, policy) else {
        return Some(Vec::new());
    };
    if crossings.is_empty() {
        return Some(Vec::new());
    }
    let (f, s) = (line.f, 1 - line.f);
    let c = Dyadic::from_rational(&line.c)?;
    // The levels: s1 < crossing < s2, each pair inside the gap left by the previous one.
    let reach = 2f64.powi(-30);
    let mut levels: Vec<[Dyadic; 2]> = Vec::new();
    let mut floor = line.low[1];
    for (i, x) in crossings.iter().enumerate() {
        let ceiling = crossings.get(i + 1).map_or(line.high[0], |y| y[0]);
        let s1 = dyadic_between(floor.max(x[0] - reach), x[0])?;
        let s2 = dyadic_between(x[1], ceiling.min(x[1] + reach))?;
        levels.push([s1, s2]);
        floor = s2.to_f64();
    }
    let (lo_end, hi_end) = {
        let fr = t.locations[&a.from].axis(s)[0];
        let to = t.locations[&a.to].axis(s)[0];
        if fr <= to {
            (a.from, a.to)
        } else {
            (a.to, a.from)
        }
    };
    let point = |x: Dyadic| {
        let mut uv = [c, c];
        uv[s] = x;
        let id = CrossingId::Exact { u: uv[0], v: uv[1] };
        let r = Rect::from_axes(
            [uv[0].to_f64_bounds().0, uv[0].to_f64_bounds().1],
            [uv[1].to_f64_bounds().0, uv[1].to_f64_bounds().1],
        );
        (id, r)
    };
    let mut chain = vec![lo_end];
    for [s1, s2] in &levels {
        for x in [*s1, *s2] {
            let (id, r) = point(x);
            t.locations.insert(id, r);
            chain.push(id);
        }
    }
    chain.push(hi_end);
    let arc = |from, to| Arc {
        from,
        to,
        cell: a.cell,
        kind: a.kind,
    };
    let mut middles = Vec::new();
    for (i, w) in chain.windows(2).enumerate() {
        let piece = arc(w[0], w[1]);
        if i == 0 {
            t.arcs[k] = piece;
        } else {
            t.arcs.push(piece);
        }
        if i % 2 == 1 {
            let [s1, s2] = levels[i / 2];
            let mut r = Rect::from_axes([0.0, 0.0], [0.0, 0.0]);
            r.set_axis(f, [c.to_f64_bounds().0, c.to_f64_bounds().1]);
            r.set_axis(s, [s1.to_f64_bounds().0, s2.to_f64_bounds().1]);
            middles.push((t.arcs.len() - 1, r));
        }
    }
    Some(middles)
}

/// Splits arc `k` of `t` at two dyadic levels of its graph variable either side of the
/// crossing `x`: the arc is replaced by its lower piece (at `k`) and the middle and upper
/// pieces are appended. Returns the middle arc's index and a box enclosing it,
/// or `None` if the crossing is not strictly inside the arc's range or a level's crossing is
/// not isolated.
fn split_around(
    g: &Bernstein<Rational>,
    t: &mut CurveTopology,
    k: usize,
    x: &Rect,
    policy: &mut Policy,
) -> Option<(usize, Rect)> {
    let a = t.arcs[k].clone();
    let m = a.kind.monotone_axis()?;
    let o = 1 - m;
    let (low, high, from_low) = end_ranges(t, &a, o);
    let xo = x.axis(o);
    if !(low[1] < xo[0] && xo[1] < high[0]) {
        return None;
    }
    let reach = 2f64.powi(-30);
    let c1 = dyadic_between(low[1].max(xo[0] - reach), xo[0])?;
    let c2 = dyadic_between(xo[1], high[0].min(xo[1] + reach))?;
    let (id1, r1, i1) = fibre_crossing(g, &a.cell, o, c1, policy)?;
    let (id2, r2, i2) = fibre_crossing(g, &a.cell, o, c2, policy)?;
    let cell_between = |lo: Dyadic, hi: Dyadic| {
        let mut c = a.cell;
        c.lo[o] = lo;
        c.hi[o] = hi;
        c
    };
    let (lo_end, hi_end) = if from_low {
        (a.from, a.to)
    } else {
        (a.to, a.from)
    };
    let arc = |from, to, cell| Arc {
        from,
        to,
        cell,
        kind: a.kind,
    };
    t.locations.insert(id1, r1);
    t.locations.insert(id2, r2);
    t.intervals.insert(id1, i1);
    t.intervals.insert(id2, i2);
    t.arcs[k] = arc(lo_end, id1, cell_between(a.cell.lo[o], c1));
    t.arcs.push(arc(id1, id2, cell_between(c1, c2)));
    t.arcs
        .push(arc(id2, hi_end, cell_between(c2, a.cell.hi[o])));
    let n = t.arcs.len();
    let at = r1.axis(m);
    let mid = arc_box(g, &a.cell, o, [c1, c2], at);
    Some((n - 2, mid))
}
