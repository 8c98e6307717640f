//! Certified visible regions of the patches of a model (paper 000, section 5): for each
//! patch, the parameter cells proven visible, proven hidden (with their QI), and unresolved,
//! the loops bounding the proven-visible region and the possibly-visible region, and bounds on
//! the visible fraction of its parameter square and of its surface area.
//!
//! The QI of a point of a patch (the number of surface layers strictly in front of it) can
//! change only where, seen along its ray, some outline point lies in front of it: a contour
//! point, or a point of a patch boundary across which the surface does not continue in the
//! image; or where another surface passes through it; or across its own contour.
//! So each patch's square is subdivided (a quadtree, to `max_depth`) until a cell is
//! **quiet**: its silhouette function has a strict sign on it, and every box of the outline
//! trees (`outline`) is proven behind it or apart from it in the image, except its own
//! boundary near it where its image map is injective, and every patch that shares no corner
//! with it is apart from it in space. The QI is constant on every connected union of quiet
//! cells (`proofs/visible-regions.md`, claim 1), so one certified ray test
//! ([`crate::analysis::visibility::ray::layers_in_front`]) per connected quiet region decides all its cells.
//! Cells never made quiet are unresolved, with the reason. The visible region's true boundary
//! (silhouette, boundary and occlusion curves) lies in the unresolved cells: the loops of the
//! proven-visible cells and of the not-proven-hidden cells enclose it from inside and outside.
//!
//! [`visible_regions`] is a forward pipeline: `outline.rs` (the outline trees of every patch:
//! contour and side boxes, with their image and depth bounds) → `cells.rs` (each patch's
//! quadtree down to quiet or unresolved leaves, each blocked leaf with its [`crate::Reason`])
//! → `patch_region` here (quiet leaves joined into regions, one ray test per region, the
//! loops of `loops.rs`, the area bounds of `area.rs`) → with trimming, `trimming.rs` (the
//! hidden-line drawing's visible outline lifted by `occlusion/` onto the surface behind).
//!
//! With [`VisibleOptions::trimming`] that boundary is also drawn, from a certified hidden-line
//! drawing: each patch's visible silhouette and side pieces, and the occlusion curves of the
//! visible outline in front of it, lifted onto it ([`TrimCurve`], `proofs/visible-regions.md`,
//! claim 4), each with a proven distance bound with a tolerance, chained into loops.

mod area;
mod cells;
mod injective;
mod loops;
mod occlusion;
mod outline;
mod trimming;

pub use trimming::{chain_loops, MissingOcclusion, TrimCurve, TrimKind, TrimLoop};

use crate::analysis::contour::silhouette::silhouette_function;
use crate::analysis::frame::Frame;
use crate::analysis::view::View;
use crate::analysis::visibility::facing::{facing, Facing};
use crate::analysis::visibility::hlr::{hidden_lines, HlrOptions, ADJACENT_ASSUMPTION};
use crate::analysis::visibility::ray::{layers_in_front, RayOptions, Sample};
use crate::analysis::visibility::scene::Scene;
use crate::error::Error;
use crate::model::{Model, WeldTolerance};
use crate::number::margin;
use crate::number::{Precision, Rational};
use crate::reason::Reason;
use crate::solver::precision::{Escalations, Policy};
use crate::solver::CurveOptions;
use crate::surface::DrawPatch;
use cells::{patch_leaves, Context, Leaf, LeafIndex};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Budgets and resolution.
#[derive(Clone, Debug)]
pub struct VisibleOptions {
    /// Only its deadline is used (what has not been decided by then is unresolved).
    pub curve: CurveOptions,
    /// The ray tests' budgets.
    pub ray: RayOptions,
    /// The deepest cell level (cells of side 2^-max_depth).
    pub max_depth: u32,
    /// The deepest level of the outline trees.
    pub outline_depth: u32,
    /// The base grid level of the area bounds (split further, up to 4 more levels, where a
    /// grid box's bounds leave more than `area_tolerance` of its share of the patch's area
    /// undecided).
    pub area_level: u32,
    /// See `area_level`.
    pub area_tolerance: f64,
    /// Ray tests tried per quiet region before it is left unresolved.
    pub samples: usize,
    /// Clusters: stretches of shared edges across which the surface provably continues in
    /// the image are not outline ([`crate::analysis::visibility::fold_edges`]). Off: every edge is outline (for
    /// measuring what clusters save).
    pub clusters: bool,
    /// Find the trimming curves of the visible regions (silhouette, boundary and occlusion
    /// curves) from a certified hidden-line drawing.
    pub trimming: bool,
    /// The tolerance in model units within which the trimming curves are drawn (`None`:
    /// drawn, not bounded).
    pub tol: Option<f64>,
    /// How patch boundaries are matched into shared edges; `None`: the model's default
    /// ([`crate::model::default_weld`]).
    pub weld: Option<WeldTolerance>,
}

