//! Bitangent curves of a model: for every pair of patches (a patch with itself included) whose
//! normals can be parallel, the curve of pairs `(p, q)` with one tangent plane, solved by the
//! n-variable curve solver ([`crate::solver::space_curve`]) on the system of
//! [`crate::analysis::bitangent::system`] in `(u, v, s, t)`, and mapped to the surface.
//!
//! Pairs of patches whose cones of normals are disjoint (and not opposite) are pruned without
//! solving. For a patch with itself, the spurious diagonal is kept out by
//! [`DiagonalTest::excludes`], and only one of the two orders of each pair is solved (the
//! Morton half of [`mirror_dropped`]); the curve's ends on the boundary between the halves are
//! joined to their mirror images, so every pair is reported once (`proofs/bitangent.md`).
//! Where two patches meet in space (a shared side, a pole, an intersection), pairs of nearby
//! points are not separated from the spurious coincident pairs: boxes whose two pieces'
//! enclosures overlap at `coincidence_depth` are reported unresolved.

use crate::analysis::bitangent::system::{
    bitangent_system, deflated_normal, mirror_dropped, normals_apart, seam_excludes, shared_sides,
    DiagonalTest,
};
use crate::analysis::bitangent::tangent_lines::{tangent_plane_along, TangentLine};
use crate::analysis::chords::space_curve::Accuracy;
use crate::analysis::chords::sphere_curve::{largest, piece_error};
use crate::analysis::frame::Frame;
use crate::error::Error;
use crate::geometry::vec3::cross;
use crate::geometry::Rect;
use crate::model::Model;
use crate::number::{Interval, Number, Rational};
use crate::reason::Reason;
use crate::solver::chain::chain;
use crate::solver::precision::{past, Escalations};
use crate::solver::space_curve::ArcAccept;
use crate::solver::space_curve::{
    solve_space_curve_excluding, unwarp, unwarp_interval, warp, BoxVerdict, SpaceCurve,
    SpaceCurveOptions, PAIR_WARP,
};
use crate::surface::Evaluator;
use crate::surface::RationalPatch;
use rayon::prelude::*;

/// What to compute.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct BitangentOptions {
    /// Budgets of the curve solver (its `tolerance` and `accept` are set from
    /// `tolerance`).
    pub solver: SpaceCurveOptions,
    /// The largest allowed distance in space between the drawn polylines and the true curves
    /// (both points of each pair), in model units; `None`: topology only.
    pub tolerance: Option<f64>,
    /// The depth from which a box whose two pieces may meet in space is given up.
    pub coincidence_depth: u32,
}

impl Default for BitangentOptions {
    fn default() -> Self {
        BitangentOptions::with_tolerance(None)
    }
}

impl BitangentOptions {
    /// The same options with a wall-clock deadline for the solver (past it, no box is
    /// subdivided and no further patch or pair is started).
    pub fn with_deadline(mut self, deadline: Option<std::time::Instant>) -> BitangentOptions {
        self.solver.deadline = deadline;
        self
    }

    /// The defaults for a model: per pair 10,000 boxes for the topology, 50,000 with a
    /// tolerance, to depth 20 (a curve that turns very near a grid plane needs small boxes
    /// there; on two spheres one such turn needed depth 17). A pair with a plane tangent along
    /// a curve (a 2-dimensional set of pairs) uses its whole budget.
    pub fn with_tolerance(tolerance: Option<f64>) -> BitangentOptions {
        let max_depth = 20;
        let max_boxes = if tolerance.is_some() { 50_000 } else { 10_000 };
        let mut solver = SpaceCurveOptions {
            max_depth,
            max_boxes,
            ..SpaceCurveOptions::default()
        };
        // The faces are 3-dimensional: room for two levels of their subdivision and part of a
        // third (a curve crossing a face at a shallow angle needs it; with 64 boxes, two
        // spheres took 5 times as many boxes).
        solver.face.max_boxes = 256;
        BitangentOptions {
            solver,
            tolerance,
            coincidence_depth: 4,
        }
    }
}

pub use super::result::{
    BitangentBranch, BitangentCurves, BitangentPlaneSet, BitangentPoint, BitangentSingular,
    BitangentUnresolved, PairBitangents,
};

