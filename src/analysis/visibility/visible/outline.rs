//! The outline of a model in a view, as lazily refined trees of boxes with image and depth
//! bounds: where the QI of a point behind it can change (`proofs/visible-regions.md`).
//!
//! - **Contour trees**, one per patch: boxes of its parameter square on which the silhouette
//!   function's Bernstein range contains 0 (every contour point lies in a kept box at every
//!   level, `proofs/coefficient-range.md`).
//! - **Side trees**, one per distinct edge (collapsed sides are points and are left out):
//!   intervals of the side parameter. A stretch of a shared edge whose two sheets are proven
//!   to lie on opposite sides of its image (the surface continues across it in the image) is
//!   not outline and is pruned.
//! - **Region trees**, one per patch: boxes of its whole square, for the penetration test.
//!
//! Children are computed once, on first use, and shared by every thread.

use crate::analysis::projection::ImagePolys;
use crate::analysis::visibility::fold_edges::{continues_on, edge_orientations};
use crate::analysis::visibility::scene::{same_degrees, ImageBounds, Scene};
use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision};
use crate::surface::Edge;
use std::sync::OnceLock;

use crate::bernstein::Poly;
type IPoly = Bernstein<Interval>;

/// Image polynomials in f64 intervals, at common degrees (x, y, q) and (depth, w).
#[derive(Clone, Debug)]
pub(super) struct IntervalImage {
    x: IPoly,
    y: IPoly,
    q: IPoly,
    depth: IPoly,
    w: IPoly,
}

impl IntervalImage {
    pub(super) fn new(im: &ImagePolys) -> IntervalImage {
        let c = |p: &Poly| p.convert::<Interval>(Precision::F64);
        let (x, q) = same_degrees(&im.x, &im.q);
        let (y, q2) = same_degrees(&im.y, &q);
        let (x, _) = same_degrees(&x, &q2);
        let (depth, w) = same_degrees(&im.depth, &im.w);
        IntervalImage {
            x: c(&x),
            y: c(&y),
            q: c(&q2),
            depth: c(&depth),
            w: c(&w),
        }
    }

    /// The four quarters of a 2-variable image (u low/high × v low/high, in the order
    /// `(0,0), (1,0), (0,1), (1,1)`), by de Casteljau midpoint splits.
    pub(super) fn quarters(&self) -> [IntervalImage; 4] {
        let [x, y, q, depth, w] = [&self.x, &self.y, &self.q, &self.depth, &self.w].map(quarters);
        let mut out = Vec::with_capacity(4);
        for k in 0..4 {
            out.push(IntervalImage {
                x: x[k].clone(),
                y: y[k].clone(),
                q: q[k].clone(),
                depth: depth[k].clone(),
                w: w[k].clone(),
            });
        }
        out.try_into().expect("four quarters")
    }

    /// Outward image and depth bounds on the whole domain of the polynomials, `None` if a
    /// denominator coefficient is not proven positive.
    pub(super) fn whole_bounds(&self) -> Option<ImageBounds> {
        Some(ImageBounds {
            x: coefficient_ratio(&self.x, &self.q)?,
            y: coefficient_ratio(&self.y, &self.q)?,
            depth: coefficient_ratio(&self.depth, &self.w)?,
        })
    }

    /// Outward image and depth bounds on a box of the variables (the rational convex-hull
    /// property: with positive denominator coefficients, every value of `x / q` lies between
    /// the least and greatest coefficient ratio). `None` if a denominator coefficient is not
    /// proven positive.
    pub(super) fn bounds(&self, lo: &[f64], hi: &[f64]) -> Option<ImageBounds> {
        let r = |p: &IPoly| p.restrict_box_f64(lo, hi);
        let (q, w) = (r(&self.q), r(&self.w));
        Some(ImageBounds {
            x: coefficient_ratio(&r(&self.x), &q)?,
            y: coefficient_ratio(&r(&self.y), &q)?,
            depth: coefficient_ratio(&r(&self.depth), &w)?,
        })
    }
}

/// The least and greatest coefficient ratio `num_k / den_k` (outward), which bound
/// `num / den` when every `den_k` is positive; `None` otherwise.
fn coefficient_ratio(num: &IPoly, den: &IPoly) -> Option<[f64; 2]> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (n, d) in num.coeffs().iter().zip(den.coeffs()) {
        let x = n.mul(&d.recip().filter(|_| d.lo() > 0.0)?);
        lo = lo.min(x.lo());
        hi = hi.max(x.hi());
    }
    Some([lo, hi])
}

/// The four quarters of a 2-variable polynomial, in the order of [`IntervalImage::quarters`].
pub(super) fn quarters(p: &IPoly) -> [IPoly; 4] {
    let (a, b) = p.subdivide_half(0);
    let (a0, a1) = a.subdivide_half(1);
    let (b0, b1) = b.subdivide_half(1);
    [a0, b0, a1, b1]
}

/// Bounds that separate from nothing.
pub(super) const UNBOUNDED: ImageBounds = ImageBounds {
    x: [f64::NEG_INFINITY, f64::INFINITY],
    y: [f64::NEG_INFINITY, f64::INFINITY],
    depth: [f64::NEG_INFINITY, f64::INFINITY],
};

/// Whether the Bernstein range of `p` on the box contains 0.
pub(super) fn may_vanish(p: &IPoly, lo: &[f64], hi: &[f64]) -> bool {
    let r = crate::analysis::visibility::sheets::range_on(p, lo, hi);
    r.lo() <= 0.0 && r.hi() >= 0.0
}

