//! The JSON and text report of `limn visible` (field names are a public contract, see README).

use crate::analysis::view::View;
use crate::analysis::visibility::visible::*;
use std::collections::BTreeMap;

/// The JSON document of `limn visible --format json`.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct VisibleReport {
    /// The model file.
    pub model: String,
    /// The view.
    pub view: serde_json::Value,
    /// Every cell of every patch decided.
    pub certified: bool,
    /// Bounds on the visible share of the model's surface area.
    pub area_fraction: [f64; 2],
    /// Per patch (without `cells` unless asked for).
    pub patches: Vec<PatchRegion>,
    /// Work counts.
    pub stats: VisibleStats,
    /// What the result assumes without proof.
    pub assumptions: Vec<String>,
    /// Visible outline pieces whose occlusion curve was not found (the trimming loops of the
    /// patch behind them are incomplete).
    pub missing_occlusions: Vec<MissingOcclusion>,
    /// Pairs of patches proven to intersect (their intersection curve is not a trimming
    /// curve).
    pub intersecting_patches: Vec<[usize; 2]>,
    /// Wall time in milliseconds.
    pub time_ms: f64,
    /// Worker threads.
    pub threads: usize,
}

impl VisibleReport {
    /// The report of a result; the leaf cells are kept only if `cells`.
    pub fn new(
        model: &str,
        view: &View,
        r: &VisibleRegions,
        cells: bool,
        time_ms: f64,
        threads: usize,
    ) -> VisibleReport {
        let mut patches = r.patches.clone();
        if !cells {
            for p in &mut patches {
                p.cells.clear();
            }
        }
        VisibleReport {
            model: model.to_string(),
            view: view.to_json(),
            certified: r.is_certified(),
            area_fraction: r.area_fraction,
            patches,
            stats: r.stats.clone(),
            assumptions: r.assumptions.clone(),
            missing_occlusions: r.missing_occlusions.clone(),
            intersecting_patches: r.intersecting_patches.clone(),
            time_ms,
            threads,
        }
    }

    /// A short text summary: one line per patch.
    pub fn text(&self) -> String {
        let mut t = format!("model: {}\n", self.model);
        t += &format!(
            "visible share of the surface area: [{:.4}, {:.4}]; {}\n",
            self.area_fraction[0],
            self.area_fraction[1],
            if self.certified {
                "every cell decided"
            } else {
                "NOT every cell decided (the true share lies in the bounds)"
            }
        );
        t += "patch  type       area share        square share      cells (visible/hidden/unresolved)\n";
        for p in &self.patches {
            let kind = serde_json::to_value(p.facing)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default();
            t += &format!(
                "{:>5}  {:<9}  [{:.4}, {:.4}]  [{:.4}, {:.4}]  {}/{}/{}\n",
                p.patch,
                kind,
                p.area_fraction[0],
                p.area_fraction[1],
                p.domain_fraction[0],
                p.domain_fraction[1],
                p.counts[0],
                p.counts[1],
                p.counts[2]
            );
        }
        let mut reasons: BTreeMap<String, (usize, f64)> = BTreeMap::new();
        for p in &self.patches {
            for u in &p.unresolved {
                let e = reasons.entry(u.reason.to_string()).or_default();
                e.0 += u.cells;
                e.1 += u.domain_fraction;
            }
        }
        for (why, (n, d)) in reasons.iter().take(12) {
            t += &format!("  unresolved: {n} cells ({d:.4} patch squares): {why}\n");
        }
        if reasons.len() > 12 {
            t += &format!("  ... and {} more reasons\n", reasons.len() - 12);
        }
        let s = &self.stats;
        t += &format!(
            "work: {} cells, {} quiet regions, {} ray tests ({} refused)\n",
            s.cells, s.quiet_regions, s.ray_tests, s.refused_ray_tests
        );
        t += &format!(
            "trimming curves: {} ({} certified), chained into {} loops ({} closed); {} outline pieces without an occlusion curve; {} intersecting patch pairs (their intersection curves are not trimming curves)\n",
            s.trim_curves,
            s.certified_trim_curves,
            s.trim_loops,
            s.closed_trim_loops,
            self.missing_occlusions.len(),
            self.intersecting_patches.len()
        );
        for a in &self.assumptions {
            t += &format!("assumed: {a}\n");
        }
        t += &format!("time: {:.1} ms on {} threads\n", self.time_ms, self.threads);
        t
    }
}