/// Records the planes tangent to both patches of a pair along the given lines of each
/// (`lines[0]` of the first patch, `lines[1]` of the second), and gives the undecided boxes next
/// to such a set (for want of a regular minor) the set as their reason
/// (`proofs/bitangent.md`, Lemma 6).
fn explain_plane_sets(out: &mut PairBitangents, lines: &[Vec<TangentLine>; 2]) {
    let [i, j] = out.patches;
    for l1 in &lines[0] {
        for l2 in lines[1].iter().filter(|l2| l1.same_plane(l2)) {
            let set = plane_set([i, j], l1, l2);
            if out.plane_sets.contains(&set) {
                continue;
            }
            out.plane_sets.push(set);
            let reason = Reason::PlaneSet {
                patches: [i, j],
                lines: [l1.name(), l2.name()],
            };
            for u in out.unresolved.iter_mut().filter(|u| {
                matches!(
                    u.reason,
                    Reason::NoRegularMinor | Reason::UnresolvedSingularPoint
                ) && near(&u.cell[l1.axis], &l1.at)
                    && near(&u.cell[2 + l2.axis], &l2.at)
            }) {
                u.reason.clone_from(&reason);
            }
        }
    }
}

/// Whether `at` lies in the interval grown by its width on both sides (a box next to a line).
fn near(interval: &[f64; 2], at: &Rational) -> bool {
    let (x, w) = (at.to_f64(), interval[1] - interval[0]);
    interval[0] - w <= x && x <= interval[1] + w
}

/// The record of a plane tangent along two lines.
fn plane_set(patches: [usize; 2], l1: &TangentLine, l2: &TangentLine) -> BitangentPlaneSet {
    let n = l1.normal.clone().map(|c| c.to_f64());
    // Unit length, with the sign that makes the offset nonnegative.
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let len = if l1.offset < 0 { -len } else { len };
    BitangentPlaneSet {
        patches,
        first: l1.name(),
        second: l2.name(),
        // (+ 0.0 turns a −0 into 0.)
        normal: n.map(|c| c / len + 0.0),
        offset: l1.offset.to_f64() / len,
    }
}

/// The warp factor of variable `k` (for a patch with itself, the second pair repeats the first).
fn lambda(same: bool, k: usize) -> f64 {
    let k = if same { k % 2 } else { k };
    PAIR_WARP[k].0 as f64 / PAIR_WARP[k].1 as f64
}

/// A cone that contains every normal of a patch: a unit axis and a half-angle below π/2 (the
/// normals are positive combinations of the coefficient vectors of the deflated normal).
pub fn normal_cone(patch: &RationalPatch) -> Option<([f64; 3], f64)> {
    let (n, _) = deflated_normal(patch);
    // The coordinates at one degree, so that their coefficients pair up.
    let d: Vec<usize> = (0..2)
        .map(|a| n.iter().map(|p| p.degrees()[a]).max().unwrap_or(0))
        .collect();
    let n = n.map(|p| p.elevate_to(&d));
    let vecs: Vec<[f64; 3]> = (0..n[0].coeffs().len())
        .map(|i| std::array::from_fn(|k| n[k].coeffs()[i].to_f64()))
        .filter(|v: &[f64; 3]| v.iter().any(|x| *x != 0.0))
        .collect();
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|x| x / l)
    };
    let mut axis = [0.0; 3];
    for v in &vecs {
        let u = unit(*v);
        for k in 0..3 {
            axis[k] += u[k];
        }
    }
    if axis.iter().all(|x| *x == 0.0) {
        return None;
    }
    let axis = unit(axis);
    let mut half = 0.0f64;
    for v in &vecs {
        let u = unit(*v);
        let c = (u[0] * axis[0] + u[1] * axis[1] + u[2] * axis[2]).clamp(-1.0, 1.0);
        half = half.max(c.acos());
    }
    // A margin for the rounding of the coefficients and of this computation.
    let half = half + 1e-9;
    (half < std::f64::consts::FRAC_PI_2).then_some((axis, half))
}

/// Whether two cones hold no parallel (or antiparallel) pair of vectors.
fn cones_apart(a: &([f64; 3], f64), b: &([f64; 3], f64)) -> bool {
    let c = (a.0[0] * b.0[0] + a.0[1] * b.0[1] + a.0[2] * b.0[2]).clamp(-1.0, 1.0);
    let angle = c.acos();
    let reach = a.1 + b.1 + 1e-9;
    angle > reach && std::f64::consts::PI - angle > reach
}

fn unit_or_zero(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if l > 0.0 {
        v.map(|x| x / l)
    } else {
        [0.0; 3]
    }
}

/// A patch's data for a pair: its evaluator and its interval jets.
struct Side {
    eval: Evaluator,
    jets: DiagonalTest,
}

