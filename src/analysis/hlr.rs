//! Certified hidden-line drawings of rational Bézier models (paper 000, extended to any model).
//!
//! The lines of the drawing are the patch boundaries (each shared edge once) and the
//! silhouette arcs of the certified silhouette ([`super::silhouette`]). Along a line the number
//! of surface layers in front of it (its QI) can change only where, in the image, it crosses
//! another line (a silhouette or a boundary: the outline of some sheet), where it crosses
//! itself, or where it passes through a patch (a penetration). So:
//!
//! 1. each line is cut into segments: sides into parameter intervals on which their image is
//!    strictly monotone in one image direction, silhouettes into the arcs of the curve
//!    solver's certified cells;
//! 2. every pair of segments whose image boxes meet is solved as a square system (the image
//!    coincidence plus each silhouette's equation, 2 to 4 unknowns) by the certified system
//!    solver; every isolated root cuts both segments there, every unresolved box marks the
//!    stretch it covers as unresolved. A segment never crosses itself (its image is monotone)
//!    and two consecutive segments of one line that are monotone in a common direction never
//!    cross (their union's image is monotone), so those pairs are skipped with that proof;
//! 3. every segment is solved against every patch that is not adjacent to its own for
//!    penetrations (the spatial coincidence), which cut it the same way;
//! 4. between cuts the QI is constant, and is found by one certified ray test
//!    ([`super::ray::layers_in_front`]) at a sample point; if a sample is refused, others are
//!    tried, and a piece with no proven sample is reported unresolved.
//!
//! What is not proven is reported: unresolved pieces (with the reason), silhouette regions the
//! curve solver did not resolve, and the assumption that adjacent patches do not cross each
//! other (penetrations are searched between non-adjacent patches only).

use super::facing::{facing, Facing};
use super::model_curves::zero_across;
use super::projection::{lift, side_point, ImagePolys};
use super::ray::{fix_axis, layers_in_front, ratio_bounds, ImageBounds, RayOptions, Sample, Scene};
use super::silhouette::{silhouette, DrawPatch, View};
use crate::bernstein::Bernstein;
use crate::model::{Model, WeldTolerance};
use crate::number::{Interval, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::Ladder;
use crate::solver::system::{solve_system, DyadicBoxN, SystemOptions, SystemRoots};
use crate::solver::univariate::{isolate_roots_in, refine_root, Root};
use crate::solver::CurveOptions;
use crate::surface::Edge;
use rayon::prelude::*;

type Poly = Bernstein<Rational>;

/// Budgets and drawing density.
#[derive(Clone, Debug)]
pub struct HlrOptions {
    /// The silhouette solver's budgets.
    pub curve: CurveOptions,
    /// The ray tests' budgets.
    pub ray: RayOptions,
    /// Budgets of each crossing or penetration system.
    pub crossing: SystemOptions,
    /// Points drawn per segment piece (at least 2).
    pub draw_steps: usize,
}

impl Default for HlrOptions {
    fn default() -> Self {
        HlrOptions {
            curve: CurveOptions::default(),
            ray: RayOptions::default(),
            crossing: SystemOptions {
                max_depth: 24,
                max_boxes: 3_000,
                refine_width: 1e-12,
            },
            draw_steps: 8,
        }
    }
}

/// What a line is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LineKind {
    /// A silhouette arc.
    Silhouette,
    /// A patch boundary (a side; a shared edge is drawn once).
    Boundary,
}

/// One segment of a line, with the exact polynomials its crossings are solved on.
#[derive(Clone, Debug)]
struct Segment {
    kind: LineKind,
    patch: usize,
    /// The side, for a boundary.
    edge: Option<Edge>,
    /// The line it belongs to, and its position along it.
    chain: usize,
    order: usize,
    /// Image polynomials in the segment's variables (t for a side, (u, v) for an arc).
    image: ImagePolys,
    /// The silhouette function (arcs).
    constraint: Option<Poly>,
    /// The variables' box: the parameter interval of a side, or the arc's cell.
    domain: DyadicBoxN,
    /// The variable that parameterizes the segment.
    axis: usize,
    /// The parameter extent of the curve in it.
    range: [f64; 2],
    /// Image and depth bounds.
    bounds: ImageBounds,
    /// The image tangent's numerators along the image axes (positive multiples of the
    /// derivative along the segment's orientation).
    tangent: [Poly; 2],
    /// A direction `e` in which the image is strictly monotone, with the sign of
    /// `e · tangent`.
    monotone: Option<([Rational; 2], bool)>,
}

