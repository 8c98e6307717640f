//! Stage 1c of the drawing: the intersection curves of patches that pass through each other
//! (the teapot's spout and handle through its body), as lines.
//!
//! Every pair of patches that share no corner, are not trimmed (the faces of a B-rep meet only
//! along their edges, as the trim assumption states), and whose image and depth boxes meet is
//! solved by [`pair_intersection`]: certified arcs in `(u, v, s, t)`, each a graph over one
//! variable in its box. Each arc is a segment of kind [`LineKind::Intersection`] whose
//! variables are all four and whose constraints are the curve's three equations, so that the
//! crossing and penetration systems of the later stages take it as they take any line
//! (`proofs/hidden-lines.md`, "Intersection curves"). The surface does not end or fold along
//! such a curve, so it is never outline: it cuts no other line. Its own QI changes only where
//! it crosses an outline in the image or passes through a third patch, which the systems find.
//! Ends on patch sides are vertices of those sides; boxes the curve solver left undecided are
//! reported as unresolved pieces, never drawn as if decided.

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::intersection::{intersection_system, pair_intersection, PairIntersection};
use crate::analysis::projection::ImagePolys;
use crate::analysis::visibility::hlr::lines::{
    bounds_on, class_of, dyadic_above, dyadic_below, rat, side_uv, Key, Meet, Segment, Vertex,
};
use crate::analysis::visibility::hlr::result::{HlrPiece, LineKind};
use crate::analysis::visibility::ray::Sample;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::{fix_var, lift, Poly};
use crate::model::Model;
use crate::number::{Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::space_curve::{unwarp_interval, SpaceCrossing, SpaceCurveOptions};
use crate::solver::system::{solve_system, DyadicBoxN, SystemOptions};
use crate::surface::{DrawPatch, Edge};
use rayon::prelude::*;
use std::sync::Arc;

/// The intersection lines of a scene.
pub(super) struct IntersectionLines {
    /// Their segments, one per certified arc.
    pub(super) segments: Vec<Segment>,
    /// The boxes of intersection curves the solver did not decide, as unresolved pieces.
    pub(super) unresolved: Vec<HlrPiece>,
    /// Pairs of patches solved.
    pub(super) pairs: usize,
}

/// The pairs of patches whose intersection curves are searched: not adjacent (no common
/// corner, no side along the other's), neither trimmed, image boxes and depth ranges meeting.
fn candidate_pairs(scene: &Scene) -> Vec<[usize; 2]> {
    let n = scene.bounds.len();
    let mut out = Vec::new();
    for p in 0..n {
        for q in p + 1..n {
            let (a, b) = (&scene.bounds[p], &scene.bounds[q]);
            let depth = a.depth[0] <= b.depth[1] && b.depth[0] <= a.depth[1];
            if depth
                && a.meets_image(b)
                && !scene.trimmed(p)
                && !scene.trimmed(q)
                && !scene.adjacent(p, q)
            {
                out.push([p, q]);
            }
        }
    }
    out
}

/// The intersection curves of every candidate pair, as segments (chains from `first_chain`);
/// their ends on patch sides become vertices of those sides (`boundary`, indexed by edge
/// class).
pub(super) fn intersection_lines(
    scene: &Scene,
    model: &Model,
    boundary: &mut [Segment],
    first_chain: usize,
    deadline: Option<std::time::Instant>,
) -> IntersectionLines {
    let pairs = candidate_pairs(scene);
    let opts = SpaceCurveOptions {
        max_boxes: 3_000,
        deadline,
        ..SpaceCurveOptions::default()
    };
    let solved: Vec<(PairIntersection, Arc<[Poly; 3]>)> = pairs
        .par_iter()
        .map(|&[p, q]| {
            let (a, b) = (&model.patches[p].surface, &model.patches[q].surface);
            (
                pair_intersection(a, b, &opts),
                Arc::new(intersection_system(a, b)),
            )
        })
        .collect();
    let mut out = IntersectionLines {
        segments: Vec::new(),
        unresolved: Vec::new(),
        pairs: pairs.len(),
    };
    let mut chain = first_chain;
    for (index, ([p, q], (pair, eqs))) in pairs.iter().zip(solved).enumerate() {
        let curve = &pair.curve;
        let draw = DrawPatch::new(&model.patches[*p].surface);
        for u in &curve.unresolved {
            let cell = pair.unwarp_box(&u.cell);
            if !outside_squares(&cell) {
                out.unresolved
                    .push(unresolved_piece([*p, *q], &cell, u.reason.clone(), &draw));
            }
        }
        if curve.arcs.is_empty() {
            continue;
        }
        let meet = Arc::new(Meet {
            other: *q,
            image: lifted(&scene.images[*p]),
            eqs,
        });
        for branch in &curve.branches {
            let ids = &branch.crossings;
            let n = if branch.closed {
                ids.len()
            } else {
                ids.len().saturating_sub(1)
            };
            for k in 0..n {
                let (a, b) = (ids[k], ids[(k + 1) % ids.len()]);
                let Some(arc) = curve
                    .arcs
                    .iter()
                    .find(|x| (x.from == a && x.to == b) || (x.from == b && x.to == a))
                else {
                    continue;
                };
                let ends = [a, b].map(|c| pair.unwarp_box(&curve.crossings[c].enclosure));
                let cell = pair.unwarp_box(&arc.cell);
                if outside_squares(&cell) {
                    continue;
                }
                let unresolved = |why| unresolved_piece([*p, *q], &cell, why, &draw);
                if arc.monotone_in >= 4 {
                    // An arc from a singular point: not a graph over one variable.
                    out.unresolved.push(unresolved(Reason::IntersectionBranch));
                    continue;
                }
                let axis = arc.monotone_in;
                let end_at = |c: usize, e: &Vec<[f64; 2]>| End {
                    at: e.clone(),
                    face: face_of(&pair, &curve.crossings[c]),
                    key: Key::Meet {
                        pair: index,
                        crossing: c,
                    },
                };
                let whole = [end_at(a, &ends[0]), end_at(b, &ends[1])];
                let pieces = if cell.iter().all(|x| x[0] >= 0.0 && x[1] <= 1.0) {
                    vec![whole]
                } else {
                    // Solved past a side: the stretches of the arc inside both squares.
                    match clip_arc(&pair, &arc.cell, axis, whole) {
                        Some(pieces) => pieces,
                        None => {
                            out.unresolved.push(unresolved(Reason::IntersectionClip));
                            continue;
                        }
                    }
                };
                for [e0, e1] in pieces {
                    let range = [
                        e0.at[axis][0].min(e1.at[axis][0]),
                        e0.at[axis][1].max(e1.at[axis][1]),
                    ];
                    // The arc's box inside the squares, narrowed along its variable to the
                    // stretch's extent (a graph over that variable lies within it).
                    let mut c: Vec<[f64; 2]> = cell
                        .iter()
                        .map(|x| [x[0].max(0.0), x[1].min(1.0)])
                        .collect();
                    c[axis] = [c[axis][0].max(range[0]), c[axis][1].min(range[1])];
                    let domain: DyadicBoxN = c
                        .iter()
                        .map(|x| (dyadic_below(x[0]), dyadic_above(x[1])))
                        .collect();
                    let vertices = [e0, e1]
                        .into_iter()
                        .map(|e| end_vertex(scene, boundary, e, [*p, *q], axis))
                        .collect();
                    let image = meet.image.clone();
                    out.segments.push(Segment {
                        kind: LineKind::Intersection,
                        patch: *p,
                        edge: None,
                        chain,
                        order: k,
                        bounds: bounds_on(&image, &domain),
                        image,
                        constraint: None,
                        domain,
                        axis,
                        range,
                        tangent: [(); 2].map(|()| Poly::constant(4, Rational::new())),
                        monotone: None,
                        vertices,
                        on: vec![(*p, None, false), (*q, None, false)],
                        line: None,
                        curve: None,
                        touches: Vec::new(),
                        elsewhere: Vec::new(),
                        meet: Some(meet.clone()),
                    });
                }
            }
            chain += 1;
        }
    }
    out
}

/// The first patch's image polynomials in `(u, v, s, t)`.
fn lifted(im: &ImagePolys) -> ImagePolys {
    im.map(|p| lift(p, 4, 0))
}

/// An end of a stretch of an intersection curve: its box in `(u, v, s, t)`, the side of a
/// patch it lies on (variable, at 1), and its key if it lies on none.
#[derive(Clone, Debug)]
struct End {
    at: Vec<[f64; 2]>,
    face: Option<(usize, bool)>,
    key: Key,
}

/// Whether a box of `(u, v, s, t)` lies outside the patches' squares (beyond a side, or on it).
fn outside_squares(cell: &[[f64; 2]]) -> bool {
    cell.iter().any(|x| x[1] <= 0.0 || x[0] >= 1.0)
}

/// The side of a patch that a crossing on the solver's boundary lies on, if that boundary is a
/// side (not the edge of a domain extended past it).
fn face_of(pair: &PairIntersection, c: &SpaceCrossing) -> Option<(usize, bool)> {
    if !c.on_boundary {
        return None;
    }
    let one = c.at == Dyadic::ONE;
    let [lo, hi] = pair.span[c.axis];
    let side = if one { hi == 1.0 } else { lo == 0.0 };
    side.then_some((c.axis, one))
}

/// The stretches of an arc (in the solver's box `cell`, a graph over variable `axis`) inside
/// both patches' squares, where its box reaches past a side: the arc is cut where it crosses
/// each side's hyperplane (roots of the three equations with that variable fixed, in the
/// span's coordinates, where the point is inside the solver's domain), and each stretch
/// between cuts is in or out as a whole, decided at its middle. `None` if a root or a middle
/// is not decided.
fn clip_arc(
    pair: &PairIntersection,
    cell: &[[f64; 2]],
    axis: usize,
    ends: [End; 2],
) -> Option<Vec<[End; 2]>> {
    let unit: Vec<[f64; 2]> = (0..4)
        .map(|k| unwarp_interval(cell[k], pair.lambda[k]))
        .collect();
    let box_of = |skip: usize| -> Option<DyadicBoxN> {
        (0..4)
            .filter(|&k| k != skip)
            .map(|k| Some((dyadic_below(unit[k][0]), dyadic_above(unit[k][1]))))
            .collect()
    };
    let opts = SystemOptions {
        max_depth: 30,
        max_boxes: 2_000,
        refine_width: 1e-12,
        ..SystemOptions::default()
    };
    // The points of the curve in the box on the hyperplane x_k = c, in the patches' parameters.
    let slice = |k: usize, c: &Rational| -> Option<Vec<Vec<[f64; 2]>>> {
        let g = pair.to_unit(k, c);
        let eqs: Vec<Poly> = pair.eqs.iter().map(|e| fix_var(e, k, &g)).collect();
        let r = solve_system(&eqs, &[], &box_of(k)?, &opts);
        if !r.unresolved.is_empty() || r.roots.iter().any(|x| !x.inside) {
            return None;
        }
        let gf = [g.lower_f64(), g.upper_f64()];
        Some(
            r.roots
                .iter()
                .map(|x| {
                    let mut e = x.enclosure.clone();
                    e.insert(k, gf);
                    (0..4).map(|v| pair.from_unit(v, e[v])).collect()
                })
                .collect(),
        )
    };
    let lo = ends[0].at[axis][0].min(ends[1].at[axis][0]);
    let hi = ends[0].at[axis][1].max(ends[1].at[axis][1]);
    let mut cuts: Vec<End> = Vec::new();
    for (k, y) in unit.iter().enumerate() {
        let x = pair.from_unit(k, *y);
        for (c, one) in [(0.0, false), (1.0, true)] {
            if x[0] < c && c < x[1] {
                for at in slice(k, &Rational::from(i32::from(one)))? {
                    if at[axis][1] >= lo && at[axis][0] <= hi {
                        cuts.push(End {
                            at,
                            face: Some((k, one)),
                            key: Key::Meet {
                                pair: usize::MAX,
                                crossing: 0,
                            },
                        });
                    }
                }
            }
        }
    }
    let mut points: Vec<End> = ends.to_vec();
    points.extend(cuts);
    points.sort_by(|a, b| {
        (a.at[axis][0] + a.at[axis][1]).total_cmp(&(b.at[axis][0] + b.at[axis][1]))
    });
    // Cuts whose boxes overlap (the curve leaving through two sides at one point, an edge of
    // the squares) are one cut, its box their hull: a stretch between two such points, were
    // they distinct, lies in that box and is neither drawn nor decided, as within any cut's
    // enclosure.
    let mut merged: Vec<End> = Vec::new();
    for e in points {
        match merged.last_mut() {
            Some(last)
                if (0..4).all(|k| last.at[k][0] <= e.at[k][1] && e.at[k][0] <= last.at[k][1]) =>
            {
                for k in 0..4 {
                    last.at[k] = [last.at[k][0].min(e.at[k][0]), last.at[k][1].max(e.at[k][1])];
                }
                last.face = last.face.or(e.face);
            }
            _ => merged.push(e),
        }
    }
    let mut out = Vec::new();
    for w in merged.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if a.at[axis][1] >= b.at[axis][0] {
            return None; // two cuts not apart along the arc
        }
        // The middle of the stretch: the only point of the curve in the box on its slice.
        if b.at[axis][1] <= 0.0 || a.at[axis][0] >= 1.0 {
            continue; // beyond a side in the arc's own variable
        }
        let m = Rational::from_f64(0.5 * (a.at[axis][1] + b.at[axis][0]))?;
        let at = slice(axis, &m)?;
        let [mid] = at.as_slice() else {
            return None;
        };
        let inside = mid.iter().all(|x| x[0] > 0.0 && x[1] < 1.0);
        let outside = mid.iter().any(|x| x[1] < 0.0 || x[0] > 1.0);
        if inside {
            out.push([a.clone(), b.clone()]);
        } else if !outside {
            return None;
        }
    }
    Some(out)
}

