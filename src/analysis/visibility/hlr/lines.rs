//! Stage 1 of the drawing: the candidate lines, cut into segments. The lines are the patch
//! boundaries (each edge once), the silhouette arcs of the certified silhouette (cut at
//! dyadic parameters until each piece's image is monotone in one image direction) and the
//! silhouette lines inside patches, with the vertices where lines meet in space (patch
//! corners, silhouette junctions on sides, cut points).

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::projection::{side_point, ImagePolys};
use crate::analysis::visibility::hlr::result::LineKind;
use crate::analysis::visibility::ray::fix_axis;
use crate::analysis::visibility::scene::{ratio_bounds, ImageBounds, Scene};
use crate::bernstein::Bernstein;
use crate::number::{Interval, Precision, Rational, Sign};
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::Policy;
use crate::solver::system::DyadicBoxN;
use crate::solver::univariate::{isolate_roots_in, refine_root};
use crate::solver::CrossingId;
use crate::surface::Edge;

use crate::bernstein::Poly;

/// Every line of the drawing as segments: the sides first, then the silhouette arcs, then the
/// silhouette lines inside patches; the junctions of arcs and lines on sides are the sides'
/// vertices.
pub(super) fn candidate_lines(
    scene: &Scene,
    sil: &Silhouette,
    policy: &mut Policy,
) -> Vec<Segment> {
    let mut segments = boundary_segments(scene, policy);
    let arcs = silhouette_segments(scene, sil, &mut segments, policy);
    let first_chain = segments.len() + arcs.iter().map(|a| a.chain).max().unwrap_or(0) + 1;
    let lines = zero_line_segments(scene, sil, &mut segments, &arcs, first_chain, policy);
    segments.extend(arcs);
    segments.extend(lines);
    segments
}

/// One segment of a line, with the exact polynomials its crossings are solved on.
#[derive(Clone, Debug)]
pub(super) struct Segment {
    pub(super) kind: LineKind,
    pub(super) patch: usize,
    /// The side, for a boundary.
    pub(super) edge: Option<Edge>,
    /// The line it belongs to, and its position along it.
    pub(super) chain: usize,
    pub(super) order: usize,
    /// Image polynomials in the segment's variables (t for a side, (u, v) for an arc).
    pub(super) image: ImagePolys,
    /// The silhouette function (arcs).
    pub(super) constraint: Option<Poly>,
    /// The variables' box: the parameter interval of a side, or the arc's cell.
    pub(super) domain: DyadicBoxN,
    /// The variable that parameterizes the segment.
    pub(super) axis: usize,
    /// The parameter extent of the curve in it.
    pub(super) range: [f64; 2],
    /// Image and depth bounds.
    pub(super) bounds: ImageBounds,
    /// The image tangent's numerators along the image axes (positive multiples of the
    /// derivative along the segment's orientation).
    pub(super) tangent: [Poly; 2],
    /// A direction `e` in which the image is strictly monotone, with the sign of
    /// `e · tangent`.
    pub(super) monotone: Option<([Rational; 2], bool)>,
    /// The points where it meets other lines in space (its ends, and junctions on a side).
    pub(super) vertices: Vec<Vertex>,
    /// The patches it lies on: `(patch, side, reversed)` for the users of an edge (reversed:
    /// the side runs opposite to the segment's parameter), `(patch, None, false)` for an arc.
    pub(super) on: Vec<(usize, Option<Edge>, bool)>,
    /// For a silhouette line inside its patch (where the silhouette function vanishes
    /// identically): the fixed variable and its value; the segment's parameter is the other.
    pub(super) line: Option<(usize, Dyadic)>,
    /// For a trimming curve: the curve `(U, V, W)` in the patch's parameters, in the
    /// segment's parameter `t` (`(u, v) = (U/W, V/W)`).
    pub(super) curve: Option<[Poly; 3]>,
    /// Patches the segment is not searched against for penetrations: those of the faces that
    /// share a B-rep edge or vertex with its face ([`super::trim_lines::brep_neighbours`]).
    pub(super) touches: Vec<usize>,
    /// Stretches of a side (parameter intervals, bounds rounded inwards) that run along a
    /// B-rep edge another face's line draws ([`super::trim_lines`]): not lines of the
    /// drawing, so neither drawn nor cutting others (the B-rep assumption: the faces meet
    /// along that edge, which is drawn and cuts once).
    pub(super) elsewhere: Vec<[f64; 2]>,
    /// For an intersection curve of two patches: its variables are `(u, v, s, t)`, the
    /// parameters of `patch` then of the other ([`Meet`]).
    pub(super) meet: Option<std::sync::Arc<Meet>>,
}