/// A piece of a line with constant visibility.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct HlrPiece {
    /// Silhouette or boundary.
    pub kind: LineKind,
    /// The patch the line lies on (for a shared edge, its first user).
    pub patch: usize,
    /// The side, for a boundary.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge: Option<Edge>,
    /// Its parameter interval (the side parameter, or the arc's free parameter).
    pub param: [f64; 2],
    /// The number of surface layers in front of it (`None` if not proven).
    pub qi: Option<usize>,
    /// Whether the QI is proven (and constant along the piece).
    pub certified: bool,
    /// Why not, if not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// Points in space for drawing (not certified positions).
    pub points: Vec<[f64; 3]>,
    /// The same points as (patch, u, v).
    pub points_uv: Vec<(usize, f64, f64)>,
}

/// Counts of the work done.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct HlrStats {
    /// Line segments.
    pub segments: usize,
    /// Segment pairs whose image boxes meet (solved or skipped by monotonicity).
    pub pairs: usize,
    /// Pairs skipped because their union's image is monotone.
    pub monotone_pairs: usize,
    /// Pairs culled by their image boxes.
    pub culled_pairs: usize,
    /// Segment-patch penetration systems solved.
    pub penetration_systems: usize,
    /// Boxes examined by the crossing and penetration systems.
    pub boxes: usize,
    /// Ray tests run, and those refused (another sample was tried).
    pub samples: usize,
    /// Ray tests refused.
    pub refused_samples: usize,
    /// Silhouette boxes the curve solver left unresolved (their lines are not drawn).
    pub silhouette_unresolved: usize,
}

/// A hidden-line drawing.
#[derive(Clone, Debug, serde::Serialize)]
pub struct HiddenLines {
    /// The pieces, in line order.
    pub pieces: Vec<HlrPiece>,
    /// Per patch, its self-visible type.
    pub facing: Vec<Facing>,
    /// Work counts.
    pub stats: HlrStats,
}

impl HiddenLines {
    /// Whether every piece's visibility is proven and every silhouette region resolved.
    pub fn is_certified(&self) -> bool {
        self.stats.silhouette_unresolved == 0 && self.pieces.iter().all(|p| p.certified)
    }
}

/// A piece whose visibility is not proven, as listed in the report.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct UnresolvedPiece {
    /// Silhouette or boundary.
    pub kind: LineKind,
    /// The patch.
    pub patch: usize,
    /// The side, for a boundary.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge: Option<Edge>,
    /// Its parameter interval.
    pub param: [f64; 2],
    /// Why.
    pub reason: String,
}

/// The JSON document of `limn hlr --format json` (field names are a public contract, see
/// README).
#[derive(Clone, Debug, serde::Serialize)]
pub struct HlrReport {
    /// The model file.
    pub model: String,
    /// The view.
    pub view: serde_json::Value,
    /// Every piece's visibility proven and every silhouette region resolved.
    pub certified: bool,
    /// The pieces.
    pub pieces: Vec<HlrPiece>,
    /// The pieces whose visibility is not proven.
    pub unresolved: Vec<UnresolvedPiece>,
    /// Per patch, its self-visible type.
    pub facing: Vec<Facing>,
    /// Work counts.
    pub stats: HlrStats,
    /// Wall time in milliseconds.
    pub time_ms: f64,
    /// Worker threads.
    pub threads: usize,
}

