//! The cells of one patch's parameter square: a quadtree whose leaves are either **quiet**
//! (no point of the outline can lie in front of any of their points, no other patch passes
//! through them, no contour of their own inside: their QI is constant, and constant across
//! quiet neighbours, `proofs/visible-regions.md`, claim 1) or blocked by what may be in front.

use crate::analysis::visibility::scene::{ImageBounds, Scene};
use crate::analysis::visibility::sheets::{outline_direction, FoldPolys};
use crate::analysis::visibility::visible::injective::JacobianGrid;
use crate::analysis::visibility::visible::outline::{
    quarters, IntervalImage, Node, Outline, Tree, TreeKind,
};
use crate::analysis::visibility::visible::VisibleOptions;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::Interval;
use crate::number::{Precision, Rational, Sign};
use crate::reason::Reason;
use std::cell::OnceCell;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

type IPoly = Bernstein<Interval>;

/// A leaf of the quadtree, at `level`, with integer position `(i, j)` at that level.
#[derive(Clone, Debug)]
pub(super) struct Leaf {
    pub(super) level: u32,
    pub(super) i: u32,
    pub(super) j: u32,
    /// `None`: quiet; otherwise why not.
    pub(super) blocked: Option<Reason>,
}

impl Leaf {
    pub(super) fn lo(&self) -> [f64; 2] {
        let s = 0.5f64.powi(self.level as i32);
        [self.i as f64 * s, self.j as f64 * s]
    }
    pub(super) fn hi(&self) -> [f64; 2] {
        let s = 0.5f64.powi(self.level as i32);
        [(self.i + 1) as f64 * s, (self.j + 1) as f64 * s]
    }
}

/// What one patch's search needs.
pub(super) struct Context<'a> {
    pub(super) scene: &'a Scene,
    pub(super) outline: &'a Outline,
    /// Per patch, the silhouette function in f64 intervals.
    pub(super) gs: &'a [IPoly],
    /// Per patch, its injective boxes (computed when first needed).
    pub(super) injective: &'a [OnceLock<JacobianGrid>],
    /// Per patch, which grid blocks the fold lemma holds on (filled when first asked).
    pub(super) folds: &'a [FoldBlocks],
    pub(super) opts: &'a VisibleOptions,
}

type Cand<'a> = (&'a Tree, &'a Node);

/// Per patch: per grid block `(level, i, j)`, whether the fold lemma holds on it; and the fold
/// polynomials per quantized outline direction (one of [`DIRECTIONS`] over a half turn).
#[derive(Default)]
pub(super) struct FoldBlocks {
    blocks: Mutex<HashMap<(u32, u32, u32), bool>>,
    polys: Mutex<HashMap<u32, Option<Arc<FoldPolys>>>>,
}

/// Outline directions are quantized to this many per half turn, so that each patch builds few
/// fold polynomials (the lemma holds for whatever rotation is used; a close one makes it
/// succeed).
const DIRECTIONS: u32 = 32;

/// A cell's geometry.
struct CellBox {
    bounds: ImageBounds,
    size: f64,
    level: u32,
    i: u32,
    j: u32,
    /// A box around the cell, in the patch's square, on which its image map is injective
    /// (computed when first needed).
    own: OnceCell<Option<Rect>>,
}

/// Whether the box `[lo, hi]` (a node's) lies in `b`.
fn within(lo: [f64; 2], hi: [f64; 2], b: &Rect) -> bool {
    b.contains(&Rect::new(lo, hi))
}

/// The leaves of patch `p`'s quadtree.
pub(super) fn patch_leaves(ctx: &Context, p: usize) -> Vec<Leaf> {
    let o = ctx.outline;
    let mut cands: Vec<Cand> = Vec::new();
    for t in o.contours.iter().chain(&o.sides) {
        if let Some(r) = &t.root {
            cands.push((t, r));
        }
    }
    for t in &o.regions {
        if t.patch != p && !ctx.scene.adjacent(p, t.patch) {
            if let Some(r) = &t.root {
                cands.push((t, r));
            }
        }
    }
    let mut out = Vec::new();
    let polys = CellPolys {
        g: ctx.gs[p].clone(),
        image: o.images[p].clone(),
    };
    visit(ctx, p, 0, 0, 0, &polys, cands, &mut out);
    out
}