/// The real parameter box of a solver box's variables `offset, offset + 1`.
fn params(same: bool, cell: &[[f64; 2]], offset: usize) -> ([f64; 2], [f64; 2]) {
    let a = unwarp_interval(cell[offset], lambda(same, offset));
    let b = unwarp_interval(cell[offset + 1], lambda(same, offset + 1));
    ([a[0], b[0]], [a[1], b[1]])
}

fn boxes_meet(a: &[Interval; 3], b: &[Interval; 3]) -> bool {
    (0..3).all(|k| a[k].lo() <= b[k].hi() && b[k].lo() <= a[k].hi())
}

/// The bitangents of one pair of patches (`same`: the first is the second; the indices are
/// only recorded).
///
/// # Examples
/// ```
/// use limn::analysis::bitangent::curves::{pair_bitangents, BitangentOptions};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let q = |n: i64| Rational::from(n);
/// // z = x² + y², a convex bowl: no two points share a tangent plane.
/// let p = shapes::graph(&[(2, 0, q(1)), (0, 2, q(1))], [q(-1), q(1)], [q(-1), q(1)]);
/// let b = pair_bitangents(&p, 0, &p, 0, &BitangentOptions::default());
/// assert!(b.is_certified() && b.branches.is_empty());
/// ```
pub fn pair_bitangents(
    first: &RationalPatch,
    i: usize,
    second: &RationalPatch,
    j: usize,
    options: &BitangentOptions,
) -> PairBitangents {
    let same = i == j;
    let mut out = empty_pair([i, j], options);
    // Past the deadline before any set-up (the jets and evaluators of both patches are exact
    // products, the costliest step of a small pair): the whole pair is unresolved.
    if past(options.solver.deadline) {
        let half = Rational::from((1, 2));
        let at = [first, second].map(|p| p.eval(&half, &half).map(|c| c.to_f64()));
        out.unresolved.push(not_searched([i, j], at));
        return out;
    }
    let sides = [first, second].map(|patch| Side {
        eval: Evaluator::new(patch),
        jets: DiagonalTest::new(patch),
    });
    let centre = |cell: &[[f64; 2]]| -> [[f64; 3]; 2] {
        std::array::from_fn(|k| {
            let (lo, hi) = params(same, cell, 2 * k);
            sides[k]
                .eval
                .eval(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]))[0]
        })
    };
    let (eqs, divided) = bitangent_system(first, second);
    out.divided_sides = divided;
    let lambdas: Vec<Rational> = (0..4)
        .map(|k| Rational::from(PAIR_WARP[if same { k % 2 } else { k }]))
        .collect();
    let eqs: Vec<_> = eqs.iter().map(|p| warp(p, &lambdas)).collect();
    let accuracy: Option<[Accuracy; 2]> = options.tolerance.and_then(|_| {
        Some([
            Accuracy::new(first, [lambda(same, 0), lambda(same, 1)])?,
            Accuracy::new(second, [lambda(same, 2), lambda(same, 3)])?,
        ])
    });
    let mut opts = options.solver.clone();
    if let (Some([a, b]), Some(t)) = (&accuracy, options.tolerance) {
        // An arc is accurate when its bound in space on both patches (the one reported)
        // meets the tolerance.
        opts.tolerance = Some(vec![f64::INFINITY; 4]);
        let (a, b) = (a.clone(), b.clone());
        opts.accept = Some(ArcAccept(std::sync::Arc::new(move |from, to, dev| {
            a.error_of(from, to, dev, 0) <= t && b.error_of(from, to, dev, 2) <= t
        })));
    }
    let coincidence_depth = options.coincidence_depth;
    let seams = if same {
        Vec::new()
    } else {
        shared_sides(first, second)
    };
    let verdict = |cell: &[[f64; 2]], depth: u32| -> BoxVerdict {
        if same && mirror_dropped(cell, depth) {
            return BoxVerdict::Drop;
        }
        let (lo1, hi1) = params(same, cell, 0);
        let (lo2, hi2) = params(same, cell, 2);
        if depth >= 1 && normals_apart(&sides[0].jets, &sides[1].jets, (lo1, hi1), (lo2, hi2)) {
            return BoxVerdict::Drop;
        }
        if same && depth >= 1 {
            let h = Rect::new(lo1, hi1).hull(&Rect::new(lo2, hi2));
            if h.width(0) <= 0.5 && h.width(1) <= 0.5 && sides[0].jets.excludes(h.lo, h.hi) {
                return BoxVerdict::Drop;
            }
        }
        if depth >= 1
            && seams.iter().any(|side| {
                let (b1, b2) = (Rect::new(lo1, hi1), Rect::new(lo2, hi2));
                seam_excludes(&sides[0].jets, &sides[1].jets, side, b1, b2)
            })
        {
            return BoxVerdict::Drop;
        }
        if depth >= coincidence_depth {
            let a = sides[0].jets.image(lo1, hi1);
            let b = sides[1].jets.image(lo2, hi2);
            if !matches!((a, b), (Some(a), Some(b)) if !boxes_meet(&a, &b)) {
                return BoxVerdict::Unresolved(Reason::CoincidentPieces);
            }
        }
        BoxVerdict::Solve
    };
    let curve = solve_space_curve_excluding(&eqs, &[], &verdict, &opts);
    let mut lines: [Vec<TangentLine>; 2] = [Vec::new(), Vec::new()];
    out.singular_points = curve
        .singular_points
        .iter()
        .map(|sp| {
            let x = sp.unwarped(&lambdas);
            for (side, (patch, k)) in [(first, 0), (second, 2)].into_iter().enumerate() {
                for axis in 0..2 {
                    if let Some(l) = tangent_plane_along(patch, axis, &x[k + axis]) {
                        if !lines[side].contains(&l) {
                            lines[side].push(l);
                        }
                    }
                }
            }
            let f: Vec<f64> = x.iter().map(Rational::to_f64).collect();
            BitangentSingular {
                patches: [i, j],
                exact: x.iter().map(ToString::to_string).collect(),
                at: [
                    sides[0].eval.eval(f[0], f[1])[0],
                    sides[1].eval.eval(f[2], f[3])[0],
                ],
                branches: sp.branches,
            }
        })
        .collect();
    out.boxes = curve.boxes;
    out.escalations = curve.escalations.clone();
    out.unresolved = curve
        .unresolved
        .iter()
        .map(|u| {
            let cell: Vec<[f64; 2]> = (0..4)
                .map(|k| unwarp_interval(u.cell[k], lambda(same, k)))
                .collect();
            BitangentUnresolved {
                patches: [i, j],
                at: centre(&u.cell),
                cell,
                reason: u.reason.clone(),
            }
        })
        .collect();
    explain_plane_sets(&mut out, &lines);
    out.tangent_lines = lines;
    if let (Some([a, b]), Some(t)) = (&accuracy, options.tolerance) {
        let bound = curve
            .arcs
            .iter()
            .map(|arc| Some(a.error(&curve, arc, 0)?.max(b.error(&curve, arc, 2)?)))
            .try_fold(0.0f64, |m, e| e.map(|e| m.max(e)));
        out.error_bound = bound;
        out.within_tolerance = bound.is_some_and(|b| b <= t);
    }
    out.branches = branches(&curve, same, &sides, [i, j]);
    out
}