impl HlrReport {
    /// The report of a drawing.
    pub fn new(model: &str, view: &View, h: &HiddenLines, time_ms: f64, threads: usize) -> HlrReport {
        HlrReport {
            model: model.to_string(),
            view: view.to_json(),
            certified: h.is_certified(),
            unresolved: h
                .pieces
                .iter()
                .filter(|p| !p.certified)
                .map(|p| UnresolvedPiece {
                    kind: p.kind,
                    patch: p.patch,
                    edge: p.edge,
                    param: p.param,
                    reason: p.reason.clone().unwrap_or_default(),
                })
                .collect(),
            pieces: h.pieces.clone(),
            facing: h.facing.clone(),
            stats: h.stats.clone(),
            time_ms,
            threads,
        }
    }

    /// A short text summary.
    pub fn text(&self) -> String {
        let count = |f: &dyn Fn(&HlrPiece) -> bool| self.pieces.iter().filter(|p| f(p)).count();
        let mut t = format!("model: {}\n", self.model);
        t += &format!(
            "hidden lines: {} pieces ({} visible, {} hidden, {} unresolved); {}\n",
            self.pieces.len(),
            count(&|p| p.qi == Some(0)),
            count(&|p| p.qi.is_some_and(|q| q > 0)),
            count(&|p| p.qi.is_none()),
            if self.certified {
                "every piece's visibility is proven"
            } else {
                "NOT fully certified (see unresolved)"
            }
        );
        let kinds = [Facing::Front, Facing::Back, Facing::Partial, Facing::EdgeOn, Facing::Undecided];
        let names = ["front", "back", "partial", "edge-on", "undecided"];
        let parts: Vec<String> = kinds
            .iter()
            .zip(names)
            .map(|(k, n)| format!("{} {n}", self.facing.iter().filter(|f| *f == k).count()))
            .collect();
        t += &format!("patches: {}\n", parts.join(", "));
        let s = &self.stats;
        t += &format!(
            "work: {} segments, {} pairs ({} culled, {} monotone), {} penetration systems, {} boxes, {} ray tests ({} refused)\n",
            s.segments, s.pairs, s.culled_pairs, s.monotone_pairs, s.penetration_systems, s.boxes, s.samples, s.refused_samples
        );
        if s.silhouette_unresolved > 0 {
            t += &format!(
                "silhouette: {} regions unresolved (lines there are not drawn)\n",
                s.silhouette_unresolved
            );
        }
        for u in self.unresolved.iter().take(10) {
            t += &format!(
                "  unresolved: {:?} on patch {} at [{:.6}, {:.6}]: {}\n",
                u.kind, u.patch, u.param[0], u.param[1], u.reason
            );
        }
        if self.unresolved.len() > 10 {
            t += &format!("  ... and {} more\n", self.unresolved.len() - 10);
        }
        t += &format!("time: {:.1} ms on {} threads\n", self.time_ms, self.threads);
        t
    }
}

/// Why a drawing cannot be made.
pub use super::projection::ProjectionError as HlrError;

