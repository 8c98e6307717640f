//! The report of `limn curves --kind flecnodal`: JSON (field names are a public contract, see
//! README), text, SVG (projected along a view direction) and OBJ polylines.

use crate::analysis::flecnodal::curves::{FlecnodalCurves, FlecnodalSingular, FlecnodalUnresolved};
use crate::analysis::view::View;
use crate::model::Model;
use crate::report::render::{
    curves_svg, gather, obj_polyline, reason_lines, verdict_lines, Work, INCOMPLETE_STYLE,
};
use crate::solver::precision::Escalations;

/// The polylines of curves, with whether each is closed.
fn lines<'a>(cs: &[&'a FlecnodalCurve]) -> Vec<(&'a [[f64; 3]], bool)> {
    cs.iter().map(|c| (c.points.as_slice(), c.closed)).collect()
}

/// One flecnodal curve of the report.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FlecnodalCurve {
    /// The patch.
    pub patch: usize,
    /// A closed loop.
    pub closed: bool,
    /// Nothing missing at its ends (they lie on the patch's sides).
    pub complete: bool,
    /// Points in space, in order.
    pub points: Vec<[f64; 3]>,
    /// The same points as `(u, v)`.
    pub points_uv: Vec<[f64; 2]>,
    /// The asymptotic direction `(a, b)` in the parameter plane at each point (unit, up to
    /// sign).
    pub directions_uv: Vec<[f64; 2]>,
    /// The unit direction in space of the line with 4-point contact at each point (up to
    /// sign): the view direction of the visual event there.
    pub lines: Vec<[f64; 3]>,
}

/// A patch not solved.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DegeneratePatch {
    /// The patch.
    pub patch: usize,
    /// Why.
    pub reason: String,
}

/// A side of a patch whose points are not analysed: both equations vanish there for every
/// direction (a collapsed side), so its factor was divided out.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct UnanalysedSide {
    /// The patch.
    pub patch: usize,
    /// The side: `u=0`, `u=1`, `v=0` or `v=1`.
    pub side: &'static str,
}

/// Work counts.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct FlecnodalStats {
    /// Patches.
    pub patches: usize,
    /// Curves.
    pub curves: usize,
    /// Points on them.
    pub points: usize,
    /// The solver's work (flattened into `stats`).
    #[serde(flatten)]
    pub work: Work,
}

/// The document of `limn curves --kind flecnodal`.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct FlecnodalReport {
    /// The model file.
    pub model: String,
    /// "flecnodal".
    pub kind: &'static str,
    /// Topology proven on every patch (nothing unresolved or degenerate, every curve
    /// complete), and with a tolerance every drawn segment proven within it.
    pub certified: bool,
    /// The tolerance in model units, if any.
    pub tolerance: Option<f64>,
    /// With a tolerance: the largest proven distance between a drawn segment and its curve.
    pub error_bound: Option<f64>,
    /// The curves.
    pub curves: Vec<FlecnodalCurve>,
    /// The boxes of `(u, v, s)` not decided.
    pub unresolved: Vec<FlecnodalUnresolved>,
    /// Exact singular points of the curves, with their branches where decided.
    pub singular_points: Vec<FlecnodalSingular>,
    /// Patches not solved.
    pub degenerate: Vec<DegeneratePatch>,
    /// Sides whose points are not analysed (collapsed sides).
    pub unanalysed_sides: Vec<UnanalysedSide>,
    /// Work counts.
    pub stats: FlecnodalStats,
}

