//! Curves on a model given by one exact polynomial per patch (silhouettes, parabolic
//! curves): each patch solved with certified topology, collapsed sides divided out, sides and
//! lines where the polynomial vanishes added back, crossings joined across shared edges where
//! the join is proven (`proofs/silhouette-join.md`), and, with a tolerance, the arcs traced
//! with certified accuracy (`proofs/chord-accuracy.md`). [`model_curves`] is the one entry
//! point; each family says what differs in its [`CurveRules`].

use crate::analysis::chords::plane_curve::PatchAccuracy;
use crate::analysis::contour::chaining::{chain_model, CurveEnds};
use crate::analysis::contour::curves::TrimSummary;
use crate::analysis::contour::curves::{Degenerate, Node, Silhouette, SingularPoint, SolvedPatch};
use crate::analysis::contour::drawing::refined_for;
use crate::analysis::contour::joins::{ends_at_edge, join_side, join_zero_side, Joins};
use crate::analysis::contour::sides::{
    both_on, corner_index, deflate_side_counted, side_axis, side_of,
};
use crate::analysis::contour::trims::clip_to_faces;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::model::{Model, PatchAdjacency, WeldTolerance};
use crate::number::{Precision, Rational};
use crate::solver::plane_curve::zero_lines::{add_line, solve_curve_lines, LinedCurve, ZeroLine};
use crate::solver::plane_curve::ArcKind;
use crate::solver::precision::Policy;
use crate::solver::{CurveOptions, CurveTopology, Dyadic, Escalations};
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The options of the curve families on a model: [`silhouette`](super::silhouette::silhouette)
/// and [`parabolic`](super::parabolic::parabolic).
///
/// # Examples
/// ```
/// let mut options = limn::ContourOptions::default();
/// options.tol = Some(1e-6); // every drawn segment within 1e-6 model units of the true curve
/// options.curve.max_depth = 20;
/// ```
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct ContourOptions {
    /// The solver's budgets and precision ladder.
    pub curve: CurveOptions,
    /// How patch boundaries are matched into shared edges; `None`: the model's default
    /// ([`crate::model::default_weld`]: exact, or for IGES the file's stated resolution).
    pub weld: Option<WeldTolerance>,
    /// The tolerance, in model units, within which every drawn segment is proven to lie of the
    /// true curve (`proofs/chord-accuracy.md`); `None`: the topology is certified, the drawing
    /// is not bounded.
    pub tol: Option<f64>,
}

impl ContourOptions {
    /// Options with these parts.
    pub fn new(curve: CurveOptions, weld: WeldTolerance, tol: Option<f64>) -> ContourOptions {
        ContourOptions {
            curve,
            weld: Some(weld),
            tol,
        }
    }

    /// The weld tolerance for `model`.
    pub fn weld_for(&self, model: &Model) -> WeldTolerance {
        self.weld
            .unwrap_or_else(|| crate::model::default_weld(model))
    }
}

/// What differs between the curve families solved on a model by [`model_curves`].
#[derive(Clone, Debug)]
pub struct CurveRules {
    /// Crossings on a shared edge are also joined where the two patches' normals are exactly
    /// parallel along it (true for silhouettes, whose function is the normal times a fixed
    /// vector; not for other families).
    pub parallel_normal_joins: bool,
    /// The `degenerate` kind of a patch whose function vanishes identically ("edge-on" for a
    /// silhouette).
    pub whole_patch: &'static str,
    /// The `degenerate` kind of a side on which it vanishes ("silhouette side").
    pub whole_side: &'static str,
    /// The `degenerate` kind of a line inside a patch on which it vanishes ("silhouette
    /// line").
    pub whole_line: &'static str,
    /// For a family whose function vanishes on a collapsed side only through a known factor
    /// (a silhouette's: the normal's), the order of that factor on the side. Where the
    /// function vanishes to a higher order, the collapsed point is itself on the curve
    /// (`proofs/silhouette-join.md`, "Collapsed sides"); `None`: not analysed (the collapsed
    /// factor is divided out whole).
    pub spurious_collapse: Option<fn(&RationalPatch, Edge) -> usize>,
}

/// Whether the curves are clipped to the model's trimmed faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Faces {
    /// Clipped to the faces the file states (surfaces no face names are used whole).
    Trimmed,
    /// On the whole surfaces (for analyses that do not honour trims yet).
    Untrimmed,
}

