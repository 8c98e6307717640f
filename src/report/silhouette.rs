//! The JSON and text report of `limn silhouette` and `limn curves --kind parabolic` (field
//! names are a public contract: `docs/commands/silhouette.md`).

use crate::analysis::contour::curves::{Degenerate, Silhouette, SilhouetteCurve, SingularPoint};
use crate::analysis::view::View;
use crate::solver::Escalations;
use crate::surface::Edge;
use std::collections::BTreeMap;

/// Undecided regions of one patch, summarised: how many boxes, the hull of their boxes.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct UnresolvedSummary {
    /// The patch.
    pub patch: usize,
    /// The number of unresolved boxes.
    pub boxes: usize,
    /// The (u, v) hull `[[u0, v0], [u1, v1]]` of those boxes.
    pub hull: [[f64; 2]; 2],
    /// Why (the reason of the first box).
    pub reason: String,
}

/// The JSON document of `limn silhouette --format json` (field names are a public contract,
/// see README).
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct SilhouetteReport {
    /// The model file.
    pub model: String,
    /// The curve family: "silhouette", "parabolic".
    pub kind: String,
    /// "certified", or an uncertified float baseline: "mesh", "srf-node".
    pub method: String,
    /// `{"dir": [x, y, z]}` or `{"eye": [x, y, z]}`, as f64 (absent for curves that do not
    /// depend on a view).
    #[serde(skip_serializing_if = "serde_json::Value::is_null")]
    pub view: serde_json::Value,
    /// Whether the whole answer is certified: topology proven and every drawn segment within
    /// `tolerance` of the true curve.
    pub certified: bool,
    /// The world-space tolerance the drawing was certified against (absent: not asked).
    pub tolerance: Option<f64>,
    /// Whether the topology of every curve is proven (no unresolved region, every join proven).
    pub topology_certified: bool,
    /// The curves.
    pub curves: Vec<SilhouetteCurve>,
    /// Points where three or more arcs meet, with how many.
    pub singular_points: Vec<SingularPoint>,
    /// Undecided regions, per patch.
    pub unresolved: Vec<UnresolvedSummary>,
    /// Shared edges across which curves could not be joined with proof.
    pub unjoined_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Shared edges where curves end, proven (the function jumps across them).
    pub ending_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Degenerate cases recognised exactly.
    pub degenerate: Vec<Degenerate>,
    /// Work done.
    pub stats: SilhouetteStats,
}

/// Work counters of a silhouette run.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct SilhouetteStats {
    /// Boxes examined.
    pub boxes: usize,
    /// Sign questions settled at each precision level.
    pub escalations: Escalations,
    /// Wall time in milliseconds.
    pub time_ms: f64,
    /// Worker threads.
    pub threads: usize,
}

impl SilhouetteReport {
    /// The report of an uncertified float baseline (paper 002): curves per patch, nothing
    /// proven (`certified` and `topology_certified` are false).
    pub fn baseline(
        model: &str,
        view: &View,
        method: crate::analysis::contour::baseline::BaselineMethod,
        curves: Vec<SilhouetteCurve>,
        time_ms: f64,
    ) -> SilhouetteReport {
        let mut r =
            SilhouetteReport::new(model, view, &Silhouette::from_curves(curves), time_ms, 1);
        r.topology_certified = false;
        r.method = match method {
            crate::analysis::contour::baseline::BaselineMethod::Mesh => "mesh",
            crate::analysis::contour::baseline::BaselineMethod::SrfNode => "srf-node",
        }
        .to_string();
        r
    }

    /// The report of a silhouette run.
    pub fn new(
        model: &str,
        view: &View,
        s: &Silhouette,
        time_ms: f64,
        threads: usize,
    ) -> SilhouetteReport {
        SilhouetteReport::of_curves(model, "silhouette", view.to_json(), s, time_ms, threads)
    }

    /// The report of a run of [`model_curves`](crate::analysis::contour::family::model_curves) for the curve family `kind`, with the view it
    /// depends on (JSON null if none).
    pub fn of_curves(
        model: &str,
        kind: &str,
        view: serde_json::Value,
        s: &Silhouette,
        time_ms: f64,
        threads: usize,
    ) -> SilhouetteReport {
        let mut per_patch: BTreeMap<usize, UnresolvedSummary> = BTreeMap::new();
        for (p, cell, reason) in &s.unresolved {
            let [lo, hi] = cell.to_f64();
            let e = per_patch.entry(*p).or_insert_with(|| UnresolvedSummary {
                patch: *p,
                boxes: 0,
                hull: [lo, hi],
                reason: reason.clone(),
            });
            e.boxes += 1;
            for k in 0..2 {
                e.hull[0][k] = e.hull[0][k].min(lo[k]);
                e.hull[1][k] = e.hull[1][k].max(hi[k]);
            }
        }
        let topology_certified = s.topology_certified();
        SilhouetteReport {
            model: model.to_string(),
            kind: kind.to_string(),
            method: "certified".to_string(),
            view,
            certified: s.certified(),
            tolerance: s.tolerance,
            topology_certified,
            curves: s.curves.clone(),
            singular_points: s.singular_points.clone(),
            unresolved: per_patch.into_values().collect(),
            unjoined_edges: s.unjoined_edges.clone(),
            ending_edges: s.ending_edges.clone(),
            degenerate: s.degenerate.clone(),
            stats: SilhouetteStats {
                boxes: s.boxes,
                escalations: s.escalations.clone(),
                time_ms,
                threads,
            },
        }
    }
}