/// What a tree covers.
#[derive(Debug)]
pub(super) enum TreeKind {
    /// The contour of a patch: the zeros of its silhouette function.
    Contour { g: IPoly },
    /// An edge, in the side parameter of its first user; `fold` holds the two users'
    /// orientation polynomials when the edge has exactly two
    /// ([`crate::analysis::visibility::fold_edges`]).
    Side {
        edge: Edge,
        image: Box<IntervalImage>,
        fold: Option<[IPoly; 2]>,
        /// Every user of the edge: (patch, side, runs opposite to the first user).
        users: Vec<(usize, Edge, bool)>,
    },
    /// The whole patch (for penetrations).
    Region,
}

/// A box (2 variables) or an interval (a side: only index 0 is used) with its bounds.
#[derive(Debug)]
pub(super) struct Node {
    pub(super) lo: [f64; 2],
    pub(super) hi: [f64; 2],
    pub(super) level: u32,
    pub(super) bounds: ImageBounds,
    children: OnceLock<Vec<Node>>,
}

impl Node {
    /// The larger side of its image box.
    pub(super) fn image_size(&self) -> f64 {
        (self.bounds.x[1] - self.bounds.x[0]).max(self.bounds.y[1] - self.bounds.y[0])
    }
}

/// One tree of the outline.
#[derive(Debug)]
pub(super) struct Tree {
    /// The patch it lies on (the first user, for an edge).
    pub(super) patch: usize,
    pub(super) kind: TreeKind,
    /// `None` when nothing of it is outline (a contour-free patch, a pruned edge).
    pub(super) root: Option<Node>,
    /// Its deepest level.
    pub(super) max_level: u32,
}

impl Tree {
    fn nvars(&self) -> usize {
        match self.kind {
            TreeKind::Side { .. } => 1,
            _ => 2,
        }
    }

    /// Makes a node on a box, or `None` if the box holds nothing of the outline.
    fn node(
        &self,
        scene_image: &IntervalImage,
        lo: [f64; 2],
        hi: [f64; 2],
        level: u32,
    ) -> Option<Node> {
        let k = self.nvars();
        let image = match &self.kind {
            TreeKind::Contour { g } => {
                if !may_vanish(g, &lo[..k], &hi[..k]) {
                    return None;
                }
                scene_image
            }
            TreeKind::Side { image, fold, .. } => {
                // The two sheets on opposite sides of the edge's image: not outline.
                if fold.as_ref().is_some_and(|o| continues_on(o, lo[0], hi[0])) {
                    return None;
                }
                image
            }
            TreeKind::Region => scene_image,
        };
        Some(Node {
            lo,
            hi,
            level,
            bounds: image.bounds(&lo[..k], &hi[..k]).unwrap_or(UNBOUNDED),
            children: OnceLock::new(),
        })
    }

    /// The children of a node (halves of an interval, quarters of a box) that hold outline.
    pub(super) fn children<'a>(&self, images: &[IntervalImage], n: &'a Node) -> &'a [Node] {
        if n.level >= self.max_level {
            return &[];
        }
        n.children.get_or_init(|| {
            let im = &images[self.patch];
            let mid = [0.5 * (n.lo[0] + n.hi[0]), 0.5 * (n.lo[1] + n.hi[1])];
            let mut out = Vec::new();
            if self.nvars() == 1 {
                for (a, b) in [(n.lo[0], mid[0]), (mid[0], n.hi[0])] {
                    out.extend(self.node(im, [a, 0.0], [b, 0.0], n.level + 1));
                }
            } else {
                for (a0, b0) in [(n.lo[0], mid[0]), (mid[0], n.hi[0])] {
                    for (a1, b1) in [(n.lo[1], mid[1]), (mid[1], n.hi[1])] {
                        out.extend(self.node(im, [a0, a1], [b0, b1], n.level + 1));
                    }
                }
            }
            out
        })
    }
}

/// The outline trees of a scene, with the patches' interval images (indexed by patch).
#[derive(Debug)]
pub(super) struct Outline {
    pub(super) images: Vec<IntervalImage>,
    pub(super) contours: Vec<Tree>,
    pub(super) sides: Vec<Tree>,
    pub(super) regions: Vec<Tree>,
}

impl Outline {
    /// The trees of a scene; `gs` are the patches' silhouette functions.
    /// Without `clusters` no stretch of an edge is pruned.
    pub(super) fn new(scene: &Scene, gs: &[IPoly], max_level: u32, clusters: bool) -> Outline {
        let images: Vec<IntervalImage> = scene.images.iter().map(IntervalImage::new).collect();
        let whole = ([0.0, 0.0], [1.0, 1.0]);
        let mk = |patch: usize, kind: TreeKind, hi: [f64; 2], images: &[IntervalImage]| {
            let mut t = Tree {
                patch,
                kind,
                root: None,
                max_level,
            };
            t.root = t.node(&images[patch], whole.0, hi, 0);
            t
        };
        let contours = gs
            .iter()
            .enumerate()
            .map(|(i, g)| mk(i, TreeKind::Contour { g: g.clone() }, whole.1, &images))
            .collect();
        let regions = (0..gs.len())
            .map(|i| mk(i, TreeKind::Region, whole.1, &images))
            .collect();
        let sides = scene
            .adjacency
            .edges
            .iter()
            .map(|us| {
                let first = us[0];
                let users: Vec<(usize, Edge, bool)> = us
                    .iter()
                    .map(|u| (u.patch, u.edge, u.reversed != first.reversed))
                    .collect();
                let kind = TreeKind::Side {
                    edge: first.edge,
                    image: Box::new(IntervalImage::new(
                        &scene.images[first.patch].on_side(first.edge),
                    )),
                    fold: if clusters {
                        edge_orientations(scene, &users)
                    } else {
                        None
                    },
                    users,
                };
                mk(first.patch, kind, [1.0, 0.0], &images)
            })
            .collect();
        Outline {
            images,
            contours,
            sides,
            regions,
        }
    }
}