/// For a patch with itself: pairs of crossings that are mirror images of each other, `(x, y)`
/// with `y = σ(x)`: `x` ends a branch away from the boundary (at the border of the dropped
/// half), `σ(x)` lies in the uniqueness region of the crossing `y` on the mirrored hyperplane,
/// and `σ(x)` solves the system because the tangents at the second point of `x` are
/// independent (`proofs/bitangent.md`, Lemma 3).
fn mirror_pairs(curve: &SpaceCurve, jets: &DiagonalTest) -> Vec<(usize, usize)> {
    let mut degree = vec![0usize; curve.crossings.len()];
    for a in &curve.arcs {
        degree[a.from] += 1;
        degree[a.to] += 1;
    }
    let swap = [2, 3, 0, 1];
    let mut pairs = Vec::new();
    for (x, c) in curve.crossings.iter().enumerate() {
        if degree[x] != 1 || c.on_boundary || c.singular.is_some() {
            continue;
        }
        let mirrored: Vec<[f64; 2]> = (0..4).map(|k| c.enclosure[swap[k]]).collect();
        let axis = swap[c.axis];
        let face: Vec<[f64; 2]> = mirrored
            .iter()
            .enumerate()
            .filter(|&(k, _)| k != axis)
            .map(|(_, e)| *e)
            .collect();
        let Some(y) = curve.crossings.iter().position(|d| {
            d.axis == axis
                && d.at == c.at
                && face
                    .iter()
                    .zip(&d.unique_in)
                    .all(|(a, b)| b[0] <= a[0] && a[1] <= b[1])
        }) else {
            continue;
        };
        let (lo, hi) = params(true, &c.enclosure, 2);
        if y != x && jets.tangents_independent(lo, hi) && !pairs.contains(&(y, x)) {
            pairs.push((x, y));
        }
    }
    pairs
}

