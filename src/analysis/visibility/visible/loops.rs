//! The boundary loops of a union of quadtree leaves, on the unit grid of the finest level.
//!
//! Every side of a member leaf, stretch by stretch, is a boundary edge where the leaf across
//! it is not a member (or lies beyond the square). Edges run with the region on their left
//! (counter-clockwise around the region, clockwise around its holes) and are chained at their
//! ends into closed loops; collinear vertices are dropped.

use crate::analysis::visibility::visible::cells::LeafIndex;
use std::collections::HashMap;

/// A point of the unit grid.
type Pt = (i64, i64);

/// The closed loops (first vertex not repeated) bounding the leaves with `member[k]`.
pub(super) fn boundary_loops(index: &LeafIndex, member: &[bool]) -> Vec<Vec<Pt>> {
    let mut next: HashMap<Pt, Vec<Pt>> = HashMap::new();
    for (k, _) in member.iter().enumerate().filter(|(_, m)| **m) {
        let (x0, y0, s) = index.extent(k);
        for side in 0..4 {
            for (n, a, b) in index.across(k, side) {
                if n.is_some_and(|n| member[n]) {
                    continue;
                }
                // Counter-clockwise around the leaf.
                let (from, to) = match side {
                    0 => ((a, y0), (b, y0)),
                    1 => ((x0 + s, a), (x0 + s, b)),
                    2 => ((b, y0 + s), (a, y0 + s)),
                    _ => ((x0, b), (x0, a)),
                };
                next.entry(from).or_default().push(to);
            }
        }
    }
    let mut loops = Vec::new();
    let mut starts: Vec<Pt> = next.keys().copied().collect();
    starts.sort_unstable();
    for s in starts {
        while let Some(first) = next.get_mut(&s).and_then(|v| v.pop()) {
            let mut pts = vec![s];
            let mut at = first;
            while at != s {
                pts.push(at);
                let Some(n) = next.get_mut(&at).and_then(|v| v.pop()) else {
                    break; // cannot happen: every vertex has as many edges in as out
                };
                at = n;
            }
            loops.push(simplify(pts));
        }
    }
    loops
}

/// Drops the vertices where the loop goes straight on.
fn simplify(pts: Vec<Pt>) -> Vec<Pt> {
    let n = pts.len();
    if n < 3 {
        return pts;
    }
    (0..n)
        .filter(|&k| {
            let (a, b, c) = (pts[(k + n - 1) % n], pts[k], pts[(k + 1) % n]);
            (b.0 - a.0) * (c.1 - b.1) - (b.1 - a.1) * (c.0 - b.0) != 0
        })
        .map(|k| pts[k])
        .collect()
}

/// The signed area of a loop (positive: counter-clockwise), in unit-grid squares.
pub(super) fn signed_area(pts: &[Pt]) -> i64 {
    let n = pts.len();
    (0..n)
        .map(|k| {
            let (a, b) = (pts[k], pts[(k + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<i64>()
        / 2
}
