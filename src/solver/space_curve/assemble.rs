//! Gluing the boxes' arcs at their shared face crossings into the curve's branches.

use crate::solver::dyadic::Dyadic;
use crate::solver::space_curve::subdivision::{RawArc, RawCrossing};
use crate::solver::space_curve::topology::{SpaceArc, SpaceBranch, SpaceCrossing, SpaceCurve};
use crate::solver::system::{within, without};
use std::collections::HashMap;

/// Names each crossing once (two raw crossings on one hyperplane are the same point when one's
/// enclosure lies in the other's uniqueness region), and chains the arcs into branches; the
/// named crossing of each raw one.
pub(crate) fn assemble(
    out: &mut SpaceCurve,
    raw: Vec<RawCrossing>,
    arcs: Vec<RawArc>,
) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..raw.len()).collect();
    pub(crate) fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let mut by_plane: HashMap<(usize, Dyadic), Vec<usize>> = HashMap::new();
    for (k, c) in raw.iter().enumerate() {
        if !c.on_boundary && c.singular.is_none() {
            by_plane.entry((c.axis, c.at)).or_default().push(k);
        }
    }
    let face = |c: &RawCrossing| without(&c.enclosure, c.axis);
    let mut planes: Vec<_> = by_plane.into_values().collect();
    planes.sort();
    for members in planes {
        for (x, &a) in members.iter().enumerate() {
            for &b in &members[x + 1..] {
                if within(&face(&raw[a]), &raw[b].unique_in)
                    || within(&face(&raw[b]), &raw[a].unique_in)
                {
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
    }
    let mut id: HashMap<usize, usize> = HashMap::new();
    for k in 0..raw.len() {
        let root = find(&mut parent, k);
        if let std::collections::hash_map::Entry::Vacant(e) = id.entry(root) {
            e.insert(out.crossings.len());
            let c = &raw[root];
            out.crossings.push(SpaceCrossing {
                axis: c.axis,
                at: c.at,
                enclosure: c.enclosure.clone(),
                on_boundary: c.on_boundary,
                unique_in: c.unique_in.clone(),
                singular: c.singular,
            });
        }
    }
    let named: Vec<usize> = (0..raw.len()).map(|k| id[&find(&mut parent, k)]).collect();
    let ends = |k: usize| named[k];
    out.arcs = arcs
        .into_iter()
        .map(|a| SpaceArc {
            from: ends(a.from),
            to: ends(a.to),
            cell: a.cell,
            monotone_in: a.monotone_in,
            deviation: a.deviation,
        })
        .collect();
    let edges: Vec<(usize, usize)> = out.arcs.iter().map(|a| (a.from, a.to)).collect();
    // A branch ending at a singular point whose star was decided is complete there.
    let crossings = &out.crossings;
    out.branches = crate::solver::chain::chain(
        &edges,
        crossings.len(),
        &|v| crossings[v].on_boundary,
        &|v| crossings[v].singular.is_some(),
    )
    .into_iter()
    .map(|c| SpaceBranch {
        crossings: c.vertices,
        closed: c.closed,
        complete: c.complete,
    })
    .collect();
    named
}
