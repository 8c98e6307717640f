//! Curves on a model given by one exact polynomial per patch (silhouettes, parabolic
//! curves): each patch solved with certified topology, collapsed sides divided out, sides and
//! lines where the polynomial vanishes added back, crossings joined across shared edges where
//! the join is proven (`proofs/silhouette-join.md`), and, with a tolerance, the arcs traced
//! with certified accuracy (`proofs/chord-accuracy.md`). [`model_curves`] is the one entry
//! point; each family says what differs in its [`CurveRules`].

use super::accuracy::{PatchAccuracy, Traced};
use crate::bernstein::Bernstein;
use crate::model::{Model, PatchAdjacency, SideUse, WeldTolerance};
use crate::number::{Precision, Rational};
use crate::solver::lines::{add_line, line_point, solve_curve_lines, LinedCurve, ZeroLine};
use crate::solver::{CrossingId, CurveOptions, CurveTopology, Dyadic, Escalations};
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// A degenerate situation recognised exactly.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Degenerate {
    /// The patch.
    pub patch: usize,
    /// "edge-on" (g ≡ 0: the whole patch is on the silhouette, e.g. a plane seen edge-on),
    /// "collapsed side" (a side collapsed to a point, where the normal vanishes),
    /// "silhouette side" (g vanishes on a whole side: the side is part of the silhouette) or
    /// "silhouette line" (g vanishes on a whole line u = c or v = c inside the patch); for
    /// other curve families, the names their [`CurveRules`] give.
    pub kind: &'static str,
    /// The side, for "collapsed side" and "silhouette side".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<Edge>,
    /// The line, for "silhouette line": "u=c" or "v=c" with c exact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<String>,
}

/// A node of the model-level curve graph: a crossing of one patch.
type Node = (usize, CrossingId);

/// A silhouette curve on the model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SilhouetteCurve {
    /// The patches it crosses, in order of first visit.
    pub patches: Vec<usize>,
    /// A closed loop.
    pub closed: bool,
    /// Its topology is proven: every join is proven and an open curve ends on the open
    /// boundary of the model.
    pub certified_topology: bool,
    /// Topology proven and every drawn segment within the tolerance of the true curve
    /// (`proofs/chord-accuracy.md`); false without a tolerance.
    pub certified: bool,
    /// The largest proven distance between a drawn segment and the true curve, in model units
    /// (absent without a tolerance, or where no bound was reached).
    pub error_bound: Option<f64>,
    /// Points along the curve in order, (patch, u, v): the crossings at the centres of their
    /// certified locations and, between them, drawing points on the curve computed in f64 on
    /// lines across each arc's box (not certified).
    pub points_uv: Vec<(usize, f64, f64)>,
    /// The same points in space (f64 evaluation of the patch at those parameters).
    pub points: Vec<[f64; 3]>,
    /// Boxes of parameters that cover the curve, each with the drawn points it holds: a proven
    /// enclosure of the curve along its polyline, for bounds on functions along it (as the
    /// directions of [`super::events`]). Empty for curves not found by the certified solver.
    #[serde(skip)]
    pub pieces: Vec<CurvePiece>,
}

/// A box of one patch's parameters that holds a piece of a curve and the drawn points
/// `first..=last` of it ([`SilhouetteCurve::pieces`]). The pieces of a curve cover it, and
/// every drawn segment lies in one of them.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePiece {
    /// The patch.
    pub patch: usize,
    /// `[lo, hi]` in (u, v).
    pub cell: [[f64; 2]; 2],
    /// The first drawn point it holds (an index into `points_uv`).
    pub first: usize,
    /// The last.
    pub last: usize,
}

/// What the curve solver was given and proved for one patch.
#[derive(Clone, Debug)]
pub struct SolvedPatch {
    /// The polynomial solved.
    pub g: Bernstein<Rational>,
    /// The sides whose linear factor was divided out of the silhouette function, with how many
    /// times: collapsed sides (points), and sides on which it vanishes (part of the silhouette,
    /// added back as arcs).
    pub divided: Vec<(Edge, usize)>,
    /// Lines inside the square on which the silhouette function vanishes, divided out too
    /// (added back as arcs).
    pub lines: Vec<ZeroLine>,
    /// The solver's result.
    pub topology: CurveTopology,
}

/// The silhouette of a model.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Silhouette {
    /// The curves.
    pub curves: Vec<SilhouetteCurve>,
    /// Where three or more arcs meet.
    pub singular_points: Vec<SingularPoint>,
    /// Per patch: its certified topology in the parameter square.
    #[serde(skip)]
    pub patches: Vec<CurveTopology>,
    /// Per patch: the exact polynomial solved (g with the factors of the sides on which it
    /// vanishes divided out), the sides divided with their powers, and the solver's topology
    /// before joins (what a certificate states).
    #[serde(skip)]
    pub solved: Vec<SolvedPatch>,
    /// Degenerate cases.
    pub degenerate: Vec<Degenerate>,
    /// Undecided regions: (patch, box, reason).
    pub unresolved: Vec<(usize, crate::solver::DyadicBox, String)>,
    /// Shared edges across which the curves could not be joined with proof (patch sides).
    pub unjoined_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Shared edges across which the function jumps (a crease for silhouettes, a curvature
    /// discontinuity for parabolic curves): crossings common to both patches (at the same
    /// exact point) are joined, and every other curve reaching them ends there, proven.
    pub ending_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Boxes examined, summed over patches.
    pub boxes: usize,
    /// The tolerance the curves were traced to (absolute, model units), if any.
    pub tolerance: Option<f64>,
    /// Sign questions by the level that settled them.
    pub escalations: Escalations,
}