/// A cell's polynomials, restricted to it by midpoint subdivision.
struct CellPolys {
    /// The silhouette function.
    g: IPoly,
    /// The image and depth.
    image: IntervalImage,
}

#[allow(clippy::too_many_arguments)]
fn visit<'a>(
    ctx: &Context<'a>,
    p: usize,
    level: u32,
    i: u32,
    j: u32,
    polys: &CellPolys,
    cands: Vec<Cand<'a>>,
    out: &mut Vec<Leaf>,
) {
    let leaf = |blocked: Option<Reason>| Leaf {
        level,
        i,
        j,
        blocked,
    };
    if ctx.opts.curve.past_deadline() {
        out.push(leaf(Some(Reason::TimeLimit)));
        return;
    }
    let split = level < ctx.opts.max_depth;
    let recurse = |cands: Vec<Cand<'a>>, out: &mut Vec<Leaf>| {
        let gq = quarters(&polys.g);
        let iq = polys.image.quarters();
        for (k, (g, image)) in gq.into_iter().zip(iq).enumerate() {
            let (di, dj) = ((k % 2) as u32, (k / 2) as u32);
            let child = CellPolys { g, image };
            visit(
                ctx,
                p,
                level + 1,
                2 * i + di,
                2 * j + dj,
                &child,
                cands.clone(),
                out,
            );
        }
    };
    // Its own contour inside: split (the QI changes across it).
    if !matches!(polys.g.range_sign(), Sign::Positive | Sign::Negative) {
        if split {
            recurse(cands, out);
        } else {
            out.push(leaf(Some(Reason::OwnSilhouette)));
        }
        return;
    }
    let Some(bounds) = polys.image.whole_bounds() else {
        if split {
            recurse(cands, out);
        } else {
            out.push(leaf(Some(Reason::ImageUnbounded)));
        }
        return;
    };
    let size = (bounds.x[1] - bounds.x[0]).max(bounds.y[1] - bounds.y[0]);
    let cb = CellBox {
        bounds,
        size,
        level,
        i,
        j,
        own: OnceCell::new(),
    };
    let blockers = blockers(ctx, p, &cb, cands);
    match blockers.first() {
        None => out.push(leaf(None)),
        Some(b) if !split => {
            let why = reason(b.0);
            out.push(leaf(Some(why)));
        }
        Some(_) => recurse(blockers, out),
    }
}

/// Why a node blocks a cell.
fn reason(t: &Tree) -> Reason {
    let patch = t.patch;
    match &t.kind {
        TreeKind::Contour { .. } => Reason::SilhouetteInFront { patch },
        TreeKind::Side { edge, .. } => Reason::BoundaryInFront { patch, edge: *edge },
        TreeKind::Region => Reason::PatchThrough { patch },
    }
}

/// The patch's grid of Jacobian ranges (at level 5 at most: `injective.rs`).
fn jacobian_grid<'a>(ctx: &Context<'a>, p: usize) -> &'a JacobianGrid {
    ctx.injective[p].get_or_init(|| {
        let m = &ctx.scene.jacobians[p];
        let c = |x: &Bernstein<Rational>| x.convert(Precision::F64);
        JacobianGrid::new(
            &[c(&m[0][0]), c(&m[0][1]), c(&m[1][0]), c(&m[1][1])],
            ctx.opts.max_depth.min(5),
        )
    })
}