impl VisibleOptions {
    /// These options with shared edges matched by `weld`.
    pub fn with_weld(mut self, weld: WeldTolerance) -> VisibleOptions {
        self.weld = Some(weld);
        self
    }
}

impl Default for VisibleOptions {
    fn default() -> Self {
        VisibleOptions {
            curve: CurveOptions::default(),
            ray: RayOptions::default(),
            max_depth: 8,
            outline_depth: 12,
            area_level: 4,
            area_tolerance: 0.01,
            samples: 6,
            clusters: true,
            trimming: true,
            tol: None,
            weld: None,
        }
    }
}

/// A leaf cell of a patch's square.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Cell {
    /// Lower corner (u, v) (dyadic, exact).
    pub lo: [f64; 2],
    /// Upper corner.
    pub hi: [f64; 2],
    /// The proven QI of every point of the cell off the patch boundary (0: visible), or
    /// `None`.
    pub qi: Option<usize>,
    /// Why the QI is not proven.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Reason>,
}

/// A closed loop in a patch's square (first point not repeated), with the same points in
/// space.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Loop {
    /// Vertices (u, v): a polygon of cell sides (the straight sides are sampled every 1/16).
    pub uv: Vec<[f64; 2]>,
    /// The points in space (f64 evaluation, for drawing).
    pub xyz: Vec<[f64; 3]>,
    /// Whether it bounds a hole (clockwise) rather than an outer boundary (counter-clockwise).
    pub hole: bool,
}

/// Unresolved cells grouped by reason.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct UnresolvedArea {
    /// Why.
    pub reason: Reason,
    /// How many cells.
    pub cells: usize,
    /// Their share of the parameter square.
    pub domain_fraction: f64,
}

/// The visible region of one patch.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PatchRegion {
    /// The patch.
    pub patch: usize,
    /// Its self-visible type.
    pub facing: Facing,
    /// Every cell's QI is proven.
    pub certified: bool,
    /// Bounds on the visible share of the parameter square.
    pub domain_fraction: [f64; 2],
    /// Bounds on the visible share of the surface area.
    pub area_fraction: [f64; 2],
    /// Bounds on the surface area.
    pub area: [f64; 2],
    /// Bounds on the visible surface area (the proven-visible cells, and the unresolved ones
    /// for the upper bound).
    pub visible_area: [f64; 2],
    /// The loops bounding the cells proven visible (inside the true visible region).
    pub visible_loops: Vec<Loop>,
    /// The loops bounding the cells not proven hidden (around the true visible region).
    pub possibly_visible_loops: Vec<Loop>,
    /// Cells proven visible, hidden, unresolved.
    pub counts: [usize; 3],
    /// The unresolved cells, by reason.
    pub unresolved: Vec<UnresolvedArea>,
    /// The leaf cells (the certificate of the result).
    pub cells: Vec<Cell>,
    /// The curves bounding the visible region: its own visible silhouette and sides, and the
    /// occlusion curves of the visible outline in front of it.
    pub trimming: Vec<TrimCurve>,
    /// The trimming curves chained end to end.
    pub trim_loops: Vec<TrimLoop>,
}

