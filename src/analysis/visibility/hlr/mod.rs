//! Certified hidden-line drawings of rational Bézier models (paper 000, extended to any model).
//!
//! The lines of the drawing are the patch boundaries (each shared edge once) and the
//! silhouette arcs of the certified silhouette ([`crate::analysis::contour::silhouette`]). Along
//! a line the number of surface layers in front of it (its QI) can change only where, in the
//! image, it crosses another line that is outline (a silhouette or a boundary across which the
//! surface does not continue), where it crosses itself, or where it passes through a patch
//! (a penetration). [`hidden_lines`] is a forward pipeline of four stages, one module each,
//! every stage's output the next one's input:
//!
//! 1. `lines.rs`: the candidate lines, cut into segments whose images are monotone,
//!    with the vertices where lines meet in space (patch corners, silhouette junctions on
//!    sides, cut points);
//! 2. `roles.rs`: which stretches of each segment are outline: a shared
//!    edge across which the surface provably continues in the image is inside a cluster
//!    (paper 000, section 4) and cannot change the QI of what lies behind it;
//! 3. `crossings.rs`: every pair of segments whose image boxes meet, every side's
//!    self-crossings, every segment against every patch that shares no corner with its own,
//!    solved as square systems (`systems.rs`) by the certified system solver, with the boxes
//!    around shared vertices and folds excluded by the lemmas of `proofs/hidden-lines.md`
//!    (`lemmas.rs`); the result is a list of events (cuts and unresolved
//!    stretches) per segment;
//! 4. `pieces.rs`: each segment cut at its events into pieces; between cuts the QI is
//!    constant (`proofs/hidden-lines.md`, claim 1) and is found by one certified ray test
//!    ([`crate::analysis::visibility::ray::layers_in_front`]) at a sample point (others are tried
//!    if one is refused); each piece is drawn (`drawing.rs`), to a tolerance with a bound.
//!
//! What is not proven is reported: unresolved pieces (with the reason), silhouette regions the
//! curve solver did not resolve, and the assumption that adjacent patches do not cross each
//! other (penetrations are searched between non-adjacent patches only).

mod crossings;
mod cusps;
mod drawing;
mod intersection_lines;
mod lemmas;
mod lines;
mod pieces;
mod result;
mod roles;
mod systems;
mod trim_lines;

pub use result::{Behind, HiddenLines, HlrPiece, HlrStats, LineKind, ADJACENT_ASSUMPTION};

use crossings::crossings;
use intersection_lines::{intersection_lines, silhouette_meets};
use lines::candidate_lines;
use pieces::all_pieces;
use roles::line_roles;
use trim_lines::{brep_neighbours, trim_lines};

use crate::analysis::contour::drawing::refined_for;
use crate::analysis::contour::silhouette::silhouette_curves;
use crate::analysis::frame::Frame;
use crate::analysis::view::View;
use crate::analysis::visibility::facing::{facing, Facing};
use crate::analysis::visibility::ray::RayOptions;
use crate::analysis::visibility::scene::Scene;
use crate::error::Error;
use crate::model::{Model, WeldTolerance};
use crate::solver::precision::{Escalations, Policy};
use crate::solver::system::SystemOptions;
use crate::solver::CurveOptions;
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
    /// Restrict every patch to the trimmed faces of its surface ([`Model::faces`]): the
    /// trimming curves are lines, every other line is drawn only inside the faces, and ray
    /// tests count only points inside them. Off: every surface whole (as the visible
    /// regions still take it).
    pub trims: bool,
    /// Draw the curves where patches that share no corner pass through each other
    /// ([`crate::analysis::intersection`]) as lines of kind [`LineKind::Intersection`]. Off:
    /// they are not drawn (as the visible regions take the drawing).
    pub intersections: bool,
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
                ..SystemOptions::default()
            },
            draw_steps: 8,
            tol: None,
            clusters: true,
            behind: false,
            weld: None,
            trims: true,
            intersections: true,
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
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    let h = drawing(&frame.model(model), &frame.view(view), opts)?;
    Ok(h.in_model_frame(&frame, opts.tol))
}

