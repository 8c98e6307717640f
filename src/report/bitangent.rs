//! The report of `limn curves --kind bitangent`: JSON (field names are a public contract, see
//! README), text, SVG (projected along a view direction) and OBJ polylines.

use crate::analysis::bitangent::curves::{
    BitangentCurves, BitangentPlaneSet, BitangentSingular, BitangentUnresolved,
};
use crate::analysis::view::View;
use crate::model::Model;
use crate::report::render::{
    curves_svg, gather, obj_polyline, reason_lines, verdict_lines, Work, INCOMPLETE_STYLE,
};
use crate::solver::precision::Escalations;

/// One bitangent curve of the report: a chain of pairs of points with one tangent plane.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentCurve {
    /// The patches of the first and of the second points.
    pub patches: [usize; 2],
    /// A closed loop.
    pub closed: bool,
    /// Nothing missing at its ends (they lie on the patches' sides).
    pub complete: bool,
    /// The first points in space, in order.
    pub points: Vec<[f64; 3]>,
    /// The second points, in the same order.
    pub points_second: Vec<[f64; 3]>,
    /// The first points' `(u, v)` on the first patch.
    pub points_uv: Vec<[f64; 2]>,
    /// The second points' `(u, v)` on the second patch.
    pub points_uv_second: Vec<[f64; 2]>,
    /// The unit direction from the first to the second point: the view direction of the
    /// visual event of the pair (up to sign).
    pub lines: Vec<[f64; 3]>,
    /// The unit normal of the common tangent plane.
    pub normals: Vec<[f64; 3]>,
}

/// Work counts.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct BitangentStats {
    /// Patches.
    pub patches: usize,
    /// Pairs of patches considered (a patch with itself included).
    pub pairs: usize,
    /// Pairs pruned by their cones of normals.
    pub pairs_pruned: usize,
    /// Patches whose pair with themselves was excluded whole by the diagonal lemma.
    pub self_pairs_excluded: usize,
    /// Pairs solved.
    pub pairs_solved: usize,
    /// Curves.
    pub curves: usize,
    /// Pairs of points on them.
    pub points: usize,
    /// The solver's work (flattened into `stats`).
    #[serde(flatten)]
    pub work: Work,
}

/// The document of `limn curves --kind bitangent`.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct BitangentReport {
    /// The model file.
    pub model: String,
    /// "bitangent".
    pub kind: &'static str,
    /// Topology proven for every pair (nothing unresolved, every curve complete), and with a
    /// tolerance every drawn segment proven within it.
    pub certified: bool,
    /// The tolerance in model units, if any.
    pub tolerance: Option<f64>,
    /// With a tolerance: the largest proven distance between a drawn segment and its curve.
    pub error_bound: Option<f64>,
    /// The curves.
    pub curves: Vec<BitangentCurve>,
    /// The boxes of `(u, v, s, t)` not decided.
    pub unresolved: Vec<BitangentUnresolved>,
    /// Exact singular points of the curves, with their branches where decided.
    pub singular_points: Vec<BitangentSingular>,
    /// 2-dimensional sets of pairs: planes tangent to two patches along lines.
    pub plane_sets: Vec<BitangentPlaneSet>,
    /// Work counts.
    pub stats: BitangentStats,
}

impl BitangentReport {
    /// The report of a run.
    pub fn new(
        model: &str,
        r: &BitangentCurves,
        tolerance: Option<f64>,
        ms: f64,
        threads: usize,
    ) -> BitangentReport {
        let curves: Vec<BitangentCurve> = r
            .pairs
            .iter()
            .flat_map(|p| &p.branches)
            .map(|b| BitangentCurve {
                patches: b.patches,
                closed: b.closed,
                complete: b.complete,
                points: b.points.iter().map(|p| p.p).collect(),
                points_second: b.points.iter().map(|p| p.q).collect(),
                points_uv: b.points.iter().map(|p| p.first_uv).collect(),
                points_uv_second: b.points.iter().map(|p| p.second_uv).collect(),
                lines: b.points.iter().map(|p| p.line).collect(),
                normals: b.points.iter().map(|p| p.normal).collect(),
            })
            .collect();
        let unresolved: Vec<BitangentUnresolved> = gather(&r.pairs, |p| &p.unresolved);
        let singular_points: Vec<BitangentSingular> = gather(&r.pairs, |p| &p.singular_points);
        let plane_sets: Vec<BitangentPlaneSet> = gather(&r.pairs, |p| &p.plane_sets);
        let error_bound = tolerance.and_then(|_| {
            r.pairs
                .iter()
                .try_fold(0.0f64, |m, p| p.error_bound.map(|e| m.max(e)))
        });
        let within = r.pairs.iter().all(|p| p.within_tolerance);
        BitangentReport {
            model: model.to_string(),
            kind: "bitangent",
            certified: r.is_certified() && within,
            tolerance,
            error_bound,
            stats: BitangentStats {
                patches: r.patches,
                pairs: r.pairs_total,
                pairs_pruned: r.pruned,
                self_pairs_excluded: r.excluded_self,
                pairs_solved: r.pairs.len(),
                curves: curves.len(),
                points: curves.iter().map(|c| c.points.len()).sum(),
                work: Work {
                    boxes: r.pairs.iter().map(|p| p.boxes).sum(),
                    escalations: r.pairs.iter().fold(Escalations::default(), |mut e, p| {
                        e.merge(&p.escalations);
                        e
                    }),
                    unresolved: unresolved.len(),
                    ms,
                    threads,
                },
            },
            curves,
            unresolved,
            singular_points,
            plane_sets,
        }
    }