/// The curve where two patches meet, as the segments on it see it.
#[derive(Debug)]
pub(super) struct Meet {
    /// The second patch (the segment's `patch` is the first).
    pub(super) other: usize,
    /// The three equations in `(u, v, s, t)` ([`crate::analysis::intersection::intersection_system`]).
    pub(super) eqs: std::sync::Arc<[Poly; 3]>,
    /// The first patch's image polynomials in `(u, v, s, t)`.
    pub(super) image: ImagePolys,
}

/// Where a vertex of the line network is.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Key {
    /// A welded patch corner (its vertex id).
    Corner(usize),
    /// A point of an edge, by its parameter interval on the edge's first user.
    Side { class: usize, t: [f64; 2] },
    /// A crossing of a patch's silhouette inside the patch.
    Inner { patch: usize, id: CrossingId },
    /// A point where an arc was cut to make its pieces' images monotone (a unique id).
    Param { id: usize },
    /// A crossing of an intersection curve inside its pair's domain (pair, crossing).
    Meet { pair: usize, crossing: usize },
    /// A point where an intersection curve meets a silhouette of one of its patches (a
    /// unique id).
    Fold { id: usize },
    /// The point where piece `k` of loop `lp` of a face starts (and piece `k − 1` ends).
    Joint { face: usize, lp: usize, k: usize },
    /// A point of a loop piece where it crosses a patch side or a silhouette, by its
    /// parameter interval on the piece.
    Trim {
        face: usize,
        lp: usize,
        piece: usize,
        t: [f64; 2],
    },
}

/// A vertex of a segment.
#[derive(Clone, Debug)]
pub(super) struct Vertex {
    pub(super) key: Key,
    /// Its parameter interval on the segment.
    pub(super) param: [f64; 2],
    /// Its parameter box on each patch it lies on: `(patch, lo, hi)`.
    pub(super) uv: Vec<(usize, [Rational; 2], [Rational; 2])>,
}

impl Segment {
    /// Whether the parameter interval `t` lies in a stretch drawn by another line
    /// ([`Segment::elsewhere`]).
    pub(super) fn drawn_elsewhere(&self, t: [f64; 2]) -> bool {
        self.elsewhere.iter().any(|e| e[0] <= t[0] && t[1] <= e[1])
    }
}

impl Key {
    pub(super) fn matches(&self, other: &Key) -> bool {
        match (self, other) {
            (Key::Corner(a), Key::Corner(b)) => a == b,
            (Key::Side { class: a, t: s }, Key::Side { class: b, t: u }) => {
                a == b && s[0] <= u[1] && u[0] <= s[1]
            }
            (Key::Inner { patch: a, id: x }, Key::Inner { patch: b, id: y }) => a == b && x == y,
            (Key::Param { id: a }, Key::Param { id: b }) => a == b,
            (
                Key::Meet {
                    pair: a,
                    crossing: x,
                },
                Key::Meet {
                    pair: b,
                    crossing: y,
                },
            ) => a == b && x == y,
            (Key::Fold { id: a }, Key::Fold { id: b }) => a == b,
            (
                Key::Joint {
                    face: f,
                    lp: l,
                    k: a,
                },
                Key::Joint {
                    face: g,
                    lp: m,
                    k: b,
                },
            ) => f == g && l == m && a == b,
            (
                Key::Trim {
                    face: f,
                    lp: l,
                    piece: a,
                    t: s,
                },
                Key::Trim {
                    face: g,
                    lp: m,
                    piece: b,
                    t: u,
                },
            ) => f == g && l == m && a == b && s[0] <= u[1] && u[0] <= s[1],
            _ => false,
        }
    }
}

/// The image bounds of image polynomials on a box of their variables.
pub(super) fn bounds_on(im: &ImagePolys, domain: &DyadicBoxN) -> ImageBounds {
    let lo: Vec<Rational> = domain.iter().map(|d| d.0.to_rational()).collect();
    let hi: Vec<Rational> = domain.iter().map(|d| d.1.to_rational()).collect();
    let r = |p: &Poly| p.restrict_box_rational(&lo, &hi);
    ImageBounds {
        x: ratio_bounds(&r(&im.x), &r(&im.q)),
        y: ratio_bounds(&r(&im.y), &r(&im.q)),
        depth: ratio_bounds(&r(&im.depth), &r(&im.w)),
    }
}

/// The sign of a polynomial on a box, if strict: `Some(true)` positive.
pub(super) fn strict_sign(p: &Poly, domain: &DyadicBoxN) -> Option<bool> {
    sign_on(&p.convert(Precision::F64), domain)
}

/// The strict sign of an interval polynomial on a dyadic box (its Bernstein coefficients
/// there), if all coefficients share one.
pub(super) fn sign_on(p: &Bernstein<Interval>, domain: &DyadicBoxN) -> Option<bool> {
    // Bounds rounded outward: a sign on the larger box holds on the box.
    let lo: Vec<f64> = domain.iter().map(|d| d.0.to_f64_bounds().0).collect();
    let hi: Vec<f64> = domain.iter().map(|d| d.1.to_f64_bounds().1).collect();
    match p.restrict_box_f64(&lo, &hi).range_sign() {
        Sign::Positive => Some(true),
        Sign::Negative => Some(false),
        _ => None,
    }
}