/// The hidden-line drawing of a model in a view.
///
/// # Errors
/// As [`super::projection::Projection::new`] (an empty model, a zero direction, an eye not in
/// front of every patch).
///
/// # Examples
/// ```
/// use limn::analysis::hlr::{hidden_lines, HlrOptions};
/// use limn::analysis::silhouette::View;
/// use limn::model::{Format, Model, WeldTolerance};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let model = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
/// let view = View::Direction([1, 2, 3].map(Rational::from));
/// let h = hidden_lines(&model, &view, &HlrOptions::default(), WeldTolerance::Exact).unwrap();
/// // The outline of a sphere is visible all round.
/// assert!(h.pieces.iter().any(|p| p.kind == limn::analysis::hlr::LineKind::Silhouette));
/// assert!(h.pieces.iter().filter(|p| p.kind == limn::analysis::hlr::LineKind::Silhouette)
///     .all(|p| p.qi == Some(0)));
/// ```
pub fn hidden_lines(
    model: &Model,
    view: &View,
    opts: &HlrOptions,
    weld: WeldTolerance,
) -> Result<HiddenLines, HlrError> {
    let scene = Scene::new(model, view, weld)?;
    let sil = silhouette(model, view, &opts.curve, weld, None);
    let mut stats = HlrStats {
        silhouette_unresolved: sil.unresolved.len(),
        ..HlrStats::default()
    };
    let mut segments = boundary_segments(model, &scene);
    segments.extend(silhouette_segments(&scene, &sil));
    stats.segments = segments.len();

    // Pairs of segments, and segment-patch penetrations.
    let mut pairs = Vec::new();
    for a in 0..segments.len() {
        for b in a + 1..segments.len() {
            let (sa, sb) = (&segments[a], &segments[b]);
            if !sa.bounds.meets_image(&sb.bounds) {
                stats.culled_pairs += 1;
                continue;
            }
            stats.pairs += 1;
            if sa.chain == sb.chain && sa.order.abs_diff(sb.order) == 1 && common_monotone(sa, sb)
            {
                stats.monotone_pairs += 1;
                continue;
            }
            pairs.push((a, b));
        }
    }
    let mut penetrations = Vec::new();
    for (a, s) in segments.iter().enumerate() {
        for (j, jb) in scene.bounds.iter().enumerate() {
            if j == s.patch || adjacent(&scene, s.patch, j) {
                continue;
            }
            let overlap_depth = jb.depth[0] <= s.bounds.depth[1] && s.bounds.depth[0] <= jb.depth[1];
            if jb.meets_image(&s.bounds) && overlap_depth {
                penetrations.push((a, j));
            }
        }
    }
    stats.penetration_systems = penetrations.len();

    let crossing_events: Vec<(usize, usize, SystemRoots)> = pairs
        .par_iter()
        .map(|&(a, b)| {
            let (eqs, domain) = crossing_system(&segments[a], &segments[b]);
            (a, b, solve_system(&eqs, &[], &domain, &opts.crossing))
        })
        .collect();
    let penetration_events: Vec<(usize, SystemRoots)> = penetrations
        .par_iter()
        .map(|&(a, j)| {
            let (eqs, domain) = penetration_system(&segments[a], &scene.images[j]);
            (a, solve_system(&eqs, &[], &domain, &opts.crossing))
        })
        .collect();

    let mut events: Vec<Vec<Event>> = vec![Vec::new(); segments.len()];
    for (a, b, r) in &crossing_events {
        stats.boxes += r.boxes;
        let na = segments[*a].domain.len();
        let (ia, ib) = (segments[*a].axis, na + segments[*b].axis);
        for root in &r.roots {
            events[*a].push(Event::cut(root.enclosure[ia]));
            events[*b].push(Event::cut(root.enclosure[ib]));
        }
        for bx in &r.unresolved {
            let why = format!(
                "its crossing with another line (patch {}) is not isolated here",
                segments[*b].patch
            );
            events[*a].push(Event::unresolved(bx[ia], why));
            let why = format!(
                "its crossing with another line (patch {}) is not isolated here",
                segments[*a].patch
            );
            events[*b].push(Event::unresolved(bx[ib], why));
        }
    }
    for (a, r) in &penetration_events {
        stats.boxes += r.boxes;
        let ia = segments[*a].axis;
        for root in &r.roots {
            events[*a].push(Event::cut(root.enclosure[ia]));
        }
        for bx in &r.unresolved {
            events[*a].push(Event::unresolved(
                bx[ia],
                "where it may pass through another patch is not isolated here".into(),
            ));
        }
    }

    // Pieces, and their QI.
    let draws: Vec<DrawPatch> = model.patches.iter().map(|p| DrawPatch::new(&p.surface)).collect();
    let per_segment: Vec<(Vec<HlrPiece>, usize, usize)> = segments
        .par_iter()
        .zip(events.par_iter())
        .map(|(s, ev)| pieces_of(&scene, s, ev, &draws[s.patch], opts))
        .collect();
    let mut pieces = Vec::new();
    for (p, samples, refused) in per_segment {
        pieces.extend(p);
        stats.samples += samples;
        stats.refused_samples += refused;
    }
    let facing = model.patches.par_iter().map(|p| facing(&p.surface, view)).collect();
    Ok(HiddenLines {
        pieces,
        facing,
        stats,
    })
}

/// A cut or an unresolved stretch on a segment's parameter.
#[derive(Clone, Debug)]
struct Event {
    at: [f64; 2],
    unresolved: Option<String>,
}