/// The vertex at an end of a stretch: on a side of either patch, a vertex of that side too
/// (the side passes through the other patch there); inside, the crossing.
fn end_vertex(
    scene: &Scene,
    boundary: &mut [Segment],
    end: End,
    patches: [usize; 2],
    axis: usize,
) -> Vertex {
    let e = &end.at;
    let boxes: Vec<(usize, [Rational; 2], [Rational; 2])> = (0..2)
        .map(|side| {
            let (a, b) = (e[2 * side], e[2 * side + 1]);
            (
                patches[side],
                [rat(a[0].max(0.0)), rat(b[0].max(0.0))],
                [rat(a[1].min(1.0)), rat(b[1].min(1.0))],
            )
        })
        .collect();
    let param = e[axis];
    if let Some((k, one)) = end.face {
        let side = k / 2;
        let own = k % 2;
        let edge = match (own, one) {
            (0, false) => Edge::U0,
            (0, true) => Edge::U1,
            (_, false) => Edge::V0,
            (_, true) => Edge::V1,
        };
        let along = e[2 * side + 1 - own];
        let along = [along[0].max(0.0), along[1].min(1.0)];
        if let Some((class, rev)) = class_of(scene, patches[side], edge) {
            let t = if rev {
                [1.0 - along[1], 1.0 - along[0]]
            } else {
                along
            };
            let key = Key::Side { class, t };
            let mut uv = side_uv(&boundary[class].on, t);
            uv.push(boxes[1 - side].clone());
            if !boundary[class].vertices.iter().any(|x| x.key == key) {
                boundary[class].vertices.push(Vertex {
                    key: key.clone(),
                    param: t,
                    uv: uv.clone(),
                });
            }
            return Vertex { key, param, uv };
        }
    }
    Vertex {
        key: end.key,
        param,
        uv: boxes,
    }
}