/// The image tangent of an arc of patch `patch` on `g = 0`: the field `(−g_v, g_u)` pushed to
/// the image by the numerators of the Jacobian rows (a positive multiple of the derivative
/// of the image point along that field).
pub(super) fn tangent_polys_arc(scene: &Scene, patch: usize, g: &Poly) -> [Poly; 2] {
    let (gu, gv) = (g.deriv(0), g.deriv(1));
    let t = [gv.neg(), gu];
    let j = &scene.jacobians[patch];
    [0, 1].map(|r| &(&j[r][0] * &t[0]) + &(&j[r][1] * &t[1]))
}

/// The tangent of a segment set up past the deadline: the zero field in `nvars` variables,
/// from which nothing is proven (no direction is strictly monotone along it, no corner has a
/// tangent), so the segment stays unresolved.
fn untraced_tangent(nvars: usize) -> [Poly; 2] {
    [(); 2].map(|()| Poly::constant(nvars, Rational::new()))
}

/// The segment's image is strictly monotone along `e` if `e · tangent` has a strict sign on
/// its box; the sign is returned.
pub(super) fn monotone_along(
    t: &[Poly; 2],
    e: &[Rational; 2],
    domain: &DyadicBoxN,
) -> Option<bool> {
    let p = &t[0].scale(&e[0]) + &t[1].scale(&e[1]);
    strict_sign(&p, domain)
}

/// A direction in which the segment's image is monotone: the image tangent at its centre,
/// rounded to a rational direction.
pub(super) fn find_monotone(t: &[Poly; 2], domain: &DyadicBoxN) -> Option<([Rational; 2], bool)> {
    let mid: Vec<f64> = domain
        .iter()
        .map(|d| 0.5 * (d.0.to_f64() + d.1.to_f64()))
        .collect();
    let tf = t
        .clone()
        .map(|p| p.convert::<f64>(Precision::F64).eval(&mid));
    let e = rational_direction(tf)?;
    monotone_along(t, &e, domain).map(|s| (e, s))
}

/// A vector's direction rounded to a rational one (components on the 1/1024 grid of the
/// unit vector), `None` for the zero vector or one not finite.
pub(super) fn rational_direction(v: [f64; 2]) -> Option<[Rational; 2]> {
    let n = v[0].hypot(v[1]);
    if !n.is_finite() || n <= 0.0 {
        return None;
    }
    let r = |x: f64| Rational::from_f64((x / n * 1024.0).round() / 1024.0).unwrap_or_default();
    Some(v.map(r))
}

/// The corner indices (into `PatchAdjacency::corners`) at the start and end of a side, in
/// its increasing parameter.
pub(super) fn side_corners(edge: Edge) -> (usize, usize) {
    match edge {
        Edge::V0 => (0, 1),
        Edge::U1 => (1, 2),
        Edge::V1 => (3, 2),
        Edge::U0 => (0, 3),
    }
}

/// A rational from an f64 (exact).
pub(super) fn rat(x: f64) -> Rational {
    Rational::from_f64(x).unwrap_or_default()
}

/// The parameter box, on each user patch, of the edge point with class parameter in `t`.
pub(super) fn side_uv(
    users: &[(usize, Option<Edge>, bool)],
    t: [f64; 2],
) -> Vec<(usize, [Rational; 2], [Rational; 2])> {
    users
        .iter()
        .filter_map(|&(p, e, rev)| {
            let e = e?;
            let (a, b) = if rev {
                (1.0 - t[1], 1.0 - t[0])
            } else {
                (t[0], t[1])
            };
            let lo = side_point(e, &rat(a));
            let hi = side_point(e, &rat(b));
            Some((p, lo, hi))
        })
        .collect()
}

/// The boundary lines: each distinct edge once, as one segment.
fn boundary_segments(scene: &Scene, policy: &Policy) -> Vec<Segment> {
    let mut out = Vec::new();
    for (chain, users) in scene.adjacency.edges.iter().enumerate() {
        let first = users[0];
        let im = scene.images[first.patch].on_side(first.edge);
        let on: Vec<(usize, Option<Edge>, bool)> = users
            .iter()
            .map(|u| (u.patch, Some(u.edge), u.reversed != first.reversed))
            .collect();
        let (c0, c1) = side_corners(first.edge);
        let corners = &scene.adjacency.corners[first.patch];
        let vertices = vec![
            Vertex {
                key: Key::Corner(corners[c0]),
                param: [0.0, 0.0],
                uv: side_uv(&on, [0.0, 0.0]),
            },
            Vertex {
                key: Key::Corner(corners[c1]),
                param: [1.0, 1.0],
                uv: side_uv(&on, [1.0, 1.0]),
            },
        ];
        out.push(exact_curve(
            LineKind::Boundary,
            first.patch,
            Some(first.edge),
            chain,
            im,
            vertices,
            on,
            None,
            policy,
        ));
    }
    out
}