/// Whether a node lies on the cell's own patch inside the box where its image map is
/// injective: then none of its points is strictly in front of a point of the cell.
fn own_excluded(ctx: &Context, p: usize, cell: &CellBox, t: &Tree, n: &Node) -> bool {
    let mine = match &t.kind {
        TreeKind::Contour { .. } => t.patch == p,
        TreeKind::Side { users, .. } => users.iter().any(|u| u.0 == p),
        TreeKind::Region => false,
    };
    if !mine {
        return false;
    }
    let own = cell
        .own
        .get_or_init(|| jacobian_grid(ctx, p).around(cell.level, cell.i, cell.j));
    if matches!(t.kind, TreeKind::Contour { .. })
        && !own.as_ref().is_some_and(|o| within(n.lo, n.hi, o))
    {
        return in_fold_block(ctx, p, cell, n);
    }
    let Some(own) = own else {
        return false;
    };
    match &t.kind {
        TreeKind::Contour { .. } => t.patch == p && within(n.lo, n.hi, own),
        TreeKind::Side { users, .. } => users.iter().any(|&(q, e, rev)| {
            if q != p {
                return false;
            }
            let (a, b) = if rev {
                (1.0 - n.hi[0], 1.0 - n.lo[0])
            } else {
                (n.lo[0], n.hi[0])
            };
            own.contains(&side_box(e, a, b))
        }),
        TreeKind::Region => false,
    }
}

/// Whether the cell and a node of its own contour lie in one block of grid boxes (the 3×3
/// boxes around the cell's ancestor at levels 7 down to 2, the smallest that holds the node
/// first) on which the fold lemma holds
/// (`proofs/ray-count.md`): then no contour point of the node has the image of a point of
/// the cell (its fibre in the block is itself, and the cell's points are not on the contour).
fn in_fold_block(ctx: &Context, p: usize, cell: &CellBox, n: &Node) -> bool {
    for level in (2..=cell.level.min(7)).rev() {
        let s = cell.level - level;
        let (a, b) = (cell.i >> s, cell.j >> s);
        let last = (1u32 << level) - 1;
        let unit = 0.5f64.powi(level as i32);
        let (a0, a1) = (a.saturating_sub(1), (a + 1).min(last));
        let (b0, b1) = (b.saturating_sub(1), (b + 1).min(last));
        let block = Rect::new(
            [a0 as f64 * unit, b0 as f64 * unit],
            [(a1 + 1) as f64 * unit, (b1 + 1) as f64 * unit],
        );
        if !within(n.lo, n.hi, &block) {
            continue;
        }
        let key = (level, a, b);
        let folds = &ctx.folds[p];
        let known = folds
            .blocks
            .lock()
            .expect("no poisoning")
            .get(&key)
            .copied();
        let holds = known.unwrap_or_else(|| {
            let mid = [
                dyadic_rational(a0 + a1 + 1, level + 1),
                dyadic_rational(b0 + b1 + 1, level + 1),
            ];
            let h =
                fold_polys(ctx, p, &mid).is_some_and(|f| f.holds_within(&block.lo, &block.hi, 2));
            folds.blocks.lock().expect("no poisoning").insert(key, h);
            h
        });
        if holds {
            return true;
        }
    }
    false
}

/// The fold polynomials of patch `p` for the outline direction near `mid`, quantized.
fn fold_polys(ctx: &Context, p: usize, mid: &[Rational]) -> Option<Arc<FoldPolys>> {
    let t = outline_direction(ctx.scene, p, mid)?;
    let half_turn = std::f64::consts::PI;
    let angle = t[1].atan2(t[0]).rem_euclid(half_turn);
    let bin = ((angle / half_turn * DIRECTIONS as f64).round() as u32) % DIRECTIONS;
    let folds = &ctx.folds[p];
    if let Some(f) = folds.polys.lock().expect("no poisoning").get(&bin) {
        return f.clone();
    }
    let a = bin as f64 * half_turn / DIRECTIONS as f64;
    let f = FoldPolys::along(ctx.scene, p, [a.cos(), a.sin()]).map(Arc::new);
    folds
        .polys
        .lock()
        .expect("no poisoning")
        .insert(bin, f.clone());
    f
}

/// `num / 2^shift` as a rational.
fn dyadic_rational(num: u32, shift: u32) -> Rational {
    let mut r = Rational::from(num);
    r >>= shift;
    r
}

