//! STEP topology (ISO 10303-42): faces, their bounds and loops, oriented edges and edge curves
//! with their pcurves, read into trimmed faces on exact patches and the B-rep's topology.

use super::geometry::{cross3, dot, Curve, Cylinder, PlaneFrame, StepSurface};
use super::Reader;
use crate::io::trimmed::{self, DomainFailure, SurfaceInfo};
use crate::io::{Place, ReadError};
use crate::model::{
    Brep, BrepEdge, Face, Format, LoopError, Model, ModelPatch, PatchSource, TrimLoop, Warning,
};
use crate::number::Rational;
use crate::surface::{NurbsCurve, NurbsSurface, ParameterCurve, Point3, RationalPatch};
use std::collections::{BTreeMap, BTreeSet};

/// A loop as read: its `FACE_BOUND` number, whether it is the outer bound, and its edges' pcurves
/// with their places among the B-rep edges.
type ReadLoop = (u64, bool, Vec<(ParameterCurve, Option<usize>)>);

/// The most Bézier pieces one curve may split into.
const MAX_CURVE_PIECES: usize = 100_000;

/// How far (max norm) an edge's vertex may lie from the end of its model-space B-spline curve
/// to be taken as that end, relative to `1 +` the curve's largest control-point coordinate.
const END_MATCH: (i64, i64) = (1, 1_000_000);

/// How far an edge's vertex may lie from its pcurve's end mapped onto the surface, relative to
/// `1 +` the surface's largest control-point coordinate, before the face is used untrimmed.
const VERTEX_GAP: f64 = 1e-5;

/// How far (relative to the larger side of the domain) a trimming curve may leave its surface's
/// parameter domain and have its face used untrimmed rather than refused.
const OUTSIDE_DOMAIN: f64 = 1e-3;

/// [`trimmed::PARAMETER_GAP`], the gap a loop is closed across, as a fraction of the domain's side.
const PARAMETER_GAP_F64: f64 = trimmed::PARAMETER_GAP.0 as f64 / trimmed::PARAMETER_GAP.1 as f64;

/// A pcurve range whose ends lie this near the edge's vertices on the surface (relative to
/// `1 +` their largest coordinate) is taken without searching for the nearest parameters.
const NEAR_VERTEX: f64 = 1e-7;

/// One edge of a loop as read: the pcurve pieces it may use in the loop's direction (two for
/// a seam, whose pcurves lie on both sides of the surface's seam), its B-rep edge, and its
/// start vertex along the loop.
struct LoopEdge {
    candidates: Vec<Vec<ParameterCurve>>,
    edge: usize,
    start: Point3,
}

/// The topology gathered while faces are read.
#[derive(Default)]
struct Topology {
    /// Edges by `EDGE_CURVE` number: their place in `edges`.
    index: BTreeMap<u64, usize>,
    edges: Vec<BrepEdge>,
    vertices: BTreeSet<u64>,
    faces: usize,
    loops: usize,
    inner_loops: usize,
}

impl Topology {
    fn use_edge(&mut self, id: u64, ends: [Point3; 2]) -> usize {
        let next = self.edges.len();
        let i = *self.index.entry(id).or_insert(next);
        if i == next {
            self.edges.push(BrepEdge {
                list: id as usize,
                index: 0,
                uses: 0,
                ends,
            });
        }
        self.edges[i].uses += 1;
        i
    }
}

/// What becomes of a face that is not read as trimmed.
enum Untrimmed {
    /// Its surface is used whole.
    Whole(String),
    /// It is left out (its surface is not read, or a plane without usable loops).
    LeftOut(String),
}

/// The end points of a B-spline curve's domain (in model space, or in a surface's
/// parameters for a pcurve), by exact de Boor evaluation.
fn nurbs_ends(c: &Curve) -> Option<[Vec<Rational>; 2]> {
    let Curve::Nurbs {
        degree,
        knots,
        points,
        weights,
    } = c
    else {
        return None;
    };
    fn ends<const K: usize>(
        degree: usize,
        knots: &[Rational],
        points: &[Vec<Rational>],
        weights: &[Rational],
    ) -> Option<[Vec<Rational>; 2]> {
        let n = NurbsCurve::<K>::new(degree, knots.to_vec(), points, weights, None).ok()?;
        let [a, b] = n.range().clone();
        Some([n.eval(&a), n.eval(&b)])
    }
    match points.first()?.len() {
        2 => ends::<3>(*degree, knots, points, weights),
        3 => ends::<4>(*degree, knots, points, weights),
        _ => None,
    }
}

/// The max-norm distance of two points, in f64.
fn distance(a: &[Rational], b: &[Rational]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| Rational::from(x - y).abs().to_f64())
        .fold(0.0, f64::max)
}

/// The largest absolute coordinate of some points, plus 1.
fn scale<'a>(points: impl Iterator<Item = &'a Rational>) -> Rational {
    points.map(|x| x.clone().abs()).max().unwrap_or_default() + Rational::from(1)
}

/// The curve's parameter at a vertex: exact on a line (the foot of the perpendicular); on a
/// B-spline curve the end of its domain the vertex is (the preferred end first), if it is one.
fn parameter_at(
    c: &Curve,
    ends: Option<&[Vec<Rational>; 2]>,
    p: &[Rational],
    prefer_end: bool,
) -> Option<Rational> {
    match c {
        Curve::Line { p: o, d } => {
            let diff: Vec<Rational> = p
                .iter()
                .zip(o)
                .map(|(a, b)| Rational::from(a - b))
                .collect();
            Some(dot(&diff, d) / dot(d, d))
        }
        Curve::Nurbs { points, .. } => {
            let ends = ends?;
            let tol = scale(points.iter().flatten()) * Rational::from(END_MATCH);
            let domain = c.domain()?;
            let near = |k: usize| {
                ends[k]
                    .iter()
                    .zip(p)
                    .all(|(a, b)| Rational::from(a - b).abs() <= tol)
            };
            let order = if prefer_end { [1, 0] } else { [0, 1] };
            order
                .into_iter()
                .find(|&k| near(k))
                .map(|k| domain[k].clone())
        }
    }
}

/// The parameter interval in which the line `p + t d` lies in the box `domain`, if any.
fn clip_line(
    p: &[Rational],
    d: &[Rational],
    domain: &[[Rational; 2]; 2],
) -> Option<(Rational, Rational)> {
    let mut lo: Option<Rational> = None;
    let mut hi: Option<Rational> = None;
    for k in 0..2 {
        let [a, b] = &domain[k];
        if d[k] == 0 {
            if p[k] < *a || p[k] > *b {
                return None;
            }
            continue;
        }
        let ta = Rational::from(a - &p[k]) / &d[k];
        let tb = Rational::from(b - &p[k]) / &d[k];
        let (t0, t1) = if ta <= tb { (ta, tb) } else { (tb, ta) };
        lo = Some(lo.map_or(t0.clone(), |l| l.max(t0)));
        hi = Some(hi.map_or(t1.clone(), |h| h.min(t1)));
    }
    let (lo, hi) = (lo?, hi?);
    (lo < hi).then_some((lo, hi))
}

/// How many samples the search for a vertex's parameter on a pcurve starts with.
const INVERSION_SAMPLES: usize = 256;