/// An unresolved box of an intersection curve as a piece: its centre drawn, its QI unknown.
fn unresolved_piece(
    patches: [usize; 2],
    cell: &[[f64; 2]],
    why: Reason,
    draw: &DrawPatch,
) -> HlrPiece {
    let c: Vec<f64> = cell.iter().map(|x| 0.5 * (x[0] + x[1])).collect();
    HlrPiece {
        kind: LineKind::Intersection,
        patch: patches[0],
        edge: None,
        meets: Some(patches[1]),
        param: cell[0],
        qi: None,
        certified: false,
        reason: Some(Reason::IntersectionUnresolved {
            patches,
            why: Box::new(why),
        }),
        error_bound: None,
        points: vec![draw.eval(c[0], c[1])],
        points_uv: vec![(patches[0], c[0], c[1])],
        outline: Some(false),
        behind: None,
    }
}

/// The sample of an intersection segment at parameter `c` (its variable `axis`): the other
/// three variables are the only root of the curve's equations in the segment's box, isolated
/// by the certified system solver; `None` if there is not exactly one.
pub(super) fn meet_sample(s: &Segment, c: &Rational) -> Option<Sample> {
    let m = s.meet.as_ref()?;
    let eqs: Vec<Poly> = m
        .eqs
        .iter()
        .map(|e| crate::bernstein::fix_var(e, s.axis, c))
        .collect();
    let domain: DyadicBoxN = (0..4)
        .filter(|&k| k != s.axis)
        .map(|k| s.domain[k])
        .collect();
    let opts = SystemOptions {
        max_depth: 24,
        max_boxes: 400,
        refine_width: 1e-12,
        ..SystemOptions::default()
    };
    let r = solve_system(&eqs, &[], &domain, &opts);
    if r.roots.len() != 1 || !r.unresolved.is_empty() {
        return None;
    }
    // The enclosure grown by 2^-30 and rounded out to the 2^-40 grid (a sample's box is
    // dyadic), within the region where the root is unique: the ray systems' roots, whose
    // free variables are the sample's, then have enclosures strictly inside it.
    let root = &r.roots[0];
    let (e, unique) = (&root.enclosure, &root.unique_in);
    let grow = 2f64.powi(-30);
    let cell: [[Dyadic; 2]; 3] = std::array::from_fn(|k| {
        let lo = dyadic_above((e[k][0] - grow).max(unique[k][0]));
        let hi = dyadic_below((e[k][1] + grow).min(unique[k][1]));
        let (l, h) = (lo.to_f64_bounds().0, hi.to_f64_bounds().1);
        if l <= e[k][0] && e[k][1] <= h {
            [lo, hi]
        } else {
            [dyadic_below(e[k][0]), dyadic_above(e[k][1])]
        }
    });
    let inside = (0..3).all(|k| {
        unique[k][0] <= cell[k][0].to_f64_bounds().0 && cell[k][1].to_f64_bounds().1 <= unique[k][1]
    });
    if !inside {
        return None;
    }
    let cell = cell.map(|c| c.map(|d| d.to_rational()));
    Some(Sample::Meet {
        patches: [s.patch, m.other],
        axis: s.axis,
        at: c.clone(),
        cell,
        fixed: Arc::new(eqs),
    })
}