impl FlecnodalReport {
    /// The report of a run.
    pub fn new(
        model: &str,
        r: &FlecnodalCurves,
        tolerance: Option<f64>,
        ms: f64,
        threads: usize,
    ) -> FlecnodalReport {
        let curves: Vec<FlecnodalCurve> = r
            .patches
            .iter()
            .flat_map(|p| &p.branches)
            .map(|b| FlecnodalCurve {
                patch: b.patch,
                closed: b.closed,
                complete: b.complete,
                points: b.points.iter().map(|p| p.xyz).collect(),
                points_uv: b.points.iter().map(|p| p.uv).collect(),
                directions_uv: b.points.iter().map(|p| p.direction_uv).collect(),
                lines: b.points.iter().map(|p| p.line).collect(),
            })
            .collect();
        let unresolved: Vec<FlecnodalUnresolved> = gather(&r.patches, |p| &p.unresolved);
        let singular_points: Vec<FlecnodalSingular> = gather(&r.patches, |p| &p.singular_points);
        let degenerate: Vec<DegeneratePatch> = r
            .patches
            .iter()
            .filter_map(|p| {
                p.degenerate.as_ref().map(|reason| DegeneratePatch {
                    patch: p.patch,
                    reason: reason.clone(),
                })
            })
            .collect();
        let unanalysed_sides = r
            .patches
            .iter()
            .flat_map(|p| {
                p.divided_sides.iter().map(|&side| UnanalysedSide {
                    patch: p.patch,
                    side,
                })
            })
            .collect();
        let error_bound = tolerance.and_then(|_| {
            r.patches
                .iter()
                .filter(|p| p.degenerate.is_none())
                .try_fold(0.0f64, |m, p| p.error_bound.map(|e| m.max(e)))
        });
        let within = r.patches.iter().all(|p| p.within_tolerance);
        FlecnodalReport {
            model: model.to_string(),
            kind: "flecnodal",
            certified: r.is_certified() && within,
            tolerance,
            error_bound,
            stats: FlecnodalStats {
                patches: r.patches.len(),
                curves: curves.len(),
                points: curves.iter().map(|c| c.points.len()).sum(),
                work: Work {
                    boxes: r.patches.iter().map(|p| p.boxes).sum(),
                    escalations: r.patches.iter().fold(Escalations::default(), |mut e, p| {
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
            degenerate,
            unanalysed_sides,
        }
    }

    /// A short human-readable summary.
    pub fn text(&self) -> String {
        let s = &self.stats;
        let (verdict, bound) = verdict_lines(
            self.certified,
            s.work.unresolved,
            self.curves.iter().filter(|c| !c.complete).count(),
            &format!(", {} degenerate patches", self.degenerate.len()),
            self.tolerance,
            self.error_bound,
        );
        let mut out = format!(
            "{}: {} flecnodal curves ({} points) on {} patches, {verdict}\n{bound}",
            self.model, s.curves, s.points, s.patches
        );
        out += &reason_lines(
            self.unresolved.iter().map(|u| (&u.reason, u.patch)),
            "patches",
        );
        for p in &self.singular_points {
            out += &format!(
                "  patch {}: singular point at (u, v, s) = ({}) exactly, {}\n",
                p.patch,
                p.exact.join(", "),
                match p.branches {
                    Some(b) => format!("{b} branches from it (proven)"),
                    None => "its branches not resolved".to_string(),
                }
            );
        }
        for d in &self.degenerate {
            out += &format!("  patch {}: degenerate: {}\n", d.patch, d.reason);
        }
        for u in &self.unanalysed_sides {
            out += &format!(
                "  patch {}: side {} not analysed (the system vanishes there for every direction: a collapsed side)\n",
                u.patch, u.side
            );
        }
        out += &s.work.line();
        out
    }

    /// The curves drawn in the view plane over the patches' sides in grey: complete curves
    /// green, incomplete ones red and dashed, the centres of unresolved boxes marked in red.
    pub fn svg(&self, model: &Model, view: &View) -> String {
        let (complete, incomplete): (Vec<&FlecnodalCurve>, Vec<&FlecnodalCurve>) =
            self.curves.iter().partition(|c| c.complete);
        let title = format!(
            "{}: {} flecnodal curves, {}",
            self.model,
            self.stats.curves,
            if self.certified {
                "certified".to_string()
            } else {
                format!("{} unresolved boxes (red)", self.stats.work.unresolved)
            }
        );
        let marks: Vec<[f64; 3]> = self.unresolved.iter().map(|u| u.at).collect();
        curves_svg(
            model,
            view,
            &title,
            vec![
                (r##"stroke="#0a4" stroke-width="1.6""##, lines(&complete)),
                (INCOMPLETE_STYLE, lines(&incomplete)),
            ],
            &marks,
        )
    }

    /// The curves as OBJ polylines.
    pub fn obj(&self) -> String {
        let mut out = format!("# limn flecnodal curves: {}\n", self.model);
        let mut next = 1usize;
        for (k, c) in self.curves.iter().enumerate() {
            out += &format!(
                "# curve {k}: patch {}, {}, {}\n",
                c.patch,
                if c.closed { "closed" } else { "open" },
                if c.complete { "complete" } else { "incomplete" }
            );
            obj_polyline(&mut out, &mut next, &c.points, c.closed);
        }
        out
    }
}

crate::report::document::curve_document!(FlecnodalReport);
