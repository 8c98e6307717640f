//! Chaining the patches' arcs, glued at their joined crossings, into the model's curves:
//! closed loops and open curves, with where three or more arcs meet.

use crate::analysis::chords::plane_curve::{PatchAccuracy, Traced};
use crate::analysis::contour::curves::{
    CubicPiece, CurvePiece, Node, SilhouetteCurve, SingularPoint,
};
use crate::analysis::contour::drawing::{densify, DENSIFY_STEPS};
use crate::analysis::contour::joins::Joins;
use crate::analysis::contour::sides::side_of;
use crate::bernstein::Bernstein;
use crate::number::margin;
use crate::solver::{CrossingId, CurveTopology};
use crate::surface::DrawPatch;
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Where the model's curves may end, proven: on the open boundary of the patches, and on
/// trimming curves (with the proven distance from the drawn end to the true one).
pub(crate) struct CurveEnds<'a> {
    /// Patch sides on the model's open boundary.
    pub(crate) open_boundary: &'a [(usize, Edge)],
    /// Joined nodes on trimming curves ([`super::trims`]).
    pub(crate) trim_ends: &'a BTreeMap<Node, f64>,
}

pub(crate) fn chain_model(
    tops: &[CurveTopology],
    gs_fast: &[Bernstein<f64>],
    patches: &[&RationalPatch],
    joins: &mut Joins,
    ends: CurveEnds,
    accuracy: Option<(&[Option<PatchAccuracy>], f64)>,
    deadline: Option<std::time::Instant>,
) -> (Vec<SilhouetteCurve>, Vec<SingularPoint>) {
    let CurveEnds {
        open_boundary,
        trim_ends,
    } = ends;
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
    // Ends on trimming curves are ends on the boundary of the faces.
    let ends_on_boundary = |n: &Node| boundary_nodes.contains(n) || trim_ends.contains_key(n);
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
        let mut cubics = Vec::new();
        let mut cubic_bound: Option<f64> = accuracy.map(|_| 0.0);
        let mut worst: Option<f64> = accuracy.map(|_| 0.0);
        for &(arc, backwards) in &walked {
            let (p, k) = arc_ref[arc];
            if !visited.contains(&p) {
                visited.push(p);
            }
            let a = &tops[p].arcs[k];
            // Without a trace, the arc's box holds the arc and all its drawing points.
            let cell = a.cell.to_f64();
            let whole = |n: usize| vec![(cell, 0, n - 1)];
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
                    if t.cubics.is_empty() {
                        cubic_bound = None;
                    }
                    let mut own: Vec<CubicPiece> = t
                        .cubics
                        .iter()
                        .map(|c| CubicPiece {
                            patch: p,
                            cubic: c.clone(),
                        })
                        .collect();
                    if backwards {
                        own.reverse();
                        for q in &mut own {
                            q.cubic.uv.reverse();
                            q.cubic.space.reverse();
                        }
                    }
                    for q in &own {
                        cubic_bound = cubic_bound.map(|w| w.max(q.cubic.bound));
                    }
                    cubics.extend(own);
                    (t.points.clone(), local)
                }
                Some(None) => {
                    worst = None;
                    cubic_bound = None;
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
        // A curve that ends on a trimming curve is drawn to a level next to it: the rest of
        // the true curve lies within the proven extent of the arc between
        // (`proofs/trimmed-faces.md`, 8).
        if !closed {
            for n in [&nodes[0], nodes.last().expect("nonempty")] {
                if let Some(&e) = trim_ends.get(n) {
                    worst = worst.map(|w| w.max(e));
                }
            }
        }
        // The drawn points are f64 evaluations: their rounding is part of the bound
        // (`proofs/chord-accuracy.md`, "The drawn points"; the traced vertices lie in the unit
        // square).
        let worst = worst.and_then(|w| {
            let r = visited
                .iter()
                .map(|&p| draw[p].rounding())
                .try_fold(0.0f64, |a, r| Some(a.max(r?)))?;
            Some(margin::up(w + r, margin::FEW))
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
            cubic_bound: cubic_bound.filter(|_| !cubics.is_empty()),
            cubics,
        });
    }
    // Junctions: nodes where three or more proven arcs meet.
    let singular = incident
        .iter()
        .filter(|(_, arcs)| arcs.len() >= 3)
        .map(|(&(p, id), arcs)| {
            let cell = tops[p].locations[&id];
            let uv = cell.center();
            SingularPoint {
                patch: p,
                uv,
                point: draw[p].eval(uv[0], uv[1]),
                cell,
                exact: matches!(id, CrossingId::Exact { .. }),
                branches: arcs.len(),
            }
        })
        .collect();
    (curves, singular)
}