impl Event {
    fn cut(at: [f64; 2]) -> Event {
        Event {
            at,
            unresolved: None,
        }
    }
    fn unresolved(at: [f64; 2], why: String) -> Event {
        Event {
            at,
            unresolved: Some(why),
        }
    }
}

/// Whether two patches share a corner or an edge.
fn adjacent(scene: &Scene, a: usize, b: usize) -> bool {
    let (ca, cb) = (&scene.adjacency.corners[a], &scene.adjacency.corners[b]);
    ca.iter().any(|x| cb.contains(x))
}

/// The image bounds of image polynomials on a box of their variables.
fn bounds_on(im: &ImagePolys, domain: &DyadicBoxN) -> ImageBounds {
    let lo: Vec<Rational> = domain.iter().map(|d| d.0.to_rational()).collect();
    let hi: Vec<Rational> = domain.iter().map(|d| d.1.to_rational()).collect();
    let r = |p: &Poly| p.restrict_box_rational(&lo, &hi);
    ImageBounds {
        x: ratio_bounds(&r(&im.x), &r(&im.q)),
        y: ratio_bounds(&r(&im.y), &r(&im.q)),
        depth: ratio_bounds(&r(&im.depth), &r(&im.w)),
    }
}

/// The sign of a polynomial on a box, if strict: `Some(true)` positive.
fn strict_sign(p: &Poly, domain: &DyadicBoxN) -> Option<bool> {
    let lo: Vec<Interval> = domain
        .iter()
        .map(|d| Interval::point(d.0.to_f64_bounds().0))
        .collect();
    let hi: Vec<Interval> = domain
        .iter()
        .map(|d| Interval::point(d.1.to_f64_bounds().1))
        .collect();
    let r = p.convert::<Interval>(Precision::F64).restrict_box(&lo, &hi);
    let c = r.coeffs();
    if c.iter().all(|x| x.lo() > 0.0) {
        Some(true)
    } else if c.iter().all(|x| x.hi() < 0.0) {
        Some(false)
    } else {
        None
    }
}

/// The image tangent of an arc of patch `patch` on `g = 0`: the field `(−g_v, g_u)` pushed to
/// the image by the numerators of the Jacobian rows (a positive multiple of the derivative
/// of the image point along that field).
fn tangent_polys_arc(scene: &Scene, patch: usize, g: &Poly) -> [Poly; 2] {
    let (gu, gv) = (g.deriv(0), g.deriv(1));
    let t = [gv.neg(), gu];
    let j = &scene.jacobians[patch];
    [0, 1].map(|r| &(&j[r][0] * &t[0]) + &(&j[r][1] * &t[1]))
}

/// The segment's image is strictly monotone along `e` if `e · tangent` has a strict sign on
/// its box; the sign is returned.
fn monotone_along(t: &[Poly; 2], e: &[Rational; 2], domain: &DyadicBoxN) -> Option<bool> {
    let p = &t[0].scale(&e[0]) + &t[1].scale(&e[1]);
    strict_sign(&p, domain)
}

/// A direction in which the segment's image is monotone: the image tangent at its centre,
/// rounded to a rational direction.
fn find_monotone(t: &[Poly; 2], domain: &DyadicBoxN) -> Option<([Rational; 2], bool)> {
    let mid: Vec<f64> = domain.iter().map(|d| 0.5 * (d.0.to_f64() + d.1.to_f64())).collect();
    let tf: Vec<f64> = t
        .iter()
        .map(|p| p.convert::<f64>(Precision::F64).eval(&mid))
        .collect();
    let n = tf[0].hypot(tf[1]);
    if !n.is_finite() || n <= 0.0 {
        return None;
    }
    let r = |x: f64| Rational::from_f64((x / n * 1024.0).round() / 1024.0).unwrap_or_default();
    let e = [r(tf[0]), r(tf[1])];
    monotone_along(t, &e, domain).map(|s| (e, s))
}