    /// A short human-readable summary.
    pub fn text(&self) -> String {
        let s = &self.stats;
        let (verdict, bound) = verdict_lines(
            self.certified,
            s.work.unresolved,
            self.curves.iter().filter(|c| !c.complete).count(),
            "",
            self.tolerance,
            self.error_bound,
        );
        let mut out = format!(
            "{}: {} bitangent curves ({} pairs of points) on {} patches, {verdict}\n{bound}",
            self.model, s.curves, s.points, s.patches
        );
        out += &format!(
            "{} pairs of patches: {} pruned by their normal cones, {} patches without self-bitangents (diagonal lemma), {} solved\n",
            s.pairs, s.pairs_pruned, s.self_pairs_excluded, s.pairs_solved
        );
        out += &reason_lines(
            self.unresolved
                .iter()
                .map(|u| (&u.reason, format!("{}-{}", u.patches[0], u.patches[1]))),
            "pairs",
        );
        for p in &self.plane_sets {
            out += &format!(
                "  pair {}-{}: every pair of points of {} and {} is bitangent (the plane {:.6} x + {:.6} y + {:.6} z = {:.6} is tangent along both, checked exactly)\n",
                p.patches[0],
                p.patches[1],
                p.first,
                p.second,
                p.normal[0],
                p.normal[1],
                p.normal[2],
                p.offset
            );
        }
        // Singular points on a plane set are explained by it: counted, not listed.
        let on_sets = |p: &BitangentSingular| {
            p.branches.is_none() && self.plane_sets.iter().any(|s| s.patches == p.patches)
        };
        let explained = self.singular_points.iter().filter(|p| on_sets(p)).count();
        if explained > 0 {
            out += &format!(
                "  {explained} exact singular points lie on these sets (listed in the JSON)\n"
            );
        }
        for p in self.singular_points.iter().filter(|p| !on_sets(p)) {
            out += &format!(
                "  pair {}-{}: singular point at (u, v, s, t) = ({}) exactly, {}\n",
                p.patches[0],
                p.patches[1],
                p.exact.join(", "),
                match p.branches {
                    Some(b) => format!("{b} branches from it (proven)"),
                    None => "its branches not resolved".to_string(),
                }
            );
        }
        out += &s.work.line();
        out
    }

    /// The curves of both points drawn in the view plane over the patches' sides in grey:
    /// first points blue, second points green, incomplete curves red and dashed, the centres of
    /// unresolved boxes marked in red.
    pub fn svg(&self, model: &Model, view: &View) -> String {
        let (complete, incomplete): (Vec<&BitangentCurve>, Vec<&BitangentCurve>) =
            self.curves.iter().partition(|c| c.complete);
        let firsts = complete
            .iter()
            .map(|c| (c.points.as_slice(), c.closed))
            .collect();
        let seconds = complete
            .iter()
            .map(|c| (c.points_second.as_slice(), c.closed))
            .collect();
        let open = incomplete
            .iter()
            .flat_map(|c| {
                [
                    (c.points.as_slice(), c.closed),
                    (c.points_second.as_slice(), c.closed),
                ]
            })
            .collect();
        let title = format!(
            "{}: {} bitangent curves (first points blue, second green), {}",
            self.model,
            self.stats.curves,
            if self.certified {
                "certified".to_string()
            } else {
                format!("{} unresolved boxes (red)", self.stats.work.unresolved)
            }
        );
        let marks: Vec<[f64; 3]> = self.unresolved.iter().flat_map(|u| u.at).collect();
        curves_svg(
            model,
            view,
            &title,
            vec![
                (r##"stroke="#04c" stroke-width="1.6""##, firsts),
                (r##"stroke="#0a4" stroke-width="1.6""##, seconds),
                (INCOMPLETE_STYLE, open),
            ],
            &marks,
        )
    }

    /// The curves as OBJ polylines: per curve, the first points' polyline, then the second's.
    pub fn obj(&self) -> String {
        let mut out = format!("# limn bitangent curves: {}\n", self.model);
        let mut next = 1usize;
        for (k, c) in self.curves.iter().enumerate() {
            for (which, points) in [("first", &c.points), ("second", &c.points_second)] {
                out += &format!(
                    "# curve {k} ({which} points): patches {:?}, {}, {}\n",
                    c.patches,
                    if c.closed { "closed" } else { "open" },
                    if c.complete { "complete" } else { "incomplete" }
                );
                obj_polyline(&mut out, &mut next, points, c.closed);
            }
        }
        out
    }
}

crate::report::document::curve_document!(BitangentReport);