impl Silhouette {
    /// A result made of curves only (no per-patch data, nothing unresolved): for baselines.
    pub fn from_curves(curves: Vec<SilhouetteCurve>) -> Silhouette {
        Silhouette {
            curves,
            singular_points: Vec::new(),
            patches: Vec::new(),
            solved: Vec::new(),
            degenerate: Vec::new(),
            unresolved: Vec::new(),
            unjoined_edges: Vec::new(),
            ending_edges: Vec::new(),
            boxes: 0,
            tolerance: None,
            escalations: Escalations::default(),
        }
    }
}

/// The side a crossing lies on (the first one, for a corner) and its parameter along it,
/// as the dyadic interval containing it.
pub(crate) fn side_of(id: &CrossingId) -> Vec<(Edge, Dyadic, Dyadic)> {
    let on = |fixed: usize, c: Dyadic| -> Option<Edge> {
        match (fixed, c) {
            (0, c) if c == Dyadic::ZERO => Some(Edge::U0),
            (0, c) if c == Dyadic::ONE => Some(Edge::U1),
            (1, c) if c == Dyadic::ZERO => Some(Edge::V0),
            (1, c) if c == Dyadic::ONE => Some(Edge::V1),
            _ => None,
        }
    };
    match *id {
        CrossingId::Exact { u, v } => {
            let mut out = Vec::new();
            if let Some(e) = on(0, u) {
                out.push((e, v, v));
            }
            if let Some(e) = on(1, v) {
                out.push((e, u, u));
            }
            out
        }
        CrossingId::Segment {
            fixed, c, s0, s1, ..
        } => on(fixed, c).map(|e| (e, s0, s1)).into_iter().collect(),
    }
}

/// The silhouette function restricted to a side, as a univariate polynomial in the side's
/// own parameter (increasing with u or v).
pub(crate) fn side_polynomial(g: &Bernstein<Rational>, edge: Edge) -> Bernstein<Rational> {
    let [m, n] = [g.degrees()[0], g.degrees()[1]];
    let coeffs: Vec<Rational> = match edge {
        Edge::V0 => (0..=m).map(|i| g.coeff(&[i, 0]).clone()).collect(),
        Edge::V1 => (0..=m).map(|i| g.coeff(&[i, n]).clone()).collect(),
        Edge::U0 => (0..=n).map(|j| g.coeff(&[0, j]).clone()).collect(),
        Edge::U1 => (0..=n).map(|j| g.coeff(&[m, j]).clone()).collect(),
    };
    Bernstein::new(&[coeffs.len() - 1], coeffs).expect("univariate")
}

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
) -> bool {
    let (na, nb) = (pa.normal(), pb.normal());
    let side = |n: &[Bernstein<Rational>; 3], e: Edge, rev: bool| -> [Bernstein<Rational>; 3] {
        [0, 1, 2].map(|k| {
            let p = side_polynomial(&n[k], e);
            if rev {
                let mut c = p.coeffs().to_vec();
                c.reverse();
                Bernstein::new(p.degrees(), c).expect("same shape")
            } else {
                p
            }
        })
    };
    let (a, b) = (side(&na, ea, false), side(&nb, eb, reversed));
    let cross_zero = (0..3).all(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        (&(&a[i] * &b[j]) - &(&a[j] * &b[i])).is_zero()
    });
    if !cross_zero {
        return false;
    }
    let dot = &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2]);
    let roots = crate::solver::isolate_roots(
        &dot,
        &crate::solver::Ladder::default(),
        40,
        &mut Escalations::default(),
    );
    // A normal vanishing exactly at an end of the edge is a corner, which is joined by vertex
    // identity and excluded from the side's crossings: only interior zeros matter.
    let interior = |r: &crate::solver::Root| !matches!(r, crate::solver::Root::At { t } if *t == Dyadic::ZERO || *t == Dyadic::ONE);
    !roots.identically_zero && !roots.roots.iter().any(interior) && roots.unresolved.is_empty()
}

/// Union-find over model nodes.
struct Joins {
    parent: BTreeMap<Node, Node>,
}

impl Joins {
    fn find(&mut self, x: Node) -> Node {
        let p = *self.parent.get(&x).unwrap_or(&x);
        if p == x {
            return x;
        }
        let r = self.find(p);
        self.parent.insert(x, r);
        r
    }
    fn union(&mut self, a: Node, b: Node) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent.insert(hi, lo);
        }
    }
}