/// Two consecutive segments of one line whose images are monotone in a common direction with
/// the same orientation: their union's image is monotone, so they meet only at their shared
/// end (proofs/hidden-lines.md).
fn common_monotone(a: &Segment, b: &Segment) -> bool {
    let (Some((ea, sa)), Some((eb, sb))) = (&a.monotone, &b.monotone) else {
        return false;
    };
    monotone_along(&b.tangent, ea, &b.domain) == Some(*sa)
        || monotone_along(&a.tangent, eb, &a.domain) == Some(*sb)
}

/// The boundary lines: each distinct edge once, cut into monotone parameter intervals.
fn boundary_segments(_model: &Model, scene: &Scene) -> Vec<Segment> {
    let mut out = Vec::new();
    for (chain, users) in scene.adjacency.edges.iter().enumerate() {
        let first = users[0];
        let im = scene.images[first.patch].on_side(first.edge);
        // Monotone intervals by bisection (up to 2^-6); a stretch that is never monotone
        // keeps its finest intervals, and its self-crossings are solved like any pair.
        let mut stack = vec![(Dyadic::ZERO, Dyadic::ONE, 0u32)];
        let mut intervals = Vec::new();
        let t = tangent_polys_side(&im);
        let tangent = t.clone();
        while let Some((lo, hi, depth)) = stack.pop() {
            let dom = vec![(lo, hi)];
            match find_monotone(&t, &dom) {
                Some(m) => intervals.push((lo, hi, Some(m))),
                None if depth >= 6 => intervals.push((lo, hi, None)),
                None => {
                    let mid = lo.midpoint(hi).expect("shallow");
                    stack.push((mid, hi, depth + 1));
                    stack.push((lo, mid, depth + 1));
                }
            }
        }
        for (order, (lo, hi, monotone)) in intervals.into_iter().enumerate() {
            let domain = vec![(lo, hi)];
            out.push(Segment {
                kind: LineKind::Boundary,
                patch: first.patch,
                edge: Some(first.edge),
                chain,
                order,
                bounds: bounds_on(&im, &domain),
                image: im.clone(),
                constraint: None,
                tangent: tangent.clone(),
                range: [lo.to_f64(), hi.to_f64()],
                domain,
                axis: 0,
                monotone,
            });
        }
    }
    out
}

/// The image tangent of a side: the numerators of the derivatives of the image coordinates.
fn tangent_polys_side(im: &ImagePolys) -> [Poly; 2] {
    let d = |f: &Poly| &(&f.deriv(0) * &im.q) - &(f * &im.q.deriv(0));
    [d(&im.x), d(&im.y)]
}

/// The silhouette arcs, one segment per certified cell; the arcs of one branch form a line.
fn silhouette_segments(scene: &Scene, sil: &super::silhouette::Silhouette) -> Vec<Segment> {
    let mut out = Vec::new();
    let chain0 = scene.adjacency.edges.len();
    let mut chain = chain0;
    for (i, solved) in sil.solved.iter().enumerate() {
        let topo = &solved.topology;
        for branch in &topo.branches {
            let ids = &branch.crossings;
            let n = if branch.closed { ids.len() } else { ids.len().saturating_sub(1) };
            let mut order = 0;
            for k in 0..n {
                let (a, b) = (&ids[k], &ids[(k + 1) % ids.len()]);
                let Some(arc) = topo
                    .arcs
                    .iter()
                    .find(|x| (x.from == *a && x.to == *b) || (x.from == *b && x.to == *a))
                else {
                    continue;
                };
                let axis = match arc.reason {
                    "graph over u" => 0,
                    "graph over v" => 1,
                    _ => continue, // along a side: drawn as the boundary
                };
                let domain: DyadicBoxN = vec![
                    (arc.cell.lo[0], arc.cell.hi[0]),
                    (arc.cell.lo[1], arc.cell.hi[1]),
                ];
                let (pa, pb) = (topo.locations[a], topo.locations[b]);
                let range = [
                    pa[0][axis].min(pb[0][axis]),
                    pa[1][axis].max(pb[1][axis]),
                ];
                let tangent = tangent_polys_arc(scene, i, &solved.g);
                let monotone = find_monotone(&tangent, &domain);
                out.push(Segment {
                    kind: LineKind::Silhouette,
                    patch: i,
                    edge: None,
                    chain,
                    order,
                    bounds: bounds_on(&scene.images[i], &domain),
                    image: scene.images[i].clone(),
                    constraint: Some(solved.g.clone()),
                    domain,
                    axis,
                    range,
                    tangent,
                    monotone,
                });
                order += 1;
            }
            chain += 1;
        }
    }
    out
}