/// The image tangent of a side: the numerators of the derivatives of the image coordinates.
pub(super) fn tangent_polys_side(im: &ImagePolys) -> [Poly; 2] {
    let d = |f: &Poly| &(&f.deriv(0) * &im.q) - &(f * &im.q.deriv(0));
    [d(&im.x), d(&im.y)]
}

/// The edge class and the user's reversal of a patch side.
pub(super) fn class_of(scene: &Scene, patch: usize, edge: Edge) -> Option<(usize, bool)> {
    scene
        .adjacency
        .edges
        .iter()
        .enumerate()
        .find_map(|(c, users)| {
            let me = users.iter().find(|u| u.patch == patch && u.edge == edge)?;
            Some((c, me.reversed != users[0].reversed))
        })
}

/// The vertex of a silhouette crossing of patch `i`.
pub(super) fn crossing_vertex(
    scene: &Scene,
    boundary: &[Segment],
    topo: &crate::solver::CurveTopology,
    i: usize,
    id: &CrossingId,
    axis: usize,
) -> Vertex {
    let loc = topo.locations[id];
    let param = loc.axis(axis);
    let own = (i, loc.lo.map(rat), loc.hi.map(rat));
    // A patch corner.
    if let CrossingId::Exact { u, v } = id {
        let at = |d: &Dyadic| *d == Dyadic::ZERO || *d == Dyadic::ONE;
        if at(u) && at(v) {
            let k = match (*u == Dyadic::ONE, *v == Dyadic::ONE) {
                (false, false) => 0,
                (true, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            };
            let vid = scene.adjacency.corners[i][k];
            let uv = boundary
                .iter()
                .flat_map(|b| b.vertices.iter())
                .find(|x| x.key == Key::Corner(vid))
                .map_or_else(|| vec![own.clone()], |x| x.uv.clone());
            return Vertex {
                key: Key::Corner(vid),
                param,
                uv,
            };
        }
    }
    let sides = crate::analysis::contour::sides::side_of(id);
    if let Some(&(edge, s0, s1)) = sides.first() {
        let (lo, hi) = topo
            .intervals
            .get(id)
            .map_or((s0.to_f64(), s1.to_f64()), |(a, b)| {
                (a.to_f64(), b.to_f64())
            });
        if let Some((class, rev)) = class_of(scene, i, edge) {
            let t = if rev { [1.0 - hi, 1.0 - lo] } else { [lo, hi] };
            return Vertex {
                key: Key::Side { class, t },
                param,
                uv: side_uv(&boundary[class].on, t),
            };
        }
        // A collapsed side (a pole): one point.
        if let Some(&(_, _, vid)) = scene
            .adjacency
            .collapsed
            .iter()
            .find(|(p, e, _)| *p == i && *e == edge)
        {
            return Vertex {
                key: Key::Corner(vid),
                param,
                uv: vec![own],
            };
        }
    }
    Vertex {
        key: Key::Inner { patch: i, id: *id },
        param,
        uv: vec![own],
    }
}

/// The silhouette arcs, one segment per certified cell; the arcs of one branch form a line.
/// Their ends on sides are added to the sides as vertices (junctions).
fn silhouette_segments(
    scene: &Scene,
    sil: &Silhouette,
    boundary: &mut [Segment],
    policy: &mut Policy,
) -> Vec<Segment> {
    let mut out = Vec::new();
    let mut chain = boundary.len();
    let mut next_id = 0;
    for (i, solved) in sil.solved.iter().enumerate() {
        let topo = &solved.topology;
        for branch in &topo.branches {
            let ids = &branch.crossings;
            let n = if branch.closed {
                ids.len()
            } else {
                ids.len().saturating_sub(1)
            };
            let mut order = 0;
            for k in 0..n {
                let (a, b) = (&ids[k], &ids[(k + 1) % ids.len()]);
                let Some(arc) = topo
                    .arcs
                    .iter()
                    .find(|x| (x.from == *a && x.to == *b) || (x.from == *b && x.to == *a))
                else {
                    order += 1; // not consecutive across the gap
                    continue;
                };
                // The arc's parameter: the axis it is a graph over.
                let axis = match arc.kind.monotone_axis() {
                    Some(m) => 1 - m,
                    None => {
                        // Along a side: drawn as the boundary.
                        order += 1;
                        continue;
                    }
                };
                let (pa, pb) = (topo.locations[a], topo.locations[b]);
                let range = pa.hull(&pb).axis(axis);
                // The cell, narrowed along the parameter to the arc's extent: other arcs of
                // the same cell (each meets a parameter line once) lie outside it.
                let mut domain: DyadicBoxN = vec![
                    (arc.cell.lo[0], arc.cell.hi[0]),
                    (arc.cell.lo[1], arc.cell.hi[1]),
                ];
                let (lo, hi) = (dyadic_below(range[0]), dyadic_above(range[1]));
                domain[axis] = (domain[axis].0.max(lo), domain[axis].1.min(hi));
                let domain = narrow_to_curve(&solved.g, &domain, axis);
                let tangent = if policy.past_deadline() {
                    untraced_tangent(2)
                } else {
                    tangent_polys_arc(scene, i, &solved.g)
                };
                let vertices: Vec<Vertex> = [a, b]
                    .iter()
                    .map(|id| crossing_vertex(scene, boundary, topo, i, id, axis))
                    .collect();
                // Every junction cuts the side, even one whose interval overlaps another's.
                for v in &vertices {
                    if let Key::Side { class, t } = &v.key {
                        if !boundary[*class].vertices.iter().any(|x| x.key == v.key) {
                            boundary[*class].vertices.push(Vertex {
                                key: v.key.clone(),
                                param: *t,
                                uv: v.uv.clone(),
                            });
                        }
                    }
                }
                let whole = Segment {
                    kind: LineKind::Silhouette,
                    patch: i,
                    edge: None,
                    chain,
                    order,
                    bounds: bounds_on(&scene.images[i], &domain),
                    image: scene.images[i].clone(),
                    constraint: Some(solved.g.clone()),
                    monotone: find_monotone(&tangent, &domain),
                    domain,
                    axis,
                    range,
                    tangent,
                    vertices,
                    on: vec![(i, None, false)],
                    line: None,
                    curve: None,
                    touches: Vec::new(),
                    elsewhere: Vec::new(),
                    meet: None,
                };
                // Along the branch, vertex a comes first.
                let forward = whole.vertices[0].param[0] <= whole.range[0];
                let mut pieces = split_monotone(whole, 6, &mut next_id, policy);
                if !forward {
                    pieces.reverse();
                }
                for mut p in pieces {
                    p.order = order;
                    out.push(p);
                    order += 1;
                }
            }
            chain += 1;
        }
    }
    out
}

/// An arc cut at dyadic parameters (bisection, up to `depth` times) into pieces whose images
/// are monotone; the cut points become shared vertices. Pieces never made monotone stay (their
/// self-crossings are reported unresolved).
pub(super) fn split_monotone(
    s: Segment,
    depth: u32,
    next_id: &mut usize,
    policy: &mut Policy,
) -> Vec<Segment> {
    // Past the deadline a piece stays as it is (not proven monotone, so unresolved; the
    // crossings stage then names the time limit).
    if s.monotone.is_some() || depth == 0 || policy.past_deadline() {
        return vec![s];
    }
    let (lo, hi) = s.domain[s.axis];
    let Some(mid) = lo.midpoint(hi) else {
        return vec![s];
    };
    let c = mid.to_f64();
    if c <= s.range[0] || c >= s.range[1] {
        return vec![s];
    }
    let Some(g) = s.constraint.clone() else {
        return vec![s];
    };
    // The arc's point on the line axis = mid: the only root of g there in the cell.
    let m = 1 - s.axis;
    let line = fix_axis(&g, s.axis, &mid.to_rational());
    let roots = isolate_roots_in(&line, s.domain[m].0, s.domain[m].1, 40, policy);
    if roots.roots.len() != 1 || !roots.unresolved.is_empty() {
        return vec![s];
    }
    let r = refine_root(&line, roots.roots[0], 1e-12, policy);
    let mut lo_uv = [mid.to_rational(), mid.to_rational()];
    let mut hi_uv = lo_uv.clone();
    lo_uv[m] = r.lo().to_rational();
    hi_uv[m] = r.hi().to_rational();
    let cut = Vertex {
        key: Key::Param { id: *next_id },
        param: [c, c],
        uv: vec![(s.patch, lo_uv, hi_uv)],
    };
    let half = |range: [f64; 2], dom: (Dyadic, Dyadic), keep_low: bool| {
        let mut d = s.clone();
        d.domain[s.axis] = dom;
        d.domain = narrow_to_curve(&g, &d.domain, s.axis);
        d.range = range;
        d.bounds = bounds_on(&d.image, &d.domain);
        d.monotone = find_monotone(&d.tangent, &d.domain);
        d.vertices = s
            .vertices
            .iter()
            .filter(|v| {
                if keep_low {
                    v.param[1] <= c
                } else {
                    v.param[0] >= c
                }
            })
            .cloned()
            .chain([cut.clone()])
            .collect();
        d
    };
    *next_id += 1;
    let low = half([s.range[0], c], (lo, mid), true);
    let high = half([c, s.range[1]], (mid, hi), false);
    let mut out = split_monotone(low, depth - 1, next_id, policy);
    out.extend(split_monotone(high, depth - 1, next_id, policy));
    out
}

/// The box narrowed across the parameter axis to the hull of the sub-boxes (of a bisection
/// of that axis into up to 64) where `g` may vanish (a Bernstein coefficient sign test):
/// the arc inside the box lies in it.
pub(super) fn narrow_to_curve(g: &Poly, domain: &DyadicBoxN, axis: usize) -> DyadicBoxN {
    let m = 1 - axis;
    let gi: Bernstein<Interval> = g.convert(Precision::F64);
    let mut keep: Option<(Dyadic, Dyadic)> = None;
    let (l0, h0) = domain[m];
    let exact = |d: Dyadic| {
        let (a, b) = d.to_f64_bounds();
        a == b
    };
    // Where the box's ends across the axis are exact in f64, `g` is restricted to the box
    // once (outward along the axis: a sign on the larger box holds on the box) and each half
    // is one de Casteljau split of its parent: the polynomial on the real half, whose ends
    // are the dyadic midpoints. Otherwise (`None`) each sub-box is restricted on its own.
    let whole = (exact(l0) && exact(h0)).then(|| {
        let lo: Vec<f64> = domain.iter().map(|d| d.0.to_f64_bounds().0).collect();
        let hi: Vec<f64> = domain.iter().map(|d| d.1.to_f64_bounds().1).collect();
        gi.restrict_box_f64(&lo, &hi)
    });
    let mut stack = vec![(l0, h0, 0u32, whole)];
    while let Some((lo, hi, depth, p)) = stack.pop() {
        let signed = match &p {
            Some(p) => p.range_sign().is_nonzero(),
            None => {
                let mut d = domain.clone();
                d[m] = (lo, hi);
                sign_on(&gi, &d).is_some()
            }
        };
        if signed {
            continue;
        }
        match lo.midpoint(hi) {
            Some(mid) if depth < 6 => {
                let (left, right) = match p.map(|p| p.subdivide_half(m)) {
                    Some((l, r)) => (Some(l), Some(r)),
                    None => (None, None),
                };
                stack.push((lo, mid, depth + 1, left));
                stack.push((mid, hi, depth + 1, right));
            }
            _ => keep = Some(keep.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi)))),
        }
    }
    let mut out = domain.clone();
    if let Some(k) = keep {
        out[m] = k;
    }
    out
}