/// What differs between the curve families solved on a model by [`model_curves`].
#[derive(Clone, Debug)]
pub struct CurveRules {
    /// Crossings on a shared edge are also joined where the two patches' normals are exactly
    /// parallel along it (true for silhouettes, whose function is the normal times a fixed
    /// vector; not for other families).
    pub parallel_normal_joins: bool,
    /// The `degenerate` kind of a patch whose function vanishes identically ("edge-on" for a
    /// silhouette).
    pub whole_patch: &'static str,
    /// The `degenerate` kind of a side on which it vanishes ("silhouette side").
    pub whole_side: &'static str,
    /// The `degenerate` kind of a line inside a patch on which it vanishes ("silhouette
    /// line").
    pub whole_line: &'static str,
}

/// The curves `g_i = 0` on a model, one exact polynomial per patch (any family defined by
/// one equation in the patch parameters: silhouettes, parabolic curves): solved per patch with
/// certified topology, with collapsed sides divided out, sides and lines where `g` vanishes
/// added back, crossings joined across shared edges where the join is proven, and, with a
/// tolerance, traced with certified accuracy (`proofs/silhouette-join.md`,
/// `proofs/chord-accuracy.md`).
///
/// # Panics
/// If `gs` does not have one bivariate polynomial per patch.
pub fn model_curves(
    model: &Model,
    gs: Vec<Bernstein<Rational>>,
    rules: &CurveRules,
    opts: &CurveOptions,
    weld: WeldTolerance,
    tol: Option<f64>,
) -> Silhouette {
    assert_eq!(gs.len(), model.patches.len(), "one polynomial per patch");
    let patches: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
    let adj = PatchAdjacency::of_patches(&patches, weld);
    // On a collapsed side the normal vanishes, so g has that side's linear factor: divide it
    // out (exactly), so that the spurious zero set along the side does not meet the real curve
    // in a singular point. The sign inside the square is unchanged.
    let mut divided: Vec<Vec<(Edge, usize)>> = vec![Vec::new(); gs.len()];
    let solve_gs: Vec<Bernstein<Rational>> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let mut g = g.clone();
            for &(patch, edge, _) in &adj.collapsed {
                if patch == i {
                    let (h, k) = deflate_side_counted(&g, edge);
                    g = h;
                    if k > 0 {
                        divided[i].push((edge, k));
                    }
                }
            }
            // A side on which g vanishes identically is part of the silhouette, exactly; but
            // where the rest of the curve meets it, g is singular (and if g vanishes to a
            // higher order there, g keeps one sign across it). Divide its factor out entirely:
            // the quotient h has the same sign inside the square and a regular curve there,
            // and the side is added back as arcs, split where h's curve meets it.
            for edge in Edge::ALL {
                let (h, k) = deflate_side_counted(&g, edge);
                g = h;
                if k > 0 {
                    divided[i].push((edge, k));
                }
            }
            g
        })
        .collect();
    let collapsed_side = |i: usize, e: Edge| {
        adj.collapsed
            .iter()
            .any(|&(p, edge, _)| p == i && edge == e)
    };
    let zero_sides: Vec<Vec<Edge>> = divided
        .iter()
        .enumerate()
        .map(|(i, d)| {
            d.iter()
                .map(|&(e, _)| e)
                .filter(|&e| !collapsed_side(i, e))
                .collect()
        })
        .collect();
    let opts = &refined_for(opts, model, tol);
    // Lines inside the square on which g vanishes (the circle of vertical normals on a surface
    // of revolution seen from the side) are divided out too, and added back as arcs.
    let lined: Vec<LinedCurve> = solve_gs
        .par_iter()
        .map(|g| solve_curve_lines(g, opts))
        .collect();
    let lines: Vec<Vec<ZeroLine>> = lined.iter().map(|c| c.lines.clone()).collect();
    let solved: Vec<SolvedPatch> = lined
        .iter()
        .zip(divided)
        .map(|(c, divided)| SolvedPatch {
            g: c.quotient.clone(),
            divided,
            lines: c.lines.clone(),
            topology: c.solved.clone(),
        })
        .collect();
    let mut tops: Vec<CurveTopology> = lined.into_iter().map(|c| c.topology).collect();
    let quotients: Vec<Bernstein<Rational>> = solved.iter().map(|p| p.g.clone()).collect();

    for ((t, sides), lines) in tops.iter_mut().zip(&zero_sides).zip(&lines) {
        // Where lines of the other direction cross this one.
        let crossing = |fixed: usize| -> Vec<Dyadic> {
            lines
                .iter()
                .filter(|z| z.axis != fixed)
                .map(|z| z.at)
                .collect()
        };
        for &edge in sides {
            let (fixed, at_one) = side_axis(edge);
            let c = if at_one { Dyadic::ONE } else { Dyadic::ZERO };
            add_line(t, fixed, c, &crossing(fixed));
        }
    }

    let mut degenerate = Vec::new();
    let mut unresolved = Vec::new();
    let mut escalations = Escalations::default();
    let mut boxes = 0;
    for (i, t) in tops.iter().enumerate() {
        if t.identically_zero {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_patch,
                side: None,
                line: None,
            });
        }
        for &side in &zero_sides[i] {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_side,
                side: Some(side),
                line: None,
            });
        }
        for z in &lines[i] {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_line,
                side: None,
                line: Some(z.to_string()),
            });
        }
        for u in &t.unresolved {
            unresolved.push((i, u.cell, u.reason.clone()));
        }
        escalations.merge(&t.escalations);
        boxes += t.boxes;
    }
    // Collapsed sides: the normal vanishes there, so g does too; the "curve" along them is not
    // a silhouette. Drop arcs on them; crossings on them are all the one collapsed point.
    let mut joins = Joins {
        parent: BTreeMap::new(),
    };
    for &(patch, edge, _) in &adj.collapsed {
        degenerate.push(Degenerate {
            patch,
            kind: "collapsed side",
            side: Some(edge),
            line: None,
        });
        tops[patch]
            .arcs
            .retain(|a| !(a.reason == "on edge" && both_on(&a.from, &a.to, edge)));
    }
    // Shared edges: join crossings when the two side polynomials are exactly proportional.
    let mut unjoined = Vec::new();
    let mut open_boundary: Vec<(usize, Edge)> = Vec::new();
    let mut ending = Vec::new();
    for class in &adj.edges {
        if class.len() == 1 {
            open_boundary.push((class[0].patch, class[0].edge));
            continue;
        }
        if class.len() != 2 {
            continue;
        }
        let (a, b) = (class[0], class[1]);
        let normals = rules.parallel_normal_joins.then_some(&patches[..]);
        let joined = join_side(&tops, &gs, normals, a, b, &mut joins)
            || join_zero_side(&mut tops, &gs, &quotients, a, b, &mut joins);
        if joined {
            continue;
        }
        if ends_at_edge(&tops, &gs, a, b, &mut joins) {
            // The function jumps across the edge: crossings common to both patches are joined,
            // every other curve reaching it ends there.
            open_boundary.push((a.patch, a.edge));
            open_boundary.push((b.patch, b.edge));
            ending.push((a.patch, a.edge, b.patch, b.edge));
        } else {
            unjoined.push((a.patch, a.edge, b.patch, b.edge));
        }
    }
    let gs_fast: Vec<Bernstein<f64>> = gs.iter().map(|g| g.convert(Precision::F64)).collect();
    // Crossings on a collapsed side are its vertex; crossings exactly at a patch corner are the
    // welded corner vertex: one node per vertex.
    let mut vertex_nodes: BTreeMap<usize, Vec<Node>> = BTreeMap::new();
    for &(patch, edge, vertex) in &adj.collapsed {
        for a in &tops[patch].arcs {
            for id in [a.from, a.to] {
                if side_of(&id).iter().any(|s| s.0 == edge) {
                    vertex_nodes.entry(vertex).or_default().push((patch, id));
                }
            }
        }
    }
    for (patch, t) in tops.iter().enumerate() {
        for a in &t.arcs {
            for id in [a.from, a.to] {
                if let Some(k) = corner_index(&id) {
                    vertex_nodes
                        .entry(adj.corners[patch][k])
                        .or_default()
                        .push((patch, id));
                }
            }
        }
    }
    for nodes in vertex_nodes.values() {
        for w in nodes.windows(2) {
            joins.union(w[0], w[1]);
        }
    }
    let accuracy: Option<Vec<Option<PatchAccuracy>>> = tol.map(|_| {
        quotients
            .par_iter()
            .enumerate()
            .map(|(i, g)| (!tops[i].arcs.is_empty()).then(|| PatchAccuracy::new(patches[i], g)))
            .collect()
    });
    let (curves, singular_points) = chain_model(
        &tops,
        &gs_fast,
        &patches,
        &mut joins,
        &open_boundary,
        accuracy.as_deref().zip(tol),
        opts.deadline,
    );
    Silhouette {
        curves,
        singular_points,
        patches: tops,
        solved,
        degenerate,
        unresolved,
        unjoined_edges: unjoined,
        ending_edges: ending,
        boxes,
        tolerance: tol,
        escalations,
    }
}

