//! Certified bounds on the surface area of parameter boxes of a patch.
//!
//! The area element is `|S_u × S_v| = |Ñ| / W³` for a rational patch and `|Ñ|` for a
//! polynomial one (`proofs/normal-degree.md`). On a box, the Bernstein range of the exact
//! polynomial `Ñ · Ñ` and of `W` (positive) bound it from both sides; the area of a box is its
//! parameter area times those bounds. The bounds are kept on an adaptive quadtree built once
//! per patch by midpoint subdivision: a cell coarser than a tree leaf sums its sub-boxes, a
//! finer one uses its leaf's bounds (a box's range bounds hold on every sub-box).

use crate::analysis::visibility::visible::outline::quarters;
use crate::bernstein::Bernstein;
use crate::number::margin;
use crate::number::{Interval, Number, Precision};
use crate::surface::RationalPatch;

type IPoly = Bernstein<Interval>;

/// A node of the adaptive tree of density bounds.
enum DensityNode {
    /// Bounds on the area element over the box.
    Leaf([f64; 2]),
    /// The quarters (order of [`quarters`]), with the area bounds of the whole box.
    Split(Box<[DensityNode; 4]>, [f64; 2]),
}

/// The area element of one patch, bounded on an adaptive quadtree: a box is split (down to
/// `max_level`) while its bounds leave more than `slack` of the patch's area undecided per
/// box of the `base_level` grid.
pub(super) struct AreaElement {
    root: DensityNode,
}

/// Bounds on `sqrt(n2) / w³` from the coefficient ranges of `n2 = Ñ · Ñ` and `w` on a box.
fn density(n2: &IPoly, w: Option<&IPoly>) -> [f64; 2] {
    let r = n2.hull();
    // sqrt is correctly rounded: one step outward encloses.
    let a = r.lo().max(0.0).sqrt().next_down().max(0.0);
    let b = r.hi().max(0.0).sqrt().next_up();
    let root = Interval::new(a, b);
    let d = match w {
        None => root,
        Some(w) => {
            let wr = w.hull();
            let Some(inv) = wr.mul(&wr).mul(&wr).recip().filter(|_| wr.lo() > 0.0) else {
                return [0.0, f64::INFINITY];
            };
            root.mul(&inv)
        }
    };
    let (a, b) = (d.lo(), d.hi());
    [a.max(0.0), b]
}

/// Builds the tree below a box at `level` (parameter area `4^-level`): split while above
/// `base_level`, or while its bounds leave more than `slack` undecided, down to `max_level`.
fn build(
    n2: &IPoly,
    w: Option<&IPoly>,
    level: u32,
    [base_level, max_level]: [u32; 2],
    slack: f64,
) -> DensityNode {
    if level >= base_level {
        let d = density(n2, w);
        let box_area = 0.25f64.powi(level as i32);
        if level >= max_level || (d[1] - d[0]) * box_area <= slack {
            return DensityNode::Leaf(d);
        }
    }
    let nq = quarters(n2);
    let wq = w.map(quarters);
    let kids: Vec<DensityNode> = (0..4)
        .map(|k| {
            let wk = wq.as_ref().map(|q| &q[k]);
            build(&nq[k], wk, level + 1, [base_level, max_level], slack)
        })
        .collect();
    let mut sum = [0.0, 0.0];
    for kid in &kids {
        let a = node_area(kid, level + 1);
        sum[0] += a[0];
        sum[1] += a[1];
    }
    let kids: [DensityNode; 4] = kids.try_into().unwrap_or_else(|_| unreachable!());
    DensityNode::Split(Box::new(kids), sum)
}

/// The area bounds of a whole node at `level`.
fn node_area(n: &DensityNode, level: u32) -> [f64; 2] {
    match n {
        DensityNode::Leaf(d) => {
            let a = 0.25f64.powi(level as i32);
            [
                margin::down(d[0] * a, margin::FEW),
                margin::up(d[1] * a, margin::FEW),
            ]
        }
        DensityNode::Split(_, s) => [
            margin::down(s[0], margin::FEW),
            margin::up(s[1], margin::FEW),
        ],
    }
}

impl AreaElement {
    /// The tree of a patch: boxes of the `base_level` grid at least, split while their
    /// undecided area exceeds `tol` of the patch's area per grid box, down to `max_level`.
    pub(super) fn new(
        patch: &RationalPatch,
        base_level: u32,
        max_level: u32,
        tol: f64,
    ) -> AreaElement {
        // Ñ exact, Ñ · Ñ in intervals (an enclosure of the exact product's coefficients,
        // `proofs/de-casteljau-enclosure.md`).
        let n: Vec<IPoly> = patch
            .normal()
            .iter()
            .map(|c| c.convert(Precision::F64))
            .collect();
        let n2: IPoly = &(&(&n[0] * &n[0]) + &(&n[1] * &n[1])) + &(&n[2] * &n[2]);
        let w: Option<IPoly> =
            (!patch.is_polynomial()).then(|| patch.homogeneous()[3].convert(Precision::F64));
        // A first estimate of the area (the lower bound on the base grid), for the slack.
        let base = build(&n2, w.as_ref(), 0, [base_level, base_level], 0.0);
        let slack = tol * node_area(&base, 0)[0] * 0.25f64.powi(base_level as i32);
        let root = build(&n2, w.as_ref(), 0, [base_level, max_level], slack);
        AreaElement { root }
    }

    /// Bounds on the surface area of the cell `(i, j)` at `level`.
    pub(super) fn area(&self, level: u32, i: u32, j: u32) -> [f64; 2] {
        let mut node = &self.root;
        let mut l = 0;
        loop {
            match node {
                DensityNode::Leaf(d) => {
                    let a = 0.25f64.powi(level as i32);
                    return [
                        margin::down(d[0] * a, margin::FEW),
                        margin::up(d[1] * a, margin::FEW),
                    ];
                }
                DensityNode::Split(kids, _) => {
                    if l == level {
                        return node_area(node, l);
                    }
                    let s = level - l - 1;
                    let k = ((i >> s) & 1) + 2 * ((j >> s) & 1);
                    node = &kids[k as usize];
                    l += 1;
                }
            }
        }
    }
}