/// The point of an intersection segment at parameter `t` (its variable `axis`), in f64: the
/// other three variables by Newton's method from the point of the chord between the box's
/// ends (not certified: the drawing without a tolerance).
pub(super) fn meet_point(s: &Segment, t: f64, ends: [&[f64; 4]; 2]) -> Option<[f64; 4]> {
    let m = s.meet.as_ref()?;
    let f: Vec<crate::bernstein::Bernstein<f64>> =
        m.eqs.iter().map(|e| e.convert(Precision::F64)).collect();
    let free: Vec<usize> = (0..4).filter(|&k| k != s.axis).collect();
    let d: Vec<Vec<crate::bernstein::Bernstein<f64>>> = f
        .iter()
        .map(|p| free.iter().map(|&k| p.deriv(k)).collect())
        .collect();
    let [a, b] = ends;
    let w = if b[s.axis] != a[s.axis] {
        (t - a[s.axis]) / (b[s.axis] - a[s.axis])
    } else {
        0.5
    };
    let mut x: [f64; 4] = std::array::from_fn(|k| a[k] + w.clamp(0.0, 1.0) * (b[k] - a[k]));
    x[s.axis] = t;
    for _ in 0..30 {
        let r: Vec<f64> = f.iter().map(|p| p.eval(&x)).collect();
        let j: Vec<Vec<f64>> = d
            .iter()
            .map(|row| row.iter().map(|p| p.eval(&x)).collect())
            .collect();
        let dx = solve3(&j, &r)?;
        for (i, &k) in free.iter().enumerate() {
            x[k] -= dx[i];
        }
        if dx.iter().all(|v| v.abs() < 1e-14) {
            break;
        }
    }
    let inside = (0..4).all(|k| {
        let (lo, hi) = (s.domain[k].0.to_f64(), s.domain[k].1.to_f64());
        x[k] >= lo - 1e-9 && x[k] <= hi + 1e-9
    });
    inside.then_some(x)
}