/// [`hidden_lines`] of the model as it is given.
fn drawing(model: &Model, view: &View, opts: &HlrOptions) -> Result<HiddenLines, Error> {
    let weld = opts
        .weld
        .unwrap_or_else(|| crate::model::default_weld(model));
    let mut scene = Scene::new(model, view, weld)?;
    if opts.trims {
        scene = scene.with_faces(model, trim_contact(model, weld));
    }
    // With a tolerance, the arcs' ends are located finely enough for it.
    let curve = refined_for(&opts.curve, model, opts.tol);
    let sil = silhouette_curves(
        model,
        view,
        &curve,
        weld,
        None,
        crate::analysis::contour::family::Faces::Untrimmed,
    );
    let mut stats = HlrStats {
        silhouette_unresolved: sil.unresolved.len(),
        escalations: sil.escalations.clone(),
        ..HlrStats::default()
    };
    // 1. The candidate lines, cut into segments.
    let mut policy =
        Policy::new(&opts.curve.ladder, &mut stats.escalations).with_deadline(opts.curve.deadline);
    let mut segments = candidate_lines(&scene, &sil, &mut policy);
    // 1b. The trimming curves, and the other lines cut where they cross them.
    let first_chain = segments.iter().map(|s| s.chain + 1).max().unwrap_or(0);
    let mut next_id = 1 << 40;
    let trims = trim_lines(
        &scene,
        model,
        &sil,
        &mut segments,
        first_chain,
        &mut next_id,
        &mut policy,
    );
    stats.trim_segments = trims.segments.len();
    stats.trim_crossings = trims.crossings;
    segments.extend(trims.segments);
    // The faces around a B-rep face meet it only along their common edges and vertices.
    let neighbours = brep_neighbours(model);
    for s in &mut segments {
        for (p, _, _) in &s.on {
            for q in neighbours.get(*p).into_iter().flatten() {
                if !s.touches.contains(q) {
                    s.touches.push(*q);
                }
            }
        }
    }
    // 1c. The curves where patches pass through each other.
    // A file that states faces or a B-rep says its faces meet only along their edges (the
    // trim assumption): the curves where their untrimmed surfaces cross are not searched.
    let mut meets_unresolved = Vec::new();
    if opts.intersections && model.faces.is_empty() && model.brep.is_none() {
        let first_chain = segments.iter().map(|s| s.chain + 1).max().unwrap_or(0);
        let boundary = scene.adjacency.edges.len();
        let meets = intersection_lines(
            &scene,
            model,
            &mut segments[..boundary],
            first_chain,
            opts.curve.deadline,
        );
        stats.intersection_pairs = meets.pairs;
        stats.intersection_segments = meets.segments.len();
        stats.intersection_unresolved = meets.unresolved.len();
        let first = segments.len();
        segments.extend(meets.segments);
        meets_unresolved = meets.unresolved;
        let range = first..segments.len();
        stats.intersection_folds = silhouette_meets(&sil, &mut segments, range, &mut next_id);
    }
    stats.segments = segments.len();
    // 2. Which stretches of them are outline.
    let roles = line_roles(&scene, &segments, opts);
    stats.cluster_edges = roles.cluster_edges();
    // 3. Where the QI along them can change.
    let mut found = crossings(&scene, &sil, &segments, &roles, opts, &mut stats);
    for (k, e) in trims.events {
        found.events[k].push(e);
    }
    // 4. The pieces between, their QI, drawn.
    let mut pieces = all_pieces(
        model,
        &scene,
        &sil,
        &segments,
        &found.events,
        &roles,
        opts,
        &mut stats,
    );
    pieces.extend(meets_unresolved);
    let typed: Vec<(Facing, Escalations)> = model
        .patches
        .par_iter()
        .map(|p| {
            let mut counts = Escalations::default();
            let f = facing(
                &p.surface,
                view,
                &mut Policy::new(&opts.curve.ladder, &mut counts),
            );
            (f, counts)
        })
        .collect();
    let mut facing_types = Vec::with_capacity(typed.len());
    for (f, counts) in typed {
        facing_types.push(f);
        stats.escalations.merge(&counts);
    }
    let mut assumptions = vec![ADJACENT_ASSUMPTION.to_string()];
    assumptions.extend(scene.contact_assumption());
    if let WeldTolerance::Absolute(d) = weld {
        assumptions.push(weld_assumption(d));
    }
    if scene.faces.iter().any(Option::is_some) {
        assumptions.push(trim_assumption(
            scene.trim_contact,
            model.inversion_distance(),
        ));
    }
    assumptions.extend(model.reader_assumptions());
    Ok(HiddenLines {
        pieces,
        facing: facing_types,
        stats,
        assumptions,
        intersecting_patches: found.intersecting.into_iter().collect(),
        tolerance: opts.tol,
    })
}

/// How near another face a point of a trimming curve is taken to lie on it: the weld
/// distance, and at least 2^-30 of the model's diagonal (exact data meet exactly, and no
/// interval test can prove a distance of zero), and at least `2√3` times the bound of the
/// curves inverted from model-space edges (the curves of one edge on its two faces are each
/// within the bound of the edge in the max norm, so within twice of each other, and `√3` times
/// that in the Euclidean distance the contact test measures; `proofs/edge-inversion.md`).
fn trim_contact(model: &Model, weld: WeldTolerance) -> f64 {
    let floor = model.diagonal() * 2f64.powi(-30);
    let d = match weld {
        WeldTolerance::Absolute(d) => d.max(floor),
        WeldTolerance::Exact => floor,
    };
    d.max(2.0 * 3f64.sqrt() * model.inversion_distance())
}

/// The assumption of a drawing on trimmed faces with contact distance `d`, some of whose
/// trimming curves were inverted from model-space edges within `inverted` (0: none).
pub fn trim_assumption(d: f64, inverted: f64) -> String {
    let made = if inverted > 0.0 {
        format!(" (where the file gives an edge only in model space, limn's curve on the face is proven within {inverted:.3e} of it, and the face is the region that curve bounds)")
    } else {
        String::new()
    };
    format!(
        "faces meet only along the trimming curves the file gives them{made} (the curves of a B-rep edge on its faces are one curve in space: it is drawn once and not searched for penetrations of the faces it bounds; the lines of a B-rep face are not searched for penetrations of the faces that share an edge or a vertex with it), and a point of a trimming curve is the same point as any point of another face within {d:.3e} of it (the faces meet there)"
    )
}

/// The assumption of a tolerance weld: sides matched within `d` are one edge, and a side whose
/// control points lie within `d` of one point is that point (a pole).
pub fn weld_assumption(d: f64) -> String {
    format!(
        "patch sides matched within {d:.3e} (--weld) are the same edge, and a side whose control points lie within {d:.3e} of one point is taken as that point (a pole): their points are taken as one point of space"
    )
}
