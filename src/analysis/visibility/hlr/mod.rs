//! Certified hidden-line drawings of rational Bézier models (paper 000, extended to any model).
//!
//! The lines of the drawing are the patch boundaries (each shared edge once) and the
//! silhouette arcs of the certified silhouette ([`crate::analysis::contour::silhouette`]). Along a line the number
//! of surface layers in front of it (its QI) can change only where, in the image, it crosses
//! another line (a silhouette or a boundary: the outline of some sheet), where it crosses
//! itself, or where it passes through a patch (a penetration). So:
//!
//! 1. each line is cut into segments: a side is one segment; a silhouette arc of the curve
//!    solver's certified cells is cut at dyadic parameters until its image is monotone in one
//!    image direction. Where lines meet in space (patch corners, silhouette junctions on sides,
//!    cut points) they share a vertex, and a side is cut at each junction on it;
//! 2. every pair of segments whose image boxes meet is solved as a square system (the image
//!    coincidence plus each silhouette's equation, 2 to 4 unknowns) by the certified system
//!    solver, a side's self-crossings by the same equations divided exactly by `t − s`;
//!    every isolated root cuts both segments, every unresolved box marks the stretch it covers
//!    as unresolved. Boxes around shared vertices, and around a silhouette arc where the fold
//!    lemma holds, are excluded with a proof that they hold no other crossing (the lemmas of
//!    `proofs/hidden-lines.md`, in `lemmas.rs`);
//! 3. every segment is solved against every patch that is not adjacent to its own for
//!    penetrations (the spatial coincidence), which cut it the same way;
//! 4. between cuts the QI is constant (`proofs/hidden-lines.md`, claim 1), and is found by one
//!    certified ray test ([`crate::analysis::visibility::ray::layers_in_front`]) at a sample point; if a sample is
//!    refused, others are tried, and a piece with no proven sample is reported unresolved.
//!
//! What is not proven is reported: unresolved pieces (with the reason), silhouette regions the
//! curve solver did not resolve, and the assumption that adjacent patches do not cross each
//! other (penetrations are searched between non-adjacent patches only).

mod drawing;
mod lemmas;
mod network;
mod pieces;
mod result;
mod systems;

use pieces::{pieces_of, SampleTally};
pub use result::{Behind, HiddenLines, HlrPiece, HlrStats, LineKind, ADJACENT_ASSUMPTION};

use crate::error::Error;
use lemmas::*;
use network::*;
use systems::*;

use crate::analysis::chords::plane_curve::PatchAccuracy;
use crate::analysis::contour::drawing::refined_for;
use crate::analysis::contour::silhouette::silhouette_curves;
use crate::analysis::view::View;
use crate::analysis::visibility::facing::facing;
use crate::analysis::visibility::fold_edges::{
    continuing_stretches, edge_orientations, edge_roles,
};
use crate::analysis::visibility::ray::RayOptions;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::Bernstein;
use crate::model::{Model, WeldTolerance};
use crate::number::Interval;
use crate::solver::dyadic::Dyadic;
use crate::solver::plane_curve::TIME_LIMIT_REASON;
use crate::solver::system::{solve_system_excluding, DyadicBoxN, SystemOptions, SystemRoots};
use crate::solver::CurveOptions;
use crate::surface::DrawPatch;
use crate::surface::Edge;
use rayon::prelude::*;

/// Budgets and drawing density.
#[derive(Clone, Debug)]
pub struct HlrOptions {
    /// The silhouette solver's budgets.
    pub curve: CurveOptions,
    /// The ray tests' budgets.
    pub ray: RayOptions,
    /// Budgets of each crossing or penetration system.
    pub crossing: SystemOptions,
    /// Points drawn per segment piece (at least 2), without a tolerance.
    pub draw_steps: usize,
    /// The tolerance, in model units, within which every piece's drawing is proven to lie of
    /// the true piece in space (`proofs/hidden-lines.md`, "Drawing to a tolerance"); `None`:
    /// drawn at `draw_steps` evenly spaced parameters, not bounded.
    pub tol: Option<f64>,
    /// Clusters (paper 000, section 4): an edge across which the surface provably continues
    /// in the image ([`crate::analysis::visibility::fold_edges`]) cannot change the QI of what lies behind it, so
    /// its crossings do not cut other lines, and two such edges are not solved against each
    /// other. Off: every edge is treated as outline (for measuring what clusters save).
    pub clusters: bool,
    /// Find, for every visible outline piece, the first surface point behind it at its
    /// sample ([`HlrPiece::behind`]): the start of its occlusion curve on the surface behind
    /// (the visible regions' trimming curves). Costs the ray tests of the patches behind.
    pub behind: bool,
    /// How patch boundaries are matched into shared edges; `None`: the model's default
    /// ([`crate::model::default_weld`]).
    pub weld: Option<WeldTolerance>,
}