/// The solution of a 3×3 linear system by Cramer's rule (`None` if singular).
fn solve3(j: &[Vec<f64>], r: &[f64]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let a: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| j[i][k]));
    let d = det(a);
    if !d.is_finite() || d == 0.0 {
        return None;
    }
    Some(std::array::from_fn(|c| {
        let mut m = a;
        for i in 0..3 {
            m[i][c] = r[i];
        }
        det(m) / d
    }))
}

/// Drawing points of an intersection segment's stretch `[p0, p1]`, evenly spaced in its
/// parameter (Newton's method from the chord between its ends' boxes): not certified.
pub(super) fn meet_points(
    s: &Segment,
    draw: &DrawPatch,
    p0: f64,
    p1: f64,
    steps: usize,
) -> super::drawing::Drawn {
    let Some(ends) = meet_ends(s) else {
        return (Vec::new(), Vec::new());
    };
    let mut uv = Vec::new();
    for k in 0..=steps {
        let t = p0 + (p1 - p0) * k as f64 / steps as f64;
        if let Some(x) = meet_point(s, t, [&ends[0], &ends[1]]) {
            uv.push((s.patch, x[0], x[1]));
        }
    }
    let points = uv.iter().map(|&(_, u, v)| draw.eval(u, v)).collect();
    (uv, points)
}