/// The parameter box of a side's stretch `[a, b]`.
fn side_box(e: crate::surface::Edge, a: f64, b: f64) -> Rect {
    use crate::surface::Edge;
    match e {
        Edge::V0 => Rect::new([a, 0.0], [b, 0.0]),
        Edge::V1 => Rect::new([a, 1.0], [b, 1.0]),
        Edge::U0 => Rect::new([0.0, a], [0.0, b]),
        Edge::U1 => Rect::new([1.0, a], [1.0, b]),
    }
}

/// The candidates that may still change the cell's QI, refined to about the cell's size.
fn blockers<'a>(
    ctx: &Context<'a>,
    p: usize,
    cell: &CellBox,
    cands: Vec<Cand<'a>>,
) -> Vec<Cand<'a>> {
    let b = &cell.bounds;
    let mut stack = cands;
    let mut out = Vec::new();
    while let Some((t, n)) = stack.pop() {
        let nb = &n.bounds;
        if !nb.meets_image(b) {
            continue;
        }
        match t.kind {
            TreeKind::Region => {
                if nb.depth[0] > b.depth[1] || b.depth[0] > nb.depth[1] {
                    continue;
                }
            }
            _ => {
                // Behind (or level with) every point of the cell: not strictly in front.
                if nb.depth[0] >= b.depth[1] {
                    continue;
                }
                if own_excluded(ctx, p, cell, t, n) {
                    continue;
                }
            }
        }
        if n.level < t.max_level && n.image_size() > 0.5 * cell.size {
            for c in t.children(&ctx.outline.images, n) {
                stack.push((t, c));
            }
            continue;
        }
        out.push((t, n));
    }
    out
}

/// Leaves by position, for neighbour queries.
pub(super) struct LeafIndex {
    /// The deepest level (the unit grid).
    pub(super) depth: u32,
    map: HashMap<(u32, u32, u32), usize>,
    pos: Vec<(u32, u32, u32)>,
}

impl LeafIndex {
    pub(super) fn new(leaves: &[Leaf], depth: u32) -> LeafIndex {
        let pos: Vec<(u32, u32, u32)> = leaves.iter().map(|l| (l.level, l.i, l.j)).collect();
        let map = pos.iter().enumerate().map(|(k, x)| (*x, k)).collect();
        LeafIndex { depth, map, pos }
    }

    /// The leaf holding the unit cell `(x, y)` of the finest grid.
    pub(super) fn locate(&self, x: i64, y: i64) -> Option<usize> {
        let n = 1i64 << self.depth;
        if x < 0 || y < 0 || x >= n || y >= n {
            return None;
        }
        (0..=self.depth).find_map(|lev| {
            let s = self.depth - lev;
            self.map
                .get(&(lev, (x >> s) as u32, (y >> s) as u32))
                .copied()
        })
    }

    /// A leaf's extent on the unit grid: `(x0, y0, size)`.
    pub(super) fn extent(&self, k: usize) -> (i64, i64, i64) {
        let (level, i, j) = self.pos[k];
        let s = 1i64 << (self.depth - level);
        (i as i64 * s, j as i64 * s, s)
    }

    /// The neighbours across one side of a leaf (0: bottom, 1: right, 2: top, 3: left), each
    /// with the stretch `[a, b)` of the side it covers (unit coordinates along the side's
    /// axis, increasing); `None` beyond the square.
    pub(super) fn across(&self, k: usize, side: usize) -> Vec<(Option<usize>, i64, i64)> {
        let (x0, y0, s) = self.extent(k);
        let mut out = Vec::new();
        let mut a = if side % 2 == 0 { x0 } else { y0 };
        let end = a + s;
        while a < end {
            let (x, y) = match side {
                0 => (a, y0 - 1),
                1 => (x0 + s, a),
                2 => (a, y0 + s),
                _ => (x0 - 1, a),
            };
            let k = self.locate(x, y);
            let b = match k {
                None => end,
                Some(k) => {
                    let (nx, ny, ns) = self.extent(k);
                    let start = if side % 2 == 0 { nx } else { ny };
                    (start + ns).min(end)
                }
            };
            out.push((k, a, b));
            a = b;
        }
        out
    }
}