/// The crossing system of two segments: image coincidence and their constraints, in the
/// variables of `a` then of `b`.
fn crossing_system(a: &Segment, b: &Segment) -> (Vec<Poly>, DyadicBoxN) {
    let (na, nb) = (a.domain.len(), b.domain.len());
    let n = na + nb;
    let la = |p: &Poly| lift(p, n, 0);
    let lb = |p: &Poly| lift(p, n, na);
    let coincide = |fa: &Poly, fb: &Poly| {
        &(&la(fa) * &lb(&b.image.q)) - &(&lb(fb) * &la(&a.image.q))
    };
    let mut eqs = vec![
        coincide(&a.image.x, &b.image.x),
        coincide(&a.image.y, &b.image.y),
    ];
    eqs.extend(a.constraint.iter().map(la));
    eqs.extend(b.constraint.iter().map(lb));
    let mut domain = a.domain.clone();
    domain.extend(b.domain.iter().copied());
    (eqs, domain)
}

/// The penetration system of a segment and a patch: the same point in space.
fn penetration_system(a: &Segment, j: &ImagePolys) -> (Vec<Poly>, DyadicBoxN) {
    let na = a.domain.len();
    let n = na + 2;
    let la = |p: &Poly| lift(p, n, 0);
    let lj = |p: &Poly| lift(p, n, na);
    let coincide = |fa: &Poly, fj: &Poly, da: &Poly, dj: &Poly| {
        &(&la(fa) * &lj(dj)) - &(&lj(fj) * &la(da))
    };
    let mut eqs = vec![
        coincide(&a.image.x, &j.x, &a.image.q, &j.q),
        coincide(&a.image.y, &j.y, &a.image.q, &j.q),
        coincide(&a.image.depth, &j.depth, &a.image.w, &j.w),
    ];
    eqs.extend(a.constraint.iter().map(la));
    let mut domain = a.domain.clone();
    domain.extend([(Dyadic::ZERO, Dyadic::ONE), (Dyadic::ZERO, Dyadic::ONE)]);
    (eqs, domain)
}

/// The dyadic with the smallest denominator in the open interval `(lo, hi)` (lo < hi).
fn dyadic_between(lo: f64, hi: f64) -> Option<Rational> {
    for k in 1..=50u32 {
        let scale = (1u64 << k) as f64;
        let n = (lo * scale).floor() + 1.0;
        if n / scale < hi {
            let q = Rational::from((n as i64, 1i64 << k));
            if q > 0 && q < 1 {
                return Some(q);
            }
        }
    }
    None
}

/// The pieces of a segment between its events, with their QI.
fn pieces_of(
    scene: &Scene,
    s: &Segment,
    events: &[Event],
    draw: &DrawPatch,
    opts: &HlrOptions,
) -> (Vec<HlrPiece>, usize, usize) {
    let mut ev: Vec<&Event> = events
        .iter()
        .filter(|e| e.at[1] > s.range[0] && e.at[0] < s.range[1])
        .collect();
    ev.sort_by(|a, b| a.at[0].total_cmp(&b.at[0]));
    let mut out = Vec::new();
    let (mut samples, mut refused) = (0, 0);
    let mut cursor = s.range[0];
    let mut emit = |p0: f64, p1: f64, qi: Result<usize, String>| {
        let (points_uv, points) = draw_points(s, draw, p0, p1, opts.draw_steps);
        let (qi, reason) = match qi {
            Ok(n) => (Some(n), None),
            Err(e) => (None, Some(e)),
        };
        out.push(HlrPiece {
            kind: s.kind,
            patch: s.patch,
            edge: s.edge,
            param: [p0, p1],
            certified: qi.is_some(),
            qi,
            reason,
            points,
            points_uv,
        });
    };
    let mut i = 0;
    while cursor < s.range[1] {
        // The next event at or after the cursor.
        let next = ev.get(i).map_or(s.range[1], |e| e.at[0].max(cursor));
        if next > cursor {
            let qi = qi_of(scene, s, cursor, next.min(s.range[1]), opts, &mut samples, &mut refused);
            emit(cursor, next.min(s.range[1]), qi);
        }
        let Some(e) = ev.get(i) else { break };
        let end = e.at[1].min(s.range[1]).max(cursor);
        if let Some(why) = &e.unresolved {
            if end > next {
                emit(next, end, Err(why.clone()));
            }
        }
        cursor = cursor.max(end);
        i += 1;
    }
    (out, samples, refused)
}

