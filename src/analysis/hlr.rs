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
use super::ray::{
    fix_axis, fold_box_around, injective_box_around, layers_in_front, ratio_bounds, ImageBounds,
    RayOptions, Sample, Scene,
};
use super::silhouette::{silhouette, DrawPatch, View};
use crate::bernstein::Bernstein;
use crate::model::{Model, WeldTolerance};
use crate::number::{Interval, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::Ladder;
use crate::solver::system::{solve_system_excluding, DyadicBoxN, SystemOptions, SystemRoots};
use crate::solver::univariate::{isolate_roots_in, refine_root, Root};
use crate::solver::{CrossingId, CurveOptions};
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
    /// The points where it meets other lines in space (its ends, and junctions on a side).
    vertices: Vec<Vertex>,
    /// The patches it lies on: `(patch, side, reversed)` for the users of an edge (reversed:
    /// the side runs opposite to the segment's parameter), `(patch, None, false)` for an arc.
    on: Vec<(usize, Option<Edge>, bool)>,
}

/// Where a vertex of the line network is.
#[derive(Clone, Debug, PartialEq)]
enum Key {
    /// A welded patch corner (its vertex id).
    Corner(usize),
    /// A point of an edge, by its parameter interval on the edge's first user.
    Side { class: usize, t: [f64; 2] },
    /// A crossing of a patch's silhouette inside the patch.
    Inner { patch: usize, id: CrossingId },
    /// A point where an arc was cut to make its pieces' images monotone: the line and the
    /// parameter (its f64 bits).
    Param { chain: usize, at: u64 },
}

/// A vertex of a segment.
#[derive(Clone, Debug)]
struct Vertex {
    key: Key,
    /// Its parameter interval on the segment.
    param: [f64; 2],
    /// Its parameter box on each patch it lies on: `(patch, lo, hi)`.
    uv: Vec<(usize, [Rational; 2], [Rational; 2])>,
}

