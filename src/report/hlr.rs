//! The JSON and text report of `limn hlr` (field names are a public contract, see README).

use crate::analysis::view::View;
use crate::analysis::visibility::facing::Facing;
use crate::analysis::visibility::hlr::*;
use crate::surface::Edge;

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
#[non_exhaustive]
pub struct HlrReport {
    /// The model file.
    pub model: String,
    /// The view.
    pub view: serde_json::Value,
    /// Every piece's visibility proven (and, with a tolerance, its drawing within it) and every
    /// silhouette region resolved.
    pub certified: bool,
    /// The tolerance asked for (`--tol`), in model units; `null` if none.
    pub tolerance: Option<f64>,
    /// With a tolerance: the largest proven drawing error of any piece (`null` if some piece's
    /// drawing is not bounded).
    pub largest_error: Option<f64>,
    /// The pieces.
    pub pieces: Vec<HlrPiece>,
    /// The pieces whose visibility is not proven.
    pub unresolved: Vec<UnresolvedPiece>,
    /// Per patch, its self-visible type.
    pub facing: Vec<Facing>,
    /// Work counts.
    pub stats: HlrStats,
    /// What the result assumes without proof.
    pub assumptions: Vec<String>,
    /// Pairs of patches proven to intersect (their intersection curve is not drawn).
    pub intersecting_patches: Vec<[usize; 2]>,
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
            tolerance: h.tolerance,
            largest_error: h.largest_error(),
            unresolved: h
                .pieces
                .iter()
                .filter(|p| !p.certified)
                .map(|p| UnresolvedPiece {
                    kind: p.kind,
                    patch: p.patch,
                    edge: p.edge,
                    param: p.param,
                    reason: p.reason.as_ref().map(|r| r.to_string()).unwrap_or_default(),
                })
                .collect(),
            pieces: h.pieces.clone(),
            facing: h.facing.clone(),
            stats: h.stats.clone(),
            assumptions: h.assumptions.clone(),
            intersecting_patches: h.intersecting_patches.clone(),
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
        match self.tolerance {
            Some(tol) => {
                let unbounded = count(&|p| p.error_bound.is_none());
                t += &match self.largest_error {
                    Some(e) => format!(
                        "accuracy: every piece drawn within {e:.3e} of the true line (tolerance {tol:.3e})\n"
                    ),
                    None => format!(
                        "accuracy: tolerance {tol:.3e}; {unbounded} pieces not proven within it\n"
                    ),
                }
            }
            None => t += "accuracy: the drawn points are not bounded (no tolerance asked)\n",
        }
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
        if s.trim_segments > 0 || s.outside_faces > 0 {
            t += &format!(
                "trimmed faces: {} trimming-curve segments, {} crossings with sides and silhouettes, {} pieces outside the faces left out\n",
                s.trim_segments, s.trim_crossings, s.outside_faces
            );
        }
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
        if !self.intersecting_patches.is_empty() {
            let pairs: Vec<String> = self
                .intersecting_patches
                .iter()
                .map(|[a, b]| format!("{a}-{b}"))
                .collect();
            let drawn = count(&|p| p.kind == LineKind::Intersection);
            let how = if self.stats.intersection_pairs == 0 {
                "their intersection curves are not drawn".to_string()
            } else {
                format!(
                    "their intersection curves drawn: {drawn} pieces, {} certified",
                    count(&|p| p.kind == LineKind::Intersection && p.certified)
                )
            };
            t += &format!("intersecting patches ({how}): {}\n", pairs.join(", "));
        }
        for a in &self.assumptions {
            t += &format!("assumed: {a}\n");
        }
        t += &format!("time: {:.1} ms on {} threads\n", self.time_ms, self.threads);
        t
    }
}