/// Chains the solver's arcs (and, for a patch with itself, the mirror joins) into branches of
/// pairs, each pair once.
fn branches(
    curve: &SpaceCurve,
    same: bool,
    sides: &[Side; 2],
    patches: [usize; 2],
) -> Vec<BitangentBranch> {
    let mirrors = if same {
        mirror_pairs(curve, &sides[0].jets)
    } else {
        Vec::new()
    };
    let mut edges: Vec<(usize, usize)> = curve.arcs.iter().map(|a| (a.from, a.to)).collect();
    edges.extend(&mirrors);
    // A side of the domain, or a singular point whose branches are proven, ends a branch.
    let boundary = |v: usize| curve.crossings[v].on_boundary;
    let branch_point = |v: usize| curve.crossings[v].singular.is_some();
    let point = |v: usize, flipped: bool| -> BitangentPoint {
        let t = curve.crossings[v].point();
        let x: Vec<f64> = (0..4).map(|k| unwarp(t[k], lambda(same, k))).collect();
        let (a, b) = if flipped { (2, 0) } else { (0, 2) };
        let [p, pu, pv] = sides[0].eval.eval(x[a], x[a + 1]);
        let [q, ..] = sides[1].eval.eval(x[b], x[b + 1]);
        BitangentPoint {
            first_uv: [x[a], x[a + 1]],
            second_uv: [x[b], x[b + 1]],
            p,
            q,
            line: unit_or_zero(std::array::from_fn(|k| q[k] - p[k])),
            normal: unit_or_zero(cross(pu, pv)),
        }
    };
    // The lines of an arc's pairs: q − p over its tube (the two points' boxes are independent,
    // so the difference of the surfaces' enclosures encloses it).
    let arc_error = |arc: usize, ends: [[f64; 3]; 2]| {
        let tube = curve.arc_tube(&curve.arcs[arc]);
        let (lo1, hi1) = params(same, &tube, 0);
        let (lo2, hi2) = params(same, &tube, 2);
        let p = sides[0].jets.image(lo1, hi1)?;
        let q = sides[1].jets.image(lo2, hi2)?;
        piece_error(&std::array::from_fn(|k| q[k].sub(&p[k])), &ends)
    };
    chain(&edges, curve.crossings.len(), &boundary, &branch_point)
        .into_iter()
        .map(|c| {
            // Across a mirror join the next crossings are the other order of the same pairs.
            let mut flipped = false;
            let mut points = Vec::with_capacity(c.vertices.len());
            let mut errors = Vec::with_capacity(c.edges.len());
            for (k, &v) in c.vertices.iter().enumerate() {
                if k > 0 {
                    let u = c.vertices[k - 1];
                    if mirrors.contains(&(u, v)) || mirrors.contains(&(v, u)) {
                        flipped = !flipped;
                        continue;
                    }
                }
                points.push(point(v, flipped));
            }
            // Each solver arc joins two drawn points whose lines are those of its crossings (a
            // mirror join draws nothing: its ends are one pair in two orders).
            for (k, &e) in c.edges.iter().enumerate() {
                if e < curve.arcs.len() {
                    let ends = [c.vertices[k], c.vertices[(k + 1) % c.vertices.len()]];
                    errors.push(arc_error(e, ends.map(|v| point(v, false).line)));
                }
            }
            BitangentBranch {
                patches,
                points,
                closed: c.closed,
                complete: c.complete,
                line_error: largest(errors),
            }
        })
        .collect()
}

/// The bitangents of every pair of patches of a model, pairs pruned by their normal cones and
/// solved in parallel: certified topology, and with a tolerance every drawn segment within it
/// (`proofs/bitangent.md`).
///
/// # Errors
/// None today (the curves do not depend on a view); the `Result` is the shape every entry
/// point has.
///
/// # Examples
/// ```
/// use limn::{bitangent_curves, BitangentOptions, Model};
/// use limn::number::Rational;
/// let q = |n: i64| Rational::from(n);
/// // A convex bowl z = x² + y² + xy/3: no two points share a tangent plane.
/// let bowl = limn::testing::shapes::graph(
///     &[(2, 0, q(1)), (0, 2, q(1)), (1, 1, Rational::from((1, 3)))],
///     [q(-1), q(1)],
///     [q(-1), q(2)],
/// );
/// let model = Model::from_patches(limn::model::Format::Json, vec![bowl]);
/// let b = bitangent_curves(&model, &BitangentOptions::default())?;
/// assert!(b.is_certified());
/// assert!(b.pairs.iter().all(|p| p.branches.is_empty()));
/// # Ok::<(), limn::Error>(())
/// ```
pub fn bitangent_curves(model: &Model, opts: &BitangentOptions) -> Result<BitangentCurves, Error> {
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    let r = pairs(&frame.model(model), opts)?;
    Ok(r.in_model_frame(&frame, opts.tolerance))
}