/// A box of a patch's parameters, `[[u_lo, u_hi], [v_lo, v_hi]]` in f64, that may reach past
/// the unit square: a box on which a lemma about the patch's polynomials (which extend past
/// their square) is proven.
pub(super) type ParamBox = [[f64; 2]; 2];

/// The f64 box inside a dyadic box (corners rounded inwards).
pub(super) fn param_box(b: &DyadicBoxN) -> ParamBox {
    [0, 1].map(|a| [b[a].0.to_f64_bounds().1, b[a].1.to_f64_bounds().0])
}

/// The dyadic interval (40 bits) inside `x ∩ [0, 1]`, if it is not empty.
fn dyadic_within(x: [f64; 2]) -> Option<(Dyadic, Dyadic)> {
    let (lo, hi) = (dyadic_above(x[0]), dyadic_below(x[1]));
    (x[0] <= 1.0 && x[1] >= 0.0 && lo <= hi).then_some((lo, hi))
}

/// The part of a segment's domain that lies in the parameter box `b` of patch `p`, if the
/// segment lies on `p` and meets `b`; for a trimming curve, the run of its parameter inside
/// `b` that holds the parameter interval `near` (if given; else the longest run).
pub(super) fn sub_domain(
    s: &Segment,
    p: usize,
    b: &ParamBox,
    near: Option<[f64; 2]>,
) -> Option<DyadicBoxN> {
    let &(_, edge, rev) = s.on.iter().find(|x| x.0 == p)?;
    let within = |a: usize| dyadic_within(b[a]);
    if let Some(m) = &s.meet {
        // The variables of patch p among (u, v, s, t): the first pair or the second.
        let offset = if p == s.patch {
            0
        } else if p == m.other {
            2
        } else {
            return None;
        };
        let mut d = s.domain.clone();
        for (a, x) in d[offset..offset + 2].iter_mut().enumerate() {
            let y = within(a)?;
            *x = (x.0.max(y.0), x.1.min(y.1));
        }
        return d.iter().all(|(l, h)| l < h).then_some(d);
    }
    if let Some(c) = &s.curve {
        return crate::analysis::visibility::hlr::trim_lines::curve_sub_domain(s, c, b, near);
    }
    // Whether an exact coordinate lies in the box's interval along `axis`.
    let holds = |axis: usize, at: Dyadic| {
        let (l, h) = at.to_f64_bounds();
        b[axis][0] <= l && h <= b[axis][1]
    };
    if let Some((axis, at)) = s.line {
        if !holds(axis, at) {
            return None;
        }
        let (lo, hi) = within(1 - axis)?;
        let (lo, hi) = (lo.max(s.domain[0].0), hi.min(s.domain[0].1));
        return (lo < hi).then(|| vec![(lo, hi)]);
    }
    match edge {
        None => {
            let d: DyadicBoxN = (0..2)
                .map(|a| {
                    let (l, h) = within(a)?;
                    Some((s.domain[a].0.max(l), s.domain[a].1.min(h)))
                })
                .collect::<Option<_>>()?;
            d.iter().all(|(l, h)| l < h).then_some(d)
        }
        Some(e) => {
            // The side's fixed coordinate must lie in the box; its free one gives the range.
            let (fixed, at_one) = match e {
                Edge::V0 => (1, false),
                Edge::V1 => (1, true),
                Edge::U0 => (0, false),
                Edge::U1 => (0, true),
            };
            if !holds(fixed, if at_one { Dyadic::ONE } else { Dyadic::ZERO }) {
                return None;
            }
            let (lo, hi) = within(1 - fixed)?;
            let (lo, hi) = if rev {
                (hi.one_minus(), lo.one_minus())
            } else {
                (lo, hi)
            };
            let (lo, hi) = (lo.max(s.domain[0].0), hi.min(s.domain[0].1));
            (lo < hi).then(|| vec![(lo, hi)])
        }
    }
}