/// Counts of the work done.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct VisibleStats {
    /// Leaf cells.
    pub cells: usize,
    /// Connected quiet regions (one ray test decides each).
    pub quiet_regions: usize,
    /// Ray tests run.
    pub ray_tests: usize,
    /// Ray tests refused (another point was tried).
    pub refused_ray_tests: usize,
    /// Trimming curves, and those certified.
    pub trim_curves: usize,
    /// See `trim_curves`.
    pub certified_trim_curves: usize,
    /// Trimming loops, and those that close.
    pub trim_loops: usize,
    /// See `trim_loops`.
    pub closed_trim_loops: usize,
    /// The precision that settled each sign decided through the ladder (the patches' types;
    /// the hidden-line drawing's, with trimming curves).
    pub escalations: Escalations,
}

/// The visible regions of a model in a view.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct VisibleRegions {
    /// Per patch.
    pub patches: Vec<PatchRegion>,
    /// Bounds on the visible share of the whole model's surface area.
    pub area_fraction: [f64; 2],
    /// Work counts.
    pub stats: VisibleStats,
    /// What the result assumes without proof.
    pub assumptions: Vec<String>,
    /// Visible outline pieces whose occlusion curve on the surface behind was not found.
    pub missing_occlusions: Vec<MissingOcclusion>,
    /// Pairs of patches proven to intersect: their intersection curve bounds visible regions
    /// too, and is not among the trimming curves.
    pub intersecting_patches: Vec<[usize; 2]>,
}

impl VisibleRegions {
    /// Whether every cell of every patch is decided.
    pub fn is_certified(&self) -> bool {
        self.patches.iter().all(|p| p.certified)
    }

    /// The regions of the model in `frame` carried back to the model's coordinates
    /// (`proofs/model-frame.md`): points in space moved by the origin, the trimming curves'
    /// error bounds grown by the rounding that adds (a curve past `tol` then, only for a
    /// model some 2⁵⁰ times the tolerance from the origin, no longer certified, with its
    /// reason); parameters, cells and areas are unchanged by a translation.
    pub(crate) fn in_model_frame(mut self, frame: &Frame, tol: Option<f64>) -> VisibleRegions {
        if frame.is_identity() {
            return self;
        }
        for p in &mut self.patches {
            for l in p
                .visible_loops
                .iter_mut()
                .chain(&mut p.possibly_visible_loops)
            {
                frame.points(&mut l.xyz);
            }
            for c in &mut p.trimming {
                if !frame.drawing(&mut c.xyz, &mut c.error_bound, tol) {
                    c.error_bound = None;
                    c.certified = false;
                    c.reason.get_or_insert(Reason::RoundingPastTolerance);
                }
            }
        }
        self
    }
}

/// The visible regions of a model's patches in a view.
///
/// # Errors
/// [`Error::View`] as [`crate::analysis::projection::Projection::new`].
///
/// # Examples
/// ```
/// use limn::analysis::visibility::visible::{visible_regions, VisibleOptions};
/// use limn::analysis::view::View;
/// use limn::model::{Format, Model, WeldTolerance};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let model = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
/// let view = View::Direction([1, 2, 3].map(Rational::from));
/// let mut opts = VisibleOptions::default().with_weld(WeldTolerance::Exact);
/// opts.max_depth = 5;
/// let r = visible_regions(&model, &view, &opts)?;
/// // Half of a sphere's area faces any parallel view.
/// let [lo, hi] = r.area_fraction;
/// assert!(lo <= 0.5 && 0.5 <= hi && hi - lo < 0.5);
/// # Ok::<(), limn::Error>(())
/// ```
pub fn visible_regions(
    model: &Model,
    view: &View,
    opts: &VisibleOptions,
) -> Result<VisibleRegions, Error> {
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    let r = regions(&frame.model(model), &frame.view(view), opts)?;
    Ok(r.in_model_frame(&frame, opts.tol))
}