/// The curves `g_i = 0` on a model, one exact polynomial per patch (any family defined by
/// one equation in the patch parameters: silhouettes, parabolic curves): solved per patch with
/// certified topology, with collapsed sides divided out, sides and lines where `g` vanishes
/// added back, crossings joined across shared edges where the join is proven, and, with a
/// tolerance, traced with certified accuracy (`proofs/silhouette-join.md`,
/// `proofs/chord-accuracy.md`).
///
/// # Panics
/// If `gs` does not have one bivariate polynomial per patch.
pub fn model_curves(
    model: &Model,
    gs: Vec<Bernstein<Rational>>,
    rules: &CurveRules,
    opts: &CurveOptions,
    weld: WeldTolerance,
    tol: Option<f64>,
    faces: Faces,
) -> Silhouette {
    assert_eq!(gs.len(), model.patches.len(), "one polynomial per patch");
    let patches: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
    let adj = PatchAdjacency::of_patches(&patches, weld);
    // On a collapsed side the normal vanishes, so g has that side's linear factor: divide it
    // out (exactly), so that the spurious zero set along the side does not meet the real curve
    // in a singular point. The sign inside the square is unchanged.
    let mut divided: Vec<Vec<(Edge, usize)>> = vec![Vec::new(); gs.len()];
    let solve_gs: Vec<Bernstein<Rational>> = gs
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let mut g = g.clone();
            for &(patch, edge, _) in &adj.collapsed {
                if patch == i {
                    let (h, k) = deflate_side_counted(&g, edge);
                    g = h;
                    if k > 0 {
                        divided[i].push((edge, k));
                    }
                }
            }
            g
        })
        .collect();
    // Collapsed sides where the function vanishes to a higher order than its spurious factor:
    // their collapsed point is on the curve.
    let on_curve_poles: Vec<(usize, Edge, usize)> = adj
        .collapsed
        .iter()
        .filter(|&&(i, edge, _)| {
            let Some(order) = rules.spurious_collapse else {
                return false;
            };
            let k = divided[i].iter().find(|d| d.0 == edge).map_or(0, |d| d.1);
            k > order(patches[i], edge)
        })
        .copied()
        .collect();
    let solve_gs: Vec<Bernstein<Rational>> = solve_gs
        .into_iter()
        .enumerate()
        .map(|(i, mut g)| {
            // A side on which g vanishes identically is part of the silhouette, exactly; but
            // where the rest of the curve meets it, g is singular (and if g vanishes to a
            // higher order there, g keeps one sign across it). Divide its factor out entirely:
            // the quotient h has the same sign inside the square and a regular curve there,
            // and the side is added back as arcs, split where h's curve meets it.
            for edge in Edge::ALL {
                let (h, k) = deflate_side_counted(&g, edge);
                g = h;
                if k > 0 {
                    divided[i].push((edge, k));
                }
            }
            g
        })
        .collect();
    let collapsed_side = |i: usize, e: Edge| {
        adj.collapsed
            .iter()
            .any(|&(p, edge, _)| p == i && edge == e)
    };
    let zero_sides: Vec<Vec<Edge>> = divided
        .iter()
        .enumerate()
        .map(|(i, d)| {
            d.iter()
                .map(|&(e, _)| e)
                .filter(|&e| !collapsed_side(i, e))
                .collect()
        })
        .collect();
    let opts = &refined_for(opts, model, tol);
    // Lines inside the square on which g vanishes (the circle of vertical normals on a surface
    // of revolution seen from the side) are divided out too, and added back as arcs.
    let lined: Vec<LinedCurve> = solve_gs
        .par_iter()
        .map(|g| solve_curve_lines(g, opts))
        .collect();
    let lines: Vec<Vec<ZeroLine>> = lined.iter().map(|c| c.lines.clone()).collect();
    let solved: Vec<SolvedPatch> = lined
        .iter()
        .zip(divided)
        .map(|(c, divided)| SolvedPatch {
            g: c.quotient.clone(),
            divided,
            lines: c.lines.clone(),
            topology: c.solved.clone(),
        })
        .collect();
    let mut tops: Vec<CurveTopology> = lined.into_iter().map(|c| c.topology).collect();
    let quotients: Vec<Bernstein<Rational>> = solved.iter().map(|p| p.g.clone()).collect();

    for ((t, sides), lines) in tops.iter_mut().zip(&zero_sides).zip(&lines) {
        // Where lines of the other direction cross this one.
        let crossing = |fixed: usize| -> Vec<Dyadic> {
            lines
                .iter()
                .filter(|z| z.axis != fixed)
                .map(|z| z.at)
                .collect()
        };
        for &edge in sides {
            let (fixed, at_one) = side_axis(edge);
            let c = if at_one { Dyadic::ONE } else { Dyadic::ZERO };
            add_line(t, fixed, c, &crossing(fixed));
        }
    }

    let mut degenerate = Vec::new();
    let mut unresolved = Vec::new();
    let mut escalations = Escalations::default();
    let mut boxes = 0;
    for (i, t) in tops.iter().enumerate() {
        if t.identically_zero {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_patch,
                side: None,
                line: None,
            });
        }
        for &side in &zero_sides[i] {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_side,
                side: Some(side),
                line: None,
            });
        }
        for z in &lines[i] {
            degenerate.push(Degenerate {
                patch: i,
                kind: rules.whole_line,
                side: None,
                line: Some(z.to_string()),
            });
        }
        for u in &t.unresolved {
            unresolved.push((i, u.cell, u.reason.clone()));
        }
        escalations.merge(&t.escalations);
        boxes += t.boxes;
    }
    // Collapsed sides: the normal vanishes there, so g does too; the "curve" along them is not
    // a silhouette. Drop arcs on them; crossings on them are all the one collapsed point.
    let mut joins = Joins {
        parent: BTreeMap::new(),
    };
    for &(patch, edge, _) in &adj.collapsed {
        degenerate.push(Degenerate {
            patch,
            kind: "collapsed side",
            side: Some(edge),
            line: None,
        });
        tops[patch]
            .arcs
            .retain(|a| !(a.kind == ArcKind::OnEdge && both_on(&a.from, &a.to, edge)));
    }
    // Shared edges: join crossings when the two side polynomials are exactly proportional.
    let mut unjoined = Vec::new();
    let mut open_boundary: Vec<(usize, Edge)> = Vec::new();
    let mut ending = Vec::new();
    for class in &adj.edges {
        if class.len() == 1 {
            open_boundary.push((class[0].patch, class[0].edge));
            continue;
        }
        if class.len() != 2 {
            continue;
        }
        let (a, b) = (class[0], class[1]);
        // Past the deadline the edge is left unjoined (the silhouette is then not certified).
        if opts.past_deadline() {
            unjoined.push((a.patch, a.edge, b.patch, b.edge));
            continue;
        }
        let normals = rules.parallel_normal_joins.then_some(&patches[..]);
        let joined = join_side(
            &tops,
            &gs,
            normals,
            a,
            b,
            &mut joins,
            &mut Policy::new(&opts.ladder, &mut escalations),
        ) || join_zero_side(&mut tops, &gs, &quotients, a, b, &mut joins);
        if joined {
            continue;
        }
        if ends_at_edge(
            &tops,
            &gs,
            a,
            b,
            &mut joins,
            &mut Policy::new(&opts.ladder, &mut escalations),
        ) {
            // The function jumps across the edge: crossings common to both patches are joined,
            // every other curve reaching it ends there.
            open_boundary.push((a.patch, a.edge));
            open_boundary.push((b.patch, b.edge));
            ending.push((a.patch, a.edge, b.patch, b.edge));
        } else {
            unjoined.push((a.patch, a.edge, b.patch, b.edge));
        }
    }
    let gs_fast: Vec<Bernstein<f64>> = gs.iter().map(|g| g.convert(Precision::F64)).collect();
    // Crossings on a collapsed side are its vertex; crossings exactly at a patch corner are the
    // welded corner vertex: one node per vertex.
    let mut vertex_nodes: BTreeMap<usize, Vec<Node>> = BTreeMap::new();
    for &(patch, edge, vertex) in &adj.collapsed {
        for a in &tops[patch].arcs {
            for id in [a.from, a.to] {
                if side_of(&id).iter().any(|s| s.0 == edge) {
                    vertex_nodes.entry(vertex).or_default().push((patch, id));
                }
            }
        }
    }
    for (patch, t) in tops.iter().enumerate() {
        for a in &t.arcs {
            for id in [a.from, a.to] {
                if let Some(k) = corner_index(&id) {
                    vertex_nodes
                        .entry(adj.corners[patch][k])
                        .or_default()
                        .push((patch, id));
                }
            }
        }
    }
    for nodes in vertex_nodes.values() {
        for w in nodes.windows(2) {
            joins.union(w[0], w[1]);
        }
    }
    // On trimmed faces: the arcs clipped to them (`proofs/trimmed-faces.md`, 8).
    let clipped = match faces {
        Faces::Trimmed if !model.faces.is_empty() => Some(clip_to_faces(
            model,
            &mut tops,
            &quotients,
            &mut joins,
            &mut Policy::new(&opts.ladder, &mut escalations),
        )),
        _ => None,
    };
    if let Some(c) = &clipped {
        unresolved.extend(c.unresolved.iter().cloned());
    }
    let trim_ends = clipped
        .as_ref()
        .map(|c| c.trim_ends.clone())
        .unwrap_or_default();
    let accuracy: Option<Vec<Option<PatchAccuracy>>> = tol.map(|_| {
        quotients
            .par_iter()
            .enumerate()
            .map(|(i, g)| (!tops[i].arcs.is_empty()).then(|| PatchAccuracy::new(patches[i], g)))
            .collect()
    });
    let (curves, mut singular_points) = chain_model(
        &tops,
        &gs_fast,
        &patches,
        &mut joins,
        CurveEnds {
            open_boundary: &open_boundary,
            trim_ends: &trim_ends,
        },
        accuracy.as_deref().zip(tol),
        opts.deadline,
    );
    singular_points.extend(isolated_poles(&on_curve_poles, &adj, &tops, &patches));
    Silhouette {
        curves,
        singular_points,
        patches: tops,
        solved,
        degenerate,
        unresolved,
        unjoined_edges: unjoined,
        ending_edges: ending,
        boxes,
        tolerance: tol,
        escalations,
        frame: crate::analysis::frame::Frame::identity(),
        trims: clipped.map(|c| TrimSummary {
            faces: model.faces.len(),
            crossings: c.crossings,
            dropped_arcs: c.dropped,
            trim_ends: c.trim_ends.len(),
        }),
    }
}