/// A dyadic (40 bits) at or below an f64 in [0, 1].
pub(super) fn dyadic_below(x: f64) -> Dyadic {
    let n = (x.clamp(0.0, 1.0) * (1u64 << 40) as f64).floor() as u64;
    Dyadic::new(n.min(1 << 40), 40)
}

/// A dyadic (40 bits) at or above an f64 in [0, 1].
pub(super) fn dyadic_above(x: f64) -> Dyadic {
    let n = (x.clamp(0.0, 1.0) * (1u64 << 40) as f64).ceil() as u64;
    Dyadic::new(n.min(1 << 40), 40)
}

/// The dyadic (40 bits) at or below / above a rational in [0, 1].
pub(super) fn dyadic_floor(x: &Rational) -> Rational {
    let mut y = Rational::from(x << 40u32);
    y = Rational::from(y.floor_ref());
    y >>= 40u32;
    y
}

pub(super) fn dyadic_ceil(x: &Rational) -> Rational {
    let mut y = Rational::from(x << 40u32);
    y = Rational::from(y.ceil_ref());
    y >>= 40u32;
    y
}

/// The silhouette lines inside patches (where the silhouette function vanishes identically on
/// an axis line `u = c` or `v = c`, found exactly by the curve solver): each is a segment like a
/// side, a fold curve of its patch. Their ends on sides are junctions of those sides; the
/// crossings of the patch's other silhouette arcs on them are their vertices.
fn zero_line_segments(
    scene: &Scene,
    sil: &Silhouette,
    boundary: &mut [Segment],
    arcs: &[Segment],
    first_chain: usize,
    policy: &Policy,
) -> Vec<Segment> {
    let mut out = Vec::new();
    let mut chain = first_chain;
    for (i, solved) in sil.solved.iter().enumerate() {
        for zl in &solved.lines {
            let (axis, at) = (zl.axis, zl.at);
            let atq = at.to_rational();
            let im = scene.images[i].on_line(axis, &atq);
            let point = |t: f64| -> ([Rational; 2], [Rational; 2]) {
                let mut uv = [atq.clone(), atq.clone()];
                uv[1 - axis] = rat(t);
                (uv.clone(), uv)
            };
            let mut vertices = Vec::new();
            // Its ends, on the sides of the patch across the line.
            for (t, edge) in [
                (0.0, if axis == 0 { Edge::V0 } else { Edge::U0 }),
                (1.0, if axis == 0 { Edge::V1 } else { Edge::U1 }),
            ] {
                let (lo, hi) = point(t);
                let key = match class_of(scene, i, edge) {
                    Some((class, rev)) => {
                        let c = at.to_f64();
                        Key::Side {
                            class,
                            t: if rev { [1.0 - c, 1.0 - c] } else { [c, c] },
                        }
                    }
                    None => match scene
                        .adjacency
                        .collapsed
                        .iter()
                        .find(|(p, e, _)| *p == i && *e == edge)
                    {
                        Some(&(_, _, vid)) => Key::Corner(vid),
                        None => continue,
                    },
                };
                let uv = match &key {
                    Key::Side { class, t } => side_uv(&boundary[*class].on, *t),
                    _ => vec![(i, lo, hi)],
                };
                if let Key::Side { class, t } = &key {
                    if !boundary[*class].vertices.iter().any(|x| x.key == key) {
                        boundary[*class].vertices.push(Vertex {
                            key: key.clone(),
                            param: *t,
                            uv: uv.clone(),
                        });
                    }
                }
                vertices.push(Vertex {
                    key,
                    param: [t, t],
                    uv,
                });
            }
            // The patch's silhouette arcs that end on it.
            for a in arcs.iter().filter(|a| a.patch == i && a.line.is_none()) {
                for v in &a.vertices {
                    let Key::Inner { id, .. } = &v.key else {
                        continue;
                    };
                    let on_line = match *id {
                        CrossingId::Exact { u, v: vv } => [u, vv][axis] == at,
                        CrossingId::Segment { fixed, c, .. } => fixed == axis && c == at,
                    };
                    if on_line && !vertices.iter().any(|x: &Vertex| x.key == v.key) {
                        let (_, lo, hi) = &v.uv[0];
                        vertices.push(Vertex {
                            key: v.key.clone(),
                            param: [lo[1 - axis].to_f64(), hi[1 - axis].to_f64()],
                            uv: v.uv.clone(),
                        });
                    }
                }
            }
            out.push(exact_curve(
                LineKind::Silhouette,
                i,
                None,
                chain,
                im,
                vertices,
                vec![(i, None, false)],
                Some((axis, at)),
                policy,
            ));
            chain += 1;
        }
    }
    out
}