/// [`visible_regions`] of the model as it is given.
fn regions(model: &Model, view: &View, opts: &VisibleOptions) -> Result<VisibleRegions, Error> {
    let weld = opts
        .weld
        .unwrap_or_else(|| crate::model::default_weld(model));
    let scene = Scene::new(model, view, weld)?;
    let gs: Vec<_> = model
        .patches
        .par_iter()
        .map(|p| silhouette_function(&p.surface, view).convert(Precision::F64))
        .collect();
    // Computed when a patch first needs one.
    let injective: Vec<std::sync::OnceLock<injective::JacobianGrid>> = (0..model.patches.len())
        .map(|_| std::sync::OnceLock::new())
        .collect();
    let folds: Vec<cells::FoldBlocks> = (0..model.patches.len())
        .map(|_| cells::FoldBlocks::default())
        .collect();
    let outline = outline::Outline::new(&scene, &gs, opts.outline_depth, opts.clusters);
    let ctx = Context {
        scene: &scene,
        outline: &outline,
        gs: &gs,
        injective: &injective,
        folds: &folds,
        opts,
    };
    let per_patch: Vec<(PatchRegion, VisibleStats, [[f64; 2]; 3])> = (0..model.patches.len())
        .into_par_iter()
        .map(|p| patch_region(&ctx, model, view, p))
        .collect();
    let mut stats = VisibleStats::default();
    let mut sums = [[0.0; 2]; 3];
    let mut patches = Vec::new();
    for (r, s, a) in per_patch {
        stats.cells += s.cells;
        stats.quiet_regions += s.quiet_regions;
        stats.ray_tests += s.ray_tests;
        stats.refused_ray_tests += s.refused_ray_tests;
        stats.escalations.merge(&s.escalations);
        for k in 0..3 {
            sums[k][0] += a[k][0];
            sums[k][1] += a[k][1];
        }
        patches.push(r);
    }
    let mut assumptions = vec![ADJACENT_ASSUMPTION.to_string()];
    assumptions.extend(scene.contact_assumption());
    if let WeldTolerance::Absolute(d) = weld {
        assumptions.push(crate::analysis::visibility::hlr::weld_assumption(d));
    }
    assumptions.extend(model.reader_assumptions());
    let mut missing_occlusions = Vec::new();
    let mut intersecting_patches = Vec::new();
    if opts.trimming {
        let hopts = HlrOptions {
            curve: opts.curve.clone(),
            ray: opts.ray.clone(),
            // The lifts magnify the pieces' drawing error (`proofs/visible-regions.md`,
            // claim 4): the pieces are drawn to a fraction of the tolerance.
            tol: opts.tol.map(|t| t / OCCLUDER_TOL_DIVISOR),
            clusters: opts.clusters,
            behind: true,
            weld: Some(weld),
            // The regions are of whole surfaces still: so are their occluders.
            trims: false,
            // The visible regions are not yet bounded by intersection curves.
            intersections: false,
            ..HlrOptions::default()
        };
        let h = hidden_lines(model, view, &hopts)?;
        let t = trimming::trimming_curves(model, &scene, &h, &opts.ray, opts.tol);
        missing_occlusions = t.missing;
        intersecting_patches = h.intersecting_patches.clone();
        for (region, curves) in patches.iter_mut().zip(t.curves) {
            region.trim_loops = chain_loops(&curves, TRIM_GAP);
            region.trimming = curves;
            stats.trim_curves += region.trimming.len();
            stats.certified_trim_curves += region.trimming.iter().filter(|c| c.certified).count();
            stats.trim_loops += region.trim_loops.len();
            stats.closed_trim_loops += region.trim_loops.iter().filter(|l| l.closed).count();
        }
    }
    let area_fraction = fraction_bounds(sums, stats.cells + patches.len());
    Ok(VisibleRegions {
        patches,
        area_fraction,
        stats,
        assumptions,
        missing_occlusions,
        intersecting_patches,
    })
}

/// The hidden-line pieces behind the trimming curves are drawn to the tolerance divided by
/// this.
pub const OCCLUDER_TOL_DIVISOR: f64 = 32.0;

/// The largest gap in (u, v) between two trimming curves' ends chained into one loop.
pub const TRIM_GAP: f64 = 1e-6;