/// A pcurve's point at `t` in f64 (`t` clamped to a B-spline curve's domain).
fn curve_point_f64(c: &Curve, t: f64) -> [f64; 2] {
    match c {
        Curve::Line { p, d } => [0, 1].map(|k| p[k].to_f64() + t * d[k].to_f64()),
        Curve::Nurbs {
            degree,
            knots,
            points,
            weights,
        } => {
            let knots: Vec<f64> = knots.iter().map(Rational::to_f64).collect();
            let hom: Vec<[f64; 3]> = points
                .iter()
                .zip(weights)
                .map(|(p, w)| {
                    let w = w.to_f64();
                    [p[0].to_f64() * w, p[1].to_f64() * w, w]
                })
                .collect();
            let h = crate::surface::de_boor_f64(*degree, &knots, &hom, t);
            [h[0] / h[2], h[1] / h[2]]
        }
    }
}

/// The parameter in `[lo, hi]` at which the pcurve, mapped onto the surface by `at`, comes
/// nearest the point `target`: a float search (samples, then golden sections around the best
/// one). Only a candidate: the vertex check of the face judges whichever range is taken.
fn nearest_parameter(
    c: &Curve,
    at: &dyn Fn(f64, f64) -> [f64; 3],
    (lo, hi): (f64, f64),
    target: [f64; 3],
) -> Option<f64> {
    let gap = |t: f64| {
        let [u, v] = curve_point_f64(c, t);
        let p = at(u, v);
        (0..3).map(|k| (p[k] - target[k]).abs()).fold(0.0, f64::max)
    };
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return None;
    }
    let step = (hi - lo) / INVERSION_SAMPLES as f64;
    let best = (0..=INVERSION_SAMPLES)
        .map(|i| (gap(lo + i as f64 * step), i))
        .min_by(|x, y| x.0.total_cmp(&y.0))?
        .1;
    let (mut a, mut b) = (
        (lo + (best as f64 - 1.0) * step).max(lo),
        (lo + (best as f64 + 1.0) * step).min(hi),
    );
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (x, y) = (b - r * (b - a), a + r * (b - a));
        if gap(x) <= gap(y) {
            b = y;
        } else {
            a = x;
        }
    }
    let t = (a + b) / 2.0;
    t.is_finite().then_some(t)
}

/// The parameters `((P - o)·x, (P - o)·y)` of a point's foot on a plane, exact.
fn plane_uv(frame: &PlaneFrame, p: &[Rational]) -> Vec<Rational> {
    let PlaneFrame { o, x, y } = frame;
    let d: Vec<Rational> = p
        .iter()
        .zip(o)
        .map(|(a, b)| Rational::from(a - b))
        .collect();
    vec![dot(&d, x), dot(&d, y)]
}

/// The surface point at `(u, v)`, exact; on a B-spline surface at the nearest point of its
/// domain (loops that leave the domain are judged by [`trimmed::check_in_domain`]).
fn surface_point(s: &StepSurface, u: &Rational, v: &Rational) -> Point3 {
    match s {
        StepSurface::Nurbs(n, _) => {
            let d = n.domain();
            let clamp = |x: &Rational, r: &[Rational; 2]| {
                if *x < r[0] {
                    r[0].clone()
                } else if *x > r[1] {
                    r[1].clone()
                } else {
                    x.clone()
                }
            };
            n.eval(&clamp(u, &d[0]), &clamp(v, &d[1]))
        }
        StepSurface::Plane(f) => {
            [0, 1, 2].map(|k| &f.o[k] + Rational::from(u * &f.x[k]) + Rational::from(v * &f.y[k]))
        }
        // t is taken modulo 4 (a loop laid on a turn [m, m + 4]).
        StepSurface::Cylinder(c) => surface_point_of(c, u, v),
    }
}

/// A cylinder's point at `(t, v)` (`t` modulo 4).
fn surface_point_of(c: &Cylinder, t: &Rational, v: &Rational) -> Point3 {
    c.point(t, v).unwrap_or_else(|| c.circle.c.clone())
}

/// A parameter curve moved by `d` in `t` (exact: `X + d W` in homogeneous form).
fn shifted(c: &ParameterCurve, d: &Rational) -> ParameterCurve {
    let hom = c
        .homogeneous()
        .iter()
        .map(|h| {
            [
                &h[0] + Rational::from(d * &h[2]),
                h[1].clone(),
                h[2].clone(),
            ]
        })
        .collect();
    ParameterCurve::from_homogeneous(hom).unwrap_or_else(|| c.clone())
}

/// The least and largest `v` of the loops' control points.
fn heights(loops: &[ReadLoop]) -> Option<[Rational; 2]> {
    let mut vs = loops
        .iter()
        .flat_map(|(_, _, c)| c.iter())
        .flat_map(|(c, _)| c.points())
        .map(|p| p[1].clone());
    let first = vs.next()?;
    let (lo, hi) = vs.fold((first.clone(), first), |(lo, hi), v| {
        (lo.min(v.clone()), hi.max(v))
    });
    Some([lo, hi])
}

/// The least and largest `t` of a loop's control points.
fn t_range(curves: &[(ParameterCurve, Option<usize>)]) -> Option<(Rational, Rational)> {
    let mut ts = curves
        .iter()
        .flat_map(|(c, _)| c.points())
        .map(|p| p[0].clone());
    let first = ts.next()?;
    Some(ts.fold((first.clone(), first), |(lo, hi), t| {
        (lo.min(t.clone()), hi.max(t))
    }))
}

/// A cylinder face's loops laid out on one turn `[m, m + 4]` of `t`: where a loop jumps across
/// the seam (a piece starting 4 away in `t` from where the one before ends, at its height), the
/// rest of the loop is moved by 4 to join it; each loop left is then moved by a multiple
/// of 4 into the turn, for the least whole quarter `m` whose turn holds them all. A loop that
/// goes once round (its end 4 from its start) is an end circle of a band: two such, each at one
/// height, the face's lowest and highest, make the face's outer boundary the whole band (the
/// patch's domain), and are removed (`.1` is then true). `Err` when the loops fit no such
/// turn, or go round otherwise. `[lo, hi]` are the loops' least and largest heights.
fn on_one_turn(
    loops: &mut Vec<ReadLoop>,
    [lo, hi]: &[Rational; 2],
) -> Result<(usize, bool), String> {
    let four = Rational::from(4);
    // Heights that meet across the seam within the gap the loops are closed across (a
    // fraction [`trimmed::PARAMETER_GAP`] of the domain's longer side) are one point.
    let level = PARAMETER_GAP_F64 * Rational::from(hi - lo).to_f64().max(4.0);
    let mut round = Vec::new();
    for (k, (_, _, curves)) in loops.iter_mut().enumerate() {
        let mut offset = Rational::from(0);
        for i in 0..curves.len() {
            if i > 0 {
                let end = curves[i - 1].0.end();
                let start = curves[i].0.start();
                let jump = Rational::from(&end[0] - &start[0]) - &offset;
                let dv = Rational::from(&start[1] - &end[1]).abs().to_f64();
                if jump.clone().abs() == four {
                    if dv > level {
                        return Err(format!(
                            "a loop crosses the seam with its heights {dv:.3e} apart there"
                        ));
                    }
                    offset += jump;
                }
            }
            if offset != 0 {
                curves[i].0 = shifted(&curves[i].0, &offset);
            }
        }
        let (first, last) = match (curves.first(), curves.last()) {
            (Some(f), Some(l)) => (f.0.start(), l.0.end()),
            _ => continue,
        };
        let dv = Rational::from(&first[1] - &last[1]).abs().to_f64();
        if Rational::from(&last[0] - &first[0]).abs() == four && dv <= level {
            round.push(k);
        }
    }
    let band = !round.is_empty();
    if band {
        let at = |k: usize| -> Option<Rational> {
            let mut vs = loops[k]
                .2
                .iter()
                .flat_map(|(c, _)| c.points())
                .map(|p| p[1].clone());
            let v = vs.next()?;
            vs.all(|w| w == v).then_some(v)
        };
        let ends = round.len() == 2
            && matches!((at(round[0]), at(round[1])), (Some(a), Some(b))
                if (a == *lo && b == *hi) || (a == *hi && b == *lo));
        if !ends {
            return Err(
                "a loop goes round the cylinder other than as an end circle of a band".into(),
            );
        }
        for k in round.into_iter().rev() {
            loops.remove(k);
        }
    }
    // (A band's end circles are gone: its holes choose the turn like any loop.)
    'turn: for m in 0..4usize {
        let lo = Rational::from(m as u32);
        let hi = Rational::from(m as u32 + 4);
        let mut moves = Vec::with_capacity(loops.len());
        for (_, _, curves) in loops.iter() {
            let Some((a, b)) = t_range(curves) else {
                moves.push(Rational::from(0));
                continue;
            };
            let mut d = Rational::from(0);
            while Rational::from(&a + &d) < lo {
                d += 4;
            }
            while Rational::from(&a + &d) >= hi {
                d -= 4;
            }
            if Rational::from(&b + &d) > hi {
                continue 'turn;
            }
            moves.push(d);
        }
        for ((_, _, curves), d) in loops.iter_mut().zip(moves) {
            if d != 0 {
                for (c, _) in curves.iter_mut() {
                    *c = shifted(c, &d);
                }
            }
        }
        return Ok((m, band));
    }
    Err("its loops fit no one turn of the cylinder starting at a quarter".into())
}

