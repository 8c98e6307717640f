//! Silhouettes (contour generators) of rational Bézier models, with certified topology.
//!
//! For a patch with unnormalized normal Ñ (a positive multiple of S_u × S_v), the silhouette
//! function is `g = Ñ · V` for a parallel view direction V (front-facing where g < 0), or
//! `g = Ñ · (E W − P)` for a perspective eye E, with `P = [wx, wy, wz]` and W the weight
//! (front-facing where g > 0). Both are exact polynomials; the silhouette is `g = 0`, solved
//! per patch by [`solve_curve`] and joined across shared edges where the join is proven
//! (`proofs/silhouette-join.md`).

use crate::bernstein::Bernstein;
use crate::model::{Model, PatchAdjacency, SideUse, WeldTolerance};
use crate::number::{Number, Precision, Rational};
use crate::solver::{solve_curve, CrossingId, CurveOptions, CurveTopology, Dyadic, Escalations};
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// A view: parallel direction (from the viewer into the scene) or perspective eye point.
#[derive(Clone, Debug, PartialEq)]
pub enum View {
    /// Parallel projection along this direction.
    Direction([Rational; 3]),
    /// Perspective from this eye point.
    Eye([Rational; 3]),
}

/// The silhouette function of a patch for a view (exact).
///
/// # Examples
/// ```
/// use limn::analysis::silhouette::{silhouette_function, View};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let patch = &shapes::sphere(&Rational::from(1))[0];
/// let z = Rational::new();
/// let g = silhouette_function(patch, &View::Direction([z.clone(), z, Rational::from(1)]));
/// assert_eq!(g.nvars(), 2);
/// ```
pub fn silhouette_function(patch: &RationalPatch, view: &View) -> Bernstein<Rational> {
    let n = patch.normal();
    match view {
        View::Direction(d) => {
            let terms: Vec<Bernstein<Rational>> = (0..3).map(|k| n[k].scale(&d[k])).collect();
            (&(&terms[0] + &terms[1]) + &terms[2]).reduce_degree_exact()
        }
        View::Eye(e) => {
            let [px, py, pz, w] = patch.homogeneous();
            let p = [px, py, pz];
            let mut sum: Option<Bernstein<Rational>> = None;
            for k in 0..3 {
                let to_eye = &w.scale(&e[k]) - &p[k];
                let term = &n[k] * &to_eye;
                sum = Some(match sum {
                    None => term,
                    Some(s) => &s + &term,
                });
            }
            sum.expect("three terms").reduce_degree_exact()
        }
    }
}

/// A degenerate situation recognised exactly.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Degenerate {
    /// The patch.
    pub patch: usize,
    /// "edge-on" (g ≡ 0: the whole patch is on the silhouette, e.g. a plane seen edge-on),
    /// or "collapsed side" (a side collapsed to a point, where the normal vanishes).
    pub kind: &'static str,
    /// The side, for "collapsed side".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<Edge>,
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
    /// The crossings in order: (patch, u, v) at the centre of each certified location.
    pub points_uv: Vec<(usize, f64, f64)>,
    /// The same points in space (f64 evaluation of the patch at those parameters).
    pub points: Vec<[f64; 3]>,
}

/// The silhouette of a model.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Silhouette {
    /// The curves.
    pub curves: Vec<SilhouetteCurve>,
    /// Per patch: its certified topology in the parameter square.
    #[serde(skip)]
    pub patches: Vec<CurveTopology>,
    /// Degenerate cases.
    pub degenerate: Vec<Degenerate>,
    /// Undecided regions: (patch, box, reason).
    pub unresolved: Vec<(usize, crate::solver::DyadicBox, String)>,
    /// Shared edges across which the curves could not be joined with proof (patch sides).
    pub unjoined_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Boxes examined, summed over patches.
    pub boxes: usize,
    /// Sign questions by the level that settled them.
    pub escalations: Escalations,
}