/// Bounds on `V / (V + H + U)` (with the unresolved part `U` anywhere between) from bounds on
/// the visible, hidden and unresolved parts: `x / (x + y)` grows with `x` and falls with `y`.
/// The parts are sums of `terms` nonnegative bounds; the quotient's relative rounding is at
/// most that of its two operands' sums and three more operations, covered by the margin
/// (`proofs/rounding-margins.md`, the count-dependent margin).
fn fraction_bounds([v, h, u]: [[f64; 2]; 3], terms: usize) -> [f64; 2] {
    let f = |x: f64, y: f64| if x + y > 0.0 { x / (x + y) } else { 0.0 };
    let m = margin::covering(2 * terms + 3, margin::MANY);
    let lo = margin::down(f(v[0], h[1] + u[1]), m);
    let hi = margin::up(f(v[1] + u[1], h[0]), m);
    [lo.max(0.0), hi.min(1.0)]
}

/// `num / 2^shift` as a rational.
fn dyadic(num: u64, shift: u32) -> Rational {
    let mut r = Rational::from(num);
    r >>= shift;
    r
}

/// Points tried in a leaf: its centre, then points off its diagonals (dyadic, at sixteenths
/// of the leaf, away from the symmetric positions where rays tend to graze patch edges).
fn sample_points(l: &Leaf) -> Vec<[Rational; 2]> {
    let (i, j) = (l.i as u64, l.j as u64);
    [(8, 8), (5, 11), (11, 5), (3, 7), (13, 9), (7, 13)]
        .iter()
        .map(|&(a, b)| {
            [
                dyadic(16 * i + a, l.level + 4),
                dyadic(16 * j + b, l.level + 4),
            ]
        })
        .collect()
}

/// Union-find root.
fn root(parent: &mut [usize], mut k: usize) -> usize {
    while parent[k] != k {
        parent[k] = parent[parent[k]];
        k = parent[k];
    }
    k
}