/// Divides out the linear factor of a side on which `g` vanishes identically (v for V0,
/// 1 − v for V1, u for U0, 1 − u for U1), as many times as it divides; exact
/// ([`Bernstein::divide_face_factor`]).
pub fn deflate_side(g: &Bernstein<Rational>, edge: Edge) -> Bernstein<Rational> {
    deflate_side_counted(g, edge).0
}

/// The variable and end of a side: (0, false) for u = 0, …
fn side_axis(edge: Edge) -> (usize, bool) {
    match edge {
        Edge::U0 => (0, false),
        Edge::U1 => (0, true),
        Edge::V0 => (1, false),
        Edge::V1 => (1, true),
    }
}

/// [`deflate_side`], with the number of factors divided out.
pub fn deflate_side_counted(g: &Bernstein<Rational>, edge: Edge) -> (Bernstein<Rational>, usize) {
    let (axis, at_one) = side_axis(edge);
    let mut g = g.clone();
    let mut k = 0;
    while !g.is_zero() {
        match g.divide_face_factor(axis, at_one) {
            Some(q) => {
                g = q;
                k += 1;
            }
            None => break,
        }
    }
    (g, k)
}

/// Which corner of the patch a crossing is at: 0 = (0,0), 1 = (1,0), 2 = (1,1), 3 = (0,1).
fn corner_index(id: &CrossingId) -> Option<usize> {
    let CrossingId::Exact { u, v } = *id else {
        return None;
    };
    let end = |x: Dyadic| x == Dyadic::ZERO || x == Dyadic::ONE;
    (end(u) && end(v)).then(|| match (u == Dyadic::ONE, v == Dyadic::ONE) {
        (false, false) => 0,
        (true, false) => 1,
        (true, true) => 2,
        (false, true) => 3,
    })
}