/// The centres of the boxes of a segment's two end vertices, in `(u, v, s, t)`.
fn meet_ends(s: &Segment) -> Option<[[f64; 4]; 2]> {
    let m = s.meet.as_ref()?;
    let centre = |v: &Vertex| -> Option<[f64; 4]> {
        let on = |p: usize| {
            let (_, lo, hi) = v.uv.iter().find(|x| x.0 == p)?;
            Some([0, 1].map(|k| 0.5 * (lo[k].to_f64() + hi[k].to_f64())))
        };
        let (a, b) = (on(s.patch)?, on(m.other)?);
        Some([a[0], a[1], b[0], b[1]])
    };
    Some([centre(s.vertices.first()?)?, centre(s.vertices.get(1)?)?])
}

/// The points where an intersection segment meets a silhouette arc of one of its two patches:
/// the roots of the curve's equations and that patch's silhouette function (four in four),
/// each a vertex of both (a [`Key::Fold`]). There the image of the intersection curve is
/// tangent to the outline, so their crossing system has a double root; with the shared
/// vertex, the fold lemma excludes a box around it that holds no crossing but the point itself
/// (`proofs/hidden-lines.md`, "Intersection curves"). Returns how many were found.
pub(super) fn silhouette_meets(
    sil: &Silhouette,
    segments: &mut [Segment],
    meets: std::ops::Range<usize>,
    next_id: &mut usize,
) -> usize {
    let opts = SystemOptions {
        max_depth: 24,
        max_boxes: 600,
        refine_width: 1e-12,
        ..SystemOptions::default()
    };
    let found: Vec<Vec<(usize, Vec<[f64; 2]>)>> = segments[meets.clone()]
        .par_iter()
        .map(|s| {
            let Some(m) = &s.meet else {
                return Vec::new();
            };
            let mut out = Vec::new();
            for (side, patch) in [s.patch, m.other].into_iter().enumerate() {
                let Some(solved) = sil.solved.get(patch) else {
                    continue;
                };
                let mut eqs: Vec<Poly> = m.eqs.to_vec();
                eqs.push(lift(&solved.g, 4, 2 * side));
                let r = solve_system(&eqs, &[], &s.domain, &opts);
                out.extend(r.roots.into_iter().map(|x| (side, x.enclosure)));
            }
            out
        })
        .collect();
    let mut count = 0;
    for (k, roots) in meets.zip(found) {
        for (side, e) in roots {
            let (patch, other) = {
                let m = segments[k].meet.as_ref().expect("an intersection segment");
                (
                    [segments[k].patch, m.other][side],
                    [segments[k].patch, m.other],
                )
            };
            let key = Key::Fold { id: *next_id };
            *next_id += 1;
            let boxes: Vec<(usize, [Rational; 2], [Rational; 2])> = (0..2)
                .map(|h| {
                    let (a, b) = (e[2 * h], e[2 * h + 1]);
                    (other[h], [rat(a[0]), rat(b[0])], [rat(a[1]), rat(b[1])])
                })
                .collect();
            let uv = [e[2 * side], e[2 * side + 1]];
            // The silhouette arcs of that patch whose boxes hold the point.
            let mut on_arc = false;
            for t in segments.iter_mut() {
                if t.kind != LineKind::Silhouette || t.patch != patch || t.line.is_some() {
                    continue;
                }
                let holds = (0..2).all(|a| {
                    t.domain[a].0.to_f64() <= uv[a][0] && uv[a][1] <= t.domain[a].1.to_f64()
                });
                if holds && t.constraint.is_some() {
                    t.vertices.push(Vertex {
                        key: key.clone(),
                        param: uv[t.axis],
                        uv: boxes.clone(),
                    });
                    on_arc = true;
                }
            }
            if on_arc {
                // A vertex of every segment of the pair's curve: the fold lemma's box around
                // it also excludes the near-tangent crossings of the silhouette with the
                // neighbouring segments, which meet it nowhere in the box (only the point
                // itself, on one of them, shares the silhouette's image there).
                let mine = segments[k].meet.clone().expect("an intersection segment");
                for s in segments.iter_mut() {
                    if s.meet.as_ref().is_some_and(|m| Arc::ptr_eq(m, &mine)) {
                        s.vertices.push(Vertex {
                            key: key.clone(),
                            param: e[s.axis],
                            uv: boxes.clone(),
                        });
                    }
                }
                count += 1;
            }
        }
    }
    count
}