/// The QI of a segment's stretch `[p0, p1]`, from the first proven sample.
fn qi_of(
    scene: &Scene,
    s: &Segment,
    p0: f64,
    p1: f64,
    opts: &HlrOptions,
    samples: &mut usize,
    refused: &mut usize,
) -> Result<usize, String> {
    let w = p1 - p0;
    let mut last = String::from("no sample point found in the piece");
    for (a, b) in [(0.25, 0.75), (0.1, 0.3), (0.7, 0.9)] {
        let Some(c) = dyadic_between(p0 + a * w, p0 + b * w) else {
            continue;
        };
        let Some(sample) = sample_at(s, &c) else {
            continue;
        };
        *samples += 1;
        match layers_in_front(scene, &sample, &opts.ray) {
            Ok(n) => return Ok(n),
            Err(e) => {
                *refused += 1;
                last = e;
            }
        }
    }
    Err(last)
}

/// The sample point of a segment at parameter `c`.
fn sample_at(s: &Segment, c: &Rational) -> Option<Sample> {
    match (&s.constraint, s.edge) {
        (None, Some(edge)) => Some(Sample::Exact {
            patch: s.patch,
            uv: side_point(edge, c),
        }),
        (Some(g), _) => {
            let m = 1 - s.axis;
            let line = fix_axis(g, s.axis, c);
            let stats = &mut Default::default();
            let (lo, hi) = s.domain[m];
            let roots = isolate_roots_in(&line, lo, hi, &Ladder::default(), 40, stats);
            if roots.roots.len() != 1 || !roots.unresolved.is_empty() {
                return None;
            }
            let r = refine_root(&line, roots.roots[0], 1e-12, &Ladder::default(), stats);
            let Root::Between { lo, hi } = r else {
                return None;
            };
            Some(Sample::Silhouette {
                patch: s.patch,
                axis: s.axis,
                at: c.clone(),
                interval: [lo.to_rational(), hi.to_rational()],
                g: g.clone(),
            })
        }
        (None, None) => None,
    }
}

/// Drawing points of a segment's stretch.
fn draw_points(
    s: &Segment,
    draw: &DrawPatch,
    p0: f64,
    p1: f64,
    steps: usize,
) -> (Vec<(usize, f64, f64)>, Vec<[f64; 3]>) {
    let steps = steps.max(2);
    let mut uv = Vec::new();
    let gf = s.constraint.as_ref().map(|g| g.convert::<f64>(Precision::F64));
    for k in 0..=steps {
        let t = p0 + (p1 - p0) * k as f64 / steps as f64;
        match (&gf, s.edge) {
            (None, Some(edge)) => {
                let p = match edge {
                    Edge::V0 => [t, 0.0],
                    Edge::V1 => [t, 1.0],
                    Edge::U0 => [0.0, t],
                    Edge::U1 => [1.0, t],
                };
                uv.push(p);
            }
            (Some(g), _) => {
                let m = 1 - s.axis;
                let (lo, hi) = (s.domain[m].0.to_f64(), s.domain[m].1.to_f64());
                if let Some(x) = zero_across(g, m, t, lo, hi) {
                    let mut p = [0.0; 2];
                    p[m] = x;
                    p[s.axis] = t;
                    uv.push(p);
                }
            }
            (None, None) => {}
        }
    }
    let points = uv.iter().map(|p| draw.eval(p[0], p[1])).collect();
    (uv.into_iter().map(|p| (s.patch, p[0], p[1])).collect(), points)
}
