//! Silhouettes (contour generators) of rational Bézier models, with certified topology.
//!
//! For a patch with unnormalized normal Ñ (a positive multiple of S_u × S_v), the silhouette
//! function is `g = Ñ · V` for a parallel view direction V (front-facing where g < 0), or
//! `g = Ñ · (E W − P)` for a perspective eye E, with `P = [wx, wy, wz]` and W the weight
//! (front-facing where g > 0). Both are exact polynomials; the silhouette is `g = 0`, solved
//! per patch and joined across shared edges where the join is proven, by the model-level
//! curve machinery ([`model_curves`], `proofs/silhouette-join.md`).

use crate::bernstein::Bernstein;
use crate::model::{Model, WeldTolerance};
use crate::number::{Number, Rational};
use crate::solver::{CurveOptions, Escalations};
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;
use std::collections::BTreeMap;

pub use super::model_curves::{
    deflate_side, deflate_side_counted, eval_f64, model_curves, CurveRules, Degenerate, DrawPatch,
    Silhouette, SilhouetteCurve, SingularPoint, SolvedPatch,
};

/// A view: parallel direction (from the viewer into the scene) or perspective eye point.
#[derive(Clone, Debug, PartialEq)]
pub enum View {
    /// Parallel projection along this direction.
    Direction([Rational; 3]),
    /// Perspective from this eye point.
    Eye([Rational; 3]),
}

/// The silhouette function of a patch for a view (exact).
///
/// # Examples
/// ```
/// use limn::analysis::silhouette::{silhouette_function, View};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let patch = &shapes::sphere(&Rational::from(1))[0];
/// let z = Rational::new();
/// let g = silhouette_function(patch, &View::Direction([z.clone(), z, Rational::from(1)]));
/// assert_eq!(g.nvars(), 2);
/// ```
pub fn silhouette_function(patch: &RationalPatch, view: &View) -> Bernstein<Rational> {
    let n = patch.normal();
    match view {
        View::Direction(d) => {
            let terms: Vec<Bernstein<Rational>> = (0..3).map(|k| n[k].scale(&d[k])).collect();
            (&(&terms[0] + &terms[1]) + &terms[2]).reduce_degree_exact()
        }
        View::Eye(e) => {
            let [px, py, pz, w] = patch.homogeneous();
            let p = [px, py, pz];
            let mut sum: Option<Bernstein<Rational>> = None;
            for k in 0..3 {
                let to_eye = &w.scale(&e[k]) - &p[k];
                let term = &n[k] * &to_eye;
                sum = Some(match sum {
                    None => term,
                    Some(s) => &s + &term,
                });
            }
            sum.expect("three terms").reduce_degree_exact()
        }
    }
}

/// Computes the silhouette of a model's patches for a view.
///
/// Patches are solved in parallel (rayon); the result does not depend on the thread count.
/// Shared edges are found with `weld` (see [`crate::model::PatchAdjacency`]).
pub fn silhouette(
    model: &Model,
    view: &View,
    opts: &CurveOptions,
    weld: WeldTolerance,
    tol: Option<f64>,
) -> Silhouette {
    let gs: Vec<Bernstein<Rational>> = model
        .patches
        .par_iter()
        .map(|p| silhouette_function(&p.surface, view))
        .collect();
    let rules = CurveRules {
        parallel_normal_joins: true,
        whole_patch: "edge-on",
        whole_side: "silhouette side",
        whole_line: "silhouette line",
    };
    model_curves(model, gs, &rules, opts, weld, tol)
}

/// Parses "x,y,z" into an exact view vector.
///
/// # Errors
/// A message if the text is not three numbers or is the zero vector.
pub fn parse_vector(text: &str) -> Result<[Rational; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers x,y,z, found {text:?}"));
    }
    let mut v = Vec::with_capacity(3);
    for p in parts {
        v.push(crate::number::parse_exact(p).map_err(|e| format!("{text:?}: {e}"))?);
    }
    let v: [Rational; 3] = v.try_into().map_err(|_| "three numbers".to_string())?;
    Ok(v)
}

impl View {
    /// The view as JSON: `{"dir": [x, y, z]}` or `{"eye": [x, y, z]}` (f64).
    pub fn to_json(&self) -> serde_json::Value {
        let v = |x: &[Rational; 3]| x.clone().map(|c| c.to_f64());
        match self {
            View::Direction(d) => serde_json::json!({ "dir": v(d) }),
            View::Eye(e) => serde_json::json!({ "eye": v(e) }),
        }
    }

    /// Whether a direction view is the zero vector (meaningless).
    pub fn is_degenerate(&self) -> bool {
        match self {
            View::Direction(d) => d.iter().all(|c| c.sign().is_zero()),
            View::Eye(_) => false,
        }
    }
}

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
        method: super::baseline::BaselineMethod,
        curves: Vec<SilhouetteCurve>,
        time_ms: f64,
    ) -> SilhouetteReport {
        let mut r =
            SilhouetteReport::new(model, view, &Silhouette::from_curves(curves), time_ms, 1);
        r.topology_certified = false;
        r.method = match method {
            super::baseline::BaselineMethod::Mesh => "mesh",
            super::baseline::BaselineMethod::SrfNode => "srf-node",
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

    /// The report of a run of [`model_curves`] for the curve family `kind`, with the view it
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
        let topology_certified = s.unresolved.is_empty()
            && s.unjoined_edges.is_empty()
            && s.curves.iter().all(|c| c.certified_topology);
        SilhouetteReport {
            model: model.to_string(),
            kind: kind.to_string(),
            method: "certified".to_string(),
            view,
            certified: topology_certified
                && s.curves.iter().all(|c| c.certified)
                && s.tolerance.is_some(),
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

#[cfg(test)]
mod tests {
    use super::super::model_curves::{parallel_normals, proportional, side_polynomial};
    use super::*;

    fn quad(p: [[i64; 3]; 4]) -> RationalPatch {
        let q = |v: [i64; 3]| v.map(Rational::from);
        RationalPatch::polynomial([1, 1], p.into_iter().map(q).collect()).unwrap()
    }

    /// Two patches of one plane, the second not a parallelogram: their normals along the
    /// shared edge are parallel with a varying ratio (1 + v), so the silhouette functions are
    /// not proportional but the join is still proven; lifting the far side makes a crease.
    #[test]
    fn parallel_normals_join_tangent_continuous_edges_only() {
        let a = quad([[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]);
        let b = quad([[1, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0]]);
        assert!(parallel_normals(&a, Edge::U1, &b, Edge::U0, false));
        let v = View::Direction([Rational::from(1), Rational::from(2), Rational::from(3)]);
        let (ga, gb) = (silhouette_function(&a, &v), silhouette_function(&b, &v));
        assert!(!proportional(
            &side_polynomial(&ga, Edge::U1),
            &side_polynomial(&gb, Edge::U0),
            false
        ));
        let creased = quad([[1, 0, 0], [1, 1, 0], [2, 0, 1], [3, 1, 1]]);
        assert!(!parallel_normals(&a, Edge::U1, &creased, Edge::U0, false));
        // Opposite parameter directions are handled by the reversal flag.
        let flipped = quad([[1, 1, 0], [1, 0, 0], [3, 1, 0], [2, 0, 0]]);
        assert!(parallel_normals(&a, Edge::U1, &flipped, Edge::U0, true));
    }
}