/// A segment that is a whole exact curve of one parameter in [0, 1] (a side, or a silhouette
/// line inside a patch).
#[allow(clippy::too_many_arguments)]
fn exact_curve(
    kind: LineKind,
    patch: usize,
    edge: Option<Edge>,
    chain: usize,
    image: ImagePolys,
    vertices: Vec<Vertex>,
    on: Vec<(usize, Option<Edge>, bool)>,
    line: Option<(usize, Dyadic)>,
    policy: &Policy,
) -> Segment {
    let tangent = if policy.past_deadline() {
        untraced_tangent(1)
    } else {
        tangent_polys_side(&image)
    };
    let domain = vec![(Dyadic::ZERO, Dyadic::ONE)];
    Segment {
        kind,
        patch,
        edge,
        chain,
        order: 0,
        bounds: bounds_on(&image, &domain),
        monotone: find_monotone(&tangent, &domain),
        image,
        constraint: None,
        tangent,
        range: [0.0, 1.0],
        domain,
        axis: 0,
        vertices,
        on,
        line,
        curve: None,
        touches: Vec::new(),
        elsewhere: Vec::new(),
        meet: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sign change of `g` along lines across the box lies in the narrowed box, by both
    /// routes (f64-exact ends: one restriction and splits; other ends: a restriction per
    /// sub-box), on random bicubics.
    #[test]
    fn the_narrowed_box_holds_the_curve() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        // Ends 1/4 and 3/4, then the same ends moved by 2^-57 (not f64-exact).
        let routes = [
            (Dyadic::new(1, 2), Dyadic::new(3, 2)),
            (
                Dyadic::new((1 << 55) + 1, 57),
                Dyadic::new((3 << 55) - 1, 57),
            ),
        ];
        let mut narrowed = 0;
        for case in 0..40 {
            let coeffs: Vec<Rational> = (0..16)
                .map(|_| Rational::from((next() % 9) as i64 - 4))
                .collect();
            let g = Poly::new(&[3, 3], coeffs).unwrap();
            let gf: Bernstein<f64> = g.map(|c| c.to_f64());
            for axis in 0..2 {
                for (l, h) in routes {
                    let domain = vec![(Dyadic::new(1, 3), Dyadic::new(7, 8)), (l, h)];
                    let domain = if axis == 0 {
                        domain
                    } else {
                        vec![domain[1], domain[0]]
                    };
                    let out = narrow_to_curve(&g, &domain, axis);
                    let m = 1 - axis;
                    let (ol, oh) = (out[m].0.to_f64(), out[m].1.to_f64());
                    narrowed += usize::from(out[m] != domain[m]);
                    let (al, ah) = (domain[axis].0.to_f64(), domain[axis].1.to_f64());
                    let (ml, mh) = (domain[m].0.to_f64(), domain[m].1.to_f64());
                    let n = 400;
                    for i in 0..=20 {
                        let a = al + (ah - al) * i as f64 / 20.0;
                        let at = |t: f64| {
                            let mut x = [0.0; 2];
                            x[axis] = a;
                            x[m] = ml + (mh - ml) * t;
                            gf.eval(&x)
                        };
                        for k in 0..n {
                            let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                            let (g0, g1) = (at(t0), at(t1));
                            if g0 * g1 < 0.0 && g0.abs() > 1e-9 && g1.abs() > 1e-9 {
                                let (x0, x1) = (ml + (mh - ml) * t0, ml + (mh - ml) * t1);
                                assert!(
                                    x1 >= ol && x0 <= oh,
                                    "case {case} axis {axis}: crossing in [{x0}, {x1}] outside [{ol}, {oh}]"
                                );
                            }
                        }
                    }
                }
            }
        }
        assert!(narrowed > 0);
    }
}