/// The side a crossing lies on (the first one, for a corner) and its parameter along it,
/// as the dyadic interval containing it.
fn side_of(id: &CrossingId) -> Vec<(Edge, Dyadic, Dyadic)> {
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
fn side_polynomial(g: &Bernstein<Rational>, edge: Edge) -> Bernstein<Rational> {
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
fn proportional(p: &Bernstein<Rational>, q: &Bernstein<Rational>, reversed: bool) -> bool {
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

/// Computes the silhouette of a model's patches for a view.
///
/// Patches are solved in parallel (rayon); the result does not depend on the thread count.
/// Shared edges are found with `weld` (see [`PatchAdjacency`]).
pub fn silhouette(
    model: &Model,
    view: &View,
    opts: &CurveOptions,
    weld: WeldTolerance,
) -> Silhouette {
    let patches: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
    let gs: Vec<Bernstein<Rational>> = patches
        .par_iter()
        .map(|p| silhouette_function(p, view))
        .collect();
    let mut tops: Vec<CurveTopology> = gs.par_iter().map(|g| solve_curve(g, opts)).collect();
    let adj = PatchAdjacency::of_patches(&patches, weld);

    let mut degenerate = Vec::new();
    let mut unresolved = Vec::new();
    let mut escalations = Escalations::default();
    let mut boxes = 0;
    for (i, t) in tops.iter().enumerate() {
        if t.identically_zero {
            degenerate.push(Degenerate {
                patch: i,
                kind: "edge-on",
                side: None,
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
    let mut pole_nodes: BTreeMap<usize, Vec<Node>> = BTreeMap::new();
    for &(patch, edge, vertex) in &adj.collapsed {
        degenerate.push(Degenerate {
            patch,
            kind: "collapsed side",
            side: Some(edge),
        });
        let t = &mut tops[patch];
        t.arcs
            .retain(|a| !(a.reason == "on edge" && both_on(&a.from, &a.to, edge)));
        for a in &t.arcs {
            for id in [a.from, a.to] {
                if side_of(&id).iter().any(|s| s.0 == edge) {
                    pole_nodes.entry(vertex).or_default().push((patch, id));
                }
            }
        }
    }
    for nodes in pole_nodes.values() {
        for w in nodes.windows(2) {
            joins.union(w[0], w[1]);
        }
    }
    // Shared edges: join crossings when the two side polynomials are exactly proportional.
    let mut unjoined = Vec::new();
    let mut open_boundary: Vec<(usize, Edge)> = Vec::new();
    for class in &adj.edges {
        if class.len() == 1 {
            open_boundary.push((class[0].patch, class[0].edge));
            continue;
        }
        if class.len() != 2 {
            continue;
        }
        let (a, b) = (class[0], class[1]);
        if !join_side(&tops, &gs, a, b, &mut joins) {
            unjoined.push((a.patch, a.edge, b.patch, b.edge));
        }
    }
    let curves = chain_model(&tops, &patches, &mut joins, &open_boundary);
    Silhouette {
        curves,
        patches: tops,
        degenerate,
        unresolved,
        unjoined_edges: unjoined,
        boxes,
        escalations,
    }
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
    a: SideUse,
    b: SideUse,
    joins: &mut Joins,
) -> bool {
    let pa = side_polynomial(&gs[a.patch], a.edge);
    let pb = side_polynomial(&gs[b.patch], b.edge);
    let reversed = a.reversed != b.reversed;
    if !proportional(&pa, &pb, reversed) {
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

fn chain_model(
    tops: &[CurveTopology],
    patches: &[&RationalPatch],
    joins: &mut Joins,
    open_boundary: &[(usize, Edge)],
) -> Vec<SilhouetteCurve> {
    // Arcs of all patches, with their ends mapped to joined nodes.
    let mut arcs: Vec<(Node, Node, usize)> = Vec::new();
    for (p, t) in tops.iter().enumerate() {
        for a in &t.arcs {
            arcs.push((joins.find((p, a.from)), joins.find((p, a.to)), p));
        }
    }
    let mut incident: BTreeMap<Node, Vec<usize>> = BTreeMap::new();
    for (i, (a, b, _)) in arcs.iter().enumerate() {
        incident.entry(*a).or_default().push(i);
        incident.entry(*b).or_default().push(i);
    }
    let ends_on_boundary = |n: &Node| {
        side_of(&n.1)
            .iter()
            .any(|s| open_boundary.contains(&(n.0, s.0)))
    };
    let mut used = vec![false; arcs.len()];
    let mut curves = Vec::new();
    let starts: Vec<(Node, bool)> = incident
        .iter()
        .filter(|(_, v)| v.len() != 2)
        .map(|(k, _)| (*k, true))
        .chain(incident.keys().map(|k| (*k, false)))
        .collect();
    for (start, open) in starts {
        let Some(&first) = incident[&start].iter().find(|&&i| !used[i]) else {
            continue;
        };
        let mut nodes = vec![start];
        let mut at = start;
        let mut arc = first;
        let mut closed = false;
        loop {
            used[arc] = true;
            let (x, y, _) = arcs[arc];
            let next = if x == at { y } else { x };
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
        let degrees_ok = nodes.iter().all(|n| incident[n].len() == 2)
            || (!closed
                && incident[&nodes[0]].len() == 1
                && incident[nodes.last().expect("nonempty")].len() == 1);
        let certified = if closed {
            degrees_ok
        } else {
            degrees_ok
                && ends_on_boundary(&nodes[0])
                && ends_on_boundary(nodes.last().expect("nonempty"))
        };
        let mut visited = Vec::new();
        let mut points_uv = Vec::new();
        let mut points = Vec::new();
        for (p, id) in &nodes {
            if !visited.contains(p) {
                visited.push(*p);
            }
            let [u, v] = tops[*p].point(id);
            points_uv.push((*p, u, v));
            points.push(eval_f64(patches[*p], u, v));
        }
        curves.push(SilhouetteCurve {
            patches: visited,
            closed,
            certified_topology: certified,
            points_uv,
            points,
        });
    }
    curves
}

/// The point S(u, v) in f64 (for drawing; not a certified quantity).
pub fn eval_f64(patch: &RationalPatch, u: f64, v: f64) -> [f64; 3] {
    let h = patch.homogeneous();
    let x = [u, v];
    let c: Vec<f64> = h
        .iter()
        .map(|p| p.convert::<f64>(Precision::F64).eval(&x))
        .collect();
    [c[0] / c[3], c[1] / c[3], c[2] / c[3]]
}

/// Parses "x,y,z" into an exact view vector.
///
/// # Errors
/// A message if the text is not three numbers or is the zero vector.
pub fn parse_vector(text: &str) -> Result<[Rational; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers x,y,z, found {text:?}"));
    }
    let mut v = Vec::with_capacity(3);
    for p in parts {
        v.push(crate::number::parse_exact(p).map_err(|e| format!("{text:?}: {e}"))?);
    }
    let v: [Rational; 3] = v.try_into().map_err(|_| "three numbers".to_string())?;
    Ok(v)
}

impl View {
    /// Whether a direction view is the zero vector (meaningless).
    pub fn is_degenerate(&self) -> bool {
        match self {
            View::Direction(d) => d.iter().all(|c| c.sign().is_zero()),
            View::Eye(_) => false,
        }
    }
}