impl Key {
    fn matches(&self, other: &Key) -> bool {
        match (self, other) {
            (Key::Corner(a), Key::Corner(b)) => a == b,
            (Key::Side { class: a, t: s }, Key::Side { class: b, t: u }) => {
                a == b && s[0] <= u[1] && u[0] <= s[1]
            }
            (Key::Inner { patch: a, id: x }, Key::Inner { patch: b, id: y }) => a == b && x == y,
            (Key::Param { chain: a, at: x }, Key::Param { chain: b, at: y }) => a == b && x == y,
            _ => false,
        }
    }
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
    /// Boxes around shared vertices excluded by a lemma (proofs/hidden-lines.md).
    pub excluded_vertices: usize,
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
    pub fn new(
        model: &str,
        view: &View,
        h: &HiddenLines,
        time_ms: f64,
        threads: usize,
    ) -> HlrReport {
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
        let kinds = [
            Facing::Front,
            Facing::Back,
            Facing::Partial,
            Facing::EdgeOn,
            Facing::Undecided,
        ];
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
    let mut segments = boundary_segments(&scene);
    let arcs = silhouette_segments(&scene, &sil, &mut segments);
    segments.extend(arcs);
    stats.segments = segments.len();

    // Pairs of segments (with the boxes around shared vertices proven to hold no other
    // crossing), self-crossings of sides, and segment-patch penetrations.
    let mut events: Vec<Vec<Event>> = vec![Vec::new(); segments.len()];
    let mut jobs: Vec<Job> = Vec::new();
    for (a, sa) in segments.iter().enumerate() {
        // Every vertex inside a segment cuts it (a junction on a side).
        for v in &sa.vertices {
            events[a].push(Event::cut(v.param));
        }
        match (&sa.constraint, &sa.monotone) {
            (None, _) => jobs.push(Job::SelfCrossing(a)),
            (Some(_), Some(_)) => {}
            (Some(_), None) => events[a].push(Event::unresolved(
                sa.range,
                "its image is not proven free of self-crossings (a cusp of the outline?)".into(),
            )),
        }
        for (b, sb) in segments.iter().enumerate().skip(a + 1) {
            if !sa.bounds.meets_image(&sb.bounds) {
                stats.culled_pairs += 1;
                continue;
            }
            stats.pairs += 1;
            if sa.chain == sb.chain && sa.order.abs_diff(sb.order) == 1 && common_monotone(sa, sb) {
                stats.monotone_pairs += 1;
                continue;
            }
            jobs.push(Job::Pair(a, b));
        }
        for (j, jb) in scene.bounds.iter().enumerate() {
            if sa.on.iter().any(|x| x.0 == j) || sa.on.iter().any(|x| adjacent(&scene, x.0, j)) {
                continue;
            }
            let overlap_depth =
                jb.depth[0] <= sa.bounds.depth[1] && sa.bounds.depth[0] <= jb.depth[1];
            if jb.meets_image(&sa.bounds) && overlap_depth {
                stats.penetration_systems += 1;
                jobs.push(Job::Penetration(a, j));
            }
        }
    }
    if std::env::var_os("LIMN_HLR_VERTS").is_some() {
        for (k, sg) in segments.iter().enumerate() {
            eprintln!(
                "SEG {k} {:?} p{} {:?} range {:?} verts {:?} mono {}",
                sg.kind,
                sg.patch,
                sg.edge,
                sg.range,
                sg.vertices
                    .iter()
                    .map(|v| (&v.key, v.param))
                    .collect::<Vec<_>>(),
                sg.monotone.is_some()
            );
        }
    }
    let results: Vec<(Job, SystemRoots, Vec<DyadicBoxN>)> = jobs
        .par_iter()
        .map(|job| {
            let (eqs, domain, exclude) = match *job {
                Job::Pair(a, b) => {
                    let (eqs, domain) = crossing_system(&segments[a], &segments[b]);
                    let mut exclude = arc_fold_exclusion(&scene, &segments[a], &segments[b]);
                    for va in &segments[a].vertices {
                        for vb in &segments[b].vertices {
                            if va.key.matches(&vb.key) {
                                if let Some(x) =
                                    vertex_exclusion(&scene, &segments[a], &segments[b], va, vb)
                                {
                                    exclude.push(x);
                                }
                            }
                        }
                    }
                    (eqs, domain, exclude)
                }
                Job::SelfCrossing(a) => {
                    let (eqs, domain) = self_crossing_system(&segments[a]);
                    (eqs, domain, Vec::new())
                }
                Job::Penetration(a, j) => {
                    let (eqs, domain) = penetration_system(&segments[a], &scene.images[j]);
                    (eqs, domain, Vec::new())
                }
            };
            let r = solve_system_excluding(&eqs, &[], &domain, &exclude, &opts.crossing);
            (*job, r, exclude)
        })
        .collect();
    for (job, r, exclude) in &results {
        if std::env::var_os("LIMN_HLR_DEBUG").is_some() && !r.unresolved.is_empty() {
            let desc = |k: usize| {
                let s = &segments[k];
                format!(
                    "{:?} p{} {:?} dom {:?}",
                    s.kind,
                    s.patch,
                    s.edge,
                    s.domain
                        .iter()
                        .map(|d| [d.0.to_f64(), d.1.to_f64()])
                        .collect::<Vec<_>>()
                )
            };
            match *job {
                Job::Pair(a, b) => eprintln!(
                    "PAIR {} x {}: boxes {} unresolved {} roots {} excl {}",
                    desc(a),
                    desc(b),
                    r.boxes,
                    r.unresolved.len(),
                    r.roots.len(),
                    exclude.len()
                ),
                Job::SelfCrossing(a) => eprintln!(
                    "SELF {}: boxes {} unresolved {}",
                    desc(a),
                    r.boxes,
                    r.unresolved.len()
                ),
                Job::Penetration(a, j) => eprintln!(
                    "PEN {} x patch {j}: boxes {} unresolved {}",
                    desc(a),
                    r.boxes,
                    r.unresolved.len()
                ),
            }
        }
        stats.boxes += r.boxes;
        stats.excluded_vertices += exclude.len();
        // Which variables are each segment's parameter, and what an unresolved box means.
        let (targets, why): (Vec<(usize, usize)>, String) = match *job {
            Job::Pair(a, b) => {
                let na = segments[a].domain.len();
                (
                    vec![(a, segments[a].axis), (b, na + segments[b].axis)],
                    format!(
                        "where it crosses a line of patch {} (or patch {}) is not isolated",
                        segments[b].patch, segments[a].patch
                    ),
                )
            }
            Job::SelfCrossing(a) => (
                vec![(a, 0), (a, 1)],
                "where its image crosses itself is not isolated".into(),
            ),
            Job::Penetration(a, j) => (
                vec![(a, segments[a].axis)],
                format!("where it may pass through patch {j} is not isolated"),
            ),
        };
        for root in &r.roots {
            for &(s, k) in &targets {
                events[s].push(Event::cut(root.enclosure[k]));
            }
        }
        for bx in &r.unresolved {
            for &(s, k) in &targets {
                events[s].push(Event::unresolved(bx[k], why.clone()));
            }
        }
    }

    // Pieces, and their QI.
    let draws: Vec<DrawPatch> = model
        .patches
        .iter()
        .map(|p| DrawPatch::new(&p.surface))
        .collect();
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
    let facing = model
        .patches
        .par_iter()
        .map(|p| facing(&p.surface, view))
        .collect();
    Ok(HiddenLines {
        pieces,
        facing,
        stats,
    })
}

/// A system to solve.
#[derive(Clone, Copy, Debug)]
enum Job {
    /// Two segments' image crossings.
    Pair(usize, usize),
    /// A side's image crossing itself.
    SelfCrossing(usize),
    /// A segment passing through a patch.
    Penetration(usize, usize),
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
    let mid: Vec<f64> = domain
        .iter()
        .map(|d| 0.5 * (d.0.to_f64() + d.1.to_f64()))
        .collect();
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

/// The corner indices (into `PatchAdjacency::corners`) at the start and end of a side, in
/// its increasing parameter.
fn side_corners(edge: Edge) -> (usize, usize) {
    match edge {
        Edge::V0 => (0, 1),
        Edge::U1 => (1, 2),
        Edge::V1 => (3, 2),
        Edge::U0 => (0, 3),
    }
}

/// A rational from an f64 (exact).
fn rat(x: f64) -> Rational {
    Rational::from_f64(x).unwrap_or_default()
}

/// The parameter box, on each user patch, of the edge point with class parameter in `t`.
fn side_uv(
    users: &[(usize, Option<Edge>, bool)],
    t: [f64; 2],
) -> Vec<(usize, [Rational; 2], [Rational; 2])> {
    users
        .iter()
        .filter_map(|&(p, e, rev)| {
            let e = e?;
            let (a, b) = if rev {
                (1.0 - t[1], 1.0 - t[0])
            } else {
                (t[0], t[1])
            };
            let lo = side_point(e, &rat(a));
            let hi = side_point(e, &rat(b));
            Some((p, lo, hi))
        })
        .collect()
}

/// The boundary lines: each distinct edge once, as one segment.
fn boundary_segments(scene: &Scene) -> Vec<Segment> {
    let mut out = Vec::new();
    for (chain, users) in scene.adjacency.edges.iter().enumerate() {
        let first = users[0];
        let im = scene.images[first.patch].on_side(first.edge);
        let tangent = tangent_polys_side(&im);
        let domain = vec![(Dyadic::ZERO, Dyadic::ONE)];
        let on: Vec<(usize, Option<Edge>, bool)> = users
            .iter()
            .map(|u| (u.patch, Some(u.edge), u.reversed != first.reversed))
            .collect();
        let (c0, c1) = side_corners(first.edge);
        let corners = &scene.adjacency.corners[first.patch];
        let vertices = vec![
            Vertex {
                key: Key::Corner(corners[c0]),
                param: [0.0, 0.0],
                uv: side_uv(&on, [0.0, 0.0]),
            },
            Vertex {
                key: Key::Corner(corners[c1]),
                param: [1.0, 1.0],
                uv: side_uv(&on, [1.0, 1.0]),
            },
        ];
        out.push(Segment {
            kind: LineKind::Boundary,
            patch: first.patch,
            edge: Some(first.edge),
            chain,
            order: 0,
            bounds: bounds_on(&im, &domain),
            monotone: find_monotone(&tangent, &domain),
            image: im,
            constraint: None,
            tangent,
            range: [0.0, 1.0],
            domain,
            axis: 0,
            vertices,
            on,
        });
    }
    out
}

/// The image tangent of a side: the numerators of the derivatives of the image coordinates.
fn tangent_polys_side(im: &ImagePolys) -> [Poly; 2] {
    let d = |f: &Poly| &(&f.deriv(0) * &im.q) - &(f * &im.q.deriv(0));
    [d(&im.x), d(&im.y)]
}

/// The edge class and the user's reversal of a patch side.
fn class_of(scene: &Scene, patch: usize, edge: Edge) -> Option<(usize, bool)> {
    scene
        .adjacency
        .edges
        .iter()
        .enumerate()
        .find_map(|(c, users)| {
            let me = users.iter().find(|u| u.patch == patch && u.edge == edge)?;
            Some((c, me.reversed != users[0].reversed))
        })
}

/// The vertex of a silhouette crossing of patch `i`.
fn crossing_vertex(
    scene: &Scene,
    boundary: &[Segment],
    topo: &crate::solver::CurveTopology,
    i: usize,
    id: &CrossingId,
    axis: usize,
) -> Vertex {
    let loc = topo.locations[id];
    let param = [loc[0][axis], loc[1][axis]];
    let own = (
        i,
        [rat(loc[0][0]), rat(loc[0][1])],
        [rat(loc[1][0]), rat(loc[1][1])],
    );
    // A patch corner.
    if let CrossingId::Exact { u, v } = id {
        let at = |d: &Dyadic| *d == Dyadic::ZERO || *d == Dyadic::ONE;
        if at(u) && at(v) {
            let k = match (*u == Dyadic::ONE, *v == Dyadic::ONE) {
                (false, false) => 0,
                (true, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            };
            let vid = scene.adjacency.corners[i][k];
            let uv = boundary
                .iter()
                .flat_map(|b| b.vertices.iter())
                .find(|x| x.key == Key::Corner(vid))
                .map_or_else(|| vec![own.clone()], |x| x.uv.clone());
            return Vertex {
                key: Key::Corner(vid),
                param,
                uv,
            };
        }
    }
    let sides = super::model_curves::side_of(id);
    if let Some(&(edge, s0, s1)) = sides.first() {
        let (lo, hi) = topo
            .intervals
            .get(id)
            .map_or((s0.to_f64(), s1.to_f64()), |(a, b)| {
                (a.to_f64(), b.to_f64())
            });
        if let Some((class, rev)) = class_of(scene, i, edge) {
            let t = if rev { [1.0 - hi, 1.0 - lo] } else { [lo, hi] };
            return Vertex {
                key: Key::Side { class, t },
                param,
                uv: side_uv(&boundary[class].on, t),
            };
        }
        // A collapsed side (a pole): one point.
        if let Some(&(_, _, vid)) = scene
            .adjacency
            .collapsed
            .iter()
            .find(|(p, e, _)| *p == i && *e == edge)
        {
            return Vertex {
                key: Key::Corner(vid),
                param,
                uv: vec![own],
            };
        }
    }
    Vertex {
        key: Key::Inner { patch: i, id: *id },
        param,
        uv: vec![own],
    }
}

/// The silhouette arcs, one segment per certified cell; the arcs of one branch form a line.
/// Their ends on sides are added to the sides as vertices (junctions).
fn silhouette_segments(
    scene: &Scene,
    sil: &super::silhouette::Silhouette,
    boundary: &mut [Segment],
) -> Vec<Segment> {
    let mut out = Vec::new();
    let mut chain = boundary.len();
    for (i, solved) in sil.solved.iter().enumerate() {
        let topo = &solved.topology;
        for branch in &topo.branches {
            let ids = &branch.crossings;
            let n = if branch.closed {
                ids.len()
            } else {
                ids.len().saturating_sub(1)
            };
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
                let (pa, pb) = (topo.locations[a], topo.locations[b]);
                let range = [pa[0][axis].min(pb[0][axis]), pa[1][axis].max(pb[1][axis])];
                // The cell, narrowed along the parameter to the arc's extent: other arcs of
                // the same cell (each meets a parameter line once) lie outside it.
                let mut domain: DyadicBoxN = vec![
                    (arc.cell.lo[0], arc.cell.hi[0]),
                    (arc.cell.lo[1], arc.cell.hi[1]),
                ];
                let (lo, hi) = (dyadic_below(range[0]), dyadic_above(range[1]));
                domain[axis] = (domain[axis].0.max(lo), domain[axis].1.min(hi));
                let domain = narrow_to_curve(&solved.g, &domain, axis);
                let tangent = tangent_polys_arc(scene, i, &solved.g);
                let vertices: Vec<Vertex> = [a, b]
                    .iter()
                    .map(|id| crossing_vertex(scene, boundary, topo, i, id, axis))
                    .collect();
                for v in &vertices {
                    if let Key::Side { class, t } = &v.key {
                        let side = &mut boundary[*class];
                        if !side.vertices.iter().any(|x| x.key.matches(&v.key)) {
                            side.vertices.push(Vertex {
                                key: v.key.clone(),
                                param: *t,
                                uv: v.uv.clone(),
                            });
                        }
                    }
                }
                let whole = Segment {
                    kind: LineKind::Silhouette,
                    patch: i,
                    edge: None,
                    chain,
                    order,
                    bounds: bounds_on(&scene.images[i], &domain),
                    image: scene.images[i].clone(),
                    constraint: Some(solved.g.clone()),
                    monotone: find_monotone(&tangent, &domain),
                    domain,
                    axis,
                    range,
                    tangent,
                    vertices,
                    on: vec![(i, None, false)],
                };
                // Along the branch, vertex a comes first.
                let forward = whole.vertices[0].param[0] <= whole.range[0];
                let mut pieces = split_monotone(whole, 6);
                if !forward {
                    pieces.reverse();
                }
                for mut p in pieces {
                    p.order = order;
                    out.push(p);
                    order += 1;
                }
            }
            chain += 1;
        }
    }
    out
}

/// An arc cut at dyadic parameters (bisection, up to `depth` times) into pieces whose images
/// are monotone; the cut points become shared vertices. Pieces never made monotone stay (their
/// self-crossings are reported unresolved).
fn split_monotone(s: Segment, depth: u32) -> Vec<Segment> {
    if s.monotone.is_some() || depth == 0 {
        return vec![s];
    }
    let (lo, hi) = s.domain[s.axis];
    let Some(mid) = lo.midpoint(hi) else {
        return vec![s];
    };
    let c = mid.to_f64();
    if c <= s.range[0] || c >= s.range[1] {
        return vec![s];
    }
    let Some(g) = s.constraint.clone() else {
        return vec![s];
    };
    // The arc's point on the line axis = mid: the only root of g there in the cell.
    let m = 1 - s.axis;
    let line = fix_axis(&g, s.axis, &mid.to_rational());
    let stats = &mut Default::default();
    let roots = isolate_roots_in(
        &line,
        s.domain[m].0,
        s.domain[m].1,
        &Ladder::default(),
        40,
        stats,
    );
    if roots.roots.len() != 1 || !roots.unresolved.is_empty() {
        return vec![s];
    }
    let r = refine_root(&line, roots.roots[0], 1e-12, &Ladder::default(), stats);
    let mut lo_uv = [mid.to_rational(), mid.to_rational()];
    let mut hi_uv = lo_uv.clone();
    lo_uv[m] = r.lo().to_rational();
    hi_uv[m] = r.hi().to_rational();
    let cut = Vertex {
        key: Key::Param {
            chain: s.chain,
            at: c.to_bits(),
        },
        param: [c, c],
        uv: vec![(s.patch, lo_uv, hi_uv)],
    };
    let half = |range: [f64; 2], dom: (Dyadic, Dyadic), keep_low: bool| {
        let mut d = s.clone();
        d.domain[s.axis] = dom;
        d.domain = narrow_to_curve(&g, &d.domain, s.axis);
        d.range = range;
        d.bounds = bounds_on(&d.image, &d.domain);
        d.monotone = find_monotone(&d.tangent, &d.domain);
        d.vertices = s
            .vertices
            .iter()
            .filter(|v| {
                if keep_low {
                    v.param[1] <= c
                } else {
                    v.param[0] >= c
                }
            })
            .cloned()
            .chain([cut.clone()])
            .collect();
        d
    };
    let low = half([s.range[0], c], (lo, mid), true);
    let high = half([c, s.range[1]], (mid, hi), false);
    let mut out = split_monotone(low, depth - 1);
    out.extend(split_monotone(high, depth - 1));
    out
}

/// The box narrowed across the parameter axis to the hull of the sub-boxes (of a bisection
/// of that axis into up to 64) where `g` may vanish (a Bernstein coefficient sign test):
/// the arc inside the box lies in it.
fn narrow_to_curve(g: &Poly, domain: &DyadicBoxN, axis: usize) -> DyadicBoxN {
    let m = 1 - axis;
    let gi: Bernstein<Interval> = g.convert(Precision::F64);
    let mut keep: Option<(Dyadic, Dyadic)> = None;
    let mut stack = vec![(domain[m].0, domain[m].1, 0u32)];
    while let Some((lo, hi, depth)) = stack.pop() {
        let mut d = domain.clone();
        d[m] = (lo, hi);
        let l: Vec<Interval> = d
            .iter()
            .map(|x| Interval::point(x.0.to_f64_bounds().0))
            .collect();
        let h: Vec<Interval> = d
            .iter()
            .map(|x| Interval::point(x.1.to_f64_bounds().1))
            .collect();
        let c = gi.restrict_box(&l, &h);
        let c = c.coeffs();
        if c.iter().all(|x| x.lo() > 0.0) || c.iter().all(|x| x.hi() < 0.0) {
            continue;
        }
        match lo.midpoint(hi) {
            Some(mid) if depth < 6 => {
                stack.push((lo, mid, depth + 1));
                stack.push((mid, hi, depth + 1));
            }
            _ => {
                keep = Some(keep.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
            }
        }
    }
    let mut out = domain.clone();
    if let Some(k) = keep {
        out[m] = k;
    }
    out
}

/// The part of a segment's domain that lies in the parameter box `b` of patch `p`, if the
/// segment lies on `p` and meets `b`.
fn sub_domain(s: &Segment, p: usize, b: &DyadicBoxN) -> Option<DyadicBoxN> {
    let &(_, edge, rev) = s.on.iter().find(|x| x.0 == p)?;
    match edge {
        None => {
            let d: DyadicBoxN = (0..2)
                .map(|a| (s.domain[a].0.max(b[a].0), s.domain[a].1.min(b[a].1)))
                .collect();
            d.iter().all(|(l, h)| l < h).then_some(d)
        }
        Some(e) => {
            // The side's fixed coordinate must lie in the box; its free one gives the range.
            let (fixed, at_one) = match e {
                Edge::V0 => (1, false),
                Edge::V1 => (1, true),
                Edge::U0 => (0, false),
                Edge::U1 => (0, true),
            };
            let c = if at_one { Dyadic::ONE } else { Dyadic::ZERO };
            if !(b[fixed].0 <= c && c <= b[fixed].1) {
                return None;
            }
            let (lo, hi) = b[1 - fixed];
            let (lo, hi) = if rev {
                (hi.one_minus(), lo.one_minus())
            } else {
                (lo, hi)
            };
            let (lo, hi) = (lo.max(s.domain[0].0), hi.min(s.domain[0].1));
            (lo < hi).then(|| vec![(lo, hi)])
        }
    }
}

/// A box of the pair's product domain around a shared vertex that holds no crossing of the
/// two segments other than points they share in space (which are vertices, where both are
/// cut anyway), proven by one of the lemmas of `proofs/hidden-lines.md`; `None` if none
/// applies.
fn vertex_exclusion(
    scene: &Scene,
    a: &Segment,
    b: &Segment,
    va: &Vertex,
    vb: &Vertex,
) -> Option<DyadicBoxN> {
    // A patch both lie on near the vertex: the fold lemma (if one is a silhouette arc of it)
    // or the injective box.
    for (p, lo, hi) in &va.uv {
        let Some((_, lo2, hi2)) = vb.uv.iter().find(|x| x.0 == *p) else {
            continue;
        };
        if !a.on.iter().any(|x| x.0 == *p) || !b.on.iter().any(|x| x.0 == *p) {
            continue;
        }
        let lo: [Rational; 2] = std::array::from_fn(|k| lo[k].clone().min(lo2[k].clone()));
        let hi: [Rational; 2] = std::array::from_fn(|k| hi[k].clone().max(hi2[k].clone()));
        let lo = lo.map(|x| dyadic_floor(&x));
        let hi = hi.map(|x| dyadic_ceil(&x));
        let fold = [a, b]
            .iter()
            .any(|s| s.kind == LineKind::Silhouette && s.patch == *p);
        let bx = if fold {
            fold_box_around(scene, *p, &lo, &hi)
        } else {
            injective_box_around(scene, *p, &lo, &hi)
        };
        if let Some(bx) = bx {
            if let (Some(da), Some(db)) = (sub_domain(a, *p, &bx), sub_domain(b, *p, &bx)) {
                return Some(da.into_iter().chain(db).collect());
            }
        }
    }
    // Different patches: the two images leave the vertex on opposite sides of a line.
    opposite_monotone(a, b, va, vb)
}

/// A dyadic (40 bits) at or below an f64 in [0, 1].
fn dyadic_below(x: f64) -> Dyadic {
    let n = (x.clamp(0.0, 1.0) * (1u64 << 40) as f64).floor() as u64;
    Dyadic::new(n.min(1 << 40), 40)
}

/// A dyadic (40 bits) at or above an f64 in [0, 1].
fn dyadic_above(x: f64) -> Dyadic {
    let n = (x.clamp(0.0, 1.0) * (1u64 << 40) as f64).ceil() as u64;
    Dyadic::new(n.min(1 << 40), 40)
}

/// Lemma F (the fold lemma, `proofs/ray-count.md`) for a pair where one segment is a
/// silhouette arc of a patch the other lies on: on a box B around the arc's cell where it
/// holds, every crossing of the arc with a curve of the patch inside B is a point the two
/// share in space (a vertex, where both are cut), so the product of the arc's cell and the
/// other's part inside B is excluded.
fn arc_fold_exclusion(scene: &Scene, a: &Segment, b: &Segment) -> Vec<DyadicBoxN> {
    let (arc, other, arc_first) =
        if a.kind == LineKind::Silhouette && b.on.iter().any(|x| x.0 == a.patch) {
            (a, b, true)
        } else if b.kind == LineKind::Silhouette && a.on.iter().any(|x| x.0 == b.patch) {
            (b, a, false)
        } else {
            return Vec::new();
        };
    let Some(g) = &arc.constraint else {
        return Vec::new();
    };
    // The arc's box, or pieces of it along its parameter where one box does not do.
    let mut out = Vec::new();
    let mut stack = vec![(arc.domain.clone(), 0u32)];
    while let Some((d, depth)) = stack.pop() {
        let lo = [d[0].0.to_rational(), d[1].0.to_rational()];
        let hi = [d[0].1.to_rational(), d[1].1.to_rational()];
        if let Some(bx) = fold_box_around(scene, arc.patch, &lo, &hi) {
            if let Some(near) = sub_domain(other, arc.patch, &bx) {
                out.push(if arc_first {
                    d.iter().copied().chain(near).collect()
                } else {
                    near.into_iter().chain(d.iter().copied()).collect()
                });
            }
            continue;
        }
        if depth >= 4 {
            continue;
        }
        let (l, h) = d[arc.axis];
        let Some(mid) = l.midpoint(h) else { continue };
        for half in [(l, mid), (mid, h)] {
            let mut e = d.clone();
            e[arc.axis] = half;
            stack.push((narrow_to_curve(g, &e, arc.axis), depth + 1));
        }
    }
    out
}

/// The dyadic (40 bits) at or below / above a rational in [0, 1].
fn dyadic_floor(x: &Rational) -> Rational {
    let mut y = Rational::from(x << 40u32);
    y = Rational::from(y.floor_ref());
    y >>= 40u32;
    y
}

fn dyadic_ceil(x: &Rational) -> Rational {
    let mut y = Rational::from(x << 40u32);
    y = Rational::from(y.ceil_ref());
    y >>= 40u32;
    y
}

/// The near part of a segment at one of its ends, and the sign of moving away from it along
/// the segment's orientation (+1: increasing parameter / the tangent field's direction).
fn near_end(s: &Segment, v: &Vertex, depth: u32) -> Option<(DyadicBoxN, bool)> {
    // The vertex that defines the start (end) of the segment's parameter extent.
    let at_start = v.param[0] <= s.range[0];
    let at_end = v.param[1] >= s.range[1];
    if at_start == at_end {
        return None;
    }
    // The parameter axis restricted to the first (last) 2^-depth of the domain's width.
    let (lo, hi) = s.domain[s.axis];
    let mut d = s.domain.clone();
    d[s.axis] = if at_start {
        let mut c = hi;
        for _ in 0..depth {
            c = lo.midpoint(c)?;
        }
        (lo, c)
    } else {
        let mut c = lo;
        for _ in 0..depth {
            c = c.midpoint(hi)?;
        }
        (c, hi)
    };
    let away_up = match &s.constraint {
        // A side: moving away from its start increases the parameter.
        None => at_start,
        // An arc: the field (−g_v, g_u) moves along the parameter axis with the sign of −g_v
        // (axis u) or g_u (axis v), strict on the cell.
        Some(g) => {
            let field_up = if s.axis == 0 {
                !strict_sign(&g.deriv(1), &s.domain)?
            } else {
                strict_sign(&g.deriv(0), &s.domain)?
            };
            at_start == field_up
        }
    };
    Some((d, away_up))
}

/// Lemma L1: if near the vertex both images are strictly monotone along one direction e, one
/// moving to larger e and the other to smaller e as they leave the vertex, they meet only at
/// the vertex's image.
fn opposite_monotone(a: &Segment, b: &Segment, va: &Vertex, vb: &Vertex) -> Option<DyadicBoxN> {
    for depth in 0..=6 {
        let (da, away_a) = near_end(a, va, depth)?;
        let (db, away_b) = near_end(b, vb, depth)?;
        let Some((e, _)) = find_monotone(&a.tangent, &da) else {
            continue;
        };
        let (Some(sa), Some(sb)) = (
            monotone_along(&a.tangent, &e, &da),
            monotone_along(&b.tangent, &e, &db),
        ) else {
            continue;
        };
        // Leaving the vertex: e increases along a iff sa == away_a.
        if (sa == away_a) != (sb == away_b) {
            return Some(da.into_iter().chain(db).collect());
        }
    }
    None
}

/// `(a(t) b(s) − a(s) b(t)) / (t − s)` for univariate polynomials of one degree n, as a
/// polynomial of degree (n − 1, n − 1) in (t, s): exact, through the power basis.
fn antisymmetric_quotient(a: &Poly, b: &Poly) -> Poly {
    let (a, b) = same_degree(a, b);
    let n = a.degrees()[0];
    let (ma, mb) = (to_power(&a), to_power(&b));
    let m = n.max(1) - 1;
    let mut q = vec![Rational::new(); (m + 1) * (m + 1)];
    for i in 0..=n {
        for j in i + 1..=n {
            let c = Rational::from(&ma[i] * &mb[j]) - Rational::from(&ma[j] * &mb[i]);
            if c == 0 {
                continue;
            }
            // (t^i s^j − t^j s^i) = −(ts)^i (t − s) Σ_{k<d} t^k s^{d−1−k}, d = j − i.
            for k in 0..j - i {
                q[(i + k) * (m + 1) + (j - 1 - k)] -= &c;
            }
        }
    }
    from_power_2d(&q, m)
}

fn same_degree(a: &Poly, b: &Poly) -> (Poly, Poly) {
    let n = a.degrees()[0].max(b.degrees()[0]);
    (a.elevate_to(&[n]), b.elevate_to(&[n]))
}

fn binom(n: usize, k: usize) -> Rational {
    let mut r = Rational::from(1);
    for i in 0..k {
        r *= Rational::from(((n - i) as i64, (i + 1) as i64));
    }
    r
}

/// Power-basis coefficients of a univariate Bernstein polynomial.
fn to_power(p: &Poly) -> Vec<Rational> {
    let n = p.degrees()[0];
    let b = p.coeffs();
    (0..=n)
        .map(|k| {
            let mut s = Rational::new();
            for (i, bi) in b.iter().enumerate().take(k + 1) {
                let t = Rational::from(bi * &binom(k, i));
                if (k - i) % 2 == 0 {
                    s += t;
                } else {
                    s -= t;
                }
            }
            s * binom(n, k)
        })
        .collect()
}

/// The Bernstein form of degree (m, m) of a power-basis polynomial `Σ q[i(m+1)+j] t^i s^j`.
fn from_power_2d(q: &[Rational], m: usize) -> Poly {
    // b_{ij} = Σ_{k≤i, l≤j} C(i,k) C(j,l) / (C(m,k) C(m,l)) q_{kl}.
    let w: Vec<Vec<Rational>> = (0..=m)
        .map(|i| {
            (0..=m)
                .map(|k| {
                    if k <= i {
                        binom(i, k) / binom(m, k)
                    } else {
                        Rational::new()
                    }
                })
                .collect()
        })
        .collect();
    let mut out = vec![Rational::new(); (m + 1) * (m + 1)];
    for i in 0..=m {
        for j in 0..=m {
            let mut s = Rational::new();
            for k in 0..=i {
                for l in 0..=j {
                    let c = &q[k * (m + 1) + l];
                    if *c != 0 {
                        s += Rational::from(&w[i][k] * &w[j][l]) * c;
                    }
                }
            }
            out[i * (m + 1) + j] = s;
        }
    }
    Bernstein::new(&[m, m], out).expect("degree (m, m)")
}

/// The self-crossings of a side's image: both coincidence equations divided by `t − s`.
fn self_crossing_system(s: &Segment) -> (Vec<Poly>, DyadicBoxN) {
    let im = &s.image;
    let eqs = vec![
        antisymmetric_quotient(&im.x, &im.q),
        antisymmetric_quotient(&im.y, &im.q),
    ];
    let mut domain = s.domain.clone();
    domain.extend(s.domain.iter().copied());
    (eqs, domain)
}

/// The crossing system of two segments: image coincidence and their constraints, in the
/// variables of `a` then of `b`.
fn crossing_system(a: &Segment, b: &Segment) -> (Vec<Poly>, DyadicBoxN) {
    let (na, nb) = (a.domain.len(), b.domain.len());
    let n = na + nb;
    let la = |p: &Poly| lift(p, n, 0);
    let lb = |p: &Poly| lift(p, n, na);
    let coincide =
        |fa: &Poly, fb: &Poly| &(&la(fa) * &lb(&b.image.q)) - &(&lb(fb) * &la(&a.image.q));
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
    let coincide =
        |fa: &Poly, fj: &Poly, da: &Poly, dj: &Poly| &(&la(fa) * &lj(dj)) - &(&lj(fj) * &la(da));
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
    let mut out: Vec<HlrPiece> = Vec::new();
    let (mut samples, mut refused) = (0, 0);
    let mut cursor = s.range[0];
    let mut emit = |p0: f64, p1: f64, qi: Result<usize, String>| {
        // Consecutive unresolved stretches are reported as one piece (the first reason).
        if let (Err(_), Some(last)) = (&qi, out.last_mut()) {
            if !last.certified && last.param[1] >= p0 {
                let (uv, pts) = draw_points(s, draw, last.param[1], p1, opts.draw_steps);
                last.param[1] = p1;
                last.points.extend(pts.into_iter().skip(1));
                last.points_uv.extend(uv.into_iter().skip(1));
                return;
            }
        }
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
            let qi = qi_of(
                scene,
                s,
                cursor,
                next.min(s.range[1]),
                opts,
                &mut samples,
                &mut refused,
            );
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

/// Drawing points as (patch, u, v) and in space.
type Drawn = (Vec<(usize, f64, f64)>, Vec<[f64; 3]>);

/// Drawing points of a segment's stretch.
fn draw_points(s: &Segment, draw: &DrawPatch, p0: f64, p1: f64, steps: usize) -> Drawn {
    let steps = steps.max(2);
    let mut uv = Vec::new();
    let gf = s
        .constraint
        .as_ref()
        .map(|g| g.convert::<f64>(Precision::F64));
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
    (
        uv.into_iter().map(|p| (s.patch, p[0], p[1])).collect(),
        points,
    )
}