fn both_on(a: &CrossingId, b: &CrossingId, edge: Edge) -> bool {
    side_of(a).iter().any(|s| s.0 == edge) && side_of(b).iter().any(|s| s.0 == edge)
}

/// The crossings of a patch's arcs that lie inside a side (corners excluded), sorted along it.
fn side_crossings(t: &CurveTopology, edge: Edge) -> Vec<(Dyadic, Dyadic, CrossingId)> {
    let mut v: Vec<(Dyadic, Dyadic, CrossingId)> = Vec::new();
    for a in &t.arcs {
        for id in [a.from, a.to] {
            let sides = side_of(&id);
            if sides.len() == 1 && sides[0].0 == edge && !v.iter().any(|x| x.2 == id) {
                v.push((sides[0].1, sides[0].2, id));
            }
        }
    }
    v.sort();
    v
}

/// Joins the crossings on a shared edge, if the silhouette functions of the two patches are
/// proportional on it (so their zeros are the same points). Returns whether it did.
fn join_side(
    tops: &[CurveTopology],
    gs: &[Bernstein<Rational>],
    patches: Option<&[&RationalPatch]>,
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
) -> bool {
    let pa = side_polynomial(&gs[a.patch], a.edge);
    let pb = side_polynomial(&gs[b.patch], b.edge);
    let reversed = a.reversed != b.reversed;
    if pa.is_zero() || pb.is_zero() {
        return false;
    }
    if !proportional(&pa, &pb, reversed)
        && !patches
            .is_some_and(|p| parallel_normals(p[a.patch], a.edge, p[b.patch], b.edge, reversed))
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
fn ends_at_edge(
    tops: &[CurveTopology],
    gs: &[Bernstein<Rational>],
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
) -> bool {
    let reversed = a.reversed != b.reversed;
    let (pa, pb) = (
        side_polynomial(&gs[a.patch], a.edge),
        side_polynomial(&gs[b.patch], b.edge),
    );
    if pa.is_zero() || pb.is_zero() {
        return false;
    }
    let avoids = |crossings: Vec<(Dyadic, Dyadic, CrossingId)>,
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
            let r = crate::solver::isolate_roots_in(
                other,
                lo,
                hi,
                &crate::solver::Ladder::default(),
                40,
                &mut Escalations::default(),
            );
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

/// Points added inside each arc for drawing.
const DENSIFY_STEPS: usize = 8;

/// The budgets with crossings located finely enough for a tolerance `tol` (model units): their
/// location boxes then take a small part of it (the end pieces of the accuracy bound,
/// `proofs/chord-accuracy.md`).
pub(crate) fn refined_for(opts: &CurveOptions, model: &Model, tol: Option<f64>) -> CurveOptions {
    let mut opts = opts.clone();
    if let Some(t) = tol {
        let rel = t / model.diagonal().max(f64::MIN_POSITIVE);
        opts.refine_width = opts.refine_width.min((rel * 1e-3).max(1e-15));
    }
    opts
}

/// The points of an arc for drawing: its two crossings (certified locations) and
/// `steps − 1` points between them. Each is the zero of g on a line across the arc's box along
/// which g is strictly monotone (so the line meets this arc exactly once), found in f64 by the
/// Illinois method: drawing points, not certified ones.
fn densify(
    g: &Bernstein<f64>,
    t: &CurveTopology,
    a: &crate::solver::curve2::Arc,
    steps: usize,
) -> Vec<[f64; 2]> {
    let (p0, p1) = (t.point(&a.from), t.point(&a.to));
    let m = match a.reason {
        "graph over v" => 0,
        "graph over u" => 1,
        // Along an edge where g vanishes: every point of the segment is on the curve.
        _ => {
            let n = 4 * steps;
            return (0..=n)
                .map(|i| {
                    let s = i as f64 / n as f64;
                    [p0[0] + (p1[0] - p0[0]) * s, p0[1] + (p1[1] - p0[1]) * s]
                })
                .collect();
        }
    };
    let o = 1 - m;
    let [lo, hi] = a.cell.to_f64();
    let mut pts = vec![p0];
    for i in 1..steps {
        let s = p0[o] + (p1[o] - p0[o]) * i as f64 / steps as f64;
        if let Some(x) = zero_across(g, m, s, lo[m], hi[m]) {
            let mut q = [0.0; 2];
            q[m] = x;
            q[o] = s;
            pts.push(q);
        }
    }
    pts.push(p1);
    pts
}

/// The zero of g on the line where variable `1 − m` equals `s`, with variable `m` in
/// `[lo, hi]` where g changes sign, found in f64 by the Illinois method (a drawing point, not
/// a certified one); `None` without a sign change.
pub(crate) fn zero_across(g: &Bernstein<f64>, m: usize, s: f64, lo: f64, hi: f64) -> Option<f64> {
    let f = |x: f64| {
        let mut pt = [0.0; 2];
        pt[m] = x;
        pt[1 - m] = s;
        g.eval(&pt)
    };
    let (mut x0, mut x1) = (lo, hi);
    let (mut f0, mut f1) = (f(x0), f(x1));
    if f0 * f1 >= 0.0 || f0.is_nan() || f1.is_nan() {
        return None;
    }
    let mut side = 0;
    for _ in 0..60 {
        let x = (x0 * f1 - x1 * f0) / (f1 - f0);
        let fx = f(x);
        if fx == 0.0 || (x1 - x0).abs() < 1e-14 {
            x0 = x;
            x1 = x;
            break;
        }
        if fx * f1 < 0.0 {
            (x0, f0) = (x1, f1);
            (x1, f1) = (x, fx);
            side = 0;
        } else {
            (x1, f1) = (x, fx);
            if side == 1 {
                f0 *= 0.5;
            }
            side = 1;
        }
    }
    Some(0.5 * (x0 + x1))
}

/// Joins the crossings of two patches with a side on which the silhouette lies, when the
/// solved polynomials (the silhouette functions with the side's factor divided out) are exactly
/// proportional on it: then their roots on the side, where each patch's curve meets it, are the
/// same points, and the i-th crossings along the side are joined. Patch `b`'s arcs along the
/// side have been dropped already (patch `a`'s, split at the same points, stand for both).
fn join_by_quotients(
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
            .filter(|a| a.reason != "on edge")
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

/// The point of a side at parameter t, in the patch's (u, v).
fn side_point(edge: Edge, t: Dyadic) -> CrossingId {
    let (fixed, at_one) = side_axis(edge);
    line_point(fixed, if at_one { Dyadic::ONE } else { Dyadic::ZERO }, t)
}

/// Joins a shared edge on which both silhouette functions vanish identically: the edge is
/// part of the silhouette, exactly. Both patches' arcs along it are replaced by one chain
/// (kept in patch `a`) through all their points, and `b`'s crossings on the edge are joined to
/// `a`'s at the same (exact, dyadic) parameter (`proofs/silhouette-join.md`).
fn join_zero_side(
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
                            !(arc.reason == "on edge" && both_on(&arc.from, &arc.to, b.edge))
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
            .retain(|arc| !(arc.reason == "on edge" && both_on(&arc.from, &arc.to, edge)));
    }
    ts.sort();
    ts.dedup();
    let ta = &mut tops[a.patch];
    for w in ts.windows(2) {
        let (from, to) = (side_point(a.edge, w[0]), side_point(a.edge, w[1]));
        for id in [from, to] {
            if let CrossingId::Exact { u, v } = id {
                let p = [u.to_f64(), v.to_f64()];
                ta.locations.insert(id, [p, p]);
            }
        }
        ta.arcs.push(crate::solver::curve2::Arc {
            from,
            to,
            cell: crate::solver::DyadicBox::UNIT,
            reason: "on edge",
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
fn join_one_sided(
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
        .retain(|arc| !(arc.reason == "on edge" && both_on(&arc.from, &arc.to, zero.edge)));
    let at: Vec<Dyadic> = extra.iter().map(|e| e.1).collect();
    add_line(tz, fixed, c, &at);
    for (id, t) in extra {
        joins.union((other.patch, id), (zero.patch, line_point(fixed, c, t)));
    }
    true
}

fn chain_model(
    tops: &[CurveTopology],
    gs_fast: &[Bernstein<f64>],
    patches: &[&RationalPatch],
    joins: &mut Joins,
    open_boundary: &[(usize, Edge)],
    accuracy: Option<(&[Option<PatchAccuracy>], f64)>,
    deadline: Option<std::time::Instant>,
) -> (Vec<SilhouetteCurve>, Vec<SingularPoint>) {
    let draw: Vec<DrawPatch> = patches.iter().map(|p| DrawPatch::new(p)).collect();
    // The certified traces of all arcs, in parallel (each arc is independent).
    type Trace = Option<Traced>;
    let traced: Option<Vec<Vec<Trace>>> = accuracy.map(|(acc, tol)| {
        tops.par_iter()
            .enumerate()
            .map(|(p, t)| {
                t.arcs
                    .par_iter()
                    .map(|a| {
                        // Past the time limit, arcs are drawn but not traced (not certified).
                        let late = deadline.is_some_and(|d| std::time::Instant::now() >= d);
                        acc[p]
                            .as_ref()
                            .filter(|_| !late)
                            .map(|pa| pa.trace(a, t.locations[&a.from], t.locations[&a.to], tol))
                    })
                    .collect()
            })
            .collect()
    });
    // Arcs of all patches, with their ends mapped to joined nodes.
    let mut arcs: Vec<(Node, Node, usize)> = Vec::new();
    let mut arc_ref: Vec<(usize, usize)> = Vec::new();
    for (p, t) in tops.iter().enumerate() {
        for (k, a) in t.arcs.iter().enumerate() {
            arcs.push((joins.find((p, a.from)), joins.find((p, a.to)), p));
            arc_ref.push((p, k));
        }
    }
    let mut incident: BTreeMap<Node, Vec<usize>> = BTreeMap::new();
    for (i, (a, b, _)) in arcs.iter().enumerate() {
        incident.entry(*a).or_default().push(i);
        incident.entry(*b).or_default().push(i);
    }
    // A joined node is on the open boundary if any of the crossings joined into it is.
    let mut boundary_nodes: std::collections::BTreeSet<Node> = std::collections::BTreeSet::new();
    for (p, t) in tops.iter().enumerate() {
        for a in &t.arcs {
            for id in [a.from, a.to] {
                if side_of(&id)
                    .iter()
                    .any(|s| open_boundary.contains(&(p, s.0)))
                {
                    boundary_nodes.insert(joins.find((p, id)));
                }
            }
        }
    }
    let ends_on_boundary = |n: &Node| boundary_nodes.contains(n);
    let mut used = vec![false; arcs.len()];
    let mut curves = Vec::new();
    // Open curves start at every arc of a node of degree other than 2 (a junction starts as
    // many curves as it has arcs); what is left are closed loops.
    let starts: Vec<(Node, bool)> = incident
        .iter()
        .filter(|(_, v)| v.len() != 2)
        .flat_map(|(k, v)| std::iter::repeat_n((*k, true), v.len()))
        .chain(incident.keys().map(|k| (*k, false)))
        .collect();
    for (start, open) in starts {
        let Some(&first) = incident[&start].iter().find(|&&i| !used[i]) else {
            continue;
        };
        let mut nodes = vec![start];
        let mut walked: Vec<(usize, bool)> = Vec::new();
        let mut at = start;
        let mut arc = first;
        let mut closed = false;
        loop {
            used[arc] = true;
            let (x, y, _) = arcs[arc];
            let next = if x == at { y } else { x };
            walked.push((arc, x != at));
            if next == start && !open {
                closed = true;
                break;
            }
            nodes.push(next);
            at = next;
            let inc = &incident[&at];
            if inc.len() != 2 {
                break;
            }
            match inc.iter().find(|&&j| !used[j]) {
                Some(&j) => arc = j,
                None => break,
            }
        }
        // A walk passes only through nodes of degree 2. An open curve's end is proven if it
        // lies on the model's open boundary (degree 1) or is a junction of three or more
        // proven arcs (a singular point of the silhouette); a degree-1 end elsewhere is a join
        // that could not be proven.
        let end_ok = |n: &Node| match incident[n].len() {
            1 => ends_on_boundary(n),
            d => d >= 3,
        };
        let certified = if closed {
            nodes.iter().all(|n| incident[n].len() == 2)
        } else {
            end_ok(&nodes[0]) && end_ok(nodes.last().expect("nonempty"))
        };
        let mut visited = Vec::new();
        let mut points_uv = Vec::new();
        let mut pieces = Vec::new();
        let mut worst: Option<f64> = accuracy.map(|_| 0.0);
        for &(arc, backwards) in &walked {
            let (p, k) = arc_ref[arc];
            if !visited.contains(&p) {
                visited.push(p);
            }
            let a = &tops[p].arcs[k];
            // Without a trace, the arc's box holds the arc and all its drawing points.
            let [lo, hi] = a.cell.to_f64();
            let whole = |n: usize| vec![([lo, hi], 0, n - 1)];
            let (mut pts, mut local) = match traced.as_ref().map(|t| &t[p][k]) {
                Some(Some(t)) => {
                    match t.bound {
                        Some(e) => worst = worst.map(|w: f64| w.max(e)),
                        None => worst = None,
                    }
                    let local = if t.pieces.is_empty() {
                        whole(t.points.len())
                    } else {
                        t.pieces.clone()
                    };
                    (t.points.clone(), local)
                }
                Some(None) => {
                    worst = None;
                    let pts = densify(&gs_fast[p], &tops[p], a, DENSIFY_STEPS);
                    let n = pts.len();
                    (pts, whole(n))
                }
                None => {
                    let pts = densify(&gs_fast[p], &tops[p], a, DENSIFY_STEPS);
                    let n = pts.len();
                    (pts, whole(n))
                }
            };
            if backwards {
                pts.reverse();
                let n = pts.len();
                for piece in &mut local {
                    *piece = (piece.0, n - 1 - piece.2, n - 1 - piece.1);
                }
            }
            // Each arc starts where the previous one ended: keep that point once.
            let skip = usize::from(!points_uv.is_empty());
            let start = points_uv.len() - skip;
            pieces.extend(local.into_iter().map(|(cell, i, j)| CurvePiece {
                patch: p,
                cell,
                first: start + i,
                last: start + j,
            }));
            points_uv.extend(pts.into_iter().skip(skip).map(|[u, v]| (p, u, v)));
        }
        let points = points_uv
            .iter()
            .map(|&(p, u, v)| draw[p].eval(u, v))
            .collect();
        // The drawn points are f64 evaluations: their rounding is part of the bound
        // (`proofs/chord-accuracy.md`, "The drawn points"; the traced vertices lie in the unit
        // square).
        let worst = worst.and_then(|w| {
            let r = visited
                .iter()
                .map(|&p| draw[p].rounding())
                .try_fold(0.0f64, |a, r| Some(a.max(r?)))?;
            Some((w + r) * (1.0 + 1e-12))
        });
        let within = accuracy.is_some_and(|(_, tol)| worst.is_some_and(|w| w <= tol));
        curves.push(SilhouetteCurve {
            patches: visited,
            closed,
            certified_topology: certified,
            certified: certified && within,
            error_bound: worst,
            points_uv,
            points,
            pieces,
        });
    }
    // Junctions: nodes where three or more proven arcs meet.
    let singular = incident
        .iter()
        .filter(|(_, arcs)| arcs.len() >= 3)
        .map(|(&(p, id), arcs)| {
            let [lo, hi] = tops[p].locations[&id];
            let uv = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
            SingularPoint {
                patch: p,
                uv,
                point: draw[p].eval(uv[0], uv[1]),
                cell: [lo, hi],
                exact: matches!(id, CrossingId::Exact { .. }),
                branches: arcs.len(),
            }
        })
        .collect();
    (curves, singular)
}

/// A point where three or more arcs of the silhouette meet (the curve reaching a side on
/// which the silhouette function vanishes, or several patches' curves through one vertex).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SingularPoint {
    /// A patch it lies on.
    pub patch: usize,
    /// Its (u, v) there (the centre of `box`).
    pub uv: [f64; 2],
    /// The point in space.
    pub point: [f64; 3],
    /// A box in (u, v) that contains it, `[[u0, v0], [u1, v1]]` (a point if exact).
    #[serde(rename = "box")]
    pub cell: [[f64; 2]; 2],
    /// Its parameters are exact dyadic numbers.
    pub exact: bool,
    /// The number of curve arcs that end at it.
    pub branches: usize,
}

/// A patch in f64 for drawing: its homogeneous polynomials converted once.
pub struct DrawPatch {
    h: [Bernstein<f64>; 4],
    /// A bound on the distance between [`DrawPatch::eval`]'s point and the exact one, on the
    /// unit square.
    rounding: Option<f64>,
}

impl DrawPatch {
    /// Converts a patch (once).
    pub fn new(patch: &RationalPatch) -> DrawPatch {
        let h = patch.homogeneous().map(|p| p.convert(Precision::F64));
        DrawPatch {
            rounding: rounding_bound(&h),
            h,
        }
    }

    /// A bound, for every (u, v) of the unit square, on the distance between the f64 point
    /// [`DrawPatch::eval`] computes and the exact point `S(u, v)`
    /// (`proofs/chord-accuracy.md`, "The drawn points"); `None` if a weight is not positive
    /// (or the bound is not small beside the least weight).
    pub fn rounding(&self) -> Option<f64> {
        self.rounding
    }

    /// The point S(u, v) in f64, for drawing: on the unit square within
    /// [`DrawPatch::rounding`] of the exact point.
    pub fn eval(&self, u: f64, v: f64) -> [f64; 3] {
        let x = [u, v];
        let c: Vec<f64> = self.h.iter().map(|p| p.eval(&x)).collect();
        [c[0] / c[3], c[1] / c[3], c[2] / c[3]]
    }
}

/// The a priori bound of [`DrawPatch::rounding`] (`proofs/chord-accuracy.md`, "The drawn
/// points"): each homogeneous coordinate evaluated in f64 (fibre by fibre, the coefficients
/// rounded from the exact ones) is within `γ_K · max|c|` of the exact value, with
/// `K = 3(n_u + n_v) + 4` and `γ_K = K u / (1 − K u)`; the quotient by the weight (at least its
/// least coefficient, less its own error) adds the error of the weight times `|S|` (at most the
/// largest `|P_i / W_i|`, the convex-hull property) and one rounding.
fn rounding_bound(h: &[Bernstein<f64>; 4]) -> Option<f64> {
    let u = f64::EPSILON / 2.0;
    let d = h[3].degrees();
    if h.iter().any(|p| p.degrees() != d) || d.len() != 2 {
        return None;
    }
    let k = (3 * (d[0] + d[1]) + 4) as f64;
    let gamma = k * u / (1.0 - k * u);
    let max_abs = |p: &Bernstein<f64>| p.coeffs().iter().fold(0.0f64, |a, c| a.max(c.abs()));
    // The exact coefficients are within one rounding of these.
    let margin = 1.0 + 4.0 * u;
    let w = h[3].coeffs();
    let w_min = w.iter().copied().fold(f64::INFINITY, f64::min) / margin;
    if !(w_min > 0.0 && w_min.is_finite()) {
        return None;
    }
    let e_w = gamma * max_abs(&h[3]) * margin;
    if e_w >= 0.5 * w_min {
        return None;
    }
    let mut sum = 0.0;
    for p in &h[..3] {
        let s_max = p
            .coeffs()
            .iter()
            .zip(w)
            .fold(0.0f64, |a, (c, wi)| a.max(c.abs() / wi))
            * margin
            * margin;
        let e_p = gamma * max_abs(p) * margin;
        let quotient = (e_p + s_max * e_w) / (w_min - e_w);
        let r = (quotient + 2.0 * u * (s_max + quotient)) * margin;
        sum += r * r;
    }
    let bound = sum.sqrt() * margin;
    bound.is_finite().then_some(bound)
}

/// The point S(u, v) in f64 (for drawing; not a certified quantity). For many points of one
/// patch, build a [`DrawPatch`] once instead.
pub fn eval_f64(patch: &RationalPatch, u: f64, v: f64) -> [f64; 3] {
    DrawPatch::new(patch).eval(u, v)
}
