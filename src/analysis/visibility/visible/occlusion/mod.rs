//! Occlusion curves: where a visible outline piece hides the surface right behind it
//! (paper 000, section 4, made certified: `proofs/visible-regions.md`, claim 4).
//!
//! A visible piece of the outline (a silhouette, a free side or a fold edge, QI 0) has, on
//! the ray through each of its points, a first surface point behind it. On the far side of
//! the piece in the image that point is visible, on the near side it is hidden by the piece's
//! own sheet: the curve these points trace is a boundary of the visible region of the surface
//! behind. The hidden-line drawing finds the first point behind at one sample of the piece
//! ([`crate::analysis::visibility::hlr::Behind`]); between its cuts no outline crosses the piece in the
//! image, so that sheet stays first behind all along it (claim 4 (c)).
//!
//! The curve is followed from the sample along the piece's drawn polyline: each drawn point's
//! image is lifted onto the patch behind by Newton's method, crossing to the next patch where
//! the lift leaves one across a continuing edge (a *window* proven on both patches, (f)). It
//! is certified with the piece's own proven drawing error `e` (every chord within `e` of its
//! stretch of the true piece, pointwise): Krawczyk's operator with the image point as an
//! interval parameter proves, for each chord's tube, a parameter box `W` that holds exactly
//! one preimage of every image point of the tube (d), chained from the sample's point behind
//! through the boxes of the vertices. The distance between the true curve and the drawn chord
//! is then bounded by the piece's error lifted through the inverse Jacobian over `W`, plus the
//! second-order terms of the chord (e). Near a fold of the surface behind the first term grows
//! without bound: those stretches are reported with their bound, or unproven.

mod lift;
mod prove;
mod walk;

pub(crate) use lift::LiftPatch;
pub(crate) use prove::Anchor;

use crate::analysis::visibility::scene::Scene;
use crate::model::Model;
use crate::reason::Reason;
use crate::surface::DrawPatch;
use rayon::prelude::*;

/// An occlusion curve on one patch: a stretch of the lift of a visible outline piece.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct OcclusionRun {
    /// The patch the curve lies on (the surface right behind the piece).
    pub patch: usize,
    /// Its points (u, v) on that patch (in its square).
    pub uv: Vec<[f64; 2]>,
    /// The same points in space.
    pub xyz: Vec<[f64; 3]>,
    /// A proven bound on the Hausdorff distance in space between the drawn polyline and the
    /// true curve on this patch, or `None`.
    pub error_bound: Option<f64>,
    /// Why it is not certified, if it is not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Reason>,
}

/// What lifting needs of the scene: per patch its lifting polynomials and its drawing
/// evaluator.
pub(crate) struct Lifting<'a> {
    pub scene: &'a Scene,
    pub patches: Vec<LiftPatch>,
    pub draws: Vec<DrawPatch>,
}

impl<'a> Lifting<'a> {
    /// Converts (once) every patch of the model.
    pub(crate) fn new(model: &Model, scene: &'a Scene) -> Lifting<'a> {
        Lifting {
            scene,
            patches: (0..model.patches.len())
                .into_par_iter()
                .map(|j| LiftPatch::new(scene, &model.patches[j].surface, j))
                .collect(),
            draws: model
                .patches
                .iter()
                .map(|p| DrawPatch::new(&p.surface))
                .collect(),
        }
    }
}