/// One patch: its leaves, their QI by quiet region, loops, fractions; with the area bounds
/// of its visible, hidden and unresolved parts.
fn patch_region(
    ctx: &Context,
    model: &Model,
    view: &View,
    p: usize,
) -> (PatchRegion, VisibleStats, [[f64; 2]; 3]) {
    let opts = ctx.opts;
    let leaves = patch_leaves(ctx, p);
    let index = LeafIndex::new(&leaves, opts.max_depth);
    let n = leaves.len();
    // Quiet regions: quiet leaves joined across shared sides.
    let mut parent: Vec<usize> = (0..n).collect();
    for k in 0..n {
        if leaves[k].blocked.is_some() {
            continue;
        }
        for side in [1, 2] {
            for (m, _, _) in index.across(k, side) {
                if let Some(m) = m.filter(|m| leaves[*m].blocked.is_none()) {
                    let (a, b) = (root(&mut parent, k), root(&mut parent, m));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut regions: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (k, leaf) in leaves.iter().enumerate() {
        if leaf.blocked.is_none() {
            let r = root(&mut parent, k);
            regions.entry(r).or_default().push(k);
        }
    }
    let mut stats = VisibleStats {
        cells: n,
        quiet_regions: regions.len(),
        ..VisibleStats::default()
    };
    // Every quiet leaf is in a region, whose ray tests set its QI below.
    let mut qi: Vec<Result<usize, Reason>> = leaves
        .iter()
        .map(|l| Err(l.blocked.clone().unwrap_or(Reason::NoRayTest)))
        .collect();
    for members in regions.values() {
        // The coarsest leaves first: their centres lie farthest from the region's edge.
        let mut order = members.clone();
        order.sort_by_key(|&k| (leaves[k].level, k));
        let mut result = Err(Reason::NoRayTest);
        let mut tries = 0;
        'tries: for &k in &order {
            for uv in sample_points(&leaves[k]) {
                if tries >= opts.samples {
                    break 'tries;
                }
                if opts.curve.past_deadline() {
                    result = Err(Reason::TimeLimit);
                    break 'tries;
                }
                tries += 1;
                stats.ray_tests += 1;
                match layers_in_front(ctx.scene, &Sample::Exact { patch: p, uv }, &opts.ray) {
                    Ok(c) => {
                        result = Ok(c);
                        break 'tries;
                    }
                    Err(e) => {
                        stats.refused_ray_tests += 1;
                        result = Err(Reason::RayTestsFailed(Box::new(e)));
                    }
                }
            }
        }
        for &k in members {
            qi[k] = result.clone();
        }
    }

    // Cells, counts, fractions.
    // Past the deadline, the base grid only (looser bounds, still bounds).
    let finer = if opts.curve.past_deadline() { 0 } else { 4 };
    let area = area::AreaElement::new(
        &model.patches[p].surface,
        opts.area_level,
        opts.area_level + finer,
        opts.area_tolerance,
    );
    let mut cells = Vec::with_capacity(n);
    let mut counts = [0usize; 3];
    let mut dom = [0.0f64; 3];
    let mut sums = [[0.0f64; 2]; 3];
    // Grouped by their sentences, in the order of the sentences.
    let mut reasons: BTreeMap<String, (Reason, usize, f64)> = BTreeMap::new();
    for (l, q) in leaves.iter().zip(&qi) {
        let kind = match q {
            Ok(0) => 0,
            Ok(_) => 1,
            Err(_) => 2,
        };
        let d = 0.25f64.powi(l.level as i32);
        counts[kind] += 1;
        dom[kind] += d;
        let a = area.area(l.level, l.i, l.j);
        sums[kind][0] += a[0];
        sums[kind][1] += a[1];
        if let Err(why) = q {
            let e = reasons
                .entry(why.to_string())
                .or_insert_with(|| (why.clone(), 0, 0.0));
            e.1 += 1;
            e.2 += d;
        }
        cells.push(Cell {
            lo: l.lo(),
            hi: l.hi(),
            qi: q.as_ref().ok().copied(),
            reason: q.as_ref().err().cloned(),
        });
    }
    let draw = DrawPatch::new(&model.patches[p].surface);
    let unit = 0.5f64.powi(opts.max_depth as i32);
    let to_loops = |member: Vec<bool>| -> Vec<Loop> {
        loops::boundary_loops(&index, &member)
            .into_iter()
            .map(|pts| {
                let hole = loops::signed_area(&pts) < 0;
                let mut uv = Vec::new();
                for k in 0..pts.len() {
                    let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                    let a = [a.0 as f64 * unit, a.1 as f64 * unit];
                    let b = [b.0 as f64 * unit, b.1 as f64 * unit];
                    let steps = (((b[0] - a[0]).abs() + (b[1] - a[1]).abs()) * 16.0)
                        .ceil()
                        .max(1.0) as usize;
                    for s in 0..steps {
                        let t = s as f64 / steps as f64;
                        uv.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
                    }
                }
                let xyz = uv.iter().map(|c| draw.eval(c[0], c[1])).collect();
                Loop { uv, xyz, hole }
            })
            .collect()
    };
    let visible_loops = to_loops(qi.iter().map(|q| *q == Ok(0)).collect());
    let possibly_visible_loops =
        to_loops(qi.iter().map(|q| !matches!(q, Ok(c) if *c > 0)).collect());
    // Sums of powers of 1/4 no finer than 4^-14: exact in f64.
    let domain_fraction = [dom[0], (dom[0] + dom[2]).min(1.0)];
    let area_margin = margin::covering(n + 3, margin::MANY);
    let region = PatchRegion {
        patch: p,
        facing: facing(
            &model.patches[p].surface,
            view,
            &mut Policy::new(&opts.curve.ladder, &mut stats.escalations),
        ),
        certified: counts[2] == 0,
        domain_fraction,
        area_fraction: fraction_bounds(sums, n),
        // Sums of the `n` cells' bounds, then of the three kinds.
        area: [
            margin::down(sums.iter().map(|s| s[0]).sum::<f64>(), area_margin),
            margin::up(sums.iter().map(|s| s[1]).sum::<f64>(), area_margin),
        ],
        visible_area: [
            margin::down(sums[0][0], area_margin),
            margin::up(sums[0][1] + sums[2][1], area_margin),
        ],
        visible_loops,
        possibly_visible_loops,
        counts,
        unresolved: reasons
            .into_iter()
            .map(|(_, (reason, cells, d))| UnresolvedArea {
                reason,
                cells,
                domain_fraction: d,
            })
            .collect(),
        cells,
        trimming: Vec::new(),
        trim_loops: Vec::new(),
    };
    (region, stats, sums)
}
