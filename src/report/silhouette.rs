//! The JSON and text report of `limn silhouette` and `limn curves --kind parabolic` (field
//! names are a public contract: `docs/commands/silhouette.md`).

use crate::analysis::contour::curves::{
    Degenerate, Silhouette, SilhouetteCurve, SingularPoint, TrimSummary,
};
use crate::analysis::view::View;
use crate::geometry::Rect;
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
    /// The (u, v) hull of those boxes, written by its corners `[[u0, v0], [u1, v1]]`.
    pub hull: Rect,
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
    /// What clipping to the model's trimmed faces did (absent when the model has none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trims: Option<TrimSummary>,
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
    /// The text summary.
    pub fn text(&self) -> String {
        let r = self;
        let mut t = String::new();
        let closed = r.curves.iter().filter(|c| c.closed).count();
        t += &format!("model: {}\n", r.model);
        if r.method != "certified" {
            t += &format!(
                "method: {} (uncertified float baseline of paper 002: nothing is proven)\n",
                r.method
            );
        }
        if r.view.is_null() {
            t += &format!("kind: {}\n", r.kind);
        } else {
            t += &format!("view: {}\n", r.view);
        }
        t += &format!(
            "curves: {} ({} closed); topology {}\n",
            r.curves.len(),
            closed,
            if r.topology_certified {
                "certified"
            } else {
                "NOT fully certified (see unresolved / unjoined)"
            }
        );
        if r.method == "certified" {
            let worst = r
                .curves
                .iter()
                .filter_map(|c| c.error_bound)
                .fold(0.0f64, f64::max);
            match r.tolerance {
                Some(tol) if r.certified => t += &format!("accuracy: certified, every segment within {worst:.3e} of the true curve (tolerance {tol:.3e})\n"),
                Some(tol) => t += &format!("accuracy: tolerance {tol:.3e}; not certified for every curve (see the curves)\n"),
                None => t += "accuracy: not bounded (no tolerance asked)\n",
            }
            if r.tolerance.is_some() {
                let n: usize = r.curves.iter().map(|c| c.cubics.len()).sum();
                let covered = r.curves.iter().filter(|c| c.cubic_bound.is_some()).count();
                let worst = r
                    .curves
                    .iter()
                    .filter_map(|c| c.cubic_bound)
                    .fold(0.0f64, f64::max);
                t += &format!(
                    "cubics: {n} certified cubic pieces, {covered} of {} curves covered, each within {worst:.3e}\n",
                    r.curves.len()
                );
            }
        }
        for (i, c) in r.curves.iter().enumerate() {
            t += &format!(
                "  curve {i}: {} points, patches {:?}, {}{}\n",
                c.points.len(),
                c.patches,
                if c.closed { "closed" } else { "open" },
                if c.certified_topology {
                    ""
                } else {
                    ", topology not certified"
                }
            );
        }
        for p in r.singular_points.iter().filter(|p| p.branches == 0) {
            t += &format!(
                "isolated point of the curve: [{:.6}, {:.6}, {:.6}] (the collapsed side of patch {} through ({:.6}, {:.6}))\n",
                p.point[0], p.point[1], p.point[2], p.patch, p.uv[0], p.uv[1]
            );
        }
        for p in r.singular_points.iter().filter(|p| p.branches > 0) {
            t += &format!(
                "singular point: patch {} at ({:.6}, {:.6}), {} arcs meet ({}), point [{:.6}, {:.6}, {:.6}]\n",
                p.patch,
                p.uv[0],
                p.uv[1],
                p.branches,
                if p.exact { "exact" } else { "isolated" },
                p.point[0],
                p.point[1],
                p.point[2]
            );
        }
        for u in &r.unresolved {
            t += &format!(
                "unresolved: patch {}, {} boxes in [{:.6}, {:.6}] x [{:.6}, {:.6}]: {}\n",
                u.patch, u.boxes, u.hull.lo[0], u.hull.hi[0], u.hull.lo[1], u.hull.hi[1], u.reason
            );
        }
        for e in &r.unjoined_edges {
            t += &format!("unjoined edge: patch {} {:?} / patch {} {:?} (no proven join: the two patches' functions are not proportional there (nor, for silhouettes, the normals parallel), and their zeros on it are not proven apart; or the curve meets a side on which it lies at a point known only within an interval; or the time limit was reached before the edge was examined)\n", e.0, e.1, e.2, e.3);
        }
        if !r.ending_edges.is_empty() {
            t += &format!(
                "edges where curves end: {} (the function jumps across them; crossings common to both patches are joined, every other is proven not to be a zero of the other patch's function)\n",
                r.ending_edges.len()
            );
        }
        let mut kinds: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
        for d in &r.degenerate {
            *kinds.entry(d.kind).or_default() += 1;
        }
        for (k, n) in kinds {
            t += &format!("degenerate: {n} x {k}\n");
        }
        if let Some(c) = &r.trims {
            t += &format!(
                "trimmed faces: {} (curves clipped to them: {} crossings with trimming curves, {} arcs outside dropped, {} curve ends on trimming curves)\n",
                c.faces, c.crossings, c.dropped_arcs, c.trim_ends
            );
        }
        t += &format!(
            "stats: {} boxes, {} sign questions escalated beyond f64, {:.1} ms on {} threads\n",
            r.stats.boxes,
            r.stats.escalations.escalated(),
            r.stats.time_ms,
            r.stats.threads
        );
        t
    }

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
            let cell = cell.to_f64();
            let e = per_patch.entry(*p).or_insert_with(|| UnresolvedSummary {
                patch: *p,
                boxes: 0,
                hull: cell,
                reason: reason.to_string(),
            });
            e.boxes += 1;
            e.hull = e.hull.hull(&cell);
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
            trims: s.trims.clone(),
            stats: SilhouetteStats {
                boxes: s.boxes,
                escalations: s.escalations.clone(),
                time_ms,
                threads,
            },
        }
    }
}