impl Reader<'_> {
    /// Reads the model: every face of the file, the patches of their surfaces, the B-rep.
    pub(super) fn read_model(&mut self) -> Result<Model, ReadError> {
        let mut face_ids = Vec::new();
        let mut shells = 0;
        for (id, inst) in &self.ex.instances {
            if inst.complex {
                continue;
            }
            match inst.records[0].name.as_str() {
                "ADVANCED_FACE" | "FACE_SURFACE" => face_ids.push(*id),
                "CLOSED_SHELL" | "OPEN_SHELL" => shells += 1,
                _ => {}
            }
        }
        if face_ids.is_empty() {
            return Err(ReadError::new(
                self.name,
                Place::File,
                "no face (ADVANCED_FACE or FACE_SURFACE) in the file",
            ));
        }
        let mut model = Model::from_patches(Format::Step, Vec::new());
        // An assembly's placements of its parts (not applied).
        model.placements_ignored = self
            .ex
            .instances
            .values()
            .filter(|i| {
                i.records.iter().any(|r| {
                    matches!(
                        r.name.as_str(),
                        "REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION" | "MAPPED_ITEM"
                    )
                })
            })
            .count();
        if model.placements_ignored > 0 {
            self.warnings.push(Warning {
                place: "file".into(),
                message: format!(
                    "an assembly: {} placements of parts are not applied yet (each part is read in its own coordinates)",
                    model.placements_ignored
                ),
            });
        }
        let mut surfaces: BTreeMap<u64, (SurfaceInfo, StepSurface)> = BTreeMap::new();
        let mut topo = Topology::default();
        let mut untrimmed: BTreeMap<String, Vec<u64>> = BTreeMap::new();
        let mut largest_gap = 0.0f64;
        for id in face_ids {
            match self.face(id, &mut model, &mut surfaces, &mut topo, &mut largest_gap)? {
                Ok(face) => model.faces.push(face),
                Err(Untrimmed::Whole(why)) => untrimmed
                    .entry(format!("face(s) used untrimmed: {why}"))
                    .or_default()
                    .push(id),
                Err(Untrimmed::LeftOut(why)) => {
                    model.left_out += 1;
                    untrimmed
                        .entry(format!("face(s) left out: {why}"))
                        .or_default()
                        .push(id)
                }
            }
        }
        if model.patches.is_empty() {
            let why = untrimmed.keys().next().cloned().unwrap_or_default();
            return Err(ReadError::new(
                self.name,
                Place::File,
                format!("no face of the file is on a surface limn reads ({why})"),
            ));
        }
        // One line per kind of reason: the instance numbers in it are named by the faces.
        let mut by_kind: BTreeMap<String, Vec<u64>> = BTreeMap::new();
        for (why, ids) in untrimmed {
            by_kind
                .entry(without_numbers(&why))
                .or_default()
                .extend(ids);
        }
        for (why, mut ids) in by_kind {
            ids.sort_unstable();
            let list: Vec<String> = ids.iter().take(8).map(|i| format!("#{i}")).collect();
            let more = if ids.len() > 8 { ", …" } else { "" };
            self.warnings.push(Warning {
                place: format!("{}{more}", list.join(", ")),
                message: format!("{} {why}", ids.len()),
            });
        }
        if self.projected.edges > 0 {
            self.warnings.push(Warning {
                place: "file".into(),
                message: format!(
                    "{} edge(s) without a pcurve on their plane faces mapped into the planes from their model-space curves, each within {:.3e} of its plane",
                    self.projected.edges, self.projected.largest_off_plane
                ),
            });
        }
        if !model.faces.is_empty() {
            let loops: usize = model.faces.iter().map(|f| f.loops().count()).sum();
            self.warnings.push(Warning {
                place: "file".into(),
                message: format!(
                    "{} trimmed face(s) with {loops} loop(s) read (see `limn info`); the largest distance of an edge's vertex from its pcurve's end on the surface is {largest_gap:.3e}",
                    model.faces.len()
                ),
            });
        }
        // The surfaces the patches come from (B-spline surfaces, planes, cylinders' faces).
        model.surfaces = model
            .patches
            .iter()
            .map(|p| p.source.surface)
            .collect::<std::collections::BTreeSet<_>>()
            .len();
        model.brep = Some(Brep {
            vertices: topo.vertices.len(),
            edges: topo.edges,
            faces: topo.faces,
            loops: topo.loops,
            inner_loops: topo.inner_loops,
            shells,
        });
        model.warnings = std::mem::take(&mut self.warnings);
        Ok(model)
    }

    /// Registers a B-spline surface's patches (once per surface).
    fn nurbs_patches(
        &mut self,
        id: u64,
        n: &NurbsSurface,
        closed: [bool; 2],
        model: &mut Model,
        surfaces: &mut BTreeMap<u64, (SurfaceInfo, StepSurface)>,
    ) -> Result<SurfaceInfo, ReadError> {
        if let Some((info, _)) = surfaces.get(&id) {
            return Ok(info.clone());
        }
        crate::io::count_bezier_points(&mut self.bezier_points, n).map_err(|m| self.err(id, m))?;
        let pieces = n.to_bezier();
        let index = model.surfaces;
        model.surfaces += 1;
        let info = SurfaceInfo::of_nurbs(index, n, &pieces, closed);
        for (span, patch) in pieces {
            model.patches.push(ModelPatch {
                surface: patch,
                source: PatchSource::of_span(index, Some(id as usize), span, &info.spans),
            });
        }
        surfaces.insert(
            id,
            (
                info.clone(),
                StepSurface::Nurbs(Box::new(n.clone()), closed),
            ),
        );
        Ok(info)
    }

    /// One face: its trimmed face, or what becomes of it and why.
    fn face(
        &mut self,
        id: u64,
        model: &mut Model,
        surfaces: &mut BTreeMap<u64, (SurfaceInfo, StepSurface)>,
        topo: &mut Topology,
        largest_gap: &mut f64,
    ) -> Result<Result<Face, Untrimmed>, ReadError> {
        let a = self.ex.instances[&id].records[0].params.clone();
        let bounds = self
            .list(id, self.attr(id, &a, 1, "bounds")?, "bounds")?
            .to_vec();
        let sid = self.reference(id, self.attr(id, &a, 2, "face_geometry")?, "face_geometry")?;
        self.logical(id, self.attr(id, &a, 3, "same_sense")?, "same_sense")?;
        topo.faces += 1;
        let surface = self.surface(id, sid)?;
        let mut why: Option<String> = surface.as_ref().err().cloned();
        // Each bound: its loop's number, whether it is the outer bound, its edges.
        let mut read: Vec<(u64, bool, Vec<LoopEdge>)> = Vec::new();
        for (k, b) in bounds.iter().enumerate() {
            let bid = self.reference(id, b, "bound")?;
            let ba = self.simple(id, bid, "bound", &["FACE_OUTER_BOUND", "FACE_BOUND"])?;
            let outer = self.ex.instances[&bid].records[0].name == "FACE_OUTER_BOUND";
            let lp = self.reference(bid, self.attr(bid, ba, 1, "bound")?, "loop")?;
            self.logical(bid, self.attr(bid, ba, 2, "orientation")?, "orientation")?;
            topo.loops += 1;
            if k > 0 {
                topo.inner_loops += 1;
            }
            match self.edge_loop(bid, lp, (sid, surface.as_ref().ok()), why.is_none(), topo)? {
                Ok(edges) if edges.is_empty() => {}
                Ok(edges) => read.push((lp, outer, edges)),
                Err(w) => {
                    why.get_or_insert(w);
                }
            }
        }
        let surface = match surface {
            Ok(s) => s,
            Err(w) => return Ok(Err(Untrimmed::LeftOut(w))),
        };
        // Planes and cylinders are unbounded: their patches are made from the face's loops.
        let is_plane = matches!(surface, StepSurface::Plane(_) | StepSurface::Cylinder(_));
        let info = match &surface {
            StepSurface::Nurbs(n, closed) => {
                Some(self.nurbs_patches(sid, n, *closed, model, surfaces)?)
            }
            StepSurface::Plane(_) | StepSurface::Cylinder(_) => None,
        };
        if let Some(w) = why {
            return Ok(Err(if is_plane {
                Untrimmed::LeftOut(format!(
                    "{w}; a plane or cylinder is bounded by its loops only"
                ))
            } else {
                Untrimmed::Whole(w)
            }));
        }
        // Seams: the pcurve nearest the loop's neighbouring edges at both ends; a seam used
        // twice takes its other pcurve the second time.
        let mut loops: Vec<ReadLoop> = Vec::new();
        let mut gaps = Vec::new();
        for (lp, outer, edges) in read {
            let mut chosen: Vec<Option<usize>> = edges
                .iter()
                .map(|e| (e.candidates.len() == 1).then_some(0))
                .collect();
            let end_of = |e: &LoopEdge, c: usize| e.candidates[c].last().map(|p| p.end());
            let start_of = |e: &LoopEdge, c: usize| e.candidates[c].first().map(|p| p.start());
            for k in 0..edges.len() {
                if chosen[k].is_some() {
                    continue;
                }
                let prev = (k + edges.len() - 1) % edges.len();
                let next = (k + 1) % edges.len();
                // The gaps to both neighbours (over the pcurves still open to a neighbour not
                // chosen yet): a seam's two pcurves may lie equally far from one neighbour.
                let options = |j: usize| match chosen[j] {
                    Some(c) => c..c + 1,
                    None => 0..edges[j].candidates.len(),
                };
                let gap = |c: usize| {
                    let before = options(prev)
                        .filter_map(|cp| {
                            Some(distance(
                                &end_of(&edges[prev], cp)?,
                                &start_of(&edges[k], c)?,
                            ))
                        })
                        .fold(f64::INFINITY, f64::min);
                    let after = options(next)
                        .filter_map(|cn| {
                            Some(distance(
                                &end_of(&edges[k], c)?,
                                &start_of(&edges[next], cn)?,
                            ))
                        })
                        .fold(f64::INFINITY, f64::min);
                    before + after
                };
                let pick =
                    (0..edges[k].candidates.len()).min_by(|&x, &y| gap(x).total_cmp(&gap(y)));
                chosen[k] = pick;
                // A seam used twice in one loop (once each way) uses each of its pcurves once.
                if let Some(c) = pick {
                    if let Some(j) = (k + 1..edges.len())
                        .find(|&j| edges[j].edge == edges[k].edge && edges[j].candidates.len() == 2)
                    {
                        chosen[j] = Some(1 - c.min(1));
                    }
                }
            }
            let mut curves = Vec::new();
            for (e, c) in edges.into_iter().zip(chosen) {
                let c = c.unwrap_or(0);
                if let Some(first) = e.candidates[c].first() {
                    gaps.push((first.start(), e.start.clone()));
                }
                let edge = e.edge;
                curves.extend(
                    e.candidates
                        .into_iter()
                        .nth(c)
                        .unwrap_or_default()
                        .into_iter()
                        .map(|p| (p, Some(edge))),
                );
            }
            loops.push((lp, outer, curves));
        }
        if loops.is_empty() {
            return Ok(Err(if is_plane {
                Untrimmed::LeftOut("a plane or cylinder without edge loops is unbounded".into())
            } else {
                Untrimmed::Whole("it has no edge loops".into())
            }));
        }
        // A cylinder face's loops on one turn; a band's end circles are its domain's sides.
        let mut cylinder = None;
        let mut band = false;
        if let StepSurface::Cylinder(_) = &surface {
            let Some(heights) = heights(&loops) else {
                return Ok(Err(Untrimmed::LeftOut("its loops have no points".into())));
            };
            match on_one_turn(&mut loops, &heights) {
                Ok((m, b)) => {
                    cylinder = Some((m, heights));
                    band = b;
                }
                Err(w) => return Ok(Err(Untrimmed::LeftOut(w))),
            }
        }
        let info = match info {
            Some(i) => i,
            None => {
                let made = match (&surface, cylinder) {
                    (StepSurface::Cylinder(c), Some((m, h))) => {
                        self.cylinder_patches(sid, c, m, h, model)?
                    }
                    _ => self.plane_patch(sid, &surface, &loops, model),
                };
                match made {
                    Some(i) => i,
                    None => {
                        return Ok(Err(Untrimmed::LeftOut(
                            "its loops bound no area of the surface".into(),
                        )))
                    }
                }
            }
        };
        // How closely the pcurves follow the edges.
        let size = match &surface {
            StepSurface::Nurbs(..) | StepSurface::Cylinder(_) => {
                let b = model
                    .patches
                    .iter()
                    .filter(|p| p.source.surface == info.index);
                scale(b.flat_map(|p| p.surface.points().iter().flatten())).to_f64()
            }
            StepSurface::Plane(f) => scale(f.o.iter()).to_f64(),
        };
        for (uv, vertex) in &gaps {
            let g = distance(&surface_point(&surface, &uv[0], &uv[1]), vertex);
            *largest_gap = largest_gap.max(g);
            if g > VERTEX_GAP * size {
                return Ok(Err(Untrimmed::Whole(format!(
                    "a pcurve's end lies {g:.3e} from its edge's vertex on the surface (more than {:.1e} of the surface's size)",
                    VERTEX_GAP
                ))));
            }
        }
        let closing = info.closing();
        let mut closed = Vec::new();
        for (lp, outer, curves) in loops {
            match TrimLoop::close(curves, &closing, Some(lp as usize)) {
                Ok(l) => closed.push((outer, l)),
                // Writers of STEP close loops to their model-space tolerance, which may leave
                // pcurves a little apart: a gap within [`OUTSIDE_DOMAIN`] of the domain's side
                // leaves the face untrimmed, a larger one is a broken file.
                Err(LoopError::Gap { gap, tolerance, .. })
                    if gap <= OUTSIDE_DOMAIN / PARAMETER_GAP_F64 * tolerance =>
                {
                    return Ok(Err(Untrimmed::Whole(format!(
                        "loop #{lp} does not close by {gap:.3e} in the surface's parameters"
                    ))))
                }
                Err(e) => return Err(self.err(lp, format!("loop: {e}"))),
            }
        }
        // The outer loop: the one the file names, else the one whose box holds every other.
        // (A band's outer boundary is its domain: every loop left is a hole.)
        let outer_at = if band {
            None
        } else {
            closed.iter().position(|(o, _)| *o).or_else(|| {
                let boxes: Vec<[[f64; 2]; 2]> = closed.iter().map(|(_, l)| loop_box(l)).collect();
                (0..boxes.len()).find(|&i| {
                    boxes.iter().all(|b| {
                        (0..2).all(|k| boxes[i][k][0] <= b[k][0] && b[k][1] <= boxes[i][k][1])
                    })
                })
            })
        };
        let mut outer = None;
        let mut inner = Vec::new();
        for (k, (_, l)) in closed.into_iter().enumerate() {
            if Some(k) == outer_at {
                outer = Some(l);
            } else {
                inner.push(l);
            }
        }
        let face = Face {
            surface: info.index,
            entity: Some(id as usize),
            domain: info.domain.clone(),
            outer,
            inner,
        };
        match trimmed::check_in_domain(&face, &info) {
            Ok(()) => Ok(Ok(face)),
            Err(DomainFailure::AcrossSeam(w)) => Ok(Err(Untrimmed::Whole(w))),
            Err(DomainFailure::Outside {
                entity,
                message,
                by,
            }) => {
                // Writers of STEP leave pcurves a little outside the domain (their tolerances
                // are in model space): a small excursion leaves the face untrimmed, a large
                // one is a broken file.
                let side = info
                    .domain
                    .iter()
                    .map(|r| Rational::from(&r[1] - &r[0]).to_f64())
                    .fold(0.0, f64::max);
                if by <= OUTSIDE_DOMAIN * side {
                    Ok(Err(Untrimmed::Whole(format!(
                        "a trimming curve leaves the surface's parameter domain by {by:.3e}"
                    ))))
                } else {
                    Err(self.err(entity.map_or(id, |e| e as u64), message))
                }
            }
        }
    }

    /// The patch of a plane over the box of its face's loops, and its information.
    fn plane_patch(
        &mut self,
        sid: u64,
        s: &StepSurface,
        loops: &[ReadLoop],
        model: &mut Model,
    ) -> Option<SurfaceInfo> {
        let mut lo: Option<[Rational; 2]> = None;
        let mut hi: Option<[Rational; 2]> = None;
        for (_, _, curves) in loops {
            for (c, _) in curves {
                for p in c.points() {
                    let l = lo.get_or_insert_with(|| [p[0].clone(), p[1].clone()]);
                    let h = hi.get_or_insert_with(|| [p[0].clone(), p[1].clone()]);
                    for k in 0..2 {
                        if p[k] < l[k] {
                            l[k] = p[k].clone();
                        }
                        if p[k] > h[k] {
                            h[k] = p[k].clone();
                        }
                    }
                }
            }
        }
        let (lo, hi) = (lo?, hi?);
        if lo[0] >= hi[0] || lo[1] >= hi[1] {
            return None;
        }
        let domain = [
            [lo[0].clone(), hi[0].clone()],
            [lo[1].clone(), hi[1].clone()],
        ];
        let mut corners = Vec::with_capacity(4);
        for u in &domain[0] {
            for v in &domain[1] {
                corners.push(surface_point(s, u, v));
            }
        }
        let patch = RationalPatch::polynomial([1, 1], corners).ok()?;
        let index = model.surfaces;
        model.surfaces += 1;
        model.patches.push(ModelPatch {
            surface: patch,
            source: PatchSource {
                surface: index,
                entity: Some(sid as usize),
                span: None,
                parameters: Some(domain.clone()),
            },
        });
        Some(SurfaceInfo {
            index,
            spans: [vec![domain[0].clone()], vec![domain[1].clone()]],
            domain,
            collapsed: [false; 4],
            closed: [false; 2],
            // A plane's edges are projected onto it exactly.
            inverter: None,
        })
    }

    /// The edges of a loop with their pcurves on surface `sid` (only counted in the topology
    /// when `want` is false), or why they cannot be used. A vertex loop has no edges.
    fn edge_loop(
        &mut self,
        from: u64,
        lp: u64,
        (sid, surface): (u64, Option<&StepSurface>),
        want: bool,
        topo: &mut Topology,
    ) -> Result<Result<Vec<LoopEdge>, String>, ReadError> {
        let inst = self.instance(from, lp, "loop")?;
        match (inst.complex, inst.records[0].name.as_str()) {
            (false, "EDGE_LOOP") => {}
            (false, "VERTEX_LOOP") => return Ok(Ok(Vec::new())),
            _ => {
                return Ok(Err(format!(
                    "its loop #{lp} is a {}, which limn does not read yet",
                    inst.kind()
                )))
            }
        }
        let a = inst.records[0].params.clone();
        let list = self
            .list(lp, self.attr(lp, &a, 1, "edge_list")?, "edge list")?
            .to_vec();
        if list.is_empty() {
            return Err(self.err(lp, "the loop has no edges"));
        }
        let mut out = Vec::with_capacity(list.len());
        let mut why = None;
        for oe in &list {
            let oe = self.reference(lp, oe, "oriented edge")?;
            let oa = self.simple(lp, oe, "edge", &["ORIENTED_EDGE"])?;
            let ec = self.reference(oe, self.attr(oe, oa, 3, "edge_element")?, "edge_element")?;
            let orientation =
                self.logical(oe, self.attr(oe, oa, 4, "orientation")?, "orientation")?;
            let ea = self
                .simple(oe, ec, "edge element", &["EDGE_CURVE"])?
                .to_vec();
            let mut ends = Vec::with_capacity(2);
            for (k, what) in [(1, "edge_start"), (2, "edge_end")] {
                let v = self.reference(ec, self.attr(ec, &ea, k, what)?, what)?;
                let va = self.simple(ec, v, "vertex", &["VERTEX_POINT"])?;
                let p = self.reference(
                    v,
                    self.attr(v, va, 1, "vertex_geometry")?,
                    "vertex_geometry",
                )?;
                let p = self.point(v, p, 3)?;
                topo.vertices.insert(v);
                ends.push([p[0].clone(), p[1].clone(), p[2].clone()]);
            }
            let ends: [Point3; 2] = [ends[0].clone(), ends[1].clone()];
            let geom =
                self.reference(ec, self.attr(ec, &ea, 3, "edge_geometry")?, "edge_geometry")?;
            let same = self.logical(ec, self.attr(ec, &ea, 4, "same_sense")?, "same_sense")?;
            let edge = topo.use_edge(ec, ends.clone());
            if !want || why.is_some() {
                continue;
            }
            match self.edge_pcurves(ec, geom, (sid, surface), &ends, same)? {
                Ok(mut candidates) => {
                    let forward = same == orientation;
                    if !forward {
                        for c in &mut candidates {
                            c.reverse();
                            for p in c.iter_mut() {
                                *p = p.reversed();
                            }
                        }
                    }
                    let start = if orientation {
                        ends[0].clone()
                    } else {
                        ends[1].clone()
                    };
                    out.push(LoopEdge {
                        candidates,
                        edge,
                        start,
                    });
                }
                Err(w) => why = Some(w),
            }
        }
        Ok(match why {
            Some(w) => Err(w),
            None => Ok(out),
        })
    }

    /// The pcurves of edge `ec` on surface `sid` over the edge's range, in the curve's own
    /// direction: one list of Bézier pieces per pcurve (two for a seam).
    fn edge_pcurves(
        &mut self,
        ec: u64,
        geom: u64,
        (sid, surface): (u64, Option<&StepSurface>),
        ends: &[Point3; 2],
        same: bool,
    ) -> Result<Result<Vec<Vec<ParameterCurve>>, String>, ReadError> {
        let inst = self.instance(ec, geom, "edge geometry")?;
        let name = inst.records[0].name.clone();
        if inst.complex
            || !matches!(
                name.as_str(),
                "SURFACE_CURVE" | "SEAM_CURVE" | "BOUNDED_SURFACE_CURVE" | "INTERSECTION_CURVE"
            )
        {
            match surface {
                Some(StepSurface::Plane(f)) => {
                    return self.projected_onto_plane(ec, geom, f, ends, same)
                }
                Some(StepSurface::Cylinder(c)) => {
                    return self.mapped_onto_cylinder(ec, geom, c, ends, same)
                }
                _ => {}
            }
            return Ok(Err(format!(
                "edge #{ec} has no parameter-space curve (its geometry is a {}); inverting a model-space curve onto the surface is not built yet",
                inst.kind()
            )));
        }
        let a = inst.records[0].params.clone();
        let c3 = self.reference(geom, self.attr(geom, &a, 1, "curve_3d")?, "curve_3d")?;
        // A cylinder's pcurves are in its angle, which no rational map takes to limn's
        // parameter: the model-space curve is mapped instead.
        if let Some(StepSurface::Cylinder(c)) = surface {
            return self.mapped_onto_cylinder(ec, c3, c, ends, same);
        }
        let assoc = self
            .list(
                geom,
                self.attr(geom, &a, 2, "associated_geometry")?,
                "associated geometry",
            )?
            .to_vec();
        let mut pcurves = Vec::new();
        for g in &assoc {
            let g = self.reference(geom, g, "associated geometry")?;
            let gi = self.instance(geom, g, "associated geometry")?;
            if gi.complex || gi.records[0].name != "PCURVE" {
                continue;
            }
            let pa = gi.records[0].params.clone();
            let basis =
                self.reference(g, self.attr(g, &pa, 1, "basis_surface")?, "basis_surface")?;
            if basis != sid {
                continue;
            }
            let rep = self.reference(
                g,
                self.attr(g, &pa, 2, "reference_to_curve")?,
                "reference_to_curve",
            )?;
            let ra = self.simple(g, rep, "representation", &["DEFINITIONAL_REPRESENTATION"])?;
            let items = self.list(rep, self.attr(rep, ra, 1, "items")?, "items")?;
            let Some(first) = items.first() else {
                return Err(self.err(rep, "the representation has no items"));
            };
            pcurves.push(self.reference(rep, first, "item")?);
        }
        if pcurves.is_empty() {
            if let Some(StepSurface::Plane(f)) = surface {
                return self.projected_onto_plane(ec, c3, f, ends, same);
            }
            return Ok(Err(format!(
                "edge #{ec} has no pcurve on the face's surface #{sid}; inverting its model-space curve onto the surface is not built yet"
            )));
        }
        // The edge's range on its curve, from the vertices (in the curve's direction).
        let curve3 = self.curve(geom, c3, 3)?;
        let range = match &curve3 {
            Ok(c) => {
                let e = nurbs_ends(c);
                let (s, t) = if same {
                    (&ends[0], &ends[1])
                } else {
                    (&ends[1], &ends[0])
                };
                let a = parameter_at(c, e.as_ref(), s, false);
                let b = parameter_at(c, e.as_ref(), t, true);
                a.zip(b)
            }
            Err(_) => None,
        };
        let (s, t) = if same {
            (&ends[0], &ends[1])
        } else {
            (&ends[1], &ends[0])
        };
        let mut out = Vec::with_capacity(pcurves.len());
        for pc in pcurves {
            let c = match (self.curve(ec, pc, 2)?, surface) {
                (Ok(c), _) => c,
                // On a plane the model-space curve serves instead.
                (Err(_), Some(StepSurface::Plane(f))) => {
                    return self.projected_onto_plane(ec, c3, f, ends, same)
                }
                (Err(w), _) => return Ok(Err(w)),
            };
            // The edge's range on the pcurve: candidates, the one whose ends lie nearest the
            // vertices on the surface taken (a file may parameterise the pcurve unlike the
            // model-space curve; the vertex check below still judges the choice).
            let mut candidates: Vec<(Rational, Rational)> = Vec::new();
            if let Some(StepSurface::Plane(p)) = surface {
                // On a plane the vertices' parameters are exact (their feet on the plane).
                let (a, b) = (plane_uv(p, s), plane_uv(p, t));
                let e = nurbs_ends(&c);
                candidates.extend(parameter_at(&c, e.as_ref(), &a, false).zip(parameter_at(
                    &c,
                    e.as_ref(),
                    &b,
                    true,
                )));
            }
            match c.domain() {
                Some(d) => {
                    let slack = Rational::from(&d[1] - &d[0]) * Rational::from((1, 1_000_000_000));
                    if let Some(r) = range.as_ref().filter(|r| {
                        r.0 >= Rational::from(&d[0] - &slack)
                            && r.1 <= Rational::from(&d[1] + &slack)
                    }) {
                        candidates.push(r.clone());
                    }
                    candidates.push((d[0].clone(), d[1].clone()));
                }
                None => {
                    candidates.extend(range.clone());
                    if let (Some(StepSurface::Nurbs(n, _)), Curve::Line { p, d }) = (surface, &c) {
                        candidates.extend(clip_line(p, d, &n.domain()));
                    }
                }
            }
            let score = |r: &(Rational, Rational)| -> f64 {
                let Some(surface) = surface else { return 0.0 };
                match (c.point(&r.0), c.point(&r.1)) {
                    (Some(a), Some(b)) => distance(&surface_point(surface, &a[0], &a[1]), s)
                        .max(distance(&surface_point(surface, &b[0], &b[1]), t)),
                    _ => f64::INFINITY,
                }
            };
            // A file may also parameterise a pcurve so that none of these fits (a line
            // pcurve of unit speed on a surface with another parameterisation, a circle's
            // angle against a B-spline pcurve): then the parameters nearest the vertices.
            let size = scale(s.iter().chain(t.iter())).to_f64();
            let fits = |r: &(Rational, Rational)| score(r) <= NEAR_VERTEX * size;
            if !candidates.iter().any(fits) {
                if let Some(StepSurface::Nurbs(n, _)) = surface {
                    let f = n.to_f64();
                    let exact = match (&c, c.domain()) {
                        (_, Some([a, b])) => Some((a, b)),
                        (Curve::Line { p, d }, None) => clip_line(p, d, &n.domain()),
                        _ => None,
                    };
                    let interval = exact.as_ref().map(|(a, b)| (a.to_f64(), b.to_f64()));
                    // A parameter found within 2^-40 of the interval's side is that side.
                    let snap = |x: f64| {
                        let (lo, hi) = exact.as_ref()?;
                        let width = Rational::from(hi - lo);
                        let x = Rational::from_f64(x)?;
                        let near = |e: &Rational| {
                            Rational::from(&x - e).abs() <= Rational::from(&width >> 40u32)
                        };
                        Some(if near(lo) {
                            lo.clone()
                        } else if near(hi) {
                            hi.clone()
                        } else {
                            x
                        })
                    };
                    let f64s = |x: &[Rational]| [x[0].to_f64(), x[1].to_f64(), x[2].to_f64()];
                    let at = |u: f64, v: f64| f.eval(u, v);
                    if let Some((lo, hi)) = interval {
                        // A vertex on a closed surface's seam has two nearest parameters:
                        // each end is searched for first, the other after (or before) it.
                        let (s, t) = (f64s(s), f64s(t));
                        let a = nearest_parameter(&c, &at, (lo, hi), s);
                        let after =
                            a.and_then(|a| Some((a, nearest_parameter(&c, &at, (a, hi), t)?)));
                        let b = nearest_parameter(&c, &at, (lo, hi), t);
                        let before =
                            b.and_then(|b| Some((nearest_parameter(&c, &at, (lo, b), s)?, b)));
                        for (a, b) in after.into_iter().chain(before) {
                            candidates.extend(snap(a).zip(snap(b)));
                        }
                    }
                }
            }
            let Some(range) = candidates
                .into_iter()
                .filter(|r| r.0 < r.1)
                .map(|r| (score(&r), r))
                .min_by(|x, y| x.0.total_cmp(&y.0))
                .map(|(_, r)| r)
            else {
                return Ok(Err(format!(
                    "edge #{ec}: its range on the line pcurve #{pc} is not known (its model-space curve is not a line or a B-spline curve ending at its vertices)"
                )));
            };
            match self.pieces_on(pc, &c, range)? {
                Ok(p) => out.push(p),
                Err(w) => return Ok(Err(format!("edge #{ec}: {w}"))),
            }
        }
        Ok(Ok(out))
    }

    /// The patches of a cylinder over the heights its face's loops reach (`t` over the whole
    /// circle, closed in `t`): each face on a cylinder has its own patches.
    fn cylinder_patches(
        &mut self,
        sid: u64,
        c: &Cylinder,
        m: usize,
        [lo, hi]: [Rational; 2],
        model: &mut Model,
    ) -> Result<Option<SurfaceInfo>, ReadError> {
        if lo >= hi {
            return Ok(None);
        }
        let Some(n) = c.surface(m, &lo, &hi) else {
            return Err(self.err(sid, "the cylinder's surface could not be made"));
        };
        let mut own = BTreeMap::new();
        let info = self.nurbs_patches(sid, &n, [true, false], model, &mut own)?;
        Ok(Some(info))
    }

    /// An edge on a cylinder face, from its model-space curve: a line along the axis (through
    /// its start vertex; its end vertex checked on the segment's end) is the
    /// segment `t = t₀` between its vertices' heights (on the seam `t₀ = 0`, also `t₀ = 4`:
    /// two candidates); a circle about the axis of the cylinder's radius is the segment
    /// `v = v₀` between its vertices' parameters, split at the seam when it crosses it
    /// (`proofs/trimmed-faces.md` 9, claim 4). Other curves, and curves off the cylinder by more
    /// than [`VERTEX_GAP`] of the part's size, are not mapped (the reason is returned).
    fn mapped_onto_cylinder(
        &mut self,
        ec: u64,
        id: u64,
        cyl: &Cylinder,
        ends: &[Point3; 2],
        same: bool,
    ) -> Result<Result<Vec<Vec<ParameterCurve>>, String>, ReadError> {
        let (c, conic) = match self.model_curve(ec, id)? {
            Ok(c) => c,
            Err(w) => return Ok(Err(format!("edge #{ec} on a cylinder: {w}"))),
        };
        let (s, t) = if same {
            (&ends[0], &ends[1])
        } else {
            (&ends[1], &ends[0])
        };
        let size = scale(s.iter().chain(t.iter())).to_f64();
        let near = |d: Rational| d.abs().to_f64() <= VERTEX_GAP * size;
        let (a, b) = (cyl.parameters(s), cyl.parameters(t));
        let point = |x: &Rational, y: &Rational| vec![x.clone(), y.clone()];
        let segment = |p: &[Rational], q: &[Rational]| ParameterCurve::segment(p, q);
        let zero = Rational::from(0);
        let four = Rational::from(4);
        match (&c, &conic) {
            (Curve::Line { p: on, d }, None) => {
                // Through its start vertex (up to the tolerance), and along the axis: the
                // direction has no part across it.
                let gap: Vec<Rational> = (0..3).map(|k| Rational::from(&s[k] - &on[k])).collect();
                let h = dot(&gap, &cyl.z);
                if !(0..3).all(|k| near(&gap[k] - Rational::from(&h * &cyl.z[k]))) {
                    return Ok(Err(format!(
                        "edge #{ec} on a cylinder: its line #{id} does not pass through its vertex"
                    )));
                }
                let along = dot(d, &cyl.z);
                let across: Vec<Rational> =
                    (0..3).map(|k| &d[k] - Rational::from(&along * &cyl.z[k])).collect();
                let dn = d.iter().map(|x| x.clone().abs()).max().unwrap_or_default();
                let slack = dn * Rational::from((1, 1_000_000_000));
                if !across.iter().all(|x| x.clone().abs() <= slack) {
                    return Ok(Err(format!(
                        "edge #{ec} on a cylinder: its line #{id} is not along the axis"
                    )));
                }
                // The segment's end against the end vertex (its start is checked with the
                // loop's other vertices).
                let far = distance(&surface_point_of(cyl, &a[0], &b[1]), t);
                if far > VERTEX_GAP * size || a[1] == b[1] {
                    return Ok(Err(format!(
                        "edge #{ec} on a cylinder: its line #{id} is not a ruling through its vertices"
                    )));
                }
                let p = point(&a[0], &a[1]);
                let q = point(&a[0], &b[1]);
                let mut out = vec![vec![segment(&p, &q)]];
                if a[0] == zero {
                    out.push(vec![segment(&point(&four, &a[1]), &point(&four, &b[1]))]);
                }
                Ok(Ok(out))
            }
            (_, Some(k)) => {
                // About the axis, of the cylinder's radius, in a plane across it.
                let n = cross3(&k.x, &k.y);
                let dz = dot(&n, &cyl.z);
                let off: Vec<Rational> = (0..3).map(|i| &n[i] - Rational::from(&dz * &cyl.z[i])).collect();
                let centre: Vec<Rational> =
                    (0..3).map(|i| Rational::from(&k.c[i] - &cyl.circle.c[i])).collect();
                let h = dot(&centre, &cyl.z);
                let centre_off: Vec<Rational> =
                    (0..3).map(|i| &centre[i] - Rational::from(&h * &cyl.z[i])).collect();
                let round = k.radii[0] == k.radii[1];
                if !round
                    || !off.iter().all(|x| near(x.clone() * cyl.radius()))
                    || !centre_off.iter().all(|x| near(x.clone()))
                    || !near(Rational::from(&k.radii[0] - cyl.radius()))
                {
                    return Ok(Err(format!(
                        "edge #{ec} on a cylinder: its curve #{id} is not a circle about the cylinder's axis"
                    )));
                }
                // The edge's direction about the axis: the circle's, against it when the
                // circle's normal points down the axis, and reversed once more when a trimmed
                // curve runs against its circle.
                let counter = (dz > 0) != k.reversed;
                let (ta, tb) = (a[0].clone(), b[0].clone());
                let at = |x: &Rational| point(x, &h);
                let mut pieces = Vec::new();
                if counter {
                    if ta < tb {
                        pieces.push(segment(&at(&ta), &at(&tb)));
                    } else {
                        if ta < four {
                            pieces.push(segment(&at(&ta), &at(&four)));
                        }
                        if zero < tb {
                            pieces.push(segment(&at(&zero), &at(&tb)));
                        }
                    }
                } else if tb < ta {
                    pieces.push(segment(&at(&ta), &at(&tb)));
                } else {
                    if zero < ta {
                        pieces.push(segment(&at(&ta), &at(&zero)));
                    }
                    if tb < four {
                        pieces.push(segment(&at(&four), &at(&tb)));
                    }
                }
                Ok(Ok(vec![pieces]))
            }
            _ => Ok(Err(format!(
                "edge #{ec} on a cylinder: its curve #{id} is neither a ruling nor a circle about the axis; inverting other curves onto a cylinder is not built yet"
            ))),
        }
    }

    /// An edge without a pcurve on a plane face: its model-space curve `id` mapped into the
    /// plane's frame (exact, [`Curve::in_plane`]) on the range its vertices give, in the
    /// curve's own direction, if the curve lies within [`VERTEX_GAP`] of the plane (the bound
    /// of [`Curve::off_plane`], relative to `1 +` the vertices' largest coordinate).
    fn projected_onto_plane(
        &mut self,
        ec: u64,
        id: u64,
        f: &PlaneFrame,
        ends: &[Point3; 2],
        same: bool,
    ) -> Result<Result<Vec<Vec<ParameterCurve>>, String>, ReadError> {
        let (c, conic) = match self.model_curve(ec, id)? {
            Ok(c) => c,
            Err(w) => return Ok(Err(format!("edge #{ec} has no pcurve and {w}"))),
        };
        let (s, t) = if same {
            (&ends[0], &ends[1])
        } else {
            (&ends[1], &ends[0])
        };
        // The ranges the edge runs over: on a conic from the start vertex's parameter to the
        // end's, across the parameterisation's seam when the end comes first (the whole conic
        // when the vertices are one point).
        let ranges = match &conic {
            Some(k) => {
                let [d0, d1] = k.domain();
                let (a, b) = (k.parameter(s), k.parameter(t));
                if a < b {
                    vec![(a, b)]
                } else {
                    [(a, d1), (d0, b)]
                        .into_iter()
                        .filter(|(x, y)| x < y)
                        .collect()
                }
            }
            None => {
                let e = nurbs_ends(&c);
                let Some(range) = parameter_at(&c, e.as_ref(), s, false).zip(parameter_at(
                    &c,
                    e.as_ref(),
                    t,
                    true,
                )) else {
                    return Ok(Err(format!(
                        "edge #{ec} has no pcurve and its vertices are not the ends of its curve #{id}"
                    )));
                };
                vec![range]
            }
        };
        let off = ranges
            .iter()
            .map(|r| c.off_plane(f, r).to_f64())
            .fold(0.0, f64::max);
        let size = scale(s.iter().chain(t.iter())).to_f64();
        if off > VERTEX_GAP * size {
            return Ok(Err(format!(
                "edge #{ec} has no pcurve and its curve #{id} may lie {off:.3e} off the face's plane (more than {VERTEX_GAP:.1e} of the part's size)"
            )));
        }
        self.projected.edges += 1;
        self.projected.largest_off_plane = self.projected.largest_off_plane.max(off);
        let image = c.in_plane(f);
        let mut pieces = Vec::new();
        for r in ranges {
            match self.pieces_on(id, &image, r)? {
                Ok(p) => pieces.extend(p),
                Err(w) => return Ok(Err(format!("edge #{ec}: {w}"))),
            }
        }
        Ok(Ok(vec![pieces]))
    }

    /// The Bézier pieces of a plane curve on `[a, b]`.
    fn pieces_on(
        &mut self,
        id: u64,
        c: &Curve,
        (a, b): (Rational, Rational),
    ) -> Result<Result<Vec<ParameterCurve>, String>, ReadError> {
        if a >= b {
            return Ok(Err(format!(
                "its range [{}, {}] on curve #{id} is empty or reversed",
                a.to_f64(),
                b.to_f64()
            )));
        }
        match c {
            Curve::Line { p, d } => {
                let at = |t: &Rational| -> Vec<Rational> {
                    p.iter()
                        .zip(d)
                        .map(|(x, y)| x + Rational::from(t * y))
                        .collect()
                };
                Ok(Ok(vec![ParameterCurve::segment(&at(&a), &at(&b))]))
            }
            Curve::Nurbs {
                degree,
                knots,
                points,
                weights,
            } => {
                let dom = c.domain().expect("a B-spline curve");
                let slack = Rational::from(&dom[1] - &dom[0]) * Rational::from((1, 1_000_000_000));
                let clamp = |t: Rational| {
                    if t < dom[0] && Rational::from(&dom[0] - &t) <= slack {
                        dom[0].clone()
                    } else if t > dom[1] && Rational::from(&t - &dom[1]) <= slack {
                        dom[1].clone()
                    } else {
                        t
                    }
                };
                let n = NurbsCurve::<3>::new(
                    *degree,
                    knots.clone(),
                    points,
                    weights,
                    Some([clamp(a), clamp(b)]),
                )
                .map_err(|e| self.err(id, e.to_string()))?;
                let count = n.span_count();
                if count > MAX_CURVE_PIECES {
                    return Err(self.err(id, format!("the curve splits into {count} Bézier pieces, more than the {MAX_CURVE_PIECES} allowed")));
                }
                self.bezier_points = self.bezier_points.saturating_add(count * (degree + 1));
                if self.bezier_points > crate::io::MAX_BEZIER_POINTS {
                    return Err(self.err(id, format!("the model's surfaces and curves would have more than the {} Bézier control points allowed", crate::io::MAX_BEZIER_POINTS)));
                }
                Ok(Ok(n.to_bezier().into_iter().map(|(_, c)| c).collect()))
            }
        }
    }
}

/// The text with every instance number `#123` written `#…` (and the measured distances and
/// curve numbers kept), so that reasons of one kind read alike.
fn without_numbers(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        out.push(c);
        if c == '#' && chars.peek().is_some_and(char::is_ascii_digit) {
            while chars.peek().is_some_and(char::is_ascii_digit) {
                chars.next();
            }
            out.push('…');
        }
    }
    out
}

/// A loop's box in `(u, v)` from its control points, in f64 (for choosing the outer loop).
fn loop_box(l: &TrimLoop) -> [[f64; 2]; 2] {
    let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 2];
    for p in &l.pieces {
        for q in p.curve.points() {
            for k in 0..2 {
                let x = q[k].to_f64();
                b[k][0] = b[k][0].min(x);
                b[k][1] = b[k][1].max(x);
            }
        }
    }
    b
}