/// The collapsed points on the curve that no arc reaches: isolated points of the curve
/// (`proofs/silhouette-join.md`, "Collapsed sides"), each once, with the side of the first
/// patch that collapses to it.
fn isolated_poles(
    on_curve: &[(usize, Edge, usize)],
    adj: &PatchAdjacency,
    tops: &[CurveTopology],
    patches: &[&RationalPatch],
) -> Vec<SingularPoint> {
    let mut out: Vec<SingularPoint> = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for &(patch, edge, point) in on_curve {
        if !seen.insert(point) {
            continue;
        }
        // Every side that collapses to this point, on every patch.
        let reached = adj
            .collapsed
            .iter()
            .filter(|c| c.2 == point)
            .any(|&(p, e, _)| {
                tops[p].arcs.iter().any(|a| {
                    [a.from, a.to]
                        .iter()
                        .any(|id| side_of(id).iter().any(|s| s.0 == e))
                })
            });
        // Or a corner of any patch at this point (a patch whose side does not collapse there).
        let at_corner = adj.corners.iter().enumerate().any(|(p, cs)| {
            cs.iter().enumerate().any(|(k, &c)| {
                c == point
                    && tops[p]
                        .arcs
                        .iter()
                        .any(|a| [a.from, a.to].iter().any(|id| corner_index(id) == Some(k)))
            })
        });
        if reached || at_corner {
            continue;
        }
        let (axis, at_one) = side_axis(edge);
        let mut uv = [0.5, 0.5];
        uv[axis] = if at_one { 1.0 } else { 0.0 };
        let mut cell = Rect::UNIT;
        cell.lo[axis] = uv[axis];
        cell.hi[axis] = uv[axis];
        let q = |x: f64| Rational::from_f64(x).unwrap_or_default();
        let p = patches[patch].eval(&q(uv[0]), &q(uv[1]));
        out.push(SingularPoint {
            patch,
            uv,
            point: p.map(|c| c.to_f64()),
            cell,
            exact: true,
            branches: 0,
        });
    }
    out
}