impl HlrOptions {
    /// These options with shared edges matched by `weld`.
    pub fn with_weld(mut self, weld: WeldTolerance) -> HlrOptions {
        self.weld = Some(weld);
        self
    }
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
            tol: None,
            clusters: true,
            behind: false,
            weld: None,
        }
    }
}

/// The hidden-line drawing of a model in a view.
///
/// # Errors
/// [`Error::View`] as [`crate::analysis::projection::Projection::new`] (an empty model, a zero
/// direction, an eye not in front of every patch).
///
/// # Examples
/// ```
/// use limn::analysis::visibility::hlr::{hidden_lines, HlrOptions};
/// use limn::analysis::view::View;
/// use limn::model::{Format, Model, WeldTolerance};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let model = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
/// let view = View::Direction([1, 2, 3].map(Rational::from));
/// let h = hidden_lines(&model, &view, &HlrOptions::default().with_weld(WeldTolerance::Exact))?;
/// // The outline of a sphere is visible all round.
/// assert!(h.pieces.iter().any(|p| p.kind == limn::analysis::visibility::hlr::LineKind::Silhouette));
/// assert!(h.pieces.iter().filter(|p| p.kind == limn::analysis::visibility::hlr::LineKind::Silhouette)
///     .all(|p| p.qi == Some(0)));
/// # Ok::<(), limn::Error>(())
/// ```
pub fn hidden_lines(model: &Model, view: &View, opts: &HlrOptions) -> Result<HiddenLines, Error> {
    let weld = opts
        .weld
        .unwrap_or_else(|| crate::model::default_weld(model));
    let scene = Scene::new(model, view, weld)?;
    // With a tolerance, the arcs' ends are located finely enough for it.
    let curve = refined_for(&opts.curve, model, opts.tol);
    let sil = silhouette_curves(model, view, &curve, weld, None);
    let mut stats = HlrStats {
        silhouette_unresolved: sil.unresolved.len(),
        escalations: sil.escalations.clone(),
        ..HlrStats::default()
    };
    let mut segments = boundary_segments(&scene);
    let arcs = silhouette_segments(
        &scene,
        &sil,
        &mut segments,
        &opts.curve.ladder,
        &mut stats.escalations,
    );
    let first_chain = segments.len() + arcs.iter().map(|a| a.chain).max().unwrap_or(0) + 1;
    let lines = zero_line_segments(&scene, &sil, &mut segments, &arcs, first_chain);
    segments.extend(arcs);
    segments.extend(lines);
    stats.segments = segments.len();
    // Where segments are not outline (cannot change the QI of what lies behind them), and,
    // when what lies behind them is wanted, where they are proven folds (outline): then
    // decided finely near junctions, and every segment is cut where its role is decided.
    let roles: Vec<[Vec<[f64; 2]>; 2]> = segments
        .par_iter()
        .map(|s| match (opts.clusters, opts.behind) {
            (false, _) => [Vec::new(), Vec::new()],
            (true, false) => [inside_cluster(&scene, s), Vec::new()],
            (true, true) => edge_roles_of(&scene, s),
        })
        .collect();
    let inner: Vec<Vec<[f64; 2]>> = roles.iter().map(|r| r[0].clone()).collect();
    let outline: Vec<bool> = inner.iter().map(|v| v != &[[0.0, 1.0]]).collect();
    let folds: Vec<Vec<[f64; 2]>> = roles.into_iter().map(|[_, f]| f).collect();
    stats.cluster_edges = outline.iter().filter(|o| !**o).count();
    // Whether a segment can change the QI of what crosses behind it at parameters in `at`.
    let outline_at =
        |s: usize, at: [f64; 2]| !inner[s].iter().any(|r| r[0] <= at[0] && at[1] <= r[1]);

    // Pairs of segments (with the boxes around shared vertices proven to hold no other
    // crossing), self-crossings of sides, and segment-patch penetrations.
    let mut events: Vec<Vec<Event>> = vec![Vec::new(); segments.len()];
    // The silhouette regions the curve solver left unresolved are not segments: their
    // crossings with the other lines are not searched, so every segment whose image can meet
    // theirs is unresolved along its whole length.
    let mut blockers: Vec<(usize, DyadicBoxN, String)> = Vec::new();
    for (i, cell, _) in &sil.unresolved {
        let b = vec![(cell.lo[0], cell.hi[0]), (cell.lo[1], cell.hi[1])];
        blockers.push((
            *i,
            b,
            format!("its image may cross the silhouette of patch {i} where the curve solver left it unresolved"),
        ));
    }
    for (p, b, why) in &blockers {
        let bounds = bounds_on(&scene.images[*p], b);
        for (k, sg) in segments.iter().enumerate() {
            if sg.bounds.meets_image(&bounds) {
                events[k].push(Event::unresolved(sg.range, why.clone()));
            }
        }
    }
    let mut jobs: Vec<Job> = Vec::new();
    for (a, sa) in segments.iter().enumerate() {
        // Every vertex inside a segment cuts it (a junction on a side).
        for v in &sa.vertices {
            events[a].push(Event::cut(v.param));
        }
        // With what lies behind wanted, so does every end of a stretch of decided role.
        if opts.behind {
            for r in inner[a].iter().chain(&folds[a]) {
                for x in r.iter().filter(|x| sa.range[0] < **x && **x < sa.range[1]) {
                    events[a].push(Event::cut([*x, *x]));
                }
            }
        }
        match (&sa.constraint, &sa.monotone) {
            // A stretch the surface continues across cannot change its own QI.
            (None, _) if !outline[a] => {}
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
            if !outline[a] && !outline[b] {
                stats.cluster_pairs += 1;
                continue;
            }
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
    // The fold boxes of each silhouette arc, once.
    let covers: Vec<Vec<(DyadicBoxN, DyadicBoxN)>> = segments
        .par_iter()
        .map(|s| {
            if opts.curve.past_deadline() {
                Vec::new()
            } else {
                fold_cover(&scene, s)
            }
        })
        .collect();
    let results: Vec<(Job, SystemRoots, Vec<DyadicBoxN>, bool)> = jobs
        .par_iter()
        .map(|job| {
            if opts.curve.past_deadline() {
                // Not solved: every stretch the system covers is unresolved.
                let domain: Vec<[f64; 2]> = job_domain(&segments, *job)
                    .iter()
                    .map(|d| [d.0.to_f64(), d.1.to_f64()])
                    .collect();
                let r = SystemRoots {
                    unresolved: vec![domain],
                    ..SystemRoots::default()
                };
                return (*job, r, Vec::new(), true);
            }
            let (eqs, domain, exclude) = match *job {
                Job::Pair(a, b) => {
                    let (eqs, domain) = crossing_system(&segments[a], &segments[b]);
                    let mut exclude = arc_fold_exclusion(&segments[a], &segments[b], &covers, a, b);
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
            (*job, r, exclude, false)
        })
        .collect();
    let mut intersecting = std::collections::BTreeSet::new();
    for (job, r, exclude, timed_out) in &results {
        stats.boxes += r.boxes;
        if let Job::Penetration(a, j) = *job {
            for &(p, _, _) in segments[a].on.iter().filter(|_| !r.roots.is_empty()) {
                intersecting.insert([p.min(j), p.max(j)]);
            }
        }
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
        // A crossing cuts a segment only if the other segment can change its QI there.
        let counts = |bx: &[[f64; 2]], s: usize| -> bool {
            match *job {
                Job::Pair(a, b) => {
                    let na = segments[a].domain.len();
                    let (other, k) = if s == a {
                        (b, na + segments[b].axis)
                    } else {
                        (a, segments[a].axis)
                    };
                    outline_at(other, bx[k])
                }
                _ => true,
            }
        };
        for root in &r.roots {
            for &(s, k) in &targets {
                if counts(&root.enclosure, s) {
                    events[s].push(Event::cut(root.enclosure[k]));
                }
            }
        }
        let why = if *timed_out {
            TIME_LIMIT_REASON.to_string()
        } else {
            why
        };
        for bx in &r.unresolved {
            for &(s, k) in &targets {
                if counts(bx, s) {
                    events[s].push(Event::unresolved(bx[k], why.clone()));
                }
            }
        }
    }

    // Pieces, and their QI.
    let draws: Vec<DrawPatch> = model
        .patches
        .iter()
        .map(|p| DrawPatch::new(&p.surface))
        .collect();
    // The accuracy bounds of each patch with a line, for drawing to a tolerance.
    let accuracy: Vec<Option<PatchAccuracy>> = (0..model.patches.len())
        .into_par_iter()
        .map(|i| {
            let used = segments.iter().any(|s| s.patch == i);
            let surface = &model.patches[i].surface;
            opts.tol.filter(|_| used).map(|_| match sil.solved.get(i) {
                Some(solved) => PatchAccuracy::new(surface, &solved.g),
                None => PatchAccuracy::lines_only(surface),
            })
        })
        .collect();
    let per_segment: Vec<(Vec<HlrPiece>, SampleTally)> = segments
        .par_iter()
        .zip(events.par_iter())
        .zip(inner.par_iter().zip(folds.par_iter()))
        .map(|((s, ev), (inner, folds))| {
            let acc = accuracy[s.patch].as_ref();
            pieces_of(&scene, s, ev, &draws[s.patch], acc, [inner, folds], opts)
        })
        .collect();
    let mut pieces = Vec::new();
    for (p, tally) in per_segment {
        pieces.extend(p);
        stats.samples += tally.samples;
        stats.refused_samples += tally.refused;
        stats.escalations.merge(&tally.escalations);
    }
    let facing = model
        .patches
        .par_iter()
        .map(|p| facing(&p.surface, view))
        .collect();
    let mut assumptions = vec![ADJACENT_ASSUMPTION.to_string()];
    if let WeldTolerance::Absolute(d) = weld {
        assumptions.push(weld_assumption(d));
    }
    Ok(HiddenLines {
        pieces,
        facing,
        stats,
        assumptions,
        intersecting_patches: intersecting.into_iter().collect(),
        tolerance: opts.tol,
    })
}

/// The assumption of a tolerance weld: sides matched within `d` are one edge, and a side whose
/// control points lie within `d` of one point is that point (a pole).
pub fn weld_assumption(d: f64) -> String {
    format!(
        "patch sides matched within {d} (--weld) are the same edge, and a side whose control points lie within {d} of one point is taken as that point (a pole): their points are taken as one point of space"
    )
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

/// The variables' box of a job's system.
fn job_domain(segments: &[Segment], job: Job) -> DyadicBoxN {
    let unit = (Dyadic::ZERO, Dyadic::ONE);
    match job {
        Job::Pair(a, b) => segments[a]
            .domain
            .iter()
            .chain(&segments[b].domain)
            .copied()
            .collect(),
        Job::SelfCrossing(a) => segments[a]
            .domain
            .iter()
            .chain(&segments[a].domain)
            .copied()
            .collect(),
        Job::Penetration(a, _) => segments[a]
            .domain
            .iter()
            .copied()
            .chain([unit, unit])
            .collect(),
    }
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

/// The stretches of a segment's parameter across which it is a shared edge and the surface
/// provably continues in the image ([`crate::analysis::visibility::fold_edges`]); empty for other segments.
fn inside_cluster(scene: &Scene, s: &Segment) -> Vec<[f64; 2]> {
    orientations_of(scene, s).map_or_else(Vec::new, |o| continuing_stretches(&o, 6))
}

/// [`crate::analysis::visibility::fold_edges::edge_roles`] of a side shared by two patches (deep near junctions);
/// none for other segments.
fn edge_roles_of(scene: &Scene, s: &Segment) -> [Vec<[f64; 2]>; 2] {
    orientations_of(scene, s).map_or_else(|| [Vec::new(), Vec::new()], |o| edge_roles(&o, 24, 2048))
}

/// The two orientations along a side shared by exactly two patches ([`crate::analysis::visibility::fold_edges`]).
fn orientations_of(scene: &Scene, s: &Segment) -> Option<[Bernstein<Interval>; 2]> {
    if s.kind != LineKind::Boundary || s.line.is_some() {
        return None;
    }
    let users: Option<Vec<(usize, Edge, bool)>> =
        s.on.iter().map(|&(p, e, r)| Some((p, e?, r))).collect();
    edge_orientations(scene, &users?)
}

/// Whether two patches share a corner or an edge.
fn adjacent(scene: &Scene, a: usize, b: usize) -> bool {
    let (ca, cb) = (&scene.adjacency.corners[a], &scene.adjacency.corners[b]);
    ca.iter().any(|x| cb.contains(x))
}