/// A pair left unresolved by the time limit before it was set up, located at the patches'
/// centres.
fn not_searched(patches: [usize; 2], at: [[f64; 3]; 2]) -> BitangentUnresolved {
    BitangentUnresolved {
        patches,
        at,
        cell: vec![[0.0, 1.0]; 4],
        reason: Reason::TimeLimit,
    }
}

/// A pair past the deadline: its result with only [`not_searched`].
fn late_pair(patches: [usize; 2], at: [[f64; 3]; 2], opts: &BitangentOptions) -> PairBitangents {
    let mut out = empty_pair(patches, opts);
    out.unresolved.push(not_searched(patches, at));
    out
}

/// A pair's result before anything is found.
fn empty_pair(patches: [usize; 2], opts: &BitangentOptions) -> PairBitangents {
    PairBitangents {
        patches,
        branches: Vec::new(),
        unresolved: Vec::new(),
        singular_points: Vec::new(),
        plane_sets: Vec::new(),
        tangent_lines: [Vec::new(), Vec::new()],
        boxes: 0,
        escalations: Escalations::default(),
        divided_sides: Vec::new(),
        error_bound: None,
        within_tolerance: opts.tolerance.is_none(),
    }
}

/// [`bitangent_curves`] of the model as it is given.
fn pairs(model: &Model, opts: &BitangentOptions) -> Result<BitangentCurves, Error> {
    let patches: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
    let cones: Vec<Option<([f64; 3], f64)>> = patches.par_iter().map(|p| normal_cone(p)).collect();
    let mut todo = Vec::new();
    let mut pruned = 0;
    for i in 0..patches.len() {
        for j in i..patches.len() {
            if i != j {
                if let (Some(a), Some(b)) = (&cones[i], &cones[j]) {
                    if cones_apart(a, b) {
                        pruned += 1;
                        continue;
                    }
                }
            }
            todo.push((i, j));
        }
    }
    let excluded: Vec<bool> = patches
        .par_iter()
        .map(|p| {
            // Past the deadline the pair is kept, and left unresolved by its own check.
            !past(opts.solver.deadline) && DiagonalTest::new(p).excludes([0.0, 0.0], [1.0, 1.0])
        })
        .collect();
    todo.retain(|&(i, j)| i != j || !excluded[i]);
    // The patches' centres, for the pairs the deadline leaves unsearched (once per patch, not
    // an exact evaluation per pair: 180,000 pairs of 600 patches cost seconds that way).
    let half = Rational::from((1, 2));
    let centres: Vec<[f64; 3]> = patches
        .par_iter()
        .map(|p| p.eval(&half, &half).map(|c| c.to_f64()))
        .collect();
    let mut pairs: Vec<PairBitangents> = todo
        .par_iter()
        .map(|&(i, j)| {
            if past(opts.solver.deadline) {
                late_pair([i, j], [centres[i], centres[j]], opts)
            } else {
                pair_bitangents(patches[i], i, patches[j], j, opts)
            }
        })
        .collect();
    // A line along which a plane is tangent, found through one pair, serves every pair of its
    // patch: the sets a pair's own singular points missed (the rim's opposite patches).
    let mut lines: Vec<Vec<TangentLine>> = vec![Vec::new(); patches.len()];
    for p in &pairs {
        for (side, &k) in p.patches.iter().enumerate() {
            for l in &p.tangent_lines[side] {
                if !lines[k].contains(l) {
                    lines[k].push(l.clone());
                }
            }
        }
    }
    for p in pairs.iter_mut() {
        let [i, j] = p.patches;
        explain_plane_sets(p, &[lines[i].clone(), lines[j].clone()]);
    }
    Ok(BitangentCurves {
        patches: patches.len(),
        pairs,
        pruned,
        excluded_self: excluded.iter().filter(|e| **e).count(),
        pairs_total: patches.len() * (patches.len() + 1) / 2,
    })
}
